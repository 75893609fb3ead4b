"""The power-hacksaw mechanism of the hacksaw study (report and slides; Chapter 1).

An offset crank-slider: the motor turns the crank ``r2`` (angle ``theta2``); the coupler ``r3``
(angle ``theta3``) drives the saw frame, whose pin slides on a guide at height ``r1y`` above the
crank pivot. The vector ``r1 = r2 + r3`` from the crank pivot to the slider pin has length ``r1``
and angle ``theta1``, with ``r1 sin(theta1) = r1y``. The study follows the branch with the coupler
pointing back (``theta3`` near ``pi``) and writes ``r1`` with a negative length, ``theta1`` in
``(-pi/2, 0)``; this module keeps that convention.

The nine unknowns, always in this order (SI units, radians)::

    r1, theta1, theta3, Vr, omega1, omega3, Ar, alpha1, alpha3

The constraint equations, in the study's row order:

* position ``(c, x, y)``: ``r1 sin(theta1) - r1y``, ``-r1 cos(theta1) + r2 cos(theta2) +
  r3 cos(theta3)``, ``r1 sin(theta1) - r2 sin(theta2) - r3 sin(theta3)``; the study's
  single-point code first eliminates ``r1 = r1y / sin(theta1)`` from the ``x`` and ``y`` rows
  (``form="eliminated"``), its trajectory code does not (``form="loop"``);
* velocity ``(x', y', c')`` and acceleration ``(c'', x'', y'')``: their first and second time
  derivatives, linear in the unknown rates with the matrix ``J`` of the loop form, whose
  determinant is ``-r1 r3 cos(theta3)``. Where ``cos(theta3) = 0`` (the coupler perpendicular to
  the guide) the rates are undefined: a *dead point*, which the solvers refuse
  (:class:`~mechnum.errors.SingularJacobianError`).

The motor starts from rest with a jerk-limited profile: the angular acceleration rises linearly to
``alpha_max`` over ``T/3``, holds for ``T/3`` and falls back to zero over ``T/3``, where ``T`` is
the time of the first revolution; the speed is constant afterwards.

Every public function checks its input (finite real arrays of the right shapes, a
:class:`Geometry`, known options) and raises :class:`ValueError` naming the argument; the
solvers work on the unchecked private kernels, so the checks cost nothing inside Newton's loop.
"""

import functools
import inspect
from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.errors import GeometryError, SingularJacobianError, UnreachablePoseError
from mechnum.newton import solve, solve_batch

