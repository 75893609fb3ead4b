"""The study of the 2RFR (001: 11.3, 13.2, Annex II 3): its example, its paths, its published
numbers, and their reproduction.

The example of Table 7 (:data:`TABLE7`, :data:`TABLE7_THETA`) and its published solutions
(:data:`TABLE7_PUBLISHED`), in the study's convention ``(psi1, k_rel1, psi2, k_rel2)``
(:func:`chart_from_thesis`, :func:`thesis_from_chart`); the study's six trajectories
(:func:`path`: straight lines, circles and rectangles); :func:`recover_inputs` finds the inputs
of the example from the printed solutions, and :func:`reproduce` computes every registry value
of the chapter.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.rfr2._elliptic import forward, residual
from mechnum.mechanisms.rfr2._model import (
    TABLE7,
    TABLE7_THETA,
    chart_from_thesis,
    rods,
    thesis_from_chart,
)
from mechnum.mechanisms.rfr2._shooting import forward_shooting, shooting_guess, shooting_system
from mechnum.mechanisms.rfr2._trajectories import STUDY_PATHS, path
from mechnum.mechanisms.thesis import EI, LENGTH, STUDY_NODES, YOUNG
from mechnum.rods import ClampedRods

__all__ = ["TABLE7", "TABLE7_PUBLISHED", "TABLE7_THETA", "chart_from_thesis", "path",
           "recover_inputs", "reproduce", "thesis_from_chart"]

TABLE7_PUBLISHED = np.array([[5.304574, 0.969830, 1.825456, -0.992135],
                             [1.962541, -0.004391, 4.811041, 0.943413]])
"""Table 7 as printed, ``(psi1, k_rel1, psi2, k_rel2)`` of its solutions 1 and 2: input data of
:func:`recover_inputs` (the reproduction computes them, see :func:`reproduce`)."""


def recover_inputs(solutions: ArrayLike, free: str = "EI") -> dict:
    """The example's inputs that the printed solutions of Table 7 determine, by least squares.

    Each printed solution ``(psi1, k_rel1, psi2, k_rel2)`` fixes both rods' shapes and
    forces in their clamp frames; the mechanism must close (``tip1 = tip2``) and carry its
    load (``n1 + n2 = F``): four equations per solution, eight for two. With motor 1 at
    ``(-0.3, 0)`` (the origin of the study's frame) and the printed load ``F`` (which fixes the
    orientation), they determine the two motor angles, motor 2's position and one of the
    rods' stiffness ``EI`` (with ``L`` = 1 m) or their length ``L`` (with the code's ``EI``):
    ``L`` and ``EI`` enter the forces only as ``EI / L**2``. The printed digits (6 decimals)
    leave a residual of about ``1e-5``.

    Parameters
    ----------
    solutions : array_like, shape (m, 4)
        Printed solutions (mode 1), ``m >= 2``.
    free : {"EI", "L"}, optional
        The rod property to fit with the angles and motor 2.

    Returns
    -------
    dict
        ``theta`` (rad), ``motor2`` (m), ``EI`` (N m^2) or ``L`` (m), and ``residual``, the
        largest residual of the fit (m or N).

    Examples
    --------
    >>> fit = recover_inputs(TABLE7_PUBLISHED)
    >>> np.round(np.degrees(fit["theta"]), 3).tolist(), np.round(fit["motor2"], 4).tolist()
    ([40.0, 60.0], [0.3, 0.0])
    """
    from scipy.optimize import least_squares

    _validate.choice(free, ("EI", "L"), "free")
    s = _validate.array(solutions, "solutions", shape=(None, 4))
    if len(s) < 2:
        raise ValueError("at least two solutions are needed to fix the inputs")
    z = chart_from_thesis(s)
    pair = ClampedRods(1.0, 1.0, (1, 1))                    # EI = L = 1

    def residuals(q):
        theta, motor2 = q[:2], q[2:4]
        EI_, L = (q[4], LENGTH) if free == "EI" else (EI, q[4])
        tip, n = pair(z, np.stack((TABLE7.origins[0], motor2)) / L, theta, jacobian=False)[:2]
        return np.concatenate(((tip[:, 0] - tip[:, 1]).ravel() * L,
                               (n.sum(axis=1) * EI_ / L ** 2 - TABLE7.force).ravel()))

    fit = least_squares(residuals, [0.5, 1.0, 0.0, 0.0, 0.05 if free == "EI" else 1.2],
                        xtol=1e-15, ftol=1e-15, gtol=1e-15)
    return {"theta": fit.x[:2], "motor2": fit.x[2:4], free: float(fit.x[4]),
            "residual": float(np.abs(residuals(fit.x)).max())}


def _path_sizes() -> dict:
    """The sizes of the study's trajectories, measured on :func:`path`'s points."""
    out = {}
    for kind in STUDY_PATHS:
        p, unit = path(kind), " (m)" if kind.startswith("inverse") else " (rad)"
        name = kind.replace(" ", " path: ", 1)
        if kind.endswith("line"):
            out[f"{name} length{unit}"] = float(np.hypot(*(p[-1] - p[0])))
            out[f"{name} direction (deg)"] = float(np.degrees(np.arctan2(*(p[-1] - p[0])[::-1])))
            out[f"{name} divisions"] = float(len(p) - 1)
        elif kind.endswith("circles"):
            radii = np.unique(np.round(np.hypot(*p.T), 12))
            outer = np.isclose(np.hypot(*p.T), radii[-1])
            out[f"{name} outer diameter{unit}"] = float(2 * radii[-1])
            out[f"{name} number"] = float(np.count_nonzero(radii))
            out[f"{name} divisions"] = float(outer.sum())
        else:
            b, h = 2 * np.abs(p[:, 0]).max(), 2 * np.abs(p[:, 1]).max()
            scale = np.round(np.maximum(np.abs(p[:, 0]) / b, np.abs(p[:, 1]) / h), 12)
            out[f"{name} outer base{unit}"], out[f"{name} outer height{unit}"] = b, h
            out[f"{name} number"] = float(np.count_nonzero(np.unique(scale)))
            out[f"{name} divisions per side"] = float(np.sum(scale == scale.max()) / 4)
    return out


def reproduce() -> dict:
    """The chapter's registry values, computed (see ``book/published_values.csv``).

    Table 7 from the equilibria that :func:`forward` finds (each printed solution
    matched with the nearest one), the example's inputs from :func:`recover_inputs`, the
    number of mode-1 equilibria, and the residual of the study's force balance (104) as
    printed at its own solution 1.

    Examples
    --------
    >>> values = reproduce()
    >>> len(values) > 10 and all(isinstance(v, float) for v in values.values())
    True
    """
    eq = forward(TABLE7, TABLE7_THETA, rng=0)
    values = {}
    for i, printed in enumerate(TABLE7_PUBLISHED, start=1):
        found = eq.solutions[np.argmin(np.abs(eq.solutions - printed).max(axis=1))]
        for name, value in zip(("psi1", "k_rel1", "psi2", "k_rel2"), found):
            values[f"Table 7 solution {i} {name}"] = float(value)
    fit = recover_inputs(TABLE7_PUBLISHED)
    printed = chart_from_thesis(TABLE7_PUBLISHED[0])
    load = rods(TABLE7, TABLE7_THETA, printed)[1].sum(axis=0)
    values.update({"motor angle theta1 (fitted to Table 7)": float(np.degrees(fit["theta"][0])),
                   "motor angle theta2 (fitted to Table 7)": float(np.degrees(fit["theta"][1])),
                   "motor 2 x (text: (0, 0.3); fitted to Table 7)": float(fit["motor2"][0]),
                   "motor 2 y (text: (0, 0.3); fitted to Table 7)": float(fit["motor2"][1]),
                   "rod length L (fitted to Table 7)": recover_inputs(TABLE7_PUBLISHED,
                                                                      "L")["L"],
                   "rod diameter (fitted to Table 7, E = 210 GPa)": float(
                       1e3 * (64 * fit["EI"] / (np.pi * YOUNG)) ** 0.25),
                   "load F_x (n1 + n2 at the printed solution 1)": float(load[0]),
                   "load F_y (n1 + n2 at the printed solution 1)": float(load[1])})
    values["mode-1 equilibria for the Table 7 inputs"] = float(len(eq.pose))
    # the listing of EmpArt_xyR returns tips relative to their clamps: at the printed
    # solution 1 its residual Res_x, Res_y is the distance between the motors
    relative = rods(TABLE7, TABLE7_THETA, printed)[0] - TABLE7.origins
    values["tip gap at the printed solution 1 with EmpArt_xyR as listed (m)"] = float(
        np.hypot(*(relative[0] - relative[1])))
    X = shooting_guess(TABLE7, TABLE7_THETA, eq.x)
    shot = forward_shooting(TABLE7, TABLE7_THETA, X, nodes=STUDY_NODES)
    scale = np.array([TABLE7.EI / TABLE7.L, TABLE7.L, TABLE7.L] * 2 + [TABLE7.EI] * 2)
    values["shooting residual at convergence, N = 41 (N m, m, N)"] = float(np.max(np.abs(
        shooting_system(TABLE7, STUDY_NODES, "pose")[0](shot.x, shot.inputs)[0] * scale)))
    values["elliptic residual (105) at convergence (m, N)"] = float(np.abs(residual(
        TABLE7, TABLE7_THETA, eq.x)).max())
    values.update(_path_sizes())
    sol1 = eq.forces[np.argmin(np.abs(eq.solutions - TABLE7_PUBLISHED[0]).max(axis=1))]
    values["force balance (104) as printed, at solution 1 (N)"] = float(
        np.hypot(*(sol1.sum(axis=0) + TABLE7.force)))
    return values
