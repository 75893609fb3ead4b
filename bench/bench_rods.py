"""Benchmarks of Chapter 3 (study 001): one rod by shooting, by the closed form, and by peers.

Each pair runs the package and a peer in the same process, at the same accuracy, and the
module prints the ratios (package time over peer time, minimum over rounds) at its end:

* **shooting against collocation**: a cantilever under a transverse tip load
  ``P L^2 / EI = 0.1 ... 15`` and the pinned rod through that cantilever's tip, each from its
  default start, on the fewest RK4 nodes that bring the tip within ``1e-10 L`` of the exact
  rod; ``scipy.integrate.solve_bvp`` on the same problem with the loosest tolerance that does
  the same (a pinned rod's error is backward: its ``(m0, n)`` integrated exactly, tip and
  ``m(L)``). Target: ratio <= 1.
* **the same shooting on plain floats**: ``shoot_cantilever`` (41 nodes) against twenty lines of
  RK4 and Newton on Python floats (what is left is input checks, the closed-form start and
  Newton's bookkeeping).
* **the closed-form tip**: ``cantilever(..., nodes=2)`` against the textbook closed form of
  Bisshopp and Drucker (Brent's method on ``K(k) - F(phi1, k) = sqrt(P L^2 / EI)``, then the
  tip). Target: ratio <= 2.
* **one rod's sweep**: ``rods.integrate`` of one rod (RK4 on Python floats) against the
  package's vectorised sweep on a batch of one (numpy).
* **every equilibrium through a point**: ``rods.pinned_equilibria`` at the thesis's point
  (EI = L = 1, tip (0.8, 0.1), modes 1 to 3: nine equilibria, five of them looped) against
  MINPACK's ``hybr`` (``scipy.optimize.root``) from every cell of a 12 x 12 grid of the same
  regular chart per mode, the coarsest uniform grid from which it finds all nine. Both must
  return the same nine rods.

Run with ``make bench``, or ``pytest bench/bench_rods.py -o python_files='bench_*.py'
--benchmark-only``. Timings on a shared machine are noisy: compare ratios from one run.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_bvp
from scipy.optimize import brentq, root
from scipy.special import ellipe, ellipeinc, ellipk, ellipkinc

from mechnum import rods
from mechnum.rods import _regular as regular
from mechnum.rods import _rod as rod_module

EI, L = 1.0, 1.0
TOL = 1e-10                       # the accuracy every contender must reach (tip, over L)
# per load: RK4 nodes of the cantilever and of the pinned rod, and solve_bvp's tolerances for
# both, each the least that reaches TOL (asserted below, so a change cannot hide)
CASES = {0.1: (33, 33, 1e-8, 1e-5), 1.0: (101, 105, 3e-8, 3e-8), 5.0: (197, 273, 3e-8, 3e-8),
         10.0: (249, 441, 3e-7, 3e-8), 15.0: (289, 609, 3e-7, 1e-8)}
RESULTS = {}


@pytest.fixture(scope="module", autouse=True)
def ratios(request):
    """Print package time over peer time for every pair measured, at the module's end."""
    yield
    lines = ["", "bench_rods: time of mechnum / time of the peer (minimum over rounds)"]
    for (what, case), times in sorted(RESULTS.items()):
        if {"mechnum", "peer"} <= set(times):
            ours, peer = times["mechnum"], times["peer"]
            load = f"PL2/EI = {case:g}" if case else ""
            lines.append(f"  {what:38} {load:>13}   {ours * 1e3:8.3f} ms / "
                         f"{peer * 1e3:8.3f} ms = {ours / peer:.2f}")
    with request.config.pluginmanager.getplugin("capturemanager").global_and_fixture_disabled():
        print("\n".join(lines))


def record(benchmark, what, case, who):
    RESULTS.setdefault((what, case), {})[who] = benchmark.stats.stats.min


def exact(alpha):
    return rods.cantilever(EI, L, [0.0, alpha], nodes=2)


def backward_error(m0, force, target):
    """The tip's distance from the target and ``m(L)`` (scaled) of ``(m0, n)`` integrated
    on 20000 RK4 steps (error below 1e-15): a pinned rod's backward error."""
    rod = rods.integrate(EI, L, m0, force, nodes=20001)
    return max(np.abs(rod.tip - target).max() / L,
               abs(rod.m[-1]) / (np.hypot(*force) * L + EI / L))


def linear_guess(s, P):
    """Linear beam theory for a transverse tip load ``P``: ``(x, y, theta, m)`` on ``s``."""
    return np.vstack((s, P * (s ** 2 / 2 - s ** 3 / 6), P * (s - s ** 2 / 2), P * (1 - s)))


def bvp_cantilever(alpha, tol):
    def f(s, y):
        return np.vstack((np.cos(y[2]), np.sin(y[2]), y[3] / EI, -alpha * np.cos(y[2])))

    def bc(ya, yb):
        return np.array([ya[0], ya[1], ya[2], yb[3]])

    s = np.linspace(0.0, L, 41)
    return solve_bvp(f, bc, s, linear_guess(s, alpha), tol=tol, max_nodes=100000)


