"""The hydraulic-actuator mechanism of seed 004: the force the cylinder must exert.

The annex (a Mathcad sheet) drives a three-link mechanism with a hydraulic cylinder. The barrel
(link 2) turns about the ground pivot ``O2``; the rod (link 3) slides in it and turns with it; the
rod's end ``A`` is pinned to the rocker (link 4), which turns about ``O4``. With ``O2`` at the
origin and ``O4 = (-o2, o4)``, the pivots are ``d = sqrt(o2**2 + o4**2)`` apart and the loop closes
when

.. math:: (a + l)\\,e^{i\\theta_2} = O_4 + b\\,e^{i\\theta_4},

where ``a(t) = 0.6 + 0.02 sin(2 pi t)`` m is the cylinder's stroke, the one degree of freedom. The
annex solves the loop from the triangle ``O2 O4 A`` (:func:`positions`); :func:`solve_loop`
solves the same two equations by :func:`mechnum.newton.solve`.

Every angular velocity is proportional to the stroke rate: ``omega_j = k_j(a) a_dot``, where
``k_j = d theta_j / d a`` is a *velocity coefficient*, and ``eps_j = k_j a_ddot + k_j' a_dot**2``.
With ``delta = theta_2 - theta_4`` the loop gives exactly

    ``k4 = 1 / (b sin delta)``,  ``k2 = cos delta / ((a + l) sin delta)``;

the annex uses instead ``k4 = sin delta / b`` and ``k2 = sin delta cos delta / (a + l)``, which
agree with the exact ones only where ``delta = pi/2`` (``model="annex"`` in :func:`kinematics`).

The force ``Q`` along the cylinder follows by two routes, both written without dividing by the
stroke rate (the annex's virtual-power formula is 0/0 when the actuator is at rest):

* virtual power (:func:`virtual_power_force`): ``Q = sum_i m_i a_Gi . J_i + I_Gi eps_i k_i
  + m_i g J_iy``, where ``J_i = v_Gi / a_dot`` is the velocity coefficient of the centre of mass;
* Lagrange (:func:`lagrange_force`): ``Q = M(a) a_ddot + M'(a) a_dot**2 / 2 + V'(a)``, with the
  generalised mass ``M = (I_O2 + m3 (a + g3)**2 + I_G3) k2**2 + m3 + I_O4 k4**2``.

With consistent velocity coefficients (exact, or the annex's with their own derivatives) the two
routes agree to round-off. The annex's printed Lagrange formula does not: its rod gravity term has
``cos(2 delta) / (a + l)`` where ``k2`` belongs, which is the whole of the 0.0132088 N it reports
as the routes' numerical error (``annex_slip=True`` in :func:`lagrange_force` reproduces it).

The parameters are those the annex prints (:data:`ANNEX`), suspicious ones included: the rocker's
centroidal inertia ``I_G4 = g4**2 m2 / 3`` uses the barrel's mass ``m2`` (printed ``I_O4 = 0.96``
confirms it), and its centre of mass lies ``g4 = 0.6`` m from ``O4`` though the crank ``b`` is
0.25 m long. Gravity is Mathcad's built-in ``g = 9.80665`` m/s**2, the only value that reproduces
the printed ``Q(0) = 43.14926`` N.
"""

from dataclasses import dataclass, fields

import numpy as np

from mechnum.errors import GeometryError, SingularJacobianError, UnreachablePoseError
from mechnum.newton import solve

G_MATHCAD = 9.80665
"""Standard gravity (m/s**2), Mathcad's built-in ``g``, the value the annex uses."""

_MODELS = ("exact", "annex")


