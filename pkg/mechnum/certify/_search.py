"""Branch and prune: every root of a system in a box, each proven, or the boxes left undecided.

:func:`~mechnum.certify.roots` takes boxes from a stack (depth first) and tests each
(``test_box``): a box is **excluded** (the residual's enclosure, or
its mean-value form, or Krawczyk's operator proves it holds no root), **proven** (Krawczyk's
operator maps it, or the box enlarged around a root near its face and cut back to the searched
box, into its interior: exactly one root), or **bisected**. The direction of the cut is the one
along which the residual's component nearest to excluding 0 widens most (its "smear"
``|J_ij| width_j``), or else the widest relative to the searched box. A box narrower than
``min_width`` of the searched box in that direction, or any box left when ``max_boxes`` have been
tested, is kept as **undecided**: never dropped.

Every box a test runs on lies in its searched box: the functions are never asked about points
outside the domain the caller gave (a chart that ends at ``t = 0`` is not evaluated beyond it),
so a root proven in a box lies in the interior of its searched box, and searched boxes whose
interiors are disjoint cannot count one root twice.
"""

from __future__ import annotations

import operator
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.certify import _guard as guard
from mechnum.certify import _krawczyk as kr
from mechnum.certify._certificate import EXCLUSIONS, SCOPES, Certificate, Leaf
from mechnum.certify._verify import distinct_roots, overlapping, sorted_roots
from mechnum.certify.balls import as_array, guarded
from mechnum.results import Result

__all__ = ["MAX_BOXES", "MAX_BOXES_LIMIT", "MIN_WIDTH", "MIN_WIDTH_RANGE", "NARROW",
           "REFINEMENTS", "SEARCH", "Roots", "roots"]

SEARCH = "mechnum.certify.roots"
"""The name a certificate of :func:`roots` carries in its field ``search``."""
MAX_BOXES = 100_000
"""Default bound on the boxes tested."""
MAX_BOXES_LIMIT = 10_000_000
"""The largest ``max_boxes`` accepted (a bound on the work: about a day of tests)."""
REFINEMENTS = 8
# Krawczyk iterations that tighten a root's enclosure once it is proven (each at least halves
# the width, and they converge quadratically: a few reach the rounding level).
NARROW = 1e-3
MIN_WIDTH = 1e-10
"""Default: boxes are not cut below this fraction of the searched box's width."""
MIN_WIDTH_RANGE = (1e-15, 0.5)
"""The accepted range of ``min_width``: a box of 53-bit floats cannot be cut much below 1e-15
of its width, and above 0.5 no box would be cut."""


@dataclass(frozen=True, kw_only=True)
class Roots(Result):
    """Every root of a system in a box, each proven, and what stayed undecided.

    The fields of ``mechnum.results.Result`` (``x``: the midpoints of the root
    enclosures, ``(count, n)``; ``status``: ``"converged"`` when no leaf is undecided,
    ``"undecided"`` otherwise; ``iterations``: boxes tested; ``nfev``, ``njev``), and:

    Attributes
    ----------
    roots : ndarray, shape (count, n, 2)
        An enclosure of each root; each holds exactly one root of the system, and no two the
        same one.
    excluded : int
        Leaves proven to hold no root.
    undecided : ndarray, shape (u, n, 2)
        Leaves that could be neither excluded nor proven (too narrow to cut, beyond
        ``max_boxes``, or a root on the searched box's face): there may be roots in them.
    scope : str
        What the search proves: ``"all"`` (every root in the searched boxes, when
        ``complete``) or ``"existence"`` (the roots found exist; the boxes are not a domain
        searched whole, such as boxes around sampled roots).
    complete : bool
        ``scope`` is ``"all"`` and no leaf is undecided: ``count`` is then the number of roots
        in the boxes, a theorem (for the functions that ``residual`` and ``jacobian``
        enclose). Always False for ``"existence"``.
    count : int
        ``len(roots)``.
    boxes : int
        Boxes tested (also ``iterations``).
    seconds : float
        Time of the search.
    searched : ndarray, shape (m, n, 2)
        The searched boxes.
    leaves : tuple of tuple of mechnum.certify.Leaf
        Each searched box's leaves, in depth-first order (:meth:`certificate`).
    """

    roots: np.ndarray
    excluded: int
    undecided: np.ndarray
    scope: str
    complete: bool
    count: int
    boxes: int
    seconds: float
    searched: np.ndarray
    leaves: tuple

    @property
    def undecided_fraction(self) -> float:
        """float: the undecided leaves' share of the searched volume (0 when complete)."""
        def volume(boxes):
            boxes = np.asarray(boxes)
            return float(np.prod(boxes[..., 1] - boxes[..., 0], axis=-1).sum()) if len(
                boxes) else 0.0
        total = volume(self.searched)
        return volume(self.undecided) / total if total > 0 else 0.0

    @property
    def evaluations(self) -> int:
        """int: evaluations of the residual and of the Jacobian, ``nfev + njev``."""
        return self.nfev + self.njev

    def certificate(self, inputs: dict | None = None) -> Certificate:
        """The leaves with the test each passed, as a
        :class:`~mechnum.certify.Certificate` of this search's ``scope``.

        Parameters
        ----------
        inputs : dict, optional
            What was searched, stored with the certificate (JSON-serialisable).
        """
        return Certificate(boxes=self.searched, leaves=self.leaves, roots=self.roots,
                           count=self.count, scope=self.scope,
                           complete=self.complete if self.scope == "all" else None,
                           search=SEARCH, inputs=dict(inputs or {}),
                           work={"boxes": self.boxes, "nfev": self.nfev, "njev": self.njev,
                                 "seconds": round(self.seconds, 3)})


