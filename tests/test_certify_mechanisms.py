"""Tests of the certified equilibria of the rods and the flexible mechanisms (issue: proofs,
not samples): the enclosures of the closed form, the chapters' counts, the sampled solvers
against the certified ones, and the stored certificates."""

import dataclasses
import json
import pathlib

import numpy as np
import pytest
from flint import arb

from mechnum import certify, rods
from mechnum.certify.balls import ball, bounds
from mechnum.mechanisms import pfr3, rfr2
from mechnum.mechanisms.pfr3 import certified as pfr3_certified
from mechnum.mechanisms.rfr2 import certified as rfr2_certified
from mechnum.rods import _balls as balls
from mechnum.rods import _regular as regular
from mechnum.rods import certified
from mechnum.rods.certified import TWO_PI

TABLE7, THETA7 = rfr2.study.TABLE7, rfr2.study.TABLE7_THETA
TABLE8, LAMBDAS8 = pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS

CERTIFICATES = pathlib.Path(__file__).parent.parent / "book" / "certificates"


def test_the_balls_enclose_the_closed_form():
    """Random boxes of the chart, wide and narrow, at its edges too: every float evaluation
    of :mod:`mechnum.rods.regular` inside the box lies in the enclosure (to its rounding)."""
    rng = np.random.default_rng(7)
    for _ in range(60):
        mode, sign = int(rng.integers(1, 4)), int(rng.choice([-1, 1]))
        p0 = rng.uniform(0, 2 * np.pi)
        p1 = min(2 * np.pi, p0 + 10 ** rng.uniform(-5, 0.5))
        t0 = rng.choice([0.0, rng.uniform(0, regular.T_MAX)])
        t1 = min(regular.T_MAX, t0 + 10 ** rng.uniform(-6, 0))
        T = ball(t0, t1) if sign > 0 else ball(-t1, -t0)
        rod = balls.clamped_pinned(1.3, 0.9, ball(p0, p1), T, mode, sign, jacobian=True)
        psi = rng.uniform(p0, p1, 8)
        t = sign * rng.uniform(max(t0, 1e-12), t1, 8)
        ok = (psi > 0) & (psi < 2 * np.pi)
        exact = regular.clamped_pinned_regular(1.3, 0.9, psi[ok], t[ok], mode)
        values = np.column_stack((exact.tip, exact.force, exact.clamp_moment))
        for column, enclosure in enumerate(rod.tip + rod.force + [rod.moment]):
            lo, hi = bounds(enclosure)
            slack = 1e-9 * (1 + np.abs(values[:, column]))
            assert np.all((lo - slack <= values[:, column]) & (values[:, column] <= hi + slack))
        for i in range(5):
            for j in range(2):
                lo, hi = bounds(rod.jacobian[i][j])
                v = exact.jacobian[:, i, j]
                slack = 1e-7 * (1 + np.abs(v))
                assert np.all((lo - slack <= v) & (v <= hi + slack))


@pytest.fixture(scope="module")
def pinned():
    return rods.certify_pinned(1.0, 1.0, [0.8, 0.1], modes=(1, 2, 3))


def test_chapter3_pinned_rod_is_certified_complete(pinned):
    assert pinned.complete and pinned.status == "converged"
    assert pinned.count == 9 and pinned.solutions.shape == (9, 3)
    assert [int(np.sum(pinned.solutions[:, 2] == m)) for m in (1, 2, 3)] == [1, 4, 4]
    # the looped mode-2 rod that the reviewer found
    looped = pinned.solutions[np.argmin(np.abs(pinned.solutions[:, 1] - 0.99961))]
    rod = regular.clamped_pinned_regular(1.0, 1.0, looped[0],
                                         regular.t_from_k_rel(looped[0], looped[1]), 2)
    # the reviewer's values are printed to 5 significant digits (2.7309): rel 1e-4 is that rounding
    np.testing.assert_allclose(rod.clamp_moment, 2.7309, rtol=1e-4)
    # the reviewer's force is printed to 4 digits (423.2, 56.3): rel 1e-3 covers the rounding of the
    # smaller component
    np.testing.assert_allclose(rod.force, [423.2, 56.3], rtol=1e-3)
    for (psi, t), (_, _, mode) in zip(pinned.x, pinned.solutions):
        tip = regular.clamped_pinned_regular(1.0, 1.0, psi, t, mode).tip
        # a certified root, its tip recomputed in floating point: round-off of O(1) numbers
        assert np.abs(tip - [0.8, 0.1]).max() < 1e-12
    assert pinned.stable == [None] * 9


