"""Tests of mechnum.rods: RK4 shooting and the elliptic closed form of planar rods."""

import cmath

import mpmath
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from mechnum import rods
from mechnum.continuation import pseudo_arclength
from mechnum.errors import ConvergenceError, MechnumError
from mechnum.mechanisms.elastica import study as elastica
from mechnum.rods import NoEquilibriumError
from mechnum.rods import _rod as rod_module
from mechnum.rods import _shooting as shooting
from mechnum.rods._pinned import START_TOL

PI = np.pi
EPS = np.finfo(float).eps
EXAMPLES = settings(max_examples=200, deadline=None)


def polar(alpha, psi, EI=1.0, L=1.0):
    """The tip force of magnitude ``alpha EI / L**2`` at direction ``psi``."""
    return alpha * EI / L ** 2 * np.array([np.cos(psi), np.sin(psi)])


# --- RK4 sweeps -------------------------------------------------------------------------

def test_pure_moment_gives_a_circular_arc():
    EI, L, M = 2.0, 1.5, 3.0
    rod = rods.integrate(EI, L, M, [0.0, 0.0], nodes=201)
    kappa = M / EI
    assert_allclose(rod.x, np.sin(kappa * rod.s) / kappa, rtol=0, atol=1e-10)
    assert_allclose(rod.y, (1 - np.cos(kappa * rod.s)) / kappa, rtol=0, atol=1e-10)
    assert_allclose(rod.theta, kappa * rod.s, rtol=0, atol=1e-14)


def test_clamp_pose_rotates_and_translates_the_rod():
    a = rods.integrate(1.0, 1.0, 0.3, [0.2, 0.5])
    c, s = np.cos(0.7), np.sin(0.7)
    force = np.array([c * 0.2 - s * 0.5, s * 0.2 + c * 0.5])
    b = rods.integrate(1.0, 1.0, 0.3, force, theta0=0.7, origin=[1.0, -2.0])
    assert_allclose(b.x, 1.0 + c * a.x - s * a.y, rtol=0, atol=1e-13)
    assert_allclose(b.y, -2.0 + s * a.x + c * a.y, rtol=0, atol=1e-13)
    assert_allclose(b.m, a.m, rtol=0, atol=1e-13)


def test_float_sweep_equals_the_vectorised_sweep():
    # one rod takes the float sweep, a batch the numpy one: the same RK4 to rounding
    EI, L = np.array([0.7, 1.3]), np.array([1.2, 0.8])
    m0, force = np.array([0.4, -2.0]), np.array([[-1.1, 0.6], [3.0, -0.2]])
    batch = rods.integrate(EI, L, m0, force, theta0=[0.3, -0.1], nodes=101)
    for i in range(2):
        one = rods.integrate(EI[i], L[i], m0[i], force[i], theta0=[0.3, -0.1][i], nodes=101)
        for name in ("x", "y", "theta", "m"):
            assert_allclose(getattr(one, name), getattr(batch, name)[i], rtol=0, atol=1e-13)


def test_tip_jacobian_matches_central_differences():
    EI, L = 0.7, 1.2
    p = np.array([0.4, -1.1, 0.6])

    def tip(q):
        return rods.tip_jacobian(EI, L, q[0], q[1:])[0]

    _, J = rods.tip_jacobian(EI, L, p[0], p[1:])
    h = 1e-6
    fd = np.column_stack([(tip(p + h * e) - tip(p - h * e)) / (2 * h) for e in np.eye(3)])
    assert_allclose(J, fd, rtol=0, atol=1e-8)


def test_batch_broadcasts_like_separate_rods():
    forces = np.array([[0.0, 1.0], [-2.0, 0.5], [1.0, -1.0]])
    batch = rods.integrate([1.0, 2.0, 3.0], [1.0, 0.5, 2.0], [0.1, 0.2, 0.3], forces)
    for i, (EI, L, m0) in enumerate(zip([1.0, 2.0, 3.0], [1.0, 0.5, 2.0], [0.1, 0.2, 0.3])):
        one = rods.integrate(EI, L, m0, forces[i])
        assert_allclose(batch.x[i], one.x, rtol=0, atol=1e-15)
        assert_allclose(batch.s[i], one.s, rtol=1e-15)


def test_empty_batches_give_empty_results():
    assert rods.integrate(1.0, 1.0, np.zeros(0), np.zeros((0, 2))).x.shape == (0, 41)
    assert rods.tip_jacobian(1.0, 1.0, np.zeros(0), np.zeros((0, 2)))[1].shape == (0, 4, 3)
    assert rods.shoot_cantilever(1.0, 1.0, np.zeros((0, 2))).rod.tip.shape == (0, 2)
    assert rods.shoot_pinned(1.0, 1.0, np.zeros((0, 2))).rod.tip.shape == (0, 2)


@EXAMPLES
@given(st.floats(1e-3, 1e3), st.floats(1e-3, 1e2), st.floats(-1e3, 1e3), st.integers(2, 60),
       st.floats(-10.0, 10.0))
def test_pure_moment_sweep_follows_its_circle(EI, L, M, nodes, theta0):
    # with no force m is constant and theta = theta0 + M s / EI exactly, at any step count
    rod = rods.integrate(EI, L, M, [0.0, 0.0], theta0=theta0, nodes=nodes)
    assert rod.x.shape == (nodes,)
    assert_allclose(rod.m, M, rtol=1e-15)
    assert_allclose(rod.theta, theta0 + M * rod.s / EI, rtol=0,
                    atol=1e-12 * (abs(theta0) + abs(M) * L / EI) + 1e-300)
    # the chord never exceeds the length (an inextensible rod)
    assert np.hypot(*rod.tip) <= L * (1 + 1e-12)


