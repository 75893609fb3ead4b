"""The compiled closed form (mechnum.rods._kernels) against the numpy reference (the regular
module of mechnum.rods): Carlson's integrals, the rods, and the joint systems of the searches.

Errors are measured in each quantity's own units (tip over L, force over EI / L**2, clamp
moment over EI / L), vector by vector (the tip, the force, each row of a Jacobian: its largest
entry) and relative to the larger of the vector's size and 1: the tip's rates of a nearly
unloaded rod are differences of terms of order L in either code (the rotation of the straight
rod), determined only to the rounding of L, and a force's rate where it is stationary in ``t``
likewise.
"""

import numpy as np
import pytest
from scipy.special import elliprd, elliprf

from mechnum import rods
from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2 import _elliptic as elliptic
from mechnum.mechanisms.rfr2._model import full_system
from mechnum.rods import _kernels as kernels
from mechnum.rods import _regular as regular

EI, L = 0.0522, 0.83
UNITS = np.array([L, L, EI / L ** 2, EI / L ** 2, EI / L])


def _chart_points(n, seed, t_max):
    """Random chart points: every mode up to 3, both signs of t (both branches of each mode),
    ``|t|`` uniform up to ``t_max``, near-straight rods (tiny ``t``), rods near ``|k_rel| = 1``
    (``t`` near ``t_max``), force directions near ``psi = 0``, ``pi`` and ``2 pi``; none near
    the chart's singular point ``(pi, 0)`` (:func:`test_compiled_rods_at_the_ends_of_the_chart`
    has those)."""
    rng = np.random.default_rng(seed)
    psi = rng.uniform(1e-3, 2 * np.pi - 1e-3, n)
    t = rng.uniform(-t_max, t_max, n)
    t[::5] = rng.choice([-1.0, 1.0], t[::5].shape) * 10.0 ** rng.uniform(-300, -2, t[::5].shape)
    t[1::5] = np.sign(t[1::5]) * t_max * (1.0 - 10.0 ** rng.uniform(-9, -1, t[1::5].shape))
    psi[2::5] = rng.choice([1e-6, np.pi - 0.3, np.pi + 0.3, 2 * np.pi - 1e-6], psi[2::5].shape)
    keep = (np.abs(psi - np.pi) > 0.01) | (np.abs(t) > 0.01)
    return psi[keep], t[keep], rng.integers(1, 4, n).astype(float)[keep]


def _units(rod):
    """The rods' values and Jacobian rows in units, and each one's scale (its vector's largest
    entry, at least 1)."""
    values = np.concatenate((rod.tip, rod.force, rod.clamp_moment[:, None]), -1) / UNITS
    scale = np.concatenate([np.abs(values[:, i:j]).max(axis=-1, keepdims=True).repeat(j - i, -1)
                            for i, j in ((0, 2), (2, 4), (4, 5))], axis=-1)
    J = rod.jacobian / UNITS[:, None]
    return values, np.maximum(scale, 1.0), J, np.maximum(np.abs(J).max(-1, keepdims=True), 1.0)


def _errors(psi, t, mode, fast=kernels.closed_form):
    """The compiled rods' relative differences from the reference's, entry by entry: of the
    values, and of the Jacobian."""
    (a, _, A, _), (b, scale, B, rows) = (_units(f(EI, L, psi, t, mode))
                                         for f in (fast, regular.closed_form))
    return np.abs(a - b) / scale, np.abs(A - B) / rows


def _worst(psi, t, mode):
    return tuple(float(e.max()) for e in _errors(psi, t, mode))


