"""Tests of certificates and their verifier: round trips, and every tampered certificate refused.

``verify`` trusts nothing a certificate stores. Each test below tampers with one thing
(the count, the searched boxes, the leaf groups, the cover, a Krawczyk test box, the scope or
``complete``) and checks that ``verify`` refuses it with a ``CertificateError`` that says what
is wrong; each would pass a verifier that skipped that one check. Two are aimed at mutants of
the verifier in particular: a cover whose leaves do not touch (a merge that checked only that
two leaves differ in one coordinate would accept it), and two enclosures that cannot be told
to hold one root or two (``complete`` without ``not unsure`` would call it complete).
``from_json`` is fed malformed JSON of every kind and must name the problem.
"""

import json

import numpy as np
import pytest
from flint import arb

from mechnum import certify
from mechnum.certify import Certificate, CertificateError, Leaf
from mechnum.certify import _verify as verify_module

BOX = [[-3.0, 3.0], [-3.0, 3.0]]


def circle_hyperbola():
    """``x**2 + y**2 = 4``, ``x y = 1``: four roots in ``BOX``."""
    return (lambda X: [X[0] * X[0] + X[1] * X[1] - 4, X[0] * X[1] - 1],
            lambda X: [[2 * X[0], 2 * X[1]], [X[1], X[0]]])


def cubic():
    """``(x**3 - x) (x + 3)``: roots -3, -1, 0 and 1."""
    return (lambda X: [(X[0] ** 3 - X[0]) * (X[0] + 3)],
            lambda X: [[(3 * X[0] ** 2 - 1) * (X[0] + 3) + X[0] ** 3 - X[0]]])


TWO_BOXES = [[[-2.0, 2.0]], [[-4.0, -2.0]]]


@pytest.fixture(scope="module")
def plane():
    f, J = circle_hyperbola()
    return f, J, certify.roots(f, J, BOX).certificate({"system": "circle and hyperbola"})


@pytest.fixture(scope="module")
def line():
    f, J = cubic()
    return f, J, certify.roots(f, J, TWO_BOXES).certificate()


def tampered(cert, change):
    data = json.loads(cert.to_json())
    change(data)
    return Certificate.from_json(json.dumps(data))


def refused(cert, f, J, match, domain=BOX, **options):
    with pytest.raises(CertificateError, match=match):
        certify.verify(cert, f, J, domain=domain, **options)


def test_the_certificate_verifies_and_round_trips(plane, tmp_path):
    f, J, cert = plane
    path = tmp_path / "cert.json"
    cert.save(path)
    loaded = Certificate.load(path)
    assert loaded.inputs == {"system": "circle and hyperbola"}
    assert loaded.search == "mechnum.certify.roots" and loaded.scope == "all"
    assert json.loads(loaded.to_json()) == json.loads(cert.to_json())
    assert all(np.array_equal(a.box, b.box) for pa, pb in zip(loaded.leaves, cert.leaves)
               for a, b in zip(pa, pb))                      # bit for bit
    checked = certify.verify(loaded, f, J, domain=BOX)
    assert (checked.count, checked.scope, checked.complete) == (4, "all", True)
    assert checked.iterations == sum(len(part) for part in cert.leaves)


def test_two_searched_boxes_verify(line):
    f, J, cert = line
    checked = certify.verify(cert, f, J, domain=TWO_BOXES)
    assert checked.count == 4 and checked.complete


# ---- the count, the boxes and the leaf groups

def test_a_count_edited_to_seven_is_refused(plane):
    f, J, cert = plane
    refused(tampered(cert, lambda d: d.update(count=7)), f, J,
            "says count 7, the leaves prove 4")


def test_roots_added_with_the_count_are_refused(plane):
    f, J, cert = plane
    bad = tampered(cert, lambda d: d.update(count=5, roots=d["roots"] + d["roots"][:1]))
    refused(bad, f, J, "says count 5, the leaves prove 4")
    bad = tampered(cert, lambda d: d.update(roots=d["roots"][:3]))
    refused(bad, f, J, "stores 3 root enclosures, the leaves prove 4")


