"""One flexible rod of the flexible-mechanisms thesis (study 001): its data and its example.

The thesis's first program (its Annex II, 1.1 and 1.2) solves a rod clamped at the origin
along +x whose tip is pinned at ``(0.8, 0.1)`` m: a steel rod (``E = 210 GPa``) of length
1 m and circular section of diameter 2 mm, 61 RK4 nodes, initial guesses
``m0 = 0.1`` N m and ``n0 = (0.1, 0.1)`` N, tolerance ``1e-7``. Its Newton loop is not the
one of :func:`~mechnum.rods.shoot_pinned`: it differentiates by forward differences
with a step of ``1e-10``, halves a step that increases the largest residual, and stops when the
largest residual or its change falls below the tolerance. :func:`study_shooting` is that
loop, on the package's RK4 rod (:func:`mechnum.rods.integrate`); :func:`reproduce`
recomputes the registry's rows of Chapter 3, the thesis's budget (its Section 14 and Tabla 9,
from the hours and rates its text states) among them.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, rods
from mechnum.errors import ConvergenceError, SingularJacobianError
from mechnum.results import Result

__all__ = ["COMPUTER", "COMPUTER_HOURS", "COMPUTER_YEARS", "DIAMETER", "EI", "GUESS", "HOURS",
           "LENGTH", "LICENCE", "LICENCE_HOURS", "MATTIASSON", "NODES", "RATES", "TARGET", "TOL",
           "YOUNG", "reproduce", "study_shooting"]

LENGTH = 1.0                                  # m
YOUNG = 210e9                                 # Pa
DIAMETER = 2e-3                               # m
EI = YOUNG * 0.25 * np.pi * (0.5 * DIAMETER) ** 4   # N m^2 (I = pi r^4 / 4)
NODES = 61
TARGET = np.array([0.8, 0.1])                 # m, the pinned tip
GUESS = np.array([0.1, 0.1, 0.1])             # (m0 [N m], n_x [N], n_y [N]), the study's
TOL = 1e-7
FD_STEP = 1e-10
HALVING_FLOOR = 1e-3                          # the study's: halve a step while |delta| > 1e-3 tol
_MAX_COND = 1.0 / np.finfo(float).eps         # a Jacobian past this condition has no digit left
MAX_NODES = 10_000
"""Most RK4 nodes of :func:`study_shooting` (a bound on the work: four sweeps per iteration on
Python floats; the study uses 61)."""
MAX_ITER = 1_000
"""Most iterations of :func:`study_shooting` (a bound on the work; the study has none)."""

# A benchmark the thesis does not give, for validating any cantilever solver: Mattiasson
# (1981), Table 1 (after Bisshopp and Drucker 1945), a cantilever under a transverse tip load
# P; rows (P L^2 / EI, horizontal shortening u / L, deflection v / L), to five digits.
MATTIASSON = np.array([(1.0, 0.05643, 0.30172), (2.0, 0.16064, 0.49346),
                       (5.0, 0.38763, 0.71379), (10.0, 0.55500, 0.81061)])
MATTIASSON.flags.writeable = False

# The thesis's budget (its Section 14 and Tabla 9), as its text states it: two annual Matlab
# licences of 800 EUR (the student's charged in full, the professor's at 2 EUR/h over 400 h a
# year); two computers of 600 EUR (6 years of 400 h); 250 h of junior and 50 h of senior
# engineering at "25 and 40 EUR/h, respectively".
LICENCE = 800.0                               # EUR, each
LICENCE_HOURS = 400.0                         # h a year of the professor's licence
COMPUTER = 600.0                              # EUR, each
COMPUTER_YEARS, COMPUTER_HOURS = 6.0, 400.0   # years of life, h of use a year
HOURS = {"junior": 250.0, "senior": 50.0}     # h
RATES = {"junior": 25.0, "senior": 40.0}      # EUR/h


@dataclass(frozen=True, kw_only=True)
class StudyShooting(Result):
    """The outcome of :func:`study_shooting`.

    Attributes
    ----------
    x : ndarray, shape (3,)
        ``(m0, n_x, n_y)`` at the last iterate.
    status : str
        ``"converged"``, the largest residual at most ``tol`` (else the loop raises).
    message, nfev, njev
        As in :class:`~mechnum.results.Result` (integrations of the rod; no Jacobian is
        evaluated, its forward differences count as integrations).
    iterations : int
        Newton steps taken.
    rod : Rod
        The rod at the last iterate.
    history : ndarray, shape (iterations + 1, 3)
        ``(m0, n_x, n_y)`` after every accepted step, the seed first.
    halvings : int
        Step halvings done in all.
    max_residual : float
        Largest residual component at the last iterate (m or N m).
    """

    rod: rods.Rod
    history: np.ndarray
    halvings: int
    max_residual: float


def _residual(p, target, EI, L, nodes):
    """Tip residuals ``(x - x_t, y - y_t, m(L))`` of a batch of unknowns ``p`` (batch, 3)."""
    rod = rods.integrate(EI, L, p[:, 0], p[:, 1:], nodes=nodes)
    return np.column_stack((rod.tip - target, rod.m[:, -1])), rod


def study_shooting(seed: ArrayLike = GUESS, target: ArrayLike = TARGET, *, EI: float = EI,
                   L: float = LENGTH, nodes: int = NODES, tol: float = TOL,
                   maxiter: int = 200) -> StudyShooting:
    """The thesis's shooting loop (Annex II, 1.2: ``IK_NewRaph``), step by step.

    Parameters
    ----------
    seed : array_like, shape (3,)
        Initial ``(m0, n_x, n_y)`` (the study's guess by default).
    target : array_like, shape (2,)
        The pinned tip (m).
    EI, L : float, optional
        Bending stiffness (N m^2) and length (m) of the rod; the study's by default.
    nodes, tol
        The loop's RK4 nodes (``2 <= nodes <=`` :data:`MAX_NODES`) and tolerance; the study's
        by default.
    maxiter : int, optional
        Most outer iterations (the study has no limit; at most :data:`MAX_ITER`).

    Returns
    -------
    StudyShooting

    Raises
    ------
    ValueError
        If an input is malformed (shapes, non-finite values, non-positive sizes).
    SingularJacobianError
        If the forward-difference Jacobian is singular (the straight rod of a zero seed:
        MATLAB's ``J\\resid0`` would warn and return infinities).
    ConvergenceError
        If the loop stops with a residual above ``tol`` (the study's ``OUT.solution = 0``).

    Examples
    --------
    >>> res = study_shooting()
    >>> res.iterations, round(float(res.rod.clamp_moment), 4), np.round(res.rod.force, 3).tolist()
    (6, -0.6076, [-3.231, -1.163])
    """
    EI = _validate.scalar(EI, "EI", positive=True)
    L = _validate.scalar(L, "L", positive=True)
    p = _validate.array(seed, "seed", shape=(3,))
    target = _validate.array(target, "target", shape=(2,))
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    tol = _validate.tolerance(tol)
    maxiter = _validate.maxiter(maxiter, maximum=MAX_ITER)
    resid = _residual(p[None], target, EI, L, nodes)[0][0]
    resid0 = np.zeros(3)
    history, halvings, calls = [p.copy()], 0, 1
    while (np.max(np.abs(resid)) > tol and np.max(np.abs(resid - resid0)) > tol
           and len(history) <= maxiter):
        resid0 = resid
        perturbed = p + np.vstack((np.zeros(3), FD_STEP * np.eye(3)))
        values = _residual(perturbed, target, EI, L, nodes)[0]
        calls += 1
        jac = (values[1:] - values[0]).T / FD_STEP
        if not np.linalg.cond(jac) < _MAX_COND:   # also inf and NaN: the study's J\r fails
            rod = rods.integrate(EI, L, p[0], p[1:], nodes=nodes)
            raise SingularJacobianError(
                f"the study's shooting loop met a singular Jacobian at iteration "
                f"{len(history) - 1}, (m0, n_x, n_y) = {p.tolist()} (a straight rod: no "
                f"small change of m0 or n moves its tip sideways to first order)",
                _outcome(rod, history, halvings, resid, calls, tol, "singular"))
        delta = -np.linalg.solve(jac, resid0)
        p = p + delta
        resid = _residual(p[None], target, EI, L, nodes)[0][0]
        calls += 1
        while (np.max(np.abs(resid)) > np.max(np.abs(resid0))
               and np.max(np.abs(delta)) > tol * HALVING_FLOOR):
            delta = 0.5 * delta
            p = p - delta
            resid = _residual(p[None], target, EI, L, nodes)[0][0]
            halvings, calls = halvings + 1, calls + 1
        history.append(p.copy())
    rod = rods.integrate(EI, L, p[0], p[1:], nodes=nodes)
    failed = "maxiter" if len(history) > maxiter else "stagnated"
    result = _outcome(rod, history, halvings, resid, calls, tol, failed)
    if not result.converged:
        raise ConvergenceError(result.message, result)
    return result


def _outcome(rod, history, halvings, resid, calls, tol, failed):
    """The :class:`StudyShooting` of the loop's state: converged if the largest residual is at
    most ``tol``, else ``failed``."""
    largest, k = float(np.max(np.abs(resid))), len(history) - 1
    status = "converged" if largest <= tol else failed
    message = (f"the study's shooting loop converged in {k} iterations" if status == "converged"
               else f"the study's shooting loop stopped ({status}) after {k} iterations with "
                    f"residual {largest:.3g} > {tol:g}")
    return StudyShooting(x=np.array(history[-1]), status=status, message=message,
                         iterations=k, nfev=calls, njev=0, rod=rod, history=np.array(history),
                         halvings=halvings, max_residual=largest)


def _q(rod):
    """The study's ``q`` (``phi2 = q pi / 2``) of a rod found by shooting, unrounded."""
    return 2.0 / np.pi * rods.elliptic_parameters(EI, LENGTH, rod.clamp_moment, rod.force)[3]


def _budget():
    """The rows of the thesis's budget (its Section 14 and Tabla 9) from the hours and rates its
    text states, and the two rates (for :func:`reproduce`)."""
    licence_rate = LICENCE / LICENCE_HOURS
    computer_rate = COMPUTER / (COMPUTER_YEARS * COMPUTER_HOURS)
    rows = {"Matlab": LICENCE + licence_rate * HOURS["senior"],
            "computers": computer_rate * (HOURS["junior"] + HOURS["senior"]),
            "senior": HOURS["senior"] * RATES["senior"],
            "junior": HOURS["junior"] * RATES["junior"]}
    return {"licence rate": licence_rate, "computer rate": computer_rate, **rows,
            "total": sum(rows.values())}


def reproduce(nodes: int = NODES) -> dict:
    """The chapter's registry values, computed (see ``book/published_values.csv``).

    ``q`` of the study's (43) is recovered from rods found by RK4 shooting (on ``nodes``
    nodes, ``2 <= nodes <=`` :data:`MAX_NODES`; 61 as in the study, whose ``q`` deviate from
    the odd integers by RK4's error, falling like ``nodes**-4``): the study's own example
    (mode 2), a cantilever (mode 1) and the mode-3 equilibrium of least force through the same
    pinned point. The budget rows come from the hours and rates of :func:`budget` (until the
    study page computes them).

    Examples
    --------
    >>> values = reproduce()
    >>> len(values) > 0 and all(isinstance(v, float) for v in values.values())
    True
    """
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    example = study_shooting(nodes=nodes).rod
    cantilever = rods.shoot_cantilever(EI, LENGTH, [0.0, EI / LENGTH ** 2], nodes=nodes).rod
    psi, k_rel, mode = rods.pinned_equilibria(EI, LENGTH, TARGET, modes=(3,))[0]
    guess = rods.clamped_pinned(EI, LENGTH, psi, k_rel, mode)
    mode3 = rods.shoot_pinned(EI, LENGTH, TARGET, [guess.clamp_moment, *guess.force],
                              nodes=nodes).rod
    costs = _budget()
    return {"q of mode 1 (cantilever, P L^2/EI = 1)": float(_q(cantilever)),
            "q of mode 2 (the Annex II 1.1 example)": float(_q(example)),
            "q of mode 3 (same pinned point)": float(_q(mode3)),
            "hourly cost of the professor's Matlab licence": costs["licence rate"],
            "hourly cost of a computer": costs["computer rate"],
            "Tabla 9: Matlab": costs["Matlab"],
            "Tabla 9: computers (Ordenadores)": costs["computers"],
            "Tabla 9: senior engineering": costs["senior"],
            "Tabla 9: junior engineering": costs["junior"],
            "Tabla 9: total": costs["total"]}
