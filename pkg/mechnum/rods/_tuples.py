"""Necessary conditions of equilibrium for tuples of leaves, one per rod, tested in floats.

A mechanism of rods whose tips are joined (a point, a rigid platform) is in equilibrium only if
its rods' tips and forces satisfy an :class:`Assembly`: some pairs of tips ``distance`` apart
(0: the same point), the forces summing to the load ``F``, and their moment about the tips'
centroid equal to the load's moment ``M``. Given one leaf per rod (:mod:`mechnum.rods._leaves`:
boxes of the rods' charts with their tips, forces, magnitudes and directions enclosed),
:func:`tuple_codes` tells, for many tuples at once (numpy), which ones **cannot** hold an
equilibrium, and why (:data:`REASONS`):

* ``"tips"``: two tips' boxes cannot be ``distance`` apart;
* ``"area"``: three tips cannot span a triangle of the platform's signed area (its distances
  allow its mirror image too);
* ``"force"``: the boxes of the forces cannot sum to ``F`` (componentwise);
* ``"magnitude"``: a rod's ``R`` misses the distances from 0 to the box
  ``F - sum of the others' forces``;
* ``"direction"``: the force's direction misses the directions of that box (its cone of
  directions, of angle below pi, has the whole box on the far side of one of its edges), or,
  for two rods whose other loads ``C`` are small beside them, the forces are farther from
  antiparallel than ``arcsin(|C| / R)`` allows;
* ``"moment"``: the moments about the centroid cannot sum to ``M``;
* ``"statics"``: with each force ``R_i u_i`` of direction ``u_i`` in its range, the balance
  (and, with a moment, the moments' balance about the centroid) is a square linear system
  ``A R = b`` in the magnitudes; every solution lies in ``Y b + (I - Y A) X`` (``X``: the
  magnitudes' ranges, ``Y``: the inverse of ``A``'s midpoint; the linear form of Krawczyk's
  operator), which misses ``X``: the magnitudes the directions demand are not in range.

:func:`leaf_codes` drops single leaves: ``"bound"`` (``R`` above the a-priori bound of the rod)
and ``"reach"`` (a tip that cannot come within ``L + distance`` of a partner's clamp).

**Rounding.** Every bound in the leaves is already rounded outward. The tests combine them with
a few float additions, multiplications and square roots (IEEE 754, rounded to nearest: each
has a relative error of at most ``2**-53``; no function of libm is used: the arcsine is bounded
above by ``x / (1 - x**2)**(1/2)``). A test drops a tuple only when the violation exceeds
:data:`MARGIN` times the size of the numbers compared, more than ten million times any
rounding error the few operations can make: a tuple is dropped only when it provably holds no
equilibrium.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate

REASONS = ("live", "bound", "reach", "tips", "area", "force", "magnitude", "direction",
           "moment", "statics")
"""The codes of :func:`tuple_codes` and :func:`leaf_codes`, by index (0: not dropped)."""
MARGIN = 1e-9
"""Relative margin of every test (see the module)."""
CODE = {name: i for i, name in enumerate(REASONS)}


@dataclass(frozen=True)
class Assembly:
    """What the tips and forces of a mechanism's rods satisfy at an equilibrium.

    Attributes
    ----------
    meets : tuple of (int, int, float)
        ``(i, j, distance)``: the tips of rods ``i`` and ``j`` are ``distance`` apart (m).
    force : tuple of float
        The load: the rods' forces on their tips sum to it (N).
    moment : float or None
        Their moment about the tips' centroid equals it (N m); None: not tested.
    area : float or None
        Three rods: the signed area of the triangle of their tips, ``cross(tip_2 - tip_1,
        tip_3 - tip_1) / 2`` (m^2); None: not tested.
    vertices : array_like, shape (r, 2), or None
        The pins in the platform's frame, about their centroid: then the arms of the moments,
        ``tip_i - centroid = Rot(phi) b_i``, are enclosed from the range of ``phi`` that the
        first two tips allow, far tighter than from the tips' boxes alone.

    Examples
    --------
    >>> Assembly(((0, 1, 0.0),), (0.3, -0.1)).rods
    2
    """

    meets: tuple
    force: tuple
    moment: float = None
    area: float = None
    vertices: tuple = None

    def __post_init__(self):
        meets = []
        try:
            given = list(self.meets)
        except TypeError:
            raise ValueError(f"meets must be a sequence of (i, j, distance), got "
                             f"{_validate.shown(self.meets)}") from None
        for meet in given:
            ends = _validate.array(meet, "meet", shape=(3,))
            if np.any(ends[:2] != np.round(ends[:2])) or ends[0] == ends[1] or min(ends[:2]) < 0:
                raise ValueError(f"a meet is (i, j, distance) with rods i != j, got "
                                 f"{_validate.shown(meet)}")
            meets.append((int(ends[0]), int(ends[1]),
                          _validate.scalar(ends[2], "distance", nonnegative=True)))
        if not meets:
            raise ValueError("an assembly needs one meet or more")
        object.__setattr__(self, "meets", tuple(meets))
        force = _validate.array(self.force, "force", shape=(2,))
        object.__setattr__(self, "force", tuple(float(x) for x in force))
        if self.moment is not None:
            object.__setattr__(self, "moment", _validate.scalar(self.moment, "moment"))
        if self.area is not None:
            object.__setattr__(self, "area", _validate.scalar(self.area, "area"))
        if self.vertices is not None:
            b = _validate.array(self.vertices, "vertices", shape=(None, 2))
            if len(b) < 2 or np.abs(b.mean(axis=0)).max() > 1e-12 * (1 + np.abs(b).max()):
                raise ValueError(f"vertices must be two or more pins about their centroid, "
                                 f"got {b.tolist()}")
            object.__setattr__(self, "vertices", tuple(map(tuple, b.tolist())))

    @property
    def rods(self):
        """int: the rods named by the meets."""
        return 1 + max(max(i, j) for i, j, _ in self.meets)


def _norm_range(lo, hi):
    """``(min, max)`` of ``|x|`` over boxes ``[lo, hi]`` (..., 2), in floats."""
    near = np.maximum(np.maximum(lo, -hi), 0.0)
    far = np.maximum(np.abs(lo), np.abs(hi))
    return np.sqrt((near ** 2).sum(-1)), np.sqrt((far ** 2).sum(-1))


def _size(*arrays):
    """``1 + sum |x|`` over the last axis of each array: the scale of a margin."""
    return 1.0 + sum(np.abs(a).sum(-1) for a in arrays)


def leaf_codes(assembly, rods, k, data):
    """Codes (:data:`REASONS`) of rod ``k``'s leaves ``data`` (m, COLUMNS): ``"bound"`` or
    ``"reach"`` where no equilibrium can use them, 0 elsewhere."""
    rod = rods[k]
    codes = np.zeros(len(data), dtype=np.int8)
    codes[data[:, 8] > rod.R_max * (1 + MARGIN)] = CODE["bound"]
    for i, j, distance in assembly.meets:
        if k not in (i, j):
            continue
        other = rods[j if k == i else i]
        centre = np.asarray(other.origin)
        near, _ = _norm_range(data[:, 0:2] - centre, data[:, 2:4] - centre)
        far = (other.L + distance) * (1 + MARGIN) + MARGIN * _size(centre)
        codes[(codes == 0) & (near > far)] = CODE["reach"]
    return codes


def _tips(assembly, D):
    """The tuples whose tips cannot be the meets' distances apart."""
    out = np.zeros(len(D), dtype=bool)
    for i, j, distance in assembly.meets:
        a, b = D[:, i], D[:, j]
        if distance == 0.0:
            out |= np.any((a[:, 0:2] > b[:, 2:4]) | (b[:, 0:2] > a[:, 2:4]), axis=1)
            continue
        lo, hi = a[:, 0:2] - b[:, 2:4], a[:, 2:4] - b[:, 0:2]
        near, far = _norm_range(lo, hi)
        slack = MARGIN * (distance + _size(lo, hi))
        out |= (near > distance + slack) | (far < distance - slack)
    return out


