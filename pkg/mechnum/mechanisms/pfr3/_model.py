"""The 3PFR's geometry and equilibrium equations in closed form (study 001: 11.4, 13.3).

Three sliders move on straight guides: slider ``i`` sits at ``C_i = O_i + lambda_i (cos alpha_i,
sin alpha_i)`` and clamps rod ``i`` at the angle ``theta_i``. The rods' tips are pinned to the
vertices ``B_i`` of a rigid equilateral platform of side ``a`` with centre ``P = (x, y)`` and
angle ``phi``::

    B_i = P + Rot(phi) b_i,   b_i = a / sqrt(3) (cos beta_i, s sin beta_i),
    beta = (-150, -30, 90) deg

(the local vertices of the study's Annex II 4.1; ``s = +1``: ``B1, B2, B3`` anticlockwise, ``s =
-1``: the mirror image). A force ``F`` and a moment ``M`` act on the platform at ``P``. With
``n_i`` the force on rod ``i`` at its tip (:mod:`mechnum.rods`), the platform is in equilibrium
when ``n1 + n2 + n3 = F`` and ``sum_i (B_i - P) x n_i = M``.

Each rod is a clamped-pinned elastica in the regular chart ``(psi_i, t_i)`` of
:mod:`mechnum.rods`. Two formulations of the same equations:

* the **reduced** one (:func:`forward_system`): six unknowns, the chart ``(psi1, t1, psi2, t2,
  psi3, t3)``; ``P`` is the centroid of the tips and ``d_i = tip_i - P``; the tips form the platform
  when, in complex numbers, ``d_1 / b_1 = d_2 / b_2`` and ``|d_1 / b_1| = 1`` (then ``d_i =
  e^{i phi} b_i``): a rotation of the platform, never its mirror image (the study's (114) checks
  the three side lengths only, which a mirror image also satisfies);
* the **full** one (:func:`full_system`): nine equations ``tip_i = B_i(P, phi)``, the forces and
  the moment, in the rods' charts, the sliders ``lambda`` and the pose, for the Jacobians of the
  direct and inverse problems and for continuation.

Residuals are dimensionless: positions over ``L`` (or over ``|b_i|``), forces over ``EI / L**2``,
moments over ``EI / L``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError, UnreachablePoseError
from mechnum.mechanisms import thesis
from mechnum.mechanisms._assembly import Layout, check_modes, check_type
from mechnum.mechanisms.thesis import EI, LENGTH
from mechnum.rods import T_MAX, ClampedRods, in_chart, k_rel_from_t, t_from_k_rel

LAYOUT = Layout(rods=3, inputs=3, pose=3)
"""The unknowns of the full system: the chart (6), the sliders ``lambda`` (3), the pose (3)."""

VERTEX_ANGLES = np.radians([-150.0, -30.0, 90.0])
"""Directions of the platform's pins from its centre (Annex II 4.1, ``PB_loc``), rad."""
UNIT_CIRCLE = np.stack((np.cos(VERTEX_ANGLES), np.sin(VERTEX_ANGLES)), axis=-1)
"""The guides' reference points ``O_i`` of the study's examples: ``(cos, sin)`` of -150, -30
and 90 deg, as its code computes them (13.3.1 prints them rounded, ``(-0.866, -0.5)``...)."""
STUDY_GUIDES = np.radians([0.0, 120.0, -120.0])
"""The guides' angles ``alpha_i`` of Annex II 4.1 and 4.4 (rad)."""


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A 3PFR mechanism: three sliders on guides, three rods, a triangular platform.

    Attributes
    ----------
    origins : ndarray, shape (3, 3)
        The guides' reference points ``O_i`` (m), from which ``lambda_i`` is measured.
    guide_angles : ndarray, shape (3,)
        Directions ``alpha_i`` of the guides (rad).
    clamp_angles : ndarray, shape (3,)
        Angles ``theta_i`` of the rods at their clamps (rad).
    a : float
        Side of the equilateral platform (m).
    force : ndarray, shape (2,)
        External force on the platform at its centre (N).
    moment : float
        External moment on the platform (N m, anticlockwise).
    L, EI : float
        Length (m) and bending stiffness (N m^2) of each rod.
    orientation : {1, -1}
        1: the pins ``B1, B2, B3`` go anticlockwise around the platform; -1: the mirror image.
    diameter : float
        Diameter of the rods' circular section (m), for their bending strain only.
    strain_limit : float
        The rods' elastic limit in strain (:data:`mechnum.mechanisms.thesis.STRAIN_LIMIT`).

    Raises
    ------
    ValueError
        If an attribute is not finite or has the wrong shape.
    GeometryError
        If ``a``, ``L``, ``EI``, ``diameter`` or ``strain_limit`` is not positive, or
        ``orientation`` is not 1 or -1.

    Examples
    --------
    >>> np.round(np.degrees(TABLE8.clamp_angles), 6).tolist(), TABLE8.a, TABLE8.force.tolist()
    ([45.0, 180.0, -60.0], 0.2, [0.0, 0.5])
    """

    origins: np.ndarray
    guide_angles: np.ndarray
    clamp_angles: np.ndarray
    a: float
    force: np.ndarray = field(default_factory=lambda: np.zeros(2))
    moment: float = 0.0
    L: float = LENGTH
    EI: float = EI
    orientation: int = 1
    diameter: float = thesis.DIAMETER
    strain_limit: float = thesis.STRAIN_LIMIT

    def __post_init__(self):
        for name, shape in (("origins", (3, 2)), ("guide_angles", (3,)),
                            ("clamp_angles", (3,)), ("force", (2,))):
            object.__setattr__(self, name, _validate.array(getattr(self, name), name,
                                                           shape=shape))
        object.__setattr__(self, "moment", _validate.scalar(self.moment, "moment"))
        for name in ("a", "L", "EI", "diameter", "strain_limit"):
            value = _validate.scalar(getattr(self, name), name)
            if value <= 0:
                raise GeometryError(f"{name} must be positive, got {value!r}")
            object.__setattr__(self, name, value)
        if isinstance(self.orientation, (bool, np.bool_)) or self.orientation not in (1, -1):
            raise GeometryError(f"orientation must be 1 or -1, got {self.orientation!r}")

    @property
    def vertices(self) -> np.ndarray:
        """ndarray, shape (3, 2): the pins ``b_i`` in the platform's frame (m)."""
        return self.a / np.sqrt(3.0) * UNIT_CIRCLE * [1.0, self.orientation]

    def mirrored(self) -> Mechanism:
        """The same mechanism with the mirror image of its platform (pins in the other order).

        Examples
        --------
        >>> TABLE8.mirrored().orientation, TABLE8.mirrored().mirrored().orientation
        (-1, 1)
        """
        return Mechanism(self.origins, self.guide_angles, self.clamp_angles, self.a,
                         self.force, self.moment, self.L, self.EI, -self.orientation,
                         self.diameter, self.strain_limit)


