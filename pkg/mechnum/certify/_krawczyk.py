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

**The box, not its balls.** A box ``X`` of floats is handed to the functions as balls
(:func:`mechnum.certify.balls.guarded`), which contain it and, their radii rounded outward,
poke a little beyond its faces. A function defined on a domain ``D`` (a chart that ends at
``t = 0``) may enclose ``f`` only over the balls' part in ``D``, a set ``S`` that contains
``X``. Every test here is sound on such an ``S``: an exclusion of ``S`` excludes ``X``, and
Krawczyk's inclusion is tested against the faces of ``X`` itself, so ``K(S)`` in the interior
of ``X`` (inside ``S``) proves exactly one root in ``S``, and it lies in ``X``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
from flint import arb, arb_mat

from mechnum.certify import _guard as guard
from mechnum.certify.balls import ball, bounds, guarded

__all__ = ["CONTRACTING", "INFLATION", "MAX_CONDITION", "disjoint", "excluded_by", "inflate",
           "inside", "krawczyk", "krawczyk_test", "linearised", "mean_value_excludes", "midpoint",
           "preconditioner", "residual_excludes", "residual_of", "test_box", "to_balls",
           "to_floats"]

# A preconditioner Y is the inverse of the midpoint of J(X); beyond this condition number it
# would only widen K(X), and the box is bisected instead.
MAX_CONDITION = 1e14
# Krawczyk is retried on a box enlarged by this fraction of its width on each side (and cut
# back to the searched box) when the operator contracts (||I - Y J(X)|| < CONTRACTING) but
# K(X) pokes out of X: the root then sits on or near a face of X, where no box that ends at
# that face can hold it in its interior.
INFLATION = 0.25
CONTRACTING = 0.5


def _zero_excluded(values):
    """Whether some component of a ball vector is certainly non-zero."""
    return any(v.is_finite() and not v.contains(0) for v in values)


def residual_excludes(values: Sequence) -> bool:
    """The natural test: some component of ``f(X)`` excludes 0."""
    return _zero_excluded(values)


def midpoint(X: np.ndarray) -> tuple:
    """A float point of the float box ``X`` near its midpoint, as exact balls and as floats.

    ``0.5 lo + 0.5 hi`` is rounded twice, and can leave the box where the halves of
    subnormal ends round up (``lo = hi = 3 * 2**-1074`` gives ``4 * 2**-1074``); the
    mean-value form and Krawczyk's operator need a point of ``X``, so it is clipped to it.

    Examples
    --------
    >>> tiny = 3 * 5e-324
    >>> midpoint(np.array([[tiny, tiny], [0.0, 1.0]]))[1].tolist() == [tiny, 0.5]
    True
    """
    y = np.clip(0.5 * X[:, 0] + 0.5 * X[:, 1], X[:, 0], X[:, 1])
    return [arb(float(v)) for v in y], y


def _matrix(rows):
    return arb_mat(len(rows), len(rows[0]), [v for row in rows for v in row])


def _vector(values):
    return arb_mat(len(values), 1, list(values))


def preconditioner(J: Sequence) -> np.ndarray:
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


def mean_value_excludes(fy: Sequence, J: Sequence, X: Sequence, yb: Sequence) -> bool:
    """The mean-value test: some component of ``f(y) + J(X) (X - y)`` excludes 0 (``X``,
    ``yb``: balls)."""
    if not all(v.is_finite() for row in J for v in row):
        return False
    d = _vector([x - y for x, y in zip(X, yb)])
    values = _matrix(J) * d + _vector(fy)
    return _zero_excluded([values[i, 0] for i in range(len(X))])


def krawczyk(fy: Sequence, J: Sequence, X: Sequence, yb: Sequence, Y: np.ndarray) -> list:
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


def inside(K: list, X: np.ndarray) -> bool:
    """Whether every ball of ``K`` lies in the interior of the float box ``X``."""
    return all(k.is_finite() and bool(k.lower() > arb(float(lo)))
               and bool(k.upper() < arb(float(hi))) for k, (lo, hi) in zip(K, X))


