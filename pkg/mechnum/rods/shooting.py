"""RK4 shooting of planar Kirchhoff rods (conventions: see :mod:`mechnum.rods`).

A rod is integrated from its clamp by RK4 (:func:`integrate`); :func:`tip_jacobian`
differentiates the tip by the complex step; the shooting solvers wrap damped Newton
(:func:`mechnum.newton.solve`, or ``solve_batch`` for a batch of rods) around them, from a
start that lands on the intended equilibrium.

**Two sweeps, one algorithm.** A batch of rods advances in one vectorised sweep of
:func:`mechnum.ode.rk4` (arrays of shape ``(batch, 4)``). One rod alone takes the same RK4
steps on Python floats (:func:`_sweep_one`): a numpy call costs about a microsecond whatever
its size, a rod has four states, and the float sweep is an order of magnitude faster
(``bench/bench_rods.py``). The tests hold the two to the same digits.

**What shooting can resolve.** The tip depends on the clamp moment through the whole rod, and
``d m(L) / d m0`` grows quickly with the load (about ``1e4`` at ``lambda L = 10``, with
``lambda = sqrt(|n| / EI)``; without bound on a grid too coarse for RK4), so the rounding of
``m0`` reaches the tip multiplied by that factor. Newton stops when the residual is below
``tol`` or below that floor (:data:`ROUNDOFF_FACTOR` ulps of the start's unknowns, amplified
by the start's Jacobian), and refuses a rod whose floor exceeds :data:`MAX_FLOOR`: beyond it,
multiple shooting (:func:`shoot_pinned_multiple`), more nodes or the closed form is needed.
"""

import cmath
import functools
import math
from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError, MechnumError, SingularJacobianError
from mechnum.ode import _rk4, multiple_shooting

_STEP = 1e-30  # complex step: f(x + i h) = f(x) + i h f'(x) + O(h^2), with no cancellation
_EPS = np.finfo(float).eps
ROUNDOFF_FACTOR = 64.0
"""Ulps of rounding allowed in the unknowns before amplification (a margin of some ten over the
``sqrt(nodes)`` ulps that a sweep of a few hundred steps accumulates)."""
MAX_FLOOR = 1e-6
"""Largest residual floor accepted: a rod whose rounding alone leaves a relative residual of
``1e-6`` (``d m(L) / d m0`` near ``1e8``, ``lambda L`` near 18) is beyond single shooting."""
BRACKET_DOUBLINGS = 12
"""Steps of the search for a sign change of ``m(L)`` from a start where damped Newton fails:
from an eighth of the moment scale ``max(|n| L, EI / L)`` up to 256 times it."""
BISECTIONS = 10
"""Halvings of that bracket before Newton takes over: a thousandth of its width, well inside
Newton's quadratic basin of a simple root."""
START_TOL = 1e-9
"""Residual (tip distance over ``L``) at which the closed-form start of a pinned rod is good
enough: RK4 on the requested grid differs from the closed form by more."""
START_MAXITER = 60
"""Most iterations of that start's Newton (two or three on a transverse load, up to some seven
on loads within 45 degrees of transverse, from ``P L**2 / EI = 0.1`` to 15)."""
START_TABLE = np.linspace(0.0, 8.0, 61)
"""The values of ``lambda L`` at which the start's table of transversely loaded cantilevers is
computed: ``P L**2 / EI`` up to 64, deflections up to ``0.93 L`` (a point beyond starts from
the last)."""
SHOOTING_TOL = 1e-12
"""Newton's tolerance on a dimensionless shooting residual (positions over ``L``, forces over
``EI / L**2``, moments over ``EI / L``): its round-off is ~1e-15, a margin of a thousand."""


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
    """A rod found by shooting, with the Newton iteration that found it.

    Attributes
    ----------
    rod : Rod
        The rod at the solution.
    newton : NewtonResult or BatchNewtonResult
        The iteration on the requested grid.
    start : ndarray, shape (..., k)
        The unknowns that iteration started from: ``m0`` for a cantilever, ``(m0, n_x, n_y)``
        for a pinned rod.
    """

    rod: Rod
    newton: object
    start: np.ndarray