@dataclass(frozen=True)
class Actuator:
    """Geometry, masses, inertias and stroke law of the actuator mechanism (SI units).

    Attributes
    ----------
    o4, o2 : float
        Vertical and horizontal offsets of the rocker pivot: ``O4 = (-o2, o4)``, ``O2 = (0, 0)``.
    b : float
        Rocker crank ``O4 A``.
    l : float
        Distance ``O2 A`` minus the stroke: ``|O2 A| = a + l``.
    g2, g3, g4 : float
        Centres of mass: ``G2`` at ``g2`` from ``O2`` along the barrel, ``G3`` at ``a + g3``
        from ``O2`` along the rod, ``G4`` at ``g4`` from ``O4`` along the rocker.
    m2, m3, m4 : float
        Masses of barrel, rod and rocker.
    Ig2, Ig3, Ig4 : float
        Centroidal moments of inertia, by the annex's formulas (``Ig4`` with ``m2``, as printed).
    a0, amplitude, frequency : float
        The stroke law ``a(t) = a0 + amplitude sin(2 pi frequency t)``.

    Examples
    --------
    >>> mech = Actuator()
    >>> round(mech.d, 3), round(mech.Io2, 3), round(mech.Io4, 3)
    (1.031, 0.6, 0.96)
    """

    o4: float = 1.0
    o2: float = 0.25
    b: float = 0.25
    l: float = 0.4
    g2: float = 0.3
    g3: float = 0.2
    g4: float = 0.6
    m2: float = 5.0
    m3: float = 2.0
    m4: float = 1.0
    Ig2: float = 0.3**2 * 5.0 / 3
    Ig3: float = 0.4**2 * 2.0 / 12
    Ig4: float = 0.6**2 * 5.0 / 3
    a0: float = 0.6
    amplitude: float = 0.02
    frequency: float = 1.0

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name)
            if not np.isfinite(value):
                raise ValueError(f"{f.name} must be finite, got {value!r}")
            if value < 0 or (value == 0 and f.name not in ("o2", "o4", "g3", "amplitude")):
                raise GeometryError(f"{f.name} must be positive, got {value!r}")
        if self.d == 0:
            raise GeometryError("the pivots O2 and O4 coincide (o2 = o4 = 0)")

    @property
    def d(self):
        """Distance between the ground pivots ``O2`` and ``O4``."""
        return float(np.hypot(self.o2, self.o4))

    @property
    def Io2(self):
        """Moment of inertia of the barrel about ``O2``."""
        return self.Ig2 + self.m2 * self.g2**2

    @property
    def Io4(self):
        """Moment of inertia of the rocker about ``O4``."""
        return self.Ig4 + self.m4 * self.g4**2

    def stroke(self, t):
        """The stroke ``a(t)`` and its first two time derivatives.

        Parameters
        ----------
        t : array_like
            Times (s); must be finite.

        Returns
        -------
        a, a_dot, a_ddot : ndarray
            Stroke (m), its rate (m/s) and acceleration (m/s**2), of ``t``'s shape.

        Examples
        --------
        >>> a, v, acc = Actuator().stroke(0.0)
        >>> float(a), round(float(v), 4), float(acc)
        (0.6, 0.1257, -0.0)
        """
        t = _finite(t, "t")
        w = 2 * np.pi * self.frequency
        s, c = np.sin(w * t), np.cos(w * t)
        return self.a0 + self.amplitude * s, self.amplitude * w * c, -self.amplitude * w**2 * s


ANNEX = Actuator()
"""The mechanism as the annex prints it."""


@dataclass(frozen=True)
class Kinematics:
    """Positions and velocity coefficients of links 2 (and 3) and 4 at a set of instants.

    Attributes
    ----------
    mech : Actuator
        The mechanism.
    model : {"exact", "annex"}
        Which velocity coefficients: the loop's, or the annex's approximations.
    a, a_dot, a_ddot : ndarray
        Stroke, rate and acceleration.
    theta2, theta4 : ndarray
        Link angles (rad) from the x axis.
    k2, k4 : ndarray
        Velocity coefficients ``d theta / d a`` (rad/m).
    dk2, dk4 : ndarray
        Their derivatives along the motion, ``d k / d a`` (rad/m**2).
    """

    mech: Actuator
    model: str
    a: np.ndarray
    a_dot: np.ndarray
    a_ddot: np.ndarray
    theta2: np.ndarray
    theta4: np.ndarray
    k2: np.ndarray
    k4: np.ndarray
    dk2: np.ndarray
    dk4: np.ndarray

    @property
    def omega2(self):
        """Angular velocity of links 2 and 3 (rad/s)."""
        return self.k2 * self.a_dot

    @property
    def omega4(self):
        """Angular velocity of link 4 (rad/s)."""
        return self.k4 * self.a_dot

    @property
    def eps2(self):
        """Angular acceleration of links 2 and 3 (rad/s**2)."""
        return self.k2 * self.a_ddot + self.dk2 * self.a_dot**2

    @property
    def eps4(self):
        """Angular acceleration of link 4 (rad/s**2)."""
        return self.k4 * self.a_ddot + self.dk4 * self.a_dot**2


