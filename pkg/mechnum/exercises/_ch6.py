"""Chapter 6, the flexible 3PFR: the index of an equilibrium under constraints (6.1), and the
equations that admit the platform but not its mirror image (6.2)."""

import numpy as np

from mechnum.exercises._answers import Array, Integer, close
from mechnum.exercises._harness import Case, Exercise, Mistake

INDEX_STARTER = '''\
def constrained_index(H, A):
    """The number of negative eigenvalues of ``H`` on the null space of A.

    Parameters
    ----------
    H : ndarray, shape (n, n)
        The Hessian of the Lagrangian (symmetric).
    A : ndarray, shape (m, n)
        The constraints' Jacobian (``m = 0`` rows: no constraint).

    Returns
    -------
    int
        The index: how many independent ways the equilibrium has to escape
        (0: stable).
    """
    ...
'''

RIGID_STARTER = '''\
def rigid_residual(pins, a):
    """Three equations: zero when the pins are the platform turned.

    Parameters
    ----------
    pins : ndarray, shape (3, 2)
        The rods' tips ``B_1, B_2, B_3`` (m).
    a : float
        The platform's side (m).

    Returns
    -------
    ndarray, shape (3,)
        With ``d_i`` the offsets of the pins from their centroid and
        ``b_i = a / sqrt(3) e^{i beta_i}``, ``beta = (-150, -30, 90)``
        degrees, as complex numbers: ``Re`` and ``Im`` of
        ``d_1/b_1 - d_2/b_2``, and ``|d_1/b_1| - 1``. A mirror image of the
        platform is no zero.
    """
    ...
'''


def column(load, segments=50):
    """A clamped rod of length 1 (EI = 1) in segments, under a compressive dead load: the
    Hessian at the straight shape, and the constraint of a pinned tip (its height)."""
    h = 1.0 / segments
    T = 2 * np.eye(segments) - np.eye(segments, k=1) - np.eye(segments, k=-1)
    T[-1, -1] = 1.0
    return T / h - load * h * np.eye(segments), np.full((1, segments), h)


def _index_cases():
    rng = np.random.default_rng(61)
    M = rng.normal(size=(6, 6))
    return [Case("a column pinned at its tip (50 segments), P L^2/EI = 3",
                 (*column(3.0),)),
            Case("a column pinned at its tip (50 segments), P L^2/EI = 24", (*column(24.0),)),
            Case("a random symmetric 6 x 6 H with two constraints",
                 (M + M.T, rng.normal(size=(2, 6)))),
            Case("H = diag(0, 1, -1, 2) with no constraint", (np.diag([0.0, 1, -1, 2]),
                                                           np.zeros((0, 4))))]


INDEX = Exercise(
    number="6.1", label="ch6-ex-constrained-index", title="the index under constraints",
    statement=(
        "**Implement it yourself.** Write `constrained_index(H, A)`: the number of negative "
        "eigenvalues of the Hessian $H$ restricted to the constraints' tangent space, the null "
        "space of $A$: with the columns of $Z$ a basis of that null space (from the SVD of "
        "$A$), count the negative eigenvalues of $Z^{\\mathsf T} H Z$. A stable equilibrium "
        "has index 0. Check it on a column pinned at its tip: its index turns 1 near "
        "$PL^2/EI = 20.19$, while the same column free at its tip buckles at $\\pi^2/4$."),
    starter=INDEX_STARTER, cases=_index_cases, returns=Integer(),
    compare=lambda expected, got: (None if got == expected
                                   else f"the index is {got}, expected {expected}"),
    mistakes=(Mistake("the constraints ignored", "count on the null space of A, Z^T H Z, not "
                      "on H: a pinned tip forbids the escape a free tip would have."),
              Mistake("the row space for the null space", "the tangent space is {v: A v = 0}, "
                      "spanned by the right singular vectors beyond the rank of A, not by the "
                      "columns of A^T."),
              Mistake("zero counted as negative", "the index counts eigenvalues < 0; a zero "
                      "eigenvalue is a neutral direction, not an escape.")),
    hint="check that A @ Z is zero and Z^T Z the identity.")


def platform(centre, phi, a, mirror=False):
    """The pins of a platform of side ``a`` turned by ``phi`` about ``centre`` (or of its
    mirror image)."""
    beta = np.radians([-150.0, -30.0, 90.0]) * (-1 if mirror else 1)
    angles = phi + beta
    return np.asarray(centre) + a / np.sqrt(3) * np.column_stack((np.cos(angles),
                                                                  np.sin(angles)))


def _rigid_cases():
    rng = np.random.default_rng(62)
    return [Case("a platform of side 0.2 m turned by 0.7 rad", (platform((0.1, -0.2), 0.7, 0.2),
                                                             0.2)),
            Case("the mirror image of a platform of side 0.2 m",
                 (platform((0.1, -0.2), 0.7, 0.2, mirror=True), 0.2)),
            Case("three random points, a = 0.5 m", (rng.normal(size=(3, 2)), 0.5))]


RIGID = Exercise(
    number="6.2", label="ch6-ex-rigid-residual", title="the platform, not its mirror image",
    statement=(
        "**Implement it yourself.** Write `rigid_residual(pins, a)`, the three equations of the "
        "chapter that hold when the pins $B_1, B_2, B_3$ are the platform turned by some "
        "$\\varphi$: with complex numbers, $\\mathbf d_i$ the offsets of the pins from their "
        "centroid and $\\mathbf b_i = \\frac{a}{\\sqrt3}e^{i\\beta_i}$, "
        "$\\beta = (-150°, -30°, 90°)$, return $(\\mathrm{Re}, \\mathrm{Im})$ of "
        "$\\mathbf d_1/\\mathbf b_1 - \\mathbf d_2/\\mathbf b_2$ and "
        "$|\\mathbf d_1/\\mathbf b_1| - 1$. Evaluate it at a platform and at its mirror image, "
        "and compare with the three side lengths minus $a$, the thesis's (114)."),
    starter=RIGID_STARTER, cases=_rigid_cases, returns=Array(),
    compare=lambda expected, got: close(expected, got, rtol=1e-10, atol=1e-12,
                                        what="the residual"),
    mistakes=(Mistake("the side lengths", "three distances equal to a describe the platform "
                      "or its mirror image, the thesis's (114); the ratios d_i / b_i admit "
                      "rotations only."),
              Mistake("the pins in clockwise order", "b_1, b_2, b_3 are at -150, -30 and 90 "
                      "degrees: anticlockwise."),
              Mistake("offsets from B_1", "the offsets d_i are from the pins' centroid.")),
    hint="at a turned platform all three equations vanish; at its mirror image they do not.")
