"""Tests of mechnum.rods._index: the free and pinned indices of a clamped-pinned rod in closed
form, proven in balls, against the discretised second variation (mechnum.rods._stability) at two
resolutions; the verdict of a mechanism."""

import numpy as np
import pytest
from flint import arb
from scipy.linalg import eigvalsh_tridiagonal

from mechnum import rods
from mechnum.rods import _index
from mechnum.rods import _regular as regular


def _discretised(psi, t, mode, segments):
    """The free and pinned indices of the rod ``(psi, t)`` (``EI = L = 1``) by
    :mod:`mechnum.rods._stability`."""
    rod = rods.shape(1.0, 1.0, psi, t, mode, nodes=2 * segments + 1)
    force = regular.clamped_pinned_regular(1.0, 1.0, psi, t, mode, jacobian=False).force
    block = rods.rod_block(1.0, 1.0, rod.theta[1::2], force)
    free = len(eigvalsh_tridiagonal(block.diagonal, block.off_diagonal, select="v",
                                    select_range=(-np.inf, 0.0)))
    return free, rods.constrained_index([block], block.tip_gradient)


def _point_box(psi, t, width=1e-9):
    return [[psi, psi + width], [t, t + width]]


def test_indices_agree_with_the_discretised_second_variation():
    """Random rods of modes 1 to 3 on both branches, where both resolutions agree."""
    rng = np.random.default_rng(11)
    checked, free_seen = 0, set()
    for _ in range(60):
        mode = int(rng.integers(1, 4))
        psi, t = rng.uniform(0.05, 2 * np.pi - 0.05), rng.uniform(-0.97, 0.97)
        sign = 1 if t > 0 else -1
        free = _index.free_index(1.0, 1.0, _point_box(psi, t), mode, sign)
        pinned = rods.pinned_index(1.0, 1.0, _point_box(psi, t), mode, sign)
        coarse, fine = _discretised(psi, t, mode, 400), _discretised(psi, t, mode, 1600)
        if free is None or pinned is None or coarse != fine:
            continue
        assert (free, pinned) == fine, (mode, psi, t)
        checked += 1
        free_seen.add(free)
    assert checked >= 50 and free_seen >= {0, 1, 2, 3}


def test_the_margin_decides_the_free_index_at_its_sign_change():
    """Along ``t`` the margin ``S`` changes sign where the free problem degenerates: the index
    steps by one there, and the discretised index steps at the same place."""
    psi, mode = 1.96, 1
    ts = -np.linspace(0.01, 0.9, 60)
    S = [float(_index.margin(1.0, 1.0, _point_box(psi, t), mode, -1).mid()) for t in ts]
    change = np.nonzero(np.diff(np.sign(S)))[0]
    assert len(change) == 1
    before, after = ts[change[0]], ts[change[0] + 1]
    assert _discretised(psi, before, mode, 800)[0] != _discretised(psi, after, mode, 800)[0]


def test_the_chapter5_rods_are_proven_stable_with_their_tips_pinned():
    eq = [(1.96254145, -0.05602536), (4.81104114, 0.85596174), (5.05486676, -0.9383097)]
    for psi, t in eq:
        box = _point_box(psi, t, 1e-7)
        assert rods.pinned_index(0.0522, 1.0, box, 1, 1 if t > 0 else -1) == 0
    assert _index.free_index(0.0522, 1.0, _point_box(*eq[0], 1e-7), 1, -1) == 1


def test_wide_boxes_and_boxes_across_a_sign_change_are_undecided():
    assert _index.free_index(1.0, 1.0, [[0.5, 6.0], [0.1, 0.9]], 1, 1) is None
    psi, t0, t1 = 1.96, -0.9, -0.01            # S changes sign in between
    assert _index.free_index(1.0, 1.0, [[psi, psi + 1e-6], [t0, t1]], 1, -1) is None


@pytest.mark.parametrize("box, sign", [([[0.0, 1.0], [0.2, 0.3]], 1),
                                       ([[1.0, 2.0], [-0.1, 0.3]], 1),
                                       ([[1.0, 2.0], [0.2, 0.3]], -1),
                                       ([[1.0, 2.0], [0.2, 0.3]], 0)])
def test_boxes_outside_the_chart_are_refused(box, sign):
    with pytest.raises(ValueError):
        _index.free_index(1.0, 1.0, box, 1, sign)


def test_stiffness_index_counts_negative_eigenvalues():
    def matrix(a, b, c):
        return [[arb(a), arb(b)], [arb(b), arb(c)]]
    assert _index.stiffness_index(matrix(2.0, 0.5, 1.0)) == 0
    assert _index.stiffness_index(matrix(2.0, 3.0, 1.0)) == 1
    assert _index.stiffness_index(matrix(-2.0, 0.5, -1.0)) == 2
    assert _index.stiffness_index([[arb(1.0), arb(0.0)], [arb(0.0), arb(0.0, 1e-3)]]) is None


def test_proven_stability_combines_the_indices():
    positive = [[arb(2.0), arb(0.5)], [arb(0.5), arb(1.0)]]
    negative = [[arb(-2.0), arb(0.0)], [arb(0.0), arb(1.0)]]
    unsure = [[arb(0.0, 1e-3), arb(0.0)], [arb(0.0), arb(1.0)]]
    assert rods.proven_stability([0, 0], positive) is True
    assert rods.proven_stability([0, 1], positive) is False
    assert rods.proven_stability([0, None], negative) is False
    assert rods.proven_stability([0, None], positive) is None
    assert rods.proven_stability([0, 0], unsure) is None
