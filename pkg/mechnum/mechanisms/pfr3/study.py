"""The study of the 3PFR (001: 11.4, 13.3, Annex II 4): its examples, its published numbers, the
inputs they belong to, its own residual, and their reproduction.

* The study's mechanisms: Tabla 8's (:data:`TABLE8`, :data:`TABLE8_LAMBDAS`), Tabla 2's
  (:data:`TABLE2`, :data:`TABLE2_LAMBDAS`) and the shooting programs' (:data:`SHOOTING_EXAMPLE`,
  :data:`SHOOTING_POSE`, :data:`STUDY_RIGID_END`), with the study's convention ``(psi_i,
  k_rel_i)`` (:func:`chart_from_thesis`, :func:`thesis_from_chart`).

* Tabla 8 (13.3.1) prints two solutions to 4 decimals; its text's inputs do not all fit them and
  it omits the platform's side: :func:`thesis_residual` evaluates the printed solutions under
  candidate inputs, :func:`recover_inputs` fits the inputs to them, :func:`digit_matches` tells
  truncated digits from rounded ones.
* Tabla 2 (11.4.3) counts the solutions that the study's grid search finds for one mechanism
  (:data:`TABLE2`) at several grid sizes and tolerances. The
  study's residual (114) checks the platform's three side lengths, which the mirror image of the
  platform satisfies too; :func:`within_study_reach` says which equilibria its refinement could
  represent.
* :func:`reproduce` computes every registry value of the chapter.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import least_squares

from mechnum import _validate
from mechnum.mechanisms._assembly import Equilibria
from mechnum.mechanisms.pfr3 import _model as model
from mechnum.mechanisms.pfr3 import _shooting as shooting
from mechnum.mechanisms.pfr3._elliptic import forward
from mechnum.mechanisms.pfr3._model import (
    SHOOTING_EXAMPLE,
    SHOOTING_POSE,
    TABLE2,
    TABLE2_LAMBDAS,
    TABLE8,
    TABLE8_LAMBDAS,
    chart_from_thesis,
    thesis_from_chart,
)
from mechnum.mechanisms.pfr3._shooting import STUDY_RIGID_END
from mechnum.mechanisms.thesis import EI, STUDY_NODES, YOUNG
from mechnum.rods import k_rel_from_t

__all__ = ["SHOOTING_EXAMPLE", "SHOOTING_POSE", "STUDY_RIGID_END", "TABLE2", "TABLE2_COUNTS",
           "TABLE2_LAMBDAS", "TABLE2_NPSI", "TABLE2_TIMES", "TABLE2_TOLERANCES", "TABLE8",
           "TABLE8_LAMBDAS", "TABLE8_PUBLISHED", "TABLE8_TEXT", "chart_from_thesis",
           "digit_matches", "orientation", "recover_inputs", "reproduce", "thesis_from_chart",
           "thesis_residual", "within_study_reach"]

TABLE8_PUBLISHED = np.array([[5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952],
                             [5.9923, -0.9062, 5.3280, -0.8652, 2.8573, -0.0629]])
"""Tabla 8 as printed, ``(psi_i, k_rel_i)`` of its solutions 1 and 2: the input data of
:func:`~mechnum.mechanisms.pfr3.study.recover_inputs` (the reproduction computes them)."""
TABLE8_TEXT = model.Mechanism([[-0.866, -0.5], [0.866, -0.5], [0.0, 1.0]], model.STUDY_GUIDES,
                              np.radians([45.0, 0.0, -60.0]), 0.2, force=[0.0, 0.5])
"""Tabla 8's inputs as 13.3.1 prints them (``O_i`` rounded, ``theta_2 = 0``); the side, which
it does not print, set to the fitted 0.2 m."""
TABLE2_NPSI = (15, 20, 25, 30)
TABLE2_TOLERANCES = ((1.0, 1.0), (0.5, 1.0), (0.1, 1.0), (0.5, 1.0), (0.5, 0.5), (0.1, 0.1))
"""Tabla 2's columns ``(tol_L, tol_M)`` as printed (the fourth repeats the second)."""
TABLE2_COUNTS = np.array([[5, 5, 4, 4, 3, np.nan], [6, 6, 5, 6, 5, np.nan],
                          [6, 6, 5, 5, np.nan, 3], [np.nan, np.nan, 6, np.nan, 6, np.nan]])
