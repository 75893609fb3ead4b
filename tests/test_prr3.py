"""Tests of mechnum.mechanisms.prr3: every public function on valid, extreme and bad input.

The study's printed numbers are checked by tests/test_published_values.py through the registry;
here every function is checked by a defining property (a round trip, a residual, a derivative),
with hypothesis over the valid domain and just outside it.
"""


import matplotlib
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from mechnum.errors import GeometryError
from mechnum.mechanisms import hacksaw, prr3
from mechnum.mechanisms.prr3 import Geometry, _geometry
from mechnum.mechanisms.prr3 import _annex_i as annex_i
from mechnum.mechanisms.prr3 import _direct as DIRECT
from mechnum.mechanisms.prr3.study import EXAMPLES, WORKSPACE_GEOMETRY, annex_i_terms, reproduce
from mechnum.newton import fd_jacobian
from mechnum.plotting import animate

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

FIG = plt.subplots()  # the axes of the drawing tests, closed at the end of the module
MANY = settings(max_examples=200, deadline=None,
                suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
TABLE_5 = EXAMPLES["Table 5"][0]
# |det J| above this (dimensionless) is a regular pose: round-off moves it by about
# eps / |det J|, and its neighbouring assembly modes are far enough to be told apart.
REGULAR = 1e-2
SIGNS = [(s1, s2, s3) for s1 in (1, -1) for s2 in (1, -1) for s3 in (1, -1)]

geometries = st.builds(Geometry, L=st.floats(0.5, 2.0), a=st.floats(0.3, 2.0),
                       B2=st.floats(1.0, 4.0), B3=st.floats(0.5, 3.0), H3=st.floats(0.5, 3.0))
scales = st.sampled_from([1e-6, 1.0, 1e6])


def angle_gap(a, b):
    return np.abs(np.mod(np.asarray(a) - b + np.pi, 2 * np.pi) - np.pi)


def pose_gap(poses, pose, L=1.0):
    """Distance of each of ``poses`` to ``pose``: position relative to L plus angle."""
    poses = np.asarray(poses).reshape(-1, 3)
    return (np.hypot(*(poses[:, :2] - pose[:2]).T) / L + angle_gap(poses[:, 2], pose[2]))


@st.composite
def reachable(draw, geometry=None, margin=1e-3):
    """A geometry and a pose where every leg reaches its guide with radicands >= margin L^2."""
    g = geometry or draw(geometries)
    psi = draw(st.floats(-np.pi, np.pi))
    u, v = draw(st.floats(-0.99, 0.99)), draw(st.floats(-0.99, 0.99))
    x = g.B3 - g.a * np.cos(psi + np.pi / 3) + u * g.L  # leg 3 reaches its guide
    pose = np.array([x, v * g.L, psi])
    assume(np.all(prr3.radicands(g, pose) > margin * g.L ** 2))
    return g, pose


def singular_pose(geometry=TABLE_5, mode=(1, -1, -1), y=0.3, psi=0.5):
    """A pose of working mode ``mode`` at a direct singularity (det J = 0 on a line)."""
    def det(x):
        pose = [x, y, psi]
        return prr3.jacobian_dets(geometry, pose, prr3.branch_inputs(geometry, pose, mode))[1]
    x = brentq(det, 3.0, 3.4, xtol=1e-15)
    pose = np.array([x, y, psi])
    return pose, prr3.branch_inputs(geometry, pose, mode)


# --- Geometry -----------------------------------------------------------------------------

@MANY
@given(L=st.floats(-1e120, 1e120), a=st.floats(-1e120, 1e120), B=st.floats(-1e120, 1e120))
def test_geometry_accepts_what_it_can_resolve_and_names_the_rest(L, a, B):
    try:
        g = Geometry(L=L, a=a, B2=B, B3=1.0, H3=1.0)
    except GeometryError as error:
        assert any(name in str(error) for name in ("geometry L", "geometry a", "geometry B2"))
        assert not (1e-100 <= L <= 1e100 and 1e-100 <= a <= 1e100 and abs(B) <= 1e100
                    and max(L, a) <= 1e6 * min(L, a))
    else:
        assert (g.L, g.a, g.B2) == (L, a, B)


@pytest.mark.parametrize("kwargs, error, name", [
    (dict(L=0.0), GeometryError, "L"), (dict(a=-1.0), GeometryError, "a"),
    (dict(L=np.nan), ValueError, "L"), (dict(B2=np.inf), ValueError, "B2"),
    (dict(H3=1j), ValueError, "H3"), (dict(B3=[1.0, 2.0]), ValueError, "B3"),
    (dict(L=1e200, a=1e200), GeometryError, "L"), (dict(B2=1e101), GeometryError, "B2"),
    (dict(a=1e-7), GeometryError, "a"),
])
def test_bad_geometry_is_refused_by_name(kwargs, error, name):
    with pytest.raises(error, match=name):
        Geometry(**(dict(L=1, a=1, B2=3, B3=2, H3=3) | kwargs))


# --- geometry functions -------------------------------------------------------------------

@MANY
@given(g=geometries, poses=st.lists(st.tuples(*[st.floats(-1e3, 1e3)] * 3), max_size=4))
def test_vertices_form_the_platform_triangle(g, poses):
    v = _geometry.vertices(g, np.reshape(poses, (-1, 3)))
    assert v.shape == (len(poses), 3, 2)
    sides = np.linalg.norm(v - np.roll(v, 1, axis=1), axis=-1)
    # the sides of a rotated and shifted triangle: round-off of the rotation and of the shift
    # (poses up to 1e3 m), relative to the side and to the coordinates' size
    assert_allclose(sides, g.a, rtol=1e-9, atol=1e-12 * (1 + np.abs(v).max(initial=0)))
    assert_allclose(v[:, 0], np.reshape(poses, (-1, 3))[:, :2], rtol=0)
    if len(poses):  # counter-clockwise: P3 to the left of P1 P2
        e1, e2 = v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]
        assert np.all(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] > 0)