TABLE8 = Mechanism(UNIT_CIRCLE, STUDY_GUIDES, np.radians([45.0, 180.0, -60.0]), 0.2,
                   force=[0.0, 0.5])
"""The example of the study's Tabla 8 (13.3.1) with the inputs its solutions belong to: clamp
angles 45, **180** and -60 deg (the text prints 0 deg for rod 2; the code's option ``opt = 2``
has 180), platform side **0.2 m** (not printed), ``O_i`` unrounded, guides of Annex II 4.4
(irrelevant at ``lambda = 0``). See :func:`~mechnum.mechanisms.pfr3.study.recover_inputs`."""
TABLE8_LAMBDAS = np.zeros(3)
"""The slider inputs of Tabla 8 (m)."""
TABLE2 = Mechanism(UNIT_CIRCLE, STUDY_GUIDES, STUDY_GUIDES, 0.5, force=[0.3, -0.2])
"""The mechanism of the study's Tabla 2, as Annex II 4.4 lists it (``opt = 1``): clamp angles
equal to the guides', platform side 0.5 m, load ``(0.3, -0.2)`` N."""
TABLE2_LAMBDAS = np.full(3, 0.1)
"""The slider inputs of Annex II 4.4 (m)."""
SHOOTING_EXAMPLE = Mechanism(UNIT_CIRCLE, STUDY_GUIDES, STUDY_GUIDES, 0.2 * np.sqrt(3.0))
"""The mechanism of the shooting programs (Annex II 4.1): pins 0.2 m from the centre (side
``0.2 sqrt(3)`` m), no load; its starting pose is ``(0, 0, 60 deg)``."""
SHOOTING_POSE = np.array([0.0, 0.0, np.radians(60.0)])
"""The starting pose of Annex II 4.1, ``(x, y, phi)`` (m, m, rad)."""


