"""Benchmarks of the 3PRR chapter: the direct problem per pose, and a workspace grid.

Targets (issue 5): the direct problem in 1 ms or less per pose; the seed's 50 x 50 x 14
workspace grid (its Matlab loops over 51 x 51 x 14 poses) in 1 s or less.
"""

import numpy as np

from mechnum.mechanisms import prr3
from mechnum.mechanisms.prr3 import EXAMPLES


def test_direct_problem_table_5(benchmark):
    geometry, lam = EXAMPLES["Tabla 5"]
    poses = benchmark(prr3.direct, lam, geometry)
    assert poses.shape == (2, 3)


def test_inverse_problem_table_3(benchmark):
    geometry, pose = EXAMPLES["Tabla 3"]
    assert benchmark(prr3.inverse, pose, geometry).shape == (8, 3)


def test_workspace_grid_51_51_14(benchmark):
    geometry = prr3.Geometry(L=1, a=1, B2=3, B3=2, H3=2)  # the seed's workspace script
    x = np.linspace(-3, 6, 51)
    psi = np.arange(14) * 0.15 * np.pi
    X, Y, PSI = np.meshgrid(x, x, psi, indexing="ij")
    reach = benchmark(prr3.workspace, X, Y, PSI, geometry)
    assert reach.shape == (51, 51, 14) and reach.any()
