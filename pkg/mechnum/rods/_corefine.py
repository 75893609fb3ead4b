"""Co-refinement: one tree of boxes per rod, and the live tuples of boxes, one per rod.

A mechanism of ``r`` clamped-pinned rods joined at their tips has ``2 r`` unknowns, each rod's
chart ``(psi, t)``; a search of that space cut into boxes pays for the product of the rods'
resolutions: where one rod's tip barely depends on one of its coordinates (a straight rod in
tension, whose tip does not move as the tension changes), its boxes must be cut finely, and
under each the other rods' charts are resolved again. Here each rod has its own tree of boxes
over its own chart, both branches (:class:`~mechnum.rods._leaves.Leaves`: each box's tip and
force enclosed **once**), and the search keeps the **tuples** of boxes, one per rod, that may
hold an equilibrium:

1. each rod's chart is cut into a grid; a box beyond the a-priori bound, or whose tip cannot
   reach a partner's clamp, is dropped (:func:`~mechnum.rods._tuples.leaf_codes`); the first
   tuples are the products of the boxes left, built rod by rod and kept where the tips can be
   their distances apart, then tested whole;
2. each **round** cuts every box of a live tuple in two (:meth:`Leaves.split`) and replaces
   each live tuple by its ``2**r`` children, which are tested
   (:func:`~mechnum.rods._tuples.tuple_codes`: tips, forces componentwise, in magnitude, in
   direction and as a linear system in the magnitudes, moments); only boxes of live tuples are
   ever cut;
3. between rounds, live tuples covered by boxes whose roots a Krawczyk search counts (the
   **settled** boxes, which never overlap, so that each root is counted in one) leave the
   rounds (:meth:`Refinement.resolve`; :mod:`mechnum.rods._cosearch` finds those boxes).

**Completeness.** A tuple is dropped only when the floats of its enclosures prove that it holds
no equilibrium (:mod:`mechnum.rods._tuples`: every bound rounded outward, every test a
necessary condition), a box only when no equilibrium can use it, and the children of a tuple
cover it. So after every round, every equilibrium of the searched domain (each rod's chart,
both branches, up to its a-priori bound) lies in a live tuple or in a box that a Krawczyk
search covers, which counts it once.
"""

import itertools
import time

import numpy as np

from mechnum import _validate
from mechnum.rods._clusters import subtract
from mechnum.rods._leaves import COLUMNS, ChartRod, Leaves
from mechnum.rods._tuples import REASONS, Assembly, leaf_codes, tuple_codes

GRID = (16, 4)
"""The first grid of each branch of each rod's chart: cells in ``psi`` and in ``t``."""
MAX_GRID = 256
CHUNK = 100_000
"""Tuples tested at once (memory: ``CHUNK * r * COLUMNS`` floats)."""