def test_carlson_integrals_agree_with_scipy():
    rng = np.random.default_rng(0)
    x, y, z = rng.uniform(0.0, 2.0, (3, 2000)) * 10.0 ** rng.uniform(-12, 12, (3, 2000))
    x[::7] = 0.0
    # the arguments of the closed form: X in [0, 1], w = exp(-q) down to exp(-600)
    X, w = rng.uniform(0.0, 1.0, 2000), np.exp(-rng.uniform(0.0, 600.0, 2000))
    for ours, theirs in ((kernels.rf, elliprf), (kernels.rd, elliprd)):
        for args in ((x, y, z), (X, np.ones_like(X), w), (np.ones_like(X), w, X + 1e-300),
                     (np.zeros_like(w), w, np.ones_like(w))):
            mine = np.array([ours(*row) for row in zip(*args)])
            # both codes evaluate DLMF 19.36's series to full precision: a few ulps apart
            np.testing.assert_allclose(mine, theirs(*args), rtol=2e-15, atol=0)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_compiled_rods_agree_with_the_numpy_closed_form(seed):
    # psi uniform in (0, 2 pi), |t| up to the search's starts' START_T = 0.985: 1 - |k_rel|
    # down to 1e-14 (the study's extreme equilibria have 1e-7), every mode up to 3, both
    # branches
    values, jacobian = _worst(*_chart_points(20_000, seed, elliptic.START_T))
    assert values < 1e-13 and jacobian < 1e-13, (values, jacobian)


def test_compiled_rods_at_the_ends_of_the_chart():
    """Beyond the search's range, t up to T_MAX (1 - |k_rel| down to 1e-261), the rates
    reach 2e-12 apart: they turn on the last bits of exp, sin and R_F, which the two codes
    round differently. Near the chart's singular point (psi = pi, t -> 0: k -> 0) both codes
    lose digits as the reference's own rates do under a change of psi or t by one ulp: the
    compiled rates of each rod lie within twice that change of the reference's."""
    values, jacobian = _worst(*_chart_points(20_000, 4, regular.T_MAX))
    # relative: values to a few hundred ulps, the rates to the 2e-12 the docstring explains
    assert values < 1e-13 and jacobian < 1e-11, (values, jacobian)
    psi = np.pi + np.geomspace(1e-9, 1e-2, 300) * np.resize([-1.0, 1.0], 300)
    t = np.geomspace(1e-12, 1e-2, 300) * np.resize([1.0, 1.0, -1.0, -1.0], 300)
    mode = np.resize([1.0, 2.0, 3.0], 300)
    values, jacobian = _errors(psi, t, mode)
    ulp = np.max([_errors(psi, t, mode, moved)[1] for moved in (
        lambda *a: regular.closed_form(a[0], a[1], np.nextafter(psi, 4.0), t, mode),
        lambda *a: regular.closed_form(a[0], a[1], psi, np.nextafter(t, 0.0), mode))], axis=0)
    # values as above; each rod's rates within twice the reference's own change under one ulp
    assert values.max() < 1e-13
    assert (jacobian.max(axis=(1, 2)) <= 2 * ulp.max(axis=(1, 2)) + 1e-13).all()
    assert ulp.max() > 1e-9                 # the reference is that sensitive there


def test_one_rod_and_broadcasting_give_the_reference_shapes():
    rod = kernels.closed_form(1.0, 1.0, 2.0, 0.5, 1.0)
    assert rod.tip.shape == (2,) and rod.jacobian.shape == (5, 2)
    psi = np.full((3, 2), 2.0)
    fast = kernels.closed_form([1.0, 2.0], 1.0, psi, [0.3, -0.4], [[1.0], [2.0], [3.0]],
                               jacobian=False)
    slow = regular.closed_form([1.0, 2.0], 1.0, psi, [0.3, -0.4], [[1.0], [2.0], [3.0]],
                               jacobian=False)
    assert fast.jacobian is None and fast.tip.shape == slow.tip.shape == (3, 2, 2)
    # the same arithmetic rounded in another order: the compiled-vs-numpy bound above
    np.testing.assert_allclose(fast.tip, slow.tip, rtol=1e-13, atol=1e-15)
    empty = kernels.closed_form(1.0, 1.0, np.empty(0), np.empty(0), 1.0)
    assert empty.tip.shape == (0, 2) and empty.jacobian.shape == (0, 5, 2)


