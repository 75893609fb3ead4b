"""The study's Annex 3.2: its actuator (:data:`ANNEX`), its gravity (:data:`G_MATHCAD`, Mathcad's
built-in ``g``), and every number it prints, recomputed (:func:`reproduce`)."""

import numpy as np

from mechnum.mechanisms.actuator._dynamics import lagrange_force, virtual_power_force
from mechnum.mechanisms.actuator._model import ANNEX, G_MATHCAD
from mechnum.mechanisms.actuator._velocities import kinematics

__all__ = ["ANNEX", "G_MATHCAD", "reproduce"]

# The cylinder's bore and rod radii (m), printed only inside the annulus area S.
_BORE_RADIUS, _ROD_RADIUS = 0.016, 0.008
# The annex's grid t := 0, 0.01 .. 1 (s), and the force it divides its maximum difference by to
# get a relative error: 29 N, its claimed floor of Q_di.
_ANNEX_GRID = np.linspace(0.0, 1.0, 101)
_ANNEX_FORCE_SCALE = 29.0
_PRINTED_INSTANTS = (0.0, 0.01, 0.25, 0.75)  # where the annex prints Q_dd (s)


def reproduce() -> dict[str, float]:
    """Every number of the annex, recomputed; keys are the registry's ``quantity`` column.

    Kinematics as the annex approximates them, ``g = 9.80665``, on the annex's grid
    ``t = 0, 0.01, ..., 1``. ``Q_dd`` is the corrected Lagrange force; the maximum difference
    between the routes is computed as the annex did, with its slip in ``Q_dd``.

    Returns
    -------
    dict[str, float]

    Examples
    --------
    >>> round(reproduce()["max |Q_dd - Q_di| (annex formulas)"], 7)
    0.0132088
    """
    mech = ANNEX
    kin = kinematics(mech, _ANNEX_GRID, "annex")
    q_di = virtual_power_force(kin)
    q_dd = lagrange_force(kin)
    slip = float(np.max(np.abs(lagrange_force(kin, annex_slip=True) - q_di)))
    at = {t: int(np.argmin(np.abs(_ANNEX_GRID - t))) for t in _PRINTED_INSTANTS}
    return {
        "S (annulus area)": np.pi * (_BORE_RADIUS**2 - _ROD_RADIUS**2),
        "hs (upper clearance)": mech.hs,
        "hi (lower clearance)": mech.hi,
        "Io2": mech.Io2,
        "d (pivot distance)": mech.d,
        "Ig3": mech.inertias[1],
        "Io4": mech.Io4,
        "vcil(0)": float(kin.a_dot[0]),
        "theta2(0)": float(kin.theta2[0]),
        "theta4(0)": float(kin.theta4[0]),
        "omega2(0)": float(kin.omega2[0]),
        "omega4(0)": float(kin.omega4[0]),
        **{f"Q_dd({t:g})": float(q_dd[i]) for t, i in at.items()},
        "Q_di(0)": float(q_di[0]),
        "Q_di(0.25)": float(q_di[at[0.25]]),
        "max |Q_dd - Q_di| (annex formulas)": slip,
        "relative error": slip / _ANNEX_FORCE_SCALE,
        "min Q_di (claim: always above 29 N)": float(np.min(q_di)),
        "difference is numerical (claim)": float(np.max(np.abs(q_dd - q_di))),
    }
