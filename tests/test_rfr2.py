"""Tests of mechnum.mechanisms.rfr2: the flexible 2RFR mechanism of Chapter 5."""

from pathlib import Path

import numpy as np
import pytest

from mechnum import newton
from mechnum.errors import GeometryError
from mechnum.mechanisms import rfr2
from mechnum.published import check_row, read_registry

MECH, THETA = rfr2.TABLE7, rfr2.TABLE7_THETA
REGISTRY = Path(__file__).resolve().parents[1] / "book" / "published_values.csv"


@pytest.fixture(scope="module")
def table7():
    return rfr2.forward_elliptic(MECH, THETA, rng=0)


def test_table7_equilibria_and_their_properties(table7):
    eq = table7
    assert eq.solutions.shape == (3, 4) and eq.P.shape == (3, 2) and eq.stable.shape == (3,)
    assert eq.search.complete and eq.search.n_check == 10 * eq.search.n_starts
    # both published solutions are among them (to their 6 printed decimals)
    for printed in rfr2.TABLE7_PUBLISHED:
        assert np.abs(eq.solutions - printed).max(axis=1).min() <= 5e-7
    assert eq.stable.all() and eq.settled.all()
    assert eq.rods_cross.tolist() == [1, 0, 0] and not eq.self_cross.any()
    np.testing.assert_allclose(eq.forces.sum(axis=1), np.broadcast_to(MECH.force, (3, 2)),
                               atol=1e-12)
    assert np.abs(rfr2.residual(MECH, THETA, eq.chart)).max() < 1e-12


def test_equilibria_pass_the_independent_check(table7):
    err, moment, inflections = rfr2.verify(MECH, THETA, table7.chart)
    assert err.max() < 1e-10 and np.abs(moment).max() < 1e-10
    assert (inflections == 1).all()


def test_higher_modes_are_found_and_checked():
    eq = rfr2.forward_elliptic(MECH, THETA, (1, 3), n_starts=400, rng=3)
    assert len(eq.P) == 4
    # three of them with rod 1 in near-straight tension, 1 - |k_rel1| < 1e-7
    assert np.sum(1 - np.abs(eq.solutions[:, 1]) < 1e-7) == 3
    err, moment, inflections = rfr2.verify(MECH, THETA, eq.chart, (1, 3))
    assert err.max() < 1e-10 and np.abs(moment).max() < 1e-9
    assert (inflections == [1, 3]).all()
    assert not eq.stable.any() and eq.settled.all()


def test_shooting_agrees_with_the_closed_form(table7):
    eq = table7
    X = rfr2.shooting_guess(MECH, THETA, eq.chart)
    fk = rfr2.forward_shooting(MECH, THETA, X + 1e-3, nodes=801)   # a perturbed guess
    assert fk.newton.converged.all()
    assert np.abs(fk.P - eq.P).max() < 1e-10
    assert np.abs(fk.clamp_moments - eq.clamp_moments).max() < 1e-10
    Xi = rfr2.shooting_guess(MECH, THETA, eq.chart, unknown="theta")
    ik = rfr2.inverse_shooting(MECH, eq.P, Xi + 1e-3, nodes=801)
    assert ik.newton.converged.all() and np.abs(ik.theta - THETA).max() < 1e-10
    # round trip: shooting -> the study's (psi, k_rel) -> the closed form
    path = rfr2.forward_path(MECH, np.array([THETA]), eq.chart[0], nodes=801)
    np.testing.assert_allclose(path.chart[0], eq.chart[0], atol=1e-9)


def test_the_study_n41_shooting_misses_by_rk4_error(table7):
    X = rfr2.shooting_guess(MECH, THETA, table7.chart)
    fk = rfr2.forward_shooting(MECH, THETA, X)          # the study's 41 nodes
    assert 1e-7 < np.abs(fk.P - table7.P).max() < 1e-6


def test_shooting_jacobian_matches_finite_differences(table7):
    fun, jac, _ = rfr2.shooting_system(MECH, 41, "theta")
    X = rfr2.shooting_guess(MECH, THETA, table7.chart[:1], unknown="theta")
    known = table7.P[:1]
    h = 1e-7
    fd = np.stack([(fun(X + h * e, known) - fun(X - h * e, known)) / (2 * h)
                   for e in np.eye(8)], axis=-1)
    np.testing.assert_allclose(jac(X, known), fd, atol=1e-6 * np.abs(fd).max())


def test_closed_form_jacobian_of_the_mechanism(table7):
    fun, jac = rfr2.forward_system(MECH, THETA)
    z = table7.chart + 0.01
    h = 1e-6
    fd = np.stack([(fun(z + h * e) - fun(z - h * e)) / (2 * h) for e in np.eye(4)], axis=-1)
    np.testing.assert_allclose(jac(z), fd, rtol=1e-6, atol=1e-6)


def test_singularity_determinants(table7):
    J = rfr2.jacobians(MECH, THETA, table7.chart)
    # dP/dtheta by finite differences of the direct problem
    thetas = np.array([THETA, THETA + [1e-6, 0], THETA + [0, 1e-6]])
    path = rfr2.forward_path(MECH, thetas, table7.chart[2], method="elliptic")
    fd = (path.P[1:] - path.P[0]).T / 1e-6
    np.testing.assert_allclose(J.dP_dtheta[2], fd, rtol=1e-4)
    np.testing.assert_allclose(np.linalg.det(J.dP_dtheta) * J.det_fk, J.det_ik, rtol=1e-10)


