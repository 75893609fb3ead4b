"""Equilibria of the 3PFR for given slider inputs, proven by interval arithmetic.

:func:`~mechnum.mechanisms.pfr3.certify_forward` is the certified counterpart of
:func:`~mechnum.mechanisms.pfr3.forward`: the same six reduced equations
(:func:`~mechnum.mechanisms.pfr3.forward_system`: the tips form the platform, ``d_1 / b_1
= d_2 / b_2`` and ``|d_1 / b_1| = 1`` in complex numbers with ``d_i = tip_i - centroid``; the
forces carry ``F``; the moments about the centroid carry ``M``) in the same chart, re-derived
from the :class:`~mechnum.mechanisms.pfr3.Mechanism`'s public fields and
:func:`~mechnum.mechanisms.pfr3.clamps`, and enclosed over boxes
(:mod:`mechnum.rods.certified`). Two exclusion tests of the mechanism's own speed the search up:
the force balance in polar form (:func:`mechnum.rods.certified.forces_exclude`) and the
platform's sides (every two tips are ``a`` apart).

Without ``around``, the search covers the chart's whole domain, every rod on both branches,
by co-refinement (:func:`mechnum.rods.corefine`: a tree of boxes per rod and the live triples
of boxes, then Krawczyk's search of their clusters); rods beyond the chart (``q > Q_MAX``,
forces above about ``9e4 EI / L**2``) are outside the claim (no a-priori bound of the load is
derived for the platform). Its certificate (its inputs: :func:`certificate_inputs`) is
re-checked against the caller's own inputs by :func:`verify_certificate`. With ``around``
(chart points, for example the sampled ``forward(...).x``), it covers a small box
around each point: each equilibrium there is then proven to exist, alone in its box, and the
count is a lower bound.

**Stability.** As for the 2RFR (:mod:`mechnum.mechanisms.rfr2.certified`): the index is the sum
of the rods' pinned indices (:func:`mechnum.rods.pinned_index`) and the index of the reduced
Hessian in the platform's pose, ``sum_i G_i^T K_i G_i`` plus the turning term
``-sum_i n_i . (B_i - P)`` in ``phi`` (``G_i = d B_i / d (x, y, phi)``, ``K_i`` the tips'
stiffnesses); ``stable`` is True or False where proven (:func:`mechnum.rods.proven_stability`),
None otherwise.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from flint import acb, arb
from numpy.typing import ArrayLike

from mechnum import _validate, certify, rods
from mechnum.mechanisms._assembly import check_type
from mechnum.mechanisms.pfr3._model import Mechanism, clamps
from mechnum.rods import certified, k_rel_from_t

# certify_forward is pfr3's
__all__ = ["certificate_inputs", "certify_stability", "chart", "system", "verify_certificate"]

MAX_BOXES = 1_000_000
"""Default bound on the boxes tested (``max_boxes``)."""


def _modes(modes):
    modes = _validate.array(modes, "modes", shape=(3,))
    if np.any(modes < 1) or np.any(modes > 10) or np.any(modes != np.round(modes)):
        raise ValueError(f"modes must be three integers in [1, 10], got {modes.tolist()}")
    return [int(m) for m in modes]


def system(mech: object, lambdas: ArrayLike, modes: Sequence = (1, 1, 1)) -> tuple:
    """``residual, jacobian, rods, exclude`` of the 3PFR's reduced closed form over boxes
    (``exclude.split``: the cut of :func:`mechnum.rods.certified.forces_split`).

    Examples
    --------
    >>> from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS, chart_from_thesis
    >>> f, J, rods, exclude = system(TABLE8, TABLE8_LAMBDAS)
    >>> z = chart_from_thesis([5.1834, -0.7267, 5.0059, -0.9286, 2.6908, -0.0952])
    >>> X = [certify.balls.ball(v - 1e-3, v + 1e-3) for v in z]
    >>> [bool(v.contains(0)) for v in f(X)], exclude(X)
    ([True, True, True, True, True, True], False)
    """
    lambdas = _validate.array(lambdas, "lambdas", shape=(3,))
    modes = _modes(modes)
    origin = clamps(mech, lambdas)
    inv_b = [1 / acb(float(x), float(y)) for x, y in mech.vertices]
    inv_f, inv_fL = arb(mech.L) ** 2 / arb(mech.EI), arb(mech.L) / arb(mech.EI)
    F = [arb(float(v)) for v in mech.force]
    M, a = arb(float(mech.moment)), arb(float(mech.a))

    @certified.memoised
    def rods(X, jacobian):
        return [certified.placed(mech.EI, mech.L, X, i, modes[i], origin[i],
                                 mech.clamp_angles[i], jacobian) for i in range(3)]

    def parts(rs):
        tip = [acb(r.tip[0], r.tip[1]) for r in rs]
        centre = (tip[0] + tip[1] + tip[2]) / 3
        d = [t - centre for t in tip]
        return d, [d[i] * inv_b[i] for i in range(3)]

    def residual(X):
        rs = rods(X, False)
        d, w = parts(rs)
        torque = sum((d[i].real * rs[i].force[1] - d[i].imag * rs[i].force[0]
                      for i in range(3)), arb(0))
        return [(w[0] - w[1]).real, (w[0] - w[1]).imag, w[0].real ** 2 + w[0].imag ** 2 - 1,
                (rs[0].force[0] + rs[1].force[0] + rs[2].force[0] - F[0]) * inv_f,
                (rs[0].force[1] + rs[1].force[1] + rs[2].force[1] - F[1]) * inv_f,
                (torque - M) * inv_fL]

    def jacobian(X):
        rs = rods(X, True)
        d, w = parts(rs)
        rows = [[None] * 6 for _ in range(6)]
        for r in range(3):
            for p in range(2):
                col = 2 * r + p
                dtip = acb(rs[r].jacobian[0][p], rs[r].jacobian[1][p])
                dd = [dtip * ((1 if i == r else 0) - arb(1) / 3) for i in range(3)]
                dw = [dd[i] * inv_b[i] for i in range(3)]
                rows[0][col], rows[1][col] = (dw[0] - dw[1]).real, (dw[0] - dw[1]).imag
                rows[2][col] = 2 * (w[0].real * dw[0].real + w[0].imag * dw[0].imag)
                dforce = (rs[r].jacobian[2][p], rs[r].jacobian[3][p])
                rows[3][col], rows[4][col] = dforce[0] * inv_f, dforce[1] * inv_f
                torque = sum((dd[i].real * rs[i].force[1] - dd[i].imag * rs[i].force[0]
                              for i in range(3)), arb(0))
                torque += d[r].real * dforce[1] - d[r].imag * dforce[0]
                rows[5][col] = torque * inv_fL
        return rows

    def exclude(X):
        rs = rods(X, False)
        if certified.forces_exclude(rs, mech.force):
            return True
        for i, j in ((0, 1), (1, 2), (2, 0)):
            box = [certify.balls.bounds(rs[i].tip[k] - rs[j].tip[k]) for k in range(2)]
            low, high = certified._norm_range(box)
            if bool(a < low) or bool(a > high):
                return True
        return False

    def split(X):
        return certified.forces_split(rods(X, False), mech.force, X)

    exclude.split = split
    return residual, jacobian, rods, exclude


def _reduced(rs):
    """The reduced Hessian in the pose ``(x, y, phi)`` (3 x 3 balls) of an equilibrium."""
    P = [sum((r.tip[k] for r in rs), arb(0)) / 3 for k in range(2)]
    H = [[arb(0)] * 3 for _ in range(3)]
    for r in rs:
        K = certified.stiffness(r)
        rx, ry = r.tip[0] - P[0], r.tip[1] - P[1]
        G = [[arb(1), arb(0), -ry], [arb(0), arb(1), rx]]
        for i in range(3):
            for j in range(3):
                H[i][j] += sum((G[a][i] * K[a][b] * G[b][j] for a in range(2)
                                for b in range(2)), arb(0))
        H[2][2] -= r.force[0] * rx + r.force[1] * ry
    return H


def chart() -> np.ndarray:
    """The chart's whole domain for the 3PFR's three rods: one box per sign pattern of the ``t_i``
    (:func:`mechnum.rods.certified.branch_boxes`). What
    :func:`~mechnum.mechanisms.pfr3.certify_forward` searches without ``around``, and the
    domain that :func:`mechnum.certify.verify` checks a certificate of this mechanism against
    (scope ``"all"``: exactly these boxes; ``"existence"``: boxes inside them).

    Examples
    --------
    >>> chart().shape
    (8, 6, 2)
    """
    return certified.branch_boxes(3)


def verify_certificate(certificate: certify.Certificate, mech: object, lambdas: ArrayLike,
                       modes: Sequence = (1, 1, 1), *,
                       scope: str | None = None) -> certify.Verified:
    """Re-check a certificate of this mechanism against the caller's own inputs: the system
    of ``mech`` at ``lambdas`` and the domain they imply, the chart (:func:`chart`).

    Parameters
    ----------
    certificate : ~mechnum.certify.Certificate or ~mechnum.rods.CoCertificate
        A certificate of a search around given points, or of the whole chart; a
        :class:`~mechnum.rods.CoCertificate` (the co-refinement's, scope ``"all"``) is re-checked
        by :func:`mechnum.rods.certified.verify_corefined` on the rods and equations that ``mech``
        implies, each rod's domain derived again.
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    lambdas : array_like, shape (3,)
        The slider inputs (m).
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
    >>> from mechnum.mechanisms.pfr3 import forward
    >>> from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS
    >>> sampled = forward(TABLE8, TABLE8_LAMBDAS, rng=0).x[:1]
    >>> cert = certify_forward(TABLE8, TABLE8_LAMBDAS, around=sampled).certificate()
    >>> v = verify_certificate(cert, TABLE8, TABLE8_LAMBDAS)
    >>> v.count, v.scope, v.complete
    (1, 'existence', None)
    """
    if isinstance(certificate, rods.CoCertificate):
        return _verify_corefined(certificate, mech, lambdas, modes, scope)
    f, J, _, exclude = system(mech, lambdas, modes)
    return certify.verify(certificate, f, J, exclude, domain=chart(), scope=scope)


def certify_forward(mech: object, lambdas: ArrayLike, modes: Sequence = (1, 1, 1), *,
                    max_boxes: int = MAX_BOXES, around: ArrayLike | None = None,
                    max_live: int = certified.MAX_LIVE) -> certified.Certified:
    """Equilibria of the 3PFR at slider inputs ``lambdas`` with the given modes, proven.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    modes : (int, int, int), optional
        Buckling modes of the rods (in [1, 10]).
    max_boxes : int, optional
        The most boxes tested, at most ``mechnum.certify.MAX_BOXES_LIMIT``.
    around : array_like, shape (k, 6), optional
        Chart points to search around (boxes of half-width
        ``mechnum.rods.certified.AROUND`` times the chart's ranges) instead of the whole
        chart.
    max_live : int, optional
        Without ``around``: the most live triples of boxes after a round of the
        co-refinement (:func:`mechnum.rods.corefine`); beyond it the search stops, not
        complete.

    Returns
    -------
    mechnum.rods.certified.Certified
        ``roots``: enclosures in the chart; ``solutions``: their midpoints as
        ``(psi_i, k_rel_i)`` (``forward``'s coordinates), sorted by ``psi1``;
        ``stable``: True, False or None (see the module); ``scope``: ``"all"`` (the chart's
        whole domain searched by co-refinement, a :class:`~mechnum.rods.CertifiedAll`;
        ``complete``: the count is a theorem over it) or, with ``around``, ``"existence"``
        (each root proven, alone in its box, but others may lie elsewhere: the count is a
        lower bound and ``complete`` is False; ``certificate()`` says so).

    Examples
    --------
    Each of the equilibria that the sampling finds, proven (here the first):

    >>> from mechnum.mechanisms.pfr3 import forward
    >>> from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS
    >>> sampled = forward(TABLE8, TABLE8_LAMBDAS, rng=0)
    >>> r = certify_forward(TABLE8, TABLE8_LAMBDAS, around=sampled.x[:1])
    >>> r.count, r.scope, r.complete, np.round(r.solutions[0], 4).tolist()
    (1, 'existence', False, [5.1834, -0.7267, 5.006, -0.9287, 2.6908, -0.0953])
    """
    modes = _modes(modes)
    f, J, _, exclude = system(mech, lambdas, modes)
    if around is None:
        result = rods.corefine(_chart_rods(mech, lambdas, modes), _assembly(mech),
                               (f, J, exclude, exclude.split), max_live=max_live,
                               max_boxes=max_boxes)
        part = result.search
    else:
        part = certify.roots(f, J, certified.around_boxes(around, 3), max_boxes=max_boxes,
                             exclude=exclude, split=exclude.split, scope="existence")
    z = part.x
    solutions = z.copy()
    if len(z):
        solutions[:, 1::2] = k_rel_from_t(z[:, 0::2], z[:, 1::2])
    stable = certify_stability(mech, lambdas, part.roots, modes)
    if around is not None:
        return certified.combine([part], solutions, stable, certified.around_note(around))
    return rods.certified_all(result, solutions, stable)


def certify_stability(mech: Mechanism, lambdas: ArrayLike, roots: ArrayLike,
              modes: Sequence = (1, 1, 1)) -> list:
    """The proven verdict of each equilibrium in its enclosure (see the module): True (stable),
    False (unstable) or None (a sign not proven).

    Parameters
    ----------
    mech : ~mechnum.mechanisms.pfr3.Mechanism
    lambdas : array_like, shape (3,)
        Slider inputs (m).
    roots : array_like, shape (k, 6, 2)
        Enclosures of equilibria in the chart (for example a verified certificate's
        ``roots``), each on one branch of each rod.
    modes : (int, int, int), optional

    Returns
    -------
    list of (bool or None)

    Examples
    --------
    >>> from mechnum.mechanisms.pfr3 import forward
    >>> from mechnum.mechanisms.pfr3.study import TABLE8, TABLE8_LAMBDAS
    >>> z = forward(TABLE8, TABLE8_LAMBDAS, rng=0).x[:2]
    >>> certify_stability(TABLE8, TABLE8_LAMBDAS, np.stack((z - 1e-12, z + 1e-12), axis=-1))
    [True, True]
    """
    modes = _modes(modes)
    roots = _validate.array(roots, "roots", shape=(None, 6, 2))
    placed = system(mech, lambdas, modes)[2]
    return [rods.proven_stability(
        [rods.pinned_index(mech.EI, mech.L, root[2 * i:2 * i + 2], modes[i],
                           1 if root[2 * i + 1].mean() > 0 else -1) for i in range(3)],
        _reduced(placed(certified.enclosed(root), True))) for root in roots]


def _chart_rods(mech, lambdas, modes=(1, 1, 1)):
    """The three rods as the co-refinement searches them: each chart whole (no a-priori bound
    of the load is derived for the platform)."""
    check_type(mech, Mechanism)
    origin = clamps(mech, _validate.array(lambdas, "lambdas", shape=(3,)))
    return [certified.ChartRod(mech.EI, mech.L, m, origin[i], mech.clamp_angles[i])
            for i, m in enumerate(_modes(modes))]


def _assembly(mech):
    """The tips as far apart as the platform's pins, spanning its triangle (not its mirror
    image), the forces summing to the load, their moments about the centroid to its moment:
    the co-refinement's tests."""
    check_type(mech, Mechanism)
    b = mech.vertices
    u, v = b[1] - b[0], b[2] - b[0]
    area = 0.5 * float(u[0] * v[1] - u[1] * v[0])
    return certified.Assembly(tuple((i, j, float(np.hypot(*(b[i] - b[j]))))
                               for i in range(3) for j in range(i + 1, 3)),
                         mech.force, mech.moment, area, b)


def certificate_inputs(mech: Mechanism, lambdas: ArrayLike,
                       modes: Sequence = (1, 1, 1)) -> dict:
    """What a certificate of :func:`certify_forward` stores to be re-checked: the mechanism's
    fields, the slider inputs and the modes (JSON-ready)."""
    check_type(mech, Mechanism)
    return {"function": "mechnum.mechanisms.pfr3.certified.verify_certificate",
            "origins": mech.origins.tolist(), "guide_angles": mech.guide_angles.tolist(),
            "clamp_angles": mech.clamp_angles.tolist(), "a": mech.a,
            "force": mech.force.tolist(), "moment": mech.moment, "L": mech.L, "EI": mech.EI,
            "orientation": mech.orientation,
            "lambdas": _validate.array(lambdas, "lambdas", shape=(3,)).tolist(),
            "modes": _modes(modes), "domain": "the chart, |t| <= T_MAX",
            "unknowns": ["psi1", "t1", "psi2", "t2", "psi3", "t3"]}


def _verify_corefined(certificate, mech, lambdas, modes, scope):
    """:func:`verify_certificate` of a co-refinement's certificate, on the rods and equations
    that the caller's inputs imply (the chart's whole domain)."""
    if scope not in (None, "all"):
        raise certify.CertificateError(f"the certificate's scope is 'all', the caller asks for "
                                       f"{scope!r}")
    f, J, _, exclude = system(mech, lambdas, modes)
    return certified.verify_corefined(certificate, _chart_rods(mech, lambdas, modes),
                                      _assembly(mech), f, J, exclude)
