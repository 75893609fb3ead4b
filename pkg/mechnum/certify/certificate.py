"""Certificates: the leaves of a search with the test each passed, to re-check and to store.

A certificate holds the searched boxes and, for each, its **leaves** in depth-first order:
disjoint boxes whose union is the searched box, each with the test that decided it
(:mod:`mechnum.certify.krawczyk`) and, for Krawczyk's test, the box it was proven on (the leaf
itself, or the leaf enlarged when its root sits near a face). :func:`verify` re-runs each
leaf's test (one evaluation of the residual and, where the test needs it, one of the Jacobian)
and checks that the leaves **cover** the box: merging, like a stack, every two consecutive
leaves that are the two halves of a box must end with the searched box itself. Then the roots
are re-derived from the Krawczyk leaves (:func:`distinct_roots`) and must be the stored count.

A certificate serialises to JSON (:meth:`~mechnum.certify.certificate.Certificate.to_json`):
floats are written with Python's shortest round-trip ``repr``, so every leaf comes back bit for
bit.
"""

import itertools
import json
import time
from dataclasses import dataclass, field

import numpy as np
from flint import arb

from mechnum import _validate
from mechnum._validate import shown
from mechnum.certify import krawczyk as kr
from mechnum.errors import MechnumError

EXCLUSIONS = ("residual", "exclude", "mean-value", "krawczyk-exclusion")
TESTS = EXCLUSIONS + ("krawczyk", "undecided")
FORMAT = "mechnum-certificate-1"


class CertificateError(MechnumError):
    """A certificate that does not prove what it says: a leaf's test fails, the leaves do not
    cover the box, or the roots are not the ones stored."""


@dataclass(frozen=True)
class Leaf:
    """One leaf of a search.

    Attributes
    ----------
    box : ndarray, shape (n, 2)
        The leaf (float intervals).
    test : str
        ``"residual"``, ``"exclude"``, ``"mean-value"``, ``"krawczyk-exclusion"`` (no root),
        ``"krawczyk"``
        (exactly one root in ``test_box``) or ``"undecided"``.
    test_box : ndarray, shape (n, 2) or None
        For ``"krawczyk"``: the box on which Krawczyk's test passed (it contains ``box``).
    enclosure : ndarray, shape (n, 2) or None
        For ``"krawczyk"``: a box in ``test_box`` that holds its root: ``K(test_box)`` or a
        tighter box that Krawczyk's operator maps into its own interior.
    reason : str or None
        For ``"undecided"``: why.
    """

    box: np.ndarray
    test: str
    test_box: np.ndarray = None
    enclosure: np.ndarray = None
    reason: str = None


def _within(inner, outer):
    return bool(np.all(inner[:, 0] >= outer[:, 0]) and np.all(inner[:, 1] <= outer[:, 1]))


def _in_test_ball(E, T):
    """Whether the float box ``E`` lies in the balls of the test box ``T`` (the set on which
    Krawczyk's test was proven: it holds ``T`` and a little more, the rounding of its radii)."""
    for (lo, hi), x in zip(E, kr.to_balls(T)):
        if bool(arb(float(lo)) < x.lower()) or bool(arb(float(hi)) > x.upper()):
            return False
    return True


def _in_union(E, boxes):
    """Whether the box ``E`` lies in the union of ``boxes``: cut ``E`` along every face of the
    boxes it meets, and every cell must lie in one of them."""
    near = [B for B in boxes if _overlap(E, B)]
    cuts = [sorted({lo, hi} | {x for B in near for x in B[d] if lo < x < hi})
            for d, (lo, hi) in enumerate(E)]
    for cell in itertools.product(*(zip(c[:-1], c[1:]) if len(c) > 1 else [(c[0], c[0])]
                                     for c in cuts)):
        cell = np.array(cell)
        if not any(_within(cell, B) for B in near):
            return False
    return True


def _overlap(a, b):
    return bool(np.all(a[:, 0] <= b[:, 1]) and np.all(b[:, 0] <= a[:, 1]))


