"""The co-refined search: rounds of :mod:`mechnum.rods._corefine`, then Krawczyk's proofs.

:func:`corefine` runs the rounds of a :class:`~mechnum.rods._corefine.Refinement` and, after
each (from :data:`MIN_ROUNDS` on, once at most :data:`PROBE_LIVE` tuples are live), **probes**
them: it groups the live tuples into clusters of touching boxes (a spatial hash,
:func:`~mechnum.rods._clusters.clusters`, by branch) and tries to settle each cluster of at most
:data:`CLUSTER_TUPLES` tuples with cheap Krawczyk searches (:func:`mechnum.certify.roots`,
:data:`PROBE_BOXES` boxes each): of the cluster's hull; or, when Newton's method (in floats)
finds a root in it, of a box around that root (from half the cluster's reach from it down to
its widest tuple), and then of what that box and the boxes settled before leave of each of
the cluster's tuples (:func:`~mechnum.rods._clusters.subtract`, :data:`TUPLE_BOXES` boxes each). The
settled boxes never overlap, so that each root is counted in one of them; the live tuples
they cover leave the rounds (:meth:`~mechnum.rods._corefine.Refinement.resolve`). When no
tuple is left, one Krawczyk search of every settled box gives the count: a theorem when it is
complete (see :mod:`mechnum.rods._corefine` for why no equilibrium is missed).
"""

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from mechnum import _validate, certify
from mechnum.results import Result
from mechnum.rods._clusters import clusters, hulls, subtract
from mechnum.rods._cocertificate import certificate as cocertificate
from mechnum.rods._corefine import GRID, Refinement, checked
from mechnum.rods.certified import MAX_LIVE, Certified, combine

MAX_ROUNDS = 40
"""Default bound on the rounds."""
MIN_ROUNDS = 4
"""Clusters are probed from this round on."""
PROBE_BOXES = 16
"""The boxes a probe's search may test."""
TUPLE_BOXES = 4
"""The boxes a probe may test in one tuple of a cluster whose root is proven."""
CLUSTER_TUPLES = 512
"""Only clusters of at most this many tuples are probed."""
PROBE_LIVE = 20_000
"""The live tuples are probed only when they are this many or fewer."""
NEWTON_STEPS = 12
SHARES = (0.5, 0.125, 0.0)
"""The boxes a probe tries around a root: these shares of the cluster's reach from it (at
least the widest tuple)."""


@dataclass(frozen=True, kw_only=True)
class CoRefined(Result):
    """Every equilibrium of a co-refinement, each proven, and how the search went.

    The fields of :class:`mechnum.results.Result` (``x``: the roots' midpoints in the full
    chart, ``iterations``: rounds, ``nfev``: evaluations of the rods' enclosures and of the
    Krawczyk search's residual), and:

    Attributes
    ----------
    roots : ndarray, shape (count, 2 r, 2)
        Each holds exactly one equilibrium (Krawczyk's test).
    count : int
    complete : bool
        Every equilibrium of the domain is one of ``roots``: a theorem.
    settled : ndarray, shape (m, 2 r, 2)
        The boxes searched by the final Krawczyk search.
    search : mechnum.certify.Roots
        That search.
    rounds : tuple of dict
        the refinement's history (``rods._corefine``): per round the tuples
        ``tested`` (in all) and ``live``, the rods' ``boxes``, ``evaluations``, ``seconds``,
        ``volume`` (the live tuples' share of the domain) and ``dropped`` (by reason).
    dims, resolved : tuple
        The axis of every cut, and the boxes settled after each round: what the certificate
        needs to repeat the search (``rods._cocertificate``).
    grid : (int, int)
    probes : int
        Boxes tested by the probes.
    seconds : float
    """

    roots: np.ndarray
    count: int
    complete: bool
    settled: np.ndarray
    search: object
    rounds: tuple
    dims: tuple
    resolved: tuple
    grid: tuple
    probes: int
    seconds: float