def _vectors(value, name, size):
    """``value`` as a finite real float array whose last axis has length ``size``."""
    out = _validate.array(value, name)
    if out.ndim == 0 or out.shape[-1] != size:
        raise ValueError(f"{name} must have a last axis of length {size}, got shape {out.shape}")
    return out


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


def equations(EI, force):
    """The rod's equations (the study's (78)) as ``f(s, state)``, for any ODE or BVP solver.

    ``state = (x, y, theta, m)`` along the **first** axis (shape ``(4,)`` for one point,
    ``(4, k)`` for ``k`` points, as :func:`scipy.integrate.solve_ivp` and
    :func:`scipy.integrate.solve_bvp` pass it); ``f`` returns ``(cos theta, sin theta,
    m / EI, n_x sin theta - n_y cos theta)`` of the same shape. The package's own sweeps use
    the same lines, in ``s / L``.

    Parameters
    ----------
    EI : float or array_like
        Bending stiffness (N m^2).
    force : array_like, shape (2,)
        The force on the rod at its tip (N); it may be an unknown of a boundary value problem.

    Returns
    -------
    callable

    Examples
    --------
    >>> f = equations(2.0, [0.0, 1.0])
    >>> f(0.0, np.array([0.0, 0.0, 0.0, 1.0])).tolist()
    [1.0, 0.0, 0.5, -1.0]
    """
    force = np.asarray(force)
    rhs = _rhs(EI, 1.0, force)

    def f(s, state):
        return np.moveaxis(rhs(s, np.moveaxis(np.asarray(state), 0, -1)), -1, 0)

    return f


def _inputs(EI, L, m0, force, theta0, origin, nodes):
    """Check the inputs of a sweep and broadcast them to one batch shape."""
    EI, L = _validate.positive(EI, "EI"), _validate.positive(L, "L")
    m0, theta0 = _validate.array(m0, "m0"), _validate.array(theta0, "theta0")
    force, origin = _vectors(force, "force", 2), _vectors(origin, "origin", 2)
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    shape = np.broadcast_shapes(EI.shape, L.shape, m0.shape, theta0.shape,
                                force.shape[:-1], origin.shape[:-1])
    EI, L, m0, theta0 = (np.broadcast_to(a, shape) for a in (EI, L, m0, theta0))
    force, origin = (np.broadcast_to(a, shape + (2,)) for a in (force, origin))
    return EI, L, m0, force, theta0, origin, nodes


def _sweep(EI, L, m0, force, theta0, origin, nodes):
    """One RK4 sweep of a batch of rods: the states, shape ``batch + (nodes, 4)``."""
    y0 = np.stack(np.broadcast_arrays(origin[..., 0] / L, origin[..., 1] / L, theta0, m0), -1)
    Y = np.moveaxis(_rk4(_rhs(EI, L, force), y0, np.linspace(0.0, 1.0, nodes).tolist()), 0, -2)
    Y[..., :2] *= L[..., None, None]
    return Y


