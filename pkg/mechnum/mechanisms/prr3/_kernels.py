"""The 3PRR's formulas on checked input: the kernels that the public functions call.

Each function here takes a :class:`~mechnum.mechanisms.prr3.Geometry` and float arrays
of shape ``(..., 3)`` that the caller has checked (the functions of
``prr3``'s geometry module check, then call these), so that the forward solver and
the path search can call them many times without checking again. Nothing here validates its
input.

Examples
--------
>>> import numpy as np
>>> from mechnum.mechanisms.prr3 import Geometry
>>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
>>> loop_residuals(g, np.array([0.6, 0.4, 0.0]), np.array([0.6, 0.5, 0.25])).round(4).tolist()
[-0.84, -0.03, -0.6058]
"""

import math

import numpy as np

_ROOT3 = math.sqrt(3.0)


def vertices(mech, poses):
    """The platform vertices ``P1, P2, P3`` of poses ``(x, y, psi)``: shape ``(..., 3, 2)``."""
    x, y = poses[..., 0], poses[..., 1]
    c, s = mech.a * np.cos(poses[..., 2]), mech.a * np.sin(poses[..., 2])
    out = np.empty(poses.shape[:-1] + (3, 2))
    out[..., 0, 0], out[..., 0, 1] = x, y
    out[..., 1, 0], out[..., 1, 1] = x + c, y + s
    # (cos, sin)(psi + pi/3) by the rotation formulas: no second pair of trigonometric calls
    out[..., 2, 0], out[..., 2, 1] = x + (c - _ROOT3 * s) / 2, y + (s + _ROOT3 * c) / 2
    return out


def sliders(mech, lambdas):
    """The slider points ``C1, C2, C3`` of inputs ``lambdas``: shape ``(..., 3, 2)``."""
    out = np.zeros(lambdas.shape[:-1] + (3, 2))
    out[..., 0, 0] = lambdas[..., 0]
    out[..., 1, 0] = mech.B2 - lambdas[..., 1]
    out[..., 2, 0], out[..., 2, 1] = mech.B3, mech.H3 - lambdas[..., 2]
    return out


def bars(mech, poses, lambdas):
    """The bar vectors ``P_i - C_i``: shape ``(..., 3, 2)``."""
    return vertices(mech, poses) - sliders(mech, lambdas)


def loop_residuals(mech, poses, lambdas):
    """``|P_i - C_i|^2 - L^2`` (m^2), shape ``(..., 3)``; an overflow gives ``inf``."""
    with np.errstate(over="ignore", invalid="ignore"):
        return np.sum(bars(mech, poses, lambdas) ** 2, axis=-1) - mech.L ** 2


def radicands(mech, poses):
    """``L^2 - d_i^2`` of each leg (m^2), shape ``(..., 3)``; an overflow gives ``-inf``."""
    v = vertices(mech, poses)
    distance = np.stack([v[..., 0, 1], v[..., 1, 1], mech.B3 - v[..., 2, 0]], axis=-1)
    with np.errstate(over="ignore"):
        return (mech.L - distance) * (mech.L + distance)


def slider_points(mech, lambdas):
    """The slider points as complex numbers ``x + i y``: shape ``(..., 3)``."""
    out = np.empty(lambdas.shape[:-1] + (3,), dtype=complex)
    out[..., 0] = lambdas[..., 0]
    out[..., 1] = mech.B2 - lambdas[..., 1]
    out[..., 2] = mech.B3 + 1j * (mech.H3 - lambdas[..., 2])
    return out


def bars_and_jacobian(mech, poses, lambdas):
    """The bars (:func:`bars`) and the direct Jacobian (:func:`direct_jacobian`), at once."""
    v = vertices(mech, poses)
    u = v - sliders(mech, lambdas)
    lever = v - v[..., :1, :]  # P_i - P: its derivative with respect to psi is its normal
    dpsi = u[..., 1] * lever[..., 0] - u[..., 0] * lever[..., 1]
    return u, 2 * np.concatenate([u, dpsi[..., None]], axis=-1)


def direct_jacobian(mech, poses, lambdas):
    """Jacobian of :func:`loop_residuals` in the pose ``(x, y, psi)``: shape ``(..., 3, 3)``."""
    return bars_and_jacobian(mech, poses, lambdas)[1]


def dets_of(mech, bars, jacobian):
    """The dimensionless determinants ``(inverse, direct)`` from the bars and the Jacobian."""
    inverse = -bars[..., 0, 0] * bars[..., 1, 0] * bars[..., 2, 1] / mech.L ** 3
    direct = jacobian / (2 * mech.L)
    direct[..., 2] /= mech.a
    return inverse, np.linalg.det(direct)


def jacobian_dets(mech, poses, lambdas):
    """The dimensionless determinants ``(inverse, direct)``, each of shape ``(...)``."""
    return dets_of(mech, *bars_and_jacobian(mech, poses, lambdas))