class Refinement:
    """The rods' boxes and the live tuples of a co-refinement, round by round.

    Parameters
    ----------
    rods : sequence of mechnum.rods._leaves.ChartRod
    assembly : mechnum.rods._tuples.Assembly
    grid : (int, int)
        Cells of the first grid in ``psi`` and ``t`` (each ``<= MAX_GRID``).

    Attributes
    ----------
    live : ndarray of int, shape (n, r)
        The live tuples: one box id per rod.
    leaves : list of mechnum.rods._leaves.Leaves
    history : list of dict
        Per round (0: the first grid): ``tested``, ``live``, ``boxes``, ``evaluations``,
        ``seconds``, ``volume`` (the live tuples' share of the domain), ``dropped`` (by
        reason).
    dims : list of tuple of str
        Per round and rod, the axis of every cut (``"0"``: psi, ``"1"``: t), in order of the
        boxes' ids.
    resolved : list of ndarray
        Per round, the boxes settled by Krawczyk's search after it.
    """

    def __init__(self, rods, assembly, grid=GRID):
        if assembly.rods != len(rods):
            raise ValueError(f"the assembly joins {assembly.rods} rods, {len(rods)} given")
        self.grid = tuple(_validate.maxiter(g, "grid", maximum=MAX_GRID) for g in grid)
        self.rods, self.assembly = list(rods), assembly
        self.leaves = [Leaves(rod) for rod in self.rods]
        self.history, self.dims, self.tested = [], [], 0
        self.resolved = [self._empty()]
        self.start = time.perf_counter()
        dropped = dict.fromkeys(REASONS[1:], 0)
        first = [self._grid(k, dropped) for k in range(len(rods))]
        self.live = self._products(first, dropped)
        self._record(dropped)

    def _empty(self):
        return np.zeros((0, 2 * len(self.rods), 2))

    def _grid(self, k, dropped):
        """Rod ``k``'s first grid; the ids of its boxes that :func:`leaf_codes` keeps."""
        domains, signs = self.rods[k].domains()
        n_psi, n_t = self.grid
        boxes, branch = [], []
        for (psi, t), sign in zip(domains, signs):
            edges_p, edges_t = np.linspace(*psi, n_psi + 1), np.linspace(*t, n_t + 1)
            edges_p[-1], edges_t[[0, -1]] = psi[1], t
            for i, j in itertools.product(range(n_psi), range(n_t)):
                boxes.append([edges_p[i:i + 2], edges_t[j:j + 2]])
                branch.append(sign)
        ids = self.leaves[k].add(np.array(boxes), np.array(branch))
        codes = leaf_codes(self.assembly, self.rods, k, self.leaves[k].data[ids])
        _count(dropped, codes)
        return ids[codes == 0]

    def _products(self, first, dropped):
        """The first tuples: rod by rod, the partial tuples whose tips can meet, then the
        whole tuples that pass every test."""
        T = first[0][:, None]
        for k in range(1, len(first)):
            T = np.column_stack((np.repeat(T, len(first[k]), axis=0),
                                 np.tile(first[k], len(T))))
            partial = k < len(first) - 1
            codes = self._codes(T, ("tips",) if partial else None, rods=k + 1)
            _count(dropped, codes)
            T = T[codes == 0]
        return T

    def _codes(self, T, only=None, rods=None):
        """:func:`tuple_codes` of tuples ``T`` (n, k) of the first ``rods`` rods, in chunks."""
        assembly = self.assembly
        if rods is not None and rods < len(self.rods):
            assembly = type(assembly)(tuple(m for m in assembly.meets if max(m[:2]) < rods),
                                      assembly.force)
        out = np.zeros(len(T), dtype=np.int8)
        for s in range(0, len(T), CHUNK):
            part = T[s:s + CHUNK]
            D = np.empty((len(part), part.shape[1], COLUMNS))
            for k in range(part.shape[1]):
                D[:, k] = self.leaves[k].data[part[:, k]]
            out[s:s + CHUNK] = tuple_codes(assembly, D, only)
        self.tested += len(T)
        return out

    def step(self, dims=None):
        """One round: cut every box of a live tuple (rod ``k``'s along ``dims[k]``, one axis
        per box in order of their ids, or along the axis that widens its enclosures most),
        and keep the children tuples that may hold an equilibrium."""
        r = len(self.rods)
        if dims is not None and len(dims) != r:
            raise ValueError(f"a round needs the axes of {r} rods, got {len(dims)}")
        halves, used, dropped = [], [], dict.fromkeys(REASONS[1:], 0)
        for k in range(r):
            boxes, where = np.unique(self.live[:, k], return_inverse=True)
            given = None if dims is None else _axes(dims[k], len(boxes))
            pair = self.leaves[k].split(boxes, given)
            codes = leaf_codes(self.assembly, self.rods, k,
                               self.leaves[k].data[pair.ravel()]).reshape(-1, 2)
            used.append("".join(map(str, self.leaves[k].dim[boxes])))
            halves.append((pair[where], codes[where]))
        children = []
        for bits in itertools.product((0, 1), repeat=r):
            codes = np.max(np.column_stack([halves[k][1][:, b] for k, b in enumerate(bits)]),
                           axis=1)
            _count(dropped, codes)
            keep = codes == 0
            children.append(np.column_stack([halves[k][0][keep, b]
                                             for k, b in enumerate(bits)]))
        T = np.concatenate(children)
        self.tested += int(sum(dropped.values()))
        codes = self._codes(T)
        _count(dropped, codes)
        self.live = T[codes == 0]
        self.dims.append(tuple(used))
        self.resolved.append(self._empty())
        self._record(dropped)

    def resolve(self, hull, final=False):
        """Record the boxes ``hull`` (chart boxes whose roots Krawczyk's search counts, none
        overlapping another settled box) as settled after this round (``final``: after the
        last), and drop the live tuples that the settled boxes cover together."""
        hull = np.asarray(hull, dtype=float).reshape((-1,) + self._empty().shape[1:])
        if final:
            self.resolved.append(hull)
        else:
            self.resolved[-1] = np.concatenate((self.resolved[-1], hull))
        if not (len(hull) and len(self.live)):
            return
        boxes, settled = self.boxes()[0], self.resolved_hulls()
        touched = np.nonzero(_meets(boxes, hull).any(axis=1))[0]
        if len(touched):
            near = _meets(boxes[touched], settled)
            covered = [not subtract(boxes[i], settled[row]) for i, row in zip(touched, near)]
            keep = np.ones(len(self.live), dtype=bool)
            keep[touched[np.array(covered, dtype=bool)]] = False
            self.live = self.live[keep]

    def resolved_hulls(self):
        """Every settled box, in order."""
        return np.concatenate(self.resolved)

    def boxes(self, T=None):
        """The tuples' boxes in the full chart ``(psi_1, t_1, ..., psi_r, t_r)``, shape
        ``(n, 2 r, 2)``, and their branches as one key per tuple."""
        T = self.live if T is None else T
        r = len(self.rods)
        boxes = np.concatenate([self.leaves[k].box[T[:, k]] for k in range(r)], axis=1)
        keys = sum(((self.leaves[k].sign[T[:, k]] > 0).astype(int) << k) for k in range(r))
        return boxes.reshape(-1, 2 * r, 2), np.asarray(keys, dtype=int)

    def volume(self):
        """The live tuples' share of the searched domain's volume."""
        boxes, _ = self.boxes()
        total = np.prod([2.0 * float(np.prod(np.diff(rod.domains()[0][0], axis=1)))
                         for rod in self.rods])
        return float(np.prod(boxes[..., 1] - boxes[..., 0], axis=1).sum() / total)

    def _record(self, dropped):
        self.history.append({"tested": int(self.tested), "live": len(self.live),
                             "boxes": sum(len(x) for x in self.leaves),
                             "evaluations": sum(x.evaluations for x in self.leaves),
                             "seconds": round(time.perf_counter() - self.start, 3),
                             "volume": self.volume(),
                             "dropped": {k: v for k, v in dropped.items() if v}})