def _finite(x, name):
    x = np.asarray(x, dtype=float)
    if not np.all(np.isfinite(x)):
        raise ValueError(f"{name} must be finite, got {x!r}")
    return x


def positions(a, mech=ANNEX):
    """Link angles from the triangle of the pivots, as the annex computes them.

    ``phi`` (at ``O4``) and ``psi`` (at ``O2``) follow from the law of cosines in the triangle
    of sides ``d``, ``b`` and ``a + l``; then ``theta4 = phi - beta`` and
    ``theta2 = pi - beta - psi`` with ``beta = atan(o4 / o2)``.

    Parameters
    ----------
    a : array_like
        Strokes (m); must be finite.
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    theta2, theta4 : ndarray
        Angles (rad) of the cylinder and of the rocker.

    Raises
    ------
    UnreachablePoseError
        If ``a + l`` is outside ``[d - b, d + b]``: the loop cannot close.

    Examples
    --------
    >>> th2, th4 = positions(0.6)
    >>> round(float(th2), 6), round(float(th4), 6)
    (1.570796, 0.0)
    """
    L = _finite(a, "a") + mech.l
    d, b = mech.d, mech.b
    cos_phi = (d**2 + b**2 - L**2) / (2 * d * b)
    cos_psi = (d**2 + L**2 - b**2) / (2 * d * L)
    bad = (np.abs(cos_phi) > 1) | (np.abs(cos_psi) > 1) | (L <= 0)
    if np.any(bad):
        first = np.flatnonzero(np.atleast_1d(bad))[0]
        raise UnreachablePoseError(
            f"the loop cannot close: a + l = {np.atleast_1d(L)[first]:.6g} m is outside "
            f"[d - b, d + b] = [{d - b:.6g}, {d + b:.6g}] m")
    beta = np.arctan2(mech.o4, mech.o2)
    return np.pi - beta - np.arccos(cos_psi), np.arccos(cos_phi) - beta


def loop_residual(x, a, mech=ANNEX):
    """The two loop equations ``(a + l) e^{i theta2} - O4 - b e^{i theta4} = 0``.

    Parameters
    ----------
    x : array_like, shape (2,)
        ``(theta2, theta4)`` in radians.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    ndarray, shape (2,)
        The x and y components of the loop's closure error (m).

    Examples
    --------
    >>> np.round(loop_residual([np.pi / 2, 0.0], 0.6), 12) + 0.0
    array([0., 0.])
    """
    th2, th4 = x
    L = a + mech.l
    return np.array([L * np.cos(th2) + mech.o2 - mech.b * np.cos(th4),
                     L * np.sin(th2) - mech.o4 - mech.b * np.sin(th4)])


def loop_jacobian(x, a, mech=ANNEX):
    """Jacobian of :func:`loop_residual` with respect to ``(theta2, theta4)``.

    Its determinant is ``(a + l) b sin(theta2 - theta4)``: it vanishes at the dead points,
    where the cylinder and the crank are aligned.

    Examples
    --------
    >>> round(float(np.linalg.det(loop_jacobian([np.pi / 2, 0.0], 0.6))), 12)
    0.25
    """
    th2, th4 = x
    L = a + mech.l
    return np.array([[-L * np.sin(th2), mech.b * np.sin(th4)],
                     [L * np.cos(th2), -mech.b * np.cos(th4)]])


def solve_loop(a, mech=ANNEX, x0=(np.pi / 2, 0.0), **options):
    """Solve the loop equations for one stroke by Newton-Raphson.

    Parameters
    ----------
    a : float
        Stroke (m); must be finite.
    mech : Actuator, optional
        The mechanism.
    x0 : array_like, shape (2,), optional
        Initial guess ``(theta2, theta4)``; its branch is the one found.
    **options
        Passed to :func:`mechnum.newton.solve` (``tol``, ``maxiter``, ``criterion``, ``norm``).

    Returns
    -------
    mechnum.newton.NewtonResult
        ``x`` is ``(theta2, theta4)``.

    Raises
    ------
    SingularJacobianError, ConvergenceError
        From :func:`mechnum.newton.solve` (a dead point, a pose out of reach).

    Examples
    --------
    >>> res = solve_loop(0.62, x0=(1.5, 0.0))
    >>> np.round(res.x, 9).tolist() == np.round(positions(0.62), 9).tolist()
    True
    """
    a = float(_finite(a, "a"))
    return solve(lambda x: loop_residual(x, a, mech), x0,
                 lambda x: loop_jacobian(x, a, mech), **options)