def distinct_roots(leaves, boxes):
    """The distinct roots proven by the Krawczyk leaves, and the leaves that stay undecided.

    A leaf's root lies in its ``enclosure``: it is outside the searched boxes when the
    enclosure misses them all (the leaf holds no root), counted when the enclosure lies in one
    of them, and undecided when the enclosure straddles a box's boundary. Two enclosures hold
    the same root when one lies in the other's test box (which holds exactly one root); they
    hold different ones when they are disjoint; anything else stays undecided. An enclosure
    across the face between two searched boxes counts when it is the same root as one counted
    inside a box.

    Returns
    -------
    roots : list of ndarray (n, 2)
        Sorted by their midpoints (first coordinate first).
    undecided : list of (Leaf, str)
    """
    found, undecided, straddling = [], [], []
    for leaf in leaves:
        if leaf.test != "krawczyk":
            continue
        E, T = leaf.enclosure, leaf.test_box
        if not any(_overlap(E, B) for B in boxes):
            continue
        if not any(_within(E, B) for B in boxes):
            if not _in_union(E, boxes):
                straddling.append(leaf)
                continue
        for root in found:
            if _in_test_ball(E, root[1]) or _in_test_ball(root[0], T):
                root[0] = np.column_stack((np.maximum(E[:, 0], root[0][:, 0]),
                                           np.minimum(E[:, 1], root[0][:, 1])))
                break
            if _overlap(E, root[0]):
                undecided.append((leaf, "its root's enclosure overlaps another's"))
                break
        else:
            found.append([E, T])
    for leaf in straddling:             # the same root as a counted one, or undecided
        E, T = leaf.enclosure, leaf.test_box
        if not any(_in_test_ball(E, root[1]) or _in_test_ball(root[0], T) for root in found):
            undecided.append((leaf, "its root's enclosure straddles the searched box's face"))
    found = [E for E, _ in found]
    order = np.lexsort(np.array([E.mean(axis=1) for E in found]).T[::-1]) if found else []
    return [found[i] for i in order], undecided


def _covers(leaves, box):
    """Whether leaves in depth-first order merge, two halves at a time, into ``box``."""
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


def _floats(a):
    return None if a is None else np.asarray(a, dtype=float).tolist()


@dataclass(frozen=True)
class Certificate:
    """The leaves of a search, re-checkable by :func:`verify` and storable as JSON.

    Attributes
    ----------
    boxes : ndarray, shape (m, n, 2)
        The searched boxes.
    leaves : tuple of tuple of Leaf
        For each searched box, its leaves in depth-first order.
    roots : ndarray, shape (count, n, 2)
        The enclosures of the distinct roots.
    complete : bool
        No leaf is undecided: ``count`` is every root in the boxes.
    inputs : dict
        What was searched (the application's inputs), JSON-serialisable.
    work : dict
        ``boxes``, ``nfev``, ``njev``, ``seconds`` of the search.
    """

    boxes: np.ndarray
    leaves: tuple
    roots: np.ndarray
    complete: bool
    inputs: dict = field(default_factory=dict)
    work: dict = field(default_factory=dict)

    @property
    def count(self):
        """int: the number of distinct roots proven."""
        return len(self.roots)

    def to_json(self):
        """The certificate as JSON text (floats exact)."""
        return json.dumps({
            "format": FORMAT, "inputs": self.inputs, "work": self.work,
            "complete": self.complete, "count": self.count, "roots": _floats(self.roots),
            "boxes": _floats(self.boxes),
            "leaves": [[{k: v for k, v in (("box", _floats(leaf.box)), ("test", leaf.test),
                                           ("test_box", _floats(leaf.test_box)),
                                           ("enclosure", _floats(leaf.enclosure)),
                                           ("reason", leaf.reason)) if v is not None}
                        for leaf in part] for part in self.leaves]})

    @classmethod
    def from_json(cls, text):
        """A certificate from :meth:`to_json`'s text.

        Raises
        ------
        CertificateError
            If the text is not a certificate of this format.
        """
        try:
            data = json.loads(text)
            if data.get("format") != FORMAT:
                raise CertificateError(f"not a {FORMAT} certificate: format "
                                       f"{data.get('format')!r}")
            leaves = tuple(tuple(Leaf(np.array(leaf["box"], dtype=float), leaf["test"],
                                      _array(leaf.get("test_box")), _array(leaf.get("enclosure")),
                                      leaf.get("reason")) for leaf in part)
                           for part in data["leaves"])
            return cls(np.array(data["boxes"], dtype=float), leaves,
                       np.array(data["roots"], dtype=float).reshape(-1, *np.shape(
                           data["boxes"])[1:]), bool(data["complete"]), data["inputs"],
                       data["work"])
        except (KeyError, TypeError, ValueError) as error:
            raise CertificateError(f"a malformed certificate: {error}") from error

    def save(self, path):
        """Write :meth:`to_json` to ``path``."""
        with open(path, "w", encoding="utf-8") as out:
            out.write(self.to_json())

    @classmethod
    def load(cls, path):
        """Read a certificate that :meth:`save` wrote."""
        with open(path, encoding="utf-8") as text:
            return cls.from_json(text.read())


def _array(value):
    return None if value is None else np.array(value, dtype=float)


@dataclass(frozen=True)
class Verified:
    """What :func:`verify` re-proved.

    Attributes
    ----------
    count : int
        Distinct roots proven (each in its enclosure, exactly one per enclosure).
    complete : bool
        No leaf is undecided: ``count`` is every root in the boxes.
    roots : ndarray, shape (count, n, 2)
    leaves : int
    nfev, njev : int
    seconds : float
    """

    count: int
    complete: bool
    roots: np.ndarray
    leaves: int
    nfev: int
    njev: int
    seconds: float


