"""Tests of mechnum.rods.regular, stability and crossing: the methods the flexible mechanisms
(Chapters 5 and 6) are built on."""

import numpy as np
import pytest

from mechnum import rods
from mechnum.rods import _crossing as crossing
from mechnum.rods import _regular as regular
from mechnum.rods import _stability as stability

EI, L = 0.0522, 1.0


def _random_rods(n, seed):
    rng = np.random.default_rng(seed)
    psi = rng.uniform(0.05, 2 * np.pi - 0.05, n)
    t = rng.uniform(0.02, 0.97, n) * rng.choice([-1.0, 1.0], n)
    return psi, t, rng.integers(1, 4, n).astype(float)


def test_regular_chart_agrees_with_the_study_chart():
    psi, t, mode = _random_rods(500, 1)
    k_rel = regular.k_rel_from_t(psi, t)
    keep = np.abs(k_rel) < 1 - 1e-6          # where scipy's m = k**2 still holds its digits
    a = regular.clamped_pinned_regular(EI, L, psi[keep], t[keep], mode[keep])
    b = rods.clamped_pinned(EI, L, psi[keep], k_rel[keep], mode[keep])
    assert np.abs(a.tip - b.tip).max() < 1e-9
    # the two charts' closed forms agree up to scipy's loss of digits near k = 1, which the mask
    # above keeps below 1e-9
    np.testing.assert_allclose(a.force, b.force, rtol=1e-9, atol=1e-12)
    # as above, for the forces
    np.testing.assert_allclose(a.clamp_moment, b.clamp_moment, rtol=1e-9, atol=1e-12)


def test_chart_conversions_round_trip_to_both_ends():
    psi = np.array([0.3, 2.0, np.pi, 4.0, 6.1, 2.0, 5.0])
    k_rel = np.array([1e-9, -1e-6, 0.5, -0.999, 1 - 1e-9, -(1 - 1e-12), 0.3])
    # the round trip through t loses the digits of 1 - |k_rel| that t carries (k_rel up to 1 -
    # 1e-12): 1e-9 relative
    np.testing.assert_allclose(regular.k_rel_from_t(psi, regular.t_from_k_rel(psi, k_rel)),
                               k_rel, rtol=1e-9, atol=0)


def test_analytic_jacobian_matches_central_differences():
    psi, t, mode = _random_rods(300, 2)
    rod = regular.clamped_pinned_regular(EI, L, psi, t, mode)

    def out(p, s):
        r = regular.clamped_pinned_regular(EI, L, p, s, mode, jacobian=False)
        return np.concatenate((r.tip, r.force, r.clamp_moment[:, None]), axis=-1)

    h = 1e-6
    fd = np.stack(((out(psi + h, t) - out(psi - h, t)) / (2 * h),
                   (out(psi, t + h) - out(psi, t - h)) / (2 * h)), axis=-1)
    scale = 1 + np.abs(rod.jacobian)
    # central differences with h = 1e-6 err by h^2 times the third derivatives (about 1e-12) and
    # round-off eps / h ~ 1e-10: 1e-6 relative to 1 + |J| is wide
    assert np.max(np.abs(fd - rod.jacobian) / scale) < 1e-6


@pytest.mark.parametrize("jacobian", [True, False])
def test_closed_form_computes_each_integral_once_on_the_rows_that_need_it(monkeypatch,
                                                                         jacobian):
    """Carlson integrals per rod: every rod needs R_F and R_D of its partial wave; the others
    than mode 1 on its growing branch K and E(k) (two more); the growing branch R_D(1, w, X)
    for its rates, and R_F once more where its excess's series does not serve (a large load).
    Counted, row by row, in one batch that mixes them all."""
    from mechnum.rods import _growing as growing

    evaluated = {"rows": 0}

    def counted(integral):
        def call(*args):
            out = integral(*args)
            evaluated["rows"] += np.size(out)
            return out
        return call

    for module in (regular, growing):
        for name in ("elliprf", "elliprd"):
            monkeypatch.setattr(module, name, counted(getattr(module, name)))
    # (psi, t, mode): a = cos(psi/2) > 0 for psi < pi, so t > 0 there is the growing branch
    rows = [(1.0, 1e-3, 1), (2.0, 2e-4, 1),          # growing, small load: series
            (1.0, 0.9, 1), (2.5, 0.7, 1),           # growing, large load
            (1.0, -0.5, 1), (4.0, 0.5, 1), (1.0, 0.5, 2), (5.0, -0.3, 3)]   # the others
    need = [2 + jacobian] * 2 + [3 + jacobian] * 2 + [4] * 4
    psi, t, mode = (np.array(c, dtype=float) for c in zip(*rows))
    regular.closed_form(EI, L, psi, t, mode, jacobian=jacobian)
    assert evaluated["rows"] == sum(need)
    for row, count in zip(rows, need):                  # and one rod at a time
        evaluated["rows"] = 0
        regular.closed_form(EI, L, *row, jacobian=jacobian)
        assert evaluated["rows"] == count, row


