"""Newton-Raphson for systems of nonlinear equations, one, many, and all solutions.

Five forms share one step rule:

* :func:`solve` solves one system ``f(x) = 0`` of ``n`` equations in ``n`` unknowns and keeps
  its whole history;
* :func:`solve_batch` solves ``batch`` independent systems of the same size at once, with
  arrays of shape ``(batch, n)``; each system stops when it converges, the others go on, and
  each reports a ``status``;
* :func:`solve_all` looks for every root of one system: :func:`solve_batch` from many starts,
  the roots deduplicated and counted, and a completeness check (ten times more starts that find
  no new root);
* :func:`broyden` replaces the Jacobian of :func:`solve` after the first by rank-one updates
  (Broyden's method): no Jacobian evaluations, superlinear instead of quadratic convergence;
* :func:`solve_path` follows a root while a parameter changes (continuation), one path or a
  batch of paths.

The Newton step solves ``J(x_k) dx = -f(x_k)`` and sets ``x_{k+1} = x_k + dx``. With
``damping=True`` the step is shortened, ``x_{k+1} = x_k + alpha dx`` with ``alpha = 1, 1/2,
1/4, ...``, until the residual norm decreases enough (Armijo's rule,
``||f(x_k + alpha dx)|| <= (1 - 1e-4 alpha) ||f(x_k)||``): a backtracking line search, which
keeps a bad start from being thrown far away. A start whose line search finds no such
``alpha`` has *stagnated* (it sits near a local minimum of ``||f||`` that is no root) and is
dropped instead of being iterated to ``maxiter``. An optional ``domain`` (a test of the iterates)
keeps the iterates where the equations make sense; a step that leaves it is shortened too (with
damping) or the system is dropped.

The stopping criterion is explicit because iteration counts depend on it:

* ``criterion="step"`` stops after the first step with ``||dx|| < tol`` (the rule of most course
  codes, the hacksaw study's included; the accepted ``x`` is the one after that step);
* ``criterion="residual"`` stops as soon as ``||f(x_k)|| < tol``.

``norm`` is the ``ord`` of :func:`numpy.linalg.norm` (default 2, the Euclidean norm).

Without an analytic Jacobian, a forward-difference one is used (:func:`fd_jacobian`): column
``j`` is ``(f(x + h_j e_j) - f(x)) / h_j`` with ``h_j = sqrt(eps) * max(1, |x_j|)``, accurate to
about half the digits of ``f``, which still gives Newton a fast (no longer quadratic) rate.
The methods here are real: a residual or a Jacobian with complex values is refused.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.errors import ConvergenceError, SingularJacobianError

_SQRT_EPS = np.sqrt(np.finfo(float).eps)  # the forward-difference step that balances errors
_MAX_COND = 1.0 / np.finfo(float).eps  # a condition number past which no digit is left
_TINY = np.finfo(float).tiny
_CRITERIA = ("step", "residual")
_NORMS = (1, 2, np.inf)
# Armijo's sufficient decrease: accept alpha when ||f|| falls by at least 1e-4 alpha of itself
# (the customary constant: any decrease counts, but not a vanishing one).
_ARMIJO = 1e-4
# Backtracking gives up after this many halvings (alpha < 1e-6): the start has stagnated.
_MAX_HALVINGS = 20
# In an all-solutions search, a start gets 4 halvings (alpha >= 1/16): a start whose Newton step
# must be cut further lies where Newton's linear model is poor, and dropping it costs hits, not
# roots (other starts reach them), while its 20 halvings per step would dominate the run (on the
# 2RFR of Chapter 5, 4 halvings keep half the converging starts for 1/30 of the time).
_SEARCH_HALVINGS = 4
STATUSES = ("converged", "maxiter", "singular", "non-finite", "stagnated", "left-domain")
"""What :attr:`BatchNewtonResult.status` may say of a system: it met the criterion; it ran out
of iterations; its Jacobian was singular; its residual stopped being finite; its line search
found no decrease (damping); its iterate left the ``domain``."""


@dataclass(frozen=True)
class NewtonResult:
    """The outcome of :func:`solve`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The last iterate.
    iterations : int
        Newton steps taken.
    converged : bool
        Whether the stopping criterion was met.
    history : ndarray, shape (iterations + 1, n)
        Every iterate, the initial guess first.
    residual_norms : ndarray, shape (iterations + 1,)
        ``||f(x_k)||`` for every iterate in ``history``.
    step_norms : ndarray, shape (iterations,)
        ``||x_{k+1} - x_k||`` for every step.
    """

    x: np.ndarray
    iterations: int
    converged: bool
    history: np.ndarray
    residual_norms: np.ndarray
    step_norms: np.ndarray


@dataclass(frozen=True)
class BatchNewtonResult:
    """The outcome of :func:`solve_batch`, like scipy's result objects.

    Attributes
    ----------
    x : ndarray, shape (batch, n)
        The last iterate of every system.
    iterations : ndarray of int, shape (batch,)
        Newton steps taken by each system.
    status : ndarray of str, shape (batch,)
        What happened to each system, one of :data:`STATUSES`.
    step_norms : ndarray, shape (max(iterations), batch)
        ``||x_{k+1} - x_k||`` of every step of every system, NaN after a system stopped.
    residual_norms : ndarray, shape (batch,)
        ``||f(x)||`` at the returned ``x``.
    nfev, njev : int
        Calls of ``fun`` and of ``jac`` (each on the whole batch).
    """

    x: np.ndarray
    iterations: np.ndarray
    status: np.ndarray
    step_norms: np.ndarray
    residual_norms: np.ndarray
    nfev: int
    njev: int

    @property
    def converged(self):
        """ndarray of bool: which systems met the stopping criterion."""
        return self.status == "converged"

    @property
    def singular(self):
        """ndarray of bool: which systems stopped on a singular Jacobian."""
        return self.status == "singular"


@dataclass(frozen=True)
class RootSet:
    """The outcome of :func:`solve_all`: the distinct roots found, and how hard they were looked for.

    Attributes
    ----------
    roots : ndarray, shape (r, n)
        The distinct roots, ``r >= 0``, in the order of their first component.
    hits : ndarray of int, shape (r,)
        How many starts (of both runs) converged to each root: a root with few hits has a small
        basin of attraction, a warning that others like it may have been missed.
    residual_norms : ndarray, shape (r,)
        ``||f||`` at each root.
    n_starts : int
        Starts of the search.
    n_check : int
        Starts of the completeness check (new ones, ``check`` times as many).
    new_in_check : int
        Roots that only the check found (they are in ``roots``). Zero is the evidence of
        completeness: ten times more starts found nothing new. It is evidence, not proof: a
        root whose basin no start hits stays unseen.
    status_counts : dict
        How many starts of both runs ended in each status of :data:`STATUSES`.
    """

    roots: np.ndarray
    hits: np.ndarray
    residual_norms: np.ndarray
    n_starts: int
    n_check: int
    new_in_check: int
    status_counts: dict

    @property
    def complete(self):
        """bool: whether the completeness check found no new root."""
        return self.new_in_check == 0


def fd_jacobian(fun, x, fx=None):
    """Forward-difference Jacobian of ``fun`` at ``x``, for one system or a batch.

    Parameters
    ----------
    fun : callable
        ``fun(x)`` with ``x`` of shape ``(n,)`` or ``(batch, n)``, returning the same shape.
    x : ndarray, shape (n,) or (batch, n)
        Where to differentiate.
    fx : ndarray, optional
        ``fun(x)``, if already known.

    Returns
    -------
    ndarray, shape (n, n) or (batch, n, n)
        ``J[..., i, j] ~= d fun_i / d x_j``.

    Examples
    --------
    >>> import numpy as np
    >>> J = fd_jacobian(lambda x: np.array([x[0] ** 2, x[0] * x[1]]), np.array([1.0, 2.0]))
    >>> np.round(J, 6)
    array([[2., 0.],
           [2., 1.]])
    """
    x = _validate.array(x, "x", ndim=(1, 2))
    fx = _evaluate(fun, x, "fun") if fx is None else fx
    n = x.shape[-1]
    h = _SQRT_EPS * np.maximum(1.0, np.abs(x))
    jac = np.empty(x.shape[:-1] + (n, n))
    for j in range(n):
        xj = x.copy()
        xj[..., j] += h[..., j]
        jac[..., :, j] = (_evaluate(fun, xj, "fun") - fx) / h[..., j, None]
    return jac


def _controls(tol, maxiter, criterion, norm):
    return (_validate.tolerance(tol), _validate.maxiter(maxiter),
            _validate.choice(criterion, _CRITERIA, "criterion"), _validate.choice(norm, _NORMS, "norm"))


def _evaluate(fun, x, what):
    """Call ``fun(x)`` and check that it returns a real array of ``x``'s shape."""
    fx = np.asarray(fun(x))
    if np.iscomplexobj(fx):
        raise ValueError(f"{what} returned complex values: this Newton solver is real "
                         f"(split a complex system into real and imaginary parts)")
    fx = fx.astype(float, copy=False)
    if fx.shape != x.shape:
        raise ValueError(f"{what} returned shape {fx.shape}, expected {x.shape}")
    return fx


