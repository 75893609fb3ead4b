"""Stability of rod equilibria: the second variation of the energy under the constraints.

An equilibrium of elastic rods under dead loads is stable when the total potential energy
(bending energy minus the work of the loads) has a strict local minimum there, among the
configurations that the supports allow (the motors locked, the tips pinned together or to a
platform). The test is the sign of the **second variation**: on the tangent space of the
constraints, the Hessian of the Lagrangian (the energy plus the constraints times their
multipliers, which are the internal forces) must be positive definite. The number of its
negative eigenvalues, the *index*, counts the independent ways the equilibrium can escape.

The rod is discretised in ``N`` segments of length ``h = L / N``; the unknowns are the angles
``theta_j`` of the tangent at the midpoints ``s_j = (j - 1/2) h``. With the clamp angle
``theta_c`` (fixed) the bending energy and the tip are (midpoint rule, second order in ``h``)::

    U = EI / h (theta_1 - theta_c)**2 + sum_j EI / (2 h) (theta_{j+1} - theta_j)**2
    tip = clamp + h sum_j (cos theta_j, sin theta_j)

For a rod whose tip carries the force ``n`` (the force on the rod, as in :mod:`mechnum.rods`),
the Hessian of ``U - n . tip`` is the second-difference matrix of ``U`` plus the diagonal
``h n . (cos theta_j, sin theta_j)`` (tension stiffens, compression softens), and the gradient of
the tip, the rows of the constraints, is ``h (-sin theta_j, cos theta_j)``. A mechanism
assembles these blocks with its own constraints and calls :func:`constrained_eigenvalues`. The
Hessian is evaluated on the exact (continuous) equilibrium sampled at the midpoints, with its
exact forces as multipliers; its eigenvalues divided by ``h`` converge at second order to
those of the continuous second variation (the Rayleigh quotient
``int (EI theta'**2 + n . t theta**2) ds / int theta**2 ds``), so the index is settled once two
resolutions agree on it, with no eigenvalue near zero.

References: the energy criterion with constraints is the second-order condition of constrained
optimisation (Nocedal and Wright, *Numerical Optimization*, 2006, Theorem 12.6); for rods, see
Maddocks, *Stability and folds*, Arch. Rational Mech. Anal. 99 (1987) 301-328.
"""

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.linalg import LinAlgError, eigvalsh_tridiagonal, null_space, solve_banded

from mechnum import _validate
from mechnum.errors import SingularJacobianError
from mechnum.rods._rod import rod_scales

SYMMETRY_TOL = 1e-10
"""Largest asymmetry ``|H - H^T|`` accepted, relative to ``H``'s largest entry: a Hessian
assembled in floating point is symmetric to rounding; more is an error of assembly."""


@dataclass(frozen=True)
class RodBlock:
    """One discretised rod of :func:`rod_block`.

    Attributes
    ----------
    theta : ndarray, shape (N,)
        Tangent angles at the segment midpoints (rad).
    diagonal, off_diagonal : ndarray, shapes (N,) and (N - 1,)
        The tridiagonal Hessian of ``U - n . tip`` with respect to ``theta`` (N m).
    tip_gradient : ndarray, shape (2, N)
        ``d tip / d theta`` (m).
    h : float
        Segment length (m).
    """

    theta: np.ndarray
    diagonal: np.ndarray
    off_diagonal: np.ndarray
    tip_gradient: np.ndarray
    h: float

    @property
    def hessian(self) -> np.ndarray:
        """ndarray, shape (N, N): the Hessian as a dense matrix."""
        return (np.diag(self.diagonal) + np.diag(self.off_diagonal, 1)
                + np.diag(self.off_diagonal, -1))