def bvp_pinned(tip, tol):
    def f(s, y, p):
        return np.vstack((np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                          p[0] * np.sin(y[2]) - p[1] * np.cos(y[2])))

    def bc(ya, yb, p):
        return np.array([ya[0], ya[1], ya[2], yb[0] - tip[0], yb[1] - tip[1], yb[3]])

    s, P = np.linspace(0.0, L, 41), 3.0 * EI * tip[1] / L ** 3
    return solve_bvp(f, bc, s, linear_guess(s, P), p=[0.0, P], tol=tol, max_nodes=100000)


@pytest.mark.parametrize("alpha", CASES)
def test_cantilever_shooting(benchmark, alpha):
    nodes = CASES[alpha][0]
    res = benchmark(rods.shoot_cantilever, EI, L, [0.0, alpha], nodes=nodes)
    assert np.abs(res.rod.tip - exact(alpha).tip).max() <= TOL
    record(benchmark, "cantilever, tip to 1e-10", alpha, "mechnum")


@pytest.mark.parametrize("alpha", CASES)
def test_cantilever_solve_bvp(benchmark, alpha):
    res = benchmark(bvp_cantilever, alpha, CASES[alpha][2])
    assert res.status == 0 and np.abs(res.y[:2, -1] - exact(alpha).tip).max() <= TOL
    record(benchmark, "cantilever, tip to 1e-10", alpha, "peer")


@pytest.mark.parametrize("alpha", CASES)
def test_pinned_shooting(benchmark, alpha):
    tip = exact(alpha).tip
    res = benchmark(rods.shoot_pinned, EI, L, tip, nodes=CASES[alpha][1])
    assert backward_error(res.rod.clamp_moment, res.rod.force, tip) <= TOL
    record(benchmark, "pinned rod, tip to 1e-10", alpha, "mechnum")


@pytest.mark.parametrize("alpha", CASES)
def test_pinned_solve_bvp(benchmark, alpha):
    tip = exact(alpha).tip
    res = benchmark(bvp_pinned, tip, CASES[alpha][3])
    assert res.status == 0 and backward_error(res.y[3, 0], res.p, tip) <= TOL
    record(benchmark, "pinned rod, tip to 1e-10", alpha, "peer")


def plain_float_shooting(alpha, nodes):
    """Shooting for a transverse tip load on Python floats: RK4 on ``(x, y, theta, m)`` and
    the variational equations of ``d/d m0``, Newton from linear theory (``m0 = P L``)."""
    h, P = L / (nodes - 1), alpha * EI / L ** 2

    def f(t, m, dt, dm):
        return math.cos(t), math.sin(t), m / EI, -P * math.cos(t), dm / EI, P * math.sin(t) * dt

    m0 = P * L
    for _ in range(50):
        x = y = t = dt = 0.0
        m, dm = m0, 1.0
        for _ in range(nodes - 1):
            k1 = f(t, m, dt, dm)
            k2 = f(t + h / 2 * k1[2], m + h / 2 * k1[3], dt + h / 2 * k1[4], dm + h / 2 * k1[5])
            k3 = f(t + h / 2 * k2[2], m + h / 2 * k2[3], dt + h / 2 * k2[4], dm + h / 2 * k2[5])
            k4 = f(t + h * k3[2], m + h * k3[3], dt + h * k3[4], dm + h * k3[5])
            x, y, t, m, dt, dm = (v + h / 6 * (a + 2 * b + 2 * c + d) for v, a, b, c, d in
                                  zip((x, y, t, m, dt, dm), k1, k2, k3, k4))
        if abs(m) < 1e-13 * P * L:
            return x, y
        m0 -= m / dm
    raise RuntimeError("no convergence")


def test_overhead_shoot_cantilever(benchmark):
    res = benchmark(rods.shoot_cantilever, EI, L, [0.0, 1.0], nodes=41)
    assert np.abs(res.rod.tip - plain_float_shooting(1.0, 41)).max() < 1e-12
    record(benchmark, "shooting, 41 nodes, PL2/EI = 1", 0, "mechnum")


def test_overhead_plain_floats(benchmark):
    tip = benchmark(plain_float_shooting, 1.0, 41)
    assert abs(tip[1] - exact(1.0).tip[1]) < 3e-9
    record(benchmark, "shooting, 41 nodes, PL2/EI = 1", 0, "peer")


def textbook_tip(alpha):
    """Bisshopp and Drucker's closed form of a cantilever under a transverse tip load:
    ``K(k) - F(phi1, k) = sqrt(alpha)`` with ``sin(phi1) = 1 / (k sqrt 2)`` by Brent's method,
    then ``x / L = 2 k cos(phi1) / sqrt(alpha)`` and ``y / L = 1 - 2 (E(k) - E(phi1, k)) /
    sqrt(alpha)``."""
    lam = math.sqrt(alpha)

    def g(k):
        return ellipk(k * k) - ellipkinc(math.asin(1 / (k * math.sqrt(2))), k * k) - lam

    k = brentq(g, (1 + 1e-15) / math.sqrt(2), 1 - 1e-16, xtol=1e-16, rtol=8.9e-16)
    phi1 = math.asin(1 / (k * math.sqrt(2)))
    return (2 * k * math.cos(phi1) / lam,
            1 - 2 * (ellipe(k * k) - ellipeinc(phi1, k * k)) / lam)


