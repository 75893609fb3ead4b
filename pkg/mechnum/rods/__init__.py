"""Planar Kirchhoff rods: RK4 shooting and the elliptic-integral closed form.

Conventions (used by every function here and by the flexible mechanisms built on them)

* A rod of length ``L`` (m) and bending stiffness ``EI`` (N m^2) is inextensible, unshearable
  and straight when unloaded. The arc length ``s`` runs from ``s = 0`` at the **clamped** end
  to ``s = L`` at the other end, the **tip** (free, or pinned to a platform).
* The state at ``s`` is ``(x, y, theta, m)``: the centreline position (m), the angle of the
  tangent from the x axis (rad, anticlockwise) and the bending moment ``m = EI dtheta/ds``
  (N m, positive anticlockwise).
* ``n = (n_x, n_y)`` (N) is the internal force, constant along a rod with no distributed
  load: the force that the part beyond ``s`` exerts on the part before ``s``. So ``n`` is
  the external force applied **on the rod at its tip** (the load of a cantilever, or the force
  that the platform exerts on the rod); the clamp exerts ``-n`` and the moment ``-m(0)``.
* The equations (the study's (78)) are::

      x' = cos(theta),  y' = sin(theta),  theta' = m / EI,  m' = n_x sin(theta) - n_y cos(theta)

  and a free or pinned tip carries no moment, ``m(L) = 0``.
* Arrays: ``EI``, ``L``, ``m0``, ``theta0`` broadcast over a leading batch shape; forces and
  points have a last axis of length 2. Many rods are integrated in one RK4 sweep.

The closed form (:func:`clamped_pinned`) works in the rod's **local frame**: clamp at the
origin, clamped tangent along +x (``theta(0) = 0``), tip force ``n = R (cos psi, sin psi)``
with ``R > 0``. It is valid for ``0 < psi < 2 pi`` (``psi = 0`` is pure tension: a straight
rod with no ``k``), ``0 < |k_rel| < 1`` and buckling ``mode = 1, 2, ...``, the number of
inflection points of ``theta`` (zeros of ``m``) on ``0 < s <= L``, the tip's included.
With ``k_min = |cos(psi/2)|`` (the study's code; its text calls it a function of ``k``),
``k = sign(k_rel) k_min + (1 - k_min) k_rel``, ``phi1 = arcsin(cos(psi/2) / k)`` and
``phi2 = (mode - 1/2) pi``; ``sign(k) = sign(m(0))``. scipy's elliptic integrals take the
parameter ``m = k**2``. To place a closed-form rod clamped at ``(x0, y0)`` at angle
``theta0``, rotate its tip and its force by ``theta0`` and add ``(x0, y0)``: ``psi`` is the
force direction relative to the clamped tangent.

What the package holds: the rod, its equations and its RK4 sweeps (:class:`Rod`,
:func:`equations`, :func:`integrate`, :func:`tip_jacobian`); a cantilever by either method
(:func:`cantilever`); the closed form in the study's chart ``(psi, k_rel)``
(:func:`clamped_pinned`, :func:`elliptic_k`, :func:`elliptic_parameters`,
:func:`k_rel_for_force`) and in the regular chart ``(psi, t)``, which holds every digit
(:func:`clamped_pinned_regular` with its Jacobian, :func:`shape`, :func:`k_rel_from_t`,
:func:`t_from_k_rel`; :class:`ClampedRods` for a mechanism's rods in a solver's loop, and
the compiled residual and Jacobian of rods whose tips meet, :class:`MeetingRods`, for the
searches and the atlas of the rod mechanisms); every
equilibrium through a point and what a shot rod is (:func:`pinned_equilibria`,
:func:`classify`); the shooting solvers, single and multiple (:func:`shoot_cantilever`,
:func:`shoot_pinned`, :func:`shoot_pinned_multiple`, :class:`Shooting`); the second variation
(:func:`rod_block`, :func:`constrained_eigenvalues`, :func:`constrained_index`,
:func:`constrained_index_with_body`); crossings (:func:`self_crossings`,
:func:`mutual_crossings`); a cantilever's equilibria under a growing dead load, for
continuation (:class:`DeadLoad`); the pinned rod proven (:func:`certify_pinned`); every
equilibrium of rods that meet, proven by co-refinement over their whole charts
(:func:`corefine`, :func:`certified_all`; the rods and their assembly are
:mod:`mechnum.rods.certified`'s), and a rod's proven index (:func:`pinned_index`,
:func:`proven_stability`). What every
mechanism built of rods shares is ``mechanisms._assembly``.
In a Newton loop over the rods of a mechanism, call a :class:`ShotRods` (:func:`tip_jacobian`,
checked once when made) once on the batch of all rods: one sweep gives every tip and every
``d tip / d (m0, n_x, n_y)``, and costs little more than one rod (the cost of a sweep is per
numpy call, not per rod).
"""

from mechnum.rods._bodies import constrained_index_with_body
from mechnum.rods._cantilever import cantilever
from mechnum.rods._clamps import chart_from_clamps, peak_moment
from mechnum.rods._cocertificate import CoCertificate as CoCertificate
from mechnum.rods._cocertificate import CoVerified as CoVerified
from mechnum.rods._cosearch import CertifiedAll as CertifiedAll
from mechnum.rods._cosearch import CoRefined as CoRefined
from mechnum.rods._cosearch import certified_all, corefine
from mechnum.rods._crossing import mutual_crossings, self_crossings
from mechnum.rods._elliptic import (
    NoEquilibriumError,
    NotAnElasticaError,
    clamped_pinned,
    elliptic_k,
    elliptic_parameters,
    k_rel_for_force,
)
from mechnum.rods._index import pinned_index, proven_stability
from mechnum.rods._loading import DeadLoad
from mechnum.rods._meeting import MeetingRods
from mechnum.rods._multiple import shoot_pinned_multiple
from mechnum.rods._pinned import classify, pinned_equilibria
from mechnum.rods._profile import shape
from mechnum.rods._regular import (
    T_MAX,
    ClampedRods,
    clamped_pinned_regular,
    in_chart,
    k_rel_from_t,
    t_from_k_rel,
)
from mechnum.rods._rod import Rod, ShotRods, equations, integrate, tip_jacobian
from mechnum.rods._shooting import (
    SHOOTING_TOL,
    UnresolvedRodError,
    shoot_cantilever,
    shoot_pinned,
)

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.rods._shooting import Shooting as Shooting
from mechnum.rods._stability import constrained_eigenvalues, constrained_index, rod_block
from mechnum.rods.certified import certify_pinned

__all__ = ["SHOOTING_TOL", "T_MAX", "ClampedRods", "DeadLoad", "MeetingRods", "NoEquilibriumError",
           "NotAnElasticaError", "Rod", "ShotRods", "UnresolvedRodError", "cantilever",
           "certified_all", "certify_pinned", "chart_from_clamps", "clamped_pinned",
           "clamped_pinned_regular", "classify", "constrained_eigenvalues", "constrained_index",
           "constrained_index_with_body", "corefine", "elliptic_k", "elliptic_parameters",
           "equations", "in_chart", "integrate", "k_rel_for_force", "k_rel_from_t",
           "mutual_crossings", "peak_moment", "pinned_equilibria", "pinned_index",
           "proven_stability", "rod_block", "self_crossings", "shape", "shoot_cantilever",
           "shoot_pinned", "shoot_pinned_multiple", "t_from_k_rel", "tip_jacobian"]
