"""One rod's chart cut into boxes, each with its tip and force enclosed once: the leaves.

A :class:`ChartRod` is a clamped-pinned rod of a mechanism (stiffness, length, mode, clamp),
searched over its regular chart ``(psi, t)`` (``rods._regular``) on both branches:
``0 <= psi <= 2 pi``, ``0 <= sign t <= t_max``. :class:`Leaves` holds the boxes of that chart
that a search has made, as arrays (one row per box, never removed): the box, its branch, its
parent and children, and the enclosures of :func:`enclose`, in the global frame, rounded
outward (each float bound holds the exact bound of the box's rods):

=========  =========================================================
columns    what
=========  =========================================================
0:2, 2:4   tip, lower and upper (m)
4:6, 6:8   force on the rod at its tip, lower and upper (N)
8, 9       the force's magnitude ``R``, lower and upper (N)
10, 11     the force's direction ``psi + angle`` (rad), lower and upper
12, 13     where the enclosures widen: ``|J| width`` per chart axis
=========  =========================================================

The enclosures come from ``rods._balls`` (Arb's balls, every operation rounded
outward), intersected with the mean-value form ``value(centre) + J(box) (box - centre)``, which
is the tighter of the two once a box is small. The branch of a box is stored, never guessed
from the box (a box ``[-0.25, 0]`` as a ball pokes above 0).

A box is cut in two along one axis (:func:`cut`): ``t`` at its middle; ``psi`` at its middle,
or, where the rods of the box reach the edge ``psi = 0`` or ``2 pi`` of a branch on which the
load grows without bound there (every branch but mode 1's growing one, whose rods at that edge
are straight), at the geometric mean of the distances to that edge (at 1/64 of the far one
when the box touches it): the load grows like ``log(1 / psi)``, so halving ``psi`` would
gain one ``log 2`` of it per cut.
"""

import math
from dataclasses import dataclass

import numpy as np
from flint import arb

from mechnum import _validate
from mechnum.certify import balls as B
from mechnum.certify.balls import ball, bounds
from mechnum.rods import _balls as balls
from mechnum.rods import _regular as regular

TWO_PI = 2.0 * np.pi
COLUMNS = 14
EDGE_SHARE = 1.0 / 64.0
"""Where a box touching a singular edge of ``psi`` is cut: at this share of its far end."""
GEOMETRIC = 4.0
"""A box of ``psi`` whose far distance to the edge exceeds this many times its near one is cut
at their geometric mean."""


@dataclass(frozen=True)
class ChartRod:
    """A rod of a mechanism, as a search over its chart sees it.

    Attributes
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    mode : int
        Buckling mode.
    origin : tuple of float
        The clamp (m).
    angle : float
        The clamped tangent's angle (rad).
    t_max : float
        The chart's ``|t|`` is searched up to here (``<= T_MAX``; from an a-priori bound).
    lam_max : float
        No equilibrium has ``Lambda = lambda L`` above this (``inf``: no bound).
    """

    EI: float
    L: float
    mode: int
    origin: tuple
    angle: float
    t_max: float = regular.T_MAX
    lam_max: float = math.inf

    def __post_init__(self):
        for name in ("EI", "L", "t_max"):
            object.__setattr__(self, name, _validate.scalar(getattr(self, name), name,
                                                            positive=True))
        lam_max = _validate.array(self.lam_max, "lam_max", shape=(), finite=False)
        if np.isnan(lam_max) or not lam_max > 0:
            raise ValueError(f"lam_max must be positive (or inf), got {float(lam_max)!r}")
        object.__setattr__(self, "lam_max", float(lam_max))
        if self.t_max > regular.T_MAX:
            raise ValueError(f"t_max must be at most T_MAX = {regular.T_MAX!r}, got "
                             f"{self.t_max!r}")
        if isinstance(self.mode, bool) or int(self.mode) != self.mode or self.mode < 1:
            raise ValueError(f"mode must be an integer >= 1, got {self.mode!r}")
        object.__setattr__(self, "mode", int(self.mode))
        origin = _validate.array(self.origin, "origin", shape=(2,))
        object.__setattr__(self, "origin", tuple(float(x) for x in origin))
        object.__setattr__(self, "angle", _validate.scalar(self.angle, "angle"))

    @property
    def R_max(self):
        """float: the largest force magnitude ``EI lam_max**2 / L**2`` (rounded up)."""
        if math.isinf(self.lam_max):
            return math.inf
        bound = arb(self.EI) * arb(self.lam_max) ** 2 / arb(self.L) ** 2
        return math.nextafter(float(bound.upper()), math.inf)

    def domains(self):
        """The chart's two closed boxes ``[[0, 2 pi], [0, t_max]]`` and ``[[0, 2 pi],
        [-t_max, 0]]``, with their branches ``(1, -1)``."""
        return (np.array([[[0.0, TWO_PI], [0.0, self.t_max]],
                          [[0.0, TWO_PI], [-self.t_max, 0.0]]]), np.array([1, -1]))