def _newton(system, hull):
    """A root near the middle of ``hull`` by Newton's method in floats (the residual at exact
    points), or None when the iterates leave the hull or do not settle."""
    residual, jacobian = system[0], system[1]
    x = hull.mean(axis=1)
    for _ in range(NEWTON_STEPS):
        X = [certify.balls.ball(v) for v in x]
        f = np.array([float(v.mid()) for v in residual(X)])
        J = np.array([[float(v.mid()) for v in row] for row in jacobian(X)])
        try:
            step = np.linalg.solve(J, -f)
        except np.linalg.LinAlgError:
            return None
        x = x + step
        if not (np.all(np.isfinite(x)) and np.all(x >= hull[:, 0]) and np.all(x <= hull[:, 1])):
            return None
        if np.all(np.abs(step) <= 1e-13 * (1.0 + np.abs(x))):
            return x
    return None


def _apart(U, boxes):
    """Whether the box ``U`` overlaps none of ``boxes`` (faces may touch)."""
    return not any(np.all(U[:, 0] < B[:, 1]) and np.all(B[:, 0] < U[:, 1]) for B in boxes)


class _Prober:
    """Settles clusters of live tuples by cheap Krawczyk searches (see the module); the boxes
    it settles never overlap each other nor the ones settled before."""

    def __init__(self, system):
        self.system, self.boxes = system, 0

    def settles(self, U, budget=PROBE_BOXES):
        """Whether Krawczyk's search of the box ``U`` closes within ``budget`` boxes."""
        residual, jacobian, exclude, split = self.system
        trial = certify.roots(residual, jacobian, U[None], max_boxes=budget, exclude=exclude,
                              split=split)
        self.boxes += trial.boxes
        return trial.complete

    def __call__(self, state):
        """The new boxes that settle clusters of the live tuples of ``state``."""
        boxes, keys = state.boxes()
        labels = clusters(boxes, keys)
        sizes = np.bincount(labels) if len(labels) else np.zeros(0, dtype=int)
        settled, ready = list(state.resolved_hulls()), []
        for c, H in enumerate(hulls(boxes, labels)):
            if sizes[c] <= CLUSTER_TUPLES:
                ready += self._cluster(H, boxes[labels == c], settled)
        return np.array(ready).reshape((-1,) + boxes.shape[1:])

    def _take(self, pieces, settled, budget):
        """The pieces that settle, added to ``settled``."""
        done = [p for p in pieces if self.settles(p, budget)]
        settled += done
        return done

    def _cluster(self, H, members, settled):
        if _apart(H, settled) and self.settles(H):
            settled.append(H)
            return [H]
        root = _newton(self.system, H)
        if root is None:
            return []
        out = []
        half = 0.5 * (members[:, :, 1] - members[:, :, 0]).max(axis=0)
        reach = np.maximum(root - H[:, 0], H[:, 1] - root)
        for share in SHARES:
            side = np.maximum(share * reach, half)
            U = np.column_stack((np.maximum(root - side, H[:, 0]),
                                 np.minimum(root + side, H[:, 1])))
            if _apart(U, settled) and self.settles(U):
                settled.append(U)
                out.append(U)
                break
        if not out:
            return []
        for B in members:
            out += self._take(subtract(B, settled), settled, TUPLE_BOXES)
        return out


