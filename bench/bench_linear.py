"""Benchmarks of mechnum.linear against pyamg's relaxation, in the same run (issue 17).

One sweep of Jacobi, Gauss-Seidel and SOR on the 2-D Poisson matrix (5-point Laplacian) at
50 x 50 and 200 x 200 interior nodes (n = 40,000, where a dense matrix would take 12.8 GB): the
target is at most 3x pyamg's compiled ``relaxation.jacobi`` / ``gauss_seidel`` / ``sor``.
``mechnum`` sweeps a prepared splitting (the solvers' compiled sweep, built once, as a multigrid
cycle reuses its smoother; building it costs about one sweep, measured in its own group);
pyamg's functions take the matrix at every call. Then a whole SOR solve at Young's omega against
the same number of pyamg sweeps, and ``sor_spectral_radii`` over 5001 omegas (target 0.5 s).
Each mechnum benchmark runs after its pyamg peer, checks the 3x target on the ratio of the
medians and keeps it in ``extra_info``; ``test_ratios`` prints them all (``-s``).

Run with ``make bench`` (or ``pytest bench/bench_linear.py -o python_files='bench_*.py'
--benchmark-only``). Timings on a shared machine are noisy: read the ratios, not the times.
"""

import numpy as np
import pytest
from pyamg.relaxation import relaxation as amg

from mechnum import linear
from mechnum.linear._sweeps import splitting
from mechnum.mechanisms import finger as F

SIZES = (50, 200)
METHODS = ("jacobi", "gauss_seidel", "sor")
OMEGA = 1.5  # any SOR factor: the cost of a sweep does not depend on it
MEDIANS = {}  # (group, library) -> median seconds, filled by the benchmarks below
SOLVE_SWEEPS = 173  # Young's SOR to a relative residual of 1e-8 on the 50 x 50 problem


def _problem(m):
    A = linear.poisson2d(m)
    rng = np.random.default_rng(m)
    return A, rng.standard_normal(A.shape[0]), rng.standard_normal(A.shape[0])


def _pyamg_sweep(method, A, x, b):
    if method == "jacobi":
        amg.jacobi(A, x, b, iterations=1, omega=1.0)
    elif method == "gauss_seidel":
        amg.gauss_seidel(A, x, b, iterations=1)
    else:
        amg.sor(A, x, b, OMEGA, iterations=1)
    return x


def _record(benchmark, group, library):
    """Keep the median; for mechnum, check it against pyamg's (measured first) and keep the
    ratio in the benchmark's extra_info."""
    if benchmark.stats is None:  # benchmarks disabled
        return
    MEDIANS[group, library] = benchmark.stats.stats.median
    if library == "mechnum" and (group, "pyamg") in MEDIANS:
        ratio = MEDIANS[group, "mechnum"] / MEDIANS[group, "pyamg"]
        benchmark.extra_info["ratio to pyamg"] = ratio
        assert not group.startswith("sweep") or ratio <= 3, f"{group}: {ratio:.2f}x pyamg"


@pytest.mark.parametrize("m", SIZES)
@pytest.mark.parametrize("method", METHODS)
def test_sweep_pyamg(benchmark, method, m):
    A, x, b = _problem(m)
    benchmark.group = f"sweep {method} {m}x{m}"
    benchmark(_pyamg_sweep, method, A, x.copy(), b)
    _record(benchmark, f"sweep {method} {m}x{m}", "pyamg")


@pytest.mark.parametrize("m", SIZES)
@pytest.mark.parametrize("method", METHODS)
def test_sweep_mechnum(benchmark, method, m):
    A, x, b = _problem(m)
    split = splitting(A, method, OMEGA)
    benchmark.group = f"sweep {method} {m}x{m}"
    out = benchmark(split.sweep, x, b)
    _record(benchmark, f"sweep {method} {m}x{m}", "mechnum")
    assert np.allclose(out, _pyamg_sweep(method, A, x.copy(), b), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("m", SIZES)
def test_splitting_setup(benchmark, m):
    A, _, _ = _problem(m)
    benchmark.group = f"setup {m}x{m}"
    benchmark(splitting, A, "sor", OMEGA)


def test_sor_solve_pyamg(benchmark):
    A, _, b = _problem(50)
    omega = linear.young_omega(np.cos(np.pi / 51))

    def solve():
        x = np.zeros_like(b)
        amg.sor(A, x, b, omega, iterations=SOLVE_SWEEPS)
        return x

    benchmark.group = "SOR solve 50x50"
    x = benchmark(solve)
    _record(benchmark, "SOR solve 50x50", "pyamg")
    assert np.linalg.norm(b - A @ x) <= 1.01e-8 * np.linalg.norm(b)


def test_sor_solve_mechnum(benchmark):
    A, _, b = _problem(50)
    omega = linear.young_omega(np.cos(np.pi / 51))
    benchmark.group = "SOR solve 50x50"
    result = benchmark(linear.sor, A, b, omega, tol=1e-8, criterion="residual",
                       relative=True, norm=2)
    _record(benchmark, "SOR solve 50x50", "mechnum")
    assert result.iterations == SOLVE_SWEEPS


def test_sor_spectral_radii_5001(benchmark):
    A, b = F.design_matrix(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT)
    omegas = np.linspace(0.0004, 1.9996, 5001)
    radii = benchmark(linear.sor_spectral_radii, A.T @ A, omegas)
    assert radii.shape == (5001,) and np.all(radii < 1)
    assert benchmark.stats is None or benchmark.stats.stats.median <= 0.5


def _ratio_table():
    ratios = {group: MEDIANS[group, "mechnum"] / MEDIANS[group, "pyamg"]
              for group, library in MEDIANS if library == "mechnum"}
    return "\n".join(f"  {group:<24} {ratio:6.2f}" for group, ratio in sorted(ratios.items()))


def test_ratios(benchmark):
    """The summary (shown with ``-s``): mechnum's median over pyamg's, per group."""
    benchmark.group = "ratios"
    table = benchmark.pedantic(_ratio_table, rounds=1, iterations=1)
    print("\nmechnum / pyamg, ratio of medians:\n" + table)
