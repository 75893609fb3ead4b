"""Natural-parameter continuation: :func:`solve_path` follows a root along given parameters.

Each step fixes the parameter and corrects the state by damped Newton
(:func:`mechnum.newton.solve_batch`) from a secant prediction; a point where Newton converged on
another branch (across a fold) is reported as a ``"branch-jump"``. The package's docstring and
:func:`solve_path`'s show it at work.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, newton
from mechnum.results import Result, status_counts

PATH_TOL = 1e-12
"""Default tolerance of :func:`solve_path`: Newton stops when ``||f|| <= PATH_TOL`` (the residual
criterion, absolute: the callers scale their equations to order one, and from a good prediction
a converged point needs no confirming step)."""
MAX_JUMP = 10.0
"""Default of :func:`solve_path`'s ``max_jump``: a converged point that moved more than ten times
as fast (in the unknowns per unit of parameter) as the fastest of the three steps before it has
left its branch. Approaching a square-root fold at equal parameter steps, the speed grows by at
most ``1 / (sqrt(2) - 1) = 2.4`` per step, so a branch followed faithfully stays far below the
bound; a solution that truly changes ten times faster than it did needs finer steps anyway."""
PATH_POINTS_LIMIT = 10_000_000
"""The most points (steps times paths) of one :func:`solve_path`."""
_SPEEDS = 3  # the steps before a point whose speed bounds its own (max_jump)
# A move below sqrt(eps) (1 + |x|) is no jump, however fast: a path that stood still to round-off
# (speeds of 1e-16) and starts to move is not leaving its branch.
_VISIBLE = np.sqrt(np.finfo(float).eps)


@dataclass(frozen=True, kw_only=True)
class PathResult(Result):
    """The outcome of :func:`solve_path`.

    Attributes
    ----------
    x : ndarray, shape (steps, batch, n) (or (steps, n) for one path)
        The solution at every step, NaN where the status is not ``"converged"``.
    status : ndarray of str, shape (steps, batch) (or (steps,))
        What happened at every step (:data:`~mechnum.results.STATUSES`): Newton's status,
        ``"branch-jump"`` where Newton converged on another branch (the point is not part of
        the path), or ``"lost"`` for the steps after an abandoned path (``resume=False``).
    message : str
        The counts of the statuses.
    iterations : ndarray of int, same shape as ``status``
        Newton steps taken at every step.
    nfev, njev : int
        Calls of ``fun`` and ``jac`` (on batches).
    det : ndarray, same shape as ``status``
        ``det`` of the Jacobian in the unknowns at every converged point (NaN elsewhere): its
        sign changes only across a fold or a bifurcation, which no path passes.
    """

    det: np.ndarray


def _pair(fun, jac):
    """``fun(x, p)`` and ``jac(x, p)`` (or ``True``, or None) as one ``(f, J)`` per parameter
    set: the functions of ``x`` for :func:`mechnum.newton.solve_batch`, and the Jacobian."""
    def residual(p):
        return lambda z: fun(z, p)

    def jacobian(p):
        return jac if jac is None or jac is True else (lambda z: jac(z, p))

    def at(z, p):  # the Jacobian at converged points, for its determinant; calls of fun, jac
        if jac is True:
            return np.asarray(fun(z, p)[1], dtype=float), 1, 1
        if jac is None:
            return newton.fd_jacobian(lambda w: fun(w, p), z), z.shape[-1] + 1, 0
        return np.asarray(jac(z, p), dtype=float), 0, 1

    return residual, jacobian, at


def solve_path(fun: Callable, seed: ArrayLike, params: ArrayLike,
               jac: Callable | bool | None = None, *, tol: float = PATH_TOL,
               maxiter: int = 10, domain: Callable | None = None,
               halvings: int = 4, criterion: str = "residual",
               resume: bool = True, max_jump: float | None = MAX_JUMP) -> PathResult:
    """Follow solutions of ``fun(x, p) = 0`` along a sequence of parameters, by continuation.

    Step ``i`` solves ``fun(x, params[i]) = 0`` by damped Newton
    (:func:`~mechnum.newton.solve_batch`) from a secant prediction,
    ``x_{i-1} + c (x_{i-1} - x_{i-2})`` with ``c`` the projection of the parameter step
    ``p_i - p_{i-1}`` on the last one (1 on a uniform straight path, 0 where the path turns a
    right angle; ``x_{i-1}`` itself after a failure or at the first steps), so each solution
    stays on the branch of the one before; small parameter steps keep it there. Many paths may
    be followed at once (a batch); each may fail on its own.

    Newton may still converge on *another* branch: past a fold, where the branch followed
    turns back and no nearby solution is left, it leaps to a distant one. A converged point is
    a **branch jump**, reported with the status ``"branch-jump"`` and not as a point of the
    path, when

    * the sign of ``det J`` (the Jacobian in ``x``) differs from the last accepted point's: a
      singular Jacobian, a fold or a bifurcation, lies between them; or
    * its speed ``||x_i - x_last|| / ||p_i - p_last||`` exceeds ``max_jump`` times the
      fastest of the (up to three) steps before it (checked once the path has one step), and
      its move exceeds ``sqrt(eps) (1 + ||x_last||)`` (a path that stood still to round-off
      may start to move).

    A jump is treated as a failure: the next step starts again from the last accepted point.

    Parameters
    ----------
    fun : callable
        ``fun(x, p) -> (m, n)`` for ``x`` of shape ``(m, n)`` and ``p`` of shape ``(m, ...)``:
        the rows of ``x`` and their parameters; with ``jac=True``, ``fun(x, p) -> (f, J)``.
    seed : array_like, shape (n,) or (batch, n)
        A solution at (or a start close to) ``params[0]``, of one path or of each of ``batch``.
    params : array_like, shape (steps, ...) or (steps, batch, ...)
        The parameters of every step (finite, real): for one path (``seed`` of shape ``(n,)``),
        or for each of ``batch`` paths; ``steps * batch`` at most :data:`PATH_POINTS_LIMIT`.
        No steps is a valid, empty path.
    jac : callable, True or None, optional
        ``jac(x, p) -> (m, n, n)``, or ``True`` if ``fun`` returns it; default forward
        differences.
    tol, maxiter, criterion : optional
        Newton's tolerance (:data:`PATH_TOL`), most iterations per step (from a good prediction
        Newton needs a few; a step that needs more has likely lost the branch) and stopping
        criterion (the residual: no last step spent confirming a converged one).
    domain : callable, optional
        ``domain(x) -> (m,) bool``, as in :func:`~mechnum.newton.solve_batch`.
    halvings : int, optional
        Most halvings of a Newton step, as in :func:`~mechnum.newton.solve_all` (whose default
        it shares: a start whose step must be cut below 1/16 lies where Newton's linear model
        is poor).
    resume : bool, optional
        After a step that fails, go on from the last converged solution (the study's
        trajectories do so), or abandon the path (``False``: the rest of it is ``"lost"``).
    max_jump : float or None, optional
        The bound on a point's speed relative to the steps before it (:data:`MAX_JUMP`);
        ``None`` tests the sign of ``det J`` only.

    Returns
    -------
    PathResult

    Raises
    ------
    ValueError
        Ill-shaped, complex or non-finite ``seed`` or ``params``, an invalid option, or ``fun``,
        ``jac``, ``domain`` returning the wrong shapes.

    Examples
    --------
    The positive root of ``x**2 = p`` as ``p`` goes from 1 to 4:

    >>> p = np.linspace(1.0, 4.0, 7)
    >>> path = solve_path(lambda x, c: x ** 2 - c[:, None], [1.0], p,
    ...                   lambda x, c: 2 * x[:, :, None])
    >>> bool(np.allclose(path.x[:, 0], np.sqrt(p))), bool(path.converged.all())
    (True, True)

    A two-link arm of unit links reaches for points that pass within ``0.001`` of its reach:
    its elbow angle ``q[1]`` falls to ``0.063``, and from there Newton lands on the other
    assembly (the elbow bent the other way, ``det J`` of the other sign). That point is
    reported, and the next one is found on the arm's own branch again:

    >>> def arm(q, P):
    ...     a, b = q[:, 0], q[:, 0] + q[:, 1]
    ...     return np.stack([np.cos(a) + np.cos(b) - P[:, 0], np.sin(a) + np.sin(b) - P[:, 1]],
    ...                     axis=-1)
    >>> phi = np.linspace(0.0, 1.0, 5)
    >>> r = 1.999 - 0.6 * np.abs(phi - 0.5)
    >>> elbow = np.arccos(r[0] ** 2 / 2 - 1)
    >>> path = solve_path(arm, [-elbow / 2, elbow],
    ...                   np.column_stack([r * np.cos(phi), r * np.sin(phi)]))
    >>> path.status.tolist()
    ['converged', 'converged', 'converged', 'branch-jump', 'converged']
    >>> path.x[:, 1].round(3).tolist()
    [1.112, 0.782, 0.063, nan, 1.112]
    """
    _validate.function(fun, "fun")
    if jac is not True:
        _validate.function(jac, "jac", optional=True)
    x = _validate.array(seed, "seed", ndim=(1, 2))
    params = _validate.array(params, "params")
    if params.ndim == 0:
        raise ValueError(f"params must hold one parameter set per step, got the scalar "
                         f"{params!r}")
    if x.shape[-1] == 0:
        raise ValueError(f"seed must have at least one unknown, got shape {x.shape}")
    resume = _validate.flag(resume, "resume")
    if max_jump is not None:
        max_jump = _validate.scalar(max_jump, "max_jump", positive=True)
    single = x.ndim == 1
    if single:
        x, params = x[None], params[:, None]
    if params.ndim < 2 or params.shape[1] != len(x):
        raise ValueError(f"params must have shape (steps, {len(x)}, ...) for {len(x)} paths, "
                         f"got {params.shape}")
    if params.shape[0] * len(x) > PATH_POINTS_LIMIT:
        raise ValueError(f"at most {PATH_POINTS_LIMIT} points (a bound on the work), got "
                         f"{params.shape[0]} steps of {len(x)} paths")
    residual, jacobian, at = _pair(fun, jac)
    path = _Path(x, params, max_jump)
    for i, p in enumerate(params):
        path.status[i, ~path.alive] = "lost"
        rows = np.flatnonzero(path.alive)
        if not rows.size:
            path.status[i:] = "lost"
            break
        start = path.prediction(i, p, rows, domain)
        res = newton.solve_batch(residual(p[rows]), start, jacobian(p[rows]), tol=tol,
                                 maxiter=maxiter, criterion=criterion,
                                 damping=True, domain=domain, raise_on_failure=False,
                                 halvings=halvings)
        path.nfev, path.njev = path.nfev + res.nfev, path.njev + res.njev
        done = rows[res.converged]
        det = np.empty(0)
        if done.size:
            J, nfev, njev = at(res.x[res.converged], p[done])
            if J.shape[-2:] != (x.shape[-1],) * 2:
                raise ValueError(f"the Jacobian in x must be square, ({x.shape[-1]}, "
                                 f"{x.shape[-1]}) for {x.shape[-1]} unknowns: jac (or fun) "
                                 f"gives shape {J.shape[-2:]}")
            det, path.nfev, path.njev = np.linalg.det(J), path.nfev + nfev, path.njev + njev
        path.accept(i, p, rows, res, det)
        if not resume:
            path.alive &= path.status[i] == "converged"
    if single:
        return path.result(lambda a: a[:, 0])
    return path.result(lambda a: a)


class _Path:
    """The state of :func:`solve_path`: the last two accepted points of every path (for the
    secant prediction), the sign of ``det J`` and the speeds of the last steps (for the jump
    test), and the arrays of the result."""

    def __init__(self, x, params, max_jump):
        steps, batch = len(params), len(x)
        self.params, self.max_jump = params, max_jump
        self.out = np.full((steps,) + x.shape, np.nan)
        self.status = np.full((steps, batch), "", dtype="<U11")
        self.iterations = np.zeros((steps, batch), dtype=int)
        self.det = np.full((steps, batch), np.nan)
        self.last, self.before = x.copy(), x.copy()
        first = params[0].astype(float) if steps else np.zeros((batch, 1))
        self.last_p, self.before_p = first, first.copy()
        self.streak = np.zeros(batch, dtype=int)    # converged steps in a row
        self.accepted = np.zeros(batch, dtype=int)  # converged points so far
        self.sign = np.zeros(batch)                 # sign of det J at the last accepted point
        self.speeds = np.full((batch, _SPEEDS), np.nan)
        self.alive = np.ones(batch, dtype=bool)
        self.nfev = self.njev = 0

    def prediction(self, i, p, rows, domain):
        """The secant prediction of step ``i`` for the paths ``rows``."""
        batch = len(self.last)
        step = (p - self.params[i - 1]).reshape(batch, -1) if i else np.zeros((batch, 1))
        previous = (self.last_p - self.before_p).reshape(batch, -1)
        length = np.sum(previous ** 2, axis=1)
        scale = np.divide(np.sum(step * previous, axis=1), length, out=np.zeros(batch),
                          where=(self.streak >= 2) & (length > 0))
        start = (self.last + scale[:, None] * (self.last - self.before))[rows]
        if domain is not None:    # a prediction out of the domain falls back on the last point
            within = np.asarray(domain(start))
            if within.shape != (len(start),):
                raise ValueError(f"domain returned shape {within.shape}, expected "
                                 f"({len(start)},): one bool per path")
            start = np.where(within.astype(bool)[:, None], start, self.last[rows])
        return start

    def accept(self, i, p, rows, res, det):
        """Record step ``i``: Newton's statuses, the jumps, and the accepted points."""
        batch = len(self.last)
        self.status[i, rows], self.iterations[i, rows] = res.status, res.iterations
        ok = np.zeros(batch, dtype=bool)
        ok[rows[res.converged]] = True
        new = np.full(self.last.shape, np.nan)
        new[rows[res.converged]] = res.x[res.converged]
        dets = np.full(batch, np.nan)
        dets[rows[res.converged]] = det
        flat = p.reshape(batch, -1)
        moved = np.linalg.norm(new - self.last, axis=1)
        dp = np.linalg.norm(flat - self.last_p.reshape(batch, -1), axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):
            speed = np.where(dp > 0, moved / dp, np.nan)
            fastest = np.max(np.where(np.isnan(self.speeds), -1.0, self.speeds), axis=1)
            visible = moved > _VISIBLE * (1.0 + np.linalg.norm(self.last, axis=1))
            too_fast = (self.max_jump is not None) & (fastest >= 0) & (dp > 0) & visible & (
                speed > (self.max_jump or 0.0) * fastest)
        flipped = (self.sign * np.sign(dets)) < 0
        jump = ok & (flipped | too_fast)
        self.status[i, jump] = "branch-jump"
        ok &= ~jump
        self.out[i, ok], self.det[i, ok] = new[ok], dets[ok]
        self.before = np.where(ok[:, None], self.last, self.before)
        self.before_p = np.where(ok.reshape((-1,) + (1,) * (p.ndim - 1)), self.last_p,
                                 self.before_p)
        self.last = np.where(ok[:, None], new, self.last)
        self.last_p = np.where(ok.reshape((-1,) + (1,) * (p.ndim - 1)), p, self.last_p)
        self.streak = np.where(ok, self.streak + 1, 0)
        shift = ok & (dp > 0) & (self.accepted >= 1)
        self.speeds[shift] = np.column_stack((self.speeds[shift, 1:], speed[shift]))
        self.sign = np.where(ok & (dets != 0), np.sign(dets), self.sign)
        self.accepted += ok

    def result(self, view):
        counts = {s: c for s, c in status_counts(self.status).items() if c}
        return PathResult(x=view(self.out), status=view(self.status),
                          message=f"{self.status.size} points: {counts}",
                          iterations=view(self.iterations), nfev=self.nfev, njev=self.njev,
                          det=view(self.det))


