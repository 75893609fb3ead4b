"""Tests of mechnum.mechanisms.hacksaw: motor profile, equations, Jacobians, closed form, sweeps."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum.errors import GeometryError, UnreachablePoseError
from mechnum.mechanisms import hacksaw as hs
from mechnum.newton import fd_jacobian

T = hs.first_revolution_time()
motor_states = st.tuples(st.floats(-2 * np.pi, 2 * np.pi), st.floats(-10, 10), st.floats(-10, 10))


def test_first_revolution_time_completes_a_revolution():
    for alpha_max in (1.0, 5.0, 20.0):
        T_ = hs.first_revolution_time(alpha_max)
        assert hs.motor(T_, alpha_max)[0] == pytest.approx(2 * np.pi, rel=1e-14)
    with pytest.raises(ValueError, match="alpha_max"):
        hs.first_revolution_time(0.0)


def test_motor_profile_is_continuous_and_integrates():
    t = np.linspace(0, 2 * T, 200001)
    theta, omega, alpha = hs.motor(t)
    dt = t[1] - t[0]
    assert np.abs(np.diff(omega)).max() < 10 * dt  # |alpha| <= 5: no jump in speed
    assert np.abs(np.diff(theta)).max() < 10 * dt
    np.testing.assert_allclose(np.gradient(theta, dt)[1:-1], omega[1:-1], atol=1e-6)
    np.testing.assert_allclose(np.gradient(omega, dt)[1:-1], alpha[1:-1], atol=1e-3)
    assert alpha.max() == pytest.approx(5.0) and alpha.min() == 0.0
    assert omega[-1] == pytest.approx(10 * T / 3)


@pytest.mark.parametrize("t", [-1.0, np.nan, [0.0, np.inf]])
def test_motor_rejects_bad_times(t):
    with pytest.raises(ValueError, match="t must"):
        hs.motor(t)


@settings(max_examples=100, deadline=None)
@given(state=motor_states)
def test_closed_form_satisfies_all_nine_equations(state):
    x = hs.closed_form(motor_state=state)
    scale = 1 + abs(state[1]) ** 2 + abs(state[2])
    assert np.abs(hs.residual(x, *state)).max() <= 1e-13 * scale
    assert np.cos(x[2]) < 0 and x[0] < 0  # the study's branch and sign convention


@settings(max_examples=40, deadline=None)
@given(state=motor_states, seed=st.integers(0, 2**32 - 1))
def test_newton_from_a_perturbed_state_converges_back(state, seed):
    exact = hs.closed_form(motor_state=state)
    perturbation = np.random.default_rng(seed).normal(scale=[0.01, 0.05, 0.05, 0.1, 0.5, 0.5,
                                                             1, 5, 5])
    x0 = exact + perturbation
    simultaneous = hs.solve_simultaneous(state, x0, tol=1e-12).x
    consecutive = np.concatenate([r.x for r in hs.solve_consecutive(state, x0, tol=1e-12)])
    scale = np.maximum(1.0, np.abs(exact))
    assert np.all(np.abs(simultaneous - exact) <= 1e-9 * scale)
    assert np.all(np.abs(consecutive - exact) <= 1e-9 * scale)


def test_jacobians_match_finite_differences():
    rng = np.random.default_rng(7)
    for _ in range(20):
        x, state = rng.uniform(-2, 2, 9), rng.uniform(-3, 3, 3)
        J = hs.jacobian(x)
        np.testing.assert_allclose(J, fd_jacobian(lambda z: hs.residual(z, *state), x),
                                   atol=2e-6 * np.abs(J).max())
        for form in ("loop", "eliminated"):
            q = x[:3]
            np.testing.assert_allclose(
                hs.position_jacobian(q, form=form),
                fd_jacobian(lambda z: hs.position_residual(z, state[0], form=form), q),
                atol=1e-5 * np.abs(hs.position_jacobian(q, form=form)).max())


def test_jacobian_is_vectorised_and_block_triangular():
    x = hs.closed_form(np.linspace(0, 2 * T, 7))
    J = hs.jacobian(x)
    assert J.shape == (7, 9, 9)
    # a batch and a single state may take different SIMD paths of sin/cos: equal to round-off
    np.testing.assert_allclose(J[3], hs.jacobian(x[3]), rtol=1e-14, atol=1e-15)
    assert not J[:, 0:3, 3:].any() and not J[:, 3:6, 6:].any()
    np.testing.assert_allclose(np.linalg.det(hs.position_jacobian(x[:, :3])),
                               -x[:, 0] * hs.STUDY.r3 * np.cos(x[:, 2]), rtol=1e-12)


def test_rate_equations_are_linear_in_the_rates():
    x = hs.closed_form(0.8)
    state = hs.motor(0.8)
    q, v = x[:3], x[3:6]
    v0 = np.array([0.3, -1.0, 2.0])
    linear = hs.rate_jacobian(q) @ (v0 - v)
    np.testing.assert_allclose(hs.velocity_residual(v0, q, state[0], state[1]), linear,
                               atol=1e-14)


def test_form_must_be_known():
    with pytest.raises(ValueError, match="form"):
        hs.position_residual(np.ones(3), 0.0, form="reduced")
    with pytest.raises(ValueError, match="form"):
        hs.position_jacobian(np.ones(3), form="reduced")


def test_unreachable_pose_is_named():
    with pytest.raises(UnreachablePoseError, match=r"r3 = 1.09091 > 1 at theta2 = -1.5708"):
        hs.closed_form(motor_state=(-np.pi / 2, 0.0, 0.0), geometry=hs.Geometry(r3=0.110))


@pytest.mark.parametrize("method", hs.METHODS)
def test_sweeps_agree_with_the_closed_form(method):
    t = np.linspace(0, 2 * T, 60)
    x = hs.sweep(t, method, tol=1e-10)
    assert x.shape == (60, 9)
    np.testing.assert_allclose(x, hs.closed_form(t), atol=1e-9)


def test_sweep_rejects_bad_input():
    with pytest.raises(ValueError, match="method"):
        hs.sweep(np.linspace(0, 1, 5), "parallel")
    with pytest.raises(ValueError, match="1-D"):
        hs.sweep(np.zeros((2, 2)), "batched")
    with pytest.raises(ValueError, match="seed"):
        hs.solve_consecutive((0.0, 0.0, 0.0), np.zeros(8))


def test_reproduce_covers_the_study():
    values = hs.reproduce()
    assert values["r1 at rest (consecutive)"] == pytest.approx(hs.closed_form(0.0)[0], abs=1e-9)
    assert all(np.isfinite(v) for v in values.values())


@pytest.mark.parametrize("kwargs", [{"r1y": 0.0}, {"r2": -0.075}, {"r3": np.nan}, {"r3": np.inf}])
def test_degenerate_geometry_is_named(kwargs):
    with pytest.raises(GeometryError, match=f"{next(iter(kwargs))} must be a finite positive"):
        hs.Geometry(**kwargs)


@pytest.mark.parametrize("kwargs, match", [({}, "either t or motor_state"),
                                           ({"t": 1.0, "motor_state": (0, 0, 0)}, "either"),
                                           ({"motor_state": (np.nan, 0.0, 0.0)}, "finite"),
                                           ({"t": [0.0, np.nan]}, "t must")])
def test_closed_form_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        hs.closed_form(**kwargs)


def test_non_finite_seed_is_a_value_error():
    with pytest.raises(ValueError, match="x0 must be finite"):
        hs.solve_simultaneous((0.0, 0.0, 0.0), np.full(9, np.nan))
