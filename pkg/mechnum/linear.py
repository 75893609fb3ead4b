"""Linear systems: least squares, stationary iterations, conjugate gradients, conditioning.

**Stationary iterations.** Write ``A = D - L - U`` with ``D`` the diagonal of ``A`` and ``-L``,
``-U`` its strictly lower and upper parts. One *sweep* of successive over-relaxation (SOR)
updates the unknowns in turn, each from the newest values of the others::

    for i in range(n):
        sigma = sum(A[i, j] * x[j] for j != i)
        x[i] = (1 - omega) * x[i] + omega * (b[i] - sigma) / A[i, i]

(:func:`sweep_by_components` is exactly this loop). Gauss-Seidel is ``omega = 1``; Jacobi uses
only the old values on the right. In matrix form a sweep is ``x <- M x + c`` with the
iteration matrix ``M = P^{-1} N`` of the splitting ``A = P - N``:

* Jacobi: ``P = D``;
* Gauss-Seidel: ``P = D - L``;
* SOR: ``P = D / omega - L``, so ``M = (D - omega L)^{-1} ((1 - omega) D + omega U)``.

The iteration converges from every start if and only if the spectral radius ``rho(M) < 1``
(:func:`iteration_matrix`, :func:`sor_spectral_radii`, :func:`optimal_omega`). The solvers
never form ``M``: a sweep is the loop above, compiled (numba) over the non-zeros of ``A`` held
in compressed rows, so it costs ``O(nnz)`` for a ``scipy.sparse`` matrix as for a dense one.

**Stopping.** The criterion is explicit, because iteration counts depend on it:

* ``criterion="step"``: stop when ``||x_{k+1} - x_k|| / omega <= tol`` (times ``||x_{k+1}||``
  if ``relative``). The step of SOR is ``omega`` times the Gauss-Seidel-like correction
  ``(D - omega L)^{-1} r_k``; dividing by ``omega`` tests that correction, a preconditioned
  residual, and not a step made small by a small ``omega``. For Jacobi and Gauss-Seidel this is
  the rule of Burden and Faires' algorithms 7.1 and 7.2;
* ``criterion="residual"``: stop when ``||b - A x_k|| <= tol`` (times ``||b||`` if
  ``relative``).

An iteration whose residual grows beyond :data:`DIVERGENCE_GROWTH` times its start, or
overflows, is reported as diverging (:class:`~mechnum.errors.DivergenceError`).

**Direct least squares** (:func:`least_squares`): Householder QR, the SVD, and the normal
equations by Cholesky, by LU with partial pivoting, or iteratively.
"""

import dataclasses
from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse as sp
from scipy.linalg import cho_factor, cho_solve, lu_factor, lu_solve, qr, solve_triangular
from scipy.optimize import minimize_scalar

from mechnum import _validate
from mechnum.errors import (ConvergenceError, DivergenceError, RelaxationFactorError,
                            SingularJacobianError)

METHODS = ("jacobi", "gauss_seidel", "sor")
CRITERIA = ("step", "residual")
NORMS = (np.inf, 1, 2)
LEAST_SQUARES_METHODS = ("qr", "svd", "cholesky", "lu") + METHODS + ("cg",)
#: A residual this many times larger than at the start (or than ``||b||``) means divergence: a
#: convergent iteration can grow transiently, but not by eight orders of magnitude.
DIVERGENCE_GROWTH = 1e8
#: Sweeps run per call of the compiled loop: the Python overhead is paid once per chunk, and the
#: norms of a chunk (two arrays of this length) cost nothing next to the sweeps.
CHUNK = 4096
#: Error messages of the stationary solvers quote rho(M) for matrices up to this order, where
#: the dense eigenvalue problem costs milliseconds.
DIAGNOSTIC_ORDER = 200
#: optimal_omega scans rho(M_SOR) on this grid of (0, 2) (spacing 0.005, fine enough to land in
#: the basin of the minimum), then minimises between the neighbours of the best grid point ...
OMEGA_GRID = np.linspace(0.005, 1.995, 399)
#: ... down to this width of the bracket: rho has a cusp at the optimum, where a bracketing
#: method needs no derivative.
OMEGA_XTOL = 1e-10
#: sor_spectral_radii forms its iteration matrices in blocks of at most this many entries
#: (16 MB of float64 per array), so that thousands of omegas cost one batched call per block.
BLOCK_ENTRIES = 2 ** 21
#: Iterative refinement gives up when a correction is not at least this much smaller than the
#: one before: the low-precision factorisation no longer contracts the error.
REFINEMENT_CONTRACTION = 0.5
#: A matrix is symmetric for conjugate gradients when ``max abs(A - A^T)`` is at most this
#: times ``max abs(A)``: the round-off of forming a product such as ``A^T A``, with a margin.
SYMMETRY_RTOL = 1e-12

