"""Every clamped-pinned equilibrium that reaches a point, proven (Chapter 3's pinned rod).

:func:`certify_pinned` searches the regular chart ``(psi, t)`` of :mod:`mechnum.rods.regular`
of each mode with :func:`mechnum.certify.roots`, the closed form enclosed by
:mod:`mechnum.rods.balls`. The searched boxes are the chart's whole closed domain, one per
branch: ``0 <= psi <= 2 pi`` and ``0 <= t <= T_MAX`` or ``-T_MAX <= t <= 0``. What lies beyond
``|t| = T_MAX`` (``q > Q_MAX = 600``: rods pulled by more than ``(Q_MAX / 2)**2 EI / L**2`` or
so) is not searched: those rods are straight to within ``(2 pi mode + 2) L / Lambda`` of their
length (``Lambda = L sqrt(R / EI) > Q_MAX / 2``), so their tips lie more than
``L (1 - (2 pi mode + 2) / 300)`` from the clamp, and :func:`certify_pinned` checks that the
target is nearer than that (else it says so in the result's ``message``, which is then not
``complete``).
"""

from dataclasses import dataclass

import numpy as np
from flint import arb

from mechnum import _validate, certify
from mechnum.rods import balls, regular

TWO_PI = 2.0 * np.pi
CHART_BOX = ((0.0, TWO_PI), (0.0, regular.T_MAX))
"""The chart's closed domain on the branch ``t > 0`` (mirrored for ``t < 0``)."""
# Lambda = lambda L of a rod at the chart's edge q = Q_MAX is at least about Q_MAX / 2 - 1
# (Lambda ~ q / 2 + log 4 - ... for large q): a lower bound used for the tail beyond the chart.
TAIL_LAMBDA = regular.Q_MAX / 2.0 - 1.0
MAX_BOXES = 200_000


@dataclass(frozen=True, kw_only=True)
class Certified(certify.Roots):
    """A certified search of an application, with the solutions in the package's coordinates.

    Attributes
    ----------
    solutions : ndarray
        The midpoints of the root enclosures, in the coordinates of the corresponding sampled
        solver (``pinned_equilibria``: rows ``(psi, k_rel, mode)``; ``forward_elliptic``:
        ``(psi_i, k_rel_i)`` per rod).
    stable : list of (bool or None)
        Per solution: True (proven stable), False (proven unstable), None (not decided).
    parts : tuple of mechnum.certify.Roots
        The searches (one per mode, or one for a mechanism), each with its certificate.
    """

    solutions: np.ndarray
    stable: list
    parts: tuple


def combine(parts, solutions, stable, extra=""):
    """One :class:`Certified` of several searches (their counts and work added)."""
    roots = np.concatenate([p.roots for p in parts]) if parts else np.zeros((0, 2, 2))
    undecided = np.concatenate([p.undecided for p in parts])
    complete = all(p.complete for p in parts) and not extra
    count = sum(p.count for p in parts)
    message = "; ".join(p.message for p in parts) + extra
    return Certified(x=roots.mean(axis=2), status="converged" if complete else "undecided",
                     message=message, iterations=sum(p.iterations for p in parts),
                     nfev=sum(p.nfev for p in parts), njev=sum(p.njev for p in parts),
                     roots=roots, excluded=sum(p.excluded for p in parts),
                     undecided=undecided, complete=complete, count=count,
                     boxes=sum(p.boxes for p in parts), seconds=sum(p.seconds for p in parts),
                     searched=np.concatenate([p.searched for p in parts]),
                     leaves=sum((p.leaves for p in parts), ()), solutions=solutions,
                     stable=list(stable), parts=tuple(parts))


def branch_boxes(n_rods):
    """The chart's domain for ``n_rods`` rods: one box per sign pattern of the ``t_i``."""
    out = []
    for signs in np.ndindex(*(2,) * n_rods):
        box = []
        for s in signs:
            box += [CHART_BOX[0], CHART_BOX[1] if s == 0 else (-CHART_BOX[1][1], 0.0)]
        out.append(box)
    return np.array(out)