def test_inverse_path_by_both_methods(table7):
    points = table7.P[2] + rfr2.straight_path(0.05, np.pi, 10)
    fast = rfr2.inverse_path(MECH, points, THETA, table7.chart[2], method="elliptic")
    study = rfr2.inverse_path(MECH, points, THETA, table7.chart[2], nodes=201)
    assert fast.converged.all() and study.converged.all()
    assert np.abs(fast.theta - study.theta).max() < 1e-7
    np.testing.assert_allclose(fast.P, points, atol=1e-12)


def test_shooting_path_crosses_a_mode_change(table7):
    # from the study's solution 2 the clamp moment of rod 2 vanishes on the way: closed form
    # (fixed modes) stops there, shooting goes on into mode (1, 2)
    points = table7.P[1] + rfr2.straight_path(0.5, np.pi, 100)[:30]
    fast = rfr2.inverse_path(MECH, points, THETA, table7.chart[1], method="elliptic")
    study = rfr2.inverse_path(MECH, points, THETA, table7.chart[1])
    assert not fast.converged.all() and study.converged.all()
    assert [1, 2] in study.modes.tolist()


def test_forward_map_starts_at_the_equilibrium(table7):
    grid = rfr2.forward_map(MECH, np.radians([38.0, 40.0, 42.0]), np.radians([59.0, 61.0]),
                            THETA, table7.chart[2])
    assert grid.P.shape == (3, 2, 2) and grid.converged.all()
    assert np.abs(rfr2.residual(MECH, grid.theta, grid.chart)).max() < 1e-11


def test_draw_returns_artists(table7):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    artists = rfr2.draw(ax, MECH, table7.state(0))
    assert len(artists) >= 8 and len(ax.lines) >= 7
    plt.close(fig)


def test_study_paths():
    assert rfr2.path("inverse line").shape == (101, 2)
    np.testing.assert_allclose(rfr2.path("inverse line")[-1], [-0.5, 0.0], atol=1e-15)
    assert rfr2.path("direct circles").shape == (41, 2)
    corners = rfr2.path("inverse rectangles")
    assert corners.shape == (65, 2) and np.abs(corners).max() == pytest.approx(0.1)


# --- bad input ------------------------------------------------------------------------------

def test_motors_too_far_apart_for_the_rods():
    with pytest.raises(GeometryError, match="cannot meet"):
        rfr2.Mechanism(origins=[[0.0, 0.0], [2.5, 0.0]])
    with pytest.raises(GeometryError, match="EI"):
        rfr2.Mechanism(origins=[[0.0, 0.0], [0.5, 0.0]], EI=-1.0)


@pytest.mark.parametrize("theta, modes, match", [([np.nan, 1.0], (1, 1), "finite"),
                                                  ([1.0], (1, 1), "shape"),
                                                  ([1.0, 2.0], (0, 1), "modes"),
                                                  ([1.0, 2.0], (1, 1.5), "modes")])
def test_bad_forward_input(theta, modes, match):
    with pytest.raises(ValueError, match=match):
        rfr2.forward_elliptic(MECH, theta, modes, n_starts=8)


def test_angles_with_no_equilibrium_give_an_empty_result():
    # motors 1.9 m apart turned away from each other: the rods meet in hairpins at 83 N
    mech = rfr2.Mechanism(origins=[[-0.95, 0.0], [0.95, 0.0]])
    eq = rfr2.forward_elliptic(mech, [np.pi, 0.0], n_starts=40, check=2, rng=0)
    assert len(eq.P) == 4 and np.allclose(np.linalg.norm(eq.forces, axis=-1), 83.4976, atol=1e-3)
    # 1.998 m apart they would need ~1e5 EI / L**2: beyond any rod of the chart (T_MAX)
    mech = rfr2.Mechanism(origins=[[-0.999, 0.0], [0.999, 0.0]])
    eq = rfr2.forward_elliptic(mech, [np.pi, 0.0], n_starts=40, check=2, rng=0)
    assert eq.solutions.shape == (0, 4) and eq.P.shape == (0, 2) and eq.stable.shape == (0,)
    assert eq.rods_cross.shape == (0,)


def test_unreachable_end_effector_is_not_converged():
    sol = rfr2.inverse_shooting(MECH, [3.0, 0.0], np.zeros(8) + 0.1)
    assert not sol.newton.converged.any()
    assert set(sol.newton.status) <= set(newton.STATUSES)


def test_bad_chart_is_a_value_error():
    with pytest.raises(ValueError, match="chart"):
        rfr2.residual(MECH, THETA, [1.0, 0.0, 1.0, 0.5])


def test_reproduce_matches_the_registry_keys():
    # every value of reproduce() has its row, and each row says what the value is
    values = rfr2.reproduce()
    rows = read_registry(REGISTRY, "05_flexible_2rfr")
    assert set(values) <= {row["quantity"] for row in rows}
    for row in rows:
        check_row(row, values.get(row["quantity"]))
