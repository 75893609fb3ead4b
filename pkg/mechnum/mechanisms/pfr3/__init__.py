"""The flexible 3PFR mechanism of the flexible-mechanisms study (001: 11.4, 13.3, Annex II 4).

Three sliders on straight guides move the clamped ends of three flexible rods whose other ends
are pinned to the vertices of a rigid triangular platform, which carries a force and a moment.

* :mod:`~mechnum.mechanisms.pfr3.model`: the :class:`Mechanism`, the study's examples
  (:data:`TABLE8`, :data:`TABLE2`), and the equilibrium equations in closed form, in a
  formulation that admits only real assemblies of the platform (never its mirror image);
* :mod:`~mechnum.mechanisms.pfr3.equilibria`: :func:`forward_elliptic` (the protocol's
  :func:`forward`), every equilibrium for given slider inputs, and :func:`inverse`, for a given
  pose;
* :mod:`~mechnum.mechanisms.pfr3.analysis`: each equilibrium's stability, crossings, bending
  strain and an independent check;
* :mod:`~mechnum.mechanisms.pfr3.shooting`: the study's RK4 shooting, inverse and direct;
* :mod:`~mechnum.mechanisms.pfr3.paths`: trajectories by continuation, the determinants of the
  direct and inverse problems, maps over the plane, singularity curves
  (:func:`singular_points`) and the workspace's edge (:func:`workspace`);
* :mod:`~mechnum.mechanisms.pfr3.atlases`: :func:`atlas`, the equilibria and the stable ones
  over a grid of slider inputs on a plane (:func:`plane`), and the folds;
* :mod:`~mechnum.mechanisms.pfr3.study`: the study's published numbers, the inputs they belong
  to, and its own residual; :func:`reproduce` gives the registry's values;
* :mod:`~mechnum.mechanisms.pfr3.drawing`: :func:`shapes` and :func:`draw`.

The mechanism protocol, the same verbs as the 2RFR's, the mechanism first: :func:`forward`
(with ``status`` and ``stable``), :func:`inverse`, :func:`singular_points`, :func:`workspace`,
:func:`atlas` and ``draw(ax, mech, state, *, artists=None)``. The shared parts (results,
searches, paths, maps) are :mod:`mechnum.rods.assembly`'s; the study's constants
:mod:`mechnum.mechanisms.thesis`'s.
"""

from mechnum.mechanisms.pfr3.analysis import (
    crossings,
    index,
    resolutions,
    second_variation,
    stability,
    strain,
    verify,
)
from mechnum.mechanisms.pfr3.atlases import atlas, plane
from mechnum.mechanisms.pfr3.certified import certify_forward
from mechnum.mechanisms.pfr3.drawing import draw, shapes
from mechnum.mechanisms.pfr3.equilibria import (
    Equilibria,
    forward,
    forward_elliptic,
    inverse,
    inverse_sampler,
    sampler,
)
from mechnum.mechanisms.pfr3.model import (
    LAYOUT,
    SHOOTING_EXAMPLE,
    SHOOTING_POSE,
    TABLE2,
    TABLE2_LAMBDAS,
    TABLE8,
    TABLE8_LAMBDAS,
    Mechanism,
    chart_from_thesis,
    check_closure,
    clamps,
    forward_system,
    full_system,
    pins,
    pose_of_tips,
    thesis_from_chart,
)
from mechnum.mechanisms.pfr3.paths import (
    Path,
    forward_path,
    inverse_map,
    inverse_path,
    jacobians,
    singular_points,
    workspace,
    workspace_edge,
)
from mechnum.mechanisms.pfr3.reproduction import reproduce
from mechnum.mechanisms.pfr3.shooting import (
    Shooting,
    forward_shooting,
    inverse_shooting,
    shooting_guess,
    shooting_system,
)
from mechnum.mechanisms.pfr3.study import (
    TABLE8_PUBLISHED,
    digit_matches,
    orientation,
    recover_inputs,
    thesis_residual,
    within_study_reach,
)

__all__ = [
    "LAYOUT", "SHOOTING_EXAMPLE", "SHOOTING_POSE", "TABLE2", "TABLE2_LAMBDAS", "TABLE8",
    "TABLE8_LAMBDAS", "TABLE8_PUBLISHED", "Equilibria", "Mechanism", "Path", "Shooting",
    "atlas", "certify_forward", "chart_from_thesis", "check_closure", "clamps", "crossings",
    "digit_matches", "draw",
    "forward", "forward_elliptic", "forward_path", "forward_shooting", "forward_system",
    "full_system", "index", "inverse", "inverse_map", "inverse_path", "inverse_sampler",
    "inverse_shooting", "jacobians", "orientation", "pins", "plane", "pose_of_tips",
    "recover_inputs",
    "reproduce", "resolutions", "sampler", "second_variation", "shapes", "shooting_guess",
    "shooting_system", "singular_points", "stability", "strain", "thesis_from_chart",
    "thesis_residual", "verify", "within_study_reach", "workspace", "workspace_edge",
]