TABLE2_TIMES = np.array([[2030, 1686, 1270, 1067, 985, np.nan],
                         [4848, 4341, 3170, 3534, 3592, np.nan],
                         [9908, 12176, 7771, 7171, np.nan, 5467],
                         [np.nan, np.nan, 17241, np.nan, 11750, np.nan]])
"""Tabla 2's solution counts and run times (s), NaN where it prints none."""
STUDY_GAP = 1e-12
"""The closest ``1 - |k_rel|`` the study's refinement can hold: its ``Jacobian`` (Annex II 4.5)
steps ``k_rel`` by ``1e-12`` and aborts (NaN) when that leaves ``|k_rel| < 1``."""


def thesis_residual(mech: model.Mechanism, lambdas: ArrayLike, solutions: ArrayLike,
                    modes: ArrayLike = (1, 1, 1)) -> np.ndarray:
    """The study's refinement residual at solutions ``(psi_i, k_rel_i)`` (Annex II 4.5,
    ``Residue``; its (114) with the force balance of its code).

    Returns
    -------
    ndarray, shape (..., 6)
        ``|B2 - B1| - a``, ``|B3 - B2| - a``, ``|B1 - B3| - a`` (m), ``F - sum n_i`` (N) and
        ``sum (B_i - P) x (-n_i) + M`` about the centroid ``P`` (N m).

    Examples
    --------
    >>> r = thesis_residual(model.TABLE8, model.TABLE8_LAMBDAS, TABLE8_PUBLISHED)
    >>> bool(np.abs(r).max() < 2e-4)                # the printed digits leave ~1e-4
    True
    >>> float(np.round(thesis_residual(TABLE8_TEXT, model.TABLE8_LAMBDAS,
    ...                                TABLE8_PUBLISHED[0])[0], 3))     # theta_2 = 0
    1.679
    """
    z = model.chart_from_thesis(solutions)
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    tip, force, _, _ = model.rods(mech, lambdas, z, modes, jacobian=False)
    sides = np.linalg.norm(np.roll(tip, -1, axis=-2) - tip, axis=-1) - mech.a
    r = tip - tip.mean(axis=-2, keepdims=True)
    moment = -model.cross(r, force).sum(axis=-1) + mech.moment
    return np.concatenate((sides, mech.force - force.sum(axis=-2), moment[..., None]), axis=-1)


def orientation(mech: model.Mechanism, lambdas: ArrayLike, chart: ArrayLike,
                modes: ArrayLike = (1, 1, 1)) -> np.ndarray:
    """+1 where the tips ``B1, B2, B3`` of equilibria (chart points (..., 6)) go anticlockwise,
    -1 where clockwise: the sign of ``(B2 - B1) x (B3 - B1)``.

    Examples
    --------
    >>> orientation(model.TABLE8, model.TABLE8_LAMBDAS, model.chart_from_thesis(
    ...     TABLE8_PUBLISHED)).tolist()
    [1.0, 1.0]
    """
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    tip = model.rods(mech, lambdas, chart, modes, jacobian=False)[0]
    return np.sign(model.cross(tip[..., 1, :] - tip[..., 0, :], tip[..., 2, :] - tip[..., 0, :]))


