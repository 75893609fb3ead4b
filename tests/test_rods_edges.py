"""The edges of mechnum.rods: the defects of issue 23, each with the input that exposed it, and
the property tests of the shooting solvers (random valid input: the documented tolerance, or a
named error)."""

import warnings

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from mechnum import rods
from mechnum.errors import DivergenceError, MechnumError, SingularJacobianError
from mechnum.mechanisms.elastica import study as elastica
from mechnum.rods import _crossing as crossing
from mechnum.rods import _profile as profile
from mechnum.rods import _regular as regular
from mechnum.rods import _shooting as shooting
from mechnum.rods import _stability as stability
from mechnum.rods._bodies import constrained_index_with_body
from mechnum.rods._pinned import RESOLVED

PI = np.pi


def pieces_solve_the_equations(EI, rod, atol):
    """Each piece between two nodes of ``rod``, integrated by scipy's DOP853 from the first
    node's state, ends at the next node (an integrator other than the package's)."""
    n = rod.force

    def rhs(_, u):
        return [np.cos(u[2]), np.sin(u[2]), u[3] / EI, n[0] * np.sin(u[2]) - n[1] * np.cos(u[2])]

    S = np.column_stack((rod.x, rod.y, rod.theta, rod.m))
    for j in range(len(S) - 1):
        sol = solve_ivp(rhs, (rod.s[j], rod.s[j + 1]), S[j], method="DOP853", rtol=1e-13,
                        atol=1e-14)
        assert np.abs(sol.y[:2, -1] - S[j + 1, :2]).max() < atol, j


# --- D1: shapes at psi = pi exactly -------------------------------------------------------

def test_closed_form_shape_at_psi_pi_exactly_is_a_rod():
    # the nodes of the study's chart at psi = pi were displaced by up to 0.18 L
    rod = rods.clamped_pinned(1.0, 1.0, PI, 0.532417777150811, nodes=401).rod
    chords = np.hypot(np.diff(rod.x), np.diff(rod.y))
    assert chords.max() <= 0.0025 * (1 + 1e-12) and chords.min() > 0.0025 * (1 - 1e-4)
    pieces_solve_the_equations(1.0, rod, 1e-11)


@pytest.mark.parametrize("t", [0.1191, -0.5934, 0.1385, 0.1743, 0.9, -0.95])
def test_regular_shape_at_psi_pi_exactly_is_a_rod(t):
    rod = profile.shape(1.0, 1.0, PI, t, nodes=201)
    # nodes spaced L / 200 = 0.005 along the arc; the chords are shorter, up to their rounding
    # (1e-12 relative)
    assert np.hypot(np.diff(rod.x), np.diff(rod.y)).max() <= 0.005 * (1 + 1e-12)
    pieces_solve_the_equations(1.0, rod, 1e-10)


# --- D3: loads that 41 RK4 nodes cannot resolve -------------------------------------------

@pytest.mark.parametrize("load", [1e3, 1e4])
def test_shooting_an_unresolvable_load_is_a_named_error(load):
    # it used to return a rod whose tip is 0.75 L from the true one, converged
    with pytest.raises(rods.UnresolvedRodError, match="cannot resolve") as error:
        rods.shoot_cantilever(1.0, 1.0, [0.0, load])
    assert isinstance(error.value.result, rods.Shooting)
    with pytest.raises(rods.UnresolvedRodError):
        rods.cantilever(1.0, 1.0, [0.0, load], "shooting")


def test_the_nodes_the_error_suggests_resolve_the_load():
    with pytest.raises(rods.UnresolvedRodError, match="about") as error:
        rods.shoot_cantilever(1.0, 1.0, [0.0, 300.0])
    nodes = int(str(error.value).split("about ")[1].split(")")[0])
    res = rods.shoot_cantilever(1.0, 1.0, [0.0, 300.0], nodes=nodes)
    # the nodes the error message suggests resolve the tip to the closed form within 1e-6 (the
    # message's promise)
    assert np.abs(res.rod.tip - rods.cantilever(1.0, 1.0, [0.0, 300.0]).tip).max() < 1e-6
    with pytest.raises(rods.UnresolvedRodError, match="beyond single shooting"):
        rods.shoot_cantilever(1.0, 1.0, [0.0, 1e3])