@EXAMPLES
@given(st.floats(1e-2, 1e2), st.floats(1e-2, 1e1), st.floats(-50, 50), st.floats(-50, 50),
       st.floats(-50, 50))
@example(EI=0.01953125, L=0.828125, m0=22.0, nx=23.0, ny=10.0)  # d2 tip / d m0^2 = 3e5
def test_tip_jacobian_is_the_derivative_of_the_sweep(EI, L, m0, nx, ny):
    assume(max(abs(nx), abs(ny)) * L ** 2 / EI < 1e3)      # RK4 stays finite on 20 steps
    # checked against a complex step of the float sweep (one rod, Python's complex numbers)
    # against tip_jacobian's numpy sweep of complex copies: the same map, other arithmetic
    _, J = rods.tip_jacobian(EI, L, m0, [nx, ny], nodes=21)
    scale = np.abs(J).max() + 1.0
    # The two paths round differently (20 steps x 4 stages), and J itself moves with its
    # inputs: allow 100 eps of the change of J per unit relative change of each input.
    p = np.array([m0, nx, ny])
    moved = [p + 1e-7 * (1 + abs(p[k])) * np.eye(3)[k] for k in range(3)]
    moved = [rods.tip_jacobian(EI, L, q[0], q[1:], nodes=21)[1] for q in moved]
    roundoff = 100 * np.finfo(float).eps * sum(np.abs(M - J) for M in moved) / 1e-7
    h = 1e-30
    for j, q in enumerate(([m0 + 1j * h, nx, ny], [m0, nx + 1j * h, ny], [m0, nx, ny + 1j * h])):
        end = rod_module.sweep(EI, L, *q, 0.0, 21, trig=cmath, keep=False)
        gap = np.abs(np.array([v[0].imag / h for v in end]) - J[:, j])
        assert np.all(gap <= 1e-10 * (np.abs(J[:, j]) + scale) + roundoff[:, j])


# --- The closed form of the cantilever ---------------------------------------------------

def mp_cantilever(EI, L, force):
    """The study's closed form, (86) and (87) at the tip, in 60-digit arithmetic."""
    with mpmath.workdps(60):
        nx, ny = mpmath.mpf(force[0]), mpmath.mpf(force[1])
        psi = mpmath.atan2(ny, nx) % (2 * mpmath.pi)
        a, lam = mpmath.cos(psi / 2), mpmath.sqrt(mpmath.sqrt(nx ** 2 + ny ** 2) / EI)
        sign = 1 if a >= 0 else -1

        def k_of(u):     # |k| = |a| + (1 - |a|) u, the study's k_rel = u
            return sign * (abs(a) + (1 - abs(a)) * u)

        def lam_L(u):
            k = k_of(u)
            return mpmath.ellipf(mpmath.pi / 2, k ** 2) - mpmath.ellipf(mpmath.asin(a / k), k ** 2)

        lo, hi = mpmath.mpf(0), mpmath.mpf(1)
        for _ in range(250):
            lo, hi = ((lo + hi) / 2, hi) if lam_L((lo + hi) / 2) < lam * L else (lo, (lo + hi) / 2)
        k = k_of((lo + hi) / 2)
        phi1 = mpmath.asin(a / k)
        dE = mpmath.ellipe(mpmath.pi / 2, k ** 2) - mpmath.ellipe(phi1, k ** 2)
        A, dC = 2 * dE - lam * L, -mpmath.cos(phi1)
        x = -(mpmath.cos(psi) * A + 2 * k * mpmath.sin(psi) * dC) / lam
        y = -(mpmath.sin(psi) * A - 2 * k * mpmath.cos(psi) * dC) / lam
        return np.array([float(x), float(y)]), float(2 * EI * k * lam * mpmath.cos(phi1))


@pytest.mark.parametrize("alpha", [1e-12, 1e-3, 1.0, 50.0, 300.0, 1e3, 1e4])
@pytest.mark.parametrize("psi", [PI / 2, 2.5, 0.3, 3.1, 4.0, 6.2])
def test_closed_form_holds_every_digit_at_every_load(alpha, psi):
    # the study's formulas lose the small loads (3.3e-13 came out 2.2e-10 at 1e-12) and the
    # large ones (every load above 323 gave the rod of 323): here, rounding only
    force = polar(alpha, psi)
    tip, m0 = mp_cantilever(1.0, 1.0, force)
    rod = rods.cantilever(1.0, 1.0, force, nodes=2)
    assert_allclose(rod.tip, tip, rtol=0, atol=4 * EPS)
    assert_allclose(rod.clamp_moment, m0, rtol=1e-13)
    assert_allclose(rod.force, force, rtol=0)


def test_small_loads_are_linear_beam_theory():
    EI, L = 3.0, 2.0
    for P in (1e-200, 1e-12, 1e-9):
        rod = rods.cantilever(EI, L, [0.0, P], nodes=2)
        assert_allclose(rod.tip, [L, P * L ** 3 / (3 * EI)], rtol=1e-12)
        assert_allclose(rod.clamp_moment, P * L, rtol=1e-12)


