"""Benchmarks of Chapter 1: the 1000-point, two-revolution sweep of the hacksaw.

Targets on a 2-core machine: the batched sweep in 20 ms or less and within 50x of the closed
form; each per-point loop (consecutive, simultaneous) in 300 ms or less. A peer, SciPy's
MINPACK ``hybr`` in the same per-point loop, sets the simultaneous loop's scale.
Run with ``make bench`` (or ``pytest bench/bench_hacksaw.py -o python_files='bench_*.py'
--benchmark-only``).
"""

import numpy as np
import pytest

from mechnum.mechanisms import hacksaw as hs

TIMES = np.linspace(0.0, 2 * hs.first_revolution_time(), 1000)


def test_closed_form(benchmark):
    x = benchmark(hs.closed_form, TIMES)
    assert x.shape == (1000, 9)


@pytest.mark.parametrize("method", hs.METHODS)
def test_sweep(benchmark, method):
    rounds = 20 if method == "batched" else 5
    x = benchmark.pedantic(hs.sweep, args=(TIMES, method), rounds=rounds, warmup_rounds=1)
    assert np.abs(x - hs.closed_form(TIMES)).max() < 1e-9


def scipy_root_sweep(times):
    """A peer: the simultaneous loop with SciPy's MINPACK ``hybr`` instead of our Newton."""
    from scipy.optimize import root

    out, x = np.empty((times.size, 9)), hs.TRAJECTORY_SEED
    for i, state in enumerate(np.stack(hs.motor(times), axis=-1)):
        x = root(hs.residual, x, args=tuple(state), jac=lambda z, *_: hs.jacobian(z),
                 method="hybr", tol=1e-12).x
        out[i] = x
    return out


def test_sweep_scipy_root_peer(benchmark):
    x = benchmark.pedantic(scipy_root_sweep, args=(TIMES,), rounds=5, warmup_rounds=1)
    assert np.abs(x - hs.closed_form(TIMES)).max() < 1e-9
