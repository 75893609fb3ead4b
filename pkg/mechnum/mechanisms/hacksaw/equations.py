"""The constraint equations of the saw and their Jacobians, for one state or a batch.

Position ``(c, x, y)`` in ``q = (r1, theta1, theta3)``
(:func:`~mechnum.mechanisms.hacksaw.position_residual`, in the loop or the eliminated form),
velocity ``(x', y', c')`` (:func:`~mechnum.mechanisms.hacksaw.velocity_residual`) and
acceleration ``(c'', x'', y'')`` (:func:`~mechnum.mechanisms.hacksaw.acceleration_residual`),
and all nine at once (:func:`~mechnum.mechanisms.hacksaw.residual`). The rate equations are
linear in their unknowns, with the position Jacobian as their matrix, rows permuted
(:func:`~mechnum.mechanisms.hacksaw.rate_jacobian`); the 9x9 Jacobian
(:func:`~mechnum.mechanisms.hacksaw.jacobian`) is block lower triangular. Where
``|cos(theta3)|`` falls below ``DEAD_POINT_COS`` (a dead point) the rate equations are
singular. Each public evaluator checks its input and calls a private kernel (``_loop``,
``_velocity``, ...), which the solvers call directly.
"""

import numpy as np

from mechnum.errors import SingularJacobianError
from mechnum.mechanisms.hacksaw.model import STUDY, _public

# A dead point: theta3 comes from an arcsin whose error grows like eps / |cos(theta3)|, so the
# rates' relative error grows like eps / cos(theta3)**2. Below this |cos(theta3)| they would keep
# fewer than about eight digits (2.2e-16 / 1e-8): the solvers raise instead of answering.
DEAD_POINT_COS = 1e-4
_RATE_ROWS = [1, 2, 0]  # velocity rows (x', y', c') as position rows (c, x, y)


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
    >>> from mechnum.mechanisms.hacksaw import closed_form
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
    >>> from mechnum.mechanisms.hacksaw import closed_form
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
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
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
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
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
    >>> from mechnum.mechanisms.hacksaw import closed_form, motor
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
    >>> from mechnum.mechanisms.hacksaw import closed_form
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