def recover_inputs(solutions: ArrayLike, clamp_angles: ArrayLike, *,
                   origins: ArrayLike = model.UNIT_CIRCLE,
                   force: ArrayLike = (0.0, 0.5)) -> dict:
    """The clamp angles, platform side and bending stiffness that printed solutions determine.

    Each printed solution fixes the three rods' shapes and forces in their clamp frames; with
    the clamps at ``origins`` and the load ``force``, the mechanism must close into the
    platform and balance it: six equations per solution (those of
    :func:`~mechnum.mechanisms.pfr3.forward_system`), twelve for two, for five unknowns
    (three angles, ``a`` and ``EI``), fitted by least squares from ``clamp_angles``.

    Parameters
    ----------
    solutions : array_like, shape (m, 6)
        Printed solutions (mode 1).
    clamp_angles : array_like, shape (3,)
        The start of the fit (rad): a candidate set of inputs.
    origins, force : array_like, optional
        The guides' points and the load, taken as given.

    Returns
    -------
    dict
        ``clamp_angles`` (rad), ``a`` (m), ``EI`` (N m^2) and ``residual``, the largest
        (dimensionless) residual of the fit.

    Examples
    --------
    >>> fit = recover_inputs(TABLE8_PUBLISHED, np.radians([45.0, 180.0, -60.0]))
    >>> np.round(np.degrees(fit["clamp_angles"]), 1).tolist(), round(fit["a"], 3)
    ([45.0, 180.0, -60.0], 0.2)
    """
    s = _validate.array(solutions, "solutions", shape=(None, 6))
    start = _validate.array(clamp_angles, "clamp_angles", shape=(3,))

    def residuals(q):
        mech = model.Mechanism(origins, model.STUDY_GUIDES, q[:3], q[3], force=force,
                               EI=q[4])
        return model.forward_system(mech, np.zeros(3))(model.chart_from_thesis(s))[0].ravel()

    fit = least_squares(residuals, np.concatenate((start, [0.3, EI])),
                        bounds=([-np.inf] * 3 + [1e-3, 1e-3 * EI], np.inf),
                        x_scale=[1.0, 1.0, 1.0, 0.1, EI], xtol=1e-15, ftol=1e-15,
                        gtol=1e-15)
    return {"clamp_angles": fit.x[:3], "a": float(fit.x[3]), "EI": float(fit.x[4]),
            "residual": float(np.abs(fit.fun).max())}


def digit_matches(exact: ArrayLike, printed: ArrayLike, decimals: int = 4) -> tuple[int, int]:
    """How many printed numbers are the truncation, and how many the rounding, of ``exact``.

    Examples
    --------
    >>> digit_matches([5.005957, 2.69081], [5.0059, 2.6908])
    (2, 1)

    Raises
    ------
    ValueError
        If the two are not finite arrays of one shape, or ``decimals`` not an integer in
        ``[0, 15]`` (a double holds no more).
    """
    exact, printed = _validate.array(exact, "exact"), _validate.array(printed, "printed")
    if exact.shape != printed.shape:
        raise ValueError(f"exact and printed must have one shape, got {exact.shape} and "
                         f"{printed.shape}")
    decimals = _validate.maxiter(decimals, "decimals", minimum=0, maximum=15)
    scale = 10.0 ** decimals
    truncated = np.trunc(exact * scale) / scale
    rounded = np.round(exact * scale) / scale
    tiny = 0.5 / scale * 1e-6
    return (int(np.sum(np.abs(truncated - printed) < tiny)),
            int(np.sum(np.abs(rounded - printed) < tiny)))


def within_study_reach(chart: ArrayLike) -> np.ndarray:
    """Which equilibria (chart points, shape (..., 6)) the study's refinement can hold: every
    rod with ``1 - |k_rel| > STUDY_GAP`` (computed without cancellation).

    Examples
    --------
    >>> within_study_reach(model.chart_from_thesis(TABLE8_PUBLISHED)).tolist()
    [True, True]
    """
    z = _validate.array(chart, "chart")
    gap = k_rel_from_t(z[..., 0::2], z[..., 1::2], complement=True)
    return np.all(gap > STUDY_GAP, axis=-1)


NAMES = ("psi1", "k_rel1", "psi2", "k_rel2", "psi3", "k_rel3")


def _cell(n_psi, tolerances):
    return f"n_psi = {n_psi}, tol_L = {tolerances[0]:g}, tol_M = {tolerances[1]:g}"


def table2_cells() -> list:
    """``(name, count, time)`` of every cell of Tabla 2 that prints a count."""
    cells = []
    for i, n_psi in enumerate(TABLE2_NPSI):
        for j, tolerances in enumerate(TABLE2_TOLERANCES):
            if not np.isnan(TABLE2_COUNTS[i, j]):
                name = _cell(n_psi, tolerances) + (" (4th column)" if j == 3 else "")
                cells.append((name, TABLE2_COUNTS[i, j], TABLE2_TIMES[i, j]))
    return cells


