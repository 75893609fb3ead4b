"""Tests of :mod:`mechnum.mechanisms.actuator` (the study's Annex 3.2).

Every public function has a test of its bad inputs and a hypothesis test (200 examples) of a
property that its result must satisfy: a loop that closes, a derivative that finite differences
confirm, three routes to the force that agree, a force that gives its motion back.
"""

import dataclasses
from pathlib import Path

import matplotlib
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from published import agrees, read_published

from mechnum.errors import (
    ConvergenceError,
    GeometryError,
    SingularJacobianError,
    UnreachablePoseError,
)
from mechnum.mechanisms.actuator import (
    Actuator,
    draw,
    energy,
    forward,
    forward_dynamics,
    inverse,
    kane_force,
    kinematics,
    lagrange_force,
    lagrange_terms,
    loop_jacobian,
    loop_residual,
    partial_velocities,
    singular_points,
    solve_loop,
    stroke_kinematics,
    virtual_power_force,
)
from mechnum.mechanisms.actuator._velocities import centres_of_mass
from mechnum.mechanisms.actuator.study import ANNEX
from mechnum.plotting import animate

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

REGISTRY = Path(__file__).resolve().parents[1] / "book" / "published_values.csv"
PUBLISHED = read_published(REGISTRY, "07_actuator_force")
GRID = np.linspace(0.0, 1.0, 101)  # the annex's t := 0, 0.01 .. 1
MANY = settings(max_examples=200, deadline=None)
ROUTES = (virtual_power_force, kane_force, lagrange_force)


# --- strategies ----------------------------------------------------------------------------

@st.composite
def mechanisms(draw_):
    """Valid mechanisms whose stroke stays within reach, at least 0.2 b from the dead points."""
    unit = st.floats(0.1, 2.0)
    o2, o4, b = draw_(unit), draw_(unit), draw_(st.floats(0.05, 0.9))
    d = float(np.hypot(o2, o4))
    b = min(b, 0.9 * d)
    L0 = d + b * draw_(st.floats(-0.6, 0.6))  # a0 + l
    l = L0 * draw_(st.floats(0.2, 0.8))
    inertia = st.one_of(st.none(), st.floats(0.0, 10.0))
    return Actuator(o4=o4, o2=o2, b=b, l=l, g2=draw_(unit), g3=draw_(st.floats(0.0, 2.0)),
                    g4=draw_(unit), m2=draw_(st.floats(0.1, 10.0)), m3=draw_(st.floats(0.1, 10.0)),
                    m4=draw_(st.floats(0.1, 10.0)), Ig2=draw_(inertia), Ig3=draw_(inertia),
                    Ig4=draw_(inertia), a0=L0 - l, amplitude=0.2 * b * draw_(st.floats(0.0, 1.0)),
                    frequency=draw_(st.floats(0.1, 5.0)))


def reach(mech):
    """The strokes at which the loop closes."""
    return abs(mech.d - mech.b) - mech.l, mech.d + mech.b - mech.l


def cycle(mech, n=21):
    return np.linspace(0.0, 1.0 / mech.frequency, n)


# --- the printed values (read from the registry, never copied) -----------------------------

def test_the_slip_reproduces_the_printed_forces():
    kin = kinematics(ANNEX, GRID, model="annex")
    q_slip, q_di = lagrange_force(kin, annex_slip=True), virtual_power_force(kin)
    for t in (0.0, 0.01, 0.25, 0.75):
        assert agrees(PUBLISHED[f"Q_dd({t:g})"], q_slip[round(100 * t)]), t
    assert agrees(PUBLISHED["max |Q_dd - Q_di| (annex formulas)"], np.max(np.abs(q_slip - q_di)))
    assert GRID[np.argmax(np.abs(q_slip - q_di))] == 0.25
    # corrected, the printed Q_dd(0.25) and Q_dd(0.75) no longer agree: they are the slip's
    q_dd = lagrange_force(kin)
    assert not agrees(PUBLISHED["Q_dd(0.25)"], q_dd[25])
    assert not agrees(PUBLISHED["Q_dd(0.75)"], q_dd[75])