def _sweep_one(EI, L, m0, nx, ny, theta0, nodes, trig=math, keep=True):
    """The RK4 sweep of one rod on Python scalars (float, or complex with ``trig=cmath``).

    The stages are those of :func:`mechnum.ode.rk4` for ``(x / L, y / L, theta, m)`` in
    ``sigma = s / L``; as ``x`` and ``y`` do not enter the right-hand side, their stages need
    only the stages of ``theta``. Returns the lists ``x, y, theta, m`` at every node (with
    ``keep``) or at the tip only.
    """
    cos, sin = trig.cos, trig.sin
    c_EI, nx, ny, h = L / EI, nx * L, ny * L, 1.0 / (nodes - 1)
    half, sixth = 0.5 * h, h / 6.0
    x, y, t, m = 0.0, 0.0, theta0, m0
    xs, ys, ts, ms = [x], [y], [t], [m]
    for _ in range(nodes - 1):
        c1, s1 = cos(t), sin(t)
        t2, m2 = t + half * c_EI * m, m + half * (nx * s1 - ny * c1)
        c2, s2 = cos(t2), sin(t2)
        t3, m3 = t + half * c_EI * m2, m + half * (nx * s2 - ny * c2)
        c3, s3 = cos(t3), sin(t3)
        t4, m4 = t + h * c_EI * m3, m + h * (nx * s3 - ny * c3)
        c4, s4 = cos(t4), sin(t4)
        cc, ss = c1 + 2.0 * (c2 + c3) + c4, s1 + 2.0 * (s2 + s3) + s4
        x, y = x + sixth * cc, y + sixth * ss
        t, m = t + sixth * c_EI * (m + 2.0 * (m2 + m3) + m4), m + sixth * (nx * ss - ny * cc)
        if keep:
            xs.append(x), ys.append(y), ts.append(t), ms.append(m)
    if not keep:
        xs, ys, ts, ms = [x], [y], [t], [m]
    return [v * L for v in xs], [v * L for v in ys], ts, ms


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
        Number of equally spaced nodes, ends included (``nodes - 1`` RK4 steps), ``>= 2``.

    Returns
    -------
    Rod
        Arrays of shape ``batch + (nodes,)``, ``batch`` the broadcast of the inputs' shapes
        (possibly empty).

    Raises
    ------
    ValueError
        If an input is not finite, ``EI`` or ``L`` is not positive, a shape is wrong, or
        ``nodes`` is not an integer ``>= 2``.

    Examples
    --------
    >>> rod = integrate(1.0, 1.0, 0.5, [0.0, 0.0], nodes=41)   # pure moment: a circular arc
    >>> bool(abs(rod.tip[1] - (1 - np.cos(0.5)) / 0.5) < 1e-8), round(float(rod.tip_angle), 12)
    (True, 0.5)
    """
    EI, L, m0, force, theta0, origin, nodes = _inputs(EI, L, m0, force, theta0, origin, nodes)
    if m0.size == 1:
        x, y, t, m = _sweep_one(float(EI.flat[0]), float(L.flat[0]), float(m0.flat[0]),
                                float(force.flat[0]), float(force.flat[1]),
                                float(theta0.flat[0]), nodes)
        Y = np.column_stack((x, y, t, m)).reshape(m0.shape + (nodes, 4))
        Y[..., 0] += origin[..., 0, None]
        Y[..., 1] += origin[..., 1, None]
    else:
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

    Raises
    ------
    ValueError
        As :func:`integrate`.

    Examples
    --------
    Near the straight rod (linear beam theory, at fixed ``m0``): ``dy(L)/dm0 = L^2 / (2 EI)``
    and ``dy(L)/dn_y = -L^3 / (6 EI)``.

    >>> tip, J = tip_jacobian(2.0, 1.0, 0.0, [0.0, 1e-9])
    >>> round(float(J[1, 0]), 8), round(float(J[1, 2]), 8), round(float(J[3, 0]), 8)
    (0.25, -0.08333333, 1.0)
    """
    return _tip(_differentiated(*_inputs(EI, L, m0, force, theta0, origin, nodes), (0, 1, 2)))


