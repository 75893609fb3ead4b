"""The mechanism, and its two rods in closed form in the regular chart.

:class:`~mechnum.mechanisms.rfr2.Mechanism` holds the motors, the load and the rods' length and
stiffness (:data:`TABLE7`: the study's example). An equilibrium is four numbers, the chart
``(psi1, t1, psi2, t2)`` of :mod:`mechnum.rods.regular`;
:func:`~mechnum.mechanisms.rfr2.chart_from_thesis` converts the study's
``(psi1, k_rel1, psi2, k_rel2)`` to it, and ``_rods`` evaluates both rods of chart points in the
global frame (tips, forces, clamp moments and their derivatives), the kernel of every
closed-form function of the package.
"""

from dataclasses import dataclass, field

import numpy as np

from mechnum import _validate
from mechnum.errors import GeometryError
from mechnum.rods import regular

LENGTH = 1.0                                   # m, both rods (Annex II 3.4)
YOUNG = 210e9                                  # Pa
DIAMETER = 1.5e-3                              # m
EI = YOUNG * 0.25 * np.pi * (0.5 * DIAMETER) ** 4   # N m^2 (I = pi r^4 / 4)


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

    Raises
    ------
    ValueError
        If an attribute is not finite or has the wrong shape.
    GeometryError
        If ``L`` or ``EI`` is not positive, or the motors are ``2 L`` or more apart (the rods
        cannot meet).

    Examples
    --------
    >>> TABLE7.origins.tolist(), TABLE7.force.tolist(), round(TABLE7.EI, 7)
    ([[-0.3, 0.0], [0.3, 0.0]], [0.3, -0.1], 0.052186)
    """

    origins: np.ndarray
    force: np.ndarray = field(default_factory=lambda: np.zeros(2))
    L: float = LENGTH
    EI: float = EI

    def __post_init__(self):
        object.__setattr__(self, "origins", _validate.array(self.origins, "origins",
                                                            shape=(2, 2)))
        object.__setattr__(self, "force", _validate.array(self.force, "force", shape=(2,)))
        for name in ("L", "EI"):
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


def _modes(modes):
    modes = _validate.array(modes, "modes", shape=(2,))
    if np.any(modes < 1) or np.any(modes != np.round(modes)):
        raise ValueError(f"modes must be two integers >= 1, got {modes.tolist()}")
    return modes


def _theta(theta, shape=(2,)):
    return _validate.array(theta, "theta", shape=shape)


def _rods(mech, modes, z, theta):
    """Both rods of the chart points ``z`` (..., 4) at motor angles ``theta`` (..., 2), global:
    tips and forces (..., 2 rods, 2), clamp moments (..., 2), and the derivatives of
    ``(tip, force)`` in the chart (..., 2, 4, 2) and in the motor angle (..., 2, 4)."""
    z = np.asarray(z, dtype=float)
    if not np.all(_in_chart(z.reshape(-1, 4))):
        raise ValueError("chart points (psi1, t1, psi2, t2) need 0 < psi < 2 pi and "
                         f"0 < |t| <= {regular.T_MAX:.6f}, got {_validate._shown(z)}")
    rod = regular._closed_form(mech.EI, mech.L, z[..., 0::2], z[..., 1::2], modes, True)
    tip, force, d_chart, d_angle = regular.place(rod, mech.origins, theta)
    return tip, force, rod.clamp_moment, d_chart, d_angle


def _in_chart(z):
    """Whether chart points ``(psi1, t1, psi2, t2)`` lie where the chart is defined."""
    psi, t = z[:, 0::2], z[:, 1::2]
    return np.all((psi > 0) & (psi < regular.TWO_PI) & (t != 0)
                  & (np.abs(t) <= regular.T_MAX), axis=1)


def chart_from_thesis(solutions):
    """The chart ``(psi1, t1, psi2, t2)`` of the study's ``(psi1, k_rel1, psi2, k_rel2)``.

    Examples
    --------
    >>> z = chart_from_thesis([5.304574, 0.969830, 1.825456, -0.992135])
    >>> np.round(z, 6).tolist()
    [5.304574, 0.880277, 1.825456, -0.906868]
    """
    s = _validate.array(solutions, "solutions")
    if s.shape[-1] != 4:
        raise ValueError(f"solutions must have a last axis of 4, got shape {s.shape}")
    return _chart(s[..., 0::2], s[..., 1::2])


def _chart(psi, k_rel):
    """The chart ``(psi1, t1, psi2, t2)`` of both rods' ``psi`` and ``k_rel`` (..., 2 rods)."""
    t = regular.t_from_k_rel(psi, k_rel)
    return np.stack((psi[..., 0], t[..., 0], psi[..., 1], t[..., 1]), axis=-1)


def _clamp_states(mech, theta, chart, modes):
    tip, force, moment = _rods(mech, _modes(modes), np.asarray(chart, float), _theta(theta))[:3]
    return tip, force, moment