def test_only_mathcads_gravity_reproduces_q0():
    kin = kinematics(ANNEX, 0.0, model="annex")
    assert agrees(PUBLISHED["Q_di(0)"], virtual_power_force(kin))
    assert not agrees(PUBLISHED["Q_di(0)"], virtual_power_force(kin, g=9.81))


# --- Actuator ------------------------------------------------------------------------------

def test_derived_inertias_follow_the_masses():
    assert_allclose(Actuator(m2=6.0).inertias[0], 6.0 * 0.6**2 / 12, rtol=1e-15)
    heavier = dataclasses.replace(ANNEX, m2=6.0, m3=3.0, l=0.5)
    assert_allclose(heavier.inertias, [6.0 * 0.6**2 / 12, 3.0 * 0.5**2 / 12, ANNEX.Ig4],
                    rtol=1e-15)  # I_G4 was given (the annex's, with m2 = 5), so it stays
    assert_allclose(ANNEX.inertias, [0.15, 0.4**2 * 2.0 / 12, 0.6], rtol=1e-15)
    assert_allclose([ANNEX.Io2, ANNEX.Io4], [0.6, 0.96], rtol=1e-15)
    assert Actuator(Ig2=0.0).inertias[0] == 0.0


@pytest.mark.parametrize("changes, error, message", [
    (dict(b=np.nan), ValueError, "b must be finite"),
    (dict(m2=1 + 1j), ValueError, "m2 must be real"),
    (dict(l="long"), ValueError, "l must be numeric"),
    (dict(o4=[1.0, 2.0]), ValueError, "o4 must have 0 dimension"),
    (dict(m3=-2.0), GeometryError, "m3 must be positive"),
    (dict(b=0.0), GeometryError, "b must be positive"),
    (dict(frequency=0.0), GeometryError, "frequency must be positive"),
    (dict(amplitude=-0.01), GeometryError, "amplitude must be non-negative"),
    (dict(Ig3=-1e-3), GeometryError, "Ig3 must be non-negative"),
    (dict(Ig4=np.inf), ValueError, "Ig4 must be finite"),
    (dict(o2=0.0, o4=0.0), GeometryError, "coincide"),
    (dict(ls=0.3), GeometryError, "upper end ls = 0.3 m must lie above its lower stop"),
    (dict(li=0.8), GeometryError, "must lie above its lower stop li = 0.8"),
])
def test_actuator_rejects_bad_parameters(changes, error, message):
    with pytest.raises(error, match=message):
        Actuator(**changes)


@MANY
@given(st.sampled_from(["b", "l", "g2", "m2", "m4", "g4", "o2", "g3", "amplitude", "Ig2", "a0"]),
       st.floats(-1.0, 3.0))
def test_actuator_accepts_exactly_its_domain(name, value):
    may_be_zero = name in ("o2", "g3", "amplitude", "Ig2")
    try:
        mech = Actuator(**{name: value})
    except GeometryError as error:
        assert name in str(error) and (value < 0 or (value == 0 and not may_be_zero))
        return
    assert name == "a0" or value > 0 or (may_be_zero and value >= 0)
    bars = [mech.m2 * (2 * mech.g2) ** 2 / 12, mech.m3 * mech.l**2 / 12,
            mech.m4 * (2 * mech.g4) ** 2 / 12]
    if name == "Ig2":
        bars[0] = value
    assert_allclose(mech.inertias, bars, rtol=1e-15)


# --- stroke --------------------------------------------------------------------------------

@pytest.mark.parametrize("t, message", [
    ([0.0, np.nan], "t must be finite"), (1j, "t must be real"), ("0", "t must be numeric")])
def test_stroke_rejects_bad_times(t, message):
    with pytest.raises(ValueError, match=message):
        ANNEX.stroke(t)


@MANY
@given(mechanisms(), st.lists(st.floats(-10.0, 10.0), max_size=5))
def test_stroke_is_a_harmonic_motion(mech, t):
    a, v, acc = mech.stroke(t)
    w = 2 * np.pi * mech.frequency
    assert a.shape == v.shape == acc.shape == (len(t),)
    assert_allclose((a - mech.a0) ** 2 + (v / w) ** 2, mech.amplitude**2, rtol=1e-9,
                    atol=1e-12)
    assert_allclose(acc, -w**2 * (a - mech.a0), rtol=0, atol=1e-12 * (1 + w**2))


