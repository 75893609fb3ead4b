"""Benchmarks of Chapter 5 (seed 001): the flexible 2RFR mechanism of Table 7.

Targets on the book's 2-core machine (medians): every mode-1 equilibrium, with the
completeness check of ten times more starts, in 0.07 s (0.12 s with the numpy closed form,
``mechnum.rods._kernels.reference``, reported); every equilibrium with modes up to 3 per rod
in 5 s; a 101 x 101 map of det J_FK in 1 s; a 100-point inverse trajectory in 0.2 s. Beside
them, the plain multistart the package replaces: ``scipy.optimize.fsolve`` from each start in
turn, on the same residual and analytic Jacobian, with the same test of a root (residual below
1e-10, in the chart), from as many starts as the package's search alone (a tenth of its search
plus check, to keep the run short: compare the time per start). How the search's cost grows
with the modes, (1, 1) to (3, 3), is printed (``-s``). The study reports no run time for the
2RFR.
"""

import time

import numpy as np
from peers import fsolve_each

from mechnum.mechanisms import rfr2
from mechnum.mechanisms.rfr2._elliptic import sample
from mechnum.rods import _kernels as kernels
from mechnum.rods import in_chart

MECH, THETA = rfr2.study.TABLE7, rfr2.study.TABLE7_THETA
MODES = [(m1, m2) for m1 in (1, 2, 3) for m2 in (1, 2, 3)]
COUNTS = {(1, 1): 3, (1, 2): 5, (1, 3): 4, (2, 1): 2, (2, 2): 6, (2, 3): 4, (3, 1): 1,
          (3, 2): 4, (3, 3): 5}   # what the chapter finds (and verifies by solve_ivp)
SEARCH_TARGET, NUMPY_TARGET = 0.07, 0.12   # s, the mode-1 search with its check (medians)
MEDIANS = {}


def _fsolve_multistart(modes, n_starts, seed=0):
    """Every root that fsolve reaches from ``n_starts`` starts, one start at a time."""
    system = rfr2.forward_system(MECH, THETA, modes)
    starts = sample(np.random.default_rng(seed), n_starts)
    return fsolve_each(system, in_chart, starts)


def test_mode1_equilibria_of_table7(benchmark):
    eq = benchmark(rfr2.forward, MECH, THETA, rng=0)
    assert len(eq.pose) == 3 and eq.search.complete
    MEDIANS["compiled"] = benchmark.stats.stats.median
    assert benchmark.stats.stats.median <= SEARCH_TARGET


def test_mode1_equilibria_of_table7_numpy_closed_form(benchmark, capsys):
    def numpy_path():
        with kernels.reference():
            return rfr2.forward(MECH, THETA, rng=0)

    eq = benchmark(numpy_path)
    assert len(eq.pose) == 3 and eq.search.complete
    median = benchmark.stats.stats.median
    with capsys.disabled():
        print(f"\n2RFR mode-1 search with its check: numpy closed form {median * 1e3:.1f} ms "
              f"(target {NUMPY_TARGET * 1e3:g} ms)" + (
                  f", compiled {MEDIANS['compiled'] * 1e3:.1f} ms (target "
                  f"{SEARCH_TARGET * 1e3:g} ms)" if "compiled" in MEDIANS else ""))
    assert median <= NUMPY_TARGET


def test_mode1_equilibria_scipy_fsolve_multistart(benchmark):
    roots = benchmark.pedantic(_fsolve_multistart, args=((1, 1), 200), rounds=1, iterations=1)
    assert len(roots) <= 3


def _all_modes():
    return [rfr2.forward(MECH, THETA, modes=m, rng=2) for m in MODES]


def test_equilibria_with_modes_up_to_3(benchmark, capsys):
    found = benchmark.pedantic(_all_modes, rounds=1, iterations=1)
    assert [len(e.pose) for e in found] == [COUNTS[m] for m in MODES]
    lines = []
    for m in MODES:                       # how the search's cost grows with the modes
        seconds = []
        for _ in range(5):
            start = time.perf_counter()
            rfr2.forward(MECH, THETA, modes=m, rng=2)
            seconds.append(time.perf_counter() - start)
        lines.append(f"  modes {m}: {np.median(seconds) * 1e3:6.1f} ms, {COUNTS[m]} equilibria")
    benchmark.extra_info["median seconds per modes"] = lines
    with capsys.disabled():
        print("\n2RFR search with its check, by the rods' modes (medians of 5):\n"
              + "\n".join(lines))


def test_equilibria_with_modes_up_to_3_scipy_fsolve_multistart(benchmark):
    found = benchmark.pedantic(lambda: [_fsolve_multistart(m, 200) for m in MODES], rounds=1,
                               iterations=1)
    assert sum(len(r) for r in found) <= 34


def test_det_jfk_map_101x101(benchmark):
    eq = rfr2.forward(MECH, THETA, rng=0)
    grid = np.radians(np.linspace(0.0, 180.0, 101))
    result = benchmark.pedantic(rfr2.forward_map, args=(MECH, grid, grid, THETA, eq.x[2]),
                                rounds=3, iterations=1)
    assert result.det_fk.shape == (101, 101) and result.converged.mean() > 0.8


def test_inverse_trajectory_100_points(benchmark):
    eq = rfr2.forward(MECH, THETA, rng=0)
    points = eq.pose[2] + rfr2.study.path("inverse line")       # the study's straight line, opt 4
    result = benchmark(rfr2.inverse_path, MECH, points, THETA, eq.x[2], method="elliptic")
    assert result.converged.all()


def test_inverse_trajectory_100_points_study_shooting(benchmark):
    eq = rfr2.forward(MECH, THETA, rng=0)
    points = eq.pose[2] + rfr2.study.path("inverse line")
    result = benchmark.pedantic(rfr2.inverse_path, args=(MECH, points, THETA, eq.x[2]),
                                rounds=1, iterations=1)
    assert result.converged.all()
