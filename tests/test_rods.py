"""Tests of mechnum.rods: RK4 shooting and the elliptic closed form of planar rods."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum import rods
from mechnum.errors import ConvergenceError
from mechnum.rods import NoEquilibriumError

PI = np.pi


def test_pure_moment_gives_a_circular_arc():
    EI, L, M = 2.0, 1.5, 3.0
    rod = rods.integrate(EI, L, M, [0.0, 0.0], nodes=201)
    kappa = M / EI
    assert np.allclose(rod.x, np.sin(kappa * rod.s) / kappa, atol=1e-10)
    assert np.allclose(rod.y, (1 - np.cos(kappa * rod.s)) / kappa, atol=1e-10)
    assert np.allclose(rod.theta, kappa * rod.s, atol=1e-14)


def test_clamp_pose_rotates_and_translates_the_rod():
    a = rods.integrate(1.0, 1.0, 0.3, [0.2, 0.5])
    c, s = np.cos(0.7), np.sin(0.7)
    force = np.array([c * 0.2 - s * 0.5, s * 0.2 + c * 0.5])
    b = rods.integrate(1.0, 1.0, 0.3, force, theta0=0.7, origin=[1.0, -2.0])
    assert np.allclose(b.x, 1.0 + c * a.x - s * a.y, atol=1e-13)
    assert np.allclose(b.y, -2.0 + s * a.x + c * a.y, atol=1e-13)
    assert np.allclose(b.m, a.m, atol=1e-13)


def test_tip_jacobian_matches_finite_differences():
    EI, L = 0.7, 1.2
    p = np.array([0.4, -1.1, 0.6])

    def tip(q):
        return rods.tip_jacobian(EI, L, q[0], q[1:])[0]

    _, J = rods.tip_jacobian(EI, L, p[0], p[1:])
    h = 1e-6
    fd = np.column_stack([(tip(p + h * e) - tip(p - h * e)) / (2 * h) for e in np.eye(3)])
    assert np.allclose(J, fd, atol=1e-8)


def test_batch_broadcasts_like_separate_rods():
    forces = np.array([[0.0, 1.0], [-2.0, 0.5], [1.0, -1.0]])
    batch = rods.integrate([1.0, 2.0, 3.0], [1.0, 0.5, 2.0], [0.1, 0.2, 0.3], forces)
    for i, (EI, L, m0) in enumerate(zip([1.0, 2.0, 3.0], [1.0, 0.5, 2.0], [0.1, 0.2, 0.3])):
        one = rods.integrate(EI, L, m0, forces[i])
        assert np.allclose(batch.x[i], one.x, atol=1e-15) and np.allclose(batch.s[i], one.s)


@pytest.mark.parametrize("alpha", [0.1, 1.0, 3.0, 10.0])
@pytest.mark.parametrize("direction", [PI / 2, 2.5, 4.0, -0.3])
def test_shooting_and_closed_form_agree(alpha, direction):
    EI, L = 1.3, 0.9
    force = alpha * EI / L ** 2 * np.array([np.cos(direction), np.sin(direction)])
    a = rods.cantilever(EI, L, force, "elliptic", nodes=1601)
    # started 5 % off the closed form's clamp moment: a compressive load above the Euler load
    # has other equilibria, and the default guess may lead to one of them (next test)
    b = rods.shoot_cantilever(EI, L, force, m0=1.05 * a.clamp_moment, nodes=1601).rod
    for name in ("x", "y", "theta"):
        assert np.abs(getattr(a, name) - getattr(b, name)).max() < 1e-10, name
    assert np.abs(a.m - b.m).max() < 1e-10 * alpha * EI / L


def test_the_guess_selects_the_equilibrium_above_the_euler_load():
    EI, L = 1.3, 0.9
    force = 10 * EI / L ** 2 * np.array([np.cos(4.0), np.sin(4.0)])
    primary = rods.cantilever(EI, L, force, "elliptic")
    other = rods.shoot_cantilever(EI, L, force).rod       # bends up, against n_y < 0
    assert primary.tip[1] < 0 < other.tip[1]
    assert abs(other.m[-1]) < 1e-12
    assert rods.elliptic_parameters(EI, L, other.clamp_moment, other.force)[1] > 0


def test_small_load_limit_is_linear_beam_theory():
    EI, L, P = 3.0, 2.0, 1e-4
    rod = rods.cantilever(EI, L, [0.0, P], "elliptic")
    assert np.isclose(rod.tip[1], P * L ** 3 / (3 * EI), rtol=1e-6, atol=0)
    assert np.isclose(rod.tip_angle, P * L ** 2 / (2 * EI), rtol=1e-6, atol=0)


@pytest.mark.parametrize("mode", [1, 2, 3])
def test_euler_critical_loads(mode):
    # cantilever in compression: P_cr = (2 q - 1)^2 pi^2 EI / (4 L^2) (Timoshenko and Gere)
    EI, L = 2.0, 3.0
    rod = rods.clamped_pinned(EI, L, PI, 1e-6, mode)
    euler = (2 * mode - 1) ** 2 * PI ** 2 * EI / (4 * L ** 2)
    assert np.isclose(rod.R, euler, rtol=1e-9, atol=0)


# Mattiasson (1981), Table 1 (after Bisshopp and Drucker 1945): a cantilever under a transverse
# tip load P; horizontal shortening u/L and deflection v/L against P L^2 / EI
MATTIASSON = [(1.0, 0.05643, 0.30172), (2.0, 0.16064, 0.49346), (5.0, 0.38763, 0.71379),
              (10.0, 0.55500, 0.81061)]


@pytest.mark.parametrize("alpha, u, v", MATTIASSON)
@pytest.mark.parametrize("method", ["elliptic", "shooting"])
def test_large_deflection_cantilever_table(alpha, u, v, method):
    rod = rods.cantilever(1.0, 1.0, [0.0, alpha], method, nodes=801)
    assert abs(1 - rod.tip[0] - u) <= 5e-6 and abs(rod.tip[1] - v) <= 5e-6


def test_closed_form_shape_ends_where_its_tip_is():
    rod = rods.clamped_pinned(1.0, 1.0, [1.0, 4.0], [-0.6, 0.3], [2, 1], nodes=51)
    assert np.allclose(rod.rod.tip, rod.tip, atol=1e-13)
    assert np.allclose(rod.rod.m[..., -1], 0.0, atol=1e-12)
    assert np.allclose(rod.rod.theta[..., 0], 0.0, atol=1e-7)
    assert np.allclose(rod.rod.m[..., 0], rod.clamp_moment, atol=1e-13)


def test_force_near_k_min_keeps_its_digits():
    # tiny k_rel: arcsin(cos(psi/2)/k) would lose half the digits of phi1, hence of R
    import mpmath
    kr = 1e-10
    k, kmin = rods.elliptic_k(PI / 2, kr)
    with mpmath.workdps(40):
        kk = mpmath.mpf(kmin) + (1 - mpmath.mpf(kmin)) * mpmath.mpf(kr)
        p1 = mpmath.asin(mpmath.mpf(kmin) / kk)     # the same float cos(psi/2)
        R = float((mpmath.ellipf(PI / 2, kk ** 2) - mpmath.ellipf(p1, kk ** 2)) ** 2)
    assert abs(rods.clamped_pinned(1.0, 1.0, PI / 2, kr).R / R - 1) < 1e-10


@settings(max_examples=40, deadline=None)
@given(st.floats(0.05, 2 * PI - 0.05), st.floats(0.01, 0.99), st.integers(1, 3),
       st.sampled_from([-1.0, 1.0]))
def test_elliptic_parameters_invert_the_closed_form(psi, k_abs, mode, sign):
    rod = rods.clamped_pinned(1.0, 1.0, psi, sign * k_abs, mode)
    p, k_rel, m, phi2 = rods.elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    assert np.isclose(p, psi, atol=1e-9) and np.isclose(k_rel, sign * k_abs, atol=1e-8)
    assert m == mode and np.isclose(phi2, (mode - 0.5) * PI, atol=1e-7)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.05, 2 * PI - 0.05), st.floats(0.001, 0.999), st.integers(1, 3))
def test_k_rel_for_force_inverts_the_closed_form(psi, k_abs, mode):
    k_rel = np.copysign(k_abs, np.cos(psi / 2))
    R = rods.clamped_pinned(2.0, 1.5, psi, k_rel, mode).R
    assert np.isclose(rods.k_rel_for_force(2.0, 1.5, psi, R, mode), k_rel, rtol=1e-9, atol=1e-12)


def test_dF_dk_matches_finite_differences():
    from scipy.special import ellipkinc
    phi, k, h = 1.1, 0.6, 1e-6
    fd = (ellipkinc(phi, (k + h) ** 2) - ellipkinc(phi, (k - h) ** 2)) / (2 * h)
    assert np.isclose(rods.elliptic._dF_dk(phi, k), fd, rtol=1e-8)


def test_pinned_shooting_finds_the_closed_form_equilibria():
    EI, L, tip = 0.5, 1.0, np.array([0.6, 0.3])
    sols = rods.pinned_equilibria(EI, L, tip, modes=(1, 2))
    assert len(sols) >= 2
    closed = rods.clamped_pinned(EI, L, sols[:, 0], sols[:, 1], sols[:, 2])
    assert np.allclose(closed.tip, tip, atol=1e-12)
    guesses = np.column_stack((closed.clamp_moment, closed.force))
    shot = rods.shoot_pinned(EI, L, np.tile(tip, (len(sols), 1)), guesses * 1.01, nodes=801)
    assert np.allclose(shot.rod.tip, tip, atol=1e-12)
    assert np.allclose(shot.rod.force, closed.force, rtol=1e-8)


def test_batch_shooting_equals_single():
    forces = np.array([[0.0, 1.0], [-0.5, 2.0]])
    batch = rods.shoot_cantilever(1.0, 1.0, forces)
    for i, f in enumerate(forces):
        assert np.allclose(batch.rod.tip[i], rods.shoot_cantilever(1.0, 1.0, f).rod.tip,
                           atol=1e-12)


def test_axial_force_gives_the_straight_rod():
    for method in ("elliptic", "shooting"):
        rod = rods.cantilever(1.0, 2.0, [-1.0, 0.0], method)
        assert np.allclose(rod.tip, [2.0, 0.0]) and np.all(rod.m == 0)


@pytest.mark.parametrize("call, match", [
    (lambda: rods.integrate(-1.0, 1.0, 0.0, [0, 1]), "EI must be finite and positive"),
    (lambda: rods.integrate(1.0, 0.0, 0.0, [0, 1]), "L must be finite and positive"),
    (lambda: rods.integrate(1.0, 1.0, np.nan, [0, 1]), "m0 must be finite"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1, 2]), "last axis of length 2"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0, 1], nodes=1), "nodes"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 0.0, 0.5), "psi must lie"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 2 * PI, 0.5), "psi must lie"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.0), "k_rel must satisfy"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 1.0), "k_rel must satisfy"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.5, mode=0), "mode must be"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 1.0, 0.5, mode=1.5), "mode must be"),
    (lambda: rods.k_rel_for_force(1.0, 1.0, 1.0, 0.0), "R must be finite and positive"),
    (lambda: rods.elliptic_parameters(1.0, 1.0, 0.1, [0.0, 0.0]), "must not be zero"),
    (lambda: rods.elliptic_parameters(1.0, 1.0, 0.0, [2.0, 0.0]), "pure tension"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [1.0, 0.5], [0, 0, 0]), "farther than L"),
    (lambda: rods.cantilever(1.0, 1.0, [0, 1], "euler"), "method must be"),
    (lambda: rods.pinned_equilibria(1.0, 1.0, [1.2, 0.0]), "closer than L"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_load_below_a_modes_range_has_no_equilibrium():
    with pytest.raises(NoEquilibriumError, match="mode 2 needs R >"):
        rods.k_rel_for_force(1.0, 1.0, 1.0, 0.5, mode=2)


def test_newton_that_cannot_converge_raises():
    with pytest.raises(ConvergenceError):
        rods.shoot_cantilever(1.0, 1.0, [0.0, 50.0], maxiter=2)