# --- positions -----------------------------------------------------------------------------

def test_positions_reject_bad_input():
    with pytest.raises(ValueError, match="a must be finite"):
        forward(ANNEX, [0.6, np.inf])
    with pytest.raises(ValueError, match="a must be real"):
        forward(ANNEX, 0.6 + 0j)
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        forward(None, 0.6)
    with pytest.raises(UnreachablePoseError, match=r"a \+ l = 1.5 m is outside"):
        forward(ANNEX, [0.6, 1.1])
    assert forward(ANNEX, []).x.shape == (0, 2, 2)  # an empty batch is valid


@MANY
@given(mechanisms(), st.floats(-1.0, 1.0))
def test_positions_close_the_loop_or_refuse(mech, u):
    low, high = reach(mech)
    a = low + (high - low) * (0.5 + 0.7 * u)  # up to 20 % of the range beyond each end
    try:
        both = forward(mech, a).x
    except UnreachablePoseError:
        assert not low <= a <= high
        return
    assert low <= a <= high and both.shape == (2, 2)
    for x in both:  # each mode closes the loop
        assert_allclose(loop_residual(mech, x, a), 0.0, atol=1e-12)
    # the modes are mirror images across O2 O4: the same stroke, the other side of the line
    pins = (a + mech.l) * np.exp(1j * both[:, 0])
    line = complex(-mech.o2, mech.o4)
    sides = (pins * np.conj(line)).imag
    assert sides[0] * sides[1] <= 1e-12 * (a + mech.l) * mech.d


# --- loop equations ------------------------------------------------------------------------

@pytest.mark.parametrize("function", [loop_residual, loop_jacobian])
def test_loop_functions_reject_bad_input(function):
    with pytest.raises(ValueError, match=r"x must have shape \(\.\.\., 2\)"):
        function(ANNEX, [1.0, 0.0, 0.0], 0.6)
    with pytest.raises(ValueError, match="x must have"):
        function(ANNEX, 0.6, 0.6)
    with pytest.raises(ValueError, match="x must be finite"):
        function(ANNEX, [np.nan, 0.0], 0.6)
    with pytest.raises(ValueError, match="a must have 0 dimension"):
        function(ANNEX, [1.0, 0.0], [0.6, 0.6])
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        function(None, [1.0, 0.0], 0.6)


@MANY
@given(mechanisms(), st.floats(-4.0, 4.0), st.floats(-4.0, 4.0), st.floats(0.0, 1.0))
def test_residual_vanishes_at_the_pose_and_is_periodic(mech, th2, th4, u):
    low, high = reach(mech)
    a = low + (high - low) * (0.05 + 0.9 * u)
    assert_allclose(loop_residual(mech, forward(mech, a).x[..., 0, :], a), 0.0, atol=1e-12)
    x = np.array([th2, th4])
    assert_allclose(loop_residual(mech, x + 2 * np.pi, a), loop_residual(mech, x, a),
                    rtol=1e-12, atol=1e-12)


@MANY
@given(mechanisms(), st.floats(-4.0, 4.0), st.floats(-4.0, 4.0), st.floats(0.0, 1.0))
def test_jacobian_matches_central_differences_and_its_determinant(mech, th2, th4, a):
    x, h = np.array([th2, th4]), 1e-6
    fd = np.column_stack([(loop_residual(mech, x + h * e, a) - loop_residual(mech, x - h * e, a))
                          / (2 * h) for e in np.eye(2)])
    jac = loop_jacobian(mech, x, a)
    assert_allclose(jac, fd, rtol=0, atol=1e-8 * (1 + a + mech.l + mech.b))
    assert_allclose(np.linalg.det(jac), (a + mech.l) * mech.b * np.sin(th2 - th4), rtol=1e-10,
                    atol=1e-12)
    batch = np.array([x, x + 1.0])  # a batch of pairs gives the stack of their Jacobians
    assert_allclose(loop_jacobian(mech, batch, a)[1], loop_jacobian(mech, x + 1.0, a),
                    rtol=1e-15)


# --- Newton on the loop: two kinds of singularity ------------------------------------------