@pytest.mark.parametrize("psi", [1.0, 2.5, 4.0, 5.5])
def test_small_oblique_loads_keep_their_digits(psi):
    # a tiny load at an angle: the tip deflection is not the difference of the rotated
    # positions along and across the force (that gave y with 85 % error at alpha = 1e-14)
    EI, L, alpha = 2.0, 0.5, 1e-14
    force = polar(alpha, psi, EI, L)
    rod = rods.cantilever(EI, L, force, nodes=3)
    P = force[1]
    assert rod.tip[0] <= L
    assert_allclose(rod.tip[1], P * L ** 3 / (3 * EI), rtol=1e-13)   # beam theory, to O(alpha)
    assert_allclose(rod.theta[-1], P * L ** 2 / (2 * EI), rtol=1e-13)


def test_large_loads_follow_the_force():
    # a transverse load P: beyond a boundary layer of length 1 / lambda at the clamp
    # (lambda = sqrt(P / EI)) the rod lies along the force, and up to terms exp(-lambda L)
    # the tip is (sqrt(2), lambda L - 2 + sqrt(2)) / lambda (the clamp turns it by 90 degrees)
    for alpha in (1e3, 1e4, 1e5):
        rod = rods.cantilever(1.0, 1.0, [0.0, alpha], nodes=2)
        lam = np.sqrt(alpha)
        assert_allclose(rod.force, [0.0, alpha], rtol=0)
        assert_allclose(rod.tip * lam, [np.sqrt(2), lam - 2 + np.sqrt(2)], rtol=1e-13)
        assert np.hypot(*rod.tip) <= 1.0


def test_load_beyond_double_precision_is_a_named_error():
    with pytest.raises(ValueError, match="beyond the loads that the closed form represents"):
        rods.cantilever(1.0, 1.0, [0.0, 1e6])


@EXAMPLES
@given(st.floats(-200.0, 4.9), st.floats(0.0, 2 * PI), st.floats(1e-3, 1e3),
       st.floats(1e-3, 1e2), st.integers(2, 41))
def test_closed_form_cantilever_is_an_equilibrium(log_alpha, psi, EI, L, nodes):
    force = polar(10.0 ** log_alpha, psi, EI, L)
    assume(force[1] != 0)
    rod = rods.cantilever(EI, L, force, nodes=nodes)
    assert rod.x.shape == (nodes,) and np.all(np.isfinite(rod.x + rod.y + rod.theta + rod.m))
    assert np.hypot(*rod.tip) <= L * (1 + 4 * EPS)          # inextensible
    assert rod.m[-1] == 0 and rod.theta[0] == 0              # free tip, clamp along +x
    # the moment balance of the whole rod, m(0) = n_y x(L) - n_x y(L), which the closed form
    # does not use
    moment = np.hypot(*force) * L
    assert_allclose(rod.clamp_moment, force[1] * rod.x[-1] - force[0] * rod.y[-1], rtol=0,
                    atol=64 * EPS * moment)
    if 10.0 ** log_alpha < 1e-9:        # linear beam theory, to its own O(alpha**2)
        assert_allclose(rod.tip, [L, force[1] * L ** 3 / (3 * EI)], rtol=0,
                        atol=8 * EPS * L + L * 10.0 ** (2 * log_alpha))


@EXAMPLES
@given(st.floats(-3.0, 1.2), st.floats(0.01, 2 * PI - 0.01))
def test_closed_form_shape_is_the_rk4_shape(log_alpha, psi):
    force = polar(10.0 ** log_alpha, psi)
    a = rods.cantilever(1.0, 1.0, force, nodes=11)
    b = rods.integrate(1.0, 1.0, a.clamp_moment, force, nodes=401)   # RK4 from its m0
    for name in ("x", "y", "theta"):
        assert_allclose(getattr(a, name), getattr(b, name)[::40], rtol=0, atol=1e-7)


@pytest.mark.parametrize("alpha", [0.1, 1.0, 3.0, 10.0])
@pytest.mark.parametrize("direction", [PI / 2, 2.5, 4.0, -0.3])
def test_shooting_and_closed_form_agree(alpha, direction):
    EI, L = 1.3, 0.9
    force = polar(alpha, direction, EI, L)
    a = rods.cantilever(EI, L, force, "elliptic", nodes=1601)
    b = rods.cantilever(EI, L, force, "shooting", nodes=1601)
    for name in ("x", "y", "theta"):
        assert_allclose(getattr(a, name), getattr(b, name), rtol=0, atol=1e-10, err_msg=name)
    assert_allclose(a.m, b.m, rtol=0, atol=1e-10 * alpha * EI / L)


def test_shooting_stays_on_the_closed_form_branch_at_large_loads():
    # issue: 201 nodes at P L^2/EI = 100 used to return another equilibrium
    a = rods.cantilever(1.0, 1.0, [0.0, 100.0], nodes=201)
    b = rods.cantilever(1.0, 1.0, [0.0, 100.0], "shooting", nodes=201)
    assert_allclose(b.tip, a.tip, rtol=0, atol=1e-7)


def test_shooting_from_the_default_start_takes_one_step():
    for alpha in (0.1, 1.0, 5.0, 15.0):
        res = rods.shoot_cantilever(1.0, 1.0, [0.0, alpha], nodes=201)
        assert res.newton.iterations <= 1
        assert_allclose(res.start, rods.cantilever(1.0, 1.0, [0.0, alpha]).clamp_moment,
                        rtol=1e-15)