def corefine(rods, assembly, system, *, grid=GRID, max_rounds=MAX_ROUNDS,
             max_live=MAX_LIVE, max_boxes=certify.MAX_BOXES):
    """Every equilibrium of rods joined at their tips, proven: co-refinement, then Krawczyk.

    Parameters
    ----------
    rods : sequence of mechnum.rods._leaves.ChartRod
        The rods, with their a-priori bounds (``t_max``, ``lam_max``).
    assembly : mechnum.rods._tuples.Assembly
        How their tips meet, and the load.
    system : (callable, callable, callable or None, callable or None)
        ``residual, jacobian, exclude, split`` of the mechanism's equations in the full chart
        ``(psi_1, t_1, ..., psi_r, t_r)`` over boxes (see :func:`mechnum.certify.roots`).
    grid : (int, int), optional
        The first grid of each branch of each rod's chart, in ``psi`` and ``t``.
    max_rounds : int, optional
        Bound on the rounds (``<= 200``); the tuples left then are searched whole, in the
        hulls of their clusters.
    max_live : int, optional
        Bound on the live tuples after a round (``<= 50_000_000``): beyond it the rounds stop
        and the result is incomplete (its ``rounds`` tell how far they went).
    max_boxes : int, optional
        Bound on the boxes of the final Krawczyk search.

    Returns
    -------
    CoRefined
    """
    max_rounds = _validate.maxiter(max_rounds, "max_rounds", maximum=200)
    max_live = _validate.maxiter(max_live, "max_live", maximum=50_000_000)
    rods, assembly, system = checked(rods, assembly, system)
    state = Refinement(rods, assembly, grid)
    probe = _Prober(system)
    while 0 < len(state.live) <= max_live and len(state.history) <= max_rounds:
        state.step()
        if len(state.history) > MIN_ROUNDS and len(state.live) <= PROBE_LIVE:
            state.resolve(probe(state))
    if 0 < len(state.live) <= max_live:
        boxes, keys = state.boxes()
        settled, last = list(state.resolved_hulls()), []
        for H in hulls(boxes, clusters(boxes, keys)):
            pieces = subtract(H, settled)
            settled += pieces
            last += pieces
        state.resolve(np.array(last).reshape((-1,) + boxes.shape[1:]), final=True)
    return conclude(state, system, probe.boxes, max_boxes)


def conclude(state, system, probes=0, max_boxes=certify.MAX_BOXES):
    """The Krawczyk search of every settled box, and the result."""
    residual, jacobian, exclude, split = system
    settled = state.resolved_hulls()
    search = certify.roots(residual, jacobian, settled, max_boxes=max_boxes, exclude=exclude,
                           split=split, scope="all")
    complete = bool(search.complete) and not len(state.live)
    rounds = len(state.history) - 1
    last = state.history[-1]
    message = (f"{search.count} equilibria proven after {rounds} rounds ({last['boxes']} "
               f"boxes of the rods' charts, {state.tested} tuples tested, {probes} boxes "
               f"probed, {len(settled)} boxes settled); " + search.message)
    if len(state.live):
        message += (f"; {len(state.live)} tuples left undecided ({state.volume():.2e} of the "
                    f"domain's volume): not complete")
    return CoRefined(x=search.x, status="converged" if complete else "undecided",
                     message=message, iterations=rounds,
                     nfev=last["evaluations"] + search.nfev, njev=search.njev,
                     roots=search.roots, count=search.count, complete=complete,
                     settled=settled, search=search, rounds=tuple(state.history),
                     dims=tuple(state.dims), resolved=tuple(state.resolved),
                     grid=state.grid, probes=probes,
                     seconds=time.perf_counter() - state.start)


@dataclass(frozen=True, kw_only=True)
class CertifiedAll(Certified):
    """A mechanism's :class:`~mechnum.rods.certified.Certified` found by co-refinement: its
    ``parts`` are the final Krawczyk search, ``complete`` covers the co-refinement too, and
    :meth:`certificate` is the co-refinement's (``rods._cocertificate``).

    Attributes
    ----------
    corefined : CoRefined
        The search, with its rounds.
    """

    corefined: CoRefined

    def certificate(self, inputs=None):
        """The :class:`~mechnum.rods._cocertificate.CoCertificate` of the search."""
        return cocertificate(self.corefined, inputs)


def certified_all(result, solutions, stable, extra=""):
    """The :class:`CertifiedAll` of a :class:`CoRefined` with the mechanism's solutions and
    verdicts (``extra``: a note that makes it incomplete)."""
    part = combine([result.search], solutions, stable, extra)
    fields = {f.name: getattr(part, f.name) for f in dataclasses.fields(part)}
    complete = part.complete and result.complete
    fields.update(complete=complete, status="converged" if complete else "undecided",
                  message=result.message + extra, iterations=result.iterations,
                  nfev=result.nfev, seconds=result.seconds)
    return CertifiedAll(**fields, corefined=result)
