"""Chapter 1: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


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


ARMIJO, HALVINGS = 1e-4, 20  # the statement's rule: lambda = 1, 1/2, ..., 2**-20


def newton_damped(F, J, x0, tol=1e-6, maxiter=50):
    """Newton's method with Armijo's backtracking and the study's stop.

    Returns ``(x, iterations)``: the iterate after the first Newton step
    shorter than ``tol``, and the steps taken. Raises ``RuntimeError``
    after ``maxiter`` steps, or when no step length passes Armijo's test.
    """
    x = np.array(x0, dtype=float)
    size = np.linalg.norm(F(x))
    for k in range(1, maxiter + 1):
        dx = np.linalg.solve(J(x), -F(x))
        for lam in 0.5 ** np.arange(21):  # 1, 1/2, ..., 2**-20
            trial = np.linalg.norm(F(x + lam * dx))
            if trial <= (1 - 1e-4 * lam) * size:  # Armijo's test
                break
        else:
            raise RuntimeError(f"no step length passes at step {k}")
        x, size = x + lam * dx, trial
        if np.linalg.norm(dx) < tol:  # the study's test, on Newton's step
            return x, k
    raise RuntimeError(f"no Newton step below {tol} in {maxiter} steps")


def broyden_inverse_update(H, s, y):
    """The inverse of ``B + (y - B s) s^T / (s^T s)``, given ``H = B^-1``,
    the step ``s`` and the change ``y`` of ``F`` along it."""
    Hy = H @ y  # H times the change of F
    sH = s @ H  # the row vector s^T H
    denominator = s @ Hy  # s^T H y
    return H + np.outer(s - Hy, sH) / denominator  # Sherman-Morrison


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
def _plain(F, J, x0, tol=1e-6, maxiter=50):  # the chapter's ten lines, without damping
    x = np.array(x0, dtype=float)
    for k in range(1, maxiter + 1):
        dx = np.linalg.solve(J(x), -F(x))
        x = x + dx
        if np.linalg.norm(dx) < tol:
            return x, k
    raise RuntimeError("maxiter")


def _damped_variant(test="full", armijo=ARMIJO):
    def variant(F, J, x0, tol=1e-6, maxiter=50):
        x = np.array(x0, dtype=float)
        size = np.linalg.norm(F(x))
        for k in range(1, maxiter + 1):
            dx = np.linalg.solve(J(x), -F(x))
            for lam in 0.5 ** np.arange(HALVINGS + 1):
                trial = np.linalg.norm(F(x + lam * dx))
                if trial <= (1 - armijo * lam) * size:
                    break
            else:
                raise RuntimeError("stagnated")
            x, size = x + lam * dx, trial
            if (np.linalg.norm(lam * dx) if test == "damped" else
                    size if test == "residual" else np.linalg.norm(dx)) < tol:
                return x, k
        raise RuntimeError("maxiter")
    return variant


def _uncounted(F, J, x0, tol=1e-6, maxiter=50):
    x, k = newton_damped(F, J, x0, tol, maxiter)
    return x, k - 1


# Typical mistakes of 1.3
def _bad_broyden(H, s, y):  # Broyden's other ("bad") update: not the inverse of the chapter's
    return H + np.outer(s - H @ y, y) / (y @ y)


def _without_h(H, s, y):
    return H + np.outer(s - H @ y, s) / (s @ H @ y)


def _direct(H, s, y):  # the chapter's update of B, applied to H
    return H + np.outer(y - H @ s, s) / (s @ s)


SOLUTIONS = {
    "1.1": Solution(loop_equations, {"the report's typo": _typo,
                                     "a transposed Jacobian": _transposed,
                                     "a sign": _cosine_sign},
                    forbidden=("mechnum.mechanisms.hacksaw.position_residual",
                               "mechnum.mechanisms.hacksaw.position_jacobian")),
    "1.2": Solution(newton_damped, {"no damping": _plain,
                                    "the test on the damped step": _damped_variant("damped"),
                                    "a stopping test on the residual":
                                        _damped_variant("residual"),
                                    "plain decrease for Armijo's test":
                                        _damped_variant(armijo=0.0),
                                    "an uncounted last step": _uncounted},
                    forbidden=("mechnum.newton.solve", "scipy.optimize.fsolve",
                               "scipy.optimize.root")),
    "1.3": Solution(broyden_inverse_update, {"Broyden's other update": _bad_broyden,
                                             "s^T for s^T H": _without_h,
                                             "the update of B applied to H": _direct},
                    forbidden=("mechnum.newton.broyden",)),
}