# --- D5, D6: |k_rel| within an ulp of 1 ----------------------------------------------------

@pytest.mark.parametrize("gap", [1e-15, 5e-16, 1.2e-16])
def test_closed_form_at_k_rel_next_to_one(gap):
    # it returned NaN; the growing branch is the cantilever under the same force, whose chart
    # (rods.cantilever) is another code's
    rod = rods.clamped_pinned(1.0, 1.0, 2.0, 1 - gap)
    assert_allclose(rod.tip, rods.cantilever(1.0, 1.0, rod.force, nodes=2).tip, rtol=1e-13)
    other = rods.clamped_pinned(1.0, 1.0, 2.0, -(1 - gap), [1, 2])
    assert np.isfinite(other.tip).all() and np.all(np.hypot(*other.tip.T) < 1.0)


def test_elliptic_parameters_of_a_nearly_straight_rod():
    # mode 3.2e19 came out of scipy's F(phi, k**2) with k**2 rounded to 1
    rod = rods.clamped_pinned(1.0, 1.0, 4.0, -(1 - 1e-12), 3)
    psi, k_rel, mode, phi2 = rods.elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    assert mode == 3 and psi == pytest.approx(4.0, rel=1e-14)
    assert_allclose(1 + k_rel, 1e-12, rtol=1e-3)     # the rounding of m0, amplified 1e4 times
    assert_allclose(phi2, 2.5 * PI, rtol=1e-6)


@pytest.mark.parametrize("m0, force", [(5.0, [1.0, 1e-300]), (3.0, [0.0, 1.0]),
                                       (-40.0, [-3.0, 2.0])])
def test_no_elliptic_parameters_outside_the_family(m0, force):
    # |k| > 1: k_rel came out 1.7e300 and the mode NaN, with no error
    with pytest.raises(rods.NotAnElasticaError, match="never vanishes"):
        rods.elliptic_parameters(1.0, 1.0, m0, force)


def test_a_batch_may_ask_for_nan_outside_the_family():
    rod = rods.clamped_pinned(1.0, 1.0, 2.0, -0.4, 2)
    psi, k_rel, mode, phi2 = rods.elliptic_parameters(
        1.0, 1.0, [float(rod.clamp_moment), 5.0], [rod.force, [1.0, 1e-300]], outside="nan")
    # the same rod's parameters recovered from its clamp moment and force: round-off of the
    # inversion
    assert_allclose([k_rel[0], mode[0]], [-0.4, 2.0], rtol=1e-12)
    assert np.isnan([k_rel[1], mode[1], phi2[1]]).all() and np.isfinite(psi).all()
    with pytest.raises(ValueError, match="outside must be one of"):
        rods.elliptic_parameters(1.0, 1.0, 5.0, [1.0, 1.0], outside="ignore")


# --- D11: the unloaded rod --------------------------------------------------------------------

@pytest.mark.parametrize("t", [1e-6, 1e-10, 1e-12, 1e-150])
def test_shape_of_a_nearly_unloaded_rod_is_linear_beam_theory(t):
    # chords were 0.2 % long at t = 1e-10 and the clamp 3e-4 L off at 1e-12: now every node
    # within rounding of the length (a few ulps of L) of linear beam theory
    rod = profile.shape(2.0, 1.5, 2.0, t, nodes=31)
    s, ny = rod.s, rod.force[1]
    beam = ny / 2.0 * (1.5 * s ** 2 / 2 - s ** 3 / 6)      # y(s), to O(load**2)
    ulps = 8 * np.finfo(float).eps * 1.5
    # the deflection is at most 1.6e-12 L here (t <= 1e-6), so beam theory's neglected terms (of
    # its square, 1e-24) are far below rounding: every node within a few ulps of L (atol) of it;
    # rtol 1e-9 adds little room, at the largest load only
    assert_allclose(rod.y, beam, rtol=1e-9, atol=ulps)
    assert_allclose(rod.x, s, rtol=0, atol=ulps)
    # every chord is L / 30 = 0.05 up to the rounding of the nodes (two ulps of L)
    assert_allclose(np.hypot(np.diff(rod.x), np.diff(rod.y)), 0.05, rtol=0, atol=2 * ulps)


