"""Tests of mechnum.rods.pinned: every equilibrium through a point, and what a shot rod is."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from mechnum import rods
from mechnum.mechanisms.elastica import study as el
from mechnum.rods import _pinned as pinned
from mechnum.rods import _regular as regular

THESIS = np.array([0.8, 0.1])         # the thesis's pinned point, EI = L = 1


def dop853(EI, L, m0, force):
    """The rod from its clamp by scipy's DOP853 (not the package's RK4): the state at L and
    the number of sign changes of m on 0 < s < L (the inflections between clamp and tip),
    where ``|m|`` exceeds ``1e-6`` of the moments (on the straight tail of a rod in tension
    ``m`` is exponentially small, below the integration's amplified error)."""
    def rhs(_, y):
        return [np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                force[0] * np.sin(y[2]) - force[1] * np.cos(y[2])]

    sol = solve_ivp(rhs, (0.0, L), [0.0, 0.0, 0.0, m0], method="DOP853", rtol=1e-13,
                    atol=1e-14, dense_output=True)
    m = sol.sol(np.linspace(0.0, L, 20001)[1:-1])[3]
    m = m[np.abs(m) > 1e-6 * max(abs(m0), np.hypot(*force) * L)]
    return sol.y[:, -1], int(np.count_nonzero(np.diff(np.sign(m))))


@pytest.fixture(scope="module")
def thesis():
    sols = rods.pinned_equilibria(1.0, 1.0, THESIS, modes=(1, 2, 3))
    return sols, rods.clamped_pinned(1.0, 1.0, sols[:, 0], sols[:, 1], sols[:, 2])


def test_every_equilibrium_at_the_thesis_point_is_one_by_dop853(thesis):
    # each root of the closed form, integrated from its clamp by another integrator, ends at
    # the point with no moment, and its moment changes sign mode - 1 times before the tip
    sols, closed = thesis
    for (psi, k_rel, mode), m0, force in zip(sols, closed.clamp_moment, closed.force):
        end, inflections = dop853(1.0, 1.0, m0, force)
        scale = max(abs(m0), np.hypot(*force))            # the moments of the problem (L = 1)
        assert np.abs(end[:2] - THESIS).max() < 1e-7, (psi, k_rel, mode)
        assert abs(end[3]) < 1e-8 * scale, (psi, k_rel, mode)
        assert inflections == mode - 1


def test_the_thesis_point_has_one_two_and_two_looped_rods_per_mode(thesis):
    # sampled counts (Newton from each of 180,000 cells of the chart per mode finds the same):
    # mode 1 has one rod, looped in tension; modes 2 and 3 have the two of the study's chart
    # and two looped ones each, among them the issue's mode-2 rod (m0 = 2.7309 EI / L,
    # n = (423.2, 56.3) EI / L**2, k_rel = 0.99961), which sampling in k_rel missed
    sols, closed = thesis
    assert sols[:, 2].tolist() == [1, 2, 2, 2, 2, 3, 3, 3, 3]
    issue = np.flatnonzero(np.abs(closed.clamp_moment - 2.7309) < 5e-5)
    assert issue.size == 1 and sols[issue[0], 2] == 2
    # the study prints the force to one decimal (423.2, 56.3): atol 0.05 is half its last unit
    assert_allclose(closed.force[issue[0]], [423.2, 56.3], rtol=0, atol=0.05)
    # and k_rel to five decimals (0.99961): atol 5e-6 is half its last unit
    assert_allclose(sols[issue[0], 1], 0.99961, rtol=0, atol=5e-6)
    looped = np.hypot(*closed.force.T) > 100      # all the looped rods are in strong tension
    assert looped.tolist() == [True, False, False, True, True, False, False, True, True]


@pytest.mark.parametrize("n_psi, n_k", [(30, 15), (240, 120)])
def test_coarser_and_finer_grids_find_the_same_equilibria(thesis, n_psi, n_k):
    sols = rods.pinned_equilibria(1.0, 1.0, THESIS, modes=(1, 2, 3), n_psi=n_psi, n_k=n_k)
    # the same roots polished by Newton to the residual 1e-13 from other grids' starts: round-off of
    # the chart
    assert_allclose(sols, thesis[0], rtol=1e-9, atol=1e-12)


def test_the_chart_t_holds_what_k_rel_cannot():
    # near the reach, a rod in tension has 1 - |k_rel| = 1.6e-231, which the study's chart
    # rounds to 1: that chart refuses, the regular one returns it
    with pytest.raises(ValueError, match="chart='t'"):
        rods.pinned_equilibria(1.0, 1.0, [0.99, 0.1], modes=(1, 2))
    sols = rods.pinned_equilibria(1.0, 1.0, [0.99, 0.1], modes=(1, 2), chart="t")
    tips = regular.clamped_pinned_regular(1.0, 1.0, sols[:, 0], sols[:, 1], sols[:, 2]).tip
    # the roots' tips recomputed in floating point; pinned_equilibria polishes to the residual 1e-13
    # (its tol), and 1e-10 allows for the amplification near k_rel = 1
    assert_allclose(tips, np.tile([0.99, 0.1], (len(sols), 1)), rtol=0, atol=1e-10)
    # k_rel's complement so close to 1 that the other chart rounds it to 1 (the point of this case)
    assert np.min(regular.k_rel_from_t(sols[:, 0], sols[:, 1], complement=True)) < 1e-200


@settings(max_examples=15, deadline=None)
@given(st.floats(0.05, 0.97), st.floats(-np.pi, np.pi), st.sampled_from([(1,), (2,), (1, 2)]))
def test_every_root_returned_is_a_distinct_equilibrium(radius, angle, modes):
    point = radius * np.array([np.cos(angle), np.sin(angle)])
    sols = rods.pinned_equilibria(2.0, 1.0, point, modes=modes, n_psi=40, n_k=20, chart="t")
    assert set(sols[:, 2]) <= set(modes)
    rod = regular.clamped_pinned_regular(2.0, 1.0, sols[:, 0], sols[:, 1], sols[:, 2])
    assert np.abs(rod.tip - point).max(initial=0.0) <= pinned.TIP_ACCEPT
    for i in range(len(sols)):
        for j in range(i):
            # two equilibria of one mode are distinct roots (their charts differ by far more than
            # the 1e-6 of Newton's tolerance)
            assert sols[i, 2] != sols[j, 2] or np.abs(sols[i, :2] - sols[j, :2]).max() > 1e-6
    R = np.hypot(*rod.force.T)
    assert np.all(np.diff(sols[:, 2]) >= 0)
    assert np.all((np.diff(sols[:, 2]) > 0) | (np.diff(R) >= 0))     # by mode, then force


def test_a_point_near_the_reach_leaks_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert len(rods.pinned_equilibria(1.0, 1.0, [0.999, 0.0])) > 0


@pytest.mark.parametrize("kwargs, match", [
    ({"n_psi": 10 ** 6}, "n_psi must be an integer <= 100000"),
    ({"n_psi": 1000, "n_k": 1000}, "n_psi \\* n_k must be at most"),
    ({"n_k": 0}, "n_k must be"),
    ({"chart": "psi"}, "chart must be one of"),
    ({"modes": (0,)}, "mode must be"),
    ({"tol": -1.0}, "tol must be positive"),
])
def test_bad_input_of_the_search(kwargs, match):
    with pytest.raises(ValueError, match=match):
        rods.pinned_equilibria(1.0, 1.0, THESIS, **kwargs)


# --- classify --------------------------------------------------------------------------------

def test_classify_names_the_equilibrium_of_a_resolved_rod(thesis):
    sols, closed = thesis
    for i in (1, 5):                          # the study's mode-2 and mode-3 rods
        guess = [closed.clamp_moment[i], *closed.force[i]]
        shot = rods.shoot_pinned(1.0, 1.0, THESIS, guess, nodes=201).rod
        verdict = rods.classify(1.0, 1.0, shot)
        assert verdict.kind == "elastica" and verdict.mode == sols[i, 2]
        # RK4 on 200 steps errs by about 1e-8 here (h^4 = 6e-10 times the derivatives): the
        # classified parameters agree to 1e-7 relative
        assert_allclose([verdict.psi, verdict.k_rel], sols[i, :2], rtol=1e-7)
        assert verdict.gap < 1e-7                  # RK4's error on 200 steps


def test_classify_works_in_any_clamp_frame():
    shot = rods.shoot_pinned(1.0, 1.0, THESIS, [4.0, -20.0, 2.0], nodes=61).rod
    c, s = np.cos(0.7), np.sin(0.7)
    turned = rods.integrate(1.0, 1.0, shot.clamp_moment, [[c, -s], [s, c]] @ shot.force,
                            theta0=0.7, origin=[2.0, -1.0], nodes=61)
    a, b = rods.classify(1.0, 1.0, shot), rods.classify(1.0, 1.0, turned)
    assert a.kind == b.kind == "elastica" and a.mode == b.mode
    # the same rod rotated and moved: the classification is invariant up to round-off of the
    # rotation
    assert_allclose([b.psi, b.k_rel], [a.psi, a.k_rel], rtol=1e-9)


def test_classify_calls_spurious_what_no_equilibrium_is_near():
    # a moment that never vanishes (|k| > 1: the rod curls in whole turns)
    curled = rods.integrate(1.0, 1.0, 5.0, [0.0, 1.0], nodes=41)
    verdict = rods.classify(1.0, 1.0, curled)
    assert verdict.kind == "spurious" and "never vanishes" in verdict.reason
    assert np.isnan(verdict.mode) and "spurious" in str(verdict)
    # Chapter 3's single shooting of the thesis's rod from the sketch that rises, then dips:
    # 61 nodes, lambda h near 1, a rod of the discrete equations only
    s = np.linspace(0.0, 1.0, el.NODES)
    y = 0.1 * s + 0.15 * np.sin(np.pi * s)
    sketch = rods.Rod(s, 0.8 * s, y, np.arctan2(np.gradient(y, s), 0.8), np.zeros(s.size),
                      np.array([0.1, 0.1]))
    with pytest.raises(rods.UnresolvedRodError) as error:
        rods.shoot_pinned_multiple(el.EI, el.LENGTH, el.TARGET, sketch, segments=1)
    verdict = rods.classify(el.EI, el.LENGTH, error.value.result.rod)
    assert verdict.kind == "spurious" and verdict.lambda_h > 0.5


def test_classify_knows_the_straight_rod():
    straight = rods.integrate(1.0, 1.0, 0.0, [-1.0, 0.0], nodes=21)
    assert rods.classify(1.0, 1.0, straight).kind == "straight"


@pytest.mark.parametrize("rod, match", [
    ("rod", "rod must be one Rod"),
    (rods.integrate(1.0, 1.0, [0.1, 0.2], [0.0, 1.0]), "rod must be one Rod"),
])
def test_classify_checks_its_rod(rod, match):
    with pytest.raises(ValueError, match=match):
        rods.classify(1.0, 1.0, rod)