def _check_leaf(leaf, residual, jacobian, counter, exclude):
    """Re-run the leaf's test; the reason it fails, or None."""
    if leaf.test not in TESTS:
        return f"an unknown test {leaf.test!r}"
    if leaf.test == "undecided":
        return None
    if leaf.test == "krawczyk":
        T = leaf.test_box
        if T is None or not _within(leaf.box, T):
            return "its Krawczyk box does not contain it"
        passed, K = kr.krawczyk_test(residual, jacobian, kr.to_balls(T), counter)
        if not passed:
            return "Krawczyk's test fails on its box"
        E = kr.to_floats(K)
        E = np.column_stack((np.maximum(E[:, 0], T[:, 0]), np.minimum(E[:, 1], T[:, 1])))
        stored = leaf.enclosure
        if stored is None or not _within(stored, T):
            return "its root's enclosure is not in its Krawczyk box"
        if not _within(E, stored) and not kr.krawczyk_test(residual, jacobian,
                                                           kr.to_balls(stored), counter)[0]:
            return "its root is not proven to lie in the stored enclosure"
        return None
    X = kr.to_balls(leaf.box)
    if leaf.test == "residual":
        counter["nfev"] += 1
        excluded = kr.residual_excludes(kr.values_of(residual, X))
        return None if excluded else "the residual does not exclude 0"
    if leaf.test == "exclude":
        return None if exclude is not None and exclude(X) else "the exclusion test fails"
    J = kr.matrix_of(jacobian, X)
    yb, _ = kr.midpoint(X)
    fy = kr.values_of(residual, yb)
    counter["nfev"] += 1
    counter["njev"] += 1
    if leaf.test == "mean-value":
        return None if kr.mean_value_excludes(fy, J, X, yb) else "the mean-value form holds 0"
    Y = kr.preconditioner(J)
    if Y is None or not kr.disjoint(kr.krawczyk(fy, J, X, yb, Y)[0], X):
        return "Krawczyk's operator meets the box"
    return None


def verify(certificate, residual, jacobian, exclude=None):
    """Re-check a certificate: every leaf's test, the cover, the roots.

    Parameters
    ----------
    certificate : Certificate
        From :meth:`~mechnum.certify.search.Roots.certificate` or
        :meth:`~mechnum.certify.certificate.Certificate.load`.
    residual, jacobian : callable
        The functions the certificate was made with (see :func:`~mechnum.certify.search.roots`).
    exclude : callable, optional
        The exclusion test the search was given, if any.

    Returns
    -------
    Verified

    Raises
    ------
    CertificateError
        If a leaf's test fails (its number and box are named), the leaves of a box do not
        cover it, or the roots are not those stored.

    Examples
    --------
    >>> from mechnum import certify
    >>> f = lambda x: [x[0] * x[0] - 2]
    >>> J = lambda x: [[2 * x[0]]]
    >>> cert = certify.roots(f, J, [[-3.0, 3.0]], max_boxes=100).certificate()
    >>> v = verify(cert, f, J)
    >>> v.count, v.complete
    (2, True)
    """
    if not isinstance(certificate, Certificate):
        raise ValueError(f"certificate must be a Certificate, got {shown(certificate)}")
    _validate.function(residual, "residual"), _validate.function(jacobian, "jacobian")
    _validate.function(exclude, "exclude", optional=True)
    start = time.perf_counter()
    counter = {"nfev": 0, "njev": 0}
    for b, (box, part) in enumerate(zip(certificate.boxes, certificate.leaves)):
        if not _covers(part, box):
            raise CertificateError(f"the leaves of box {b} do not cover it: {box.tolist()}")
        for i, leaf in enumerate(part):
            problem = _check_leaf(leaf, residual, jacobian, counter, exclude)
            if problem:
                raise CertificateError(f"leaf {i} of box {b}, {leaf.box.tolist()} "
                                       f"({leaf.test}): {problem}")
    leaves = [leaf for part in certificate.leaves for leaf in part]
    found, unsure = distinct_roots(leaves, certificate.boxes)
    complete = not unsure and all(leaf.test != "undecided" for leaf in leaves)
    if len(found) != certificate.count or complete != certificate.complete:
        raise CertificateError(f"the leaves prove {len(found)} roots (complete: {complete}), "
                               f"the certificate says {certificate.count} "
                               f"(complete: {certificate.complete})")
    for E, stored in zip(found, certificate.roots):
        if not _overlap(E, stored):
            raise CertificateError(f"a root's enclosure {E.tolist()} is not the stored "
                                   f"{stored.tolist()}")
    return Verified(len(found), complete, np.array(found).reshape(certificate.roots.shape),
                    len(leaves), counter["nfev"], counter["njev"],
                    time.perf_counter() - start)
