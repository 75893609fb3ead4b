"""Multiple shooting of a pinned rod from a sketch of its shape (conventions: :mod:`mechnum.rods`).

Single shooting (``rods``'s shooting module) integrates the whole rod from its clamp, and the
rounding of the clamp's unknowns reaches the tip amplified by up to ``exp(lambda L)``; multiple
shooting cuts the rod into segments, each amplifying by ``exp(lambda L / segments)`` only, and
starts from a whole shape, so that the equilibrium found is the one the shape resembles.
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.ode import multiple_shooting
from mechnum.rods._rod import Rod, rod_scales
from mechnum.rods._shooting import MAX_ITER, Shooting, check_resolved, shooting_result


def shoot_pinned_multiple(EI: float, L: float, tip: ArrayLike, seed: Rod, *, segments: int = 4,
                          theta0: float = 0.0, tol: float = 1e-10,
                          maxiter: int = 50) -> Shooting:
    """A pinned rod by multiple shooting (:func:`mechnum.ode.multiple_shooting`) from a shape.

    The state ``(x, y, theta, m, n_x, n_y)`` (the force as two states with ``n' = 0``) is
    integrated by RK4 on ``seed``'s nodes, cut into ``segments``; the unknowns are the states
    at the segments' starts, the equations the clamp ``(0, 0, theta0)``, the pinned tip with
    ``m(L) = 0``, and continuity. The start is a whole shape, so the equilibrium found is the
    one that shape resembles, and each segment amplifies rounding by ``exp(lambda L /
    segments)`` only.

    The sketch must bend as the rod sought does: its angles and moments select the
    equilibrium. A sketch with no moment will do (Newton finds the moments), a straight one
    will not: along a straight line the axial force moves nothing to first order, so its
    Jacobian is singular (or nearly, and Newton wanders), and the solver raises.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    tip : array_like, shape (2,)
        The pinned point (m), within ``L`` of the clamp.
    seed : Rod
        A sketch of the rod (the seed): its nodes (``N >= 2``, equally spaced from 0 to ``L``),
        shape, moments and force (a zero force will do).
    segments : int, optional
        Number of segments, ``1 <= segments <= N - 1`` (1 is plain shooting).
    theta0, tol, maxiter
        Clamp angle (rad); Newton's residual tolerance and most iterations (at most
        :data:`MAX_ITER`).

    Returns
    -------
    mechnum.rods.Shooting
        ``newton`` is the :class:`~mechnum.newton.NewtonResult` of the segments' states,
        ``x`` the solution's ``(m0, n_x, n_y)`` and ``start`` the seed's.

    Raises
    ------
    ValueError
        If an input is malformed or the point is out of reach.
    ConvergenceError, SingularJacobianError
        If Newton fails (from a straight sketch, for one).
    UnresolvedRodError
        If the rod found is no equilibrium to RK4's error.

    Examples
    --------
    A sketch that dips below the chord and comes back up, with no moment and no force, finds
    the mode-2 rod of that shape through the thesis's point (``k_rel < 0``: it bends down
    first):

    >>> s = np.linspace(0.0, 1.0, 61)
    >>> y = 0.1 * s - 0.15 * np.sin(np.pi * s)
    >>> sketch = Rod(s, 0.8 * s, y, np.arctan2(np.gradient(y, s), 0.8), np.zeros(61),
    ...              np.zeros(2))
    >>> res = shoot_pinned_multiple(1.0, 1.0, [0.8, 0.1], sketch, segments=6)
    >>> np.round(res.rod.force, 3).tolist(), round(float(res.rod.clamp_moment), 3)
    ([-19.589, -7.054], -3.684)
    """
    EI, L = rod_scales(EI, L, scalar=True)
    tip = _validate.array(tip, "tip", shape=(2,))
    if np.hypot(*tip) > L:
        raise ValueError(f"the pinned point {tip!r} is farther than L = {L} from the clamp")
    theta0 = _validate.scalar(theta0, "theta0")
    maxiter = _validate.maxiter(maxiter, maximum=MAX_ITER)
    if not isinstance(seed, Rod):
        raise ValueError(f"seed must be a Rod (a sketch of the shape), got {type(seed)}")
    s = _validate.array(seed.s, "seed.s", ndim=1)
    states = [_validate.array(getattr(seed, name), f"seed.{name}", shape=s.shape)
              for name in ("x", "y", "theta", "m")]
    force = _validate.array(seed.force, "seed.force", shape=(2,))
    if s.size < 2 or not np.allclose(s, np.linspace(0.0, L, s.size), rtol=0, atol=1e-12 * L):
        raise ValueError(f"seed.s must be {s.size} >= 2 equally spaced nodes from 0 to L = {L}")

    def rhs(_, z):      # (x / L, y / L, theta, m, n_x, n_y), in sigma = s / L
        out = np.zeros_like(z)
        c, sn = np.cos(z[..., 2]), np.sin(z[..., 2])
        out[..., 0], out[..., 1], out[..., 2] = c, sn, z[..., 3] * (L / EI)
        out[..., 3] = L * (z[..., 4] * sn - z[..., 5] * c)
        return out

    counts = _Counts()

    def bc(za, zb):
        counts.add(np.iscomplexobj(za) or np.iscomplexobj(zb))
        return np.array([za[0], za[1], za[2] - theta0, zb[0] - tip[0] / L, zb[1] - tip[1] / L,
                         zb[3] * L / EI])

    Z = np.column_stack((states[0] / L, states[1] / L, states[2], states[3],
                         np.broadcast_to(force, (s.size, 2))))
    sol = multiple_shooting(rhs, bc, s / L, Z, segments=segments, tol=tol, maxiter=maxiter)
    y = sol.x
    rod = Rod(s, y[:, 0] * L, y[:, 1] * L, y[:, 2], y[:, 3], y[0, 4:].copy())
    x = np.array([y[0, 3], *y[0, 4:]])
    batch = Rod(*(np.asarray(v)[None] for v in (rod.s, rod.x, rod.y, rod.theta, rod.m,
                                                 rod.force)))
    result = shooting_result("shoot_pinned_multiple", sol.newton, x[None],
                             np.array([[states[3][0], *force]]), batch, (), tol, counts)
    check_resolved(EI, L, result, segments)
    return result


class _Counts:
    """Calls of the residual and of the Jacobian of multiple shooting, told apart by the
    boundary conditions' arguments (complex in the Jacobian's complex steps: 12 per call)."""

    def __init__(self):
        self.nfev, self._complex = 0, 0

    def add(self, complex_step):
        if complex_step:
            self._complex += 1
        else:
            self.nfev += 1

    @property
    def njev(self):
        return self._complex // 12
