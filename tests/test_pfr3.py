"""Tests of the flexible 3PFR mechanism (mechnum.mechanisms.pfr3)."""

import numpy as np
import pytest

from mechnum.errors import GeometryError, UnreachablePoseError
from mechnum.mechanisms import pfr3
from mechnum.mechanisms.pfr3 import equilibria, model, shooting, study
from mechnum.rods import regular
from mechnum.rods.stability import constrained_eigenvalues

MECH, LAMBDAS = pfr3.TABLE8, pfr3.TABLE8_LAMBDAS


@pytest.fixture(scope="module")
def table8():
    return pfr3.forward_elliptic(MECH, LAMBDAS, rng=0)


def _central(fun, x, h):
    """Central differences of a batched ``fun`` at the rows of ``x``: (batch, out, in)."""
    cols = [(fun(x + h * e) - fun(x - h * e)) / (2 * h) for e in np.eye(x.shape[1])]
    return np.stack(cols, axis=-1)


def test_reduced_jacobian_is_the_derivative_of_the_residual(table8):
    fun, jac = model.forward_system(MECH, LAMBDAS, (1, 2, 1))
    z = equilibria.sampler(MECH, LAMBDAS)(np.random.default_rng(3), 20)
    z = z[model.in_chart(z + 1e-6) & model.in_chart(z - 1e-6)]
    J, Jn = jac(z), _central(fun, z, 1e-6)
    assert np.abs(J - Jn).max() < 1e-6 * np.abs(J).max()


def test_full_jacobian_is_the_derivative_of_the_nine_equations(table8):
    system = model.full_system(MECH)
    n = len(table8.chart)
    v = np.concatenate((table8.chart, np.broadcast_to(LAMBDAS + 0.01, (n, 3)),
                        table8.pose + 0.02), axis=1)

    def G(u):
        return system(u[:, :6], u[:, 6:9], u[:, 9:])[0]

    D = system(v[:, :6], v[:, 6:9], v[:, 9:])[1]
    assert np.abs(D - _central(G, v, 1e-7)).max() < 1e-6 * np.abs(D).max()


@pytest.mark.parametrize("unknown", ["pose", "lambdas"])
@pytest.mark.parametrize("rigid_end", [0.0, shooting.STUDY_RIGID_END])
def test_shooting_jacobian_is_the_derivative_of_109(table8, unknown, rigid_end):
    fun, jac, _ = shooting.shooting_system(MECH, 101, unknown, rigid_end)
    printed = table8.chart[table8.buildable]
    X = pfr3.shooting_guess(MECH, LAMBDAS, printed, unknown=unknown) + 0.01
    known = table8.pose[table8.buildable] if unknown == "lambdas" else np.zeros((2, 3))
    J, Jn = jac(X, known), _central(lambda x: fun(x, known), X, 1e-6)
    assert np.abs(J - Jn).max() < 1e-7 * np.abs(J).max()


def test_table8_has_nine_mode1_equilibria_all_verified(table8):
    assert len(table8.pose) == 9 and table8.search.complete
    err, moment, inflections, pieces = pfr3.verify(MECH, LAMBDAS, table8.chart)
    assert err.max() < 1e-10 and np.abs(moment).max() < 1e-9
    assert (inflections == 1).all() and pieces.max() > 1      # some rods in strong tension
    residual = model.forward_system(MECH, LAMBDAS)[0](table8.chart)
    assert np.abs(residual).max() < 1e-10       # forces of 60 N are 1e3 EI / L**2


def test_the_printed_solutions_are_the_truncated_buildable_equilibria(table8):
    assert table8.buildable.sum() == 2
    found = np.trunc(table8.solutions[table8.buildable] * 1e4) / 1e4
    assert np.allclose(np.sort(found, axis=0), np.sort(study.TABLE8_PUBLISHED, axis=0),
                       atol=1e-9)