def test_shooting_recovers_from_a_start_beyond_a_hump():
    # m(L) has a local maximum between 0.6 P L and the root: damped Newton stalls there, and
    # the search for the nearest sign change takes over
    res = rods.shoot_cantilever(1.0, 1.0, [0.0, 10.0], m0=6.0, nodes=201)
    assert_allclose(res.rod.tip, rods.cantilever(1.0, 1.0, [0.0, 10.0]).tip, rtol=0,
                    atol=1e-7)
    with pytest.raises(ConvergenceError):
        rods.shoot_cantilever(1.0, 1.0, [0.0, 10.0], m0=6.0, nodes=201, damping=False)


def test_the_start_selects_the_equilibrium_above_the_euler_load():
    EI, L = 1.3, 0.9
    force = polar(10.0, 4.0, EI, L)
    grows = rods.cantilever(EI, L, force, "elliptic")
    other = rods.shoot_cantilever(EI, L, force, m0=0.0).rod       # bends up, against n_y < 0
    assert grows.tip[1] < 0 < other.tip[1]
    assert abs(other.m[-1]) < 1e-12
    assert rods.elliptic_parameters(EI, L, grows.clamp_moment, grows.force)[1] < 0
    assert rods.elliptic_parameters(EI, L, other.clamp_moment, other.force)[1] > 0


def test_axial_force_leaves_the_rod_straight_and_a_slight_tilt_follows_beam_column_theory():
    # compression below the Euler load: shooting from a bent start returns to the straight rod
    res = rods.shoot_cantilever(1.0, 1.0, [-1.0, 0.0], m0=0.3)     # Euler: 2.47 N
    assert abs(res.rod.clamp_moment) < 1e-12 and np.abs(res.rod.y).max() < 1e-12
    # a transverse force eps with the axial force N: v = eps (tan(bL) - bL) / (b**3 EI),
    # b = sqrt(N / EI); the closed form (not the straight-rod branch) gives it
    EI, L, N, eps = 1.0, 2.0, 0.4, 1e-9
    b = np.sqrt(N / EI)
    rod = rods.cantilever(EI, L, [-N, eps], "elliptic", nodes=2)
    assert_allclose(rod.tip[1], eps * (np.tan(b * L) - b * L) / (b ** 3 * EI), rtol=1e-6,
                    atol=8 * EPS * L)      # the rounding of a coordinate of size L


def test_shooting_resolves_stiff_rods_to_its_rounding_floor():
    # at lambda L = 10 rounding in m0 reaches m(L) multiplied by about 1e4: the residual
    # criterion accounts for it instead of failing
    res = rods.shoot_cantilever(1.0, 1.0, [0.0, 100.0], nodes=2001)
    assert res.newton.converged
    # 20 RK4 steps of lambda h = 5 amplify by some 65 each: nothing is left to resolve
    with pytest.raises(ConvergenceError, match="single shooting cannot resolve"):
        rods.shoot_cantilever(1.0, 1.0, [0.0, 1e4], nodes=21)


@EXAMPLES
@given(st.floats(-6.0, 1.2), st.floats(0.0, 2 * PI), st.floats(0.1, 10.0))
def test_shoot_cantilever_converges_from_its_default_start(log_alpha, psi, EI):
    force = polar(10.0 ** log_alpha, psi, EI)
    assume(force[1] != 0)
    res = rods.shoot_cantilever(EI, 1.0, force, nodes=61)
    exact = rods.cantilever(EI, 1.0, force, nodes=61)
    assert res.newton.iterations <= 2
    assert_allclose(res.rod.tip, exact.tip, rtol=0, atol=1e-6)       # RK4 on 60 steps
    assert abs(res.rod.m[-1]) <= 1e-12 * max(np.hypot(*force), EI)


def test_batch_shooting_equals_single():
    forces = np.array([[0.0, 1.0], [-0.5, 2.0]])
    batch = rods.shoot_cantilever(1.0, 1.0, forces)
    for i, f in enumerate(forces):
        assert_allclose(batch.rod.tip[i], rods.shoot_cantilever(1.0, 1.0, f).rod.tip,
                        rtol=0, atol=1e-12)


# --- The closed form of the study: k_rel and modes ----------------------------------------

@pytest.mark.parametrize("mode", [1, 2, 3])
def test_euler_critical_loads(mode):
    # cantilever in compression: P_cr = (2 q - 1)^2 pi^2 EI / (4 L^2) (Timoshenko and Gere)
    EI, L = 2.0, 3.0
    rod = rods.clamped_pinned(EI, L, PI, 1e-6, mode)
    euler = (2 * mode - 1) ** 2 * PI ** 2 * EI / (4 * L ** 2)
    assert_allclose(rod.R, euler, rtol=1e-9)


@pytest.mark.parametrize("alpha, u, v", elastica.MATTIASSON.tolist())   # five digits
@pytest.mark.parametrize("method", ["elliptic", "shooting"])
def test_large_deflection_cantilever_table(alpha, u, v, method):
    rod = rods.cantilever(1.0, 1.0, [0.0, alpha], method, nodes=801)
    assert abs(1 - rod.tip[0] - u) <= 5e-6 and abs(rod.tip[1] - v) <= 5e-6


def test_closed_form_shape_ends_where_its_tip_is():
    rod = rods.clamped_pinned(1.0, 1.0, [1.0, 4.0], [-0.6, 0.3], [2, 1], nodes=51)
    assert_allclose(rod.rod.tip, rod.tip, rtol=0, atol=1e-13)
    assert_allclose(rod.rod.m[..., -1], 0.0, rtol=0, atol=1e-12)
    assert_allclose(rod.rod.theta[..., 0], 0.0, rtol=0, atol=1e-7)
    assert_allclose(rod.rod.m[..., 0], rod.clamp_moment, rtol=0, atol=1e-13)