@MANY
@given(g=geometries, lam=st.tuples(*[st.floats(-1e6, 1e6)] * 3))
def test_sliders_sit_on_their_guides_at_their_inputs(g, lam):
    c = _geometry.sliders(g, lam)
    assert c[0, 1] == c[1, 1] == 0 and c[2, 0] == g.B3
    assert_allclose([c[0, 0], g.B2 - c[1, 0], g.H3 - c[2, 1]], lam, rtol=0,
                    atol=1e-9 * (1 + abs(g.B2)
                                                                                 + abs(g.H3)))


@MANY
@given(case=reachable())
def test_every_inverse_solution_closes_the_loops_and_the_radicands_say_so(case):
    g, pose = case
    lam = prr3.inverse(g, pose)
    assert lam.shape == (8, 3)  # no leg tangent: radicands >= 1e-3 L^2
    assert_allclose(_geometry.loop_residuals(g, pose, lam), 0, atol=1e-12 * g.L ** 2)
    bars = _geometry.bars(g, pose, lam)
    assert_allclose(np.sum(bars ** 2, -1) - g.L ** 2, _geometry.loop_residuals(g, pose, lam),
                    rtol=0, atol=1e-13)
    rad = prr3.radicands(g, pose)  # the bar's component across its guide is sqrt(L^2 - rad)
    across = np.abs([bars[0, 0, 1], bars[0, 1, 1], bars[0, 2, 0]])
    assert_allclose(across ** 2, g.L ** 2 - rad, rtol=0, atol=1e-12)
    assert len({tuple(np.round(row, 9)) for row in lam}) == 8


@MANY
@given(case=reachable(margin=-1.0), signs=st.sampled_from(SIGNS))
def test_branch_inputs_close_the_loops_where_the_legs_reach(case, signs):
    g, pose = case
    poses = np.stack([pose, pose + [0.0, 3 * g.L, 0.0]])  # the second: leg 1 cannot reach
    lam = prr3.branch_inputs(g, poses, signs)
    reach = prr3.radicands(g, poses) >= 0
    assert np.array_equal(np.isfinite(lam), reach)
    if reach[0].all():
        assert_allclose(_geometry.loop_residuals(g, pose, lam[0]), 0, atol=1e-12)
        assert any(np.allclose(lam[0], row, atol=1e-12) for row in prr3.inverse(g, pose))


def test_a_tangent_leg_gives_one_value_of_its_input():
    geometry, _ = EXAMPLES["Table 3"]
    pose = [0.6, 1.0, 0.0]  # y_P = L: legs 1 and 2 tangent (psi = 0 puts P2 at the same y)
    lam = prr3.inverse(geometry, pose)
    assert lam.shape == (2, 3)
    assert_allclose(lam[:, :2], [[0.6, 1.4], [0.6, 1.4]], rtol=0, atol=1e-15)
    assert_allclose(prr3.radicands(geometry, pose)[:2], 0.0, atol=1e-15)
    assert prr3.inverse(geometry, [0.6, 1.4, 0.0]).shape == (0, 3)


@MANY
@given(case=reachable(margin=-1.0), k=st.integers(0, 7))
def test_jacobians_match_finite_differences(case, k):
    g, pose = case
    lam = prr3.branch_inputs(g, pose, SIGNS[k])
    assume(np.all(np.isfinite(lam)))
    J = _geometry.direct_jacobian(g, pose, lam)
    assert_allclose(J, fd_jacobian(lambda p: _geometry.loop_residuals(g, p, lam), pose), rtol=0,
                    atol=1e-6)
    Ji = _geometry.inverse_jacobian(g, pose, lam)
    assert_allclose(Ji, fd_jacobian(lambda q: _geometry.loop_residuals(g, pose, q), lam), rtol=0,
                    atol=1e-6)
    assert np.count_nonzero(Ji - np.diag(np.diag(Ji))) == 0


@MANY
@given(case=reachable(margin=-1.0), k=st.integers(0, 7), scale=scales)
def test_jacobian_dets_are_dimensionless(case, k, scale):
    g, pose = case
    lam = prr3.branch_inputs(g, pose, SIGNS[k])
    assume(np.all(np.isfinite(lam)))
    big = Geometry(L=g.L * scale, a=g.a * scale, B2=g.B2 * scale, B3=g.B3 * scale,
                   H3=g.H3 * scale)
    pose_big = np.r_[pose[:2] * scale, pose[2]]
    assert_allclose(prr3.jacobian_dets(big, pose_big, lam * scale),
                    prr3.jacobian_dets(g, pose, lam), rtol=0, atol=1e-9)
    inverse_det, direct_det = prr3.jacobian_dets(g, pose, lam)
    assert_allclose(inverse_det * (2 * g.L) ** 3,
                    np.linalg.det(_geometry.inverse_jacobian(g, pose, lam)),
                    rtol=1e-9, atol=1e-12)


