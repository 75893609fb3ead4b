"""Benchmarks of Chapter 7 (the actuator force): inverse and forward dynamics.

Targets on a 2-core machine: the force over 1000 instants (kinematics included) in 10 ms or less
by each of the three routes; the forward dynamics of one cycle (100 RK4 steps) in 200 ms or less.
Peers in the same run: for inverse dynamics, the force as SymPy's mechanics package derives it
(``LagrangesMethod`` on the closed-form positions) and lambdifies it for NumPy; for forward
dynamics, SciPy's adaptive ``solve_ivp`` (RK45) at the accuracy of the 100 RK4 steps.
Run with ``make bench`` (or ``pytest bench/bench_actuator.py -o python_files='bench_*.py'
--benchmark-only``).
"""

from functools import cache

import numpy as np
import pytest

from mechnum.mechanisms.actuator import (
    forward_dynamics,
    kane_force,
    kinematics,
    lagrange_force,
    lagrange_terms,
    stroke_kinematics,
    virtual_power_force,
)
from mechnum.mechanisms.actuator.study import ANNEX, G_MATHCAD

T = np.linspace(0.0, 1.0, 1000)
CYCLE = np.linspace(0.0, 1.0, 101)
ROUTES = {"lagrange": lagrange_force, "kane": kane_force, "virtual power": virtual_power_force}


@cache
def sympy_force():
    """Q(a, a_dot, a_ddot) by SymPy's LagrangesMethod, lambdified for NumPy (the peer)."""
    import sympy as sp
    from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

    m, t = ANNEX, sp.Symbol("t")
    a = dynamicsymbols("a")
    L, d, beta = a + m.l, sp.sqrt(sp.Float(m.o2) ** 2 + m.o4**2), sp.atan2(m.o4, m.o2)
    th2 = sp.pi - beta - sp.acos((d**2 + L**2 - m.b**2) / (2 * d * L))
    th4 = sp.acos((d**2 + m.b**2 - L**2) / (2 * d * m.b)) - beta
    centres = [(m.g2 * sp.cos(th2), m.g2 * sp.sin(th2)),
               ((a + m.g3) * sp.cos(th2), (a + m.g3) * sp.sin(th2)),
               (-m.o2 + m.g4 * sp.cos(th4), m.o4 + m.g4 * sp.sin(th4))]
    bodies = zip((m.m2, m.m3, m.m4), m.inertias, centres, (th2, th2, th4))
    lagrangian = 0
    for mass, inertia, (x, y), angle in bodies:
        speed2 = x.diff(t) ** 2 + y.diff(t) ** 2
        lagrangian += mass * speed2 / 2 + inertia * angle.diff(t) ** 2 / 2 - mass * G_MATHCAD * y
    force = LagrangesMethod(lagrangian, [a]).form_lagranges_equations()[0]
    rates = sp.symbols("a a_dot a_ddot")
    plain = force.subs({a.diff(t, 2): rates[2], a.diff(t): rates[1]}).subs(a, rates[0])
    return sp.lambdify(rates, plain, "numpy")


@pytest.mark.parametrize("route", ROUTES)
def test_force_1000_instants(benchmark, route):
    q = benchmark(lambda: ROUTES[route](kinematics(ANNEX, T)))
    assert q.shape == T.shape


def test_force_1000_instants_sympy_peer(benchmark):
    force = sympy_force()
    q = benchmark(force, *ANNEX.stroke(T))
    np.testing.assert_allclose(q, lagrange_force(kinematics(ANNEX, T)), rtol=0, atol=1e-9)


def prescribed(s):
    return lagrange_force(kinematics(ANNEX, s))


def test_forward_dynamics_one_cycle(benchmark):
    a0, v0, _ = ANNEX.stroke(0.0)
    motion = benchmark.pedantic(forward_dynamics, args=(ANNEX, prescribed, CYCLE, a0, v0),
                                rounds=5, warmup_rounds=1)
    assert np.max(np.abs(motion.a - ANNEX.stroke(CYCLE)[0])) < 2e-9


def test_forward_dynamics_one_cycle_scipy_peer(benchmark):
    from scipy.integrate import solve_ivp

    def rate(time, y):
        terms = lagrange_terms(stroke_kinematics(ANNEX, y[0], y[1]))
        acc = (prescribed(time) - 0.5 * terms.mass_slope * y[1] ** 2 - terms.potential_slope)
        return [y[1], float(acc / terms.mass)]

    a0, v0, _ = ANNEX.stroke(0.0)
    solution = benchmark.pedantic(
        solve_ivp, args=(rate, (0.0, 1.0), [a0, v0]),
        kwargs=dict(method="RK45", t_eval=CYCLE, rtol=1e-10, atol=1e-12),
        rounds=5, warmup_rounds=1)
    assert np.max(np.abs(solution.y[0] - ANNEX.stroke(CYCLE)[0])) < 2e-9
