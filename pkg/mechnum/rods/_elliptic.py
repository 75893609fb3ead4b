"""The closed form of a clamped-pinned rod in the study's chart ``(psi, k_rel)`` (conventions:
:mod:`mechnum.rods`).

The study parametrises a rod of a given ``mode`` by the direction ``psi`` of its tip force and
the relative modulus ``k_rel`` (its (89) to (91)). This module keeps that chart for the reader,
and evaluates it through the regular chart of ``rods``'s regular module, which holds every
digit where the study's formulas do not (``k_rel -> 0``, ``|k_rel| -> 1``, ``psi = pi``):
:func:`clamped_pinned` converts ``k_rel`` to the chart's ``t`` exactly
(:func:`mechnum.rods.t_from_k_rel`). Its inverses: :func:`k_rel_for_force` (the
growing branch that carries a force, in the chart of ``rods``'s growing module) and
:func:`elliptic_parameters` (the rod that starts from a clamp moment and a force).
"""

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import elliprf

from mechnum import _validate
from mechnum.errors import MechnumError
from mechnum.rods import _profile as profile
from mechnum.rods import _regular as regular
from mechnum.rods._growing import growing_branch
from mechnum.rods._jacobi import amplitude
from mechnum.rods._rod import MAX_NODES, Rod, as_modes, as_vectors, batch_shape, rod_scales

TWO_PI = 2.0 * np.pi
_EPS = np.finfo(float).eps
_TINY = np.finfo(float).tiny
AXIAL = 4.0 * _EPS
"""A force whose ``|cos(psi/2)|`` is below this is axial: ``psi = numpy.pi`` (which is ``pi`` to
rounding, ``cos(psi/2) = 6e-17``) is pure compression, with the Euler load as least load."""


class NoEquilibriumError(MechnumError):
    """A rod has no equilibrium on the requested branch (a load below a mode's range)."""


class NotAnElasticaError(MechnumError, ValueError):
    """A clamp moment and a force that start no clamped-pinned rod: the moment never vanishes
    along the rod (``|k| >= 1``, the rod curls in whole turns), so no tip can be pinned."""


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


