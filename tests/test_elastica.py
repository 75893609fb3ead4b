"""Tests of mechnum.mechanisms.elastica: the thesis's single-rod example (seed 001)."""

import numpy as np
import pytest

from mechnum import rods
from mechnum.errors import ConvergenceError
from mechnum.mechanisms import elastica as el


def test_study_data():
    assert np.isclose(el.EI, 210e9 * np.pi * 1e-12 / 4, rtol=1e-15)
    assert el.NODES == 61 and np.array_equal(el.TARGET, [0.8, 0.1])


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
    assert np.allclose(res.rod.force, closed.force[i], rtol=2e-6)
    assert np.isclose(res.rod.clamp_moment, closed.clamp_moment[i], rtol=2e-6)


def test_plain_newton_from_the_same_guess_goes_elsewhere():
    plain = rods.shoot_pinned(el.EI, el.LENGTH, el.TARGET, el.GUESS, nodes=el.NODES)
    mode = rods.elliptic_parameters(el.EI, el.LENGTH, plain.rod.clamp_moment, plain.rod.force)[2]
    assert mode > 2


def test_bad_guess_and_no_convergence():
    with pytest.raises(ValueError, match="guess must be 3 finite"):
        el.study_shooting([0.1, np.nan, 0.1])
    with pytest.raises(ConvergenceError, match="residual"):
        el.study_shooting(maxiter=1)


def test_reproduce_recovers_the_odd_q_of_each_mode():
    values = el.reproduce()
    assert set(values) == {"q of mode 1 (cantilever, P L^2/EI = 1)",
                           "q of mode 2 (the Annex II 1.1 example)",
                           "q of mode 3 (same pinned point)"}
    assert np.allclose(sorted(values.values()), [1, 3, 5], atol=1e-4)
