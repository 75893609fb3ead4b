"""Where the mechanism is singular: the Jacobians of the direct and the inverse problem.

:func:`~mechnum.mechanisms.rfr2.jacobians` gives, at equilibria, the determinants of the
Jacobians of the dimensionless residual ``G`` with respect to the unknowns of each problem,
whose zeros are the singularities, and how the end effector moves with the motors.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.rfr2.model import _modes, _rods

_FK = [0, 1, 2, 3, 6, 7]       # unknowns of the direct problem: the chart and P
_IK = [0, 1, 2, 3, 4, 5]       # of the inverse problem: the chart and theta


def _full(mech, modes, z, theta, P):
    """``G = ((tip1 - P) / L, (tip2 - P) / L, (n1 + n2 - F) L**2 / EI)`` (..., 6) and its
    Jacobian (..., 6, 8) with respect to ``(psi1, t1, psi2, t2, theta1, theta2, x_P, y_P)``."""
    tip, force, _, d_chart, d_angle = _rods(mech, modes, z, theta)
    L, f = mech.L, mech.EI / mech.L ** 2
    G = np.concatenate(((tip[..., 0, :] - P) / L, (tip[..., 1, :] - P) / L,
                        (force.sum(axis=-2) - mech.force) / f), axis=-1)
    D = np.zeros(G.shape + (8,))
    for r in range(2):
        rows = slice(2 * r, 2 * r + 2)
        D[..., rows, 2 * r:2 * r + 2] = d_chart[..., r, :2, :] / L
        D[..., 4:6, 2 * r:2 * r + 2] = d_chart[..., r, 2:, :] / f
        D[..., rows, 4 + r] = d_angle[..., r, :2] / L
        D[..., 4:6, 4 + r] = d_angle[..., r, 2:] / f
        D[..., rows, 6:8] = -np.eye(2) / L
    return G, D


@dataclass(frozen=True)
class Jacobians:
    """The Jacobians of equilibria (:func:`jacobians`).

    Attributes
    ----------
    det_fk : ndarray
        ``det dG / d(chart, P)``: zero where the direct problem is singular (the motors
        locked, ``P`` can still move: the mechanism gains a freedom).
    det_ik : ndarray
        ``det dG / d(chart, theta)``: zero where the inverse problem is singular (``P`` cannot
        move in some direction, whatever the motors do: the edge of the workspace).
    dP_dtheta : ndarray, shape (..., 2, 2)
        How ``P`` moves with the motors (m/rad): the study's code's ``FK_Jacobian``. Its
        determinant is ``L**2 det_ik / det_fk``, and the code's ``IK_Jacobian`` is its inverse.
    """

    det_fk: np.ndarray
    det_ik: np.ndarray
    dP_dtheta: np.ndarray


def jacobians(mech, theta, chart, modes=(1, 1)):
    """Determinants of the direct and inverse problems of equilibria, and ``dP / dtheta``.

    ``G`` is the dimensionless residual (tips to ``P`` over ``L``, forces over
    ``EI / L**2``); the determinants are those of its Jacobian with respect to the unknowns
    of each problem (the chart of the rods and ``P``, or the chart and ``theta``), whose
    zeros do not depend on how the rods are parametrised (the study's 8 x 8 shooting
    Jacobians of (98) vanish at the same places).

    Examples
    --------
    >>> from mechnum.mechanisms.rfr2 import TABLE7, TABLE7_THETA, forward_elliptic
    >>> eq = forward_elliptic(TABLE7, TABLE7_THETA, rng=0)
    >>> J = jacobians(TABLE7, TABLE7_THETA, eq.chart)
    >>> ratio = np.linalg.det(J.dP_dtheta) * J.det_fk / (TABLE7.L ** 2 * J.det_ik)
    >>> bool(np.allclose(ratio, 1.0)), np.sign(J.det_fk).tolist()
    (True, [-1.0, 1.0, -1.0])
    """
    z = _validate.array(chart, "chart")
    theta = _validate.array(theta, "theta")
    tip = _rods(mech, _modes(modes), z, theta)[0]
    _, D = _full(mech, _modes(modes), z, theta, tip[..., 0, :])
    A, B = D[..., _FK], D[..., _IK]
    dP = -np.linalg.solve(A, D[..., 4:6])[..., 4:6, :]
    return Jacobians(np.linalg.det(A), np.linalg.det(B), dP * mech.L)