def _area(area, D):
    """Three tips whose triangle cannot have the signed area ``area``."""
    if D.shape[1] != 3:
        return np.zeros(len(D), dtype=bool)
    u_lo, u_hi = D[:, 1, 0:2] - D[:, 0, 2:4], D[:, 1, 2:4] - D[:, 0, 0:2]
    v_lo, v_hi = D[:, 2, 0:2] - D[:, 0, 2:4], D[:, 2, 2:4] - D[:, 0, 0:2]
    a = _product(u_lo[:, 0], u_hi[:, 0], v_lo[:, 1], v_hi[:, 1])
    b = _product(u_lo[:, 1], u_hi[:, 1], v_lo[:, 0], v_hi[:, 0])
    slack = MARGIN * (1.0 + np.abs(a[0]) + np.abs(a[1]) + np.abs(b[0]) + np.abs(b[1])
                      + abs(area))
    return (a[0] - b[1] > 2 * area + slack) | (a[1] - b[0] < 2 * area - slack)


def _others(D, F, i):
    """The box ``F - sum_{j != i} n_j`` (lo, hi) and its size for the margins."""
    lo, hi = np.array(F, dtype=float).copy(), np.array(F, dtype=float).copy()
    size = _size(lo)
    for j in range(D.shape[1]):
        if j != i:
            lo, hi = lo - D[:, j, 6:8], hi - D[:, j, 4:6]
            size = size + _size(D[:, j, 4:6], D[:, j, 6:8])
    return lo, hi, size


