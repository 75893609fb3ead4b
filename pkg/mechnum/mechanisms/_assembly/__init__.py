"""What every mechanism built of elastica shares (private to :mod:`mechnum.mechanisms`): its
results, its searches, its paths and maps.

To this module a mechanism built of ``r`` clamped-pinned rods (the 2RFR of Chapter 5, the 3PFR
of Chapter 6) is a :class:`Layout`: the ``2 r`` coordinates of its rods in the regular chart of
:mod:`mechnum.rods`, its ``k`` *inputs* (motor angles, slider positions) and its *pose* (end
effector, platform) of ``d`` numbers. Its full equilibrium system ``G(chart, inputs, pose) = 0``
(``2 r + d`` equations) and its derivatives ``D``, in the columns ``(chart, inputs, pose)``,
give both problems:

* the **direct** (forward) problem solves ``G`` for ``(chart, pose)`` at given inputs; where
  ``det_fk = det dG/d(chart, pose)`` vanishes the locked inputs no longer hold the mechanism;
* the **inverse** problem solves ``G`` for ``(chart, inputs)`` at a given pose; where ``det_ik =
  det dG/d(chart, inputs)`` vanishes the pose cannot move in some direction (the workspace's
  edge).

Here are, once for every such mechanism:

* the results, in the result contract of ``mechnum.results`` (public as
  ``mechnum.mechanisms.Equilibria`` and the others): :class:`Equilibria` (every equilibrium of
  an all-solutions search, with its stability, crossings and bending strain, and whether it can
  be built), :class:`Path` (one equilibrium followed along a path or over a grid),
  :class:`Shooting` (equilibria by RK4 shooting), :class:`Atlas`, :class:`Jacobians`, and
  :class:`State`, one equilibrium as a mechanism's ``draw`` and ``workspace`` take it;
* the drivers: :func:`search` (all solutions from many starts, with the completeness check),
  :func:`shoot`, :func:`follow` (continuation that never reports a point of another branch as
  converged), :func:`follow_grid` (a map over a grid, from a neighbour),
  :func:`workspace_edge` (where a branch ends on rays), :func:`jacobians` and
  :func:`zero_crossings` (singular points on a map);
* the atlas (:func:`atlas_of`, :class:`Atlas`, :func:`draw_atlas`): how many equilibria, and
  how many stable ones, over a grid of the inputs, by continuation and all-solutions searches
  only where continuation cannot vouch for the count, in parallel (joblib, or a dask cluster).

Each mechanism (:mod:`mechnum.mechanisms.rfr2`, :mod:`mechnum.mechanisms.pfr3`) defines its
equations and drawing and calls these; the two never import each other. Every system here
gives its residual and Jacobian together, ``fun(u) -> (f, J)``, as :func:`mechnum.newton.solve`
takes them with ``jac=True``; the bounds on the work (:data:`MAX_NODES` and the others) and the
checks of the input are here too.
"""

from mechnum.mechanisms._assembly._atlas import ANCHOR_SPACING, Atlas, AtlasProblem, atlas_of
from mechnum.mechanisms._assembly._atlas import STEP_TOL as ATLAS_STEP_TOL
from mechnum.mechanisms._assembly._checks import (
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
    plane_grid,
    points,
)
from mechnum.mechanisms._assembly._drawing import check_state, draw_atlas, draw_parts, fold_segments
from mechnum.mechanisms._assembly._drivers import (
    continuation_system,
    follow,
    follow_grid,
    search,
    shoot,
    singular_points,
    workspace_edge,
    zero_crossings,
)
from mechnum.mechanisms._assembly._results import (
    Equilibria,
    Jacobians,
    Layout,
    Path,
    ShotEquilibria,
    State,
    Trace,
    closed_form_path,
    determinants,
    equilibria_message,
    jacobians,
    path_message,
    path_of,
    shooting_result,
    trace_of,
)

__all__ = ["ANCHOR_SPACING", "ATLAS_STEP_TOL", "MAX_CHECK", "MAX_DENSE_SEGMENTS",
           "MAX_DIRECTIONS", "MAX_LEVELS", "MAX_NODES", "MAX_POINTS", "MAX_RAY_STEPS",
           "MAX_SEGMENTS", "MAX_STARTS", "PATH_MAXITER", "PATH_TOL", "STATUS_DTYPE", "Atlas",
           "AtlasProblem", "Equilibria", "Jacobians", "Layout", "Path", "ShotEquilibria", "State",
           "Trace", "atlas_of", "check_equilibrium", "check_modes", "check_segments",
           "check_state", "check_type", "closed_form_path", "continuation_system", "determinants",
           "draw_atlas", "draw_parts", "equilibria_message", "fold_segments", "follow",
           "follow_grid", "grid_axes", "jacobians", "path_message", "path_of", "plane_grid",
           "points", "search", "shoot", "shooting_result", "singular_points", "trace_of",
           "workspace_edge", "zero_crossings"]
