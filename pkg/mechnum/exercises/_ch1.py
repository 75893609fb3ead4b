"""Chapter 1, Newton on the power hacksaw: the loop equations with their Jacobian (1.1),
Newton's method with Armijo's backtracking and the study's stopping test (1.2), and Broyden's
update of the inverse matrix (1.3)."""

import numpy as np

from mechnum.exercises._answers import Array, Integer, Tuple, close
from mechnum.exercises._harness import Case, Exercise, Mistake
from mechnum.mechanisms import hacksaw

STUDY = (0.045, 0.075, 0.17)  # the study's r1y, r2, r3 (m)

LOOP_STARTER = '''\
def loop_equations(q, theta2, r1y, r2, r3):
    """The hacksaw's three position equations and their Jacobian.

    Parameters
    ----------
    q : ndarray, shape (3,)
        The unknowns ``(r1, theta1, theta3)`` (m, rad, rad).
    theta2, r1y, r2, r3 : float
        The crank angle (rad); the guide's height, crank, coupler (m).

    Returns
    -------
    F, J : ndarray, shapes (3,) and (3, 3)
        ``(F_c, F_x, F_y)`` in the chapter's order; ``J[i, j] = dF_i/dq_j``.
    """
    ...
'''

NEWTON_STARTER = '''\
def newton_damped(F, J, x0, tol=1e-6, maxiter=50):
    """Newton's method with Armijo's backtracking and the study's stop.

    Returns ``(x, iterations)``: the iterate after the first Newton step
    shorter than ``tol``, and the steps taken. Raises ``RuntimeError``
    after ``maxiter`` steps, or when no step length passes Armijo's test.
    """
    ...
'''

UPDATE_STARTER = '''\
def broyden_inverse_update(H, s, y):
    """The inverse of ``B + (y - B s) s^T / (s^T s)``, given ``H = B^-1``,
    the step ``s`` and the change ``y`` of ``F`` along it."""
    ...
'''


def _loop_cases():
    rng = np.random.default_rng(11)
    cases = [Case("the study's seed at rest, q = (-0.1, -0.5, 3), theta2 = 0",
                  (np.array([-0.1, -0.5, 3.0]), 0.0, *STUDY))]
    for k in range(4):
        q = rng.uniform([-0.3, -np.pi, -np.pi], [0.3, np.pi, np.pi])
        geometry = rng.uniform([0.02, 0.05, 0.12], [0.06, 0.1, 0.2])
        cases.append(Case(f"random state {k + 1} of a random saw",
                          (q, float(rng.uniform(-np.pi, np.pi)), *geometry)))
    return cases


def _loop_compare(expected, got):
    F, J = got
    return (close(expected[0], F, rtol=1e-12, atol=1e-14, what="F")
            or close(expected[1], J, rtol=1e-12, atol=1e-14, what="J"))


LOOP = Exercise(
    number="1.1", label="ch1-ex-loop-equations", title="the loop equations and their Jacobian",
    statement=(
        "**Implement it yourself.** Write `loop_equations(q, theta2, r1y, r2, r3)`, which returns "
        "the three position equations $F = (F_c, F_x, F_y)$ of the hacksaw at "
        "$q = (r_1, \\theta_1, \\theta_3)$, as the chapter writes them (with $r_3$, not the "
        "report's $r_3\\cos\\theta_2$), and their Jacobian $J_{ij} = \\partial F_i/\\partial q_j$ "
        "by hand. Check your $J$ against forward differences of your $F$ before you run the "
        "check."),
    starter=LOOP_STARTER, cases=_loop_cases, compare=_loop_compare,
    returns=Tuple(Array(), Array(), names=("F", "J")),
    mistakes=(Mistake("the report's typo", "F_x and F_y need r3 cos(theta3) and r3 sin(theta3); "
                      "the report prints theta2 there."),
              Mistake("a transposed Jacobian", "row i of J holds the derivatives of F_i, column j "
                      "those with respect to q_j; yours is J transposed."),
              Mistake("a sign", "d/dtheta1 of -r1 cos(theta1) is +r1 sin(theta1).")),
    hint="compare your J with forward differences of your F, column by column.")