NAMES = ("r1", "theta1", "theta3", "Vr", "omega1", "omega3", "Ar", "alpha1", "alpha3")
ALPHA_MAX = 5.0  # rad/s^2, the study's maximum motor acceleration
TOL = 1e-6  # the study's tolerance on the Euclidean norm of the Newton step
#: The initial guess of the study's MATLAB code (``Pi``).
STUDY_SEED = np.array([-0.1, -0.5, 3.0, -0.5, 0.0, 0.5, -0.5, 0.0, 0.5])
#: The initial guess that the report prints: the MATLAB's with the six rates' signs flipped.
REPORT_SEED = np.array([-0.1, -0.5, 3.0, 0.5, 0.0, -0.5, 0.5, 0.0, -0.5])
#: The seed of the first trajectory point in the study's code: the rounded solution at rest.
TRAJECTORY_SEED = np.array([-0.0997, -0.4684, 2.8737, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
# A dead point: theta3 comes from an arcsin whose error grows like eps / |cos(theta3)|, so the
# rates' relative error grows like eps / cos(theta3)**2. Below this |cos(theta3)| they would keep
# fewer than about eight digits (2.2e-16 / 1e-8): the solvers raise instead of answering.
DEAD_POINT_COS = 1e-4
FORMS = ("loop", "eliminated")
METHODS = ("consecutive", "simultaneous", "batched")
PREDICTORS = ("previous", "velocity")
_RATE_ROWS = [1, 2, 0]  # velocity rows (x', y', c') as position rows (c, x, y)
DRAW_PAD = 0.25  # blank border around a drawing, in crank lengths: room for the joints' dots


@dataclass(frozen=True)
class Geometry:
    """Link lengths of the saw, in metres (defaults: the study's).

    Raises
    ------
    GeometryError
        If a length is not a finite positive real number.

    Examples
    --------
    >>> Geometry(r3=0.2).r3
    0.2
    >>> Geometry(r2=-1.0)
    Traceback (most recent call last):
    ...
    mechnum.errors.GeometryError: r2 must be positive, got -1.0
    """

    r1y: float = 0.045
    r2: float = 0.075
    r3: float = 0.170

    def __post_init__(self):
        for name in ("r1y", "r2", "r3"):
            try:
                value = _validate.scalar(getattr(self, name), name, positive=True)
            except ValueError as error:
                raise GeometryError(str(error)) from None
            object.__setattr__(self, name, value)


STUDY = Geometry()


def _check(geometry=STUDY, states=(), motor=()):
    """Check a geometry, states ``(name, value, width)`` of shape ``(..., width)`` and motor
    quantities ``(name, value)``; return the arrays, once their batch shapes are known to
    broadcast together."""
    if not isinstance(geometry, Geometry):
        raise ValueError(f"geometry must be a hacksaw.Geometry, got {geometry!r}")
    arrays, batches = [], []
    for name, value, width in states:
        a = _validate.array(value, name)
        if a.ndim == 0 or a.shape[-1] != width:
            raise ValueError(f"{name} must have shape (..., {width}), got shape {a.shape}")
        arrays.append(a)
        batches.append((name, a.shape[:-1]))
    for name, value in motor:
        arrays.append(_validate.array(value, name))
        batches.append((name, arrays[-1].shape))
    try:
        np.broadcast_shapes(*(shape for _, shape in batches))
    except ValueError:
        shown = ", ".join(f"{name} {shape}" for name, shape in batches)
        raise ValueError(f"the batch shapes do not broadcast together: {shown}") from None
    return arrays


def _finite(out, what):
    """``out``, if finite; inputs that are finite may still overflow the formulas."""
    if not np.all(np.isfinite(out)):
        raise ValueError(f"{what} is not finite for these inputs: they are too large "
                         f"(overflow) or the form is singular there")
    return out


def _motor_state(motor_state):
    """``(theta2, omega2, alpha2)``, checked: three finite real arrays that broadcast."""
    try:
        th2, w2, a2 = motor_state
    except (TypeError, ValueError):
        raise ValueError(f"motor_state must be (theta2, omega2, alpha2), got {motor_state!r}")
    return _check(motor=(("theta2", th2), ("omega2", w2), ("alpha2", a2)))


def first_revolution_time(alpha_max=ALPHA_MAX):
    """Time ``T`` of the motor's first revolution, from ``theta2(T) = alpha_max T**2 / 3 = 2 pi``.

    Raises
    ------
    ValueError
        If ``alpha_max`` is not a finite positive number, or so small that ``T`` overflows.

    Examples
    --------
    >>> round(first_revolution_time(), 6)
    1.941626
    """
    alpha_max = _validate.scalar(alpha_max, "alpha_max", positive=True)
    T = float(np.sqrt(6.0 * np.pi / alpha_max))
    if not np.isfinite(T):
        raise ValueError(f"alpha_max = {alpha_max!r} is too small: the first revolution "
                         f"time overflows")
    return T


def _motor(t, alpha_max):
    """The motor profile at checked times ``t`` (the kernel of :func:`motor`)."""
    T, A = first_revolution_time(alpha_max), alpha_max
    phase = np.minimum(np.floor(3.0 * t / T), 3.0).astype(int)  # 0, 1, 2 ramps; 3 cruise
    theta = np.choose(phase, [
        A * t**3 / (2 * T),
        A * T**2 / 54 - A * t * (T - 3 * t) / 6,
        A * T**2 / 6 - 5 * A * T * t / 6 + 3 * A * t**2 / 2 - A * t**3 / (2 * T),
        2 * A * T * t / 3 - A * T**2 / 3])
    omega = np.choose(phase, [
        3 * A * t**2 / (2 * T),
        A * t - A * T / 6,
        3 * A * t - 5 * A * T / 6 - 3 * A * t**2 / (2 * T),
        np.full_like(t, 2 * A * T / 3)])
    alpha = np.choose(phase, [3 * A * t / T, np.full_like(t, A), 3 * A - 3 * A * t / T,
                              np.zeros_like(t)])
    return theta, omega, alpha


def motor(t, alpha_max=ALPHA_MAX):
    """Angle, speed and acceleration of the motor at times ``t`` (the study's profile).

    Parameters
    ----------
    t : array_like
        Times in seconds, ``t >= 0``.
    alpha_max : float, optional
        Largest angular acceleration, rad/s^2.

    Returns
    -------
    theta2, omega2, alpha2 : ndarray
        Each of the shape of ``t``, in rad, rad/s and rad/s^2.

    Raises
    ------
    ValueError
        If some ``t`` is negative or not finite, ``alpha_max`` is not finite and positive, or
        ``t`` is so large that the crank angle overflows.

    Examples
    --------
    >>> T = first_revolution_time()
    >>> [round(float(v), 6) for v in motor(T)]
    [6.283185, 6.472086, 0.0]
    """
    t = _validate.array(t, "t")
    if np.any(t < 0):
        raise ValueError(f"t must be non-negative, got a smallest t of {float(t.min())!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        out = _motor(t, alpha_max)
    if not np.all(np.isfinite(out[0])):
        raise ValueError(f"t is too large: the crank angle overflows at t = {float(t.max())!r} s")
    return out


def _public(*states, motor=()):
    """Check the input and output of a public evaluator of the equations: the geometry, the
    ``form`` if there is one, the ``states`` (``(name, width)``: arrays of shape
    ``(..., width)``) and the ``motor`` quantities (names), that their batch shapes broadcast,
    and that the result is finite. (The solvers call the private kernels directly: inside
    Newton's loop the checks would only cost time.)"""
    def decorate(evaluator):
        signature = inspect.signature(evaluator)

        @functools.wraps(evaluator)
        def public(*args, **kwargs):
            bound = signature.bind(*args, **kwargs)
            bound.apply_defaults()
            given = bound.arguments
            checked = _check(given["geometry"], [(n, given[n], w) for n, w in states],
                             [(n, given[n]) for n in motor])
            given.update(zip([n for n, _ in states] + list(motor), checked))
            if "form" in given:
                _validate.choice(given["form"], FORMS, "form")
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                out = evaluator(*bound.args)
            return _finite(out, f"the {evaluator.__name__.replace('_', ' ')}")

        return public
    return decorate


def _parts(x):
    """The components of ``x`` along its last axis (NumPy scalars when ``x`` is 1-D: fast)."""
    return tuple(x) if x.ndim == 1 else tuple(x[..., k] for k in range(x.shape[-1]))


def _trig(x):
    """``sin`` and ``cos`` of ``theta1`` and ``theta3`` of states ``x`` (last axis >= 3)."""
    _, t1, t3 = _parts(x)[:3]
    return np.sin(t1), np.cos(t1), np.sin(t3), np.cos(t3)


def _shared_trig():
    """A ``_trig`` that remembers its last argument. Newton evaluates the residual at an
    iterate, then the Jacobian at the same iterate (the same array): they share its sines and
    cosines. (For the solvers' own closures, whose iterates are never changed in place.)"""
    last = [None, None]

    def trig(x):
        if x is not last[0]:
            last[:] = x, _trig(x)
        return last[1]
    return trig


def _crank(theta2):
    """``sin`` and ``cos`` of the crank angles (they are fixed while Newton iterates)."""
    return np.sin(theta2), np.cos(theta2)


def _pack(*columns):
    """Stack arrays (or scalars) along a new last axis, broadcasting them."""
    try:
        out = np.array(columns, dtype=float)  # scalars, or arrays of one shape
    except ValueError:
        out = np.array(np.broadcast_arrays(*columns))
    return out if out.ndim == 1 else np.moveaxis(out, 0, -1)


def _matrix(n, entries):
    """An ``(..., n, n)`` array of zeros with the ``{(row, col): value}`` entries filled in."""
    shape = np.shape(next(iter(entries.values())))
    if not shape:  # one point: fastest as one list
        rows, cols = zip(*entries)
        out = np.zeros((n, n))
        out[rows, cols] = list(entries.values())
        return out
    out = np.zeros(np.broadcast_shapes(*(np.shape(v) for v in entries.values())) + (n, n))
    for (i, j), value in entries.items():
        out[..., i, j] = value
    return out


@_public(("q", 3), motor=("theta2",))
def position_residual(q, theta2, geometry=STUDY, form="loop"):
    """Position constraints ``(c, x, y)`` at ``q = (r1, theta1, theta3)``.

    ``form="loop"`` is the loop equation as written; ``form="eliminated"`` replaces ``r1`` by
    ``r1y / sin(theta1)`` in the ``x`` and ``y`` rows, as the study's single-point code does.

    Parameters
    ----------
    q : array_like, shape (..., 3)
    theta2 : array_like
        Crank angles, broadcasting against the batch shape ``q.shape[:-1]``.
    geometry : Geometry, optional
    form : {"loop", "eliminated"}, optional

    Returns
    -------
    ndarray, shape: the broadcast batch shape ``+ (3,)``

    Examples
    --------
    >>> q = closed_form(0.0)[:3]
    >>> bool(np.allclose(position_residual(q, 0.0), 0, atol=1e-14))
    True
    """
    return _loop(q, _crank(theta2), geometry, form)


def _loop(q, crank, g, form="loop", trig=None):
    """The kernel of :func:`position_residual`, ``crank = (sin, cos)(theta2)``; ``trig``, the
    ``_trig(q)`` if known (so in every kernel)."""
    s1, c1, s3, c3 = _trig(q) if trig is None else trig
    s2, c2 = crank
    r1 = _parts(q)[0]
    x, y = (-g.r1y * c1 / s1, g.r1y) if form == "eliminated" else (-r1 * c1, r1 * s1)
    return _pack(r1 * s1 - g.r1y, x + g.r2 * c2 + g.r3 * c3, y - g.r2 * s2 - g.r3 * s3)


def _position_entries(q, g, form="loop", trig=None):
    """Nonzero entries of the position Jacobian, ``{(row, col): value}`` (``trig``: the
    ``_trig(q)``, if known)."""
    s1, c1, s3, c3 = _trig(q) if trig is None else trig
    r1 = _parts(q)[0]
    if form == "eliminated":
        rows_xy = {(1, 1): g.r1y / s1**2, (1, 2): -g.r3 * s3, (2, 2): -g.r3 * c3}
    else:
        rows_xy = {(1, 0): -c1, (1, 1): r1 * s1, (1, 2): -g.r3 * s3,
                   (2, 0): s1, (2, 1): r1 * c1, (2, 2): -g.r3 * c3}
    return {(0, 0): s1, (0, 1): r1 * c1, **rows_xy}


@_public(("q", 3))
def position_jacobian(q, geometry=STUDY, form="loop"):
    """Jacobian of :func:`position_residual` with respect to ``(r1, theta1, theta3)``.

    Its determinant, in the loop form, is ``-r1 r3 cos(theta3)``.

    Returns
    -------
    ndarray, shape ``q.shape[:-1] + (3, 3)``

    Examples
    --------
    >>> J = position_jacobian(np.array([-0.1, -0.5, 3.0]))
    >>> bool(np.isclose(np.linalg.det(J), 0.1 * 0.17 * np.cos(3.0)))
    True
    """
    return _loop_jacobian(q, geometry, form)


def _loop_jacobian(q, g, form="loop", trig=None):
    return _matrix(3, _position_entries(q, g, form, trig))


def rate_jacobian(q, geometry=STUDY):
    """Jacobian of the velocity constraints ``(x', y', c')`` in ``(Vr, omega1, omega3)``.

    The acceleration constraints ``(c'', x'', y'')`` have the same matrix in
    ``(Ar, alpha1, alpha3)`` with its rows in their order: :func:`position_jacobian`.

    Returns
    -------
    ndarray, shape ``q.shape[:-1] + (3, 3)``

    Examples
    --------
    >>> q = closed_form(0.0)[:3]
    >>> bool(np.allclose(rate_jacobian(q)[2], position_jacobian(q)[0]))
    True
    """
    return position_jacobian(q, geometry)[..., _RATE_ROWS, :]


@_public(("v", 3), ("q", 3), motor=("theta2", "omega2"))
def velocity_residual(v, q, theta2, omega2, geometry=STUDY):
    """Velocity constraints ``(x', y', c')`` at ``v = (Vr, omega1, omega3)``, given ``q``.

    Returns
    -------
    ndarray, shape: the broadcast batch shape of the inputs ``+ (3,)``

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> th2, w2, _ = motor(0.5)
    >>> bool(np.abs(velocity_residual(x[3:6], x[:3], th2, w2)).max() < 1e-15)
    True
    """
    return _velocity(v, q, _crank(theta2), omega2, geometry)


def _velocity(v, q, crank, w2, g, trig=None):
    """The kernel of :func:`velocity_residual`, ``crank = (sin, cos)(theta2)``."""
    s1, c1, s3, c3 = _trig(q) if trig is None else trig
    s2, c2 = crank
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    c = vr * s1 + r1 * w1 * c1
    return _pack(-vr * c1 + r1 * w1 * s1 - g.r2 * w2 * s2 - g.r3 * w3 * s3,
                 c - g.r2 * w2 * c2 - g.r3 * w3 * c3,
                 c)


@_public(("a", 3), ("v", 3), ("q", 3), motor=("theta2", "omega2", "alpha2"))
def acceleration_residual(a, v, q, theta2, omega2, alpha2, geometry=STUDY):
    """Acceleration constraints ``(c'', x'', y'')`` at ``a = (Ar, alpha1, alpha3)``.

    Returns
    -------
    ndarray, shape: the broadcast batch shape of the inputs ``+ (3,)``

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> bool(np.abs(acceleration_residual(x[6:], x[3:6], x[:3], *motor(0.5))).max() < 1e-13)
    True
    """
    return _acceleration(a, v, q, _crank(theta2), omega2, alpha2, geometry)


def _acceleration(a, v, q, crank, w2, a2, g, trig=None):
    """The kernel of :func:`acceleration_residual`, ``crank = (sin, cos)(theta2)``."""
    s1, c1, s3, c3 = _trig(q) if trig is None else trig
    s2, c2 = crank
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    ar, a1, a3 = _parts(a)
    c = -r1 * s1 * w1**2 + 2 * vr * c1 * w1 + ar * s1 + a1 * r1 * c1
    x = (r1 * c1 * w1**2 + 2 * vr * s1 * w1 - ar * c1 + a1 * r1 * s1
         - g.r2 * (c2 * w2**2 + a2 * s2) - g.r3 * (c3 * w3**2 + a3 * s3))
    y = c + g.r2 * (s2 * w2**2 - a2 * c2) + g.r3 * (s3 * w3**2 - a3 * c3)
    return _pack(c, x, y)


@_public(("x", 9), motor=("theta2", "omega2", "alpha2"))
def residual(x, theta2, omega2, alpha2, geometry=STUDY):
    """All nine constraints (position, velocity, acceleration) at the states ``x``.

    Parameters
    ----------
    x : array_like, shape (..., 9)
    theta2, omega2, alpha2 : array_like
        The motor state, broadcasting against the batch shape ``x.shape[:-1]``.
    geometry : Geometry, optional

    Returns
    -------
    ndarray, shape: the broadcast batch shape ``+ (9,)``

    Examples
    --------
    >>> x = closed_form(1.0)
    >>> bool(np.abs(residual(x, *motor(1.0))).max() < 1e-14)
    True
    """
    return _residual(x, _crank(theta2), omega2, alpha2, geometry)


def _residual(x, crank, w2, a2, g, trig=None):
    """The kernel of :func:`residual`, ``crank = (sin, cos)(theta2)``."""
    q, v, a = x[..., 0:3], x[..., 3:6], x[..., 6:9]
    trig = _trig(x) if trig is None else trig
    return np.concatenate([_loop(q, crank, g, trig=trig), _velocity(v, q, crank, w2, g, trig),
                           _acceleration(a, v, q, crank, w2, a2, g, trig)], axis=-1)


@_public(("x", 9))
def jacobian(x, geometry=STUDY):
    """Jacobian of :func:`residual` in the nine unknowns; shape ``x.shape[:-1] + (9, 9)``.

    Block lower triangular: position rows depend on ``q`` only, velocity rows on ``q`` and
    ``v``; the diagonal blocks are the position Jacobian (rows permuted for the velocity).

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> J = jacobian(x)
    >>> bool(np.allclose(J[3:6, 3:6], rate_jacobian(x[:3])) and not J[0:3, 3:].any())
    True
    """
    return _jacobian(x, geometry)


def _jacobian(x, g, trig=None):
    s1, c1, s3, c3 = trig = _trig(x) if trig is None else trig
    r1, _, _, vr, w1, w3, ar, a1, a3 = _parts(x)
    block = _position_entries(x, g, trig=trig)
    dc_dr1 = -s1 * w1**2 + a1 * c1
    dc_dt1 = -r1 * c1 * w1**2 - 2 * vr * s1 * w1 + ar * c1 - a1 * r1 * s1
    dc_dvr, dc_dw1 = 2 * w1 * c1, 2 * vr * c1 - 2 * r1 * w1 * s1
    entries = {
        **block,
        **{(3 + (i - 1) % 3, 3 + j): value for (i, j), value in block.items()},
        **{(6 + i, 6 + j): value for (i, j), value in block.items()},
        # velocity rows x', y', c' in (r1, theta1, theta3)
        (3, 0): w1 * s1, (3, 1): vr * s1 + r1 * w1 * c1, (3, 2): -g.r3 * w3 * c3,
        (4, 0): w1 * c1, (4, 1): vr * c1 - r1 * w1 * s1, (4, 2): g.r3 * w3 * s3,
        (5, 0): w1 * c1, (5, 1): vr * c1 - r1 * w1 * s1,
        # acceleration rows c'', x'', y'' in (r1, theta1, theta3) and in (Vr, omega1, omega3)
        (6, 0): dc_dr1, (6, 1): dc_dt1, (6, 3): dc_dvr, (6, 4): dc_dw1,
        (7, 0): c1 * w1**2 + a1 * s1,
        (7, 1): -r1 * s1 * w1**2 + 2 * vr * c1 * w1 + ar * s1 + a1 * r1 * c1,
        (7, 2): g.r3 * (s3 * w3**2 - a3 * c3),
        (7, 3): 2 * w1 * s1, (7, 4): 2 * vr * s1 + 2 * r1 * w1 * c1, (7, 5): -2 * g.r3 * w3 * c3,
        (8, 0): dc_dr1, (8, 1): dc_dt1, (8, 2): g.r3 * (c3 * w3**2 + a3 * s3),
        (8, 3): dc_dvr, (8, 4): dc_dw1, (8, 5): 2 * g.r3 * w3 * s3,
    }
    return _matrix(9, entries)


def _dead_points(cos_theta3, theta2):
    """Raise where ``|cos(theta3)| < DEAD_POINT_COS``: the rate equations are singular."""
    c3 = np.abs(cos_theta3)
    if np.any(c3 < DEAD_POINT_COS):
        k = np.flatnonzero(np.ravel(c3) < DEAD_POINT_COS)[0]
        th2 = np.ravel(np.broadcast_to(theta2, np.shape(c3)))[k]
        raise SingularJacobianError(
            f"dead point at theta2 = {th2:.9g} rad: |cos(theta3)| = {np.ravel(c3)[k]:.2g} < "
            f"{DEAD_POINT_COS:g}, the coupler is perpendicular to the guide and the rate "
            f"equations (determinant -r1 r3 cos(theta3)) are singular")


def _closed_form(th2, w2, a2, g):
    s2, c2 = np.sin(th2), np.cos(th2)
    ratio = (g.r1y - g.r2 * s2) / g.r3
    if np.any(np.abs(ratio) > 1):
        bad = np.flatnonzero(np.abs(np.ravel(ratio)) > 1)[0]
        raise UnreachablePoseError(
            f"unreachable pose: |r1y - r2 sin(theta2)| / r3 = {abs(np.ravel(ratio)[bad]):.6g} > 1 "
            f"at theta2 = {np.ravel(th2 + 0 * ratio)[bad]:.6g} rad")
    t3 = np.pi - np.arcsin(ratio)
    s3, c3 = np.sin(t3), np.cos(t3)
    _dead_points(c3, th2)
    xr = g.r2 * c2 + g.r3 * c3  # r1 cos(theta1)
    t1 = np.arctan2(g.r1y, np.abs(xr))  # acot(xr / r1y) in (-pi/2, pi/2], accurate for tiny r1y
    t1 = np.where(xr < 0, -t1, t1)
    s1, c1 = np.sin(t1), np.cos(t1)
    r1 = g.r1y / s1
    # the rows c and x solved for the two unknowns of r1 (determinant r1): no tan(theta1)
    w3 = -w2 * g.r2 * c2 / (g.r3 * c3)
    p = w2 * g.r2 * s2 + w3 * g.r3 * s3  # r1 omega1 sin(theta1) - Vr cos(theta1)
    vr, w1 = -c1 * p, s1 * p / r1
    a3 = (g.r2 * (s2 * w2**2 - a2 * c2) + g.r3 * s3 * w3**2) / (g.r3 * c3)
    u = g.r2 * (c2 * w2**2 + a2 * s2) + g.r3 * (c3 * w3**2 + a3 * s3)
    ar, a1 = r1 * w1**2 - c1 * u, (s1 * u - 2 * vr * w1) / r1
    return np.stack(np.broadcast_arrays(r1, t1, t3, vr, w1, w3, ar, a1, a3), axis=-1)


def closed_form(t=None, geometry=STUDY, *, motor_state=None, alpha_max=ALPHA_MAX):
    """The exact kinematics: all nine unknowns at times ``t`` (or at given motor states).

    The study's list of formulas, corrected (its ``r1`` and ``omega3`` are wrong), with
    ``theta1 = acot(x / r1y)`` computed by ``arctan2`` (accurate for a tiny ``r1y``) and the
    rates of ``r1`` solved without ``tan(theta1)`` (no removable 0/0 at ``theta1 = pi/2``).

    Parameters
    ----------
    t : array_like, optional
        Times in seconds; the motor state comes from :func:`motor`.
    geometry : Geometry, optional
    motor_state : tuple of array_like, optional
        ``(theta2, omega2, alpha2)`` instead of ``t``.
    alpha_max : float, optional
        The motor's largest acceleration, used with ``t``.

    Returns
    -------
    ndarray, shape ``np.shape(t) + (9,)`` (or the broadcast shape of ``motor_state``)

    Raises
    ------
    ValueError
        If neither or both of ``t`` and ``motor_state`` are given, an input is not finite, or
        the result overflows.
    UnreachablePoseError
        If ``|r1y - r2 sin(theta2)| > r3``: the coupler cannot reach the guide.
    SingularJacobianError
        At a dead point, ``|cos(theta3)| < DEAD_POINT_COS``: the rates are undefined.

    Examples
    --------
    >>> np.round(closed_form(0.0)[:3], 6)
    array([-0.099672, -0.468422,  2.873694])
    """
    if (t is None) == (motor_state is None):
        raise ValueError("give either t or motor_state")
    _check(geometry)
    th2, w2, a2 = motor(t, alpha_max) if motor_state is None else _motor_state(motor_state)
    with np.errstate(over="ignore", invalid="ignore"):
        x = _closed_form(th2, w2, a2, geometry)
    return _finite(x, "the closed-form kinematics")


def _linear_rates(q, th2, w2, a2, g, crank=None):
    """The velocity and acceleration stages, linear in their unknowns, as two linear solves
    (each one exact Newton step from zero: the residual at zero is minus the right side);
    ``crank``, the ``_crank(th2)`` if known. Raises at a dead point."""
    trig = _trig(q)
    _dead_points(trig[3], th2)
    crank = _crank(th2) if crank is None else crank
    J = _loop_jacobian(q, g, trig=trig)  # rows (c, x, y); the velocity rows are (x', y', c')
    zero = np.zeros(np.broadcast_shapes(q.shape, np.shape(w2) + (3,)))
    rhs = -_velocity(zero, q, crank, w2, g, trig)[..., [2, 0, 1]]
    v = np.linalg.solve(J, rhs[..., None])[..., 0]
    rhs = -_acceleration(zero, v, q, crank, w2, a2, g, trig)
    return v, np.linalg.solve(J, rhs[..., None])[..., 0]


def solve_rates(q, motor_state, geometry=STUDY):
    """Velocities and accelerations at the positions ``q``: two linear solves, no iteration.

    The velocity and acceleration constraints are linear in their unknowns, with the matrix
    :func:`rate_jacobian` (rows permuted: :func:`position_jacobian`), so each stage is one
    linear solve; Newton would take one exact step from any seed, then a confirming step.

    Parameters
    ----------
    q : array_like, shape (..., 3)
        Positions ``(r1, theta1, theta3)`` that satisfy the position constraints.
    motor_state : tuple of array_like
        ``(theta2, omega2, alpha2)``, broadcasting against ``q.shape[:-1]``.
    geometry : Geometry, optional

    Returns
    -------
    v, a : ndarray, shape: the broadcast batch shape ``+ (3,)``
        ``(Vr, omega1, omega3)`` and ``(Ar, alpha1, alpha3)``.

    Raises
    ------
    SingularJacobianError
        At a dead point, ``|cos(theta3)| < DEAD_POINT_COS``.

    Examples
    --------
    >>> x = closed_form(1.0)
    >>> v, a = solve_rates(x[:3], motor(1.0))
    >>> bool(np.allclose(np.concatenate([v, a]), x[3:], rtol=1e-13, atol=1e-13))
    True
    """
    th2, w2, a2 = _motor_state(motor_state)
    q, th2, w2, a2 = _check(geometry, [("q", q, 3)],
                            [("theta2", th2), ("omega2", w2), ("alpha2", a2)])
    with np.errstate(over="ignore", invalid="ignore"):
        v, a = _linear_rates(q, th2, w2, a2, geometry)
    return _finite(v, "the velocities"), _finite(a, "the accelerations")


def _seed(seed, batch=False):
    """A checked seed: shape (9,), or (n, 9) if ``batch``."""
    seed = _validate.array(seed, "seed", ndim=(1, 2) if batch else 1)
    if seed.shape[-1] != 9:
        raise ValueError(f"seed must have shape (9,){' or (n, 9)' if batch else ''}, "
                         f"got shape {seed.shape}")
    return seed


def _consecutive(th2, w2, a2, seed, g, tol, form="loop"):
    """The study's consecutive scheme, on checked input (the kernel of solve_consecutive)."""
    newton, crank, trig = (solve if seed.ndim == 1 else solve_batch), _crank(th2), _shared_trig()
    pos = newton(lambda q: _loop(q, crank, g, form, trig(q)), seed[..., 0:3],
                 lambda q: _loop_jacobian(q, g, form, trig(q)), tol=tol)
    q = pos.x
    _dead_points(np.cos(q[..., 2]), th2)
    ja = _loop_jacobian(q, g)  # of the acceleration rows; the velocity rows permute it
    jv = ja[..., _RATE_ROWS, :]
    vel = newton(lambda v: _velocity(v, q, crank, w2, g), seed[..., 3:6], lambda v: jv, tol=tol)
    acc = newton(lambda a: _acceleration(a, vel.x, q, crank, w2, a2, g), seed[..., 6:9],
                 lambda a: ja, tol=tol)
    return pos, vel, acc


def solve_consecutive(motor_state, seed, geometry=STUDY, *, tol=TOL, form="loop"):
    """Solve position, then velocity, then acceleration, each by Newton from ``seed``.

    The study's consecutive scheme: three 3x3 Newton solves, each stopped by the step criterion
    (so the linear rate stages take two iterations: an exact step, then a confirming one).
    With ``seed`` of shape ``(n, 9)`` and motor states of shape ``(n,)``, the ``n`` points are
    solved at once (:func:`mechnum.newton.solve_batch`), each with its own convergence.

    Parameters
    ----------
    motor_state : tuple of float or of ndarray
        ``(theta2, omega2, alpha2)``.
    seed : array_like, shape (9,) or (n, 9)
        Initial guess of the nine unknowns.
    geometry : Geometry, optional
    tol : float, optional
        Tolerance on the Euclidean norm of each Newton step (the study's rule).
    form : {"loop", "eliminated"}, optional
        Form of the position equations (see :func:`position_residual`).

    Returns
    -------
    tuple of NewtonResult (or of BatchNewtonResult)
        The position, velocity and acceleration solves; ``np.concatenate([r.x for r in ...],
        axis=-1)`` is the state.

    Raises
    ------
    ConvergenceError, SingularJacobianError
        If Newton fails (the error holds the partial result), or stops at a dead point.

    Examples
    --------
    >>> stages = solve_consecutive((0.0, 0.0, 0.0), STUDY_SEED)
    >>> [r.iterations for r in stages]
    [4, 2, 2]
    """
    th2, w2, a2 = _motor_state(motor_state)
    seed = _seed(seed, batch=True)
    _check(geometry, [("seed", seed, 9)], [("theta2", th2), ("omega2", w2), ("alpha2", a2)])
    form = _validate.choice(form, FORMS, "form")
    return _consecutive(th2, w2, a2, seed, geometry, _validate.tolerance(tol), form)


def _simultaneous(th2, w2, a2, seed, g, tol):
    crank, trig = _crank(th2), _shared_trig()
    res = solve(lambda x: _residual(x, crank, w2, a2, g, trig(x)), seed,
                lambda x: _jacobian(x, g, trig(x)), tol=tol)
    _dead_points(np.cos(res.x[2]), th2)
    return res


def solve_simultaneous(motor_state, seed, geometry=STUDY, *, tol=TOL):
    """Solve the nine equations of one point at once, by Newton on the 9x9 system.

    Parameters
    ----------
    motor_state : tuple of float
        ``(theta2, omega2, alpha2)``.
    seed : array_like, shape (9,)
    geometry : Geometry, optional
    tol : float, optional
        Tolerance on the Euclidean norm of the Newton step.

    Returns
    -------
    NewtonResult

    Raises
    ------
    ConvergenceError, SingularJacobianError
        If Newton fails, or stops at a dead point.

    Examples
    --------
    >>> res = solve_simultaneous((0.0, 0.0, 0.0), STUDY_SEED)
    >>> res.iterations, np.round(res.x[:3], 6).tolist()
    (5, [-0.099672, -0.468422, 2.873694])
    """
    th2, w2, a2 = _motor_state(motor_state)
    if th2.ndim or w2.ndim or a2.ndim:
        raise ValueError("motor_state must be three scalars: the 9x9 solve is of one point")
    _check(geometry)
    return _simultaneous(float(th2), float(w2), float(a2), _seed(seed), geometry,
                         _validate.tolerance(tol))


@dataclass(frozen=True)
class SweepResult:
    """The outcome of :func:`sweep`.

    Attributes
    ----------
    x : ndarray, shape (n, 9)
        The nine unknowns at every time.
    iterations : ndarray of int, shape (n, k)
        Newton iterations of every solve at every point: ``k = 3`` (position, velocity,
        acceleration) for ``"consecutive"``; ``k = 1`` for ``"simultaneous"`` (the 9x9 system)
        and for ``"batched"`` (the position stage; its rate stages are linear solves).
    """

    x: np.ndarray
    iterations: np.ndarray


def sweep(t, method, geometry=STUDY, *, seed=TRAJECTORY_SEED, tol=TOL, alpha_max=ALPHA_MAX,
          predictor="previous"):
    """The kinematics over the times ``t`` by Newton, seeded as the study seeds it (or better).

    Parameters
    ----------
    t : array_like, shape (n,)
        Times in seconds, ``n >= 0``.
    method : {"consecutive", "simultaneous", "batched"}
        ``"consecutive"``: three 3x3 Newton solves per point (:func:`solve_consecutive`);
        ``"simultaneous"``: one 9x9 solve per point (:func:`solve_simultaneous`); both go from
        point to point, the first seeded with ``seed``. ``"batched"``: the position stage of
        all points at once (:func:`mechnum.newton.solve_batch`, every point seeded with
        ``seed``), then the two linear stages as two batched linear solves
        (:func:`solve_rates`).
    geometry : Geometry, optional
    seed : array_like, shape (9,), optional
        The study's first seed by default.
    tol : float, optional
        Tolerance on the norm of the Newton step.
    alpha_max : float, optional
        The motor's largest acceleration.
    predictor : {"previous", "velocity"}, optional
        How the loops seed point ``i + 1``: with the solution at point ``i`` (the study's
        rule), or with a step of continuation along the trajectory, the positions moved by
        ``h`` times their velocities and the velocities by ``h`` times their accelerations,
        ``h = t[i + 1] - t[i]`` (a first-order Taylor predictor). Only for the loops.

    Returns
    -------
    SweepResult

    Raises
    ------
    ValueError
        If an input is invalid (the predictor of a batched sweep included).
    ConvergenceError, SingularJacobianError
        If Newton fails at some point, or a point is a dead point.

    Examples
    --------
    >>> t = np.linspace(0, 2 * first_revolution_time(), 50)
    >>> res = sweep(t, "batched")
    >>> bool(np.abs(res.x - closed_form(t)).max() < 1e-9), res.iterations.shape
    (True, (50, 1))
    """
    method = _validate.choice(method, METHODS, "method")
    predictor = _validate.choice(predictor, PREDICTORS, "predictor")
    t = _validate.array(t, "t", ndim=1)
    seed, tol = _seed(seed), _validate.tolerance(tol)
    _check(geometry)
    if method == "batched" and predictor != "previous":
        raise ValueError("predictor applies to the per-point loops; the batched sweep seeds "
                         "every point with seed")
    th2, w2, a2 = motor(t, alpha_max)
    if method == "batched":
        crank, trig = _crank(th2), _shared_trig()
        pos = solve_batch(lambda q: _loop(q, crank, geometry, trig=trig(q)),
                          np.tile(seed[:3], (t.size, 1)),
                          lambda q: _loop_jacobian(q, geometry, trig=trig(q)), tol=tol)
        v, a = _linear_rates(pos.x, th2, w2, a2, geometry, crank)
        return SweepResult(np.concatenate([pos.x, v, a], axis=-1), pos.iterations[:, None])
    out, iterations = np.empty((t.size, 9)), np.empty((t.size, 3 if method == "consecutive"
                                                       else 1), dtype=int)
    x = seed
    for i in range(t.size):
        if i and predictor == "velocity":
            x = x + (t[i] - t[i - 1]) * np.concatenate([x[3:], np.zeros(3)])
        if method == "consecutive":
            stages = _consecutive(th2[i], w2[i], a2[i], x, geometry, tol)
        else:
            stages = (_simultaneous(th2[i], w2[i], a2[i], x, geometry, tol),)
        x = out[i] = np.concatenate([r.x for r in stages])
        iterations[i] = [r.iterations for r in stages]
    return SweepResult(out, iterations)


def joints(x, theta2, geometry=STUDY):
    """The crank pivot ``O``, crank pin ``A`` and slider pin ``B`` of the states ``x``.

    Parameters
    ----------
    x : array_like, shape (..., 9) or (..., 3)
        States (or positions ``(r1, theta1, theta3)``).
    theta2 : array_like
        Crank angles, broadcasting against ``x.shape[:-1]``.
    geometry : Geometry, optional

    Returns
    -------
    O, A, B : ndarray, shape: the broadcast batch shape ``+ (2,)``
        Points in metres; ``A - O`` has length ``r2``, and at a solution ``B - A`` has length
        ``r3`` and ``B`` lies on the guide.

    Examples
    --------
    >>> O, A, B = joints(closed_form(0.0), 0.0)
    >>> A.tolist(), round(float(B[1]), 12)
    ([0.075, 0.0], 0.045)
    """
    x = _validate.array(x, "x")
    width = 3 if x.shape[-1:] == (3,) else 9
    x, theta2 = _check(geometry, [("x", x, width)], [("theta2", theta2)])
    A = geometry.r2 * np.stack(np.broadcast_arrays(np.cos(theta2), np.sin(theta2)), axis=-1)
    B = x[..., 0, None] * np.stack([np.cos(x[..., 1]), np.sin(x[..., 1])], axis=-1)
    A, B = np.broadcast_arrays(A, B)
    return np.zeros_like(A), A, B


def draw(ax, x, theta2, geometry=STUDY, *, legend=True):
    """Draw the saw in the state ``x`` at the crank angle ``theta2`` on the axes ``ax``.

    The guide, the crank ``O A``, the coupler ``A B``, the vector ``r1`` from ``O`` to ``B``
    (dashed) and the slider; the axes get equal scales, labels in metres, and limits that
    hold the mechanism in every pose (so that an animation does not jump).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    x : array_like, shape (9,) or (3,)
        One state (or its positions).
    theta2 : float
    geometry : Geometry, optional
    legend : bool, optional
        Whether to label the parts in a legend.

    Returns
    -------
    list of matplotlib.artist.Artist
        The guide, crank, coupler, ``r1`` and slider, in that order.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> guide, crank, coupler, r1, slider = draw(ax, closed_form(0.0), 0.0)
    >>> crank.get_xydata().tolist()
    [[0.0, 0.0], [0.075, 0.0]]
    >>> plt.close(fig)
    """
    O, A, B = joints(x, theta2, geometry)
    if O.ndim != 1:
        raise ValueError(f"draw takes one state, got a batch of shape {O.shape[:-1]}")
    g = geometry
    parts = [ax.axhline(g.r1y, color="0.75", lw=6, zorder=0, label="guide of the saw frame"),
             *ax.plot(*np.stack([O, A]).T, "o-", lw=3, label="crank $r_2$"),
             *ax.plot(*np.stack([A, B]).T, "o-", lw=3, label="coupler $r_3$"),
             *ax.plot(*np.stack([O, B]).T, "k--", lw=1, label=r"$\vec r_1 = \vec r_2 + \vec r_3$"),
             *ax.plot(*B, "ks", ms=12, label="slider $B$")]
    pad = DRAW_PAD * g.r2
    ax.set_xlim(-g.r2 - g.r3 - pad, g.r2 + pad)  # the slider's farthest left, the crank's right
    ax.set_ylim(-g.r2 - pad, max(g.r1y, g.r2) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if legend:
        ax.legend(loc="lower left")
    return parts


def reproduce():
    """Recompute every number of the study that the registry holds (``book/published_values.csv``).

    Returns
    -------
    dict
        ``{quantity: value}`` keyed by the registry's ``quantity`` column for Chapter 1.

    Examples
    --------
    >>> values = reproduce()
    >>> values["iterations, simultaneous 9x9 at rest"]
    5
    """
    T = first_revolution_time()
    speed = float(motor(T)[1])
    rest = (0.0, 0.0, 0.0)
    pos, vel, acc = solve_consecutive(rest, STUDY_SEED)
    simultaneous = solve_simultaneous(rest, STUDY_SEED)
    t = np.linspace(0.0, 2 * T, 1000)
    exact = closed_form(t)
    by_stage = {m: sweep(t, m).x for m in ("consecutive", "simultaneous")}
    error = np.abs(by_stage["simultaneous"] - exact).max(axis=0)
    rpm = speed * 60 / (2 * np.pi)
    largest_rate = float(np.abs(simultaneous.x[3:]).max())
    values = {
        "first revolution time T (report)": T,
        "first revolution time T (slides)": T,
        "final motor speed": speed,
        "final motor speed in rpm (report)": rpm,
        "final motor speed in rpm (slides)": rpm,
        "two revolutions 2T (rounded)": 2 * T,
        "two revolutions 2T": 2 * T,
        "iterations, position stage at rest": pos.iterations,
        "iterations, velocity stage at rest": vel.iterations,
        "iterations, acceleration stage at rest": acc.iterations,
        "iterations, simultaneous 9x9 at rest": simultaneous.iterations,
        "largest |velocity| at rest (consecutive)": float(np.abs(vel.x).max()),
        "largest |acceleration| at rest (consecutive)": float(np.abs(acc.x).max()),
        "largest |rate| at rest (simultaneous)": largest_rate,
        "largest |velocity| at rest (slides)": float(np.abs(vel.x).max()),
        "largest |acceleration| at rest (slides)": float(np.abs(acc.x).max()),
        "largest |rate| at rest (slides, simultaneous)": largest_rate,
        "largest |simultaneous - consecutive| over the trajectory": float(
            np.linalg.norm(by_stage["simultaneous"] - by_stage["consecutive"], axis=1).max()),
        "largest error of positions and velocities (simultaneous)": float(error[:6].max()),
        "largest error of accelerations (simultaneous)": float(error[6:].max()),
        "largest error of all nine unknowns (simultaneous)": float(error.max()),
        "largest error of all nine unknowns (slides)": float(error.max()),
    }
    for label, x in (("consecutive", pos.x), ("simultaneous", simultaneous.x), ("slides", pos.x)):
        for name, value in zip(NAMES[:3], x):
            values[f"{name} at rest ({label})"] = float(value)
    for name, value in zip(NAMES[:3], pos.x):  # the slides print the rounded rest solution
        values[f"first trajectory seed {name} (slides)"] = float(value)
    return values