def reproduce(table8: Equilibria | None = None, table2: Equilibria | None = None,
              table2_mirrored: Equilibria | None = None) -> dict:
    """The chapter's registry values, computed.

    Tabla 8 from the equilibria that :func:`forward` finds (each printed solution
    matched with the nearest one, truncated to the printed 4 decimals as the study did), the
    example's inputs from :func:`~mechnum.mechanisms.pfr3.study.recover_inputs`, the numbers
    of equilibria, the residuals of the study's equations (110) and (113) as printed, and the
    roots of the study's own system for Tabla 2's mechanism within the study's reach.

    Parameters
    ----------
    table8, table2, table2_mirrored : mechnum.mechanisms.Equilibria, optional
        The mode-1 equilibria of :data:`TABLE8`, of :data:`TABLE2` and of its mirrored
        platform, if already computed (a chapter passes its own); by default :func:`forward`
        with ``rng=0``.

    Examples
    --------
    >>> values = reproduce()
    >>> values["mode-1 equilibria for the Table 8 inputs"]
    9.0
    """
    values = {}
    lambdas = model.TABLE8_LAMBDAS
    eq = forward(model.TABLE8, lambdas, rng=0) if table8 is None else table8
    matched = []
    for i, printed in enumerate(TABLE8_PUBLISHED, start=1):
        k = int(np.argmin(np.abs(eq.solutions - printed).max(axis=1)))
        matched.append(k)
        for name, value in zip(NAMES, np.trunc(eq.solutions[k] * 1e4) / 1e4):
            values[f"Table 8 solution {i} {name}, truncated to 4 decimals"] = float(value)
    fit = recover_inputs(TABLE8_PUBLISHED, np.radians([45.0, 180.0, -60.0]))
    angles = np.degrees(fit["clamp_angles"])
    for i in range(3):
        values[f"clamp angle theta{i + 1} (fitted to Table 8)"] = float(angles[i])
    values["platform side a (fitted to Table 8)"] = fit["a"]
    values["Young's modulus (fitted to Table 8, 1.5 mm rod)"] = fit["EI"] / EI * YOUNG / 1e9
    printed = model.chart_from_thesis(TABLE8_PUBLISHED[0])
    tip, force, _, _ = model.rods(model.TABLE8, lambdas, printed, jacobian=False)
    values["load F_x (n1 + n2 + n3 at the printed solution 1)"] = float(force.sum(axis=0)[0])
    values["load F_y (n1 + n2 + n3 at the printed solution 1)"] = float(force.sum(axis=0)[1])
    values["mode-1 equilibria for the Table 8 inputs"] = float(len(eq.pose))
    # (110) as printed: f12 repeats rod 1's tip and force three times
    tip, force = (a[matched[0]] for a in model.rods(model.TABLE8, lambdas, eq.x,
                                                     jacobian=False)[:2])
    P = eq.pose[matched[0], :2]
    F = model.TABLE8.force
    values["moment balance f12 of (110) as printed, at Table 8 solution 1 (N m)"] = float(
        3 * model.cross(tip[0], force[0]) - model.cross(P, F))
    values["force balance (113) as printed, at Table 8 solution 1 (N)"] = float(
        np.hypot(*(force.sum(axis=0) + F)))
    # the study's convergence tests, met by the package
    X = shooting.shooting_guess(model.TABLE8, lambdas, eq.x[matched])
    shot = shooting.forward_shooting(model.TABLE8, lambdas, X, nodes=STUDY_NODES)
    fun = shooting.shooting_system(model.TABLE8, STUDY_NODES, "pose")[0]
    scale = np.array([EI, 1.0, 1.0] * 3 + [EI] * 3)
    values["shooting residual at convergence, N = 41 (N m, m, N)"] = float(np.abs(
        fun(shot.x, np.broadcast_to(lambdas, (2, 3)))[0] * scale).max())
    values["elliptic residual (114) at convergence (m, N, N m)"] = float(np.abs(
        thesis_residual(model.TABLE8, lambdas, eq.solutions[matched])).max())
    # Tabla 2: the roots of the study's system (real and mirror assemblies) within its reach
    real = (forward(model.TABLE2, model.TABLE2_LAMBDAS, rng=0) if table2 is None
            else table2)
    mirror = (forward(model.TABLE2.mirrored(), model.TABLE2_LAMBDAS, rng=0)
              if table2_mirrored is None else table2_mirrored)
    reach = float(within_study_reach(real.x).sum()
                  + within_study_reach(mirror.x).sum())
    for name, _, _ in table2_cells():
        values[f"Table 2 solutions, {name}"] = reach
    values["real mode-1 equilibria of the Table 2 mechanism"] = float(len(real.pose))
    return values
