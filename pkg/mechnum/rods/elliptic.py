"""The closed form in elliptic integrals of a clamped-pinned rod (conventions: mechnum.rods).

scipy's ``ellipkinc(phi, m)`` and ``ellipeinc(phi, m)`` are ``F(phi, k)`` and ``E(phi, k)`` with
the parameter ``m = k**2``; ``ellipj`` gives the amplitude ``phi = am(u | m)``.
"""

from dataclasses import dataclass

import numpy as np
from scipy.special import ellipeinc, ellipj, ellipkinc, expit

from mechnum import newton
from mechnum.errors import ConvergenceError, MechnumError
from mechnum.rods.shooting import Rod, _finite, _positive

TWO_PI = 2.0 * np.pi


class NoEquilibriumError(MechnumError):
    """A rod has no equilibrium on the requested branch (a load below a mode's range)."""


@dataclass(frozen=True)
class EllipticRod:
    """The closed-form clamped-pinned rod of :func:`clamped_pinned` (local frame).

    Attributes
    ----------
    k, k_min, phi1, phi2 : ndarray
        Elliptic modulus, its least admissible magnitude, and the amplitudes at clamp and tip.
    R : ndarray
        Magnitude of the tip force (N); ``force = R (cos psi, sin psi)``.
    force, tip : ndarray, shape (..., 2)
        Tip force (N) and tip position (m).
    tip_angle, clamp_moment : ndarray
        ``theta(L)`` (rad) and ``m(0)`` (N m).
    rod : Rod or None
        The shape at ``nodes`` equally spaced points, when asked for.
    """

    k: np.ndarray
    k_min: np.ndarray
    phi1: np.ndarray
    phi2: np.ndarray
    R: np.ndarray
    force: np.ndarray
    tip: np.ndarray
    tip_angle: np.ndarray
    clamp_moment: np.ndarray
    rod: Rod = None


def elliptic_k(psi, k_rel):
    """The modulus ``k`` and its least magnitude ``k_min`` from ``(psi, k_rel)``.

    ``k_min = |cos(psi/2)|`` and ``k = sign(k_rel) k_min + (1 - k_min) k_rel`` (the study's
    (91)), so ``k_rel`` in ``(-1, 0) U (0, 1)`` maps onto the admissible
    ``k_min < |k| < 1``.

    Parameters
    ----------
    psi : array_like
        Direction of the tip force in the local frame, in ``(0, 2 pi)`` (rad).
    k_rel : array_like
        Relative modulus, ``0 < |k_rel| < 1``.

    Returns
    -------
    k, k_min : ndarray

    Raises
    ------
    ValueError
        If ``psi`` or ``k_rel`` is outside its open range (or not finite).

    Examples
    --------
    >>> k, kmin = elliptic_k(2 * np.pi / 3, [-0.5, 0.5])
    >>> np.round(k, 12).tolist(), round(float(kmin), 12)
    ([-0.75, 0.75], 0.5)
    """
    psi, k_rel = _finite("psi", psi), _finite("k_rel", k_rel)
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError(f"psi must lie in the open interval (0, 2 pi), got {psi!r}")
    if np.any((k_rel == 0) | (np.abs(k_rel) >= 1)):
        raise ValueError(f"k_rel must satisfy 0 < |k_rel| < 1, got {k_rel!r}")
    k_min = np.abs(np.cos(0.5 * psi))
    return np.sign(k_rel) * k_min + _one_minus_k_min(psi) * k_rel, k_min


def _one_minus_k_min(psi):
    """``1 - |cos(psi/2)|`` without cancellation (``sin(psi/2)**2 / (1 + |cos(psi/2)|)``)."""
    return np.sin(0.5 * psi) ** 2 / (1.0 + np.abs(np.cos(0.5 * psi)))


def _mode(mode):
    mode = np.asarray(mode)
    if not np.all(np.isfinite(mode)) or np.any(mode < 1) or np.any(mode != np.round(mode)):
        raise ValueError(f"mode must be an integer >= 1, got {mode!r}")
    return mode.astype(float)


def _shape(phi, psi, k, phi1, F1, E1, lam, EI):
    """``(x, y, theta, m)`` at amplitude ``phi`` (the study's (86), (87), (37) and (42))."""
    m = k * k
    dF, dE = ellipkinc(phi, m) - F1, ellipeinc(phi, m) - E1
    dC = np.cos(phi) - np.cos(phi1)
    x = -(np.cos(psi) * (2 * dE - dF) + 2 * k * np.sin(psi) * dC) / lam
    y = -(np.sin(psi) * (2 * dE - dF) - 2 * k * np.cos(psi) * dC) / lam
    theta = psi - 2 * np.arccos(np.clip(k * np.sin(phi), -1.0, 1.0))
    return x, y, theta, 2 * EI * k * lam * np.cos(phi)


