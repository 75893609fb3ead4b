"""Tests of mechnum.mechanisms.finger: geometry, synthesis, the study's data, bad input, and
properties checked by hypothesis (200 examples each)."""

import math

import matplotlib
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum.errors import (DivergenceError, GeometryError, RelaxationFactorError,
                            SingularJacobianError, UnreachablePoseError)
from mechnum.mechanisms import finger as F

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TABLE3 = F.TABLE3_LINKAGE
HYPOTHESIS = settings(max_examples=200, deadline=None)


def _segments_cross(P1, P2, Q1, Q2):
    def side(A, B, C):
        return np.sign((B[:, 0] - A[:, 0]) * (C[:, 1] - A[:, 1])
                       - (B[:, 1] - A[:, 1]) * (C[:, 0] - A[:, 0]))
    return (side(P1, P2, Q1) != side(P1, P2, Q2)) & (side(Q1, Q2, P1) != side(Q1, Q2, P2))


def _freudenstein_misfit(k, theta_in, theta_out):
    """Freudenstein's equation written out term by term, independently of design_matrix."""
    return [k[0] * math.cos(o) + k[1] * math.cos(i) + k[2] - math.cos(o - i)
            for i, o in zip(theta_in, theta_out)]


# --- the study's data ----------------------------------------------------------------------------

def test_angle_convention_against_table1():
    # Freudenstein's equation with k of the Table 1 linkage holds at the measured angles.
    theta_in, theta_out = F.angles_from_points(F.TABLE1_EI[:, :2], F.TABLE1_EI[:, 2:],
                                               F.TABLE1_R4)
    misfit = np.array(_freudenstein_misfit(F.freudenstein_coefficients(F.table1_linkage()),
                                           theta_in, theta_out))
    good = np.arange(10) != 2  # row 3 holds the study's typo
    assert np.abs(misfit[good]).max() < 2e-6
    assert np.abs(misfit[2]) > 5e-4


def test_table1_linkage_is_the_median_of_the_rows():
    L = F.table1_linkage()
    E, I = F.TABLE1_EI[:, :2], F.TABLE1_EI[:, 2:]
    r1 = [math.hypot(*e) for e in E]
    assert L.r1 == sorted(r1)[4] / 2 + sorted(r1)[5] / 2
    assert L.r4 == F.TABLE1_R4
    assert abs(math.dist(E[0], I[0]) - L.r2) < 1e-4


def test_crossed_branch_is_the_studys():
    L = F.table1_linkage()
    theta_in, theta_out = F.angles_from_points(F.TABLE1_EI[:, :2], F.TABLE1_EI[:, 2:], L.r4)
    crossed, open_ = F.pose(theta_in, L, F.CROSSED), F.pose(theta_in, L, F.OPEN)
    good = np.arange(10) != 2
    assert np.abs(crossed.E - F.TABLE1_EI[:, :2])[good].max() < 1e-4
    assert np.all(_segments_cross(crossed.D, crossed.E, crossed.H, crossed.I))
    assert not np.any(_segments_cross(open_.D, open_.E, open_.H, open_.I))


def test_unrounded_inputs_round_to_table2_but_one():
    printed = np.round(F.TABLE2_THETA_IN_UNROUNDED, 4)
    differs = np.flatnonzero(printed != F.TABLE2_THETA_IN)
    assert differs.tolist() == [11]
    assert printed[11] == 6.0476 and F.TABLE2_THETA_IN[11] == 6.0474


@pytest.mark.parametrize("branch", [F.CROSSED, F.OPEN])
def test_input_and_output_analyses_invert_each_other_on_the_study(branch):
    theta_in = np.linspace(4.6, 6.2, 9)
    forward = F.pose(theta_in, TABLE3, branch)
    back = F.pose_from_output(forward.theta_out, TABLE3, branch)
    assert_allclose(back.theta_in, theta_in, rtol=0, atol=1e-10)


def test_unreachable_pose_is_reported():
    assert F.reachable([3.9357, 4.5117], TABLE3).tolist() == [False, True]
    with pytest.raises(UnreachablePoseError, match="3.9357"):
        F.pose([3.9357, 4.5117], TABLE3)
    with pytest.raises(UnreachablePoseError):
        F.pose_from_output([1.04], TABLE3)