@pytest.mark.parametrize("alpha", [0.1, 1.0, 5.0, 15.0])
def test_tip_closed_form(benchmark, alpha):
    rod = benchmark(rods.cantilever, EI, L, [0.0, alpha], nodes=2)
    assert np.abs(rod.tip - textbook_tip(alpha)).max() < 1e-14
    record(benchmark, "closed-form tip", alpha, "mechnum")


@pytest.mark.parametrize("alpha", [0.1, 1.0, 5.0, 15.0])
def test_tip_textbook(benchmark, alpha):
    tip = benchmark(textbook_tip, alpha)
    assert np.abs(np.array(tip) - exact(alpha).tip).max() < 1e-14
    record(benchmark, "closed-form tip", alpha, "peer")


def test_sweep_one_rod_on_floats(benchmark):
    rod = benchmark(rods.integrate, EI, L, 2.0, [0.0, 5.0], nodes=201)
    assert rod.x.shape == (201,)
    record(benchmark, "one rod, 200 RK4 steps (peer: numpy)", 0, "mechnum")


def test_sweep_one_rod_vectorised(benchmark):
    # the same sweep on numpy arrays of one rod: what a single rod cost before
    args = (np.ones(1), np.ones(1), np.full(1, 2.0), np.zeros(1), np.full(1, 5.0), np.zeros(1),
            201)
    x = benchmark(rod_module.sweep, *args, trig=np)[0]
    assert np.abs(np.concatenate(x) - rods.integrate(EI, L, 2.0, [0.0, 5.0], nodes=201).x
                  ).max() < 1e-13
    record(benchmark, "one rod, 200 RK4 steps (peer: numpy)", 0, "peer")


def test_closed_form_41_nodes(benchmark):
    rod = benchmark(rods.cantilever, EI, L, [0.0, 1.0], nodes=41)
    assert rod.x.shape == (41,)


def test_hundred_cantilevers_shot_in_one_batch(benchmark):
    forces = np.column_stack((np.zeros(100), np.linspace(0.1, 3.0, 100)))
    res = benchmark(rods.shoot_cantilever, EI, L, forces, nodes=41)
    assert res.newton.converged.all()


THESIS = np.array([0.8, 0.1])


def hybr_equilibria(point, modes=(1, 2, 3), cells=12):
    """Every root of ``tip(psi, t, mode) = point`` that MINPACK's hybr reaches from the centres
    of a ``cells x cells`` grid of the regular chart (``cells / 2`` values of ``|t|`` per
    sign), rows ``(psi, t, mode)``."""
    psi = (np.arange(cells) + 0.5) / cells * 2 * np.pi
    t = (np.arange(cells // 2) + 0.5) / (cells // 2) * regular.T_MAX
    found = []
    for mode in modes:
        roots = []
        for start in np.stack(np.meshgrid(psi, np.concatenate((-t, t))), -1).reshape(-1, 2):
            sign = np.sign(start[1])

            def f(z, sign=sign, mode=mode):
                if not (0 < z[0] < 2 * np.pi and 0 < z[1] * sign <= regular.T_MAX):
                    return [1e3, 1e3]             # outside the chart: far from any root
                return regular.closed_form(EI, L, z[0], z[1], mode, jacobian=False,
                                           check=False).tip - point

            r = root(f, start, method="hybr", tol=1e-13)
            if (r.success and np.abs(f(r.x)).max() < 1e-10
                    and not any(np.abs(r.x - z).max() < 1e-7 for z in roots)):
                roots.append(r.x)
        found += [(*z, mode) for z in roots]
    found = np.array(found)
    return found[np.lexsort((found[:, 1], found[:, 0], found[:, 2]))]


def same_nine(found):
    ours = rods.pinned_equilibria(EI, L, THESIS, chart="t")
    ours = ours[np.lexsort((ours[:, 1], ours[:, 0], ours[:, 2]))]
    assert found.shape == ours.shape == (9, 3)
    assert np.abs(found - ours).max() < 1e-9


def test_every_equilibrium_pinned_equilibria(benchmark):
    sols = benchmark.pedantic(rods.pinned_equilibria, args=(EI, L, THESIS), kwargs={"chart": "t"},
                              rounds=5, warmup_rounds=1)
    same_nine(sols[np.lexsort((sols[:, 1], sols[:, 0], sols[:, 2]))])
    record(benchmark, "every equilibrium through (0.8, 0.1)", 0, "mechnum")


def test_every_equilibrium_scipy_root(benchmark):
    found = benchmark.pedantic(hybr_equilibria, args=(THESIS,), rounds=2, warmup_rounds=0)
    same_nine(found)
    record(benchmark, "every equilibrium through (0.8, 0.1)", 0, "peer")