def test_force_near_k_min_keeps_its_digits():
    # tiny k_rel: arcsin(cos(psi/2)/k) would lose half the digits of phi1, hence of R
    kr = 1e-10
    _k, kmin = rods.elliptic_k(PI / 2, kr)
    with mpmath.workdps(40):
        kk = mpmath.mpf(kmin) + (1 - mpmath.mpf(kmin)) * mpmath.mpf(kr)
        p1 = mpmath.asin(mpmath.mpf(kmin) / kk)     # the same float cos(psi/2)
        R = float((mpmath.ellipf(PI / 2, kk ** 2) - mpmath.ellipf(p1, kk ** 2)) ** 2)
    assert_allclose(rods.clamped_pinned(1.0, 1.0, PI / 2, kr).R, R, rtol=1e-10)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.05, 2 * PI - 0.05), st.floats(0.01, 0.99), st.integers(1, 3),
       st.sampled_from([-1.0, 1.0]))
def test_elliptic_parameters_invert_the_closed_form(psi, k_abs, mode, sign):
    rod = rods.clamped_pinned(1.0, 1.0, psi, sign * k_abs, mode)
    p, k_rel, m, phi2 = rods.elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    assert_allclose([p, k_rel, phi2], [psi, sign * k_abs, (mode - 0.5) * PI], rtol=0,
                    atol=1e-7)
    assert m == mode


@EXAMPLES
@given(st.floats(0.001, 2 * PI - 0.001), st.floats(1e-6, 1 - 1e-6), st.integers(1, 3),
       st.floats(1e-3, 1e3), st.floats(1e-2, 1e2))
def test_k_rel_for_force_inverts_the_closed_form(psi, k_abs, mode, EI, L):
    k_rel = np.copysign(k_abs, np.cos(psi / 2))
    R = rods.clamped_pinned(EI, L, psi, k_rel, mode).R
    found = rods.k_rel_for_force(EI, L, psi, R, mode)
    # the study's chart loses relative digits of R like eps / (1 - |k_rel|), and its elliptic
    # integrals like eps / (1 - k_min**2) near pure tension: compare in R
    assert_allclose(rods.clamped_pinned(EI, L, psi, found, mode).R, R,
                    rtol=1e-11 / (1 - k_abs) + 1e-11 / k_abs + 1e-14 / np.sin(psi / 2) ** 2)


@EXAMPLES
@given(st.floats(0.001, 2 * PI - 0.001), st.floats(-300.0, 3.0), st.integers(1, 3))
def test_k_rel_for_force_answers_or_names_the_limit(psi, log_R, mode):
    try:
        k_rel = rods.k_rel_for_force(1.0, 1.0, psi, 10.0 ** log_R, mode)
    except NoEquilibriumError as error:    # below the least load of a higher mode
        assert mode > 1 or abs(psi - PI) < 1e-3, error
        return
    except ValueError as error:            # k_rel rounds to +-1 or underflows
        assert "not representable" in str(error)
        return
    assert 0 < abs(k_rel) < 1 and np.sign(k_rel) == np.sign(np.cos(psi / 2))


def test_k_rel_for_force_refuses_what_its_chart_cannot_hold():
    with pytest.raises(ValueError, match="not representable"):    # k_rel rounds to 1
        rods.k_rel_for_force(1.0, 1.0, PI / 2, 1e3)
    with pytest.raises(ValueError, match="not representable"):    # k_rel underflows
        rods.k_rel_for_force(1.0, 1.0, PI / 2, 1e-320)


def test_load_below_a_modes_range_has_no_equilibrium():
    with pytest.raises(NoEquilibriumError, match="mode 2 needs R >"):
        rods.k_rel_for_force(1.0, 1.0, 1.0, 0.5, mode=2)


# --- Pinned rods ----------------------------------------------------------------------------

def test_pinned_shooting_finds_the_closed_form_equilibria():
    # every equilibrium that single shooting resolves on 800 steps (lambda L + 4 ln(lambda h)
    # below the solvers' RISK; not the rod looped in the strongest tension): shot from a
    # start 0.1 % off, the same rod (the looped rod, in tension, is lost from 1 % off)
    EI, L, tip = 0.5, 1.0, np.array([0.6, 0.3])
    sols = rods.pinned_equilibria(EI, L, tip, modes=(1, 2))
    closed = rods.clamped_pinned(EI, L, sols[:, 0], sols[:, 1], sols[:, 2])
    lam_L = np.sqrt(closed.R / EI) * L
    mild = lam_L + 4 * np.log(lam_L / 800) < shooting.RISK
    assert sols[:, 2].tolist() == [1, 2, 2, 2, 2] and mild.tolist() == [1, 1, 1, 1, 0]
    # (k_rel rounded to a double moves the looped rod, 1 - |k_rel| = 1.4e-6, by eps / 1.4e-6)
    assert_allclose(closed.tip, np.broadcast_to(tip, closed.tip.shape), rtol=0, atol=1e-10)
    guesses = np.column_stack((closed.clamp_moment, closed.force))[mild]
    shot = rods.shoot_pinned(EI, L, np.tile(tip, (4, 1)), guesses * 1.001, nodes=801)
    # (the looped rod's rounding floor, lambda L = 12: some 1e-12)
    assert_allclose(shot.rod.tip, np.broadcast_to(tip, (4, 2)), rtol=0, atol=1e-11)
    assert_allclose(shot.rod.force, closed.force[mild], rtol=1e-7)


