"""Tests of mechnum.mechanisms.prr3: the study's Tables 3 to 6, round trips, bad input."""

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mechnum.errors import GeometryError
from mechnum.mechanisms import prr3
from mechnum.mechanisms.prr3 import EXAMPLES, Geometry
from mechnum.newton import fd_jacobian

TABLE_3 = [(1.5165, 0.48348, -0.18254), (1.5165, 0.48348, 1.6505), (1.5165, 2.3165, -0.18254),
           (1.5165, 2.3165, 1.6505), (-0.31652, 0.48348, -0.18254), (-0.31652, 0.48348, 1.6505),
           (-0.31652, 2.3165, -0.18254), (-0.31652, 2.3165, 1.6505)]
TABLE_4 = [(3.9539, -1.071, 1.4132), (3.9539, -1.071, 3.4072), (3.9539, 0.64677, 1.4132),
           (3.9539, 0.64677, 3.4072), (2.0461, -1.071, 1.4132), (2.0461, -1.071, 3.4072),
           (2.0461, 0.64677, 1.4132), (2.0461, 0.64677, 3.4072)]
TABLE_5 = [(1.5162, 0.87519, 7.1679), (2.2171, 0.97615, 345.6206)]  # sorted by psi
TABLE_6 = [(1.2312, 0.55593, 9.9967), (1.0535, 0.7569, 341.5164)]


def half_unit(value):
    """Half a unit in the last of the 5 significant digits Matlab's num2str prints."""
    text = f"{value:.5g}"
    decimals = len(text.split(".")[1]) if "." in text else 0
    return 0.5 * 10.0 ** -decimals * (1 + 1e-9)


@pytest.mark.parametrize("table, published", [("Tabla 3", TABLE_3), ("Tabla 4", TABLE_4)])
def test_inverse_reproduces_tables_3_and_4(table, published):
    geometry, pose = EXAMPLES[table]
    lam = prr3.inverse(pose, geometry)
    assert lam.shape == (8, 3)
    for row, pub in zip(lam, published):  # same order as the study's rows
        for value, p in zip(row, pub):
            assert abs(value - p) <= half_unit(p)


@pytest.mark.parametrize("table, published", [("Tabla 5", TABLE_5), ("Tabla 6", TABLE_6)])
def test_direct_reproduces_tables_5_and_6(table, published):
    geometry, lam = EXAMPLES[table]
    poses = prr3.direct(lam, geometry)
    assert poses.shape == (2, 3)
    for (x, y, psi), (px, py, ppsi) in zip(poses, published):
        assert abs(x - px) <= half_unit(px) and abs(y - py) <= half_unit(py)
        assert abs(np.degrees(psi) - ppsi) <= 0.5e-4 * (1 + 1e-9)
    assert np.abs(prr3.loop_residuals(poses, lam, geometry)).max() < 1e-13


@pytest.mark.parametrize("table", ["Tabla 3", "Tabla 4"])
def test_every_inverse_solution_round_trips_through_the_direct_problem(table):
    geometry, pose = EXAMPLES[table]
    for lam in prr3.inverse(pose, geometry):
        poses = prr3.direct(lam, geometry)
        gap = np.abs(poses - pose)
        gap[:, 2] = np.abs(np.mod(gap[:, 2] + np.pi, 2 * np.pi) - np.pi)
        assert gap.max(axis=1).min() < 1e-10


def test_polynomial_equals_equation_148_times_one_plus_t_squared_to_the_fourth():
    geometry, lam = EXAMPLES["Tabla 6"]
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
        value = np.polynomial.polynomial.polyval(t, prr3.polynomial(lam, geometry))
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
    geometry, lam = EXAMPLES["Tabla 6"]
    assert abs(prr3.polynomial(lam, geometry)[8]) > 1  # but the degree is 8


def test_direct_jacobian_matches_finite_differences():
    geometry, lam = EXAMPLES["Tabla 5"]
    for pose in prr3.direct(lam, geometry):
        J = prr3.direct_jacobian(pose, lam, geometry)
        fd = fd_jacobian(lambda p: prr3.loop_residuals(p, lam, geometry), pose)
        assert np.allclose(J, fd, atol=1e-6)


def test_unreachable_pose_has_no_inverse_solution():
    geometry, _ = EXAMPLES["Tabla 3"]
    assert prr3.inverse([0.6, 1.4, 0.0], geometry).shape == (0, 3)
    assert not prr3.workspace(0.6, 1.4, 0.0, geometry)


def test_tangent_leg_is_an_inverse_singularity_with_one_value():
    geometry, _ = EXAMPLES["Tabla 3"]
    pose = [0.6, 1.0, 0.0]  # y_P = L: leg 1 tangent to its guide, P2 too (psi = 0)
    lam = prr3.inverse(pose, geometry)
    assert lam.shape == (2, 3)
    assert np.allclose(lam[:, 0], 0.6) and np.allclose(lam[:, 1], 3 - 1.6)
    assert np.allclose(prr3.radicands(pose, geometry)[:2], 0.0)