@pytest.mark.parametrize("method, options", [
    ("cholesky", {}), ("lu", {}), ("svd", {}), ("sor", dict(omega=1.65, tol=1e-13)),
    ("gauss_seidel", dict(tol=1e-13)), ("sor", dict(omega=0.33, tol=1e-13, maxiter=20_000)),
    ("cg", dict(tol=1e-15))])
def test_synthesis_methods_agree_on_table2(method, options):
    qr = F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, "qr")
    other = F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, method, **options)
    assert_allclose(other.k, qr.k, rtol=0, atol=1e-9)
    # The least-squares optimality: the misfit of Freudenstein's equation, written out term by
    # term, is orthogonal to each column (cos theta_out, cos theta_in, 1).
    misfit = _freudenstein_misfit(qr.k, F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT)
    assert_allclose(qr.residuals, misfit, rtol=0, atol=1e-14)
    for column in (np.cos(F.TABLE2_THETA_OUT), np.cos(F.TABLE2_THETA_IN), np.ones(13)):
        assert abs(column @ misfit) < 1e-13
    # and the study's fit is 35.08, 8.70, 30.02 mm, not its Table 3
    assert [round(qr.linkage.r1, 2), round(qr.linkage.r2, 2), round(qr.linkage.r3, 2)] == \
        [35.08, 8.70, 30.02]


def test_jacobi_diverges_on_the_studys_normal_equations():
    with pytest.raises(DivergenceError, match="jacobi diverges"):
        F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, "jacobi")


def test_synthesis_recovers_an_exact_linkage():
    true = F.Linkage(30.0, 7.5, 24.0, 7.0)
    theta_in = np.linspace(4.7, 6.2, 8)
    fit = F.synthesize(theta_in, F.pose(theta_in, true).theta_out, 7.0)
    assert_allclose([fit.linkage.r1, fit.linkage.r2, fit.linkage.r3], [30.0, 7.5, 24.0],
                    rtol=1e-10)
    assert np.abs(fit.residuals).max() < 1e-12


def test_ill_conditioned_example_formula():
    for delta in (1e-1, 1e-3):
        x, cond = F.ill_conditioned_example(delta, 2 * delta)
        assert cond == pytest.approx((3 + delta) * (4 + delta) / delta, rel=1e-9)
        assert_allclose(x, [-3.0, -2.0], rtol=1e-9)


def test_reproduce_covers_the_tables():
    values = F.reproduce()
    assert sum(k.startswith("Tabla 4 pos") for k in values) == 52
    assert values["Tabla 3 r1"] == pytest.approx(35.0761, abs=5e-5)
    assert values["best omega"] == pytest.approx(1.6527, abs=5e-5)


def test_draw_puts_the_links_at_the_pose():
    fig, ax = plt.subplots()
    p = F.pose([5.0, 5.5], TABLE3)
    links, ground = F.draw(ax, p)
    assert_allclose(links.get_xydata(), [p.D[0], p.E[0], p.I[0], p.H[0]])
    assert_allclose(ground.get_xydata(), [p.D[0], p.H[0]])
    same = F.draw(ax, p, 1, lines=(links, ground))
    assert same == (links, ground)
    assert_allclose(links.get_xydata()[1], p.E[1])
    with pytest.raises(ValueError, match="out of range"):
        F.draw(ax, p, 2)
    with pytest.raises(ValueError, match="Pose"):
        F.draw(ax, TABLE3)
    plt.close(fig)


# --- bad input -----------------------------------------------------------------------------------