def test_pinned_equilibria_may_find_none():
    # no rod that bends one way only, not even one that loops, takes 1 m to (0.9, 0) (sampled:
    # Newton from each of 45,000 cells of the chart finds none either)
    sols = rods.pinned_equilibria(1.0, 1.0, [0.9, 0.0], modes=(1,))
    assert sols.shape == (0, 3)


@pytest.mark.parametrize("alpha", [0.1, 1.0, 5.0, 10.0, 15.0])
def test_pinned_default_start_reaches_the_mode_1_rod(alpha):
    # the point where a transverse load alpha EI / L**2 takes the cantilever's tip
    closed = rods.cantilever(1.0, 1.0, [0.0, alpha], nodes=2)
    res = rods.shoot_pinned(1.0, 1.0, closed.tip, nodes=201)
    assert res.newton.iterations <= 2
    assert_allclose(res.rod.force, [0.0, alpha], rtol=0, atol=1e-6 * alpha)
    assert_allclose(res.rod.tip, closed.tip, rtol=0, atol=1e-12)


@pytest.mark.parametrize("psi", [PI / 4, PI / 2, 3 * PI / 4, -PI / 2])
def test_pinned_default_start_converges_over_the_load_range(psi):
    # issue 17: for P L**2 / EI from 0.1 to 15, the default start is the closed-form cantilever
    # whose tip is at the point (its Newton converged: the tip within START_TOL, the clamp
    # moment that cantilever's), under the load that put the tip there; shooting then needs
    # a Newton step or two (the second for RK4's error on 41 nodes at large loads)
    EI, L = 2.0, 0.5
    for alpha in np.geomspace(0.1, 15.0, 13):
        force = polar(alpha, psi, EI, L)
        point = rods.cantilever(EI, L, force, nodes=2).tip
        res = rods.shoot_pinned(EI, L, point, nodes=41)
        closed = rods.cantilever(EI, L, res.start[1:], nodes=2)
        assert np.abs(closed.tip - point).max() <= START_TOL * L
        assert_allclose(res.start[0], closed.clamp_moment, rtol=1e-12)
        assert_allclose(res.start[1:], force, rtol=0, atol=1e-3 * alpha * EI / L ** 2)
        assert res.newton.converged and res.newton.iterations <= 2


@EXAMPLES
@given(st.floats(-1.0, np.log10(15.0)), st.floats(PI / 4, 3 * PI / 4),
       st.sampled_from([-1.0, 1.0]), st.floats(-PI, PI))
def test_pinned_default_start_on_mode_1_points(log_alpha, psi, side, theta0):
    # a point that a mode-1 cantilever reaches under a load from 0.1 to 15 EI / L**2 within 45
    # degrees of transverse, with the clamp turned by theta0: the default start finds that rod
    # (near-tension points close to the reach L are ill-conditioned: no such promise there)
    force = polar(10.0 ** log_alpha, side * psi)
    local = rods.cantilever(1.0, 1.0, force, nodes=2)
    c, s = np.cos(theta0), np.sin(theta0)
    point = np.array([[c, -s], [s, c]]) @ local.tip
    res = rods.shoot_pinned(1.0, 1.0, point, theta0=theta0, nodes=41)
    assert_allclose(res.rod.tip, point, rtol=0, atol=1e-12)
    assert_allclose(res.rod.clamp_moment, local.clamp_moment, rtol=1e-4, atol=1e-6)


def test_pinned_batch_equals_single():
    points = np.array([[0.9, 0.3], [0.5, -0.6]])
    batch = rods.shoot_pinned(1.0, 1.0, points, nodes=61)
    for i, point in enumerate(points):
        one = rods.shoot_pinned(1.0, 1.0, point, nodes=61)
        assert_allclose(batch.rod.force[i], one.rod.force, rtol=1e-9, atol=1e-9)


def test_plain_and_damped_newton_from_the_same_start():
    # from this start plain Newton leaps to a mode-8 rod; damping keeps it near: mode 2
    EI, tip, guess = 0.1649, [0.8, 0.1], [0.1, 0.1, 0.1]
    modes = [rods.elliptic_parameters(EI, 1.0, r.clamp_moment, r.force)[2]
             for r in (rods.shoot_pinned(EI, 1.0, tip, guess, nodes=61, damping=d).rod
                       for d in (False, True))]
    assert modes == [8, 2]


def test_multiple_shooting_follows_the_sketch():
    # the two mode-2 rods through the thesis's point: the S-shape of the sketch decides
    s = np.linspace(0.0, 1.0, 61)
    found = []
    for bulge in (-0.15, 0.15):
        y = 0.1 * s + bulge * np.sin(PI * s)
        sketch = rods.Rod(s, 0.8 * s, y, np.arctan2(np.gradient(y, s), 0.8), np.zeros(61),
                          np.array([0.1, 0.1]))
        rod = rods.shoot_pinned_multiple(1.0, 1.0, [0.8, 0.1], sketch, segments=6).rod
        assert_allclose(rod.tip, [0.8, 0.1], rtol=0, atol=1e-10)
        assert abs(rod.m[-1]) < 1e-9
        found.append(rods.elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)[1:3])
    (k_down, mode_down), (k_up, mode_up) = found
    assert mode_down == mode_up == 2 and k_down < 0 < k_up