def _jacobian(jac, fun, x):
    """``jac(x)`` (or forward differences), checked: real, of shape ``x.shape + (n,)``."""
    if jac is None:
        return fd_jacobian(fun, x)
    J = np.asarray(jac(x))
    if np.iscomplexobj(J):
        raise ValueError("jac returned complex values: this Newton solver is real")
    J = J.astype(float, copy=False)
    if J.shape != x.shape + x.shape[-1:]:
        raise ValueError(f"jac returned shape {J.shape}, expected {x.shape + x.shape[-1:]}")
    return J


def _largest(a):
    """The largest entry along the last axis. (NumPy reduces a short last axis slowly, one row
    at a time: reduce the transposed copy along its first axis, many rows at once.)"""
    return np.ascontiguousarray(a.reshape(-1, a.shape[-1]).T).max(axis=0).reshape(a.shape[:-1])


def _norms(v, norm):
    """``np.linalg.norm(v, norm, axis=-1)`` for a stack of short vectors, several times faster
    (the sums over the short last axis are products with a vector of ones)."""
    if v.ndim == 1:
        return np.linalg.norm(v, norm)
    a = np.abs(v)
    if norm == np.inf:
        return _largest(a)
    ones = np.ones(v.shape[-1])
    return a @ ones if norm == 1 else np.sqrt((a * a) @ ones)