@pytest.mark.parametrize("t", [1e-300, -1e-300, 1e-200])
def test_the_chart_holds_the_unloaded_rod(t):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rod = regular.clamped_pinned_regular(1.0, 1.0, 2.0, t)
    assert np.isfinite(rod.tip).all() and np.isfinite(rod.jacobian).all()
    if t > 0:     # the growing branch: the straight rod, no force
        assert_allclose(rod.tip, [1.0, 0.0], rtol=1e-15, atol=1e-300)


@pytest.mark.parametrize("psi", [0.5, 2.0, 4.0, 5.8])
@pytest.mark.parametrize("t", [1e-3, 1e-6, 1e-9])
def test_tip_derivative_in_t_near_the_unloaded_rod(psi, t):
    # d tip / dt of the growing branch vanishes like t: the quotient rule lost every digit
    rod = regular.clamped_pinned_regular(1.0, 1.0, psi, np.copysign(t, np.cos(psi / 2)))
    h = 1e-3 * t
    a, b = (regular.closed_form(1.0, 1.0, psi, np.copysign(t + d, np.cos(psi / 2)),
                                jacobian=False).tip for d in (h, -h))
    # central differences: truncation 1e-6 relative, rounding eps L / h (x is near L; y is
    # computed to full relative precision, so its differences resolve y' ~ t)
    assert_allclose(rod.jacobian[:2, 1] * np.sign(np.cos(psi / 2)), (a - b) / (2 * h),
                    rtol=1e-5, atol=4 * np.finfo(float).eps / h)


# --- D13: non-finite answers from finite input -----------------------------------------------

def test_overflowing_sweep_is_a_named_error():
    with pytest.raises(DivergenceError, match="overflowed"):
        rods.tip_jacobian(1.0, 1.0, 0.0, [1e300, 1e300])
    with pytest.raises(DivergenceError, match="overflowed"):
        rods.integrate(1.0, 1.0, 0.0, [1e300, 1e300])


@pytest.mark.parametrize("u, k, complement, match", [
    (np.nan, 0.5, np.sqrt(0.75), "u must be finite"),
    (1.0, 0.8, 0.5, "complement"),
    (1.0, 1.2, 0.0, "|k| <= 1"),
    (1.0, 0.6, -0.8, "0 <= complement <= 1"),
])
def test_amplitude_checks_its_input(u, k, complement, match):
    with pytest.raises(ValueError, match=match):
        profile.amplitude(u, k, complement)


# --- D15: multiple shooting from a sketch -------------------------------------------------------

def test_the_docstrings_sketch_needs_no_force():
    s = np.linspace(0.0, 1.0, 61)
    y = 0.1 * s - 0.15 * np.sin(PI * s)
    for force in ([0.0, 0.0], [0.1, 0.1], [-1.0, 0.0]):
        sketch = rods.Rod(s, 0.8 * s, y, np.arctan2(np.gradient(y, s), 0.8), np.zeros(61),
                          np.array(force))
        res = rods.shoot_pinned_multiple(1.0, 1.0, [0.8, 0.1], sketch, segments=6)
        assert rods.classify(1.0, 1.0, res.rod).mode == 2 and res.x[0] < 0


@pytest.mark.parametrize("force", [[0.0, 0.0], [0.1, 0.1]])
def test_a_straight_sketch_fails_by_name_or_finds_an_equilibrium(force):
    # a straight line determines no axial force: a named error, or (by chance) a true rod
    rng = np.random.default_rng(1)
    for _ in range(10):
        r, a = rng.uniform(0.2, 0.95), rng.uniform(-PI, PI)
        tip = r * np.array([np.cos(a), np.sin(a)])
        s = np.linspace(0.0, 1.0, 41)
        sketch = rods.Rod(s, tip[0] * s, tip[1] * s, np.full(41, a), np.zeros(41),
                          np.array(force))
        try:
            res = rods.shoot_pinned_multiple(1.0, 1.0, tip, sketch, segments=4)
        except MechnumError:
            continue
        assert rods.classify(1.0, 1.0, res.rod).kind == "elastica"


# --- R4, R6, R7, H4 and flags: bad input gets a ValueError that names it ---------------------

BLOCK = stability.rod_block(1.0, 1.0, np.zeros(4), [0.0, 0.0])


