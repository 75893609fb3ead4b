"""Conjugate gradients, and the model problems on which they meet the stationary methods.

For a symmetric positive definite ``A``, :func:`~mechnum.linear.conjugate_gradient` minimises
the ``A``-norm of the error over a Krylov space that grows by one dimension per step, each step
at the cost of one product ``A p``. :func:`~mechnum.linear.poisson2d` is the 5-point Laplacian,
sparse, on which SOR at Young's factor and conjugate gradients are compared;
:func:`~mechnum.linear.poisson3d`, the 7-point one, is where a sparse factorisation fills in
far more than on a plane grid of as many unknowns.
"""

import numba
import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.linear._checks import check_matrix
from mechnum.linear._stationary import (
    MAXITER_LIMIT,
    TOL,
    IterationResult,
    _initial_guess,
    _keeps_history,
)
from mechnum.results import StoppingRule

#: A matrix is symmetric for conjugate gradients when ``max abs(A - A^T)`` is at most this
#: times ``max abs(A)``: the round-off of forming a product such as ``A^T A``, with a margin.
SYMMETRY_RTOL = 1e-12
#: The largest grid of :func:`~mechnum.linear.poisson2d`: ``m = 2000`` is four million unknowns
#: and twenty million non-zeros (a quarter of a gigabyte).
POISSON_LIMIT = 2000
#: The largest grid of :func:`~mechnum.linear.poisson3d`: ``m = 160`` is four million unknowns
#: and 28 million non-zeros, as :data:`POISSON_LIMIT` on the plane.
POISSON3D_LIMIT = 160


@numba.njit(cache=True)
def _dot(u, v):
    """``u @ v`` in one compiled loop: conjugate gradients take two per step, and a threaded
    BLAS call costs more in synchronisation than in arithmetic at these sizes."""
    total = 0.0
    for i in range(u.size):
        total += u[i] * v[i]
    return total


def _check_symmetric(A):
    gap = abs(A - A.T).max() if sp.issparse(A) else np.abs(A - A.T).max()
    if gap > SYMMETRY_RTOL * abs(A).max():
        raise ValueError(f"conjugate gradients need a symmetric A: max |A - A^T| = {gap:.3g}")


def conjugate_gradient(A: ArrayLike | sp.sparray, b: ArrayLike, seed: ArrayLike | None = None, *,
                       tol: float = TOL, maxiter: int | None = None,
                       keep_history: bool | None = None) -> IterationResult:
    """Solve ``A x = b`` for a symmetric positive definite ``A`` by conjugate gradients.

    Each step costs one product ``A p``; in exact arithmetic the method ends in at most ``n``
    steps, and the error falls at least like ``((sqrt(kappa) - 1) / (sqrt(kappa) + 1))^k``.

    Parameters
    ----------
    A : array_like or scipy.sparse matrix, shape (n, n)
        Symmetric positive definite.
    b : array_like, shape (n,)
    seed : array_like, shape (n,), optional
        The initial guess (default zero).
    tol : float, optional
        Stop when the (recursively updated) residual ``||r_k||_2 <= tol ||b||_2``.
    maxiter : int, optional
        Most steps (default ``10 n``; at most ten million).
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
    rule = StoppingRule.checked(tol, 10 * b.size if maxiter is None else maxiter, "residual", 2,
                                True, maxiter_limit=MAXITER_LIMIT)
    x = _initial_guess(seed, b)  # a new array: updated in place below
    keep = _keeps_history(A, keep_history)
    # b and x scaled by a power of two near |b|: exact, and it keeps the squares of the dot
    # products in range (b = 1e-162 would make b . b subnormal and alpha meaningless)
    size = max(np.abs(b).max(), np.abs(x).max())
    scale = 2.0 ** np.round(np.log2(size)) if size > 0 else 1.0
    b, x = b / scale, x / scale
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
    converged = bool(residuals[-1] <= limit)
    message = (f"conjugate gradients converged in {len(steps)} steps (residual <= {rule.tol:g}"
               f" ||b||)" if converged else
               f"conjugate gradients did not converge in {rule.maxiter} steps: residual "
               f"{residuals[-1] * scale:.3g} > {limit * scale:.3g}")
    result = IterationResult(x=x * scale, status="converged" if converged else "maxiter",
                             message=message, iterations=len(steps), nfev=len(steps) + 1,
                             njev=0, history=np.array(history) * scale if keep else None,
                             residual_norms=np.array(residuals) * scale,
                             step_norms=np.array(steps) * scale)
    if not converged:
        raise ConvergenceError(message, result)
    return result


def poisson2d(m: int) -> sp.csr_array:
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
    m = _validate.maxiter(m, "m", maximum=POISSON_LIMIT)
    T, I = _second_difference(m), sp.eye_array(m)
    return sp.csr_array(sp.kron(I, T) + sp.kron(T, I))


def poisson3d(m: int) -> sp.csr_array:
    """The 7-point Laplacian on an ``m x m x m`` grid of interior nodes, as a sparse matrix.

    As :func:`poisson2d` in three dimensions, nodes numbered plane by plane: ``6`` on the
    diagonal, ``-1`` for each of the six neighbours; ``n = m^3`` unknowns, about ``7 n``
    non-zeros. Symmetric positive definite, consistently ordered, with the same Jacobi
    spectral radius ``cos(pi / (m + 1))`` as the plane grid of side ``m``.

    Parameters
    ----------
    m : int
        Interior nodes per side, ``1 <= m <=`` :data:`POISSON3D_LIMIT`.

    Examples
    --------
    >>> A = poisson3d(2)
    >>> A.shape, A.nnz, A.diagonal().tolist()
    ((8, 8), 32, [6.0, 6.0, 6.0, 6.0, 6.0, 6.0, 6.0, 6.0])
    """
    m = _validate.maxiter(m, "m", maximum=POISSON3D_LIMIT)
    T, I = _second_difference(m), sp.eye_array(m)
    A = sp.kron(I, poisson2d(m), format="csr") + sp.kron(T, sp.eye_array(m * m), format="csr")
    A.eliminate_zeros()  # the plane's blocks, stored dense by kron, hold explicit zeros
    return sp.csr_array(A)


def _second_difference(m):
    """``-u'' h^2`` on ``m`` interior nodes with zero ends: tridiagonal ``(-1, 2, -1)``."""
    return sp.diags_array([-1.0, 2.0, -1.0], offsets=[-1, 0, 1], shape=(m, m))
