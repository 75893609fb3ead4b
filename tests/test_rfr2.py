"""Tests of mechnum.mechanisms.rfr2: the flexible 2RFR mechanism of Chapter 5."""

import inspect
from pathlib import Path

import numpy as np
import pytest
from published import check_row, read_registry

from mechnum import newton
from mechnum.errors import GeometryError
from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2 import _analysis as analysis
from mechnum.mechanisms.rfr2 import _elliptic as elliptic
from mechnum.mechanisms.rfr2 import _shooting as shooting
from mechnum.mechanisms.rfr2 import _trajectories as trajectories
from mechnum.results import STATUSES

MECH, THETA = rfr2.study.TABLE7, rfr2.study.TABLE7_THETA
REGISTRY = Path(__file__).resolve().parents[1] / "book" / "published_values.csv"


@pytest.fixture(scope="module")
def table7():
    return rfr2.forward(MECH, THETA, rng=0)


def test_table7_equilibria_and_their_properties(table7):
    eq = table7
    assert eq.solutions.shape == (3, 4) and eq.pose.shape == (3, 2) and eq.stable.shape == (3,)
    assert eq.search.complete and eq.search.n_check == 10 * eq.search.n_starts
    # both published solutions are among them (to their 6 printed decimals)
    for printed in rfr2.study.TABLE7_PUBLISHED:
        assert np.abs(eq.solutions - printed).max(axis=1).min() <= 5e-7
    assert eq.stable.all() and eq.settled.all()
    assert eq.rods_cross.tolist() == [1, 0, 0] and not eq.self_cross.any()
    np.testing.assert_allclose(eq.forces.sum(axis=1), np.broadcast_to(MECH.force, (3, 2)),
                               rtol=0, atol=1e-12)
    assert np.abs(rfr2.residual(MECH, THETA, eq.x)).max() < 1e-12


def test_equilibria_pass_the_independent_check(table7):
    err, moment, inflections = rfr2.verify(MECH, THETA, table7.x)
    assert err.max() < 1e-10 and np.abs(moment).max() < 1e-10
    assert (inflections == 1).all()


def test_higher_modes_are_found_and_checked():
    eq = rfr2.forward(MECH, THETA, modes=(1, 3), n_starts=400, rng=3)
    assert len(eq.pose) == 4
    # three of them with rod 1 in near-straight tension, 1 - |k_rel1| < 1e-7
    assert np.sum(1 - np.abs(eq.solutions[:, 1]) < 1e-7) == 3
    err, moment, inflections = rfr2.verify(MECH, THETA, eq.x, (1, 3))
    assert err.max() < 1e-10 and np.abs(moment).max() < 1e-9
    assert (inflections == [1, 3]).all()
    assert not eq.stable.any() and eq.settled.all()


def test_shooting_agrees_with_the_closed_form(table7):
    eq = table7
    X = rfr2.shooting_guess(MECH, THETA, eq.x)
    fk = rfr2.forward_shooting(MECH, THETA, X + 1e-3, nodes=801)   # a perturbed guess
    assert fk.newton.converged.all()
    assert np.abs(fk.pose - eq.pose).max() < 1e-10
    assert np.abs(fk.clamp_moments - eq.clamp_moments).max() < 1e-10
    Xi = rfr2.shooting_guess(MECH, THETA, eq.x, unknown="inputs")
    ik = rfr2.inverse_shooting(MECH, eq.pose, Xi + 1e-3, nodes=801)
    assert ik.newton.converged.all() and np.abs(ik.inputs - THETA).max() < 1e-10
    # round trip: shooting -> the study's (psi, k_rel) -> the closed form
    path = rfr2.forward_path(MECH, np.array([THETA]), eq.x[0], nodes=801)
    np.testing.assert_allclose(path.chart[0], eq.x[0], rtol=0, atol=1e-9)


def test_the_study_n41_shooting_misses_by_rk4_error(table7):
    X = rfr2.shooting_guess(MECH, THETA, table7.x)
    fk = rfr2.forward_shooting(MECH, THETA, X)          # the study's 41 nodes
    assert 1e-7 < np.abs(fk.pose - table7.pose).max() < 1e-6