def test_solve_loop_rejects_bad_input():
    with pytest.raises(ValueError, match="a must be finite"):
        solve_loop(ANNEX, np.nan)
    with pytest.raises(ValueError, match=r"seed must have shape \(2,\)"):
        solve_loop(ANNEX, 0.6, seed=(1.0,))
    with pytest.raises(ValueError, match="maxiter"):
        solve_loop(ANNEX, 0.6, maxiter=0)
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        solve_loop(None, 0.6)
    with pytest.raises(ConvergenceError):
        solve_loop(ANNEX, 1.5)  # out of reach: no root to converge to


def test_singular_guess_on_a_regular_mechanism():
    """theta2 = theta4 makes the Jacobian singular wherever the mechanism is: an accident of
    the guess, not a property of the pose, which a nudged guess avoids."""
    with pytest.raises(SingularJacobianError) as caught:
        solve_loop(ANNEX, 0.6, seed=(1.5, 1.5))
    assert caught.value.result.iterations == 0
    for damping in (False, True):
        res = solve_loop(ANNEX, 0.6, seed=(1.5, 1.4), damping=damping)
        assert_allclose(res.x, forward(ANNEX, 0.6).x[0], rtol=1e-12, atol=1e-12)


def test_newton_slows_to_a_linear_rate_at_a_dead_point():
    """At a dead point (a property of the pose) the root is double: every Newton step halves
    the error instead of squaring it, and the error stalls near sqrt(eps)."""
    dead = Actuator(o2=0.0, o4=1.0, b=0.25, l=0.25, a0=1.0, amplitude=0.0)  # a + l = d + b
    res = solve_loop(dead, 1.0, seed=(1.5, 1.4), maxiter=100)
    assert_allclose(singular_points(dead)[1], 1.0, rtol=1e-15)  # this stroke is a dead point
    ratios = res.step_norms[3:15] / res.step_norms[2:14]
    assert_allclose(ratios, 0.5, rtol=0.02)
    assert 1e-10 < np.max(np.abs(res.x - np.pi / 2)) < 1e-6
    with pytest.raises(SingularJacobianError, match="dead point"):
        kinematics(dead, 0.0)
    assert np.isfinite(virtual_power_force(kinematics(dead, 0.0, model="annex")))


@MANY
@given(mechanisms(), st.floats(0.0, 1.0), st.floats(-0.2, 0.2), st.floats(-0.2, 0.2))
def test_newton_from_a_near_guess_closes_the_loop(mech, u, e2, e4):
    # From 0.2 rad off, Newton closes the loop, but on a slim triangle (a short crank b) the
    # start may lie in the basin of the other assembly mode: the defining property is the loop
    # closing; from a start close enough (1e-3 rad) it is the triangle's own pose.
    low, high = reach(mech)
    a = low + (high - low) * (0.1 + 0.8 * u)
    exact = forward(mech, a).x[0]
    res = solve_loop(mech, a, seed=exact + [e2, e4])
    assert res.converged
    assert_allclose(loop_residual(mech, res.x, a), 0.0, atol=1e-10 * (a + mech.l))
    near = solve_loop(mech, a, seed=exact + 1e-3 * np.sign([e2, e4]))
    assert_allclose(near.x, exact, rtol=1e-9, atol=1e-9)


# --- kinematics ----------------------------------------------------------------------------

def test_kinematics_reject_bad_input():
    with pytest.raises(ValueError, match="t must be finite"):
        kinematics(ANNEX, [0.0, np.nan])
    with pytest.raises(ValueError, match="model must be one of"):
        kinematics(ANNEX, 0.0, model="approximate")
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        kinematics(None, 0.0)
    with pytest.raises(ValueError, match="must broadcast together"):
        stroke_kinematics(ANNEX, [0.6, 0.61], [0.1, 0.1, 0.1])
    with pytest.raises(ValueError, match="a_dot must be real"):
        stroke_kinematics(ANNEX, 0.6, 1j)
    with pytest.raises(UnreachablePoseError, match="cannot close"):
        kinematics(Actuator(a0=1.5, ls=1.8), 0.0)
    empty = kinematics(ANNEX, [])
    assert empty.a.shape == empty.k4.shape == lagrange_force(empty).shape == (0,)


