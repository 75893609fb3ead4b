"""Rods known by their clamp states: their chart (:func:`chart_from_clamps`) and the largest
bending moment along them (:func:`peak_moment`), exactly."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods import _regular as regular
from mechnum.rods._elliptic import elliptic_parameters


def _clamp_states(clamp_angle, clamp_moment, force):
    """The clamp states of rods, checked (finite; ``force`` with a last axis of 2, one per rod:
    the angles and moments broadcast to its rods) and broadcast together."""
    angle, m0 = _validate.array(clamp_angle, "clamp_angle"), _validate.array(clamp_moment,
                                                                            "clamp_moment")
    n = _validate.array(force, "force")
    if n.shape[-1:] != (2,):
        raise ValueError(f"force must have a last axis of 2, got shape {n.shape}")
    shape = _validate.broadcast(clamp_angle=angle, clamp_moment=m0, force=n[..., 0])
    if shape != n.shape[:-1]:
        raise ValueError(f"clamp_angle {angle.shape} and clamp_moment {m0.shape} must "
                         f"broadcast to the rods of force {n.shape}")
    return (np.broadcast_to(angle, shape), np.broadcast_to(m0, shape),
            np.broadcast_to(n, shape + (2,)))


def chart_from_clamps(EI: float, L: float, clamp_angle: ArrayLike, clamp_moment: ArrayLike,
                      force: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
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
        clamp state (a rod straight to rounding, or in tension beyond the chart), or whose
        force lies along its clamped tangent to rounding (``psi`` 0 or ``2 pi``, the chart's
        edge).
    modes : ndarray of int, shape (..., r)
        0 where the clamp state gives none (a rod straight to rounding).

    Examples
    --------
    A straight rod pulled along its tangent, its clamp moment and the force's normal
    component round-off: ``psi`` rounds to ``2 pi``, and the rod has no chart.

    >>> chart, modes = chart_from_clamps(1.0, 1.0, [0.0], [-2.5e-17], [[0.2, -5.1e-17]])
    >>> bool(chart[0] == 2 * np.pi), bool(np.isnan(chart[1]))
    (True, True)
    """
    EI, L = _validate.numbers(dict(EI=EI, L=L), positive=("EI", "L"))
    clamp_angle, clamp_moment, force = _clamp_states(clamp_angle, clamp_moment, force)
    c, s = np.cos(clamp_angle), np.sin(clamp_angle)
    local = np.stack((c * force[..., 0] + s * force[..., 1],
                      -s * force[..., 0] + c * force[..., 1]), axis=-1)
    psi, k_rel, modes, _ = elliptic_parameters(EI, L, clamp_moment, local, outside="nan")
    # a rod straight to rounding, or on the chart's edge psi = 0 (2 pi), has no chart
    inside = (k_rel != 0) & (np.abs(k_rel) < 1) & (psi > 0) & (psi < regular.TWO_PI)
    chart = np.full(psi.shape[:-1] + (2 * psi.shape[-1],), np.nan)
    chart[..., 0::2] = psi
    chart[..., 1::2][inside] = regular.t_from_k_rel(psi[inside], k_rel[inside])
    return chart, np.where(np.isnan(modes), 0, modes).astype(int)


def peak_moment(EI: float, clamp_moment: ArrayLike, force: ArrayLike, clamp_angle: ArrayLike,
                modes: ArrayLike) -> np.ndarray:
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

    >>> from mechnum.rods import shape
    >>> rod = shape(1.0, 1.0, 2.0, -0.6, 2, nodes=20001)
    >>> peak = peak_moment(1.0, rod.m[0], rod.force, 0.0, 2)
    >>> bool(abs(peak - np.abs(rod.m).max()) < 1e-6), bool(peak > abs(rod.m[0]))
    (True, True)
    """
    (EI,) = _validate.numbers(dict(EI=EI), positive=("EI",))
    clamp_angle, m0, n = _clamp_states(clamp_angle, clamp_moment, force)
    modes = _validate.array(modes, "modes")
    _validate.broadcast(clamp_moment=m0, modes=modes)
    c, s = np.cos(clamp_angle), np.sin(clamp_angle)
    along = c * n[..., 0] + s * n[..., 1]                        # n . t(0)
    across = c * n[..., 1] - s * n[..., 0]                       # t(0) x n
    crest = np.sqrt(np.maximum(m0 ** 2 + 2 * EI * (along + np.hypot(n[..., 0], n[..., 1])),
                               0.0))
    passed = (modes >= 2) | (m0 * across < 0)
    return np.where(passed, np.maximum(crest, np.abs(m0)), np.abs(m0))
