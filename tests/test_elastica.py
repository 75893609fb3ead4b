"""Tests of mechnum.mechanisms.elastica: the thesis's single-rod example (study 001)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import quad

from mechnum import rods
from mechnum.errors import ConvergenceError, MechnumError, SingularJacobianError
from mechnum.mechanisms import elastica
from mechnum.mechanisms.elastica import study as el
from mechnum.mechanisms.elastica._model import ARROW


def test_bending_stiffness_is_that_of_a_solid_circular_section():
    # I is the second moment of area of the disc about a diameter, int y**2 dA, by quadrature
    r = el.DIAMETER / 2
    second_moment = quad(lambda y: y ** 2 * 2 * np.sqrt(r * r - y * y), -r, r,
                         epsabs=0, epsrel=1e-13)[0]
    # quad's epsrel 1e-13 on a smooth integrand: the product agrees to about that, 1e-10 a wide
    # margin
    assert_allclose(el.EI, el.YOUNG * second_moment, rtol=1e-10)


def test_study_loop_reaches_the_mode_2_equilibrium_of_the_closed_form():
    res = el.study_shooting()
    assert res.max_residual <= el.TOL and np.array_equal(res.history[0], el.GUESS)
    _psi, _k_rel, mode, _ = rods.elliptic_parameters(el.EI, el.LENGTH, res.rod.clamp_moment,
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
    ({"seed": [0.1, np.nan, 0.1]}, "seed must be finite"),
    ({"seed": [0.1, 0.1]}, "seed must have shape \\(3,\\)"),
    ({"seed": [0.1, 0.1, 1j]}, "seed must be real"),
    ({"target": [0.8]}, "target must have shape \\(2,\\)"),
    ({"EI": 0.0}, "EI must be positive"),
    ({"L": -1.0}, "L must be positive"),
    ({"nodes": 1}, "nodes must be an integer >= 2"),
    ({"nodes": 1e6}, "nodes must be an integer <= 10000"),
    ({"maxiter": 10 ** 9}, "maxiter must be an integer <= 1000"),
    ({"tol": -1e-7}, "tol must be positive"),
    ({"maxiter": np.inf}, "maxiter must be an integer"),
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
    costs = el._budget()
    rows = ("Matlab", "computers", "senior", "junior")
    assert costs["total"] == sum(costs[name] for name in rows)
    monkeypatch.setattr(el, "HOURS", {name: 2 * h for name, h in el.HOURS.items()})
    doubled = el._budget()
    for name in ("computers", "senior", "junior"):       # hour-proportional rows double
        assert_allclose(doubled[name], 2 * costs[name], rtol=1e-15)
    assert doubled["licence rate"] == costs["licence rate"]


def test_reproduce_recovers_the_odd_q_of_each_mode_from_shooting():
    # q = 2 phi2 / pi of rods shot on 61 RK4 nodes deviates from 1, 3, 5 by RK4's error, which
    # falls like h**4: doubling the resolution divides each deviation by 16 (any bias of q,
    # even far below the deviations' own size at 61 nodes, breaks that ratio)
    values, finer = el.reproduce(), el.reproduce(nodes=121)
    q, q_fine = ([v[name] for name in v if name.startswith("q of mode")] for v in (values, finer))
    deviation, fine = np.subtract(q, [1, 3, 5]), np.subtract(q_fine, [1, 3, 5])
    # RK4's error at 61 nodes is of order h^4 = 7e-8 times the derivatives: the deviations are below
    # 1e-4; 14 to 18 brackets the ratio 16 of h^4
    assert np.all(np.abs(deviation) < 1e-4)
    assert np.all((deviation / fine > 14) & (deviation / fine < 18)), deviation / fine
    assert all(isinstance(v, float) for v in values.values())


def test_draw_shows_the_equilibrium_and_moves_without_adding():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    push = rods.DeadLoad(el.EI, el.LENGTH, np.pi - 0.1, segments=20)
    mech = elastica.Mechanism()
    fig, ax = plt.subplots()
    first = elastica.draw(ax, mech, _state(push, push.start(0.3)))
    lines = len(ax.lines)
    u = push.start(-0.5)
    moved = elastica.draw(ax, mech, _state(push, u), artists=first)
    assert moved is first and len(ax.lines) == lines
    rod = push.rod(u)
    drawn = moved["rod"].get_xydata()
    assert_allclose(drawn[[0, -1]], [[0.0, 0.0], rod.tip], rtol=0, atol=1e-5)   # RK4, 41 nodes
    head = moved["force"].get_xydata()
    assert_allclose(head[1], drawn[-1], rtol=1e-15)                   # the head at the tip
    assert_allclose(head[1] - head[0], ARROW * el.LENGTH * push.direction, rtol=1e-12)
    with pytest.raises(ValueError, match="mech must be"):
        elastica.draw(ax, "column", _state(push, u))
    with pytest.raises(ValueError, match="state"):
        elastica.draw(ax, mech, [0.0, 1.0, 2.0])
    with pytest.raises(ValueError, match="ax must be"):
        elastica.draw(None, mech, _state(push, u))
    plt.close(fig)


def _state(push, u):
    """The state ``(tip, (m0, force))`` of a cantilever under a dead load at ``u``."""
    rod = push.rod(u)
    return rod.tip, (rod.m[0], rod.force)


def test_forward_finds_every_pinned_equilibrium_and_draws_each():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    found = elastica.forward(elastica.Mechanism(1.0, 1.0), el.TARGET, modes=(1, 2, 3))
    assert found.modes.tolist() == [1, 2, 2, 2, 2, 3, 3, 3, 3] and found.converged.all()
    fig, ax = plt.subplots()
    artists = elastica.draw(ax, elastica.Mechanism(1.0, 1.0), found.state(0))
    # the chart recovered from the clamp state of a rod in strong tension (1 - |k_rel| ~ 1e-9)
    assert_allclose(artists["rod"].get_xydata()[-1], el.TARGET, rtol=0, atol=1e-6)
    plt.close(fig)
