"""Tests of mechnum.rods._apriori: the reach of a loaded rod and the a-priori bounds on the
load of a pinned rod and of the 2RFR's rods, against the closed form and sampled equilibria."""

import numpy as np
import pytest
import scipy.optimize
from flint import arb

from mechnum import rods
from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
from mechnum.rods import _apriori, certified
from mechnum.rods import _regular as regular


def _chart(n, seed, near_euler=False):
    """Chart points of every mode and branch; ``near_euler``: near the straight rod at the
    Euler load (``psi = pi``, ``t -> 0-``), where the reach is largest."""
    rng = np.random.default_rng(seed)
    if near_euler:
        psi = np.pi + rng.uniform(-1e-3, 1e-3, n)
        t = -10 ** rng.uniform(-8, -3, n)
    else:
        psi = rng.uniform(1e-3, 2 * np.pi - 1e-3, n)
        t = rng.uniform(1e-6, regular.T_MAX, n) * rng.choice([-1.0, 1.0], n)
    return psi, t


def _reach_ratio(psi, t, mode):
    """``Lambda |tip / L - e|`` of chart rods (``EI = L = 1``)."""
    rod = regular.clamped_pinned_regular(1.0, 1.0, psi, t, mode, jacobian=False)
    lam = np.sqrt(np.hypot(*rod.force.T))
    e = np.stack((np.cos(psi), np.sin(psi)), axis=-1)
    return lam * np.hypot(*(rod.tip - e).T)


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_every_rod_lies_within_its_reach(mode):
    """Everywhere in the chart, and where the constant is nearly attained: a smaller constant
    than the largest sampled ratio (``2 pi mode`` near the straight rod at the Euler load)
    would fail here."""
    ratios = np.concatenate([_reach_ratio(*_chart(4000, mode), mode),
                             _reach_ratio(*_chart(500, mode, near_euler=True), mode)])
    assert np.all(ratios <= _apriori.reach(mode))
    assert ratios.max() > 0.95 * _apriori.reach(mode)
    # near the Euler load D -> j pi, v b -> 0: the ratio approaches 2 j pi from below
    assert ratios.max() > 2 * np.pi * mode * (1 - 1e-3)


def test_reach_is_rounded_up_and_checks_its_mode():
    exact = 2 * ((arb.pi()) ** 2 + 1).sqrt()
    # rounded up by one ulp or so of 6.59 (8.9e-16): far below 1e-14
    assert bool(arb(_apriori.reach(1)) >= exact) and _apriori.reach(1) - float(exact.mid()) < 1e-14
    for bad in (0, 11, 1.5, True, "1", None):
        with pytest.raises(ValueError, match="mode"):
            _apriori.reach(bad)


def test_chart_t_bound_holds_every_rod_below_the_load():
    psi, t = _chart(20000, 4)
    for mode in (1, 2, 3):
        rod = regular.clamped_pinned_regular(1.0, 1.0, psi, t, mode, jacobian=False)
        lam = np.sqrt(np.hypot(*rod.force.T))
        for lam_max in (2.0, 10.39, 34.0):
            assert np.all(np.abs(t[lam <= lam_max]) <= certified.chart_t_bound(lam_max))
    # the bound is nearly attained: a rod just inside it carries almost lam_max
    bound = certified.chart_t_bound(10.39)
    tip = regular.clamped_pinned_regular(1.0, 1.0, 1e-4, bound * (1 - 1e-12), 1).force
    assert np.sqrt(np.hypot(*tip)) > 10.39 - np.log(2) - 1e-3
    assert certified.chart_t_bound(1e4) == regular.T_MAX
    # |t| = (q / (1 + q))**(1/2) with q = 2 log cosh(1e-3), about 1e-3
    assert 0 < certified.chart_t_bound(1e-3) < 0.05
    for tiny in (5e-324, 1e-300, 1e-10):     # q <= lam**2 rounded up: finite, near lam
        assert tiny * (1 - 1e-9) <= certified.chart_t_bound(tiny) <= 2 * np.sqrt(tiny)