def test_rate_is_round_off_where_the_actuator_stops():
    """At t = 0.25 and 0.75 s the stroke rate is zero but for round-off, of either sign; the
    annex's division by it (0/0 in exact arithmetic) then gives the limit, and NaN at an
    exact zero."""
    kin = kinematics(ANNEX, [0.25, 0.75])
    assert_allclose(kin.a_dot, 0.0, atol=1e-15)
    assert np.all(kin.a_dot != 0)
    assert_allclose(virtual_power_force(kin, divide_by_rate=True), lagrange_force(kin),
                    rtol=1e-13)
    at_rest = stroke_kinematics(ANNEX, kin.a, 0.0, kin.a_ddot)
    assert np.all(np.isnan(virtual_power_force(at_rest, divide_by_rate=True)))
    assert_allclose(virtual_power_force(at_rest), lagrange_force(kin), rtol=1e-13)


def test_annex_coefficients_are_exact_only_at_right_angle():
    exact, annex = kinematics(ANNEX, GRID), kinematics(ANNEX, GRID, model="annex")
    assert_allclose([annex.k2[0], annex.k4[0]], [exact.k2[0], exact.k4[0]], rtol=1e-13,
                    atol=1e-13)
    delta = exact.theta2 - exact.theta4
    assert_allclose(annex.k4 / exact.k4, np.sin(delta) ** 2, rtol=1e-13)
    assert np.max(np.abs(annex.k4 / exact.k4 - 1)) > 1e-3


@MANY
@given(mechanisms(), st.floats(0.0, 1.0))
def test_exact_coefficients_are_derivatives_of_the_positions(mech, u):
    low, high = reach(mech)
    a, h = low + (high - low) * (0.2 + 0.6 * u), 1e-5
    kin = stroke_kinematics(mech, a)
    ahead, behind = stroke_kinematics(mech, a + h), stroke_kinematics(mech, a - h)
    for k, th in ((kin.k2, "theta2"), (kin.k4, "theta4")):
        k_fd = (getattr(ahead, th) - getattr(behind, th)) / (2 * h)
        assert_allclose(k, k_fd, rtol=1e-6, atol=1e-6)
    for k, dk in (("k2", "dk2"), ("k4", "dk4")):
        dk_fd = (getattr(ahead, k) - getattr(behind, k)) / (2 * h)
        assert_allclose(getattr(kin, dk), dk_fd, rtol=1e-5, atol=1e-5 * (1 + abs(dk_fd)))


# --- partial velocities --------------------------------------------------------------------

@pytest.mark.parametrize("function", [partial_velocities, centres_of_mass, kane_force,
                                      virtual_power_force, lagrange_force, lagrange_terms,
                                      energy])
def test_dynamics_reject_what_is_not_kinematics(function):
    with pytest.raises(ValueError, match="kin must be the Kinematics"):
        function(np.linspace(0.0, 1.0, 5))


@MANY
@given(mechanisms(), st.floats(0.0, 1.0))
def test_partial_velocities_are_derivatives_of_the_centres(mech, u):
    """(Of centres_of_mass and partial_velocities together.) With the exact coefficients,
    J = dG/da and dJ/da are derivatives of the positions. (The
    annex's coefficients are not: its model turns e2 at the rate k2 of its own.)"""
    low, high = reach(mech)
    a, h = low + (high - low) * (0.2 + 0.6 * u), 1e-5
    pv = partial_velocities(stroke_kinematics(mech, a))
    side = [stroke_kinematics(mech, a + s) for s in (h, -h)]
    centres = [centres_of_mass(kin) for kin in side]
    assert_allclose(pv.v, (centres[0] - centres[1]) / (2 * h), rtol=1e-5,
                    atol=1e-5 * (1 + np.abs(pv.v).max()))
    v = [partial_velocities(kin).v for kin in side]
    assert_allclose(pv.dv, (v[0] - v[1]) / (2 * h), rtol=1e-5,
                    atol=1e-5 * (1 + np.abs(pv.dv).max()))
    assert_allclose(pv.omega, [pv.omega[0], pv.omega[0], (side[0].theta4 - side[1].theta4)
                               / (2 * h)], rtol=1e-6)


# --- the three routes to the force ---------------------------------------------------------

