"""Many systems at once: :func:`solve_batch`, Newton-Raphson on arrays of shape ``(batch, n)``.

Every system takes the step of :func:`mechnum.newton.solve`; a system that meets the criterion
(or fails) is frozen while the others go on, so each has its own iteration count and ``status``.

Examples
--------
>>> import numpy as np
>>> solve_batch(lambda x: x ** 2 - 4.0, [[1.0], [-1.0]], lambda x: 2 * x[:, :, None]).x.tolist()
[[2.0], [-2.0]]
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.newton._core import (
    HALVINGS_LIMIT,
    MAX_HALVINGS,
    MAXITER_LIMIT,
    TOL,
    Equations,
    bounded,
    describe,
    inside,
    line_search,
    newton_step,
    norms,
)
from mechnum.results import Result, StoppingRule, status_counts


@dataclass(frozen=True, kw_only=True)
class BatchNewtonResult(Result):
    """The outcome of :func:`solve_batch`, like scipy's result objects.

    Attributes
    ----------
    x : ndarray, shape (batch, n)
        The last iterate of every system.
    status : ndarray of str, shape (batch,)
        What happened to each system, one of :data:`~mechnum.results.STATUSES`.
    message : str
        How many converged, and the causes of the failures.
    iterations : ndarray of int, shape (batch,)
        Newton steps taken by each system.
    nfev, njev : int
        Calls of ``fun`` and of ``jac`` (each on the whole batch, or on the systems still
        running with ``independent=True``).
    step_norms : ndarray, shape (max(iterations), batch)
        ``||x_{k+1} - x_k||`` of every step taken by every system, NaN after a system stopped.
    full_step_norms : ndarray, shape (max(iterations), batch)
        ``||dx_k||`` of the full Newton steps, the quantity the step criterion tests.
    residual_norms : ndarray, shape (batch,)
        ``||f(x)||`` at the returned ``x``.
    """

    step_norms: np.ndarray
    full_step_norms: np.ndarray
    residual_norms: np.ndarray

    @property
    def singular(self) -> np.ndarray:
        """ndarray of bool: which systems stopped on a singular Jacobian."""
        return self.status == "singular"


def solve_batch(fun: Callable, seeds: ArrayLike, jac: Callable | bool | None = None, *,
                tol: float = TOL, maxiter: int = 50, criterion: str = "step", norm: float = 2,
                damping: bool = False, domain: Callable | None = None,
                raise_on_failure: bool = True, max_step: float | None = None,
                independent: bool = False, halvings: int = MAX_HALVINGS,
                relative: bool | None = None) -> BatchNewtonResult:
    """Solve ``batch`` independent systems ``fun(x)[b] = 0`` at once by Newton-Raphson.

    Every system takes the step of :func:`~mechnum.newton.solve`; a system that meets the
    criterion (or fails) is frozen while the others go on, so each has its own iteration count
    and ``status``. ``fun`` (and ``jac``) are evaluated on the whole batch, so they may depend
    on a per-system parameter (a time, a pose) by position in the batch; with
    ``independent=True`` they are evaluated on the systems still running only.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (batch, n)`` for ``x`` of shape ``(batch, n)``; with ``jac=True``,
        ``fun(x) -> (f, J)``, ``J`` of shape ``(batch, n, n)``.
    seeds : array_like, shape (batch, n)
        The initial guesses, one per system; must be finite and real. An empty batch is valid.
    jac : callable, True or None, optional
        ``jac(x) -> ndarray (batch, n, n)``; ``True`` if ``fun`` returns it. Default: forward
        differences.
    tol, maxiter, criterion, norm, damping, max_step, relative, halvings
        As in :func:`~mechnum.newton.solve`, applied to each system; with damping, a system
        whose line search stagnates gets the status "stagnated".
    domain : callable, optional
        ``domain(x) -> ndarray of bool (batch,)``, whether each iterate lies where the equations
        are meant to be solved. A step that leaves it is shortened (with damping) or ends its
        system with the status "left-domain"; ``fun`` is never called on a point outside it
        (only the ``seeds`` are the caller's to choose inside).
    raise_on_failure : bool, optional
        Raise (as below) if some system does not converge; with False, return the result and
        let the caller read ``status``.
    independent : bool, optional
        Declare that ``fun``, ``jac`` and ``domain`` do not depend on the position in the batch
        (one system from many starts, as in :func:`~mechnum.newton.solve_all`): then they are
        called on the rows that need them only, and the backtracking step lengths of all the
        systems that refuse a full step are tried in one call, so that a few slow systems do
        not cost a whole batch per halving.

    Returns
    -------
    BatchNewtonResult

    Raises
    ------
    ValueError
        As in :func:`~mechnum.newton.solve`, or ``domain`` returns the wrong shape.
    SingularJacobianError
        If the Jacobian of some system is singular at one of its iterates (and
        ``raise_on_failure``); ``result`` holds the :class:`BatchNewtonResult`.
    ConvergenceError
        If some other system fails to converge (and ``raise_on_failure``); ``result`` holds the
        :class:`BatchNewtonResult`, whose ``status`` tells which and why.

    Examples
    --------
    One equation from two seeds, one per root:

    >>> import numpy as np
    >>> res = solve_batch(lambda x: x ** 2 - 2.0, [[1.0], [-1.0]], lambda x: 2 * x[:, :, None])
    >>> res.x[:, 0].round(8).tolist()
    [1.41421356, -1.41421356]

    Three equations, with a parameter per system (by its position in the batch):

    >>> c = np.array([2.0, 3.0, 4.0])
    >>> res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((3, 1)),
    ...                   lambda x: 2 * x[:, :, None])
    >>> res.x[:, 0].round(8).tolist(), res.iterations.tolist()
    ([1.41421356, 1.73205081, 2.0], [5, 6, 6])
    >>> res = solve_batch(lambda x: x ** 2 + 1.0, [[0.3], [3.0]], lambda x: 2 * x[:, :, None],
    ...                   damping=True, raise_on_failure=False)
    >>> res.status.tolist()    # x**2 + 1 has no real root: a minimum of |f| at 0, no root
    ['stagnated', 'stagnated']
    """
    x = _validate.array(seeds, "seeds", ndim=2)
    if x.shape[1] == 0:
        raise ValueError(f"seeds must have shape (batch, n) with n >= 1, got shape {x.shape}")
    rule = StoppingRule.checked(tol, maxiter, criterion, norm, relative,
                                         maxiter_limit=MAXITER_LIMIT)
    damping = _validate.flag(damping, "damping")
    raise_on_failure = _validate.flag(raise_on_failure, "raise_on_failure")
    independent = _validate.flag(independent, "independent")
    max_step = None if max_step is None else _validate.tolerance(max_step, "max_step")
    halvings = _validate.maxiter(halvings, "halvings", maximum=HALVINGS_LIMIT)
    eqs = Equations(fun, jac)
    run = _Run(eqs, x.copy(), rule, independent)
    steps, full = [], []
    for k in range(rule.maxiter + 1):
        rows = run.check()
        if not rows.size or k == rule.maxiter:
            break
        rows, dx = run.step(rows)
        full.append(run.full)
        if not rows.size:
            steps.append(np.full(len(x), np.nan))
            continue
        dx, shrink = (dx, None) if max_step is None else bounded(dx, max_step)
        at = run.at
        x_old = run.x[at]
        if damping:
            sure = run.meets_step(run.full[at], x_old + dx)
            trial, failed, _ = line_search(run.call, x_old, run.f[at],
                                           None if run.J is None else run.J[at], dx,
                                           np.ones(len(rows), dtype=bool), run.rnorm[at],
                                           sure, rule.norm, domain, shrink=shrink,
                                           stacked=independent, halvings=halvings)
            moved = failed == ""
            run.stop(rows[~moved], failed[~moved])
            x_new, f_new, J_new = trial.x, trial.f, trial.J
        else:
            x_new = x_old + dx
            moved = np.ones(len(rows), dtype=bool)
            if domain is not None:  # a step out of the domain is not taken, nor evaluated
                moved = inside(domain, x_new)
                run.stop(rows[~moved], "left-domain")
                x_new[~moved] = x_old[~moved]
            f_new, J_new = run.call(x_new, moved)
        steps.append(run.advance(rows, moved, x_new, f_new, J_new))
    run.stop(run.running, "maxiter")
    shape = (len(steps), len(x))
    result = BatchNewtonResult(
        x=run.x, status=run.status, message=_message(run.status, run.rnorm, rule),
        iterations=run.iterations, nfev=eqs.nfev, njev=eqs.njev,
        step_norms=np.array(steps).reshape(shape), full_step_norms=np.array(full).reshape(shape),
        residual_norms=run.rnorm)
    if raise_on_failure and not result.converged.all():
        error = SingularJacobianError if result.singular.any() else ConvergenceError
        raise error(result.message, result)
    return result


class _Run:
    """The state of :func:`solve_batch`: iterates, residuals (and Jacobians from ``fun``), and
    the status of every system (``""`` while it runs).

    Every iteration works on the rows of the running systems only (gathered once, scattered
    back once), so that its cost follows the systems still running, not the batch: only the
    array of iterates, which ``fun`` and ``jac`` receive, is copied (never changed in place).
    """

    def __init__(self, eqs, x, rule, independent):
        self.eqs, self.rule, self.independent = eqs, rule, independent
        self.iterations = np.zeros(len(x), dtype=int)
        self.status = np.full(len(x), "", dtype="<U11")
        self.running = np.ones(len(x), dtype=bool)  # status == "", kept up to date
        self.x = x
        # copies: these are updated in place, and fun may return arrays it keeps (a memo)
        self.f, self.J = (None if a is None else a.copy() for a in eqs.value(x))
        self.rnorm = norms(self.f, rule.norm)
        self.limit = rule.tol * self.rnorm if rule.relative else rule.tol
        self.full = None    # the norms of the last full steps (NaN where none was taken)
        self.rows = self.at = np.arange(0)    # the rows of the iteration under way

    def _index(self, rows):
        """``rows`` as an index: the whole batch as a slice (views, no copies)."""
        return slice(None) if len(rows) == len(self.x) else rows

    def call(self, points, which):
        """``(f, J or None)`` at ``points`` of the rows under way, at least at ``which`` (a
        mask of them); the other systems, if ``fun`` depends on the position in the batch,
        at their own iterates."""
        if not self.independent:
            if isinstance(self.at, slice):
                return self.eqs.value(points)
            full = self.x.copy()
            full[self.rows] = points
            f, J = self.eqs.value(full)
            return f[self.rows], None if J is None else J[self.rows]
        if which.all():
            return self.eqs.value(points)
        f = np.full(points.shape, np.nan)
        J = None if self.eqs.jac is not True else np.full(points.shape + points.shape[-1:],
                                                          np.nan)
        if which.any():
            f_rows, J_rows = self.eqs.value(points[which])
            f[which] = f_rows
            if J is not None:
                J[which] = J_rows
        return f, J

    def stop(self, which, why):
        """End the systems ``which`` (a mask, or indices) with the status ``why``."""
        if which.any() if which.dtype == bool else which.size:
            self.status[which] = why
            self.running[which] = False

    def meets_step(self, full_norm, x_next):
        """Which systems' full steps meet the step criterion (none for the residual one)."""
        if self.rule.criterion != "step":
            return np.zeros(len(full_norm), dtype=bool)
        scale = norms(x_next, self.rule.norm) if self.rule.relative else 1.0
        with np.errstate(invalid="ignore"):
            return np.isfinite(full_norm) & (full_norm <= self.rule.tol * scale)

    def check(self):
        """Stop the systems whose residual is not finite or that meet the criterion; the rows
        of those that run on."""
        rows = np.flatnonzero(self.running)
        at = self._index(rows)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(self.rnorm[at])
            if bad.any():
                self.stop(rows[bad], "non-finite")
                rows = rows[~bad]
                at = rows
            if self.rule.criterion == "residual":
                met = self.rnorm[at] <= (self.limit[at] if np.ndim(self.limit) else self.limit)
            elif self.full is None:
                return rows
            else:
                met = self.meets_step(self.full[at], self.x[at])
        if met.any():
            self.stop(rows[met], "converged")
            rows = rows[~met]
        return rows

    def step(self, rows):
        """The full Newton steps of the systems ``rows``; the systems whose Jacobian is
        singular or not finite are stopped. Returns the rows that go on and their steps
        (their norms in ``full``, with 0 for the stopped ones); ``at`` indexes them."""
        self.rows = rows
        self.at = at = self._index(rows)
        if self.J is not None:
            J = self.J[at]
        elif self.independent:
            J = self.eqs.jacobian(self.x[at], self.f[at])
        else:
            J = self.eqs.jacobian(self.x, self.f)[at]
        # (one test of the whole stack first: reducing over its small last axes is slow)
        finite = (np.ones(len(rows), dtype=bool) if np.isfinite(J).all()
                  else np.isfinite(J).all(axis=(-2, -1)))
        if finite.all():
            dx, stuck, _ = newton_step(J, self.f[at])
            go = ~stuck
        else:
            self.stop(rows[~finite], "non-finite")
            dx, go = np.zeros((len(rows), self.x.shape[1])), finite.copy()
            if finite.any():
                dx[finite], stuck, _ = newton_step(J[finite], self.f[rows[finite]])
                go[np.flatnonzero(finite)[stuck]] = False
        self.stop(rows[finite & ~go], "singular")
        self.full = norms(dx, self.rule.norm)
        if not isinstance(at, slice):       # NaN for the systems not stepping
            taken, self.full = self.full, np.full(len(self.x), np.nan)
            self.full[at] = taken
        if not go.all():
            self.rows = rows = rows[go]
            self.at, dx = rows, dx[go]
        return rows, dx

    def advance(self, rows, moved, x_new, f_new, J_new):
        """Move the systems ``rows[moved]`` to their new points; the norms of their steps."""
        if not moved.all():
            rows, x_new, f_new = rows[moved], x_new[moved], f_new[moved]
            J_new = None if J_new is None else J_new[moved]
        at = self._index(rows)
        self.iterations[at] += 1
        out = norms(x_new - self.x[at], self.rule.norm)
        if not isinstance(at, slice):       # NaN for the systems not moving
            taken, out = out, np.full(len(self.x), np.nan)
            out[at] = taken
        # a new array of iterates (never one changed in place: fun and jac may remember the
        # last array they were called with), the new points themselves when all moved
        if isinstance(at, slice):
            self.x = x_new
        else:
            self.x = self.x.copy()
            self.x[at] = x_new
        self.f[at] = f_new
        if self.J is not None and J_new is not None:
            self.J[at] = J_new
        self.rnorm[at] = norms(f_new, self.rule.norm)
        return out


def _message(status, rnorm, rule):
    """The batch's outcome in a sentence: the count of converged systems and of each failure,
    the first failing systems, and the largest finite residual norm among them."""
    failed = np.flatnonzero(status != "converged")
    text = f"{len(status) - failed.size} of {len(status)} systems converged ({describe(rule)})"
    if not failed.size:
        return text
    kinds = {s: c for s, c in status_counts(status).items() if c and s != "converged"}
    finite = rnorm[failed][np.isfinite(rnorm[failed])]
    largest = f"{finite.max():.3g}" if finite.size else "none finite"
    return (f"{text}; failed: {kinds} (first: {failed[:10].tolist()}; largest residual norm "
            f"of a failed system {largest}); a singular Jacobian does not stop the others")
