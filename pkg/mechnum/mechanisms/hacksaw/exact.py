"""The kinematics without iteration: the closed form, and the rate stages as linear solves.

:func:`~mechnum.mechanisms.hacksaw.closed_form` is the study's list of formulas, corrected;
:func:`~mechnum.mechanisms.hacksaw.solve_rates` solves the velocity and acceleration stages,
which are linear in their unknowns, as two linear solves.
"""

import numpy as np

from mechnum.errors import UnreachablePoseError
from mechnum.mechanisms.hacksaw.equations import (_acceleration, _crank, _dead_points,
                                                  _loop_jacobian, _trig, _velocity)
from mechnum.mechanisms.hacksaw.model import (ALPHA_MAX, STUDY, _check, _finite, _motor_state,
                                              motor)


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