def _newton_step(jac, fx):
    """Solve ``J dx = -f`` for one system or a stack; flag the (numerically) singular ``J``.

    Besides an exactly singular ``J`` (LAPACK's zero pivot), a step is flagged when
    ``max|J_ij| ||dx||_1 / ||f||_1``, a lower bound of the condition number ``||J||_1
    ||J^-1||_1`` (since ``||J||_1 >= max|J_ij|`` and ``||J^-1||_1 >= ||dx||_1 / ||f||_1``),
    exceeds ``1/eps``: then no digit of ``dx`` can be trusted. A system with ``f = 0`` is never
    flagged.

    Returns
    -------
    dx : ndarray
        The steps (zero where flagged).
    singular : ndarray of bool
        The flags, one per system.
    cond : ndarray or None
        The lower bounds of the condition numbers (``inf`` where ``J`` is exactly singular),
        or None when nothing is flagged.
    """
    exact = np.zeros(fx.shape[:-1], dtype=bool)
    try:  # a 1-D right-hand side for one system, a stack of columns for a batch
        dx = (np.linalg.solve(jac, -fx) if fx.ndim == 1
              else np.linalg.solve(jac, -fx[..., None])[..., 0])
    except np.linalg.LinAlgError:  # some J is exactly singular: find which
        dx = np.zeros_like(fx)
        for i in np.ndindex(fx.shape[:-1]):
            try:
                dx[i] = np.linalg.solve(jac[i], -fx[i])
            except np.linalg.LinAlgError:
                exact[i] = True
    fsize = _norms(fx, 1)
    growth = _largest(np.abs(jac).reshape(jac.shape[:-2] + (-1,))) * _norms(dx, 1)
    trusted = growth <= _MAX_COND * fsize  # False where growth is inf or NaN
    if trusted.all() and not exact.any():
        return dx, exact, None
    singular = (exact | ~trusted) & (fsize > 0)
    cond = np.where(exact, np.inf, growth / np.maximum(fsize, _TINY))
    return np.where(singular[..., None], 0.0, dx), singular, cond


def _line_search(call, x, fx, dx, moving, rnorm, tol, norm, domain, stacked=False,
                 halvings=_MAX_HALVINGS):
    """Backtracking for the systems ``moving`` of a batch: halve ``alpha`` from 1 until the
    trial point lies in the domain and ``||f||`` decreases by Armijo's rule (or the step is
    already below ``tol``). ``call(points, rows)`` evaluates the residual (at least of the
    systems ``rows``). With ``stacked`` (the systems do not depend on their position), the
    step lengths ``1/2, 1/4, ...`` of the systems that refuse ``alpha = 1`` are all tried in one
    call, with the same outcome as one halving at a time. Returns the new ``x``, ``f(x)``, the
    status of the systems that found no such ``alpha`` ("stagnated" or "left-domain", ""
    elsewhere) and the calls of ``fun``."""
    alpha = np.ones(len(x))
    size = _norms(dx, norm)
    x_new, fx_new = x.copy(), fx.copy()
    pending, outside = moving.copy(), np.zeros(len(x), dtype=bool)
    for calls in range(1, halvings + 2):
        if stacked and calls == 2:
            return _all_halvings(call, x, dx, x_new, fx_new, pending, rnorm, size, tol, norm,
                                 domain, halvings)
        trial = np.where(pending[:, None], x + alpha[:, None] * dx, x_new)
        inside = np.ones(len(x), dtype=bool) if domain is None else np.asarray(domain(trial), bool)
        # fun is never evaluated outside the domain (where it may be undefined or raise)
        f_trial = call(np.where(inside[:, None], trial, x_new), pending & inside)
        t_norm = _norms(f_trial, norm)
        ok = pending & inside & np.isfinite(t_norm) & (
            (t_norm <= (1 - _ARMIJO * alpha) * rnorm) | (alpha * size < tol))
        x_new[ok], fx_new[ok] = trial[ok], f_trial[ok]
        pending &= ~ok
        outside = pending & ~inside
        if not pending.any():
            break
        alpha[pending] /= 2
    failed = np.where(outside, "left-domain", "stagnated")
    return x_new, fx_new, np.where(pending, failed, ""), calls


def _all_halvings(call, x, dx, x_new, fx_new, pending, rnorm, size, tol, norm, domain,
                  halvings):
    """The rest of :func:`_line_search` for position-free systems: ``alpha = 2**-1, ...,
    2**-halvings`` of every pending system in one call; each takes its largest acceptable
    ``alpha``, as the halving loop would."""
    rows = np.flatnonzero(pending)
    alpha = 0.5 ** np.arange(1, halvings + 1)
    trial = x[rows, None, :] + alpha[:, None] * dx[rows, None, :]       # (rows, alphas, n)
    flat = trial.reshape(-1, x.shape[1])
    inside = (np.ones(len(flat), dtype=bool) if domain is None
              else np.asarray(domain(flat), bool))
    f_flat = np.full(flat.shape, np.nan)
    if inside.any():
        f_flat[inside] = call(flat[inside], np.ones(inside.sum(), dtype=bool))
    t_norm = _norms(f_flat, norm).reshape(len(rows), -1)
    ok = inside.reshape(len(rows), -1) & np.isfinite(t_norm) & (
        (t_norm <= (1 - _ARMIJO * alpha) * rnorm[rows, None])
        | (alpha * size[rows, None] < tol))
    first = ok.argmax(axis=1)
    found = ok[np.arange(len(rows)), first]
    take = rows[found]
    x_new[take] = trial[found, first[found]]
    fx_new[take] = f_flat.reshape(len(rows), -1, x.shape[1])[found, first[found]]
    status = np.full(len(x), "", dtype="<U11")
    status[rows[~found]] = np.where(inside.reshape(len(rows), -1)[~found, -1], "stagnated",
                                    "left-domain")
    return x_new, fx_new, status, 2