def test_shooting_jacobian_matches_finite_differences(table7):
    fun, _ = shooting.shooting_system(MECH, 41, "inputs")
    X = rfr2.shooting_guess(MECH, THETA, table7.x[:1], unknown="inputs")
    known = table7.pose[:1]
    h = 1e-7
    fd = np.stack([(fun(X + h * e, known)[0] - fun(X - h * e, known)[0]) / (2 * h)
                   for e in np.eye(8)], axis=-1)
    np.testing.assert_allclose(fun(X, known)[1], fd, rtol=0, atol=1e-6 * np.abs(fd).max())


def test_closed_form_jacobian_of_the_mechanism(table7):
    system = rfr2.forward_system(MECH, THETA)
    z = table7.x + 0.01
    h = 1e-6
    fd = np.stack([(system(z + h * e)[0] - system(z - h * e)[0]) / (2 * h) for e in np.eye(4)],
                  axis=-1)
    np.testing.assert_allclose(system(z)[1], fd, rtol=1e-6, atol=1e-6)


def test_singularity_determinants(table7):
    J = rfr2.jacobians(MECH, THETA, table7.x)
    # dP/dtheta by finite differences of the direct problem
    thetas = np.array([THETA, THETA + [1e-6, 0], THETA + [0, 1e-6]])
    path = rfr2.forward_path(MECH, thetas, table7.x[2], method="elliptic")
    fd = (path.pose[1:] - path.pose[0]).T / 1e-6
    np.testing.assert_allclose(J.dpose_dinputs[2], fd, rtol=1e-4)
    np.testing.assert_allclose(np.linalg.det(J.dpose_dinputs) * J.det_fk, J.det_ik, rtol=1e-10)


def test_inverse_path_by_both_methods(table7):
    points = table7.pose[2] + trajectories.straight_path(0.05, np.pi, 10)
    fast = rfr2.inverse_path(MECH, points, THETA, table7.x[2], method="elliptic")
    study = rfr2.inverse_path(MECH, points, THETA, table7.x[2], nodes=201)
    assert fast.converged.all() and study.converged.all()
    assert np.abs(fast.inputs - study.inputs).max() < 1e-7
    np.testing.assert_allclose(fast.pose, points, rtol=0, atol=1e-12)


def test_shooting_path_crosses_a_mode_change(table7):
    # from the study's solution 2 the clamp moment of rod 2 vanishes on the way: closed form
    # (fixed modes) stops there, shooting goes on into mode (1, 2)
    points = table7.pose[1] + trajectories.straight_path(0.5, np.pi, 100)[:30]
    fast = rfr2.inverse_path(MECH, points, THETA, table7.x[1], method="elliptic")
    study = rfr2.inverse_path(MECH, points, THETA, table7.x[1])
    assert not fast.converged.all() and study.converged.all()
    assert [1, 2] in study.modes.tolist()


def test_forward_map_starts_at_the_equilibrium(table7):
    grid = rfr2.forward_map(MECH, np.radians([38.0, 40.0, 42.0]), np.radians([59.0, 61.0]),
                            THETA, table7.x[2])
    assert grid.pose.shape == (3, 2, 2) and grid.converged.all()
    assert np.abs(rfr2.residual(MECH, grid.inputs, grid.chart)).max() < 1e-11


def test_draw_returns_artists_on_the_rods(table7):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    artists = rfr2.draw(ax, MECH, table7.state(0))
    assert len(artists) == 8 and len(ax.lines) == 7
    assert sorted(artists) == ["end_effector", "load", "motor1", "motor2", "rod1", "rod2",
                               "tangent1", "tangent2"]
    x, y = rfr2.shapes(MECH, THETA, table7.x[0])
    for r, line in ((0, artists["rod1"]), (1, artists["rod2"])):
        # each rod from its own motor, along its motor's angle, to the end effector
        np.testing.assert_allclose(np.column_stack(line.get_data()),
                                   np.column_stack((x[r], y[r])), rtol=0, atol=1e-12)
        np.testing.assert_allclose(line.get_xydata()[0], MECH.origins[r], rtol=0, atol=1e-12)
        np.testing.assert_allclose(line.get_xydata()[-1], table7.pose[0], rtol=0, atol=1e-9)
        start = line.get_xydata()[1] - MECH.origins[r]         # the first chord, L / 200
        assert abs(np.arctan2(start[1], start[0]) - THETA[r]) < 0.03
        tangent = np.diff(artists[f"tangent{r + 1}"].get_xydata(), axis=0)[0]
        np.testing.assert_allclose(np.arctan2(tangent[1], tangent[0]), THETA[r], rtol=1e-12)
    # moved to another equilibrium: the same artists, on its rods
    again = rfr2.draw(ax, MECH, table7.state(2), artists=artists)
    assert again is artists and len(ax.lines) == 7
    np.testing.assert_allclose(artists["rod1"].get_xydata()[-1], table7.pose[2], rtol=0,
                               atol=1e-9)
    np.testing.assert_allclose(artists["load"].xy, table7.pose[2] + 0.3 * MECH.force,
                               rtol=1e-12)
    with pytest.raises(ValueError, match="ax must be"):
        rfr2.draw(None, MECH, table7.state(0))
    with pytest.raises(ValueError, match="artists must be"):
        rfr2.draw(ax, MECH, table7.state(0), artists={"rod1": artists["rod1"]})
    with pytest.raises(ValueError, match="state must be a State"):
        rfr2.draw(ax, MECH, THETA)
    plt.close(fig)


