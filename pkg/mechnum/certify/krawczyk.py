"""The tests of one box: interval exclusion, the mean-value form and Krawczyk's operator.

For ``f: R^n -> R^n``, continuously differentiable on a box ``X``, with ``J(X)`` an interval
matrix that contains ``f'(x)`` for every ``x`` in ``X``, a point ``y`` of ``X`` and any real
matrix ``Y`` (here the inverse of the midpoint of ``J(X)``), **Krawczyk's operator** is::

    K(X) = y - Y f(y) + (I - Y J(X)) (X - y)

Every root of ``f`` in ``X`` lies in ``K(X)`` (the mean-value theorem: ``x - Y f(x)`` at a root is
the root itself). Hence (Krawczyk 1969, Moore 1977; Neumaier, *Interval Methods for Systems of
Equations*, 1990, Theorem 5.1.8):

* ``K(X) & X`` empty: ``X`` holds no root;
* ``K(X)`` in the interior of ``X``: ``X`` holds **exactly one** root, and it lies in ``K(X)``
  (the map ``x - Y f(x)`` sends ``X`` into itself, so Brouwer gives a root; the interval matrix
  ``I - Y J(X)`` then has spectral radius below 1, so ``Y`` and every matrix of ``J(X)`` are
  regular, and two roots ``x1, x2`` would give ``0 = f(x1) - f(x2) = A (x1 - x2)`` with a
  regular ``A``).

The first test of a box is cheaper: if the interval value of ``f`` over ``X`` (the natural
extension, or the mean-value form ``f(y) + J(X) (X - y)`` where that is tighter) excludes 0 in one
component, ``X`` holds no root. Every ball comes from Arb, which rounds outward: the tests are
proofs for the functions that ``residual`` and ``jacobian`` enclose, whatever the rounding.
"""

import numpy as np
from flint import arb, arb_mat

from mechnum.certify.balls import ball, bounds

# A preconditioner Y is the inverse of the midpoint of J(X); beyond this condition number it
# would only widen K(X), and the box is bisected instead.
MAX_CONDITION = 1e14
# Krawczyk is retried on a box enlarged by this fraction of its width on each side when the
# operator contracts (||I - Y J(X)|| < CONTRACTING) but K(X) pokes out of X: the root then sits
# on or near a face of X, where no box that ends at that face can hold it in its interior.
INFLATION = 0.25
CONTRACTING = 0.5


def values_of(residual, X):
    """``residual(X)`` as a list of balls (numbers are converted exactly)."""
    return [v if isinstance(v, arb) else arb(v) for v in residual(X)]


def matrix_of(jacobian, X):
    """``jacobian(X)`` as a list of rows of balls."""
    return [[v if isinstance(v, arb) else arb(v) for v in row] for row in jacobian(X)]


def _zero_excluded(values):
    """Whether some component of a ball vector is certainly non-zero."""
    return any(v.is_finite() and not v.contains(0) for v in values)


def residual_excludes(values):
    """The natural test: some component of ``f(X)`` excludes 0."""
    return _zero_excluded(values)


def midpoint(X):
    """Float midpoints of a box of balls, as exact balls and as floats."""
    y = np.array([0.5 * lo + 0.5 * hi for lo, hi in (bounds(x) for x in X)])
    return [arb(float(v)) for v in y], y


def _matrix(rows):
    n = len(rows)
    return arb_mat(n, len(rows[0]), [v for row in rows for v in row])


def _vector(values):
    return arb_mat(len(values), 1, list(values))


def preconditioner(J):
    """The inverse of the midpoint of ``J`` (floats), or None where it is singular, not finite
    or too ill-conditioned."""
    mid = np.array([[float(v.mid()) if v.is_finite() else np.nan for v in row] for row in J])
    if not np.all(np.isfinite(mid)):
        return None
    try:
        if np.linalg.cond(mid) > MAX_CONDITION:
            return None
        return np.linalg.inv(mid)
    except np.linalg.LinAlgError:
        return None


def mean_value_excludes(fy, J, X, yb):
    """The mean-value test: some component of ``f(y) + J(X) (X - y)`` excludes 0."""
    if not all(v.is_finite() for row in J for v in row):
        return False
    d = _vector([x - y for x, y in zip(X, yb)])
    values = _matrix(J) * d + _vector(fy)
    return _zero_excluded([values[i, 0] for i in range(len(X))])


