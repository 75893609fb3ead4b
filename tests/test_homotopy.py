"""Tests of mechnum.homotopy: the path tracker and the total-degree homotopy on known roots."""

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from strategies import separated

from mechnum import homotopy
from mechnum.errors import ConvergenceError
from mechnum.polynomials import PolynomialSystem, bezout_bound
from mechnum.results import Result


def schedule(h0):
    """Steps to s = 1 by the documented rule when none is rejected: h doubles after three
    accepted steps in a row, up to 0.1, and the last step ends at 1."""
    s, h, steps, successes = 0.0, h0, 0, 0
    while s < 1.0:
        h = min(h, 1.0 - s)
        s, steps, successes = (1.0 if h >= 1.0 - s else s + h), steps + 1, successes + 1
        if successes == 3:
            h, successes = min(2 * h, 0.1), 0
    return steps


@pytest.mark.parametrize("h0", [0.01, 0.001, 0.05])
def test_track_follows_a_path_to_its_end(h0):
    # x^2 = 1 + 3 s: the root starting at -1 ends at -2, a smooth path where no step is rejected
    H = lambda x, s: (x ** 2 - (1 + 3 * s), np.diag(2 * x), np.array([-3.0 + 0j]))  # noqa: E731
    end = homotopy.track(H, [-1.0 + 0j], h0=h0)
    assert end.s == 1.0 and end.status == "converged" and end.converged
    assert end.rejected == 0 and end.steps == schedule(h0) == end.iterations
    assert end.nfev == end.njev >= 5 * end.steps      # four stages and a corrector per step
    # track's corrector stops at its tolerance TOL = 1e-9 (relative): the endpoint is no more
    # accurate than that
    assert_allclose(end.x, [-2.0], rtol=1e-9)


def test_track_reports_a_lost_path():
    # x^2 = (1 - 2 s): two roots meet at s = 1/2 (a singular point): the path cannot pass it
    H = lambda x, s: (x ** 2 - (1 - 2 * s), np.diag(2 * x), np.array([2.0 + 0j]))  # noqa: E731
    end = homotopy.track(H, [1.0 + 0j], max_steps=500)
    assert end.s < 1.0 and end.status == "lost" and end.rejected > 0
    assert end.iterations == end.steps + end.rejected and "lost at s" in end.message


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
    assert np.all(result.ends == "finite") and np.all(result.status == "converged")
    assert len(result.x) == 6
    for root in known:
        # polished endpoints of simple roots carry round-off (about 1e-15 on a system of unit size):
        # 1e-8 leaves room for the worst-conditioned of the drawn systems
        assert np.abs(result.x - root).max(axis=1).min() < 1e-8
    real = result.real(1e-8)
    assert len(real) == 2 * np.sum(a + b > 0)


def test_paths_to_infinity_are_classified():
    # x y = 1, x^2 = 4: Bezout 4, two finite roots, two at infinity
    system = PolynomialSystem.from_dicts([{(1, 1): 1, (0, 0): -1}, {(2, 0): 1, (0, 0): -4}])
    result = homotopy.solve(system, rng=3)
    assert sorted(result.ends.tolist()) == ["at-infinity", "at-infinity", "finite", "finite"]
    # the two simple roots, polished on the system: round-off of O(1) numbers
    assert_allclose(result.real(), [[-2.0, -0.5], [2.0, 0.5]], atol=1e-10, rtol=0)
    at_infinity = result.endpoints[result.ends == "at-infinity"]
    # an endpoint at infinity has x0 below _AT_INFINITY = 1e-6 of |X|: the classification's own
    # threshold
    assert np.all(np.abs(at_infinity[:, 0]) < 1e-6 * np.linalg.norm(at_infinity, axis=1))


CIRCLE = PolynomialSystem.from_dicts([{(2, 0): 1, (0, 2): 1, (0, 0): -4},
                                      {(1, 1): 1, (0, 0): -1}])


@pytest.mark.parametrize("call, message", [
    (lambda: homotopy.solve("x^2"), "PolynomialSystem"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1, 1): 1}])), "square"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1,): 1, (0,): -1}]), tol=-1), "tol"),
    (lambda: homotopy.solve(PolynomialSystem.from_dicts([{(1,): 1, (0,): -1}]), same=0), "same"),
    (lambda: homotopy.track(lambda x, s: None, [1.0], h0=-1), "h0"),
    (lambda: homotopy.track(lambda x, s: None, [1.0], max_steps=0), "max_steps"),
    (lambda: homotopy.track(lambda x, s: None, [1.0], max_steps=10 ** 9), "bound on the work"),
    (lambda: homotopy.track(lambda x, s: None, [np.nan]), "seed must be finite"),
    (lambda: homotopy.track(lambda x, s: (x, np.eye(2), x), [1.0]), "fun must return"),
    (lambda: homotopy.solve(CIRCLE, rng="a"), "rng must be"),
    (lambda: homotopy.solve(CIRCLE, rng=-1), "rng must be"),
    (lambda: homotopy.solve(CIRCLE, raise_on_failure="no"), "raise_on_failure must be"),
])
def test_bad_input_raises_a_value_error_that_names_it(call, message):
    with pytest.raises(ValueError, match=message):
        call()


