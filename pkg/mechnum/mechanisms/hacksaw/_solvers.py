"""Newton's method as the study applies it: one point in stages or at once, and a trajectory.

:func:`~mechnum.mechanisms.hacksaw.solve_consecutive` solves position, velocity and
acceleration in turn (three 3x3 systems), :func:`~mechnum.mechanisms.hacksaw.solve_simultaneous`
the nine equations at once, and :func:`~mechnum.mechanisms.hacksaw.sweep` a whole trajectory,
point after point as the study does, or all its points at once. A sweep follows one assembly
mode: a point whose solution lands in the other mode (or in the other sign of ``r1``) is a
branch jump, which the loops repair from the previous point's solution, or report.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError
from mechnum.mechanisms.hacksaw import _kernels as kernels
from mechnum.mechanisms.hacksaw._model import (
    ALPHA_MAX,
    FORMS,
    TOL,
    TRAJECTORY_SEED,
    Geometry,
    checked,
    checked_motor,
    motor,
)
from mechnum.newton import solve, solve_batch
from mechnum.results import Result

METHODS = ("consecutive", "simultaneous", "batched")
PREDICTORS = ("previous", "velocity")
MAX_POINTS = 1_000_000
"""The most points of a sweep (a point costs some 10 kB in the batched sweep's Jacobians)."""
# Newton's stopping rule of the study: the Euclidean norm of the step (absolute), below ``tol``.
_RULE = {"criterion": "step", "norm": 2, "relative": False}


def _seed(seed, batch=False):
    """A checked seed: shape (9,), or (n, 9) if ``batch``."""
    seed = _validate.array(seed, "seed", ndim=(1, 2) if batch else 1)
    if seed.shape[-1] != 9:
        raise ValueError(f"seed must have shape (9,){' or (n, 9)' if batch else ''}, "
                         f"got shape {seed.shape}")
    return seed


def _branch(x):
    """The signs that name a state's branch: of ``r1`` and of ``cos(theta3)`` (the mode)."""
    return np.stack([np.sign(x[..., 0]), np.sign(np.cos(x[..., 2]))], axis=-1)


def _consecutive(g, th2, w2, a2, seed, tol, form="loop"):
    """The study's consecutive scheme, on checked input (the kernel of solve_consecutive)."""
    newton = solve if seed.ndim == 1 else solve_batch
    crank, sines = kernels.crank(th2), kernels.shared_trig()
    pos = newton(lambda q: kernels.loop(g, q, crank, form, sines(q)), seed[..., 0:3],
                 lambda q: kernels.loop_jacobian(g, q, form, sines(q)), tol=tol, **_RULE)
    q = pos.x
    kernels.dead_points(np.cos(q[..., 2]), th2)
    ja = kernels.loop_jacobian(g, q)  # of the acceleration rows; the velocity rows permute it
    jv = ja[..., kernels.RATE_ROWS, :]
    vel = newton(lambda v: kernels.velocity(g, v, q, crank, w2), seed[..., 3:6], lambda v: jv,
                 tol=tol, **_RULE)
    acc = newton(lambda a: kernels.acceleration(g, a, vel.x, q, crank, w2, a2), seed[..., 6:9],
                 lambda a: ja, tol=tol, **_RULE)
    return pos, vel, acc


@dataclass(frozen=True, kw_only=True)
class Stages(Result):
    """The outcome of :func:`solve_consecutive`: the state, and its three Newton solves.

    Attributes
    ----------
    x : ndarray, shape (9,) or (n, 9)
        The nine unknowns (of every point).
    status : str or ndarray of str
        ``"converged"`` (a solve that fails raises).
    message : str
        The iterations of each stage.
    iterations : ndarray of int, shape (3,) or (n, 3)
        The Newton steps of the position, velocity and acceleration stages.
    nfev, njev : int
        Calls of the three stages' residuals and Jacobians.
    stages : tuple of NewtonResult (or of BatchNewtonResult)
        The position, velocity and acceleration solves.
    """

    stages: tuple


def solve_consecutive(mech: Geometry, motor_state: tuple, seed: ArrayLike, *,
                      tol: float = TOL, form: str = "loop") -> Stages:
    """Solve position, then velocity, then acceleration, each by Newton from ``seed``.

    The study's consecutive scheme: three 3x3 Newton solves, each stopped by the step criterion
    (so the linear rate stages take two iterations: an exact step, then a confirming one).
    With ``seed`` of shape ``(n, 9)`` and motor states of shape ``(n,)``, the ``n`` points are
    solved at once (:func:`mechnum.newton.solve_batch`), each with its own convergence.

    Parameters
    ----------
    mech : Geometry
    motor_state : tuple of float or of ndarray
        ``(theta2, omega2, alpha2)``.
    seed : array_like, shape (9,) or (n, 9)
        Initial guess of the nine unknowns.
    tol : float, optional
        Tolerance on the Euclidean norm of each Newton step (the study's rule).
    form : {"loop", "eliminated"}, optional
        Form of the position equations (see :func:`position_residual`).

    Returns
    -------
    Stages

    Raises
    ------
    ConvergenceError, SingularJacobianError
        If Newton fails (the error holds the partial result), or stops at a dead point.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY, STUDY_SEED
    >>> res = solve_consecutive(STUDY, (0.0, 0.0, 0.0), STUDY_SEED)
    >>> res.iterations.tolist(), res.x[:3].round(4).tolist()
    ([4, 2, 2], [-0.0997, -0.4684, 2.8737])
    """
    th2, w2, a2 = checked_motor(motor_state)
    seed = _seed(seed, batch=True)
    checked(mech, [("seed", seed, 9)], [("theta2", th2), ("omega2", w2), ("alpha2", a2)])
    form = _validate.choice(form, FORMS, "form")
    stages = _consecutive(mech, th2, w2, a2, seed, _validate.tolerance(tol), form)
    iterations = np.stack([r.iterations for r in stages], axis=-1)
    return Stages(x=np.concatenate([r.x for r in stages], axis=-1), status=stages[0].status,
                  message="position, velocity and acceleration stages converged in "
                          f"{np.asarray(iterations).tolist()} iterations",
                  iterations=iterations, nfev=sum(r.nfev for r in stages),
                  njev=sum(r.njev for r in stages), stages=stages)


def _simultaneous(g, th2, w2, a2, seed, tol):
    crank, sines = kernels.crank(th2), kernels.shared_trig()
    res = solve(lambda x: kernels.residual(g, x, crank, w2, a2, sines(x)), seed,
                lambda x: kernels.jacobian(g, x, sines(x)), tol=tol, **_RULE)
    kernels.dead_points(np.cos(res.x[2]), th2)
    return res


def solve_simultaneous(mech: Geometry, motor_state: tuple, seed: ArrayLike, *,
                       tol: float = TOL) -> object:
    """Solve the nine equations of one point at once, by Newton on the 9x9 system.

    Parameters
    ----------
    mech : Geometry
    motor_state : tuple of float
        ``(theta2, omega2, alpha2)``.
    seed : array_like, shape (9,)
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
    >>> from mechnum.mechanisms.hacksaw.study import STUDY, STUDY_SEED
    >>> res = solve_simultaneous(STUDY, (0.0, 0.0, 0.0), STUDY_SEED)
    >>> res.iterations, np.round(res.x[:3], 6).tolist()
    (5, [-0.099672, -0.468422, 2.873694])
    """
    th2, w2, a2 = checked_motor(motor_state)
    if th2.ndim or w2.ndim or a2.ndim:
        raise ValueError("motor_state must be three scalars: the 9x9 solve is of one point")
    checked(mech)
    return _simultaneous(mech, float(th2), float(w2), float(a2), _seed(seed),
                         _validate.tolerance(tol))


@dataclass(frozen=True, kw_only=True)
class SweepResult(Result):
    """The outcome of :func:`sweep`.

    Attributes
    ----------
    x : ndarray, shape (n, 9)
        The nine unknowns at every time.
    status : ndarray of str, shape (n,)
        ``"converged"`` at every point (a point that fails raises).
    message : str
        How many points, and the iterations in all.
    nfev, njev : int
        Calls of the residuals and Jacobians of every solve.
    iterations : ndarray of int, shape (n, k)
        Newton iterations of every solve at every point (those of a repaired branch jump
        included): ``k = 3`` (position, velocity, acceleration) for ``"consecutive"``; ``k = 1``
        for ``"simultaneous"`` (the 9x9 system) and for ``"batched"`` (the position stage; its
        rate stages are linear solves).
    """



def _batched(g, th2, w2, a2, seed, tol):
    """All the points at once: the position stage by solve_batch, the rates by linear solves."""
    crank, sines = kernels.crank(th2), kernels.shared_trig()
    pos = solve_batch(lambda q: kernels.loop(g, q, crank, sines=sines(q)),
                      np.broadcast_to(seed[:3], (th2.size, 3)),
                      lambda q: kernels.loop_jacobian(g, q, sines=sines(q)), tol=tol, **_RULE)
    jumped = np.any(_branch(pos.x) != _branch(seed), axis=-1)
    if jumped.any():
        raise ConvergenceError(
            f"{jumped.sum()} of {th2.size} points converged to another branch than the "
            f"seed's (first at theta2 = {th2[jumped][0]:.6g} rad): seed them nearer, or "
            f"sweep point by point", pos)
    v, a = kernels.linear_rates(g, pos.x, th2, w2, a2, crank)
    return _swept(np.concatenate([pos.x, v, a], axis=-1), pos.iterations[:, None], pos.nfev,
                  pos.njev)


def _swept(x, iterations, nfev, njev):
    """The :class:`SweepResult` of the points ``x`` and their iterations."""
    return SweepResult(x=x, status=np.full(len(x), "converged"), iterations=iterations,
                       message=f"{len(x)} points converged in {int(iterations.sum())} "
                               "Newton iterations", nfev=nfev, njev=njev)


def _loops(g, t, th2, w2, a2, seed, tol, method, predictor):
    """Point after point; a solution on another branch is solved again from the previous
    point's solution, and raises if it jumps again."""
    out = np.empty((t.size, 9))
    iterations = np.zeros((t.size, 3 if method == "consecutive" else 1), dtype=int)
    previous, nfev, njev = seed, 0, 0
    for i in range(t.size):
        seeds = [previous]
        if i and predictor == "velocity":  # first-order Taylor: positions, then velocities
            step = t[i] - t[i - 1]
            seeds.insert(0, previous + step * np.concatenate([previous[3:], np.zeros(3)]))
        for start in seeds:
            if method == "consecutive":
                stages = _consecutive(g, th2[i], w2[i], a2[i], start, tol)
            else:
                stages = (_simultaneous(g, th2[i], w2[i], a2[i], start, tol),)
            x = np.concatenate([r.x for r in stages])
            iterations[i] += [r.iterations for r in stages]
            nfev, njev = nfev + sum(r.nfev for r in stages), njev + sum(r.njev for r in stages)
            if np.all(_branch(x) == _branch(previous)):
                break
        else:
            raise ConvergenceError(
                f"at t = {t[i]:.6g} s (point {i}) Newton jumped from the branch of the previous "
                f"point (signs of r1 and cos(theta3): {_branch(previous).tolist()}) to "
                f"{_branch(x).tolist()}: the steps of t are too coarse", stages[-1])
        out[i] = previous = x
    return _swept(out, iterations, nfev, njev)


def sweep(mech: Geometry, t: ArrayLike, method: str, *, seed: ArrayLike = TRAJECTORY_SEED,
          tol: float = TOL, alpha_max: float = ALPHA_MAX,
          predictor: str = "previous") -> SweepResult:
    """The kinematics over the times ``t`` by Newton, seeded as the study seeds it (or better).

    Every point stays on the seed's branch: the same assembly mode (the sign of
    ``cos(theta3)``) and the same sign of ``r1``. In the loops, a point whose solution lands on
    another branch (a coarse step of ``t``, a far prediction) is solved again from the previous
    point's solution; if that jumps too, or a batched point jumps, :class:`ConvergenceError`
    says where.

    Parameters
    ----------
    mech : Geometry
    t : array_like, shape (n,)
        Times in seconds, ``0 <= n <=`` :data:`MAX_POINTS`.
    method : {"consecutive", "simultaneous", "batched"}
        ``"consecutive"``: three 3x3 Newton solves per point (:func:`solve_consecutive`);
        ``"simultaneous"``: one 9x9 solve per point (:func:`solve_simultaneous`); both go from
        point to point, the first seeded with ``seed``. ``"batched"``: the position stage of
        all points at once (:func:`mechnum.newton.solve_batch`, every point seeded with
        ``seed``), then the two linear stages as two batched linear solves
        (:func:`solve_rates`).
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
        If Newton fails at some point or leaves the seed's branch, or a point is a dead point.

    Examples
    --------
    >>> from mechnum.mechanisms.hacksaw.study import STUDY
    >>> from mechnum.mechanisms.hacksaw import closed_form, first_revolution_time
    >>> t = np.linspace(0, 2 * first_revolution_time(), 50)
    >>> res = sweep(STUDY, t, "batched")
    >>> bool(np.abs(res.x - closed_form(STUDY, t)).max() < 1e-9), res.iterations.shape
    (True, (50, 1))
    """
    checked(mech)
    method = _validate.choice(method, METHODS, "method")
    predictor = _validate.choice(predictor, PREDICTORS, "predictor")
    t = _validate.array(t, "t", ndim=1)
    _validate.maxiter(t.size, "the number of points of t", minimum=0, maximum=MAX_POINTS)
    seed, tol = _seed(seed), _validate.tolerance(tol)
    if method == "batched" and predictor != "previous":
        raise ValueError("predictor applies to the per-point loops; the batched sweep seeds "
                         "every point with seed")
    th2, w2, a2 = motor(t, alpha_max)
    if method == "batched":
        return _batched(mech, th2, w2, a2, seed, tol)
    return _loops(mech, t, th2, w2, a2, seed, tol, method, predictor)
