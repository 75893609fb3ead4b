"""Where the mechanism is singular: the Jacobians of the direct and the inverse problem.

:func:`~mechnum.mechanisms.rfr2.jacobians` gives, at equilibria, the determinants of the
Jacobians of the dimensionless residual ``G`` (:func:`~mechnum.mechanisms.rfr2.full_system`)
with respect to the unknowns of each problem, whose zeros are the singularities, and how the end
effector moves with the motors; :func:`~mechnum.mechanisms.rfr2.singular_points` finds where a
determinant changes sign over a map.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum.mechanisms.rfr2.model import LAYOUT, Mechanism, full_system, rods
from mechnum.rods import assembly


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
        determinant is ``det_ik / det_fk``, and the code's ``IK_Jacobian`` is its inverse.
    """

    det_fk: np.ndarray
    det_ik: np.ndarray
    dP_dtheta: np.ndarray


def jacobians(mech: Mechanism, theta: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1)) -> Jacobians:
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
    >>> ratio = np.linalg.det(J.dP_dtheta) * J.det_fk / J.det_ik
    >>> bool(np.allclose(ratio, 1.0)), np.sign(J.det_fk).tolist()
    (True, [-1.0, 1.0, -1.0])
    """
    assembly.check_type(mech, Mechanism)
    tip = rods(mech, theta, chart, modes, jacobian=False)[0]
    D = full_system(mech, modes)(chart, theta, tip[..., 0, :])[1]
    return Jacobians(*assembly.determinants(D, LAYOUT))