def _direction(box, J, value, widths):
    """The coordinate to cut: in the residual's component nearest to excluding 0 (largest
    ``|mid| / rad`` of its enclosure), the coordinate that widens it most (largest
    ``|J_ij| width_j``, the smear); where the Jacobian's enclosure is not finite, the widest
    coordinate relative to the searched box (also where the smear's choice is already
    ``NARROW`` times narrower than that one: cutting it again would not help)."""
    w = box[:, 1] - box[:, 0]
    relative = w / widths
    if J is not None and all(v.is_finite() for row in J for v in row):
        near = [float(abs(v.mid()) / v.rad()) if v.is_finite() and v.rad() > 0 else 0.0
                for v in value]
        i = int(np.argmax(near))
        smear = np.array([float(abs(v).upper()) for v in J[i]]) * w
        j = int(np.argmax(np.where(relative > 0, smear, -1.0)))
        if smear[j] > 0 and relative[j] >= NARROW * relative.max():
            return j
    return int(np.argmax(relative))


def _suggested(split, X):
    """The caller's cut ``(d, value)`` of the float box ``X``, or None (checked: an index of a
    coordinate and a finite number)."""
    suggestion = split(guarded(X))
    if suggestion is None:
        return None
    try:
        d, cut = suggestion
        d, cut = operator.index(d), float(cut)
    except (TypeError, ValueError):
        raise guard.ResidualError(f"split must return None or (coordinate, value), got "
                                  f"{_validate.shown(suggestion)}") from None
    if not (0 <= d < len(X) and np.isfinite(cut)):
        raise guard.ResidualError(f"split returned coordinate {d} and value {cut!r}: a "
                                  f"coordinate in [0, {len(X)}) and a finite value are needed")
    return d, cut


def _cut(X, J, value, widths, split):
    """The coordinate and the value to cut ``X`` at: the caller's ``split`` where it gives one
    inside the box (and not within a tenth of the width of a face), else the midpoint of
    :func:`_direction`'s coordinate."""
    if split is not None:
        suggestion = _suggested(split, X)
        if suggestion is not None:
            d, cut = suggestion
            lo, hi = X[d]
            margin = 0.1 * (hi - lo)
            if lo + margin < cut < hi - margin:
                return d, cut
    d = _direction(X, J, value, widths)
    return d, 0.5 * X[d, 0] + 0.5 * X[d, 1]


def _boxes(box):
    boxes = _validate.array(box, "box", finite=False)
    boxes = boxes[None] if boxes.ndim == 2 else boxes
    if boxes.ndim != 3 or boxes.shape[-1] != 2:
        raise ValueError(f"box must be (n, 2) or (m, n, 2), got shape {boxes.shape}")
    if boxes.shape[1] == 0:
        raise ValueError("box must have at least one coordinate, got shape "
                         f"{boxes.shape}")
    boxes = np.array([as_array(b) for b in boxes]).reshape(boxes.shape)
    pair = overlapping(boxes)
    if pair is not None:
        raise ValueError(f"the searched boxes {pair[0]} and {pair[1]} overlap: a root in both "
                         f"would be counted twice; give boxes whose interiors are disjoint")
    return boxes


