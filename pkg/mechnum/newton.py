"""Newton-Raphson for systems of nonlinear equations.

Two forms share one step rule:

* :func:`solve` solves one system ``f(x) = 0`` of ``n`` equations in ``n`` unknowns and keeps
  its whole history;
* :func:`solve_batch` solves ``batch`` independent systems of the same size at once, with
  arrays of shape ``(batch, n)``; each system stops when it converges, the others go on.

The Newton step solves ``J(x_k) dx = -f(x_k)`` and sets ``x_{k+1} = x_k + dx``. The stopping
criterion is explicit because iteration counts depend on it:

* ``criterion="step"`` stops after the first step with ``||dx|| < tol`` (the rule of most course
  codes, the hacksaw study's included; the accepted ``x`` is the one after that step);
* ``criterion="residual"`` stops as soon as ``||f(x_k)|| < tol``.

``norm`` is the ``ord`` of :func:`numpy.linalg.norm` (default 2, the Euclidean norm).

Without an analytic Jacobian, a forward-difference one is used (:func:`fd_jacobian`): column
``j`` is ``(f(x + h_j e_j) - f(x)) / h_j`` with ``h_j = sqrt(eps) * max(1, |x_j|)``, accurate to
about half the digits of ``f``, which still gives Newton a fast (no longer quadratic) rate.
"""

from dataclasses import dataclass

import numpy as np

from mechnum.errors import ConvergenceError, SingularJacobianError

_SQRT_EPS = np.sqrt(np.finfo(float).eps)
_MAX_COND = 1.0 / np.finfo(float).eps  # a condition number past which no digit is left
_TINY = np.finfo(float).tiny
_CRITERIA = ("step", "residual")


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
    """The outcome of :func:`solve_batch`.

    Attributes
    ----------
    x : ndarray, shape (batch, n)
        The last iterate of every system.
    iterations : ndarray of int, shape (batch,)
        Newton steps taken by each system.
    converged : ndarray of bool, shape (batch,)
        Whether each system met the stopping criterion.
    singular : ndarray of bool, shape (batch,)
        Which systems stopped on a singular Jacobian (frozen there, the others went on).
    step_norms : ndarray, shape (max(iterations), batch)
        ``||dx||`` of every step of every system, NaN after a system stopped.
    residual_norms : ndarray, shape (batch,)
        ``||f(x)||`` at the returned ``x``.
    """

    x: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray
    singular: np.ndarray
    step_norms: np.ndarray
    residual_norms: np.ndarray


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
    x = np.asarray(x, dtype=float)
    fx = fun(x) if fx is None else fx
    n = x.shape[-1]
    h = _SQRT_EPS * np.maximum(1.0, np.abs(x))
    jac = np.empty(x.shape[:-1] + (n, n))
    for j in range(n):
        xj = x.copy()
        xj[..., j] += h[..., j]
        jac[..., :, j] = (fun(xj) - fx) / h[..., j, None]
    return jac


def _check_inputs(x0, tol, maxiter, criterion, ndim):
    x = np.array(x0, dtype=float)
    if x.ndim != ndim or x.shape[-1] == 0:
        shape = "(n,)" if ndim == 1 else "(batch, n)"
        raise ValueError(f"x0 must have shape {shape}, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be finite, got {x0!r}")
    if criterion not in _CRITERIA:
        raise ValueError(f"criterion must be one of {_CRITERIA}, got {criterion!r}")
    if not tol > 0:
        raise ValueError(f"tol must be positive, got {tol!r}")
    if int(maxiter) != maxiter or maxiter < 1:
        raise ValueError(f"maxiter must be a positive integer, got {maxiter!r}")
    return x


