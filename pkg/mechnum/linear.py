"""Linear systems: stationary iterations, their convergence, conditioning and refinement.

Write ``A = D - L - U`` with ``D`` the diagonal of ``A`` and ``-L``, ``-U`` its strictly lower
and upper parts. A stationary method splits ``A = P - N`` and iterates

    ``x_{k+1} = M x_k + P^{-1} b``,   ``M = P^{-1} N``,

which converges for every ``x_0`` if and only if the spectral radius ``rho(M) < 1``:

* Jacobi: ``P = D``;
* Gauss-Seidel: ``P = D - L``;
* SOR with relaxation factor ``omega``: ``P = D / omega - L`` (Gauss-Seidel for ``omega = 1``).

The iteration is carried out in this matrix form (two triangular solves once, one
matrix-vector product per sweep), which is the component-by-component sweep of the textbooks
written with numpy. The stopping criterion is explicit, because iteration counts depend on it:

* ``criterion="step"``: stop when ``||x_{k+1} - x_k|| < tol`` (times ``||x_{k+1}||`` if
  ``relative``), the rule of Burden and Faires' algorithms 7.1 to 7.3 with ``norm=inf``;
* ``criterion="residual"``: stop when ``||b - A x_k|| < tol`` (times ``||b||`` if ``relative``).

An iteration whose residual grows beyond ``1e8`` times its initial value, or overflows, is
reported as diverging (:class:`~mechnum.errors.DivergenceError`) instead of being looped on.
"""

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, lu_solve, solve_triangular
from scipy.optimize import minimize_scalar

from mechnum.errors import (ConvergenceError, DivergenceError, RelaxationFactorError,
                            SingularJacobianError)

_METHODS = ("jacobi", "gauss_seidel", "sor")
_CRITERIA = ("step", "residual")
_GROWTH = 1e8


@dataclass(frozen=True)
class IterationResult:
    """The outcome of an iterative linear solver.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The last iterate.
    iterations : int
        Sweeps (or refinement steps) taken.
    converged : bool
        Whether the stopping criterion was met.
    history : ndarray, shape (iterations + 1, n)
        Every iterate, the initial guess first.
    residual_norms : ndarray, shape (iterations + 1,)
        ``||b - A x_k||`` for every iterate, in the norm of the criterion.
    """

    x: np.ndarray
    iterations: int
    converged: bool
    history: np.ndarray
    residual_norms: np.ndarray


@dataclass(frozen=True)
class OptimalOmega:
    """The outcome of :func:`optimal_omega`.

    Attributes
    ----------
    omega : float
        The relaxation factor minimising the spectral radius of the SOR iteration matrix.
    spectral_radius : float
        That minimal spectral radius.
    how : str
        ``"young"`` (the classical formula ``2 / (1 + sqrt(1 - rho_J^2))``) or
        ``"numerical"`` (a minimisation of ``rho(M_SOR(omega))`` over ``(0, 2)``).
    """

    omega: float
    spectral_radius: float
    how: str


def check_matrix(A, square=True):
    """Return ``A`` as a finite float matrix, or raise :class:`ValueError` naming the problem.

    Parameters
    ----------
    A : array_like, shape (n, n), or (m, n) if not ``square``
        The matrix.
    square : bool, optional
        Whether ``A`` must be square.

    Returns
    -------
    ndarray

    Examples
    --------
    >>> check_matrix([[1, 2], [3, 4]]).dtype
    dtype('float64')
    """
    A = np.array(A, dtype=float)
    if A.ndim != 2 or A.size == 0 or (square and A.shape[0] != A.shape[1]):
        kind = "square matrix" if square else "matrix"
        raise ValueError(f"A must be a non-empty {kind}, got shape {A.shape}")
    if not np.all(np.isfinite(A)):
        raise ValueError("A must be finite, it holds NaN or inf")
    return A


def _check_system(A, b):
    A = check_matrix(A)
    b = np.array(b, dtype=float)
    if b.shape != A.shape[:1]:
        raise ValueError(f"b must have shape {A.shape[:1]}, got shape {b.shape}")
    if not np.all(np.isfinite(b)):
        raise ValueError("b must be finite, it holds NaN or inf")
    cond = condition_number(A, 1)
    if cond * np.finfo(float).eps > 1:
        raise SingularJacobianError(
            f"A is singular to working precision (1-norm condition number {cond:.3g})")
    return A, b


