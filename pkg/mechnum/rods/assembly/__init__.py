"""What every mechanism built of elastica shares: its results, its searches, its paths and maps.

To this module a mechanism built of ``r`` clamped-pinned rods (the 2RFR of Chapter 5, the 3PFR
of Chapter 6) is a :class:`Layout`: the ``2 r`` coordinates of its rods in the regular chart
(:mod:`mechnum.rods.regular`), its ``k`` *inputs* (motor angles, slider positions) and its *pose*
(end effector, platform) of ``d`` numbers. Its full equilibrium system ``G(chart, inputs, pose)
= 0`` (``2 r + d`` equations) and its derivatives ``D``, in the columns ``(chart, inputs,
pose)``, give both problems:

* the **direct** (forward) problem solves ``G`` for ``(chart, pose)`` at given inputs; where
  ``det_fk = det dG/d(chart, pose)`` vanishes the locked inputs no longer hold the mechanism;
* the **inverse** problem solves ``G`` for ``(chart, inputs)`` at a given pose; where ``det_ik =
  det dG/d(chart, inputs)`` vanishes the pose cannot move in some direction (the workspace's
  edge).

Here are, once for every such mechanism:

* the results, in the result contract of ``mechnum.results``: :class:`Equilibria` (every
  equilibrium of an all-solutions search, with its stability, crossings and bending strain, and
  whether it can be built), :class:`Path` (one equilibrium followed along a path or over a
  grid), :class:`Shooting` (equilibria by RK4 shooting), and :class:`State`, one equilibrium as
  a mechanism's ``draw`` takes it;
* the drivers: :func:`search` (all solutions from many starts, with the completeness check),
  :func:`follow` (continuation that never reports a point of another branch as converged),
  :func:`follow_grid` (a map over a grid, from a neighbour), :func:`workspace_edge` (where a
  branch ends on rays), :func:`jacobians` and :func:`zero_crossings` (singular points on a map);
* :func:`peak_moment`, the largest bending moment along a clamped-pinned rod, for the strain
  that decides whether a rod can be built;
* the atlas (:func:`atlas_of`, :class:`Atlas`, :func:`draw_atlas`): how many equilibria, and
  how many stable ones, over a grid of the inputs, by continuation and all-solutions searches
  only where continuation cannot vouch for the count, in parallel (:mod:`parallel`: joblib,
  or a dask cluster).

Each mechanism (:mod:`mechnum.mechanisms.rfr2`, :mod:`mechnum.mechanisms.pfr3`) defines its
equations and drawing and calls these; the two never import each other.

The package's modules, whose names are all importable from here:
:mod:`~mechnum.rods.assembly.checks` (the bounds on the work,
:data:`~mechnum.rods.assembly.checks.MAX_NODES` and the others, and the checks of the input),
``results`` (the result classes), ``drivers`` (searches, paths, maps), ``drawing``,
``clamps`` (rods known by their clamp states), ``atlas`` and ``parallel``.
"""

from mechnum.rods.assembly.atlas import ANCHOR_SPACING, Atlas, AtlasProblem, atlas_of
from mechnum.rods.assembly.checks import (
    MAX_CHECK,
    MAX_DENSE_SEGMENTS,
    MAX_DIRECTIONS,
    MAX_LEVELS,
    MAX_NODES,
    MAX_POINTS,
    MAX_RAY_STEPS,
    MAX_SEGMENTS,
    MAX_STARTS,
    PATH_MAXITER,
    PATH_TOL,
    STATUS_DTYPE,
    check_equilibrium,
    check_modes,
    check_segments,
    check_type,
    grid_axes,
    points,
)
from mechnum.rods.assembly.clamps import chart_from_clamps, peak_moment
from mechnum.rods.assembly.drawing import draw_atlas, draw_parts, drawing_state, fold_segments
from mechnum.rods.assembly.drivers import (
    continuation_system,
    follow,
    follow_grid,
    memoised,
    search,
    shoot,
    singular_points,
    workspace_edge,
    zero_crossings,
)
from mechnum.rods.assembly.results import (
    Equilibria,
    Layout,
    Path,
    Shooting,
    State,
    Trace,
    closed_form_path,
    determinants,
    equilibria_message,
    jacobians,
    path_message,
    path_of,
    shooting_result,
)

__all__ = [
    "ANCHOR_SPACING", "Atlas", "AtlasProblem", "atlas_of", "draw_atlas", "fold_segments",
    "MAX_CHECK", "MAX_DENSE_SEGMENTS", "MAX_DIRECTIONS", "MAX_LEVELS", "MAX_NODES", "MAX_POINTS",
    "MAX_RAY_STEPS", "MAX_SEGMENTS", "MAX_STARTS", "PATH_MAXITER", "PATH_TOL", "STATUS_DTYPE",
    "Equilibria", "Layout", "Path", "Shooting", "State", "Trace", "chart_from_clamps",
    "check_equilibrium", "check_modes", "check_segments", "check_type", "closed_form_path",
    "continuation_system", "determinants", "draw_parts", "drawing_state", "equilibria_message",
    "follow", "follow_grid", "grid_axes", "jacobians", "memoised", "path_message", "path_of",
    "peak_moment", "points", "search", "shoot", "shooting_result", "singular_points",
    "workspace_edge", "zero_crossings",
]
