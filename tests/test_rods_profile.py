"""Tests of the shapes of clamped-pinned rods in any tension (mechnum.rods.profile)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipj

from mechnum.rods import _profile as profile
from mechnum.rods import _regular as regular


def test_amplitude_matches_scipy_away_from_k_1():
    rng = np.random.default_rng(0)
    u, k = rng.uniform(-20, 20, 200), rng.uniform(0, 0.99, 200)
    phi = profile.amplitude(u, k, np.sqrt((1 - k) * (1 + k)))
    # amplitudes of O(1) to O(20) computed two ways (the profile's and scipy's Jacobi functions):
    # round-off, 1e-12
    assert np.abs(phi - ellipj(u, k * k)[3]).max() < 1e-12


def test_amplitude_near_k_1_from_the_complement():
    """With k' = 1e-12, am(u) has cos(am) = k' sinh(K - u) / dn near the quarter period; the
    DLMF 22.10.ii expansion in k'**2 is exact to 1e-24 for u <= 12."""
    kp = 1e-12
    u = np.linspace(0.5, 12.0, 40)
    expected = (2 * np.arctan(np.exp(u)) - np.pi / 2
                + kp ** 2 / 4 * (np.sinh(u) * np.cosh(u) - u) / np.cosh(u))
    # the expansion is exact to 1e-24 (the docstring above), so only the amplitude's round-off
    # remains: values up to pi/2, a few ulps
    assert np.abs(profile.amplitude(u, np.sqrt(1 - kp ** 2), kp) - expected).max() < 1e-14


def test_shape_agrees_with_regular_for_moderate_rods():
    rng = np.random.default_rng(1)
    psi, t, mode = rng.uniform(0.1, 6.2, 40), rng.uniform(-0.95, 0.95, 40), rng.integers(1, 4, 40)
    a, b = profile.shape(1.0, 1.0, psi, t, mode, nodes=51), profile.shape(1.0, 1.0, psi, t,
                                                                           mode, nodes=51)
    # two closed forms of the same rods at 51 nodes: round-off of O(1) coordinates
    assert np.abs(a.x - b.x).max() < 1e-12 and np.abs(a.y - b.y).max() < 1e-12
    # as above, for the bending moments
    assert np.abs(a.m - b.m).max() < 1e-12


@pytest.mark.parametrize("psi, t, mode", [(6.0288, 0.9912, 1), (5.77, 0.9916, 2),
                                          (0.5759, -0.99, 1), (2.0, -0.99, 3)])
def test_shape_in_strong_tension_solves_the_rod_equations(psi, t, mode):
    """Each of 60 pieces integrated by solve_ivp from the profile's state ends at the next."""
    EI = 0.0522
    rod = profile.shape(EI, 1.0, psi, t, mode, nodes=61)
    end = regular.clamped_pinned_regular(EI, 1.0, psi, t, mode)
    # the profile's tip and its closing moment against the regular chart's: round-off
    assert np.abs(rod.tip - end.tip).max() < 1e-12 and abs(rod.m[-1]) < 1e-12
    n = rod.force

    def rhs(_, u):
        return [np.cos(u[2]), np.sin(u[2]), u[3] / EI, n[0] * np.sin(u[2]) - n[1] * np.cos(u[2])]

    S = np.column_stack((rod.x, rod.y, rod.theta, rod.m))
    for j in range(60):
        sol = solve_ivp(rhs, (rod.s[j], rod.s[j + 1]), S[j], method="DOP853", rtol=1e-13,
                        atol=1e-14)
        # DOP853 at rtol 1e-13 over one piece of 1/60: its error is far below 1e-11; the profile's
        # nodes are at round-off
        assert np.abs(sol.y[:2, -1] - S[j + 1, :2]).max() < 1e-11