def _newton_cases():
    def saw(theta2, geometry=STUDY):  # the package's loop equations, not the exercise's
        mech = hacksaw.Geometry(*geometry)
        return (lambda q: hacksaw.position_residual(mech, q, theta2),
                lambda q: hacksaw.position_jacobian(mech, q))
    two = (lambda x: np.array([x[0] ** 2 + x[0] * x[1] - 3.0, np.exp(x[0] - 1) + x[1] ** 3 - 9.0]),
           lambda x: np.array([[2 * x[0] + x[1], x[0]], [np.exp(x[0] - 1), 3 * x[1] ** 2]]))
    no_root = (lambda x: np.array([x[0] ** 2 + 1.0, x[1]]),
               lambda x: np.array([[2 * x[0], 0.0], [0.0, 1.0]]))
    seed, leap = np.array([-0.1, -0.5, 3.0]), np.array([-0.1, -0.45, 1.82])
    return [Case("the hacksaw at rest from the study's seed, tol = 1e-6",
                 (*saw(0.0), seed, 1e-6, 50)),
            Case("the hacksaw at rest from (-0.1, -0.45, 1.82), where undamped Newton leaps to "
                 "the other assembly mode, tol = 1e-6", (*saw(0.0), leap, 1e-6, 50)),
            Case("the same start with a loose tol = 1, where the first step is damped to a "
                 "quarter of Newton's", (*saw(0.0), leap, 1.0, 50)),
            Case("the hacksaw at theta2 = 2 rad from the study's seed, tol = 1e-10",
                 (*saw(2.0), seed, 1e-10, 50)),
            Case("a 2 x 2 system with a non-symmetric Jacobian from (1.5, 1.5), tol = 1e-9",
                 (*two, np.array([1.5, 1.5]), 1e-9, 50)),
            Case("the hacksaw at rest from the study's seed with maxiter = 2 (it needs 4 steps)",
                 (*saw(0.0), seed, 1e-6, 2)),
            Case("F(x) = (x_0^2 + 1, x_1), which has no root, from (0.75, 1)",
                 (*no_root, np.array([0.75, 1.0]), 1e-6, 50))]


def _newton_probes():  # one step only, on the 2 x 2 system: where each mistake shows
    return [Case("one step", (*_newton_cases()[4].args[:3], np.inf, 1))]


def _newton_compare(expected, got):
    x, k = got
    if k != expected[1]:
        return f"{k} iterations, expected {expected[1]}"
    return close(expected[0], x, rtol=1e-9, atol=1e-12, what="x")


NEWTON = Exercise(
    number="1.2", label="ch1-ex-newton-damped",
    title="damped Newton with the study's stopping test",
    statement=(
        "**Implement it yourself.** Write `newton_damped(F, J, x0, tol, maxiter)`, the rescue "
        "of the chapter's basins: Newton's step $\\Delta x_k$ solves "
        "$J(x_k)\\,\\Delta x_k = -F(x_k)$, and $x_{k+1} = x_k + \\lambda\\Delta x_k$ takes the "
        "first $\\lambda = 1, \\frac12, \\frac14, \\dots, 2^{-20}$ that passes Armijo's test "
        "$\\|F(x_k + \\lambda\\Delta x_k)\\|_2 \\le (1 - 10^{-4}\\lambda)\\,\\|F(x_k)\\|_2$. Stop "
        "by the study's rule, after the first Newton step with $\\|\\Delta x_k\\|_2 <$ `tol` "
        "(that step counted), and return the iterate after it and the number of steps. Raise "
        "`RuntimeError` when no $\\lambda$ passes, and after `maxiter` steps. From the start of "
        "the chapter's figure where plain Newton leaves the study's mode, yours must reach the "
        "study's pose, as `newton.solve(..., damping=True)` does."),
    starter=NEWTON_STARTER, cases=_newton_cases, compare=_newton_compare,
    returns=Tuple(Array(), Integer(), names=("x", "the number of steps")),
    probes=_newton_probes,
    mistakes=(Mistake("no damping", "this is the chapter's undamped loop: halve the step until "
                      "Armijo's test holds before you take it."),
              Mistake("the test on the damped step", "test Newton's full step dx, not the "
                      "shortened lambda dx: a short damped step does not mean convergence."),
              Mistake("a stopping test on the residual", "the study stops on Newton's full "
                      "step, ||dx|| < tol, not on ||F(x)||."),
              Mistake("plain decrease for Armijo's test", "Armijo asks for a decrease of at "
                      "least 1e-4 lambda ||F||, not any decrease."),
              Mistake("an uncounted last step", "the step that passes the test is taken and "
                      "counted.")),
    hint="print lambda, ||F|| and ||dx|| at each step and compare with newton.solve(F, x0, J, "
         "tol=tol, relative=False, damping=True).")