@MANY
@given(x=st.floats(-1e300, 1e300), y=st.floats(-1e300, 1e300), psi=st.floats(-1e6, 1e6))
def test_workspace_agrees_with_inverse_even_far_away(x, y, psi):
    g = TABLE_5
    reach = prr3.workspace(g, np.stack(np.broadcast_arrays(x, y, psi), axis=-1))
    assert reach.shape == () and reach == (len(prr3.inverse(g, [x, y, psi])) > 0)


def test_workspace_is_vectorised_and_takes_empty_grids():
    g = TABLE_5
    x, y, psi = np.meshgrid(np.linspace(-1, 4, 11), np.linspace(-1, 2, 7), [0.0, 1.0],
                            indexing="ij")
    reach = prr3.workspace(g, np.stack(np.broadcast_arrays(x, y, psi), axis=-1))
    assert reach.shape == (11, 7, 2) and reach.any() and not reach.all()
    expected = [len(prr3.inverse(g, p)) > 0 for p in np.stack([x, y, psi], -1).reshape(-1, 3)]
    assert np.array_equal(reach.ravel(), expected)
    assert prr3.workspace(g, np.empty((0, 3))).shape == (0,)


# --- the polynomial -----------------------------------------------------------------------

@MANY
@given(case=reachable(), k=st.integers(0, 7))
def test_polynomial_vanishes_at_every_true_pose_and_at_plus_minus_i(case, k):
    g, pose = case
    lam = prr3.inverse(g, pose)[k]
    C = prr3.polynomial(g, lam)
    scale = np.abs(C).max()
    assume(abs(np.cos(pose[2] / 2)) > 0.05)  # t = tan(psi/2) of order 1
    # a self-motion (the polynomial vanishes identically but for round-off; make explore found
    # two): forward reports a continuum, and no relative bound on C's values can hold
    if prr3.forward(g, lam).status == "singular":
        assert scale <= 1e-12 * (1 + np.ptp(lam) + g.L + g.a) ** 8
        return
    t = np.tan(pose[2] / 2)
    size = np.polynomial.polynomial.polyval(abs(t), np.abs(C))  # sum |C_k| |t|^k
    # round-off of the coefficients themselves: eps times the largest
    assert abs(np.polynomial.polynomial.polyval(t, C)) <= 1e-10 * size + 1e-13 * scale
    assert abs(np.polynomial.polynomial.polyval(1j, C)) < 1e-13 * np.abs(C).sum()
    q = prr3.deflate(C)  # (1 + t^2) q is C again
    assert_allclose(np.convolve([1, 0, 1], q), C, rtol=0, atol=1e-12 * scale)


def test_polynomial_equals_equation_148_times_one_plus_t_squared_to_the_fourth():
    geometry, lam = EXAMPLES["Table 6"]
    l1, l2, l3 = lam
    a, B2, B3, H3, L = geometry.a, geometry.B2, geometry.B3, geometry.H3, geometry.L
    r3 = np.sqrt(3)
    for psi in np.linspace(-3, 3, 7):
        s, c = np.sin(psi), np.cos(psi)
        f1, f2 = 2 * a * c + 2 * l1 + 2 * (l2 - B2), 2 * a * s
        f3 = 2 * a * (l2 - B2) * c - l1 ** 2 + a ** 2 + (l2 - B2) ** 2
        g1 = -a * r3 * s + a * c + 2 * (l1 - B3)
        g2 = a * s + a * r3 * c + 2 * (l3 - H3)
        g3 = ((a * (l3 - H3) + a * r3 * B3) * s + (a * r3 * (l3 - H3) - a * B3) * c
              - l1 ** 2 + B3 ** 2 + a ** 2 + (l3 - H3) ** 2)
        eq148 = ((f3 * g2 - f2 * g3 - l1 * (f2 * g1 - f1 * g2)) ** 2 + (f1 * g3 - f3 * g1) ** 2
                 - L ** 2 * (f2 * g1 - f1 * g2) ** 2)
        t = np.tan(psi / 2)
        value = np.polynomial.polynomial.polyval(t, prr3.polynomial(geometry, lam))
        assert value == pytest.approx(eq148 * (1 + t ** 2) ** 4, rel=1e-11)


def test_one_plus_t_squared_divides_the_polynomial_symbolically():
    # (1 + t^2) times cos, sin and 1 are 1 - t^2, 2 t and 1 + t^2: at t = i, 2, 2 i and 0.
    # The polynomial has real coefficients, so P(i) = 0 for all inputs means 1 + t^2 divides it.
    l1, l2, l3, a, L, B2, B3, H3 = sp.symbols("lambda1:4 a L B2 B3 H3", real=True)
    c, s, one, r3 = 2, 2 * sp.I, 0, sp.sqrt(3)
    f1, f2 = 2 * a * c + (2 * l1 + 2 * (l2 - B2)) * one, 2 * a * s
    f3 = 2 * a * (l2 - B2) * c + (-l1 ** 2 + a ** 2 + (l2 - B2) ** 2) * one
    g1 = -a * r3 * s + a * c + 2 * (l1 - B3) * one
    g2 = a * s + a * r3 * c + 2 * (l3 - H3) * one
    g3 = ((a * (l3 - H3) + a * r3 * B3) * s + (a * r3 * (l3 - H3) - a * B3) * c
          + (-l1 ** 2 + B3 ** 2 + a ** 2 + (l3 - H3) ** 2) * one)
    D = f2 * g1 - f1 * g2
    assert sp.expand((f3 * g2 - f2 * g3 - l1 * D) ** 2 + (f1 * g3 - f3 * g1) ** 2
                     - L ** 2 * D ** 2) == 0