@pytest.mark.parametrize("call, match", [
    (lambda: rods.clamped_pinned(1.0, 1.0, [1.0, 2.0, 3.0], [0.5, 0.5]), "do not broadcast"),
    (lambda: regular.clamped_pinned_regular(1.0, 1.0, [1.0, 2.0, 3.0], [0.5, 0.5]),
     "do not broadcast"),
    (lambda: regular.place(regular.clamped_pinned_regular(1.0, 1.0, 2.0, 0.5), [0.0, 0.0, 0.0],
                           0.0), "origin must have a last axis of length 2"),
    (lambda: regular.place("rod", [0.0, 0.0], 0.0), "RegularRod"),
    (lambda: rods.integrate(1.0, 1.0, [0.1, 0.2, 0.3], [[0, 1], [1, 0]]), "m0 \\(3,\\)"),
    (lambda: rods.tip_jacobian(1.0, 1.0, [0.1, 0.2, 0.3], [[0, 1], [1, 0]]), "m0 \\(3,\\)"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [[0, 1], [0, 2]], m0=[1.0, 2.0, 3.0]),
     "one per force"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [[0.5, 0.5], [0.6, 0.1]], [[1, 2, 3]] * 3),
     "one per point"),
    (lambda: stability.constrained_index([np.zeros(3)], np.zeros((1, 3))), "RodBlocks"),
    (lambda: constrained_index_with_body(["block"], np.zeros((1, 1)), np.zeros((1, 5))),
     "RodBlocks"),
    (lambda: rods.equations(0.0, [0.0, 1.0]), "EI must be positive"),
    (lambda: rods.equations(1.0, [0.0, 1.0, 2.0]), "force must have shape \\(2,\\)"),
    (lambda: rods.integrate(1.0, 1.0, 0.0, [0.0, 1.0], nodes=10 ** 6), "<= 100000"),
    (lambda: rods.shoot_pinned(1.0, 1.0, [0.5, 0.5], damping="x"), "damping must be True"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [0.0, 1.0], damping="yes"), "damping must be"),
    (lambda: rods.shoot_cantilever(1.0, 1.0, [0.0, 1.0], maxiter=10 ** 7), "maxiter must be"),
    (lambda: regular.k_rel_from_t(2.0, 0.5, complement="yes"), "complement must be True"),
    (lambda: regular.clamped_pinned_regular(1.0, 1.0, 2.0, 0.5, jacobian=1), "jacobian must"),
    (lambda: crossing.mutual_crossings([0, 1], [0, 1], [0, 1], [1, 0], shared_tip=1),
     "shared_tip must be True"),
    (lambda: stability.constrained_eigenvalues([[1.0, 2.0], [0.0, 1.0]], np.zeros((0, 2))),
     "symmetric"),
    (lambda: constrained_index_with_body([BLOCK], [[0.0, 1.0], [0.0, 0.0]],
                                         np.zeros((1, 6))), "symmetric"),
    (lambda: rods.clamped_pinned(1.0, 1.0, 2.0, 0.5, nodes=10 ** 6), "<= 100000"),
    (lambda: profile.shape(1.0, 1.0, 2.0, 0.5, nodes=10 ** 6), "<= 100000"),
    (lambda: rods.DeadLoad(1.0, 1.0, PI, segments=10 ** 6), "segments must be"),
    (lambda: rods.k_rel_for_force(1.0, 1.0, 1.0, 1.0, maxiter=10 ** 6), "maxiter must be"),
])
def test_bad_input_is_named(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_axial_load_below_euler_has_no_buckled_rod():
    # psi = pi is pure compression: no rod below the Euler load pi**2 / 4 (it returned one)
    with pytest.raises(rods.NoEquilibriumError, match="needs R > 2.4674"):
        rods.k_rel_for_force(1.0, 1.0, PI, 2.0)
    assert rods.k_rel_for_force(1.0, 1.0, PI, 2.5) > 0


def test_a_zero_pivot_neither_warns_nor_miscounts():
    # diagonal 0 first: the L D L^T of the pivots divided by zero
    block = stability.RodBlock(np.zeros(3), np.array([0.0, 2.0, 2.0]), np.array([1.0, 1.0]),
                               np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        index = stability.constrained_index([block], block.tip_gradient[:1])
    expected = np.sum(stability.constrained_eigenvalues(block.hessian, block.tip_gradient[:1]) < 0)
    assert index == expected


def test_a_singular_rod_block_is_a_named_error():
    block = stability.RodBlock(np.zeros(2), np.array([1.0, 1.0]), np.array([1.0]),
                               np.array([[1.0, 0.0]]), 1.0)
    with pytest.raises(SingularJacobianError, match="singular"):
        stability.constrained_index([block], block.tip_gradient)


# --- the property tests of the shooting solvers ---------------------------------------------

FORCES = st.tuples(st.floats(-2.0, 3.5), st.floats(0.0, 2 * PI), st.floats(0.1, 10.0))


@settings(max_examples=60, deadline=None)
@given(FORCES, st.integers(11, 401))
@example((3.0, PI / 2, 1.0), 41)        # the load, P L**2 / EI = 1e3 on 41 nodes
@example((2.5, 4.0, 1.0), 201)
@example((3.0, 1.0, 1.0), 11)          # Newton fails before the check: still "cannot resolve"
def test_shoot_cantilever_meets_its_promise_or_names_its_failure(load, nodes):
    log_alpha, psi, EI = load
    force = 10.0 ** log_alpha * EI * np.array([np.cos(psi), np.sin(psi)])
    try:
        res = rods.shoot_cantilever(EI, 1.0, force, nodes=nodes)
    except MechnumError as error:
        assert isinstance(error, (rods.UnresolvedRodError, SingularJacobianError)) or \
            "cannot resolve" in str(error)
        return
    # documented: m(L) below tol times the moments (or the rounding floor, at most MAX_FLOOR),
    # and from the default start the closed form's rod to within RESOLVED L
    assert res.converged
    assert abs(res.rod.m[-1]) <= shooting.MAX_FLOOR * max(np.hypot(*force), EI)
    exact = rods.cantilever(EI, 1.0, force, nodes=2) if force[1] else res.rod
    assert np.abs(res.rod.tip - exact.tip).max() <= RESOLVED


@settings(max_examples=40, deadline=None)
@given(st.floats(0.05, 0.99), st.floats(-PI, PI), st.floats(0.1, 10.0), st.integers(21, 201),
       st.booleans())
def test_shoot_pinned_meets_its_promise_or_names_its_failure(radius, angle, EI, nodes, damped):
    point = radius * np.array([np.cos(angle), np.sin(angle)])
    try:
        res = rods.shoot_pinned(EI, 1.0, point, nodes=nodes, damping=damped)
    except MechnumError:
        return
    # documented: the scaled residual below tol (raised to the rounding floor, at most
    # MAX_FLOOR), and the rod an equilibrium to RK4's error, never a spurious one
    residual = [*(res.rod.tip - point), res.rod.m[-1] / EI]
    assert res.converged and np.abs(residual).max() <= shooting.MAX_FLOOR
    assert rods.classify(EI, 1.0, res.rod).kind == "elastica"


@settings(max_examples=25, deadline=None)
@given(st.floats(0.2, 6.0), st.floats(-0.9, 0.9).filter(lambda t: abs(t) > 0.05),
       st.integers(1, 2), st.integers(1, 8), st.floats(-0.1, 0.1))
def test_shoot_pinned_multiple_meets_its_promise_or_names_its_failure(psi, t, mode, segments,
                                                                       bend):
    # a sketch: a closed-form rod of the chart, its angles bent by up to 0.1 rad, no moment
    # and no force
    exact = profile.shape(1.0, 1.0, psi, t, mode, nodes=41)
    sketch = rods.Rod(exact.s, exact.x, exact.y, exact.theta + bend * np.sin(PI * exact.s),
                      np.zeros(41), np.zeros(2))
    try:
        res = rods.shoot_pinned_multiple(1.0, 1.0, exact.tip, sketch, segments=segments)
    except MechnumError:
        return
    # documented: Newton's residual below tol = 1e-10 (tip, m(L) L / EI), and no spurious rod
    assert res.converged
    assert np.abs(res.rod.tip - exact.tip).max() <= 1e-10 and abs(res.rod.m[-1]) <= 1e-10
    assert rods.classify(1.0, 1.0, res.rod).kind in ("elastica", "straight")


def test_the_study_loop_takes_its_new_argument_names():
    res = elastica.study_shooting(EI=elastica.EI, L=elastica.LENGTH)
    assert res.max_residual <= elastica.TOL
