"""The flexible 2RFR mechanism of the flexible-mechanisms study (001: 11.3, 13.2, Annex II 3).

Two motors on the ground, at ``O1`` and ``O2``, turn the clamped ends of two flexible rods to the
angles ``theta = (theta1, theta2)``; the rods' other ends are pinned together at the end effector
``P``, which carries an external force ``F``. Each rod is a clamped-pinned elastica
(:mod:`mechnum.rods`), and the mechanism is in equilibrium when

* both tips are at ``P``: ``tip1 = tip2 = P``;
* the forces that the rods receive at their tips carry the load: ``n1 + n2 = F`` (the study's
  (92) and (98), and its code; its (104) prints ``+ F`` on the other side, the wrong sign).

Three formulations, as in the study, and what this module adds to them:

* **Closed form** (the study's 11.3.2): each rod is its force direction ``psi_i`` in the rod's
  clamp frame and a shape parameter, in the regular chart ``t_i`` of :mod:`mechnum.rods.regular`
  (the study's ``k_rel`` is singular at both ends of its range). The four unknowns
  ``(psi1, t1, psi2, t2)`` satisfy four equations, ``tip1 = tip2`` and ``n1 + n2 = F``, with an
  analytic Jacobian. :func:`forward_elliptic` finds every equilibrium of given buckling modes
  (:func:`mechnum.newton.solve_all`) with the evidence that there are no more, its stability
  (:mod:`mechnum.rods.stability`) and whether the rods cross (:mod:`mechnum.rods.crossing`).
* **RK4 shooting** (the study's 11.3.1): :func:`forward_shooting` and :func:`inverse_shooting`,
  the study's unknowns (its (99) and (102)) and equations (98), with complex-step Jacobians.
* **Continuation**: :func:`inverse_path` and :func:`forward_path` follow one equilibrium along
  a path of end-effector positions or of motor angles (the study's trajectories, :func:`path`),
  and :func:`forward_map` over a grid of motor angles; :func:`jacobians` gives the determinants
  whose zeros are the singularities.

The residual is dimensionless: positions over ``L``, forces over ``EI / L**2``.

The package's modules:

* :mod:`~mechnum.mechanisms.rfr2.model`: the :class:`Mechanism`, the study's example
  (:data:`~mechnum.mechanisms.rfr2.model.TABLE7`,
  :data:`~mechnum.mechanisms.rfr2.model.TABLE7_THETA`), and both rods in the chart
  (:func:`chart_from_thesis`);
* :mod:`~mechnum.mechanisms.rfr2.elliptic`: the closed form's equations
  (:func:`forward_system`, :func:`residual`) and all its equilibria
  (:func:`forward_elliptic`, :class:`Equilibria`);
* :mod:`~mechnum.mechanisms.rfr2.analysis`: each equilibrium's stability (:func:`stability`,
  :func:`eigenvalues`), shape (:func:`shapes`), crossings (:func:`crossings`) and an
  independent check (:func:`verify`);
* :mod:`~mechnum.mechanisms.rfr2.shooting`: RK4 shooting (:func:`forward_shooting`,
  :func:`inverse_shooting`, :func:`shooting_guess`, :class:`Shooting`);
* :mod:`~mechnum.mechanisms.rfr2.singularities`: the Jacobians whose determinants vanish at
  the singularities (:func:`jacobians`, :class:`Jacobians`);
* :mod:`~mechnum.mechanisms.rfr2.continuation`: equilibria followed along paths
  (:func:`inverse_path`, :func:`forward_path`, :func:`forward_map`, :class:`Path`);
* :mod:`~mechnum.mechanisms.rfr2.trajectories`: the study's paths (:func:`straight_path`,
  :func:`circles`, :func:`rectangles`, :func:`path`);
* :mod:`~mechnum.mechanisms.rfr2.drawing`: :func:`draw`;
* :mod:`~mechnum.mechanisms.rfr2.study`: the published Table 7
  (:data:`~mechnum.mechanisms.rfr2.study.TABLE7_PUBLISHED`), :func:`recover_inputs` and
  :func:`reproduce`.
"""

# Also imported, though private: _rods, _in_chart, _sample, _shooting_system and _memoised,
# which the tests, Chapter 5 and the three-rod mechanism use.
from mechnum.mechanisms.rfr2.analysis import (EIGEN_SEGMENTS, IVP_RTOL, SEGMENTS, SHAPE_NODES,
                                              crossings, eigenvalues, shapes, stability, verify)
from mechnum.mechanisms.rfr2.certified import certify_forward
from mechnum.mechanisms.rfr2.continuation import Path, forward_map, forward_path, inverse_path
from mechnum.mechanisms.rfr2.drawing import draw
from mechnum.mechanisms.rfr2.elliptic import (START_T, Equilibria, _sample, forward_elliptic,
                                              forward_system, residual)
from mechnum.mechanisms.rfr2.model import (DIAMETER, EI, LENGTH, TABLE7, TABLE7_THETA, YOUNG,
                                           Mechanism, _in_chart, _rods, chart_from_thesis)
from mechnum.mechanisms.rfr2.shooting import (SHOOTING_TOL, STUDY_NODES, Shooting, _memoised,
                                              _shooting_system, forward_shooting,
                                              inverse_shooting, shooting_guess)
from mechnum.mechanisms.rfr2.singularities import Jacobians, jacobians
from mechnum.mechanisms.rfr2.study import TABLE7_PUBLISHED, recover_inputs, reproduce
from mechnum.mechanisms.rfr2.trajectories import (STUDY_PATHS, circles, path, rectangles,
                                                  straight_path)

__all__ = [
    # model
    "LENGTH", "YOUNG", "DIAMETER", "EI", "Mechanism", "TABLE7", "TABLE7_THETA",
    "chart_from_thesis",
    # elliptic
    "START_T", "forward_system", "residual", "Equilibria", "forward_elliptic",
    # analysis
    "SEGMENTS", "EIGEN_SEGMENTS", "IVP_RTOL", "SHAPE_NODES", "stability", "eigenvalues",
    "shapes", "crossings", "verify",
    # shooting
    "STUDY_NODES", "SHOOTING_TOL", "Shooting", "forward_shooting", "inverse_shooting",
    "shooting_guess",
    # singularities
    "Jacobians", "jacobians",
    # continuation
    "Path", "inverse_path", "forward_path", "forward_map",
    # trajectories
    "straight_path", "circles", "rectangles", "STUDY_PATHS", "path",
    # drawing
    "draw",
    # study
    "TABLE7_PUBLISHED", "recover_inputs", "reproduce",
    # certified
    "certify_forward",
]