@pytest.mark.parametrize("route", ROUTES + (lagrange_terms, energy))
def test_routes_reject_bad_options(route):
    kin = kinematics(ANNEX, 0.0)
    with pytest.raises(ValueError, match="g must be finite"):
        route(kin, g=np.inf)
    with pytest.raises(ValueError, match="g must be real"):
        route(kin, g=9.8j)
    with pytest.raises(ValueError, match="g must have 0 dimension"):
        route(kin, g=[9.8, 9.8])


def test_flags_must_be_booleans():
    kin = kinematics(ANNEX, 0.0)
    for flag in ("yes", 1, 0.0, None):  # truthy or falsy is not a bool
        with pytest.raises(ValueError, match="annex_slip must be True or False"):
            lagrange_force(kin, annex_slip=flag)
        with pytest.raises(ValueError, match="divide_by_rate must be True or False"):
            virtual_power_force(kin, divide_by_rate=flag)
    assert lagrange_force(kin, annex_slip=np.True_) == lagrange_force(kin, annex_slip=True)


@pytest.mark.parametrize("model", ["exact", "annex"])
def test_three_routes_agree_on_the_annex(model):
    kin = kinematics(ANNEX, np.linspace(0.0, 1.0, 1001), model=model)
    q = lagrange_force(kin)
    for route in (virtual_power_force, kane_force):
        assert_allclose(route(kin), q, rtol=0, atol=1e-12)


@MANY
@given(mechanisms(), st.floats(-20.0, 20.0), st.sampled_from(["exact", "annex"]))
def test_three_routes_agree_on_random_mechanisms(mech, g, model):
    kin = kinematics(mech, cycle(mech), model)
    q = lagrange_force(kin, g)
    atol = 1e-10 * (1 + np.max(np.abs(q)))
    assert_allclose(virtual_power_force(kin, g), q, rtol=0, atol=atol)
    assert_allclose(kane_force(kin, g), q, rtol=0, atol=atol)


@MANY
@given(mechanisms(), st.floats(0.0, 1.0), st.sampled_from(["exact", "annex"]))
def test_lagrange_terms_are_the_mass_and_the_slopes(mech, u, model):
    low, high = reach(mech)
    a, h = low + (high - low) * (0.2 + 0.6 * u), 1e-5
    terms = lagrange_terms(stroke_kinematics(mech, a, model=model))
    pv = partial_velocities(stroke_kinematics(mech, a, model=model))
    masses, inertias = np.array([mech.m2, mech.m3, mech.m4]), np.array(mech.inertias)
    assert_allclose(terms.mass, np.sum(masses * np.abs(pv.v) ** 2 + inertias * pv.omega**2),
                    rtol=1e-12)
    if model == "exact":  # M' and V' are slopes along the positions (the annex's M' is not)
        side = [lagrange_terms(stroke_kinematics(mech, a + s)) for s in (h, -h)]
        assert_allclose(terms.mass_slope, (side[0].mass - side[1].mass) / (2 * h),
                        rtol=1e-5, atol=1e-5 * (1 + terms.mass))
        v = [energy(stroke_kinematics(mech, a + s)).potential for s in (h, -h)]
        assert_allclose(terms.potential_slope, (v[0] - v[1]) / (2 * h),
                        rtol=1e-6, atol=1e-6 * (1 + abs(v[0])))


# --- energy --------------------------------------------------------------------------------

def test_energy_rejects_bad_gravity():
    with pytest.raises(ValueError, match="g must be finite"):
        energy(kinematics(ANNEX, 0.0), g=np.nan)


def test_work_equals_the_change_of_energy_only_with_exact_kinematics():
    t, h = np.linspace(0.0, 1.0, 41), 1e-4
    for model, balanced in (("exact", True), ("annex", False)):
        kin = kinematics(ANNEX, t, model=model)
        rate = (energy(kinematics(ANNEX, t + h)).total
                - energy(kinematics(ANNEX, t - h)).total) / (2 * h)
        gap = np.max(np.abs(lagrange_force(kin) * kin.a_dot - rate))
        assert (gap < 1e-6) == balanced, (model, gap)