def growing(mode, sign, psi_lo, psi_hi):
    """Whether the boxes lie on mode 1's growing branch (``sign(t) = sign(cos(psi / 2))``),
    where the rods at ``psi = 0`` and ``2 pi`` are straight (elsewhere the load is unbounded
    there). Vectorised over the boxes; a box across ``psi = pi`` counts as not growing."""
    left, right = psi_hi <= np.pi, psi_lo >= np.pi
    return (mode == 1) & (((sign > 0) & left) | ((sign < 0) & right))


def cut(box, dim, mode, sign):
    """Where to cut boxes ``(m, 2, 2)`` along their axes ``dim`` (m,) (see the module)."""
    rows = np.arange(len(box))
    lo, hi = box[rows, dim, 0], box[rows, dim, 1]
    middle = 0.5 * lo + 0.5 * hi
    left, right = hi <= np.pi, lo >= np.pi
    near = np.where(left, lo, TWO_PI - hi)
    far = np.where(left, hi, TWO_PI - lo)
    singular = (dim == 0) & (left | right) & ~growing(mode, sign, box[:, 0, 0], box[:, 0, 1])
    with np.errstate(invalid="ignore"):
        at = np.where(near == 0.0, EDGE_SHARE * far, np.sqrt(near * far))
        use = singular & ((near == 0.0) | (far > GEOMETRIC * near))
    at = np.where(left, at, TWO_PI - at)
    out = np.where(use, at, middle)
    return np.where((out > lo) & (out < hi), out, middle)


def enclose(rod, box, sign, *, mean_value=True):
    """The enclosures of the rods of one chart box, as a row of :data:`COLUMNS` floats.

    Parameters
    ----------
    rod : ChartRod
    box : ndarray, shape (2, 2)
        ``[[psi_lo, psi_hi], [t_lo, t_hi]]`` on the branch ``sign``.
    sign : {1, -1}
        The branch.
    mean_value : bool, optional
        Intersect with the mean-value form (one more evaluation, at the box's centre).

    Examples
    --------
    >>> rod = ChartRod(1.0, 1.0, 1, (0.0, 0.0), 0.0)
    >>> row = enclose(rod, np.array([[2.0, 2.01], [0.5, 0.51]]), 1)
    >>> exact = regular.clamped_pinned_regular(1.0, 1.0, 2.005, 0.505).tip
    >>> bool(np.all(row[0:2] <= exact) and np.all(exact <= row[2:4]))
    True
    """
    X = [ball(*box[0]), ball(*box[1])]
    local = balls.clamped_pinned(rod.EI, rod.L, X[0], X[1], rod.mode, sign, jacobian=True)
    placed = balls.place(local, rod.origin, rod.angle)
    values = placed.tip + placed.force
    J = placed.jacobian
    widths = box[:, 1] - box[:, 0]
    smear = np.array(widths / (TWO_PI, 1.0))
    if all(v.is_finite() for row in J for v in row):
        scale = [1.0 / rod.L] * 2 + [rod.L ** 2 / rod.EI] * 2
        smear = np.array([sum(float(abs(J[r][c]).upper()) * scale[r] for r in range(4))
                          * widths[c] for c in range(2)])
        if mean_value and widths.max() > 0:
            centre = [arb(0.5 * box[c, 0] + 0.5 * box[c, 1]) for c in range(2)]
            point = balls.place(balls.clamped_pinned(rod.EI, rod.L, centre[0], centre[1],
                                                     rod.mode, sign), rod.origin, rod.angle)
            step = [X[c] - centre[c] for c in range(2)]
            form = [v + J[r][0] * step[0] + J[r][1] * step[1]
                    for r, v in enumerate(point.tip + point.force)]
            values = [B.meet(v, m) for v, m in zip(values, form)]
    (tx, ty, fx, fy), R = (bounds(v) for v in values), bounds(local.R)
    direction = (math.nextafter(box[0, 0] + rod.angle, -math.inf),
                 math.nextafter(box[0, 1] + rod.angle, math.inf))
    return np.array([tx[0], ty[0], tx[1], ty[1], fx[0], fy[0], fx[1], fy[1],
                     max(R[0], 0.0), R[1], *direction, *smear])