def _splitting(A, method, omega):
    """``(P, N)`` with ``A = P - N`` for the method; ``P`` is diagonal or lower triangular."""
    if method not in _METHODS:
        raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
    if method != "sor":
        omega = 1.0
    elif not (np.isfinite(omega) and 0 < omega < 2):
        raise RelaxationFactorError(
            f"SOR relaxation factor omega must lie in (0, 2), got {omega!r}: "
            f"rho(M_SOR) >= |omega - 1| >= 1 outside it")
    zero = np.flatnonzero(np.diag(A) == 0)
    if zero.size:
        raise SingularJacobianError(
            f"zero diagonal entries A[i, i] for i in {zero.tolist()}: the splitting matrix is "
            f"singular (reorder the equations)")
    D = np.diag(np.diag(A))
    P = D if method == "jacobi" else np.tril(A, -1) + D / omega
    return P, P - A


def iteration_matrix(A, method, omega=1.0):
    """The iteration matrix ``M = P^{-1} N`` of Jacobi, Gauss-Seidel or SOR.

    Parameters
    ----------
    A : array_like, shape (n, n)
        The system matrix; finite, with a non-zero diagonal.
    method : {"jacobi", "gauss_seidel", "sor"}
        The splitting.
    omega : float, optional
        The SOR relaxation factor, in ``(0, 2)`` (ignored by the other methods).

    Returns
    -------
    ndarray, shape (n, n)

    Raises
    ------
    ValueError
        If ``A`` is not a finite square matrix or ``method`` is unknown.
    SingularJacobianError
        If ``A`` has a zero diagonal entry.
    RelaxationFactorError
        If ``omega`` is outside ``(0, 2)`` for SOR.

    Examples
    --------
    >>> iteration_matrix([[2.0, -1.0], [-1.0, 2.0]], "jacobi")
    array([[0. , 0.5],
           [0.5, 0. ]])
    """
    A = check_matrix(A)
    P, N = _splitting(A, method, omega)
    return solve_triangular(P, N, lower=True)


def spectral_radius(M):
    """The largest modulus of the eigenvalues of a square matrix.

    Parameters
    ----------
    M : array_like, shape (n, n)

    Returns
    -------
    float

    Examples
    --------
    >>> round(spectral_radius([[0.0, 2.0], [-0.5, 0.0]]), 12)   # eigenvalues +-i
    1.0
    """
    return float(np.max(np.abs(np.linalg.eigvals(check_matrix(M)))))


def condition_number(A, p=2):
    """The condition number ``||A|| ||A^+||`` in the norm ``p``.

    Parameters
    ----------
    A : array_like, shape (n, n), or (m, n) for ``p=2``
        The matrix; for ``p=2`` a rectangular one is allowed (ratio of extreme singular values).
    p : {1, 2, inf, "fro"}, optional
        The norm.

    Returns
    -------
    float
        ``inf`` for a singular matrix.

    Examples
    --------
    >>> round(condition_number([[1.0, 0.0], [0.0, 1e-3]], np.inf), 9)
    1000.0
    """
    if p not in (1, 2, np.inf, "fro"):
        raise ValueError(f"p must be 1, 2, inf or 'fro', got {p!r}")
    A = check_matrix(A, square=p != 2)
    if p == 2:
        s = np.linalg.svd(A, compute_uv=False)
        return float(s[0] / s[-1]) if s[-1] > 0 else np.inf
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        return np.inf
    return float(np.linalg.norm(A, p) * np.linalg.norm(inv, p))


def _check_controls(x0, n, tol, maxiter, criterion):
    x = np.zeros(n) if x0 is None else np.array(x0, dtype=float)
    if x.shape != (n,) or not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be a finite vector of shape {(n,)}, got {x0!r}")
    if criterion not in _CRITERIA:
        raise ValueError(f"criterion must be one of {_CRITERIA}, got {criterion!r}")
    if not tol > 0:
        raise ValueError(f"tol must be positive, got {tol!r}")
    if int(maxiter) != maxiter or maxiter < 1:
        raise ValueError(f"maxiter must be a positive integer, got {maxiter!r}")
    return x


def _norms(v, norm):
    """Vector norms along the last axis (the inf-norm without the overhead of ``linalg.norm``)."""
    return np.abs(v).max(axis=-1) if norm == np.inf else np.linalg.norm(v, norm, axis=-1)