@MANY
@given(mechanisms(), st.floats(-20.0, 20.0))
def test_force_power_is_the_rate_of_energy(mech, g):
    t, h = cycle(mech, 9), 1e-5 / mech.frequency
    kin = kinematics(mech, t)
    rate = (energy(kinematics(mech, t + h), g).total
            - energy(kinematics(mech, t - h), g).total) / (2 * h)
    power = lagrange_force(kin, g) * kin.a_dot
    assert_allclose(energy(kin).kinetic, 0.5 * lagrange_terms(kin).mass * kin.a_dot**2,
                    rtol=1e-12)
    assert_allclose(power, rate, rtol=0, atol=1e-5 * (1 + np.max(np.abs(power))))


# --- forward dynamics ----------------------------------------------------------------------

def _prescribed(mech):
    return lambda s: float(lagrange_force(kinematics(mech, s)))


def test_forward_dynamics_rejects_bad_input():
    t, q = np.linspace(0.0, 0.1, 3), _prescribed(ANNEX)
    with pytest.raises(ValueError, match="force must be a callable"):
        forward_dynamics(ANNEX, 43.0, t, 0.6, 0.1)
    with pytest.raises(ValueError, match=r"force\(t\) must be finite"):
        forward_dynamics(ANNEX, lambda s: np.nan, t, 0.6, 0.1)
    with pytest.raises(ValueError, match=r"force\(t\) must have 0 dimension"):
        forward_dynamics(ANNEX, lambda s: [1.0, 2.0], t, 0.6, 0.1)
    with pytest.raises(ValueError, match="at least 2 nodes"):
        forward_dynamics(ANNEX, q, [0.0], 0.6, 0.1)
    with pytest.raises(ValueError, match="a0 must be finite"):
        forward_dynamics(ANNEX, q, t, np.nan, 0.1)
    with pytest.raises(ValueError, match="model must be one of"):
        forward_dynamics(ANNEX, q, t, 0.6, 0.1, model="rigid")
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        forward_dynamics(None, q, t, 0.6, 0.1)
    with pytest.raises(UnreachablePoseError):  # pushed beyond the reach of the loop
        forward_dynamics(ANNEX, lambda s: 1e4, np.linspace(0.0, 1.0, 11), 0.6, 0.0)


def test_forward_dynamics_is_fourth_order():
    a0, v0, _ = ANNEX.stroke(0.0)
    errors = []
    for n in (25, 50, 100):
        t = np.linspace(0.0, 1.0, n + 1)
        motion = forward_dynamics(ANNEX, _prescribed(ANNEX), t, a0, v0)
        errors.append(np.max(np.abs(motion.a - ANNEX.stroke(t)[0])))
    orders = np.log2(np.array(errors[:-1]) / errors[1:])
    assert_allclose(orders, 4.0, rtol=0.025)


def _natural_rate(mech):
    """sqrt(max |V''| / M) over the stroke (1/s): how fast the mechanism topples, or swings."""
    a, h = mech.a0 + mech.amplitude * np.linspace(-1.0, 1.0, 9), 1e-6
    up, down = (lagrange_terms(stroke_kinematics(mech, a + s)) for s in (h, -h))
    stiffness = np.abs(up.potential_slope - down.potential_slope) / (2 * h)
    return float(np.sqrt(np.max(stiffness / up.mass)))


@MANY
@given(mechanisms())
def test_forward_dynamics_gives_the_prescribed_stroke_back(mech):
    """RK4 converges to the prescribed stroke at fourth order: doubling the steps divides the
    error by about 16 (a wrong term of Lagrange's equation makes it converge to another motion,
    and the error stays). The horizon is a quarter cycle, or three e-folding times of the
    mechanism's own instability if shorter (beyond, any error grows faster than RK4 shrinks
    it); the steps resolve both."""
    rate = _natural_rate(mech)
    horizon = min(0.25 / mech.frequency, 3.0 / max(rate, 1e-12))
    steps = 8 + int(4 * (rate + mech.frequency) * horizon)
    a0, v0, _ = mech.stroke(0.0)
    errors = []
    for n in (steps, 2 * steps):
        t = np.linspace(0.0, horizon, n + 1)
        motion = forward_dynamics(mech, _prescribed(mech), t, a0, v0)
        assert motion.a.shape == motion.a_dot.shape == t.shape
        a, v, _ = mech.stroke(t)
        errors.append(np.max(np.abs(motion.a - a)) + np.max(np.abs(motion.a_dot - v)) * horizon)
    assert errors[1] <= errors[0] / 8 + 1e-12
    assert errors[1] <= 1e-3 * mech.amplitude + 1e-12


