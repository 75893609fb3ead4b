"""Chapter 1, Newton on the power hacksaw: the loop equations with their Jacobian (1.1), and
Newton's method with the study's stopping test (1.2)."""

import numpy as np

from mechnum.exercises._harness import Case, Exercise, Mistake, close

STUDY = (0.045, 0.075, 0.17)  # the study's r1y, r2, r3 (m)


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
    r1, theta1, theta3 = q
    s1, c1 = np.sin(theta1), np.cos(theta1)
    s3, c3 = np.sin(theta3), np.cos(theta3)
    F = np.array([r1 * s1 - r1y,
                  -r1 * c1 + r2 * np.cos(theta2) + r3 * c3,
                  r1 * s1 - r2 * np.sin(theta2) - r3 * s3])
    J = np.array([[s1, r1 * c1, 0.0],
                  [-c1, r1 * s1, -r3 * s3],
                  [s1, r1 * c1, -r3 * c3]])
    return F, J


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
    x = np.array(x0, dtype=float)
    for k in range(1, maxiter + 1):
        dx = np.linalg.solve(J(x), -F(x))
        x = x + dx
        if np.linalg.norm(dx) < tol:
            return x, k
    raise RuntimeError(f"no step below {tol} in {maxiter} steps")


# Typical mistakes of 1.1
def _typo(q, theta2, r1y, r2, r3):
    F, J = loop_equations(q, theta2, r1y, r2, r3)
    F[1] += r3 * (np.cos(theta2) - np.cos(q[2]))
    F[2] -= r3 * (np.sin(theta2) - np.sin(q[2]))
    return F, J


def _transposed(q, theta2, r1y, r2, r3):
    F, J = loop_equations(q, theta2, r1y, r2, r3)
    return F, J.T


def _cosine_sign(q, theta2, r1y, r2, r3):
    F, J = loop_equations(q, theta2, r1y, r2, r3)
    J[1, 1] = -J[1, 1]
    return F, J


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
    reference=loop_equations, cases=_loop_cases, compare=_loop_compare,
    mistakes=(Mistake("the report's typo", "F_x and F_y need r3 cos(theta3) and r3 sin(theta3); "
                      "the report prints theta2 there.", _typo),
              Mistake("a transposed Jacobian", "row i of J holds the derivatives of F_i, column j "
                      "those with respect to q_j; yours is J transposed.", _transposed),
              Mistake("a sign", "d/dtheta1 of -r1 cos(theta1) is +r1 sin(theta1).",
                      _cosine_sign)),
    hint="compare your J with forward differences of your F, column by column.")


# Typical mistakes of 1.2
def _residual_test(F, J, x0, tol=1e-6, maxiter=50):
    x = np.array(x0, dtype=float)
    for k in range(maxiter):
        if np.linalg.norm(F(x)) < tol:
            return x, k
        x = x + np.linalg.solve(J(x), -F(x))
    raise RuntimeError("no convergence")


def _uncounted(F, J, x0, tol=1e-6, maxiter=50):
    x, k = newton_study(F, J, x0, tol, maxiter)
    return x, k - 1


def _transposed_solve(F, J, x0, tol=1e-6, maxiter=50):
    return newton_study(F, lambda x: J(x).T, x0, tol, maxiter)


def _newton_cases():
    def hacksaw(theta2, geometry=STUDY):
        return (lambda q: loop_equations(q, theta2, *geometry)[0],
                lambda q: loop_equations(q, theta2, *geometry)[1])
    two = (lambda x: np.array([x[0] ** 2 + x[0] * x[1] - 3.0, np.exp(x[0] - 1) + x[1] ** 3 - 9.0]),
           lambda x: np.array([[2 * x[0] + x[1], x[0]], [np.exp(x[0] - 1), 3 * x[1] ** 2]]))
    seed = np.array([-0.1, -0.5, 3.0])
    return [Case("the hacksaw at rest from the study's seed, tol = 1e-6",
                 (*hacksaw(0.0), seed, 1e-6, 50)),
            Case("the hacksaw at theta2 = 2 rad from the study's seed, tol = 1e-10",
                 (*hacksaw(2.0), seed, 1e-10, 50)),
            Case("a saw with r3 = 0.13 m at theta2 = -1 rad, tol = 1e-8",
                 (*hacksaw(-1.0, (0.045, 0.075, 0.13)), seed, 1e-8, 50)),
            Case("a 2 x 2 system with a non-symmetric Jacobian from (1.5, 1.5), tol = 1e-9",
                 (*two, np.array([1.5, 1.5]), 1e-9, 50))]


def _newton_probes():  # one step only, on the 2 x 2 system: where each mistake shows
    return [Case("one step", (*_newton_cases()[-1].args[:3], np.inf, 1))]


def _newton_compare(expected, got):
    x, k = got
    if int(k) != expected[1]:
        return f"{int(k)} iterations, expected {expected[1]}"
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
    reference=newton_study, cases=_newton_cases, compare=_newton_compare,
    probes=_newton_probes,
    mistakes=(Mistake("a stopping test on the residual", "the study stops on the step "
                      "||dx|| < tol, tested after the step is taken, not on ||F(x)||.",
                      _residual_test),
              Mistake("an uncounted last step", "the step that passes the test is taken and "
                      "counted.", _uncounted),
              Mistake("a transposed Jacobian", "solve J(x) dx = -F(x) with J itself, not J.T.",
                      _transposed_solve)),
    hint="print ||dx|| at each step and compare with the chapter's table at rest; check the "
         "sign of the step (x + dx with J dx = -F).")