def rod_block(EI: float, L: float, theta: ArrayLike, force: ArrayLike) -> RodBlock:
    """The discretised second variation of one rod, from its angles at the segment midpoints.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    theta : array_like, shape (N,)
        Tangent angles of the equilibrium at the midpoints ``s_j = (j - 1/2) L / N``
        (``N >= 2``), for example ``rod.theta[1::2]`` of a rod sampled at ``2 N + 1`` nodes.
    force : array_like, shape (2,)
        The force on the rod at its tip (N).

    Returns
    -------
    RodBlock

    Examples
    --------
    An unloaded straight rod: the Hessian is the bending stiffness alone.

    >>> block = rod_block(1.0, 1.0, np.zeros(4), [0.0, 0.0])
    >>> block.hessian * block.h
    array([[ 3., -1.,  0.,  0.],
           [-1.,  2., -1.,  0.],
           [ 0., -1.,  2., -1.],
           [ 0.,  0., -1.,  1.]])
    """
    EI, L = rod_scales(EI, L, scalar=True)
    theta = _validate.array(theta, "theta", ndim=1)
    force = _validate.array(force, "force", shape=(2,))
    segments = _validate.maxiter(len(theta), "the number of segments", minimum=2)
    h = L / segments
    stiffness = np.full(segments, 2.0)
    # the clamp is h/2 from the first midpoint (a spring 2 EI / h); the free tip has none
    stiffness[0], stiffness[-1] = 3.0, 1.0
    c, s = np.cos(theta), np.sin(theta)
    return RodBlock(theta, EI / h * stiffness + h * (force[0] * c + force[1] * s),
                    np.full(segments - 1, -EI / h), h * np.stack((-s, c)), h)


def symmetric(matrix: ArrayLike, name: str) -> np.ndarray:
    """``matrix`` as a finite square float array, checked symmetric to :data:`SYMMETRY_TOL`.

    Examples
    --------
    >>> symmetric([[1.0, 2.0], [2.0, 1.0]], "hessian").shape
    (2, 2)
    >>> symmetric([[1.0, 2.0], [0.0, 1.0]], "hessian")
    Traceback (most recent call last):
    ...
    ValueError: hessian must be symmetric: |H - H^T| = 2 against its largest entry 2
    """
    matrix = _validate.array(matrix, name, ndim=2)
    if matrix.shape[0] != matrix.shape[1]:
        raise ValueError(f"{name} must be square, got shape {matrix.shape}")
    gap, size = np.abs(matrix - matrix.T).max(initial=0.0), np.abs(matrix).max(initial=0.0)
    if gap > SYMMETRY_TOL * size:
        raise ValueError(f"{name} must be symmetric: |H - H^T| = {gap:.3g} against its largest "
                         f"entry {size:.3g}")
    return matrix


def constrained_eigenvalues(hessian: ArrayLike, constraints: ArrayLike) -> np.ndarray:
    """Eigenvalues of a Hessian on the null space of the constraints' Jacobian.

    Parameters
    ----------
    hessian : array_like, shape (n, n)
        Symmetric Hessian of the Lagrangian.
    constraints : array_like, shape (c, n)
        Jacobian of the constraints, ``c < n`` (``c = 0``: none). Rows that depend on the
        others (the axial displacement of a straight rod's tip, zero to first order) constrain
        nothing: the null space is that of the independent ones.

    Returns
    -------
    ndarray, shape (n - rank,)
        The eigenvalues of ``Z^T H Z`` in ascending order, ``Z`` an orthonormal basis of the
        null space; the number of negative ones is the index of the equilibrium.

    Raises
    ------
    ValueError
        If the shapes do not match, or the Hessian is not symmetric (to
        :data:`SYMMETRY_TOL`).

    Examples
    --------
    ``x**2 - y**2`` is a saddle, but a minimum on the line ``y = 0``:

    >>> constrained_eigenvalues([[2.0, 0.0], [0.0, -2.0]], [[0.0, 1.0]])
    array([2.])
    """
    hessian = symmetric(hessian, "hessian")
    constraints = _validate.array(constraints, "constraints", ndim=2)
    n = hessian.shape[0]
    if constraints.shape[1] != n or constraints.shape[0] >= n:
        raise ValueError(f"hessian {hessian.shape} and constraints {constraints.shape} must be "
                         f"(n, n) and (c, n) with c < n")
    Z = null_space(constraints)    # dependent rows (a straight rod's axial tip) drop out
    return np.linalg.eigvalsh(Z.T @ (0.5 * (hessian + hessian.T)) @ Z)


