"""Chapter 4, the rigid 3PRR: the companion matrix of a polynomial (4.1), and one Newton step on
the mechanism's three loop equations (4.2)."""

from types import SimpleNamespace

import numpy as np

from mechnum.exercises._answers import Array, close
from mechnum.exercises._harness import Case, Exercise, Mistake

COMPANION_STARTER = '''\
def companion(c):
    """The companion matrix of a polynomial: its eigenvalues are the roots.

    Parameters
    ----------
    c : ndarray, shape (n + 1,)
        The coefficients ``c_0, ..., c_n`` in ascending powers of ``t`` (as
        ``prr3.polynomial`` returns them), ``c_n != 0``.

    Returns
    -------
    ndarray, shape (n, n)
        Ones below the diagonal and ``-c_k / c_n`` in the last column.
    """
    ...
'''

NEWTON_STEP_STARTER = '''\
def prr3_newton_step(pose, lam, g):
    """One Newton step on the 3PRR's loop equations.

    Parameters
    ----------
    pose : ndarray, shape (3,)
        The current iterate ``(x, y, psi)``: the vertex ``P_1`` (m) and the
        platform's angle (rad).
    lam : ndarray, shape (3,)
        The inputs ``(lambda_1, lambda_2, lambda_3)`` (m).
    g : object
        The geometry, with attributes ``a, L, B2, B3, H3`` (m), as
        ``prr3.Geometry``.

    Returns
    -------
    ndarray, shape (3,)
        The next iterate of ``F_i = |P_i - C_i|^2 - L^2 = 0``.
    """
    ...
'''


def _companion_cases():
    return [Case("(t - 1)(t + 2)(t - 3) times 4", (4 * np.poly([1.0, -2.0, 3.0])[::-1],)),
            Case("(t^2 + 1)(t - 0.5)(t + 3)(t - 2) times -2.5",
                 (-2.5 * np.poly([1j, -1j, 0.5, -3.0, 2.0]).real[::-1],)),
            Case("a degree-8 polynomial with the roots 0.1, -0.7, 1.3, -2, 2.5, 3 +- 0.5i, "
                 "-4 times 7", (7 * np.poly([0.1, -0.7, 1.3, -2, 2.5, 3 + 0.5j, 3 - 0.5j,
                                             -4]).real[::-1],))]


def _eigenvalues_compare(expected, got):
    if got.shape != expected.shape:
        return f"the matrix has shape {got.shape}, expected {expected.shape}"
    want, have = (np.sort_complex(np.linalg.eigvals(M)) for M in (expected, got))
    return close(want.real, have.real, rtol=1e-8, atol=1e-10,
                 what="the real parts of the sorted eigenvalues") or close(
        want.imag, have.imag, rtol=1e-8, atol=1e-10,
        what="the imaginary parts of the sorted eigenvalues")


COMPANION = Exercise(
    number="4.1", label="ch4-ex-companion", title="the companion matrix",
    statement=(
        "**Implement it yourself.** Write `companion(c)`, the companion matrix of the polynomial "
        "$\\sum_{k=0}^n c_k t^k$ with coefficients in ascending powers (the order of "
        "`prr3.polynomial`): ones below the diagonal and $-c_k/c_n$ in the last column. Show "
        "that its characteristic polynomial is the polynomial divided by $c_n$, and compare "
        "its eigenvalues with `np.roots(c[::-1])` on the degree-8 polynomial of Table 6."),
    starter=COMPANION_STARTER, cases=_companion_cases, compare=_eigenvalues_compare,
    returns=Array(),
    mistakes=(Mistake("no division by the leading coefficient", "the last column is "
                      "-c_k / c_n: the eigenvalues are the roots only of the monic polynomial."),
              Mistake("the coefficients in descending order", "c[0] is the constant term; "
                      "read in reverse, you get the reciprocals of the roots."),
              Mistake("a sign", "the last column holds -c_k / c_n, with the minus.")),
    hint="expand det(tI - M) along the last column for n = 2 by hand.")


def _newton_cases():
    first = SimpleNamespace(a=0.3, L=1.0, B2=2.0, B3=2.5, H3=1.5)
    other = SimpleNamespace(a=0.5, L=1.2, B2=3.0, B3=2.0, H3=2.0)
    return [Case("a mechanism with a = 0.3, L = 1 m from the pose (0.6, 0.7, 0.2)",
                 (np.array([0.6, 0.7, 0.2]), np.array([1.2, 0.5, 0.4]), first)),
            Case("the same mechanism from the pose (1.0, 0.5, -0.4)",
                 (np.array([1.0, 0.5, -0.4]), np.array([0.3, 0.9, 1.1]), first)),
            Case("a mechanism with a = 0.5, L = 1.2 m from the pose (0.8, 0.9, 2.5)",
                 (np.array([0.8, 0.9, 2.5]), np.array([0.5, 1.0, 0.7]), other))]


STEP_RTOL, STEP_ATOL = 1e-5, 1e-6
"""4.2's tolerance on the next pose: a forward-difference Jacobian with a step h between 1e-9
and 1e-6 errs by about h |F''| / 2 + eps |F| / h, which moves the next pose of the cases by
less than 0.7 of this tolerance (tests/test_exercises.py measures it); each typical mistake
moves it by more than 1e5 times the tolerance."""


PRR3_NEWTON = Exercise(
    number="4.2", label="ch4-ex-newton-step", title="one Newton step on the 3PRR",
    statement=(
        "**Implement it yourself.** Write `prr3_newton_step(pose, lam, g)`, one Newton step on "
        "the three loop equations $F_i(x, y, \\psi) = |P_i - C_i|^2 - L^2$ of the chapter, with "
        "the Jacobian by hand: row $i$ is $2\\,(u_i,\\ u_i\\cdot n_i)$ with $u_i = P_i - C_i$ "
        "and $n_i = \\partial P_i/\\partial\\psi$ (forward differences with a step between "
        "$10^{-9}$ and $10^{-6}$ move the step by less than the check's tolerance, $10^{-5}$ of "
        "the pose). Iterate it from a pose near one of Table 6's and watch the residual square "
        "at each step; compare the limit with `prr3.forward`."),
    starter=NEWTON_STEP_STARTER, cases=_newton_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=STEP_RTOL, atol=STEP_ATOL,
                                        what="the next pose"),
    mistakes=(Mistake("a transposed Jacobian", "row i of J holds the derivatives of F_i; solve "
                      "J d = -F with J, not J.T."),
              Mistake("the factor 2 of the Jacobian", "d/dx |u|^2 = 2 u_x: without the 2 the "
                      "step is twice Newton's and the iteration no longer converges "
                      "quadratically."),
              Mistake("a sign", "the step is pose - J^{-1} F.")),
    hint="check your Jacobian against forward differences of F, column by column.")