def test_annex_i_as_printed_against_the_expansion():
    # The typeset coefficients have as many terms as the expansion of (148) in the K and Q;
    # the wrong ones (wrong powers, hence absent from the expansion) are all in C8, C7, C6, C2.
    t, L, lam = sp.symbols("t L lambda1")
    K, Q = sp.symbols("K1:6"), sp.symbols("Q1:10")
    c, s, one = 1 - t ** 2, 2 * t, 1 + t ** 2
    f1, f2, f3 = K[0] * c + K[1] * one, K[2] * s, K[3] * c + K[4] * one
    g1, g2, g3 = [Q[3 * j] * s + Q[3 * j + 1] * c + Q[3 * j + 2] * one for j in range(3)]
    D = f2 * g1 - f1 * g2
    poly = sp.Poly(sp.expand((f3 * g2 - f2 * g3 - lam * D) ** 2 + (f1 * g3 - f3 * g1) ** 2
                             - L ** 2 * D ** 2), t)
    names = {str(v): v for v in (*K, *Q, L, lam)}
    wrong = {}
    for k, printed in annex_i_terms().items():
        expansion = sp.Poly(poly.coeff_monomial(t ** k), *names.values())
        assert len(printed) == len(expansion.terms())
        monomials = [sp.Mul(*(names[n] ** p for n, p in powers.items()))
                     for _, powers in printed]
        wrong[k] = sum(expansion.coeff_monomial(m) != coefficient
                       for (coefficient, _), m in zip(printed, monomials))
    assert {k for k, n in wrong.items() if n} == {8, 7, 6, 2}


def test_annex_i_parser_refuses_what_is_not_a_monomial():
    assert annex_i.parse_terms("3*K1^2 - Q5") == [(3, {"K1": 2}), (-1, {"Q5": 1})]
    with pytest.raises(ValueError, match="not a monomial"):
        annex_i.parse_terms("3*K1^2 - Q5/2")
    with pytest.raises(ValueError, match="text must be a str"):
        annex_i.parse_terms(None)


@MANY
@given(case=reachable(), k=st.integers(0, 7))
def test_equations_vanish_at_the_true_pose_and_map_back(case, k):
    g, pose = case
    lam = prr3.inverse(g, pose)[k]
    system = prr3.equations(g, lam)
    point = [pose[0] / g.L, pose[1] / g.L, np.cos(pose[2]), np.sin(pose[2])]
    assert np.abs(system(point)).max() < 1e-11
    back = prr3.solutions_from_equations(g, [point])[0]
    assert pose_gap(back, pose, g.L)[0] < 1e-12


# --- the direct problem -------------------------------------------------------------------

@MANY
@given(case=reachable())
@example(case=(Geometry(L=2.0, a=0.5, B2=1.0, B3=1.0, H3=1.0),
               np.array([1.750846179, 0.0, 2.0 ** -9])))
def test_direct_returns_the_pose_of_every_inverse_solution(case):
    g, pose = case
    lam = prr3.inverse(g, pose)
    sol = prr3.forward(g, lam)
    assert np.array_equal(sol.counts, np.bincount(sol.input_index, minlength=8))
    assert np.all(sol.counts <= 6)
    assert np.all(sol.residuals <= 1e-6)
    # the loops close to 1e-6 L^2 (in m^2): near a direct singularity, where the polish stops,
    # that is all (L = 2, pose (1.750846179, 0, 2^-9): 2.9e-6 m^2 = 7e-7 L^2)
    assert_allclose(_geometry.loop_residuals(g, sol.x, lam[sol.input_index]), 0,
                    atol=1e-6 * g.L ** 2)
    assert np.all((sol.x[:, 2] >= 0) & (sol.x[:, 2] < 2 * np.pi))
    for k in range(8):  # the pose itself, unless it is near a direct singularity, where two
        if abs(prr3.jacobian_dets(g, pose, lam[k])[1]) > REGULAR:  # roots nearly merge
            assert pose_gap(sol.x[sol.input_index == k], pose, g.L).min() < 1e-9


@MANY
@given(lam=st.lists(st.tuples(*[st.floats(-2, 5)] * 3), min_size=0, max_size=5))
def test_direct_on_a_batch_equals_direct_on_each_input(lam):
    g = TABLE_5
    batch = np.reshape(lam, (-1, 3))
    sol = prr3.forward(g, batch)
    assert sol.x.shape == (sol.counts.sum(), 3) and sol.counts.shape == (len(batch),)
    for k, one in enumerate(batch):
        alone = prr3.forward(g, one)
        assert alone.counts.shape == () and alone.counts == sol.counts[k]
        assert_allclose(alone.x, sol.x[sol.input_index == k], rtol=0, atol=1e-12)
        assert np.all(alone.residuals <= 1e-6)


@pytest.mark.parametrize("k", range(4))
def test_direct_finds_as_many_real_poses_as_the_homotopy(k):
    # an independent count: every finite solution of the four quadratics, by continuation
    from mechnum import homotopy
    rng = np.random.default_rng(k)
    g = TABLE_5
    while True:
        pose = np.array([rng.uniform(0, 4), rng.uniform(-1, 1), rng.uniform(0, 2 * np.pi)])
        if np.all(prr3.radicands(g, pose) > 1e-2):
            break
    lam = prr3.inverse(g, pose)[rng.integers(8)]
    found = homotopy.solve(prr3.equations(g, lam), rng=k)
    real = prr3.solutions_from_equations(g, found.real(1e-7))
    poses = prr3.forward(g, lam).x
    assert len(poses) == len(real) >= 2
    for p in real:
        assert pose_gap(poses, p).min() < 1e-7