def clamped_pinned(EI, L, psi, k_rel, mode=1, *, nodes=None):
    """The clamped-pinned (or end-loaded cantilever) rod in closed form.

    With ``lambda = sqrt(R / EI)``: ``lambda L = F(phi2, k) - F(phi1, k)`` gives ``R``; along the
    rod ``F(phi, k) = F(phi1, k) + lambda s``, ``cos((psi - theta)/2) = k sin(phi)`` and::

        x = -(cos psi (2 dE - dF) + 2 k sin psi dC) / lambda
        y = -(sin psi (2 dE - dF) - 2 k cos psi dC) / lambda

    where ``dE = E(phi, k) - E(phi1, k)``, ``dF`` likewise and ``dC = cos(phi) - cos(phi1)``;
    ``m = 2 EI k lambda cos(phi)``. Conventions and ranges: see the module docstring.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m).
    psi, k_rel : array_like
        Force direction (rad, in ``(0, 2 pi)``) and relative modulus (``0 < |k_rel| < 1``),
        broadcast together.
    mode : int or array_like of int, optional
        Buckling mode, ``>= 1``.
    nodes : int, optional
        If given, also sample the shape at this many equally spaced nodes.

    Returns
    -------
    EllipticRod

    Raises
    ------
    ValueError
        If an input is outside its range.

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, np.pi, 1e-6)   # compression at the Euler load
    >>> round(float(rod.R / (np.pi ** 2 / 4)), 9)
    1.0
    """
    EI, L = _positive("EI", EI), _positive("L", L)
    k, k_min = elliptic_k(psi, k_rel)
    psi = np.asarray(psi, dtype=float)
    # phi1 = arcsin(cos(psi/2) / k), the study's (89), written as an arctan2 of
    # sin(phi1) |k| and cos(phi1) |k| = sqrt((|k| - k_min)(|k| + k_min)), with
    # |k| - k_min = (1 - k_min) |k_rel| exactly: arcsin near 1 would lose half the digits.
    phi1 = np.arctan2(np.cos(0.5 * psi) * np.sign(k),
                      np.sqrt(_one_minus_k_min(psi) * np.abs(k_rel) * (np.abs(k) + k_min)))
    phi2 = (_mode(mode) - 0.5) * np.pi
    m = k * k
    F1, E1 = ellipkinc(phi1, m), ellipeinc(phi1, m)
    lam = (ellipkinc(phi2, m) - F1) / L
    R = EI * lam ** 2

    x2, y2, theta2, _ = _shape(phi2, psi, k, phi1, F1, E1, lam, EI)
    force = np.stack(np.broadcast_arrays(R * np.cos(psi), R * np.sin(psi)), axis=-1)
    rod = None
    if nodes is not None:
        s = np.linspace(0.0, 1.0, int(nodes)) * np.asarray(L)[..., None]
        phi = ellipj(F1[..., None] + lam[..., None] * s, m[..., None])[3]
        xs, ys, ts, ms = _shape(phi, *(np.asarray(a)[..., None]
                                       for a in (psi, k, phi1, F1, E1, lam, EI)))
        rod = Rod(np.broadcast_to(s, xs.shape), xs, ys, ts, ms, force)
    return EllipticRod(k, k_min, phi1, phi2, R, force, np.stack((x2, y2), axis=-1), theta2,
                       2 * EI * k * lam * np.cos(phi1), rod)


def _dF_dk(phi, k):
    """Partial derivative of ``F(phi, k)`` in the modulus ``k`` (DLMF 19.4; tested by FD)."""
    m, kc2 = k * k, 1.0 - k * k
    delta = np.sqrt(1.0 - m * np.sin(phi) ** 2)
    return ((ellipeinc(phi, m) - kc2 * ellipkinc(phi, m)) / (k * kc2)
            - k * np.sin(phi) * np.cos(phi) / (kc2 * delta))


