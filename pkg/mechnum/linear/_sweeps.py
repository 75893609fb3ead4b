"""One sweep of a stationary method: the loop component by component, and the splitting.

Write ``A = D - L - U`` with ``D`` the diagonal of ``A`` and ``-L``, ``-U`` its strictly lower
and upper parts. One *sweep* of successive over-relaxation (SOR) updates the unknowns in turn,
each from the newest values of the others::

    for i in range(n):
        sigma = sum(A[i, j] * x[j] for j != i)
        x[i] = (1 - omega) * x[i] + omega * (b[i] - sigma) / A[i, i]

(:func:`~mechnum.linear.sweep_by_components` is exactly this loop). Gauss-Seidel is
``omega = 1``; Jacobi uses only the old values on the right. In matrix form a sweep is
``x <- M x + c`` with the iteration matrix ``M = P^{-1} N`` of the splitting ``A = P - N``:

* Jacobi: ``P = D``;
* Gauss-Seidel: ``P = D - L``;
* SOR: ``P = D / omega - L``, so ``M = (D - omega L)^{-1} ((1 - omega) D + omega U)``.

The solvers never form ``M``: a :class:`Splitting` holds ``A`` in compressed
rows, and a sweep is the loop above compiled (numba) over its non-zeros, so it costs ``O(nnz)``
for a ``scipy.sparse`` matrix as for a dense one.
"""

import dataclasses
from dataclasses import dataclass

import numba
import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import SingularJacobianError
from mechnum.linear._checks import _dense, _relaxation_factor, check_matrix

METHODS = ("jacobi", "gauss_seidel", "sor")


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

    def sweep(self, x: ArrayLike, b: ArrayLike) -> np.ndarray:
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


def splitting(A: ArrayLike | sp.sparray, method: str = "gauss_seidel",
              omega: float = 1.0) -> "Splitting":
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


def sweep_by_components(A: ArrayLike, b: ArrayLike, x: ArrayLike,
                        omega: float = 1.0) -> np.ndarray:
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