def clamps(mech: Mechanism, lambdas: ArrayLike) -> np.ndarray:
    """Clamp positions ``C_i = O_i + lambda_i (cos alpha_i, sin alpha_i)``, shape (..., 3, 2).

    Examples
    --------
    >>> np.round(clamps(TABLE2, TABLE2_LAMBDAS), 4).tolist()[0]
    [-0.766, -0.5]
    """
    check_type(mech, Mechanism)
    lambdas = _validate.array(lambdas, "lambdas")
    if lambdas.shape[-1:] != (3,):
        raise ValueError(f"lambdas must have a last axis of 3, got shape {lambdas.shape}")
    return clamps_at(mech, lambdas)


def clamps_at(mech: Mechanism, lambdas: np.ndarray) -> np.ndarray:
    """:func:`clamps` of checked sliders (..., 3): the kernel of the solvers' inner loops."""
    return mech.origins + lambdas[..., None] * np.stack((np.cos(mech.guide_angles),
                                                         np.sin(mech.guide_angles)), axis=-1)


def cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The scalar cross product ``u_x v_y - u_y v_x`` of 2-vectors (last axis)."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def _rot(phi):
    c, s = np.cos(phi), np.sin(phi)
    return np.stack((np.stack((c, -s), -1), np.stack((s, c), -1)), -2)


def pins(mech: Mechanism, pose: ArrayLike) -> np.ndarray:
    """The pins ``B_i`` of the platform at ``pose = (x, y, phi)``, shape (..., 3, 2).

    Examples
    --------
    >>> np.round(pins(SHOOTING_EXAMPLE, SHOOTING_POSE), 6).tolist()[2]
    [-0.173205, 0.1]
    """
    check_type(mech, Mechanism)
    pose = _validate.array(pose, "pose")
    if pose.shape[-1:] != (3,):
        raise ValueError(f"pose must have a last axis of 3 (x, y, phi), got shape {pose.shape}")
    return pins_at(mech, pose)


def pins_at(mech: Mechanism, pose: np.ndarray) -> np.ndarray:
    """:func:`pins` of checked poses (..., 3): the kernel of the solvers' inner loops."""
    r = np.einsum("...ij,kj->...ki", _rot(pose[..., 2]), mech.vertices)
    return pose[..., None, :2] + r


def check_closure(mech: Mechanism, lambdas: ArrayLike) -> None:
    """Raise :class:`GeometryError` if no platform of side ``a`` can be pinned to the rods.

    Every pin lies within ``L`` of its clamp, so two clamps ``C_i, C_j`` must satisfy
    ``a - 2 L <= |C_i - C_j| <= a + 2 L``.

    Examples
    --------
    >>> check_closure(TABLE8, TABLE8_LAMBDAS)
    >>> check_closure(TABLE8, [3.0, 0.0, 0.0])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechnum.errors.GeometryError: clamps 3 and 1 are 2.608 m apart: a platform of side 0.2 m ...
    """
    c = clamps(mech, _validate.array(lambdas, "lambdas", shape=(3,)))
    for i, j in ((0, 1), (1, 2), (2, 0)):
        gap = float(np.hypot(*(c[j] - c[i])))
        if not mech.a - 2 * mech.L <= gap <= mech.a + 2 * mech.L:
            raise GeometryError(
                f"clamps {i + 1} and {j + 1} are {gap:.4g} m apart: a platform of side "
                f"{mech.a:g} m on rods of length {mech.L:g} m cannot close (needs "
                f"{mech.a - 2 * mech.L:.4g} to {mech.a + 2 * mech.L:.4g} m)")