def test_closed_form_and_shooting_agree_both_ways(table8):
    z = table8.chart[table8.buildable]
    X = pfr3.shooting_guess(MECH, LAMBDAS, z) + 1e-3
    direct = pfr3.forward_shooting(MECH, LAMBDAS, X, nodes=801)
    assert direct.newton.converged.all()
    assert np.abs(direct.pose - table8.pose[table8.buildable]).max() < 1e-10
    Xi = pfr3.shooting_guess(MECH, LAMBDAS, z, unknown="lambdas") + 1e-3
    inverse = pfr3.inverse_shooting(MECH, table8.pose[table8.buildable], Xi, nodes=801)
    assert np.abs(inverse.lambdas - LAMBDAS).max() < 1e-10
    # and back: the clamp states of shooting give the closed form's rods
    assert np.abs(inverse.forces - table8.forces[table8.buildable]).max() < 1e-9


def test_the_formulation_admits_no_mirror_image():
    real = pfr3.forward_elliptic(pfr3.TABLE2, pfr3.TABLE2_LAMBDAS, rng=1)
    mirror = pfr3.forward_elliptic(pfr3.TABLE2.mirrored(), pfr3.TABLE2_LAMBDAS, rng=1,
                                   check=0)
    assert len(real.pose) == 3
    assert (study.orientation(pfr3.TABLE2, pfr3.TABLE2_LAMBDAS, real.chart) == 1).all()
    assert (study.orientation(pfr3.TABLE2, pfr3.TABLE2_LAMBDAS, mirror.chart) == -1).all()
    reach = mirror.chart[study.within_study_reach(mirror.chart)]
    # the study's residual (114) vanishes at a mirror image, the package's does not
    assert np.abs(study.thesis_residual(pfr3.TABLE2, pfr3.TABLE2_LAMBDAS,
                                        model.thesis_from_chart(reach))).max() < 1e-8
    fun = model.forward_system(pfr3.TABLE2, pfr3.TABLE2_LAMBDAS)[0]
    assert len(reach) == 3 and np.abs(fun(reach)).max(axis=1).min() > 0.1


def test_recovered_inputs_of_table8():
    good = study.recover_inputs(study.TABLE8_PUBLISHED, np.radians([45.0, 180.0, -60.0]))
    assert np.allclose(np.degrees(good["clamp_angles"]), [45.0, 180.0, -60.0], atol=0.01)
    assert abs(good["a"] - 0.2) < 1e-4 and abs(good["EI"] / model.EI - 1) < 1e-4
    printed = study.recover_inputs(study.TABLE8_PUBLISHED, np.radians([45.0, 0.0, -60.0]))
    assert printed["residual"] > 1e3 * good["residual"]


def _discrete_lagrangian(mech, z, segments):
    """The discretised Lagrangian of one equilibrium as a function of (angles, P, phi), with
    the multipliers (the rods' tip forces) and clamps of the equilibrium."""
    force = model.rods(mech, LAMBDAS, z, jacobian=False)[1]
    clamps, h, EI = model.clamps(mech, LAMBDAS), mech.L / segments, mech.EI

    def L(x):
        theta, P, phi = x[:3 * segments].reshape(3, segments), x[-3:-1], x[-1]
        B = model.pins(mech, np.concatenate((P, [phi])))
        total = -mech.force @ P - mech.moment * phi
        for i in range(3):
            t = theta[i]
            total += EI / h * (t[0] - mech.clamp_angles[i]) ** 2
            total += EI / (2 * h) * np.sum(np.diff(t) ** 2)
            end = clamps[i] + h * np.array([np.cos(t).sum(), np.sin(t).sum()])
            total -= force[i] @ (end - B[i])
        return total

    return L