_NORM_CODES = {np.inf: 0, 1: 1, 2: 2}
_RUNNING, _CONVERGED, _DIVERGED = 0, 1, 2


@dataclass(frozen=True)
class StoppingRule:
    """When an iteration stops: the options that every iterative solver of the module takes.

    Attributes
    ----------
    tol : float
        Tolerance of the criterion, positive.
    maxiter : int
        Most sweeps (or steps), at least 1.
    criterion : {"step", "residual"}
        Stop on the step (divided by ``omega``) or on the residual ``||b - A x_k||``.
    norm : {inf, 1, 2}
        The vector norm of the criterion and of the recorded norms.
    relative : bool
        Divide the step by ``||x_{k+1}||`` (the residual by ``||b||``) before comparing.

    Examples
    --------
    >>> StoppingRule(tol=1e-8).criterion
    'step'
    >>> StoppingRule(tol=-1.0)
    Traceback (most recent call last):
    ...
    ValueError: tol must be positive, got -1.0
    """

    tol: float = 1e-10
    maxiter: int = 10_000
    criterion: str = "step"
    norm: float = np.inf
    relative: bool = False

    def __post_init__(self):
        set_ = object.__setattr__  # the dataclass is frozen: store the checked values
        set_(self, "tol", _validate.tolerance(self.tol))
        set_(self, "maxiter", _validate.maxiter(self.maxiter))
        _validate.choice(self.criterion, CRITERIA, "criterion")
        _validate.choice(self.norm, NORMS, "norm")
        if not isinstance(self.relative, (bool, np.bool_)):
            raise ValueError(f"relative must be True or False, got {self.relative!r}")


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
    history : ndarray, shape (iterations + 1, n), or None
        Every iterate, the initial guess first (None when it was not kept).
    residual_norms : ndarray, shape (iterations + 1,)
        ``||b - A x_k||`` for every iterate, in the norm of the criterion.
    step_norms : ndarray, shape (iterations,)
        ``||x_{k+1} - x_k||`` of every sweep (of every correction, for refinement).
    """

    x: np.ndarray
    iterations: int
    converged: bool
    history: np.ndarray | None
    residual_norms: np.ndarray
    step_norms: np.ndarray


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
        ``"young"`` (the formula ``2 / (1 + sqrt(1 - rho_J^2))``) or ``"numerical"`` (a
        minimisation of ``rho(M_SOR(omega))`` over ``(0, 2)``).
    """

    omega: float
    spectral_radius: float
    how: str


@dataclass(frozen=True)
class SorSweep:
    """The outcome of :func:`sor_sweep`: one entry per relaxation factor.

    Attributes
    ----------
    omegas : ndarray, shape (k,)
    spectral_radii : ndarray, shape (k,), or None
        ``rho(M_SOR(omega))`` (None for a sparse matrix, whose iteration matrix is not formed).
    iterations : ndarray of int, shape (k,)
        Sweeps taken (``maxiter`` where it did not converge).
    converged : ndarray of bool, shape (k,)
    """

    omegas: np.ndarray
    spectral_radii: np.ndarray | None
    iterations: np.ndarray
    converged: np.ndarray


@dataclass(frozen=True)
class LeastSquares:
    """The outcome of :func:`least_squares`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        The solution (of minimum norm, for ``method="svd"`` on a rank-deficient ``A``).
    residuals : ndarray, shape (m,)
        ``A x - b``.
    rank : int
        The numerical rank of ``A`` (singular values above ``max(m, n) eps sigma_1``).
    singular_values : ndarray, shape (min(m, n),)
    solver : IterationResult or None
        The iterative solver's result, for the iterative methods.
    """

    x: np.ndarray
    residuals: np.ndarray
    rank: int
    singular_values: np.ndarray
    solver: IterationResult | None


@dataclass(frozen=True)
class Splitting:
    """``A = P - N`` for Jacobi, Gauss-Seidel or SOR, ready to sweep (see :func:`splitting`).

    Attributes
    ----------
    A : scipy.sparse.csr_array, shape (n, n)
        The matrix, in compressed rows (the sweep runs over its non-zeros).
    method : {"jacobi", "gauss_seidel", "sor"}
    omega : float
        The relaxation factor (1 for Jacobi and Gauss-Seidel).
    diagonal : ndarray, shape (n,)
        The diagonal of ``A``, non-zero.
    rows : tuple of ndarray
        ``(indptr, indices, data)`` of ``A`` with unsigned indices, the compiled sweep's input
        (an unsigned index spares it a negative-index test on every non-zero).
    """

    A: sp.csr_array
    method: str
    omega: float
    diagonal: np.ndarray
    rows: tuple = dataclasses.field(repr=False)

    def sweep(self, x, b):
        """One sweep from ``x``: the next iterate (``x`` itself is not changed).

        Examples
        --------
        >>> split = splitting([[4.0, 1.0], [1.0, 3.0]], "gauss_seidel")
        >>> split.sweep([0.0, 0.0], [1.0, 2.0]).tolist()
        [0.25, 0.5833333333333334]
        """
        n = self.diagonal.size
        b = _validate.array(b, "b", shape=(n,))
        x = _validate.array(x, "x", shape=(n,)).copy()
        _sweep(*self.rows, self.diagonal, b, x, self.omega, self.method == "jacobi",
               np.empty(n))
        return x


