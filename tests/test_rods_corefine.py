"""Tests of the co-refined search (mechnum.rods._leaves, _tuples, _corefine, _cosearch,
_cocertificate; mechnum.rods._clusters): its enclosures and tests never drop a box or a tuple
that holds a known equilibrium, its clusters, Table 7's complete count, and its certificate,
re-checked and refused when tampered with."""

import json

import numpy as np
import pytest

from mechnum import certify, rods
from mechnum.mechanisms import pfr3, rfr2
from mechnum.mechanisms.pfr3 import certified as pfr3_certified
from mechnum.mechanisms.pfr3 import clamps
from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS
from mechnum.mechanisms.rfr2 import certified as rfr2_certified
from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
from mechnum.rods import _clusters, _corefine, _leaves, _tuples, certified
from mechnum.rods import _regular as regular
from mechnum.rods._clusters import clusters, hulls

TABLE7_ROOTS = rfr2.forward(TABLE7, TABLE7_THETA, rng=0).x
TABLE8_ROOTS = pfr3.forward(TABLE8, TABLE8_LAMBDAS, rng=0).x


def _box_around(psi, t, rng):
    """A random chart box holding ``(psi, t)``, on its branch, of width 1e-7 to 1."""
    w = 10 ** rng.uniform(-7, 0, 2) * rng.uniform(0, 1, (2, 2))
    box = np.array([[psi - w[0, 0], psi + w[0, 1]], [t - w[1, 0], t + w[1, 1]]])
    box[0] = np.clip(box[0], 0.0, 2 * np.pi)
    box[1] = np.clip(box[1], 0.0, regular.T_MAX) if t > 0 else np.clip(
        box[1], -regular.T_MAX, 0.0)
    return box


def test_a_leaf_encloses_every_rod_of_its_box():
    rng = np.random.default_rng(3)
    for _ in range(40):
        mode = int(rng.integers(1, 4))
        rod = _leaves.ChartRod(0.7, 1.3, mode, rng.uniform(-1, 1, 2), rng.uniform(-3, 3))
        psi, t = rng.uniform(0.01, 2 * np.pi - 0.01), rng.uniform(-0.99, 0.99)
        box = _box_around(psi, t, rng)
        row = _leaves.enclose(rod, box, 1 if t > 0 else -1)
        p = rng.uniform(*box[0], 20)
        s = rng.uniform(*box[1], 20)
        ok = (p > 0) & (p < 2 * np.pi) & (s != 0)
        exact = regular.clamped_pinned_regular(rod.EI, rod.L, p[ok], s[ok], mode)
        tip, force, _, _ = regular.place(exact, rod.origin, rod.angle)
        slack = 1e-12 * (1 + np.abs(tip).max())
        assert np.all(row[0:2] - slack <= tip) and np.all(tip <= row[2:4] + slack)
        slack = 1e-12 * (1 + np.abs(force).max())
        assert np.all(row[4:6] - slack <= force) and np.all(force <= row[6:8] + slack)
        R = np.hypot(*force.T)
        # the sampled rods' forces are floats of the closed form: a few ulps from exact
        assert np.all(row[8] <= R * (1 + 1e-12)) and np.all(R <= row[9] * (1 + 1e-12))
        assert row[10] <= p[ok].min() + rod.angle and p[ok].max() + rod.angle <= row[11]


def test_cuts_partition_a_box_and_go_geometric_at_a_singular_edge():
    rod = _leaves.ChartRod(1.0, 1.0, 1, (0.0, 0.0), 0.0)
    leaves = _leaves.Leaves(rod)
    ids = leaves.add([[[0.0, 0.5], [-0.5, 0.0]], [[0.0, 0.5], [0.0, 0.5]],
                      [[5.0, 2 * np.pi], [-0.5, 0.0]]], [-1, 1, -1])
    halves = leaves.split(ids, [0, 0, 0])
    lo, hi = leaves.box[halves[:, 0]], leaves.box[halves[:, 1]]
    assert np.array_equal(lo[:, 0, 0], leaves.box[ids, 0, 0])
    assert np.array_equal(lo[:, 0, 1], hi[:, 0, 0])
    assert np.array_equal(hi[:, 0, 1], leaves.box[ids, 0, 1])
    # decaying branch at psi = 0: the load is unbounded there, so the cut is near the edge;
    # growing branch: the rods there are straight, so the middle
    assert lo[0, 0, 1] == 0.5 * _leaves.EDGE_SHARE and lo[1, 0, 1] == 0.25
    assert lo[2, 0, 1] == 0.5 * 5.0 + 0.5 * (2 * np.pi)    # growing (t < 0, psi > pi)
    with pytest.raises(ValueError, match="one axis"):
        leaves.split(ids[:1], [1])


