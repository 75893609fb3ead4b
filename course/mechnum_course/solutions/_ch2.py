"""Chapter 2: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


def one_sor_sweep(A, b, x, omega):
    """One SOR sweep, component by component.

    Parameters
    ----------
    A : ndarray, shape (n, n)
        The matrix, with a non-zero diagonal.
    b : ndarray, shape (n,)
        The right-hand side.
    x : ndarray, shape (n,)
        The current iterate (left unchanged).
    omega : float
        The relaxation factor, ``0 < omega < 2``.

    Returns
    -------
    ndarray, shape (n,)
        The iterate after one sweep over ``i = 0, ..., n - 1``.
    """
    x = np.array(x, dtype=float)
    for i in range(len(b)):
        sigma = sum(A[i, j] * x[j] for j in range(len(b)) if j != i)
        x[i] = (1 - omega) * x[i] + omega * (b[i] - sigma) / A[i, i]
    return x


def lstsq_householder(A, b):
    """The least-squares solution of ``A x ~ b`` by Householder QR.

    Parameters
    ----------
    A : ndarray, shape (m, n)
        A matrix of full column rank, ``m >= n``.
    b : ndarray, shape (m,)
        The right-hand side.

    Returns
    -------
    ndarray, shape (n,)
        The ``x`` that minimises ``||A x - b||_2``.
    """
    R, y = np.array(A, dtype=float), np.array(b, dtype=float)
    m, n = R.shape
    for k in range(n):  # I - 2 v v^T zeroes column k below row k
        v = R[k:, k].copy()
        v[0] += np.copysign(np.linalg.norm(v), v[0])  # no cancellation
        v /= np.linalg.norm(v)
        R[k:, k:] -= 2 * np.outer(v, v @ R[k:, k:])
        y[k:] -= 2 * v * (v @ y[k:])
    x = np.zeros(n)  # back substitution on R x = (Q^T b)[:n]
    for i in range(n - 1, -1, -1):
        x[i] = (y[i] - R[i, i + 1:n] @ x[i + 1:]) / R[i, i]
    return x


# Typical mistakes of 2.1
def _jacobi(A, b, x, omega):
    old, x = np.array(x, dtype=float), np.array(x, dtype=float)
    for i in range(len(b)):
        sigma = sum(A[i, j] * old[j] for j in range(len(b)) if j != i)
        x[i] = (1 - omega) * old[i] + omega * (b[i] - sigma) / A[i, i]
    return x


def _unrelaxed_old_value(A, b, x, omega):
    x = np.array(x, dtype=float)
    for i in range(len(b)):
        sigma = sum(A[i, j] * x[j] for j in range(len(b)) if j != i)
        x[i] = omega * (b[i] - sigma) / A[i, i]
    return x


def _short_sweep(A, b, x, omega):
    x = np.array(x, dtype=float)
    for i in range(len(b) - 1):
        sigma = sum(A[i, j] * x[j] for j in range(len(b)) if j != i)
        x[i] = (1 - omega) * x[i] + omega * (b[i] - sigma) / A[i, i]
    return x


def _backward(A, b, x, omega):
    order = np.arange(len(b))[::-1]
    return one_sor_sweep(A[np.ix_(order, order)], b[order], x[order], omega)[np.argsort(order)]



# Typical mistakes of 2.2
def _normal_equations(A, b):
    return np.linalg.solve(A.T @ A, A.T @ b)


def _no_qt(A, b):
    R = np.linalg.qr(A)[1]
    return np.linalg.solve(R, b[:R.shape[0]])


def _transposed_r(A, b):
    Q, R = np.linalg.qr(A)
    return np.linalg.solve(R.T, Q.T @ b)


def _cancelling(A, b):  # v_0 = x_0 - sign(x_0) ||x||: cancels where x is nearly e_1
    R, y = np.array(A, dtype=float), np.array(b, dtype=float)
    m, n = R.shape
    for k in range(n):
        v = R[k:, k].copy()
        v[0] -= np.copysign(np.linalg.norm(v), v[0])
        v /= np.linalg.norm(v)
        R[k:, k:] -= 2 * np.outer(v, v @ R[k:, k:])
        y[k:] -= 2 * v * (v @ y[k:])
    return np.linalg.solve(np.triu(R[:n]), y[:n])


SOLUTIONS = {
    "2.1": Solution(one_sor_sweep, {"a Jacobi sweep": _jacobi,
                                    "the relaxation without (1 - omega) x_i": _unrelaxed_old_value,
                                    "an off-by-one sweep": _short_sweep,
                                    "a backward sweep": _backward},
                    forbidden=("mechnum.linear.sweep_by_components",)),
    "2.2": Solution(lstsq_householder, {"the normal equations": _normal_equations,
                                        "b left without its reflections": _no_qt,
                                        "a transposed R": _transposed_r,
                                        "the cancelling sign": _cancelling},
                    forbidden=("numpy.linalg.qr", "numpy.linalg.lstsq", "numpy.linalg.pinv",
                               "scipy.linalg.qr", "scipy.linalg.lstsq", "scipy.linalg.pinv",
                               "numpy.linalg.svd", "scipy.linalg.svd")),
}