def test_study_paths():
    assert rfr2.study.path("inverse line").shape == (101, 2)
    np.testing.assert_allclose(rfr2.study.path("inverse line")[-1], [-0.5, 0.0], rtol=0,
                               atol=1e-15)
    circles = rfr2.study.path("direct circles")
    assert circles.shape == (41, 2)
    # five circles of diameters 0.04 to 0.2, eight points each from angle 0, and the centre
    radii = np.hypot(*circles.T)
    np.testing.assert_allclose(np.unique(np.round(radii, 12)), [0, 0.02, 0.04, 0.06, 0.08, 0.1],
                               rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(circles[1], [0.02, 0.0], rtol=1e-12)
    corners = rfr2.study.path("inverse rectangles")
    assert corners.shape == (65, 2) and np.abs(corners).max() == pytest.approx(0.1, rel=1e-12)
    with pytest.raises(ValueError, match="bound on the work"):
        trajectories.circles(0.2, 10**4, 10**3)


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
        rfr2.forward(MECH, theta, modes=modes, n_starts=8)


def test_angles_with_no_equilibrium_give_an_empty_result():
    # motors 1.9 m apart turned away from each other: the rods meet in hairpins at 83 N
    mech = rfr2.Mechanism(origins=[[-0.95, 0.0], [0.95, 0.0]])
    eq = rfr2.forward(mech, [np.pi, 0.0], n_starts=40, check=2, rng=0)
    assert len(eq.pose) == 4 and np.allclose(np.linalg.norm(eq.forces, axis=-1), 83.4976, atol=1e-3)
    # 1.998 m apart they would need ~1e5 EI / L**2: beyond any rod of the chart (T_MAX)
    mech = rfr2.Mechanism(origins=[[-0.999, 0.0], [0.999, 0.0]])
    eq = rfr2.forward(mech, [np.pi, 0.0], n_starts=40, check=2, rng=0)
    assert eq.solutions.shape == (0, 4) and eq.pose.shape == (0, 2) and eq.stable.shape == (0,)
    assert eq.rods_cross.shape == (0,)


def test_unreachable_end_effector_is_not_converged():
    sol = rfr2.inverse_shooting(MECH, [3.0, 0.0], np.zeros(8) + 0.1)
    assert not sol.newton.converged.any()
    assert set(sol.newton.status) <= set(STATUSES)


def test_bad_chart_is_a_value_error():
    with pytest.raises(ValueError, match="chart"):
        rfr2.residual(MECH, THETA, [1.0, 0.0, 1.0, 0.5])


def test_reproduce_matches_the_registry_keys():
    # every value of reproduce() has its row, and each row says what the value is
    values = rfr2.study.reproduce()
    rows = read_registry(REGISTRY, "05_flexible_2rfr")
    assert set(values) <= {row["quantity"] for row in rows}
    for row in rows:
        check_row(row, values.get(row["quantity"]))


# --- the mechanism protocol and the shared results (issue 22) --------------------------------

def test_forward_follows_the_result_contract(table7):
    eq = table7
    assert eq.status.tolist() == ["converged"] * 3 and eq.converged.all()
    assert eq.x.shape == (3, 4) and eq.nfev > 0 and eq.njev > 0
    assert "3 equilibria from 200 starts" in eq.message and "no other" in eq.message
    # the inputs given, one pose per equilibrium
    assert np.array_equal(eq.inputs, THETA) and eq.pose.shape == (3, 2)
    state = eq.state(1)
    assert state.modes == (1, 1) and np.array_equal(state.chart, eq.x[1])


def test_inverse_finds_every_equilibrium_at_an_end_effector(table7):
    eq = rfr2.inverse(MECH, table7.pose[2], rng=0)
    # the forward equilibrium is among them, with its motor angles
    k = np.argmin(np.abs(eq.inputs - THETA).max(axis=1))
    assert np.abs(eq.inputs[k] - THETA).max() < 1e-10
    np.testing.assert_allclose(eq.x[k], table7.x[2], rtol=0, atol=1e-9)
    # every one of them an equilibrium with its end effector at P (checked independently)
    assert np.abs(rfr2.residual(MECH, eq.inputs, eq.x)).max() < 1e-12
    tips = rfr2.rods(MECH, eq.inputs, eq.x, jacobian=False)[0]
    assert np.abs(tips - table7.pose[2]).max() < 1e-12
    assert eq.pose.shape == (2,) and eq.inputs.shape == (len(eq.x), 2)
    assert eq.search.complete and len(eq.x) >= 2
    system = elliptic.inverse_system(MECH, table7.pose[2])
    h, z = 1e-6, eq.x + 0.01
    fd = np.stack([(system(z + h * e)[0] - system(z - h * e)[0]) / (2 * h) for e in np.eye(4)],
                  axis=-1)
    np.testing.assert_allclose(system(z)[1], fd, rtol=1e-6, atol=1e-6)


def test_strain_is_the_largest_bending_strain(table7):
    from mechnum.rods import _profile as profile
    strain = analysis.strain(MECH, THETA, table7.x)
    np.testing.assert_array_equal(strain, table7.strain)
    # sampled along the rods (20001 nodes): the closed form is the supremum of the samples
    for z, e in zip(table7.x, strain):
        rod = profile.shape(MECH.EI, MECH.L, z[0::2], z[1::2], 1, nodes=20001)
        sampled = 0.5 * MECH.diameter * np.abs(rod.m).max(axis=-1) / MECH.EI
        assert (sampled <= e * (1 + 1e-12)).all() and (sampled > e * (1 - 1e-7)).all()
    # music wire bends 0.77 %: Table 7's solution 1 needs 0.79 %, so only the equilibrium
    # whose rods neither cross nor yield can be built
    assert table7.elastic.tolist() == [True, True, False]
    assert table7.crossing_free.tolist() == [False, True, True]
    assert table7.buildable.tolist() == [False, True, False]
    stronger = rfr2.Mechanism(MECH.origins, MECH.force, strain_limit=0.01)
    assert rfr2.forward(stronger, THETA, rng=0).buildable.tolist() == [
        False, True, True]


def test_the_jump_of_chapter_5_across_a_fold_is_no_converged_point():
    # Chapter 5's inverse circles from its first equilibrium: between points 22 and 23 Newton
    # leapt across a fold (det_ik from -1e4 to +1e4, theta2 from 89 to 136 deg)
    eq = rfr2.forward(MECH, THETA, rng=2)
    circles = eq.pose[0] + rfr2.study.path("inverse circles")
    ik = rfr2.inverse_path(MECH, circles, THETA, eq.x[0])
    assert ik.converged[:22].all() and ik.status[22] == "branch-jump"
    assert not ik.converged[22:].any() and np.isnan(ik.inputs[22:]).all()
    assert (np.sign(ik.det_ik[ik.converged]) == -1).all()
    assert "22 of 41 points converged" in ik.message


def test_dpose_dinputs_is_the_derivative_for_rods_of_any_length():
    long = rfr2.Mechanism([[-0.6, 0.0], [0.6, 0.0]], force=[1.2, -0.4], L=2.0)
    eq = rfr2.forward(long, THETA, n_starts=100, check=1, rng=0)
    J = rfr2.jacobians(long, THETA, eq.x)
    h = 1e-6
    for k in range(len(eq.x)):
        steps = np.array([THETA, THETA + [h, 0], THETA + [0, h]])
        path = rfr2.forward_path(long, steps, eq.x[k], method="elliptic")
        fd = (path.pose[1:] - path.pose[0]).T / h
        np.testing.assert_allclose(J.dpose_dinputs[k], fd, rtol=1e-4, atol=1e-6)
    np.testing.assert_allclose(np.linalg.det(J.dpose_dinputs) * J.det_fk, J.det_ik, rtol=1e-9)


def test_workspace_ends_where_the_inverse_problem_folds(table7):
    edge = rfr2.workspace(MECH, table7.state(2), directions=4, step=0.02, levels=4)
    assert edge.pose.shape == (4, 2) and edge.converged.all()
    reach = np.hypot(*(edge.pose - table7.pose[2]).T)
    assert (reach > 0.4).all() and (reach < 0.8).all()
    # where the rods kept their modes, the closed form's det_ik has fallen to a hundredth of
    # its value at the start: the branch folds there (shooting changed a mode on one ray)
    kept = (edge.modes == 1).all(axis=1)
    centre = rfr2.jacobians(MECH, THETA, table7.x[2]).det_ik
    end = rfr2.jacobians(MECH, edge.inputs[kept], edge.chart[kept]).det_ik
    assert kept.sum() >= 2 and (np.abs(end) < 0.01 * np.abs(centre)).all()


def test_singular_points_of_a_map(table7):
    g = np.radians(np.linspace(0.0, 180.0, 19))
    grid = rfr2.forward_map(MECH, g, g, THETA, table7.x[0])
    points = rfr2.singular_points(MECH, grid)
    assert len(points) > 0
    # each between two grid neighbours where det_ik changes sign, on the map's grid axes
    step = g[1] - g[0]
    assert ((points >= g[0]) & (points <= g[-1])).all()
    on_lines = np.isclose(np.remainder(points / step + 0.5, 1.0) - 0.5, 0.0, atol=1e-9)
    assert on_lines.any(axis=1).all()
    with pytest.raises(ValueError, match="grid must be a map"):
        rfr2.singular_points(MECH, rfr2.inverse_path(MECH, table7.pose[:1], THETA,
                                                     table7.x[0]))


# --- issue 23: bad input, empty batches, bounds ---------------------------------------------

@pytest.mark.parametrize("method", ["shooting", "elliptic"])
def test_empty_paths_are_valid(table7, method):
    ik = rfr2.inverse_path(MECH, np.empty((0, 2)), THETA, table7.x[2], method=method)
    fk = rfr2.forward_path(MECH, [], table7.x[2], method=method)
    for path in (ik, fk):
        assert path.inputs.shape == (0, 2) and path.chart.shape == (0, 4)
        assert path.status.shape == (0,) and path.message == "0 of 0 points converged"


def test_an_empty_grid_is_a_valid_map(table7):
    grid = rfr2.forward_map(MECH, [], np.radians([58.0, 60.0]), THETA, table7.x[2])
    assert grid.pose.shape == (0, 2, 2) and grid.converged.shape == (0, 2)


@pytest.mark.parametrize("call", [
    lambda z: rfr2.residual(MECH, np.zeros((3, 2)), np.stack([z, z])),
    lambda z: rfr2.shapes(MECH, np.zeros((3, 2)), np.stack([z, z])),
    lambda z: analysis.crossings(MECH, np.zeros((3, 2)), np.stack([z, z])),
    lambda z: rfr2.jacobians(MECH, np.zeros((3, 2)), np.stack([z, z])),
])
def test_shapes_that_do_not_broadcast_are_named(table7, call):
    with pytest.raises(ValueError, match="chart of shape .* and theta of shape"):
        call(table7.x[0])


def test_shooting_batches_that_do_not_match_are_named(table7):
    X = rfr2.shooting_guess(MECH, THETA, table7.x[:2], unknown="inputs")
    with pytest.raises(ValueError, match="3 known values for 2 seeds"):
        rfr2.inverse_shooting(MECH, np.zeros((3, 2)), X)
    with pytest.raises(ValueError, match="thetas must have a last axis of 2"):
        rfr2.forward_path(MECH, np.zeros((4, 3)), table7.x[0])


@pytest.mark.parametrize("rng", ["a", -1, 1.5])
def test_bad_rng_is_a_value_error(rng):
    with pytest.raises(ValueError, match="rng must be"):
        rfr2.forward(MECH, THETA, n_starts=8, rng=rng)


@pytest.mark.parametrize("mech", [None, "TABLE7", object()])
def test_a_mechanism_of_the_wrong_kind_is_named(mech):
    from mechnum.mechanisms import pfr3
    for bad in (mech, pfr3.study.TABLE8):
        with pytest.raises(ValueError, match="mech must be a Mechanism"):
            rfr2.forward(bad, THETA, n_starts=8, rng=0)


@pytest.mark.parametrize("rtol", [0.0, 1e-300, -1e-8, 0.1])
def test_verify_refuses_tolerances_it_cannot_meet(table7, rtol):
    with pytest.raises(ValueError, match="rtol"):
        rfr2.verify(MECH, THETA, table7.x, rtol=rtol)


def test_stability_checks_its_resolutions_and_its_equilibrium(table7):
    z = table7.x[0]
    with pytest.raises(ValueError, match="bound on the work"):
        analysis.stability(MECH, THETA, z, segments=(200, 10**6))
    with pytest.raises(ValueError, match="pair of integers"):
        analysis.stability(MECH, THETA, z, segments=200)
    with pytest.raises(ValueError, match="pair of integers"):
        analysis.stability(MECH, THETA, z, segments=(200,))
    assert analysis.index(MECH, THETA, z, segments=100) == 0
    with pytest.raises(ValueError, match="no equilibrium"):
        analysis.stability(MECH, THETA, [1.0, 0.5, 2.0, 0.5])
    with pytest.raises(ValueError, match="bound on the work"):
        analysis.eigenvalues(MECH, THETA, z, segments=10**5)


@pytest.mark.parametrize("flag", ["yes", 1, None])
def test_flags_must_be_bools(table7, flag):
    with pytest.raises(ValueError, match="resume must be True or False"):
        rfr2.forward_path(MECH, [THETA], table7.x[0], resume=flag)
    with pytest.raises(ValueError, match="jacobian must be True or False"):
        rfr2.rods(MECH, THETA, table7.x[0], jacobian=flag)


def test_sizes_are_bounded(table7):
    with pytest.raises(ValueError, match="bound on the work"):
        rfr2.forward(MECH, THETA, n_starts=10**6)
    with pytest.raises(ValueError, match="bound on the work"):
        rfr2.forward(MECH, THETA, check=1000)
    with pytest.raises(ValueError, match="bound on the work"):
        rfr2.forward_path(MECH, [THETA], table7.x[0], nodes=10**7)
    with pytest.raises(ValueError, match="bound on the work"):
        rfr2.workspace(MECH, table7.state(0), step=1e-6)


@pytest.mark.parametrize(("theta", "modes"), [(THETA, (1, 1)), (np.radians([55.0, 62.0]), (1, 1)),
                                              (THETA, (2, 3))])
def test_every_start_of_the_lockstep_search_ends_as_it_does_alone(theta, modes):
    """The search and its check run as one batch (each start's rows evaluated together with
    the others', the halvings of all the starts that refuse a full step tried in one call);
    each start, run alone as a batch of one (its halvings one at a time), ends with the same
    status, after the same iterations, at the same point."""
    from mechnum.rods import _kernels as kernels

    halvings = inspect.signature(newton.solve_all).parameters["halvings"].default
    found = elliptic.search_roots(MECH, theta, modes, 25, 3, 7)
    rng = np.random.default_rng(7)
    starts = np.concatenate((elliptic.sample(rng, 25), elliptic.sample(rng, 75)))
    M = MECH

    def both(z):
        return kernels.meeting(M.EI, M.L, M.origins, theta, np.array(modes, float), M.force, z)

    alone = [newton.solve_batch(both, start[None], True, tol=elliptic.SEARCH_TOL,
                                maxiter=elliptic.SEARCH_MAXITER, damping=True,
                                domain=elliptic.in_chart_rows, raise_on_failure=False,
                                halvings=halvings) for start in starts]
    lockstep = found[0]
    assert lockstep.status.tolist() == [r.status[0] for r in alone]
    assert lockstep.iterations.tolist() == [r.iterations[0] for r in alone]
    assert len(set(lockstep.status.tolist())) > 2             # the test sees several outcomes
    ends = np.array([r.x[0] for r in alone])[lockstep.status == "converged"]
    for root in lockstep.x:           # the same roots, and no other
        assert (np.abs(ends - root).max(axis=1) < 1e-12).any()
    gap = np.abs(ends[:, None] - lockstep.x[None]).max(axis=-1).min(axis=1)
    assert gap.max() < 1e-8
