"""Tests of mechnum.mechanisms.finger: geometry, synthesis, the study's data."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum.errors import DivergenceError, GeometryError, UnreachablePoseError
from mechnum.mechanisms import finger as F

TABLE3 = F.TABLE3_LINKAGE


def _segments_cross(P1, P2, Q1, Q2):
    def side(A, B, C):
        return np.sign((B[:, 0] - A[:, 0]) * (C[:, 1] - A[:, 1])
                       - (B[:, 1] - A[:, 1]) * (C[:, 0] - A[:, 0]))
    return (side(P1, P2, Q1) != side(P1, P2, Q2)) & (side(Q1, Q2, P1) != side(Q1, Q2, P2))


def test_angle_convention_against_table1():
    # Freudenstein's equation with k of the Tabla 1 linkage holds at the measured angles.
    theta_in, theta_out = F.angles_from_points(F.TABLE1_EI[:, :2], F.TABLE1_EI[:, 2:],
                                               F.TABLE1_R4)
    A, b = F.design_matrix(theta_in, theta_out)
    residual = A @ F.freudenstein_coefficients(F.table1_linkage()) - b
    good = np.arange(10) != 2  # row 3 holds the study's typo
    assert np.abs(residual[good]).max() < 2e-5
    assert np.abs(residual[2]) > 1e-4


def test_crossed_branch_is_the_studys():
    L = F.table1_linkage()
    theta_in, theta_out = F.angles_from_points(F.TABLE1_EI[:, :2], F.TABLE1_EI[:, 2:], L.r4)
    crossed, open_ = F.pose(theta_in, L, F.CROSSED), F.pose(theta_in, L, F.OPEN)
    good = np.arange(10) != 2
    assert np.abs(crossed.E - F.TABLE1_EI[:, :2])[good].max() < 1e-4
    assert np.all(_segments_cross(crossed.D, crossed.E, crossed.H, crossed.I))
    assert not np.any(_segments_cross(open_.D, open_.E, open_.H, open_.I))


@pytest.mark.parametrize("branch", [F.CROSSED, F.OPEN])
def test_input_and_output_analyses_are_inverse(branch):
    theta_in = np.linspace(4.6, 6.2, 9)
    forward = F.pose(theta_in, TABLE3, branch)
    back = F.pose_from_output(forward.theta_out, TABLE3, branch)
    assert np.allclose(back.theta_in, theta_in, atol=1e-10)
    assert np.allclose(np.linalg.norm(forward.I - forward.E, axis=1), TABLE3.r2)


def test_unreachable_pose_is_reported():
    assert F.reachable([3.9357, 4.5117], TABLE3).tolist() == [False, True]
    with pytest.raises(UnreachablePoseError, match="3.9357"):
        F.pose([3.9357, 4.5117], TABLE3)
    with pytest.raises(UnreachablePoseError):
        F.pose_from_output([1.04], TABLE3)
    with pytest.raises(ValueError, match="driver"):
        F.reachable([1.0], TABLE3, "coupler")


@pytest.mark.parametrize("method, options", [("normal", {}), ("sor", dict(omega=1.65)),
                                             ("gauss_seidel", {}), ("sor", dict(omega=0.33))])
def test_synthesis_methods_agree_on_table2(method, options):
    qr = F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, "qr")
    other = F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, method,
                         tol=1e-13, maxiter=20_000, **options) if method != "normal" else \
        F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, method)
    assert np.allclose(other.k, qr.k, atol=1e-9)
    assert np.allclose(qr.residuals, F.design_matrix(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT)[0]
                       @ qr.k - np.cos(F.TABLE2_THETA_OUT - F.TABLE2_THETA_IN))


def test_jacobi_diverges_on_the_studys_normal_equations():
    with pytest.raises(DivergenceError):
        F.synthesize(F.TABLE2_THETA_IN, F.TABLE2_THETA_OUT, 6.9989, "jacobi")


def test_synthesis_recovers_an_exact_linkage():
    true = F.Linkage(30.0, 7.5, 24.0, 7.0)
    theta_in = np.linspace(4.7, 6.2, 8)
    fit = F.synthesize(theta_in, F.pose(theta_in, true).theta_out, 7.0)
    assert np.allclose([fit.linkage.r1, fit.linkage.r2, fit.linkage.r3], [30.0, 7.5, 24.0])
    assert np.abs(fit.residuals).max() < 1e-12


@pytest.mark.parametrize("call, error", [
    (lambda: F.Linkage(1.0, -2.0, 3.0, 1.0), GeometryError),
    (lambda: F.Linkage(1.0, np.nan, 3.0, 1.0), ValueError),
    (lambda: F.linkage_from_coefficients([0.1, -0.2, -1.0], 1.0), GeometryError),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1, -100.0], 1.0), GeometryError),
    (lambda: F.linkage_from_coefficients([-0.1, -0.1], 1.0), ValueError),
    (lambda: F.synthesize([4.0, 5.0], [1.0, 2.0], 7.0), ValueError),
    (lambda: F.synthesize([4.0, 5.0, 6.0], [1.0, 2.0], 7.0), ValueError),
    (lambda: F.synthesize([4.0, 5.0, 6.0], [1.0, 2.0, 3.0], 7.0, "lu"), ValueError),
    (lambda: F.pose([np.inf], TABLE3), ValueError),
    (lambda: F.pose([5.0], TABLE3, branch=0), ValueError),
])
def test_bad_input(call, error):
    with pytest.raises(error):
        call()


def test_ill_conditioned_example_formula():
    for delta in (1e-1, 1e-3):
        x, cond = F.ill_conditioned_example(delta, 2 * delta)
        assert cond == pytest.approx((3 + delta) * (4 + delta) / delta, rel=1e-9)
        assert x == pytest.approx([-3.0, -2.0])


lengths = st.floats(0.5, 50.0)


@settings(max_examples=60, deadline=None)
@given(lengths, lengths, lengths, lengths)
def test_freudenstein_round_trip(r1, r2, r3, r4):
    L = F.Linkage(r1, r2, r3, r4)
    back = F.linkage_from_coefficients(F.freudenstein_coefficients(L), r4)
    assert np.allclose([back.r1, back.r2, back.r3], [r1, r2, r3], rtol=1e-7)


@settings(max_examples=40, deadline=None)
@given(st.floats(10, 40), st.floats(0, 2 * np.pi), st.floats(2, 10), st.floats(0.05, 0.95))
def test_freudenstein_equation_holds_on_assembled_poses(r3, theta, r2, u):
    # Build an assembled pose directly (no filtering): with the input rocker at theta, the
    # distance d = |DI| is fixed, and the loop closes iff |r1 - r2| <= d <= r1 + r2, so r1 is
    # drawn strictly inside [|d - r2|, d + r2].
    r4 = 7.0
    d = np.sqrt(r4**2 + r3**2 + 2 * r3 * r4 * np.cos(theta))
    r1 = abs(d - r2) + u * (d + r2 - abs(d - r2))
    L = F.Linkage(r1, r2, r3, r4)
    assert F.reachable([theta], L)[0]
    p = F.pose([theta], L)
    A, b = F.design_matrix(p.theta_in, p.theta_out)
    assert abs((A @ F.freudenstein_coefficients(L) - b)[0]) < 1e-9
