"""Tests of mechnum.mechanisms.elastica: the thesis's single-rod example (study 001)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum import rods
from mechnum.errors import ConvergenceError, MechnumError, SingularJacobianError
from mechnum.mechanisms import elastica as el


def test_bending_stiffness_is_that_of_a_solid_circular_section():
    # I = pi d**4 / 64, the textbook form of the module's pi r**4 / 4 with r = d / 2
    assert_allclose(el.EI, el.YOUNG * np.pi * el.DIAMETER ** 4 / 64, rtol=1e-15)
    assert np.hypot(*el.TARGET) < el.LENGTH      # the study's pinned point is within reach


def test_study_loop_reaches_the_mode_2_equilibrium_of_the_closed_form():
    res = el.study_shooting()
    assert res.max_residual <= el.TOL and np.array_equal(res.history[0], el.GUESS)
    psi, k_rel, mode, _ = rods.elliptic_parameters(el.EI, el.LENGTH, res.rod.clamp_moment,
                                                   res.rod.force)
    assert mode == 2
    exact = rods.pinned_equilibria(el.EI, el.LENGTH, el.TARGET, modes=(2,))
    closed = rods.clamped_pinned(el.EI, el.LENGTH, exact[:, 0], exact[:, 1], 2)
    i = np.argmin(np.abs(closed.clamp_moment - res.rod.clamp_moment))
    # 61 RK4 nodes: the discretisation error is about 1e-6 relative
    assert_allclose(res.rod.force, closed.force[i], rtol=2e-6)
    assert_allclose(res.rod.clamp_moment, closed.clamp_moment[i], rtol=2e-6)


def test_plain_newton_from_the_same_guess_goes_elsewhere():
    plain = rods.shoot_pinned(el.EI, el.LENGTH, el.TARGET, el.GUESS, nodes=el.NODES,
                              damping=False)
    mode = rods.elliptic_parameters(el.EI, el.LENGTH, plain.rod.clamp_moment, plain.rod.force)[2]
    assert mode > 2


def test_a_zero_guess_is_a_singular_jacobian_not_a_linalg_error():
    # the straight rod: no small change of m0 or n moves its tip sideways to first order
    with pytest.raises(SingularJacobianError, match="singular Jacobian at iteration 0") as error:
        el.study_shooting([0, 0, 0])
    assert error.value.result.iterations == 0


@pytest.mark.parametrize("kwargs, match", [
    (dict(guess=[0.1, np.nan, 0.1]), "guess must be finite"),
    (dict(guess=[0.1, 0.1]), "guess must have shape \\(3,\\)"),
    (dict(guess=[0.1, 0.1, 1j]), "guess must be real"),
    (dict(target=[0.8]), "target must have shape \\(2,\\)"),
    (dict(ei=0.0), "ei must be positive"),
    (dict(length=-1.0), "length must be positive"),
    (dict(nodes=1), "nodes must be an integer >= 2"),
    (dict(tol=-1e-7), "tol must be positive"),
    (dict(maxiter=np.inf), "maxiter must be an integer"),
])
def test_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        el.study_shooting(**kwargs)


def test_no_convergence_is_a_named_error_with_the_partial_result():
    with pytest.raises(ConvergenceError, match="residual") as error:
        el.study_shooting(maxiter=1)
    assert error.value.result.iterations == 1


@settings(max_examples=200, deadline=None)
@given(st.lists(st.one_of(st.floats(-1e6, 1e6), st.sampled_from([0.0, 1e-300, -1e-300])),
                min_size=3, max_size=3))
def test_study_loop_answers_or_names_its_failure(guess):
    try:
        res = el.study_shooting(guess, nodes=21, maxiter=30)
    except MechnumError as error:              # singular, or no convergence: named
        assert isinstance(error, (SingularJacobianError, ConvergenceError))
        return
    assert res.max_residual <= el.TOL
    assert_allclose(res.rod.tip, el.TARGET, rtol=0, atol=el.TOL)
    assert abs(res.rod.m[-1]) <= el.TOL


def test_budget_adds_its_rows_and_scales_with_the_hours(monkeypatch):
    costs = el.budget()
    rows = ("Matlab", "computers", "senior", "junior")
    assert costs["total"] == sum(costs[name] for name in rows)
    monkeypatch.setattr(el, "HOURS", {name: 2 * h for name, h in el.HOURS.items()})
    doubled = el.budget()
    for name in ("computers", "senior", "junior"):       # hour-proportional rows double
        assert_allclose(doubled[name], 2 * costs[name])
    assert doubled["licence rate"] == costs["licence rate"]


def test_reproduce_recovers_the_odd_q_of_each_mode_from_shooting():
    values = el.reproduce()
    q = [values[name] for name in values if name.startswith("q of mode")]
    assert_allclose(q, [1, 3, 5], atol=1e-4)      # q = 2 phi2 / pi, from 61-node RK4 rods
    assert all(isinstance(v, float) for v in values.values())