def _update_cases():
    rng = np.random.default_rng(13)
    mech, x0 = hacksaw.Geometry(*STUDY), np.array([-0.1, -0.5, 3.0])
    F, B = hacksaw.position_residual(mech, x0, 0.0), hacksaw.position_jacobian(mech, x0)
    s = -np.linalg.solve(B, F)
    y = hacksaw.position_residual(mech, x0 + s, 0.0) - F
    cases = [Case("the hacksaw's first Broyden step at rest, from the study's seed",
                  (np.linalg.inv(B), s, y))]
    for n in (2, 4):
        B = rng.normal(size=(n, n)) + n * np.eye(n)
        cases.append(Case(f"a random {n} x {n} matrix, step and change",
                          (np.linalg.inv(B), rng.normal(size=n), rng.normal(size=n))))
    return cases


UPDATE = Exercise(
    number="1.3", label="ch1-ex-broyden-inverse", title="Broyden's update of the inverse",
    statement=(
        "**Implement it yourself.** Broyden's method solves $B_k\\,\\Delta x = -F(x_k)$ at "
        "every step. With $H_k = B_k^{-1}$ at hand, a step is a product, "
        "$\\Delta x = -H_k F(x_k)$, and needs no solve. Write "
        "`broyden_inverse_update(H, s, y)`, which returns the inverse of the chapter's "
        "$B + (y - Bs)\\,s^{\\mathsf T}/(s^{\\mathsf T}s)$ given $H = B^{-1}$, in $O(n^2)$ "
        "operations and without inverting or solving anything (the check runs your function "
        "without `inv`, `solve`, `pinv` and `lstsq`): derive it by the Sherman-Morrison "
        "formula, $(A + uv^{\\mathsf T})^{-1} = A^{-1} - A^{-1}u\\,v^{\\mathsf T}"
        "A^{-1}/(1 + v^{\\mathsf T}A^{-1}u)$. Then check the secant condition "
        "$H_{k+1}\\,y = s$ on your answer."),
    starter=UPDATE_STARTER, cases=_update_cases,
    compare=lambda expected, got: close(expected, got, rtol=1e-9, atol=1e-12,
                                        what="the updated inverse"),
    returns=Array(),
    forbidden=tuple(f"{module}.{name}" for module in ("numpy.linalg", "scipy.linalg")
                    for name in ("inv", "solve", "pinv", "lstsq")),
    mistakes=(Mistake("Broyden's other update", "H + (s - H y) y^T / (y^T y) is the 'bad' "
                      "Broyden update, a different method: yours must be the inverse of the "
                      "chapter's B update, whose row vector is s^T H."),
              Mistake("s^T for s^T H", "Sherman-Morrison puts A^{-1} on both sides: the row "
                      "vector is s^T H, and the denominator s^T H y."),
              Mistake("the update of B applied to H", "(y - B s) s^T / (s^T s) updates B; "
                      "its inverse updates H by (s - H y) s^T H / (s^T H y).")),
    hint="check that H_new @ y equals s, and that H_new @ B_new is the identity for a small "
         "example with B_new = inv(H) updated by the chapter's formula.")
