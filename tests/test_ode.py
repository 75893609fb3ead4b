"""Tests of mechnum.ode: classical RK4."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum.ode import rk4


def harmonic(_, y):
    return np.stack((y[..., 1], -y[..., 0]), axis=-1)


def test_fourth_order_convergence():
    errors = []
    for n in (10, 20, 40, 80):
        y = rk4(harmonic, [1.0, 0.0], np.linspace(0.0, 2.0, n + 1))
        errors.append(abs(y[-1, 0] - np.cos(2.0)))
    slopes = -np.diff(np.log(errors)) / np.log(2.0)
    assert np.all(np.abs(slopes - 4.0) < 0.1), slopes


def test_exact_for_cubic_polynomials():
    # RK4 integrates y' = 3 s^2 (a quadrature, Simpson's rule) exactly
    y = rk4(lambda s, y: np.full_like(y, 3.0 * s ** 2), [0.0], np.array([0.0, 0.3, 1.0, 2.0]))
    assert np.allclose(y[:, 0], [0.0, 0.027, 1.0, 8.0], atol=1e-14)


def test_batch_equals_separate_runs_and_backward_grid():
    s = np.linspace(0.0, 1.5, 31)
    batch = rk4(harmonic, [[1.0, 0.0], [0.0, 2.0]], s)
    for i, y0 in enumerate(([1.0, 0.0], [0.0, 2.0])):
        assert np.array_equal(batch[:, i], rk4(harmonic, y0, s))
    back = rk4(harmonic, batch[-1, 0], s[::-1])
    assert np.allclose(back[-1], [1.0, 0.0], atol=1e-6)


@settings(max_examples=30, deadline=None)
@given(st.floats(-3, 3), st.floats(0.1, 2.0), st.integers(2, 50))
def test_linear_decay_matches_the_rk4_amplification_factor(a, length, steps):
    # for y' = a y, one RK4 step multiplies by 1 + z + z^2/2 + z^3/6 + z^4/24, z = a h
    z = a * length / steps
    y = rk4(lambda s, y: a * y, [1.0], np.linspace(0.0, length, steps + 1))
    growth = 1 + z + z ** 2 / 2 + z ** 3 / 6 + z ** 4 / 24
    assert np.isclose(y[-1, 0], growth ** steps, rtol=1e-12)


@pytest.mark.parametrize("y0, s, match", [
    ([np.nan], [0.0, 1.0], "y0 must be finite"),
    ([1.0], [0.0], "at least 2 nodes"),
    ([1.0], [0.0, 1.0, 0.5], "strictly"),
    ([1.0], [0.0, np.inf], "finite"),
])
def test_bad_input(y0, s, match):
    with pytest.raises(ValueError, match=match):
        rk4(lambda s, y: y, y0, s)


def test_wrong_shape_from_f():
    with pytest.raises(ValueError, match="shape"):
        rk4(lambda s, y: np.zeros(3), [1.0, 2.0], [0.0, 1.0])
