"""Every equilibrium of the 2RFR at given motor angles, proven by interval arithmetic.

:func:`~mechnum.mechanisms.rfr2.certify_forward` is the certified counterpart of
:func:`~mechnum.mechanisms.rfr2.forward`: the same four equations (both tips at one
point, ``n1 + n2 = F``; dimensionless: positions over ``L``, forces over ``EI / L**2``) in the
same chart ``(psi1, t1, psi2, t2)``, re-derived here from the
:class:`~mechnum.mechanisms.rfr2.Mechanism`'s public fields and enclosed over boxes
(:mod:`mechnum.rods.certified`). The whole chart, both branches of each rod, is searched by
co-refinement (:func:`mechnum.rods.corefine`: a tree of boxes per rod and the live pairs of
boxes, then Krawczyk's search of their clusters), each rod's chart cut to the a-priori bound
on its load (:func:`mechnum.rods.certified.pair_bound`: no equilibrium has a rod beyond it); its
certificate (its inputs: :func:`certificate_inputs`) is re-checked against the caller's own
inputs by :func:`verify_certificate`.

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
Each rod's pinned index is proven in closed form over the root's enclosure
(:func:`mechnum.rods.pinned_index`), and ``K1 + K2`` by :func:`~mechnum.certify.definite`:
``stable`` is True (proven stable), False (proven unstable) or None where a sign is not
proven (:func:`mechnum.rods.proven_stability`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from flint import arb
from numpy.typing import ArrayLike

from mechnum import _validate, certify, rods
from mechnum.mechanisms._assembly import check_type
from mechnum.mechanisms.rfr2._model import Mechanism
from mechnum.rods import T_MAX, certified, k_rel_from_t

# certify_forward is rfr2's
__all__ = ["certificate_inputs", "certify_stability", "chart", "system", "verify_certificate"]

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
    certificate : ~mechnum.certify.Certificate or ~mechnum.rods.CoCertificate
        A certificate of a search around given points, or of the whole chart; a
        :class:`~mechnum.rods.CoCertificate` (the co-refinement's, scope ``"all"``) is re-checked
        by :func:`mechnum.rods.certified.verify_corefined` on the rods and equations that ``mech``
        implies, each rod's domain derived again.
    mech : ~mechnum.mechanisms.rfr2.Mechanism
    theta : array_like, shape (2,)
        The motor angles (rad).
    modes : tuple of int, optional
        The rods' buckling modes.
    scope : {"all", "existence"}, optional
        The scope required (None: the certificate's own).

    Returns
    -------
    ~mechnum.certify.Verified or ~mechnum.rods.CoVerified

    Raises
    ------
    ~mechnum.certify.CertificateError
        If the certificate does not prove what it says for these inputs
        (:func:`mechnum.certify.verify`, :func:`mechnum.rods.certified.verify_corefined`).

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
    if isinstance(certificate, rods.CoCertificate):
        return _verify_corefined(certificate, mech, theta, modes, scope)
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
    mechnum.rods.CertifiedAll or mechnum.rods.certified.Certified
        ``roots``: enclosures in the chart ``(psi1, t1, psi2, t2)``; ``solutions``: their
        midpoints as ``(psi1, k_rel1, psi2, k_rel2)`` (the coordinates of
        ``forward``'s ``solutions``), sorted by ``psi1``; ``stable``: True (proven
        stable), False (proven unstable) or None (see the module); ``complete``: the count is
        a theorem (the chart searched whole, every rod beyond it excluded by the a-priori
        bound). Without ``around``, a :class:`~mechnum.rods.CertifiedAll`, whose
        ``certificate(certificate_inputs(...))`` :func:`verify_certificate` re-checks.

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
    f, J, _, exclude = system(mech, theta, modes)
    if around is None:
        result = rods.corefine(_chart_rods(mech, theta, modes), _assembly(mech),
                               (f, J, exclude, exclude.split), max_boxes=max_boxes)
        part = result.search
    else:
        part = certify.roots(f, J, certified.around_boxes(around, 2), max_boxes=max_boxes,
                             exclude=exclude, split=exclude.split, scope="existence")
    k_rel = (k_rel_from_t(part.x[:, 0::2], part.x[:, 1::2]) if part.count
             else np.zeros((0, 2)))
    solutions = np.stack((part.x[:, 0], k_rel[:, 0], part.x[:, 2], k_rel[:, 1]), axis=-1)
    stable = certify_stability(mech, theta, part.roots, modes)
    if around is not None:
        return certified.combine([part], solutions, stable, certified.around_note(around))
    beyond = all(rod.t_max < T_MAX for rod in _chart_rods(mech, theta, modes)) or (
        tail_excluded(mech, modes))
    return rods.certified_all(result, solutions, stable, "" if beyond else (
        "; rods beyond the chart (q > Q_MAX) are not excluded"))


def certify_stability(mech: Mechanism, theta: ArrayLike, roots: ArrayLike,
              modes: Sequence = (1, 1)) -> list:
    """The proven verdict of each equilibrium in its enclosure (see the module): True (stable),
    False (unstable) or None (a sign not proven).

    Parameters
    ----------
    mech : ~mechnum.mechanisms.rfr2.Mechanism
    theta : array_like, shape (2,)
        Motor angles (rad).
    roots : array_like, shape (k, 4, 2)
        Enclosures of equilibria in the chart (for example a verified certificate's
        ``roots``), each on one branch of each rod.
    modes : (int, int), optional

    Returns
    -------
    list of (bool or None)

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> z = forward(TABLE7, TABLE7_THETA, rng=0).x
    >>> certify_stability(TABLE7, TABLE7_THETA, np.stack((z - 1e-9, z + 1e-9), axis=-1))
    [True, True, True]
    """
    modes = _modes(modes)
    roots = _validate.array(roots, "roots", shape=(None, 4, 2))
    placed = system(mech, theta, modes)[2]
    out = []
    for root in roots:
        r1, r2 = placed(certified.enclosed(root), True)
        K1, K2 = certified.stiffness(r1), certified.stiffness(r2)
        reduced = [[K1[i][j] + K2[i][j] for j in range(2)] for i in range(2)]
        pinned = [rods.pinned_index(mech.EI, mech.L, root[2 * i:2 * i + 2], modes[i],
                                    1 if root[2 * i + 1].mean() > 0 else -1)
                  for i in range(2)]
        out.append(rods.proven_stability(pinned, reduced))
    return out


def _chart_rods(mech, theta, modes=(1, 1)):
    """The two rods as the co-refinement searches them: each chart up to the a-priori bound on
    its load (:func:`mechnum.rods.certified.pair_bound`; the chart's whole range where that bound is
    beyond it, for which :func:`tail_excluded` must then exclude the rest).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> [round(rod.lam_max, 2) for rod in _chart_rods(TABLE7, TABLE7_THETA)]
    [10.39, 10.39]
    """
    check_type(mech, Mechanism)
    theta = _validate.array(theta, "theta", shape=(2,))
    modes = _modes(modes)
    gap = float(np.hypot(*(mech.origins[1] - mech.origins[0])))
    bound = certified.pair_bound(modes, gap, float(np.hypot(*mech.force)), mech.EI, mech.L)
    return [certified.ChartRod(mech.EI, mech.L, modes[i], mech.origins[i], theta[i],
                          certified.chart_t_bound(bound[i]), bound[i]) for i in range(2)]


def _assembly(mech):
    """The tips at one point, the forces summing to the load: the co-refinement's tests."""
    check_type(mech, Mechanism)
    return certified.Assembly(((0, 1, 0.0),), mech.force)