def branch_of(X, i):
    """The sign of ``t`` of rod ``i`` on the box of balls ``X`` (boxes lie on one side)."""
    return 1 if bool(X[2 * i + 1].upper() > 0) else -1


def pinned_system(EI, L, target, mode):
    """``residual, jacobian`` of ``tip(psi, t) - target`` (over ``L``) for :mod:`mechnum.certify`.

    Examples
    --------
    >>> from mechnum.certify import ball
    >>> f, J = pinned_system(1.0, 1.0, [0.8, 0.1], 2)
    >>> [bool(v.contains(0)) for v in f([ball(3.0, 3.1), ball(0.3, 0.5)])]
    [True, True]
    """
    tx, ty = arb(float(target[0])), arb(float(target[1]))
    inv_L = 1 / arb(float(L))

    def residual(X):
        rod = balls.clamped_pinned(EI, L, X[0], X[1], mode, branch_of(X, 0))
        return [(rod.tip[0] - tx) * inv_L, (rod.tip[1] - ty) * inv_L]

    def jacobian(X):
        rod = balls.clamped_pinned(EI, L, X[0], X[1], mode, branch_of(X, 0), jacobian=True)
        return [[rod.jacobian[i][j] * inv_L for j in range(2)] for i in range(2)]

    return residual, jacobian


def certify_pinned(EI, L, target, modes=(1, 2, 3), *, max_boxes=MAX_BOXES):
    """Every clamped-pinned equilibrium whose tip is at ``target``, proven by interval arithmetic.

    The certified counterpart of :func:`mechnum.rods.pinned_equilibria` (same inputs, same
    coordinates of the solutions): a branch-and-prune search of the regular chart of each mode
    (see the module). When the result is ``complete``, the count is a theorem: there are
    exactly ``count`` equilibria of these modes with ``|t| <= T_MAX``, each in its enclosure,
    and none beyond (the tail bound of the module).

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    target : array_like, shape (2,)
        The pinned point in the rod's local frame (m), nearer than ``L`` to the clamp.
    modes : iterable of int, optional
        Buckling modes (``1 <= mode <= 10``).
    max_boxes : int, optional
        Boxes tested per mode, at most ``mechnum.certify.MAX_BOXES_LIMIT``.

    Returns
    -------
    Certified
        ``solutions``: rows ``(psi, k_rel, mode)`` (the midpoints of the enclosures, sorted
        by mode); ``stable``: None for each (the stability of a pinned rod is not certified
        here); ``parts``: one search per mode, each with its ``certificate()``.

    Examples
    --------
    >>> r = certify_pinned(1.0, 1.0, [0.8, 0.1], modes=(1,))
    >>> r.count, r.complete
    (0, True)
    """
    EI = _validate.scalar(EI, "EI", positive=True)
    L = _validate.scalar(L, "L", positive=True)
    target = _validate.array(target, "target", shape=(2,))
    if np.hypot(*target) >= L:
        raise ValueError(f"target must be nearer than L = {L} to the clamp, got "
                         f"{target.tolist()}")
    modes = [_validate.maxiter(m, "mode", maximum=10) for m in modes]
    parts, rows = [], []
    for mode in modes:
        f, J = pinned_system(EI, L, target, mode)
        part = certify.roots(f, J, branch_boxes(1), max_boxes=max_boxes)
        parts.append(part)
        for psi, t in part.x:
            rows.append((psi, float(regular.k_rel_from_t(psi, t)), mode))
    reach = 1.0 - (2.0 * np.pi * max(modes, default=1) + 2.0) / TAIL_LAMBDA
    extra = "" if np.hypot(*target) < reach * L else (
        f"; the target is farther than {reach:.3f} L: rods beyond the chart are not excluded")
    solutions = np.array(rows, dtype=float).reshape(-1, 3)
    return combine(parts, solutions, [None] * len(rows), extra)
