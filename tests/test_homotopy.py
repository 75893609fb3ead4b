"""Tests of mechnum.homotopy: the path tracker and the total-degree homotopy on known roots."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from mechnum import homotopy
from mechnum.polynomials import PolynomialSystem, bezout_bound
from strategies import separated


def test_track_follows_a_path_to_its_end():
    # x^2 = 1 + 3 s: the root starting at -1 ends at -2
    H = lambda x, s: (x ** 2 - (1 + 3 * s), np.diag(2 * x), np.array([-3.0 + 0j]))
    end = homotopy.track(H, [-1.0 + 0j])
    assert end.s == 1.0 and end.steps >= 1
    assert_allclose(end.x, [-2.0], atol=1e-9)


def test_track_reports_a_lost_path():
    # x^2 = (1 - 2 s): two roots meet at s = 1/2 (a singular point): the path cannot pass it
    H = lambda x, s: (x ** 2 - (1 - 2 * s), np.diag(2 * x), np.array([2.0 + 0j]))
    end = homotopy.track(H, [1.0 + 0j], max_steps=500)
    assert end.s < 1.0


def _triangular(a, b):
    """x^3 ... with known roots: (x - a0)(x - a1)(x - a2) = 0, y^2 = x + b."""
    cubic = np.polynomial.polynomial.polyfromroots(a)
    first = {(k, 0): c for k, c in enumerate(cubic) if c != 0}
    second = {(0, 2): 1.0, (1, 0): -1.0, (0, 0): -b}
    roots = [(x, s * np.sqrt(complex(x + b))) for x in a for s in (1, -1)]
    return PolynomialSystem.from_dicts([first, second]), np.array(roots)


@settings(max_examples=50, deadline=None)  # 50 random systems: 300 paths tracked
@given(a=separated(3, -2, 2, gap=0.3), b=st.floats(-2, 2), seed=st.integers(0, 2 ** 32 - 1))
def test_total_degree_homotopy_finds_every_known_root(a, b, seed):
    assume(np.abs(a + b).min() > 0.1)  # six distinct roots (y = 0 would double two)
    system, known = _triangular(a, b)
    result = homotopy.solve(system, rng=seed)
    assert len(result.status) == bezout_bound(system) == 6
    assert np.all(result.status == "finite")
    assert len(result.solutions) == 6
    for root in known:
        assert np.abs(result.solutions - root).max(axis=1).min() < 1e-8
    real = result.real(1e-8)
    assert len(real) == 2 * np.sum(a + b > 0)


def test_paths_to_infinity_are_classified():
    # x y = 1, x^2 = 4: Bezout 4, two finite roots, two at infinity
    system = PolynomialSystem.from_dicts([{(1, 1): 1, (0, 0): -1}, {(2, 0): 1, (0, 0): -4}])
    result = homotopy.solve(system, rng=3)
    assert sorted(result.status.tolist()) == ["at-infinity", "at-infinity", "finite", "finite"]
    assert_allclose(result.real(), [[-2.0, -0.5], [2.0, 0.5]], atol=1e-10)
    at_infinity = result.endpoints[result.status == "at-infinity"]
    assert np.all(np.abs(at_infinity[:, 0]) < 1e-6 * np.linalg.norm(at_infinity, axis=1))


@pytest.mark.parametrize("call, message", [
    (lambda: homotopy.solve("x^2"), "PolynomialSystem"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1, 1): 1}])), "square"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1,): 1, (0,): -1}]), tol=-1), "tol"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1,): 1, (0,): -1}]), same=0), "same"),
    (lambda: homotopy.track(lambda x, s: None, [1.0], h0=-1), "h0"),
    (lambda: homotopy.track(lambda x, s: None, [1.0], max_steps=0), "max_steps"),
])
def test_bad_input_raises_a_value_error_that_names_it(call, message):
    with pytest.raises(ValueError, match=message):
        call()
