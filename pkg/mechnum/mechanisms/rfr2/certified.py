"""Every equilibrium of the 2RFR at given motor angles, proven by interval arithmetic.

:func:`~mechnum.mechanisms.rfr2.certify_forward` is the certified counterpart of
:func:`~mechnum.mechanisms.rfr2.forward`: the same four equations (both tips at one
point, ``n1 + n2 = F``; dimensionless: positions over ``L``, forces over ``EI / L**2``) in the
same chart ``(psi1, t1, psi2, t2)``, re-derived here from the
:class:`~mechnum.mechanisms.rfr2.Mechanism`'s public fields and enclosed over boxes
(:mod:`mechnum.rods.certified`), searched by :func:`~mechnum.certify.roots` over the
chart's whole domain (four boxes, one per sign pattern of ``t1, t2``).

**Beyond the chart.** A rod with ``q > Q_MAX`` has ``Lambda >= TAIL_LAMBDA`` (about 300) and its
tip within ``eps L`` of ``L e`` (``e``: its force's direction; :mod:`mechnum.rods.certified`).
Its force is at least ``R = EI TAIL_LAMBDA**2 / L**2``; the other rod's is ``F`` minus it,
at least ``R - |F|``, so its ``Lambda`` is large too and the forces are antiparallel to within
``|e1 + e2| <= 2 |F| / R``. Both tips at one point then need
``|O1 - O2| >= L (2 - 2 |F| / R - eps1 - eps2)``; ``tail_excluded`` checks that the motors
are nearer than that (as for the study's Table 7), else the result is not ``complete``.

**Stability.** The index of an equilibrium is the sum of the rods' indices with their tips pinned
and the index of the reduced Hessian ``K1 + K2`` (each ``K_i = d n_i / d tip_i`` along the
rod's branch, :func:`mechnum.rods.certified.stiffness`), by Haynsworth's inertia additivity.
``stable`` is False where :func:`~mechnum.certify.definite` proves ``K1 + K2`` over
the root's enclosure to have a negative eigenvalue, None otherwise (the pinned-tip indices are
not enclosed).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from flint import arb
from numpy.typing import ArrayLike

from mechnum import _validate, certify
from mechnum.mechanisms._assembly import check_type
from mechnum.mechanisms.rfr2._model import Mechanism
from mechnum.rods import certified, k_rel_from_t

__all__ = ["chart", "system", "verify_certificate"]  # certify_forward is rfr2's

MAX_BOXES = 400_000
"""Default bound on the boxes tested (``max_boxes``)."""


def _modes(modes):
    modes = _validate.array(modes, "modes", shape=(2,))
    if np.any(modes < 1) or np.any(modes > 10) or np.any(modes != np.round(modes)):
        raise ValueError(f"modes must be two integers in [1, 10], got {modes.tolist()}")
    return [int(m) for m in modes]


def system(mech: Mechanism, theta: ArrayLike, modes: Sequence = (1, 1)) -> tuple:
    """``residual, jacobian`` of the 2RFR's closed form over boxes, for :mod:`mechnum.certify`,
    with ``rods(X, jacobian)`` (both rods, placed) and ``exclude(X)`` (the force balance in
    polar form, :func:`mechnum.rods.certified.forces_exclude`), whose attribute ``split`` is
    the cut that :func:`mechnum.rods.certified.forces_split` suggests.

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> f, J, rods, exclude = system(TABLE7, TABLE7_THETA)
    >>> ball = certify.balls.ball
    >>> X = [ball(1.96, 1.97), ball(-0.06, -0.05), ball(4.81, 4.82),
    ...      ball(0.85, 0.86)]                  # holds a root: no test excludes it
    >>> [bool(v.contains(0)) for v in f(X)], exclude(X)
    ([True, True, True, True], False)
    """
    check_type(mech, Mechanism)
    theta = _validate.array(theta, "theta", shape=(2,))
    modes = _modes(modes)
    inv_L, inv_f = 1 / arb(mech.L), arb(mech.L) ** 2 / arb(mech.EI)
    F = [arb(float(v)) for v in mech.force]

    @certified.memoised
    def rods(X, jacobian):
        return [certified.placed(mech.EI, mech.L, X, i, modes[i], mech.origins[i], theta[i],
                                 jacobian) for i in range(2)]

    def residual(X):
        r1, r2 = rods(X, False)
        return [(r1.tip[c] - r2.tip[c]) * inv_L for c in range(2)] + [
            (r1.force[c] + r2.force[c] - F[c]) * inv_f for c in range(2)]

    def jacobian(X):
        r1, r2 = rods(X, True)
        return ([[r1.jacobian[c][0] * inv_L, r1.jacobian[c][1] * inv_L,
                  -r2.jacobian[c][0] * inv_L, -r2.jacobian[c][1] * inv_L] for c in range(2)]
                + [[r1.jacobian[c][0] * inv_f, r1.jacobian[c][1] * inv_f,
                    r2.jacobian[c][0] * inv_f, r2.jacobian[c][1] * inv_f] for c in (2, 3)])

    def exclude(X):
        return certified.forces_exclude(rods(X, False), mech.force)

    def split(X):
        return certified.forces_split(rods(X, False), mech.force, X)

    exclude.split = split
    return residual, jacobian, rods, exclude


def tail_excluded(mech: Mechanism, modes: Sequence = (1, 1)) -> bool:
    """Whether no equilibrium has a rod beyond the chart (``q > Q_MAX``), by the bound of the
    module (True for the study's Table 7).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7
    >>> tail_excluded(TABLE7, (3, 3))
    True
    """
    modes = _modes(modes)
    R = mech.EI * certified.TAIL_LAMBDA ** 2 / mech.L ** 2
    F = float(np.hypot(*mech.force))
    if F >= R:
        return False
    other = np.sqrt((R - F) / mech.EI) * mech.L
    eps = certified.tail_reach(modes[0]) + certified.tail_reach(modes[1], min(
        other, certified.TAIL_LAMBDA))
    eps = max(eps, certified.tail_reach(modes[1]) + certified.tail_reach(modes[0], min(
        other, certified.TAIL_LAMBDA)))
    gap = float(np.hypot(*(mech.origins[1] - mech.origins[0])))
    return bool(gap < mech.L * (2.0 - 2.0 * F / R - eps) * (1 - 1e-9))


def chart() -> np.ndarray:
    """The chart's whole domain for the 2RFR's two rods: one box per sign pattern of the ``t_i``
    (:func:`mechnum.rods.certified.branch_boxes`). What
    :func:`~mechnum.mechanisms.rfr2.certify_forward` searches without ``around``, and the
    domain that :func:`mechnum.certify.verify` checks a certificate of this mechanism against
    (scope ``"all"``: exactly these boxes; ``"existence"``: boxes inside them).

    Examples
    --------
    >>> chart().shape
    (4, 4, 2)
    """
    return certified.branch_boxes(2)


def verify_certificate(certificate: certify.Certificate, mech: Mechanism, theta: ArrayLike,
                       modes: Sequence = (1, 1), *,
                       scope: str | None = None) -> certify.Verified:
    """Re-check a certificate of this mechanism against the caller's own inputs: the system
    of ``mech`` at ``theta`` and the domain they imply, the chart (:func:`chart`).

    Parameters
    ----------
    certificate : ~mechnum.certify.Certificate
    mech : ~mechnum.mechanisms.rfr2.Mechanism
    theta : array_like, shape (2,)
        The motor angles (rad).
    modes : tuple of int, optional
        The rods' buckling modes.
    scope : {"all", "existence"}, optional
        The scope required (None: the certificate's own).

    Returns
    -------
    ~mechnum.certify.Verified

    Raises
    ------
    ~mechnum.certify.CertificateError
        If the certificate does not prove what it says for these inputs
        (:func:`mechnum.certify.verify`).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> sampled = forward(TABLE7, TABLE7_THETA, rng=0).x[:1]
    >>> cert = certify_forward(TABLE7, TABLE7_THETA, around=sampled).certificate()
    >>> v = verify_certificate(cert, TABLE7, TABLE7_THETA)
    >>> v.count, v.scope, v.complete
    (1, 'existence', None)
    """
    f, J, _, exclude = system(mech, theta, modes)
    return certify.verify(certificate, f, J, exclude, domain=chart(), scope=scope)


def certify_forward(mech: Mechanism, theta: ArrayLike, modes: Sequence = (1, 1), *,
                    max_boxes: int = MAX_BOXES,
                    around: ArrayLike | None = None) -> certified.Certified:
    """Every equilibrium of the 2RFR at motor angles ``theta`` with the given modes, proven.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.rfr2.Mechanism
    theta : array_like, shape (2,)
        Motor angles (rad).
    modes : (int, int), optional
        Buckling modes of rod 1 and rod 2 (in [1, 10]).
    max_boxes : int, optional
        The most boxes tested, at most ``mechnum.certify.MAX_BOXES_LIMIT``.
    around : array_like, shape (k, 4), optional
        Chart points (for example ``forward(...).x``) to search around instead of
        the whole chart (boxes of :func:`mechnum.rods.certified.around_boxes`): each
        equilibrium found there is proven, alone in its box, and the count is a lower bound
        (``complete`` is then False).

    Returns
    -------
    mechnum.rods.certified.Certified
        ``roots``: enclosures in the chart ``(psi1, t1, psi2, t2)``; ``solutions``: their
        midpoints as ``(psi1, k_rel1, psi2, k_rel2)`` (the coordinates of
        ``forward``'s ``solutions``), sorted by ``psi1``; ``stable``: False (proven
        unstable) or None (see the module); ``complete``: the count is a theorem (the chart
        searched whole, and the tail beyond it excluded).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> sampled = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> r = certify_forward(TABLE7, TABLE7_THETA, around=sampled.x)
    >>> r.count, r.complete, bool(np.abs(r.solutions - sampled.solutions).max() < 1e-12)
    (3, False, True)
    """
    modes = _modes(modes)
    f, J, rods, exclude = system(mech, theta, modes)
    boxes = chart() if around is None else certified.around_boxes(around, 2)
    part = certify.roots(f, J, boxes, max_boxes=max_boxes, exclude=exclude,
                         split=exclude.split, scope="all" if around is None else "existence")
    k_rel = (k_rel_from_t(part.x[:, 0::2], part.x[:, 1::2]) if part.count
             else np.zeros((0, 2)))
    solutions = np.stack((part.x[:, 0], k_rel[:, 0], part.x[:, 2], k_rel[:, 1]), axis=-1)
    stable = []
    for root in part.roots:
        r1, r2 = rods(certified.enclosed(root), True)
        K1, K2 = certified.stiffness(r1), certified.stiffness(r2)
        stable.append(certified.verdict([[K1[i][j] + K2[i][j] for j in range(2)]
                                         for i in range(2)]))
    extra = certified.around_note(around) + ("" if tail_excluded(mech, modes) else (
        "; rods beyond the chart (q > Q_MAX) are not excluded"))
    return certified.combine([part], solutions, stable, extra)
