"""Tests of the index of rods attached to a rigid body (mechnum.rods.bodies)."""

import numpy as np
import pytest

from mechnum.rods._bodies import constrained_index_with_body
from mechnum.rods._stability import constrained_eigenvalues, rod_block


def _dense(blocks, D):
    sizes = [len(b.diagonal) for b in blocks]
    n = sum(sizes) + len(D)
    H, start = np.zeros((n, n)), 0
    for b, m in zip(blocks, sizes):
        H[start:start + m, start:start + m] = b.hessian
        start += m
    H[start:, start:] = D
    return H


@pytest.mark.parametrize("seed", range(6))
def test_index_equals_the_dense_count(seed):
    rng = np.random.default_rng(seed)
    blocks = [rod_block(1.0, 1.0, rng.normal(0, 1, 30), rng.normal(0, 30, 2)) for _ in range(3)]
    D = rng.normal(0, 3, (3, 3))
    D = D + D.T
    D[:2, :2] = 0.0                         # a free translation: a singular body block
    G = rng.normal(0, 1, (6, 93))
    expected = int(np.sum(constrained_eigenvalues(_dense(blocks, D), G) < 0))
    assert constrained_index_with_body(blocks, D, G) == expected


def test_three_straight_unloaded_rods_holding_a_free_platform_are_stable():
    """Rods along the radii of a platform, no force: bending costs energy, nothing else moves."""
    N, r = 50, 0.2
    angles = np.radians([-150.0, -30.0, 90.0]) + np.pi          # each rod points inwards
    blocks = [rod_block(1.0, 1.0, np.full(N, a), [0.0, 0.0]) for a in angles]
    G = np.zeros((6, 3 * N + 3))
    for i, (b, a) in enumerate(zip(blocks, angles)):
        pin = -r * np.array([np.cos(a), np.sin(a)])              # B_i - P
        G[2 * i:2 * i + 2, i * N:(i + 1) * N] = b.tip_gradient
        G[2 * i:2 * i + 2, -3:-1] = -np.eye(2)
        G[2 * i:2 * i + 2, -1] = pin[1], -pin[0]
    assert constrained_index_with_body(blocks, np.zeros((3, 3)), G) == 0


def test_shapes_are_checked():
    block = rod_block(1.0, 1.0, np.zeros(4), [0.0, 0.0])
    with pytest.raises(ValueError, match="constraints"):
        constrained_index_with_body([block], np.zeros((1, 1)), np.zeros((2, 4)))