def test_far_apart_sliders_have_no_pose_even_at_1e300():
    g = EXAMPLES["Table 6"][0]
    sol = prr3.forward(g, [[1e100, 0.0, 0.0], [1e300, -1e300, 1e300], [0.4, 0.1, 0.6]])
    assert sol.counts.tolist() == [0, 0, 2]
    c = _geometry.sliders(g, [1e100, 0.0, 0.0])  # no pose: sliders 1 and 2 are 1e100 apart
    assert np.linalg.norm(c[0] - c[1]) > 2 * g.L + g.a


@pytest.mark.parametrize("scale", [1e-90, 1e-3, 1e3, 1e90])
def test_direct_does_not_depend_on_the_unit_of_length(scale):
    g, lam = EXAMPLES["Table 6"]
    big = Geometry(L=g.L * scale, a=g.a * scale, B2=g.B2 * scale, B3=g.B3 * scale,
                   H3=g.H3 * scale)
    base = prr3.forward(g, lam).x
    poses = prr3.forward(big, np.multiply(lam, scale)).x
    assert_allclose(poses[:, :2] / scale, base[:, :2], rtol=0, atol=1e-12)
    assert_allclose(poses[:, 2], base[:, 2], rtol=0, atol=1e-12)


def test_pose_at_psi_pi_is_found_whatever_the_leading_coefficient():
    g = EXAMPLES["Table 3"][0]
    pose = np.array([1.25, -0.75, np.pi])
    for lam in prr3.inverse(g, pose):
        assert pose_gap(prr3.forward(g, lam).x, pose).min() < 1e-12


def test_pose_where_the_elimination_is_singular_is_still_found():
    g = TABLE_5
    pose = np.array([1.0, 0.6, 0.0])  # lambda1 + lambda2 = B2 - a: circles 1 and 2 coincide
    lam = prr3.inverse(g, pose)[0]
    assert lam[0] + lam[1] == pytest.approx(g.B2 - g.a)
    sol = prr3.forward(g, lam)
    hit = np.argmin(pose_gap(sol.x, pose))
    assert pose_gap(sol.x, pose)[hit] < 1e-9
    assert sol.elimination_singular[hit] and not sol.singular[hit]


def test_a_pose_at_a_direct_singularity_is_found_and_flagged():
    pose, lam = singular_pose()
    sol = prr3.forward(TABLE_5, lam)
    hit = np.argmin(pose_gap(sol.x, pose))
    assert pose_gap(sol.x, pose)[hit] < 1e-6  # a double root: about sqrt(eps)
    assert sol.singular[hit]


def test_a_self_motion_is_reported_as_a_continuum():
    g = TABLE_5
    lam = [3.5, 0.5, 2.8]  # C2 = C3 = (2.5, 0): the platform turns about P = (2.5, 0)
    scale = np.abs(prr3.polynomial(g, [2.0, 0.5, 0.2])).max()
    assert np.abs(prr3.polynomial(g, lam)).max() < 1e-12 * scale  # zero but for round-off
    for psi in (0.3, 2.0, 4.0):
        assert_allclose(_geometry.loop_residuals(g, [2.5, 0.0, psi], lam), 0, atol=1e-14)
    sol = prr3.forward(g, [lam, [2.0, 0.5, 0.2]])
    assert sol.status.tolist() == ["singular", "converged"] and sol.counts.tolist() == [0, 2]


def test_polish_leaves_a_singular_pose_and_far_jumps_alone():
    pose, lam = singular_pose()
    out = DIRECT._polish(TABLE_5, pose[None], lam)
    assert_allclose(out, pose[None], rtol=0, atol=1e-15)  # J singular: no step taken, no NaN
    start = pose + [0.0, 0.0, 0.2]  # far from any pose: Newton would run elsewhere
    moved = DIRECT._polish(TABLE_5, start[None], lam)
    step = np.hypot(*(moved - start)[0, :2]) + abs(moved - start)[0, 2]
    assert step == 0.0 or step <= 1e-2


@MANY
@given(case=reachable(geometry=TABLE_5), seed=st.integers(0, 2 ** 32 - 1))
def test_newton_from_many_starts_finds_only_poses_of_the_polynomial(case, seed):
    g, pose = case
    lam = prr3.inverse(g, pose)[seed % 8]
    rng = np.random.default_rng(seed)
    seeds = np.vstack([pose + rng.normal(0, 1e-3, 3), np.column_stack(
        [rng.uniform(-1, 5, 20), rng.uniform(-2, 3, 20), rng.uniform(0, 2 * np.pi, 20)])])
    newton = prr3.forward_by_newton(g, lam, seeds)
    poly = prr3.forward(g, lam).x
    assume(abs(prr3.jacobian_dets(g, pose, lam)[1]) > REGULAR)  # else Newton is only linear
    assert pose_gap(newton, pose).min() < 1e-8  # the start next to the pose converges to it
    for p in newton:
        if abs(prr3.jacobian_dets(g, p, lam)[1]) > REGULAR:
            assert pose_gap(poly, p).min() < 1e-8