def check_reach(mech: Mechanism, pose: ArrayLike) -> None:
    """Raise :class:`UnreachablePoseError` if a pin of the platform at ``pose`` (..., 3) is
    farther than ``L`` from its guide's line (no slider position reaches it).

    Examples
    --------
    >>> check_reach(TABLE8, [0.0, 0.0, 0.0])
    >>> check_reach(TABLE8, [0.0, 2.5, 0.0])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechnum.errors.UnreachablePoseError: pin 1 of the pose [0.0, 2.5, 0.0] is 2.942 m from ...
    """
    check_type(mech, Mechanism)
    pose = _validate.array(pose, "pose")
    if pose.shape[-1:] != (3,):
        raise ValueError(f"pose must have a last axis of 3 (x, y, phi), got shape {pose.shape}")
    normal = np.stack((-np.sin(mech.guide_angles), np.cos(mech.guide_angles)), -1)
    distance = np.abs(np.sum((pins(mech, pose) - mech.origins) * normal, axis=-1))
    far = distance > mech.L
    if far.any():
        where = np.argwhere(far)[0]
        raise UnreachablePoseError(
            f"pin {where[-1] + 1} of the pose {pose[tuple(where[:-1])].tolist()} is "
            f"{distance[tuple(where)]:.4g} m from its guide, beyond the rod's length "
            f"{mech.L:g} m")


def check_chart(chart: ArrayLike) -> np.ndarray:
    """Chart points ``(psi1, t1, psi2, t2, psi3, t3)`` (..., 6) as a float array, checked.

    Examples
    --------
    >>> check_chart([1.0, 0.5, 1.0, 0.0, 1.0, 0.5])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: chart points (psi1, t1, psi2, t2, psi3, t3) need 0 < psi < 2 pi and 0 < |t| ...
    """
    z = _validate.array(chart, "chart", finite=False)
    if z.shape[-1:] != (6,):
        raise ValueError(f"chart must have a last axis of 6, got shape {z.shape}")
    outside = ~in_chart(z.reshape(-1, 6))
    if outside.any():
        raise ValueError("chart points (psi1, t1, psi2, t2, psi3, t3) need 0 < psi < 2 pi and "
                         f"0 < |t| <= {T_MAX:.6f}, got {z.reshape(-1, 6)[outside][:2]}")
    return z


def rods(mech: Mechanism, lambdas: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1, 1),
         jacobian: bool = True) -> tuple:
    """The three rods of chart points (..., 6), placed at their clamps.

    Returns
    -------
    tip, force : ndarray, shape (..., 3, 2)
        Global tips (m) and forces on the rods at their tips (N).
    clamp_moment : ndarray, shape (..., 3)
        ``m(0)`` of each rod (N m).
    d_chart : ndarray, shape (..., 3, 4, 2) or None
        ``d (tip, force) / d (psi_i, t_i)``.

    Examples
    --------
    >>> z = chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> tip, force, moment, _ = rods(TABLE8, TABLE8_LAMBDAS, z)
    >>> np.round(force.sum(axis=0), 3).tolist()          # the load, to the printed digits
    [0.0, 0.5]
    """
    check_type(mech, Mechanism)
    z = check_chart(chart)
    c = clamps(mech, lambdas)
    try:
        np.broadcast_shapes(z.shape[:-1], c.shape[:-2])
    except ValueError:
        raise ValueError(f"chart of shape {z.shape} and lambdas of shape {c.shape[:-1]} do not "
                         "broadcast together") from None
    family = ClampedRods(mech.EI, mech.L, check_modes(modes, 3))
    return rods_at(family, mech, np.asarray(lambdas, dtype=float), z,
                   _validate.flag(jacobian, "jacobian"))


def rods_at(family: ClampedRods, mech: Mechanism, lambdas: np.ndarray, chart: np.ndarray,
            jacobian: bool = True) -> tuple:
    """:func:`rods` on checked input, the rods' stiffness, length and modes in ``family``: the
    kernel of the solvers' inner loops (no check, no copy)."""
    return family(chart, clamps_at(mech, lambdas), mech.clamp_angles, jacobian=jacobian)[:4]


