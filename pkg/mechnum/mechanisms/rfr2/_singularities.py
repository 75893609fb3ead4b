"""Where the mechanism is singular: the Jacobians of the direct and the inverse problem.

:func:`~mechnum.mechanisms.rfr2.jacobians` gives, at equilibria, the determinants of the
Jacobians of the dimensionless residual ``G`` (:func:`~mechnum.mechanisms.rfr2.full_system`)
with respect to the unknowns of each problem, whose zeros are the singularities, and how the end
effector moves with the motors; :func:`~mechnum.mechanisms.rfr2.singular_points` finds where a
determinant changes sign over a map.
"""

from __future__ import annotations

from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms import _assembly as assembly
from mechnum.mechanisms.rfr2._model import LAYOUT, Mechanism, full_system, rods


def jacobians(mech: Mechanism, theta: ArrayLike, chart: ArrayLike,
              modes: ArrayLike = (1, 1)) -> assembly.Jacobians:
    """Determinants of the direct and inverse problems of equilibria, and how the end
    effector moves with the motors (m/rad): the study's code's ``FK_Jacobian``.

    ``G`` is the dimensionless residual (tips to ``P`` over ``L``, forces over
    ``EI / L**2``); the determinants are those of its Jacobian with respect to the unknowns
    of each problem (the chart of the rods and ``P``, or the chart and ``theta``), whose
    zeros do not depend on how the rods are parametrised (the study's 8 x 8 shooting
    Jacobians of (98) vanish at the same places).

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.rfr2 import forward
    >>> from mechnum.mechanisms.rfr2.study import TABLE7, TABLE7_THETA
    >>> eq = forward(TABLE7, TABLE7_THETA, rng=0)
    >>> J = jacobians(TABLE7, TABLE7_THETA, eq.x)
    >>> ratio = np.linalg.det(J.dpose_dinputs) * J.det_fk / J.det_ik
    >>> bool(np.allclose(ratio, 1.0)), np.sign(J.det_fk).tolist()
    (True, [-1.0, 1.0, -1.0])
    """
    assembly.check_type(mech, Mechanism)
    theta, chart = _validate.array(theta, "theta"), _validate.array(chart, "chart")
    tip = rods(mech, theta, chart, modes, jacobian=False)[0]
    D = full_system(mech, modes)(chart, theta, tip[..., 0, :])[1]
    return assembly.determinants(D, LAYOUT)
