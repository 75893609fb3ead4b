"""Benchmarks of the compiled closed form (``mechnum.rods._kernels``) against the numpy one
(``mechnum.rods``' regular module, its reference), and what compiling it costs.

* Per point: the residual and Jacobian of the 2RFR's two rods (:func:`kernels.meeting`, what
  the search evaluates) at 2000 chart points, compiled and with numpy; the time per point and
  the ratio are printed (``-s``).
* Compilation (numba, ``cache=True``): the first calls of every compiled function in a fresh
  process, with an empty cache (numba compiles them, once per installation: the cache is kept
  beside the module, ``NUMBA_CACHE_DIR`` here) and with the cache (what every later process
  pays: each test worker, each notebook's kernel, each dask worker). Whole-process figures,
  printed and stored in ``extra_info``.
"""

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2._elliptic import sample
from mechnum.rods import _kernels as kernels

MECH, THETA = rfr2.study.TABLE7, rfr2.study.TABLE7_THETA
POINTS = sample(np.random.default_rng(0), 2000)
TIMES = {}
FIRST_CALLS = """
import time
start = time.perf_counter()
import numpy as np
from mechnum.rods import _kernels as kernels
imported = time.perf_counter()
kernels.closed_form(1.0, 1.0, 2.0, 0.5, 1.0)
kernels.meeting(1.0, 1.0, np.zeros((2, 2)), [0.1, 0.2], [1.0, 1.0], [0.0, 0.0],
                np.array([[1.0, 0.5, 2.0, 0.5]]))
kernels.pinned_starts(np.array([[0.9, 0.3]]), np.array([[0.0, 1.0]]), tol=1e-9, maxiter=60,
                      halvings=20)
print(imported - start, time.perf_counter() - imported)
"""


def _meeting():
    return kernels.meeting(MECH.EI, MECH.L, MECH.origins, THETA, [1.0, 1.0], MECH.force, POINTS)


def test_residual_and_jacobian_compiled(benchmark):
    f, J = benchmark(_meeting)
    assert np.isfinite(J).all()
    TIMES["compiled"] = benchmark.stats.stats.median


def test_residual_and_jacobian_numpy(benchmark, capsys):
    def numpy_path():
        with kernels.reference():
            return _meeting()

    f, J = benchmark(numpy_path)
    assert np.isfinite(J).all()
    ours = TIMES.get("compiled")
    per_point = benchmark.stats.stats.median / len(POINTS) * 1e6
    with capsys.disabled():
        print(f"\nthe 2RFR's two rods, residual and Jacobian: numpy {per_point:.1f} us per "
              f"point" + ("" if ours is None else f", compiled {ours / len(POINTS) * 1e6:.2f} "
                          f"us ({benchmark.stats.stats.median / ours:.1f} times faster)"))


def _first_calls(cache):
    """Seconds of ``import`` and of the first calls, in a fresh process with numba's cache in
    the folder ``cache``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    out = subprocess.run([sys.executable, "-c", FIRST_CALLS], env=env, capture_output=True,
                         text=True, check=True)
    return tuple(float(x) for x in out.stdout.split())


def test_compilation_cost(benchmark, capsys):
    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        cold = _first_calls(cache)                     # compiles, and fills the cache
        cold_process = time.perf_counter() - start
        warm = benchmark.pedantic(_first_calls, args=(cache,), rounds=3, iterations=1)
    benchmark.extra_info.update(first_calls_compiling=cold[1], first_calls_cached=warm[1],
                                import_seconds=warm[0], cold_process=cold_process)
    with capsys.disabled():
        print(f"\ncompiled kernels: first calls {cold[1]:.1f} s when numba compiles them (once per "
              f"installation; the whole process {cold_process:.1f} s), {warm[1]:.2f} s from "
              f"its cache (each later process: a test worker, a notebook), import "
              f"{warm[0]:.2f} s")
    assert warm[1] < cold[1]