# ---------------------------------------------------------------------------------------------
# Input checks


def check_matrix(A, square=True):
    """``A`` as a finite real float matrix, dense or compressed-row sparse, or a ValueError.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n), or (m, n) if not ``square``
    square : bool, optional
        Whether ``A`` must be square.

    Returns
    -------
    ndarray or scipy.sparse.csr_array
        A float array, or for sparse input a CSR array with sorted, summed indices.

    Examples
    --------
    >>> check_matrix([[1, 2], [3, 4]]).dtype
    dtype('float64')
    >>> check_matrix([[1.0, 2.0]])
    Traceback (most recent call last):
    ...
    ValueError: A must be a non-empty square matrix, got shape (1, 2)
    """
    if sp.issparse(A):
        if A.dtype.kind not in "biuf":
            raise ValueError(f"A must be a real numeric matrix, got dtype {A.dtype}")
        A = sp.csr_array(A, dtype=float)
        if not A.has_canonical_format:
            A = A.copy()
            A.sum_duplicates()
        if not np.all(np.isfinite(A.data)):
            raise ValueError("A must be finite, it holds NaN or inf")
    else:
        A = _validate.array(A, "A", ndim=2)
    if A.shape[0] * A.shape[1] == 0 or (square and A.shape[0] != A.shape[1]):
        kind = "square matrix" if square else "matrix"
        raise ValueError(f"A must be a non-empty {kind}, got shape {A.shape}")
    return A


def _dense(A, what, square=True):
    """A checked dense matrix; a sparse one is refused, since ``what`` needs it dense."""
    if sp.issparse(A):
        raise ValueError(f"{what} needs a dense matrix (it forms an n x n matrix or its "
                         f"eigenvalues); pass A.toarray() for a small sparse matrix")
    return check_matrix(A, square)


def _relaxation_factor(omega):
    """``omega`` as a float in (0, 2), or a RelaxationFactorError."""
    try:
        omega = _validate.scalar(omega, "omega")
    except ValueError as error:
        raise RelaxationFactorError(f"SOR needs a relaxation factor omega in (0, 2): {error}")
    if not 0 < omega < 2:
        raise RelaxationFactorError(
            f"SOR relaxation factor omega must lie in (0, 2), got {omega!r}: "
            f"rho(M_SOR) >= |omega - 1| >= 1 outside it")
    return omega


def _relaxation_factors(omegas):
    """``omegas`` as a 1-d float array of factors in (0, 2), or a RelaxationFactorError."""
    try:
        omegas = _validate.array(omegas, "omegas", ndim=1)
    except ValueError as error:
        raise RelaxationFactorError(f"SOR needs relaxation factors in (0, 2): {error}")
    for omega in omegas:
        _relaxation_factor(omega)
    return omegas


def _check_system(A, b):
    """Checked ``A`` (dense or sparse) and ``b``; a dense ``A`` singular to working precision
    raises (a sparse one is not tested: it would need a factorisation)."""
    A = check_matrix(A)
    b = _validate.array(b, "b", shape=(A.shape[0],))
    if not sp.issparse(A):
        cond = condition_number(A, 1)
        if cond * np.finfo(float).eps >= 1:
            raise SingularJacobianError(
                f"A is singular to working precision (1-norm condition number {cond:.3g})")
    return A, b


# ---------------------------------------------------------------------------------------------
# The splittings and their iteration matrices


def splitting(A, method="gauss_seidel", omega=1.0):
    """The splitting of ``A`` for a stationary method, checked and ready to sweep.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n)
        Finite, with a non-zero diagonal.
    method : {"jacobi", "gauss_seidel", "sor"}
    omega : float, optional
        The SOR relaxation factor, in ``(0, 2)`` (ignored by the other methods).

    Returns
    -------
    Splitting

    Raises
    ------
    ValueError
        Ill-shaped or non-finite ``A``, unknown ``method``.
    RelaxationFactorError
        ``omega`` outside ``(0, 2)`` for SOR.
    SingularJacobianError
        A zero diagonal entry (``P`` would be singular).

    Examples
    --------
    >>> split = splitting([[2.0, -1.0], [-1.0, 2.0]], "sor", 1.2)
    >>> split.method, split.omega, split.diagonal.tolist()
    ('sor', 1.2, [2.0, 2.0])
    """
    _validate.choice(method, METHODS, "method")
    omega = _relaxation_factor(omega) if method == "sor" else 1.0
    A = sp.csr_array(check_matrix(A))
    diagonal = A.diagonal()
    zero = np.flatnonzero(diagonal == 0)
    if zero.size:
        raise SingularJacobianError(
            f"zero diagonal entries A[i, i] for i in {zero[:10].tolist()}: the splitting "
            f"matrix is singular (reorder the equations)")
    rows = (A.indptr.astype(np.uint64), A.indices.astype(np.uint64), A.data)
    return Splitting(A, method, omega, diagonal, rows)


