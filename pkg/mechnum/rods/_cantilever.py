"""A cantilever under a tip force, by the closed form or by shooting: :func:`cantilever`."""

from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.rods._growing import growing_rod
from mechnum.rods._rod import MAX_NODES, Rod, integrate, rod_scales
from mechnum.rods._shooting import shoot_cantilever

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
    near ``1e5`` (see ``rods``'s growing module); ``nodes=2`` asks for the clamp and the
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
        ``2 <= nodes <=`` ``MAX_NODES = 100_000``.

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
    return growing_rod(EI, L, force, nodes)