def checked(rods, assembly, system=None):
    """The inputs of :func:`corefine` (and of the verifier), checked: rods, assembly and, if
    given, the four functions of the system.

    Raises
    ------
    ValueError
        If ``rods`` is not a sequence of :class:`~mechnum.rods._leaves.ChartRod`, one per rod of
        ``assembly`` (an :class:`~mechnum.rods._tuples.Assembly`), or ``system`` not
        ``(residual, jacobian, exclude or None, split or None)``.
    """
    if isinstance(rods, (str, bytes)) or not hasattr(rods, "__len__") or not all(
            isinstance(rod, ChartRod) for rod in rods):
        raise ValueError(f"rods must be a sequence of ChartRod, got {_validate.shown(rods)}")
    if not isinstance(assembly, Assembly) or assembly.rods != len(rods):
        raise ValueError(f"assembly must be an Assembly of the {len(rods)} rods, got "
                         f"{_validate.shown(assembly)}")
    if system is not None:
        if not isinstance(system, (tuple, list)) or len(system) != 4:
            raise ValueError(f"system must be (residual, jacobian, exclude, split), got "
                             f"{_validate.shown(system)}")
        for name, f in zip(("residual", "jacobian", "exclude", "split"), system):
            _validate.function(f, name, optional=name in ("exclude", "split"))
        system = tuple(system)
    return list(rods), assembly, system


def _count(dropped, codes):
    for code in np.unique(codes[codes > 0]):
        dropped[REASONS[code]] += int(np.sum(codes == code))


def _axes(text, count):
    """The axes of a string of ``"0"`` and ``"1"`` (one per box)."""
    if not isinstance(text, str) or len(text) != count or set(text) - {"0", "1"}:
        raise ValueError(f"the axes of {count} cuts must be {count} characters 0 or 1, got "
                         f"{_validate.shown(text)}")
    return np.frombuffer(text.encode(), dtype=np.uint8) - ord("0")


def _meets(boxes, others):
    """``(n, m)``: whether the interiors of boxes ``(n, d, 2)`` and ``others`` ``(m, d, 2)``
    meet."""
    return np.all((boxes[:, None, :, 0] < others[None, :, :, 1])
                  & (others[None, :, :, 0] < boxes[:, None, :, 1]), axis=2)