def solve(fun, x0, jac=None, *, tol=1e-10, maxiter=50, criterion="step", norm=2, damping=False,
          max_step=None):
    """Solve ``fun(x) = 0`` by Newton-Raphson.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (n,)``, the residual (real).
    x0 : array_like, shape (n,)
        Initial guess; must be finite and real.
    jac : callable, optional
        ``jac(x) -> ndarray (n, n)``, the Jacobian. Default: :func:`fd_jacobian`.
    tol : float, optional
        Tolerance of the stopping criterion (positive).
    maxiter : int, optional
        Most Newton steps.
    criterion : {"step", "residual"}, optional
        Stop on ``||dx|| < tol`` (after that step) or on ``||f(x)|| < tol``.
    norm : {2, 1, inf}, optional
        Vector norm of the criterion.
    damping : bool, optional
        Backtrack along each step until ``||f||`` decreases (see the module's description);
        raise :class:`~mechnum.errors.ConvergenceError` if no step length decreases it.
    max_step : float, optional
        Shorten every Newton step to at most this size (largest component) before anything
        else: a start far from the root then moves towards it in bounded strides, where a full
        step could leap across a periodic or unbounded variable to a far, wrong basin.

    Returns
    -------
    NewtonResult

    Raises
    ------
    ValueError
        If ``x0`` is not a finite real vector, an option is invalid, or ``fun``/``jac`` return
        the wrong shape or complex values.
    SingularJacobianError
        If the Jacobian is singular at an iterate; ``result`` holds the partial result.
    ConvergenceError
        If ``maxiter`` steps do not meet the criterion, an iterate stops being finite, or (with
        damping) the line search stagnates; its ``result`` attribute holds the partial
        :class:`NewtonResult`.

    Examples
    --------
    >>> import numpy as np
    >>> res = solve(lambda x: np.array([x[0] ** 2 - 2.0]), [1.0], lambda x: np.array([[2 * x[0]]]))
    >>> res.converged, res.iterations, round(float(res.x[0]), 12)
    (True, 5, 1.414213562373)

    Plain Newton on ``arctan(x) = 0`` from ``x0 = 1.5`` overshoots further at every step and
    diverges; damped, it converges:

    >>> res = solve(lambda x: np.arctan(x), [1.5], lambda x: np.diag(1 / (1 + x**2)), damping=True)
    >>> res.converged, abs(float(res.x[0])) < 1e-12
    (True, True)
    """
    return _iterate(fun, x0, lambda x, fx: _jacobian(jac, fun, x), tol, maxiter, criterion, norm,
                    damping, "Newton", "Jacobian", max_step)


def _bounded(dx, max_step):
    """The steps ``dx`` (one per row), each shortened to at most ``max_step`` in its largest
    component; all of them if ``max_step`` is None."""
    if max_step is None:
        return dx
    largest = np.max(np.abs(dx), axis=-1, keepdims=True)
    return dx * np.minimum(1.0, max_step / np.maximum(largest, _TINY))


def _iterate(fun, x0, matrix, tol, maxiter, criterion, norm, damping, method, what,
             max_step=None):
    """The iteration of :func:`solve` and :func:`broyden`: step ``dx`` solves
    ``matrix(x, fx) dx = -fx``, where ``matrix`` is the Jacobian (Newton) or its update
    (Broyden), the ``what`` of the error messages."""
    x = _validate.array(x0, "x0", ndim=1)
    if x.size == 0:
        raise ValueError("x0 must have shape (n,) with n >= 1, got shape (0,)")
    tol, maxiter, criterion, norm = _controls(tol, maxiter, criterion, norm)
    max_step = None if max_step is None else _validate.tolerance(max_step, "max_step")
    history, residuals, steps = [x], [], []
    converged = singular = stagnated = False
    fx = _evaluate(fun, x, "fun")
    while True:
        residuals.append(np.linalg.norm(fx, norm))
        if not np.isfinite(residuals[-1]) or (criterion == "step" and steps and steps[-1] < tol):
            converged = bool(np.isfinite(residuals[-1]))
            break
        if criterion == "residual" and residuals[-1] < tol:
            converged = True
            break
        if len(steps) == maxiter:
            break
        dx, singular, cond = _newton_step(matrix(x, fx), fx)
        if singular:
            break
        dx = _bounded(dx, max_step)
        if damping:  # the batched line search, on a batch of this one system
            new, f_new, failed, _ = _line_search(
                lambda z, _: _evaluate(fun, z[0], "fun")[None], x[None], fx[None], dx[None],
                np.ones(1, bool), residuals[-1:], tol, norm, None)
            if failed[0]:
                stagnated = True
                break
            x_new, fx = new[0], f_new[0]
        else:
            x_new = x + dx
            fx = _evaluate(fun, x_new, "fun")
        steps.append(np.linalg.norm(x_new - x, norm))
        x = x_new
        history.append(x)
    result = NewtonResult(x, len(steps), converged, np.array(history), np.array(residuals),
                          np.array(steps))
    if singular:
        raise SingularJacobianError(
            f"singular {what} at iteration {len(steps)}: condition number >= {cond:.3g}, "
            f"residual norm {residuals[-1]:.3g}", result)
    if stagnated:
        raise ConvergenceError(
            f"the line search stagnated at iteration {len(steps)}: no step shorter than "
            f"2**-{_MAX_HALVINGS} of {method}'s decreases the residual norm {residuals[-1]:.3g} "
            f"(a local minimum of ||f|| that is no root?)", result)
    if not converged:
        raise ConvergenceError(
            f"{method} did not converge in {len(steps)} iterations: last step norm "
            f"{steps[-1] if steps else float('nan'):.3g}, residual norm {residuals[-1]:.3g} "
            f"(criterion {criterion!r}, tol {tol:g})", result)
    return result