def disjoint(K: Sequence, X: np.ndarray) -> bool:
    """Whether some component of ``K`` misses that of the balls ``X``."""
    return any(k.is_finite() and not k.overlaps(x) for k, x in zip(K, X))


def inflate(box: np.ndarray, fraction: float = INFLATION) -> np.ndarray:
    """The float box widened by ``fraction`` of its width on each side."""
    w = box[:, 1] - box[:, 0]
    return np.column_stack((box[:, 0] - fraction * w, box[:, 1] + fraction * w))


def to_balls(box: np.ndarray) -> list:
    """The plain balls of a float box."""
    return [ball(lo, hi) for lo, hi in box]


def to_floats(values: Sequence) -> np.ndarray:
    return np.array([bounds(v) for v in values])


def residual_of(residual: Callable, X: np.ndarray, counter: dict) -> list:
    """The residual's enclosure over the float box ``X`` (checked, counted)."""
    counter["nfev"] += 1
    return guard.values(residual, guarded(X), len(X))


def excluded_by(exclude: Callable | None, X: np.ndarray) -> bool:
    """The caller's own exclusion test on the float box ``X`` (checked)."""
    return guard.decision(exclude, guarded(X))


def linearised(residual: Callable, jacobian: Callable, X: np.ndarray, counter: dict) -> tuple:
    """``(J, yb, fy)``: the Jacobian's enclosure over the float box ``X``, its midpoint (exact
    balls) and the residual's enclosure there, the two evaluations counted in ``counter``."""
    n = len(X)
    J = guard.matrix(jacobian, guarded(X), n)
    counter["njev"] += 1
    yb, y = midpoint(X)
    fy = guard.values(residual, guarded(np.column_stack((y, y))), n, point=True)
    counter["nfev"] += 1
    return J, yb, fy


def test_box(residual: Callable, jacobian: Callable, X: np.ndarray, counter: dict,
             exclude: Callable | None = None) -> tuple:
    """Run the tests on the float box ``X``.

    Returns ``(test, J, K, value)``: ``test`` is ``"residual"``, ``"exclude"`` (the caller's
    own test), ``"mean-value"`` or ``"krawczyk-exclusion"`` (no root in ``X``), ``"krawczyk"``
    (exactly one, in ``K``), ``"contracting"`` (Krawczyk's operator contracts but ``K(X)`` is
    not inside ``X``: a root near a face) or None (undecided); ``J`` is the Jacobian's
    enclosure (None when the first test sufficed), ``value`` the residual's enclosure.
    ``counter`` (a dict with ``nfev``, ``njev``) counts the evaluations.
    """
    value = residual_of(residual, X, counter)
    if residual_excludes(value):
        return "residual", None, None, value
    if exclude is not None and excluded_by(exclude, X):
        return "exclude", None, None, value
    J, yb, fy = linearised(residual, jacobian, X, counter)
    balls = to_balls(X)
    if mean_value_excludes(fy, J, balls, yb):
        return "mean-value", J, None, value
    Y = preconditioner(J)
    if Y is None:
        return None, J, None, value
    K, norm = krawczyk(fy, J, balls, yb, Y)
    if disjoint(K, balls):
        return "krawczyk-exclusion", J, K, value
    if inside(K, X):
        return "krawczyk", J, K, value
    return ("contracting" if norm < CONTRACTING else None), J, K, value


def krawczyk_test(residual: Callable, jacobian: Callable, X: np.ndarray,
                  counter: dict) -> tuple:
    """One Krawczyk test of the float box ``X``: ``(passed, K)``, ``passed`` True when ``K(X)``
    lies in the interior of ``X`` (exactly one root, in ``K``)."""
    J, yb, fy = linearised(residual, jacobian, X, counter)
    Y = preconditioner(J)
    if Y is None:
        return False, None
    K = krawczyk(fy, J, to_balls(X), yb, Y)[0]
    return inside(K, X), K