class _Tips:
    """The tips of rods clamped at the origin at ``theta0``, as a function of the unknowns.

    ``split(p)`` maps the unknowns ``p`` (batch, k) to ``(m0, force)``; ``columns`` says which
    of ``(m0, n_x, n_y)`` they are. Newton asks for the residual and then the Jacobian at the
    same point: a memo of the last sweep serves both. One rod takes the float sweep.
    """

    def __init__(self, EI, L, theta0, nodes, split, columns):
        self.EI, self.L, self.theta0, self.nodes = EI, L, theta0, nodes
        self.split, self.columns, self.key, self.value = split, columns, None, None

    def __call__(self, p, jac=False):
        key = p.tobytes()
        if key != self.key or (jac and self.value[1] is None):
            m0, force = self.split(p)
            if len(p) == 1:
                try:
                    value = self._one(float(m0[0]), *force[0].tolist(), jac)
                except (OverflowError, ValueError):  # math's and cmath's word for infinity
                    value = np.full((1, 4), np.nan), np.full((1, 4, len(self.columns)), np.nan)
            else:
                value = self._batch(m0, force, jac)
            self.key, self.value = key, value
        return self.value

    def _one(self, m0, nx, ny, jac):
        args = (self.EI, self.L, m0, nx, ny, self.theta0, self.nodes)
        if not jac:
            return np.array([[v[0] for v in _sweep_one(*args, keep=False)]]), None
        J = np.empty((1, 4, len(self.columns)))
        for j, column in enumerate(self.columns):   # one complex-step sweep per unknown
            moved = list(args)
            moved[2 + column] += 1j * _STEP
            end = [v[0] for v in _sweep_one(*moved, trig=cmath, keep=False)]
            J[0, :, j] = [v.imag / _STEP for v in end]
        return np.array([[v.real for v in end]]), J

    def _batch(self, m0, force, jac):
        EI, L, theta0 = (np.full(len(m0), v) for v in (self.EI, self.L, self.theta0))
        args = (EI, L, m0, force, theta0, np.zeros((len(m0), 2)), self.nodes)
        if not jac:
            return _sweep(*args)[:, -1, :], None
        return _tip(_differentiated(*args, self.columns))


def _floor(J, scale_in, scale_out, p):
    """The rounding floor of a residual: ``ROUNDOFF_FACTOR`` ulps of the unknowns, amplified."""
    J = np.abs(J) * scale_in[..., None, :] / scale_out[..., :, None]
    size = np.maximum(np.abs(p / scale_in).max(axis=-1), 1.0)
    return float(np.max(J.max(axis=(-2, -1)) * size, initial=0.0)) * ROUNDOFF_FACTOR * _EPS


def _solve(fun, jac, x0, tol, floor, maxiter, what, damping=True):
    """Damped Newton from ``x0`` (batch, k): one system by ``solve``, a batch by
    ``solve_batch``; the tolerance is raised to the rounding floor ``floor``."""
    if floor > MAX_FLOOR:
        raise ConvergenceError(
            f"{what}: rounding in the unknowns reaches the tip amplified by "
            f"{floor / _EPS / ROUNDOFF_FACTOR:.3g} (d tip / d unknowns): single shooting cannot "
            f"resolve this rod (use more nodes, multiple shooting or the closed form)")
    tol = max(tol, floor)
    if len(x0) == 1:
        k = x0.shape[1]
        res = newton.solve(lambda p: fun(p.reshape(-1, k)).reshape(p.shape), x0[0],
                           lambda p: jac(p[None])[0], tol=tol, maxiter=maxiter,
                           criterion="residual", damping=damping)
        return res, res.x[None]
    res = newton.solve_batch(fun, x0, jac, tol=tol, maxiter=maxiter, criterion="residual",
                             damping=damping)
    return res, res.x


def _cantilever_start(EI, L, forces, theta0):
    """The clamp moments of the closed-form cantilevers (mode 1) under ``forces`` (batch, 2)."""
    # the closed form builds on this module: import it here
    from mechnum.rods.elliptic import CLOSED_FORM_MAXITER, CLOSED_FORM_TOL, _cantilever

    c, s = math.cos(theta0), math.sin(theta0)
    m0 = np.zeros(len(forces))
    for i, (nx, ny) in enumerate(forces.tolist()):
        local = (c * nx + s * ny, c * ny - s * nx)
        if local[1] != 0:
            m0[i] = _cantilever(EI, L, local, 2, CLOSED_FORM_TOL, CLOSED_FORM_MAXITER).m[0]
    return m0