class Leaves:
    """The boxes of one rod's chart that a search has made, with their enclosures (arrays,
    one row per box, in the order made).

    Attributes
    ----------
    box : ndarray, shape (n, 2, 2)
    sign : ndarray of int, shape (n,)
    data : ndarray, shape (n, COLUMNS)
        :func:`enclose`'s rows.
    children : ndarray of int, shape (n, 2)
        The two halves of a box that was cut (-1 if none).
    dim : ndarray of int, shape (n,)
        The axis it was cut along (-1 if none).
    evaluations : int
        Evaluations of the closed form in balls.

    Examples
    --------
    >>> rod = ChartRod(1.0, 1.0, 1, (0.0, 0.0), 0.0)
    >>> leaves = Leaves(rod)
    >>> ids = leaves.add(*rod.domains())
    >>> halves = leaves.split(ids)
    >>> halves.shape, len(leaves.box), bool(leaves.box[halves[0, 0], 0, 1] == np.pi)
    ((2, 2), 6, True)
    """

    def __init__(self, rod, *, mean_value=True):
        self.rod, self.mean_value = rod, mean_value
        self.box = np.zeros((0, 2, 2))
        self.sign = np.zeros(0, dtype=int)
        self.data = np.zeros((0, COLUMNS))
        self.children = np.zeros((0, 2), dtype=int)
        self.dim = np.zeros(0, dtype=int)
        self.evaluations = 0

    def __len__(self):
        return len(self.box)

    def add(self, boxes, signs):
        """Enclose new boxes ``(m, 2, 2)`` on branches ``signs`` (m,); their ids."""
        boxes, signs = np.asarray(boxes, dtype=float).reshape(-1, 2, 2), np.asarray(signs)
        rows = [enclose(self.rod, b, int(s), mean_value=self.mean_value)
                for b, s in zip(boxes, signs)]
        self.evaluations += len(rows) * (2 if self.mean_value else 1)
        start = len(self.box)
        self.box = np.concatenate((self.box, boxes))
        self.sign = np.concatenate((self.sign, signs.astype(int)))
        self.data = np.concatenate((self.data, np.array(rows).reshape(-1, COLUMNS)))
        self.children = np.concatenate((self.children, np.full((len(boxes), 2), -1)))
        self.dim = np.concatenate((self.dim, np.full(len(boxes), -1)))
        return np.arange(start, len(self.box))

    def split(self, ids, dims=None):
        """Cut the boxes ``ids`` (each at most once: a box already cut gives its halves again)
        along ``dims`` (default: the axis whose ``|J| width`` is largest); the halves' ids,
        shape ``(len(ids), 2)``.

        Raises
        ------
        ValueError
            If ``dims`` does not match ``ids`` or names an axis other than 0 and 1, or a box
            was cut along another axis before.
        """
        ids = np.asarray(ids, dtype=int)
        if dims is None:
            dims = np.argmax(self.data[ids, 12:14], axis=1)
        dims = np.asarray(dims)
        if dims.shape != ids.shape or not np.all((dims == 0) | (dims == 1)):
            raise ValueError(f"dims must be 0 (psi) or 1 (t) for each box, got "
                             f"{_validate.shown(dims)}")
        done = self.dim[ids] >= 0
        if np.any(done & (self.dim[ids] != dims)):
            raise ValueError("a box is cut along one axis only")
        new = ids[~done]
        if len(new):
            d = dims[~done]
            at = cut(self.box[new], d, self.rod.mode, self.sign[new])
            lower, upper = self.box[new].copy(), self.box[new].copy()
            lower[np.arange(len(new)), d, 1] = at
            upper[np.arange(len(new)), d, 0] = at
            made = self.add(np.stack((lower, upper), axis=1).reshape(-1, 2, 2),
                            np.repeat(self.sign[new], 2)).reshape(-1, 2)
            self.children[new], self.dim[new] = made, d
        return self.children[ids]
