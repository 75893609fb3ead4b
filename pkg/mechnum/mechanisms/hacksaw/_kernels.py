"""The saw's formulas on checked input: the kernels of the public functions and the solvers.

Each function takes the mechanism (a :class:`~mechnum.mechanisms.hacksaw.Geometry`) first and
float arrays (or NumPy scalars) that the caller has checked: the public evaluators
(``hacksaw``'s equations module) check, then call these; the solvers call them
inside Newton's loop, where checks would only cost time. ``crank`` is ``(sin, cos)(theta2)``
(:func:`crank`), fixed while Newton iterates, and ``sines`` the sines and cosines of
``theta1`` and ``theta3`` (:func:`trig`), if known. Nothing here validates its input.

Examples
--------
>>> import numpy as np
>>> from mechnum.mechanisms.hacksaw.study import STUDY
>>> x = closed_form(STUDY, 0.0, 0.0, 0.0)
>>> bool(np.abs(residual(STUDY, x, crank(0.0), 0.0, 0.0)).max() < 1e-15)
True
"""

import numpy as np

from mechnum.errors import SingularJacobianError, UnreachablePoseError

# A dead point: theta3 comes from an arcsin whose error grows like eps / |cos(theta3)|, so the
# rates' relative error grows like eps / cos(theta3)**2. Below this |cos(theta3)| they would keep
# fewer than about eight digits (2.2e-16 / 1e-8): the solvers raise instead of answering.
DEAD_POINT_COS = 1e-4
RATE_ROWS = [1, 2, 0]  # velocity rows (x', y', c') as position rows (c, x, y)
MODES = (0, 1)
"""The two assembly modes: 0, the study's (the coupler pointing back, ``cos(theta3) < 0``), and
1 (the coupler pointing forward)."""


def _parts(x):
    """The components of ``x`` along its last axis (NumPy scalars when ``x`` is 1-D: fast)."""
    return tuple(x) if x.ndim == 1 else tuple(x[..., k] for k in range(x.shape[-1]))


def trig(x):
    """``sin`` and ``cos`` of ``theta1`` and ``theta3`` of states ``x`` (last axis >= 3)."""
    _, t1, t3 = _parts(x)[:3]
    return np.sin(t1), np.cos(t1), np.sin(t3), np.cos(t3)


def shared_trig():
    """A :func:`trig` that remembers its last argument. Newton evaluates the residual at an
    iterate, then the Jacobian at the same iterate (the same array): they share its sines and
    cosines. (For the solvers' own closures, whose iterates are never changed in place.)"""
    last = [None, None]

    def remembered(x):
        if x is not last[0]:
            last[:] = x, trig(x)
        return last[1]
    return remembered


def crank(theta2):
    """``sin`` and ``cos`` of the crank angles (they are fixed while Newton iterates)."""
    return np.sin(theta2), np.cos(theta2)


def _pack(*columns):
    """Stack arrays (or scalars) along a new last axis, broadcasting them; C-contiguous (the
    linear solves and the norms of a batch are several times slower on a transposed array)."""
    shape = np.broadcast_shapes(*(np.shape(c) for c in columns))
    if not shape:  # one point: fastest as one list
        return np.array(columns, dtype=float)
    out = np.empty(shape + (len(columns),))
    for k, column in enumerate(columns):
        out[..., k] = column
    return out


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


def loop(g, q, crank, form="loop", sines=None):
    """The position constraints ``(c, x, y)`` at ``q = (r1, theta1, theta3)``."""
    s1, c1, s3, c3 = trig(q) if sines is None else sines
    s2, c2 = crank
    r1 = _parts(q)[0]
    x, y = (-g.r1y * c1 / s1, g.r1y) if form == "eliminated" else (-r1 * c1, r1 * s1)
    return _pack(r1 * s1 - g.r1y, x + g.r2 * c2 + g.r3 * c3, y - g.r2 * s2 - g.r3 * s3)


def _position_entries(g, q, form="loop", sines=None):
    """Nonzero entries of the position Jacobian, ``{(row, col): value}``."""
    s1, c1, s3, c3 = trig(q) if sines is None else sines
    r1 = _parts(q)[0]
    if form == "eliminated":
        rows_xy = {(1, 1): g.r1y / s1**2, (1, 2): -g.r3 * s3, (2, 2): -g.r3 * c3}
    else:
        rows_xy = {(1, 0): -c1, (1, 1): r1 * s1, (1, 2): -g.r3 * s3,
                   (2, 0): s1, (2, 1): r1 * c1, (2, 2): -g.r3 * c3}
    return {(0, 0): s1, (0, 1): r1 * c1, **rows_xy}


def loop_jacobian(g, q, form="loop", sines=None):
    """The Jacobian of :func:`loop` in ``(r1, theta1, theta3)``: shape ``(..., 3, 3)``."""
    if form != "loop" or q.ndim == 1:
        return _matrix(3, _position_entries(g, q, form, sines))
    s1, c1, s3, c3 = trig(q) if sines is None else sines
    r1 = q[..., 0]
    out = np.empty(q.shape + (3,))  # a batch, filled row by row: the batched sweep's hot loop
    out[..., 0, 0], out[..., 0, 1], out[..., 0, 2] = s1, r1 * c1, 0.0
    out[..., 1, 0], out[..., 1, 1], out[..., 1, 2] = -c1, r1 * s1, -g.r3 * s3
    out[..., 2, 0], out[..., 2, 1], out[..., 2, 2] = s1, out[..., 0, 1], -g.r3 * c3
    return out


