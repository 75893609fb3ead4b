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
  clamp frame and a shape parameter, in the regular chart ``t_i`` of :mod:`mechnum.rods`
  (the study's ``k_rel`` is singular at both ends of its range). The four unknowns
  ``(psi1, t1, psi2, t2)`` satisfy four equations, ``tip1 = tip2`` and ``n1 + n2 = F``, with an
  analytic Jacobian. :func:`forward` finds every equilibrium of given buckling modes
  (:func:`mechnum.newton.solve_all`) with the evidence that there are no more, its stability
  (:func:`stability`) and whether the rods cross (:func:`crossings`).
* **RK4 shooting** (the study's 11.3.1): :func:`forward_shooting` and :func:`inverse_shooting`,
  the study's unknowns (its (99) and (102)) and equations (98), with complex-step Jacobians.
* **Continuation**: :func:`inverse_path` and :func:`forward_path` follow one equilibrium along
  a path of end-effector positions or of motor angles (the study's trajectories),
  and :func:`forward_map` over a grid of motor angles; :func:`jacobians` gives the determinants
  whose zeros are the singularities.

The residual is dimensionless: positions over ``L``, forces over ``EI / L**2``.

The mechanism protocol (the same verbs as the 3PFR's, the mechanism first): :func:`forward`
(every equilibrium of given motor angles, with ``status`` and ``stable``), :func:`inverse` (of a
given end effector), :func:`singular_points`, :func:`workspace`, :func:`atlas`, and
``draw(ax, mech, state, *, artists=None)``. The shared parts (results, searches, paths, maps)
are ``mechanisms._assembly``'s; the study's constants :mod:`mechnum.mechanisms.thesis`'s.

Its study (the example of Table 7, the study's paths, its published numbers and their
reproduction) is :mod:`mechnum.mechanisms.rfr2.study`, imported on first use.
"""

from mechnum.mechanisms.rfr2._analysis import (
    verify,
)
from mechnum.mechanisms.rfr2._atlases import atlas
from mechnum.mechanisms.rfr2._continuation import (
    forward_map,
    forward_path,
    inverse_path,
    singular_points,
    workspace,
)
from mechnum.mechanisms.rfr2._drawing import draw, shapes
from mechnum.mechanisms.rfr2._elliptic import (
    forward,
    forward_system,
    inverse,
    residual,
)
from mechnum.mechanisms.rfr2._model import Mechanism, rods
from mechnum.mechanisms.rfr2._shooting import (
    forward_shooting,
    inverse_shooting,
    shooting_guess,
)
from mechnum.mechanisms.rfr2._singularities import jacobians
from mechnum.mechanisms.rfr2.certified import certify_forward

__all__ = ["Mechanism", "atlas", "certify_forward", "draw", "forward", "forward_map",
           "forward_path", "forward_shooting", "forward_system", "inverse", "inverse_path",
           "inverse_shooting", "jacobians", "residual", "rods", "shapes", "shooting_guess",
           "singular_points", "verify", "workspace"]


def __getattr__(name: str) -> object:
    """The study (:mod:`mechnum.mechanisms.rfr2.study`), imported on first use."""
    if name == "study":
        import importlib

        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
