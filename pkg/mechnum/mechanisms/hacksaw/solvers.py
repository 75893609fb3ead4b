"""Newton's method as the study applies it: one point in stages or at once, and a trajectory.

:func:`~mechnum.mechanisms.hacksaw.solve_consecutive` solves position, velocity and
acceleration in turn (three 3x3 systems), :func:`~mechnum.mechanisms.hacksaw.solve_simultaneous`
the nine equations at once, and :func:`~mechnum.mechanisms.hacksaw.sweep` a whole trajectory,
point after point as the study does, or all its points at once.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.hacksaw.equations import (_RATE_ROWS, _acceleration, _crank,
                                                  _dead_points, _jacobian, _loop, _loop_jacobian,
                                                  _residual, _shared_trig, _velocity)
from mechnum.mechanisms.hacksaw.exact import _linear_rates
from mechnum.mechanisms.hacksaw.model import (ALPHA_MAX, FORMS, STUDY, TOL, TRAJECTORY_SEED,
                                              _check, _motor_state, motor)
from mechnum.newton import solve, solve_batch

METHODS = ("consecutive", "simultaneous", "batched")
PREDICTORS = ("previous", "velocity")


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
                 lambda q: _loop_jacobian(q, g, form, trig(q)), tol=tol, relative=False)
    q = pos.x
    _dead_points(np.cos(q[..., 2]), th2)
    ja = _loop_jacobian(q, g)  # of the acceleration rows; the velocity rows permute it
    jv = ja[..., _RATE_ROWS, :]
    vel = newton(lambda v: _velocity(v, q, crank, w2, g), seed[..., 3:6], lambda v: jv, tol=tol,
                 relative=False)
    acc = newton(lambda a: _acceleration(a, vel.x, q, crank, w2, a2, g), seed[..., 6:9],
                 lambda a: ja, tol=tol, relative=False)
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
    >>> from mechnum.mechanisms.hacksaw import STUDY_SEED
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
                lambda x: _jacobian(x, g, trig(x)), tol=tol, relative=False)
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
    >>> from mechnum.mechanisms.hacksaw import STUDY_SEED
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
    >>> from mechnum.mechanisms.hacksaw import closed_form, first_revolution_time
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
                          lambda q: _loop_jacobian(q, geometry, trig=trig(q)), tol=tol,
                          relative=False)
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