# --- drawing -------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def axes():
    """One figure for the module's drawings, closed after them."""
    fig, ax = plt.subplots()
    yield ax
    plt.close(fig)


def test_draw_rejects_bad_input(axes):
    state = (0.6, forward(ANNEX, 0.6).x[0])
    with pytest.raises(ValueError, match="a must be finite"):
        draw(axes, ANNEX, (np.nan, state[1]))
    with pytest.raises(ValueError, match="state must close the loop"):
        draw(axes, ANNEX, (0.62, state[1]))
    with pytest.raises(ValueError, match=r"state must be \(a, \(theta2, theta4\)\)"):
        draw(axes, ANNEX, 0.6)
    with pytest.raises(ValueError, match="ax must be a matplotlib Axes"):
        draw(None, ANNEX, state)
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        draw(axes, None, state)
    with pytest.raises(ValueError, match="artists must be the dict that an earlier draw"):
        draw(axes, ANNEX, state, artists={"rod": None})


@MANY
@given(mech=mechanisms(), u=st.floats(0.0, 1.0), mode=st.sampled_from([0, 1]))
def test_drawing_closes_the_loop_and_moves(axes, mech, u, mode):
    low, high = reach(mech)
    for line in axes.lines[:]:
        line.remove()
    start = low + (high - low) * (0.1 + 0.8 * u)
    parts = draw(axes, mech, (start, forward(mech, start).x[mode]))
    a = low + (high - low) * (0.9 - 0.8 * u)
    assert draw(axes, mech, (a, forward(mech, a).x[mode]), artists=parts) is parts
    assert len(axes.lines) == 5  # moved, not drawn again
    pin = complex(*parts["rod"].get_xydata()[1])  # the rod's end A
    o4, end = (complex(*p) for p in parts["rocker"].get_xydata())
    assert_allclose(abs(pin), a + mech.l, rtol=1e-12)
    assert_allclose(abs(pin - o4), mech.b, rtol=1e-9)  # A is on the rocker, b from O4,
    assert_allclose(((pin - o4) / (end - o4)).imag, 0.0, atol=1e-9)  # on its line


def test_animate_moves_the_mechanism():
    strokes = ANNEX.stroke(np.linspace(0.0, 1.0, 5, endpoint=False))[0]
    html = animate(draw, ANNEX, list(zip(strokes, forward(ANNEX, strokes).x[:, 0])))
    assert html.count("data:image/png;base64") == 5


# --- inverse, singular points ------------------------------------------------------------

@MANY
@given(mechanisms(), st.floats(0.0, 1.0), st.sampled_from([0, 1]))
def test_inverse_gives_the_stroke_of_the_rocker_angle_in_either_mode(mech, u, mode):
    low, high = reach(mech)
    a = low + (high - low) * (0.05 + 0.9 * u)
    theta4 = forward(mech, a).x[mode, 1]
    assert_allclose(inverse(mech, theta4), a, rtol=1e-10, atol=1e-12 * (a + mech.l))


def test_inverse_rejects_bad_input():
    with pytest.raises(ValueError, match="theta4 must be finite"):
        inverse(ANNEX, np.nan)
    with pytest.raises(ValueError, match="mech must be an Actuator"):
        inverse(object(), 0.0)
    with pytest.raises(UnreachablePoseError, match="no direction"):  # b = d: A can reach O2
        inverse(Actuator(o2=0.0, o4=0.5, b=0.5), -np.pi / 2)


@MANY
@given(mechanisms())
def test_singular_points_are_where_the_jacobian_vanishes_and_the_modes_meet(mech):
    for a in singular_points(mech):
        if a + mech.l <= 0:
            continue  # no stroke can reach a negative length
        both = forward(mech, a).x
        gap = np.angle(np.exp(1j * (both[0] - both[1])))  # modulo 2 pi
        assert_allclose(gap, 0.0, rtol=0, atol=1e-6)  # a double root: about sqrt(eps)
        assert abs(np.linalg.det(loop_jacobian(mech, both[0], a))) < 1e-6 * (a + mech.l)
        with pytest.raises(SingularJacobianError, match="dead point"):
            stroke_kinematics(mech, a)