def iteration_matrix(A, method, omega=1.0):
    """The iteration matrix ``M = P^{-1} N`` of Jacobi, Gauss-Seidel or SOR (dense ``A``).

    Parameters
    ----------
    A : array_like, shape (n, n)
        The system matrix; finite, with a non-zero diagonal.
    method : {"jacobi", "gauss_seidel", "sor"}
    omega : float, optional
        The SOR relaxation factor, in ``(0, 2)`` (ignored by the other methods).

    Returns
    -------
    ndarray, shape (n, n)

    Raises
    ------
    ValueError, RelaxationFactorError, SingularJacobianError
        As :func:`splitting`; ValueError also for a sparse ``A``.

    Examples
    --------
    >>> iteration_matrix([[2.0, -1.0], [-1.0, 2.0]], "jacobi")
    array([[0. , 0.5],
           [0.5, 0. ]])
    """
    A = _dense(A, "iteration_matrix")
    split = splitting(A, method, omega)
    if method == "jacobi":
        return np.eye(len(A)) - A / split.diagonal[:, None]
    return _sor_matrices(A, np.array([split.omega]))[0]


def _sor_matrices(A, omegas):
    """``M_SOR(omega) = (D - omega L)^{-1} ((1 - omega) D + omega U)`` for each omega."""
    D = np.diag(np.diag(A))
    L, U = -np.tril(A, -1), -np.triu(A, 1)
    w = omegas[:, None, None]
    return np.linalg.solve(D - w * L, (1 - w) * D + w * U)


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
    return float(np.max(np.abs(np.linalg.eigvals(_dense(M, "spectral_radius")))))