def certificate_inputs(mech: Mechanism, theta: ArrayLike,
                       modes: Sequence = (1, 1)) -> dict:
    """What a certificate of :func:`certify_forward` stores to be re-checked: the mechanism's
    fields, the motor angles and the modes (JSON-ready)."""
    check_type(mech, Mechanism)
    return {"function": "mechnum.mechanisms.rfr2.certified.verify_certificate",
            "origins": mech.origins.tolist(), "force": mech.force.tolist(), "L": mech.L,
            "EI": mech.EI, "theta": _validate.array(theta, "theta", shape=(2,)).tolist(),
            "modes": _modes(modes), "unknowns": ["psi1", "t1", "psi2", "t2"]}


def _verify_corefined(certificate, mech, theta, modes, scope):
    """:func:`verify_certificate` of a co-refinement's certificate: on the rods and the
    equations that the caller's ``mech``, ``theta`` and ``modes`` imply, each rod's domain
    derived again from the a-priori bound."""
    if scope not in (None, "all"):
        raise certify.CertificateError(f"the certificate's scope is 'all', the caller asks for "
                                       f"{scope!r}")
    chart_of = _chart_rods(mech, theta, modes)
    f, J, _, exclude = system(mech, theta, modes)
    verified = certified.verify_corefined(certificate, chart_of, _assembly(mech), f, J, exclude)
    if verified.complete and not all(rod.t_max < T_MAX for rod in chart_of) and not (
            tail_excluded(mech, modes)):
        raise certify.CertificateError("rods beyond the chart are not excluded: the count is "
                                       "not complete")
    return verified