def test_pinned_sampling_equals_certified(pinned):
    sampled = rods.pinned_equilibria(1.0, 1.0, [0.8, 0.1], modes=(1, 2, 3))
    assert len(sampled) == pinned.count
    for row in pinned.solutions:
        # the sampled roots (Newton to the residual 1e-13) and the certified ones (their
        # enclosures' midpoints, far narrower) agree to round-off of the chart; 1e-8 is wide
        assert np.any(np.all(np.abs(sampled - row) < 1e-8, axis=1))


def test_certify_pinned_refuses_bad_input():
    with pytest.raises(ValueError, match="nearer than L"):
        rods.certify_pinned(1.0, 1.0, [1.0, 0.5])
    with pytest.raises(ValueError, match="mode"):
        rods.certify_pinned(1.0, 1.0, [0.8, 0.1], modes=(0,))


def _same_set(certified, sampled, tol):
    return len(certified) == len(sampled) and all(
        np.any(np.all(np.abs(sampled - row) < tol, axis=1)) for row in certified)


def test_table7_sampled_equilibria_are_proven():
    sampled = rfr2.forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA, rng=0)
    result = rfr2.certify_forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA, around=sampled.x)
    assert result.count == 3 and not result.complete and "lower bound" in result.message
    assert result.scope == "existence" and result.certificate().scope == "existence"
    assert _same_set(result.solutions, sampled.solutions, 1e-10)
    # the certified verdicts are proven, and agree with the sampled index (both resolutions)
    for verdict, index in zip(result.stable, sampled.index):
        assert verdict is bool(index.max() == 0) and index.min() == index.max()


def test_table8_sampled_equilibria_are_proven():
    sampled = pfr3.forward(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS, rng=0)
    result = pfr3.certify_forward(pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS, around=sampled.x)
    assert result.count == 9 and result.scope == "existence" and not result.complete
    assert result.status == "converged" and len(result.parts[0].undecided) == 0
    assert _same_set(result.solutions, sampled.solutions, 1e-10)
    for verdict, index in zip(result.stable, sampled.index):     # all nine proven stable
        assert verdict is bool(index.max() == 0) and index.min() == index.max()


def test_a_box_without_an_equilibrium_is_excluded():
    result = rfr2.certify_forward(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA,
                                  around=[[1.0, 0.5, 1.0, 0.5]])
    assert result.count == 0 and result.status == "converged"


def test_the_stored_table7_certificate_verifies_as_existence():
    cert = certify.Certificate.load(CERTIFICATES / "ch5_table7_modes11.json")
    f, J, _, exclude = rfr2_certified.system(rfr2.study.TABLE7, rfr2.study.TABLE7_THETA, (1, 1))
    chart = certified.branch_boxes(2)
    checked = certify.verify(cert, f, J, exclude, domain=chart)
    assert (checked.count, checked.scope, checked.complete) == (3, "existence", None)
    with pytest.raises(certify.CertificateError, match="the caller asks for 'all'"):
        certify.verify(cert, f, J, exclude, domain=chart, scope="all")
    again = rfr2_certified.verify_certificate(cert, rfr2.study.TABLE7, rfr2.study.TABLE7_THETA)
    assert (again.count, again.scope) == (3, "existence")
    with pytest.raises(certify.CertificateError, match="leaf"):          # other motor angles
        rfr2_certified.verify_certificate(cert, rfr2.study.TABLE7, rfr2.study.TABLE7_THETA + 0.01)