def _evaluate(fun, x, what):
    """Call ``fun(x)`` and check that it returns a finite array of ``x``'s shape."""
    fx = np.asarray(fun(x), dtype=float)
    if fx.shape != x.shape:
        raise ValueError(f"{what} returned shape {fx.shape}, expected {x.shape}")
    return fx


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
    fsize = np.abs(fx).sum(axis=-1)
    growth = np.abs(jac).max(axis=(-2, -1)) * np.abs(dx).sum(axis=-1)
    trusted = growth <= _MAX_COND * fsize  # False where growth is inf or NaN
    if trusted.all() and not exact.any():
        return dx, exact, None
    singular = (exact | ~trusted) & (fsize > 0)
    cond = np.where(exact, np.inf, growth / np.maximum(fsize, _TINY))
    return np.where(singular[..., None], 0.0, dx), singular, cond


def solve(fun, x0, jac=None, *, tol=1e-10, maxiter=50, criterion="step", norm=2):
    """Solve ``fun(x) = 0`` by Newton-Raphson.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (n,)``, the residual.
    x0 : array_like, shape (n,)
        Initial guess; must be finite.
    jac : callable, optional
        ``jac(x) -> ndarray (n, n)``, the Jacobian. Default: :func:`fd_jacobian`.
    tol : float, optional
        Tolerance of the stopping criterion.
    maxiter : int, optional
        Most Newton steps.
    criterion : {"step", "residual"}, optional
        Stop on ``||dx|| < tol`` (after that step) or on ``||f(x)|| < tol``.
    norm : {2, 1, inf}, optional
        Vector norm of the criterion.

    Returns
    -------
    NewtonResult

    Raises
    ------
    ValueError
        If ``x0`` is not a finite vector, or ``fun``/``jac`` return the wrong shape.
    SingularJacobianError
        If the Jacobian is singular at an iterate; ``result`` holds the partial result.
    ConvergenceError
        If ``maxiter`` steps do not meet the criterion or an iterate stops being finite; its
        ``result`` attribute holds the partial :class:`NewtonResult`.

    Examples
    --------
    >>> import numpy as np
    >>> res = solve(lambda x: np.array([x[0] ** 2 - 2.0]), [1.0], lambda x: np.array([[2 * x[0]]]))
    >>> res.converged, res.iterations, round(float(res.x[0]), 12)
    (True, 5, 1.414213562373)
    """
    x = _check_inputs(x0, tol, maxiter, criterion, ndim=1)
    jac = jac if jac is not None else (lambda z: fd_jacobian(fun, z))
    history, residuals, steps = [x], [], []
    converged = singular = False
    while True:
        fx = _evaluate(fun, x, "fun")
        residuals.append(np.linalg.norm(fx, norm))
        if not np.isfinite(residuals[-1]) or (criterion == "step" and steps and steps[-1] < tol):
            converged = bool(np.isfinite(residuals[-1]))
            break
        if criterion == "residual" and residuals[-1] < tol:
            converged = True
            break
        if len(steps) == maxiter:
            break
        J = np.asarray(jac(x), dtype=float)
        if J.shape != x.shape * 2:
            raise ValueError(f"jac returned shape {J.shape}, expected {x.shape * 2}")
        dx, singular, cond = _newton_step(J, fx)
        if singular:
            break
        x = x + dx
        history.append(x)
        steps.append(np.linalg.norm(dx, norm))
    result = NewtonResult(x, len(steps), converged, np.array(history), np.array(residuals),
                          np.array(steps))
    if singular:
        raise SingularJacobianError(
            f"singular Jacobian at iteration {len(steps)}: condition number >= {cond:.3g}, "
            f"residual norm {residuals[-1]:.3g}", result)
    if not converged:
        raise ConvergenceError(
            f"Newton did not converge in {len(steps)} iterations: last step norm "
            f"{steps[-1] if steps else float('nan'):.3g}, residual norm {residuals[-1]:.3g} "
            f"(criterion {criterion!r}, tol {tol:g})", result)
    return result