def elliptic_k(psi: ArrayLike, k_rel: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
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
    psi, k_rel = _angles(psi), _validate.array(k_rel, "k_rel")
    _validate.broadcast(psi=psi, k_rel=k_rel)
    if np.any((k_rel == 0) | (np.abs(k_rel) >= 1)):
        raise ValueError(f"k_rel must satisfy 0 < |k_rel| < 1, got {_validate.shown(k_rel)}")
    k_min = np.abs(np.cos(0.5 * psi))
    return np.sign(k_rel) * k_min + _one_minus_k_min(psi) * k_rel, k_min


def _one_minus_k_min(psi):
    """``1 - |cos(psi/2)|`` without cancellation (``sin(psi/2)**2 / (1 + |cos(psi/2)|)``)."""
    return np.sin(0.5 * psi) ** 2 / (1.0 + np.abs(np.cos(0.5 * psi)))


def _angles(psi):
    """``psi`` as a float array, checked to lie in the open interval ``(0, 2 pi)``."""
    psi = _validate.array(psi, "psi")
    if np.any((psi <= 0) | (psi >= TWO_PI)):
        raise ValueError("psi must lie in the open interval (0, 2 pi), "
                         f"got {_validate.shown(psi)}")
    return psi


def clamped_pinned(EI: ArrayLike, L: ArrayLike, psi: ArrayLike, k_rel: ArrayLike,
                   mode: ArrayLike = 1, *, nodes: int | None = None) -> EllipticRod:
    """The clamped-pinned (or end-loaded cantilever) rod in closed form.

    With ``lambda = sqrt(R / EI)``: ``lambda L = F(phi2, k) - F(phi1, k)`` gives ``R``; along the
    rod ``F(phi, k) = F(phi1, k) + lambda s``, ``cos((psi - theta)/2) = k sin(phi)`` and::

        x = -(cos psi (2 dE - dF) + 2 k sin psi dC) / lambda
        y = -(sin psi (2 dE - dF) - 2 k cos psi dC) / lambda

    where ``dE = E(phi, k) - E(phi1, k)``, ``dF`` likewise and ``dC = cos(phi) - cos(phi1)``;
    ``m = 2 EI k lambda cos(phi)``. Conventions and ranges: see :mod:`mechnum.rods`. These
    formulas are evaluated in the regular chart (``closed_form`` and
    :func:`mechnum.rods.shape`), which holds every digit at every admissible
    ``(psi, k_rel)``, ``|k_rel|`` within an ulp of 1 and ``psi = pi`` included.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    psi, k_rel : array_like
        Force direction (rad, in ``(0, 2 pi)``) and relative modulus (``0 < |k_rel| < 1``).
    mode : int or array_like of int, optional
        Buckling mode, ``>= 1``.
    nodes : int, optional
        If given (``2 <= nodes <=`` ``MAX_NODES = 100_000``), also sample the shape
        at this many equally spaced nodes.

    Returns
    -------
    EllipticRod
        Arrays of the broadcast shape of ``EI``, ``L``, ``psi``, ``k_rel`` and ``mode``.

    Raises
    ------
    ValueError
        If an input is outside its range, or the shapes do not broadcast.

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, np.pi, 1e-6)   # compression at the Euler load
    >>> round(float(rod.R / (np.pi ** 2 / 4)), 9)
    1.0
    >>> bool(np.isfinite(clamped_pinned(1.0, 1.0, 2.0, 1 - 1e-16).tip).all())
    True
    """
    (EI, L), mode = rod_scales(EI, L), as_modes(mode)
    psi, k_rel = _validate.array(psi, "psi"), _validate.array(k_rel, "k_rel")
    batch_shape(EI=EI.shape, L=L.shape, psi=psi.shape, k_rel=k_rel.shape, mode=mode.shape)
    k, k_min = elliptic_k(psi, k_rel)
    if nodes is not None:
        nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    one_minus_kmin = _one_minus_k_min(psi)
    # phi1 = arcsin(cos(psi/2) / k), the study's (89), written as an arctan2 of
    # sin(phi1) |k| and cos(phi1) |k| = sqrt((|k| - k_min)(|k| + k_min)), with
    # |k| - k_min = (1 - k_min) |k_rel| exactly: arcsin near 1 would lose half the digits.
    phi1 = np.arctan2(np.cos(0.5 * psi) * np.sign(k),
                      np.sqrt(one_minus_kmin * np.abs(k_rel) * (np.abs(k) + k_min)))
    phi2 = (mode - 0.5) * np.pi
    t = regular.t_from_k_rel(psi, k_rel)
    end = regular.closed_form(EI, L, psi, t, mode, jacobian=False)
    # theta(L) = psi - 2 arccos(k sin(phi2)) = psi - 2 atan2(k', k sin(phi2)), with
    # k'**2 = 1 - k**2 = (1 - k_min)(1 - |k_rel|)(1 + |k|) exactly
    complement = np.sqrt(one_minus_kmin * (1.0 - np.abs(k_rel)) * (1.0 + np.abs(k)))
    tip_angle = psi - 2.0 * np.arctan2(complement, k * np.sin(phi2))
    R = np.hypot(end.force[..., 0], end.force[..., 1])
    rod = None if nodes is None else profile.shape(EI, L, psi, t, mode, nodes=nodes)
    return EllipticRod(k, k_min, phi1, phi2, R, end.force, end.tip, tip_angle,
                       end.clamp_moment, rod)


def k_rel_for_force(EI: ArrayLike, L: ArrayLike, psi: ArrayLike, R: ArrayLike,
                    mode: ArrayLike = 1, *, tol: float = 1e-14,
                    maxiter: int = 100) -> np.ndarray:
    """The relative modulus whose clamped-pinned rod carries the tip force ``R`` at ``psi``.

    For a given ``psi`` and ``mode``, ``R`` grows strictly with ``|k|`` on the half of
    ``k_rel`` whose sign is that of ``cos(psi/2)`` (the branch that grows from the straight rod:
    bending towards the force), from ``R_0 = EI (2 (mode - 1) K(k_min) / L)**2`` to infinity
    (plus the Euler load ``pi**2 EI / (4 L**2)`` where the force is axial: ``psi = pi`` to
    rounding, see :data:`AXIAL`). This function solves ``lambda L = F(phi2, k) - F(phi1, k)``
    on that half (for ``psi = pi``, ``k_rel > 0``) by Newton's method safeguarded with
    bisection, in a variable ``zeta`` in which the equation is smooth and well conditioned at
    every load (``growing_branch``), and checks its residual. On
    the other half ``R`` is not monotone and one force has several ``k_rel`` (the study's
    Ilustracion 10).

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m).
    psi : array_like
        Force direction in the local frame, in ``(0, 2 pi)`` (rad).
    R : array_like
        Force magnitude (N), positive.
    mode : int or array_like of int, optional
        Buckling mode.
    tol, maxiter
        Relative tolerance on ``lambda L = L sqrt(R / EI)`` (or the rounding floor of the
        solution, if larger) and most iterations per element (at most 10000).

    Returns
    -------
    ndarray
        ``k_rel``, broadcast shape of the inputs.

    Raises
    ------
    ValueError
        If an input is out of range, or ``R`` is so large (or so small) that ``k_rel`` rounds
        to ``+-1`` (or underflows): the chart ``k_rel`` cannot hold that rod in double
        precision (:func:`mechnum.rods.cantilever` can).
    NoEquilibriumError
        If ``R <= R_0`` (a mode above the first needs a least load, and an axial force the
        Euler load).
    ConvergenceError
        If ``maxiter`` iterations do not reach ``tol``.

    Examples
    --------
    >>> kr = k_rel_for_force(1.0, 1.0, np.pi / 2, 1.0)    # a transverse unit force
    >>> rod = clamped_pinned(1.0, 1.0, np.pi / 2, kr)
    >>> round(float(rod.R), 12), np.round(rod.tip, 5).tolist()
    (1.0, [0.94357, 0.30172])
    """
    (EI, L), R = rod_scales(EI, L), _validate.positive(R, "R")
    psi, mode = _angles(psi), as_modes(mode)
    tol = _validate.tolerance(tol)
    maxiter = _validate.maxiter(maxiter, maximum=10_000)
    batch_shape(EI=EI.shape, L=L.shape, R=R.shape, psi=psi.shape, mode=mode.shape)
    EI, L, R, psi, mode = np.broadcast_arrays(EI, L, R, psi, mode)
    k_rel = np.empty(psi.shape)
    for i in np.ndindex(psi.shape):
        a, b = math.cos(0.5 * psi[i]), math.sin(0.5 * psi[i])
        target = L[i] * math.sqrt(R[i] / EI[i])
        # lambda L at zeta = 0: the whole half-waves, and the Euler load in pure compression
        low = 2.0 * (mode[i] - 1) * float(elliprf(0.0, b * b, 1.0)) + (
            0.5 * math.pi if abs(a) < AXIAL else 0.0)
        if target <= low:
            raise NoEquilibriumError(
                f"mode {mode[i]:.0f} needs R > {EI[i] * (low / L[i]) ** 2:.6g} N at "
                f"psi = {psi[i]:.6g}, got R = {R[i]:.6g}")
        v, _, k = growing_branch(a, b, target, int(mode[i]), tol=tol, maxiter=maxiter)
        k_rel[i] = (1.0 if a >= 0 else -1.0) * v * v * (1.0 + abs(a)) / (k + abs(a))
        if not _TINY <= abs(k_rel[i]) < 1.0:
            raise ValueError(
                f"R L^2/EI = {target ** 2:.6g} at psi = {psi[i]:.6g}: k_rel = {k_rel[i]:.17g} "
                f"is not representable in double precision (it rounds to +-1 or underflows); "
                f"use rods.cantilever or rods.shoot_cantilever for this rod")
    return k_rel


def elliptic_parameters(EI: ArrayLike, L: ArrayLike, clamp_moment: ArrayLike,
                        force: ArrayLike, *, outside: str = "raise") -> tuple[np.ndarray, ...]:
    """``(psi, k_rel, mode, phi2)`` of the rod that starts from a clamp moment and a tip force.

    The inverse of :func:`clamped_pinned`, for identifying a rod found by shooting (local
    frame, ``theta(0) = 0``): ``psi`` is the direction of ``force`` in ``(0, 2 pi)``,
    ``k sin(phi1) = cos(psi/2)`` and ``k cos(phi1) = m(0) / (2 EI lambda)`` (the study's (37)
    and (42) at ``s = 0``). The count of quarter periods ``q = (F(phi1, k) + lambda L) / K(k)``
    is ``2 mode - 1`` where ``m(L) = 0``, and the tip amplitude ``phi2 = am(F(phi1, k) +
    lambda L)`` is then ``(mode - 1/2) pi``. Everything is computed from the complementary
    modulus ``k'**2 = 1 - k**2 = sin(psi/2)**2 (1 - v**2)``, ``v = k cos(phi1) / sin(psi/2)``
    (Carlson's integrals; ``amplitude``), so that a rod within
    ``1e-12`` of ``|k| = 1`` keeps its mode. ``mode`` rounds ``q`` (it is 0 for a rod whose
    moment has not vanished by ``s = L``); ``phi2`` is unrounded.

    Parameters
    ----------
    EI, L : float or array_like
        Bending stiffness (N m^2) and length (m), positive.
    clamp_moment : array_like
        ``m(0)`` (N m).
    force : array_like, shape (..., 2)
        The tip force (N), not zero and not along the clamped tangent.
    outside : {"raise", "nan"}, optional
        What a rod outside the family gets (its moment never vanishes): an error, or (for a
        batch whose caller masks such rods) NaN for its ``k_rel``, ``mode`` and ``phi2``.

    Returns
    -------
    psi, k_rel, mode, phi2 : ndarray

    Raises
    ------
    ValueError
        If an input is malformed, the force is zero, or it points along the clamped tangent
        (pure tension: the chart has no rod there).
    NotAnElasticaError
        If the moment never vanishes along the rod (``|k| >= 1``) and ``outside="raise"``: no
        clamped-pinned rod, of any length, starts so (for a rod found by shooting: a spurious
        solution of the discrete equations).

    Examples
    --------
    >>> rod = clamped_pinned(1.0, 1.0, 2.0, -0.4, mode=2)
    >>> psi, k_rel, mode, _ = elliptic_parameters(1.0, 1.0, rod.clamp_moment, rod.force)
    >>> round(float(psi), 12), round(float(k_rel), 12), int(mode)
    (2.0, -0.4, 2)
    """
    EI, L = rod_scales(EI, L)
    outside = _validate.choice(outside, ("raise", "nan"), "outside")
    force, m0 = as_vectors(force, "force", 2), _validate.array(clamp_moment, "clamp_moment")
    batch_shape(EI=EI.shape, L=L.shape, clamp_moment=m0.shape, force=force.shape[:-1])
    R = np.hypot(force[..., 0], force[..., 1])
    if np.any(R == 0):
        raise ValueError("the tip force must not be zero: an unloaded rod has no k")
    psi = np.mod(np.arctan2(force[..., 1], force[..., 0]), TWO_PI)
    if np.any(psi == 0):
        raise ValueError("a tip force along the clamped tangent (psi = 0, pure tension) has "
                         "no elliptic parameters: its rod is straight")
    lam = np.sqrt(R / EI)
    a, b = np.cos(0.5 * psi), np.sin(0.5 * psi)
    c = m0 / (2.0 * EI * lam)                          # k cos(phi1)
    v = np.abs(c) / b
    if outside == "nan":
        v = np.where(v < 1, v, np.nan)
    elif np.any(v >= 1):
        raise NotAnElasticaError(
            f"m(0) = {_validate.shown(m0)} and force {_validate.shown(force)} start no "
            f"clamped-pinned rod: |k| = sqrt(cos(psi/2)**2 + (m(0) / (2 EI lambda))**2) >= 1, "
            f"so the moment never vanishes along the rod")
    m = a * a + c * c                                  # k**2
    k = np.where(c < 0, -1.0, 1.0) * np.sqrt(m)
    p = b * b * (1.0 - v) * (1.0 + v)                  # 1 - k**2, without cancellation
    k_rel = np.sign(k) * v * v * (1.0 + np.abs(a)) / (np.abs(k) + np.abs(a))
    F1 = a * np.sign(k) / np.abs(k) * elliprf(c * c / m, b * b, 1.0)   # DLMF 19.25.5
    u = F1 + lam * L
    mode = np.round(0.5 * (u / elliprf(0.0, p, 1.0) + 1.0))
    inside = np.isfinite(v)
    phi2 = np.full(np.shape(u), np.nan)
    phi2[inside] = amplitude(np.broadcast_to(u, phi2.shape)[inside],
                             np.broadcast_to(np.sqrt(m), phi2.shape)[inside],
                             np.broadcast_to(np.sqrt(p), phi2.shape)[inside])
    return psi, k_rel, mode, phi2[()]
