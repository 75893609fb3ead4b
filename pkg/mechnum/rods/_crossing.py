"""Whether rods drawn as polylines cross themselves or each other.

A planar equilibrium in which a rod passes through itself, or through another rod, cannot be
built in one plane: the physical rods would collide. The test is the classical orientation test
of two segments ``ab`` and ``cd``: they cross properly when ``c`` and ``d`` lie strictly on
opposite sides of the line ``ab`` and ``a`` and ``b`` strictly on opposite sides of ``cd``
(signs of the cross products ``(b - a) x (c - a)`` and so on). Touching segments (a shared
end) do not count, so consecutive segments of one rod never do. Sample the rods finely
enough that the polylines follow them (a few hundred nodes for the rods of this book).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate

BLOCK = 8   # segments per bounding box; any size gives the same counts, this one is fast


def _segments(x, y, name):
    x, y = _validate.array(x, f"{name} x", ndim=1), _validate.array(y, f"{name} y", ndim=1)
    if x.shape != y.shape or len(x) < 2:
        raise ValueError(f"{name} must be a polyline of at least 2 points with x and y of one "
                         f"shape, got {x.shape} and {y.shape}")
    p = np.stack((x, y), axis=-1)
    return p[:-1], p[1:]


def _cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _boxes(a, b):
    """Bounding boxes ``(lower, upper)`` of consecutive blocks of ``BLOCK`` segments."""
    starts = np.arange(0, len(a), BLOCK)
    return (np.minimum.reduceat(np.minimum(a, b), starts, axis=0),
            np.maximum.reduceat(np.maximum(a, b), starts, axis=0))


def _crossing_pairs(a, b, c, d):
    """Indices ``(i, j)`` of the segments ``a_i b_i`` that properly cross ``c_j d_j``.

    Only the segments of blocks whose bounding boxes overlap are compared: for smooth rods
    that is a few blocks along the diagonal instead of all ``len(a) * len(c)`` pairs.
    """
    (lo1, hi1), (lo2, hi2) = _boxes(a, b), _boxes(c, d)
    near = np.all((lo1[:, None] <= hi2) & (lo2 <= hi1[:, None]), axis=-1)
    block_i, block_j = np.nonzero(near)
    k = np.arange(BLOCK)
    i, j = (x.ravel() for x in np.broadcast_arrays(BLOCK * block_i[:, None, None] + k[:, None],
                                                    BLOCK * block_j[:, None, None] + k))
    keep = (i < len(a)) & (j < len(c))
    i, j = i[keep], j[keep]
    o1, o2 = _cross(b[i] - a[i], c[j] - a[i]), _cross(b[i] - a[i], d[j] - a[i])
    o3, o4 = _cross(d[j] - c[j], a[i] - c[j]), _cross(d[j] - c[j], b[i] - c[j])
    hit = (o1 * o2 < 0) & (o3 * o4 < 0)
    return i[hit], j[hit]


def self_crossings(x: ArrayLike, y: ArrayLike) -> int:
    """How many times a polyline crosses itself (pairs of non-adjacent segments that cross).

    Examples
    --------
    >>> s = np.linspace(-np.pi, np.pi, 200)           # a prolate cycloid: one loop
    >>> self_crossings(s - 2 * np.sin(s), 1 - 2 * np.cos(s)), self_crossings(s, np.sin(s))
    (1, 0)
    """
    a, b = _segments(x, y, "polyline")
    i, j = _crossing_pairs(a, b, a, b)
    return int(np.count_nonzero(j - i >= 2))


def mutual_crossings(x1: ArrayLike, y1: ArrayLike, x2: ArrayLike, y2: ArrayLike, *,
                     shared_tip: bool = False) -> int:
    """How many times two polylines cross each other.

    Parameters
    ----------
    x1, y1, x2, y2 : array_like, shape (N,)
        The two polylines.
    shared_tip : bool, optional
        Their last points coincide (two rods pinned together): the last segments meet there,
        which is no crossing, and are not compared with each other.

    Examples
    --------
    >>> s = np.linspace(0.0, 1.0, 50)
    >>> mutual_crossings(s, s, s, 1 - s), mutual_crossings(s, s, s, s + 0.1)
    (1, 0)
    """
    shared_tip = _validate.flag(shared_tip, "shared_tip")
    a, b = _segments(x1, y1, "the first polyline")
    c, d = _segments(x2, y2, "the second polyline")
    i, j = _crossing_pairs(a, b, c, d)
    if shared_tip:
        return int(np.count_nonzero((i < len(a) - 1) | (j < len(c) - 1)))
    return len(i)