def test_one_rod_of_several_stiffnesses_broadcasts():
    # EI of shape (3,) against one (psi, t): three rods, the force and Jacobian scale with EI
    rod = regular.closed_form(np.array([1.0, 2.0, 4.0]), L, 2.0, 0.5)
    one = regular.closed_form(1.0, L, 2.0, 0.5)
    assert rod.force.shape == (3, 2) and rod.jacobian.shape == (3, 5, 2)
    # EI enters as a factor (exact for a power of two); 1e-15: room for one rounding
    np.testing.assert_allclose(rod.jacobian[2, 2:], 4.0 * one.jacobian[2:], rtol=1e-15)


def test_chart_stays_accurate_in_near_straight_tension():
    # k_rel within 1e-9 of -1: the closed form against an RK4 rod shot from the same clamp
    from scipy.integrate import solve_ivp

    psi, t = 5.3, regular.t_from_k_rel(5.3, -(1 - 1e-9))
    rod = regular.clamped_pinned_regular(EI, L, psi, t)
    n = rod.force
    sol = solve_ivp(lambda s, y: [np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                                  n[0] * np.sin(y[2]) - n[1] * np.cos(y[2])],
                    (0.0, L), [0.0, 0.0, 0.0, rod.clamp_moment], method="DOP853",
                    rtol=1e-13, atol=1e-14)
    # integrating a rod in tension from its clamp amplifies errors by ~cosh(L sqrt(R / EI))
    assert np.abs(sol.y[:2, -1] - rod.tip).max() < 1e-10 and abs(sol.y[3, -1]) < 1e-9


def test_place_rotates_tip_force_and_derivatives():
    rod = regular.clamped_pinned_regular(EI, L, np.array([1.0, 4.0]), np.array([0.4, -0.6]))
    tip, _force, _d_chart, d_angle = regular.place(rod, [[1.0, 2.0], [0.0, 0.0]], [0.3, -1.0])
    h = 1e-7
    for i, angle in enumerate((0.3, -1.0)):
        a = regular.place(rod, [[1.0, 2.0], [0.0, 0.0]],
                          [angle + h if i == 0 else 0.3, angle + h if i == 1 else -1.0])
        b = regular.place(rod, [[1.0, 2.0], [0.0, 0.0]],
                          [angle - h if i == 0 else 0.3, angle - h if i == 1 else -1.0])
        fd = (np.concatenate((a[0][i], a[1][i])) - np.concatenate((b[0][i], b[1][i]))) / (2 * h)
        # as above, central differences with the test's h: 1e-7 absolute covers both errors for O(1)
        # derivatives
        np.testing.assert_allclose(d_angle[i], fd, rtol=0, atol=1e-7)
    # a rigid placement keeps distances: the same lengths up to round-off of the rotation
    np.testing.assert_allclose(np.hypot(*(tip - [[1.0, 2.0], [0.0, 0.0]]).T),
                               np.hypot(*rod.tip.T), rtol=1e-14)


@pytest.mark.parametrize("psi, t, match", [(0.0, 0.5, "psi"), (7.0, 0.5, "psi"),
                                            (1.0, 0.0, "t must"), (1.0, 1.0, "t must"),
                                            (np.nan, 0.5, "finite"), (1.0, 0.5j, "real")])