@pytest.mark.parametrize("call, error, message", [
    (lambda: F.Linkage(1.0, -2.0, 3.0, 1.0), GeometryError, "positive"),
    (lambda: F.Linkage(1.0, 0.0, 3.0, 1.0), GeometryError, "positive"),
    (lambda: F.Linkage(1.0, np.nan, 3.0, 1.0), ValueError, "r2 must be finite"),
    (lambda: F.Linkage(1.0, 2.0, 3.0, 1j), ValueError, "r4 must be real"),
    (lambda: F.Linkage(1.0, "2", 3.0, 1.0), ValueError, "r2 must be numeric"),
    (lambda: F.freudenstein_coefficients((1.0, 2.0, 3.0, 4.0)), ValueError, "Linkage"),
    (lambda: F.linkage_from_coefficients([0.1, -0.2, -1.0], 1.0), GeometryError, "negative"),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1, -100.0], 1.0), GeometryError, "r2"),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1], 1.0), ValueError, "k must have shape"),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1, np.nan], 1.0), ValueError, "finite"),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1, 0.0], -1.0), ValueError, "r4"),
    (lambda: F.design_matrix([1.0, 2.0], [1.0]), ValueError, "differ in shape"),
    (lambda: F.design_matrix([[1.0]], [[1.0]]), ValueError, "dimension"),
    (lambda: F.design_matrix([1.0, np.inf], [1.0, 2.0]), ValueError, "finite"),
    (lambda: F.synthesize([4.0, 5.0], [1.0, 2.0], 7.0), ValueError, "at least 3"),
    (lambda: F.synthesize([4.0, 5.0, 6.0], [1.0, 2.0], 7.0), ValueError, "shape"),
    (lambda: F.synthesize([4.0, 5.0, 6.0], [1.0, 2.0, 3.0], 7.0, "normal"), ValueError, "method"),
    (lambda: F.synthesize([4.0, 5.0, 6.0], [1.0, 2.0, 3.0], 0.0), ValueError, "r4"),
    (lambda: F.synthesize([5.0] * 4, [2.0] * 4, 7.0), SingularJacobianError, "rank 1"),
    (lambda: F.synthesize([5.0] * 4, [2.0] * 4, 7.0, "lu"), SingularJacobianError, "rank"),
    (lambda: F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 7.0, "sor"),
     RelaxationFactorError, "omega"),
    (lambda: F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 7.0, "sor", 2.0),
     RelaxationFactorError, "omega"),
    (lambda: F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 7.0, "qr", tol=1e-3),
     ValueError, "direct"),
    (lambda: F.reachable([1.0], TABLE3, "coupler"), ValueError, "driver"),
    (lambda: F.reachable([1.0], "TABLE3"), ValueError, "Linkage"),
    (lambda: F.pose([np.inf], TABLE3), ValueError, "finite"),
    (lambda: F.pose(5.0, TABLE3), ValueError, "dimension"),
    (lambda: F.pose([5.0], TABLE3, branch=0), ValueError, "branch"),
    (lambda: F.pose_from_output([2.0 + 1j], TABLE3), ValueError, "real"),
    (lambda: F.pose_from_output([2.0], TABLE3, branch=2), ValueError, "branch"),
    (lambda: F.place_links([1.0, 2.0], [1.0], TABLE3), ValueError, "shape"),
    (lambda: F.angles_from_points([[0.0, 1.0]], [[0.0, 1.0], [1.0, 1.0]], 1.0), ValueError,
     "I must have shape"),
    (lambda: F.angles_from_points([0.0, 1.0], [0.0, 1.0], 1.0), ValueError, "E must have"),
    (lambda: F.angles_from_points([[0.0, 1.0]], [[0.0, 1.0]], np.nan), ValueError, "r4"),
    (lambda: F.ill_conditioned_example(0, 0), SingularJacobianError, "parallel"),
    (lambda: F.ill_conditioned_example(1e-17, 0), SingularJacobianError, "singular"),
    (lambda: F.ill_conditioned_example(np.nan, 0), ValueError, "delta"),
    (lambda: F.ill_conditioned_example(0.1, [1.0, 2.0]), ValueError, "rhs_shift"),
])
def test_bad_input(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_empty_batches_are_valid():
    assert F.pose([], TABLE3).E.shape == (0, 2)
    assert F.pose_from_output([], TABLE3).I.shape == (0, 2)
    assert F.place_links([], [], TABLE3).E.shape == (0, 2)
    assert F.reachable([], TABLE3).shape == (0,)
    assert F.angles_from_points(np.empty((0, 2)), np.empty((0, 2)), 1.0)[0].shape == (0,)
    assert F.design_matrix([], [])[0].shape == (0, 3)


# --- properties ----------------------------------------------------------------------------------

lengths = st.floats(0.5, 50.0)


@HYPOTHESIS
@given(lengths, lengths, lengths, lengths)
def test_freudenstein_round_trip(r1, r2, r3, r4):
    L = F.Linkage(r1, r2, r3, r4)
    k = F.freudenstein_coefficients(L)
    assert k[0] == -r4 / r3 and k[1] == -r4 / r1
    back = F.linkage_from_coefficients(k, r4)
    assert_allclose([back.r1, back.r2, back.r3], [r1, r2, r3], rtol=1e-7)


@HYPOTHESIS
@given(st.floats(-1.0, -1e-3), st.floats(-1.0, -1e-3), st.floats(-5.0, 5.0), lengths)
def test_linkage_from_coefficients_exists_or_says_why(k1, k2, k3, r4):
    try:
        L = F.linkage_from_coefficients([k1, k2, k3], r4)
    except GeometryError as error:
        assert "r2^2" in str(error)
        return
    assert_allclose(F.freudenstein_coefficients(L), [k1, k2, k3], rtol=1e-9, atol=1e-9)


@st.composite
def assembled(draw):
    """A linkage and an input angle at which it is assembled (no filtering): with the input
    rocker at theta, |DI| = d is fixed, and the loop closes iff |r1 - r2| <= d <= r1 + r2, so r1
    is drawn strictly inside [|d - r2|, d + r2]."""
    r3, theta, r2, u = (draw(st.floats(10, 40)), draw(st.floats(0, 2 * np.pi)),
                        draw(st.floats(2, 10)), draw(st.floats(0.05, 0.95)))
    r4 = 7.0
    d = np.sqrt(r4 ** 2 + r3 ** 2 + 2 * r3 * r4 * np.cos(theta))
    r1 = abs(d - r2) + u * (d + r2 - abs(d - r2))
    return F.Linkage(r1, r2, r3, r4), theta


@HYPOTHESIS
@given(assembled(), st.sampled_from([F.CROSSED, F.OPEN]))
def test_pose_closes_the_loop_and_inverts(case, branch):
    L, theta = case
    assert F.reachable([theta], L)[0]
    p = F.pose([theta], L, branch)
    assert_allclose(np.linalg.norm(p.E - p.D, axis=1), L.r1, rtol=1e-9)
    assert_allclose(np.linalg.norm(p.I - p.E, axis=1), L.r2, rtol=1e-6, atol=1e-6)
    assert_allclose(np.linalg.norm(p.H - p.I, axis=1), L.r3, rtol=1e-9)
    assert abs(_freudenstein_misfit(F.freudenstein_coefficients(L), p.theta_in,
                                    p.theta_out)[0]) < 1e-6
    # driven by the output, one of the two branches gives the input angle back (which one
    # depends on the linkage); away from a dead point, where the two merge, to round-off
    u, v = p.E[0] - p.I[0], p.H[0] - p.I[0]
    if abs(u[0] * v[1] - u[1] * v[0]) > 1e-3 * L.r2 * L.r3:
        gaps = [abs(np.angle(np.exp(1j * (F.pose_from_output(p.theta_out, L, b).theta_in[0]
                                          - theta)))) for b in (F.CROSSED, F.OPEN)]
        assert min(gaps) < 1e-6


@HYPOTHESIS
@given(st.lists(st.floats(-10, 10), min_size=0, max_size=8), lengths, lengths, lengths, lengths,
       st.sampled_from(["input", "output"]))
def test_reachable_is_the_triangle_inequality(thetas, r1, r2, r3, r4, driver):
    L = F.Linkage(r1, r2, r3, r4)
    ok = F.reachable(thetas, L, driver)
    assert ok.shape == (len(thetas),)
    for theta, flag in zip(thetas, ok):
        if driver == "input":
            d, r = math.hypot(-r4 - r3 * math.cos(theta), -r3 * math.sin(theta)), r1
        else:
            d, r = math.hypot(r1 * math.cos(theta) + r4, r1 * math.sin(theta)), r3
        margin = 1e-9 * (d + r + r2)
        if abs(r - r2) + margin < d < r + r2 - margin:
            assert flag
        elif d < abs(r - r2) - margin or d > r + r2 + margin:
            assert not flag


@HYPOTHESIS
@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=0, max_size=8),
       lengths, lengths, lengths, lengths)
