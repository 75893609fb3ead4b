"""Tests of :mod:`mechnum.mechanisms.actuator` (seed 004)."""

import dataclasses

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from mechnum.errors import (
    ConvergenceError,
    GeometryError,
    SingularJacobianError,
    UnreachablePoseError,
)
from mechnum.mechanisms.actuator import (
    ANNEX,
    Actuator,
    kinematics,
    lagrange_force,
    loop_jacobian,
    loop_residual,
    positions,
    solve_loop,
    virtual_power_force,
)
from mechnum.newton import fd_jacobian

GRID = np.linspace(0.0, 1.0, 101)  # the annex's t := 0, 0.01 .. 1


# --- the printed values -------------------------------------------------------------------

def test_printed_kinematics_at_rest_pose():
    kin = kinematics(0.0, model="annex")
    assert round(float(kin.theta2), 3) == 1.571
    assert round(float(kin.theta4), 3) == 0.0
    assert round(float(kin.omega2), 3) == 0.0
    assert round(float(kin.omega4), 3) == 0.503
    assert round(float(kin.a_dot), 3) == 0.126
    assert (round(ANNEX.d, 3), round(ANNEX.Io2, 3), round(ANNEX.Ig3, 3), round(ANNEX.Io4, 3)) \
        == (1.031, 0.6, 0.027, 0.96)


def test_printed_forces_with_the_annex_kinematics_and_slip():
    kin = kinematics([0.0, 0.01, 0.25, 0.75], model="annex")
    q_dd = lagrange_force(kin, annex_slip=True)
    q_di = virtual_power_force(kin)
    for computed, published, half_unit in zip(q_dd, [43.14926, 42.284, 29.371299, 56.648],
                                              [5e-6, 5e-4, 5e-7, 5e-4]):
        assert abs(computed - published) <= half_unit
    np.testing.assert_allclose(q_di[[0, 2]], [43.14926, 29.35809], atol=5e-6)


def test_printed_maximum_difference_comes_from_the_slip():
    kin = kinematics(GRID, model="annex")
    diff = lagrange_force(kin, annex_slip=True) - virtual_power_force(kin)
    assert abs(np.max(np.abs(diff)) - 0.0132088) <= 5e-8
    assert GRID[np.argmax(np.abs(diff))] == 0.25
    assert np.min(virtual_power_force(kin)) > 29


def test_gravity_9_81_does_not_reproduce_q0():
    kin = kinematics(0.0, model="annex")
    assert abs(float(virtual_power_force(kin, g=9.81)) - 43.14926) > 1e-2


# --- the two routes agree ----------------------------------------------------------------

@pytest.mark.parametrize("model", ["exact", "annex"])
def test_routes_agree_to_round_off(model):
    kin = kinematics(np.linspace(0, 1, 1001), model=model)
    q_vp, q_l = virtual_power_force(kin), lagrange_force(kin)
    assert np.max(np.abs(q_vp - q_l)) <= 1e-12 * np.max(np.abs(q_l))


def test_routes_agree_where_the_actuator_is_at_rest():
    kin = kinematics([0.25, 0.75])
    assert np.all(kin.a_dot < 1e-15)
    np.testing.assert_allclose(virtual_power_force(kin), lagrange_force(kin), rtol=1e-13)


def _energy(t, h=1e-4):
    """T + V of the exact mechanism at the instants t, from the positions alone: velocities by
    central differences of the centres of mass and of the angles."""
    m = ANNEX

    def centres(tt):
        th2, th4 = positions(m.stroke(tt)[0])
        a = m.stroke(tt)[0]
        return [(m.g2 * np.exp(1j * th2), th2), ((a + m.g3) * np.exp(1j * th2), th2),
                (complex(-m.o2, m.o4) + m.g4 * np.exp(1j * th4), th4)]

    total = 0.0
    for mass, inertia, (z, _), (z1, th1), (z0, th0) in zip(
            (m.m2, m.m3, m.m4), (m.Ig2, m.Ig3, m.Ig4), centres(t), centres(t + h),
            centres(t - h)):
        v, w = (z1 - z0) / (2 * h), (th1 - th0) / (2 * h)
        total = total + 0.5 * (mass * abs(v) ** 2 + inertia * w**2) + mass * 9.80665 * z.imag
    return total


def test_exact_force_balances_the_energy_rate():
    """Q a_dot = d(T + V)/dt, with T and V from the positions alone (no velocity coefficient)."""
    t, h = np.linspace(0.0, 1.0, 41), 1e-4
    rate = (_energy(t + h) - _energy(t - h)) / (2 * h)
    kin = kinematics(t)
    np.testing.assert_allclose(lagrange_force(kin) * kin.a_dot, rate, atol=1e-5)


# --- kinematics --------------------------------------------------------------------------

