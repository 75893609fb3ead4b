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

from mechnum import _validate


def _segments(x, y, name):
    x, y = _validate.array(x, f"{name} x", ndim=1), _validate.array(y, f"{name} y", ndim=1)
    if x.shape != y.shape or len(x) < 2:
        raise ValueError(f"{name} must be a polyline of at least 2 points with x and y of one "
                         f"shape, got {x.shape} and {y.shape}")
    p = np.stack((x, y), axis=-1)
    return p[:-1], p[1:]


def _cross(u, v):
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _crossing_pairs(a, b, c, d):
    """``(len(a), len(c))`` booleans: segment ``a_i b_i`` properly crosses ``c_j d_j``."""
    a, b = a[:, None], b[:, None]
    o1, o2 = _cross(b - a, c - a), _cross(b - a, d - a)
    o3, o4 = _cross(d - c, a - c), _cross(d - c, b - c)
    return (o1 * o2 < 0) & (o3 * o4 < 0)


def self_crossings(x, y):
    """How many times a polyline crosses itself (pairs of non-adjacent segments that cross).

    Examples
    --------
    >>> s = np.linspace(-np.pi, np.pi, 200)           # a prolate cycloid: one loop
    >>> self_crossings(s - 2 * np.sin(s), 1 - 2 * np.cos(s)), self_crossings(s, np.sin(s))
    (1, 0)
    """
    a, b = _segments(x, y, "polyline")
    return int(np.triu(_crossing_pairs(a, b, a, b), k=2).sum())


def mutual_crossings(x1, y1, x2, y2, *, shared_tip=False):
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
    a, b = _segments(x1, y1, "the first polyline")
    c, d = _segments(x2, y2, "the second polyline")
    pairs = _crossing_pairs(a, b, c, d)
    if shared_tip:
        pairs[-1, -1] = False
    return int(pairs.sum())
