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

Modules, each importing only those before it: :mod:`mechnum.rods.rod` (the rod, its equations,
the RK4 sweeps :func:`integrate` and :func:`tip_jacobian`), :mod:`mechnum.rods.jacobi` (Jacobi's
amplitude from the complementary modulus), :mod:`mechnum.rods.growing` (the growing branch in
a chart that holds every digit, behind :func:`cantilever`), :mod:`mechnum.rods.regular` (the
closed form in the regular chart ``(psi, t)``, its Jacobian and shapes),
:mod:`mechnum.rods.elliptic` (the closed form in the study's chart ``(psi, k_rel)`` and its
inverses), :mod:`mechnum.rods.pinned` (every equilibrium through a point, and what a shot rod
is), :mod:`mechnum.rods.shooting` and :mod:`mechnum.rods.multiple` (the shooting solvers,
single and multiple),
:mod:`mechnum.rods.stability` and :mod:`mechnum.rods.bodies` (the second variation),
:mod:`mechnum.rods.crossing` and :mod:`mechnum.rods.loading` (a cantilever's equilibria under a
growing dead load, for continuation); the main names are importable from :mod:`mechnum.rods`.
In a Newton loop over the rods of a mechanism, call :func:`tip_jacobian` once on the batch of
all rods: one sweep gives every tip and every ``d tip / d (m0, n_x, n_y)``, and costs little
more than one rod (the cost of a sweep is per numpy call, not per rod).
"""

from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods._apriori import chart_t_bound, pair_bound, pinned_bound, reach
from mechnum.rods._cocertificate import CoCertificate, CoVerified
from mechnum.rods._cocertificate import verify as verify_corefined
from mechnum.rods._cosearch import MAX_LIVE, CertifiedAll, CoRefined, certified_all, corefine
from mechnum.rods._index import free_index, pinned_index, proven_stability
from mechnum.rods._leaves import ChartRod
from mechnum.rods._tuples import Assembly
from mechnum.rods.certified import certify_pinned
from mechnum.rods.elliptic import (
    TWO_PI,
    EllipticRod,
    NoEquilibriumError,
    NotAnElasticaError,
    clamped_pinned,
    elliptic_k,
    elliptic_parameters,
    k_rel_for_force,
)
from mechnum.rods.growing import closed_form
from mechnum.rods.loading import DeadLoad
from mechnum.rods.multiple import shoot_pinned_multiple
from mechnum.rods.pinned import Classification, classify, pinned_equilibria
from mechnum.rods.rod import MAX_NODES, Rod, equations, integrate, rod_scales, tip_jacobian
from mechnum.rods.shooting import (
    SHOOTING_TOL,
    Shooting,
    UnresolvedRodError,
    shoot_cantilever,
    shoot_pinned,
)

__all__ = ["MAX_LIVE", "SHOOTING_TOL", "TWO_PI", "Assembly", "CertifiedAll", "ChartRod",
           "Classification", "CoCertificate", "CoRefined", "CoVerified", "DeadLoad", "EllipticRod",
           "NoEquilibriumError", "NotAnElasticaError", "Rod", "Shooting", "UnresolvedRodError",
           "cantilever", "certified_all", "certify_pinned", "chart_t_bound", "clamped_pinned",
           "classify", "corefine", "elliptic_k", "elliptic_parameters", "equations",
           "free_index", "integrate", "k_rel_for_force", "pair_bound", "pinned_bound",
           "pinned_equilibria", "pinned_index", "proven_stability", "reach", "shoot_cantilever",
           "shoot_pinned", "shoot_pinned_multiple", "tip_jacobian", "verify_corefined"]

METHODS = ("elliptic", "shooting")


def cantilever(EI: float, L: float, force: ArrayLike, method: str = "elliptic", *,
               nodes: int = 41) -> Rod:
    """A cantilever (clamped at the origin along +x) under a tip force, by either method.

    The equilibrium returned is the one that grows continuously from the unloaded rod (mode 1,
    bending towards the force), by both methods. A purely axial force (``n_y = 0``) gives the
    straight rod, the only equilibrium below the Euler load (``pi**2 EI / (4 L**2)`` in
    compression); buckled ones are :func:`clamped_pinned` with ``psi = pi``.

    The closed form is evaluated in a chart that holds every digit at every load, from
    ``1e-200`` (linear beam theory, ``v = P L**3 / (3 EI)`` to rounding) to ``P L**2 / EI``
    near ``1e5`` (see :mod:`mechnum.rods.growing`); ``nodes=2`` asks for the clamp and the
    tip only, the fastest call.

    Parameters
    ----------
    EI, L : float
        Bending stiffness (N m^2) and length (m), positive.
    force : array_like, shape (2,)
        Tip force ``(n_x, n_y)`` (N).
    method : {"elliptic", "shooting"}
        Closed form (in Carlson's symmetric integrals) or RK4 shooting
        (:func:`shoot_cantilever`, from the closed form's clamp moment).
    nodes : int, optional
        Nodes of the returned shape (and RK4 nodes for shooting),
        ``2 <= nodes <=`` :data:`~mechnum.rods.rod.MAX_NODES`.

    Returns
    -------
    Rod
        Its ``tip`` and ``tip_angle`` are the tip position and angle.

    Raises
    ------
    ValueError
        If an input is not finite or out of range, or the load is beyond the closed form's
        range in double precision.
    ConvergenceError
        If shooting fails or cannot resolve the load at these nodes
        (:class:`UnresolvedRodError`; see :func:`shoot_cantilever`).

    Examples
    --------
    >>> import numpy as np
    >>> a = cantilever(2.0, 1.5, [-0.3, 1.0], "elliptic")
    >>> b = cantilever(2.0, 1.5, [-0.3, 1.0], "shooting", nodes=801)
    >>> bool(np.abs(a.tip - b.tip).max() < 1e-11), round(float(a.tip_angle), 6)
    (True, 0.57334)
    >>> tip = cantilever(1.0, 1.0, [0.0, 1e-12], nodes=2).tip   # linear theory: P L^3 / 3 EI
    >>> bool(abs(tip[1] / (1e-12 / 3) - 1) < 1e-12)
    True
    """
    EI, L = rod_scales(EI, L, scalar=True)
    force = _validate.array(force, "force", shape=(2,))
    method = _validate.choice(method, METHODS, "method")
    nodes = _validate.maxiter(nodes, "nodes", minimum=2, maximum=MAX_NODES)
    if force[1] == 0:
        return integrate(EI, L, 0.0, force, nodes=nodes)
    if method == "shooting":
        return shoot_cantilever(EI, L, force, nodes=nodes).rod
    return closed_form(EI, L, force, nodes)
