"""Stability of rods attached to rigid bodies: rods' tridiagonal Hessians plus a few dense
variables.

When rods hold a rigid body (a platform), the configuration is the rods' angles *and* the body's
pose, tied together by constraints (each rod's tip at its pin on the body). The Hessian of the
Lagrangian is block diagonal: one tridiagonal block per rod
(:func:`mechnum.rods.rod_block`) and a small dense block ``D`` for the pose (the
body's own terms, for example the work of the constraint forces as the body turns). The Hessian
of the pose is often singular (a free translation costs no energy by itself), so the count of
:func:`mechnum.rods.constrained_index`, which factors the whole Hessian, does not
apply.
Here the Schur complement is taken on the rods' blocks only. With ``G = [G_r, G_d]`` the
constraints' Jacobian (columns of the rods' angles, then of the dense variables), the bordered
matrix ``K = [[H_r, 0, G_r^T], [0, D, G_d^T], [G_r, G_d, 0]]`` has (Haynsworth) the inertia of
``H_r`` plus that of ``K / H_r = [[D, G_d^T], [G_d, -G_r H_r^-1 G_r^T]]``, and (for ``G`` of full
row rank ``c``) that of the constrained Hessian plus ``(c, c)`` negative and positive. Hence::

    index = neg(H_r) + neg(K / H_r) - c

with ``O(N)`` work per rod (banded solves, and LAPACK's bisection for the negative eigenvalues
of each tridiagonal block) and a dense eigenproblem of size ``k + c`` only.
"""

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods._stability import RodBlock, block_terms, rod_blocks, symmetric


def constrained_index_with_body(blocks: Sequence[RodBlock], dense: ArrayLike,
                                constraints: ArrayLike) -> int:
    """The index of rods' Hessians and a body's dense Hessian on the constraints' null space.

    Parameters
    ----------
    blocks : sequence of RodBlock
        The rods' blocks (:func:`~mechnum.rods.rod_block`), in the order of the constraints'
        columns. Each must be nonsingular.
    dense : array_like, shape (k, k)
        The symmetric Hessian of the body's ``k`` variables (may be singular).
    constraints : array_like, shape (c, sum of N + k)
        Jacobian of the constraints with respect to the rods' angles, then the body's
        variables; of full row rank.

    Returns
    -------
    int
        Negative eigenvalues of the Hessian restricted to the constraints' null space.

    Raises
    ------
    ValueError
        If the shapes do not match, a block is not a RodBlock, or ``dense`` is not symmetric
        (to ``SYMMETRY_TOL = 1e-10``).
    SingularJacobianError
        If a rod's Hessian is singular.

    Examples
    --------
    A straight unloaded rod clamped at one end, its tip pinned to a point that may slide along
    y, costing no energy (``dense = [[0]]``): the rod bends, so the slide is stable.

    >>> from mechnum.rods._stability import rod_block
    >>> block = rod_block(1.0, 1.0, np.zeros(100), [0.0, 0.0])
    >>> G = np.concatenate((block.tip_gradient, [[0.0], [-1.0]]), axis=1)
    >>> constrained_index_with_body([block], [[0.0]], G)
    0
    """
    blocks = rod_blocks(blocks)
    dense = symmetric(dense, "dense")
    G = _validate.array(constraints, "constraints", ndim=2)
    rods = sum(len(b.diagonal) for b in blocks)
    k, c = len(dense), len(G)
    if G.shape[1] != rods + k or c >= G.shape[1]:
        raise ValueError(f"dense {dense.shape} and constraints {G.shape} must be (k, k) and "
                         f"(c, {rods} + k) with c < {rods} + k")
    negative, S = block_terms(blocks, G)
    G_d = G[:, rods:]
    schur = np.block([[0.5 * (dense + dense.T), G_d.T], [G_d, -S]])
    rank = np.linalg.matrix_rank(G @ G.T, hermitian=True)     # (c, c): cheaper than G's SVD
    return int(negative + np.sum(np.linalg.eigvalsh(schur) < 0) - rank)