def velocity(g, v, q, crank, w2, sines=None):
    """The velocity constraints ``(x', y', c')`` at ``v = (Vr, omega1, omega3)``."""
    s1, c1, s3, c3 = trig(q) if sines is None else sines
    s2, c2 = crank
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    c = vr * s1 + r1 * w1 * c1
    return _pack(-vr * c1 + r1 * w1 * s1 - g.r2 * w2 * s2 - g.r3 * w3 * s3,
                 c - g.r2 * w2 * c2 - g.r3 * w3 * c3,
                 c)


def acceleration(g, a, v, q, crank, w2, a2, sines=None):
    """The acceleration constraints ``(c'', x'', y'')`` at ``a = (Ar, alpha1, alpha3)``."""
    s1, c1, s3, c3 = trig(q) if sines is None else sines
    s2, c2 = crank
    r1 = _parts(q)[0]
    vr, w1, w3 = _parts(v)
    ar, a1, a3 = _parts(a)
    c = -r1 * s1 * w1**2 + 2 * vr * c1 * w1 + ar * s1 + a1 * r1 * c1
    x = (r1 * c1 * w1**2 + 2 * vr * s1 * w1 - ar * c1 + a1 * r1 * s1
         - g.r2 * (c2 * w2**2 + a2 * s2) - g.r3 * (c3 * w3**2 + a3 * s3))
    y = c + g.r2 * (s2 * w2**2 - a2 * c2) + g.r3 * (s3 * w3**2 - a3 * c3)
    return _pack(c, x, y)


def residual(g, x, crank, w2, a2, sines=None):
    """All nine constraints at the states ``x``: shape ``(..., 9)``."""
    q, v, a = x[..., 0:3], x[..., 3:6], x[..., 6:9]
    sines = trig(x) if sines is None else sines
    return np.concatenate([loop(g, q, crank, sines=sines), velocity(g, v, q, crank, w2, sines),
                           acceleration(g, a, v, q, crank, w2, a2, sines)], axis=-1)


def jacobian(g, x, sines=None):
    """The Jacobian of :func:`residual` in the nine unknowns: shape ``(..., 9, 9)``."""
    s1, c1, s3, c3 = sines = trig(x) if sines is None else sines
    r1, _, _, vr, w1, w3, ar, a1, a3 = _parts(x)
    block = _position_entries(g, x, sines=sines)
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


def dead_points(cos_theta3, theta2):
    """Raise where ``|cos(theta3)| < DEAD_POINT_COS``: the rate equations are singular."""
    c3 = np.abs(cos_theta3)
    if np.any(c3 < DEAD_POINT_COS):
        k = np.flatnonzero(np.ravel(c3) < DEAD_POINT_COS)[0]
        th2 = np.ravel(np.broadcast_to(theta2, np.shape(c3)))[k]
        raise SingularJacobianError(
            f"dead point at theta2 = {th2:.9g} rad: |cos(theta3)| = {np.ravel(c3)[k]:.2g} < "
            f"{DEAD_POINT_COS:g}, the coupler is perpendicular to the guide and the rate "
            f"equations (determinant -r1 r3 cos(theta3)) are singular")


def closed_form(g, th2, w2, a2, mode=0):
    """The nine unknowns of assembly mode ``mode`` (0 or 1) in closed form: ``(..., 9)``."""
    s2, c2 = np.sin(th2), np.cos(th2)
    ratio = (g.r1y - g.r2 * s2) / g.r3
    if np.any(np.abs(ratio) > 1):
        bad = np.flatnonzero(np.abs(np.ravel(ratio)) > 1)[0]
        raise UnreachablePoseError(
            f"unreachable pose: |r1y - r2 sin(theta2)| / r3 = {abs(np.ravel(ratio)[bad]):.6g} > 1 "
            f"at theta2 = {np.ravel(th2 + 0 * ratio)[bad]:.6g} rad")
    t3 = np.arcsin(ratio) if mode else np.pi - np.arcsin(ratio)
    s3, c3 = np.sin(t3), np.cos(t3)
    dead_points(c3, th2)
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


def _rate_solve(g, q, sines, rhs_c, rhs_x, rhs_y):
    """Solve ``J u = (rhs_c, rhs_x, rhs_y)`` with ``J`` the position Jacobian (loop form, rows
    ``c, x, y``) by its structure: rows ``c`` and ``y`` differ only in ``theta3``'s column,
    ``-r3 cos(theta3)``, which gives ``u2`` at once; rows ``c`` and ``x`` are then a rotation by
    ``theta1`` of ``(u0, r1 u1)``. No pivoting is needed: ``r1`` and ``r3 cos(theta3)`` are
    the only divisors (the determinant is ``-r1 r3 cos(theta3)``)."""
    s1, c1, s3, c3 = sines
    r1 = _parts(q)[0]
    u2 = (rhs_c - rhs_y) / (g.r3 * c3)
    turned = rhs_x + g.r3 * s3 * u2
    return _pack(s1 * rhs_c - c1 * turned, (c1 * rhs_c + s1 * turned) / r1, u2)


def linear_rates(g, q, th2, w2, a2, crank_=None):
    """The velocity and acceleration stages, linear in their unknowns, solved (each is one
    exact Newton step from zero: the residual at zero is minus the right side); ``crank_``,
    the :func:`crank` of ``th2`` if known. Raises at a dead point."""
    sines = trig(q)
    dead_points(sines[3], th2)
    s2, c2 = crank(th2) if crank_ is None else crank_
    # the velocity rows at zero rates leave the crank's terms: the right side, rows (c, x, y)
    v = _rate_solve(g, q, sines, 0.0 * (s2 * w2), g.r2 * w2 * s2, g.r2 * w2 * c2)
    rhs = -acceleration(g, np.zeros_like(v), v, q, (s2, c2), w2, a2, sines)
    return v, _rate_solve(g, q, sines, rhs[..., 0], rhs[..., 1], rhs[..., 2])
