"""One rod clamped at the origin along +x, its tip pinned: the mechanism of Chapter 3.

:class:`Mechanism` holds the rod (its bending stiffness and length; the study's by default).
Its input is the pinned point, ``tip``; :func:`forward` finds every equilibrium of the given
buckling modes whose tip is there (:func:`mechnum.rods.pinned_equilibria`, in the regular chart
``(psi, t)`` that holds every rod, looped ones included), and :func:`draw` draws one. A state,
what :func:`draw` draws, is the pair ``(tip, (m0, force))``: the pinned point and the rod's
clamp state, its clamp moment (N m) and the force on it at its tip (N), which fix the rod.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, plotting, rods
from mechnum.errors import GeometryError
from mechnum.mechanisms.elastica.study import EI, LENGTH
from mechnum.results import Result

DRAW_NODES = 201
"""RK4 nodes of a drawn rod: a smooth curve at any size of a page."""
ARROW = 0.25
"""Length of the drawn force arrow, relative to ``L``."""


@dataclass(frozen=True)
class Mechanism:
    """A rod clamped at the origin along +x, its tip pinned at a point (the study's rod by
    default: steel, 2 mm in diameter, 1 m long).

    Attributes
    ----------
    EI : float
        Bending stiffness (N m^2), positive.
    L : float
        Length (m), positive.

    Raises
    ------
    GeometryError
        If ``EI`` or ``L`` is not a finite positive number.

    Examples
    --------
    >>> round(Mechanism().EI, 6), Mechanism().L
    (0.164934, 1.0)
    """

    EI: float = EI
    L: float = LENGTH

    def __post_init__(self) -> None:
        for name in ("EI", "L"):
            try:
                value = _validate.scalar(getattr(self, name), name, positive=True)
            except ValueError as error:
                raise GeometryError(str(error)) from None
            object.__setattr__(self, name, value)


def checked(mech: object) -> Mechanism:
    """``mech``, if it is a :class:`Mechanism`, or a ValueError that names it."""
    return _validate.instance(mech, Mechanism, "mech", "an elastica.Mechanism")


@dataclass(frozen=True, kw_only=True)
class PinnedRods(Result):
    """Every equilibrium of the pinned rod that :func:`forward` found.

    Attributes
    ----------
    x : ndarray, shape (n, 2)
        The rods in the regular chart, ``(psi, t)`` (:mod:`mechnum.rods`): the force's
        direction from the clamped tangent and the chart's coordinate.
    status : ndarray of str, shape (n,)
        ``"converged"``: each is a root to the search's tolerance.
    message : str
        How many, of which modes.
    iterations, nfev, njev : int
        Zero: the search's work is not counted.
    tip : ndarray, shape (2,)
        The pinned point (m).
    modes : ndarray of int, shape (n,)
        Each rod's buckling mode.
    clamp_moments : ndarray, shape (n,)
        ``m(0)`` (N m).
    forces : ndarray, shape (n, 2)
        The force on each rod at its tip (N).
    """

    tip: np.ndarray
    modes: np.ndarray
    clamp_moments: np.ndarray
    forces: np.ndarray

    def state(self, i: int) -> tuple:
        """Equilibrium ``i`` as :func:`draw` takes it: ``(tip, (m0, force))``."""
        return self.tip.copy(), (float(self.clamp_moments[i]), self.forces[i].copy())


def forward(mech: Mechanism, tip: ArrayLike, *, modes: tuple = (1, 2, 3), n_psi: int = 120,
            n_k: int = 60) -> PinnedRods:
    """Every equilibrium of the given modes whose tip is pinned at ``tip``: the forward problem.

    The search of :func:`mechnum.rods.pinned_equilibria`: sampled evidence, not proof (a root
    in a cell much smaller than the grid's could be missed; :func:`mechnum.rods.certify_pinned`
    proves the count).

    Parameters
    ----------
    mech : Mechanism
    tip : array_like, shape (2,)
        The pinned point (m), closer than ``L`` to the clamp.
    modes : tuple of int, optional
        The buckling modes searched.
    n_psi, n_k : int, optional
        The search's grid per mode (as in :func:`mechnum.rods.pinned_equilibria`).

    Returns
    -------
    PinnedRods

    Raises
    ------
    ValueError
        If an input is malformed or out of range.

    Examples
    --------
    The study's point: one rod of mode 1 and four of mode 2.

    >>> found = forward(Mechanism(), [0.8, 0.1], modes=(1, 2))
    >>> found.modes.tolist(), found.x.shape
    ([1, 2, 2, 2, 2], (5, 2))
    """
    mech = checked(mech)
    tip = _validate.array(tip, "tip", shape=(2,))
    rows = rods.pinned_equilibria(mech.EI, mech.L, tip, modes, n_psi=n_psi, n_k=n_k,
                                  chart="t")
    rod = rods.clamped_pinned_regular(mech.EI, mech.L, rows[:, 0], rows[:, 1],
                                      rows[:, 2].astype(int), jacobian=False)
    counts = np.bincount(rows[:, 2].astype(int)).tolist()[1:] if len(rows) else []
    return PinnedRods(x=rows[:, :2].copy(), status=np.full(len(rows), "converged"),
                      message=f"{len(rows)} equilibria; per mode from 1: {counts}",
                      iterations=0, nfev=0, njev=0, tip=tip, modes=rows[:, 2].astype(int),
                      clamp_moments=np.asarray(rod.clamp_moment, dtype=float).reshape(-1),
                      forces=np.asarray(rod.force, dtype=float).reshape(-1, 2))


def draw(ax: object, mech: Mechanism, state: tuple, *, artists: dict | None = None,
         color: str = "C0") -> dict:
    """Draw the rod in one state, or move a drawing made before to it.

    The rod (the closed form of its clamp state, :func:`mechnum.rods.shape`, on
    :data:`DRAW_NODES` points: integrating a rod in strong tension from its clamp would amplify
    the rounding of its clamp state as ``exp(L sqrt(R / EI))``), the clamp (a short bar
    across the clamped end at the origin) and the force on the rod at its tip (an arrow of
    length :data:`ARROW` ``L`` along the force, its head at the tip). Labels, limits and
    titles are the caller's.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mech : Mechanism
    state : tuple
        ``(tip, (m0, force))``: the pinned point (m, shape (2,)), the clamp moment (N m) and
        the force on the rod at its tip (N, shape (2,)), as :meth:`PinnedRods.state` gives.
        A cantilever under a dead load is a state too, its tip wherever the load puts it.
    artists : dict, optional
        The artists returned by an earlier call on ``ax``: they are moved, nothing is added
        (a frame of :func:`mechnum.plotting.animate`).
    color : str, optional
        The rod's colour.

    Returns
    -------
    dict
        The artists, keyed ``"rod"``, ``"clamp"`` and ``"force"``.

    Raises
    ------
    ValueError
        If ``ax`` is not an Axes, ``mech`` not a :class:`Mechanism`, ``state`` not a point and
        a clamp state, or ``artists`` not what an earlier call returned.

    Examples
    --------
    >>> import matplotlib.pyplot as plt
    >>> column = Mechanism(1.0, 1.0)
    >>> fig, ax = plt.subplots()
    >>> parts = draw(ax, column, ([1.0, 0.0], (0.0, [-1.0, 0.0])))  # straight, compressed
    >>> (np.round(parts["rod"].get_xydata()[[0, -1]], 12) + 0.0).tolist(), sorted(parts)
    ([[0.0, 0.0], [1.0, 0.0]], ['clamp', 'force', 'rod'])
    >>> (np.round(parts["force"].get_xydata()[:2], 12) + 0.0).tolist()   # its head at the tip
    [[1.25, 0.0], [1.0, 0.0]]
    >>> plt.close(fig)
    """
    plotting.check_axes(ax)
    mech = checked(mech)
    try:
        _, (m0, force) = state
    except (TypeError, ValueError):
        raise ValueError(f"state must be (tip, (m0, force)), got {state!r:.80}") from None
    m0 = _validate.scalar(m0, "the state's clamp moment m0")
    force = _validate.array(force, "the state's force", shape=(2,))
    rod = _shape(mech, m0, force)
    head, size = rod.tip, float(np.hypot(*force))
    along = force / size if size > 0 else np.array([1.0, 0.0])
    angle = float(np.arctan2(along[1], along[0]))
    wings = [head - 0.3 * ARROW * mech.L * np.array([np.cos(angle + a), np.sin(angle + a)])
             for a in np.radians((25.0, -25.0))]                # the arrow's head, 25 deg
    bar = 0.06 * mech.L
    shapes = {"rod": (np.column_stack((rod.x, rod.y)), {"lw": 2.5, "color": color}),
              "clamp": ([[0.0, -bar], [0.0, bar]], {"lw": 5, "color": "k"}),
              "force": ([head - ARROW * mech.L * along, head, [np.nan, np.nan], wings[0],
                         head, wings[1]], {"lw": 1.5, "color": "k"})}
    return plotting.parts(ax, shapes, artists)


def _shape(mech: Mechanism, m0: float, force: np.ndarray) -> rods.Rod:
    """The rod of a clamp state, from its chart (RK4 where it has none: a rod straight to
    rounding, or whose force lies along its clamped tangent)."""
    chart, modes = rods.chart_from_clamps(mech.EI, mech.L, [0.0], [m0], [force])
    if np.isfinite(chart).all() and modes[0] >= 1:
        return rods.shape(mech.EI, mech.L, chart[0], chart[1], int(modes[0]), nodes=DRAW_NODES)
    return rods.integrate(mech.EI, mech.L, m0, force, nodes=DRAW_NODES)