def pose_of_tips(mech: Mechanism, tip: ArrayLike) -> np.ndarray:
    """The pose ``(x, y, phi)`` of the tips ``(..., 3, 2)``: their centroid and the angle of
    ``d_1 / b_1`` (exact when the tips form the platform).

    Examples
    --------
    >>> np.round(pose_of_tips(TABLE8, pins(TABLE8, [0.1, 0.2, 0.3])), 12).tolist()
    [0.1, 0.2, 0.3]
    """
    check_type(mech, Mechanism)
    tip = _validate.array(tip, "tip")
    if tip.shape[-2:] != (3, 2):
        raise ValueError(f"tip must have shape (..., 3, 2), got shape {tip.shape}")
    return pose_at(mech, tip)


def pose_at(mech: Mechanism, tip: np.ndarray) -> np.ndarray:
    """:func:`pose_of_tips` of checked tips: the kernel of the solvers' inner loops."""
    P = tip.mean(axis=-2)
    d = tip[..., 0, :] - P
    b = mech.vertices[0]
    phi = np.arctan2(b[0] * d[..., 1] - b[1] * d[..., 0], b[0] * d[..., 0] + b[1] * d[..., 1])
    return np.concatenate((P, phi[..., None]), axis=-1)


def forward_system(mech: Mechanism, lambdas: ArrayLike,
                   modes: ArrayLike = (1, 1, 1)) -> Callable[[np.ndarray], tuple]:
    """The direct problem in closed form, reduced to the rods: residual and Jacobian, batched.

    Six dimensionless equations in the six chart coordinates: the tips form the platform
    (two complex conditions, see the module), the forces carry ``F`` and the moments about
    the centroid carry ``M``. A mirror image of the platform is no root.

    Returns
    -------
    callable
        ``system(z) -> (f, J)``, ``f`` of shape ``(batch, 6)`` and ``J`` ``(batch, 6, 6)`` for
        chart points ``z`` ``(batch, 6)``: both from one evaluation of the rods, as
        :func:`mechnum.newton.solve` takes them with ``jac=True``. Its input is not checked
        (the solvers' iterates).

    Examples
    --------
    >>> system = forward_system(TABLE8, TABLE8_LAMBDAS)
    >>> z = chart_from_thesis([[5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952]])
    >>> f, J = system(z)
    >>> f.shape, J.shape, bool(np.abs(f).max() < 2e-3)   # 4 printed decimals
    ((1, 6), (1, 6, 6), True)
    """
    check_type(mech, Mechanism)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    family = ClampedRods(mech.EI, mech.L, check_modes(modes, 3))
    b = mech.vertices @ [1.0, 1j]
    inverse = 1.0 / b
    f = mech.EI / mech.L ** 2

    def system(z):
        tip, force, _, d_chart = rods_at(family, mech, lambdas, z)
        tc = tip @ [1.0, 1j]
        d = tc - tc.mean(axis=-1, keepdims=True)
        w = d * inverse                                  # each e^{i phi} at a root
        G = np.concatenate((np.stack(((w[:, 0] - w[:, 1]).real, (w[:, 0] - w[:, 1]).imag,
                                      np.abs(w[:, 0]) ** 2 - 1.0), -1),
                            (force.sum(axis=1) - mech.force) / f,
                            ((cross(np.stack((d.real, d.imag), -1), force).sum(axis=1)
                              - mech.moment) / (f * mech.L))[:, None]), axis=-1)
        dtip = d_chart[..., 0, :] + 1j * d_chart[..., 1, :]          # (batch, rod, param)
        dforce = d_chart[..., 2:, :]                                  # (batch, rod, 2, param)
        # d d_i / d(param of rod r) = dtip_r (delta_ir - 1/3)
        dd = (np.eye(3)[None, :, :, None] - 1.0 / 3.0) * dtip[:, None, :, :]  # (b, i, r, p)
        dw = dd * inverse[None, :, None, None]
        J = np.empty((len(z), 6, 3, 2))
        J[:, 0], J[:, 1] = (dw[:, 0] - dw[:, 1]).real, (dw[:, 0] - dw[:, 1]).imag
        J[:, 2] = 2.0 * (np.conj(w[:, 0, None, None]) * dw[:, 0]).real
        J[:, 3:5] = np.moveaxis(dforce, 2, 1) / f
        torque = (dd.real * force[:, :, None, None, 1]
                  - dd.imag * force[:, :, None, None, 0]).sum(axis=1)
        torque += d.real[..., None] * dforce[:, :, 1] - d.imag[..., None] * dforce[:, :, 0]
        J[:, 5] = torque / (f * mech.L)
        return G, J.reshape(len(z), 6, 6)

    return system