def block_terms(blocks: Sequence[RodBlock], constraints: np.ndarray) -> tuple[int, np.ndarray]:
    """The rods' part of an index count: ``neg(H_r)`` and ``G_r H_r^-1 G_r^T``.

    ``blocks`` are :class:`RodBlock` s whose angles are the first columns of ``constraints``
    (shape ``(c, >= sum of N)``), in order. The negative eigenvalues of each tridiagonal block
    are counted by LAPACK's bisection (no division by a pivot), ``H_r^-1 G_r^T`` comes from
    banded solves: ``O(N)`` work per rod.

    Raises
    ------
    ValueError
        If a block is not a :class:`RodBlock`, or the constraints have too few columns.
    SingularJacobianError
        If a block is singular (the count is then undecided: use
        :func:`constrained_eigenvalues`).

    Examples
    --------
    A column pushed by ``21 EI / L**2``, beyond the free rod's Euler load ``2.47`` but below its
    second, ``22.2``: one negative direction of the free rod.

    >>> block = rod_block(1.0, 1.0, np.zeros(50), [-21.0, 0.0])
    >>> negative, S = block_terms([block], block.tip_gradient)
    >>> negative, S.shape
    (1, (2, 2))
    """
    blocks = rod_blocks(blocks)
    sizes = [len(b.diagonal) for b in blocks]
    if constraints.shape[1] < sum(sizes):
        raise ValueError(f"constraints have {constraints.shape[1]} columns for {sum(sizes)} "
                         f"angles")
    negative, S, start = 0, np.zeros((len(constraints), len(constraints))), 0
    for i, (block, n) in enumerate(zip(blocks, sizes)):
        negative += len(eigvalsh_tridiagonal(block.diagonal, block.off_diagonal, select="v",
                                             select_range=(-np.inf, 0.0)))
        bands = np.zeros((3, n))
        bands[0, 1:], bands[1], bands[2, :-1] = (block.off_diagonal, block.diagonal,
                                                 block.off_diagonal)
        g = constraints[:, start:start + n]
        try:
            S += g @ solve_banded((1, 1), bands, g.T)
        except LinAlgError:
            raise SingularJacobianError(f"the Hessian of rod {i} is singular: its index is "
                                        f"undecided (use constrained_eigenvalues)") from None
        start += n
    return negative, S


def rod_blocks(blocks: object) -> list:
    """``blocks`` as a list if it is a sequence of :class:`RodBlock`, else a ValueError that
    names them.

    Examples
    --------
    >>> rod_blocks(None)
    Traceback (most recent call last):
    ...
    ValueError: blocks must be a sequence of RodBlocks (from rod_block), got None
    """
    if not isinstance(blocks, (list, tuple)) or not all(isinstance(b, RodBlock) for b in blocks):
        shown = ([type(b).__name__ for b in blocks] if isinstance(blocks, (list, tuple))
                 else _validate.shown(blocks))
        raise ValueError(f"blocks must be a sequence of RodBlocks (from rod_block), got {shown}")
    return list(blocks)


def constrained_index(blocks: Sequence[RodBlock], constraints: ArrayLike) -> int:
    """The index (negative eigenvalues on the constraints' null space) of rods' Hessians.

    For a Hessian ``H`` made of the tridiagonal blocks of :func:`rod_block` (the rods'
    angles, in order) and constraints ``G`` of rank ``c``, the inertia of the bordered matrix
    ``[[H, G^T], [G, 0]]`` is both that of ``Z^T H Z`` plus ``(c, c)`` and (Haynsworth) that of
    ``H`` plus that of ``-G H^-1 G^T``. Hence::

        index = neg(H) + pos(G H^-1 G^T) - c

    with ``neg(H)`` counted from the pivots of each block and ``H^-1 G^T`` from banded
    solves: ``O(N)`` work per rod, so resolutions of hundreds of segments cost little. Same
    count as :func:`constrained_eigenvalues` (for an ``H`` that is not singular).

    Parameters
    ----------
    blocks : sequence of RodBlock
    constraints : array_like, shape (c, sum of N)
        Jacobian of the constraints with respect to all the rods' angles, of full row rank.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        If a block is not a :class:`RodBlock` or the shapes do not match.
    SingularJacobianError
        If a rod's Hessian is singular (its count is undecided).

    Examples
    --------
    A clamped column whose tip is pinned buckles at ``P L**2 / EI = 20.19``:

    >>> below, above = (rod_block(1.0, 1.0, np.zeros(200), [-P, 0.0]) for P in (19.0, 21.0))
    >>> [constrained_index([b], b.tip_gradient) for b in (below, above)]
    [0, 1]
    """
    blocks = rod_blocks(blocks)
    G = _validate.array(constraints, "constraints", ndim=2)
    negative, S = block_terms(blocks, G)
    if G.shape[1] != sum(len(b.diagonal) for b in blocks):
        raise ValueError(f"constraints have {G.shape[1]} columns for "
                         f"{sum(len(b.diagonal) for b in blocks)} angles")
    rank = np.linalg.matrix_rank(G)
    return int(negative + np.sum(np.linalg.eigvalsh(S) > 0) - rank)
