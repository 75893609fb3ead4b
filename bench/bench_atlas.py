"""Benchmarks of the atlas (issues 25 and 35): the 2RFR's mode-1 equilibria over grids of motor
angles, how the cost grows with the grid, on one worker and on a dask cluster.

* The atlas over Chapter 5's window (30 to 70 degrees by 40 to 80, over its folds: 2, 3 and 4
  equilibria) at 11 x 11, 21 x 21 and 41 x 41 points, one worker; the exponent of its cost in
  the number of points, fitted (least squares of log time on log points), is printed (``-s``).
  Target: the 41 x 41 atlas in 8 s (median of 3). The same 41 x 41 atlas with the numpy closed
  form (``mechnum.rods._kernels.reference``) is reported (target 15 s) and asserted to be
  the same atlas in every field.
* Its peer, in the same run: the full search (:func:`~mechnum.mechanisms.rfr2.forward`,
  the ten-times check included) at every grid point, which the atlas replaces by continuation
  wherever continuation vouches for the count; timed at one grid point in 41 (one per row, on
  the diagonal) and its time for the whole grid estimated from theirs.
* A 201 x 201 atlas (a quarter of a degree apart) on a dask ``LocalCluster`` of two workers,
  timed against the same cluster with one worker: the figure a cluster user plans from (the
  searches run on the workers; the flood, the continuation between them, in the client).

Run with ``make bench`` (or ``pytest bench/bench_atlas.py -o python_files='bench_*.py'
--benchmark-only -s``).
"""

import time

import numpy as np
import pytest

from mechnum.mechanisms import rfr2
from mechnum.rods import _kernels as kernels

MECH = rfr2.study.TABLE7
WINDOW = ((30.0, 70.0), (40.0, 80.0))     # degrees
SIZES = (11, 21, 41)
TARGET, NUMPY_TARGET = 8.0, 15.0          # seconds for the 41 x 41 atlas on one worker
FIELDS = ("counts", "stable_counts", "stable", "searched", "vouched", "folds", "status",
          "iterations")
RUNS = {}   # the atlases and their times, for the comparisons


def _axes(n):
    return tuple(np.radians(np.linspace(*limits, n)) for limits in WINDOW)


def _atlas(n, executor=1):
    return rfr2.atlas(MECH, *_axes(n), executor=executor)


@pytest.mark.parametrize("n", SIZES)
def test_atlas_one_worker(benchmark, n, capsys):
    at = benchmark.pedantic(_atlas, args=(n,), rounds=3, iterations=1)
    assert at.counts.shape == (n, n) and len(np.unique(at.counts)) > 1
    RUNS[n] = at, benchmark.stats.stats.median
    benchmark.extra_info.update(searched=int(at.searched.sum()), message=at.message)
    if n != SIZES[-1]:
        return
    assert at.searched.sum() < at.counts.size / 4
    if all(size in RUNS for size in SIZES):        # how the cost grows with the points
        points = np.array([size * size for size in SIZES], dtype=float)
        seconds = np.array([RUNS[size][1] for size in SIZES])
        exponent = np.polyfit(np.log(points), np.log(seconds), 1)[0]
        benchmark.extra_info["exponent of the time in the points"] = exponent
        with capsys.disabled():
            print("\n2RFR atlas on one worker (medians of 3): " + ", ".join(
                f"{size} x {size}: {s:.2f} s ({int(RUNS[size][0].searched.sum())} searched)"
                for size, s in zip(SIZES, seconds)) + f"; time ~ points**{exponent:.2f}")
    assert benchmark.stats.stats.median <= TARGET


def test_atlas_41x41_numpy_closed_form(benchmark, capsys):
    def numpy_path():
        with kernels.reference():
            return _atlas(41)

    at = benchmark.pedantic(numpy_path, rounds=1, iterations=1)
    compiled = RUNS.get(41, (None,))[0] or _atlas(41)
    for name in FIELDS:
        assert np.array_equal(getattr(at, name), getattr(compiled, name)), name
    assert np.array_equal(np.isnan(at.x), np.isnan(compiled.x))
    assert np.nanmax(np.abs(at.x - compiled.x)) < 1e-12
    seconds = benchmark.stats.stats.median
    with capsys.disabled():
        print(f"\n2RFR atlas 41 x 41 with the numpy closed form: {seconds:.1f} s (target "
              f"{NUMPY_TARGET:g} s), the same atlas as the compiled one")
    assert seconds <= NUMPY_TARGET


def _full_search_on_the_diagonal():
    return [rfr2.forward(MECH, (a, b), rng=0) for a, b in zip(*_axes(41))]


def test_full_search_at_every_point_peer(benchmark, capsys):
    found = benchmark.pedantic(_full_search_on_the_diagonal, rounds=1, iterations=1)
    at = RUNS.get(41, (None,))[0] or _atlas(41)
    assert [len(eq.x) for eq in found] == np.diag(at.counts).tolist()
    estimate = benchmark.stats.stats.median * 41
    benchmark.extra_info["full search at every point, estimated seconds"] = estimate
    with capsys.disabled():
        print(f"\nthe full search at every point of the 41 x 41 grid: about {estimate:.0f} s on "
              "one worker")


def test_atlas_201x201_on_a_dask_cluster(benchmark, capsys):
    distributed = pytest.importorskip("distributed")
    seconds, atlases = {}, {}
    for workers in (1, 2):
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            rfr2.atlas(MECH, *_axes(9), executor=client)   # the workers load the kernels
            start = time.perf_counter()
            if workers == 2:
                atlases[2] = benchmark.pedantic(_atlas, args=(201, client), rounds=1,
                                                iterations=1)
            else:
                atlases[1] = _atlas(201, client)
            seconds[workers] = time.perf_counter() - start
    for name in FIELDS:
        assert np.array_equal(getattr(atlases[1], name), getattr(atlases[2], name)), name
    at = atlases[2]
    benchmark.extra_info.update(one_worker=seconds[1], two_workers=seconds[2],
                                speedup=seconds[1] / seconds[2],
                                searched=int(at.searched.sum()))
    with capsys.disabled():
        print(f"\n2RFR atlas 201 x 201 on a dask LocalCluster: {seconds[1]:.0f} s on one "
              f"worker, {seconds[2]:.0f} s on two (speed-up {seconds[1] / seconds[2]:.2f}); "
              f"{at.message}")
    assert at.counts.shape == (201, 201)