def broyden(fun, x0, jac=None, *, tol=1e-10, maxiter=100, criterion="step", norm=2):
    """Solve ``fun(x) = 0`` by Broyden's method: Newton's step with an updated Jacobian.

    The Jacobian is evaluated once, at ``x0`` (``B_0 = J(x0)``); after every step
    ``s = x_{k+1} - x_k``, with ``y = f(x_{k+1}) - f(x_k)``, it is replaced by the closest
    matrix (in the Frobenius norm) that maps ``s`` to ``y`` (the secant condition
    ``B_{k+1} s = y``), a rank-one update::

        B_{k+1} = B_k + (y - B_k s) s^T / (s^T s)

    (Broyden's "good" update). Each iteration costs one evaluation of ``fun`` and no Jacobian;
    the convergence is superlinear instead of quadratic, so it takes more iterations than
    Newton: worth it when the Jacobian is expensive. Step, criteria and errors as in
    :func:`solve` (no damping).

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (n,)``, the residual (real).
    x0 : array_like, shape (n,)
        Initial guess; must be finite and real.
    jac : callable, optional
        ``jac(x) -> ndarray (n, n)``, evaluated at ``x0`` only. Default: :func:`fd_jacobian`.
    tol, maxiter, criterion, norm
        As in :func:`solve`.

    Returns
    -------
    NewtonResult
        ``iterations`` is the number of Broyden steps (each one call of ``fun``).

    Raises
    ------
    ValueError, SingularJacobianError, ConvergenceError
        As :func:`solve` (a singular update is a :class:`SingularJacobianError`).

    Examples
    --------
    >>> import numpy as np
    >>> fun = lambda x: np.array([x[0] ** 2 + x[1] ** 2 - 1.0, x[0] - x[1]])
    >>> jac = lambda x: np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])
    >>> res = broyden(fun, [1.0, 0.5], jac, tol=1e-12)
    >>> res.iterations, solve(fun, [1.0, 0.5], jac, tol=1e-12).iterations
    (7, 6)
    >>> np.round(res.x, 12).tolist()
    [0.707106781187, 0.707106781187]
    """
    last = {}

    def matrix(x, fx):
        if not last:
            B = _jacobian(jac, fun, x)
        else:
            B, s, y = last["B"], x - last["x"], fx - last["f"]
            if s @ s > 0:
                B = B + np.outer(y - B @ s, s) / (s @ s)
        last.update(B=B, x=x, f=fx)
        return B

    return _iterate(fun, x0, matrix, tol, maxiter, criterion, norm, False, "Broyden's method",
                    "Broyden matrix")