@pytest.mark.parametrize("call", [
    lambda g: prr3.inverse(g, [0.0, np.inf, 0.0]),
    lambda g: prr3.inverse(g, [[0.0, 0.0, 0.0]]),
    lambda g: prr3.inverse(g, [0.6, 0.4, 0.0], tol=-1),
    lambda g: prr3.inverse(g, [0.6, 0.4, 0.0], tol=np.nan),
    lambda g: prr3.branch_inputs(g, [0.6, 0.4, 0.0], (1, 0, 1)),
    lambda g: prr3.branch_inputs(g, [0.6, 0.4]),
    lambda g: prr3.workspace(g, [[0.0, 1.0], [0.0, 1.0]]),
    lambda g: prr3.workspace(g, [0.0, np.nan, 0.0]),
    lambda g: prr3.workspace(g, [0.0, 0.0, 0.0], tol=0.0),
    lambda g: _geometry.vertices(g, [1.0, 2.0]),
    lambda g: _geometry.sliders(g, [1.0, 2.0j, 3.0]),
    lambda g: prr3.radicands(g, "pose"),
    lambda g: _geometry.loop_residuals(g, [0.0, 0.0, 0.0], [[1.0, 2.0]]),
    lambda g: _geometry.direct_jacobian(g, [0.0, 0.0, np.nan], [0.0, 0.0, 0.0]),
    lambda g: _geometry.inverse_jacobian(g, [0.0, 0.0, 0.0], [0.0, 0.0]),
    lambda g: prr3.jacobian_dets(g, [0.0, 0.0, 0.0], [np.inf, 0.0, 0.0]),
    lambda g: prr3.polynomial(g, [1.0, 2.0]),
    lambda g: prr3.polynomial(g, [1e300, 0.0, 0.0]),
    lambda g: prr3.deflate([1.0, 2.0, 3.0]),
    lambda g: prr3.equations(g, [[0.4, 0.1, 0.6]] * 2),
    lambda g: prr3.forward(g, [1.0, 2.0]),
    lambda g: prr3.forward(g, [1.0, np.nan, 0.0]),
    lambda g: prr3.forward(g, [[[0.4, 0.1, 0.6]]]),
    lambda g: prr3.forward(g, [0.4, 0.1, 0.6], imag_tol=-1),
    lambda g: prr3.forward(g, [0.4, 0.1, 0.6], residual_tol=np.nan),
    lambda g: prr3.forward(g, np.zeros((DIRECT.MAX_INPUTS + 1, 3))),  # a bound on the work
    lambda g: prr3.forward_by_newton(g, [0.4, 0.1, 0.6], np.zeros((DIRECT.MAX_INPUTS + 1, 3))),
    lambda g: prr3.forward_by_newton(g, [0.4, 0.1, 0.6], [0.0, 0.0, 0.0]),
    lambda g: prr3.forward_by_newton(g, [0.4, 0.1, 0.6], [[0.0, 0.0, 0.0]], tol=-1),
    lambda g: prr3.draw(FIG[1], g, ([1.5, 0.5, 0.2], [[0.6, 0.4, 0.0]] * 2)),
    lambda g: prr3.draw(None, g, ([1.5, 0.5, 0.2], [0.6, 0.4, 0.0])),
    lambda g: prr3.draw(FIG[1], g, [0.6, 0.4, 0.0]),
    lambda g: prr3.draw(FIG[1], g, ([1.5, 0.5, 0.2], [0.6, 0.4, 0.0]), guides=1),
    # R4: poses and inputs that do not broadcast; D13: NaN where a solution must be
    lambda g: _geometry.loop_residuals(g, np.zeros((2, 3)), np.zeros((3, 3))),
    lambda g: _geometry.bars(g, np.zeros((2, 3)), np.zeros((4, 3))),
    lambda g: prr3.jacobian_dets(g, np.zeros((2, 3)), np.zeros((3, 3))),
    lambda g: prr3.solutions_from_equations(g, [[np.nan, 0.0, 1.0, 0.0]]),
    lambda g: prr3.solutions_from_equations(g, [[0.5, 0.5, 1.0, 1.0]]),  # cos^2 + sin^2 = 2
    lambda g: prr3.solutions_from_equations(g, [[0.5, 0.5, 1.0]]),
    # R6: no geometry, or another mechanism's
    lambda g: prr3.forward(None, [0.4, 0.1, 0.6]),
    lambda g: _geometry.vertices(None, [0.6, 0.4, 0.0]),
    lambda g: prr3.radicands(hacksaw.Geometry(), [0.6, 0.4, 0.0]),
    lambda g: prr3.inverse(None, [0.6, 0.4, 0.0]),
    lambda g: prr3.singular_points(None, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]]),
    lambda g: prr3.singular_points(g, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]], kind="both"),
    lambda g: prr3.singular_points(g, [[3.0, 0.3, 0.5], [3.4, 0.3]], signs=(1, -1, -1)),
    lambda g: prr3.singular_points(g, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]], signs=(1, 2, -1)),
    lambda g: prr3.singular_points(g, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]], samples=10 ** 7),
    lambda g: prr3.mode_change_path(g, [2.2, 0.5, 3.0], [2.3, 0.5, 3.2], (1, 1, 1),
                                    bounds=[[1.5, 3.5], [0.0, 1.0]], shape=(2000, 2000, 2)),
])
def test_bad_input_raises_a_value_error_that_names_it(call):
    with pytest.raises(ValueError, match="pose|lambdas|tol|signs|x, y|psi|y must|overflow|"
                                         "c must|seeds|takes one|shape|mech must be|ax must|"
                                         "state must|guides|points|kind|start|end|samples|inputs"):
        call(EXAMPLES["Table 6"][0])


