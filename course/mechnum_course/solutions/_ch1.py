"""Chapter 1: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


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


SOLUTIONS = {
    "1.1": Solution(loop_equations, {"the report's typo": _typo,
                                     "a transposed Jacobian": _transposed,
                                     "a sign": _cosine_sign},
                    forbidden=("mechnum.mechanisms.hacksaw.position_residual",
                               "mechnum.mechanisms.hacksaw.position_jacobian")),
    "1.2": Solution(newton_study, {"a stopping test on the residual": _residual_test,
                                   "an uncounted last step": _uncounted,
                                   "a transposed Jacobian": _transposed_solve},
                    forbidden=("mechnum.newton.solve", "scipy.optimize.fsolve",
                               "scipy.optimize.root")),
}