def _forces(F, D):
    """Componentwise: the boxes of the forces cannot sum to ``F``."""
    lo, hi = D[:, :, 4:6].sum(axis=1), D[:, :, 6:8].sum(axis=1)
    slack = MARGIN * _size(D[:, :, 4:6].reshape(len(D), -1), D[:, :, 6:8].reshape(len(D), -1),
                           np.array(F))[:, None]
    return np.any((lo > np.array(F) + slack) | (hi < np.array(F) - slack), axis=1)


def misses_box(lo, hi, c_lo, c_hi, size):
    """Forces in boxes ``[lo, hi]`` (n, 2) that cannot lie in the boxes ``[c_lo, c_hi]``
    (componentwise; ``size``: the scale of the numbers, for the margin)."""
    slack = (MARGIN * size)[..., None]
    return np.any((lo > c_hi + slack) | (hi < c_lo - slack), axis=-1)


def misses_magnitude(R_lo, R_hi, c_lo, c_hi, size):
    """Magnitudes ``[R_lo, R_hi]`` that miss the distances from 0 to the boxes
    ``[c_lo, c_hi]``."""
    near, far = _norm_range(c_lo, c_hi)
    slack = MARGIN * (size + R_hi)
    return (R_lo > far + slack) | (R_hi < near - slack)


def misses_cone(a0, a1, c_lo, c_hi, size):
    """Forces of directions ``[a0, a1]`` (narrower than 3 rad) whose cone has the whole box
    ``[c_lo, c_hi]`` beyond one of its edges. The edges as unit vectors: the cone is
    ``cross(u0, x) >= 0`` and ``cross(x, u1) >= 0``; libm's cosine and sine are within a
    few units of ``2**-53`` of the truth, far inside :data:`MARGIN`."""
    narrow = a1 - a0 < 3.0
    u0, u1 = _unit(a0), _unit(a1)
    corners = [np.stack((x, y), axis=-1) for x in (c_lo[..., 0], c_hi[..., 0])
               for y in (c_lo[..., 1], c_hi[..., 1])]
    slack = MARGIN * size
    below = np.all([u0[..., 0] * c[..., 1] - u0[..., 1] * c[..., 0] < -slack
                    for c in corners], axis=0)
    beyond = np.all([c[..., 0] * u1[..., 1] - c[..., 1] * u1[..., 0] < -slack
                     for c in corners], axis=0)
    return narrow & (below | beyond)


def _magnitudes(F, D):
    out = np.zeros(len(D), dtype=bool)
    for i in range(D.shape[1]):
        lo, hi, size = _others(D, F, i)
        out |= misses_magnitude(D[:, i, 8], D[:, i, 9], lo, hi, size)
    return out


def _unit(angle):
    return np.stack((np.cos(angle), np.sin(angle)), axis=-1)