def test_multiple_shooting_with_one_segment_is_plain_shooting():
    closed = rods.cantilever(1.0, 1.0, [0.3, 2.0], nodes=41)
    guess = rods.integrate(1.0, 1.0, 1.02 * closed.clamp_moment, 1.02 * closed.force, nodes=41)
    multi = rods.shoot_pinned_multiple(1.0, 1.0, closed.tip, guess, segments=1).rod
    plain = rods.shoot_pinned(1.0, 1.0, closed.tip, nodes=41).rod
    assert_allclose(multi.force, plain.force, rtol=1e-8)
    assert_allclose(multi.x, plain.x, rtol=0, atol=1e-10)


@settings(max_examples=200, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(0.5, 2.6), st.integers(2, 6))
def test_multiple_shooting_from_a_nearby_shape(log_alpha, psi, segments):
    # a shape 5 % off the closed form's: every segment count finds the closed-form rod
    force = polar(10.0 ** log_alpha, psi)
    closed = rods.cantilever(1.0, 1.0, force, nodes=25)
    guess = rods.Rod(closed.s, closed.x, closed.y, 1.05 * closed.theta, 1.05 * closed.m,
                     1.05 * closed.force)
    rod = rods.shoot_pinned_multiple(1.0, 1.0, closed.tip, guess, segments=segments).rod
    assert_allclose(rod.force, force, rtol=1e-4, atol=1e-4)


# --- Bad input --------------------------------------------------------------------------

SKETCH = rods.Rod(np.linspace(0, 1, 5), np.linspace(0, 0.8, 5), np.zeros(5), np.zeros(5),
                  np.zeros(5), np.array([0.1, 0.1]))


@pytest.mark.parametrize("call, match", [
    (lambda: rods.integrate(-1.0, 1.0, 0.0, [0, 1]), "EI must be positive"),
    (lambda: rods.integrate(1.0, 0.0, 0.0, [0, 1]), "L must be positive"),
    (lambda: rods.integrate(1.0, 1.0, np.nan, [0, 1]), "m0 must be finite"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1, 2]), "last axis of length 2"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1j]), "force must be real"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1], nodes=1), "nodes must be an integer >= 2"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1], nodes=np.inf), "nodes must be an integer"),
    (lambda: rods.integrate(1.0, 1.0, [0.0, 1.0, 2.0], [[0, 1], [1, 0]]), "broadcast"),
    (lambda: rods.tip_jacobian(1.0, 1.0, 0.0, [0, 1], origin=[0.0]), "origin must have"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [[[0, 1]]]), "shape \\(2,\\) or \\(batch, 2\\)"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [0, 1], tol=-1), "tol must be positive"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [0, 1], maxiter=0), "maxiter must be"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [0, 1], m0=[1.0, 2.0]), "broadcast"),
    (lambda: rods.shoot_cantilever([1.0, 2.0], 1.0, [0, 1]), "EI must have 0 dimension"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [1.0, 0.5]), "farther than L"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [0.5, 0.5], [0, 0]), "seed must have a last axis"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [0.5, np.nan]), "tip must be finite"),
    (lambda: rods.shoot_pinned_multiple(1.0, 1.0, [0.5, 0.5], "line"), "seed must be a Rod"),
    (lambda: rods.shoot_pinned_multiple(1.0, 2.0, [0.5, 0.5], SKETCH), "equally spaced"),
    (lambda: rods.shoot_pinned_multiple(1.0, 1.0, [0.5, 0.5], SKETCH, segments=5), "at most"),
    (lambda: rods.shoot_pinned_multiple(1.0, 1.0, [1.5, 0.5], SKETCH), "farther than L"),
    (lambda: rods.cantilever(1.0, 1.0, [0, 1], "euler"), "method must be one of"),
    (lambda: rods.cantilever(1.0, 1.0, [0, 1], nodes=1), "nodes must be an integer >= 2"),
    (lambda: rods.cantilever(1.0, 1.0, [0, np.inf]), "force must be finite"),
    (lambda: rods.cantilever(1.0, 1.0, [[0, 1]]), "force must have shape \\(2,\\)"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 0.0, 0.5), "psi must lie"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 2 * PI, 0.5), "psi must lie"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.0), "k_rel must satisfy"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 1.0), "k_rel must satisfy"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.5, mode=0), "mode must be"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.5, mode=1.5), "mode must be"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.5, nodes=1), "nodes must be an integer"),
    (lambda: rods.k_rel_for_force(1.0, 1.0, 1.0, 0.0), "R must be positive"),
    (lambda: rods.k_rel_for_force(1.0, 1.0, 1.0, 1.0, tol=np.nan), "tol must be finite"),
    (lambda: rods.k_rel_for_force(1.0, 1.0, 1.0, 1.0, maxiter=0.5), "maxiter must be"),
    (lambda: rods.elliptic_parameters(1.0, 1.0, 0.1, [0.0, 0.0]), "must not be zero"),
    (lambda: rods.elliptic_parameters(1.0, 1.0, 0.0, [2.0, 0.0]), "pure tension"),
    (lambda: rods.elliptic_parameters(0.0, 1.0, 0.0, [2.0, 1.0]), "EI must be positive"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [1.2, 0.0]), "closer than L"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [0.5, 0.0], n_psi=0), "n_psi must be"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [0.5, 0.0], n_k=0), "n_k must be"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [0.5, 0.0], tol=-1.0), "tol must be positive"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [0.5, 0.0], modes=(0,)), "mode must be"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_newton_that_cannot_converge_raises_a_named_error():
    with pytest.raises(MechnumError):
        rods.shoot_cantilever(1.0, 1.0, [0.0, 50.0], m0=-60.0, maxiter=1)
    with pytest.raises(MechnumError):     # plain Newton leaps until RK4 overflows
        rods.shoot_pinned(1.0, 1.0, [0.8, 0.1], [0.1, 0.1, 0.1], maxiter=5, damping=False)
    with pytest.raises(ConvergenceError, match="did not converge in 2 iterations"):
        rods.shoot_pinned(0.1649, 1.0, [0.8, 0.1], [0.1, 0.1, 0.1], maxiter=2)


