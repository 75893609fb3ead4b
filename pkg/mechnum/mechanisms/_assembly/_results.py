"""The results of the mechanisms built of rods, in the result contract of ``mechnum.results``.

:class:`Layout` (how a mechanism orders its unknowns), :class:`State` (one equilibrium, as a
mechanism's ``draw`` takes it), :class:`Equilibria` (every equilibrium of an all-solutions
search), :class:`Path` (one equilibrium followed along a path or over a grid, with
:func:`path_of` and :func:`closed_form_path` to make one), :class:`ShotEquilibria` (equilibria by
shooting) and :class:`Trace` (what continuation returns), with the determinants of both
problems (:func:`jacobians`, :func:`determinants`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from mechnum import _validate, newton
from mechnum.results import Result


@dataclass(frozen=True)
class Layout:
    """How a mechanism of ``rods`` rods, ``inputs`` inputs and a pose of ``pose`` numbers orders
    the unknowns of its full system: the columns ``(chart, inputs, pose)``.

    Examples
    --------
    >>> lay = Layout(rods=2, inputs=2, pose=2)
    >>> lay.forward_columns, lay.inverse_columns, lay.input_columns
    ([0, 1, 2, 3, 6, 7], [0, 1, 2, 3, 4, 5], [4, 5])
    """

    rods: int
    inputs: int
    pose: int

    def __post_init__(self):
        for name in ("rods", "inputs", "pose"):
            object.__setattr__(self, name, _validate.maxiter(getattr(self, name), name))

    @property
    def chart(self) -> int:
        """Chart coordinates: two per rod."""
        return 2 * self.rods

    @property
    def input_columns(self) -> list:
        return list(range(self.chart, self.chart + self.inputs))

    @property
    def forward_columns(self) -> list:
        """The unknowns of the direct problem: the chart and the pose."""
        return list(range(self.chart)) + list(range(self.chart + self.inputs,
                                                    self.chart + self.inputs + self.pose))

    @property
    def inverse_columns(self) -> list:
        """The unknowns of the inverse problem: the chart and the inputs."""
        return list(range(self.chart + self.inputs))


@dataclass(frozen=True)
class State:
    """One equilibrium, as a mechanism's ``draw(ax, mech, state)`` takes it.

    Attributes
    ----------
    inputs : ndarray, shape (k,)
        Motor angles (rad) or slider positions (m).
    chart : ndarray, shape (2 r,)
        The rods in the regular chart, ``(psi_i, t_i)``.
    modes : tuple of int
        The rods' buckling modes.
    """

    inputs: np.ndarray
    chart: np.ndarray
    modes: tuple


class Jacobians(NamedTuple):
    """The Jacobians of a mechanism's equilibria: what both problems' determinants say.

    Attributes
    ----------
    det_fk : ndarray
        ``det dG / d(chart, pose)``: zero where the direct problem is singular (the inputs
        locked, the pose can still move: the mechanism gains a freedom).
    det_ik : ndarray
        ``det dG / d(chart, inputs)``: zero where the inverse problem is singular (the pose
        cannot move in some direction, whatever the inputs do: the edge of the workspace).
    dpose_dinputs : ndarray, shape (..., d, k)
        How the pose moves with the inputs: the studies' ``FK_Jacobian``; its determinant is
        ``+-det_ik / det_fk`` in their units, and the studies' ``IK_Jacobian`` its inverse.
    """

    det_fk: np.ndarray
    det_ik: np.ndarray
    dpose_dinputs: np.ndarray


def jacobians(A, B, d_inputs, pose_rows):
    """``det_fk``, ``det_ik`` and ``dpose/dinputs`` from the Jacobians of a mechanism's equations
    in the unknowns of the direct problem (``A``) and of the inverse one (``B``), and the
    derivatives of the equations with respect to the inputs (``d_inputs``); ``pose_rows`` picks
    the pose among the direct problem's unknowns.

    Examples
    --------
    >>> A, B = np.array([[2.0, 0.0], [0.0, 1.0]]), np.array([[2.0, 0.0], [0.0, 3.0]])
    >>> fk, ik, dpose = jacobians(A, B, np.array([[0.0], [3.0]]), slice(1, 2))
    >>> float(fk), float(ik), dpose.tolist()
    (2.0, 6.0, [[-3.0]])
    """
    A, B = (_validate.array(M, name) for M, name in ((A, "A"), (B, "B")))
    for M, name in ((A, "A"), (B, "B")):
        if M.ndim < 2 or M.shape[-1] != M.shape[-2]:
            raise ValueError(f"{name} must be square matrices, shape (..., n, n), got {M.shape}")
    d_inputs = _validate.array(d_inputs, "d_inputs")
    if d_inputs.shape[:-1] != A.shape[:-1]:
        raise ValueError(f"d_inputs must have shape {A.shape[:-1]} + (k,), got {d_inputs.shape}")
    if not isinstance(pose_rows, slice) and np.asarray(pose_rows).dtype.kind not in "iu":
        raise ValueError(f"pose_rows must be a slice or integer indices, got {pose_rows!r:.60}")
    dpose = -np.linalg.solve(A, d_inputs)[..., pose_rows, :]
    return Jacobians(np.linalg.det(A), np.linalg.det(B), dpose)


def determinants(D, layout: Layout):
    """``det_fk``, ``det_ik`` and ``dpose/dinputs`` of a full system's derivatives ``D`` (...,
    equations, columns of ``layout``), by :func:`jacobians`."""
    return jacobians(D[..., layout.forward_columns], D[..., layout.inverse_columns],
                     D[..., layout.input_columns], slice(layout.chart, None))


@dataclass(frozen=True, kw_only=True)
class Equilibria(Result):
    """Every equilibrium that an all-solutions search found, and what each is like.

    A forward search (given inputs) has one ``inputs`` and a ``pose`` per equilibrium; an
    inverse search (given pose) the reverse. ``status`` is "converged" for every equilibrium
    (each is a root to the search's tolerance); ``search.complete`` says whether ten times more
    starts found no other: evidence, not proof.

    Attributes
    ----------
    x : ndarray, shape (n, 2 r)
        The equilibria: the rods in the regular chart, ``(psi_i, t_i)``.
    inputs : ndarray, shape (k,) or (n, k)
        Motor angles (rad) or sliders (m): given (forward), or of each equilibrium (inverse).
    pose : ndarray, shape (n, d) or (d,)
        End effector or platform of each equilibrium (forward), or given (inverse).
    modes : tuple of int
        The rods' buckling modes.
    solutions : ndarray, shape (n, 2 r)
        ``(psi_i, k_rel_i)``, the study's convention.
    forces : ndarray, shape (n, r, 2)
        Force on each rod at its tip (N).
    clamp_moments : ndarray, shape (n, r)
        Moments at the clamps (N m): what the motors or sliders hold.
    index : ndarray of int, shape (n, 2)
        Negative eigenvalues of the second variation at two resolutions: 0 is stable.
    rods_cross, self_cross : ndarray of int
        Crossings of the rods with each other, and of each rod with itself (a loop).
    body_cross : ndarray of int, shape (n,)
        Crossings of the rods with the rigid body they hold (the 3PFR's platform); zero where
        they hold none.
    strain : ndarray, shape (n, r)
        Largest bending strain of each rod, ``(d / 2) max |kappa|`` (:func:`peak_moment`).
    strain_limit : float
        The rods' elastic limit in strain (the mechanism's).
    search : mechnum.newton.RootSet
        The search: ``hits``, ``n_starts``, ``n_check``, ``new_in_check``, ``complete``.
    """

    inputs: np.ndarray
    pose: np.ndarray
    modes: tuple
    solutions: np.ndarray
    forces: np.ndarray
    clamp_moments: np.ndarray
    index: np.ndarray
    rods_cross: np.ndarray
    self_cross: np.ndarray
    body_cross: np.ndarray
    strain: np.ndarray
    strain_limit: float
    search: newton.RootSet

    @property
    def stable(self) -> np.ndarray:
        """ndarray of bool, shape (n,): stable at both resolutions (``index`` zero at both)."""
        return (self.index == 0).all(axis=1)

    @property
    def settled(self) -> np.ndarray:
        """ndarray of bool, shape (n,): both resolutions give the same index."""
        return self.index[:, 0] == self.index[:, 1]

    @property
    def crossing_free(self) -> np.ndarray:
        """ndarray of bool, shape (n,): no rod crosses another, itself or the body it holds."""
        n = len(self.x)
        return ((self.rods_cross.reshape(n, -1).sum(axis=1) == 0)
                & (self.self_cross.reshape(n, -1).sum(axis=1) == 0) & (self.body_cross == 0))

    @property
    def elastic(self) -> np.ndarray:
        """ndarray of bool, shape (n,): every rod's strain within ``strain_limit``."""
        return self.strain.max(axis=1, initial=0.0) <= self.strain_limit

    @property
    def buildable(self) -> np.ndarray:
        """ndarray of bool, shape (n,): stable, crossing-free and elastic: a mechanism of these
        rods can be built and holds this equilibrium."""
        return self.stable & self.crossing_free & self.elastic

    def state(self, i: int) -> State:
        """Equilibrium ``i`` as a :class:`State` (for the mechanism's ``draw``)."""
        inputs = self.inputs[i] if np.ndim(self.inputs) == 2 else self.inputs
        return State(np.array(inputs), self.x[i].copy(), self.modes)


def equilibria_message(n: int, found) -> str:
    """The message of an all-solutions search: how many, from how many starts, and the check.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> equilibria_message(3, S(n_starts=200, n_check=2000, new_in_check=0))
    '3 equilibria from 200 starts; the check of 2000 new starts found no other'
    """
    n = _validate.maxiter(n, "n", minimum=0)
    if not all(hasattr(found, a) for a in ("n_starts", "n_check", "new_in_check")):
        raise ValueError(f"found must be a search's roots (n_starts, n_check, new_in_check), "
                         f"got {found!r:.60}")
    text = f"{n} equilibri{'um' if n == 1 else 'a'} from {found.n_starts} starts"
    if not found.n_check:
        return text + "; no completeness check"
    if found.new_in_check:
        return (text + f"; the check of {found.n_check} new starts found {found.new_in_check} "
                "more: the search may be incomplete")
    return text + f"; the check of {found.n_check} new starts found no other"


@dataclass(frozen=True, kw_only=True)
class Path(Result):
    """One equilibrium followed along a path, or over a grid; NaN where it is not followed.

    ``status`` (one per point) is "converged" only on the branch the path started from: a
    point where Newton failed keeps its failure's status ("lost" where it was never tried),
    and a point on another branch, reached across a fold, is a "branch-jump", never a
    converged point (see :func:`follow`). ``x`` holds the continuation's unknowns.

    Attributes
    ----------
    params : ndarray, shape (..., p)
        What the path is given at every point: the pose (inverse) or the inputs (direct).
    inputs, pose : ndarray, shapes (..., k) and (..., d)
        Inputs and pose at every point.
    chart : ndarray, shape (..., 2 r)
        The rods, ``(psi_i, t_i)`` (NaN also where they have no chart: see the mechanism).
    modes : ndarray of int, shape (..., r)
        The rods' modes (0 where unknown).
    det_fk, det_ik : ndarray, shape (...)
        Determinants of the direct and inverse problems (see the module).
    dpose_dinputs : ndarray, shape (..., d, k)
        How the pose moves with the inputs.
    """

    params: np.ndarray
    inputs: np.ndarray
    pose: np.ndarray
    chart: np.ndarray
    modes: np.ndarray
    det_fk: np.ndarray
    det_ik: np.ndarray
    dpose_dinputs: np.ndarray

    def state(self, i) -> State:
        """The equilibrium at point ``i`` (an index of the path's shape) as a :class:`State`."""
        return State(self.inputs[i].copy(), self.chart[i].copy(),
                     tuple(int(m) for m in self.modes[i]))

    def states(self) -> list:
        """The converged points' :class:`State`, in order (row by row for a map)."""
        return [self.state(i) for i in zip(*np.nonzero(self.converged))]


def path_message(status) -> str:
    """How many points of a path converged, and what happened to the others.

    Examples
    --------
    >>> path_message(np.array(["converged", "branch-jump", "lost", "lost"]))
    '1 of 4 points converged; 1 branch-jump, 2 lost'
    """
    status = np.asarray(status)
    words, counts = np.unique(status[status != "converged"], return_counts=True)
    text = f"{int(np.sum(status == 'converged'))} of {status.size} points converged"
    return text + ("; " + ", ".join(f"{c} {w}" for w, c in zip(words, counts)) if len(words)
                   else "")


@dataclass(frozen=True, kw_only=True)
class Trace(Result):
    """What :func:`follow` returns: the continuation's unknowns ``x`` (steps, ..., m), a
    ``status`` and ``iterations`` per point (steps, ...), and the calls ``nfev``, ``njev``."""


def trace_of(x, status, iterations, nfev, njev) -> Trace:
    """The :class:`Trace` of a continuation's points, with the message of :func:`path_message`.

    Examples
    --------
    >>> trace_of(np.zeros((2, 1)), np.array(["converged", "lost"]), np.zeros(2, int), 3,
    ...          3).message
    '1 of 2 points converged; 1 lost'
    """
    return Trace(x=x, status=status, message=path_message(status), iterations=iterations,
                 nfev=nfev, njev=njev)


def path_of(trace, params, layout: Layout, evaluate, kind=Path) -> Path:
    """A :class:`Path` (or subclass ``kind``) of a :class:`Trace` along ``params``.

    ``evaluate(x, p)`` gives, at the converged points' unknowns ``x`` and parameters ``p``,
    ``(inputs, pose, chart, modes, det_fk, det_ik, dpose_dinputs)``; every field is NaN (the
    modes 0) where the trace did not converge.
    """
    ok = np.asarray(trace.status) == "converged"
    nan = np.nan
    fields = [np.full(ok.shape + (layout.inputs,), nan), np.full(ok.shape + (layout.pose,), nan),
              np.full(ok.shape + (layout.chart,), nan), np.zeros(ok.shape + (layout.rods,), int),
              np.full(ok.shape, nan), np.full(ok.shape, nan),
              np.full(ok.shape + (layout.pose, layout.inputs), nan)]
    if ok.any():
        for field, value in zip(fields, evaluate(trace.x[ok], np.asarray(params)[ok])):
            field[ok] = value
    x = np.where(ok[..., None], trace.x, nan)
    return kind(x=x, status=trace.status, message=path_message(trace.status),
                iterations=trace.iterations, nfev=trace.nfev, njev=trace.njev,
                params=np.asarray(params, dtype=float), inputs=fields[0], pose=fields[1],
                chart=fields[2], modes=fields[3], det_fk=fields[4], det_ik=fields[5],
                dpose_dinputs=fields[6])


def closed_form_path(system, layout: Layout, modes, trace, params, along, kind=Path) -> Path:
    """The :class:`Path` of a closed-form :class:`Trace` of :func:`continuation_system`: ``x =
    (chart, inputs)`` along the pose, ``(chart, pose)`` along the inputs; the modes fixed."""
    def evaluate(x, p):
        chart, other = x[:, :layout.chart], x[:, layout.chart:]
        inputs, pose = (other, p) if along == "pose" else (p, other)
        return (inputs, pose, chart, modes) + determinants(system(chart, inputs, pose)[1],
                                                            layout)

    return path_of(trace, params, layout, evaluate, kind)


@dataclass(frozen=True, kw_only=True)
class ShotEquilibria(Result):
    """Equilibria found by RK4 shooting: ``x`` the study's unknowns, ``status`` per system.

    Attributes
    ----------
    inputs, pose : ndarray, shapes (batch, k) and (batch, d)
    clamp_moments : ndarray, shape (batch, r)
        ``m(0)`` of each rod (N m).
    forces : ndarray, shape (batch, r, 2)
        Force on each rod at its tip (N).
    jacobian : ndarray, shape (batch, m, m)
        The scaled Jacobian of the equations in the unknowns, at the last iterate.
    newton : mechnum.newton.BatchNewtonResult
        The iteration itself.
    """

    inputs: np.ndarray
    pose: np.ndarray
    clamp_moments: np.ndarray
    forces: np.ndarray
    jacobian: np.ndarray
    newton: newton.BatchNewtonResult


def shooting_result(res, inputs, pose, clamp_moments, forces, jacobian,
                    kind=ShotEquilibria):
    """A :class:`ShotEquilibria` (or subclass ``kind``) of a
    :class:`~mechnum.newton.BatchNewtonResult` and its parts."""
    done = int(np.sum(res.converged))
    return kind(x=res.x, status=res.status, iterations=res.iterations, nfev=res.nfev,
                    njev=res.njev, message=f"{done} of {len(res.x)} systems converged",
                    inputs=np.array(inputs), pose=np.array(pose), clamp_moments=clamp_moments,
                    forces=forces, jacobian=jacobian, newton=res)