def test_bad_chart_input_is_a_value_error(psi, t, match):
    with pytest.raises(ValueError, match=match):
        regular.clamped_pinned_regular(EI, L, psi, t)


def test_bad_mode_is_a_value_error():
    with pytest.raises(ValueError, match="mode"):
        regular.clamped_pinned_regular(EI, L, 1.0, 0.5, mode=0)


# --- stability ---------------------------------------------------------------------------

@pytest.mark.parametrize("segments", [60, 200])
@pytest.mark.parametrize("load, index", [(0.95 * 20.19, 0), (1.05 * 20.19, 1),
                                         (0.95 * 59.68, 1), (1.05 * 59.68, 2)])
def test_clamped_pinned_column_buckles_at_its_critical_loads(load, index, segments):
    """Euler: a column clamped at one end and pinned at the other buckles at
    P L**2 / EI = 20.19 (beta L = 4.4934) and 59.68 (7.7253)."""
    block = stability.rod_block(1.0, 1.0, np.zeros(segments), [-load, 0.0])
    assert stability.constrained_index([block], block.tip_gradient) == index
    eigen = stability.constrained_eigenvalues(block.hessian, block.tip_gradient)
    assert np.sum(eigen < 0) == index


@pytest.mark.parametrize("load, index", [(0.95 * np.pi ** 2 / 4, 0), (1.05 * np.pi ** 2 / 4, 1)])
def test_free_cantilever_buckles_at_the_euler_load(load, index):
    block = stability.rod_block(1.0, 1.0, np.zeros(100), [-load, 0.0])
    eigen = stability.constrained_eigenvalues(block.hessian, np.empty((0, 100)))
    assert np.sum(eigen < 0) == index


def test_eigenvalues_converge_to_the_continuous_second_variation():
    # unloaded clamped-pinned rod: lowest Rayleigh quotient (EI / L**2) beta**2 = 20.19
    values = []
    for n in (100, 200):
        block = stability.rod_block(1.0, 1.0, np.zeros(n), [0.0, 0.0])
        values.append(stability.constrained_eigenvalues(block.hessian, block.tip_gradient)[0]
                      / block.h)
    assert abs(values[1] - 20.19073) < 0.01 and abs(values[0] - values[1]) < 0.01


# --- crossings ---------------------------------------------------------------------------

def test_crossings_of_polylines():
    s = np.linspace(-np.pi, np.pi, 300)
    assert crossing.self_crossings(s - 2 * np.sin(s), 1 - 2 * np.cos(s)) == 1
    assert crossing.self_crossings(np.cos(s), np.sin(s)) == 0
    u = np.linspace(0, 1, 50)
    assert crossing.mutual_crossings(u, u, u, 1 - u) == 1
    # two rods that meet at their shared tip only
    assert crossing.mutual_crossings(u, u, 2 - u, u) == 0
    # two rods pinned together at their last point: touching there is no crossing
    assert crossing.mutual_crossings(u, u ** 2, u, u, shared_tip=True) == 0


@pytest.mark.parametrize("seed", range(20))
def test_crossing_counts_do_not_depend_on_the_bounding_boxes(seed, monkeypatch):
    """Random walks (many crossings): the pruned count equals the count over all pairs."""
    rng = np.random.default_rng(seed)
    x, y = rng.standard_normal((2, rng.integers(2, 90))).cumsum(axis=1)
    u, v = rng.standard_normal((2, rng.integers(2, 90))).cumsum(axis=1)
    u[-1], v[-1] = x[-1], y[-1]
    counts = [crossing.self_crossings(x, y), crossing.mutual_crossings(x, y, u, v),
              crossing.mutual_crossings(x, y, u, v, shared_tip=True)]
    monkeypatch.setattr(crossing, "BLOCK", 1000)          # one box: every pair compared
    assert counts == [crossing.self_crossings(x, y), crossing.mutual_crossings(x, y, u, v),
                      crossing.mutual_crossings(x, y, u, v, shared_tip=True)]


def test_crossing_input_is_checked():
    with pytest.raises(ValueError, match="polyline"):
        crossing.self_crossings([0.0], [0.0])