def test_place_links_puts_the_rockers_on_their_circles(pairs, r1, r2, r3, r4):
    theta_in = [p[0] for p in pairs]
    theta_out = [p[1] for p in pairs]
    p = F.place_links(theta_in, theta_out, F.Linkage(r1, r2, r3, r4))
    assert_allclose(np.linalg.norm(p.E, axis=1), r1, rtol=1e-12)
    assert_allclose(np.linalg.norm(p.I - [-r4, 0.0], axis=1), r3, rtol=1e-12)
    back_in, back_out = F.angles_from_points(p.E, p.I, r4)
    assert_allclose(np.cos(back_in - np.array(theta_in)), 1.0, atol=1e-10)
    assert_allclose(np.cos(back_out - np.array(theta_out)), 1.0, atol=1e-10)


@HYPOTHESIS
@given(st.lists(st.tuples(st.floats(-100, 100), st.floats(-100, 100), st.floats(-100, 100),
                          st.floats(-100, 100)), min_size=0, max_size=6), lengths)
def test_angles_from_points_are_in_range(points, r4):
    points = np.array(points).reshape(-1, 4)
    theta_in, theta_out = F.angles_from_points(points[:, :2], points[:, 2:], r4)
    assert theta_in.shape == theta_out.shape == (len(points),)
    assert np.all((0 <= theta_out) & (theta_out < 2 * np.pi))
    assert np.all((0 <= theta_in) & (theta_in < 2 * np.pi))