# --- issue 23: singular ends, lost paths, the result contract -----------------------------------

@pytest.mark.parametrize("power", [2, 3])
def test_a_multiple_root_is_found_with_its_multiplicity(power):
    # D8: (x - 1)^2 = 0, y = 1 used to give 0 solutions, both paths 'lost', and no error: the
    # paths meet at s = 1, where the Jacobian is singular; the endgame finishes them
    c = np.polynomial.polynomial.polyfromroots([1.0] * power)
    F = PolynomialSystem.from_dicts([{(k, 0): v for k, v in enumerate(c)},
                                     {(0, 1): 1, (0, 0): -1}])
    result = homotopy.solve(F, rng=0)
    assert result.multiplicity.tolist() == [power] and len(result.x) == 1
    # a root of multiplicity m is determined to about eps^(1/m) only (its digits are those of the
    # m-th root of round-off): 1e-7 for the double root (eps^(1/2) = 1.5e-8), 1e-4 for the triple
    # one (eps^(1/3) = 6e-6)
    assert_allclose(result.real(), [[1.0, 1.0]], rtol=1e-4 if power == 3 else 1e-7)
    assert set(result.status) <= {"converged", "singular"} and "singular" in result.status
    assert (result.ends == "finite").all()


def test_simple_and_double_roots_together():
    # (x - 1)^2 (x + 2) = 0, y^2 = 4: four distinct solutions, two of them double
    c = np.polynomial.polynomial.polyfromroots([1.0, 1.0, -2.0])
    F = PolynomialSystem.from_dicts([{(k, 0): v for k, v in enumerate(c)},
                                     {(0, 2): 1, (0, 0): -4}])
    result = homotopy.solve(F, rng=4)
    # the double roots x = 1 carry about sqrt(eps) = 1.5e-8 relative error (their digits are those
    # of sqrt(round-off)): 1e-7
    assert_allclose(result.real(), [[-2, -2], [-2, 2], [1, -2], [1, 2]], rtol=1e-7)
    assert sorted(result.multiplicity.tolist()) == [1, 1, 2, 2]


def test_a_lost_path_is_an_error_or_a_status(monkeypatch):
    real_track = homotopy.track
    calls = []

    def losing(*args, **kwargs):  # the tracker loses the first path at s = 0.5
        calls.append(1)
        end = real_track(*args, **kwargs)
        if len(calls) > 1:
            return end
        return homotopy.TrackResult(x=end.x, status="lost", message="lost", iterations=1,
                                    nfev=1, njev=1, s=0.5, steps=1, rejected=0)

    monkeypatch.setattr(homotopy, "track", losing)
    with pytest.raises(ConvergenceError, match="1 of 4 paths were lost") as info:
        homotopy.solve(CIRCLE, rng=0)
    result = info.value.result
    assert result.status.tolist().count("lost") == 1 and result.ends.tolist().count("lost") == 1
    assert len(result.x) == 3      # one of the four is missing, and said so
    calls.clear()
    kept = homotopy.solve(CIRCLE, rng=0, raise_on_failure=False)
    assert not kept.converged.all() and len(kept.x) == 3


def test_results_follow_the_contract():
    result = homotopy.solve(CIRCLE, rng=0)
    assert isinstance(result, Result) and result.converged.all()
    assert result.nfev == result.njev > 0 and "4 distinct finite solutions" in result.message
    assert homotopy.ENDS == ("finite", "at-infinity", "lost")


@settings(max_examples=100, deadline=None)
@given(a=st.floats(0.1, 10.0), b=st.floats(-0.09, 10.0), seed=st.integers(0, 100))
def test_track_ends_on_the_target_system(a, b, seed):
    # x^2 = a + b s stays away from 0 (a + b s >= 0.01): the path from sqrt(a) ends at
    # sqrt(a + b), where the corrector's tolerance leaves a residual of round-off size
    b = max(b, 0.01 - a)
    H = lambda x, s: (x ** 2 - (a + b * s), np.diag(2 * x), np.array([-b + 0j]))  # noqa: E731
    end = homotopy.track(H, [np.sqrt(a) + 0j])
    assert end.status == "converged"
    # track's corrector tolerance TOL = 1e-9 (relative) on a root of size sqrt(a + b): the residual
    # x^2 - (a + b) is then below about 2 TOL (a + |b|); 1e-8 leaves a margin of five
    assert abs(end.x[0] ** 2 - (a + b)) <= 1e-8 * (a + abs(b))
