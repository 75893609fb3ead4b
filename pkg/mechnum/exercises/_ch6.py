"""Chapter 6, the flexible 3PFR: the index of an equilibrium under constraints (6.1), and the
equations that admit the platform but not its mirror image (6.2)."""

import numpy as np

from mechnum.exercises._harness import Case, Exercise, Mistake, close


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
    H, A = np.asarray(H, dtype=float), np.asarray(A, dtype=float)
    if A.shape[0] == 0:
        Z = np.eye(H.shape[0])
    else:  # the right singular vectors beyond the rank span the null space
        _, s, Vt = np.linalg.svd(A)
        rank = int((s > s[0] * max(A.shape) * np.finfo(float).eps).sum())
        Z = Vt[rank:].T
    return int((np.linalg.eigvalsh(Z.T @ H @ Z) < 0).sum())


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
    z = pins[:, 0] + 1j * pins[:, 1]
    d = z - z.mean()
    b = a / np.sqrt(3) * np.exp(1j * np.radians([-150.0, -30.0, 90.0]))
    w = d / b  # each e^{i phi} for a turned platform
    return np.array([(w[0] - w[1]).real, (w[0] - w[1]).imag, abs(w[0]) - 1])


# Typical mistakes of 6.1
def _unconstrained(H, A):
    return constrained_index(H, np.zeros((0, len(H))))


def _row_space(H, A):
    Z = np.linalg.qr(np.asarray(A, dtype=float).T)[0] if len(A) else np.eye(len(H))
    return int((np.linalg.eigvalsh(Z.T @ H @ Z) < 0).sum())


def _non_positive(H, A):
    Z = np.eye(len(H)) if len(A) == 0 else np.linalg.svd(A)[2][len(A):].T
    return int((np.linalg.eigvalsh(Z.T @ H @ Z) <= 0).sum())


def _column(load, segments=50):
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
                 (*_column(3.0),)),
            Case("a column pinned at its tip (50 segments), P L^2/EI = 24", (*_column(24.0),)),
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
    reference=constrained_index, cases=_index_cases,
    compare=lambda expected, got: (None if int(got) == got == expected
                                   else f"the index is {got}, expected {expected}"),
    mistakes=(Mistake("the constraints ignored", "count on the null space of A, Z^T H Z, not "
                      "on H: a pinned tip forbids the escape a free tip would have.",
                      _unconstrained),
              Mistake("the row space for the null space", "the tangent space is {v: A v = 0}, "
                      "spanned by the right singular vectors beyond the rank of A, not by the "
                      "columns of A^T.", _row_space),
              Mistake("zero counted as negative", "the index counts eigenvalues < 0; a zero "
                      "eigenvalue is a neutral direction, not an escape.", _non_positive)),
    hint="check that A @ Z is zero and Z^T Z the identity.")


# Typical mistakes of 6.2
def _side_lengths(pins, a):
    return np.array([np.hypot(*(pins[j] - pins[i])) - a for i, j in ((0, 1), (1, 2), (2, 0))])


def _variant(beta=(-150.0, -30.0, 90.0), offsets_from=None):
    def residual(pins, a):
        z = pins[:, 0] + 1j * pins[:, 1]
        w = (z - (z.mean() if offsets_from is None else z[offsets_from])) / (
            a / np.sqrt(3) * np.exp(1j * np.radians(beta)))
        return np.array([(w[0] - w[1]).real, (w[0] - w[1]).imag, abs(w[0]) - 1])
    return residual


def _platform(centre, phi, a, mirror=False):
    beta = np.radians([-150.0, -30.0, 90.0]) * (-1 if mirror else 1)
    angles = phi + beta
    return np.asarray(centre) + a / np.sqrt(3) * np.column_stack((np.cos(angles),
                                                                  np.sin(angles)))


def _rigid_cases():
    rng = np.random.default_rng(62)
    return [Case("a platform of side 0.2 m turned by 0.7 rad", (_platform((0.1, -0.2), 0.7, 0.2),
                                                             0.2)),
            Case("the mirror image of a platform of side 0.2 m",
                 (_platform((0.1, -0.2), 0.7, 0.2, mirror=True), 0.2)),
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
    reference=rigid_residual, cases=_rigid_cases,
    compare=lambda expected, got: close(expected, got, rtol=1e-10, atol=1e-12,
                                        what="the residual"),
    mistakes=(Mistake("the side lengths", "three distances equal to a describe the platform "
                      "or its mirror image, the thesis's (114); the ratios d_i / b_i admit "
                      "rotations only.", _side_lengths),
              Mistake("the pins in clockwise order", "b_1, b_2, b_3 are at -150, -30 and 90 "
                      "degrees: anticlockwise.", _variant(beta=(-30.0, -150.0, 90.0))),
              Mistake("offsets from B_1", "the offsets d_i are from the pins' centroid.",
                      _variant(offsets_from=0))),
    hint="at a turned platform all three equations vanish; at its mirror image they do not.")
