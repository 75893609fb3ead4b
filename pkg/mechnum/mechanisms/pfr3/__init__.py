"""The flexible 3PFR mechanism of the flexible-mechanisms study (001: 11.4, 13.3, Annex II 4).

Three sliders on straight guides move the clamped ends of three flexible rods whose other ends
are pinned to the vertices of a rigid triangular platform, which carries a force and a moment.

* the :class:`Mechanism` and the equilibrium equations in closed form, in a formulation that
  admits only real assemblies of the platform (never its mirror image): the reduced one
  (:func:`forward_system`) and the full one (:func:`full_system`), with the rods
  (:func:`rods`), the clamps (:func:`clamps`), the pins (:func:`pins`) and the pose of the tips
  (:func:`pose_of_tips`);
* :func:`forward`, every equilibrium for given slider inputs (from the physical starts of
  :func:`sampler`), and :func:`inverse`, for a given pose;
* each equilibrium's stability (:func:`stability`, :func:`index`, :func:`second_variation`),
  crossings (:func:`crossings`), bending strain (:func:`strain`) and an independent check
  (:func:`verify`);
* the study's RK4 shooting, direct and inverse (:func:`forward_shooting`,
  :func:`inverse_shooting`, :func:`shooting_guess`, :func:`shooting_system`);
* trajectories by continuation (:func:`forward_path`, :func:`inverse_path`), the determinants
  of the direct and inverse problems (:func:`jacobians`), maps over the plane
  (:func:`inverse_map`), singularity curves (:func:`singular_points`) and the workspace's edge
  (:func:`workspace`);
* :func:`atlas`, the equilibria and the stable ones over a grid of slider inputs on a plane,
  and the folds;
* :func:`shapes` and :func:`draw`; :func:`certify_forward`, every equilibrium proven.

The mechanism protocol, the same verbs as the 2RFR's, the mechanism first: :func:`forward`
(with ``status`` and ``stable``), :func:`inverse`, :func:`singular_points`, :func:`workspace`,
:func:`atlas` and ``draw(ax, mech, state, *, artists=None)``. The shared parts (results,
searches, paths, maps) are ``mechanisms._assembly``'s; the study's constants
:mod:`mechnum.mechanisms.thesis`'s. Its study (the examples of Tablas 8 and 2 and of the
shooting programs, the published numbers, the inputs they belong to and their reproduction) is
:mod:`mechnum.mechanisms.pfr3.study`, imported on first use.
"""

from mechnum.mechanisms.pfr3._analysis import (
    index,
    verify,
)
from mechnum.mechanisms.pfr3._atlases import atlas
from mechnum.mechanisms.pfr3._drawing import draw
from mechnum.mechanisms.pfr3._elliptic import forward, inverse, sampler
from mechnum.mechanisms.pfr3._model import (
    Mechanism,
    clamps,
    forward_system,
    full_system,
    pins,
    rods,
)
from mechnum.mechanisms.pfr3._paths import (
    forward_path,
    inverse_map,
    inverse_path,
    jacobians,
    singular_points,
    workspace,
)
from mechnum.mechanisms.pfr3._shooting import (
    forward_shooting,
    inverse_shooting,
    shooting_guess,
)
from mechnum.mechanisms.pfr3.certified import certify_forward

__all__ = ["Mechanism", "atlas", "certify_forward", "clamps", "draw", "forward", "forward_path",
           "forward_shooting", "forward_system", "full_system", "index", "inverse", "inverse_map",
           "inverse_path", "inverse_shooting", "jacobians", "pins", "rods", "sampler",
           "shooting_guess", "singular_points", "verify", "workspace"]


def __getattr__(name: str) -> object:
    """The study (:mod:`mechnum.mechanisms.pfr3.study`), imported on first use."""
    if name == "study":
        import importlib

        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