def solve_batch(fun, x0, jac=None, *, tol=1e-10, maxiter=50, criterion="step", norm=2):
    """Solve ``batch`` independent systems ``fun(x)[b] = 0`` at once by Newton-Raphson.

    Every system takes the step of :func:`solve`; a system that meets the criterion is frozen
    while the others go on, so each has its own iteration count. ``fun`` (and ``jac``) are
    always evaluated on the whole batch, so they may depend on a per-system parameter (a time,
    a pose) by position in the batch.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> ndarray (batch, n)`` for ``x`` of shape ``(batch, n)``.
    x0 : array_like, shape (batch, n)
        Initial guesses; must be finite.
    jac : callable, optional
        ``jac(x) -> ndarray (batch, n, n)``. Default: :func:`fd_jacobian`.
    tol, maxiter, criterion, norm
        As in :func:`solve`, applied to each system.

    Returns
    -------
    BatchNewtonResult

    Raises
    ------
    ValueError
        As in :func:`solve`.
    SingularJacobianError
        If the Jacobian of any system is singular at one of its iterates; that system is frozen
        there, the others go on, and ``result`` holds the :class:`BatchNewtonResult` whose
        ``singular`` tells which.
    ConvergenceError
        If any system fails to converge in ``maxiter`` steps; ``result`` holds the partial
        :class:`BatchNewtonResult`, whose ``converged`` tells which.

    Examples
    --------
    >>> import numpy as np
    >>> c = np.array([2.0, 3.0, 4.0])
    >>> res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((3, 1)),
    ...                   lambda x: 2 * x[:, :, None])
    >>> res.x[:, 0].round(8).tolist(), res.iterations.tolist()
    ([1.41421356, 1.73205081, 2.0], [5, 6, 6])
    """
    x = _check_inputs(x0, tol, maxiter, criterion, ndim=2)
    jac = jac if jac is not None else (lambda z: fd_jacobian(fun, z))
    batch, n = x.shape
    iterations = np.zeros(batch, dtype=int)
    active = np.ones(batch, dtype=bool)
    singular = np.zeros(batch, dtype=bool)
    steps = []
    fx = _evaluate(fun, x, "fun")
    for k in range(maxiter + 1):
        rnorm = np.linalg.norm(fx, norm, axis=-1)
        done = ~np.isfinite(rnorm)
        if criterion == "residual":
            done |= rnorm < tol
        elif steps:
            done |= steps[-1] < tol
        active &= ~done
        if not active.any() or k == maxiter:
            break
        J = np.asarray(jac(x), dtype=float)
        if J.shape != (batch, n, n):
            raise ValueError(f"jac returned shape {J.shape}, expected {(batch, n, n)}")
        dx = np.zeros_like(x)
        dx[active], stuck, _ = _newton_step(J[active], fx[active])
        singular[np.flatnonzero(active)[stuck]] = True
        active &= ~singular
        x = x + dx
        iterations += active
        steps.append(np.where(active, np.linalg.norm(dx, norm, axis=-1), np.nan))
        fx = _evaluate(fun, x, "fun")
    rnorm = np.linalg.norm(fx, norm, axis=-1)
    converged = ~active & ~singular & np.isfinite(rnorm)
    result = BatchNewtonResult(x, iterations, converged, singular,
                               np.array(steps).reshape(-1, batch), rnorm)
    if singular.any():
        raise SingularJacobianError(
            f"singular Jacobian in {singular.sum()} of {batch} systems "
            f"(first: {np.flatnonzero(singular)[:10].tolist()}); the others went on", result)
    if not converged.all():
        bad = np.flatnonzero(~converged)
        raise ConvergenceError(
            f"Newton did not converge for {bad.size} of {batch} systems in {maxiter} "
            f"iterations (first: {bad[:10].tolist()}; largest residual norm "
            f"{np.nanmax(np.where(converged, np.nan, rnorm)):.3g}, criterion {criterion!r}, "
            f"tol {tol:g})", result)
    return result
