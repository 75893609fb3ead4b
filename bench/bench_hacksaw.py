"""Benchmarks of Chapter 1: the 1000-point, two-revolution sweep of the hacksaw.

* The batched sweep against its reference, a minimal vectorised Newton written here in plain
  NumPy (:func:`reference_sweep`: Newton on the position equations of all points at once, then
  the velocity and acceleration stages as two batched linear solves). Target: the package's
  batched sweep within 1.5x of it, medians of interleaved rounds in the same run (issues 17
  and 25), asserted; the ratio is printed (``-s``) and stored in the benchmark's
  ``extra_info``.
* The two per-point loops of the study (consecutive, simultaneous), each with the study's
  previous-point seed and with the velocity predictor, and SciPy's MINPACK ``hybr`` in the
  simultaneous loop as a peer; the closed form as the floor.

Run with ``make bench`` (or ``pytest bench/bench_hacksaw.py -o python_files='bench_*.py'
--benchmark-only``). Timings on a shared machine are noisy: compare rows of one run only.
"""

import timeit

import numpy as np
import pytest

from mechnum.mechanisms import hacksaw as hs
from mechnum.mechanisms.hacksaw import study
from mechnum.mechanisms.hacksaw._solvers import PREDICTORS

TIMES = np.linspace(0.0, 2 * hs.first_revolution_time(), 1000)
EXACT = hs.closed_form(study.STUDY, TIMES)
FASTEST = {}  # the fastest time of each benchmark of this run, for the printed ratios
BATCHED_RATIO = 1.5  # the batched sweep: at most this many times the minimal Newton (medians)
ROUNDS = 41  # interleaved rounds of the two timings of the ratio


def reference_sweep(times, seed=study.TRAJECTORY_SEED, tol=study.TOL, g=study.STUDY):
    """The minimal vectorised Newton for the whole trajectory: the peer of the batched sweep."""
    th2, w2, a2 = hs.motor(times)
    s2, c2 = np.sin(th2), np.cos(th2)
    r1, t1, t3 = (np.full(times.size, value) for value in seed[:3])
    J = np.zeros((times.size, 3, 3))
    for _ in range(50):
        s1, c1, s3, c3 = np.sin(t1), np.cos(t1), np.sin(t3), np.cos(t3)
        J[:, 0, 0], J[:, 0, 1] = s1, r1 * c1
        J[:, 1, 0], J[:, 1, 1], J[:, 1, 2] = -c1, r1 * s1, -g.r3 * s3
        J[:, 2, 0], J[:, 2, 1], J[:, 2, 2] = s1, r1 * c1, -g.r3 * c3
        F = np.stack([r1 * s1 - g.r1y, -r1 * c1 + g.r2 * c2 + g.r3 * c3,
                      r1 * s1 - g.r2 * s2 - g.r3 * s3], axis=-1)
        dx = np.linalg.solve(J, -F[..., None])[..., 0]
        r1, t1, t3 = r1 + dx[:, 0], t1 + dx[:, 1], t3 + dx[:, 2]
        if np.linalg.norm(dx, axis=1).max() < tol:
            break
    s1, c1, s3, c3 = np.sin(t1), np.cos(t1), np.sin(t3), np.cos(t3)
    J[:, 0, 0], J[:, 0, 1] = s1, r1 * c1
    J[:, 1, 0], J[:, 1, 1], J[:, 1, 2] = -c1, r1 * s1, -g.r3 * s3
    J[:, 2, 0], J[:, 2, 1], J[:, 2, 2] = s1, r1 * c1, -g.r3 * c3
    # velocity rows (c', x', y') in the order of J's rows, then acceleration rows (c'', x'', y'')
    b = np.stack([np.zeros_like(w2), g.r2 * w2 * s2, g.r2 * w2 * c2], axis=-1)
    vr, w1, w3 = np.linalg.solve(J, b[..., None])[..., 0].T
    b = np.stack([r1 * s1 * w1**2 - 2 * vr * c1 * w1,
                  -r1 * c1 * w1**2 - 2 * vr * s1 * w1 + g.r2 * (c2 * w2**2 + a2 * s2)
                  + g.r3 * c3 * w3**2,
                  r1 * s1 * w1**2 - 2 * vr * c1 * w1 - g.r2 * (s2 * w2**2 - a2 * c2)
                  - g.r3 * s3 * w3**2], axis=-1)
    ar, a1, a3 = np.linalg.solve(J, b[..., None])[..., 0].T
    return np.stack([r1, t1, t3, vr, w1, w3, ar, a1, a3], axis=-1)


