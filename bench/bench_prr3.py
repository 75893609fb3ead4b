"""Benchmarks of the 3PRR chapter: the forward problem, one input and 2000 at once, and a workspace.

Targets (issue 25), each a ratio to a peer timed in the same run, asserted on medians:

* one input, as a student calls it: at most 20 times one ``np.roots`` of a degree-8 polynomial
  (the study's own step; the package adds the deflation, the real-root test, three candidate
  points per root, a Newton polish and the determinants);
* 2000 inputs in one call: at most 20 us per input, printed beside the minimal batched solver a
  reader would write (the study's polynomial for every input, the eigenvalues of the 2000
  companion matrices in one call, the real roots, Cramer's rule), with none of the package's
  checks, repairs and reports;
* the study's 51 x 51 x 14 workspace grid (its Matlab loops over 36414 poses) in 1 s or less.

Run with ``make bench`` (or ``pytest bench/bench_prr3.py -o python_files='bench_*.py'
--benchmark-only``); with ``-s`` the ratios are printed.
"""

import timeit

import numpy as np

from mechnum.mechanisms import prr3
from mechnum.mechanisms.prr3 import _geometry
from mechnum.mechanisms.prr3.study import EXAMPLES

GEOMETRY, LAMBDAS = EXAMPLES["Table 5"]
ONE_POSE_RATIO = 20  # one input: at most this many np.roots of the degree-8 polynomial
US_PER_INPUT = 20.0  # a batch of 2000: at most this many microseconds per input
ROUNDS = 41  # interleaved rounds of the two timings of a ratio: their medians are compared
# One call per round for the one-input ratio: a round of many calls lasts longer than a time
# slice of a shared machine, and the waits of the longer function would inflate its median.
ONE_CALL_ROUNDS = 401


def _inputs(n=2000, seed=0):
    """Inputs of ``n`` random reachable poses, each in a random working mode."""
    rng = np.random.default_rng(seed)
    poses = np.column_stack([rng.uniform(0, 4, 8 * n), rng.uniform(-1, 1, 8 * n),
                             rng.uniform(0, 2 * np.pi, 8 * n)])
    modes = np.stack([prr3.branch_inputs(GEOMETRY, poses, (s1, s2, s3))
                      for s1 in (1, -1) for s2 in (1, -1) for s3 in (1, -1)])
    lam = modes[rng.integers(8, size=len(poses)), np.arange(len(poses))]
    return lam[np.all(np.isfinite(lam), axis=1)][:n]


INPUTS = _inputs()


def peer_forward(lam, g):
    """The minimal batched forward problem: no deflation, no checks, no polishing."""
    C = prr3.polynomial(g, lam)  # (m, 9)
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


def medians(first, second, number, rounds=ROUNDS):
    """Median seconds per call of two functions, timed in interleaved rounds (so that a change
    of the machine's load touches both alike)."""
    times = np.array([[timeit.timeit(f, number=number) / number for f in (first, second)]
                      for _ in range(rounds)])
    return np.median(times, axis=0)


def test_forward_one_input_against_np_roots(benchmark, capsys):
    octic = prr3.polynomial(GEOMETRY, LAMBDAS)[::-1]
    sol = benchmark(prr3.forward, GEOMETRY, LAMBDAS)
    assert sol.x.shape == (2, 3)
    mine, roots = medians(lambda: prr3.forward(GEOMETRY, LAMBDAS), lambda: np.roots(octic), 1,
                          ONE_CALL_ROUNDS)
    ratio = mine / roots
    benchmark.extra_info.update(us=mine * 1e6, np_roots_us=roots * 1e6, ratio=ratio)
    with capsys.disabled():
        print(f"\n3PRR forward, one input: {mine * 1e6:.0f} us, np.roots of the octic "
              f"{roots * 1e6:.0f} us: {ratio:.1f} times (target {ONE_POSE_RATIO})")
    assert ratio <= ONE_POSE_RATIO


def test_forward_2000_inputs_against_the_minimal_batch(benchmark, capsys):
    sol = benchmark(prr3.forward, GEOMETRY, INPUTS)
    assert sol.counts.shape == (2000,) and sol.counts.min() >= 1
    mine, peer = medians(lambda: prr3.forward(GEOMETRY, INPUTS),
                         lambda: peer_forward(INPUTS, GEOMETRY), 1)
    poses, row = peer_forward(INPUTS, GEOMETRY)
    assert np.abs(_geometry.loop_residuals(GEOMETRY, poses, INPUTS[row])).max() < 1e-6
    benchmark.extra_info.update(us_per_input=mine / 2000 * 1e6, ratio_to_peer=mine / peer)
    with capsys.disabled():
        print(f"\n3PRR forward, 2000 inputs: {mine / 2000 * 1e6:.1f} us per input (target "
              f"{US_PER_INPUT:g}), minimal batch {peer / 2000 * 1e6:.1f} us: "
              f"{mine / peer:.1f} times")
    assert mine / 2000 * 1e6 <= US_PER_INPUT


def test_inverse_problem_table_3(benchmark):
    geometry, pose = EXAMPLES["Table 3"]
    assert benchmark(prr3.inverse, geometry, pose).shape == (8, 3)


def test_workspace_grid_51_51_14(benchmark):
    geometry = prr3.study.WORKSPACE_GEOMETRY  # the study's workspace script
    x = np.linspace(-3, 6, 51)
    psi = np.arange(14) * 0.15 * np.pi
    X, Y, PSI = np.meshgrid(x, x, psi, indexing="ij")
    reach = benchmark(prr3.workspace, geometry, X, Y, PSI)
    assert reach.shape == (51, 51, 14) and reach.any()
    assert benchmark.stats.stats.median < 1.0