def roots(residual: Callable, jacobian: Callable, box: ArrayLike, *, max_boxes: int = MAX_BOXES,
          min_width: float = MIN_WIDTH, exclude: Callable | None = None,
          split: Callable | None = None, scope: str = "all") -> Roots:
    """Every root of ``residual`` in a box, proven by interval arithmetic (branch and prune).

    Parameters
    ----------
    residual : callable
        ``residual(X) -> sequence of n balls``: an enclosure of ``f`` over the box ``X``, for
        every point of it. ``X`` is a list of ``n`` balls (:class:`mechnum.certify.Ball`,
        ``flint.arb`` that refuse to leave ball arithmetic); it is called on boxes and on
        points (balls of radius 0), where it must be finite.
    jacobian : callable
        ``jacobian(X) -> n sequences of n balls``: an enclosure of ``f'`` over ``X``. ``f`` must
        be continuously differentiable on every box searched.
    box : array_like, shape (n, 2) or (m, n, 2)
        The box ``[lo, hi]`` per coordinate, or ``m`` boxes searched one after the other (the
        pieces of a domain on which ``f`` is smooth), whose interiors are disjoint.
    max_boxes : int, optional
        The most boxes tested, ``<= MAX_BOXES_LIMIT``; the boxes left are undecided.
    min_width : float, optional
        Boxes are not cut below this fraction of the searched box's width, in
        ``MIN_WIDTH_RANGE``; such a box is undecided.
    exclude : callable, optional
        ``exclude(X) -> bool``: a test of the caller's own, True only where it proves that the
        box ``X`` holds no root (tried after the residual's enclosure;
        :func:`~mechnum.certify.verify` needs it too).
    split : callable, optional
        ``split(X) -> (d, value)`` or None: where the caller would cut the box ``X`` (for
        example at the edge of the directions that a force balance allows, so that one half is
        excluded at once); used when ``value`` lies inside the box, else the search's own
        choice.
    scope : {"all", "existence"}, optional
        What the boxes are: the whole domain of the question (``"all"``: a complete search
        proves the count) or boxes around roots found otherwise (``"existence"``: the roots
        proven exist, and nothing is said of the rest of the domain).

    Returns
    -------
    Roots
        ``complete`` is True only for ``scope="all"`` with no box undecided: then ``count`` is
        a theorem. What is proven assumes only that ``residual`` and ``jacobian`` enclose
        ``f`` and ``f'`` (Arb's outward rounding takes care of the rest).

    Raises
    ------
    ValueError
        If a box is not finite, has ``lo > hi``, two boxes overlap, or an argument is out of
        range.
    mechnum.certify.ResidualError
        If a function returns the wrong length, something that is not a ball, or a residual
        that is not finite at a point.
    mechnum.certify.BallArithmeticError
        If a function converts a ball to a number or branches on an uncertain comparison.

    Examples
    --------
    The circle ``x**2 + y**2 = 1`` meets the line ``y = x`` twice:

    >>> f = lambda X: [X[0] ** 2 + X[1] ** 2 - 1, X[1] - X[0]]
    >>> J = lambda X: [[2 * X[0], 2 * X[1]], [-1, 1]]
    >>> r = roots(f, J, [[-2.0, 2.0], [-2.0, 2.0]])
    >>> r.count, r.complete, r.status, np.round(r.x, 6).tolist()
    (2, True, 'converged', [[-0.707107, -0.707107], [0.707107, 0.707107]])
    """
    _validate.function(residual, "residual"), _validate.function(jacobian, "jacobian")
    _validate.function(exclude, "exclude", optional=True)
    _validate.function(split, "split", optional=True)
    scope = _validate.choice(scope, SCOPES, "scope")
    boxes = _boxes(box)
    max_boxes = _validate.maxiter(max_boxes, "max_boxes", maximum=MAX_BOXES_LIMIT)
    min_width = _validate.scalar(min_width, "min_width")
    if not MIN_WIDTH_RANGE[0] <= min_width <= MIN_WIDTH_RANGE[1]:
        raise ValueError(f"min_width must lie in {list(MIN_WIDTH_RANGE)}, got {min_width!r}")
    start = time.perf_counter()
    counter = {"nfev": 0, "njev": 0}
    tested, parts = 0, []
    for B in boxes:
        widths = np.where(B[:, 1] > B[:, 0], B[:, 1] - B[:, 0], 1.0)
        leaves, stack = [], [B]
        while stack:
            X = stack.pop()
            if tested >= max_boxes:
                leaves.append(Leaf(X, "undecided", reason="max_boxes reached"))
                continue
            tested += 1
            leaf, J, value = _decide(residual, jacobian, X, B, counter, exclude)
            if leaf is not None:
                leaves.append(leaf)
                continue
            d, cut = _cut(X, J, value, widths, split)
            if (X[d, 1] - X[d, 0]) < min_width * widths[d] or not X[d, 0] < cut < X[d, 1]:
                leaves.append(Leaf(X, "undecided", reason="narrower than min_width"))
                continue
            left, right = X.copy(), X.copy()
            left[d, 1] = right[d, 0] = cut
            stack += [right, left]
        parts.append(tuple(leaves))
    return _result(boxes, parts, scope, tested, counter, time.perf_counter() - start)


