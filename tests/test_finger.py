"""Tests of mechnum.mechanisms.finger: geometry, synthesis, the study's data, bad input, and
properties checked by hypothesis (200 examples each)."""

import math
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from published import check_row, read_published, read_registry

from mechnum.errors import (
    DivergenceError,
    GeometryError,
    RelaxationFactorError,
    SingularJacobianError,
    UnreachablePoseError,
)
from mechnum.mechanisms import finger as F
from mechnum.mechanisms.finger import study as FS
from mechnum.mechanisms.finger._model import CROSSED, MODES, OPEN
from mechnum.plotting import animate

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TABLE3 = FS.TABLE3_LINKAGE
_PATH = Path(__file__).resolve().parents[1] / "book" / "published_values.csv"
REGISTRY = {row["quantity"]: row for row in read_registry(_PATH, "02_linear_systems_finger")}
PUBLISHED = read_published(_PATH, "02_linear_systems_finger")
HYPOTHESIS = settings(max_examples=200, deadline=None)


def _segments_cross(P1, P2, Q1, Q2):
    def side(A, B, C):
        return np.sign((B[:, 0] - A[:, 0]) * (C[:, 1] - A[:, 1])
                       - (B[:, 1] - A[:, 1]) * (C[:, 0] - A[:, 0]))
    return (side(P1, P2, Q1) != side(P1, P2, Q2)) & (side(Q1, Q2, P1) != side(Q1, Q2, P2))


def pose(L, theta_in, mode=CROSSED):
    """The points of the linkage at input angles, in one assembly mode (forward, placed)."""
    theta_out = F.forward(L, theta_in).x[:, MODES.index(mode)]
    return F.place_links(L, theta_in, theta_out)


def _freudenstein_misfit(k, theta_in, theta_out):
    """Freudenstein's equation written out term by term, independently of design_matrix."""
    return [k[0] * math.cos(o) + k[1] * math.cos(i) + k[2] - math.cos(o - i)
            for i, o in zip(theta_in, theta_out)]


# --- the study's data ----------------------------------------------------------------------------

def test_angle_convention_against_table1():
    # Freudenstein's equation with k of the Table 1 linkage holds at the measured angles.
    theta_in, theta_out = F.angles_from_points(FS.TABLE1_EI[:, :2], FS.TABLE1_EI[:, 2:],
                                               FS.TABLE1_R4)
    misfit = np.array(_freudenstein_misfit(F.freudenstein_coefficients(FS.table1_linkage()),
                                           theta_in, theta_out))
    good = np.arange(10) != 2  # row 3 holds the study's typo
    assert np.abs(misfit[good]).max() < 2e-6
    assert np.abs(misfit[2]) > 5e-4


def test_table1_linkage_fits_every_row_but_the_corrupted_one():
    # one rigid linkage: with its ground pivot H = (-r4, 0), the lengths |DE|, |EI|, |HI| of
    # nine measured rows equal r1, r2, r3 to the printed digits; row 3 holds the copying error
    L = FS.table1_linkage()
    E, I = FS.TABLE1_EI[:, :2], FS.TABLE1_EI[:, 2:]
    H = (-L.r4, 0.0)
    misses = np.array([[abs(math.hypot(*e) - L.r1), abs(math.dist(e, i) - L.r2),
                        abs(math.dist(i, H) - L.r3)] for e, i in zip(E, I)]).max(axis=1) / FS.MM
    assert np.flatnonzero(misses > 1e-3).tolist() == [2]  # in millimetres, as printed
    assert np.delete(misses, 2).max() < 2e-4


def test_crossed_branch_is_the_studys():
    L = FS.table1_linkage()
    theta_in, theta_out = F.angles_from_points(FS.TABLE1_EI[:, :2], FS.TABLE1_EI[:, 2:], L.r4)
    crossed, open_ = pose(L, theta_in, CROSSED), pose(L, theta_in, OPEN)
    good = np.arange(10) != 2
    assert np.abs(crossed.E - FS.TABLE1_EI[:, :2])[good].max() < 1e-4 * FS.MM
    assert np.all(_segments_cross(crossed.D, crossed.E, crossed.H, crossed.I))
    assert not np.any(_segments_cross(open_.D, open_.E, open_.H, open_.I))


def test_unrounded_inputs_round_to_table2_but_one():
    printed = np.round(FS.TABLE2_THETA_IN_UNROUNDED, 4)
    differs = np.flatnonzero(printed != FS.TABLE2_THETA_IN)
    assert differs.tolist() == [11]
    assert printed[11] == 6.0476 and FS.TABLE2_THETA_IN[11] == 6.0474