def shoot_cantilever(EI, L, force, *, m0=None, theta0=0.0, nodes=41, tol=1e-13, maxiter=50,
                     damping=True):
    """A cantilever under a given tip force, by shooting on the clamp moment.

    Damped Newton (:func:`mechnum.newton.solve`) adjusts ``m0`` until ``m(L) = 0``, with the
    exact Jacobian of the RK4 sweep. The equilibrium found depends on the start: the default
    is the clamp moment of the closed form (:func:`mechnum.rods.cantilever`), the equilibrium
    that grows continuously from the unloaded rod (mode 1, bending towards the force), which
    RK4 on ``nodes`` nodes then reproduces to its discretisation error in one or two Newton
    steps. A start of your own may lead elsewhere (above the Euler load, to the rod bent the
    other way).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    force : array_like, shape (2,) or (batch, 2)
        Tip force (N), one or a batch (possibly empty).
    m0 : float or array_like, optional
        Start of the clamp moment (N m), one or one per force.
    theta0 : float, optional
        Clamp angle (rad); the clamp is at the origin.
    nodes : int, optional
        RK4 nodes, ``>= 2``.
    tol, maxiter
        Newton stops when ``|m(L)| < tol * max(|n| L, EI / L)`` (a residual relative to the
        moments of the problem), or below the rounding floor of the module's description if
        that is larger; most iterations.
    damping : bool, optional
        Backtrack along Newton's steps (Armijo); for one rod, if damped Newton still fails,
        restart from the sign change of ``m(L)`` nearest the start. ``False`` is plain Newton.

    Returns
    -------
    Shooting

    Raises
    ------
    ValueError
        If an input is not finite, of the wrong shape, or out of range.
    ConvergenceError, SingularJacobianError
        If Newton fails, or the rod is beyond what single shooting resolves.

    Examples
    --------
    >>> res = shoot_cantilever(1.0, 1.0, [0.0, 1.0])      # Bisshopp-Drucker, P L^2 / EI = 1
    >>> np.round(res.rod.tip, 4).tolist(), res.newton.iterations
    ([0.9436, 0.3017], 1)
    """
    EI, L = _validate.scalar(EI, "EI", positive=True), _validate.scalar(L, "L", positive=True)
    force = _vectors(force, "force", 2)
    if force.ndim > 2:
        raise ValueError(f"force must have shape (2,) or (batch, 2), got shape {force.shape}")
    theta0 = _validate.scalar(theta0, "theta0")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    tol, maxiter = _validate.tolerance(tol), _validate.maxiter(maxiter)
    batch = force.reshape(-1, 2)
    if m0 is None:
        start = _cantilever_start(EI, L, batch, theta0)
    else:
        start = np.broadcast_to(_validate.array(m0, "m0").reshape(-1), batch.shape[:1]).copy()
    tips = _Tips(EI, L, theta0, nodes, lambda p: (p[:, 0], batch), (0,))
    scale = max(float(np.abs(batch).max(initial=0.0)) * L, EI / L)
    fun = lambda p: tips(p)[0][:, 3:] / scale                       # noqa: E731
    jac = lambda p: tips(p, jac=True)[1][:, 3:, :] / scale          # noqa: E731
    x0 = start[:, None]
    floor = _floor(jac(x0), np.ones(1), np.ones(1), x0 / scale)
    try:
        res, p = _solve(fun, jac, x0, tol, floor, maxiter, "shoot_cantilever", bool(damping))
    except (ConvergenceError, SingularJacobianError):
        if len(batch) != 1 or not damping:
            raise
        # a start beyond a hump of m(L): restart from the sign change of m(L) nearest it
        x0 = _bracket(lambda m0: float(fun(np.array([[m0]]))[0, 0]), float(x0[0, 0]), scale)
        res, p = _solve(fun, jac, x0, tol, floor, maxiter, "shoot_cantilever")
    rod = integrate(EI, L, p[:, 0], batch, theta0=theta0, nodes=nodes)
    return Shooting(_reshaped(rod, force.shape[:-1]), res, start.reshape(force.shape[:-1]))


def _bracket(g, x, width):
    """A start for Newton on the scalar ``g`` where it changes sign nearest ``x``.

    Points ``x +- width 2**j / 8`` are tried on both sides, outwards, until ``g`` changes sign
    between neighbours; that bracket is halved :data:`BISECTIONS` times and its midpoint
    returned, shape (1, 1). Raises :class:`ConvergenceError` if no sign change is found.
    """
    last = {-1.0: (x, g(x)), 1.0: (x, g(x))}
    for step in width / 8 * 2.0 ** np.arange(BRACKET_DOUBLINGS):
        for direction in (-1.0, 1.0):
            (near, g_near), far = last[direction], x + direction * step
            g_far = g(far)
            if g_near * g_far <= 0:
                for _ in range(BISECTIONS):
                    mid = 0.5 * (near + far)
                    near, far = (mid, far) if g(mid) * g_far > 0 else (near, mid)
                return np.array([[0.5 * (near + far)]])
            last[direction] = far, g_far
    raise ConvergenceError(f"shoot_cantilever: m(L) changes sign nowhere within "
                           f"{step:.3g} N m of the start {x!r}")


