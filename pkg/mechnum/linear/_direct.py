"""Direct least squares, and a low-precision factorisation refined in double precision.

:func:`~mechnum.linear.least_squares` solves ``min ||A x - b||_2`` by Householder QR, the SVD,
or the normal equations (by Cholesky, by LU with partial pivoting, or iteratively), and reports
the numerical rank. :func:`~mechnum.linear.iterative_refinement` solves a square system with an
LU factorisation in single precision, corrected by residuals computed in double precision.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import cho_factor, cho_solve, lu_factor, lu_solve, qr, solve_triangular

from mechnum import _validate
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.linear._checks import SUBNORMAL_FLOOR, _check_system, _dense, condition_number
from mechnum.linear._krylov import conjugate_gradient
from mechnum.linear._stationary import IterationResult, gauss_seidel, jacobi, sor
from mechnum.linear._sweeps import METHODS
from mechnum.results import Result, StoppingRule

LEAST_SQUARES_METHODS = ("qr", "svd", "cholesky", "lu") + METHODS + ("cg",)
#: Iterative refinement gives up when a correction is not at least this much smaller than the
#: one before: the low-precision factorisation no longer contracts the error.
REFINEMENT_CONTRACTION = 0.5


@dataclass(frozen=True, kw_only=True)
class LeastSquares(Result):
    """The outcome of :func:`least_squares`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The solution (of minimum norm, for ``method="svd"`` on a rank-deficient ``A``).
    status : str
        ``"converged"``: a direct method's solution, or the iterative solver's (which raises
        when it does not converge).
    message : str
        The method and the rank.
    iterations, nfev, njev : int
        The iterative solver's (zero for a direct method).
    residuals : ndarray, shape (m,)
        ``A x - b``.
    rank : int
        The numerical rank of ``A`` (singular values above ``max(m, n) eps sigma_1``).
    singular_values : ndarray, shape (min(m, n),)
    solver : IterationResult or None
        The iterative solver's result, for the iterative methods.
    """

    residuals: np.ndarray
    rank: int
    singular_values: np.ndarray
    solver: IterationResult | None


def least_squares(A: ArrayLike, b: ArrayLike, method: str = "qr", omega: float | None = None,
                  **solver_options: object) -> "LeastSquares":
    """The least-squares solution of ``A x ~= b``: ``min ||A x - b||_2``.

    Parameters
    ----------
    A : array_like, shape (m, n)
        Dense, ``m >= n``.
    b : array_like, shape (m,)
    method : str, optional
        ``"qr"``: Householder QR, ``R x = Q^T b`` (backward stable: the error grows like
        ``kappa(A)``, plus ``kappa(A)^2`` times the relative residual); ``"svd"``: the
        pseudo-inverse, the minimum-norm solution when ``A`` is rank-deficient; the normal
        equations ``A^T A x = A^T b`` (their error grows like ``kappa(A)^2``) by
        ``"cholesky"``, by ``"lu"`` (partial pivoting), or iteratively by ``"jacobi"``,
        ``"gauss_seidel"``, ``"sor"`` (with ``omega``) or ``"cg"``.
    omega : float, optional
        The SOR relaxation factor (``method="sor"`` only, where it is required).
    **solver_options
        Passed to the iterative solver (``tol``, ``maxiter``, ...).

    Returns
    -------
    LeastSquares

    Raises
    ------
    ValueError
        Ill-shaped or non-finite input, ``m < n``, unknown method, options for a direct one.
    SingularJacobianError
        ``A`` has rank below ``n`` (every method but ``"svd"``): ``x`` is not unique.
    RelaxationFactorError
        ``method="sor"`` without a valid ``omega``.
    ConvergenceError
        An iterative method did not converge.

    Examples
    --------
    >>> A, b = [[1.0, 0.0], [1.0, 1.0], [1.0, 2.0]], [1.0, 2.0, 4.0]
    >>> least_squares(A, b).x.round(10).tolist()    # the line 5/6 + 3/2 t
    [0.8333333333, 1.5]
    """
    _validate.choice(method, LEAST_SQUARES_METHODS, "method")
    A = _dense(A, "least_squares", square=False)
    m, n = A.shape
    if m < n:
        raise ValueError(f"least squares needs at least as many rows as columns, got {A.shape}")
    b = _validate.array(b, "b", shape=(m,))
    if method != "sor" and omega is not None:
        raise ValueError(f"omega is an option of method 'sor', not of {method!r}")
    if method in ("qr", "svd", "cholesky", "lu") and solver_options:
        raise ValueError(f"method {method!r} is direct, it takes no {sorted(solver_options)}")
    U, s, Vt = np.linalg.svd(A, full_matrices=False)
    rank = int(np.sum(s > s[0] * max(m, n) * np.finfo(float).eps)) if s[0] > 0 else 0
    if rank < n and method != "svd":
        raise SingularJacobianError(
            f"A has rank {rank} < {n} (singular values {np.array2string(s, precision=3)}): "
            f"the least-squares solution is not unique; method='svd' gives the minimum-norm one")
    solver = None
    if method == "qr":
        Q, R = qr(A, mode="economic")  # LAPACK geqrf: Householder reflections
        x = solve_triangular(R, Q.T @ b)
    elif method == "svd":
        x = Vt[:rank].T @ ((U[:, :rank].T @ b) / s[:rank])
    elif method == "cholesky":
        x = cho_solve(cho_factor(A.T @ A), A.T @ b)
    elif method == "lu":
        x = lu_solve(lu_factor(A.T @ A), A.T @ b)
    elif method == "cg":
        solver = conjugate_gradient(A.T @ A, A.T @ b, **solver_options)
    elif method == "sor":
        solver = sor(A.T @ A, A.T @ b, omega, **solver_options)
    else:
        solver = (jacobi if method == "jacobi" else gauss_seidel)(A.T @ A, A.T @ b,
                                                                   **solver_options)
    x = solver.x if solver is not None else x
    return LeastSquares(x=x, status="converged",
                        message=f"least squares by {method}, rank {rank} of {n}",
                        iterations=0 if solver is None else solver.iterations,
                        nfev=0 if solver is None else solver.nfev, njev=0,
                        residuals=A @ x - b, rank=rank, singular_values=s, solver=solver)


#: Default tolerance of :func:`iterative_refinement`, relative: nine digits, reached from a
#: float32 factorisation in two or three steps when ``cond(A) < 1e5``.
REFINEMENT_TOL = 1e-9
#: The most refinement steps: each gains ``-log10(cond(A) eps32)`` digits, so a refinement that
#: needs more than a hundred has stopped contracting.
REFINEMENT_MAXITER = 100


def iterative_refinement(A: ArrayLike, b: ArrayLike, *, factor_dtype: type = np.float32,
                         tol: float = REFINEMENT_TOL, maxiter: int = 20) -> IterationResult:
    """Solve ``A x = b`` by an LU factorisation in low precision refined in double precision.

    Each step computes the residual ``r = b - A x`` in double precision, solves ``A d = r``
    with the cheap factorisation and sets ``x <- x + d``. ``A`` is scaled by a power of two and
    each right-hand side by its largest entry before the low-precision solve, so neither
    underflows nor overflows there. It converges to double-precision accuracy when
    ``cond(A) * eps(factor_dtype) < 1``.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense.
    b : array_like, shape (n,)
    factor_dtype : {numpy.float32, numpy.float64}, optional
        Precision of the factorisation.
    tol : float, optional
        Stop when ``||d||_inf <= tol ||x||_inf``; it cannot usefully be below ``cond(A) * eps``.
    maxiter : int, optional
        Most refinement steps, from 1 to :data:`REFINEMENT_MAXITER`.

    Returns
    -------
    IterationResult
        ``history`` holds the first solve and every refined iterate, ``step_norms`` the
        corrections.

    Raises
    ------
    ValueError, SingularJacobianError
        As in :func:`sor`.
    ConvergenceError
        If the corrections stop contracting (by
        ``REFINEMENT_CONTRACTION``, 0.5) before ``tol`` is met
        (``cond(A) * eps(factor_dtype)`` too large) or ``maxiter`` is hit.

    Examples
    --------
    >>> res = iterative_refinement([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0])
    >>> res.x.round(12).tolist(), res.converged
    ([0.090909090909, 0.636363636364], True)
    """
    A, b = _check_system(_dense(A, "iterative_refinement"), b)
    if np.dtype(factor_dtype) not in (np.float32, np.float64):
        raise ValueError(f"factor_dtype must be float32 or float64, got {factor_dtype!r}")
    rule = StoppingRule.checked(tol, maxiter, maxiter_limit=REFINEMENT_MAXITER)
    scale = 2.0 ** np.round(np.log2(np.abs(A).max()))  # exact: only the exponent changes
    lu = lu_factor((A / scale).astype(factor_dtype))

    def solve(r):
        size = np.abs(r).max()
        if size == 0:
            return np.zeros_like(r)
        return size / scale * lu_solve(lu, (r / size).astype(factor_dtype)).astype(float)

    x = solve(b)
    history, residuals, steps = [x], [np.linalg.norm(b - A @ x, np.inf)], []
    status = "maxiter"
    while len(steps) < rule.maxiter:
        d = solve(b - A @ x)
        x = x + d
        history.append(x)
        residuals.append(np.linalg.norm(b - A @ x, np.inf))
        steps.append(np.linalg.norm(d, np.inf))
        # a correction of a unit or two of the smallest subnormal is round-off, whatever x
        if steps[-1] <= max(rule.tol * np.linalg.norm(x, np.inf), SUBNORMAL_FLOOR):
            status = "converged"
            break
        if not (len(steps) < 2 or steps[-1] <= REFINEMENT_CONTRACTION * steps[-2]):
            status = "stagnated" if np.isfinite(steps[-1]) else "non-finite"
            break
    k = len(steps)
    message = (f"iterative refinement converged in {k} steps" if status == "converged" else
               f"iterative refinement stalled after {k} steps ({status}): correction "
               f"{steps[-1]:.3g}, 1-norm condition number {condition_number(A, 1):.3g}")
    result = IterationResult(x=x, status=status, message=message, iterations=k,
                             nfev=2 * k + 1, njev=0, history=np.array(history),
                             residual_norms=np.array(residuals), step_norms=np.array(steps))
    if status != "converged":
        raise ConvergenceError(message, result)
    return result
