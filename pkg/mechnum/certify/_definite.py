"""Definiteness of a symmetric interval matrix, proven: for certified stability.

A symmetric matrix is positive definite exactly when the pivots of its ``L D L^T``
factorisation (Gaussian elimination without pivoting) are all positive. Eliminating in ball
arithmetic encloses the pivots of **every** matrix of an interval matrix at once, so if every
pivot ball is positive, every symmetric member is positive definite. Conversely a vector ``x``
with ``x^T A x < 0`` for every member proves a negative eigenvalue for every member; ``x`` is
the eigenvector of the midpoint's smallest eigenvalue, and ``x^T A x`` is enclosed in balls.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from flint import arb

from mechnum._validate import shown
from mechnum.certify.balls import meet

__all__ = ["definite"]


def _entries(matrix):
    try:
        rows = [[v if isinstance(v, arb) else arb(v) for v in row] for row in _rows(matrix)]
    except (TypeError, ValueError) as error:
        raise ValueError(f"hessian_ball must be a square matrix of balls or floats, got "
                         f"{shown(matrix)} ({error})") from None
    n = len(rows)
    if any(len(row) != n for row in rows):
        raise ValueError(f"a square matrix is needed, got {n} rows of lengths "
                         f"{[len(row) for row in rows]}")
    return rows


def _rows(matrix):
    if hasattr(matrix, "nrows"):
        return [[matrix[i, j] for j in range(matrix.ncols())] for i in range(matrix.nrows())]
    return matrix


def definite(hessian_ball: Sequence) -> str:
    """Whether a symmetric interval matrix is positive definite: True, False or None.

    Parameters
    ----------
    hessian_ball : flint.arb_mat or sequence of sequences of arb (or floats)
        A symmetric ``n x n`` interval matrix: entries ``(i, j)`` and ``(j, i)`` are two
        enclosures of the same number, and their intersection is used (the verdict is for
        every symmetric matrix whose entries lie in both).

    Returns
    -------
    bool or None
        True: every symmetric matrix in the balls is positive definite (all ``L D L^T`` pivots
        proven positive). False: every one has a negative eigenvalue (a vector ``x`` with
        ``x^T A x < 0`` proven). None: neither could be proven (an eigenvalue near 0, or
        balls too wide).

    Raises
    ------
    ValueError
        If the matrix is not square, or not symmetric: entries ``(i, j)`` and ``(j, i)`` that
        are disjoint (no symmetric matrix lies in the balls; the message names them).

    Examples
    --------
    >>> definite([[arb(2, 0.1), arb(1)], [arb(1), arb(3)]])
    True
    >>> definite([[1.0, 2.0], [2.0, 1.0]])      # eigenvalues 3 and -1
    False
    >>> definite([[arb(0, 1e-3), 0.0], [0.0, 1.0]]) is None
    True
    >>> definite([[1.0, 0.0], [2.0, 1.0]])
    Traceback (most recent call last):
    ...
    ValueError: a symmetric matrix is needed: entries (0, 1) = 0 and \
(1, 0) = 2.00000000000000 are disjoint
    """
    A = _symmetric(_entries(hessian_ball))
    n = len(A)
    if n == 0:
        return True
    if _pivots_positive(A):
        return True
    if _negative_direction(A):
        return False
    return None


def _symmetric(A):
    """The matrix with entries ``(i, j)`` and ``(j, i)`` replaced by their intersection."""
    S = [list(row) for row in A]
    for i in range(len(A)):
        for j in range(i):
            upper, lower = A[j][i], A[i][j]
            if upper.is_finite() and lower.is_finite() and not upper.overlaps(lower):
                raise ValueError(f"a symmetric matrix is needed: entries ({j}, {i}) = "
                                 f"{upper.str()} and ({i}, {j}) = {lower.str()} are disjoint")
            S[i][j] = S[j][i] = meet(upper, lower)
    return S


def _pivots_positive(A):
    n = len(A)
    S = [list(row) for row in A]
    for k in range(n):
        pivot = S[k][k]
        if not (pivot.is_finite() and bool(pivot > 0)):
            return False
        for i in range(k + 1, n):
            factor = S[i][k] / pivot
            for j in range(k + 1, i + 1):
                S[i][j] = S[i][j] - factor * S[j][k]
                S[j][i] = S[i][j]
    return True


def _negative_direction(A):
    n = len(A)
    mid = np.array([[float(A[i][j].mid()) for j in range(n)] for i in range(n)])
    if not np.all(np.isfinite(mid)):
        return False
    x = np.linalg.eigh(mid)[1][:, 0]
    xa = [arb(float(v)) for v in x]
    quad = sum((xa[i] * A[i][j] * xa[j] for i in range(n) for j in range(n)),
               arb(0))
    return quad.is_finite() and bool(quad < 0)
