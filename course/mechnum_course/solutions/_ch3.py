"""Chapter 3: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


def rk4_step(f, s, y, h):
    """One step of the classical Runge-Kutta method of order 4.

    Parameters
    ----------
    f : callable
        The right-hand side, ``f(s, y)`` -> ndarray of the shape of ``y``.
    s : float
        The independent variable at the start of the step.
    y : ndarray
        The state at ``s``.
    h : float
        The step.

    Returns
    -------
    ndarray
        The state at ``s + h``.
    """
    k1 = f(s, y)
    k2 = f(s + h / 2, y + h / 2 * k1)
    k3 = f(s + h / 2, y + h / 2 * k2)
    k4 = f(s + h, y + h * k3)
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


def pinned_residual(q, EI, L, target, nodes):
    """The shooting residual of a rod clamped along +x, its tip pinned.

    Parameters
    ----------
    q : ndarray, shape (3,)
        The unknowns ``(m0, n_x, n_y)``: the clamp moment (N m) and the
        tip force (N).
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    target : ndarray, shape (2,)
        Where the tip is pinned (m).
    nodes : int
        RK4 on ``nodes`` equally spaced nodes from ``s = 0`` to ``s = L``
        (``nodes - 1`` steps).

    Returns
    -------
    ndarray, shape (3,)
        ``(x(L) - x_t, y(L) - y_t, m(L))``.
    """
    m0, nx, ny = q

    def f(s, y):  # the study's (78): y = (x, y, theta, m)
        return np.array([np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                         nx * np.sin(y[2]) - ny * np.cos(y[2])])

    y, h = np.array([0.0, 0.0, 0.0, m0]), L / (nodes - 1)
    for i in range(nodes - 1):
        y = rk4_step(f, i * h, y, h)
    return np.array([y[0] - target[0], y[1] - target[1], y[3]])


# Typical mistakes of 3.1
def _variant(at=(0.0, 0.5, 0.5, 1.0), start=(0.5, 0.5, 1.0), k3_from=1, weights=(1, 2, 2, 1)):
    def step(f, s, y, h):
        k = [f(s + at[0] * h, y)]
        for stage in (1, 2, 3):
            slope = k[k3_from] if stage == 2 else k[stage - 1]
            k.append(f(s + at[stage] * h, y + start[stage - 1] * h * slope))
        return y + h * sum(w * kk for w, kk in zip(weights, k)) / sum(weights)
    return step



# Typical mistakes of 3.2
def _moment_sign(q, EI, L, target, nodes):
    return pinned_residual((q[0], -q[1], -q[2]), EI, L, target, nodes)


def _target_minus_tip(q, EI, L, target, nodes):
    r = pinned_residual(q, EI, L, target, nodes)
    return np.array([-r[0], -r[1], r[2]])


def _nodes_as_steps(q, EI, L, target, nodes):
    return pinned_residual(q, EI, L, target, nodes + 1)


SOLUTIONS = {
    "3.1": Solution(rk4_step, {"the stages at s": _variant(at=(0.0, 0.0, 0.0, 0.0)),
                               "equal weights": _variant(weights=(1, 1, 1, 1)),
                               "full steps in the stages": _variant(start=(1.0, 1.0, 1.0)),
                               "k3 from k1": _variant(k3_from=0)},
                    forbidden=("mechnum.ode.rk4",)),
    "3.2": Solution(pinned_residual, {"a sign in m'": _moment_sign,
                                      "target minus tip": _target_minus_tip,
                                      "an off-by-one grid": _nodes_as_steps},
                    forbidden=("mechnum.rods.integrate",)),
}