def sor_spectral_radii(A, omegas):
    """``rho(M_SOR(omega))`` for every ``omega`` of a sweep, in batched dense algebra.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense, finite, with a non-zero diagonal.
    omegas : array_like, shape (k,)
        Relaxation factors in ``(0, 2)``; an empty sweep gives an empty result.

    Returns
    -------
    ndarray, shape (k,)

    Examples
    --------
    >>> sor_spectral_radii([[2.0, -1.0], [-1.0, 2.0]], [1.0]).round(6).tolist()
    [0.25]
    """
    A = _dense(A, "sor_spectral_radii")
    splitting(A, "gauss_seidel")  # checks the diagonal
    omegas = _relaxation_factors(omegas)
    radii = np.empty(omegas.size)
    block = max(1, BLOCK_ENTRIES // A.size)
    for start in range(0, omegas.size, block):
        M = _sor_matrices(A, omegas[start:start + block])
        radii[start:start + block] = np.abs(np.linalg.eigvals(M)).max(axis=-1)
    return radii


def young_omega(rho_jacobi):
    """Young's optimal SOR factor ``2 / (1 + sqrt(1 - rho_J^2))`` from Jacobi's spectral radius.

    It is the optimum for consistently ordered matrices whose Jacobi eigenvalues are real
    (tridiagonal SPD matrices, the 5-point Laplacian in natural order), where the optimal
    spectral radius is ``omega* - 1``.

    Examples
    --------
    >>> round(young_omega(np.cos(np.pi / 51)), 6)   # 2-D Poisson, 50 x 50 interior nodes
    1.884018
    """
    rho = _validate.scalar(rho_jacobi, "rho_jacobi", nonnegative=True)
    if not rho < 1:
        raise ValueError(f"Young's formula needs rho_jacobi < 1 (Jacobi convergent), got {rho!r}")
    return float(2.0 / (1.0 + np.sqrt(1.0 - rho ** 2)))


def _young_applies(A):
    """Young's formula holds for consistently ordered matrices; here: tridiagonal SPD ones."""
    tridiagonal = np.array_equal(A, np.triu(np.tril(A, 1), -1))
    if not (tridiagonal and np.allclose(A, A.T)):
        return False
    return bool(np.all(np.linalg.eigvalsh(A) > 0))


def optimal_omega(A):
    """The SOR relaxation factor of smallest spectral radius, and how it was found.

    For a symmetric positive definite tridiagonal matrix (consistently ordered, Jacobi
    eigenvalues real and below 1) Young's formula (:func:`young_omega`) is exact. Otherwise
    ``rho(M_SOR(omega))`` is scanned on :data:`OMEGA_GRID` and minimised between the
    neighbours of the best grid point.

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense.

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
    A = _dense(A, "optimal_omega")
    if _young_applies(A):
        omega = young_omega(spectral_radius(iteration_matrix(A, "jacobi")))
        return OptimalOmega(omega, omega - 1.0, "young")
    rho = sor_spectral_radii(A, OMEGA_GRID)
    i = int(np.argmin(rho))
    lo, hi = OMEGA_GRID[max(i - 1, 0)], OMEGA_GRID[min(i + 1, OMEGA_GRID.size - 1)]
    best = minimize_scalar(lambda w: sor_spectral_radii(A, [w])[0], bounds=(lo, hi),
                           method="bounded", options={"xatol": OMEGA_XTOL})
    omega, value = (best.x, best.fun) if best.fun <= rho[i] else (OMEGA_GRID[i], rho[i])
    return OptimalOmega(float(omega), float(value), "numerical")


def condition_number(A, p=2):
    """The condition number ``||A|| ||A^+||`` in the norm ``p`` (dense ``A``).

    Parameters
    ----------
    A : array_like, shape (n, n), or (m, n) for ``p=2``
        For ``p=2`` a rectangular matrix is allowed (ratio of extreme singular values).
    p : {1, 2, inf, "fro"}, optional

    Returns
    -------
    float
        ``inf`` for a singular matrix.

    Examples
    --------
    >>> round(condition_number([[1.0, 0.0], [0.0, 1e-3]], np.inf), 9)
    1000.0
    """
    _validate.choice(p, (1, 2, np.inf, "fro"), "p")
    A = _dense(A, "condition_number", square=p != 2)
    if p == 2:
        s = np.linalg.svd(A, compute_uv=False)
        return float(s[0] / s[-1]) if s[-1] > 0 else np.inf
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        return np.inf
    return float(np.linalg.norm(A, p) * np.linalg.norm(inv, p))


# ---------------------------------------------------------------------------------------------
# Sweeps


def sweep_by_components(A, b, x, omega=1.0):
    """One Gauss-Seidel (``omega = 1``) or SOR sweep, component by component, in plain Python.

    The textbook loop, written to be read: the solvers run the same loop compiled
    (:meth:`Splitting.sweep`).

    Parameters
    ----------
    A : array_like, shape (n, n)
        Dense, with a non-zero diagonal.
    b, x : array_like, shape (n,)
        Right-hand side and current iterate (not changed).
    omega : float, optional
        Relaxation factor in ``(0, 2)``.

    Returns
    -------
    ndarray, shape (n,)

    Examples
    --------
    >>> sweep_by_components([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], [0.0, 0.0]).tolist()
    [0.25, 0.5833333333333334]
    """
    split = splitting(_dense(A, "sweep_by_components"), "sor", omega)
    A, n = split.A.toarray(), split.diagonal.size
    b, x = _validate.array(b, "b", shape=(n,)), _validate.array(x, "x", shape=(n,)).copy()
    for i in range(n):
        sigma = sum(A[i, j] * x[j] for j in range(n) if j != i)
        x[i] = (1 - omega) * x[i] + omega * (b[i] - sigma) / A[i, i]
    return x


@numba.njit(cache=True)
def _sweep(indptr, indices, data, diagonal, b, x, omega, jacobi, work):
    """One sweep over the rows of a CSR matrix, in place (``work``: scratch of size n).

    Row ``i`` gives ``x[i] += omega * (b[i] - A[i] @ x) / A[i, i]``, the loop of
    :func:`sweep_by_components` with ``sigma = A[i] @ x - A[i, i] x[i]``; Jacobi reads the old
    iterate only, so it updates every ``x[i]`` after all the rows.
    """
    for i in range(b.size):
        residual = b[i]
        for k in range(indptr[i], indptr[i + 1]):
            residual -= data[k] * x[indices[k]]
        if jacobi:
            work[i] = residual / diagonal[i]
        else:
            x[i] += omega * residual / diagonal[i]
    if jacobi:
        x += work


@numba.njit(cache=True)
def _norm(v, p):
    """The inf- (p = 0), 1- or 2-norm of a vector, in plain loops (a BLAS call would pay its
    threads' overhead at every sweep)."""
    total = 0.0
    for value in v:
        if p == 0:
            total = max(total, abs(value))
        elif p == 1:
            total += abs(value)
        else:
            total += value * value
    return np.sqrt(total) if p == 2 else total


@numba.njit(cache=True)
def _run(csr, diagonal, b, x, omega, jacobi, rule, residuals, steps, history):
    """Up to ``steps.size`` sweeps in place; fills the norms (and ``history`` if it has rows).

    ``rule = (norm code, stop on step, relative, tol, residual limit, divergence limit)``.
    Returns ``(sweeps taken, state)``, the state being running, converged or diverged.
    """
    indptr, indices, data = csr
    p, by_step, relative, tol, limit, blow_up = rule
    n = b.size
    old, work = np.empty(n), np.empty(n)
    for k in range(steps.size):
        old[:] = x
        _sweep(indptr, indices, data, diagonal, b, x, omega, jacobi, work)
        steps[k] = _norm(x - old, p)
        for i in range(n):  # the residual b - A x
            work[i] = b[i]
            for m in range(indptr[i], indptr[i + 1]):
                work[i] -= data[m] * x[indices[m]]
        residuals[k] = _norm(work, p)
        if history.shape[0]:
            history[k] = x
        if by_step:
            done = steps[k] / omega <= tol * (_norm(x, p) if relative else 1.0)
        else:
            done = residuals[k] <= limit
        if done:
            return k + 1, 1
        if not residuals[k] <= blow_up:  # growth, overflow or NaN
            return k + 1, 2
    return steps.size, 0


@numba.njit(cache=True)
def _dot(u, v):
    """``u @ v`` in one compiled loop: conjugate gradients take two per step, and a threaded
    BLAS call costs more in synchronisation than in arithmetic at these sizes."""
    total = 0.0
    for i in range(u.size):
        total += u[i] * v[i]
    return total


def _vector_norm(v, norm):
    return float(np.linalg.norm(v, norm)) if v.size else 0.0


def _iterate(split, b, x, rule, keep_history):
    """Sweep ``split`` from ``x`` until ``rule`` stops it; ``(IterationResult, state)``."""
    A, n = split.A, b.size
    residual0, b_norm = _vector_norm(b - A @ x, rule.norm), _vector_norm(b, rule.norm)
    limit = rule.tol * b_norm if rule.relative else rule.tol
    blow_up = DIVERGENCE_GROWTH * max(residual0, b_norm, np.finfo(float).tiny)
    compiled_rule = (_NORM_CODES[rule.norm], rule.criterion == "step", bool(rule.relative),
                     rule.tol, limit, blow_up)
    x = x.copy()
    residuals, steps, history = [np.array([residual0])], [], [x[None].copy()]
    done, state = 0, _RUNNING
    with np.errstate(over="ignore", invalid="ignore"):
        while state == _RUNNING and done < rule.maxiter:
            count = min(CHUNK, rule.maxiter - done)
            chunk = np.empty(count), np.empty(count), np.empty((count * keep_history, n))
            taken, state = _run(split.rows, split.diagonal, b, x,
                                split.omega, split.method == "jacobi", compiled_rule, *chunk)
            residuals.append(chunk[0][:taken])
            steps.append(chunk[1][:taken])
            history.append(chunk[2][:taken])
            done += taken
    result = IterationResult(x, done, state == _CONVERGED,
                             np.concatenate(history) if keep_history else None,
                             np.concatenate(residuals), np.concatenate(steps or [np.empty(0)]))
    return result, state


def _solve(A, b, method, omega, x0, rule, keep_history):
    A, b = _check_system(A, b)
    split = splitting(A, method, omega)
    x = np.zeros(b.size) if x0 is None else _validate.array(x0, "x0", shape=b.shape)
    keep = not sp.issparse(A) if keep_history is None else bool(keep_history)
    result, state = _iterate(split, b, x, rule, keep)
    if state == _CONVERGED:
        return result
    name = method if method != "sor" else f"SOR (omega={split.omega:g})"
    rho = ""
    if not sp.issparse(A) and b.size <= DIAGNOSTIC_ORDER:
        rho = f"; spectral radius of the iteration matrix " \
              f"{spectral_radius(iteration_matrix(A, method, split.omega)):.4g}"
    r = result.residual_norms
    if state == _DIVERGED:
        raise DivergenceError(f"{name} diverges: residual norm {r[-1]:.3g} after "
                              f"{result.iterations} sweeps, from {r[0]:.3g}{rho}", result)
    raise ConvergenceError(f"{name} did not converge in {rule.maxiter} sweeps: residual norm "
                           f"{r[-1]:.3g} (criterion {rule.criterion!r}, tol {rule.tol:g}){rho}",
                           result)


def sor(A, b, omega, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
        relative=False, keep_history=None):
    """Solve ``A x = b`` by successive over-relaxation.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n)
        Finite, non-singular, with a non-zero diagonal. A sparse matrix is swept over its
        non-zeros and never made dense.
    b : array_like, shape (n,)
    omega : float
        Relaxation factor in ``(0, 2)``: under-relaxation below 1, over-relaxation above.
    x0 : array_like, shape (n,), optional
        Initial guess (default zero).
    tol, maxiter, criterion, norm, relative
        The stopping rule (:class:`StoppingRule`).
    keep_history : bool, optional
        Keep every iterate in ``history`` (default: for a dense ``A`` only).

    Returns
    -------
    IterationResult

    Raises
    ------
    ValueError
        Ill-shaped or non-finite input, an unknown option.
    SingularJacobianError
        A dense ``A`` singular to working precision, or a zero diagonal entry.
    RelaxationFactorError
        ``omega`` missing or outside ``(0, 2)``.
    DivergenceError
        The residual grows beyond :data:`DIVERGENCE_GROWTH` times its start, or overflows.
    ConvergenceError
        ``maxiter`` sweeps without meeting the criterion; ``result`` holds the history.

    Examples
    --------
    >>> res = sor([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], omega=1.1, tol=1e-12)
    >>> res.x.round(10).tolist(), res.converged
    ([0.0909090909, 0.6363636364], True)
    """
    rule = StoppingRule(tol, maxiter, criterion, norm, relative)
    return _solve(A, b, "sor", omega, x0, rule, keep_history)


def gauss_seidel(A, b, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
                 relative=False, keep_history=None):
    """Solve ``A x = b`` by Gauss-Seidel (SOR with ``omega = 1``); arguments as :func:`sor`.

    Examples
    --------
    >>> res = gauss_seidel([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    rule = StoppingRule(tol, maxiter, criterion, norm, relative)
    return _solve(A, b, "gauss_seidel", 1.0, x0, rule, keep_history)


def jacobi(A, b, x0=None, *, tol=1e-10, maxiter=10_000, criterion="step", norm=np.inf,
           relative=False, keep_history=None):
    """Solve ``A x = b`` by Jacobi's method; arguments as :func:`sor`.

    Examples
    --------
    >>> res = jacobi([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0], tol=1e-12)
    >>> res.x.round(10).tolist()
    [0.0909090909, 0.6363636364]
    """
    rule = StoppingRule(tol, maxiter, criterion, norm, relative)
    return _solve(A, b, "jacobi", 1.0, x0, rule, keep_history)


def sor_sweep(A, b, omegas, x0=None, *, tol=1e-10, maxiter=100_000, criterion="step",
              norm=np.inf, relative=False):
    """Run SOR for many relaxation factors: spectral radius and iteration count of each.

    Each ``omega`` runs its own iteration with the options of :func:`sor`; nothing is raised
    for one that does not converge, its ``converged`` entry is ``False``.

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
    ([40, 17, 193], [True, True, True])
    """
    A, b = _check_system(A, b)
    rule = StoppingRule(tol, maxiter, criterion, norm, relative)
    omegas = _relaxation_factors(omegas)
    x = np.zeros(b.size) if x0 is None else _validate.array(x0, "x0", shape=b.shape)
    split = splitting(A, "gauss_seidel")
    iterations, converged = np.zeros(omegas.size, int), np.zeros(omegas.size, bool)
    for i, omega in enumerate(omegas):
        with_omega = dataclasses.replace(split, method="sor", omega=float(omega))
        result, _ = _iterate(with_omega, b, x, rule, False)
        iterations[i], converged[i] = result.iterations, result.converged
    radii = None if sp.issparse(A) else sor_spectral_radii(A, omegas)
    return SorSweep(omegas, radii, iterations, converged)


# ---------------------------------------------------------------------------------------------
# Krylov, least squares, refinement, a model problem


def _check_symmetric(A):
    gap = abs(A - A.T).max() if sp.issparse(A) else np.abs(A - A.T).max()
    if gap > SYMMETRY_RTOL * abs(A).max():
        raise ValueError(f"conjugate gradients need a symmetric A: max |A - A^T| = {gap:.3g}")


def conjugate_gradient(A, b, x0=None, *, tol=1e-10, maxiter=None, keep_history=None):
    """Solve ``A x = b`` for a symmetric positive definite ``A`` by conjugate gradients.

    Each step costs one product ``A p``; in exact arithmetic the method ends in at most ``n``
    steps, and the error falls at least like ``((sqrt(kappa) - 1) / (sqrt(kappa) + 1))^k``.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n)
        Symmetric positive definite.
    b, x0 : array_like, shape (n,)
    tol : float, optional
        Stop when the (recursively updated) residual ``||r_k||_2 <= tol ||b||_2``.
    maxiter : int, optional
        Most steps (default ``10 n``).
    keep_history : bool, optional
        As in :func:`sor`.

    Returns
    -------
    IterationResult
        ``residual_norms`` in the 2-norm.

    Raises
    ------
    ValueError
        Ill-shaped, non-finite or non-symmetric input.
    SingularJacobianError
        ``p^T A p <= 0`` for a search direction: ``A`` is not positive definite.
    ConvergenceError
        ``maxiter`` steps without meeting the tolerance.

    Examples
    --------
    >>> res = conjugate_gradient([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0])
    >>> res.x.round(10).tolist(), res.iterations
    ([0.0909090909, 0.6363636364], 2)
    """
    A = check_matrix(A)
    b = _validate.array(b, "b", shape=(A.shape[0],))
    _check_symmetric(A)
    rule = StoppingRule(tol, 10 * b.size if maxiter is None else maxiter, "residual", 2, True)
    x = np.zeros(b.size) if x0 is None else _validate.array(x0, "x0", shape=b.shape).copy()
    keep = not sp.issparse(A) if keep_history is None else bool(keep_history)
    r = b - A @ x
    p, rr, limit = r.copy(), _dot(r, r), rule.tol * np.sqrt(_dot(b, b))
    history, residuals, steps = [x.copy()], [np.sqrt(rr)], []
    while residuals[-1] > limit and len(steps) < rule.maxiter:
        Ap = A @ p
        curvature = _dot(p, Ap)
        if not curvature > 0:
            raise SingularJacobianError(f"A is not positive definite: p^T A p = {curvature:.3g} "
                                        f"at step {len(steps) + 1}")
        alpha = rr / curvature
        step = alpha * p
        x += step
        r -= alpha * Ap
        rr, rr_old = _dot(r, r), rr
        p = r + (rr / rr_old) * p
        if keep:
            history.append(x.copy())
        residuals.append(np.sqrt(rr))
        steps.append(np.sqrt(_dot(step, step)))
    result = IterationResult(x, len(steps), bool(residuals[-1] <= limit),
                             np.array(history) if keep else None, np.array(residuals),
                             np.array(steps))
    if not result.converged:
        raise ConvergenceError(f"conjugate gradients did not converge in {rule.maxiter} steps: "
                               f"residual {residuals[-1]:.3g} > {limit:.3g}", result)
    return result


def least_squares(A, b, method="qr", omega=None, **solver_options):
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
    return LeastSquares(x, A @ x - b, rank, s, solver)


def iterative_refinement(A, b, *, factor_dtype=np.float32, tol=1e-9, maxiter=20):
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
        Most refinement steps, at least 1.

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
        If the corrections stop contracting (by :data:`REFINEMENT_CONTRACTION`) before ``tol``
        is met (``cond(A) * eps(factor_dtype)`` too large) or ``maxiter`` is hit.

    Examples
    --------
    >>> res = iterative_refinement([[4.0, 1.0], [1.0, 3.0]], [1.0, 2.0])
    >>> res.x.round(12).tolist(), res.converged
    ([0.090909090909, 0.636363636364], True)
    """
    A, b = _check_system(_dense(A, "iterative_refinement"), b)
    if np.dtype(factor_dtype) not in (np.float32, np.float64):
        raise ValueError(f"factor_dtype must be float32 or float64, got {factor_dtype!r}")
    rule = StoppingRule(tol, maxiter)
    scale = 2.0 ** np.round(np.log2(np.abs(A).max()))  # exact: only the exponent changes
    lu = lu_factor((A / scale).astype(factor_dtype))

    def solve(r):
        size = np.abs(r).max()
        if size == 0:
            return np.zeros_like(r)
        return size / scale * lu_solve(lu, (r / size).astype(factor_dtype)).astype(float)

    x = solve(b)
    history, residuals, steps = [x], [np.linalg.norm(b - A @ x, np.inf)], []
    converged = False
    while len(steps) < rule.maxiter:
        d = solve(b - A @ x)
        x = x + d
        history.append(x)
        residuals.append(np.linalg.norm(b - A @ x, np.inf))
        steps.append(np.linalg.norm(d, np.inf))
        if steps[-1] <= rule.tol * np.linalg.norm(x, np.inf):
            converged = True
            break
        if not (len(steps) < 2 or steps[-1] <= REFINEMENT_CONTRACTION * steps[-2]):
            break  # also on NaN
    result = IterationResult(x, len(steps), converged, np.array(history), np.array(residuals),
                             np.array(steps))
    if not converged:
        raise ConvergenceError(
            f"iterative refinement stalled after {len(steps)} steps: correction "
            f"{steps[-1]:.3g}, 1-norm condition number {condition_number(A, 1):.3g}", result)
    return result


def poisson2d(m):
    """The 5-point Laplacian on an ``m x m`` grid of interior nodes, as a sparse matrix.

    ``h^2`` times the discrete ``-(u_xx + u_yy)`` with zero boundary values, nodes numbered row
    by row: ``4`` on the diagonal, ``-1`` for each neighbour; ``n = m^2`` unknowns, about
    ``5 n`` non-zeros. Symmetric positive definite, consistently ordered, with Jacobi spectral
    radius ``cos(pi / (m + 1))``.

    Examples
    --------
    >>> poisson2d(2).toarray()
    array([[ 4., -1., -1.,  0.],
           [-1.,  4.,  0., -1.],
           [-1.,  0.,  4., -1.],
           [ 0., -1., -1.,  4.]])
    """
    m = _validate.maxiter(m, "m")
    T = sp.diags_array([-1.0, 2.0, -1.0], offsets=[-1, 0, 1], shape=(m, m))
    I = sp.eye_array(m)
    return sp.csr_array(sp.kron(I, T) + sp.kron(T, I))
