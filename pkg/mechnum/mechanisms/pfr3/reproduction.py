"""The chapter's registry values, computed (``book/published_values.csv``, chapter 6)."""

import numpy as np

from mechnum.mechanisms.pfr3 import model, shooting, study
from mechnum.mechanisms.pfr3.equilibria import forward_elliptic
from mechnum.mechanisms.thesis import EI, STUDY_NODES, YOUNG

NAMES = ("psi1", "k_rel1", "psi2", "k_rel2", "psi3", "k_rel3")


def _cell(n_psi, tolerances):
    return f"n_psi = {n_psi}, tol_L = {tolerances[0]:g}, tol_M = {tolerances[1]:g}"


def table2_cells() -> list:
    """``(name, count, time)`` of every cell of Tabla 2 that prints a count."""
    cells = []
    for i, n_psi in enumerate(study.TABLE2_NPSI):
        for j, tolerances in enumerate(study.TABLE2_TOLERANCES):
            if not np.isnan(study.TABLE2_COUNTS[i, j]):
                name = _cell(n_psi, tolerances) + (" (4th column)" if j == 3 else "")
                cells.append((name, study.TABLE2_COUNTS[i, j], study.TABLE2_TIMES[i, j]))
    return cells


def reproduce(table8=None, table2=None, table2_mirrored=None):
    """The chapter's registry values, computed.

    Tabla 8 from the equilibria that :func:`forward_elliptic` finds (each printed solution
    matched with the nearest one, truncated to the printed 4 decimals as the study did), the
    example's inputs from :func:`~mechnum.mechanisms.pfr3.study.recover_inputs`, the numbers
    of equilibria, the residuals of the study's equations (110) and (113) as printed, and the
    roots of the study's own system for Tabla 2's mechanism within the study's reach.

    Parameters
    ----------
    table8, table2, table2_mirrored : ~mechnum.mechanisms.pfr3.equilibria.Equilibria, optional
        The mode-1 equilibria of :data:`~mechnum.mechanisms.pfr3.model.TABLE8`, of
        :data:`~mechnum.mechanisms.pfr3.model.TABLE2` and of its mirrored platform, if already
        computed (a chapter passes its own); by default :func:`forward_elliptic` with
        ``rng=0``.

    Examples
    --------
    >>> values = reproduce()
    >>> values["mode-1 equilibria for the Table 8 inputs"]
    9.0
    """
    values = {}
    lambdas = model.TABLE8_LAMBDAS
    eq = forward_elliptic(model.TABLE8, lambdas, rng=0) if table8 is None else table8
    matched = []
    for i, printed in enumerate(study.TABLE8_PUBLISHED, start=1):
        k = int(np.argmin(np.abs(eq.solutions - printed).max(axis=1)))
        matched.append(k)
        for name, value in zip(NAMES, np.trunc(eq.solutions[k] * 1e4) / 1e4):
            values[f"Table 8 solution {i} {name}, truncated to 4 decimals"] = float(value)
    fit = study.recover_inputs(study.TABLE8_PUBLISHED, np.radians([45.0, 180.0, -60.0]))
    angles = np.degrees(fit["clamp_angles"])
    for i in range(3):
        values[f"clamp angle theta{i + 1} (fitted to Table 8)"] = float(angles[i])
    values["platform side a (fitted to Table 8)"] = fit["a"]
    values["Young's modulus (fitted to Table 8, 1.5 mm rod)"] = fit["EI"] / EI * YOUNG / 1e9
    printed = model.chart_from_thesis(study.TABLE8_PUBLISHED[0])
    tip, force, _, _ = model.rods(model.TABLE8, lambdas, printed, jacobian=False)
    values["load F_x (n1 + n2 + n3 at the printed solution 1)"] = float(force.sum(axis=0)[0])
    values["load F_y (n1 + n2 + n3 at the printed solution 1)"] = float(force.sum(axis=0)[1])
    values["mode-1 equilibria for the Table 8 inputs"] = float(len(eq.pose))
    # (110) as printed: f12 repeats rod 1's tip and force three times
    tip, force = (a[matched[0]] for a in model.rods(model.TABLE8, lambdas, eq.chart,
                                                     jacobian=False)[:2])
    P = eq.pose[matched[0], :2]
    F = model.TABLE8.force
    values["moment balance f12 of (110) as printed, at Table 8 solution 1 (N m)"] = float(
        3 * model.cross(tip[0], force[0]) - model.cross(P, F))
    values["force balance (113) as printed, at Table 8 solution 1 (N)"] = float(
        np.hypot(*(force.sum(axis=0) + F)))
    # the study's convergence tests, met by the package
    X = shooting.shooting_guess(model.TABLE8, lambdas, eq.chart[matched])
    shot = shooting.forward_shooting(model.TABLE8, lambdas, X, nodes=STUDY_NODES)
    fun = shooting.shooting_system(model.TABLE8, STUDY_NODES, "pose")[0]
    scale = np.array([EI, 1.0, 1.0] * 3 + [EI] * 3)
    values["shooting residual at convergence, N = 41 (N m, m, N)"] = float(np.abs(
        fun(shot.x, np.broadcast_to(lambdas, (2, 3))) * scale).max())
    values["elliptic residual (114) at convergence (m, N, N m)"] = float(np.abs(
        study.thesis_residual(model.TABLE8, lambdas, eq.solutions[matched])).max())
    # Tabla 2: the roots of the study's system (real and mirror assemblies) within its reach
    real = (forward_elliptic(model.TABLE2, model.TABLE2_LAMBDAS, rng=0) if table2 is None
            else table2)
    mirror = (forward_elliptic(model.TABLE2.mirrored(), model.TABLE2_LAMBDAS, rng=0)
              if table2_mirrored is None else table2_mirrored)
    reach = float(study.within_study_reach(real.chart).sum()
                  + study.within_study_reach(mirror.chart).sum())
    for name, _, _ in table2_cells():
        values[f"Table 2 solutions, {name}"] = reach
    values["real mode-1 equilibria of the Table 2 mechanism"] = float(len(real.pose))
    return values
