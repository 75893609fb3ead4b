"""Groups of boxes that touch, found with a spatial hash, and what a set of boxes leaves.

:func:`clusters` labels the connected components of a set of closed boxes: two boxes are
joined when they overlap or touch, and a component is every box reachable through such
joints. Each box is hashed into the cells of a grid whose cell is as wide as the widest box
(so a box meets at most two cells per axis); only boxes that share a cell are compared.
A search that keeps the boxes where roots may lie groups them this way and proves the roots
in each group's hull (:func:`hulls`). :func:`subtract` cuts a box into the boxes that other
boxes leave of it (interiors disjoint): what a set of boxes searched one by one, none of
which may overlap another, still has to cover.

Examples
--------
>>> boxes = np.array([[[0.0, 1.0]], [[1.0, 2.0]], [[5.0, 6.0]]])
>>> clusters(boxes).tolist(), hulls(boxes, clusters(boxes)).tolist()
([0, 0, 1], [[[0.0, 2.0]], [[5.0, 6.0]]])
"""

import itertools

import numpy as np

from mechnum import _validate

MAX_DIMENSIONS = 12
"""The most axes a box may have (each box meets up to ``2**n`` cells)."""


def _root(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


def clusters(boxes, keys=None):
    """Labels ``0, 1, ...`` of the groups of touching boxes.

    Parameters
    ----------
    boxes : array_like, shape (m, n, 2)
        Closed boxes, ``[lo, hi]`` per axis.
    keys : array_like of int, shape (m,), optional
        Only boxes of equal key are joined (for example the branches of a chart).

    Returns
    -------
    ndarray of int, shape (m,)
        Labels in order of each group's first box.

    Raises
    ------
    ValueError
        If ``boxes`` is not ``(m, n, 2)`` with ``lo <= hi``, ``n`` above
        :data:`MAX_DIMENSIONS`, or ``keys`` does not match.
    """
    boxes = _validate.array(boxes, "boxes")
    if boxes.ndim != 3 or boxes.shape[2] != 2 or boxes.shape[1] > MAX_DIMENSIONS or np.any(
            ~(boxes[..., 0] <= boxes[..., 1])):
        raise ValueError(f"boxes must be (m, n <= {MAX_DIMENSIONS}, 2) with lo <= hi, got "
                         f"shape {boxes.shape}")
    m = len(boxes)
    keys = np.zeros(m, dtype=int) if keys is None else _validate.array(keys, "keys").astype(int)
    if keys.shape != (m,):
        raise ValueError(f"keys must have shape ({m},), got {keys.shape}")
    if m == 0:
        return np.zeros(0, dtype=int)
    width = (boxes[..., 1] - boxes[..., 0]).max(axis=0)
    width = np.where(width > 0, width, 1.0)
    origin = boxes[..., 0].min(axis=0)
    first = np.floor((boxes[..., 0] - origin) / width).astype(np.int64)
    last = np.floor((boxes[..., 1] - origin) / width).astype(np.int64)
    cells = {}
    for i in range(m):
        for cell in itertools.product(*(range(a, b + 1) for a, b in zip(first[i], last[i]))):
            cells.setdefault((int(keys[i]),) + cell, []).append(i)
    parent = list(range(m))
    for members in cells.values():
        if len(members) < 2:
            continue
        group = boxes[members]
        lo, hi = group[:, :, 0], group[:, :, 1]
        touch = np.all((lo[:, None] <= hi[None]) & (lo[None] <= hi[:, None]), axis=2)
        for a, b in zip(*np.nonzero(np.triu(touch, 1))):
            ra, rb = _root(parent, members[a]), _root(parent, members[b])
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([_root(parent, i) for i in range(m)])
    _, labels = np.unique(roots, return_inverse=True)
    order = np.unique(labels, return_index=True)[1]
    rank = np.empty(len(order), dtype=int)
    rank[np.argsort(order)] = np.arange(len(order))
    return rank[labels]


def hulls(boxes, labels):
    """The smallest box holding each group's boxes, shape ``(groups, n, 2)``.

    Raises
    ------
    ValueError
        If ``boxes`` is not ``(m, n, 2)`` or ``labels`` not ``m`` integers ``0, 1, ...``.
    """
    boxes = _validate.array(boxes, "boxes", ndim=3)
    labels = _validate.array(labels, "labels", ndim=1)
    if len(labels) != len(boxes) or np.any(labels < 0) or np.any(labels != np.round(labels)):
        raise ValueError(f"labels must be {len(boxes)} integers >= 0, got {labels.tolist()}")
    labels = labels.astype(int)
    count = int(labels.max()) + 1 if len(labels) else 0
    out = np.empty((count, boxes.shape[1] if boxes.ndim == 3 else 0, 2))
    for c in range(count):
        group = boxes[labels == c]
        out[c, :, 0], out[c, :, 1] = group[:, :, 0].min(axis=0), group[:, :, 1].max(axis=0)
    return out


def _interiors_meet(a, b):
    return bool(np.all(a[:, 0] < b[:, 1]) and np.all(b[:, 0] < a[:, 1]))


def subtract(box, others):
    """The boxes that ``others`` leave of ``box``: disjoint interiors, their union the closure
    of ``box`` minus the ``others`` (an empty list when they cover it).

    Parameters
    ----------
    box : array_like, shape (n, 2)
    others : array_like, shape (m, n, 2)

    Returns
    -------
    list of ndarray, shape (n, 2)

    Examples
    --------
    >>> [b.tolist() for b in subtract([[0.0, 3.0]], [[[1.0, 2.0]]])]
    [[[0.0, 1.0]], [[2.0, 3.0]]]
    >>> subtract([[0.0, 1.0]], [[[-1.0, 2.0]]])
    []
    """
    box = _validate.array(box, "box", ndim=2)
    others = _validate.array(others, "others", ndim=3)
    if box.shape[1:] != (2,) or others.shape[1:] != box.shape or np.any(
            box[:, 0] > box[:, 1]) or np.any(others[..., 0] > others[..., 1]):
        raise ValueError(f"box must be (n, 2) and others (m, n, 2), with lo <= hi, got shapes "
                         f"{box.shape} and {others.shape}")
    pieces = [box]
    for other in others:
        left = []
        for piece in pieces:
            if not _interiors_meet(piece, other):
                left.append(piece)
                continue
            rest = piece.copy()
            for d in range(len(rest)):
                if rest[d, 0] < other[d, 0]:
                    cut = rest.copy()
                    cut[d, 1] = other[d, 0]
                    left.append(cut)
                    rest[d, 0] = other[d, 0]
                if rest[d, 1] > other[d, 1]:
                    cut = rest.copy()
                    cut[d, 0] = other[d, 1]
                    left.append(cut)
                    rest[d, 1] = other[d, 1]
        pieces = [p for p in left if np.all(p[:, 1] > p[:, 0])]
    return pieces
