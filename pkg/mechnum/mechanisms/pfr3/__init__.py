"""The flexible 3PFR mechanism of the flexible-mechanisms study (001: 11.4, 13.3, Annex II 4).

Three sliders on straight guides move the clamped ends of three flexible rods whose other ends
are pinned to the vertices of a rigid triangular platform, which carries a force and a moment.

* :mod:`~mechnum.mechanisms.pfr3.model`: the :class:`Mechanism`, the study's examples
  (:data:`TABLE8`, :data:`TABLE2`), and the equilibrium equations in closed form, in a
  formulation that admits only real assemblies of the platform (never its mirror image);
* :mod:`~mechnum.mechanisms.pfr3.equilibria`: :func:`forward_elliptic`, every equilibrium for
  given slider inputs with its stability, crossings and an independent check;
* :mod:`~mechnum.mechanisms.pfr3.shooting`: the study's RK4 shooting, inverse and direct;
* :mod:`~mechnum.mechanisms.pfr3.paths`: trajectories by continuation, the determinants of the
  direct and inverse problems, maps over the plane, singularity curves and the workspace's
  edge (:func:`workspace_edge`);
* :mod:`~mechnum.mechanisms.pfr3.study`: the study's published numbers, the inputs they belong
  to, and its own residual; :func:`reproduce` gives the registry's values;
* :func:`draw` draws an equilibrium.
"""

from mechnum.mechanisms.pfr3.certified import certify_forward
from mechnum.mechanisms.pfr3.drawing import draw
from mechnum.mechanisms.pfr3.equilibria import (Equilibria, crossings, forward_elliptic, sampler,
                                                shapes, stability, verify)
from mechnum.mechanisms.pfr3.model import (SHOOTING_EXAMPLE, SHOOTING_POSE, TABLE2,
                                           TABLE2_LAMBDAS, TABLE8, TABLE8_LAMBDAS, Mechanism,
                                           chart_from_thesis, check_closure, clamps,
                                           forward_system, full_system, pins, pose_of_tips,
                                           thesis_from_chart)
from mechnum.mechanisms.pfr3.paths import (Path, forward_path, inverse_map, inverse_path,
                                           jacobians, singular_points, workspace_edge)
from mechnum.mechanisms.pfr3.reproduction import reproduce
from mechnum.mechanisms.pfr3.shooting import (Shooting, forward_shooting, inverse_shooting,
                                              shooting_guess)
from mechnum.mechanisms.pfr3.study import (TABLE8_PUBLISHED, digit_matches, orientation,
                                           recover_inputs, thesis_residual, within_study_reach)