def _cones(F, D):
    """A force's cone of directions with the box of what it must equal beyond an edge."""
    out = np.zeros(len(D), dtype=bool)
    for i in range(D.shape[1]):
        lo, hi, size = _others(D, F, i)
        out |= misses_cone(D[:, i, 10], D[:, i, 11], lo, hi, size)
    return out


def _antiparallel(F, D):
    """Two rods: ``n_i + n_j = C`` with ``|C| < R_i`` puts ``n_j`` within ``arcsin(|C| / R_i)``
    of ``-n_i``."""
    if D.shape[1] != 2:
        return np.zeros(len(D), dtype=bool)
    C = float(np.hypot(*F)) * (1 + MARGIN)
    R = np.maximum(D[:, 0, 8], D[:, 1, 8])
    x = C / np.where(R > 0, R, np.inf)
    ok = x < 0.5
    delta = np.where(ok, x / np.sqrt(np.where(ok, 1.0 - x * x, 1.0)), np.pi)
    c0, h0 = 0.5 * (D[:, 0, 10] + D[:, 0, 11]), 0.5 * (D[:, 0, 11] - D[:, 0, 10])
    c1, h1 = 0.5 * (D[:, 1, 10] + D[:, 1, 11]), 0.5 * (D[:, 1, 11] - D[:, 1, 10])
    gap = np.abs(np.remainder(c1 - c0, 2.0 * np.pi) - np.pi)
    return ok & (gap > h0 + h1 + delta + MARGIN * (1.0 + np.abs(c0) + np.abs(c1)))


def cos_range(lo, hi):
    """``(min, max)`` of ``cos`` over ``[lo, hi]`` (arrays; all of ``[-1, 1]`` from a width of
    ``2 pi``), from libm's cosine at the ends and the extrema inside."""
    a, b = np.cos(lo), np.cos(hi)
    low, high = np.minimum(a, b), np.maximum(a, b)
    top = np.ceil(lo / (2 * np.pi)) * (2 * np.pi) <= hi                    # 2 k pi inside
    bottom = np.ceil((lo - np.pi) / (2 * np.pi)) * (2 * np.pi) + np.pi <= hi
    return np.where(bottom, -1.0, low), np.where(top, 1.0, high)


def _interval_matmul(Y, lo, hi):
    """``Y [lo, hi]`` for point matrices ``Y`` (n, a, b) and interval ones (n, b, c)."""
    pos, neg = np.maximum(Y, 0.0), np.minimum(Y, 0.0)
    return pos @ lo + neg @ hi, pos @ hi + neg @ lo


def _statics(assembly, D):
    """The ``"statics"`` test (see the module), where the system is square and its midpoint
    well conditioned."""
    n, r = D.shape[:2]
    rows = 3 if assembly.moment is not None else 2
    out = np.zeros(n, dtype=bool)
    if rows != r or not n:
        return out
    a0, a1 = D[:, :, 10], D[:, :, 11]
    c_lo, c_hi = cos_range(a0, a1)
    s_lo, s_hi = cos_range(a0 - np.pi / 2, a1 - np.pi / 2)
    A_lo, A_hi = np.empty((n, rows, r)), np.empty((n, rows, r))
    A_lo[:, 0], A_hi[:, 0], A_lo[:, 1], A_hi[:, 1] = c_lo, c_hi, s_lo, s_hi
    b = np.array(list(assembly.force) + ([assembly.moment] if rows == 3 else []))
    if rows == 3:
        arms_lo, arms_hi = _arms(assembly, D)
        for i in range(r):
            arm_lo, arm_hi = arms_lo[:, i], arms_hi[:, i]
            x = _product(arm_lo[:, 0], arm_hi[:, 0], s_lo[:, i], s_hi[:, i])   # x sin
            y = _product(arm_lo[:, 1], arm_hi[:, 1], c_lo[:, i], c_hi[:, i])   # y cos
            A_lo[:, 2, i], A_hi[:, 2, i] = x[0] - y[1], x[1] - y[0]
    X_lo, X_hi = D[:, :, 8], D[:, :, 9]
    mid = 0.5 * (A_lo + A_hi)
    usable = np.all(np.isfinite(mid), axis=(1, 2)) & np.all(np.isfinite(X_hi), axis=1)
    scale = np.abs(mid).max(axis=(1, 2))
    det = np.linalg.det(mid) if n else np.zeros(0)
    usable &= np.abs(det) > 1e-8 * np.where(scale > 0, scale, 1.0) ** r
    if not usable.any():
        return out
    Y = np.linalg.inv(mid[usable])
    YA_lo, YA_hi = _interval_matmul(Y, A_lo[usable], A_hi[usable])
    eye = np.eye(r)
    M_lo, M_hi = eye - YA_hi, eye - YA_lo
    P = np.stack((M_lo * X_lo[usable][:, None], M_lo * X_hi[usable][:, None],
                  M_hi * X_lo[usable][:, None], M_hi * X_hi[usable][:, None]))
    Yb = Y @ b
    K_lo, K_hi = Yb + P.min(axis=0).sum(-1), Yb + P.max(axis=0).sum(-1)
    scale = np.abs(Y).sum(-1) * (np.abs(b).sum() + 1.0 + (1.0 + np.maximum(
        np.abs(A_lo[usable]), np.abs(A_hi[usable])).max(axis=(1, 2)))[:, None]
        * X_hi[usable].sum(-1)[:, None])
    size = 1.0 + scale + np.abs(P).max(axis=0).sum(-1)
    slack = MARGIN * size
    miss = np.any((K_lo > X_hi[usable] + slack) | (K_hi < X_lo[usable] - slack), axis=1)
    out[usable] = miss
    return out