def _tuples_around(roots, rods_of, n, rng):
    """``n`` random tuples of boxes, each holding one known root's rods, as enclosures."""
    D = []
    for _ in range(n):
        z = roots[rng.integers(len(roots))]
        D.append([_leaves.enclose(rod, _box_around(z[2 * i], z[2 * i + 1], rng),
                                  1 if z[2 * i + 1] > 0 else -1)
                  for i, rod in enumerate(rods_of)])
    return np.array(D)


def test_no_test_drops_a_tuple_that_holds_a_table7_root():
    rng = np.random.default_rng(4)
    chart = rfr2_certified._chart_rods(TABLE7, TABLE7_THETA)
    assembly = rfr2_certified._assembly(TABLE7)
    D = _tuples_around(TABLE7_ROOTS, chart, 400, rng)
    assert not np.any(_tuples.tuple_codes(assembly, D))
    for k in range(2):
        assert not np.any(_tuples.leaf_codes(assembly, chart, k, D[:, k]))


def test_no_test_drops_a_triple_that_holds_a_table8_root():
    rng = np.random.default_rng(5)
    chart = pfr3_certified._chart_rods(TABLE8, TABLE8_LAMBDAS)
    origins = clamps(TABLE8, TABLE8_LAMBDAS)
    assert np.array_equal([rod.origin for rod in chart], origins)
    assembly = pfr3_certified._assembly(TABLE8)
    # the pins' distances from their coordinates: rounding of a hypot only
    assert [m[2] for m in assembly.meets] == pytest.approx([TABLE8.a] * 3, rel=1e-12)
    D = _tuples_around(TABLE8_ROOTS, chart, 400, rng)
    assert not np.any(_tuples.tuple_codes(assembly, D))
    for k in range(3):
        assert not np.any(_tuples.leaf_codes(assembly, chart, k, D[:, k]))


def test_a_corefinement_certificate_has_scope_all_only(table7):
    _, data = table7
    cert = rods.CoCertificate.from_json(json.dumps(data))
    with pytest.raises(certify.CertificateError, match="'existence'"):
        rfr2_certified.verify_certificate(cert, TABLE7, TABLE7_THETA,
                                          scope="existence")
    with pytest.raises(certify.CertificateError, match="'existence'"):
        pfr3_certified.verify_certificate(cert, TABLE8, TABLE8_LAMBDAS,
                                          scope="existence")
    inputs = pfr3_certified.certificate_inputs(TABLE8, TABLE8_LAMBDAS)
    again = pfr3.Mechanism(inputs["origins"], inputs["guide_angles"], inputs["clamp_angles"],
                           inputs["a"], force=inputs["force"], moment=inputs["moment"])
    assert np.array_equal(again.vertices, TABLE8.vertices)


def test_the_tests_drop_tuples_far_from_any_root():
    """The tests have teeth: boxes a little away from the roots are dropped, each reason
    seen."""
    rng = np.random.default_rng(6)
    chart = rfr2_certified._chart_rods(TABLE7, TABLE7_THETA)
    assembly = rfr2_certified._assembly(TABLE7)
    shifted = TABLE7_ROOTS + rng.uniform(-0.05, 0.05, (len(TABLE7_ROOTS), 4))
    codes = []
    for _ in range(20):
        D = _tuples_around(shifted + rng.uniform(-0.1, 0.1, shifted.shape), chart, 30, rng)
        codes.append(_tuples.tuple_codes(assembly, D))
    seen = {_tuples.REASONS[c] for c in np.concatenate(codes)}
    assert {"tips", "force"} <= seen and np.mean(np.concatenate(codes) > 0) > 0.5