def test_equations_are_those_the_sweeps_integrate():
    force = np.array([-2.0, 1.5])
    f = rods.equations(1.3, force)
    sol = solve_ivp(f, (0.0, 0.9), [0.0, 0.0, 0.0, 0.4], rtol=1e-12, atol=1e-12)
    rod = rods.integrate(1.3, 0.9, 0.4, force, nodes=801)
    assert_allclose(sol.y[:, -1], [*rod.tip, rod.tip_angle, rod.m[-1]], rtol=0, atol=1e-10)
    states = np.random.default_rng(0).normal(size=(4, 7))     # solve_bvp's (4, k) layout
    assert_allclose(f(0.0, states)[3], force[0] * np.sin(states[2]) - force[1] *
                    np.cos(states[2]), rtol=1e-15)
    assert_allclose(f(0.0, states)[2], states[3] / 1.3, rtol=1e-15)


def test_dead_load_jacobian_is_the_derivative_of_its_equation():
    # central differences of fun (truncation ~1e-10 at this step) against the complex step
    load = rods.DeadLoad(0.7, 1.3, 2.5, segments=40)
    u = np.array([-1.1, 4.2])
    steps = 1e-5 * np.eye(2)
    central = np.column_stack([(load.fun(u + e) - load.fun(u - e)) / 2e-5 for e in steps])
    assert_allclose(load.jac(u), central, rtol=1e-8)


def test_imperfect_column_folds_at_the_closed_form_least_load():
    # a cantilever pushed nearly along its axis: the branch bent against the small transverse
    # component of the force exists only above a least load, where it folds; it is stable on
    # the side of large deflection and unstable on the nearly straight side
    psi = np.pi - 0.1
    load = rods.DeadLoad(1.0, 1.0, psi, segments=80)
    branch = pseudo_arclength(load.fun, load.start(-0.5), load.jac, direction=[0.0, -1.0],
                              step=0.2, max_step=0.5, steps=60, stop=lambda u: u[1] > 6)
    least = minimize_scalar(lambda k: rods.clamped_pinned(1.0, 1.0, psi, k).R,
                            bounds=(-0.99, -0.01), method="bounded",
                            options={"xatol": 1e-10}).fun
    assert branch.folds.size == 1
    assert_allclose(branch.fold_points[0, 1], least, rtol=1e-7)
    index = np.array([load.index(u) for u in branch.x])
    fold = branch.folds[0]
    assert np.all(index[:fold + 1] == 0) and np.all(index[fold + 1:] == 1)


# --- The package's structure --------------------------------------------------------------

def _same_subpackage(module, target):
    """Whether ``target`` belongs to ``module``'s subpackage (mechnum.rods, or the elastica
    mechanism), whose private names are its own."""
    home = ".".join(module.split(".")[:2 if module.startswith("mechnum.rods") else 3])
    return target.startswith(home + ".")


def _rods_imports():
    """``{module: set of mechnum.rods modules it imports}`` and every private name a module of
    mechnum.rods (or the elastica mechanism) takes from another module, by reading the code
    (imports inside functions included)."""
    import ast
    import pathlib

    root = pathlib.Path(rods.__file__).parent
    files = {f"mechnum.rods.{p.stem}": p for p in root.glob("*.py") if p.stem != "__init__"}
    for p in (root.parent / "mechanisms" / "elastica").glob("*.py"):
        files[f"mechnum.mechanisms.elastica.{p.stem}"] = p
    graph, private = {}, []
    for name, path in files.items():
        tree = ast.parse(path.read_text())
        aliases, graph[name] = {}, set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("mechnum"):
                for alias in node.names:
                    target = f"{node.module}.{alias.name}"
                    module = target if target in files else node.module
                    if module in files and module != name:
                        graph[name].add(module)
                    if (alias.name.startswith("_") and alias.name != "_validate"
                            and not _same_subpackage(name, target)):
                        private.append((name, target))
                    aliases[alias.asname or alias.name] = target
        for node in ast.walk(tree):   # module._private, for a module imported by name
            if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.attr.startswith("_") and not node.attr.startswith("__")
                    and aliases.get(node.value.id, "").startswith("mechnum.")
                    and node.value.id != "_validate"
                    and not _same_subpackage(name, aliases[node.value.id])):
                private.append((name, f"{aliases[node.value.id]}.{node.attr}"))
    return graph, private


def test_rods_modules_import_no_loop_and_no_private_name():
    graph, private = _rods_imports()
    assert private == []
    done, visiting = set(), []

    def visit(module):          # depth-first: a module met again on the current path is a loop
        assert module not in visiting, f"import loop: {visiting + [module]}"
        if module not in done:
            visiting.append(module)
            for other in graph.get(module, ()):
                visit(other)
            visiting.pop()
            done.add(module)

    for module in graph:
        visit(module)
    assert "mechnum.rods._shooting" not in graph["mechnum.rods._elliptic"]  # the old loop


def test_no_rods_module_exceeds_500_lines():
    import pathlib

    root = pathlib.Path(rods.__file__).parent
    sizes = {p.name: len(p.read_text().splitlines()) for p in root.glob("*.py")}
    assert max(sizes.values()) <= 500, sizes