def test_the_stored_table8_certificate_verifies_as_existence():
    cert = certify.Certificate.load(CERTIFICATES / "ch6_table8_modes111.json")
    table8, lambdas = pfr3.study.TABLE8, pfr3.study.TABLE8_LAMBDAS
    f, J, _, exclude = pfr3_certified.system(table8, lambdas, (1, 1, 1))
    checked = certify.verify(cert, f, J, exclude, domain=certified.branch_boxes(3))
    assert (checked.count, checked.scope, checked.complete) == (9, "existence", None)
    other = pfr3_certified.system(pfr3.study.TABLE8, [0.01, 0.0, 0.0])    # other inputs: rejected
    with pytest.raises(certify.CertificateError):
        certify.verify(cert, other[0], other[1], other[3], domain=certified.branch_boxes(3))
    assert pfr3_certified.verify_certificate(cert, table8, lambdas).count == 9


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_the_stored_pinned_certificates_verify_complete(mode):
    cert = certify.Certificate.load(CERTIFICATES / f"ch3_pinned_mode{mode}.json")
    f, J = certified.pinned_system(1.0, 1.0, [0.8, 0.1], mode)
    checked = certify.verify(cert, f, J, domain=certified.branch_boxes(1))
    assert checked.scope == "all" and checked.complete
    assert checked.count == (1 if mode == 1 else 4)
    half = certify.roots(f, J, certified.branch_boxes(1)[:1]).certificate()
    with pytest.raises(certify.CertificateError, match="needs the whole domain"):
        certify.verify(half, f, J, domain=certified.branch_boxes(1))


def test_a_leaf_the_rods_refuse_is_a_certificate_error():
    """A zero-width leaf on the face t = 0 (the branches' edge, where the rods' closed form
    is refused) spliced into the stored mode-1 cover still merges into its box; verify then
    names the leaf and the rods' reason in a CertificateError."""
    data = json.loads((CERTIFICATES / "ch3_pinned_mode1.json").read_text())
    part = data["leaves"][0]
    i = next(i for i, leaf in enumerate(part) if leaf["box"][1][0] == 0.0)
    part.insert(i, {"box": [part[i]["box"][0], [0.0, 0.0]], "test": "residual"})
    f, J = certified.pinned_system(1.0, 1.0, [0.8, 0.1], 1)
    with pytest.raises(certify.CertificateError,
                       match=r"leaf .* \(residual\): the caller's functions refuse it: .*both"):
        certify.verify(certify.Certificate.from_json(json.dumps(data)), f, J,
                       domain=certified.branch_boxes(1))


def test_the_rods_refuse_boxes_across_branches_or_beyond_the_chart():
    """The branch is read from the box's own float interval: a box that ends at t = 0 is on
    its side; one across t = 0, or beyond the chart, is refused (its closed form would be
    another function, or none)."""
    f, J = certified.pinned_system(1.0, 1.0, [0.8, 0.1], 1)
    inside = f(certify.balls.guarded([[0.1, 0.2], [-0.5, 0.0]]))
    assert len(inside) == 2 and all(v.is_finite() for v in inside)
    for box, match in (([[0.1, 0.2], [-0.5, 0.5]], "both branches"),
                       ([[0.1, 0.2], [0.0, 0.0]], "both branches"),
                       ([[-0.1, 0.2], [0.1, 0.5]], "leaves the chart"),
                       ([[0.1, 0.2], [0.1, 1.0]], "leaves the chart")):
        with pytest.raises(ValueError, match=match):
            f(certify.balls.guarded(box))
        with pytest.raises(ValueError, match=match):
            certify.roots(f, J, box)
    with pytest.raises(ValueError, match="both branches"):        # a plain ball across 0
        f([ball(0.1, 0.2), ball(-0.5, 0.0)])


def test_boxes_around_points_stay_in_the_chart_and_the_branch():
    boxes = certified.around_boxes([[0.0, -0.5], [3.0, 1e-9], [TWO_PI, regular.T_MAX]], 1)
    assert boxes[0, 0, 0] == 0.0 and boxes[0, 1, 1] < 0.0
    # exact comparisons: the boxes are cut at the chart's ends, which are floats (no tolerance)
    assert boxes[1, 1, 0] == 0.0 and boxes[1, 1, 1] > 1e-9
    assert boxes[2, 0, 1] == TWO_PI and boxes[2, 1, 1] == regular.T_MAX
    for points in ([[1.0, 0.0]], [[-0.1, 0.5]], [[1.0, 1.0]]):
        with pytest.raises(ValueError, match="points of the chart"):
            certified.around_boxes(points, 1)


