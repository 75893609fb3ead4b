"""Chapter 3, the elastica: one RK4 step (3.1), and the shooting residual of the pinned rod
(3.2)."""

import numpy as np

from mechnum.exercises._answers import Array, close
from mechnum.exercises._harness import Case, Exercise, Mistake

RK4_STARTER = '''\
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
    ...
'''

SHOOTING_STARTER = '''\
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
    ...
'''


def rod(EI, force):
    """The right-hand side ``f(s, y)`` of the rod's equations (78), ``y = (x, y, theta, m)``."""
    nx, ny = force
    return lambda s, y: np.array([np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                                  nx * np.sin(y[2]) - ny * np.cos(y[2])])


def _step_cases():
    return [Case("the rod's equations (EI = 1, n = (0.3, 2) N) from (0, 0, 0, 2), h = 0.1",
                 (rod(1.0, (0.3, 2.0)), 0.0, np.array([0.0, 0.0, 0.0, 2.0]), 0.1)),
            Case("y' = (y1, -y0 + cos s) at s = 0.7, h = 0.25",
                 (lambda s, y: np.array([y[1], -y[0] + np.cos(s)]), 0.7, np.array([1.0, -0.5]),
                  0.25)),
            Case("y' = s^2 y (one component) at s = 1, h = 0.3",
                 (lambda s, y: s ** 2 * y, 1.0, np.array([2.0]), 0.3)),
            Case("a stiff rod (EI = 0.2, n = (-4, 1) N) at s = 0.4, h = 0.05",
                 (rod(0.2, (-4.0, 1.0)), 0.4, np.array([0.3, 0.1, 0.8, -0.5]), 0.05))]


RK4 = Exercise(
    number="3.1", label="ch3-ex-rk4-step", title="one RK4 step",
    statement=(
        "**Implement it yourself.** Write `rk4_step(f, s, y, h)`, one step of the classical "
        "Runge-Kutta method of order 4 (the study's (81) to (85)) for $y' = f(s, y)$: four "
        "stages, at $s$, $s + h/2$ (twice) and $s + h$, weighted $1, 2, 2, 1$ over 6. Then "
        "integrate the cantilever of the chapter with it and measure the order: the tip error "
        "should fall by 16 when $h$ halves. The check also uses right-hand sides that depend "
        "on $s$, which the rod's do not."),
    starter=RK4_STARTER, cases=_step_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-13, atol=1e-15,
                                        what="y(s + h)"),
    mistakes=(Mistake("the stages at s", "the middle stages are evaluated at s + h/2 and the "
                      "last at s + h; an autonomous f, like the rod's, hides this mistake."),
              Mistake("equal weights", "the weights are 1, 2, 2, 1 over 6."),
              Mistake("full steps in the stages", "the second and third stages start from "
                      "y + h/2 k1 and y + h/2 k2; only the fourth takes the full h."),
              Mistake("k3 from k1", "the third stage starts from y + h/2 k2, the second "
                      "stage's slope.")),
    hint="test on y' = s (exact: y + s h + h^2 / 2) and on y' = y (exact: y e^h), where RK4's "
         "error is known.")


def _shooting_cases():
    return [Case("the thesis's rod (EI = 0.164934 N m^2, L = 1 m, tip at (0.8, 0.1) m, 61 "
                 "nodes) at its guess (0.1, 0.1, 0.1)",
                 (np.array([0.1, 0.1, 0.1]), 0.164934, 1.0, np.array([0.8, 0.1]), 61)),
            Case("the thesis's rod at (-0.6, -3.2, -1.2), 61 nodes",
                 (np.array([-0.6, -3.2, -1.2]), 0.164934, 1.0, np.array([0.8, 0.1]), 61)),
            Case("a rod with EI = 2, L = 0.5 m, tip at (0.3, 0.3) m, 21 nodes",
                 (np.array([1.5, -4.0, 7.0]), 2.0, 0.5, np.array([0.3, 0.3]), 21))]


SHOOTING = Exercise(
    number="3.2", label="ch3-ex-shooting-residual", title="the shooting residual of a pinned rod",
    statement=(
        "**Implement it yourself.** Write `pinned_residual(q, EI, L, target, nodes)`: from the "
        "unknowns $q = (m_0, n_x, n_y)$, integrate the rod's equations (78) by RK4 (your "
        "`rk4_step`) over `nodes` equally spaced nodes from the clamp state $(0, 0, 0, m_0)$, "
        "and return the residual $(x(L) - x_t,\\ y(L) - y_t,\\ m(L))$ of the thesis's pinned "
        "rod. Then drive it to zero with your `newton_damped` of Chapter 1 and a "
        "forward-difference Jacobian, from the thesis's guess $(0.1, 0.1, 0.1)$."),
    starter=SHOOTING_STARTER, cases=_shooting_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-10, atol=1e-12,
                                        what="the residual"),
    mistakes=(Mistake("a sign in m'", "m' = n_x sin(theta) - n_y cos(theta) (the chapter's "
                      "convention: n is the force on the rod at its tip)."),
              Mistake("target minus tip", "the residual is the tip minus the target, "
                      "(x(L) - x_t, y(L) - y_t)."),
              Mistake("an off-by-one grid", "`nodes` nodes make nodes - 1 steps of "
                      "h = L / (nodes - 1).")),
    hint="with n = 0 the rod is an arc of curvature m0 / EI: check your tip against "
         "(EI / m0) (sin(m0 L / EI), 1 - cos(m0 L / EI)).")
