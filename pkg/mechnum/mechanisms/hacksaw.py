"""The power-hacksaw mechanism of the hacksaw study (seeds 000 and 002).

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
  derivatives, linear in the unknown rates with the matrix ``J`` of the loop form.

The motor starts from rest with a jerk-limited profile: the angular acceleration rises linearly to
``alpha_max`` over ``T/3``, holds for ``T/3`` and falls back to zero over ``T/3``, where ``T`` is
the time of the first revolution; the speed is constant afterwards.
"""

from dataclasses import dataclass

import numpy as np

from mechnum.errors import GeometryError, UnreachablePoseError
from mechnum.newton import solve, solve_batch


@dataclass(frozen=True)
class Geometry:
    """Link lengths of the saw, in metres (defaults: the study's).

    Raises
    ------
    GeometryError
        If a length is not finite and positive.

    Examples
    --------
    >>> Geometry(r3=0.2).r3
    0.2
    """

    r1y: float = 0.045
    r2: float = 0.075
    r3: float = 0.170

    def __post_init__(self):
        for name in ("r1y", "r2", "r3"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise GeometryError(f"{name} must be a finite positive length, got {value!r}")


STUDY = Geometry()
ALPHA_MAX = 5.0  # rad/s^2, the study's maximum motor acceleration
NAMES = ("r1", "theta1", "theta3", "Vr", "omega1", "omega3", "Ar", "alpha1", "alpha3")
#: The initial guess of the study's MATLAB code (``Pi``); the report prints other signs.
STUDY_SEED = np.array([-0.1, -0.5, 3.0, -0.5, 0.0, 0.5, -0.5, 0.0, 0.5])
#: The seed of the first trajectory point in the study's code: the rounded solution at rest.
TRAJECTORY_SEED = np.array([-0.0997, -0.4684, 2.8737, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
TOL = 1e-6  # the study's tolerance on the Euclidean norm of the Newton step
_RATE_ROWS = [1, 2, 0]  # velocity rows (x', y', c') as position rows (c, x, y)


def first_revolution_time(alpha_max=ALPHA_MAX):
    """Time ``T`` of the motor's first revolution, from ``theta2(T) = alpha_max T**2 / 3 = 2 pi``.

    Examples
    --------
    >>> round(first_revolution_time(), 6)
    1.941626
    """
    if not alpha_max > 0:
        raise ValueError(f"alpha_max must be positive, got {alpha_max!r}")
    return float(np.sqrt(6.0 * np.pi / alpha_max))


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

    Examples
    --------
    >>> T = first_revolution_time()
    >>> [round(float(v), 6) for v in motor(T)]
    [6.283185, 6.472086, 0.0]
    """
    t = np.asarray(t, dtype=float)
    if not np.all(np.isfinite(t)) or np.any(t < 0):
        raise ValueError("t must be finite and non-negative")
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


def _parts(x):
    """The components of ``x`` along its last axis (NumPy scalars when ``x`` is 1-D: fast)."""
    return tuple(x) if x.ndim == 1 else tuple(np.moveaxis(x, -1, 0))


def _trig(x):
    """``sin`` and ``cos`` of ``theta1`` and ``theta3`` of states ``x`` (last axis >= 3)."""
    _, t1, t3 = _parts(x)[:3]
    return np.sin(t1), np.cos(t1), np.sin(t3), np.cos(t3)


def _pack(*columns):
    """Stack arrays (or scalars) along a new last axis, broadcasting them if needed."""
    try:
        out = np.array(columns, dtype=float)
    except ValueError:  # columns of different shapes
        out = np.array(np.broadcast_arrays(*columns))
    return out if out.ndim == 1 else np.moveaxis(out, 0, -1)


def _matrix(n, entries):
    """An ``(..., n, n)`` array of zeros with the ``{(row, col): value}`` entries filled in."""
    values = _pack(*(entries.get((i, j), 0.0) for i in range(n) for j in range(n)))
    return values.reshape(values.shape[:-1] + (n, n))


def position_residual(q, theta2, geometry=STUDY, form="loop"):
    """Position constraints ``(c, x, y)`` at ``q = (r1, theta1, theta3)``; shape ``(..., 3)``.

    ``form="loop"`` is the loop equation as written; ``form="eliminated"`` replaces ``r1`` by
    ``r1y / sin(theta1)`` in the ``x`` and ``y`` rows, as the study's single-point code does.

    Examples
    --------
    >>> q = closed_form(0.0)[:3]
    >>> bool(np.allclose(position_residual(q, 0.0), 0, atol=1e-14))
    True
    """
    g = geometry
    s1, c1, s3, c3 = _trig(q)
    r1 = _parts(q)[0]
    if form == "eliminated":
        x, y = -g.r1y * c1 / s1, g.r1y
    elif form == "loop":
        x, y = -r1 * c1, r1 * s1
    else:
        raise ValueError(f"form must be 'loop' or 'eliminated', got {form!r}")
    return _pack(r1 * s1 - g.r1y,
                 x + g.r2 * np.cos(theta2) + g.r3 * c3,
                 y - g.r2 * np.sin(theta2) - g.r3 * s3)


def _position_entries(q, geometry, form="loop"):
    """Nonzero entries of the position Jacobian, ``{(row, col): value}``."""
    g = geometry
    s1, c1, s3, c3 = _trig(q)
    r1 = _parts(q)[0]
    if form == "eliminated":
        rows_xy = {(1, 1): g.r1y / s1**2, (1, 2): -g.r3 * s3, (2, 2): -g.r3 * c3}
    elif form == "loop":
        rows_xy = {(1, 0): -c1, (1, 1): r1 * s1, (1, 2): -g.r3 * s3,
                   (2, 0): s1, (2, 1): r1 * c1, (2, 2): -g.r3 * c3}
    else:
        raise ValueError(f"form must be 'loop' or 'eliminated', got {form!r}")
    return {(0, 0): s1, (0, 1): r1 * c1, **rows_xy}


def position_jacobian(q, geometry=STUDY, form="loop"):
    """Jacobian of :func:`position_residual` with respect to ``(r1, theta1, theta3)``.

    Its determinant, in the loop form, is ``-r1 r3 cos(theta3)``.

    Examples
    --------
    >>> J = position_jacobian(np.array([-0.1, -0.5, 3.0]))
    >>> bool(np.isclose(np.linalg.det(J), 0.1 * 0.17 * np.cos(3.0)))
    True
    """
    return _matrix(3, _position_entries(q, geometry, form))


def velocity_residual(v, q, theta2, omega2, geometry=STUDY):
    """Velocity constraints ``(x', y', c')`` at ``v = (Vr, omega1, omega3)``, given ``q``.

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> th2, w2, _ = motor(0.5)
    >>> bool(np.abs(velocity_residual(x[3:6], x[:3], th2, w2)).max() < 1e-15)
    True
    """
    g = geometry
    s1, c1, s3, c3 = _trig(q)
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    c = vr * s1 + r1 * w1 * c1
    return _pack(-vr * c1 + r1 * w1 * s1 - g.r2 * omega2 * np.sin(theta2) - g.r3 * w3 * s3,
                 c - g.r2 * omega2 * np.cos(theta2) - g.r3 * w3 * c3,
                 c)


def acceleration_residual(a, v, q, theta2, omega2, alpha2, geometry=STUDY):
    """Acceleration constraints ``(c'', x'', y'')`` at ``a = (Ar, alpha1, alpha3)``.

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> bool(np.abs(acceleration_residual(x[6:], x[3:6], x[:3], *motor(0.5))).max() < 1e-13)
    True
    """
    g = geometry
    s1, c1, s3, c3 = _trig(q)
    s2, c2 = np.sin(theta2), np.cos(theta2)
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    ar, a1, a3 = _parts(a)
    c = -r1 * s1 * w1**2 + 2 * vr * c1 * w1 + ar * s1 + a1 * r1 * c1
    x = (r1 * c1 * w1**2 + 2 * vr * s1 * w1 - ar * c1 + a1 * r1 * s1
         - g.r2 * (c2 * omega2**2 + alpha2 * s2) - g.r3 * (c3 * w3**2 + a3 * s3))
    y = c + g.r2 * (s2 * omega2**2 - alpha2 * c2) + g.r3 * (s3 * w3**2 - a3 * c3)
    return _pack(c, x, y)


def rate_jacobian(q, geometry=STUDY):
    """Jacobian of the velocity constraints ``(x', y', c')`` in ``(Vr, omega1, omega3)``.

    The acceleration constraints ``(c'', x'', y'')`` have the same matrix in
    ``(Ar, alpha1, alpha3)`` with its rows in their order: :func:`position_jacobian`.

    Examples
    --------
    >>> q = closed_form(0.0)[:3]
    >>> bool(np.allclose(rate_jacobian(q)[2], position_jacobian(q)[0]))
    True
    """
    return position_jacobian(q, geometry)[..., _RATE_ROWS, :]


def residual(x, theta2, omega2, alpha2, geometry=STUDY):
    """All nine constraints (position, velocity, acceleration) at the state ``x``; ``(..., 9)``.

    Examples
    --------
    >>> x = closed_form(1.0)
    >>> bool(np.abs(residual(x, *motor(1.0))).max() < 1e-14)
    True
    """
    q, v, a = x[..., 0:3], x[..., 3:6], x[..., 6:9]
    return np.concatenate([position_residual(q, theta2, geometry),
                           velocity_residual(v, q, theta2, omega2, geometry),
                           acceleration_residual(a, v, q, theta2, omega2, alpha2, geometry)],
                          axis=-1)


def jacobian(x, geometry=STUDY):
    """Jacobian of :func:`residual` in the nine unknowns; shape ``(..., 9, 9)``.

    Block lower triangular: position rows depend on ``q`` only, velocity rows on ``q`` and
    ``v``; the diagonal blocks are the position Jacobian (rows permuted for the velocity).

    Examples
    --------
    >>> x = closed_form(0.5)
    >>> J = jacobian(x)
    >>> bool(np.allclose(J[3:6, 3:6], rate_jacobian(x[:3])) and not J[0:3, 3:].any())
    True
    """
    g = geometry
    s1, c1, s3, c3 = _trig(x)
    r1, _, _, vr, w1, w3, ar, a1, a3 = _parts(x)
    block = _position_entries(x, geometry)
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


def closed_form(t=None, geometry=STUDY, *, motor_state=None, alpha_max=ALPHA_MAX):
    """The exact kinematics: all nine unknowns at times ``t`` (or at given motor states).

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
    ndarray, shape ``np.shape(t) + (9,)``

    Raises
    ------
    ValueError
        If neither or both of ``t`` and ``motor_state`` are given, or either is not finite.
    UnreachablePoseError
        If ``|r1y - r2 sin(theta2)| > r3``: the coupler cannot reach the guide.

    Examples
    --------
    >>> np.round(closed_form(0.0)[:3], 6)
    array([-0.099672, -0.468422,  2.873694])
    """
    g = geometry
    if (t is None) == (motor_state is None):
        raise ValueError("give either t or motor_state")
    if motor_state is None:
        th2, w2, a2 = motor(t, alpha_max)
    else:
        th2, w2, a2 = (np.asarray(v, dtype=float) for v in motor_state)
        if not all(np.all(np.isfinite(v)) for v in (th2, w2, a2)):
            raise ValueError(f"motor_state must be finite, got {motor_state!r}")
    s2, c2 = np.sin(th2), np.cos(th2)
    ratio = (g.r1y - g.r2 * s2) / g.r3
    if np.any(np.abs(ratio) > 1):
        bad = np.flatnonzero(np.abs(np.ravel(ratio)) > 1)[0]
        raise UnreachablePoseError(
            f"unreachable pose: |r1y - r2 sin(theta2)| / r3 = {abs(np.ravel(ratio)[bad]):.6g} > 1 "
            f"at theta2 = {np.ravel(th2 + 0 * ratio)[bad]:.6g} rad")
    t3 = np.pi - np.arcsin(ratio)
    s3, c3 = np.sin(t3), np.cos(t3)
    xr = g.r2 * c2 + g.r3 * c3  # r1 cos(theta1)
    t1 = np.arctan2(g.r1y, xr) - np.pi * (xr < 0)  # acot(xr / r1y) in (-pi/2, pi/2]
    s1, c1 = np.sin(t1), np.cos(t1)
    r1 = g.r1y / s1
    w3 = -w2 * g.r2 * c2 / (g.r3 * c3)
    vr = -c1 * (w2 * g.r2 * s2 + w3 * g.r3 * s3)
    w1 = -vr * s1 / (r1 * c1)
    a3 = (g.r2 * s2 * w2**2 + g.r3 * s3 * w3**2 - a2 * g.r2 * c2) / (g.r3 * c3)
    ar = (r1 * w1**2 - c1 * (g.r2 * (c2 * w2**2 + a2 * s2) + g.r3 * (c3 * w3**2 + a3 * s3)))
    a1 = w1**2 * s1 / c1 - (2 * vr * w1 + ar * s1 / c1) / r1
    return np.stack(np.broadcast_arrays(r1, t1, t3, vr, w1, w3, ar, a1, a3), axis=-1)


def solve_consecutive(motor_state, seed, geometry=STUDY, *, tol=TOL, form="loop"):
    """Solve position, then velocity, then acceleration, each by Newton from ``seed``.

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

    Examples
    --------
    >>> stages = solve_consecutive((0.0, 0.0, 0.0), STUDY_SEED)
    >>> [r.iterations for r in stages]
    [4, 2, 2]
    """
    th2, w2, a2 = motor_state
    seed = np.asarray(seed, dtype=float)
    if seed.ndim not in (1, 2) or seed.shape[-1] != 9:
        raise ValueError(f"seed must have shape (9,) or (n, 9), got {seed.shape}")
    newton = solve if seed.ndim == 1 else solve_batch
    pos = newton(lambda q: position_residual(q, th2, geometry, form), seed[..., 0:3],
                 lambda q: position_jacobian(q, geometry, form), tol=tol)
    q = pos.x
    ja = position_jacobian(q, geometry)  # of the acceleration rows; the velocity rows permute it
    jv = ja[..., _RATE_ROWS, :]
    vel = newton(lambda v: velocity_residual(v, q, th2, w2, geometry), seed[..., 3:6],
                 lambda v: jv, tol=tol)
    acc = newton(lambda a: acceleration_residual(a, vel.x, q, th2, w2, a2, geometry),
                 seed[..., 6:9], lambda a: ja, tol=tol)
    return pos, vel, acc


def solve_simultaneous(motor_state, seed, geometry=STUDY, *, tol=TOL):
    """Solve the nine equations at once by Newton on the 9x9 system.

    Examples
    --------
    >>> res = solve_simultaneous((0.0, 0.0, 0.0), STUDY_SEED)
    >>> res.iterations, np.round(res.x[:3], 6).tolist()
    (5, [-0.099672, -0.468422, 2.873694])
    """
    th2, w2, a2 = motor_state
    return solve(lambda x: residual(x, th2, w2, a2, geometry), seed,
                 lambda x: jacobian(x, geometry), tol=tol)


METHODS = ("consecutive", "simultaneous", "batched")


def sweep(t, method, geometry=STUDY, *, seed=TRAJECTORY_SEED, tol=TOL, alpha_max=ALPHA_MAX):
    """The kinematics over the times ``t`` by Newton, seeded as the study seeds it.

    Parameters
    ----------
    t : array_like, shape (n,)
        Times in seconds.
    method : {"consecutive", "simultaneous", "batched"}
        ``"consecutive"``: three 3x3 Newton solves per point; ``"simultaneous"``: one 9x9 solve
        per point; both seed each point with the solution at the previous one, the first with
        ``seed``. ``"batched"``: the consecutive solves of all points at once
        (:func:`mechnum.newton.solve_batch`), every point seeded with ``seed``.
    geometry : Geometry, optional
    seed : array_like, shape (9,), optional
        The study's first seed by default.
    tol : float, optional
        Tolerance on the norm of the Newton step.
    alpha_max : float, optional
        The motor's largest acceleration.

    Returns
    -------
    ndarray, shape (n, 9)

    Examples
    --------
    >>> t = np.linspace(0, 2 * first_revolution_time(), 50)
    >>> bool(np.abs(sweep(t, "batched") - closed_form(t)).max() < 1e-9)
    True
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    t = np.asarray(t, dtype=float)
    if t.ndim != 1:
        raise ValueError(f"t must be a 1-D array of times, got shape {t.shape}")
    states = np.stack(motor(t, alpha_max), axis=-1)
    if method == "batched":
        seeds = np.broadcast_to(np.asarray(seed, dtype=float), (t.size, 9))
        stages = solve_consecutive(states.T, seeds, geometry, tol=tol)
        return np.concatenate([r.x for r in stages], axis=-1)
    out = np.empty((t.size, 9))
    x = np.asarray(seed, dtype=float)
    for i, state in enumerate(states):
        if method == "consecutive":
            x = np.concatenate([r.x for r in solve_consecutive(state, x, geometry, tol=tol)])
        else:
            x = solve_simultaneous(state, x, geometry, tol=tol).x
        out[i] = x
    return out


def reproduce():
    """Recompute every number of the study that the registry holds (``book/published_values.csv``).

    Returns
    -------
    dict
        ``{quantity: value}`` keyed by the registry's ``quantity`` column for chapter 1.

    Examples
    --------
    >>> values = reproduce()
    >>> values["iterations, simultaneous 9x9 at rest"]
    5
    """
    T = first_revolution_time()
    speed = motor(T)[1]
    rest = (0.0, 0.0, 0.0)
    pos, vel, acc = solve_consecutive(rest, STUDY_SEED)
    simultaneous = solve_simultaneous(rest, STUDY_SEED)
    t = np.linspace(0.0, 2 * T, 1000)
    exact = closed_form(t)
    by_stage = {m: sweep(t, m) for m in ("consecutive", "simultaneous")}
    error = np.abs(by_stage["simultaneous"] - exact).max(axis=0)
    rpm = float(speed) * 60 / (2 * np.pi)
    values = {
        "first revolution time T (report)": T,
        "first revolution time T (slides)": T,
        "final motor speed": float(speed),
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
        "largest |rate| at rest (simultaneous)": float(np.abs(simultaneous.x[3:]).max()),
        "largest |simultaneous - consecutive| over the trajectory": float(
            np.linalg.norm(by_stage["simultaneous"] - by_stage["consecutive"], axis=1).max()),
        "largest error of positions and velocities (simultaneous)": float(error[:6].max()),
        "largest error of accelerations (simultaneous)": float(error[6:].max()),
        "largest error of all nine unknowns (simultaneous)": float(error.max()),
    }
    for label, x in (("consecutive", pos.x), ("simultaneous", simultaneous.x), ("slides", pos.x)):
        for name, value in zip(NAMES[:3], x):
            values[f"{name} at rest ({label})"] = float(value)
    return values
