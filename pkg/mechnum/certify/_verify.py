"""Re-check a certificate, trusting nothing it stores.

:func:`verify` takes a :class:`~mechnum.certify.Certificate`, the caller's own
functions and the caller's own **domain** (the boxes the question is about: for the book's
mechanisms the whole chart, both branches of every rod), and derives everything again:

1. the searched boxes: one group of leaves per box, none empty; for scope ``"all"`` the boxes
   are exactly the domain (a certificate cut down to part of a chart is refused), for
   ``"existence"`` each lies in a box of the domain; no two overlap;
2. the cover: every leaf lies in its box, and the leaves, merged two halves at a time in their
   depth-first order (halves that share a face and agree in every other coordinate, exactly),
   end as the searched box itself;
3. every leaf's test, re-run with the caller's functions (one evaluation of the residual and,
   where the test needs it, one of the Jacobian): a Krawczyk leaf's test box contains the leaf
   and lies in its searched box, and its enclosure lies in the test box and holds the root;
4. the roots (:func:`distinct_roots`), their count and ``complete`` (scope ``"all"``, no leaf
   undecided, no two enclosures that may or may not hold the same root), compared with the
   stored ones: a mismatch is a :class:`~mechnum.certify.CertificateError` that
   names both values.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum._validate import shown
from mechnum.certify import _krawczyk as kr
from mechnum.certify._certificate import SCOPES, Certificate, CertificateError
from mechnum.certify._guard import ResidualError
from mechnum.certify.balls import as_array
from mechnum.results import Result

__all__ = ["Verified", "covers", "distinct_roots", "overlapping", "sorted_roots", "verify"]


def _within(inner, outer):
    return bool(np.all(inner[:, 0] >= outer[:, 0]) and np.all(inner[:, 1] <= outer[:, 1]))


MAX_PAIRS = 2_000_000
"""The most pairs of boxes that :func:`overlapping` and :func:`distinct_roots` compare. Their
sweep compares two boxes only when their ranges meet along the sweep's coordinate (the one with
the fewest such pairs), and counts these pairs before it compares any: interior-disjoint boxes
in a row need none, a grid of ``k x k`` about ``k**3 / 2``. More than this (a few seconds of
work) is refused with an error that gives the number."""
CHUNK = 100_000
"""Pairs compared at once (a bound on the sweep's memory)."""


def meeting_pairs(boxes: np.ndarray, *, closed: bool = False) -> np.ndarray:
    """The pairs ``(i, j)``, ``i < j``, of boxes ``(m, n, 2)`` whose interiors meet
    (``lo_i < hi_j`` and ``lo_j < hi_i`` in every coordinate), or, if ``closed``, that meet
    as closed boxes (``<=``); sorted. Sort and sweep: ``O(m log m)`` plus the pairs whose
    ranges meet along the sweep's coordinate (at most ``MAX_PAIRS``).

    Raises
    ------
    ValueError
        If more than ``MAX_PAIRS`` pairs would have to be compared.

    Examples
    --------
    >>> meeting_pairs(np.array([[[0.0, 1.0]], [[1.0, 2.0]], [[1.5, 3.0]]])).tolist()
    [[1, 2]]
    >>> meeting_pairs(np.array([[[0.0, 1.0]], [[1.0, 2.0]]]), closed=True).tolist()
    [[0, 1]]
    """
    m = len(boxes)
    start = np.arange(m)
    best = None
    for d in range(boxes.shape[1] if m > 1 else 0):
        order = np.argsort(boxes[:, d, 0], kind="stable")
        ends = np.searchsorted(boxes[order, d, 0], boxes[order, d, 1],
                               side="right" if closed else "left")
        reach = np.maximum(ends - start - 1, 0)
        if best is None or reach.sum() < best[0].sum():
            best = reach, order
    if best is None:
        return np.zeros((0, 2), dtype=int)
    reach, order = best
    total = int(reach.sum())
    if total > MAX_PAIRS:
        raise ValueError(f"{m} boxes give {total} pairs to compare (boxes whose ranges meet "
                         f"along every coordinate), more than MAX_PAIRS = {MAX_PAIRS}")
    first = np.repeat(start, reach)
    second = first + 1 + np.arange(total) - np.repeat(np.cumsum(reach) - reach, reach)
    found = []
    for c in range(0, total, CHUNK):
        i, j = order[first[c:c + CHUNK]], order[second[c:c + CHUNK]]
        a, b = boxes[i], boxes[j]
        if closed:
            meet = np.all((a[..., 0] <= b[..., 1]) & (b[..., 0] <= a[..., 1]), axis=1)
        else:
            meet = np.all((a[..., 0] < b[..., 1]) & (b[..., 0] < a[..., 1]), axis=1)
        found.append(np.sort(np.column_stack((i[meet], j[meet])), axis=1))
    pairs = np.concatenate(found) if found else np.zeros((0, 2), dtype=int)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def overlapping(boxes: np.ndarray) -> tuple | None:
    """The indices ``(i, j)`` of two boxes whose interiors meet (the first such pair), or None
    (faces may touch). ``O(m log m)`` for boxes that meet along few ranges
    (:func:`meeting_pairs`).

    Examples
    --------
    >>> overlapping(np.array([[[0.0, 1.0]], [[1.0, 2.0]], [[1.5, 3.0]]]))
    (1, 2)
    """
    pairs = meeting_pairs(np.asarray(boxes, dtype=float))
    return (int(pairs[0, 0]), int(pairs[0, 1])) if len(pairs) else None


def sorted_roots(found: list) -> list:
    """Root enclosures sorted by their midpoints (first coordinate first).

    Examples
    --------
    >>> [E.tolist() for E in sorted_roots([np.array([[1.0, 2.0]]), np.array([[0.0, 0.5]])])]
    [[[0.0, 0.5]], [[1.0, 2.0]]]
    """
    if not found:
        return []
    order = np.lexsort(np.array([E.mean(axis=1) for E in found]).T[::-1])
    return [found[i] for i in order]


def distinct_roots(leaves: Sequence) -> tuple:
    """The distinct roots proven by the Krawczyk leaves of one searched box, and the leaves
    whose root cannot be told apart from another's.

    Each Krawczyk leaf's test box holds exactly one root, in its enclosure. Two leaves hold
    the same root when one's enclosure lies in the other's test box; different ones when their
    enclosures are disjoint; anything else is undecided (the count is then not proven). Each
    leaf is compared, in order, with the roots found before it whose leaf's boxes meet its
    own (:func:`meeting_pairs`; the others are disjoint from it): ``O(k log k)`` for ``k``
    leaves of few roots each.

    Returns
    -------
    roots : list of ndarray (n, 2)
        Sorted by their midpoints (first coordinate first).
    undecided : list of (Leaf, str)

    Examples
    --------
    >>> from mechnum.certify._certificate import Leaf
    >>> same = [Leaf([[0.0, 1.0]], "krawczyk", [[0.0, 1.5]], [[0.4, 0.6]]),
    ...         Leaf([[1.0, 2.0]], "krawczyk", [[0.5, 2.0]], [[0.45, 0.55]])]
    >>> roots, undecided = distinct_roots(same)
    >>> [E.tolist() for E in roots], undecided
    ([[[0.45, 0.55]]], [])
    """
    proven = [leaf for leaf in leaves if leaf.test == "krawczyk"]
    hulls = np.array([np.column_stack((np.minimum(leaf.enclosure[:, 0], leaf.test_box[:, 0]),
                                       np.maximum(leaf.enclosure[:, 1], leaf.test_box[:, 1])))
                      for leaf in proven])
    earlier = [[] for _ in proven]          # the leaves before j whose boxes meet j's
    for i, j in (meeting_pairs(hulls, closed=True) if proven else ()):
        earlier[j].append(i)
    found, founder, undecided = [], {}, []
    for j, leaf in enumerate(proven):
        E, T = leaf.enclosure, leaf.test_box
        for root in (found[founder[i]] for i in earlier[j] if i in founder):
            if _within(E, root[1]) or _within(root[0], T):
                root[0] = np.column_stack((np.maximum(E[:, 0], root[0][:, 0]),
                                           np.minimum(E[:, 1], root[0][:, 1])))
                break
            if np.all(E[:, 0] <= root[0][:, 1]) and np.all(root[0][:, 0] <= E[:, 1]):
                undecided.append((leaf, "its root's enclosure overlaps another's"))
                break
        else:
            founder[j] = len(found)
            found.append([E, T])
    return sorted_roots([E for E, _ in found]), undecided


def covers(leaves: Sequence, box: np.ndarray) -> bool:
    """Whether leaves in depth-first order merge, two halves at a time, into ``box``: two
    consecutive boxes merge when they differ in exactly one coordinate, where the first ends
    exactly where the second begins.

    Examples
    --------
    >>> from mechnum.certify._certificate import Leaf
    >>> halves = [Leaf([[0.0, 0.5]], "residual"), Leaf([[0.5, 1.0]], "residual")]
    >>> covers(halves, np.array([[0.0, 1.0]])), covers(halves[:1], np.array([[0.0, 1.0]]))
    (True, False)
    """
    stack = []
    for leaf in leaves:
        stack.append(leaf.box)
        while len(stack) >= 2:
            a, b = stack[-2], stack[-1]
            differ = np.nonzero(np.any(a != b, axis=1))[0]
            if len(differ) != 1 or a[differ[0], 1] != b[differ[0], 0]:
                break
            d = differ[0]
            merged = a.copy()
            merged[d, 1] = b[d, 1]
            stack[-2:] = [merged]
    return len(stack) == 1 and np.array_equal(stack[0], box)


@dataclass(frozen=True, kw_only=True)
class Verified(Result):
    """What :func:`verify` re-proved.

    The fields of ``mechnum.results.Result`` (``x``: the midpoints of the root enclosures,
    ``(count, n)``; ``status``: ``"converged"`` when the certificate proves what it says,
    ``"undecided"`` where a leaf of a certificate of scope ``"all"`` is undecided;
    ``iterations``: the leaves re-tested; ``nfev``, ``njev``), and:

    Attributes
    ----------
    count : int
        Distinct roots proven (each in its enclosure, exactly one per enclosure).
    scope : str
        ``"all"`` or ``"existence"``.
    complete : bool or None
        For ``"all"``: no leaf is undecided, ``count`` is every root in the domain. None for
        ``"existence"``.
    roots : ndarray, shape (count, n, 2)
        The enclosures.
    seconds : float
    """

    count: int
    scope: str
    complete: bool | None
    roots: np.ndarray
    seconds: float


def _check_krawczyk(leaf, residual, jacobian, counter, searched):
    T, stored = leaf.test_box, leaf.enclosure
    if not _within(leaf.box, T):
        return f"its Krawczyk box {T.tolist()} does not contain it"
    if not _within(T, searched):
        return f"its Krawczyk box {T.tolist()} leaves the searched box {searched.tolist()}"
    if not _within(stored, T):
        return "its root's enclosure is not in its Krawczyk box"
    passed, K = kr.krawczyk_test(residual, jacobian, T, counter)
    if not passed:
        return "Krawczyk's test fails on its box"
    E = kr.to_floats(K)
    E = np.column_stack((np.maximum(E[:, 0], T[:, 0]), np.minimum(E[:, 1], T[:, 1])))
    if not _within(E, stored) and not kr.krawczyk_test(residual, jacobian, stored, counter)[0]:
        return "its root is not proven to lie in the stored enclosure"
    return None


def _check_leaf(leaf, residual, jacobian, counter, exclude, searched):
    """Re-run the leaf's test; the reason it fails, or None."""
    if leaf.test == "undecided":
        return None
    if leaf.test == "krawczyk":
        return _check_krawczyk(leaf, residual, jacobian, counter, searched)
    X = leaf.box
    if leaf.test == "residual":
        excluded = kr.residual_excludes(kr.residual_of(residual, X, counter))
        return None if excluded else "the residual does not exclude 0"
    if leaf.test == "exclude":
        return None if exclude is not None and kr.excluded_by(exclude, X) else (
            "the exclusion test fails")
    J, yb, fy = kr.linearised(residual, jacobian, X, counter)
    balls = kr.to_balls(X)
    if leaf.test == "mean-value":
        return None if kr.mean_value_excludes(fy, J, balls, yb) else "the mean-value form holds 0"
    Y = kr.preconditioner(J)
    if Y is None or not kr.disjoint(kr.krawczyk(fy, J, balls, yb, Y)[0], balls):
        return "Krawczyk's operator meets the box"
    return None


def _listed(boxes):
    """Boxes for a message: all of them when few, else their number and the first."""
    if len(boxes) <= 2:
        return f"{len(boxes)} boxes {boxes.tolist()}"
    return f"{len(boxes)} boxes ({boxes[0].tolist()}, ...)"


def _check_domain(certificate, domain, scope):
    boxes = certificate.boxes
    if scope is not None and certificate.scope != scope:
        raise CertificateError(f"the certificate's scope is {certificate.scope!r}, the caller "
                               f"asks for {scope!r}")
    if certificate.scope == "all":
        if boxes.shape != domain.shape or not np.array_equal(boxes, domain):
            raise CertificateError(
                f"the certificate searched {_listed(boxes)}, the domain is {_listed(domain)}: "
                f"scope 'all' needs the whole domain")
    else:
        for b, box in enumerate(boxes):
            if not any(box.shape == D.shape and _within(box, D) for D in domain):
                raise CertificateError(f"searched box {b}, {box.tolist()}, lies in no box of "
                                       f"the domain, {_listed(domain)}")
    try:
        pair = overlapping(boxes)
    except ValueError as error:
        raise CertificateError(f"the searched boxes cannot be checked: {error}") from None
    if pair is not None:
        raise CertificateError(f"the searched boxes {pair[0]} and {pair[1]} overlap: "
                               f"{boxes[pair[0]].tolist()}, {boxes[pair[1]].tolist()}")
    if len(certificate.leaves) != len(boxes):
        raise CertificateError(f"the certificate has {len(boxes)} searched boxes and "
                               f"{len(certificate.leaves)} groups of leaves")


def _check_cover(b, box, part):
    if not part:
        raise CertificateError(f"searched box {b}, {box.tolist()}, has no leaves")
    for i, leaf in enumerate(part):
        if not _within(leaf.box, box):
            raise CertificateError(f"leaf {i} of box {b}, {leaf.box.tolist()}, lies outside "
                                   f"its searched box {box.tolist()}")
    if not covers(part, box):
        raise CertificateError(f"the leaves of box {b} do not cover it exactly: "
                               f"{box.tolist()}")


def _compare(certificate, found, complete):
    if certificate.count != len(found):
        raise CertificateError(f"the certificate says count {certificate.count}, the leaves "
                               f"prove {len(found)} roots")
    if certificate.complete != complete:
        raise CertificateError(f"the certificate says complete {certificate.complete}, the "
                               f"leaves prove complete {complete}")
    if len(certificate.roots) != len(found):
        raise CertificateError(f"the certificate stores {len(certificate.roots)} root "
                               f"enclosures, the leaves prove {len(found)} roots")
    for E, stored in zip(found, certificate.roots):
        if not (np.all(E[:, 0] <= stored[:, 1]) and np.all(stored[:, 0] <= E[:, 1])):
            raise CertificateError(f"a root's enclosure {E.tolist()} is not the stored "
                                   f"{stored.tolist()}")


def verify(certificate: Certificate, residual: Callable, jacobian: Callable,
           exclude: Callable | None = None, *, domain: ArrayLike | None = None,
           scope: str | None = None) -> Verified:
    """Re-check a certificate: its domain, cover, every leaf's test, the roots, count and scope.

    Parameters
    ----------
    certificate : Certificate
        From :meth:`~mechnum.certify.Roots.certificate` or
        :meth:`~mechnum.certify.Certificate.load`.
    residual, jacobian : callable
        The caller's functions (see :func:`~mechnum.certify.roots`), not the
        certificate's: the leaves must pass their tests on them.
    exclude : callable, optional
        The caller's exclusion test, if the search had one.
    domain : array_like, shape (m, n, 2) or (n, 2)
        Required. The boxes the question is about, as the caller's inputs imply them (for the book's
        mechanisms :func:`mechnum.rods.certified.branch_boxes`). A certificate of scope
        ``"all"`` must have searched exactly these boxes, one of scope ``"existence"`` boxes
        inside them.
    scope : {"all", "existence"}, optional
        The scope the caller requires (None: the certificate's own, checked as above).

    Returns
    -------
    Verified

    Raises
    ------
    CertificateError
        If anything derived differs from what the certificate stores or needs, or the
        caller's functions refuse a leaf (a ``ValueError``: a box they are not defined on);
        the message names the leaf or box and both values.
    ValueError
        If an argument is not what it must be (no ``domain``, say).

    Examples
    --------
    >>> from mechnum import certify
    >>> f = lambda x: [x[0] * x[0] - 2]
    >>> J = lambda x: [[2 * x[0]]]
    >>> cert = certify.roots(f, J, [[-3.0, 3.0]], max_boxes=100).certificate()
    >>> v = verify(cert, f, J, domain=[[-3.0, 3.0]])
    >>> v.count, v.scope, v.complete
    (2, 'all', True)
    >>> verify(cert, f, J, domain=[[-3.0, 4.0]])
    Traceback (most recent call last):
    ...
    mechnum.certify.CertificateError: the certificate searched 1 boxes \
[[[-3.0, 3.0]]], the domain is 1 boxes [[[-3.0, 4.0]]]: scope 'all' needs the whole domain
    """
    if not isinstance(certificate, Certificate):
        raise ValueError(f"certificate must be a Certificate, got {shown(certificate)}")
    _validate.function(residual, "residual"), _validate.function(jacobian, "jacobian")
    _validate.function(exclude, "exclude", optional=True)
    if domain is None:
        raise ValueError("verify needs the domain the question is about (domain=..., the "
                         "boxes the caller's inputs imply), to compare with the certificate's")
    domain = _validate.array(domain, "domain")
    domain = domain[None] if domain.ndim == 2 else domain
    if domain.ndim != 3:
        raise ValueError(f"domain must be (n, 2) or (m, n, 2), got shape {domain.shape}")
    domain = np.array([as_array(D) for D in domain]).reshape(domain.shape)
    if scope is not None:
        scope = _validate.choice(scope, SCOPES, "scope")
    start = time.perf_counter()
    _check_domain(certificate, domain, scope)
    counter = {"nfev": 0, "njev": 0}
    found, unsure = [], []
    for b, (box, part) in enumerate(zip(certificate.boxes, certificate.leaves)):
        _check_cover(b, box, part)
        for i, leaf in enumerate(part):
            try:
                problem = _check_leaf(leaf, residual, jacobian, counter, exclude, box)
            except ResidualError:
                raise
            except ValueError as error:            # the caller's functions refuse the leaf
                raise CertificateError(f"leaf {i} of box {b}, {leaf.box.tolist()} "
                                       f"({leaf.test}): the caller's functions refuse it: "
                                       f"{error}") from error
            if problem:
                raise CertificateError(f"leaf {i} of box {b}, {leaf.box.tolist()} "
                                       f"({leaf.test}): {problem}")
        roots, doubtful = distinct_roots(part)
        found += roots
        unsure += doubtful
    found = sorted_roots(found)
    leaves = [leaf for part in certificate.leaves for leaf in part]
    decided = not unsure and all(leaf.test != "undecided" for leaf in leaves)
    complete = decided if certificate.scope == "all" else None
    _compare(certificate, found, complete)
    n = certificate.boxes.shape[1]
    roots = np.array(found).reshape(-1, n, 2)
    status = "undecided" if complete is False else "converged"
    return Verified(x=roots.mean(axis=-1), status=status,
                    message=f"{len(found)} roots re-proven, scope {certificate.scope!r}"
                    + ("" if complete is not False else "; a leaf is undecided"),
                    iterations=len(leaves), nfev=counter["nfev"], njev=counter["njev"],
                    count=len(found), scope=certificate.scope, complete=complete,
                    roots=roots, seconds=time.perf_counter() - start)