def _reshaped(rod, batch):
    """``rod`` with its leading axis reshaped to ``batch`` (``()`` for one rod)."""
    return Rod(*(getattr(rod, name).reshape(batch + getattr(rod, name).shape[1:])
                 for name in ("s", "x", "y", "theta", "m", "force")))


@functools.cache
def _transverse_table():
    """``(y(L) / L, P L**2 / EI)`` of cantilevers under a transverse tip load ``P`` at
    ``lambda L`` in :data:`START_TABLE`, by the closed form (computed once)."""
    from mechnum.rods.elliptic import _growing_tip   # the closed form builds on this module

    y = [_growing_tip(0.5 * math.pi, lam)[1] for lam in START_TABLE.tolist()]
    return np.array(y), START_TABLE ** 2


def _pinned_start(EI, L, points, theta0):
    """The default start of :func:`shoot_pinned`: the closed-form cantilever through the point.

    A pinned tip carries no moment, so a pinned rod of mode 1 is the cantilever (growing
    branch) under its tip force. Damped Newton drives the closed form's tip to the point in
    the force's components ``n L**2 / EI`` in the clamp's frame (in which the tip of a nearly
    straight rod is nearly linear: its deflection follows ``n_y``, its shortening ``n_x``
    weakly), from the transverse load whose cantilever deflects as far as the point does:
    ``3 EI Y / L**3`` at small loads (linear beam theory, ``Y`` the point's offset from the
    clamp line), interpolated in a table of the closed form (:func:`_transverse_table`) at
    large ones. If Newton stops short (no mode-1 rod reaches the point, or a nearly straight
    rod leaves its axial force ill-determined), its best iterate is the start.
    """
    from mechnum.rods.elliptic import _growing_tip   # the closed form builds on this module

    def growing(n):      # the closed form at the load n = (n_x, n_y) L**2 / EI
        return _growing_tip(math.atan2(n[1], n[0]), math.sqrt(math.hypot(n[0], n[1])))

    deflections, loads = _transverse_table()
    c, s = math.cos(theta0), math.sin(theta0)
    starts = np.empty((len(points), 3))
    for i, (px, py) in enumerate(points.tolist()):
        X, Y = (c * px + s * py) / L, (c * py - s * px) / L   # the point in the clamp's frame

        def fun(n):      # n of shape (2,), or (1, 2) in the line search
            return np.reshape(np.subtract(growing(n.ravel())[:2], (X, Y)), n.shape)

        n = np.array([0.0, math.copysign(np.interp(abs(Y), deflections, loads), Y)])
        try:
            n = newton.solve(fun, n, tol=START_TOL, maxiter=START_MAXITER,
                             criterion="residual", damping=True).x
        except MechnumError as error:
            n = error.result.history[np.argmin(error.result.residual_norms)]
        nx, ny = n.tolist()
        starts[i] = (growing(n)[2] * EI / L,
                     EI / L ** 2 * (c * nx - s * ny), EI / L ** 2 * (s * nx + c * ny))
    return starts


def _pinned(EI, L, points, x0, theta0, nodes, tol, maxiter, damping):
    """Damped Newton on the pinned-tip residual from ``x0`` (batch, 3): (result, unknowns)."""
    tips = _Tips(EI, L, theta0, nodes, lambda p: (p[:, 0], p[:, 1:]), (0, 1, 2))
    scale_in = np.array([EI / L, EI / L ** 2, EI / L ** 2])      # m0, n_x, n_y
    scale_out = np.array([L, L, EI / L])                          # x, y, m at the tip

    def fun(p):
        end = tips(p)[0]
        return np.column_stack((end[:, :2] - points, end[:, 3])) / scale_out

    def jac(p):
        return tips(p, jac=True)[1][:, [0, 1, 3], :] / scale_out[:, None]

    floor = _floor(jac(x0) * scale_out[:, None], scale_in, scale_out, x0)
    return _solve(fun, jac, x0, tol, floor, maxiter, "shoot_pinned", damping)