def test_an_empty_batch_is_valid_everywhere():
    g = TABLE_5
    empty = np.empty((0, 3))
    sol = prr3.forward(g, empty)
    assert sol.x.shape == (0, 3) and sol.counts.shape == (0,)
    assert prr3.branch_inputs(g, empty).shape == (0, 3)
    assert prr3.radicands(g, empty).shape == (0, 3)
    assert _geometry.loop_residuals(g, empty, empty).shape == (0, 3)
    assert _geometry.direct_jacobian(g, empty, empty).shape == (0, 3, 3)
    assert prr3.jacobian_dets(g, empty, empty)[1].shape == (0,)
    assert prr3.polynomial(g, empty).shape == (0, 9)
    assert prr3.forward_by_newton(g, [0.4, 0.1, 0.6], empty).shape == (0, 3)


def test_draw_draws_the_guides_bars_sliders_and_platform():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    g, pose = EXAMPLES["Table 3"]
    lam = prr3.inverse(g, pose)[0]
    fig, ax = plt.subplots()
    assert len(prr3.draw(ax, g, (lam, pose))) == len(prr3.draw(ax, g, (lam, pose),
                                                               guides=False)) + 3
    artists = prr3.draw(ax, g, (lam, pose), guides=False)
    legs = artists["bars"].get_xydata().reshape(3, 3, 2)[:, :2]  # C_i, P_i and a break
    np.testing.assert_allclose(legs[:, 0], _geometry.sliders(g, lam), rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(legs[:, 1], _geometry.vertices(g, pose), rtol=1e-15, atol=1e-15)
    assert_allclose(np.linalg.norm(legs[:, 1] - legs[:, 0], axis=1), g.L, rtol=1e-12)
    assert_allclose(artists["platform"].get_xy()[:3], _geometry.vertices(g, pose), rtol=1e-15)
    other = prr3.inverse(g, pose)[5]  # another working mode: the drawing moves, nothing added
    count = len(ax.lines) + len(ax.patches)
    assert prr3.draw(ax, g, (other, pose), artists=artists, guides=False) is artists
    assert len(ax.lines) + len(ax.patches) == count
    legs = artists["bars"].get_xydata().reshape(3, 3, 2)[:, :2]
    np.testing.assert_allclose(legs[:, 0], _geometry.sliders(g, other), rtol=1e-15, atol=1e-15)
    plt.close(fig)


def test_animate_moves_the_platform_along_a_path():
    g, pose = EXAMPLES["Table 3"]
    path = pose + np.outer(np.linspace(0, 0.1, 4), [1.0, 0.5, 0.2])
    inputs = prr3.branch_inputs(g, path)
    html = animate(prr3.draw, g, list(zip(inputs, path)))
    assert html.count("data:image/png;base64") == 4


def test_reproduce_gives_every_quantity_of_the_chapter():
    values = reproduce()
    assert all(np.isfinite(v) for v in values.values())
    assert values["Table 3 number of solutions"] == 8 == values["Table 4 number of solutions"]


# --- singularity-free paths ---------------------------------------------------------------

def _assert_singularity_free(path, g, signs):
    dense = np.concatenate([a + np.linspace(0, 1, 50)[:, None] * (b - a)
                            for a, b in zip(path[:-1], path[1:])])
    lam = prr3.branch_inputs(g, dense, signs)
    assert np.all(prr3.radicands(g, dense) > 0)
    dets = prr3.jacobian_dets(g, dense, lam)[1]
    assert np.all(np.sign(dets) == np.sign(dets[0])) and np.all(np.abs(dets) > 0)


def test_mode_change_path_joins_two_assembly_modes_of_one_input():
    g, signs = TABLE_5, (1, 1, 1)
    lam0 = np.array([3.1266, 1.8887, 3.6427])
    sol = prr3.forward(g, lam0)
    start, end = sol.x[1], sol.x[3]  # the same working mode and sign of det J
    assert_allclose(prr3.branch_inputs(g, sol.x[[1, 3]], signs), [lam0, lam0], rtol=0,
                    atol=1e-9)
    path = prr3.mode_change_path(g, start, end, signs, bounds=[[-0.5, 4.5], [-1.0, 1.0]]).x
    assert_allclose(path[[0, -1]], [start, end], rtol=0, atol=1e-12)
    _assert_singularity_free(path, g, signs)


def _assemblable_poses():
    """Poses of Table 5's mechanism in the window below that its (1, 1, 1) branch assembles,
    split by the sign of det J: a pair from one part is a valid case of the test below, drawn
    directly (filtering random pairs rejects three in four and trips hypothesis's health check)."""
    rng = np.random.default_rng(5)
    poses = np.column_stack([rng.uniform(1.6, 3.4, 4000), rng.uniform(0.05, 0.95, 4000),
                             rng.uniform(0.0, 2 * np.pi, 4000)])
    lam = prr3.branch_inputs(TABLE_5, poses, (1, 1, 1))
    built = np.all(np.isfinite(lam), axis=1)
    poses, lam = poses[built], lam[built]
    det = prr3.jacobian_dets(TABLE_5, poses, lam)[1]
    return poses[det > 0], poses[det < 0]


SAME_SIGN_POSES = _assemblable_poses()


@settings(max_examples=200, deadline=None)
@given(side=st.integers(0, 1), i=st.integers(0, 10 ** 6), j=st.integers(0, 10 ** 6))
def test_mode_change_path_is_singularity_free_or_undecided(side, i, j):
    g, signs, pool = TABLE_5, (1, 1, 1), SAME_SIGN_POSES[side]
    a, b = pool[i % len(pool)], pool[j % len(pool)]
    found = prr3.mode_change_path(g, a, b, signs, bounds=[[1.5, 3.5], [0.0, 1.0]],
                                  shape=(12, 6, 24))
    assert found.status in ("converged", "undecided") and found.converged == (len(found.x) > 0)
    path = found.x
    if found.converged:  # psi is unwrapped along the path: equal modulo 2 pi at the ends
        assert pose_gap(path[0], a)[0] < 1e-12 and pose_gap(path[-1], b)[0] < 1e-12
        _assert_singularity_free(path, g, signs)


@pytest.mark.parametrize("kwargs, message", [
    (dict(start=[2.4, 0.81, 2.97], end=[2.5, -0.79, 1.99]), "one sign"),
    (dict(bounds=[[0.0, 1.0], [0.0, 1.0]]), "outside bounds"),
    (dict(bounds=[[0.0, 1.0]]), "bounds"),
    (dict(shape=(10, 10)), "shape"),
    (dict(start=[np.nan, 0.8, 3.0]), "start"),
    (dict(signs=(1, 2, 1)), "signs"),
])
def test_mode_change_path_refuses_bad_input(kwargs, message):
    args = dict(start=[2.5338, 0.8053, 3.0427], end=[2.4711, 0.7552, 4.3283],
                mech=TABLE_5, signs=(1, 1, 1), bounds=[[-0.5, 4.5], [-1.0, 1.0]]) | kwargs
    with pytest.raises(ValueError, match=message):
        prr3.mode_change_path(**args)


def test_a_root_at_infinity_is_the_pose_psi_pi():
    # (t - 1)(t + 2)(t - 3)(t + 4)(t - 5) with a zero t^6 coefficient: the sixth root is t = inf
    quintic = np.polynomial.polynomial.polyfromroots([1, -2, 3, -4, 5])
    psi = DIRECT._angles(np.r_[quintic, 0.0][None])[0]
    assert np.all(np.isfinite(psi))
    assert angle_gap(psi.real, np.pi).min() < 1e-15
    expected = 2 * np.arctan([1, -2, 3, -4, 5])
    for value in expected:
        assert angle_gap(psi.real, value).min() < 1e-12


def test_a_root_t_equal_i_is_no_pose_and_no_warning():
    # t^6 + t^2 + 2 has the factor 1 + t^2: the companion matrix returns t = +-i exactly, the
    # poles of psi = 2 atan(t). Those roots are complex, no pose; none is real.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        psi = DIRECT._angles(np.array([[2.0, 0, 1, 0, 0, 0, 1]]))[0]
    assert not np.any(np.abs(psi.imag) <= 1e-6)


def test_direct_emits_no_overflow_far_away():
    import warnings
    g = EXAMPLES["Table 6"][0]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow in the polynomial of far-apart sliders
        assert prr3.forward(g, [[1e100, 0.0, 0.0], [1e300, 0.0, -1e300]]).counts.tolist() == [0, 0]


# --- singular points ------------------------------------------------------------------------

def test_singular_points_find_the_direct_singularity_that_brentq_finds():
    pose, lam = singular_pose()  # brentq on the determinant, in this file
    found = prr3.singular_points(TABLE_5, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]],
                                 signs=(1, -1, -1))
    assert found.shape == (1, 3)
    assert_allclose(found[0], pose, rtol=1e-14)
    assert abs(prr3.jacobian_dets(TABLE_5, found[0], lam)[1]) < 1e-12