@pytest.mark.parametrize("mode", [0, 1])
def test_input_and_output_analyses_invert_each_other_on_the_study(mode):
    theta_in = np.linspace(4.6, 6.2, 9)
    theta_out = F.forward(TABLE3, theta_in).x[:, mode]
    back = F.inverse(TABLE3, theta_out)[:, mode]
    assert_allclose(back, theta_in, rtol=1e-10)


def test_unreachable_pose_is_reported():
    assert F.workspace(TABLE3, [3.9357, 4.5117]).tolist() == [False, True]
    with pytest.raises(UnreachablePoseError, match="3.9357"):
        F.forward(TABLE3, [3.9357, 4.5117])
    with pytest.raises(UnreachablePoseError):
        F.inverse(TABLE3, [1.04])


@pytest.mark.parametrize("method, options", [
    ("cholesky", {}), ("lu", {}), ("svd", {}), ("sor", dict(omega=1.65, tol=1e-13)),
    ("gauss_seidel", dict(tol=1e-13)), ("sor", dict(omega=0.33, tol=1e-13, maxiter=20_000)),
    ("cg", dict(tol=1e-15))])
def test_synthesis_methods_agree_on_table2(method, options):
    qr = F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, "qr")
    other = F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, method, **options)
    assert_allclose(other.x, qr.x, rtol=0, atol=1e-9)
    # The least-squares optimality: the misfit of Freudenstein's equation, written out term by
    # term, is orthogonal to each column (cos theta_out, cos theta_in, 1).
    misfit = _freudenstein_misfit(qr.x, FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT)
    assert_allclose(qr.residuals, misfit, rtol=0, atol=1e-14)
    for column in (np.cos(FS.TABLE2_THETA_OUT), np.cos(FS.TABLE2_THETA_IN), np.ones(13)):
        assert abs(column @ misfit) < 1e-13
    # and the study's fit is 35.08, 8.70, 30.02 mm, not its Table 3
    assert [round(qr.linkage.r1 / FS.MM, 2), round(qr.linkage.r2 / FS.MM, 2),
            round(qr.linkage.r3 / FS.MM, 2)] == [35.08, 8.70, 30.02]


def test_jacobi_diverges_on_the_studys_normal_equations():
    with pytest.raises(DivergenceError, match="jacobi diverges"):
        F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, FS.TABLE1_R4, "jacobi")


def test_synthesis_recovers_an_exact_linkage():
    true = F.Linkage(0.030, 0.0075, 0.024, 0.007)
    theta_in = np.linspace(4.7, 6.2, 8)
    fit = F.synthesize(theta_in, F.forward(true, theta_in).x[:, 0], 0.007)
    assert_allclose([fit.linkage.r1, fit.linkage.r2, fit.linkage.r3], [0.030, 0.0075, 0.024],
                    rtol=1e-10)
    assert np.abs(fit.residuals).max() < 1e-12


def test_ill_conditioned_example_formula():
    for delta in (1e-1, 1e-3):
        x, cond = FS.ill_conditioned_example(delta, 2 * delta)
        assert cond == pytest.approx((3 + delta) * (4 + delta) / delta, rel=1e-9)
        assert_allclose(x, [-3.0, -2.0], rtol=1e-9)


def test_reproduce_covers_the_tables():
    values = FS.reproduce()
    assert sum(k.startswith("Table 4 pos") for k in values) == 52
    for quantity in ("Table 3 r1", "best omega", "Fig. 1 example loop closure"):
        check_row(REGISTRY[quantity], values[quantity])
    # every row with a computed number has its value, and no other row has one
    computed = {q for q, row in REGISTRY.items() if row["computed"]}
    assert computed == set(values)


def test_fig1_printed_solution_is_the_registrys():
    assert {name: float(PUBLISHED[f"Fig. 1 example {name}"]) for name in FS.FIG1_PRINTED} == \
        FS.FIG1_PRINTED


def test_loop_closure_finds_a_closed_loop():
    # a closed quadrilateral of four vectors, with distractors: the search finds it exactly
    lengths, angles = [3.0, 4.0, 5.0, 1.0, 2.0], [0.0, 90.0, 180 + 53.13010235415598, 10, 70]
    miss, signs, count = FS.loop_closure(lengths, angles)
    assert miss < 1e-12 and np.abs(signs).tolist() == [1, 1, 1, 0, 0]
    assert len(set(signs[:3])) == 1  # the loop, in one sense or the other
    assert count == sum(math.comb(5, k) * 2 ** k for k in (3, 4, 5))