def test_a_moved_root_enclosure_is_refused(plane):
    f, J, cert = plane
    bad = tampered(cert, lambda d: d["roots"][0].__setitem__(
        0, [v + 1.0 for v in d["roots"][0][0]]))
    refused(bad, f, J, "not the stored")


def test_a_searched_box_without_leaves_is_refused(line):
    """The issue's case: two boxes and only the first one's leaves (zip would skip the
    second, and verify three roots where there are four)."""
    f, J, cert = line
    refused(tampered(cert, lambda d: d["leaves"].pop()), f, J,
            "2 searched boxes and 1 groups of leaves", domain=TWO_BOXES)
    refused(tampered(cert, lambda d: d["leaves"].__setitem__(1, [])), f, J,
            r"searched box 1, \[\[-4.0, -2.0\]\], has no leaves", domain=TWO_BOXES)


def test_an_extra_leaf_group_is_refused(line):
    f, J, cert = line
    refused(tampered(cert, lambda d: d["leaves"].append(d["leaves"][1])), f, J,
            "2 searched boxes and 3 groups of leaves", domain=TWO_BOXES)


def test_no_leaves_and_count_zero_is_refused(plane):
    f, J, cert = plane
    bad = tampered(cert, lambda d: d.update(leaves=[], count=0, roots=[]))
    refused(bad, f, J, "1 searched boxes and 0 groups of leaves")
    bad = tampered(cert, lambda d: d.update(leaves=[], boxes=[], count=0, roots=[]))
    refused(bad, f, J, "searched 0 boxes .*, the domain is 1 boxes")


def test_overlapping_searched_boxes_are_refused(line):
    """The same box twice, with its leaves twice: every root would count twice."""
    f, J, cert = line

    def doubled(d):
        d["boxes"].append(d["boxes"][0])
        d["leaves"].append(d["leaves"][0])
    bad = tampered(cert, doubled)
    refused(bad, f, J, "boxes 0 and 2 overlap", domain=bad.boxes)


# ---- the domain and the scope

def test_a_certificate_cut_down_to_part_of_the_domain_is_refused(line):
    """A certificate of one of the two boxes is complete for that box, not for the domain."""
    f, J, _ = line
    part = certify.roots(f, J, TWO_BOXES[0]).certificate()
    assert certify.verify(part, f, J, domain=TWO_BOXES[0]).complete
    refused(part, f, J, "searched 1 boxes .*, the domain is 2 boxes", domain=TWO_BOXES)
    smaller = certify.roots(f, J, [[-2.0, 0.5]]).certificate()
    refused(smaller, f, J, r"needs the whole domain", domain=TWO_BOXES[0])


def test_an_existence_certificate_claims_no_completeness(line):
    f, J, _ = line
    cert = certify.roots(f, J, [[[0.9, 1.1]], [[-1.1, -0.9]]], scope="existence").certificate()
    assert cert.complete is None and "complete" not in json.loads(cert.to_json())
    checked = certify.verify(cert, f, J, domain=TWO_BOXES)
    assert (checked.count, checked.scope, checked.complete) == (2, "existence", None)
    refused(cert, f, J, "caller asks for 'all'", domain=TWO_BOXES, scope="all")
    outside = certify.roots(f, J, [[[1.9, 2.1]]], scope="existence").certificate()
    refused(outside, f, J, "lies in no box of the domain", domain=TWO_BOXES)


def test_scope_and_complete_lies_are_refused(line):
    f, J, _ = line
    around = certify.roots(f, J, [[[0.9, 1.1]], [[-1.1, -0.9]]], scope="existence").certificate()
    lie = tampered(around, lambda d: d.update(scope="all", complete=True))
    refused(lie, f, J, "needs the whole domain", domain=TWO_BOXES)
    short = certify.roots(f, J, TWO_BOXES[0], max_boxes=5).certificate()   # undecided leaves
    assert short.complete is False
    refused(tampered(short, lambda d: d.update(complete=True)), f, J,
            "says complete True, the leaves prove complete False", domain=TWO_BOXES[0])
    with pytest.raises(CertificateError, match=r"unknown keys \['complete'\]"):
        tampered(around, lambda d: d.update(complete=True))
    with pytest.raises(CertificateError, match="complete is a bool for scope 'all'"):
        Certificate(boxes=around.boxes, leaves=around.leaves, roots=around.roots, count=2,
                    scope="existence", complete=True, search="by hand")


