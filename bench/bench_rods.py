"""Benchmarks of chapter 3 (seed 001): one cantilever under a tip load P L^2 / EI = 1, by the
closed form, by RK4 shooting (41 nodes), and by scipy's collocation solver ``solve_bvp`` on the
same problem (41-node initial mesh, tolerance chosen so that its tip error is no larger than
the shooting's, about 2.5e-9 m); plus 100 cantilevers shot in one batch."""

import numpy as np
from scipy.integrate import solve_bvp

from mechnum import rods

EI, L, FORCE = 1.0, 1.0, np.array([0.0, 1.0])
EXACT_TIP = rods.cantilever(EI, L, FORCE, "elliptic").tip


def test_cantilever_closed_form(benchmark):
    rod = benchmark(rods.cantilever, EI, L, FORCE, "elliptic")
    assert np.allclose(rod.tip, [0.943566762, 0.301720774], atol=1e-9)


def test_cantilever_shooting_41_nodes(benchmark):
    rod = benchmark(rods.cantilever, EI, L, FORCE, "shooting", nodes=41)
    assert np.abs(rod.tip - EXACT_TIP).max() < 3e-9


def _bvp():
    def f(s, y):
        return np.vstack((np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                          FORCE[0] * np.sin(y[2]) - FORCE[1] * np.cos(y[2])))

    def bc(ya, yb):
        return np.array([ya[0], ya[1], ya[2], yb[3]])

    s = np.linspace(0.0, L, 41)
    guess = np.vstack((s, s ** 2 / 2 - s ** 3 / 6, s - s ** 2 / 2, 1 - s))
    return solve_bvp(f, bc, s, guess, tol=1e-6)


def test_cantilever_scipy_solve_bvp(benchmark):
    res = benchmark(_bvp)
    assert res.status == 0 and np.abs(res.y[:2, -1] - EXACT_TIP).max() < 3e-9


def test_hundred_cantilevers_shot_in_one_batch(benchmark):
    forces = np.column_stack((np.zeros(100), np.linspace(0.1, 3.0, 100)))
    res = benchmark(rods.shoot_cantilever, EI, L, forces, nodes=41)
    assert res.newton.converged.all()