def kinematics(t, mech=ANNEX, model="exact"):
    """Positions, velocity coefficients and their derivatives at the instants ``t``.

    Parameters
    ----------
    t : array_like
        Times (s); must be finite.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        ``"exact"``: ``k4 = 1/(b sin delta)``, ``k2 = cos delta / ((a+l) sin delta)``;
        ``"annex"``: the annex's ``k4 = sin delta / b``, ``k2 = sin delta cos delta / (a+l)``.
        In both, ``dk/da`` is the exact derivative of the chosen ``k`` with
        ``d delta / d a = k2 - k4``.

    Returns
    -------
    Kinematics

    Raises
    ------
    ValueError
        If ``t`` is not finite or ``model`` is unknown.
    UnreachablePoseError
        If the loop cannot close at some instant.
    SingularJacobianError
        If ``model="exact"`` and some instant is a dead point (``sin delta = 0``).

    Examples
    --------
    >>> kin = kinematics(0.0)
    >>> round(float(kin.omega2), 6) + 0.0, round(float(kin.omega4), 6)
    (0.0, 0.502655)
    """
    if model not in _MODELS:
        raise ValueError(f"model must be one of {_MODELS}, got {model!r}")
    a, a_dot, a_ddot = mech.stroke(t)
    th2, th4 = positions(a, mech)
    L, b = a + mech.l, mech.b
    s, c = np.sin(th2 - th4), np.cos(th2 - th4)
    if model == "exact":
        if np.any(np.abs(s) < 1e-12):
            raise SingularJacobianError(
                f"dead point: sin(theta2 - theta4) = {np.min(np.abs(s)):.3g}, the cylinder "
                "and the crank are aligned and the velocity coefficients are infinite")
        k2, k4 = c / (L * s), 1 / (b * s)
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L - ddelta / (L * s**2), -c * ddelta / (b * s**2)
    else:
        k2, k4 = s * c / L, s / b
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L + (c**2 - s**2) * ddelta / L, c * ddelta / b
    return Kinematics(mech, model, a, a_dot, a_ddot, th2, th4, k2, k4, dk2, dk4)


def _bodies(kin):
    """For links 2, 3, 4: mass, centroidal inertia, k, dk/da, and the centre of mass's
    velocity coefficient ``J = v_G / a_dot`` and its derivative ``dJ/da`` (complex numbers)."""
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3 = kin.a + m.g3

    def rotating(r, k, dk, e):  # a point at fixed distance r along a link through a pivot
        return r * k * 1j * e, r * (dk * 1j - k**2) * e

    J3 = e2 + r3 * kin.k2 * 1j * e2
    dJ3 = 2 * kin.k2 * 1j * e2 + r3 * (kin.dk2 * 1j - kin.k2**2) * e2
    return [(m.m2, m.Ig2, kin.k2, kin.dk2, *rotating(m.g2, kin.k2, kin.dk2, e2)),
            (m.m3, m.Ig3, kin.k2, kin.dk2, J3, dJ3),
            (m.m4, m.Ig4, kin.k4, kin.dk4, *rotating(m.g4, kin.k4, kin.dk4, e4))]


def virtual_power_force(kin, g=G_MATHCAD):
    """Actuator force by virtual power (inverse dynamics), the annex's ``Q_di``.

    The power of the actuator, ``Q a_dot``, balances that of the inertia forces and couples and
    of gravity. Dividing every velocity by ``a_dot`` before forming the balance, as velocity
    coefficients, removes the annex's 0/0 at the instants where the actuator is at rest::

        Q = sum_i  m_i (a_Gi . J_i) + I_Gi eps_i k_i + m_i g J_iy.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Examples
    --------
    >>> round(float(virtual_power_force(kinematics(0.0))), 5)
    43.14926
    """
    g = float(_finite(g, "g"))
    q = 0.0
    for m, inertia, k, dk, J, dJ in _bodies(kin):
        acc = J * kin.a_ddot + dJ * kin.a_dot**2
        q = q + m * (acc.real * J.real + acc.imag * J.imag) + inertia * (
            k * kin.a_ddot + dk * kin.a_dot**2) * k + m * g * J.imag
    return q