def shoot_pinned(EI, L, tip, guess=None, *, theta0=0.0, nodes=41, tol=1e-12, maxiter=50,
                 damping=True):
    """A rod clamped at the origin whose tip is pinned at a given point, by shooting.

    The unknowns are ``p = (m0, n_x, n_y)``; damped Newton drives the residual
    ``((x(L) - x_t) / L, (y(L) - y_t) / L, m(L) L / EI)`` to zero with the exact Jacobian of
    :func:`tip_jacobian`. A pinned point has many equilibria (buckling modes, both senses of
    bending): the start selects one. The default start is the closed-form cantilever (mode 1,
    the growing branch) whose tip is at the point, found by damped Newton from the transverse
    load that deflects a cantilever as far (:func:`_pinned_start`): it leads to the mode-1 rod
    where the point admits one and Newton reaches it (a point near the reach ``L`` in near
    tension may defeat it: the force of a nearly straight rod is ill-determined by its tip).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    tip : array_like, shape (2,) or (batch, 2)
        The pinned point(s) (m); each within ``L`` of the clamp.
    guess : array_like, shape (3,) or (batch, 3), optional
        Start ``(m0, n_x, n_y)`` (N m, N, N).
    theta0, nodes, tol, maxiter, damping
        As in :func:`shoot_cantilever` (``tol`` on the residual above; ``damping=False`` is
        plain Newton).

    Returns
    -------
    Shooting

    Raises
    ------
    ValueError
        If a point is farther than ``L`` from the clamp (an inextensible rod cannot reach it),
        or another input is malformed.
    ConvergenceError, SingularJacobianError
        If Newton fails.

    Examples
    --------
    >>> res = shoot_pinned(1.0, 1.0, [0.8, 0.1], [4.0, -20.0, 2.0])
    >>> np.round(res.rod.tip, 12).tolist(), abs(float(res.rod.m[-1])) < 1e-12
    ([0.8, 0.1], True)
    """
    EI, L = _validate.scalar(EI, "EI", positive=True), _validate.scalar(L, "L", positive=True)
    tip = _vectors(tip, "tip", 2)
    if tip.ndim > 2:
        raise ValueError(f"tip must have shape (2,) or (batch, 2), got shape {tip.shape}")
    if np.any(np.hypot(tip[..., 0], tip[..., 1]) > L):
        raise ValueError(f"a pinned point {tip!r} is farther than L = {L} from the clamp")
    theta0 = _validate.scalar(theta0, "theta0")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2)
    tol, maxiter = _validate.tolerance(tol), _validate.maxiter(maxiter)
    points = tip.reshape(-1, 2)
    if guess is None:
        start = _pinned_start(EI, L, points, theta0)
    else:
        guess = _vectors(guess, "guess", 3)
        start = np.broadcast_to(guess, tip.shape[:-1] + (3,)).reshape(-1, 3).copy()
    res, p = _pinned(EI, L, points, start, theta0, nodes, tol, maxiter, bool(damping))
    rod = integrate(EI, L, p[:, 0], p[:, 1:], theta0=theta0, nodes=nodes)
    return Shooting(_reshaped(rod, tip.shape[:-1]), res, start.reshape(tip.shape[:-1] + (3,)))