def test_pinned_bound_holds_every_pinned_equilibrium():
    rng = np.random.default_rng(5)
    targets = [np.array([0.8, 0.1])] + [rng.uniform(-0.7, 0.7, 2) for _ in range(5)]
    for target in targets:
        d = float(np.hypot(*target))
        found = rods.pinned_equilibria(1.0, 1.0, target, modes=(1, 2, 3), chart="t")
        assert len(found)
        for psi, t, mode in found:
            rod = regular.clamped_pinned_regular(1.0, 1.0, psi, t, mode, jacobian=False)
            lam = np.sqrt(np.hypot(*rod.force))
            assert lam <= _apriori.pinned_bound(int(mode), d, 1.0)
    assert round(_apriori.pinned_bound(1, np.hypot(0.8, 0.1), 1.0)) == 34
    assert round(_apriori.pinned_bound(3, np.hypot(0.8, 0.1), 1.0)) == 98
    with pytest.raises(ValueError, match="distance"):
        _apriori.pinned_bound(1, 1.0, 1.0)


def _excess(lam, c1, c2, f, room):
    return 2 * f / lam ** 2 + c1 / lam + c2 / np.sqrt(lam ** 2 - f) - room


def test_pair_bound_is_the_crossing_and_proven():
    mech = TABLE7
    F = float(np.hypot(*mech.force))
    f, room = F * mech.L ** 2 / mech.EI, 2 - 0.6 / mech.L
    for modes in ((1, 1), (1, 3), (2, 1)):
        bound = certified.pair_bound(modes, 0.6, F, mech.EI, mech.L)
        for i in range(2):
            c = [_apriori.reach(modes[i]), _apriori.reach(modes[1 - i])]
            crossing = scipy.optimize.brentq(_excess, np.sqrt(f) + 1e-9, 1e4,
                                             args=(*c, f, room), xtol=1e-14)
            # brentq to xtol 1e-14 on a crossing near 10: both within 1e-9 of the other
            np.testing.assert_allclose(bound[i], crossing, rtol=1e-9)
            assert bool(_apriori._excess(bound[i], _apriori._reach_ball(modes[i]),
                                         _apriori._reach_ball(modes[1 - i]), arb(f),
                                         arb(room)) < 0)


def _table7_like(seed):
    rng = np.random.default_rng(seed)
    gap = rng.uniform(0.2, 1.2)
    return (rfr2.Mechanism(origins=[[-gap / 2, 0.0], [gap / 2, 0.0]],
                           force=rng.uniform(-0.5, 0.5, 2)), rng.uniform(0.2, 2.8, 2))


@pytest.mark.parametrize("seed", [None, 1, 2, 3])
def test_pair_bound_holds_every_sampled_equilibrium(seed):
    mech, theta = ((TABLE7, TABLE7_THETA) if seed is None else _table7_like(seed))
    F = float(np.hypot(*mech.force))
    gap = float(np.hypot(*(mech.origins[1] - mech.origins[0])))
    for modes in ((1, 1), (1, 2)):
        sampled = rfr2.forward(mech, theta, modes=modes, rng=0)
        bound = certified.pair_bound(modes, gap, F, mech.EI, mech.L)
        for forces in np.asarray(sampled.forces).reshape(-1, 2, 2):
            lam = np.sqrt(np.hypot(*forces.T) / mech.EI) * mech.L
            assert np.all(lam < np.array(bound))


@pytest.mark.parametrize("args, match", [
    (((1,), 0.6, 0.3, 0.05, 1.0), "two modes"), (((1, 0), 0.6, 0.3, 0.05, 1.0), "modes"),
    (((1, 1), 2.0, 0.3, 0.05, 1.0), "gap"), (((1, 1), 0.6, -0.3, 0.05, 1.0), "force"),
    (((1, 1), 0.6, 0.3, -0.05, 1.0), "EI"), (((1, 1), 0.6, np.nan, 0.05, 1.0), "force")])
def test_pair_bound_refuses_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        certified.pair_bound(*args)


def test_the_pinned_bound_excludes_the_tail_where_the_chart_argument_cannot():
    """At 0.975 L the chart's tail argument (rods beyond ``q = Q_MAX`` reach no nearer than
    0.972 L) does not exclude the tail; the a-priori bound (``Lambda <= 264``, inside the
    chart) does. At 0.985 L neither does."""
    near = rods.certify_pinned(1.0, 1.0, [0.975, 0.0], modes=(1,), max_boxes=50)
    far = rods.certify_pinned(1.0, 1.0, [0.985, 0.0], modes=(1,), max_boxes=50)
    assert "beyond the chart are not excluded" not in near.message
    assert "beyond the chart are not excluded" in far.message
    assert certified.chart_t_bound(_apriori.pinned_bound(1, 0.975, 1.0)) < regular.T_MAX
    assert certified.chart_t_bound(_apriori.pinned_bound(1, 0.985, 1.0)) == regular.T_MAX
