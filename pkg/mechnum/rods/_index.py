"""The index of a clamped-pinned rod, proven from its closed form: certified stability.

An equilibrium of a rod clamped at ``s = 0`` under the force ``n = R (cos psi, sin psi)`` at its
tip is stable when the second variation of its energy,
``Q[eta] = int_0^L (EI eta'**2 + R cos(theta - psi) eta**2) ds`` over angle variations ``eta``
with ``eta(0) = 0``, is positive; its **index** is the number of its negative eigenvalues: with
the tip free under the dead load (``iota_free``), or with the tip pinned, ``eta`` then
orthogonal to ``(-sin theta, cos theta)`` (``iota_pin``).

**The free index, in closed form.** At a fixed force the rods form a two-parameter family,
``theta = psi - 2 arccos(k sn(x, k))``, ``x = lambda s + x0``; with ``phi = am(x)`` (rising
from ``phi1`` at the clamp to ``phi2 = (j - 1/2) pi`` at the tip, ``j`` the mode), its
derivatives in ``x0`` and ``k`` are the Jacobi fields (solutions of
``EI u'' = R cos(theta - psi) u``)::

    u1 = cos(phi),   u2 = Delta sin(phi) - cos(phi) G(phi),   G = E(phi, k) - k'**2 F(phi, k)

(``Delta = (1 - k**2 sin(phi)**2)**(1/2)``, ``k'**2 = 1 - k**2``; their Wronskian in ``x`` is
``k'**2``). ``u0 = u2(phi1) u1 - u1(phi1) u2`` vanishes at the clamp. ``u1`` vanishes at
``phi = pi/2 + n pi``, where ``u0 = -cos(phi1) k' (-1)**n``: its signs alternate, so by Sturm's
separation theorem ``u0`` has exactly one zero between two consecutive zeros of ``u1`` and none
before the first: ``j - 1`` zeros in ``(0, L)``, and none at ``L``. By the oscillation theorem
(Prufer's angle of ``u0``, the Dirichlet condition at the clamp and the natural one at the
tip) ``iota_free = (j - 1) + [u0(L) u0'(L) < 0]``, and
``u0(L) du0/dphi(L) = cos(phi1) k' (u2(phi1) + cos(phi1) G(phi2))``. In the regular chart
(the regular chart (``rods._regular``): ``k sin(phi1) = a``, ``k cos(phi1) = v b``, so
``Delta(phi1) = b``; ``G(phi2) - G(phi1) = D - p Lambda``) its sign is that of::

    S = sign(t) cos(psi / 2) + |v| (D - p Lambda),    iota_free = (j - 1) + [S < 0]

**The pinned index.** The free problem is the pinned one with the tip as one more unknown, whose
energy is ``E(tip) - n . tip`` with ``d E / d tip = n``: so (Haynsworth's inertia additivity,
valid when the pinned problem is not degenerate, ``det(d tip / d (psi, t)) != 0``)
``iota_free = iota_pin + ind(K)``, ``K = d n / d tip`` (the tip stiffness,
:func:`mechnum.rods.certified.stiffness`). Hence ``iota_pin = iota_free - ind(K)``.

:func:`free_index` and :func:`pinned_index` enclose ``S``, ``det(d tip / d (psi, t))`` and
``K`` in balls over a chart box (Arb, ``rods._balls``) and return the index where
every sign is proven, None elsewhere. :func:`proven_stability` combines the rods' pinned
indices with the reduced Hessian of a mechanism (its index adds to theirs) into a verdict.
"""

import numpy as np
from flint import arb

from mechnum import _validate, certify
from mechnum.certify.balls import ball
from mechnum.rods import _balls as balls
from mechnum.rods import _regular as regular
from mechnum.rods.certified import stiffness


def _chart(psi, t, sign):
    """``a = cos(psi/2)``, ``b = sin(psi/2)``, ``|v|`` and ``p = b**2 exp(-q)`` over a box."""
    tau = t if sign > 0 else -t
    q = tau * tau / ((1 - tau) * (1 + tau))
    return (psi / 2).cos(), (psi / 2).sin(), (-(-q).expm1()).sqrt(), (psi / 2).sin() ** 2 * (
        -q).exp()


def _rod(EI, L, box, mode, sign):
    EI = _validate.scalar(EI, "EI", positive=True)
    L = _validate.scalar(L, "L", positive=True)
    box = _validate.array(box, "box", shape=(2, 2))
    if isinstance(mode, bool) or not isinstance(mode, (int, np.integer)) or mode < 1:
        raise ValueError(f"mode must be an integer >= 1, got {_validate.shown(mode)}")
    if isinstance(sign, bool) or not isinstance(sign, (int, np.integer)) or sign not in (1, -1):
        raise ValueError(f"sign must be 1 or -1, got {_validate.shown(sign)}")
    psi, t = ball(*box[0]), ball(*box[1])
    if not (bool(psi > 0) and bool(psi < 2 * arb.pi()) and bool(sign * t > 0)
            and bool(sign * t <= regular.T_MAX)):
        raise ValueError(f"the box {list(map(list, box))} must lie inside the chart, on the "
                         f"branch {sign}")
    return psi, t, balls.clamped_pinned(EI, L, psi, t, mode, sign, jacobian=True)