def _product(alo, ahi, blo, bhi):
    p = np.stack((alo * blo, alo * bhi, ahi * blo, ahi * bhi))
    return p.min(axis=0), p.max(axis=0)


def moments(arm, force):
    """Boxes of ``arm x force`` (``lo, hi``) and their size, for boxes of arms and forces
    ``(..., 4)`` (``lo_x, lo_y, hi_x, hi_y``)."""
    a = _product(arm[..., 0], arm[..., 2], force[..., 1], force[..., 3])     # x n_y
    b = _product(arm[..., 1], arm[..., 3], force[..., 0], force[..., 2])     # y n_x
    size = 1.0 + np.abs(a[0]) + np.abs(a[1]) + np.abs(b[0]) + np.abs(b[1])
    return a[0] - b[1], a[1] - b[0], size


def _turn(D, b):
    """The range ``[lo, hi]`` of the platform's angle ``phi`` that the boxes of the first two
    tips allow (``tip_2 - tip_1 = Rot(phi) (b_2 - b_1)``), and where it is known (the box of
    ``tip_2 - tip_1`` away from 0). The angles of a box's corners, from libm's ``atan2``
    (a few units of ``2**-53``), widened by ``ROUND``."""
    lo, hi = D[:, 1, 0:2] - D[:, 0, 2:4], D[:, 1, 2:4] - D[:, 0, 0:2]
    known = ~np.all((lo <= 0.0) & (hi >= 0.0), axis=1) & np.all(np.isfinite(lo) & np.isfinite(
        hi), axis=1)
    centre = np.arctan2(0.5 * (lo[:, 1] + hi[:, 1]), 0.5 * (lo[:, 0] + hi[:, 0]))
    rel = np.stack([np.remainder(np.arctan2(y, x) - centre + np.pi, 2 * np.pi) - np.pi
                    for x in (lo[:, 0], hi[:, 0]) for y in (lo[:, 1], hi[:, 1])])
    base = np.arctan2(b[1][1] - b[0][1], b[1][0] - b[0][0])
    return centre + rel.min(axis=0) - base - ROUND, centre + rel.max(axis=0) - base + ROUND, known


ROUND = 1e-12
"""Outward widening of angles and arms computed with libm (rad, m)."""