def test_arcs_meet_modulo_two_pi_at_any_number_of_turns():
    """The polar force test's arcs, shifted by whole turns (up to 10**6), agree with the
    arcs reduced to one turn (in floats, with a margin: arcs closer than it are skipped)."""
    rng = np.random.default_rng(29)
    pi = balls.B.PI
    checked = 0
    for _ in range(400):
        a0, b0 = rng.uniform(-np.pi, np.pi, 2)
        wa, wb = rng.uniform(0.01, 3.0), rng.uniform(0.01, 3.0)
        turns = int(rng.choice([-10**6, -7, -3, 3, 4, 9, 10**6]))
        gap = (b0 - a0) % TWO_PI                   # b's start, from a's start, in [0, 2 pi)
        meet = gap <= wa or gap + wb >= TWO_PI
        margin = min(abs(gap - wa), abs(gap + wb - TWO_PI))
        if margin < 1e-6:
            continue
        a = (arb(a0) + 2 * turns * pi, arb(a0 + wa) + 2 * turns * pi)
        assert certified._arcs_meet(a, (arb(b0), arb(b0 + wb))) == meet
        checked += 1
    assert checked > 350


def _one_root_around(system, mech, inputs, point, half):
    f, J, _, exclude = system(mech, inputs)
    box = np.column_stack((point - half, point + half))
    r = certify.roots(f, J, box, exclude=exclude, split=exclude.split, max_boxes=2000)
    return r, certify.verify(r.certificate(), f, J, exclude, domain=box)


@pytest.mark.parametrize("turns", [2, -3, 10**6])
def test_rfr2_motor_angles_plus_whole_turns_keep_their_equilibria(turns):
    """The same 2RFR with its motor angles turned by whole turns: a box around a known
    equilibrium is proven to hold it (the polar test once excluded it, 'complete, 0')."""
    point = rfr2.forward(TABLE7, THETA7, rng=0).x[0]
    theta = THETA7 + 2 * np.pi * turns
    r, v = _one_root_around(rfr2_certified.system, TABLE7, theta, point, 1e-3)
    assert (r.count, r.complete) == (1, True) and (v.count, v.complete) == (1, True)


def test_pfr3_clamp_angles_plus_whole_turns_keep_their_equilibria():
    """The same 3PFR with its clamps turned by three whole turns keeps Table 8's first
    equilibrium (the polar test once excluded its box)."""
    mech = dataclasses.replace(TABLE8, clamp_angles=TABLE8.clamp_angles + 6 * np.pi)
    point = pfr3.forward(TABLE8, LAMBDAS8, rng=0).x[0]
    r, v = _one_root_around(pfr3_certified.system, mech, LAMBDAS8, point, 1e-6)
    assert (r.count, r.complete) == (1, True) and (v.count, v.complete) == (1, True)


def test_the_verifier_refuses_an_exclusion_by_the_old_arc_test(monkeypatch):
    """A certificate made with the arcs compared at shifts -2..2 only (the old test) excludes
    a box around an equilibrium at motor angles + 2 turns; the verifier, re-running the
    caller's exclusion test, refuses it."""
    def old(a, b):
        two_pi = 2 * balls.B.PI
        return any(not (bool(a[1] + k * two_pi < b[0]) or bool(a[0] + k * two_pi > b[1]))
                   for k in (-2, -1, 0, 1, 2))
    point = rfr2.forward(TABLE7, THETA7, rng=0).x[0]
    theta = THETA7 + 4 * np.pi
    f, J, _, exclude = rfr2_certified.system(TABLE7, theta)
    box = np.column_stack((point - 1e-3, point + 1e-3))
    with monkeypatch.context() as patch:
        patch.setattr(certified, "_arcs_meet", old)
        bad = certify.roots(f, J, box, exclude=exclude, split=exclude.split, max_boxes=2000)
    assert (bad.count, bad.complete) == (0, True)          # the old hole
    f, J, _, exclude = rfr2_certified.system(TABLE7, theta)
    with pytest.raises(certify.CertificateError, match="exclusion test fails"):
        certify.verify(bad.certificate(), f, J, exclude, domain=box)
