"""Benchmark of the atlas (issue 25): the 2RFR's mode-1 equilibria over a 41 x 41 grid of motor
angles, on one worker and on two.

Target on the book's 2-core machine: the atlas in 20 s or less on two workers. Beside it, in the
same run, its peer: the full search (:func:`~mechnum.mechanisms.rfr2.forward`, the
ten-times check included) at every grid point, which the atlas replaces by continuation wherever
continuation vouches for the count; it is timed at one grid point in 41 (one per row, on the
diagonal) and its time for the whole grid estimated from theirs. The speed-up from one worker
to two is printed (with ``-s``); both runs give one atlas, which is asserted.

Run with ``make bench`` (or ``pytest bench/bench_atlas.py -o python_files='bench_*.py'
--benchmark-only -s``).
"""

import time

import numpy as np

from mechnum.mechanisms import rfr2

MECH = rfr2.study.TABLE7
# 1 degree apart, over the folds of Chapter 5's window (2, 3 and 4 equilibria)
THETA1, THETA2 = np.radians(np.linspace(30.0, 70.0, 41)), np.radians(np.linspace(40.0, 80.0, 41))
TARGET = 20.0  # seconds for the 41 x 41 atlas on two workers
RUNS = {}  # the atlas and its time on each number of workers, for the comparison


def _atlas(workers):
    start = time.perf_counter()
    RUNS[workers] = rfr2.atlas(MECH, THETA1, THETA2, executor=workers)
    RUNS[workers, "seconds"] = time.perf_counter() - start
    return RUNS[workers]


def test_atlas_41x41_one_worker(benchmark):
    at = benchmark.pedantic(_atlas, args=(1,), rounds=1, iterations=1)
    assert at.counts.shape == (41, 41) and len(np.unique(at.counts)) > 1
    assert at.searched.sum() < at.counts.size / 4


def _full_search_on_the_diagonal():
    return [rfr2.forward(MECH, (a, b), rng=0) for a, b in zip(THETA1, THETA2)]


def test_full_search_at_every_point_peer(benchmark):
    found = benchmark.pedantic(_full_search_on_the_diagonal, rounds=1, iterations=1)
    at = RUNS.get(1) or _atlas(1)
    assert [len(eq.x) for eq in found] == np.diag(at.counts).tolist()
    RUNS["peer", "seconds"] = benchmark.stats.stats.median * THETA1.size


def test_atlas_41x41_two_workers(benchmark, capsys):
    at = benchmark.pedantic(_atlas, args=(2,), rounds=1, iterations=1)
    one = RUNS.get(1) or _atlas(1)
    for name in ("counts", "stable_counts", "searched", "folds"):
        assert np.array_equal(getattr(at, name), getattr(one, name)), name
    seconds, serial = RUNS[2, "seconds"], RUNS[1, "seconds"]
    peer = RUNS.get(("peer", "seconds"))
    benchmark.extra_info.update(seconds=seconds, one_worker=serial, speedup=serial / seconds,
                                searched=int(at.searched.sum()), full_search_estimate=peer)
    with capsys.disabled():
        print(f"\n2RFR atlas 41 x 41: {serial:.1f} s on one worker, {seconds:.1f} s on two "
              f"(speed-up {serial / seconds:.2f}, target {TARGET:g} s); {at.message}"
              + ("" if peer is None else f"; the full search at every point: about "
                 f"{peer:.0f} s on one worker"))
    assert seconds <= TARGET
