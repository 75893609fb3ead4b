"""A cantilever under a growing dead load: its equilibria as curves, for continuation.

With the direction ``psi`` of the tip force fixed and its magnitude ``R`` free, the
equilibria of a cantilever (RK4 shooting, :func:`mechnum.rods.integrate`) form
curves in the plane of the dimensionless unknowns ``u = (m0 L / EI, R L**2 / EI)``: one equation,
``m(L) L / EI = 0``, in two unknowns, the load last. :class:`DeadLoad` gives that equation
and its derivatives for :func:`mechnum.continuation.pseudo_arclength`, and the stability of
each equilibrium: the index of the second variation of the energy
(``rods``'s stability module; a free tip adds no constraint).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods._elliptic import clamped_pinned
from mechnum.rods._rod import MAX_NODES, Rod, integrate, rod_scales, tip_states
from mechnum.rods._stability import constrained_index, rod_block


class DeadLoad:
    """A cantilever (clamped along +x at the origin) under the tip force ``R (cos psi, sin psi)``.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    psi : float
        Direction of the force (rad); ``pi`` pushes the tip towards the clamp.
    segments : int, optional
        RK4 steps and stability segments: the rod is integrated on ``2 segments + 1`` nodes,
        whose midpoint angles enter the stability test (``2 <= segments <= MAX_NODES // 2``).

    Examples
    --------
    The Euler column (``psi = pi``) is stable below ``pi**2 / 4`` and unstable above:

    >>> column = DeadLoad(1.0, 1.0, np.pi)
    >>> [column.index([0.0, a]) for a in (2.4, 2.5)]
    [0, 1]
    >>> bool(abs(column.fun([0.0, 2.5])[0]) < 1e-15), column.jac([0.0, 2.5]).shape
    (True, (1, 2))
    """

    def __init__(self, EI: float, L: float, psi: float, segments: int = 80):
        self.EI, self.L = rod_scales(EI, L, scalar=True)
        psi = _validate.scalar(psi, "psi")
        self.psi, self.direction = psi, np.array([np.cos(psi), np.sin(psi)])
        self.segments = _validate.maxiter(segments, "segments", minimum=2,
                                          maximum=MAX_NODES // 2)

    def _physical(self, u):
        u = _validate.array(u, "u", shape=(2,))
        return u[0] * self.EI / self.L, u[1] * self.EI / self.L ** 2 * self.direction

    def rod(self, u: ArrayLike) -> Rod:
        """The equilibrium's rod (:class:`~mechnum.rods.Rod`) at
        ``u = (m0 L / EI, R L**2 / EI)``."""
        return integrate(self.EI, self.L, *self._physical(u), nodes=2 * self.segments + 1)

    def fun(self, u: ArrayLike) -> np.ndarray:
        """``(m(L) L / EI,)``: zero at an equilibrium."""
        return np.array([self.rod(u).m[-1] * self.L / self.EI])

    def jac(self, u: ArrayLike) -> np.ndarray:
        """``d (m(L) L / EI) / d u``, shape ``(1, 2)`` (complex step, exact to rounding; the
        one rod on Python's complex numbers, as a shooting Newton step does)."""
        m0, force = self._physical(u)
        J = tip_states(self.EI, self.L, np.array([m0]), force[None], 0.0,
                       2 * self.segments + 1)[1][0]
        return np.array([[J[3, 0], J[3, 1:] @ self.direction / self.L]])

    def index(self, u: ArrayLike) -> int:
        """Unstable directions of the equilibrium at ``u`` (0: stable)."""
        rod = self.rod(u)
        block = rod_block(self.EI, self.L, rod.theta[1::2], rod.force)
        return constrained_index([block], np.empty((0, self.segments)))

    def start(self, k_rel: float, mode: int = 1) -> np.ndarray:
        """``u`` of the closed-form rod ``(psi, k_rel, mode)``: a point on a curve (to the RK4
        error, which Newton's corrector removes)."""
        rod = clamped_pinned(self.EI, self.L, np.mod(self.psi, 2.0 * np.pi), k_rel, mode)
        return np.array([float(rod.clamp_moment) * self.L / self.EI,
                         float(rod.R) * self.L ** 2 / self.EI])
