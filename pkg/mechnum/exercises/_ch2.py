"""Chapter 2, linear systems on the finger: one SOR sweep (2.1), and least squares by
Householder QR (2.2)."""

import numpy as np

from mechnum.exercises._answers import Array, close
from mechnum.exercises._harness import Case, Exercise, Mistake

SOR_STARTER = '''\
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
    ...
'''

LSTSQ_STARTER = '''\
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
    ...
'''


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
    starter=SOR_STARTER, cases=_sweep_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-12, atol=1e-13, what="x"),
    mistakes=(Mistake("a Jacobi sweep", "SOR uses the components already updated in this "
                      "sweep (x[j] for j < i), not the old ones."),
              Mistake("the relaxation without (1 - omega) x_i", "x_i becomes "
                      "(1 - omega) x_i + omega (b_i - sigma) / a_ii."),
              Mistake("an off-by-one sweep", "the sweep runs over every row, i = 0 to n - 1; "
                      "your last component is never updated."),
              Mistake("a backward sweep", "sweep from the first row to the last.")),
    hint="with omega = 1 one SOR sweep is one Gauss-Seidel sweep: test that case first.")


def freudenstein(theta_in, linkage):
    """Rows (cos theta1, cos theta3, 1) and b = cos(theta1 - theta3) of a crossed four-bar."""
    r1, r2, r3, r4 = linkage
    inputs = np.asarray(theta_in)
    I = np.column_stack((-r4 - r3 * np.cos(inputs), -r3 * np.sin(inputs)))
    d = np.hypot(*I.T)
    base = np.arctan2(I[:, 1], I[:, 0])
    outputs = base - np.arccos((r1 ** 2 + d ** 2 - r2 ** 2) / (2 * r1 * d))
    A = np.column_stack((np.cos(outputs), np.cos(inputs), np.ones_like(inputs)))
    return A, np.cos(outputs - inputs)


FINGER = (30.6, 7.0, 24.8, 7.0)  # a linkage of the chapter's size (mm)


TALL = 100_000
"""The height of 2.2's tall case: an m x m float matrix of this size needs 80 GB."""


def _lstsq_cases():
    rng = np.random.default_rng(22)
    cases = []
    for width in (1.0, 0.01):
        A, b = freudenstein(np.linspace(5.0, 5.0 + width, 13), FINGER)
        cases.append(Case(f"Freudenstein's 13 x 3 matrix of a finger four-bar, exact angles "
                          f"over {width} rad", (A, b)))
    t = np.linspace(-1.0, 1.0, TALL)  # an m x m Q of this height would take 80 GB
    cases.append(Case(f"a {TALL} x 3 matrix (1, t, t^2): Q and the reflections must not be "
                      "formed", (np.column_stack([np.ones_like(t), t, t * t]), np.cos(2 * t))))
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
        "$R x = (Q^{\\mathsf T} b)_{1..n}$ by back substitution. Unlike "
        "`householder_qr`, form no $m \\times m$ matrix: one case is $100\\,000 \\times 3$. "
        "The check runs it with numpy's and scipy's `qr`, `lstsq`, `pinv` and `svd` "
        "unavailable. Try it on the chapter's narrow-range design, where the normal "
        "equations lose digits."),
    starter=LSTSQ_STARTER, cases=_lstsq_cases, returns=Array(),
    forbidden=tuple(f"{module}.{name}" for module in ("numpy.linalg", "scipy.linalg")
                    for name in ("qr", "lstsq", "pinv", "svd")),
    compare=lambda expected, got: close(expected, got, rtol=1e-7, atol=1e-10, what="x"),
    mistakes=(Mistake("the normal equations", "A^T A squares the condition number: on a narrow "
                      "range of angles (cond(A) ~ 5e5) it loses about ten digits, QR about "
                      "five."),
              Mistake("b left without its reflections", "apply every reflection to b as well "
                      "(Q^T b), then solve R x = (Q^T b)[:n]."),
              Mistake("a transposed R", "R is upper triangular: back substitution from the "
                      "last row up, with R, not R.T."),
              Mistake("the cancelling sign", "v_0 = x_0 + sign(x_0) ||x||: with the other sign "
                      "v_0 is the difference of two nearly equal numbers when x is nearly "
                      "e_1, and the reflection loses its digits.")),
    hint="check that your reflections zero each column below the diagonal, and that A^T (A x "
         "- b) is near zero.")