def shoot_pinned_multiple(EI, L, tip, guess, *, segments=4, theta0=0.0, tol=1e-10,
                          maxiter=50):
    """A pinned rod by multiple shooting (:func:`mechnum.ode.multiple_shooting`) from a shape.

    The state ``(x, y, theta, m, n_x, n_y)`` (the force as two states with ``n' = 0``) is
    integrated by RK4 on ``guess``'s nodes, cut into ``segments``; the unknowns are the states
    at the segments' starts, the equations the clamp ``(0, 0, theta0)``, the pinned tip with
    ``m(L) = 0``, and continuity. The start is a whole shape, so the equilibrium found is the
    one that shape resembles, and each segment amplifies rounding by ``exp(lambda L /
    segments)`` only.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    tip : array_like, shape (2,)
        The pinned point (m), within ``L`` of the clamp.
    guess : Rod
        A guess of the rod: its nodes (``N >= 2``, equally spaced from 0 to ``L``), shape and
        force (a sketch will do: a straight line and a zero moment).
    segments : int, optional
        Number of segments, ``1 <= segments <= N - 1`` (1 is plain shooting).
    theta0, tol, maxiter
        Clamp angle (rad); Newton's residual tolerance and most iterations.

    Returns
    -------
    Shooting
        ``newton`` is the :class:`~mechnum.newton.NewtonResult` of the segments' states,
        ``start`` the guess's ``(m0, n_x, n_y)``.

    Raises
    ------
    ValueError
        If an input is malformed or the point is out of reach.
    ConvergenceError, SingularJacobianError
        If Newton fails.

    Examples
    --------
    A sketch that dips below the chord and comes back up finds the mode-2 rod of that shape
    through the thesis's point (``k_rel < 0``: it bends down first):

    >>> s = np.linspace(0.0, 1.0, 61)
    >>> y = 0.1 * s - 0.15 * np.sin(np.pi * s)
    >>> sketch = Rod(s, 0.8 * s, y, np.arctan2(np.gradient(y, s), 0.8), np.zeros(61),
    ...              np.array([0.1, 0.1]))
    >>> res = shoot_pinned_multiple(1.0, 1.0, [0.8, 0.1], sketch, segments=6)
    >>> np.round(res.rod.force, 3).tolist(), round(float(res.rod.clamp_moment), 3)
    ([-19.589, -7.054], -3.684)
    """
    EI, L = _validate.scalar(EI, "EI", positive=True), _validate.scalar(L, "L", positive=True)
    tip = _validate.array(tip, "tip", shape=(2,))
    if np.hypot(*tip) > L:
        raise ValueError(f"the pinned point {tip!r} is farther than L = {L} from the clamp")
    theta0 = _validate.scalar(theta0, "theta0")
    if not isinstance(guess, Rod):
        raise ValueError(f"guess must be a Rod (a sketch of the shape), got {type(guess)}")
    s = _validate.array(guess.s, "guess.s", ndim=1)
    states = [_validate.array(getattr(guess, name), f"guess.{name}", shape=s.shape)
              for name in ("x", "y", "theta", "m")]
    force = _validate.array(guess.force, "guess.force", shape=(2,))
    if s.size < 2 or not np.allclose(s, np.linspace(0.0, L, s.size), rtol=0, atol=1e-12 * L):
        raise ValueError(f"guess.s must be {s.size} >= 2 equally spaced nodes from 0 to L = {L}")
    def rhs(_, z):      # (x / L, y / L, theta, m, n_x, n_y), in sigma = s / L
        out = np.zeros_like(z)
        c, sn = np.cos(z[..., 2]), np.sin(z[..., 2])
        out[..., 0], out[..., 1], out[..., 2] = c, sn, z[..., 3] * (L / EI)
        out[..., 3] = L * (z[..., 4] * sn - z[..., 5] * c)
        return out

    def bc(za, zb):
        return np.array([za[0], za[1], za[2] - theta0, zb[0] - tip[0] / L, zb[1] - tip[1] / L,
                         zb[3] * L / EI])

    Z = np.column_stack((states[0] / L, states[1] / L, states[2], states[3],
                         np.broadcast_to(force, (s.size, 2))))
    sol = multiple_shooting(rhs, bc, s / L, Z, segments=segments, tol=tol, maxiter=maxiter)
    y = sol.y
    rod = Rod(s, y[:, 0] * L, y[:, 1] * L, y[:, 2], y[:, 3], y[0, 4:].copy())
    return Shooting(rod, sol.newton, np.array([states[3][0], *force]))
