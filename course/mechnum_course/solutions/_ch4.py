"""Chapter 4: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


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
    c = np.asarray(c, dtype=float)
    n = len(c) - 1
    M = np.zeros((n, n))
    M[1:, :-1] = np.eye(n - 1)
    M[:, -1] = -c[:-1] / c[-1]
    return M


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
    x, y, psi = pose
    angles = np.array([0.0, psi, psi + np.pi / 3])
    arms = g.a * np.column_stack((np.cos(angles), np.sin(angles)))
    arms[0] = 0.0  # P_1 = P
    vertices = np.array([x, y]) + arms
    sliders = np.array([[lam[0], 0.0], [g.B2 - lam[1], 0.0],
                        [g.B3, g.H3 - lam[2]]])
    u = vertices - sliders
    F = (u ** 2).sum(axis=1) - g.L ** 2
    n = np.column_stack((-arms[:, 1], arms[:, 0]))  # dP_i / dpsi
    J = 2 * np.column_stack((u, (u * n).sum(axis=1)))
    return np.asarray(pose, dtype=float) - np.linalg.solve(J, F)


# Typical mistakes of 4.1
def _not_divided(c):
    return companion(np.append(c[:-1], 1.0))


def _descending(c):
    return companion(np.asarray(c)[::-1])


def _sign(c):
    M = companion(c)
    M[:, -1] = -M[:, -1]
    return M



# Typical mistakes of 4.2
def _transposed_jacobian(pose, lam, g):
    F = _loop(pose, lam, g)
    J = np.column_stack([_loop(pose + 1e-30j * e, lam, g).imag / 1e-30 for e in np.eye(3)])
    return np.asarray(pose) - np.linalg.solve(J.T, F.real)


def _loop(pose, lam, g):
    x, y, psi = pose
    P = np.array([[x, y], [x + g.a * np.cos(psi), y + g.a * np.sin(psi)],
                  [x + g.a * np.cos(psi + np.pi / 3), y + g.a * np.sin(psi + np.pi / 3)]])
    C = np.array([[lam[0], 0.0], [g.B2 - lam[1], 0.0], [g.B3, g.H3 - lam[2]]])
    return ((P - C) ** 2).sum(axis=1) - g.L ** 2


def _no_factor_two(pose, lam, g):
    return 2 * prr3_newton_step(pose, lam, g) - np.asarray(pose)


def _plus(pose, lam, g):
    return 2 * np.asarray(pose) - prr3_newton_step(pose, lam, g)


SOLUTIONS = {
    "4.1": Solution(companion, {"no division by the leading coefficient": _not_divided,
                                "the coefficients in descending order": _descending,
                                "a sign": _sign},
                    forbidden=("mechnum.polynomials.companion", "mechnum.polynomials.roots",
                               "numpy.roots")),
    "4.2": Solution(prr3_newton_step, {"a transposed Jacobian": _transposed_jacobian,
                                       "the factor 2 of the Jacobian": _no_factor_two,
                                       "a sign": _plus},
                    forbidden=()),
}
