"""Rods whose tips meet at one point, compiled: the systems that the searches and the atlas of
the rod mechanisms evaluate thousands of times.

:class:`MeetingRods` checks the rods and their load once, when it is made, and then evaluates
the compiled closed form (``rods._kernels``) on every batch of iterates without a check, as
:class:`~mechnum.rods.ClampedRods` does for the numpy one.
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods._kernels import joined, meeting
from mechnum.rods._rod import as_modes, as_vectors, rod_scales


class MeetingRods:
    """Rods of one stiffness and one length, clamped at ``origins``, whose tips meet at one
    point under a ``load`` there (the 2RFR's rods and end effector): the residual and the
    Jacobian of that direct problem, compiled, checked once here.

    ``meeting(angles, z)`` is the system in the chart points ``z`` (batch, 2 r): ``f = ((tip_1
    - tip_2) / L, ..., (tip_{r-1} - tip_r) / L, (n_1 + ... + n_r - load) L**2 / EI)`` and its
    Jacobian (batch, 2 r, 2 r). ``joined(angles, u)`` has the joint ``P`` as unknowns too,
    ``u = (z, P)`` (batch, 2 r + 2): ``G = ((tip_1 - P) / L, ..., (tip_r - P) / L, (n_1 + ...
    + n_r - load) L**2 / EI)``, the system that continuation follows as the clamp angles
    change. ``angles`` is ``(r,)``, or ``(batch, r)`` (one row per system); with
    ``jacobian=False`` the Jacobian is None. Neither checks its input: the solvers keep their
    iterates in the chart (``0 < psi < 2 pi``, ``0 < |t| <= T_MAX``).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m) of every rod, positive.
    origins : array_like, shape (r, 2)
        The clamps (m).
    modes : sequence of int
        The rods' buckling modes, ``r`` of them, each ``>= 1``.
    load : array_like, shape (2,)
        The force on the joint (N).

    Examples
    --------
    >>> rods = MeetingRods(1.0, 1.0, [[-0.3, 0.0], [0.3, 0.0]], (1, 1), [0.3, -0.1])
    >>> f, J = rods.meeting(np.array([0.7, 1.0]), np.array([[1.0, 0.5, 2.0, -0.5]]))
    >>> f.shape, J.shape
    ((1, 4), (1, 4, 4))
    """

    def __init__(self, EI: float, L: float, origins: ArrayLike, modes: ArrayLike,
                 load: ArrayLike) -> None:
        self.EI, self.L = rod_scales(EI, L, scalar=True)
        self.modes = as_modes(modes)
        if self.modes.ndim != 1 or not self.modes.size:
            raise ValueError(f"modes must be one mode per rod, got {modes!r:.60}")
        self.origins = np.ascontiguousarray(as_vectors(origins, "origins", 2))
        if self.origins.shape != (self.modes.size, 2):
            raise ValueError(f"origins must be one clamp per rod, shape ({self.modes.size}, 2), "
                             f"got shape {self.origins.shape}")
        self.load = _validate.array(load, "load", shape=(2,))

    def meeting(self, angles: np.ndarray, z: np.ndarray, *, jacobian: bool = True) -> tuple:
        """``(f, J)`` at the chart points ``z`` with the clamps at ``angles`` (see above)."""
        return meeting(self.EI, self.L, self.origins, angles, self.modes, self.load, z,
                       jacobian=jacobian)

    def joined(self, angles: np.ndarray, u: np.ndarray, *, jacobian: bool = True) -> tuple:
        """``(G, D)`` at ``u = (z, P)`` with the clamps at ``angles`` (see above)."""
        return joined(self.EI, self.L, self.origins, angles, self.modes, self.load, u,
                      jacobian=jacobian)