def solve_batch(fun, x0, jac=None, *, tol=1e-10, maxiter=50, criterion="step", norm=2,
                damping=False, domain=None, raise_on_failure=True, max_step=None,
                independent=False, halvings=_MAX_HALVINGS):
    """Solve ``batch`` independent systems ``fun(x)[b] = 0`` at once by Newton-Raphson.

    Every system takes the step of :func:`solve`; a system that meets the criterion (or fails)
    is frozen while the others go on, so each has its own iteration count and ``status``.
    ``fun`` (and ``jac``) are evaluated on the whole batch, so they may depend on a
    per-system parameter (a time, a pose) by position in the batch; with ``independent=True``
    they are evaluated on the systems still running only.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (batch, n)`` for ``x`` of shape ``(batch, n)``.
    x0 : array_like, shape (batch, n)
        Initial guesses; must be finite and real. An empty batch is valid.
    jac : callable, optional
        ``jac(x) -> ndarray (batch, n, n)``. Default: :func:`fd_jacobian`.
    tol, maxiter, criterion, norm, damping, max_step
        As in :func:`solve`, applied to each system; with damping, a system whose line search
        stagnates gets the status "stagnated".
    domain : callable, optional
        ``domain(x) -> ndarray of bool (batch,)``, whether each iterate lies where the equations
        are meant to be solved. A step that leaves it is shortened (with damping) or ends its
        system with the status "left-domain"; ``fun`` is never called on a point outside it
        (only the starts ``x0`` are the caller's to choose inside).
    raise_on_failure : bool, optional
        Raise (as below) if some system does not converge; with False, return the result and
        let the caller read ``status``.
    independent : bool, optional
        Declare that ``fun``, ``jac`` and ``domain`` do not depend on the position in the batch
        (one system from many starts, as in :func:`solve_all`): then they are called on the
        rows that need them only, and the backtracking step lengths of all the systems that
        refuse a full step are tried in one call, so that a few slow systems do not cost a
        whole batch per halving.
    halvings : int, optional
        With damping, the most halvings of a step before the system is "stagnated" (or
        "left-domain").

    Returns
    -------
    BatchNewtonResult

    Raises
    ------
    ValueError
        As in :func:`solve`.
    SingularJacobianError
        If the Jacobian of some system is singular at one of its iterates (and
        ``raise_on_failure``); ``result`` holds the :class:`BatchNewtonResult`.
    ConvergenceError
        If some other system fails to converge (and ``raise_on_failure``); ``result`` holds the
        :class:`BatchNewtonResult`, whose ``status`` tells which and why.

    Examples
    --------
    >>> import numpy as np
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
    x = _validate.array(x0, "x0", ndim=2)
    if x.shape[1] == 0:
        raise ValueError(f"x0 must have shape (batch, n) with n >= 1, got shape {x.shape}")
    tol, maxiter, criterion, norm = _controls(tol, maxiter, criterion, norm)
    max_step = None if max_step is None else _validate.tolerance(max_step, "max_step")
    halvings = _validate.maxiter(halvings, "halvings")
    batch = len(x)
    iterations = np.zeros(batch, dtype=int)
    status = np.full(batch, "", dtype="<U11")  # "" while a system is running
    running = np.ones(batch, dtype=bool)  # status == "", kept up to date (cheaper to test)

    def call(points, rows):  # the residual at points, at least of the systems rows
        if not independent:
            return _evaluate(fun, points, "fun")
        out = np.full(points.shape, np.nan)
        if rows.any():
            out[rows] = _evaluate(fun, points[rows], "fun")
        return out

    def stop(which, why):  # end the systems ``which`` (a mask) with the status ``why``
        if which.any():
            status[which] = why
            running[which] = False

    steps = []
    fx, nfev, njev = _evaluate(fun, x, "fun"), 1, 0
    rnorm = _norms(fx, norm)
    for k in range(maxiter + 1):
        stop(running & ~np.isfinite(rnorm), "non-finite")
        met = rnorm < tol if criterion == "residual" else (steps[-1] < tol if steps else False)
        stop(running & met, "converged")
        active = running.copy()
        if not active.any() or k == maxiter:
            break
        subset = independent and not active.all()  # then jac is called on the active rows only
        J = _jacobian(jac, fun, x[active] if subset else x)
        nfev, njev = (nfev + x.shape[1], njev) if jac is None else (nfev, njev + 1)
        if active.all():  # the usual case: no copies of J and f
            dx, stuck, _ = _newton_step(J, fx)
        else:
            dx = np.zeros_like(x)
            dx[active], stuck, _ = _newton_step(J if subset else J[active], fx[active])
        if stuck.any():
            singular = active.copy()
            singular[active] = stuck
            stop(singular, "singular")
        dx = _bounded(dx, max_step)
        if damping:
            x_new, fx_new, failed, calls = _line_search(call, x, fx, dx, running, rnorm, tol,
                                                        norm, domain, independent, halvings)
            stop(failed != "", failed[failed != ""])
            nfev += calls
        else:
            x_new = x + dx  # dx is zero for the systems that are not moving
            if domain is not None:  # a step out of the domain is not taken, nor evaluated
                outside = running & ~np.asarray(domain(x_new), bool)
                stop(outside, "left-domain")
                x_new[outside] = x[outside]
            fx_new, nfev = call(x_new, running), nfev + 1
        iterations += running
        size = _norms(x_new - x, norm)
        if running.all():
            steps.append(size)
            x, fx = x_new, fx_new
        else:
            steps.append(np.where(running, size, np.nan))
            x = np.where(running[:, None], x_new, x)
            fx = np.where(running[:, None], fx_new, fx)
        rnorm = _norms(fx, norm)
    stop(running, "maxiter")
    result = BatchNewtonResult(x, iterations, status, np.array(steps).reshape(len(steps), batch), rnorm,
                               nfev, njev)
    if raise_on_failure:
        _raise_for(result, criterion, tol, maxiter)
    return result


def _raise_for(result, criterion, tol, maxiter):
    """Raise the error that the worst status of a batch calls for, if any system failed."""
    if result.converged.all():
        return
    singular = np.flatnonzero(result.singular)
    if singular.size:
        raise SingularJacobianError(
            f"singular Jacobian in {singular.size} of {len(result.x)} systems "
            f"(first: {singular[:10].tolist()}); the others went on", result)
    bad = np.flatnonzero(~result.converged)
    if bad.size:
        kinds = {s: int(np.sum(result.status == s)) for s in STATUSES[1:]
                 if np.any(result.status == s)}
        raise ConvergenceError(
            f"Newton did not converge for {bad.size} of {len(result.x)} systems in {maxiter} "
            f"iterations (first: {bad[:10].tolist()}; {kinds}; largest residual norm "
            f"{np.nanmax(np.where(result.converged, np.nan, result.residual_norms)):.3g}, "
            f"criterion {criterion!r}, tol {tol:g})", result)


def _distinct(points, same):
    """Group the rows of ``points`` that lie within ``same`` (inf-norm) of a group's first row.

    Returns the representatives and, for every row, the index of its group (one pass over
    the groups, each comparing all the rows at once)."""
    label = np.full(len(points), -1)
    reps = []
    while (free := np.flatnonzero(label < 0)).size:
        rep = points[free[0]]
        near = free[np.max(np.abs(points[free] - rep), axis=1) <= same]
        label[near] = len(reps)
        reps.append(rep)
    return np.array(reps).reshape(-1, points.shape[1]), label


def solve_all(fun, sample, jac=None, *, n_starts=1000, check=10, rng=None, starts=None,
              tol=1e-12, maxiter=50, domain=None, same=1e-8, halvings=_SEARCH_HALVINGS):
    """Every root that damped Newton finds from many starts, deduplicated, with evidence.

    The search runs :func:`solve_batch` (damped, with the status of each start) from
    ``n_starts`` starts drawn by ``sample`` (plus any given ``starts``); starts that stagnate,
    leave the ``domain`` or hit a singular Jacobian are dropped. The converged ends are grouped
    into distinct roots (those within ``same`` of each other) and counted. Then a completeness
    check runs ``check * n_starts`` new starts: the number of roots that only it finds,
    ``new_in_check``, is zero when the search looks complete.

    Parameters
    ----------
    fun : callable
        The batched residual, ``fun(x) -> (batch, n)`` for ``x`` of shape ``(batch, n)``.
    sample : callable
        ``sample(rng, m) -> ndarray (m, n)``: ``m`` random starts.
    jac : callable, optional
        The batched Jacobian, ``(batch, n, n)``; default :func:`fd_jacobian`.
    n_starts : int, optional
        Random starts of the search (``>= 1``).
    check : int, optional
        The completeness check uses ``check * n_starts`` starts; 0 skips it.
    rng : numpy.random.Generator or int, optional
        The random generator (or its seed): no hidden randomness.
    starts : array_like, shape (m, n), optional
        Starts added to the search (continuation seeds, starts aimed at small basins).
    tol, maxiter, domain
        As in :func:`solve_batch` (``criterion="step"``); ``fun``, ``jac`` and ``domain`` must
        not depend on the position in the batch (``independent=True``).
    same : float, optional
        Two converged points closer than this (largest component) are one root.
    halvings : int, optional
        Most halvings of a Newton step (4: ``alpha >= 1/16``); a start that needs more is
        dropped, as "stagnated" or "left-domain" (see the module's constants).

    Returns
    -------
    RootSet

    Examples
    --------
    The circle ``x**2 + y**2 = 4`` meets the hyperbola ``x y = 1`` in four points:

    >>> import numpy as np
    >>> fun = lambda z: np.stack([z[:, 0]**2 + z[:, 1]**2 - 4, z[:, 0] * z[:, 1] - 1], axis=-1)
    >>> jac = lambda z: np.stack([np.stack([2 * z[:, 0], 2 * z[:, 1]], -1),
    ...                           np.stack([z[:, 1], z[:, 0]], -1)], axis=1)
    >>> found = solve_all(fun, lambda rng, m: rng.uniform(-3, 3, (m, 2)), jac, n_starts=200, rng=0)
    >>> found.roots.round(6).tolist(), found.complete
    ([[-1.931852, -0.517638], [-0.517638, -1.931852], [0.517638, 1.931852], [1.931852, 0.517638]], True)
    """
    rng = np.random.default_rng(rng)
    n_starts = _validate.maxiter(n_starts, "n_starts")
    check = _validate.maxiter(check, "check", minimum=0)
    same = _validate.tolerance(same, "same")
    runs = []
    for m, extra in ((n_starts, starts), (check * n_starts, None)):
        x0 = np.asarray(sample(rng, m), dtype=float) if m else np.empty((0, 0))
        if extra is not None:
            x0 = np.concatenate([_validate.array(extra, "starts", ndim=2), x0])
        if len(x0):
            runs.append(solve_batch(fun, x0, jac, tol=tol, maxiter=maxiter, damping=True,
                                    domain=domain, raise_on_failure=False, independent=True,
                                    halvings=halvings))
    ends = [r.x[r.converged] for r in runs]
    width = runs[0].x.shape[1]
    roots, label = _distinct(np.concatenate(ends).reshape(-1, width), same)
    first = len(np.unique(label[:len(ends[0])]))
    order = np.lexsort(roots.T[::-1]) if len(roots) else np.arange(0)
    hits = np.bincount(label, minlength=len(roots))
    statuses = np.concatenate([r.status for r in runs])
    return RootSet(roots[order], hits[order], np.linalg.norm(fun(roots[order]), axis=-1)
                   if len(roots) else np.empty(0), n_starts, check * n_starts,
                   len(roots) - first, {s: int(np.sum(statuses == s)) for s in STATUSES})


@dataclass(frozen=True)
class PathResult:
    """The outcome of :func:`solve_path`.

    Attributes
    ----------
    x : ndarray, shape (steps, batch, n) (or (steps, n) for one path)
        The solution at every step, NaN where Newton did not converge.
    converged : ndarray of bool, shape (steps, batch) (or (steps,))
        Which steps converged.
    iterations : ndarray of int, same shape as ``converged``
        Newton steps taken at every step.
    """

    x: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray


def solve_path(fun, params, x0, jac=None, *, tol=1e-12, maxiter=10, domain=None,
               halvings=_SEARCH_HALVINGS, criterion="residual", resume=True):
    """Follow solutions of ``fun(x, p) = 0`` along a sequence of parameters, by continuation.

    Step ``i`` solves ``fun(x, params[i]) = 0`` by damped Newton (:func:`solve_batch`) from a
    secant prediction, ``x_{i-1} + c (x_{i-1} - x_{i-2})`` with ``c`` the projection of the
    parameter step ``p_i - p_{i-1}`` on the last one (1 on a uniform straight path, 0 where
    the path turns a right angle; ``x_{i-1}`` itself after a failure or at the first steps),
    so each solution stays on the branch of the one before; small parameter steps keep it
    there. Many paths may be followed at once (a batch); each may fail on its own.

    Parameters
    ----------
    fun : callable
        ``fun(x, p) -> (m, n)`` for ``x`` of shape ``(m, n)`` and ``p`` of shape ``(m, ...)``:
        the rows of ``x`` and their parameters.
    params : array_like, shape (steps, ...) or (steps, batch, ...)
        The parameters of every step: for one path (``x0`` of shape ``(n,)``), or for each
        of ``batch`` paths.
    x0 : array_like, shape (n,) or (batch, n)
        A solution at (or a start close to) ``params[0]``.
    jac : callable, optional
        ``jac(x, p) -> (m, n, n)``; default forward differences.
    tol, maxiter, criterion : optional
        Newton's tolerance, most iterations per step (from a good prediction Newton needs a
        few; a step that needs more has likely lost the branch) and stopping criterion (the
        residual: no last step spent confirming a converged one).
    domain : callable, optional
        ``domain(x) -> (m,) bool``, as in :func:`solve_batch`.
    halvings : int, optional
        Most halvings of a Newton step, as in :func:`solve_all`.
    resume : bool, optional
        After a step that fails, go on from the last converged solution (the study's
        trajectories do so), or abandon the path (``False``: the rest of it is NaN).

    Returns
    -------
    PathResult

    Examples
    --------
    The positive root of ``x**2 = p`` as ``p`` goes from 1 to 4:

    >>> p = np.linspace(1.0, 4.0, 7)
    >>> path = solve_path(lambda x, c: x ** 2 - c[:, None], p, [1.0],
    ...                   lambda x, c: 2 * x[:, :, None])
    >>> bool(np.allclose(path.x[:, 0], np.sqrt(p))), bool(path.converged.all())
    (True, True)
    """
    params = np.asarray(params)
    x = _validate.array(x0, "x0", ndim=(1, 2))
    single = x.ndim == 1
    if single:
        x, params = x[None], params[:, None]
    if params.ndim < 2 or params.shape[1] != len(x):
        raise ValueError(f"params must have shape (steps, {len(x)}, ...) for {len(x)} paths, "
                         f"got {params.shape}")
    steps = len(params)
    out = np.full((steps,) + x.shape, np.nan)
    converged = np.zeros((steps, len(x)), dtype=bool)
    iterations = np.zeros((steps, len(x)), dtype=int)
    last, before = x.copy(), x.copy()
    last_p, before_p = params[0].astype(float), params[0].astype(float)
    streak = np.zeros(len(x), dtype=int)    # converged steps in a row, up to the last one
    alive = np.ones(len(x), dtype=bool)
    for i, p in enumerate(params):
        rows = np.flatnonzero(alive)
        if not rows.size:
            break
        # secant prediction, scaled by the projection of this parameter step on the last one
        step = (p - params[i - 1]).reshape(len(x), -1) if i else np.zeros((len(x), 1))
        previous = (last_p - before_p).reshape(len(x), -1)
        length = np.sum(previous ** 2, axis=1)
        scale = np.divide(np.sum(step * previous, axis=1), length, out=np.zeros(len(x)),
                          where=(streak >= 2) & (length > 0))
        start = (last + scale[:, None] * (last - before))[rows]
        if domain is not None:    # a prediction out of the domain falls back on the last point
            start = np.where(np.asarray(domain(start), bool)[:, None], start, last[rows])
        res = solve_batch(lambda z, p=p[rows]: fun(z, p), start,
                          None if jac is None else (lambda z, p=p[rows]: jac(z, p)), tol=tol,
                          maxiter=maxiter, criterion=criterion, damping=True, domain=domain,
                          raise_on_failure=False, halvings=halvings)
        ok = np.zeros(len(x), dtype=bool)
        ok[rows] = res.converged
        out[i, rows[res.converged]] = res.x[res.converged]
        converged[i], iterations[i, rows] = ok, res.iterations
        before = np.where(ok[:, None], last, before)
        before_p = np.where(ok.reshape((-1,) + (1,) * (p.ndim - 1)), last_p, before_p)
        last[rows[res.converged]] = res.x[res.converged]
        last_p = np.where(ok.reshape((-1,) + (1,) * (p.ndim - 1)), p, last_p)
        streak = np.where(ok, streak + 1, 0)
        if not resume:
            alive &= ok
    if single:
        return PathResult(out[:, 0], converged[:, 0], iterations[:, 0])
    return PathResult(out, converged, iterations)
