"""Chapter 6: the reference solutions and the typical mistakes."""

import numpy as np

from mechnum_course.solutions._solution import Solution


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


SOLUTIONS = {
    "6.1": Solution(constrained_index, {"the constraints ignored": _unconstrained,
                                        "the row space for the null space": _row_space,
                                        "zero counted as negative": _non_positive},
                    forbidden=("mechnum.rods.constrained_eigenvalues",)),
    "6.2": Solution(rigid_residual, {"the side lengths": _side_lengths,
                                     "the pins in clockwise order":
                                         _variant(beta=(-30.0, -150.0, 90.0)),
                                     "offsets from B_1": _variant(offsets_from=0)},
                    forbidden=()),
}