def _iterate(M, c, A, b, x, tol, maxiter, criterion, norm, relative, keep_history):
    """Run ``k`` stationary iterations ``x <- M[j] x + c[j]`` at once (arrays ``(k, n, n)``,
    ``(k, n)``); each stops when it meets the criterion or diverges, the others go on.

    Returns ``x, iterations, converged, diverged, history, residual_norms`` (the last two are
    lists of ``(k, n)`` and ``(k,)`` arrays, kept only if ``keep_history``, for ``k = 1``).
    """
    bnorm = np.linalg.norm(b, norm)
    limit = tol * bnorm if relative and criterion == "residual" else tol
    residual = _norms(b - x @ A.T, norm)
    blow_up = _GROWTH * np.maximum(np.maximum(residual, bnorm), np.finfo(float).tiny)
    k = x.shape[0]
    x_out, iterations = x.copy(), np.zeros(k, dtype=int)
    converged, diverged = np.zeros(k, bool), np.zeros(k, bool)
    live = np.arange(k)  # the iterations still running; M, c, x, blow_up hold only those
    history, residuals = [x], [residual]
    with np.errstate(over="ignore", invalid="ignore"):
        for sweep in range(1, maxiter + 1):
            x_new = (M @ x[:, :, None])[:, :, 0] + c
            residual = _norms(b - x_new @ A.T, norm)
            if criterion == "step":
                size = _norms(x_new - x, norm)
                done = size < tol * (_norms(x_new, norm) if relative else 1.0)
            else:
                done = residual < limit
            bad = ~np.isfinite(residual) | (residual > blow_up)
            x = x_new
            if keep_history:
                history.append(x)
                residuals.append(residual)
            stop = done | bad
            if stop.any():
                ended = live[stop]
                x_out[ended], iterations[ended] = x[stop], sweep
                converged[ended], diverged[ended] = done[stop], bad[stop] & ~done[stop]
                keep = ~stop
                live, M, c, x, blow_up = live[keep], M[keep], c[keep], x[keep], blow_up[keep]
                if live.size == 0:
                    break
    x_out[live], iterations[live] = x, maxiter
    return x_out, iterations, converged, diverged, history, residuals


def _stationary(A, b, method, omega, x0, tol, maxiter, criterion, norm, relative):
    A, b = _check_system(A, b)
    x = _check_controls(x0, A.shape[0], tol, maxiter, criterion)
    P, N = _splitting(A, method, omega)
    M = solve_triangular(P, N, lower=True)
    c = solve_triangular(P, b, lower=True)
    x, iterations, converged, diverged, history, residuals = _iterate(
        M[None], c[None], A, b, x[None], tol, maxiter, criterion, norm, relative, True)
    residuals = np.array(residuals)[:, 0]
    result = IterationResult(x[0], int(iterations[0]), bool(converged[0]),
                             np.array(history)[:, 0], residuals)
    name = method if method != "sor" else f"SOR (omega={omega:g})"
    if diverged[0]:
        raise DivergenceError(
            f"{name} diverges: residual norm {residuals[-1]:.3g} after {result.iterations} "
            f"iterations, from {residuals[0]:.3g}; spectral radius of the iteration matrix "
            f"{spectral_radius(M):.4g} >= 1", result)
    if not converged[0]:
        raise ConvergenceError(
            f"{name} did not converge in {maxiter} iterations: residual norm "
            f"{residuals[-1]:.3g} (criterion {criterion!r}, tol {tol:g}); spectral radius "
            f"{spectral_radius(M):.4g}", result)
    return result


def sor(A, b, omega, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
        relative=False):
    """Solve ``A x = b`` by successive over-relaxation.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Finite, non-singular, with a non-zero diagonal.
    b : array_like, shape (n,)
    omega : float
        Relaxation factor in ``(0, 2)``: under-relaxation below 1, over-relaxation above.
    x0 : array_like, shape (n,), optional
        Initial guess (default zero).
    tol : float, optional
        Tolerance of the stopping criterion.
    maxiter : int, optional
        Most sweeps.
    criterion : {"step", "residual"}, optional
        Stop on the step ``||x_{k+1} - x_k||`` or on the residual ``||b - A x_k||``.
    norm : {inf, 1, 2}, optional
        Vector norm of the criterion and of ``residual_norms``.
    relative : bool, optional
        Divide the step by ``||x_{k+1}||`` (or the residual by ``||b||``) before comparing.

    Returns
    -------
    IterationResult

    Raises
    ------
    ValueError
        Ill-shaped or non-finite input, unknown criterion.
    SingularJacobianError
        ``A`` singular to working precision, or a zero diagonal entry.
    RelaxationFactorError
        ``omega`` outside ``(0, 2)``.
    DivergenceError
        The residual grows beyond ``1e8`` times its start, or overflows.
    ConvergenceError
        ``maxiter`` sweeps without meeting the criterion; ``result`` holds the history.

    Examples
    --------
    >>> res = sor([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], omega=1.1, tol=1e-12)
    >>> res.x.round(10).tolist(), res.converged
    ([0.0909090909, 0.6363636364], True)
    """
    return _stationary(A, b, "sor", omega, x0, tol, maxiter, criterion, norm, relative)