def test_exact_angular_rates_match_finite_differences_of_positions():
    t, h = np.linspace(0.0, 1.0, 21), 1e-4
    kin = kinematics(t)
    for j, (omega, eps) in enumerate(((kin.omega2, kin.eps2), (kin.omega4, kin.eps4))):
        th = [positions(ANNEX.stroke(t + s)[0])[j] for s in (-h, 0.0, h)]
        np.testing.assert_allclose(omega, (th[2] - th[0]) / (2 * h), atol=1e-8)
        np.testing.assert_allclose(eps, (th[2] - 2 * th[1] + th[0]) / h**2, atol=1e-5)


def test_annex_coefficients_are_exact_only_at_right_angle():
    exact, annex = kinematics(GRID), kinematics(GRID, model="annex")
    assert exact.k4[0] == pytest.approx(annex.k4[0], rel=1e-12)
    gap = np.abs(exact.k4 - annex.k4) / exact.k4
    assert np.max(gap) > 1e-3


def test_newton_solves_the_loop():
    for a in np.linspace(0.58, 0.62, 5):
        res = solve_loop(a, x0=(1.4, 0.2))
        assert res.converged
        np.testing.assert_allclose(res.x, positions(a), atol=1e-12)
        np.testing.assert_allclose(loop_residual(res.x, a), 0.0, atol=1e-14)


def test_loop_jacobian_matches_finite_differences():
    x, a = np.array([1.3, 0.2]), 0.61
    np.testing.assert_allclose(loop_jacobian(x, a), fd_jacobian(lambda z: loop_residual(z, a), x),
                               atol=1e-7)


# --- bad input ---------------------------------------------------------------------------

def test_bad_inputs_raise_named_errors():
    with pytest.raises(ValueError, match="t must be finite"):
        kinematics([0.0, np.nan])
    with pytest.raises(ValueError, match="model"):
        kinematics(0.0, model="approximate")
    with pytest.raises(ValueError, match="g must be finite"):
        lagrange_force(kinematics(0.0), g=np.inf)
    with pytest.raises(ValueError, match="b must be finite"):
        Actuator(b=np.nan)
    with pytest.raises(GeometryError, match="m3 must be positive"):
        Actuator(m3=-2.0)
    with pytest.raises(GeometryError, match="coincide"):
        Actuator(o2=0.0, o4=0.0)
    with pytest.raises(UnreachablePoseError, match="cannot close"):
        kinematics(0.0, Actuator(a0=1.5))


def test_dead_point_is_singular():
    dead = Actuator(o2=0.0, o4=1.0, b=0.25, l=0.25, a0=1.0, amplitude=0.0)  # a + l = d + b
    with pytest.raises(SingularJacobianError, match="dead point"):
        kinematics(0.0, dead)
    assert np.isfinite(virtual_power_force(kinematics(0.0, dead, model="annex")))
    with pytest.raises(SingularJacobianError):
        solve_loop(0.6, x0=(0.0, 0.0))


def test_newton_fails_out_of_reach():
    with pytest.raises((ConvergenceError, SingularJacobianError)):
        solve_loop(1.5)


# --- random geometry ---------------------------------------------------------------------

@st.composite
def mechanisms(draw):
    unit = st.floats(0.1, 2.0)
    o2, o4, b = draw(unit), draw(unit), draw(st.floats(0.05, 0.9))
    d = float(np.hypot(o2, o4))
    b = min(b, 0.9 * d)
    # a + l stays within the assembly range, away from the dead points
    L0 = d + b * draw(st.floats(-0.6, 0.6))
    l = L0 * draw(st.floats(0.2, 0.8))
    amplitude = 0.2 * b * draw(st.floats(0.0, 1.0))
    masses = [draw(st.floats(0.1, 10.0)) for _ in range(6)]
    return Actuator(o4=o4, o2=o2, b=b, l=l, g2=draw(unit), g3=draw(unit), g4=draw(unit),
                    m2=masses[0], m3=masses[1], m4=masses[2], Ig2=masses[3], Ig3=masses[4],
                    Ig4=masses[5], a0=L0 - l, amplitude=amplitude,
                    frequency=draw(st.floats(0.1, 5.0)))


@settings(max_examples=60, deadline=None)
@given(mechanisms(), st.floats(0.0, 20.0), st.sampled_from(["exact", "annex"]))
def test_virtual_power_equals_lagrange_on_random_geometry(mech, g, model):
    kin = kinematics(np.linspace(0, 1 / mech.frequency, 41), mech, model)
    q_vp, q_l = virtual_power_force(kin, g), lagrange_force(kin, g)
    scale = 1 + np.max(np.abs(q_l))
    assert np.max(np.abs(q_vp - q_l)) <= 1e-10 * scale


@settings(max_examples=40, deadline=None)
@given(mechanisms())
def test_annex_model_is_exact_where_cylinder_meets_crank_at_right_angle(mech):
    length = float(np.sqrt(mech.d**2 - mech.b**2))  # a + l with theta2 - theta4 = pi/2
    assume(length - mech.l > 1e-3)
    right = dataclasses.replace(mech, a0=length - mech.l, amplitude=0.0)
    exact, annex = kinematics(0.0, right), kinematics(0.0, right, model="annex")
    np.testing.assert_allclose([exact.k2, exact.k4], [annex.k2, annex.k4], atol=1e-9)