def test_clusters_are_the_connected_components():
    rng = np.random.default_rng(8)
    for _ in range(20):
        lo = rng.uniform(0, 4, (60, 3))
        boxes = np.stack((lo, lo + rng.uniform(0, 1, (60, 3))), axis=-1)
        keys = rng.integers(0, 2, 60)
        labels = clusters(boxes, keys)
        touch = np.all((boxes[:, None, :, 0] <= boxes[None, :, :, 1])
                       & (boxes[None, :, :, 0] <= boxes[:, None, :, 1]), axis=2)
        touch &= keys[:, None] == keys[None, :]
        reach = touch.copy()
        for _ in range(60):                     # transitive closure
            reach = reach | ((reach.astype(int) @ reach.astype(int)) > 0)
        assert np.array_equal(reach, labels[:, None] == labels[None, :])
        H = hulls(boxes, labels)
        assert np.all(H[labels, :, 0] <= boxes[..., 0]) and np.all(boxes[..., 1] <= H[labels,
                                                                                      :, 1])
    assert clusters(np.zeros((0, 2, 2))).shape == (0,)
    with pytest.raises(ValueError, match="boxes"):
        clusters(np.zeros((3, 2)))


@pytest.fixture(scope="module")
def table7():
    result = rfr2.certify_forward(TABLE7, TABLE7_THETA)
    cert = result.certificate(rfr2_certified.certificate_inputs(TABLE7,
                                                               TABLE7_THETA))
    return result, json.loads(cert.to_json())


def test_table7_has_exactly_three_equilibria_all_proven_stable(table7):
    result, _ = table7
    assert result.complete and result.count == 3 and result.status == "converged"
    assert result.stable == [True, True, True]
    lo, hi = result.roots[..., 0], result.roots[..., 1]
    for z in TABLE7_ROOTS:
        assert np.sum(np.all((lo <= z) & (z <= hi), axis=1)) == 1
    assert len(result.corefined.resolved) == len(result.corefined.rounds)   # none left over


def test_the_certificate_verifies_from_its_inputs(table7):
    _, data = table7
    verified = rfr2_certified.verify_certificate(
        rods.CoCertificate.from_json(json.dumps(data)), TABLE7, TABLE7_THETA)
    assert verified.count == 3 and verified.complete and verified.scope == "all"
    other = rfr2.Mechanism(origins=TABLE7.origins, force=[0.3, -0.2])
    with pytest.raises(certify.CertificateError, match="round 0"):
        rfr2_certified.verify_certificate(rods.CoCertificate.from_json(json.dumps(data)),
                                          other, TABLE7_THETA)


def _tampered(data, change):
    data = json.loads(json.dumps(data))
    change(data)
    return rods.CoCertificate.from_json(json.dumps(data))


def _flip(text, i):
    return text[:i] + ("1" if text[i] == "0" else "0") + text[i + 1:]


@pytest.mark.parametrize("change, match", [
    (lambda d: d["rounds"][3].update(live=d["rounds"][3]["live"] + 1), "round 3"),
    (lambda d: d["rounds"][2]["dropped"].update(tips=0), "round 2: dropped"),
    (lambda d: d["dims"][1].__setitem__(0, _flip(d["dims"][1][0], 3)), "round 2"),
    (lambda d: d["dims"][1].__setitem__(0, d["dims"][1][0][:-1]), "cuts"),
    (lambda d: d["dims"].pop(), "rounds"),
])
def test_a_tampered_certificate_is_refused_early(table7, change, match):
    _, data = table7
    with pytest.raises(certify.CertificateError, match=match):
        rfr2_certified.verify_certificate(_tampered(data, change), TABLE7,
                                          TABLE7_THETA)


def _drop_settled(data):
    last = max(i for i, r in enumerate(data["resolved"]) if r)
    data["resolved"][last] = data["resolved"][last][1:]


def _settle_twice(data):
    """A settled box settled again, in the rounds and in the Krawczyk search alike: the same
    root would be counted twice."""
    last = max(i for i, r in enumerate(data["resolved"]) if r)
    box = data["resolved"][last][0]
    data["resolved"][last].append(box)
    k = data["search"]["boxes"].index(box)
    data["search"]["boxes"].append(box)
    data["search"]["leaves"].append(data["search"]["leaves"][k])