def lagrange_force(kin, g=G_MATHCAD, annex_slip=False):
    """Actuator force by Lagrange's equation, the annex's ``Q_dd``.

    With the stroke ``a`` as generalised coordinate, ``T = M(a) a_dot**2 / 2`` and ``V(a)``
    give ``Q = M a_ddot + M' a_dot**2 / 2 + V'``, where::

        M  = (I_O2 + J3) k2**2 + m3 + I_O4 k4**2,        J3 = m3 (a + g3)**2 + I_G3,
        M' = 2 (I_O2 + J3) k2 k2' + 2 m3 (a + g3) k2**2 + 2 I_O4 k4 k4',
        V' = g [m2 g2 cos(theta2) k2 + m3 (sin(theta2) + (a + g3) cos(theta2) k2)
                + m4 g4 cos(theta4) k4].

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    annex_slip : bool, optional
        Reproduce the annex's slip in the rod's gravity term, which has
        ``cos(2 delta) / (a + l)`` where ``k2`` belongs.

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Examples
    --------
    >>> kin = kinematics([0.0, 0.25])
    >>> np.round(lagrange_force(kin), 5).tolist()
    [43.14926, 29.35295]
    """
    g = float(_finite(g, "g"))
    m = kin.mech
    r3 = kin.a + m.g3
    rot2 = m.Io2 + m.m3 * r3**2 + m.Ig3
    mass = rot2 * kin.k2**2 + m.m3 + m.Io4 * kin.k4**2
    dmass = 2 * (rot2 * kin.k2 * kin.dk2 + m.m3 * r3 * kin.k2**2 + m.Io4 * kin.k4 * kin.dk4)
    k_rod = np.cos(2 * (kin.theta2 - kin.theta4)) / (kin.a + m.l) if annex_slip else kin.k2
    dpot = g * (m.m2 * m.g2 * np.cos(kin.theta2) * kin.k2
                + m.m3 * (np.sin(kin.theta2) + r3 * np.cos(kin.theta2) * k_rod)
                + m.m4 * m.g4 * np.cos(kin.theta4) * kin.k4)
    return mass * kin.a_ddot + 0.5 * dmass * kin.a_dot**2 + dpot


def reproduce():
    """Every number of the annex, recomputed; keys are the registry's ``quantity`` column.

    Kinematics as the annex approximates them, ``g = 9.80665``, on the annex's grid
    ``t = 0, 0.01, ..., 1``. ``Q_dd`` is the corrected Lagrange force; the maximum difference
    between the routes is computed as the annex did, with its slip in ``Q_dd``.

    Returns
    -------
    dict[str, float]

    Examples
    --------
    >>> round(reproduce()["max |Q_dd - Q_di| (annex formulas)"], 7)
    0.0132088
    """
    mech = ANNEX
    grid = np.linspace(0.0, 1.0, 101)  # the annex's range t := 0, 0.01 .. 1
    kin = kinematics(grid, mech, "annex")
    q_di = virtual_power_force(kin)
    q_dd = lagrange_force(kin)
    slip = np.max(np.abs(lagrange_force(kin, annex_slip=True) - q_di))
    at = {t: int(round(100 * t)) for t in (0.0, 0.01, 0.25, 0.75)}
    a0 = float(kin.a[0])
    ls, li, e = 0.80, 0.40, 0.010  # the cylinder's printed lengths (input data, unused elsewhere)
    return {
        "S (annulus area)": np.pi * (0.016**2 - 0.008**2),
        "hs (upper clearance)": ls - e / 2 - a0,
        "hi (lower clearance)": a0 - e / 2 - li,
        "Io2": mech.Io2,
        "d (pivot distance)": mech.d,
        "Ig3": mech.Ig3,
        "Io4": mech.Io4,
        "vcil(0)": float(kin.a_dot[0]),
        "theta2(0)": float(kin.theta2[0]),
        "theta4(0)": float(kin.theta4[0]),
        "omega2(0)": float(kin.omega2[0]),
        "omega4(0)": float(kin.omega4[0]),
        **{f"Q_dd({t:g})": float(q_dd[i]) for t, i in at.items()},
        "Q_di(0)": float(q_di[0]),
        "Q_di(0.25)": float(q_di[at[0.25]]),
        "max |Q_dd - Q_di| (annex formulas)": float(slip),
        "relative error": float(slip) / 29,
        "min Q_di (claim: always above 29 N)": float(np.min(q_di)),
        "difference is numerical (claim)": float(np.max(np.abs(q_dd - q_di))),
    }
