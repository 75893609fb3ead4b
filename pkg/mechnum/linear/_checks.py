"""What the linear solvers accept: a finite real matrix, dense or sparse, and not singular.

Every entry point of :mod:`mechnum.linear` passes its matrix through
:func:`check_matrix`; the functions that form an ``n x n`` matrix or its
eigenvalues take a dense one only. The stationary solvers refuse a dense matrix that is singular
to working precision, ``cond(A) eps >= 1`` (:func:`~mechnum.linear.condition_number`), and SOR a
relaxation factor outside ``(0, 2)``, where ``rho(M_SOR) >= |omega - 1| >= 1``.
"""

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import RelaxationFactorError, SingularJacobianError

#: A residual (or a refinement's correction) of at most two units of the smallest subnormal
#: number is round-off, whatever the size of the solution: the relative tests accept it
#: (``tol ||x||`` underflows to zero for a subnormal ``x``, which no step would then meet, and a
#: subnormal solution's iterates may cycle through a few units).
SUBNORMAL_FLOOR = 2 * np.finfo(float).smallest_subnormal
#: The most relaxation factors one call takes (:func:`~mechnum.linear.sor_sweep` runs an
#: iteration for each, :func:`~mechnum.linear.sor_spectral_radii` an eigenvalue problem).
OMEGAS_LIMIT = 10_000


def check_matrix(A: ArrayLike | sp.sparray, square: bool = True) -> np.ndarray | sp.csr_array:
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
        # astype first: scipy converts some formats holding float16 (which it does not support)
        # only element by element
        A = sp.csr_array(A.astype(float, copy=False))
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


def _unit_scaled(A):
    """``A`` times the power of two that brings its largest entry into ``[0.5, 1)``: exact, and
    what a scale-invariant quantity (a condition number, an iteration matrix) is computed from,
    so that subnormal or huge entries (1e-310, 1e300) neither overflow nor lose digits."""
    top = np.abs(A).max(initial=0.0)
    return np.ldexp(A, -np.frexp(top)[1]) if top > 0 else A


def _relaxation_factor(omega):
    """``omega`` as a float in (0, 2), or a RelaxationFactorError."""
    try:
        omega = _validate.scalar(omega, "omega")
    except ValueError as error:
        raise RelaxationFactorError(
            f"SOR needs a relaxation factor omega in (0, 2): {error}") from None
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
        raise RelaxationFactorError(f"SOR needs relaxation factors in (0, 2): {error}") from None
    if omegas.size > OMEGAS_LIMIT:
        raise ValueError(f"at most {OMEGAS_LIMIT} relaxation factors (a bound on the work), got "
                         f"{omegas.size}")
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


def condition_number(A: ArrayLike, p: float | str = 2) -> float:
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
    A = _unit_scaled(_dense(A, "condition_number", square=p != 2))
    if p == 2:
        s = np.linalg.svd(A, compute_uv=False)
        return float(s[0] / s[-1]) if s[-1] > 0 else np.inf
    try:
        inv = np.linalg.inv(A)
    except np.linalg.LinAlgError:
        return np.inf
    return float(np.linalg.norm(A, p) * np.linalg.norm(inv, p))