def test_tables_7_to_10_are_table_5_shifted():
    # the registry's claim on Tables 7 to 10: each column is Table 5's plus one constant
    table5 = np.hstack(FS.published_points(PUBLISHED, 5))
    for table in (7, 8, 9, 10):
        shifts, spread = FS.column_shifts(np.hstack(FS.published_points(PUBLISHED, table)),
                                         table5)
        assert np.all(spread < 1e-15) and np.all(np.abs(shifts) > 0.4 * FS.MM)
    # and the check can fail: Table 4 is no shifted copy of Table 5
    assert FS.column_shifts(np.hstack(FS.published_points(PUBLISHED, 4)), table5)[1].max() > \
        0.1 * FS.MM


def test_draw_puts_the_links_at_the_pose_and_moves_them():
    fig, ax = plt.subplots()
    p = pose(TABLE3, [5.0, 5.5])
    drawn = F.draw(ax, TABLE3, (p.theta_in[0], p.theta_out[0]))
    assert_allclose(drawn["links"].get_xydata(), [p.D[0], p.E[0], p.I[0], p.H[0]], rtol=1e-14,
                    atol=1e-18)
    assert_allclose(drawn["ground"].get_xydata(), [p.D[0], p.H[0]], rtol=1e-15)
    moved = F.draw(ax, TABLE3, (p.theta_in[1], p.theta_out[1]), artists=drawn)
    assert moved is drawn and len(ax.lines) == 2
    assert_allclose(drawn["links"].get_xydata()[1], p.E[1], rtol=1e-14)
    with pytest.raises(ValueError, match="state must be"):
        F.draw(ax, TABLE3, p)
    with pytest.raises(ValueError, match="mech must be a finger.Linkage"):
        F.draw(ax, None, (5.0, 2.3))
    with pytest.raises(ValueError, match="ax must be a matplotlib Axes"):
        F.draw(None, TABLE3, (5.0, 2.3))
    plt.close(fig)


