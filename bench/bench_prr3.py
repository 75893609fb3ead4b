"""Benchmarks of the 3PRR chapter: the direct problem, one input and 2000 at once, and a workspace.

Targets: the direct problem over 2000 inputs at once in 20 us per input or less, beside a peer in
the same run: the minimal batched solver a reader would write (the study's polynomial for every
input, the eigenvalues of the 2000 companion matrices in one call, the real roots, Cramer's rule),
with none of the package's checks, repairs and reports; the ratio is printed. The study's
51 x 51 x 14 workspace grid (its Matlab loops over 36414 poses) in 1 s or less.
Run with ``make bench`` (or ``pytest bench/bench_prr3.py -o python_files='bench_*.py'
--benchmark-only``).
"""

import numpy as np

from mechnum.mechanisms import prr3
from mechnum.mechanisms.prr3 import EXAMPLES

GEOMETRY = EXAMPLES["Tabla 5"][0]
PEER = {}


def _inputs(n=2000, seed=0):
    """Inputs of ``n`` random reachable poses, each in a random working mode."""
    rng = np.random.default_rng(seed)
    poses = np.column_stack([rng.uniform(0, 4, 8 * n), rng.uniform(-1, 1, 8 * n),
                             rng.uniform(0, 2 * np.pi, 8 * n)])
    modes = np.stack([prr3.branch_inputs(poses, GEOMETRY, (s1, s2, s3))
                      for s1 in (1, -1) for s2 in (1, -1) for s3 in (1, -1)])
    lam = modes[rng.integers(8, size=len(poses)), np.arange(len(poses))]
    return lam[np.all(np.isfinite(lam), axis=1)][:n]


INPUTS = _inputs()


def peer_direct(lam, g):
    """The minimal batched direct problem: no deflation, no checks, no polishing."""
    C = prr3.polynomial(lam, g)  # (m, 9)
    companion = np.zeros((len(C), 8, 8))
    companion[:, np.arange(1, 8), np.arange(7)] = 1
    companion[:, :, -1] = -C[:, :8] / C[:, 8:]
    t = np.linalg.eigvals(companion)
    row, _ = np.nonzero(np.abs(t.imag) < 1e-6)
    psi = 2 * np.arctan(t[np.abs(t.imag) < 1e-6].real)
    c1 = np.column_stack([lam[row, 0], np.zeros(len(row))])
    c2 = np.column_stack([g.B2 - lam[row, 1], np.zeros(len(row))])
    c3 = np.column_stack([np.full(len(row), g.B3), g.H3 - lam[row, 2]])
    d2 = c2 - g.a * np.column_stack([np.cos(psi), np.sin(psi)])
    d3 = c3 - g.a * np.column_stack([np.cos(psi + np.pi / 3), np.sin(psi + np.pi / 3)])
    A = np.stack([d2 - c1, d3 - c1], axis=1)
    b = (np.stack([np.sum(d2 ** 2, 1), np.sum(d3 ** 2, 1)], 1) - np.sum(c1 ** 2, 1)[:, None]) / 2
    xy = np.linalg.solve(A, b[..., None])[..., 0]
    return np.column_stack([xy, np.mod(psi, 2 * np.pi)]), row


def test_direct_2000_inputs_peer(benchmark):
    poses, row = benchmark(peer_direct, INPUTS, GEOMETRY)
    PEER["median"] = benchmark.stats.stats.median
    assert np.abs(prr3.loop_residuals(poses, INPUTS[row], GEOMETRY)).max() < 1e-6


def test_direct_2000_inputs(benchmark, capsys):
    sol = benchmark(prr3.direct, INPUTS, GEOMETRY)
    assert sol.counts.shape == (2000,) and sol.counts.min() >= 1
    mine = benchmark.stats.stats.median
    if "median" not in PEER:  # run alone: time the peer here, in the same process
        import timeit
        PEER["median"] = min(timeit.repeat(lambda: peer_direct(INPUTS, GEOMETRY), number=1,
                                           repeat=5))
    ratio = mine / PEER["median"]
    benchmark.extra_info.update(us_per_input=mine / 2000 * 1e6, ratio_to_peer=ratio)
    with capsys.disabled():
        print(f"\n3PRR direct, 2000 inputs: {mine / 2000 * 1e6:.1f} us per input, peer "
              f"{PEER['median'] / 2000 * 1e6:.1f} us, ratio {ratio:.1f}")


def test_direct_problem_table_5(benchmark):
    geometry, lam = EXAMPLES["Tabla 5"]
    assert benchmark(prr3.direct, lam, geometry).poses.shape == (2, 3)


def test_inverse_problem_table_3(benchmark):
    geometry, pose = EXAMPLES["Tabla 3"]
    assert benchmark(prr3.inverse, pose, geometry).shape == (8, 3)


def test_workspace_grid_51_51_14(benchmark):
    geometry = prr3.WORKSPACE_GEOMETRY  # the study's workspace script
    x = np.linspace(-3, 6, 51)
    psi = np.arange(14) * 0.15 * np.pi
    X, Y, PSI = np.meshgrid(x, x, psi, indexing="ij")
    reach = benchmark(prr3.workspace, X, Y, PSI, geometry)
    assert reach.shape == (51, 51, 14) and reach.any()