# ---- the cover and the leaves

def test_a_removed_leaf_is_refused(plane):
    f, J, cert = plane
    excluded = [i for i, leaf in enumerate(cert.leaves[0]) if leaf.test == "residual"]
    bad = tampered(cert, lambda d: d["leaves"][0].pop(excluded[len(excluded) // 2]))
    refused(bad, f, J, "do not cover it exactly")


def test_leaves_that_do_not_touch_are_refused(line):
    """The first leaf shrunk (still excluded: a part of an excluded box), leaving a gap; a
    merge that checked only that two leaves differ in one coordinate would close it."""
    f, J, cert = line
    first = cert.leaves[0][0]
    assert first.test != "krawczyk"
    lo, hi = first.box[0]

    def shrink(d):
        d["leaves"][0][0]["box"][0][1] = hi - 0.25 * (hi - lo)
    refused(tampered(cert, shrink), f, J, "box 0 do not cover it exactly", domain=TWO_BOXES)


def test_a_leaf_outside_its_box_is_refused(line):
    f, J, cert = line
    bad = tampered(cert, lambda d: d["leaves"][1][0]["box"][0].__setitem__(0, -5.0))
    refused(bad, f, J, r"leaf 0 of box 1, \[\[-5.0, .*lies outside", domain=TWO_BOXES)


def test_a_leaf_whose_test_fails_is_refused(plane):
    """A Krawczyk leaf relabelled as excluded by the residual: its root is in it."""
    f, J, cert = plane
    i = next(i for i, leaf in enumerate(cert.leaves[0]) if leaf.test == "krawczyk")
    with pytest.raises(CertificateError, match="a 'residual' leaf has no test_box"):
        tampered(cert, lambda d: d["leaves"][0][i].update(test="residual"))

    def relabel(d):
        leaf = d["leaves"][0][i]
        del leaf["test_box"], leaf["enclosure"]
        leaf["test"] = "residual"
    refused(tampered(cert, relabel), f, J, "the residual does not exclude 0")


def test_a_moved_krawczyk_box_is_refused(plane):
    f, J, cert = plane
    i = next(i for i, leaf in enumerate(cert.leaves[0]) if leaf.test == "krawczyk")

    def move(d):
        leaf = d["leaves"][0][i]
        leaf["test_box"] = (np.array(leaf["test_box"]) + 0.01).tolist()
        leaf["enclosure"] = (np.array(leaf["enclosure"]) + 0.01).tolist()
    refused(tampered(cert, move), f, J, "Krawczyk")


def test_a_krawczyk_box_outside_its_searched_box_is_refused():
    """``x - 1`` on ``[0, 1.5]``: Krawczyk's operator is the point 1 on every box, so a test
    box enlarged beyond the searched box still passes; the verifier must refuse it there (a
    function may be another one beyond its box, as a chart's branch beyond t = 0)."""
    f, J = (lambda X: [X[0] - 1]), (lambda X: [[1]])
    cert = certify.roots(f, J, [[0.0, 1.5]]).certificate()
    i = next(i for i, leaf in enumerate(cert.leaves[0]) if leaf.test == "krawczyk")
    bad = tampered(cert, lambda d: d["leaves"][0][i].update(test_box=[[0.0, 3.0]]))
    refused(bad, f, J, r"Krawczyk box \[\[0.0, 3.0\]\] leaves the searched box",
            domain=[[0.0, 1.5]])


@pytest.mark.parametrize("change, match", [
    ({"test_box": [[0.9, 1.2]]}, r"Krawczyk box \[\[0.9, 1.2\]\] does not contain it"),
    ({"enclosure": [[0.0, 1.5]]}, "enclosure is not in its Krawczyk box"),
    ({"enclosure": [[1.1, 1.2]]}, "not proven to lie in the stored enclosure")])
def test_a_krawczyk_leaf_must_hold_its_root_in_its_boxes(change, match):
    """The leaf ``[0.75, 1.5]`` of ``x - 1`` with a test box that misses part of it, an
    enclosure beyond the test box, an enclosure without the root."""
    f, J = (lambda X: [X[0] - 1]), (lambda X: [[1]])
    leaves = [[Leaf([[0.0, 0.75]], "residual"),
               Leaf([[0.75, 1.5]], "krawczyk", [[0.75, 1.5]], [[0.99, 1.01]])]]
    cert = Certificate(boxes=[[[0.0, 1.5]]], leaves=leaves, roots=[[[0.99, 1.01]]], count=1,
                       scope="all", complete=True, search="by hand")
    assert certify.verify(cert, f, J, domain=[[0.0, 1.5]]).count == 1
    refused(tampered(cert, lambda d: d["leaves"][0][1].update(change)), f, J, match,
            domain=[[0.0, 1.5]])


def test_two_enclosures_not_told_apart_are_not_complete():
    """``x`` on ``[-1, 1]``, two leaves ``[-1, 0]`` and ``[0, 1]``, each proven on a test box
    (``[-1, 0.5]``, ``[-0.5, 1]``) whose enclosure is the whole test box: the enclosures
    overlap and neither lies in the other's test box, so they may hold one root or two. The
    count of one is a lower bound, and the certificate is not complete."""
    f, J = (lambda X: [X[0]]), (lambda X: [[1]])
    leaves = [[Leaf([[-1.0, 0.0]], "krawczyk", [[-1.0, 0.5]], [[-1.0, 0.5]]),
               Leaf([[0.0, 1.0]], "krawczyk", [[-0.5, 1.0]], [[-0.5, 1.0]])]]
    cert = Certificate(boxes=[[[-1.0, 1.0]]], leaves=leaves, roots=[[[-1.0, 0.5]]], count=1,
                       scope="all", complete=False, search="by hand")
    checked = certify.verify(cert, f, J, domain=[[-1.0, 1.0]])
    assert checked.count == 1 and checked.complete is False
    lie = Certificate(boxes=cert.boxes, leaves=cert.leaves, roots=cert.roots, count=1,
                      scope="all", complete=True, search="by hand")
    refused(lie, f, J, "says complete True, the leaves prove complete False",
            domain=[[-1.0, 1.0]])


def test_other_functions_are_refused(plane):
    _, _, cert = plane
    f = lambda X: [X[0] * X[0] + X[1] * X[1] - 4.5, X[0] * X[1] - 1]        # noqa: E731
    J = lambda X: [[2 * X[0], 2 * X[1]], [X[1], X[0]]]                      # noqa: E731
    with pytest.raises(CertificateError, match="leaf"):
        certify.verify(cert, f, J, domain=BOX)


# ---- malformed JSON

def _valid(plane):
    return json.loads(plane[2].to_json())


MALFORMED = {
    "not JSON": ("{", "not JSON"),
    "deep nesting": ("[" * 100_000 + "]" * 100_000, "not JSON|must be an object"),
    "a list": ("[1, 2]", "must be an object"),
    "no format": ('{"count": 1}', "format 'None'"),
}


@pytest.mark.parametrize("name", MALFORMED)
def test_malformed_text_is_refused(name):
    text, match = MALFORMED[name]
    with pytest.raises(CertificateError, match=match):
        Certificate.from_json(text)


def _set(path, value):
    def change(d):
        *keys, last = path
        for k in keys:
            d = d[k]
        d[last] = value
    return change


def _drop(path):
    def change(d):
        *keys, last = path
        for k in keys:
            d = d[k]
        del d[last]
    return change


BROKEN = {
    "count a string": (_set(["count"], "seven"), "count must be an integer"),
    "count a bool": (_set(["count"], True), "count must be an integer"),
    "count negative": (_set(["count"], -1), "count must be an integer"),
    "scope unknown": (_set(["scope"], "most"), "scope must be one of"),
    "complete a string": (_set(["complete"], "yes"), "complete is a bool"),
    "complete missing": (_drop(["complete"]), r"missing keys \['complete'\]"),
    "unknown key": (_set(["proof"], "trust me"), r"unknown keys \['proof'\]"),
    "inputs a list": (_set(["inputs"], []), "inputs must be a dict"),
    "search a number": (_set(["search"], 3), "search must be a str"),
    "boxes a string": (_set(["boxes"], "everything"), "boxes must be nested lists"),
    "boxes ragged": (_set(["boxes"], [[[0.0, 1.0]], [[0.0, 1.0], [2.0, 3.0]]]), "ragged"),
    "boxes with NaN": (_set(["boxes", 0, 0, 0], float("nan")), "finite intervals"),
    "a bound of 10**400": (_set(["boxes", 0, 0, 1], 10**400), "beyond the float range"),
    "a leaf's end 10**400": (_set(["leaves", 0, 0, "box", 0, 0], -10**400),
                             "beyond the float range"),
    "boxes reversed": (_set(["boxes", 0, 0], [3.0, -3.0]), "lo <= hi"),
    "boxes of bools": (_set(["boxes", 0, 0], [False, True]), "holds bool"),
    "roots of another shape": (_set(["roots"], [[[0.0, 1.0]]]), "roots must have shape"),
    "leaves a dict": (_set(["leaves"], {}), "leaves must be a list"),
    "a leaf a number": (_set(["leaves", 0, 0], 5), "a leaf must be an object"),
    "a leaf without a test": (_drop(["leaves", 0, 0, "test"]), "a leaf has the keys"),
    "a leaf's unknown test": (_set(["leaves", 0, 0, "test"], "trust"), "test must be one of"),
    "a leaf's test a list": (_set(["leaves", 0, 0, "test"], ["residual"]), "must be text"),
    "a leaf's box deep": (_set(["leaves", 0, 0, "box"], [[[[0.0]]]]), "not a number"),
    "a leaf's reason": (_set(["leaves", 0, 0, "reason"], "because"), "only an undecided"),
    "a leaf of another dimension": (_set(["leaves", 0, 0, "box"], [[0.0, 1.0]]),
                                    "the boxes' 2 coordinates"),
}


@pytest.mark.parametrize("name", BROKEN)
def test_malformed_certificates_are_refused(plane, name):
    change, match = BROKEN[name]
    data = _valid(plane)
    change(data)
    with pytest.raises(CertificateError, match=match):
        Certificate.from_json(json.dumps(data))


def test_a_certificate_of_the_old_format_is_refused(plane):
    data = _valid(plane)
    data["format"] = "mechnum-certificate-1"
    with pytest.raises(CertificateError, match="make certify"):
        Certificate.from_json(json.dumps(data))


def test_verify_refuses_bad_arguments(plane):
    f, J, cert = plane
    with pytest.raises(ValueError, match="certificate must be a Certificate"):
        certify.verify(json.loads(cert.to_json()), f, J, domain=BOX)
    with pytest.raises(ValueError, match="domain"):
        certify.verify(cert, f, J, domain=[[0.0, np.nan]])
    with pytest.raises(ValueError, match="scope"):
        certify.verify(cert, f, J, domain=BOX, scope="most")
    with pytest.raises(ValueError, match="verify needs the domain"):
        certify.verify(cert, f, J)
    with pytest.raises(CertificateError, match="sequences of Leaf"):
        Certificate(boxes=[BOX], leaves=[[arb(1)]], roots=[], count=0, scope="all",
                    complete=True, search="by hand")


def _naive_distinct(leaves):
    """distinct_roots as first written: each Krawczyk leaf against every root found."""
    found, undecided = [], []
    for leaf in (leaf for leaf in leaves if leaf.test == "krawczyk"):
        E, T = leaf.enclosure, leaf.test_box
        for root in found:
            if (np.all(E[:, 0] >= root[1][:, 0]) and np.all(E[:, 1] <= root[1][:, 1])) or (
                    np.all(root[0][:, 0] >= T[:, 0]) and np.all(root[0][:, 1] <= T[:, 1])):
                root[0] = np.column_stack((np.maximum(E[:, 0], root[0][:, 0]),
                                           np.minimum(E[:, 1], root[0][:, 1])))
                break
            if np.all(E[:, 0] <= root[0][:, 1]) and np.all(root[0][:, 0] <= E[:, 1]):
                undecided.append(leaf)
                break
        else:
            found.append([E, T])
    return verify_module.sorted_roots([E for E, _ in found]), undecided


def test_the_sweeps_find_what_comparing_every_pair_finds():
    """meeting_pairs (and overlapping) against every pair compared; distinct_roots against the
    quadratic first version, on random valid leaves around a few roots (grid-aligned ends,
    so that faces touch and enclosures nest or overlap)."""
    rng = np.random.default_rng(5)
    for _ in range(60):
        n, m = int(rng.integers(1, 4)), int(rng.integers(0, 40))
        lo = rng.integers(0, 12, (m, n)) / 4
        boxes = np.stack((lo, lo + rng.integers(0, 6, (m, n)) / 4), axis=-1)
        for closed in (False, True):
            less = np.less_equal if closed else np.less
            every = [[i, j] for i in range(m) for j in range(i + 1, m)
                     if np.all(less(boxes[i, :, 0], boxes[j, :, 1])
                               & less(boxes[j, :, 0], boxes[i, :, 1]))]
            assert verify_module.meeting_pairs(boxes, closed=closed).tolist() == every
        roots = 2.0 * rng.integers(0, 3, (3, n))      # each test box holds one root only
        leaves = []
        for _ in range(m):
            z = roots[rng.integers(0, 3)]
            T = np.column_stack((z - rng.integers(1, 8, n) / 16,
                                 z + rng.integers(1, 8, n) / 16))
            E = np.column_stack((z - rng.integers(0, 3, n) / 16, z + rng.integers(0, 3, n) / 16))
            leaves.append(Leaf(T, "krawczyk", T, np.clip(E, T[:, :1], T[:, 1:])))
        found, undecided = verify_module.distinct_roots(leaves)
        expected, doubtful = _naive_distinct(leaves)
        assert [E.tolist() for E in found] == [E.tolist() for E in expected]
        assert [leaf for leaf, _ in undecided] == doubtful


def test_verify_compares_no_pair_of_boxes_in_a_row(monkeypatch):
    """4000 searched boxes in a row: the sweep compares none of them with another (the first
    verifier compared all 8 million pairs, 130 s); a grid whose boxes meet along every
    coordinate's ranges more than MAX_PAIRS is refused, naming the number."""
    monkeypatch.setattr(verify_module, "MAX_PAIRS", 0)
    f, J = (lambda X: [X[0] * 0 + 1]), (lambda X: [[X[0] * 0]])
    xs = np.linspace(0.0, 1.0, 4001)
    boxes = np.stack((xs[:-1], xs[1:]), axis=-1)[:, None, :]
    cert = Certificate(boxes=boxes, leaves=[[Leaf(b, "residual")] for b in boxes], roots=[],
                       count=0, scope="existence", search="a row")
    assert certify.verify(cert, f, J, domain=[[0.0, 1.0]]).count == 0
    grid = np.array([[[x, x + 1], [y, y + 1]] for x in range(3) for y in range(3)], float)
    cert = Certificate(boxes=grid, leaves=[[Leaf(b, "residual")] for b in grid], roots=[],
                       count=0, scope="existence", search="a grid")
    F = lambda X: [X[0] * 0 + 1, X[1] * 0 + 1]              # noqa: E731
    refused(cert, F, F, "9 boxes give 9 pairs to compare.*MAX_PAIRS = 0",
            domain=[[0.0, 3.0], [0.0, 3.0]])