def test_animate_moves_the_linkage():
    theta_in = np.linspace(4.6, 6.2, 4)
    states = list(zip(theta_in, F.forward(TABLE3, theta_in).x[:, 0]))
    assert animate(F.draw, TABLE3, states).count("data:image/png;base64") == 4


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
    (lambda: F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, 7.0, "sor"),
     RelaxationFactorError, "omega"),
    (lambda: F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, 7.0, "sor", 2.0),
     RelaxationFactorError, "omega"),
    (lambda: F.synthesize(FS.TABLE2_THETA_IN, FS.TABLE2_THETA_OUT, 7.0, "qr", tol=1e-3),
     ValueError, "direct"),
    (lambda: F.workspace(TABLE3, [1.0], driver="coupler"), ValueError, "driver"),
    (lambda: F.workspace("TABLE3", [1.0]), ValueError, "Linkage"),
    (lambda: F.forward(TABLE3, [np.inf]), ValueError, "finite"),
    (lambda: F.forward(TABLE3, 5.0), ValueError, "dimension"),
    (lambda: F.forward(None, [5.0]), ValueError, "mech must be a finger.Linkage"),
    (lambda: F.inverse(TABLE3, [2.0 + 1j]), ValueError, "real"),
    (lambda: F.inverse(FS, [2.0]), ValueError, "mech must be"),
    (lambda: F.place_links(TABLE3, [1.0, 2.0], [1.0]), ValueError, "shape"),
    (lambda: F.angles_from_points([[0.0, 1.0]], [[0.0, 1.0], [1.0, 1.0]], 1.0), ValueError,
     "I must have shape"),
    (lambda: F.angles_from_points([0.0, 1.0], [0.0, 1.0], 1.0), ValueError, "E must have"),
    (lambda: F.angles_from_points([[0.0, 1.0]], [[0.0, 1.0]], np.nan), ValueError, "r4"),
    (lambda: FS.ill_conditioned_example(0, 0), SingularJacobianError, "parallel"),
    (lambda: FS.ill_conditioned_example(1e-17, 0), SingularJacobianError, "singular"),
    (lambda: FS.ill_conditioned_example(np.nan, 0), ValueError, "delta"),
    (lambda: FS.ill_conditioned_example(0.1, [1.0, 2.0]), ValueError, "rhs_shift"),
    # the loop search's sizes and terms (R1: terms=(10,) was an IndexError)
    (lambda: FS.loop_closure([1.0, 2.0], [0.0, 90.0], terms=(10,)), ValueError, "terms must"),
    (lambda: FS.loop_closure([1.0, 2.0], [0.0, 90.0], terms=(3, 2)), ValueError, "fewest"),
    (lambda: FS.loop_closure([1.0, 2.0], [0.0, 90.0], terms=(3, 5)), ValueError, "no sum of 3"),
    (lambda: FS.loop_closure([1.0, 2.0], [0.0, 90.0], terms="ab"), ValueError, "terms must"),
    (lambda: FS.loop_closure(np.ones(13), np.zeros(13)), ValueError, "a bound on the work"),
    (lambda: FS.loop_closure([], []), ValueError, "number of vectors"),
    (lambda: FS.loop_closure([1.0, np.nan], [0.0, 90.0]), ValueError, "lengths must be finite"),
    # the Fig. 1 example's printed unknowns (R6: a string was an AttributeError)
    (lambda: FS.fig1_vectors("x"), ValueError, "printed must be a dict"),
    (lambda: FS.fig1_vectors({"p3": 8.0}), ValueError, "printed must be a dict"),
    (lambda: FS.fig1_vectors(FS.FIG1_PRINTED | {"p3": "eight"}), ValueError, "numbers"),
    # the registry's tables (R6: table="foo" was a KeyError)
    (lambda: FS.published_points(PUBLISHED, "foo"), ValueError, "table must be one of"),
    (lambda: FS.published_points(PUBLISHED, 6), ValueError, "table must be one of"),
    (lambda: FS.published_points(PUBLISHED, 4, positions=14), ValueError, "positions"),
    (lambda: FS.published_points({}, 4), ValueError, "published lacks 52"),
    (lambda: FS.published_points([1.0], 4), ValueError, "published must be"),
    # column_shifts (D13: NaN passed silently; R4: shapes gave numpy's broadcast message)
    (lambda: FS.column_shifts([[np.nan, 1.0]], [[0.0, 1.0]]), ValueError, "table must be finite"),
    (lambda: FS.column_shifts([[1.0, 1.0]], [[0.0, np.inf]]), ValueError, "reference must be"),
    (lambda: FS.column_shifts([[1.0, 1.0]], [[0.0, 1.0, 2.0]]), ValueError, "reference must "
     "have shape"),
    (lambda: FS.column_shifts([1.0, 2.0], [1.0, 2.0]), ValueError, "2 dimension"),
    (lambda: FS.column_shifts(np.empty((0, 2)), np.empty((0, 2))), ValueError, "one row"),
])
def test_bad_input(call, error, message):
    with pytest.raises(error, match=message):
        call()


def test_empty_batches_are_valid():
    assert F.forward(TABLE3, []).x.shape == (0, 2)
    assert F.inverse(TABLE3, []).shape == (0, 2)
    assert F.place_links(TABLE3, [], []).E.shape == (0, 2)
    assert F.workspace(TABLE3, []).shape == (0,)
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
@given(assembled(), st.sampled_from([CROSSED, OPEN]))
def test_pose_closes_the_loop_and_inverts(case, branch):
    L, theta = case
    assert F.workspace(L, [theta])[0]
    p = pose(L, [theta], branch)
    assert_allclose(np.linalg.norm(p.E - p.D, axis=1), L.r1, rtol=1e-9)
    assert_allclose(np.linalg.norm(p.I - p.E, axis=1), L.r2, rtol=1e-6, atol=1e-6)
    assert_allclose(np.linalg.norm(p.H - p.I, axis=1), L.r3, rtol=1e-9)
    assert abs(_freudenstein_misfit(F.freudenstein_coefficients(L), p.theta_in,
                                    p.theta_out)[0]) < 1e-6
    # driven by the output, one of the two branches gives the input angle back (which one
    # depends on the linkage); away from a dead point, where the two merge, to round-off
    u, v = p.E[0] - p.I[0], p.H[0] - p.I[0]
    if abs(u[0] * v[1] - u[1] * v[0]) > 1e-3 * L.r2 * L.r3:
        gaps = [abs(np.angle(np.exp(1j * (back - theta))))
                for back in F.inverse(L, p.theta_out)[0]]
        assert min(gaps) < 1e-6


