"""Re-check a certificate, trusting nothing it stores.

:func:`verify` takes a :class:`~mechnum.certify.certificate.Certificate`, the caller's own
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
   stored ones: a mismatch is a :class:`~mechnum.certify.certificate.CertificateError` that
   names both values.
"""

import time
from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum._validate import shown
from mechnum.certify import krawczyk as kr
from mechnum.certify.balls import as_array
from mechnum.certify.certificate import SCOPES, Certificate, CertificateError


def _within(inner, outer):
    return bool(np.all(inner[:, 0] >= outer[:, 0]) and np.all(inner[:, 1] <= outer[:, 1]))


def _interiors_meet(a, b):
    return bool(np.all(a[:, 0] < b[:, 1]) and np.all(b[:, 0] < a[:, 1]))


def overlapping(boxes: np.ndarray) -> tuple | None:
    """The indices ``(i, j)`` of two boxes whose interiors meet, or None (faces may touch).

    Examples
    --------
    >>> overlapping(np.array([[[0.0, 1.0]], [[1.0, 2.0]], [[1.5, 3.0]]]))
    (1, 2)
    """
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            if _interiors_meet(boxes[i], boxes[j]):
                return i, j
    return None


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


def distinct_roots(leaves) -> tuple:
    """The distinct roots proven by the Krawczyk leaves of one searched box, and the leaves
    whose root cannot be told apart from another's.

    Each Krawczyk leaf's test box holds exactly one root, in its enclosure. Two leaves hold
    the same root when one's enclosure lies in the other's test box; different ones when their
    enclosures are disjoint; anything else is undecided (the count is then not proven).

    Returns
    -------
    roots : list of ndarray (n, 2)
        Sorted by their midpoints (first coordinate first).
    undecided : list of (Leaf, str)

    Examples
    --------
    >>> from mechnum.certify.certificate import Leaf
    >>> same = [Leaf([[0.0, 1.0]], "krawczyk", [[0.0, 1.5]], [[0.4, 0.6]]),
    ...         Leaf([[1.0, 2.0]], "krawczyk", [[0.5, 2.0]], [[0.45, 0.55]])]
    >>> roots, undecided = distinct_roots(same)
    >>> [E.tolist() for E in roots], undecided
    ([[[0.45, 0.55]]], [])
    """
    found, undecided = [], []
    for leaf in leaves:
        if leaf.test != "krawczyk":
            continue
        E, T = leaf.enclosure, leaf.test_box
        for root in found:
            if _within(E, root[1]) or _within(root[0], T):
                root[0] = np.column_stack((np.maximum(E[:, 0], root[0][:, 0]),
                                           np.minimum(E[:, 1], root[0][:, 1])))
                break
            if np.all(E[:, 0] <= root[0][:, 1]) and np.all(root[0][:, 0] <= E[:, 1]):
                undecided.append((leaf, "its root's enclosure overlaps another's"))
                break
        else:
            found.append([E, T])
    return sorted_roots([E for E, _ in found]), undecided


def covers(leaves, box: np.ndarray) -> bool:
    """Whether leaves in depth-first order merge, two halves at a time, into ``box``: two
    consecutive boxes merge when they differ in exactly one coordinate, where the first ends
    exactly where the second begins.

    Examples
    --------
    >>> from mechnum.certify.certificate import Leaf
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


@dataclass(frozen=True)
class Verified:
    """What :func:`verify` re-proved.

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
    leaves : int
    nfev, njev : int
    seconds : float
    """

    count: int
    scope: str
    complete: bool
    roots: np.ndarray
    leaves: int
    nfev: int
    njev: int
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
    pair = overlapping(boxes)
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


def verify(certificate, residual, jacobian, exclude=None, *, domain=None,
           scope=None) -> Verified:
    """Re-check a certificate: its domain, cover, every leaf's test, the roots, count and scope.

    Parameters
    ----------
    certificate : Certificate
        From :meth:`~mechnum.certify.search.Roots.certificate` or
        :meth:`~mechnum.certify.certificate.Certificate.load`.
    residual, jacobian : callable
        The caller's functions (see :func:`~mechnum.certify.search.roots`), not the
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
        If anything derived differs from what the certificate stores or needs; the message
        names the leaf or box and both values.
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
    mechnum.certify.certificate.CertificateError: the certificate searched 1 boxes \
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
            problem = _check_leaf(leaf, residual, jacobian, counter, exclude, box)
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
    return Verified(len(found), certificate.scope, complete,
                    np.array(found).reshape(-1, n, 2), len(leaves), counter["nfev"],
                    counter["njev"], time.perf_counter() - start)
