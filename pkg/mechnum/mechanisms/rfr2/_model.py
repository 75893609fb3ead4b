"""The mechanism, and its two rods in closed form in the regular chart.

:class:`~mechnum.mechanisms.rfr2.Mechanism` holds the motors, the load and the rods
(:data:`TABLE7`: the study's example). An equilibrium is four numbers, the chart ``(psi1, t1,
psi2, t2)`` of :mod:`mechnum.rods`; :func:`chart_from_thesis` converts the study's ``(psi1,
k_rel1, psi2, k_rel2)`` to it, :func:`rods` evaluates both rods of chart points in the global
frame (tips, forces, clamp moments and their derivatives), checked, and :func:`full_system`
gives the six equations in the rods, the motor angles and the end effector, with their
derivatives. The solvers' inner loops call the unchecked kernel :func:`rods_at` on a
:class:`mechnum.rods.ClampedRods` made once at their door.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError
from mechnum.mechanisms import thesis
from mechnum.mechanisms._assembly import Layout, check_modes, check_type
from mechnum.mechanisms.thesis import DIAMETER, EI, LENGTH
from mechnum.rods import T_MAX, ClampedRods, in_chart, k_rel_from_t, t_from_k_rel

LAYOUT = Layout(rods=2, inputs=2, pose=2)
"""The unknowns of the full system: the chart (4), the motor angles ``theta`` (2), the end
effector (2)."""


@dataclass(frozen=True)
class Mechanism:
    """A 2RFR mechanism: two motors, two rods, one external force on the end effector.

    Attributes
    ----------
    origins : ndarray, shape (2, 2)
        Motor (clamp) positions ``O1``, ``O2`` (m).
    force : ndarray, shape (2,)
        External force on the end effector (N).
    L : float
        Length of each rod (m).
    EI : float
        Bending stiffness of each rod (N m^2).
    diameter : float
        Diameter of the rods' circular section (m), for their bending strain only.
    strain_limit : float
        The rods' elastic limit in strain (:data:`mechnum.mechanisms.thesis.STRAIN_LIMIT`).

    Raises
    ------
    ValueError
        If an attribute is not finite or has the wrong shape.
    GeometryError
        If ``L``, ``EI``, ``diameter`` or ``strain_limit`` is not positive, or the motors are
        ``2 L`` or more apart (the rods cannot meet).

    Examples
    --------
    >>> TABLE7.origins.tolist(), TABLE7.force.tolist(), round(TABLE7.EI, 7)
    ([[-0.3, 0.0], [0.3, 0.0]], [0.3, -0.1], 0.052186)
    """

    origins: np.ndarray
    force: np.ndarray = field(default_factory=lambda: np.zeros(2))
    L: float = LENGTH
    EI: float = EI
    diameter: float = DIAMETER
    strain_limit: float = thesis.STRAIN_LIMIT

    def __post_init__(self):
        object.__setattr__(self, "origins", _validate.array(self.origins, "origins",
                                                            shape=(2, 2)))
        object.__setattr__(self, "force", _validate.array(self.force, "force", shape=(2,)))
        for name in ("L", "EI", "diameter", "strain_limit"):
            value = _validate.scalar(getattr(self, name), name)
            if value <= 0:
                raise GeometryError(f"{name} must be positive, got {value!r}")
            object.__setattr__(self, name, value)
        gap = float(np.hypot(*(self.origins[1] - self.origins[0])))
        if gap >= 2 * self.L:
            raise GeometryError(f"the motors are {gap:g} m apart: rods of length {self.L:g} m "
                                f"cannot meet")


TABLE7 = Mechanism(origins=[[-0.3, 0.0], [0.3, 0.0]], force=[0.3, -0.1])
"""The study's example of its Table 7 (13.2.1, Annex II 3.4): motor 2 at ``(0.3, 0)``, where its
code puts it and where the published solutions belong (the text says ``(0, 0.3)``)."""
TABLE7_THETA = np.radians([40.0, 60.0])
"""The motor angles of Table 7 (rad)."""


def broadcast(theta: ArrayLike, chart: ArrayLike) -> tuple:
    """Motor angles ``(..., 2)`` and chart points ``(..., 4)``, checked and broadcast together.

    Raises
    ------
    ValueError
        If a shape is wrong, the two do not broadcast, an angle is not finite or a chart point
        lies outside the chart.

    Examples
    --------
    >>> theta, z = broadcast(TABLE7_THETA, [[1.0, 0.5, 2.0, 0.5], [1.0, -0.5, 2.0, 0.5]])
    >>> theta.shape, z.shape
    ((2, 2), (2, 4))
    """
    z, theta = _validate.array(chart, "chart", finite=False), _validate.array(theta, "theta")
    if z.shape[-1:] != (4,) or theta.shape[-1:] != (2,):
        raise ValueError(f"chart must have shape (..., 4) and theta (..., 2), got {z.shape} "
                         f"and {theta.shape}")
    outside = ~in_chart(z.reshape(-1, 4))
    if outside.any():
        raise ValueError("chart points (psi1, t1, psi2, t2) need 0 < psi < 2 pi and "
                         f"0 < |t| <= {T_MAX:.6f}, got {z.reshape(-1, 4)[outside][:2]}")
    try:
        shape = np.broadcast_shapes(z.shape[:-1], theta.shape[:-1])
    except ValueError:
        raise ValueError(f"chart of shape {z.shape} and theta of shape {theta.shape} do not "
                         "broadcast together") from None
    return np.broadcast_to(theta, shape + (2,)), np.broadcast_to(z, shape + (4,))


def rods(mech: Mechanism, theta: ArrayLike, chart: ArrayLike, modes: ArrayLike = (1, 1), *,
         jacobian: bool = True) -> tuple:
    """Both rods of chart points at motor angles ``theta``, in the global frame.

    Parameters
    ----------
    mech : Mechanism
    theta : array_like, shape (..., 2)
        Motor angles (rad), broadcast with ``chart``.
    chart : array_like, shape (..., 4)
        ``(psi1, t1, psi2, t2)``.
    modes : (int, int), optional
    jacobian : bool, optional
        Also the derivatives in the chart (else ``None``).

    Returns
    -------
    tip, force : ndarray, shape (..., 2, 2)
        Tips (m) and forces on the rods at their tips (N), rod by rod.
    clamp_moment : ndarray, shape (..., 2)
        ``m(0)`` of each rod (N m).
    d_chart : ndarray, shape (..., 2, 4, 2) or None
        ``d (tip, force) / d (psi_i, t_i)``.
    d_angle : ndarray, shape (..., 2, 4)
        ``d (tip, force) / d theta_i``.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> tip, force, moment, _, _ = rods(TABLE7, TABLE7_THETA, z)
    >>> np.round(tip, 5).tolist(), np.round(force.sum(axis=0), 4).tolist()   # Table 7, sol. 1
    ([[-0.0811, -0.24587], [-0.0811, -0.24587]], [0.3, -0.1])
    """
    check_type(mech, Mechanism)
    theta, z = broadcast(theta, chart)
    family = ClampedRods(mech.EI, mech.L, check_modes(modes, 2))
    return rods_at(family, mech, theta, z, _validate.flag(jacobian, "jacobian"))


def rods_at(family: ClampedRods, mech: Mechanism, theta: np.ndarray, chart: np.ndarray,
            jacobian: bool = True) -> tuple:
    """:func:`rods` on checked input, the rods' stiffness, length and modes in ``family``: the
    kernel of the solvers' inner loops (no check, no copy)."""
    return family(chart, mech.origins, theta, jacobian=jacobian)