def k_rel_for_force(EI, L, psi, R, mode=1, *, tol=1e-14, maxiter=100):
    """The relative modulus whose clamped-pinned rod carries the tip force ``R`` at ``psi``.

    For a given ``psi`` and ``mode``, ``R`` grows strictly with ``|k|`` on the half of
    ``k_rel`` whose sign is that of ``cos(psi/2)`` (the branch that grows from the straight rod:
    bending towards the force), from ``R_0 = EI (2 (mode - 1) K(k_min) / L)**2`` to infinity.
    This function solves ``lambda L = F(phi2, k) - F(phi1, k)`` on that half (for ``psi = pi``,
    ``k_rel > 0``) by Newton's method safeguarded with bisection, in the variable
    ``w = sqrt(k**2 - k_min**2)`` in which the equation is smooth. On the other half ``R``
    is not monotone and one force has several ``k_rel`` (the study's Ilustracion 10).

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m).
    psi : array_like
        Force direction in the local frame, in ``(0, 2 pi)`` (rad).
    R : array_like
        Force magnitude (N), positive.
    mode : int, optional
        Buckling mode.
    tol, maxiter
        Relative tolerance on ``lambda L = L sqrt(R / EI)`` and most iterations (an iteration
        that cannot move ``w`` by more than rounding also stops).

    Returns
    -------
    ndarray
        ``k_rel``, broadcast shape of the inputs.

    Raises
    ------
    ValueError
        If an input is out of range or ``R <= 0``.
    NoEquilibriumError
        If ``R <= R_0`` (a mode above the first needs a least load).
    ConvergenceError
        If ``maxiter`` iterations do not reach ``tol``.

    Examples
    --------
    >>> kr = k_rel_for_force(1.0, 1.0, np.pi / 2, 1.0)    # a transverse unit force
    >>> rod = clamped_pinned(1.0, 1.0, np.pi / 2, kr)
    >>> round(float(rod.R), 12), np.round(rod.tip, 5).tolist()
    (1.0, [0.94357, 0.30172])
    """
    EI, L, R = _positive("EI", EI), _positive("L", L), _positive("R", R)
    psi = _finite("psi", psi)
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError(f"psi must lie in the open interval (0, 2 pi), got {psi!r}")
    phi2 = (_mode(mode) - 0.5) * np.pi
    k_min = np.abs(np.cos(0.5 * psi))
    target = L * np.sqrt(R / EI)
    w_max = np.abs(np.sin(0.5 * psi))
    target, k_min, w_max, phi2 = np.broadcast_arrays(target, k_min, w_max, phi2)
    low_end = np.where(k_min > 0, ellipkinc(phi2, k_min ** 2) - ellipkinc(0.5 * np.pi, k_min ** 2),
                       phi2)
    if np.any(target <= low_end):
        raise NoEquilibriumError(
            f"mode {mode} needs R > {float(np.max(EI * (low_end / L) ** 2)):.6g} N at "
            f"psi = {psi!r}, got R = {R!r}")
    lo, hi = np.zeros_like(target), w_max.copy()
    # start from the small-load limit g ~ w / (k_min sqrt(1 - k_min^2)), kept inside (lo, hi)
    w = np.clip(target * k_min * w_max, 0.01 * hi, 0.99 * hi)
    for _ in range(maxiter):
        k = np.sqrt(k_min ** 2 + w ** 2)
        phi1 = np.arctan2(k_min, w)
        g = ellipkinc(phi2, k * k) - ellipkinc(phi1, k * k) - target
        lo, hi = np.where(g < 0, w, lo), np.where(g < 0, hi, w)
        dg = ((_dF_dk(phi2, k) - _dF_dk(phi1, k)) * w / k
              + k_min / (k * k * np.sqrt(1.0 - (k * np.sin(phi1)) ** 2)))
        step = w - g / dg
        bad = ~((step > lo) & (step < hi))
        new = np.where(bad, 0.5 * (lo + hi), step)
        done = (np.abs(g) <= tol * target) | (np.abs(new - w) <= 4.5e-16 * w)
        w = np.where(done, w, new)
        if np.all(done):
            break
    else:
        raise ConvergenceError(f"k_rel_for_force: no convergence in {maxiter} iterations")
    k = np.sqrt(k_min ** 2 + w ** 2)
    sign = np.where(np.cos(0.5 * psi) < 0, -1.0, 1.0)
    return sign * w ** 2 / ((k + k_min) * _one_minus_k_min(psi))


def elliptic_parameters(EI, L, clamp_moment, force):
    """``(psi, k_rel, mode)`` of a clamped-pinned rod known by its clamp moment and tip force.

    The inverse of :func:`clamped_pinned`, for identifying a rod found by shooting (local
    frame, ``theta(0) = 0``): ``psi`` is the direction of ``force`` in ``[0, 2 pi)``,
    ``k sin(phi1) = cos(psi/2)`` and ``k cos(phi1) = m(0) / (2 EI lambda)`` (the study's (37)
    and (42) at ``s = 0``), and the mode is fixed by the tip amplitude
    ``phi2 = am(F(phi1, k) + lambda L)``, an odd multiple of ``pi/2``.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    clamp_moment : array_like
        ``m(0)`` (N m).
    force : array_like, shape (..., 2)
        The tip force (N), not zero.

    Returns
    -------
    psi, k_rel, mode, phi2 : ndarray
        ``phi2`` unrounded: ``(mode - 1/2) pi`` up to the accuracy of the inputs.

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, 2.0, -0.4, mode=2)
    >>> psi, k_rel, mode, _ = elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    >>> round(float(psi), 12), round(float(k_rel), 12), int(mode)
    (2.0, -0.4, 2)
    """
    force, m0 = _finite("force", force, 2), _finite("clamp_moment", clamp_moment)
    R = np.hypot(force[..., 0], force[..., 1])
    if np.any(R == 0):
        raise ValueError("the tip force must not be zero: an unloaded rod has no k")
    psi = np.mod(np.arctan2(force[..., 1], force[..., 0]), TWO_PI)
    if np.any(psi == 0):
        raise ValueError("a tip force along the clamped tangent (psi = 0, pure tension) has "
                         "no elliptic parameters: its rod is straight")
    lam = np.sqrt(R / EI)
    a, b = np.cos(0.5 * psi), m0 / (2.0 * EI * lam)
    k = np.where(b < 0, -1.0, 1.0) * np.hypot(a, b)
    k_min = np.abs(a)
    phi1 = np.arctan2(a * np.sign(k), np.abs(b))
    phi2 = ellipj(ellipkinc(phi1, k * k) + lam * L, k * k)[3]
    mode = np.round(phi2 / np.pi + 0.5)
    return psi, np.sign(k) * (np.abs(k) - k_min) / _one_minus_k_min(psi), mode, phi2