def margin(EI, L, box, mode, sign):
    """The ball ``S`` of the module over a chart box ``[[psi_lo, psi_hi], [t_lo, t_hi]]`` on
    the branch ``sign``: negative where the free tip adds one negative direction.

    Examples
    --------
    >>> S = margin(1.0, 1.0, [[1.96, 1.961], [-0.057, -0.056]], 1, -1)
    >>> bool(S < 0)
    True
    """
    psi, t, rod = _rod(EI, L, box, mode, sign)
    a, b, v, p = _chart(psi, t, sign)
    lam = (rod.R * arb(float(L)) ** 2 / arb(float(EI))).sqrt()
    along = (rod.tip[0] * psi.cos() + rod.tip[1] * psi.sin()) / arb(float(L))
    D = lam * (1 - along) / 2
    return sign * a + v * (D - p * lam)


def free_index(EI, L, box, mode, sign):
    """The index with the tip free under its load, proven over the chart box, or None.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    box : array_like, shape (2, 2)
        ``[[psi_lo, psi_hi], [t_lo, t_hi]]`` inside the chart, on one branch.
    mode : int
    sign : {1, -1}
        The branch (the sign of ``t``).

    Returns
    -------
    int or None
        ``mode - 1`` or ``mode``, the same for every rod of the box, or None where the sign of
        ``S`` is not proven.

    Examples
    --------
    Chapter 5's solution 1, rod 1 (mode 1, ``k_rel = -0.0044``): one negative direction when
    its tip is free.

    >>> free_index(0.0522, 1.0, [[1.9625, 1.9626], [-0.05603, -0.05602]], 1, -1)
    1
    """
    S = margin(EI, L, box, mode, sign)
    if not S.is_finite() or S.contains(0):
        return None
    return (mode - 1) + (1 if bool(S < 0) else 0)


def stiffness_index(K):
    """The negative eigenvalues of a symmetric 2 x 2 matrix of balls, proven, or None."""
    det = K[0][0] * K[1][1] - K[0][1] * K[1][0]
    trace = K[0][0] + K[1][1]
    if not (det.is_finite() and trace.is_finite()) or det.contains(0):
        return None
    if bool(det < 0):
        return 1
    if trace.contains(0):
        return None
    return 0 if bool(trace > 0) else 2


def pinned_index(EI, L, box, mode, sign):
    """The index with the tip pinned, ``iota_free - ind(K)``, proven over the box, or None.

    Parameters and returns as :func:`free_index`; None also where
    ``det(d tip / d (psi, t))`` is not proven non-zero (the pinned problem may be degenerate).

    Examples
    --------
    >>> pinned_index(0.0522, 1.0, [[1.9625, 1.9626], [-0.05603, -0.05602]], 1, -1)
    0
    """
    free = free_index(EI, L, box, mode, sign)
    _, _, rod = _rod(EI, L, box, mode, sign)
    J = rod.jacobian
    det = J[0][0] * J[1][1] - J[0][1] * J[1][0]
    if free is None or not det.is_finite() or det.contains(0):
        return None
    K = stiffness(rod)
    index = stiffness_index(K)
    if index is None or free - index < 0:
        return None
    return free - index


def proven_stability(pinned, reduced):
    """A mechanism's verdict from its rods' pinned indices and its reduced Hessian (balls).

    Its index is the sum of the rods' pinned indices and the reduced Hessian's (Haynsworth):
    True when every rod's is 0 and the reduced Hessian is proven positive definite; False
    when a rod's is proven positive or the reduced Hessian proven to have a negative
    eigenvalue; None otherwise.

    Examples
    --------
    >>> proven_stability([0, 0], [[arb(2.0), arb(0.5)], [arb(0.5), arb(1.0)]])
    True
    >>> proven_stability([0, None], [[arb(-1.0), arb(0.0)], [arb(0.0), arb(1.0)]])
    False
    """
    try:
        pinned = list(pinned)
    except TypeError:
        raise ValueError(f"pinned must be a sequence of indices (int >= 0 or None), got "
                         f"{_validate.shown(pinned)}") from None
    if not all(i is None or (isinstance(i, (int, np.integer)) and not isinstance(i, bool)
                             and i >= 0) for i in pinned):
        raise ValueError(f"pinned must be indices (int >= 0) or None, got {pinned!r}")
    definite = certify.definite(reduced)
    if definite is False or any(i is not None and i > 0 for i in pinned):
        return False
    if definite is True and all(i == 0 for i in pinned):
        return True
    return None
