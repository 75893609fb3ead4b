"""Chapter 1, Newton on the power hacksaw: the loop equations with their Jacobian (1.1), and
Newton's method with the study's stopping test (1.2)."""

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
    theta2 : float
        The crank angle (rad).
    r1y, r2, r3 : float
        The guide's height, the crank and the coupler (m).

    Returns
    -------
    F : ndarray, shape (3,)
        ``(F_c, F_x, F_y)``, in the chapter's order.
    J : ndarray, shape (3, 3)
        ``J[i, j] = dF_i / dq_j``.
    """
    ...
'''

NEWTON_STARTER = '''\
def newton_study(F, J, x0, tol=1e-6, maxiter=50):
    """Newton's method, stopped by the study's rule.

    Parameters
    ----------
    F, J : callable
        The residual ``F(x)``, shape (n,), and its Jacobian ``J(x)``,
        shape (n, n).
    x0 : ndarray, shape (n,)
        The seed.
    tol : float
        Stop after the first step whose 2-norm is below ``tol``.
    maxiter : int
        At most this many steps.

    Returns
    -------
    x : ndarray, shape (n,)
        The iterate after the step that passed the test.
    iterations : int
        The number of steps taken, that step included.

    Raises
    ------
    RuntimeError
        If no step passes the test within ``maxiter`` steps.
    """
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
    seed = np.array([-0.1, -0.5, 3.0])
    return [Case("the hacksaw at rest from the study's seed, tol = 1e-6",
                 (*saw(0.0), seed, 1e-6, 50)),
            Case("the hacksaw at theta2 = 2 rad from the study's seed, tol = 1e-10",
                 (*saw(2.0), seed, 1e-10, 50)),
            Case("a saw with r3 = 0.13 m at theta2 = -1 rad, tol = 1e-8",
                 (*saw(-1.0, (0.045, 0.075, 0.13)), seed, 1e-8, 50)),
            Case("a 2 x 2 system with a non-symmetric Jacobian from (1.5, 1.5), tol = 1e-9",
                 (*two, np.array([1.5, 1.5]), 1e-9, 50))]


def _newton_probes():  # one step only, on the 2 x 2 system: where each mistake shows
    return [Case("one step", (*_newton_cases()[-1].args[:3], np.inf, 1))]


def _newton_compare(expected, got):
    x, k = got
    if k != expected[1]:
        return f"{k} iterations, expected {expected[1]}"
    return close(expected[0], x, rtol=1e-9, atol=1e-12, what="x")


NEWTON = Exercise(
    number="1.2", label="ch1-ex-newton-study",
    title="Newton's method with the study's stopping test",
    statement=(
        "**Implement it yourself.** Write `newton_study(F, J, x0, tol, maxiter)`: Newton's "
        "method that solves $J(x_k)\\,\\Delta x_k = -F(x_k)$ with `np.linalg.solve`, stops after "
        "the first step with $\\|\\Delta x_k\\|_2 <$ `tol` (the study's rule, that step counted) "
        "and returns the iterate after that step and the number of steps; it raises "
        "`RuntimeError` after `maxiter` steps. Run it on your `loop_equations` at rest from the "
        "study's seed: the chapter's table says how many steps to expect."),
    starter=NEWTON_STARTER, cases=_newton_cases, compare=_newton_compare,
    returns=Tuple(Array(), Integer(), names=("x", "the number of steps")),
    probes=_newton_probes,
    mistakes=(Mistake("a stopping test on the residual", "the study stops on the step "
                      "||dx|| < tol, tested after the step is taken, not on ||F(x)||."),
              Mistake("an uncounted last step", "the step that passes the test is taken and "
                      "counted."),
              Mistake("a transposed Jacobian", "solve J(x) dx = -F(x) with J itself, not J.T.")),
    hint="print ||dx|| at each step and compare with the chapter's table at rest; check the "
         "sign of the step (x + dx with J dx = -F).")