@HYPOTHESIS
@given(st.lists(st.floats(-10, 10), min_size=0, max_size=8), lengths, lengths, lengths, lengths,
       st.sampled_from(["input", "output"]))
def test_reachable_is_the_triangle_inequality(thetas, r1, r2, r3, r4, driver):
    L = F.Linkage(r1, r2, r3, r4)
    ok = F.workspace(L, thetas, driver=driver)
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
    p = F.place_links(F.Linkage(r1, r2, r3, r4), theta_in, theta_out)
    assert_allclose(np.linalg.norm(p.E, axis=1), r1, rtol=1e-12)
    assert_allclose(np.linalg.norm(p.I - [-r4, 0.0], axis=1), r3, rtol=1e-12)
    back_in, back_out = F.angles_from_points(p.E, p.I, r4)
    assert_allclose(np.cos(back_in - np.array(theta_in)), 1.0, rtol=0, atol=1e-10)
    assert_allclose(np.cos(back_out - np.array(theta_out)), 1.0, rtol=0, atol=1e-10)


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
@given(assembled(), st.floats(0.0, 1.0), st.integers(0, 6), st.sampled_from([CROSSED, OPEN]))
def test_design_matrix_holds_at_a_linkages_own_poses(case, span, n, branch):
    # A k = b, with k the linkage's Freudenstein coefficients, at every pose it can take
    L, theta = case
    grid = theta + span * np.linspace(-0.1, 0.1, n)
    p = pose(L, grid[F.workspace(L, grid)], branch)
    A, b = F.design_matrix(p.theta_in, p.theta_out)
    assert A.shape == (len(p.theta_in), 3) and b.shape == (len(p.theta_in),)
    assert_allclose(A @ F.freudenstein_coefficients(L), b, rtol=0, atol=1e-6)


@HYPOTHESIS
@given(assembled(), st.floats(0.3, 1.2), st.sampled_from(["qr", "svd", "cholesky", "lu"]))
def test_synthesis_recovers_the_linkage_it_came_from(case, span, method):
    L, theta = case
    grid = theta + np.linspace(-span, span, 7) / 10
    ok = F.workspace(L, grid)
    if ok.sum() < 4:
        return
    p = pose(L, grid[ok])
    try:
        fit = F.synthesize(p.theta_in, p.theta_out, L.r4, method)
    except SingularJacobianError:  # nearly coincident angles: rank < 3 numerically
        return
    assert np.abs(fit.residuals).max() < 1e-6
    misfit = _freudenstein_misfit(fit.x, p.theta_in, p.theta_out)
    assert_allclose(fit.residuals, misfit, rtol=0, atol=1e-12)


@HYPOTHESIS
@given(st.floats(1e-6, 1.0), st.floats(-1.0, 1.0))
def test_ill_conditioned_example_solves_and_bounds(delta, shift):
    x, cond = FS.ill_conditioned_example(delta, shift)
    assert cond == pytest.approx((3 + delta) * (4 + delta) / delta, rel=1e-9)
    # x - 2y = 1 and x - (2 + delta) y = 1 + shift: y = -shift / delta, x = 1 + 2y
    assert_allclose(x, [1 - 2 * shift / delta, -shift / delta], rtol=1e-6, atol=1e-6)


@HYPOTHESIS
@given(assembled())
def test_draw_any_pose(case):
    L, theta = case
    fig, ax = plt.subplots()
    for mode in (0, 1):
        theta_out = F.forward(L, [theta]).x[0, mode]
        drawn = F.draw(ax, L, (theta, theta_out))
        p = F.place_links(L, [theta], [theta_out])
        assert_allclose(drawn["links"].get_xydata(), [p.D[0], p.E[0], p.I[0], p.H[0]],
                        rtol=1e-14, atol=1e-14 * L.r3)
    plt.close(fig)


@HYPOTHESIS
@given(lengths, lengths, lengths, lengths)
def test_lengths_from_coefficients_inverts_the_coefficients(r1, r2, r3, r4):
    k = F.freudenstein_coefficients(F.Linkage(r1, r2, r3, r4))
    got = F.lengths_from_coefficients(np.array([k, [0.0, -1.0, 0.0], [-1.0, -1.0, -9.0]]), r4)
    # r2 comes from a difference of squares: accurate to sqrt(eps) of the longest link
    assert_allclose(got[0], [r1, r2, r3], rtol=1e-9, atol=1e-6 * max(r1, r2, r3, r4))
    assert np.isnan(got[1:]).all()  # k1 = 0 and r2^2 < 0 belong to no linkage