def test_the_second_variation_is_the_hessian_of_the_lagrangian(table8):
    z, segments = table8.chart[0], 5
    blocks, dense, _ = pfr3.second_variation(MECH, LAMBDAS, z, segments=segments)
    n = 3 * segments + 3
    H = np.zeros((n, n))
    for i, b in enumerate(blocks):
        H[i * segments:(i + 1) * segments, i * segments:(i + 1) * segments] = b.hessian
    H[-3:, -3:] = dense
    x = np.concatenate([b.theta for b in blocks] + [table8.pose[0]])
    L, h = _discrete_lagrangian(MECH, z, segments), 1e-4
    E = np.eye(n)
    Hn = np.array([[(L(x + h * (E[i] + E[j])) - L(x + h * (E[i] - E[j]))
                     - L(x - h * (E[i] - E[j])) + L(x - h * (E[i] + E[j]))) / (4 * h * h)
                    for j in range(n)] for i in range(n)])
    assert np.abs(H - Hn).max() < 1e-5 * np.abs(H).max()


def test_stability_agrees_with_dense_eigenvalues():
    eq = pfr3.forward_elliptic(MECH, LAMBDAS, (1, 2, 1), n_starts=300, check=0, rng=2)
    for z, index in zip(eq.chart[:3], eq.index[:3]):
        N = 200
        blocks, dense, G = pfr3.second_variation(MECH, LAMBDAS, z, (1, 2, 1), segments=N)
        H = np.zeros((3 * N + 3, 3 * N + 3))
        for i, b in enumerate(blocks):
            H[i * N:(i + 1) * N, i * N:(i + 1) * N] = b.hessian
        H[-3:, -3:] = dense
        dense_index = int(np.sum(constrained_eigenvalues(H, G) < 0))
        assert pfr3.index(MECH, LAMBDAS, z, (1, 2, 1), segments=N) == dense_index
        assert dense_index >= 1                        # a mode-2 rod: unstable here


def test_paths_follow_the_closed_form_and_shooting(table8):
    k = int(np.flatnonzero(table8.buildable)[0])
    z, pose = table8.chart[k], table8.pose[k]
    line = pose + np.linspace(0.0, 0.03, 7)[:, None] * [1.0, 0.5, 0.2]
    fast = pfr3.inverse_path(MECH, line, LAMBDAS, z)
    study_way = pfr3.inverse_path(MECH, line, LAMBDAS, z, method="shooting", nodes=801)
    assert fast.converged.all() and study_way.converged.all()
    assert np.abs(fast.lambdas - study_way.lambdas).max() < 1e-9
    # the determinants vanish at the same places: same sign along the path
    assert (np.sign(fast.det_ik) == np.sign(fast.det_ik[0])).all()
    back = pfr3.forward_path(MECH, fast.lambdas, z)
    assert np.abs(back.pose - line).max() < 1e-9


def test_jacobians_relate_the_two_problems(table8):
    fk, ik, dpose = pfr3.jacobians(MECH, LAMBDAS, table8.chart)
    h, k = 1e-6, int(np.flatnonzero(table8.buildable)[0])
    steps = LAMBDAS + np.array([[0.0, 0.0, 0.0], [h, 0.0, 0.0]])
    moved = pfr3.forward_path(MECH, steps, table8.chart[k])
    assert np.abs((moved.pose[1] - moved.pose[0]) / h - dpose[k][:, 0]).max() < 1e-4
    assert fk.shape == ik.shape == (9,)


def test_inverse_map_and_singular_points(table8):
    k = int(np.flatnonzero(table8.buildable)[0])
    x = np.linspace(-0.6, 0.6, 13)
    grid = pfr3.inverse_map(MECH, x, x, table8.pose[k, 2], table8.pose[k], LAMBDAS,
                            table8.chart[k])
    assert grid.lambdas.shape == (13, 13, 3) and grid.converged.mean() > 0.3
    points = pfr3.singular_points(MECH, grid)
    assert points.shape[1] == 2