def pinned_equilibria(EI, L, tip, modes=(1, 2, 3), *, n_psi=120, n_k=80, tol=1e-13):
    """Every clamped-pinned equilibrium whose tip is at ``tip``, by the closed form.

    As the study does for its mechanisms, the admissible rectangle ``0 < psi < 2 pi``,
    ``0 < |k_rel| < 1`` of each mode is sampled on a grid (finer near ``k_rel = 0, +-1``); the
    local minima of the tip distance seed Newton's method (:func:`mechnum.newton.solve`) on
    ``tip(psi, k_rel) = target``, in variables that keep ``k_rel`` in its half-interval. A
    grid can miss a solution in a cell smaller than its spacing; refine it to check.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m).
    tip : array_like, shape (2,)
        The pinned point in the local frame (m), within ``L`` of the clamp.
    modes : iterable of int, optional
        Buckling modes searched.
    n_psi, n_k : int, optional
        Grid size per mode (``n_k`` values of ``|k_rel|`` on each sign).
    tol : float, optional
        Newton step tolerance.

    Returns
    -------
    ndarray, shape (n, 3)
        Rows ``(psi, k_rel, mode)``, sorted by mode then ``R``; ``n >= 0``.

    Examples
    --------
    >>> sols = pinned_equilibria(1.0, 1.0, [0.8, 0.1], modes=(1, 2))   # none in mode 1
    >>> sols.shape, np.round(sols[:, :2], 4).tolist()
    ((2, 3), [[3.4872, -0.3223], [3.0352, 0.4212]])
    """
    tip = _finite("tip", tip, 2)
    if tip.shape != (2,) or np.hypot(*tip) >= L:
        raise ValueError(f"tip must be one point closer than L = {L} to the clamp, got {tip!r}")
    u = (np.arange(n_k) + 0.5) / n_k
    half = 0.5 * (1 - np.cos(np.pi * u))
    k_grid = np.concatenate((-half[::-1], half))
    psi_grid = (np.arange(n_psi) + 0.5) / n_psi * TWO_PI
    found = []
    for mode in modes:
        P, K = np.meshgrid(psi_grid, k_grid, indexing="ij")
        dist = np.linalg.norm(clamped_pinned(EI, L, P, K, mode).tip - tip, axis=-1)
        padded = np.pad(dist, 1, constant_values=np.inf)
        neighbours = np.stack([padded[1 + i:1 + i + n_psi, 1 + j:1 + j + 2 * n_k]
                               for i in (-1, 0, 1) for j in (-1, 0, 1) if i or j])
        for i, j in zip(*np.nonzero(dist <= neighbours.min(axis=0))):
            sign = np.sign(K[i, j])

            def unpack(z, sign=sign):   # psi free (wrapped), |k_rel| = logistic(z[1])
                return np.mod(z[0], TWO_PI), sign * expit(np.clip(z[1], -25.0, 25.0))

            def fun(z, mode=mode, unpack=unpack):
                return clamped_pinned(EI, L, *unpack(z), mode).tip - tip

            z0 = [P[i, j], np.log(abs(K[i, j]) / (1 - abs(K[i, j])))]
            try:
                z = newton.solve(fun, z0, tol=tol, maxiter=60).x
            except (MechnumError, ValueError):
                continue
            if np.linalg.norm(fun(z)) < 1e-10 * L:
                found.append((*unpack(z), mode))
    if not found:
        return np.empty((0, 3))
    sols = np.unique(np.round(np.array(found, dtype=float), 9), axis=0)
    R = clamped_pinned(EI, L, sols[:, 0], sols[:, 1], sols[:, 2]).R
    return sols[np.lexsort((R, sols[:, 2]))]