def full_system(mech: Mechanism, modes: ArrayLike = (1, 1, 1)) -> Callable:
    """The nine equilibrium equations in the rods, the sliders and the pose, with derivatives.

    ``G = ((tip_i - B_i) / L, (n1 + n2 + n3 - F) L**2 / EI, (sum (B_i - P) x n_i - M) L / EI)``.

    Returns
    -------
    callable
        ``system(chart, lambdas, pose) -> (G, D)`` for batches ``chart (..., 6)``, ``lambdas
        (..., 3)``, ``pose (..., 3)``: ``G`` of shape (..., 9) and ``D`` (..., 9, 12), its
        derivatives with respect to ``(chart, lambdas, pose)``. Its input is not checked (the
        solvers' iterates).

    Examples
    --------
    >>> G, D = full_system(TABLE8)(chart_from_thesis(
    ...     [5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952]), TABLE8_LAMBDAS,
    ...     np.array([0.0165, 0.0206, 1.2027]))
    >>> G.shape, D.shape, bool(np.abs(G).max() < 2e-3)
    ((9,), (9, 12), True)
    """
    check_type(mech, Mechanism)
    family = ClampedRods(mech.EI, mech.L, check_modes(modes, 3))
    L, f = mech.L, mech.EI / mech.L ** 2
    guide = np.stack((np.cos(mech.guide_angles), np.sin(mech.guide_angles)), -1)

    def system(z, lambdas, pose):
        tip, force, _, dc = rods_at(family, mech, lambdas, z)
        r = pins_at(mech, pose) - pose[..., None, :2]
        moment = cross(r, force).sum(axis=-1)
        G = np.concatenate((((tip - r - pose[..., None, :2]) / L).reshape(tip.shape[:-2] + (6,)),
                            (force.sum(axis=-2) - mech.force) / f,
                            ((moment - mech.moment) / (f * L))[..., None]), axis=-1)
        D = np.zeros(G.shape + (12,))
        for i in range(3):
            rows, cols = slice(2 * i, 2 * i + 2), slice(2 * i, 2 * i + 2)
            D[..., rows, cols] = dc[..., i, :2, :] / L
            D[..., 6:8, cols] = dc[..., i, 2:, :] / f
            D[..., 8, cols] = (r[..., i, 0, None] * dc[..., i, 3, :]
                               - r[..., i, 1, None] * dc[..., i, 2, :]) / (f * L)
            D[..., rows, 6 + i] = guide[i] / L
            D[..., rows, 9:11] = -np.eye(2) / L
            D[..., rows, 11] = np.stack((r[..., i, 1], -r[..., i, 0]), -1) / L
        D[..., 8, 11] = -np.sum(r * force, axis=(-1, -2)) / (f * L)
        return G, D

    return system


def chart_from_thesis(solutions: ArrayLike) -> np.ndarray:
    """The chart ``(psi1, t1, psi2, t2, psi3, t3)`` of the study's ``(psi_i, k_rel_i)``.

    Examples
    --------
    >>> np.round(chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952]),
    ...          4).tolist()
    [5.1834, -0.7442, 5.0059, -0.8472, 2.6908, -0.1993]
    """
    s = _validate.array(solutions, "solutions")
    if s.shape[-1] != 6:
        raise ValueError(f"solutions must have a last axis of 6, got shape {s.shape}")
    out = s.copy()
    out[..., 1::2] = t_from_k_rel(s[..., 0::2], s[..., 1::2])
    return out


def thesis_from_chart(chart: ArrayLike) -> np.ndarray:
    """The study's ``(psi_i, k_rel_i)`` of chart points (..., 6)."""
    z = _validate.array(chart, "chart", finite=False)
    out = z.copy()
    if z.size:
        out[..., 1::2] = k_rel_from_t(z[..., 0::2], z[..., 1::2])
    return out