@MANY
@given(case=reachable(), signs=st.sampled_from(SIGNS), seed=st.integers(0, 2 ** 32 - 1))
def test_singular_points_are_the_sign_changes_of_the_determinant(case, signs, seed):
    g, pose = case
    end = pose + np.random.default_rng(seed).normal(0, 0.3, 3)
    found = prr3.singular_points(g, [pose, end], signs=signs, samples=50)
    s = np.linspace(0, 1, 2001)  # an independent count on a finer grid of the segment
    line = pose + np.outer(s, end - pose)
    lam = prr3.branch_inputs(g, line, signs)
    det = np.full(len(s), np.nan)  # NaN where the mode does not assemble
    built = np.all(np.isfinite(lam), axis=1)
    det[built] = prr3.jacobian_dets(g, line[built], lam[built])[1]
    changes = np.sum(det[:-1] * det[1:] <= 0)  # an exact zero on the grid counts twice
    for p in found:
        assert abs(prr3.jacobian_dets(g, p, prr3.branch_inputs(g, p, signs))[1]) < 1e-9
    assert len(found) <= changes  # the coarse grid may miss two close zeros, never invent one


def test_inverse_singular_points_are_where_a_leg_turns_tangent():
    ws = WORKSPACE_GEOMETRY
    found = prr3.singular_points(ws, [[0.5, 0.0, 0.3], [0.5, 1.5, 0.3]], kind="inverse")
    assert len(found) >= 1
    for p in found:  # some radicand vanishes there
        assert np.abs(prr3.radicands(ws, p)).min() < 1e-12


def test_the_drawing_figure_closes():
    plt.close(FIG[0])