def krawczyk(fy, J, X, yb, Y):
    """Krawczyk's operator ``K(X)`` (list of balls) and the norm bound of ``I - Y J(X)``.

    Parameters
    ----------
    fy : list of arb
        ``f(y)`` enclosed at the point ``y``.
    J : list of lists of arb
        Enclosure of the Jacobian over ``X``.
    X, yb : list of arb
        The box and the point ``y`` (exact balls).
    Y : ndarray
        The preconditioner (floats, used exactly).
    """
    n = len(X)
    Ya = arb_mat(n, n, [float(v) for v in Y.ravel()])
    M = arb_mat(n, n, [1 if i == j else 0 for i in range(n) for j in range(n)]) - Ya * _matrix(J)
    d = _vector([x - y for x, y in zip(X, yb)])
    K = _vector(yb) - Ya * _vector(fy) + M * d
    norm = max(sum(float(abs(M[i, j]).upper()) for j in range(n)) for i in range(n))
    return [K[i, 0] for i in range(n)], norm


def inside(K, X):
    """Whether every ball of ``K`` lies in the interior of the ball of ``X``."""
    return all(k.is_finite() and bool(k.lower() > x.lower()) and bool(k.upper() < x.upper())
               for k, x in zip(K, X))


def disjoint(K, X):
    """Whether some component of ``K`` misses that of ``X``."""
    return any(k.is_finite() and not k.overlaps(x) for k, x in zip(K, X))


def inflate(box, fraction=INFLATION):
    """The float box widened by ``fraction`` of its width on each side."""
    w = box[:, 1] - box[:, 0]
    return np.column_stack((box[:, 0] - fraction * w, box[:, 1] + fraction * w))


def to_balls(box):
    return [ball(lo, hi) for lo, hi in box]


def to_floats(values):
    return np.array([bounds(v) for v in values])


def _linearised(residual, jacobian, X, counter):
    """``(J, yb, fy)``: the Jacobian's enclosure over ``X``, the midpoint of ``X`` and the
    residual's enclosure there, the two evaluations counted in ``counter``."""
    J = matrix_of(jacobian, X)
    counter["njev"] += 1
    yb, _ = midpoint(X)
    fy = values_of(residual, yb)
    counter["nfev"] += 1
    return J, yb, fy


def test_box(residual, jacobian, X, counter, exclude=None):
    """Run the tests on the box of balls ``X``.

    Returns ``(test, J, K, value)``: ``test`` is ``"residual"``, ``"exclude"`` (the caller's
    own test), ``"mean-value"`` or ``"krawczyk-exclusion"`` (no root in ``X``), ``"krawczyk"``
    (exactly one, in ``K``),
    ``"contracting"`` (Krawczyk's operator contracts but ``K(X)`` is not inside ``X``: a root
    near a face) or None (undecided); ``J`` is the Jacobian's enclosure (None when the first
    test sufficed), ``value`` the residual's enclosure. ``counter`` (a dict with ``nfev``,
    ``njev``) counts the evaluations.
    """
    value = values_of(residual, X)
    counter["nfev"] += 1
    if residual_excludes(value):
        return "residual", None, None, value
    if exclude is not None and exclude(X):
        return "exclude", None, None, value
    J, yb, fy = _linearised(residual, jacobian, X, counter)
    if mean_value_excludes(fy, J, X, yb):
        return "mean-value", J, None, value
    Y = preconditioner(J)
    if Y is None:
        return None, J, None, value
    K, norm = krawczyk(fy, J, X, yb, Y)
    if disjoint(K, X):
        return "krawczyk-exclusion", J, K, value
    if inside(K, X):
        return "krawczyk", J, K, value
    return ("contracting" if norm < CONTRACTING else None), J, K, value


def krawczyk_test(residual, jacobian, X, counter):
    """One Krawczyk test of the box ``X``: ``(passed, K)``, ``passed`` True when ``K(X)`` lies in
    the interior of ``X`` (exactly one root, in ``K``)."""
    J, yb, fy = _linearised(residual, jacobian, X, counter)
    Y = preconditioner(J)
    if Y is None:
        return False, None
    K = krawczyk(fy, J, X, yb, Y)[0]
    return inside(K, X), K
