"""Paths in the 3PRR's pose space that avoid every singularity: assembly-mode changes.

A working mode (one branch of each leg, :func:`branch_inputs`) maps poses to inputs. Two poses of
the same working mode with the same inputs are two assembly modes of one input. If a path of
poses joins them with every leg reaching its guide (no inverse singularity) and the direct
Jacobian's determinant never vanishing (no direct singularity), the inputs along it trace a loop
that starts and ends at the same input: the mechanism changes assembly mode without crossing a
singularity, which a planar parallel mechanism can do by encircling a cusp of its singularity
surface in input space (Innocenti and Parenti-Castelli, 1998).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.prr3._geometry import Geometry, check, jacobian_dets, radicands, vectors
from mechnum.mechanisms.prr3._inverse import branch_inputs
from mechnum.results import Result

# Passes of neighbour averaging that turn the voxel staircase into a smooth path (each pass
# spreads a corner over one more point; 30 round the corners of a path of a few dozen voxels).
_SMOOTHING = 30
# Each segment between two voxel centres of the path is checked at this many points: the
# determinant and the radicands are smooth, and a voxel is small against their variation.
_CHECKS_PER_STEP = 8
MAX_VOXELS = 2_000_000
"""The most voxels of a search (6 times the default grid's): each holds a pose, its inputs and
determinant, some 200 bytes, so 2e6 voxels take about 400 MB."""


def _region(mech, poses, signs, sign):
    """Voxels where every leg reaches its guide and ``det J`` has the sign ``sign``."""
    lam = branch_inputs(mech, poses, signs)
    reach = np.all(radicands(mech, poses) > 0, axis=-1)
    det = jacobian_dets(mech, poses, np.where(np.isnan(lam), 0.0, lam))[1]
    return reach & (np.sign(det) == sign)


def _bfs(region, start, end):
    """Voxel indices of a shortest 6-neighbour path from ``start`` to ``end`` inside
    ``region`` (periodic along the last axis), or None."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import breadth_first_order

    ids = np.full(region.shape, -1)
    ids[region] = np.arange(region.sum())
    if ids[start] < 0 or ids[end] < 0:  # an end's voxel centre lies across a singularity
        return None
    rows, cols = [], []
    for axis in range(3):
        ahead = np.roll(ids, -1, axis=axis)
        both = (ids >= 0) & (ahead >= 0)
        if axis < 2:  # x and y are not periodic: drop the wrapped layer
            index = [slice(None)] * 3
            index[axis] = -1
            both[tuple(index)] = False
        rows.append(ids[both])
        cols.append(ahead[both])
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    n = int(region.sum())
    graph = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n)).tocsr()
    _, parent = breadth_first_order(graph, ids[start], directed=False, return_predecessors=True)
    node, chain = ids[end], []
    if node != ids[start] and parent[node] < 0:
        return None
    while node >= 0:
        chain.append(node)
        node = parent[node]
    where = np.argwhere(region)
    return where[chain[::-1]]


@dataclass(frozen=True, kw_only=True)
class ModeChangePath(Result):
    """The outcome of :func:`mode_change_path`.

    Attributes
    ----------
    x : ndarray, shape (k, 3)
        The path's poses, from ``start`` to ``end`` (``k = 0`` where none was found); ``psi``
        is continuous along it, so it may end at ``end``'s angle plus a multiple of ``2 pi``.
    status : str
        ``"converged"``: the path was found and checked finely, a certificate;
        ``"undecided"``: none was found at this resolution, which does not show that none
        exists.
    message : str
        The outcome in a sentence.
    iterations, nfev, njev : int
        Zero; ``voxels`` counts the work.
    voxels : int
        Voxels of the search.
    """

    voxels: int