def test_pose_at_psi_pi_is_found_from_the_reversed_polynomial():
    geometry, _ = EXAMPLES["Tabla 5"]
    pose = np.array([2.1, -0.9, np.pi])
    for lam in prr3.inverse(pose, geometry):
        sol = prr3.solve_direct(lam, geometry)
        hit = np.flatnonzero(np.abs(sol.poses - pose).max(axis=1) < 1e-10)
        assert hit.size == 1 and sol.from_reversed[hit[0]]


def test_pose_where_the_elimination_is_singular_is_still_found():
    geometry, _ = EXAMPLES["Tabla 5"]
    pose = np.array([1.0, 0.6, 0.0])  # lambda1 + lambda2 = B2 - a: circles 1 and 2 coincide
    lam = prr3.inverse(pose, geometry)[0]
    assert lam[0] + lam[1] == pytest.approx(geometry.B2 - geometry.a)
    sol = prr3.solve_direct(lam, geometry)
    gap = np.abs(sol.poses[:, :2] - pose[:2]).max(axis=1)
    gap += np.abs(np.mod(sol.poses[:, 2] + np.pi, 2 * np.pi) - np.pi)
    hit = np.argmin(gap)
    assert gap[hit] < 1e-9
    assert sol.elimination_singular[hit] and not sol.singular[hit]


def test_newton_finds_no_solution_the_polynomial_misses():
    rng = np.random.default_rng(3)
    geometry, lam = EXAMPLES["Tabla 6"]
    starts = np.column_stack([rng.uniform(-1, 3, 200), rng.uniform(-1, 3, 200),
                              rng.uniform(0, 2 * np.pi, 200)])
    newton = prr3.direct_by_newton(lam, geometry, starts)
    poly = prr3.direct(lam, geometry)
    assert len(newton) >= 1
    for pose in newton:
        assert np.abs(poly - pose).max(axis=1).min() < 1e-8


def test_workspace_is_vectorised_and_agrees_with_inverse():
    geometry, _ = EXAMPLES["Tabla 3"]
    x, y, psi = np.meshgrid(np.linspace(-1, 3, 9), np.linspace(-1, 2, 7), [0.0, 1.0],
                            indexing="ij")
    reach = prr3.workspace(x, y, psi, geometry)
    assert reach.shape == (9, 7, 2) and reach.any() and not reach.all()
    for index in np.ndindex(reach.shape):
        pose = [x[index], y[index], psi[index]]
        assert reach[index] == (len(prr3.inverse(pose, geometry)) > 0)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(u=st.floats(-0.99, 0.99), y=st.floats(-0.99, 0.99), psi=st.floats(-np.pi, np.pi))
def test_round_trip_random_reachable_poses(u, y, psi):
    geometry, _ = EXAMPLES["Tabla 5"]
    x = geometry.B3 - geometry.a * np.cos(psi + np.pi / 3) + u * geometry.L  # leg 3 reaches
    pose = np.array([x, y, psi])
    assume(np.all(prr3.radicands(pose, geometry) > 1e-3))
    for lam in prr3.inverse(pose, geometry):
        if abs(np.linalg.det(prr3.direct_jacobian(pose, lam, geometry))) < 1e-3:
            continue  # near a direct singularity the pose is only accurate to ~1e-8
        poses = prr3.direct(lam, geometry)
        gap = np.abs(poses[:, :2] - pose[:2]).max(axis=1)
        gap += np.abs(np.mod(poses[:, 2] - psi + np.pi, 2 * np.pi) - np.pi)
        assert gap.min() < 1e-9
        assert np.abs(prr3.loop_residuals(poses, lam, geometry)).max() < 1e-6


@settings(max_examples=40, deadline=None)
@given(lam=st.tuples(st.floats(-1, 4), st.floats(-1, 4), st.floats(-1, 4)))
def test_every_direct_solution_closes_the_loops(lam):
    geometry, _ = EXAMPLES["Tabla 6"]
    sol = prr3.solve_direct(lam, geometry)
    assert sol.poses.shape[0] <= 6
    assert np.all(sol.residuals <= 1e-6)
    assert np.all((sol.poses[:, 2] >= 0) & (sol.poses[:, 2] <= 2 * np.pi))


@pytest.mark.parametrize("field, value", [("L", 0.0), ("a", -1.0)])
def test_degenerate_geometry_raises_geometry_error(field, value):
    kwargs = dict(L=1, a=1, B2=3, B3=2, H3=3) | {field: value}
    with pytest.raises(GeometryError, match=field):
        Geometry(**kwargs)


@pytest.mark.parametrize("call", [
    lambda g: Geometry(L=np.nan, a=1, B2=3, B3=2, H3=3),
    lambda g: prr3.inverse([0.0, np.inf, 0.0], g),
    lambda g: prr3.inverse([[0.0, 0.0, 0.0]], g),
    lambda g: prr3.direct([1.0, 2.0], g),
    lambda g: prr3.direct([1.0, np.nan, 0.0], g),
    lambda g: prr3.workspace([0.0, 1.0], [0.0, 1.0, 2.0], 0.0, g),
])
def test_bad_input_raises_value_error(call):
    with pytest.raises(ValueError):
        call(EXAMPLES["Tabla 6"][0])