@pytest.mark.parametrize("modes", [(1, 1), (2, 3), (3, 1)])
def test_the_joint_systems_agree_with_the_reference(modes):
    """meeting (the 2RFR's direct problem in the chart) and joined (the chart and P, as the
    atlas follows it), compiled and in numpy, at random points of the chart and angles."""
    M = rfr2.study.TABLE7
    rng = np.random.default_rng(5)
    z = elliptic.sample(rng, 2000)
    theta = rng.uniform(0.0, np.pi, (2000, 2))
    u = np.concatenate((z, rng.normal(0.0, 0.3, (2000, 2))), axis=1)
    m = np.array(modes, dtype=float)
    for system, x, angles in ((kernels.meeting, z, rfr2.study.TABLE7_THETA),
                              (kernels.joined, u, theta)):
        f, J = system(M.EI, M.L, M.origins, angles, m, M.force, x)
        with kernels.reference():
            g, K = system(M.EI, M.L, M.origins, angles, m, M.force, x)
        scale = np.maximum(np.abs(g).max(axis=-1, keepdims=True), 1.0)     # per system
        assert (np.abs(f - g) / scale).max() < 1e-13
        rows = np.maximum(np.abs(K).max(axis=-1, keepdims=True), 1.0)
        assert (np.abs(J - K) / rows).max() < 1e-13
        f2, none = system(M.EI, M.L, M.origins, angles, m, M.force, x, jacobian=False)
        assert none is None and np.array_equal(f2, f)


def test_the_joint_systems_are_the_2rfr_equations():
    # the reference joint system is the 2RFR's own forward_system and full_system
    M = rfr2.study.TABLE7
    z = elliptic.sample(np.random.default_rng(6), 50)
    system = rfr2.forward_system(M, rfr2.study.TABLE7_THETA, (1, 2))
    theta, P = np.tile(rfr2.study.TABLE7_THETA, (50, 1)), np.full((50, 2), 0.1)
    with kernels.reference():
        f, J = kernels.meeting(M.EI, M.L, M.origins, rfr2.study.TABLE7_THETA, [1.0, 2.0],
                               M.force, z)
        F, JF = system(z)
        assert np.array_equal(f, F) and np.array_equal(J, JF)
        G, D = full_system(M, (1, 2))(z, theta, P)
        g, E = kernels.joined(M.EI, M.L, M.origins, theta, [1.0, 2.0], M.force,
                              np.concatenate((z, P), axis=1))
    assert np.array_equal(g, G) and np.array_equal(E, D[..., [0, 1, 2, 3, 6, 7]])


def test_meeting_rods_check_once_and_evaluate_the_kernels():
    M, theta = rfr2.study.TABLE7, rfr2.study.TABLE7_THETA
    z = elliptic.sample(np.random.default_rng(8), 20)
    rods_meet = rods.MeetingRods(M.EI, M.L, M.origins, (1, 2), M.force)
    f, J = rods_meet.meeting(theta, z)
    g, K = kernels.meeting(M.EI, M.L, M.origins, theta, [1.0, 2.0], M.force, z)
    assert np.array_equal(f, g) and np.array_equal(J, K)
    u = np.concatenate((z, np.full((20, 2), 0.1)), axis=1)
    G, D = rods_meet.joined(theta, u)
    assert G.shape == (20, 6) and D.shape == (20, 6, 6)
    for bad, message in (((M.EI, M.L, M.origins[:1], (1, 2), M.force), "one clamp per rod"),
                         ((M.EI, M.L, M.origins, (1, 0), M.force), "mode"),
                         ((-1.0, M.L, M.origins, (1, 1), M.force), "EI"),
                         ((M.EI, M.L, M.origins, (1, 1), [1.0, np.nan]), "load")):
        with pytest.raises(ValueError, match=message):
            rods.MeetingRods(*bad)
