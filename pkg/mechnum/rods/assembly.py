"""What every mechanism built of elastica shares: its results, its searches, its paths and maps.

To this module a mechanism built of ``r`` clamped-pinned rods (the 2RFR of Chapter 5, the 3PFR
of Chapter 6) is a :class:`Layout`: the ``2 r`` coordinates of its rods in the regular chart
(:mod:`mechnum.rods.regular`), its ``k`` *inputs* (motor angles, slider positions) and its *pose*
(end effector, platform) of ``d`` numbers. Its full equilibrium system ``G(chart, inputs, pose)
= 0`` (``2 r + d`` equations) and its derivatives ``D``, in the columns ``(chart, inputs,
pose)``, give both problems:

* the **direct** (forward) problem solves ``G`` for ``(chart, pose)`` at given inputs; where
  ``det_fk = det dG/d(chart, pose)`` vanishes the locked inputs no longer hold the mechanism;
* the **inverse** problem solves ``G`` for ``(chart, inputs)`` at a given pose; where ``det_ik =
  det dG/d(chart, inputs)`` vanishes the pose cannot move in some direction (the workspace's
  edge).

Here are, once for every such mechanism:

* the results, in the result contract of :mod:`mechnum.results`: :class:`Equilibria` (every
  equilibrium of an all-solutions search, with its stability, crossings and bending strain, and
  whether it can be built), :class:`Path` (one equilibrium followed along a path or over a
  grid), :class:`Shooting` (equilibria by RK4 shooting), and :class:`State`, one equilibrium as
  a mechanism's ``draw`` takes it;
* the drivers: :func:`search` (all solutions from many starts, with the completeness check),
  :func:`follow` (continuation that never reports a point of another branch as converged),
  :func:`follow_grid` (a map over a grid, from a neighbour), :func:`workspace_edge` (where a
  branch ends on rays), :func:`jacobians` and :func:`zero_crossings` (singular points on a map);
* :func:`peak_moment`, the largest bending moment along a clamped-pinned rod, for the strain
  that decides whether a rod can be built.

Each mechanism (:mod:`mechnum.mechanisms.rfr2`, :mod:`mechnum.mechanisms.pfr3`) defines its
equations and drawing and calls these; the two never import each other.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from mechnum import _validate, newton
from mechnum.results import Result
from mechnum.rods import elliptic_parameters, regular
from mechnum.rods.stability import TwoResolutions

# Bounds on the arguments that set an amount of work (each checked at the mechanisms' entry
# points, so that a slip such as nodes=1e7 fails at once instead of running for hours):
MAX_NODES = 100_000          # RK4 nodes (or polyline points) per rod
MAX_STARTS = 100_000         # starts of one all-solutions search (before the check)
MAX_CHECK = 100              # the completeness check, in multiples of the starts
MAX_POINTS = 1_000_000       # points of a path or of a map
MAX_SEGMENTS = 20_000        # segments per rod of a second variation (banded, O(N) work)
MAX_DENSE_SEGMENTS = 1_000   # segments per rod of a dense eigenproblem (O(N**2) memory)
MAX_RAY_STEPS = 10_000       # steps of one ray of workspace_edge, reach / step
MAX_DIRECTIONS = 3_600       # rays of workspace_edge
MAX_LEVELS = 20              # refinements of workspace_edge (the step shrinks 4**levels)
_STATUS = "<U16"
# Newton's tolerance and most iterations per step of closed-form continuation: from a good
# prediction a few iterations reach round-off; more means the branch is lost.
PATH_TOL = 1e-12
PATH_MAXITER = 10


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


def drawing_state(state, chart, modes, rods: int) -> State:
    """The :class:`State` a mechanism's ``draw(ax, mech, state)`` was given, checked; the former
    call ``draw(ax, mech, inputs, chart, modes)`` still works, with a DeprecationWarning.

    Examples
    --------
    >>> s = drawing_state(State(np.zeros(2), np.ones(4), (1, 1)), None, None, 2)
    >>> s.modes
    (1, 1)
    """
    if isinstance(state, State):
        if chart is not None or modes is not None:
            raise ValueError("give draw a State, or (deprecated) the inputs, chart and modes, "
                             "not both")
        inputs, chart, modes = state.inputs, state.chart, state.modes
    else:
        warnings.warn("draw(ax, mech, inputs, chart, modes) is deprecated: pass one State, "
                      "draw(ax, mech, eq.state(i)) or draw(ax, mech, path.state(i))",
                      DeprecationWarning, stacklevel=3)
        if chart is None:
            raise ValueError("draw needs a State (or, deprecated, the inputs and the chart)")
        inputs, modes = state, (1,) * rods if modes is None else modes
    inputs = _validate.array(inputs, "state.inputs", ndim=1)
    chart = _validate.array(chart, "state.chart", shape=(2 * rods,))
    return State(inputs, chart, tuple(int(m) for m in check_modes(modes, rods)))


def draw_parts(ax, parts, arrow, artists, arrow_color):
    """Draw (or, given the ``artists`` of an earlier call, move) a mechanism's parts.

    ``parts`` are ``(x, y, style)`` polylines (a polygon where ``style["fill"]``), ``arrow`` is
    ``(tail, head)`` or None. Returns the artists, in the order of ``parts``, the arrow last.
    """
    from matplotlib.axes import Axes

    check_type(ax, Axes, "ax")
    if artists is None:
        artists = []
        for x, y, style in parts:
            style = dict(style)
            artists += (ax.fill(x, y, **{k: v for k, v in style.items() if k != "fill"})
                        if style.get("fill") else ax.plot(x, y, **style))
        if arrow is not None:
            artists.append(ax.annotate("", xy=arrow[1], xytext=arrow[0], arrowprops={
                "arrowstyle": "->", "color": arrow_color, "lw": 1.5}))
        return artists
    if len(artists) != len(parts) + (arrow is not None):
        raise ValueError(f"artists must be the {len(parts) + (arrow is not None)} artists of "
                         f"an earlier draw of this mechanism, got {len(artists)}")
    for artist, (x, y, style) in zip(artists, parts):
        if style.get("fill"):
            artist.set_xy(np.column_stack((x, y)))
        else:
            artist.set_data(x, y)
    if arrow is not None:
        artists[-1].xy, artists[-1].xyann = tuple(arrow[1]), tuple(arrow[0])
    return artists


def check_type(value, kind, name: str = "mech"):
    """``value`` if it is a ``kind``, else a :class:`ValueError` that names both.

    Examples
    --------
    >>> check_type(None, Layout)
    Traceback (most recent call last):
    ...
    ValueError: mech must be a Layout, got NoneType None
    """
    if not isinstance(value, kind):    # bad input: the package's ValueError (results.py)
        raise ValueError(  # noqa: TRY004
            f"{name} must be a {kind.__name__}, got {type(value).__name__} {value!r:.60}")
    return value


def check_modes(modes, rods: int) -> np.ndarray:
    """The buckling modes of ``rods`` rods, checked: integers ``>= 1``.

    Examples
    --------
    >>> check_modes((1, 2), 2).tolist()
    [1.0, 2.0]
    >>> check_modes((1, 0), 2)
    Traceback (most recent call last):
    ...
    ValueError: modes must be 2 integers >= 1, got [1.0, 0.0]
    """
    out = _validate.array(modes, "modes", shape=(rods,))
    if np.any(out < 1) or np.any(out != np.round(out)):
        raise ValueError(f"modes must be {rods} integers >= 1, got {out.tolist()}")
    return out


def memoised(compute):
    """``compute(u, p)`` that remembers its last call: Newton asks for the residual and then for
    the Jacobian at the same point, and both come from one evaluation of the rods.

    Examples
    --------
    >>> calls = []
    >>> f = memoised(lambda u, p: calls.append(1) or u + p)
    >>> f(np.ones(2), 1.0), f(np.ones(2), 1.0), len(calls)
    (array([2., 2.]), array([2., 2.]), 1)
    """
    last = {}

    def call(u, p):
        key = (u.tobytes(), np.asarray(p).tobytes())
        if last.get("key") != key:
            last["key"], last["value"] = key, compute(u, p)
        return last["value"]

    return call


def continuation_system(system, layout: Layout, along: str):
    """``fun(u, p)`` and ``jac(u, p)`` of a full system ``system(chart, inputs, pose) -> (G, D)``
    for continuation: along the pose (``u = (chart, inputs)``, the inverse problem) or along the
    inputs (``u = (chart, pose)``, the direct problem).

    Examples
    --------
    One rod, one input ``a`` and a pose ``b``: three equations ``(z1 - a, z2 - b, a - b**2)``.

    >>> def system(z, a, b):
    ...     G = np.concatenate((z[:, :1] - a, z[:, 1:] - b, a - b ** 2), axis=-1)
    ...     D = np.zeros((len(z), 3, 4))
    ...     D[:, 0, [0, 2]], D[:, 1, [1, 3]] = [1.0, -1.0], [1.0, -1.0]
    ...     D[:, 2, 2], D[:, 2, 3] = 1.0, -2 * b[:, 0]
    ...     return G, D
    >>> fun, jac = continuation_system(system, Layout(rods=1, inputs=1, pose=1), "pose")
    >>> u, b = np.array([[4.0, 2.0, 4.0]]), np.array([[2.0]])       # u = (z1, z2, a)
    >>> fun(u, b).tolist(), jac(u, b)[0].tolist()
    ([[0.0, 0.0, 0.0]], [[1.0, 0.0, -1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    """
    c = layout.chart
    if _validate.choice(along, ("pose", "inputs"), "along") == "pose":
        columns = layout.inverse_columns
        both = memoised(lambda u, p: system(u[..., :c], u[..., c:], p))
    else:
        columns = layout.forward_columns
        both = memoised(lambda u, p: system(u[..., :c], p, u[..., c:]))
    return (lambda u, p: both(u, p)[0]), (lambda u, p: both(u, p)[1][..., columns])


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
    dpose = -np.linalg.solve(A, d_inputs)[..., pose_rows, :]
    return np.linalg.det(A), np.linalg.det(B), dpose


def check_segments(segments) -> tuple:
    """The resolutions of a stability test: a pair ``(coarse, fine)`` of segments per rod, each
    ``2 <= n <= MAX_SEGMENTS``. One resolution ``(n,)`` still works, with a DeprecationWarning
    (a single index is no evidence that it is settled; the mechanisms' ``index`` gives it).

    Examples
    --------
    >>> check_segments((200, 400.0))
    (200, 400)
    >>> check_segments(200)
    Traceback (most recent call last):
    ...
    ValueError: segments must be a pair of integers (coarse, fine), got 200
    """
    try:
        given = tuple(segments)
    except TypeError:
        raise ValueError(f"segments must be a pair of integers (coarse, fine), got "
                         f"{segments!r}") from None
    if len(given) == 1:
        warnings.warn("stability(..., segments=(n,)) is deprecated: stability takes a pair "
                      "(coarse, fine); the index at one resolution is index(..., segments=n)",
                      DeprecationWarning, stacklevel=3)
    elif len(given) != 2:
        raise ValueError(f"segments must be a pair of integers (coarse, fine), got {given!r}")
    return tuple(_validate.maxiter(n, "segments", minimum=2, maximum=MAX_SEGMENTS)
                 for n in given)


def check_equilibrium(residual, tol: float):
    """Raise :class:`ValueError` if a dimensionless ``residual`` exceeds ``tol``: a stability
    test of a point that is no equilibrium would describe nothing.

    Examples
    --------
    >>> check_equilibrium([0.3, 1e-9], 1e-2)
    Traceback (most recent call last):
    ...
    ValueError: the chart is no equilibrium: its dimensionless residual is 0.3 (above 0.01)
    """
    worst = float(np.max(np.abs(residual)))
    if not worst <= tol:
        raise ValueError(f"the chart is no equilibrium: its dimensionless residual is "
                         f"{worst:.3g} (above {tol:g})")


# --- results ---------------------------------------------------------------------------------

@dataclass(frozen=True, kw_only=True)
class Equilibria(Result, TwoResolutions):
    """Every equilibrium that an all-solutions search found, and what each is like.

    A forward search (given inputs) has one ``inputs`` and a ``pose`` per equilibrium; an
    inverse search (given pose) the reverse. ``x`` is ``chart``; ``status`` is "converged" for
    every equilibrium (each is a root to the search's tolerance); ``search.complete`` says
    whether ten times more starts found no other: evidence, not proof.

    Attributes
    ----------
    inputs : ndarray, shape (k,) or (n, k)
        Motor angles (rad) or sliders (m): given (forward), or of each equilibrium (inverse).
    pose : ndarray, shape (n, d) or (d,)
        End effector or platform of each equilibrium (forward), or given (inverse).
    modes : tuple of int
        The rods' buckling modes.
    solutions : ndarray, shape (n, 2 r)
        ``(psi_i, k_rel_i)``, the study's convention.
    chart : ndarray, shape (n, 2 r)
        ``(psi_i, t_i)``, the solver's regular coordinates.
    forces : ndarray, shape (n, r, 2)
        Force on each rod at its tip (N).
    clamp_moments : ndarray, shape (n, r)
        Moments at the clamps (N m): what the motors or sliders hold.
    index : ndarray of int, shape (n, 2)
        Negative eigenvalues of the second variation at two resolutions: 0 is stable.
    rods_cross, self_cross : ndarray of int
        Crossings of the rods with each other, and of each rod with itself (a loop).
    strain : ndarray, shape (n, r)
        Largest bending strain of each rod, ``(d / 2) max |kappa|`` (:func:`peak_moment`).
    strain_limit : float
        The rods' elastic limit in strain (the mechanism's).
    search : mechnum.newton.RootSet
        The search: ``roots`` (the chart), ``hits``, ``n_starts``, ``n_check``,
        ``new_in_check``, ``complete``.
    """

    inputs: np.ndarray
    pose: np.ndarray
    modes: tuple
    solutions: np.ndarray
    chart: np.ndarray
    forces: np.ndarray
    clamp_moments: np.ndarray
    index: np.ndarray
    rods_cross: np.ndarray
    self_cross: np.ndarray
    strain: np.ndarray
    strain_limit: float
    search: newton.RootSet
    drawer: ClassVar = None        # the mechanism's draw(ax, mech, state), set by its subclass

    @property
    def crossing_free(self) -> np.ndarray:
        """ndarray of bool, shape (n,): no rod crosses another or itself."""
        n = len(self.chart)
        return ((self.rods_cross.reshape(n, -1).sum(axis=1) == 0)
                & (self.self_cross.reshape(n, -1).sum(axis=1) == 0))

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
        return State(np.array(inputs), self.chart[i].copy(), self.modes)

    def draw(self, ax, mech, i: int = 0, *, artists=None, **style) -> list:
        """Draw equilibrium ``i`` with the mechanism's ``draw`` (same options); its artists."""
        return type(self).drawer(ax, mech, self.state(i), artists=artists, **style)


def equilibria_message(n: int, found) -> str:
    """The message of an all-solutions search: how many, from how many starts, and the check.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> equilibria_message(3, S(n_starts=200, n_check=2000, new_in_check=0))
    '3 equilibria from 200 starts; the check of 2000 new starts found no other'
    """
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


def determinants(D, layout: Layout):
    """``det_fk``, ``det_ik`` and ``dpose/dinputs`` of a full system's derivatives ``D`` (...,
    equations, columns of ``layout``), by :func:`jacobians`."""
    return jacobians(D[..., layout.forward_columns], D[..., layout.inverse_columns],
                     D[..., layout.input_columns], slice(layout.chart, None))


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
class Shooting(Result):
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


def shoot(fun, jac, guess, known, *, width: int, tol: float, maxiter: int):
    """Damped Newton on a shooting residual ``fun(X, known)`` (criterion: the residual) from
    ``guess`` (``(width,)`` or ``(batch, width)``), ``known`` broadcast to the batch; the
    :class:`~mechnum.newton.BatchNewtonResult` and the broadcast ``known``."""
    X0 = np.atleast_2d(_validate.array(guess, "guess", ndim=(1, 2)))
    if X0.shape[1] != width:
        raise ValueError(f"guess must have a last axis of {width} (the study's unknowns), "
                         f"got shape {np.shape(guess)}")
    known = np.asarray(known, dtype=float)
    if known.ndim == 2 and len(known) not in (1, len(X0)):
        raise ValueError(f"{len(known)} known values for {len(X0)} guesses: give one, or one "
                         "per guess")
    known = np.broadcast_to(known, (len(X0), known.shape[-1]))
    maxiter = _validate.maxiter(maxiter, "maxiter", maximum=10_000)
    res = newton.solve_batch(lambda X: fun(X, known), X0, lambda X: jac(X, known),
                             tol=_validate.tolerance(tol), maxiter=maxiter,
                             criterion="residual", damping=True, raise_on_failure=False)
    return res, known


def shooting_result(res, inputs, pose, clamp_moments, forces, jacobian, kind=Shooting):
    """A :class:`Shooting` (or subclass ``kind``) of a
    :class:`~mechnum.newton.BatchNewtonResult` and its parts."""
    done = int(np.sum(res.converged))
    return kind(x=res.x, status=res.status, iterations=res.iterations, nfev=res.nfev,
                    njev=res.njev, message=f"{done} of {len(res.x)} systems converged",
                    inputs=np.array(inputs), pose=np.array(pose), clamp_moments=clamp_moments,
                    forces=forces, jacobian=jacobian, newton=res)


# --- drivers ---------------------------------------------------------------------------------

def _counted(fun, jac):
    """``fun`` and ``jac`` that count their calls in ``counts``."""
    counts = {"nfev": 0, "njev": 0}

    def f(*args):
        counts["nfev"] += 1
        return fun(*args)

    def j(*args):
        counts["njev"] += 1
        return jac(*args)

    return f, j, counts


def search(fun, jac, sample, *, domain, n_starts, check, rng, tol, maxiter, same=1e-8):
    """Every root that damped Newton finds from ``n_starts`` starts and ``check`` times as many
    more (:func:`mechnum.newton.solve_all`), with the inputs checked and the work counted.

    Returns
    -------
    found : mechnum.newton.RootSet
    nfev, njev : int
        Calls of the residual and of the Jacobian (each on a batch of starts).
    """
    n_starts = _validate.maxiter(n_starts, "n_starts", maximum=MAX_STARTS)
    check = _validate.maxiter(check, "check", minimum=0, maximum=MAX_CHECK)
    f, j, counts = _counted(fun, jac)
    found = newton.solve_all(f, sample, j, n_starts=n_starts, check=check,
                             rng=_validate.rng(rng), domain=domain, tol=tol, maxiter=maxiter,
                             same=same)
    return found, counts["nfev"], counts["njev"]


@dataclass(frozen=True)
class Trace:
    """What :func:`follow` returns: ``x`` (steps, ..., m), ``status``, ``iterations`` (steps,
    ...) and the calls ``nfev``, ``njev``."""

    x: np.ndarray
    status: np.ndarray
    iterations: np.ndarray
    nfev: int
    njev: int


def points(value, name: str, width: int, *, batch: bool = False) -> np.ndarray:
    """A path's parameters ``(steps, width)`` (or ``(steps, batch, width)``), checked; an empty
    path is valid, a path of more than :data:`MAX_POINTS` points is not.

    Examples
    --------
    >>> points([], "thetas", 2).shape
    (0, 2)
    """
    out = _validate.array(np.reshape(value, (0, width)) if np.size(value) == 0 else value,
                          name, ndim=(2, 3) if batch else 2)
    if out.shape[-1] != width:
        raise ValueError(f"{name} must have a last axis of {width}, got shape {out.shape}")
    if out.size // width > MAX_POINTS:
        raise ValueError(f"{name} has {out.size // width} points, more than {MAX_POINTS} "
                         "(a bound on the work)")
    return out


def follow(fun, jac, params, u0, *, tol, maxiter=10, domain=None, resume=True, chart=0):
    """Follow a solution of ``fun(u, p) = 0`` along ``params`` (:func:`mechnum.newton.solve_path`),
    and keep it on its branch.

    A point is "converged" only if it lies on the branch the path started from. Two tests
    catch a step that converged on another branch: the sign of the determinant of ``jac`` (on
    one branch it keeps its sign: along a natural parameter a branch cannot pass a fold, where
    it vanishes, so a sign change means Newton leapt across the fold), and, for the first
    ``chart`` unknowns, the signs of the rods' ``t`` (the regular chart is discontinuous at
    ``t = 0``). The first point that fails either, and every point after it (they descend from
    it), get the status "branch-jump". A point where Newton failed keeps the status of its
    failure ("lost" when :func:`mechnum.newton.solve_path` gives none).

    Parameters
    ----------
    fun, jac : callable
        ``fun(u, p) -> (m, n)``, ``jac(u, p) -> (m, n, n)`` for rows ``u`` and ``p``.
    params : ndarray, shape (steps, p) or (steps, batch, p)
        The parameters of every point, for one path or for ``batch`` paths; ``steps`` may be 0.
    u0 : ndarray, shape (n,) or (batch, n)
        A solution at (or near) ``params[0]``.
    tol, maxiter, domain, resume
        As in :func:`mechnum.newton.solve_path`.
    chart : int, optional
        Leading unknowns that are a chart ``(psi_i, t_i)``, whose ``t`` signs must persist.

    Returns
    -------
    Trace

    Examples
    --------
    ``x**2 = p`` from ``x = 1``: the root follows ``sqrt(p)`` until ``p`` turns negative, where
    the branch ends (a fold at ``p = 0``).

    >>> fun = lambda x, p: x ** 2 - p
    >>> jac = lambda x, p: 2 * x[:, :, None]
    >>> tr = follow(fun, jac, np.array([[1.0], [0.25], [-0.25]]), np.array([1.0]), tol=1e-12)
    >>> (tr.status == "converged").tolist(), np.round(tr.x[:2, 0], 12).tolist()
    ([True, True, False], [1.0, 0.5])
    """
    params, u0 = np.asarray(params, dtype=float), np.asarray(u0, dtype=float)
    resume = _validate.flag(resume, "resume")
    if not len(params):
        return Trace(np.empty((0,) + u0.shape), np.empty((0,) + u0.shape[:-1], _STATUS),
                     np.zeros((0,) + u0.shape[:-1], int), 0, 0)
    f, j, counts = _counted(fun, jac)
    res = newton.solve_path(f, params, u0, j, tol=tol, maxiter=maxiter, domain=domain,
                            resume=resume)
    ok = np.asarray(res.converged, dtype=bool)
    status = np.asarray(getattr(res, "status", np.where(ok, "converged", "lost")), _STATUS)
    x, single = res.x, u0.ndim == 1
    X, P, U = (x[:, None], params[:, None], u0[None]) if single else (x, params, u0)
    OK = ok.reshape(X.shape[:2])
    det = np.full(OK.shape, np.nan)
    if OK.any():
        det[OK] = np.linalg.det(j(X[OK], P[OK]))
    ref = np.sign(np.linalg.det(jac(U, P[0])))
    first = np.sign(det[np.argmax(OK, axis=0), np.arange(OK.shape[1])])
    ref = np.where(np.isfinite(ref) & (ref != 0), ref, first)
    jump = OK & (np.sign(det) != ref)
    if chart:
        signs = np.sign(X[..., 1:chart:2]) != np.sign(U[..., 1:chart:2])
        jump |= OK & signs.any(axis=-1)
    jumped = (np.cumsum(jump, axis=0) > 0).reshape(ok.shape)
    status = np.where(ok & jumped, "branch-jump", status)
    return Trace(x, status, np.asarray(res.iterations), counts["nfev"], counts["njev"])


def _outwards(n, start):
    """The indices from ``start`` to the end and back to 0 as two paths of one length (the
    shorter padded with its last index: a step of length zero), and their lengths."""
    up, down = np.arange(start, n), np.arange(start, -1, -1)
    steps = max(len(up), len(down))
    padded = [np.pad(i, (0, steps - len(i)), mode="edge") for i in (up, down)]
    return np.stack(padded, axis=1), (len(up), len(down))


def follow_grid(trace, grid, start, u0) -> Trace:
    """A solution followed over a grid from the grid point ``start``: along the second axis both
    ways, then every column reached along the first axis both ways (each both ways at once).

    Parameters
    ----------
    trace : callable
        ``trace(params (steps, batch, p), u0 (batch, m)) -> Trace`` (:func:`follow` of the
        mechanism's system, with ``resume=False``).
    grid : ndarray, shape (nx, ny, p)
        The parameters at the grid's points.
    start : (int, int)
        The grid point of ``u0``.
    u0 : ndarray, shape (m,)
        The solution at ``grid[start]``.

    Returns
    -------
    Trace
        Shape ``(nx, ny, ...)``; "lost" where the grid was never reached.
    """
    nx, ny = grid.shape[:2]
    x = np.full((nx, ny, len(u0)), np.nan)
    status = np.full((nx, ny), "lost", dtype=_STATUS)
    iterations = np.zeros((nx, ny), dtype=int)
    if not (nx and ny):
        return Trace(x, status, iterations, 0, 0)
    calls = np.zeros(2, dtype=int)

    def both_ways(params, u):              # params (steps, 2, batch, p), u (batch, m)
        steps, _, batch, p = params.shape
        tr = trace(params.reshape(steps, 2 * batch, p), np.concatenate((u, u)))
        calls[:] += tr.nfev, tr.njev
        return (a.reshape((steps, 2, batch) + a.shape[2:])
                for a in (np.where((tr.status == "converged")[..., None], tr.x, np.nan),
                          tr.status, tr.iterations))

    js, lengths = _outwards(ny, start[1])
    column = np.full((ny, len(u0)), np.nan)
    col_x, col_s, col_i = both_ways(grid[start[0], js][:, :, None], u0[None])
    for way, n in enumerate(lengths):
        column[js[:n, way]] = col_x[:n, way, 0]
        status[start[0], js[:n, way]] = col_s[:n, way, 0]
        iterations[start[0], js[:n, way]] = col_i[:n, way, 0]
    alive = np.flatnonzero(np.isfinite(column[:, 0]))
    i_s, lengths = _outwards(nx, start[0])
    got_x, got_s, got_i = both_ways(grid[i_s][:, :, alive], column[alive])
    for way, n in enumerate(lengths):
        rows = i_s[:n, way, None]
        x[rows, alive], status[rows, alive] = got_x[:n, way], got_s[:n, way]
        iterations[rows, alive] = got_i[:n, way]
    return Trace(x, status, iterations, int(calls[0]), int(calls[1]))


def workspace_edge(trace, centre, u0, *, directions, step, reach, levels):
    """Where a branch ends on ``directions`` rays in the first two coordinates of the pose from
    ``centre`` (the others fixed): followed in steps of ``step`` up to ``reach``, then from
    each ray's last solution again in steps four times shorter, ``levels`` times.

    Parameters
    ----------
    trace : callable
        ``trace(params (steps, rays, d), u (rays, m)) -> Trace``, with ``resume=False``.
    centre : ndarray, shape (d,)
    u0 : ndarray, shape (m,)
        The solution at ``centre``.
    directions : int
        Rays at equal angles, at most :data:`MAX_DIRECTIONS`.
    step, reach : float
        The first step and the largest distance (m); ``reach / step`` at most
        :data:`MAX_RAY_STEPS`.
    levels : int
        Refinements, at most :data:`MAX_LEVELS`.

    Returns
    -------
    edge : ndarray, shape (directions, d)
        The last pose reached on each ray.
    u : ndarray, shape (directions, m)
        The solution there.
    status : ndarray of str, shape (directions,)
        "converged" where the centre's solution was found on the ray.
    nfev, njev : int
    """
    directions = _validate.maxiter(directions, "directions", maximum=MAX_DIRECTIONS)
    levels = _validate.maxiter(levels, "levels", minimum=0, maximum=MAX_LEVELS)
    step, reach = _validate.scalar(step, "step", positive=True), _validate.scalar(
        reach, "reach", positive=True)
    if reach / step > MAX_RAY_STEPS:
        raise ValueError(f"reach / step = {reach / step:.3g} steps per ray, more than "
                         f"{MAX_RAY_STEPS} (a bound on the work): take a longer step")
    angle = 2.0 * np.pi * np.arange(directions) / directions
    ray = np.column_stack((np.cos(angle), np.sin(angle)))
    u = np.tile(u0, (directions, 1))
    r, h, calls = np.zeros(directions), step, np.zeros(2, dtype=int)
    status = np.full(directions, "lost", dtype=_STATUS)
    for level in range(levels + 1):
        # each level starts at its rays' last solutions (the centre first), and goes on for
        # three steps of the level before (a step of the secant prediction needs two)
        steps = np.arange(int(np.ceil(reach / h)) + 1) if level == 0 else np.arange(13)
        radii = np.minimum(r + h * steps[:, None], reach)                  # (steps, rays)
        known = np.broadcast_to(centre, radii.shape + (len(centre),)).copy()
        known[..., :2] += radii[..., None] * ray
        tr = trace(known, u)
        calls += tr.nfev, tr.njev
        done = np.sum(tr.status == "converged", axis=0)      # steps before the first failure
        moved = np.flatnonzero(done > 0)
        u[moved], r[moved] = tr.x[done[moved] - 1, moved], radii[done[moved] - 1, moved]
        if level == 0:
            status = np.where(done > 0, "converged", tr.status[0])
        h /= 4.0
    edge = np.broadcast_to(centre, (directions, len(centre))).copy()
    edge[:, :2] += r[:, None] * ray
    return edge, u, status, int(calls[0]), int(calls[1])


def zero_crossings(x, y, values) -> np.ndarray:
    """Where a map over the grid ``x`` by ``y`` changes sign: points on its zero curve.

    Each grid edge whose ends have opposite signs gives one point, by linear interpolation
    (edges touching NaN give none): the singularity curves ``det = 0`` of a map, to the grid's
    resolution.

    Returns
    -------
    ndarray, shape (k, 2)

    Examples
    --------
    >>> g = np.linspace(-1.0, 1.0, 21)
    >>> X, Y = np.meshgrid(g, g, indexing="ij")
    >>> pts = zero_crossings(g, g, X ** 2 + Y ** 2 - 0.25)
    >>> bool(np.allclose(np.hypot(*pts.T), 0.5, atol=0.02)), len(pts)
    (True, 32)
    """
    x, y = _validate.array(x, "x", ndim=1), _validate.array(y, "y", ndim=1)
    v = _validate.array(values, "values", shape=(len(x), len(y)), finite=False)
    X, Y = np.meshgrid(x, y, indexing="ij")
    found = []
    for a, b, Pa, Pb in ((v[:-1], v[1:], (X[:-1], Y[:-1]), (X[1:], Y[1:])),
                         (v[:, :-1], v[:, 1:], (X[:, :-1], Y[:, :-1]), (X[:, 1:], Y[:, 1:]))):
        cut = (a * b < 0) & np.isfinite(a) & np.isfinite(b)
        w = a[cut] / (a[cut] - b[cut])
        found.append(np.column_stack([p[cut] + w * (q[cut] - p[cut]) for p, q in zip(Pa, Pb)]))
    return np.concatenate(found).reshape(-1, 2)


def singular_points(grid, which: str) -> np.ndarray:
    """Points where ``det_fk`` or ``det_ik`` (``which``) of a map changes sign, in the map's
    first two parameters (:func:`zero_crossings`)."""
    check_type(grid, Path, "grid")
    if grid.params.ndim != 3:
        raise ValueError(f"grid must be a map (params of shape (nx, ny, p)), got params of "
                         f"shape {grid.params.shape}")
    values = getattr(grid, _validate.choice(which, ("det_fk", "det_ik"), "which"))
    return zero_crossings(grid.params[:, 0, 0], grid.params[0, :, 1], values)


def chart_from_clamps(EI, L, clamp_angle, clamp_moment, force):
    """The chart and modes of rods known by their clamp states (shooting).

    Parameters
    ----------
    EI, L : float
    clamp_angle : array_like, shape (..., r)
        The clamped tangents' angles (rad).
    clamp_moment : array_like, shape (..., r)
    force : array_like, shape (..., r, 2)
        Global forces on the rods at their tips (N).

    Returns
    -------
    chart : ndarray, shape (..., 2 r)
        ``(psi_i, t_i)``; ``t_i`` is NaN for a rod whose ``|k_rel|`` rounds to 0 or 1 from its
        clamp state (a rod straight to rounding, or in tension beyond the chart).
    modes : ndarray of int, shape (..., r)
        0 where the clamp state gives none (a rod straight to rounding).
    """
    c, s = np.cos(clamp_angle), np.sin(clamp_angle)
    force = np.asarray(force, dtype=float)
    local = np.stack((c * force[..., 0] + s * force[..., 1],
                      -s * force[..., 0] + c * force[..., 1]), axis=-1)
    psi, k_rel, modes, _ = elliptic_parameters(EI, L, clamp_moment, local)
    inside = (k_rel != 0) & (np.abs(k_rel) < 1)     # a rod straight to rounding has no chart
    chart = np.full(psi.shape[:-1] + (2 * psi.shape[-1],), np.nan)
    chart[..., 0::2] = psi
    chart[..., 1::2][inside] = regular.t_from_k_rel(psi[inside], k_rel[inside])
    return chart, np.where(np.isnan(modes), 0, modes).astype(int)


def peak_moment(EI, clamp_moment, force, clamp_angle, modes) -> np.ndarray:
    """The largest ``|m(s)|`` along clamped-pinned rods, from their clamp states, exactly.

    Along a rod under a tip force ``n`` the first integral of the elastica is ``m(s)**2 =
    m0**2 + 2 EI (n . t(0) - n . t(s))``: ``|m|`` is largest where the tangent ``t`` points
    against ``n``, ``m_max**2 = m0**2 + 2 EI (n . t(0) + |n|)``, if the rod reaches that
    direction, and at the clamp otherwise. Between two inflections (``m = 0``) it always does:
    so does every rod of mode 2 or more (its last arc ends at the pin, an inflection). A rod of
    mode 1 does when ``m**2`` grows from the clamp, ``m0 (t(0) x n) < 0``.

    Parameters
    ----------
    EI : float
    clamp_moment : array_like, shape (...)
        ``m0`` (N m).
    force : array_like, shape (..., 2)
        The force on the rod at its tip (N).
    clamp_angle : array_like, shape (...)
        The clamped tangent's angle (rad).
    modes : array_like of int, shape (...)

    Examples
    --------
    A rod of mode 2: the largest moment is inside, beyond the clamp's 0.2 N m.

    >>> from mechnum.rods import regular
    >>> rod = regular.shape(1.0, 1.0, 2.0, -0.6, 2, nodes=20001)
    >>> peak = peak_moment(1.0, rod.m[0], rod.force, 0.0, 2)
    >>> bool(abs(peak - np.abs(rod.m).max()) < 1e-6), bool(peak > abs(rod.m[0]))
    (True, True)
    """
    m0, n = np.asarray(clamp_moment, float), np.asarray(force, float)
    c, s = np.cos(clamp_angle), np.sin(clamp_angle)
    along = c * n[..., 0] + s * n[..., 1]                        # n . t(0)
    across = c * n[..., 1] - s * n[..., 0]                       # t(0) x n
    crest = np.sqrt(np.maximum(m0 ** 2 + 2 * EI * (along + np.hypot(n[..., 0], n[..., 1])),
                               0.0))
    passed = (np.asarray(modes) >= 2) | (m0 * across < 0)
    return np.where(passed, np.maximum(crest, np.abs(m0)), np.abs(m0))