@pytest.mark.parametrize("change, match", [
    (lambda d: d.update(count=4), "4"),
    (_drop_settled, "domain"),
    (_settle_twice, "overlap"),
])
def test_a_tampered_certificate_is_refused(table7, change, match):
    _, data = table7
    with pytest.raises(certify.CertificateError, match=match):
        rfr2_certified.verify_certificate(_tampered(data, change), TABLE7,
                                          TABLE7_THETA)


def test_a_certificate_that_leaves_tuples_unsettled_is_not_complete():
    """Two rounds whose live tuples no box settles, with an empty (complete) Krawczyk search:
    consistent, but not a proof."""
    chart = rfr2_certified._chart_rods(TABLE7, TABLE7_THETA)
    assembly = rfr2_certified._assembly(TABLE7)
    state = _corefine.Refinement(chart, assembly, grid=(4, 2))
    state.step()
    state.step()
    assert len(state.live)
    f, J, _, exclude = rfr2_certified.system(TABLE7, TABLE7_THETA)
    empty = certify.roots(f, J, np.zeros((0, 4, 2)))
    cert = rods.CoCertificate(state.grid, tuple(state.dims), tuple(state.resolved),
                              tuple(state.history), empty.certificate(), 0, True)
    with pytest.raises(certify.CertificateError, match="tuples left"):
        certified.verify_corefined(cert, chart, assembly, f, J, exclude)


@pytest.mark.parametrize("text", ["", "[]", '{"format": "other"}',
                                  '{"format": "mechnum-corefinement-1", "scope": "some"}',
                                  '{"format": "mechnum-corefinement-1", "scope": "all"}'])
def test_a_malformed_certificate_is_refused(text):
    with pytest.raises(certify.CertificateError):
        rods.CoCertificate.from_json(text)


CHART = rfr2_certified._chart_rods(TABLE7, TABLE7_THETA)
ASSEMBLY = rfr2_certified._assembly(TABLE7)
SYSTEM = rfr2_certified.system(TABLE7, TABLE7_THETA)


@pytest.mark.parametrize("call, match", [
    (lambda: rods.corefine("ab", ASSEMBLY, SYSTEM), "rods"),
    (lambda: rods.corefine(CHART[:1], ASSEMBLY, SYSTEM), "assembly"),
    (lambda: rods.corefine(CHART, None, SYSTEM), "assembly"),
    (lambda: rods.corefine(CHART, ASSEMBLY, SYSTEM[:2]), "system"),
    (lambda: rods.corefine(CHART, ASSEMBLY, (None, None, None, None)), "residual"),
    (lambda: rods.corefine(CHART, ASSEMBLY, SYSTEM, max_rounds=10**9), "max_rounds"),
    (lambda: rods.corefine(CHART, ASSEMBLY, SYSTEM, max_live=0), "max_live"),
    (lambda: rods.corefine(CHART, ASSEMBLY, SYSTEM, grid=(0, 4)), "grid"),
    (lambda: certified.verify_corefined("a", CHART, ASSEMBLY, *SYSTEM), "CoCertificate"),
    (lambda: certified.ChartRod(1.0, -1.0, 1, (0.0, 0.0), 0.0), "L"),
    (lambda: certified.ChartRod(1.0, 1.0, 0, (0.0, 0.0), 0.0), "mode"),
    (lambda: certified.ChartRod(1.0, 1.0, 1, (0.0, np.nan), 0.0), "origin"),
    (lambda: certified.ChartRod(1.0, 1.0, 1, (0.0, 0.0), 0.0, t_max=2.0), "t_max"),
    (lambda: certified.ChartRod(1.0, 1.0, 1, (0.0, 0.0), 0.0, lam_max=-1.0), "lam_max"),
    (lambda: certified.Assembly([], (0.0, 0.0)), "meet"),
    (lambda: certified.Assembly(((0, 0, 0.0),), (0.0, 0.0)), "meet"),
    (lambda: certified.Assembly(((0, 1, -1.0),), (0.0, 0.0)), "distance"),
    (lambda: _clusters.hulls(np.zeros((2, 1, 2)), [0, -1]), "labels"),
    (lambda: _clusters.clusters(np.zeros((2, 1, 2)), keys=[0]), "keys"),
    (lambda: _clusters.subtract([[1.0, 0.0]], np.zeros((0, 1, 2))), "lo <= hi"),
])
def test_bad_input_is_refused(call, match):
    with pytest.raises(ValueError, match=match):
        call()