def full_system(mech: Mechanism, modes: ArrayLike = (1, 1)) -> Callable:
    """The six equilibrium equations in the rods, the motor angles and ``P``, with derivatives.

    ``G = ((tip1 - P) / L, (tip2 - P) / L, (n1 + n2 - F) L**2 / EI)``.

    Returns
    -------
    callable
        ``system(chart, theta, P) -> (G, D)`` for batches ``chart (..., 4)``, ``theta (...,
        2)``, ``P (..., 2)``: ``G`` (..., 6) and ``D`` (..., 6, 8), its derivatives in the
        columns of :data:`LAYOUT`, ``(psi1, t1, psi2, t2, theta1, theta2, x_P, y_P)``.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> G, D = full_system(TABLE7)(z, TABLE7_THETA, [-0.0811, -0.2459])
    >>> G.shape, D.shape, bool(np.abs(G).max() < 1e-3)   # the printed digits leave 4e-4
    ((6,), (6, 8), True)
    """
    check_type(mech, Mechanism)
    family = ClampedRods(mech.EI, mech.L, check_modes(modes, 2))
    L, f = mech.L, mech.EI / mech.L ** 2

    def system(chart, theta, P):        # the solvers' inner loop: no check
        tip, force, _, d_chart, d_angle = rods_at(family, mech, theta, chart)
        G = np.concatenate(((tip[..., 0, :] - P) / L, (tip[..., 1, :] - P) / L,
                            (force.sum(axis=-2) - mech.force) / f), axis=-1)
        D = np.zeros(G.shape + (8,))
        for r in range(2):
            rows = slice(2 * r, 2 * r + 2)
            D[..., rows, 2 * r:2 * r + 2] = d_chart[..., r, :2, :] / L
            D[..., 4:6, 2 * r:2 * r + 2] = d_chart[..., r, 2:, :] / f
            D[..., rows, 4 + r] = d_angle[..., r, :2] / L
            D[..., 4:6, 4 + r] = d_angle[..., r, 2:] / f
            D[..., rows, 6:8] = -np.eye(2) / L
        return G, D

    return system


def chart_from_thesis(solutions: ArrayLike) -> np.ndarray:
    """The chart ``(psi1, t1, psi2, t2)`` of the study's ``(psi1, k_rel1, psi2, k_rel2)``.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(z, 6).tolist()
    [5.304574, 0.880277, 1.825456, -0.906868]
    """
    s = _validate.array(solutions, "solutions")
    if s.shape[-1:] != (4,):
        raise ValueError(f"solutions must have a last axis of 4, got shape {s.shape}")
    out = s.copy()
    out[..., 1::2] = t_from_k_rel(s[..., 0::2], s[..., 1::2])
    return out


def thesis_from_chart(chart: ArrayLike) -> np.ndarray:
    """The study's ``(psi1, k_rel1, psi2, k_rel2)`` of chart points (..., 4).

    Examples
    --------
    >>> np.round(thesis_from_chart([5.304574, 0.880277, 1.825456, -0.906868]), 5).tolist()
    [5.30457, 0.96983, 1.82546, -0.99213]
    """
    z = _validate.array(chart, "chart")
    if z.shape[-1:] != (4,):
        raise ValueError(f"chart must have a last axis of 4, got shape {z.shape}")
    out = z.copy()
    if z.size:
        out[..., 1::2] = k_rel_from_t(z[..., 0::2], z[..., 1::2])
    return out
