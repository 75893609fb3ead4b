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
    run = _Run(eqs, x, rule, independent)
    steps, full = [], []
    for k in range(rule.maxiter + 1):
        run.check(full[-1] if full else None)
        active = run.running.copy()
        if not active.any() or k == rule.maxiter:
            break
        dx, full_norm = run.step(active)
        full.append(np.where(active, full_norm, np.nan))
        dx, shrink = bounded(dx, max_step)
        if damping:
            sure = run.meets_step(full_norm, run.x + dx)
            trial, failed, _ = line_search(run.call, run.x, run.f, run.J, dx, run.running,
                                           run.rnorm, sure, rule.norm, domain,
                                           shrink=shrink, stacked=independent,
                                           halvings=halvings)
            run.stop(failed != "", failed[failed != ""])
            x_new, f_new, J_new = trial.x, trial.f, trial.J
        else:
            x_new = run.x + dx  # dx is zero for the systems that are not moving
            if domain is not None:  # a step out of the domain is not taken, nor evaluated
                outside = run.running & ~inside(domain, x_new)
                run.stop(outside, "left-domain")
                x_new[outside] = run.x[outside]
            f_new, J_new = run.call(x_new, run.running)
        steps.append(run.advance(x_new, f_new, J_new))
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
    the status of every system (``""`` while it runs)."""

    def __init__(self, eqs, x, rule, independent):
        self.eqs, self.rule, self.independent = eqs, rule, independent
        self.iterations = np.zeros(len(x), dtype=int)
        self.status = np.full(len(x), "", dtype="<U11")
        self.running = np.ones(len(x), dtype=bool)  # status == "", kept up to date
        self.x = x
        self.f, self.J = eqs.value(x)
        self.rnorm = norms(self.f, rule.norm)
        self.limit = rule.tol * self.rnorm if rule.relative else rule.tol

    def call(self, points, rows):
        """``(f, J or None)`` at ``points``, at least of the systems ``rows``."""
        if not self.independent:
            return self.eqs.value(points)
        f = np.full(points.shape, np.nan)
        J = None if self.eqs.jac is not True else np.full(points.shape + points.shape[-1:],
                                                          np.nan)
        if rows.any():
            f_rows, J_rows = self.eqs.value(points[rows])
            f[rows] = f_rows
            if J is not None:
                J[rows] = J_rows
        return f, J

    def stop(self, which, why):
        """End the systems ``which`` (a mask) with the status ``why``."""
        if which.any():
            self.status[which] = why
            self.running[which] = False

    def meets_step(self, full_norm, x_next):
        """Which systems' full steps meet the step criterion (none for the residual one)."""
        if self.rule.criterion != "step":
            return np.zeros(len(full_norm), dtype=bool)
        scale = norms(x_next, self.rule.norm) if self.rule.relative else 1.0
        with np.errstate(invalid="ignore"):
            return np.isfinite(full_norm) & (full_norm <= self.rule.tol * scale)

    def check(self, last_full):
        """Stop the systems whose residual is not finite or that meet the criterion."""
        with np.errstate(invalid="ignore"):
            self.stop(self.running & ~np.isfinite(self.rnorm), "non-finite")
            if self.rule.criterion == "residual":
                met = self.rnorm <= self.limit
            else:
                met = (np.zeros(len(self.x), dtype=bool) if last_full is None
                       else self.meets_step(last_full, self.x))
        self.stop(self.running & met, "converged")

    def step(self, active):
        """The full Newton steps of the systems ``active`` (zero elsewhere) and their norms;
        the systems whose Jacobian is singular or not finite are stopped."""
        subset = self.independent and not active.all()  # then jac is called on active rows
        J_all = self.J if self.J is not None else None
        if subset:
            J = self.eqs.jacobian(self.x[active], self.f[active],
                                  None if J_all is None else J_all[active])
        else:
            J = self.eqs.jacobian(self.x, self.f, J_all)
            J = J if active.all() else J[active]
        finite = np.isfinite(J).all(axis=(-2, -1))
        bad = active.copy()
        bad[active] = ~finite
        self.stop(bad, "non-finite")
        dx = np.zeros_like(self.x)
        rows = np.flatnonzero(active)[finite]
        if rows.size:
            dx[rows], stuck, _ = newton_step(J[finite], self.f[rows])
            singular = np.zeros(len(self.x), dtype=bool)
            singular[rows[stuck]] = True
            self.stop(singular, "singular")
        return dx, norms(dx, self.rule.norm)

    def advance(self, x_new, f_new, J_new):
        """Move the running systems to their new points; the norms of their steps."""
        running = self.running
        self.iterations += running
        size = norms(x_new - self.x, self.rule.norm)
        keep = running[:, None]
        self.x = np.where(keep, x_new, self.x)
        self.f = np.where(keep, f_new, self.f)
        if self.J is not None and J_new is not None:
            self.J = np.where(keep[:, :, None], J_new, self.J)
        self.rnorm = norms(self.f, self.rule.norm)
        return np.where(running, size, np.nan)


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