def _record(benchmark, name, reference=None):
    """Keep the fastest time; print (and store) its ratio to ``reference``'s, if that ran."""
    FASTEST[name] = benchmark.stats.stats.min
    if reference in FASTEST:
        ratio = FASTEST[name] / FASTEST[reference]
        benchmark.extra_info[f"ratio to {reference}"] = round(ratio, 2)
        print(f"\n{name}: {ratio:.2f} x {reference}")


@pytest.mark.benchmark(group="hacksaw: 1000 points at once")
def test_reference_vectorised_newton(benchmark):
    x = benchmark.pedantic(reference_sweep, args=(TIMES,), rounds=30, warmup_rounds=2)
    assert np.abs(x - EXACT).max() < 1e-9
    _record(benchmark, "reference")


@pytest.mark.benchmark(group="hacksaw: 1000 points at once")
def test_batched_sweep(benchmark, capsys):
    res = benchmark.pedantic(hs.sweep, args=(study.STUDY, TIMES, "batched"), rounds=30,
                             warmup_rounds=2)
    assert np.abs(res.x - EXACT).max() < 1e-9
    _record(benchmark, "batched sweep", "reference")
    times = np.array([[timeit.timeit(f, number=1) for f in (
        lambda: hs.sweep(study.STUDY, TIMES, "batched"), lambda: reference_sweep(TIMES))]
        for _ in range(ROUNDS)])  # interleaved, so that a change of load touches both alike
    mine, peer = np.median(times, axis=0)
    benchmark.extra_info["median ratio to the minimal Newton"] = round(mine / peer, 2)
    with capsys.disabled():
        print(f"\nhacksaw batched sweep: {mine * 1e3:.2f} ms, minimal vectorised Newton "
              f"{peer * 1e3:.2f} ms: {mine / peer:.2f} times (target {BATCHED_RATIO})")
    assert mine / peer <= BATCHED_RATIO


@pytest.mark.benchmark(group="hacksaw: 1000 points at once")
def test_closed_form(benchmark):
    x = benchmark(hs.closed_form, study.STUDY, TIMES)
    assert x.shape == (1000, 9)
    _record(benchmark, "closed form", "reference")


def scipy_root_sweep(times):
    """A peer: the simultaneous loop with SciPy's MINPACK ``hybr`` instead of our Newton."""
    from scipy.optimize import root

    out, x = np.empty((times.size, 9)), study.TRAJECTORY_SEED
    for i, state in enumerate(np.stack(hs.motor(times), axis=-1)):
        x = root(lambda z, *s: hs.residual(study.STUDY, z, *s), x, args=tuple(state),
                 jac=lambda z, *_: hs.jacobian(study.STUDY, z), method="hybr", tol=1e-12).x
        out[i] = x
    return out


@pytest.mark.benchmark(group="hacksaw: point by point")
def test_sweep_scipy_root_peer(benchmark):
    x = benchmark.pedantic(scipy_root_sweep, args=(TIMES,), rounds=3, warmup_rounds=1)
    assert np.abs(x - EXACT).max() < 1e-9
    _record(benchmark, "scipy hybr")


@pytest.mark.benchmark(group="hacksaw: point by point")
@pytest.mark.parametrize("predictor", PREDICTORS)
@pytest.mark.parametrize("method", ["consecutive", "simultaneous"])
def test_sweep_loop(benchmark, method, predictor):
    res = benchmark.pedantic(hs.sweep, args=(study.STUDY, TIMES, method),
                             kwargs={"predictor": predictor}, rounds=3, warmup_rounds=1)
    assert np.abs(res.x - EXACT).max() < 1e-9
    _record(benchmark, f"{method}, {predictor}", "scipy hybr")
