"""RK4 shooting of planar Kirchhoff rods (conventions: see :mod:`mechnum.rods`).

A rod is integrated from its clamp by :func:`mechnum.ode.rk4`, many rods in one sweep;
:func:`tip_jacobian` differentiates the tip by the complex step; the shooting solvers wrap
:func:`mechnum.newton.solve` (or ``solve_batch``) around them.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import newton
from mechnum.ode import rk4

@dataclass(frozen=True)
class Rod:
    """A deformed rod sampled at ``N`` nodes (leading batch axes first).

    Attributes
    ----------
    s, x, y, theta, m : ndarray, shape (..., N)
        Arc length from the clamp and the state there.
    force : ndarray, shape (..., 2)
        The internal force ``n`` (the force on the rod at its tip), N.
    """

    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    m: np.ndarray
    force: np.ndarray

    @property
    def tip(self):
        """Tip position ``(x(L), y(L))``, shape (..., 2)."""
        return np.stack((self.x[..., -1], self.y[..., -1]), axis=-1)

    @property
    def tip_angle(self):
        """Tangent angle at the tip, ``theta(L)`` (rad)."""
        return self.theta[..., -1]

    @property
    def clamp_moment(self):
        """Bending moment at the clamp, ``m(0)`` (N m)."""
        return self.m[..., 0]


@dataclass(frozen=True)
class Shooting:
    """A rod found by shooting, with the Newton iteration that found it."""

    rod: Rod
    newton: object  # NewtonResult or BatchNewtonResult


def _positive(name, value):
    value = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(value)) or np.any(value <= 0):
        raise ValueError(f"{name} must be finite and positive, got {value!r}")
    return value


def _finite(name, value, last=None):
    value = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(value)):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if last is not None and (value.ndim == 0 or value.shape[-1] != last):
        raise ValueError(f"{name} must have a last axis of length {last}, got {value.shape}")
    return value


def _rhs(EI, L, force):
    """Right-hand side for ``(x / L, y / L, theta, m)`` in ``sigma = s / L`` (``L`` may vary).

    Real or complex: the complex-step derivatives of :func:`tip_jacobian` run through it.
    Few numpy calls per evaluation, as their overhead, not arithmetic, is the cost of a sweep.
    """
    nx, ny, over_EI = force[..., 0] * L, force[..., 1] * L, L / EI

    def f(_, y):
        theta = y[..., 2]
        c, s = np.cos(theta), np.sin(theta)
        out = np.empty_like(y)
        out[..., 0], out[..., 1], out[..., 2] = c, s, y[..., 3] * over_EI
        out[..., 3] = nx * s - ny * c
        return out

    return f


def _inputs(EI, L, m0, force, theta0, origin, nodes):
    """Check the inputs of a sweep and broadcast them to one batch shape."""
    EI, L = _positive("EI", EI), _positive("L", L)
    m0, theta0 = _finite("m0", m0), _finite("theta0", theta0)
    force, origin = _finite("force", force, 2), _finite("origin", origin, 2)
    if int(nodes) != nodes or nodes < 2:
        raise ValueError(f"nodes must be an integer >= 2, got {nodes!r}")
    shape = np.broadcast_shapes(EI.shape, L.shape, m0.shape, theta0.shape,
                                force.shape[:-1], origin.shape[:-1])
    EI, L, m0, theta0 = (np.broadcast_to(a, shape) for a in (EI, L, m0, theta0))
    force, origin = (np.broadcast_to(a, shape + (2,)) for a in (force, origin))
    return EI, L, m0, force, theta0, origin, int(nodes)


def _sweep(EI, L, m0, force, theta0, origin, nodes):
    """One RK4 sweep of a batch of rods: the states, shape ``batch + (nodes, 4)``."""
    y0 = np.stack(np.broadcast_arrays(origin[..., 0] / L, origin[..., 1] / L, theta0, m0), -1)
    Y = np.moveaxis(rk4(_rhs(EI, L, force), y0, np.linspace(0.0, 1.0, nodes)), 0, -2)
    Y[..., :2] *= L[..., None, None]
    return Y


_STEP = 1e-30  # complex step: f(x + i h) = f(x) + i h f'(x) + O(h^2), with no cancellation


def _differentiated(EI, L, m0, force, theta0, origin, nodes, columns):
    """A sweep of complex-step copies of every rod, one per unknown in ``columns``.

    ``columns`` picks among ``(m0, n_x, n_y)``. Returns the states, shape
    ``batch + (len(columns), nodes, 4)``: their real part is the rod, the imaginary part
    divided by ``_STEP`` its derivative with respect to that unknown, exact to rounding.
    """
    E = 1j * _STEP * np.eye(3)[list(columns)]
    return _sweep(EI[..., None], L[..., None], m0[..., None] + E[:, 0],
                  force[..., None, :] + E[:, 1:], theta0[..., None], origin[..., None, :], nodes)


def _rod(Y, s, force):
    return Rod(s, Y[..., 0], Y[..., 1], Y[..., 2], Y[..., 3], force)


def _tip(Y):
    """Tip state (..., 4) and its derivatives (..., 4, ncol) from a differentiated sweep."""
    end = Y[..., -1, :]
    return end[..., 0, :].real, np.swapaxes(end.imag, -1, -2) / _STEP


def _sweeps(EI, L, theta0, nodes, unknowns, columns):
    """A memo of the last differentiated sweep at the unknowns ``p``.

    Newton evaluates the residual and then the Jacobian at the same point; both come from
    one sweep, and so does the rod at the solution.
    """
    memo = {}

    def sweep(p):
        key = p.tobytes()
        if key not in memo:
            memo.clear()
            memo[key] = _differentiated(*_inputs(EI, L, *unknowns(p), theta0, (0.0, 0.0),
                                                 nodes), columns)
        return memo[key]

    return sweep


def integrate(EI, L, m0, force, *, theta0=0.0, origin=(0.0, 0.0), nodes=41):
    """Integrate rods from their clamps by RK4, given the clamp moment and the force.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    m0 : float or array_like
        Bending moment at the clamp, ``m(0)`` (N m).
    force : array_like, shape (..., 2)
        The internal force ``n``, the force on the rod at its tip (N).
    theta0 : float or array_like, optional
        Clamp angle (rad).
    origin : array_like, shape (..., 2), optional
        Clamp position (m).
    nodes : int, optional
        Number of equally spaced nodes, ends included (``nodes - 1`` RK4 steps).

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``, ``batch`` the broadcast of the inputs' shapes.

    Examples
    --------
    >>> rod = integrate(1.0, 1.0, 0.5, [0.0, 0.0], nodes=41)   # pure moment: a circular arc
    >>> bool(abs(rod.tip[1] - (1 - np.cos(0.5)) / 0.5) < 1e-8), float(rod.tip_angle)
    (True, 0.5)
    """
    EI, L, m0, force, theta0, origin, nodes = _inputs(EI, L, m0, force, theta0, origin, nodes)
    Y = _sweep(EI, L, m0, force, theta0, origin, nodes)
    return _rod(Y, np.linspace(0.0, 1.0, nodes) * L[..., None], force)


def tip_jacobian(EI, L, m0, force, *, theta0=0.0, origin=(0.0, 0.0), nodes=41):
    """Tip state and its derivatives with respect to ``(m0, n_x, n_y)``, in one RK4 sweep.

    The derivatives are complex-step derivatives: each rod is integrated, in the same RK4 sweep,
    as three complex copies with ``m0``, ``n_x`` or ``n_y`` moved by ``i h`` (``h = 1e-30``);
    the imaginary part of the tip over ``h`` is the derivative of the discrete RK4 map, exact
    to rounding (no subtraction, so no cancellation). This is the Jacobian a shooting Newton
    needs, for one rod or a batch; it equals the integral of the variational equations.

    Parameters
    ----------
    EI, L, m0, force, theta0, origin, nodes
        As in :func:`integrate`.

    Returns
    -------
    tip : ndarray, shape (..., 4)
        ``(x, y, theta, m)`` at ``s = L``.
    jacobian : ndarray, shape (..., 4, 3)
        ``d tip / d (m0, n_x, n_y)``.

    Examples
    --------
    Near the straight rod (linear beam theory, at fixed ``m0``): ``dy(L)/dm0 = L^2 / (2 EI)``
    and ``dy(L)/dn_y = -L^3 / (6 EI)``.

    >>> tip, J = tip_jacobian(2.0, 1.0, 0.0, [0.0, 1e-9])
    >>> round(float(J[1, 0]), 8), round(float(J[1, 2]), 8), round(float(J[3, 0]), 8)
    (0.25, -0.08333333, 1.0)
    """
    return _tip(_differentiated(*_inputs(EI, L, m0, force, theta0, origin, nodes), (0, 1, 2)))


def _newton(fun, jac, x0, tol, maxiter, criterion="step"):
    if x0.shape[0] == 1:
        res = newton.solve(lambda p: fun(p[None])[0], x0[0], lambda p: jac(p[None])[0],
                           tol=tol, maxiter=maxiter, criterion=criterion)
        return res, res.x[None]
    res = newton.solve_batch(fun, x0, jac, tol=tol, maxiter=maxiter, criterion=criterion)
    return res, res.x


def _beam_column_moment(EI, L, force, theta0):
    """Clamp moment of a linear beam-column under a tip force (transverse P, axial N)."""
    c, s = np.cos(theta0), np.sin(theta0)
    P, N = force[..., 1] * c - force[..., 0] * s, force[..., 0] * c + force[..., 1] * s
    bL = np.sqrt(np.abs(N) / EI) * L
    with np.errstate(divide="ignore", invalid="ignore"):
        factor = np.where(N > 0, np.tanh(bL) / bL, np.tan(np.minimum(bL, 1.4)) / bL)
    factor = np.where(bL < 1e-8, 1.0, np.where((N < 0) & (bL > 1.4), 1.0, factor))
    return P * L * factor


def shoot_cantilever(EI, L, force, *, m0=None, theta0=0.0, nodes=41, tol=1e-13, maxiter=50):
    """A cantilever under a given tip force, by shooting on the clamp moment.

    Newton (:func:`mechnum.newton.solve`) adjusts ``m0`` until ``m(L) = 0``; the Jacobian is
    exact (:func:`tip_jacobian`). The equilibrium found depends on the initial ``m0``: the
    default is the clamp moment of linear beam-column theory (small deflections, the axial
    force kept): ``P tanh(b L) / b`` in tension and ``P tan(b L) / b`` in compression below
    the Euler load, with ``P`` the transverse force and ``b = sqrt(|axial force| / EI)``
    (``P L`` otherwise); it leads to the branch that grows from the unloaded rod.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    force : array_like, shape (2,) or (batch, 2)
        Tip force (N), one or a batch.
    m0 : float or array_like, optional
        Initial guess of the clamp moment (N m).
    theta0 : float, optional
        Clamp angle (rad); the clamp is at the origin.
    nodes : int, optional
        RK4 nodes.
    tol, maxiter
        Newton stops when ``|m(L)| < tol * max(|n| L, EI / L)`` (a residual relative to the
        moments of the problem); most iterations.

    Returns
    -------
    Shooting

    Raises
    ------
    ConvergenceError, SingularJacobianError
        If Newton fails.

    Examples
    --------
    >>> res = shoot_cantilever(1.0, 1.0, [0.0, 1.0])      # Bisshopp-Drucker, P L^2 / EI = 1
    >>> np.round(res.rod.tip, 4).tolist(), res.newton.iterations
    ([0.9436, 0.3017], 3)
    """
    force = _finite("force", force, 2)
    batch = force.reshape(-1, 2)
    if m0 is None:
        m0 = _beam_column_moment(EI, L, batch, theta0)
    x0 = np.broadcast_to(_finite("m0", m0).reshape(-1), batch.shape[:1])[:, None]

    sweep = _sweeps(EI, L, theta0, nodes, lambda p: (p[:, 0], batch), (0,))
    scale = max(float(np.abs(batch).max()) * L, EI / L)
    res, p = _newton(lambda p: _tip(sweep(p))[0][:, 3:] / scale,
                     lambda p: _tip(sweep(p))[1][:, 3:] / scale, x0, tol, maxiter, "residual")
    return Shooting(_shot_rod(sweep(p), L, force), res)


def _shot_rod(Y, L, force):
    """The rod (real part of the first complex-step copy) of a memoised sweep."""
    Y = Y[:, 0].real.reshape(force.shape[:-1] + Y.shape[-2:])
    return _rod(Y, np.broadcast_to(np.linspace(0.0, L, Y.shape[-2]), Y.shape[:-1]), force)


def shoot_pinned(EI, L, tip, guess, *, theta0=0.0, nodes=41, tol=1e-10, maxiter=50):
    """A rod clamped at the origin whose tip is pinned at a given point, by shooting.

    The unknowns are ``p = (m0, n_x, n_y)``; Newton drives the residual
    ``(x(L) - x_t, y(L) - y_t, m(L))`` to zero with the exact Jacobian of
    :func:`tip_jacobian`. A pinned point has many equilibria (buckling modes, both senses of
    bending): the initial guess selects one.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    tip : array_like, shape (2,) or (batch, 2)
        The pinned point(s) (m); must lie within ``L`` of the clamp.
    guess : array_like, shape (3,) or (batch, 3)
        Initial ``(m0, n_x, n_y)`` (N m, N, N).
    theta0, nodes, tol, maxiter
        As in :func:`shoot_cantilever` (``tol`` on the Newton step).

    Returns
    -------
    Shooting

    Raises
    ------
    ValueError
        If a point is farther than ``L`` from the clamp (an inextensible rod cannot reach it).
    ConvergenceError, SingularJacobianError
        If Newton fails.

    Examples
    --------
    >>> res = shoot_pinned(1.0, 1.0, [0.8, 0.1], [4.0, -20.0, 2.0])
    >>> np.round(res.rod.tip, 12).tolist(), abs(float(res.rod.m[-1])) < 1e-12
    ([0.8, 0.1], True)
    """
    tip, guess = _finite("tip", tip, 2), _finite("guess", guess, 3)
    if np.any(np.hypot(tip[..., 0], tip[..., 1]) > L):
        raise ValueError(f"a pinned point {tip!r} is farther than L = {L} from the clamp")
    points = tip.reshape(-1, 2)
    x0 = np.broadcast_to(guess, tip.shape[:-1] + (3,)).reshape(-1, 3)

    sweep = _sweeps(EI, L, theta0, nodes, lambda p: (p[:, 0], p[:, 1:]), (0, 1, 2))

    def fun(p):
        end = _tip(sweep(p))[0]
        return np.column_stack((end[:, :2] - points, end[:, 3]))

    res, p = _newton(fun, lambda p: _tip(sweep(p))[1][:, [0, 1, 3], :], x0, tol, maxiter)
    return Shooting(_shot_rod(sweep(p), L, p[:, 1:].reshape(tip.shape)), res)