def _arms(assembly, D):
    """Boxes ``(lo, hi)``, ``(n, r, 2)`` each, of the arms ``tip_i - centroid``: from the tips'
    boxes, and, with the platform's ``vertices``, intersected with ``Rot(phi) b_i`` over the
    range of ``phi`` that :func:`_turn` gives."""
    r = D.shape[1]
    lo = np.stack([(r - 1) / r * D[:, i, 0:2] - sum(D[:, j, 2:4] for j in range(r) if j != i)
                   / r for i in range(r)], axis=1)
    hi = np.stack([(r - 1) / r * D[:, i, 2:4] - sum(D[:, j, 0:2] for j in range(r) if j != i)
                   / r for i in range(r)], axis=1)
    if assembly.vertices is None or len(assembly.vertices) != r:
        return lo, hi
    b = np.array(assembly.vertices)
    phi_lo, phi_hi, known = _turn(D, b)
    length, angle = np.hypot(*b.T), np.arctan2(b[:, 1], b[:, 0])
    a0, a1 = phi_lo[:, None] + angle, phi_hi[:, None] + angle
    c_lo, c_hi = cos_range(a0, a1)
    s_lo, s_hi = cos_range(a0 - np.pi / 2, a1 - np.pi / 2)
    widen = ROUND * (1.0 + length)
    exact_lo = np.stack((length * c_lo - widen, length * s_lo - widen), axis=-1)
    exact_hi = np.stack((length * c_hi + widen, length * s_hi + widen), axis=-1)
    lo = np.where(known[:, None, None], np.maximum(lo, exact_lo), lo)
    hi = np.where(known[:, None, None], np.minimum(hi, exact_hi), hi)
    return lo, hi


def _moment(assembly, D):
    """The moments of the forces about the tips' centroid cannot sum to ``M``."""
    M, r = assembly.moment, D.shape[1]
    lo, hi, size = np.zeros(len(D)), np.zeros(len(D)), np.ones(len(D))
    arms_lo, arms_hi = _arms(assembly, D)
    for i in range(r):
        arm_lo, arm_hi = arms_lo[:, i], arms_hi[:, i]
        a = _product(arm_lo[:, 0], arm_hi[:, 0], D[:, i, 5], D[:, i, 7])     # x n_y
        b = _product(arm_lo[:, 1], arm_hi[:, 1], D[:, i, 4], D[:, i, 6])     # y n_x
        lo, hi = lo + a[0] - b[1], hi + a[1] - b[0]
        size = size + np.abs(a[0]) + np.abs(a[1]) + np.abs(b[0]) + np.abs(b[1])
    slack = MARGIN * size * r
    return (lo > M + slack) | (hi < M - slack)


def tuple_codes(assembly, D, only=None):
    """The first reason (:data:`REASONS`) why each tuple cannot hold an equilibrium, or 0.

    Parameters
    ----------
    assembly : Assembly
    D : ndarray, shape (n, r, COLUMNS)
        The leaves' enclosures (:mod:`mechnum.rods._leaves`), one per rod, for ``n`` tuples.
    only : tuple of str, optional
        The tests to run (default: all); ``("tips",)`` serves tuples of some of the rods.

    Returns
    -------
    ndarray of int8, shape (n,)

    Examples
    --------
    Two leaves whose tips' boxes are apart:

    >>> D = np.zeros((1, 2, 14))
    >>> D[0, 1, 0:4] = [1.0, 1.0, 2.0, 2.0]
    >>> REASONS[tuple_codes(Assembly(((0, 1, 0.0),), (0.0, 0.0)), D)[0]]
    'tips'
    """
    D = np.asarray(D, dtype=float)
    codes = np.zeros(len(D), dtype=np.int8)
    F = np.array(assembly.force)
    tests = [("tips", lambda X: _tips(assembly, X))]
    if assembly.area is not None:
        tests.append(("area", lambda X: _area(assembly.area, X)))
    tests += [("force", lambda X: _forces(F, X)),
             ("magnitude", lambda X: _magnitudes(F, X)),
             ("direction", lambda X: _cones(F, X) | _antiparallel(F, X))]
    if assembly.moment is not None:
        tests.append(("moment", lambda X: _moment(assembly, X)))
    tests.append(("statics", lambda X: _statics(assembly, X)))
    live = np.arange(len(D))
    with np.errstate(invalid="ignore", over="ignore"):   # NaN and inf never drop a tuple
        for name, test in tests:
            if len(live) and (only is None or name in only):
                dead = test(D[live])
                codes[live[dead]] = CODE[name]
                live = live[~dead]
    return codes
