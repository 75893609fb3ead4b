"""Chapter 2, linear systems on the finger: one SOR sweep (2.1), and least squares by
Householder QR (2.2)."""

import numpy as np

from mechnum.exercises._harness import Case, Exercise, Mistake, close


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


def _sweep_cases():
    rng = np.random.default_rng(21)
    bf = np.array([[10.0, -1, 2, 0], [-1, 11, -1, 3], [2, -1, 10, -1], [0, 3, -1, 8]])
    cases = [Case("Burden and Faires' 4 x 4 system, x = 0, omega = 1.25",
                  (bf, np.array([6.0, 25, -11, 15]), np.zeros(4), 1.25))]
    for n, omega in ((3, 0.33), (5, 1.0), (6, 1.7)):
        M = rng.normal(size=(n, n))
        cases.append(Case(f"a random {n} x {n} symmetric positive definite system, "
                          f"random x, omega = {omega}",
                          (M @ M.T + n * np.eye(n), rng.normal(size=n), rng.normal(size=n),
                           omega)))
    return cases


SOR = Exercise(
    number="2.1", label="ch2-ex-sor-sweep", title="one SOR sweep",
    statement=(
        "**Implement it yourself.** Write `one_sor_sweep(A, b, x, omega)`, one sweep of SOR "
        "component by component, $i = 0, \\dots, n-1$: each $x_i$ is moved $\\omega$ times as "
        "far as Gauss-Seidel would move it, using the components already updated in this sweep. "
        "Leave the argument `x` unchanged (work on a copy) and return the new iterate. Compare "
        "it with the matrix form of the chapter, "
        "$(D - \\omega L)^{-1}[((1 - \\omega) D + \\omega U)\\,x + \\omega b]$."),
    reference=one_sor_sweep, cases=_sweep_cases,
    compare=lambda expected, got: close(expected, got, rtol=1e-12, atol=1e-13, what="x"),
    mistakes=(Mistake("a Jacobi sweep", "SOR uses the components already updated in this "
                      "sweep (x[j] for j < i), not the old ones.", _jacobi),
              Mistake("the relaxation without (1 - omega) x_i", "x_i becomes "
                      "(1 - omega) x_i + omega (b_i - sigma) / a_ii.", _unrelaxed_old_value),
              Mistake("an off-by-one sweep", "the sweep runs over every row, i = 0 to n - 1; "
                      "your last component is never updated.", _short_sweep),
              Mistake("a backward sweep", "sweep from the first row to the last.", _backward)),
    hint="with omega = 1 one SOR sweep is one Gauss-Seidel sweep: test that case first.")


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


def _freudenstein(theta_in, linkage):
    """Rows (cos theta1, cos theta3, 1) and b = cos(theta1 - theta3) of a crossed four-bar."""
    r1, r2, r3, r4 = linkage
    inputs = np.asarray(theta_in)
    I = np.column_stack((-r4 - r3 * np.cos(inputs), -r3 * np.sin(inputs)))
    d = np.hypot(*I.T)
    base = np.arctan2(I[:, 1], I[:, 0])
    outputs = base - np.arccos((r1 ** 2 + d ** 2 - r2 ** 2) / (2 * r1 * d))
    A = np.column_stack((np.cos(outputs), np.cos(inputs), np.ones_like(inputs)))
    return A, np.cos(outputs - inputs)


def _lstsq_cases():
    rng = np.random.default_rng(22)
    finger = (30.6, 7.0, 24.8, 7.0)  # a linkage of the chapter's size (mm)
    cases = []
    for width in (1.0, 0.01):
        A, b = _freudenstein(np.linspace(5.0, 5.0 + width, 13), finger)
        cases.append(Case(f"Freudenstein's 13 x 3 matrix of a finger four-bar, exact angles "
                          f"over {width} rad", (A, b)))
    A = rng.normal(size=(9, 4))
    cases.append(Case("a random 9 x 4 matrix and a b off its range", (A, rng.normal(size=9))))
    t = np.linspace(0.0, 1.0, 6)
    first = np.r_[1.0, np.full(5, 1e-8)]  # within 1e-8 of e_1: the sign decides
    cases.append(Case("a 6 x 3 matrix whose first column is within 1e-8 of e_1, its second "
                      "within 1e-4 of its first", (np.column_stack(
                          [first, first + 1e-4 * t, np.cos(3 * t)]), np.sin(2 * t) + 0.5)))
    return cases


LSTSQ = Exercise(
    number="2.2", label="ch2-ex-householder", title="least squares by Householder QR",
    statement=(
        "**Implement it yourself.** Write `lstsq_householder(A, b)`, the least-squares solution "
        "of $A x \\approx b$ by Householder QR: for each column $k$, a reflection "
        "$I - 2vv^{\\mathsf T}/v^{\\mathsf T}v$ zeroes the entries below the diagonal (choose the "
        "sign of $v_0$ that avoids cancellation: a column that is already nearly $e_1$ shows "
        "the difference), applied to $A$ and to $b$ alike; then solve "
        "$R x = (Q^{\\mathsf T} b)_{1..n}$ by back substitution. Do not form $Q$, and call "
        "none of numpy's or scipy's `qr`, `lstsq`, `pinv` and `svd`: the check runs your "
        "function with them unavailable. Try it on the chapter's narrow-range design, where "
        "the normal equations lose digits."),
    reference=lstsq_householder, cases=_lstsq_cases,
    forbidden=tuple(f"{module}.{name}" for module in ("numpy.linalg", "scipy.linalg")
                    for name in ("qr", "lstsq", "pinv", "svd")),
    compare=lambda expected, got: close(expected, got, rtol=1e-7, atol=1e-10, what="x"),
    mistakes=(Mistake("the normal equations", "A^T A squares the condition number: on a narrow "
                      "range of angles (cond(A) ~ 5e5) it loses about ten digits, QR about "
                      "five.", _normal_equations),
              Mistake("b left without its reflections", "apply every reflection to b as well "
                      "(Q^T b), then solve R x = (Q^T b)[:n].", _no_qt),
              Mistake("a transposed R", "R is upper triangular: back substitution from the "
                      "last row up, with R, not R.T.", _transposed_r),
              Mistake("the cancelling sign", "v_0 = x_0 + sign(x_0) ||x||: with the other sign "
                      "v_0 is the difference of two nearly equal numbers when x is nearly "
                      "e_1, and the reflection loses its digits.", _cancelling)),
    hint="check that your reflections zero each column below the diagonal, and that A^T (A x "
         "- b) is near zero.")
