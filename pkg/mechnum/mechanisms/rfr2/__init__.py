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

The mechanism protocol (the same verbs as the 3PFR's, the mechanism first): :func:`forward`
(every equilibrium of given motor angles, with ``status`` and ``stable``), :func:`inverse` (of a
given end effector), :func:`singular_points`, :func:`workspace`, :func:`atlas`, and
``draw(ax, mech, state, *, artists=None)``. The shared parts (results, searches, paths, maps)
are :mod:`mechnum.rods.assembly`'s; the study's constants :mod:`mechnum.mechanisms.thesis`'s.

The package's modules:

* :mod:`~mechnum.mechanisms.rfr2.model`: the :class:`Mechanism`, the study's example
  (:data:`~mechnum.mechanisms.rfr2.model.TABLE7`,
  :data:`~mechnum.mechanisms.rfr2.model.TABLE7_THETA`), both rods in the chart (:func:`rods`,
  :func:`chart_from_thesis`) and the full system (:func:`full_system`);
* :mod:`~mechnum.mechanisms.rfr2.elliptic`: the closed form's equations
  (:func:`forward_system`, :func:`inverse_system`, :func:`residual`) and all their equilibria
  (:func:`forward_elliptic`, :func:`inverse`, :class:`Equilibria`);
* :mod:`~mechnum.mechanisms.rfr2.analysis`: each equilibrium's stability (:func:`stability`,
  :func:`index`, :func:`eigenvalues`), crossings (:func:`crossings`), bending strain
  (:func:`strain`) and an independent check (:func:`verify`);
* :mod:`~mechnum.mechanisms.rfr2.shooting`: RK4 shooting (:func:`forward_shooting`,
  :func:`inverse_shooting`, :func:`shooting_guess`, :func:`shooting_system`,
  :class:`Shooting`);
* :mod:`~mechnum.mechanisms.rfr2.singularities`: the Jacobians whose determinants vanish at
  the singularities (:func:`jacobians`, :class:`Jacobians`);
* :mod:`~mechnum.mechanisms.rfr2.continuation`: equilibria followed along paths
  (:func:`inverse_path`, :func:`forward_path`, :func:`forward_map`, :func:`workspace`,
  :func:`singular_points`, :class:`Path`);
* :mod:`~mechnum.mechanisms.rfr2.atlases`: :func:`atlas`, the equilibria and the stable ones
  over a grid of motor angles, and the folds where their count changes;
* :mod:`~mechnum.mechanisms.rfr2.trajectories`: the study's paths (:func:`straight_path`,
  :func:`circles`, :func:`rectangles`, :func:`path`);
* :mod:`~mechnum.mechanisms.rfr2.drawing`: :func:`shapes` and :func:`draw`;
* :mod:`~mechnum.mechanisms.rfr2.study`: the published Table 7
  (:data:`~mechnum.mechanisms.rfr2.study.TABLE7_PUBLISHED`), :func:`recover_inputs` and
  :func:`reproduce`.
"""

import warnings

from mechnum.mechanisms.rfr2.analysis import (
    EIGEN_SEGMENTS,
    IVP_RTOL,
    SEGMENTS,
    crossings,
    eigenvalues,
    index,
    stability,
    strain,
    verify,
)
from mechnum.mechanisms.rfr2.atlases import atlas
from mechnum.mechanisms.rfr2.certified import certify_forward
from mechnum.mechanisms.rfr2.continuation import (
    Path,
    forward_map,
    forward_path,
    inverse_path,
    singular_points,
    workspace,
)
from mechnum.mechanisms.rfr2.drawing import SHAPE_NODES, draw, shapes
from mechnum.mechanisms.rfr2.elliptic import (
    START_T,
    Equilibria,
    forward,
    forward_elliptic,
    forward_system,
    inverse,
    inverse_system,
    motor_angles,
    residual,
    sample,
)
from mechnum.mechanisms.rfr2.model import (
    LAYOUT,
    TABLE7,
    TABLE7_THETA,
    Mechanism,
    broadcast,
    chart_from_thesis,
    full_system,
    in_chart,
    rods,
    thesis_from_chart,
)
from mechnum.mechanisms.rfr2.shooting import (
    Shooting,
    forward_shooting,
    inverse_shooting,
    shooting_guess,
    shooting_system,
)
from mechnum.mechanisms.rfr2.singularities import Jacobians, jacobians
from mechnum.mechanisms.rfr2.study import TABLE7_PUBLISHED, recover_inputs, reproduce
from mechnum.mechanisms.rfr2.trajectories import (
    STUDY_PATHS,
    circles,
    path,
    rectangles,
    straight_path,
)
from mechnum.mechanisms.thesis import DIAMETER, EI, LENGTH, STUDY_NODES, YOUNG
from mechnum.rods.shooting import SHOOTING_TOL

__all__ = [
    "DIAMETER", "EI", "EIGEN_SEGMENTS", "IVP_RTOL", "LAYOUT", "LENGTH", "SEGMENTS", "SHAPE_NODES",
    "SHOOTING_TOL", "START_T", "STUDY_NODES", "STUDY_PATHS", "TABLE7", "TABLE7_PUBLISHED",
    "TABLE7_THETA", "YOUNG", "Equilibria", "Jacobians", "Mechanism", "Path", "Shooting",
    "atlas", "broadcast", "certify_forward", "chart_from_thesis", "circles", "crossings", "draw",
    "eigenvalues", "forward",
    "forward_elliptic", "forward_map", "forward_path", "forward_shooting", "forward_system",
    "full_system", "in_chart", "index", "inverse", "inverse_path", "inverse_shooting",
    "inverse_system", "jacobians", "motor_angles", "path", "recover_inputs", "rectangles",
    "reproduce", "residual", "rods", "sample", "shapes", "shooting_guess", "shooting_system",
    "singular_points", "stability", "straight_path", "strain", "thesis_from_chart", "verify",
    "workspace",
]

_DEPRECATED = {"_rods": "rods", "_in_chart": "in_chart", "_sample": "sample",
               "_shooting_system": "shooting_system"}


def __getattr__(name):
    """The private names Chapter 5 and the benchmarks used, for one release: each warns and
    gives its public successor (``rfr2.rods`` takes ``(mech, theta, chart, modes)``, where
    ``_rods`` took ``(mech, modes, chart, theta)``)."""
    if name not in _DEPRECATED:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    warnings.warn(f"rfr2.{name} is deprecated: use rfr2.{_DEPRECATED[name]}",
                  DeprecationWarning, stacklevel=2)
    if name == "_rods":
        return lambda mech, modes, z, theta: rods(mech, theta, z, modes)
    return globals()[_DEPRECATED[name]]