def mode_change_path(mech: Geometry, start: ArrayLike, end: ArrayLike, signs: ArrayLike, *,
                     bounds: ArrayLike, shape: tuple[int, int, int] = (70, 50, 90)
                     ) -> ModeChangePath:
    """A path of poses from ``start`` to ``end`` that crosses no singularity.

    Both poses must belong to the working mode ``signs`` and have the same sign of the direct
    Jacobian's determinant. The pose space inside ``bounds`` (``psi`` periodic) is cut into
    voxels; a breadth-first search finds a shortest chain of neighbouring voxels where every
    leg reaches its guide and the determinant keeps its sign; the path (the voxel centres, with
    ``psi`` unwrapped, smoothed by neighbour averaging where that keeps it safe) is then
    checked finely. It is a certificate when it is found (status ``"converged"``); the status
    ``"undecided"`` means none was found at this resolution, not that none exists.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    start, end : array_like, shape (3,)
        Poses ``(x, y, psi)``.
    signs : array_like of +-1, shape (3,)
        The working mode (:func:`branch_inputs`).
    bounds : array_like, shape (2, 2)
        ``[[x_min, x_max], [y_min, y_max]]`` of the search, metres.
    shape : tuple of 3 int, optional
        Voxels along ``x``, ``y`` and ``psi``, at least 2 each and :data:`MAX_VOXELS` in all.

    Returns
    -------
    ModeChangePath

    Raises
    ------
    ValueError
        If an argument is ill-shaped or not finite, the poses lie outside ``bounds``, or their
        determinants differ in sign or vanish.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3.study import EXAMPLES
    >>> g = EXAMPLES["Table 5"][0]
    >>> a, b = np.array([2.2, 0.5, 3.0]), np.array([2.3, 0.5, 3.2])
    >>> path = mode_change_path(g, a, b, (1, 1, 1), bounds=[[1.5, 3.5], [0.0, 1.0]],
    ...                         shape=(20, 10, 36))
    >>> path.status, bool(np.allclose(path.x[0], a) and np.allclose(path.x[-1], b))
    ('converged', True)
    """
    check(mech)
    start = _validate.array(start, "start", shape=(3,))
    end = _validate.array(end, "end", shape=(3,))
    signs = _validate.array(signs, "signs", shape=(3,))
    bounds = _validate.array(bounds, "bounds", shape=(2, 2))
    shape = tuple(_validate.maxiter(n, "shape", minimum=2, maximum=MAX_VOXELS)
                  for n in _validate.array(shape, "shape", shape=(3,)))
    if np.prod(shape) > MAX_VOXELS:
        raise ValueError(f"shape must hold at most {MAX_VOXELS} voxels (a bound on the work), "
                         f"got {shape}")
    ends = np.stack([start, end])
    dets = jacobian_dets(mech, ends, branch_inputs(mech, ends, signs))[1]
    if not np.all(np.isfinite(dets)) or dets[0] * dets[1] <= 0:
        raise ValueError(f"start and end must have direct-Jacobian determinants of one sign "
                         f"in working mode {signs.tolist()}, got {dets.tolist()}")
    for pose, name in ((start, "start"), (end, "end")):
        if not np.all((bounds[:, 0] <= pose[:2]) & (pose[:2] <= bounds[:, 1])):
            raise ValueError(f"{name} = {pose.tolist()} lies outside bounds {bounds.tolist()}")
    axes = [np.linspace(*bounds[0], shape[0]), np.linspace(*bounds[1], shape[1]),
            np.linspace(0, 2 * np.pi, shape[2], endpoint=False)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    region = _region(mech, grid, signs, np.sign(dets[0]))

    def voxel(pose):
        steps = [np.abs(axes[0] - pose[0]).argmin(), np.abs(axes[1] - pose[1]).argmin(),
                 int(np.round(np.mod(pose[2], 2 * np.pi) / (2 * np.pi / shape[2]))) % shape[2]]
        return tuple(steps)

    chain = _bfs(region, voxel(start), voxel(end))
    voxels = int(np.prod(shape))
    if chain is None:
        return _outcome(np.empty((0, 3)), voxels)
    centres = grid[tuple(chain.T)]
    path = np.vstack([start, centres, end])
    path[:, 2] = np.unwrap(path[:, 2])
    path[-1, 2] = path[-2, 2] + np.mod(end[2] - path[-2, 2] + np.pi, 2 * np.pi) - np.pi
    for candidate in (_smoothed(path), path):  # the smooth path if it passes the check
        if _certified(mech, candidate, signs, np.sign(dets[0])):
            return _outcome(candidate, voxels)
    return _outcome(np.empty((0, 3)), voxels)


def _outcome(path, voxels):
    """The :class:`ModeChangePath` of a path (empty: none found)."""
    found = len(path) > 0
    message = (f"a path of {len(path)} poses that crosses no singularity, checked finely"
               if found else f"no path found on {voxels} voxels: a finer grid may find one")
    return ModeChangePath(x=path, status="converged" if found else "undecided",
                          message=message, iterations=0, nfev=0, njev=0, voxels=voxels)


def _smoothed(path):
    """``path`` with its interior points averaged with their neighbours: the voxel staircase
    becomes a smooth curve with the same ends."""
    out = path.copy()
    for _ in range(_SMOOTHING):
        out[1:-1] = (out[:-2] + 2 * out[1:-1] + out[2:]) / 4
    return out


def _certified(mech, path, signs, sign):
    """Whether every point of ``path``, and :data:`_CHECKS_PER_STEP` points between each two,
    lies where the legs reach their guides and ``det J`` has the sign ``sign``."""
    steps = np.linspace(0, 1, _CHECKS_PER_STEP, endpoint=False)[:, None]
    fine = np.concatenate([a + steps * (b - a) for a, b in zip(path[:-1], path[1:])]
                          + [path[-1:]])
    return bool(np.all(_region(mech, vectors(fine, "path"), signs, sign)))
