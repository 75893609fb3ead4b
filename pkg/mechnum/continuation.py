"""Continuation: a curve of solutions followed by its parameter, or traced through its folds.

*Natural-parameter continuation* (:func:`solve_path`) fixes the parameter at each of a given
sequence of values and corrects the state by Newton's method from a prediction. It stops at a
*fold*, where the curve turns back in the parameter and the Jacobian in the state is singular;
worse, Newton may leap across the fold onto another branch and converge there, which
:func:`solve_path` detects and reports as a ``"branch-jump"``.

Keller's *pseudo-arclength continuation* (:func:`pseudo_arclength`) treats the ``n`` equations
``F(u) = 0`` in the ``n + 1`` unknowns ``u = (state, parameter)`` alike, and steps along the
curve by its arclength ``h``:

1. the **tangent** ``t`` at a point ``u`` spans the null space of ``F'(u)`` (shape
   ``(n, n + 1)``); it is the solution of ``[F'(u); t_prev^T] t = [0; 1]``, normalised, so
   that it keeps the orientation of the previous tangent;
2. the **predictor** ``u + h t`` is corrected by Newton's method
   (:func:`mechnum.newton.solve`) on the bordered system ``F(v) = 0``, ``t . (v - u) = h``
   (the new point lies on the hyperplane at distance ``h`` along the tangent), whose Jacobian
   ``[F'(v); t^T]`` stays regular at a fold;
3. the step ``h`` is halved when Newton fails, and grows after an easy step.

A fold is where the parameter's component of the tangent changes sign; :func:`pseudo_arclength`
reports the intervals where it does and locates each fold on the curve by the secant method on
that component. Reference: H. B. Keller, *Numerical solution of bifurcation and nonlinear
eigenvalue problems* (1977); E. L. Allgower and K. Georg, *Introduction to Numerical
Continuation Methods* (2003), chapter 2.

Examples
--------
>>> import numpy as np
>>> path = solve_path(lambda x, p: x ** 2 - p[:, None], [1.0, 4.0, 9.0], [1.0])
>>> path.x[:, 0].round(12).tolist(), path.status.tolist()
([1.0, 2.0, 3.0], ['converged', 'converged', 'converged'])
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mechnum import _validate, newton
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.newton.core import SEARCH_HALVINGS, fd_jacobian, inside, newton_step
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
CORRECTOR_TOL = 1e-10
"""Default tolerance of :func:`pseudo_arclength`'s corrector: Newton's relative step test
(:data:`mechnum.newton.core.TOL`)."""
STEPS_LIMIT = 1_000_000
"""The most points :func:`pseudo_arclength` traces in one call."""
# The step grows by this factor after a step whose corrector needed at most _EASY iterations.
_GROWTH, _EASY = 1.5, 3
# Secant steps that locate a fold on its interval (each one a corrector), and the tolerance on
# the parameter's tangent component (relative to the tangent's unit length).
_FOLD_STEPS, _FOLD_TOL = 30, 1e-12
_SPEEDS = 3  # the steps before a point whose speed bounds its own (max_jump)


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

    def at(z, p):  # the Jacobian at converged points, for its determinant
        if jac is True:
            return np.asarray(fun(z, p)[1], dtype=float)
        if jac is None:
            return fd_jacobian(lambda w: fun(w, p), z)
        return np.asarray(jac(z, p), dtype=float)

    return residual, jacobian, at


def solve_path(fun: Callable, params, x0, jac: Callable | bool | None = None, *,
               tol: float = PATH_TOL, maxiter: int = 10, domain: Callable | None = None,
               halvings: int = SEARCH_HALVINGS, criterion: str = "residual",
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
      fastest of the (up to three) steps before it (checked once the path has one step).

    A jump is treated as a failure: the next step starts again from the last accepted point.

    Parameters
    ----------
    fun : callable
        ``fun(x, p) -> (m, n)`` for ``x`` of shape ``(m, n)`` and ``p`` of shape ``(m, ...)``:
        the rows of ``x`` and their parameters; with ``jac=True``, ``fun(x, p) -> (f, J)``.
    params : array_like, shape (steps, ...) or (steps, batch, ...)
        The parameters of every step (finite, real): for one path (``x0`` of shape ``(n,)``),
        or for each of ``batch`` paths; ``steps * batch`` at most :data:`PATH_POINTS_LIMIT`.
        No steps is a valid, empty path.
    x0 : array_like, shape (n,) or (batch, n)
        A solution at (or a start close to) ``params[0]``.
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
        Most halvings of a Newton step, as in :func:`~mechnum.newton.solve_all`.
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
        Ill-shaped, complex or non-finite ``params`` or ``x0``, an invalid option, or ``fun``,
        ``jac``, ``domain`` returning the wrong shapes.

    Examples
    --------
    The positive root of ``x**2 = p`` as ``p`` goes from 1 to 4:

    >>> p = np.linspace(1.0, 4.0, 7)
    >>> path = solve_path(lambda x, c: x ** 2 - c[:, None], p, [1.0],
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
    >>> path = solve_path(arm, np.column_stack([r * np.cos(phi), r * np.sin(phi)]),
    ...                   [-elbow / 2, elbow])
    >>> path.status.tolist(), path.x[:, 1].round(3).tolist()
    (['converged', 'converged', 'converged', 'branch-jump', 'converged'], [1.112, 0.782, 0.063, nan, 1.112])
    """
    x = _validate.array(x0, "x0", ndim=(1, 2))
    params = _validate.array(params, "params")
    if params.ndim == 0:
        raise ValueError(f"params must hold one parameter set per step, got the scalar "
                         f"{params!r}")
    if x.shape[-1] == 0:
        raise ValueError(f"x0 must have at least one unknown, got shape {x.shape}")
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
        res = newton.solve_batch(residual(p[rows]), start, jacobian(p[rows]), tol=tol, maxiter=maxiter, criterion=criterion,
                                 damping=True, domain=domain, raise_on_failure=False,
                                 halvings=halvings)
        path.nfev, path.njev = path.nfev + res.nfev, path.njev + res.njev
        done = rows[res.converged]
        det = np.linalg.det(at(res.x[res.converged], p[done])) if done.size else np.empty(0)
        path.njev += bool(done.size)
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
            start = np.where(inside(domain, start)[:, None], start, self.last[rows])
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
            too_fast = (self.max_jump is not None) & (fastest >= 0) & (dp > 0) & (
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


@dataclass(frozen=True, kw_only=True)
class Branch(Result):
    """A curve traced by :func:`pseudo_arclength`.

    Attributes
    ----------
    x : ndarray, shape (m, n + 1)
        The points (the parameter last), in the order traced (also :attr:`u`).
    status : str
        ``"converged"`` if the curve was traced to ``steps`` points or to ``stop``;
        ``"stagnated"`` if the step fell below ``min_step`` first.
    message, nfev, njev
        As in :class:`~mechnum.results.Result`.
    iterations : int
        Newton iterations of all the correctors.
    tangent : ndarray, shape (m, n + 1)
        The unit tangents at the points.
    folds : ndarray of int, shape (f,)
        ``i`` where a fold lies between ``u[i]`` and ``u[i + 1]``.
    fold_points : ndarray, shape (f, n + 1)
        The folds themselves (where the tangent's last component vanishes).
    rejected : int
        Steps halved because Newton failed.
    """

    tangent: np.ndarray
    folds: np.ndarray
    fold_points: np.ndarray
    rejected: int

    @property
    def u(self):
        """ndarray, shape (m, n + 1): the points (the same array as ``x``)."""
        return self.x

    @property
    def complete(self):
        """bool: False if the step fell below ``min_step`` before ``steps`` points or
        ``stop``."""
        return self.status == "converged"


class _Curve:
    """``fun`` and ``jac`` of :func:`pseudo_arclength`, checked and counted, and the corrector."""

    def __init__(self, fun, jac, size, tol, maxiter):
        self.fun, self.jac, self.n, self.tol, self.maxiter = fun, jac, size - 1, tol, maxiter
        self.nfev = self.njev = self.iterations = 0

    def value(self, u):
        out = np.asarray(self.fun(u))
        if out.shape != (self.n,) or out.dtype.kind not in "biuf":
            raise ValueError(f"fun must return a real array of shape ({self.n},) for u of "
                             f"shape ({self.n + 1},), got {out.dtype} of shape {out.shape}")
        self.nfev += 1
        return out.astype(float)

    def jacobian(self, u):
        out = np.asarray(self.jac(u))
        if out.ndim == 1 and self.n == 1:
            out = out[None]
        if out.shape != (self.n, self.n + 1) or out.dtype.kind not in "biuf":
            raise ValueError(f"jac must return a real array of shape ({self.n}, {self.n + 1}),"
                             f" got {out.dtype} of shape {out.shape}")
        self.njev += 1
        return out.astype(float)

    def correct(self, u, t, h):
        """Newton (:func:`mechnum.newton.solve`) on ``F(v) = 0``, ``t . (v - u) = h`` from
        ``u + h t``: ``(v, F'(v), iterations)``, or None if it fails."""
        try:
            res = newton.solve(lambda v: np.append(self.value(v), t @ (v - u) - h), u + h * t,
                               lambda v: np.vstack((self.jacobian(v), t)), tol=self.tol,
                               maxiter=self.maxiter)
        except (ConvergenceError, SingularJacobianError) as error:
            self.iterations += error.result.iterations
            return None
        self.iterations += res.iterations
        return res.x, self.jacobian(res.x), res.iterations


def _tangent(J, previous):
    """The unit null vector of ``J`` (shape ``(n, n + 1)``) on the side of ``previous``, or
    None where ``[J; previous]`` is singular (``J`` of rank below ``n``)."""
    border = np.vstack((J, previous))
    rhs = np.zeros(len(border))
    rhs[-1] = 1.0
    t, singular, _ = newton_step(border, -rhs)
    return None if singular else t / np.linalg.norm(t)


def _fold(curve, u, t, h, v, t_h):
    """The fold between ``u`` (tangent ``t``) and ``v``, the point at step ``h`` (tangent
    ``t_h``): the secant method
    on the step ``s`` for the last component of the tangent there (the last point reached, if
    a corrector fails on the way)."""
    def g(s):
        corrected = curve.correct(u, t, s)
        if corrected is None:
            return None
        tangent = _tangent(corrected[1], t)
        return None if tangent is None else (tangent[-1], corrected[0])

    (x0, g0), (x1, g1) = (0.0, t[-1]), (h, t_h[-1])
    for _ in range(_FOLD_STEPS):
        if abs(g1) <= _FOLD_TOL or g1 == g0:
            break
        x0, g0, x1 = x1, g1, x1 - g1 * (x1 - x0) / (g1 - g0)
        found = g(x1)
        if found is None:
            break
        g1, v = found
    return v


def pseudo_arclength(fun: Callable, jac: Callable, u0, *, direction=None, step: float = 0.1,
                     max_step: float | None = None, min_step: float = 1e-8,
                     steps: int = 200, tol: float = CORRECTOR_TOL, maxiter: int = 8,
                     stop: Callable | None = None) -> Branch:
    """Trace the curve ``F(u) = 0`` through ``u0`` by pseudo-arclength continuation.

    Parameters
    ----------
    fun : callable
        ``fun(u) -> (n,)``, for ``u`` of shape ``(n + 1,)`` (the parameter last).
    jac : callable
        ``jac(u) -> (n, n + 1)``, the Jacobian of ``fun``.
    u0 : array_like, shape (n + 1,)
        A point on the curve (to ``tol``), where ``F'`` has full rank ``n``.
    direction : array_like, shape (n + 1,), optional
        The way to go, non-zero: the first tangent is taken on its side. Default: increasing
        parameter.
    step, max_step, min_step : float, optional
        First arclength step, largest step (default ``10 step``), and the step below which
        the curve is declared lost.
    steps : int, optional
        Most points traced after ``u0``, at most :data:`STEPS_LIMIT`.
    tol, maxiter : optional
        Newton's corrector (:func:`mechnum.newton.solve`) stops when its step is below
        ``tol |v|`` (:data:`CORRECTOR_TOL`), and fails after ``maxiter`` iterations.
    stop : callable, optional
        ``stop(u) -> bool``: the point for which it is true is kept, and the tracing ends.

    Returns
    -------
    Branch

    Raises
    ------
    ValueError
        If ``u0`` is not on the curve (``|F(u0)| > 1e3 tol (1 + |u0|)``), ``fun`` or ``jac``
        return the wrong shape, or an input is out of range.
    SingularJacobianError
        If ``F'(u0)`` has rank below ``n`` (a bifurcation point, where no single tangent
        exists), or is orthogonal to ``direction``.
    ConvergenceError
        If no point after ``u0`` could be computed.

    Examples
    --------
    The circle ``x**2 + p**2 = 1`` folds at ``p = +-1``; from ``(1, 0)`` upwards:

    >>> fun = lambda u: np.array([u[0] ** 2 + u[1] ** 2 - 1.0])
    >>> jac = lambda u: np.array([[2.0 * u[0], 2.0 * u[1]]])
    >>> branch = pseudo_arclength(fun, jac, [1.0, 0.0], step=0.1, steps=40)
    >>> len(branch.folds), (np.round(branch.fold_points, 10) + 0.0).tolist()
    (2, [[0.0, 1.0], [0.0, -1.0]])
    """
    u = _validate.array(u0, "u0", ndim=1)
    if u.size < 2:
        raise ValueError(f"u0 must hold the unknowns and the parameter, got shape {u.shape}")
    tol = _validate.tolerance(tol)
    maxiter = _validate.maxiter(maxiter, maximum=newton.MAXITER_LIMIT)
    steps = _validate.maxiter(steps, "steps", maximum=STEPS_LIMIT)
    h = _validate.scalar(step, "step", positive=True)
    max_step = 10.0 * h if max_step is None else _validate.scalar(max_step, "max_step",
                                                                    positive=True)
    min_step = _validate.scalar(min_step, "min_step", positive=True)
    curve = _Curve(fun, jac, u.size, tol, maxiter)
    gap = np.linalg.norm(curve.value(u))
    if gap > 1e3 * tol * (1.0 + np.linalg.norm(u)):
        raise ValueError(f"u0 = {u!r} is not on the curve: |F(u0)| = {gap:.3g}")
    if direction is None:
        direction = np.zeros(u.size)
        direction[-1] = 1.0
    direction = _validate.array(direction, "direction", shape=u.shape)
    if not direction.any():
        raise ValueError("direction must be a non-zero vector")
    t = _tangent(curve.jacobian(u), direction)
    if t is None:
        raise SingularJacobianError(
            f"no tangent at u0 = {u!r}: F'(u0) has rank below {u.size - 1} (a bifurcation "
            f"point, where branches cross), or its null space is orthogonal to direction")
    points, tangents, folds, fold_points, rejected = [u], [t], [], [], 0
    status = "converged"
    while len(points) <= steps:
        corrected = curve.correct(u, t, h)
        t_new = None if corrected is None else _tangent(corrected[1], t)
        if t_new is None:
            h, rejected = 0.5 * h, rejected + 1
            if h < min_step:
                status = "stagnated"
                break
            continue
        v, _, iterations = corrected
        if np.sign(t_new[-1]) != np.sign(t[-1]) and t[-1] != 0:
            folds.append(len(points) - 1)
            fold_points.append(_fold(curve, u, t, h, v, t_new))
        u, t = v, t_new
        points.append(u)
        tangents.append(t)
        if iterations <= _EASY:
            h = min(_GROWTH * h, max_step)
        if stop is not None and stop(u):
            break
    if len(points) == 1:
        raise ConvergenceError(f"no point of the curve beyond u0 (the step fell below "
                               f"{min_step:g})")
    message = (f"{len(points)} points, {len(folds)} folds, {rejected} steps halved" +
               ("" if status == "converged" else f"; the step fell below {min_step:g}"))
    return Branch(x=np.array(points), status=status, message=message,
                  iterations=curve.iterations, nfev=curve.nfev, njev=curve.njev,
                  tangent=np.array(tangents), folds=np.array(folds, dtype=int),
                  fold_points=np.array(fold_points).reshape(len(fold_points), u.size),
                  rejected=rejected)