def gauss_seidel(A, b, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
                 relative=False):
    """Solve ``A x = b`` by Gauss-Seidel (SOR with ``omega = 1``); arguments as :func:`sor`.

    Examples
    --------
    >>> res = gauss_seidel([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    return _stationary(A, b, "gauss_seidel", 1.0, x0, tol, maxiter, criterion, norm, relative)


def jacobi(A, b, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
           relative=False):
    """Solve ``A x = b`` by Jacobi's method; arguments as :func:`sor`.

    Examples
    --------
    >>> res = jacobi([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    return _stationary(A, b, "jacobi", 1.0, x0, tol, maxiter, criterion, norm, relative)


def sor_spectral_radii(A, omegas):
    """``rho(M_SOR(omega))`` for every ``omega`` of a sweep.

    Parameters
    ----------
    A : array_like, shape (n, n)
    omegas : array_like, shape (k,)
        Relaxation factors in ``(0, 2)``.

    Returns
    -------
    ndarray, shape (k,)

    Examples
    --------
    >>> sor_spectral_radii([[2.0, -1.0], [-1.0, 2.0]], [1.0]).round(6).tolist()
    [0.25]
    """
    A = check_matrix(A)
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    M = np.stack([iteration_matrix(A, "sor", w) for w in omegas])
    return np.max(np.abs(np.linalg.eigvals(M)), axis=-1)


@dataclass(frozen=True)
class SorSweep:
    """The outcome of :func:`sor_sweep`: one entry per relaxation factor.

    Attributes
    ----------
    omegas, spectral_radii : ndarray, shape (k,)
    iterations : ndarray of int, shape (k,)
        Sweeps taken (``maxiter`` where it did not converge).
    converged : ndarray of bool, shape (k,)
    """

    omegas: np.ndarray
    spectral_radii: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray


def sor_sweep(A, b, omegas, x0=None, *, tol=1e-10, maxiter=100_000, criterion="step",
              norm=np.inf, relative=False):
    """Run SOR for many relaxation factors at once: spectral radius and iteration count.

    All the iterations advance together as one batch of arrays, each stopping on its own
    criterion (the options are those of :func:`sor`); nothing is raised for an ``omega`` that
    does not converge, its ``converged`` entry is ``False``.

    Parameters
    ----------
    A, b, x0, tol, maxiter, criterion, norm, relative
        As in :func:`sor`.
    omegas : array_like, shape (k,)
        Relaxation factors, each in ``(0, 2)``.

    Returns
    -------
    SorSweep

    Examples
    --------
    >>> A = [[4.0, 3.0, 0.0], [3.0, 4.0, -1.0], [0.0, -1.0, 4.0]]
    >>> sweep = sor_sweep(A, [24.0, 30.0, -24.0], [1.0, 1.24, 1.9], tol=1e-8)
    >>> sweep.iterations.tolist(), sweep.converged.tolist()
    ([40, 17, 200], [True, True, True])
    """
    A, b = _check_system(A, b)
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    x = _check_controls(x0, A.shape[0], tol, maxiter, criterion)
    splits = [_splitting(A, "sor", w) for w in omegas]
    M = np.stack([solve_triangular(P, N, lower=True) for P, N in splits])
    c = np.stack([solve_triangular(P, b, lower=True) for P, _ in splits])
    _, iterations, converged, _, _, _ = _iterate(
        M, c, A, b, np.tile(x, (omegas.size, 1)), tol, maxiter, criterion, norm, relative, False)
    return SorSweep(omegas, np.max(np.abs(np.linalg.eigvals(M)), axis=-1), iterations,
                    converged)


def _young_applies(A):
    """Young's formula holds for consistently ordered matrices; here: tridiagonal SPD ones."""
    tridiagonal = np.array_equal(A, np.triu(np.tril(A, 1), -1))
    if not (tridiagonal and np.allclose(A, A.T)):
        return False
    return bool(np.all(np.linalg.eigvalsh(A) > 0))


def optimal_omega(A):
    """The SOR relaxation factor of smallest spectral radius, and how it was found.

    For a symmetric positive definite tridiagonal matrix (consistently ordered, Jacobi
    eigenvalues real and below 1) Young's formula ``omega* = 2 / (1 + sqrt(1 - rho_J^2))`` is
    exact. Otherwise ``rho(M_SOR(omega))`` is minimised numerically: a 399-point grid on
    ``(0, 2)``, then a bounded scalar minimisation around the best grid point.

    Parameters
    ----------
    A : array_like, shape (n, n)

    Returns
    -------
    OptimalOmega

    Examples
    --------
    >>> A = [[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 2.0]]
    >>> best = optimal_omega(A)
    >>> round(best.omega, 6), round(best.spectral_radius, 6), best.how
    (1.171573, 0.171573, 'young')
    """
    A = check_matrix(A)
    if _young_applies(A):
        rho_j = spectral_radius(iteration_matrix(A, "jacobi"))
        omega = 2.0 / (1.0 + np.sqrt(1.0 - rho_j ** 2))
        return OptimalOmega(float(omega), float(omega - 1.0), "young")
    grid = np.linspace(0.005, 1.995, 399)
    rho = sor_spectral_radii(A, grid)
    i = int(np.argmin(rho))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    best = minimize_scalar(lambda w: sor_spectral_radii(A, [w])[0], bounds=(lo, hi),
                           method="bounded", options={"xatol": 1e-10})
    omega, value = (best.x, best.fun) if best.fun <= rho[i] else (grid[i], rho[i])
    return OptimalOmega(float(omega), float(value), "numerical")


def iterative_refinement(A, b, *, factor_dtype=np.float32, tol=1e-9, maxiter=20):
    """Solve ``A x = b`` by an LU factorisation in low precision refined in double precision.

    Each step computes the residual ``r = b - A x`` in double precision, solves
    ``A d = r`` with the cheap factorisation and sets ``x <- x + d``. It converges to double
    precision accuracy when ``cond(A) * eps(factor_dtype) < 1``.

    Parameters
    ----------
    A : array_like, shape (n, n)
    b : array_like, shape (n,)
    factor_dtype : dtype, optional
        Precision of the factorisation (``float32`` by default, ``float64`` also works).
    tol : float, optional
        Stop when ``||d||_inf <= tol ||x||_inf``; it cannot usefully be below ``cond(A) * eps``.
    maxiter : int, optional
        Most refinement steps.

    Returns
    -------
    IterationResult
        ``history`` holds the first solve and every refined iterate.

    Raises
    ------
    ValueError, SingularJacobianError
        As in :func:`sor`.
    ConvergenceError
        If the corrections stop halving before ``tol`` is met (``cond(A) * eps(factor_dtype)``
        too large) or ``maxiter`` is hit.

    Examples
    --------
    >>> res = iterative_refinement([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0])
    >>> res.x.round(12).tolist(), res.converged
    ([0.090909090909, 0.636363636364], True)
    """
    A, b = _check_system(A, b)
    lu = lu_factor(A.astype(factor_dtype))
    x = lu_solve(lu, b.astype(factor_dtype)).astype(float)
    history, residuals, steps = [x], [np.linalg.norm(b - A @ x, np.inf)], []
    converged = False
    for _ in range(maxiter):
        d = lu_solve(lu, (b - A @ x).astype(factor_dtype)).astype(float)
        x = x + d
        history.append(x)
        residuals.append(np.linalg.norm(b - A @ x, np.inf))
        steps.append(np.linalg.norm(d, np.inf))
        if steps[-1] <= tol * np.linalg.norm(x, np.inf):
            converged = True
            break
        if len(steps) > 1 and steps[-1] > 0.5 * steps[-2]:
            break
    result = IterationResult(x, len(steps), converged, np.array(history), np.array(residuals))
    if not converged:
        raise ConvergenceError(
            f"iterative refinement stalled after {len(steps)} steps: correction "
            f"{steps[-1]:.3g}, 1-norm condition number {condition_number(A, 1):.3g}", result)
    return result