def _decide(residual, jacobian, X, B, counter, exclude):
    """The leaf that the tests make of ``X`` (in the searched box ``B``), or None (cut it),
    with the Jacobian's and the residual's enclosures."""
    test, J, K, value = kr.test_box(residual, jacobian, X, counter, exclude)
    if test in EXCLUSIONS:
        return Leaf(X, test), J, value
    T = X
    if test == "contracting":
        T = _meet(kr.inflate(X), B)
        if np.array_equal(T, X):
            return None, J, value
        passed, K = kr.krawczyk_test(residual, jacobian, T, counter)
        if not passed:
            return None, J, value
    elif test != "krawczyk":
        return None, J, value
    return Leaf(X, "krawczyk", T, _tighten(residual, jacobian, _meet(kr.to_floats(K), T),
                                            counter)), J, value


def _tighten(residual, jacobian, E, counter):
    """A tighter enclosure of the one root in ``E``: Krawczyk's operator iterated
    (``F <- K(F) & F``, which keeps the root) while it halves a width; the last ``F`` that the
    operator maps into its own interior is returned, widened threefold where that is proven
    too (it holds the root, and one evaluation re-proves it), or ``E`` itself."""
    F, proven = E, E
    for _ in range(REFINEMENTS):
        passed, K = kr.krawczyk_test(residual, jacobian, F, counter)
        if K is None:
            break
        if passed:
            proven = F
        new = _meet(kr.to_floats(K), F)
        if np.any(new[:, 0] > new[:, 1]):          # cannot happen: F holds the root
            break
        shrunk = np.any(new[:, 1] - new[:, 0] <= 0.5 * (F[:, 1] - F[:, 0]))
        F = new
        if not shrunk:
            break
    # a margin: the box three times as wide, proven too, so that a re-check whose rounding
    # differs in the last bits (another machine's preconditioner) still passes
    wider = _meet(kr.inflate(proven, 1.0), E)
    if kr.krawczyk_test(residual, jacobian, wider, counter)[0]:
        return wider
    return proven


def _meet(a, b):
    return np.column_stack((np.maximum(a[:, 0], b[:, 0]), np.minimum(a[:, 1], b[:, 1])))


def _result(boxes, parts, scope, tested, counter, seconds):
    found, unsure = [], []
    for part in parts:
        roots, doubtful = distinct_roots(part)
        found += roots
        unsure += [leaf.box for leaf, _ in doubtful]
    leaves = [leaf for part in parts for leaf in part]
    n = boxes.shape[1]
    found = sorted_roots(found)
    undecided = [leaf.box for leaf in leaves if leaf.test == "undecided"] + unsure
    enclosures = np.array(found).reshape(-1, n, 2)
    decided = not undecided
    complete = decided and scope == "all"
    excluded = sum(leaf.test in EXCLUSIONS for leaf in leaves)
    message = (f"{len(found)} roots proven, {excluded} boxes excluded, "
               f"{len(undecided)} undecided; {tested} boxes tested")
    if complete:
        message += ": the count in the searched boxes is proven"
    elif scope == "existence":
        message += ": these roots exist (the boxes are not the whole domain)"
    return Roots(x=enclosures.mean(axis=2), status="converged" if decided else "undecided",
                 message=message, iterations=tested, nfev=counter["nfev"],
                 njev=counter["njev"], roots=enclosures, excluded=excluded,
                 undecided=np.array(undecided).reshape(-1, n, 2), scope=scope,
                 complete=complete, count=len(found), boxes=tested, seconds=seconds,
                 searched=boxes, leaves=tuple(parts))