def test_workspace_edge_ends_at_a_fold_of_the_inverse_problem():
    # The study's shooting example (Annex II 4.1) at its pose: along +x the branch folds
    # (det J_IK -> 0 while lambda1 runs off) about 0.67 m from the centre.
    mech, pose = pfr3.SHOOTING_EXAMPLE, pfr3.SHOOTING_POSE
    guess = np.concatenate([np.r_[-0.002, 0.04 * model.UNIT_CIRCLE[i], 0.0]
                            for i in range(3)])
    start = pfr3.inverse_shooting(mech, pose, guess)
    z, modes = shooting.chart_from_clamps(mech, start.clamp_moments[0], start.forces[0])
    centre = pfr3.inverse_path(mech, [pose, pose], start.lambdas[0], z, modes,
                               method="shooting")
    edge = pfr3.workspace(mech, pose, start.lambdas[0], z, modes, directions=3)
    assert edge.converged.all() and edge.pose.shape == (3, 3)
    radius = np.hypot(*(edge.pose[:, :2] - pose[:2]).T)
    assert np.allclose(radius, radius[0], atol=1e-3)      # the mechanism's threefold symmetry
    assert 0.66 < radius[0] < 0.68
    assert (np.abs(edge.det_ik) < 0.05 * abs(centre.det_ik[-1])).all()


@pytest.mark.parametrize("bad", [{"directions": 0}, {"step": -0.1}, {"levels": -1}])
def test_workspace_edge_rejects_bad_settings(bad):
    with pytest.raises(ValueError):
        pfr3.workspace(MECH, [0.0, 0.0, 0.0], LAMBDAS, np.full(6, 0.5), **bad)


def test_draw_runs(table8):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    artists = pfr3.draw(ax, MECH, table8.state(0))
    assert len(artists) >= 10
    plt.close(fig)


@pytest.mark.parametrize("bad", [[np.nan, 0.0, 0.0], [0.0, 0.0], [0.0, np.inf, 0.0]])
def test_bad_slider_inputs_raise_value_error(bad):
    with pytest.raises(ValueError, match="lambdas"):
        pfr3.forward_elliptic(MECH, bad)


def test_bad_modes_raise_value_error():
    with pytest.raises(ValueError, match="modes"):
        pfr3.forward_elliptic(MECH, LAMBDAS, (1, 0, 1))


def test_a_platform_that_cannot_close_raises_geometry_error():
    huge = pfr3.Mechanism(MECH.origins, MECH.guide_angles, MECH.clamp_angles, 5.0)
    with pytest.raises(GeometryError, match="cannot close"):
        pfr3.forward_elliptic(huge, LAMBDAS)
    with pytest.raises(GeometryError, match="positive"):
        pfr3.Mechanism(MECH.origins, MECH.guide_angles, MECH.clamp_angles, -0.2)


def test_an_unreachable_pose_raises_unreachable_pose_error(table8):
    far = np.array([[0.0, 3.0, 0.0]])
    with pytest.raises(UnreachablePoseError, match="from its guide"):
        pfr3.inverse_path(MECH, far, LAMBDAS, table8.chart[0])
    with pytest.raises(UnreachablePoseError):
        pfr3.inverse_shooting(MECH, far[0], np.zeros(12))


def test_non_finite_chart_points_raise_value_error():
    with pytest.raises(ValueError, match="chart"):
        model.rods(MECH, LAMBDAS, [1.0, 0.5, 1.0, 0.0, 1.0, 0.5])
    with pytest.raises(ValueError):
        pfr3.stability(MECH, LAMBDAS, [1.0, np.nan, 1.0, 0.5, 1.0, 0.5])


def test_empty_batches_are_valid():
    assert pfr3.crossings(MECH, LAMBDAS, np.empty((0, 6)))[0].shape == (0, 3)
    assert model.forward_system(MECH, LAMBDAS)[0](np.empty((0, 6))).shape == (0, 6)


def test_reproduce_matches_the_registry_keys():
    values = pfr3.reproduce()
    assert values["mode-1 equilibria for the Table 8 inputs"] == 9.0
    assert values["real mode-1 equilibria of the Table 2 mechanism"] == 3.0
    assert all(isinstance(v, float) for v in values.values())


def test_chart_conversion_round_trip():
    z = model.chart_from_thesis(study.TABLE8_PUBLISHED)
    assert np.allclose(model.thesis_from_chart(z), study.TABLE8_PUBLISHED, atol=1e-12)
    assert np.all(np.abs(z[:, 1::2]) < regular.T_MAX)