@HYPOTHESIS
@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10)), min_size=0, max_size=8))
def test_design_matrix_rows(pairs):
    theta_in = np.array([p[0] for p in pairs])
    theta_out = np.array([p[1] for p in pairs])
    A, b = F.design_matrix(theta_in, theta_out)
    assert A.shape == (len(pairs), 3) and b.shape == (len(pairs),)
    k = np.array([0.3, -0.2, 0.1])
    assert_allclose(A @ k - b, np.array(_freudenstein_misfit(k, theta_in, theta_out)).reshape(-1),
                    atol=1e-12)


@HYPOTHESIS
@given(assembled(), st.floats(0.3, 1.2), st.sampled_from(["qr", "svd", "cholesky", "lu"]))
def test_synthesis_recovers_the_linkage_it_came_from(case, span, method):
    L, theta = case
    grid = theta + np.linspace(-span, span, 7) / 10
    ok = F.reachable(grid, L)
    if ok.sum() < 4:
        return
    p = F.pose(grid[ok], L)
    try:
        fit = F.synthesize(p.theta_in, p.theta_out, L.r4, method)
    except SingularJacobianError:  # nearly coincident angles: rank < 3 numerically
        return
    assert np.abs(fit.residuals).max() < 1e-6
    misfit = _freudenstein_misfit(fit.k, p.theta_in, p.theta_out)
    assert_allclose(fit.residuals, misfit, atol=1e-12)


@HYPOTHESIS
@given(st.floats(1e-6, 1.0), st.floats(-1.0, 1.0))
def test_ill_conditioned_example_solves_and_bounds(delta, shift):
    x, cond = F.ill_conditioned_example(delta, shift)
    assert cond == pytest.approx((3 + delta) * (4 + delta) / delta, rel=1e-9)
    # x - 2y = 1 and x - (2 + delta) y = 1 + shift: y = -shift / delta, x = 1 + 2y
    assert_allclose(x, [1 - 2 * shift / delta, -shift / delta], rtol=1e-6, atol=1e-6)


@HYPOTHESIS
@given(assembled())
def test_draw_any_pose(case):
    L, theta = case
    fig, ax = plt.subplots()
    links, _ = F.draw(ax, F.pose([theta], L))
    assert_allclose(links.get_xydata()[2], F.pose([theta], L).I[0])
    plt.close(fig)
