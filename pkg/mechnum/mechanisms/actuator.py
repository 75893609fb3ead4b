"""The hydraulic-actuator mechanism of the study's Annex 3.2: the force the cylinder must exert.

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
The velocity coefficients of the centres of mass are Kane's *partial velocities*
(:func:`partial_velocities`).

The force ``Q`` along the cylinder is *inverse dynamics* (the force from a prescribed motion), by
three routes that share the velocity coefficients and nothing else:

* virtual power (:func:`virtual_power_force`, the annex's ``Q_di``): the accelerations of the
  centres of mass by the relative-motion formulas (centripetal, tangential, Coriolis), their
  power over the virtual motion ``delta a = 1``;
* Kane's equations (:func:`kane_force`): the accelerations by differentiating ``v = J a_dot``;
* Lagrange's equation (:func:`lagrange_force`, the annex's ``Q_dd``):
  ``Q = M(a) a_ddot + M'(a) a_dot**2 / 2 + V'(a)`` (:func:`lagrange_terms`).

With consistent velocity coefficients (exact, or the annex's with their own derivatives) the
three agree to round-off. The annex's printed Lagrange formula does not: its rod gravity term has
``cos(2 delta) / (a + l)`` where ``k2`` belongs, which is the whole of the 0.0132088 N it reports
as the routes' numerical error (``annex_slip=True`` in :func:`lagrange_force` reproduces it).
*Forward* dynamics, the motion that a given force produces, integrates Lagrange's equation by
RK4 (:func:`forward_dynamics`); :func:`energy` gives ``T + V`` for the energy balance.

The parameters are those the annex prints (:data:`ANNEX`), suspicious ones included: the rocker's
centroidal inertia ``I_G4 = g4**2 m2 / 3`` uses the barrel's mass ``m2`` (printed ``I_O4 = 0.96``
confirms it), and its centre of mass lies ``g4 = 0.6`` m from ``O4`` though the crank ``b`` is
0.25 m long. Gravity is Mathcad's built-in ``g = 9.80665`` m/s**2, the only value that reproduces
the printed ``Q(0) = 43.14926`` N.
"""

from dataclasses import dataclass, field, fields

import numpy as np

from mechnum import _validate
from mechnum.errors import GeometryError, SingularJacobianError, UnreachablePoseError
from mechnum.newton import solve
from mechnum.ode import rk4

G_MATHCAD = 9.80665
"""Standard gravity (m/s**2), Mathcad's built-in ``g``, the value the annex uses."""

_MODELS = ("exact", "annex")
# A dead point: |sin(theta2 - theta4)| below sqrt(eps). There delta comes from an arccos of an
# argument within eps of +-1, which leaves it no correct digit, and 1/sin(delta) with it.
_DEAD_POINT = np.sqrt(np.finfo(float).eps)
# Lengths and masses must be positive; these may be zero (a pivot on an axis, a centre of mass
# at the piston, a cylinder at rest, a lower stop at O2, a thin piston).
_MAY_BE_ZERO = ("o2", "o4", "li", "e", "g3", "amplitude")
# The cylinder's bore and rod radii (m), printed only inside the annulus area S.
_BORE_RADIUS, _ROD_RADIUS = 0.016, 0.008
# The annex's grid t := 0, 0.01 .. 1 (s), and the force it divides its maximum difference by to
# get a relative error: 29 N, its claimed floor of Q_di.
_ANNEX_GRID = np.linspace(0.0, 1.0, 101)
_ANNEX_FORCE_SCALE = 29.0


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
    ls, li, e : float
        The cylinder: its upper end and lower stop, at ``ls`` and ``li`` from ``O2``, and the
        piston's thickness.
    g2, g3, g4 : float
        Centres of mass: ``G2`` at ``g2`` from ``O2`` along the barrel, ``G3`` at ``a + g3``
        from ``O2`` along the rod, ``G4`` at ``g4`` from ``O4`` along the rocker.
    m2, m3, m4 : float
        Masses of barrel, rod and rocker.
    Ig2, Ig3, Ig4 : float or None
        Centroidal moments of inertia; ``None`` (the default) derives each from its link's own
        mass as a uniform bar: ``m2 (2 g2)**2 / 12``, ``m3 l**2 / 12``, ``m4 (2 g4)**2 / 12``.
    a0, amplitude, frequency : float
        The stroke law ``a(t) = a0 + amplitude sin(2 pi frequency t)``.
    inertias : tuple of float
        The centroidal moments of inertia in use, ``(I_G2, I_G3, I_G4)``: the given ones, or
        the derived ones. Computed, not an argument, so that ``dataclasses.replace(mech,
        m2=6.0)`` derives ``I_G2`` again from the new mass.

    Raises
    ------
    ValueError
        If a parameter is not a finite real number.
    GeometryError
        If a length, mass or frequency is not positive, an inertia is negative, or the
        pivots coincide.

    Examples
    --------
    >>> mech = Actuator()
    >>> round(mech.d, 3), round(mech.Io2, 3), round(mech.Io4, 3)
    (1.031, 0.6, 0.48)
    >>> round(Actuator(m2=6.0).inertias[0], 3)       # derived from the new mass
    0.18
    """

    o4: float = 1.0
    o2: float = 0.25
    b: float = 0.25
    l: float = 0.4
    ls: float = 0.80
    li: float = 0.40
    e: float = 0.010
    g2: float = 0.3
    g3: float = 0.2
    g4: float = 0.6
    m2: float = 5.0
    m3: float = 2.0
    m4: float = 1.0
    Ig2: float | None = None
    Ig3: float | None = None
    Ig4: float | None = None
    a0: float = 0.6
    amplitude: float = 0.02
    frequency: float = 1.0
    inertias: tuple = field(init=False, repr=False)

    def __post_init__(self):
        for f in fields(self):
            value = getattr(self, f.name) if f.init else None
            if value is None:
                continue
            value = _validate.scalar(value, f.name)
            object.__setattr__(self, f.name, value)
            if f.name == "a0":  # a stroke: any real number (positions() checks its reach)
                continue
            if f.name in _MAY_BE_ZERO or f.name.startswith("Ig"):
                if value < 0:
                    raise GeometryError(f"{f.name} must be non-negative, got {value!r}")
            elif not value > 0:
                raise GeometryError(f"{f.name} must be positive, got {value!r}")
        if self.d == 0:
            raise GeometryError("the pivots O2 and O4 coincide (o2 = o4 = 0)")
        bars = (self.m2 * (2 * self.g2) ** 2 / 12, self.m3 * self.l**2 / 12,
                self.m4 * (2 * self.g4) ** 2 / 12)
        given = (self.Ig2, self.Ig3, self.Ig4)
        object.__setattr__(self, "inertias",
                           tuple(bar if i is None else i for bar, i in zip(bars, given)))

    @property
    def d(self):
        """Distance between the ground pivots ``O2`` and ``O4``."""
        return float(np.hypot(self.o2, self.o4))

    @property
    def Io2(self):
        """Moment of inertia of the barrel about ``O2``."""
        return self.inertias[0] + self.m2 * self.g2**2

    @property
    def Io4(self):
        """Moment of inertia of the rocker about ``O4``."""
        return self.inertias[2] + self.m4 * self.g4**2

    @property
    def hs(self):
        """Upper clearance of the piston at ``a0``: ``ls - e/2 - a0``."""
        return self.ls - self.e / 2 - self.a0

    @property
    def hi(self):
        """Lower clearance of the piston at ``a0``: ``a0 - e/2 - li``."""
        return self.a0 - self.e / 2 - self.li

    def stroke(self, t):
        """The stroke ``a(t)`` and its first two time derivatives.

        Parameters
        ----------
        t : array_like
            Times (s); must be finite and real.

        Returns
        -------
        a, a_dot, a_ddot : ndarray
            Stroke (m), its rate (m/s) and acceleration (m/s**2), of ``t``'s shape.

        Examples
        --------
        >>> a, v, acc = Actuator().stroke(0.0)
        >>> float(a), round(float(v), 4), float(acc) + 0.0
        (0.6, 0.1257, 0.0)
        """
        t = _validate.array(t, "t")
        w = 2 * np.pi * self.frequency
        s, c = np.sin(w * t), np.cos(w * t)
        return self.a0 + self.amplitude * s, self.amplitude * w * c, -self.amplitude * w**2 * s


ANNEX = Actuator(Ig4=0.6**2 * 5.0 / 3)
"""The mechanism as the annex prints it: ``I_G4 := g4**2 m2 / 3``, with the barrel's mass."""


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


def _mechanism(mech):
    if not isinstance(mech, Actuator):
        raise ValueError(f"mech must be an Actuator, got {_validate._shown(mech)}")
    return mech


def _kinematics(kin):
    if not isinstance(kin, Kinematics):
        raise ValueError(f"kin must be the Kinematics of kinematics(), "
                         f"got {_validate._shown(kin)}")
    return kin


def _pairs(x):
    """``(theta2, theta4)`` from an array of shape (..., 2), checked."""
    x = _validate.array(x, "x", ndim=range(1, 33))
    if x.shape[-1] != 2:
        raise ValueError(f"x must have shape (..., 2): pairs (theta2, theta4), "
                         f"got shape {x.shape}")
    return x[..., 0], x[..., 1]


def positions(a, mech=ANNEX):
    """Link angles from the triangle of the pivots, as the annex computes them.

    ``phi`` (at ``O4``) and ``psi`` (at ``O2``) follow from the law of cosines in the triangle
    of sides ``d``, ``b`` and ``a + l``; then ``theta4 = phi - beta`` and
    ``theta2 = pi - beta - psi`` with ``beta = atan(o4 / o2)``.

    Parameters
    ----------
    a : array_like
        Strokes (m); must be finite and real. An empty array is valid.
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    theta2, theta4 : ndarray
        Angles (rad) of the cylinder and of the rocker, of ``a``'s shape.

    Raises
    ------
    ValueError
        If ``a`` is not finite and real, or ``mech`` is not an :class:`Actuator`.
    UnreachablePoseError
        If ``a + l`` is outside ``[|d - b|, d + b]``: the loop cannot close.

    Examples
    --------
    >>> th2, th4 = positions(0.6)
    >>> round(float(th2), 6), round(float(th4), 6)
    (1.570796, 0.0)
    """
    return _positions(_validate.array(a, "a"), _mechanism(mech))


def _positions(a, mech):
    """:func:`positions` of checked input."""
    L = a + mech.l
    d, b = mech.d, mech.b
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_phi = (d**2 + b**2 - L**2) / (2 * d * b)
        cos_psi = (d**2 + L**2 - b**2) / (2 * d * L)
    bad = ~(np.abs(cos_phi) <= 1) | ~(np.abs(cos_psi) <= 1) | (L <= 0)
    if np.any(bad):
        first = np.flatnonzero(np.ravel(bad))[0]
        raise UnreachablePoseError(
            f"the loop cannot close: a + l = {np.ravel(L)[first]:.6g} m is outside "
            f"[|d - b|, d + b] = [{abs(d - b):.6g}, {d + b:.6g}] m")
    beta = np.arctan2(mech.o4, mech.o2)
    return np.pi - beta - np.arccos(cos_psi), np.arccos(cos_phi) - beta


def loop_residual(x, a, mech=ANNEX):
    """The two loop equations ``(a + l) e^{i theta2} - O4 - b e^{i theta4} = 0``.

    Parameters
    ----------
    x : array_like, shape (..., 2)
        ``(theta2, theta4)`` in radians, or a batch of such pairs.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    ndarray, shape (..., 2)
        The x and y components of the loop's closure error (m).

    Raises
    ------
    ValueError
        If ``x`` is not finite and real with a last axis of length 2, ``a`` not a finite real
        number, or ``mech`` not an :class:`Actuator`.

    Examples
    --------
    >>> np.round(loop_residual([np.pi / 2, 0.0], 0.6), 12) + 0.0
    array([0., 0.])
    """
    th2, th4 = _pairs(x)
    mech = _mechanism(mech)
    L = _validate.scalar(a, "a") + mech.l
    return np.stack([L * np.cos(th2) + mech.o2 - mech.b * np.cos(th4),
                     L * np.sin(th2) - mech.o4 - mech.b * np.sin(th4)], axis=-1)


def loop_jacobian(x, a, mech=ANNEX):
    """Jacobian of :func:`loop_residual` with respect to ``(theta2, theta4)``.

    Its determinant is ``(a + l) b sin(theta2 - theta4)``: it vanishes at the dead points,
    where the cylinder and the crank are aligned, and at every guess with ``theta2 = theta4``.

    Parameters
    ----------
    x : array_like, shape (..., 2)
        ``(theta2, theta4)`` in radians, or a batch of such pairs.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.

    Returns
    -------
    ndarray, shape (..., 2, 2)

    Raises
    ------
    ValueError
        As :func:`loop_residual`.

    Examples
    --------
    >>> round(float(np.linalg.det(loop_jacobian([np.pi / 2, 0.0], 0.6))), 12)
    0.25
    """
    th2, th4 = _pairs(x)
    mech = _mechanism(mech)
    L = _validate.scalar(a, "a") + mech.l
    rows = [np.stack([-L * np.sin(th2), mech.b * np.sin(th4)], axis=-1),
            np.stack([L * np.cos(th2), -mech.b * np.cos(th4)], axis=-1)]
    return np.stack(rows, axis=-2)


def solve_loop(a, mech=ANNEX, x0=(np.pi / 2, 0.0), **options):
    """Solve the loop equations for one stroke by Newton-Raphson.

    Parameters
    ----------
    a : float
        Stroke (m); must be finite and real.
    mech : Actuator, optional
        The mechanism.
    x0 : array_like, shape (2,), optional
        Initial guess ``(theta2, theta4)``; its branch is the one found.
    **options
        Passed to :func:`mechnum.newton.solve` (``tol``, ``maxiter``, ``criterion``, ``norm``,
        ``damping``).

    Returns
    -------
    mechnum.newton.NewtonResult
        ``x`` is ``(theta2, theta4)``.

    Raises
    ------
    ValueError
        If ``a`` or ``x0`` are not finite and real, or an option is invalid.
    SingularJacobianError, ConvergenceError
        From :func:`mechnum.newton.solve`: a guess with ``theta2 = theta4`` (singular Jacobian
        at the start), a pose out of reach (no convergence).

    Examples
    --------
    >>> res = solve_loop(0.62, x0=(1.5, 0.0))
    >>> np.round(res.x, 9).tolist() == np.round(positions(0.62), 9).tolist()
    True
    """
    a = _validate.scalar(a, "a")
    mech = _mechanism(mech)
    x0 = _validate.array(x0, "x0", shape=(2,))
    return solve(lambda x: loop_residual(x, a, mech), x0,
                 lambda x: loop_jacobian(x, a, mech), **options)


def stroke_kinematics(a, a_dot=0.0, a_ddot=0.0, mech=ANNEX, model="exact"):
    """Positions, velocity coefficients and their derivatives at given strokes and rates.

    Parameters
    ----------
    a, a_dot, a_ddot : array_like
        Stroke (m), rate (m/s) and acceleration (m/s**2); finite, real, broadcast together.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        ``"exact"``: ``k4 = 1/(b sin delta)``, ``k2 = cos delta / ((a+l) sin delta)``;
        ``"annex"``: the annex's ``k4 = sin delta / b``, ``k2 = sin delta cos delta / (a+l)``.
        In both, ``dk/da`` is the derivative of the chosen ``k`` with
        ``d delta / d a = k2 - k4`` of the same model (the annex's accelerations follow its
        own velocities, so its model is consistent, though not the mechanism's).

    Returns
    -------
    Kinematics

    Raises
    ------
    ValueError
        If an input is not finite and real, the shapes do not broadcast, or ``model`` is
        unknown.
    UnreachablePoseError
        If the loop cannot close at some stroke.
    SingularJacobianError
        If ``model="exact"`` and some stroke is a dead point (``|sin delta| < sqrt(eps)``).

    Examples
    --------
    >>> kin = stroke_kinematics(0.6, a_dot=0.1)
    >>> round(float(kin.k4), 6), round(float(kin.omega4), 6)
    (4.0, 0.4)
    """
    model = _validate.choice(model, _MODELS, "model")
    mech = _mechanism(mech)
    a, a_dot, a_ddot = (_validate.array(a, "a"), _validate.array(a_dot, "a_dot"),
                        _validate.array(a_ddot, "a_ddot"))
    try:
        a, a_dot, a_ddot = np.broadcast_arrays(a, a_dot, a_ddot)
    except ValueError as error:
        raise ValueError(f"a, a_dot and a_ddot must broadcast together: {error}") from None
    return _stroke_kinematics(a, a_dot, a_ddot, mech, model)


def _stroke_kinematics(a, a_dot, a_ddot, mech, model):
    """:func:`stroke_kinematics` of checked input."""
    th2, th4 = _positions(a, mech)
    L, b = a + mech.l, mech.b
    s, c = np.sin(th2 - th4), np.cos(th2 - th4)
    if model == "exact":
        if np.any(np.abs(s) < _DEAD_POINT):
            raise SingularJacobianError(
                f"dead point: |sin(theta2 - theta4)| = {np.min(np.abs(s)):.3g}, the cylinder "
                "and the crank are aligned and the velocity coefficients are infinite")
        k2, k4 = c / (L * s), 1 / (b * s)
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L - ddelta / (L * s**2), -c * ddelta / (b * s**2)
    else:
        k2, k4 = s * c / L, s / b
        ddelta = k2 - k4
        dk2, dk4 = -k2 / L + (c**2 - s**2) * ddelta / L, c * ddelta / b
    return Kinematics(mech, model, a, a_dot, a_ddot, th2, th4, k2, k4, dk2, dk4)


def kinematics(t, mech=ANNEX, model="exact"):
    """Positions, velocity coefficients and their derivatives at the instants ``t``.

    The stroke, its rate and acceleration follow :meth:`Actuator.stroke`; the rest is
    :func:`stroke_kinematics`.

    Parameters
    ----------
    t : array_like
        Times (s); must be finite and real. An empty array is valid.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        As in :func:`stroke_kinematics`.

    Returns
    -------
    Kinematics

    Raises
    ------
    ValueError, UnreachablePoseError, SingularJacobianError
        As :func:`stroke_kinematics`.

    Examples
    --------
    >>> kin = kinematics(0.0)
    >>> round(float(kin.omega2), 6) + 0.0, round(float(kin.omega4), 6)
    (0.0, 0.502655)
    """
    model = _validate.choice(model, _MODELS, "model")
    return _stroke_kinematics(*_mechanism(mech).stroke(t), mech, model)


@dataclass(frozen=True)
class PartialVelocities:
    """Kane's partial velocities of the three links for the generalised speed ``a_dot``.

    Plane vectors are complex numbers ``x + i y``; the first axis runs over links 2, 3, 4.

    Attributes
    ----------
    v : ndarray of complex, shape (3,) + kin.a.shape
        ``d v_G / d a_dot``: the velocity coefficient of each centre of mass (m/s per m/s).
    omega : ndarray, shape (3,) + kin.a.shape
        ``d omega / d a_dot``: ``k2, k2, k4`` (rad/m).
    dv : ndarray of complex, shape (3,) + kin.a.shape
        ``d v / d a`` (1/m): the acceleration of ``G`` is ``v a_ddot + dv a_dot**2``.
    domega : ndarray, shape (3,) + kin.a.shape
        ``d omega / d a``: ``k2', k2', k4'`` (rad/m**2).
    """

    v: np.ndarray
    omega: np.ndarray
    dv: np.ndarray
    domega: np.ndarray


def partial_velocities(kin):
    """Kane's partial velocities: the velocity coefficients of the centres of mass.

    With the stroke rate as generalised speed, every velocity is linear in it, ``v_G = J a_dot``
    and ``omega = k a_dot``; ``J`` and ``k`` are the partial velocities:

    * ``J2 = i g2 k2 e2``, ``J3 = e2 + i (a + g3) k2 e2``, ``J4 = i g4 k4 e4``, with
      ``e_j = exp(i theta_j)``;
    * their derivatives along the motion, ``dJ/da``, e.g. ``dJ2/da = g2 (i k2' - k2**2) e2``.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.

    Returns
    -------
    PartialVelocities

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`.

    Examples
    --------
    >>> pv = partial_velocities(kinematics(0.0))
    >>> (np.round(pv.v, 6) + 0.0).tolist()   # G2 at rest; G3 up the cylinder; G4 up, g4 k4
    [0j, 1j, 2.4j]
    """
    kin = _kinematics(kin)
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3 = kin.a + m.g3
    turn2, turn4 = 1j * kin.dk2 - kin.k2**2, 1j * kin.dk4 - kin.k4**2
    v = np.array([1j * m.g2 * kin.k2 * e2, (1 + 1j * r3 * kin.k2) * e2, 1j * m.g4 * kin.k4 * e4])
    dv = np.array([m.g2 * turn2 * e2, (2j * kin.k2 + r3 * turn2) * e2, m.g4 * turn4 * e4])
    return PartialVelocities(v, np.array([kin.k2, kin.k2, kin.k4]), dv,
                             np.array([kin.dk2, kin.dk2, kin.dk4]))


def _per_link(values, kin):
    """The three links' constants shaped to broadcast against arrays of shape (3,) + a.shape."""
    return np.reshape(values, (3,) + (1,) * kin.a.ndim)


def kane_force(kin, g=G_MATHCAD):
    """Actuator force by Kane's equations.

    Kane's equation for the generalised speed ``a_dot`` is ``F + F* = 0``: the generalised active
    force ``F = Q - g sum_i m_i Im(J_i)`` (the cylinder's pair of forces contributes ``Q``, since
    the rod's partial velocity relative to the barrel is the unit axis) and the generalised
    inertia force ``F* = -sum_i m_i a_Gi . J_i + I_Gi eps_i k_i``, with the accelerations from
    differentiating ``v_G = J a_dot``: ``a_G = J a_ddot + (dJ/da) a_dot**2``
    (:func:`partial_velocities`).

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

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics` or ``g`` is not finite and real.

    Examples
    --------
    >>> round(float(kane_force(kinematics(0.0))), 5)
    43.14926
    """
    kin, g = _kinematics(kin), _validate.scalar(g, "g")
    pv = partial_velocities(kin)
    mass = _per_link([kin.mech.m2, kin.mech.m3, kin.mech.m4], kin)
    inertia = _per_link(kin.mech.inertias, kin)
    acc = pv.v * kin.a_ddot + pv.dv * kin.a_dot**2
    alpha = pv.omega * kin.a_ddot + pv.domega * kin.a_dot**2
    dot = acc.real * pv.v.real + acc.imag * pv.v.imag  # a_G . J
    inertia_force = mass * dot + inertia * alpha * pv.omega
    return np.sum(inertia_force + mass * g * pv.v.imag, axis=0)


def virtual_power_force(kin, g=G_MATHCAD, divide_by_rate=False):
    """Actuator force by virtual power, the annex's ``Q_di``.

    The accelerations of the centres of mass follow the relative-motion formulas, as the annex
    writes them: ``a_G2 = g2 (i eps2 - omega2**2) e2``, ``a_G4 = g4 (i eps4 - omega4**2) e4``,
    and for the rod's centre, sliding at ``r3 = a + g3`` along the turning barrel,
    ``a_G3 = (a_ddot - r3 omega2**2 + i (r3 eps2 + 2 omega2 a_dot)) e2`` (the last term is
    Coriolis's). The power of the actuator, of the inertia forces and couples and of gravity
    vanishes for every virtual motion the mechanism allows; for the virtual motion ``delta a = 1``
    the virtual velocities are the velocity coefficients, and::

        Q = sum_i  m_i (a_Gi . J_i) + I_Gi eps_i k_i + m_i g J_iy.

    The annex takes the actual motion instead and divides its power by ``a_dot``, which is 0/0
    where the actuator is at rest (``divide_by_rate=True``).

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    divide_by_rate : bool, optional
        Evaluate the annex's form literally: the power along the actual motion divided by the
        stroke rate. The result is NaN where the rate is exactly zero.

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`, ``g`` is not finite and real, or
        ``divide_by_rate`` is not a bool.

    Examples
    --------
    >>> round(float(virtual_power_force(kinematics(0.0))), 5)
    43.14926
    >>> kin = kinematics(0.25)                 # at rest: Mathcad's cos(pi/2) is not 0 either
    >>> float(kin.a_dot) != 0, round(float(virtual_power_force(kin, divide_by_rate=True)), 5)
    (True, 29.35295)
    """
    kin, g = _kinematics(kin), _validate.scalar(g, "g")
    _validate.choice(divide_by_rate, (True, False), "divide_by_rate")
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    w2, w4, eps2, eps4, r3 = kin.omega2, kin.omega4, kin.eps2, kin.eps4, kin.a + m.g3
    acc = np.array([m.g2 * (1j * eps2 - w2**2) * e2,
                    (kin.a_ddot - r3 * w2**2 + 1j * (r3 * eps2 + 2 * w2 * kin.a_dot)) * e2,
                    m.g4 * (1j * eps4 - w4**2) * e4])
    alpha = np.array([eps2, eps2, eps4])
    if divide_by_rate:  # the actual velocities, whose power is divided by a_dot
        rate, w, rod = kin.a_dot, np.array([w2, w2, w4]), kin.a_dot
    else:  # the virtual motion delta a = 1: the velocity coefficients
        rate, w, rod = 1.0, np.array([kin.k2, kin.k2, kin.k4]), 1.0
    v = np.array([1j * m.g2 * w[0] * e2, (rod + 1j * r3 * w[1]) * e2, 1j * m.g4 * w[2] * e4])
    mass, inertia = _per_link([m.m2, m.m3, m.m4], kin), _per_link(m.inertias, kin)
    power = np.sum(mass * (acc.real * v.real + acc.imag * v.imag) + inertia * alpha * w
                   + mass * g * v.imag, axis=0)
    with np.errstate(invalid="ignore"):
        return power / rate


@dataclass(frozen=True)
class LagrangeTerms:
    """The terms of Lagrange's equation ``Q = M a_ddot + M' a_dot**2 / 2 + V'``.

    Attributes
    ----------
    mass : ndarray
        The generalised mass ``M(a)`` (kg).
    mass_slope : ndarray
        ``M'(a) = dM/da`` (kg/m).
    potential_slope : ndarray
        ``V'(a) = dV/da`` (N): the generalised force of gravity, with its sign reversed.
    """

    mass: np.ndarray
    mass_slope: np.ndarray
    potential_slope: np.ndarray


def lagrange_terms(kin, g=G_MATHCAD, annex_slip=False):
    """Generalised mass, its slope, and the slope of the potential, at the strokes of ``kin``.

    With the stroke ``a`` as generalised coordinate, ``T = M(a) a_dot**2 / 2``, where::

        M  = (I_O2 + J3) k2**2 + m3 + I_O4 k4**2,        J3 = m3 (a + g3)**2 + I_G3,
        M' = 2 (I_O2 + J3) k2 k2' + 2 m3 (a + g3) k2**2 + 2 I_O4 k4 k4',
        V' = g [m2 g2 cos(theta2) k2 + m3 (sin(theta2) + (a + g3) cos(theta2) k2)
                + m4 g4 cos(theta4) k4].

    None depends on the rates ``kin.a_dot``, ``kin.a_ddot``.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics` or :func:`stroke_kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    annex_slip : bool, optional
        Reproduce the annex's slip in the rod's gravity term, which has
        ``cos(2 delta) / (a + l)`` where ``k2`` belongs.

    Returns
    -------
    LagrangeTerms

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics`, ``g`` is not finite and real, or
        ``annex_slip`` is not a bool.

    Examples
    --------
    >>> terms = lagrange_terms(stroke_kinematics(0.6))      # rocker crank at right angles
    >>> round(float(terms.mass), 6), round(float(terms.potential_slope / G_MATHCAD), 6)
    (17.36, 4.4)
    """
    kin, g = _kinematics(kin), _validate.scalar(g, "g")
    return _lagrange_terms(kin, g, _validate.choice(annex_slip, (True, False), "annex_slip"))


def _lagrange_terms(kin, g, annex_slip=False):
    """:func:`lagrange_terms` of checked input."""
    m = kin.mech
    r3 = kin.a + m.g3
    rot2 = m.Io2 + m.m3 * r3**2 + m.inertias[1]
    mass = rot2 * kin.k2**2 + m.m3 + m.Io4 * kin.k4**2
    slope = 2 * (rot2 * kin.k2 * kin.dk2 + m.m3 * r3 * kin.k2**2 + m.Io4 * kin.k4 * kin.dk4)
    k_rod = np.cos(2 * (kin.theta2 - kin.theta4)) / (kin.a + m.l) if annex_slip else kin.k2
    potential = g * (m.m2 * m.g2 * np.cos(kin.theta2) * kin.k2
                     + m.m3 * (np.sin(kin.theta2) + r3 * np.cos(kin.theta2) * k_rod)
                     + m.m4 * m.g4 * np.cos(kin.theta4) * kin.k4)
    return LagrangeTerms(mass, slope, potential)


def lagrange_force(kin, g=G_MATHCAD, annex_slip=False):
    """Actuator force by Lagrange's equation, the annex's ``Q_dd``.

    ``Q = d/dt dT/da_dot - dT/da + dV/da = M a_ddot + M' a_dot**2 / 2 + V'``, with the terms of
    :func:`lagrange_terms`. The annex files this route under "Dinámica directa" (direct
    dynamics), but like ``Q_di`` it is inverse dynamics: the force from a prescribed motion.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.
    annex_slip : bool, optional
        Reproduce the annex's slip in the rod's gravity term (see :func:`lagrange_terms`).

    Returns
    -------
    ndarray
        ``Q`` (N), of the shape of ``kin.a``.

    Raises
    ------
    ValueError
        As :func:`lagrange_terms`.

    Examples
    --------
    >>> kin = kinematics([0.0, 0.25])
    >>> np.round(lagrange_force(kin), 5).tolist()
    [43.14926, 29.35295]
    """
    terms = lagrange_terms(kin, g, annex_slip)
    return terms.mass * kin.a_ddot + 0.5 * terms.mass_slope * kin.a_dot**2 + terms.potential_slope


@dataclass(frozen=True)
class Energy:
    """Kinetic and potential energy of the mechanism (J).

    Attributes
    ----------
    kinetic, potential : ndarray
        ``T`` and ``V`` (zero with every centre of mass at ``y = 0``).
    """

    kinetic: np.ndarray
    potential: np.ndarray

    @property
    def total(self):
        """``T + V`` (J)."""
        return self.kinetic + self.potential


def _centres(kin):
    """Centres of mass of links 2, 3, 4 as complex numbers, shape (3,) + kin.a.shape."""
    m = kin.mech
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    return np.array([m.g2 * e2, (kin.a + m.g3) * e2, complex(-m.o2, m.o4) + m.g4 * e4])


def energy(kin, g=G_MATHCAD):
    """Kinetic and potential energy, from the partial velocities and the positions.

    ``T = sum_i (m_i |J_i|**2 + I_Gi k_i**2) a_dot**2 / 2`` and ``V = g sum_i m_i y_Gi``.
    Only ``T`` uses the velocity coefficients: along a motion, the work of ``Q`` equals the
    change of ``T + V`` if, and only if, they are the derivatives of the positions.

    Parameters
    ----------
    kin : Kinematics
        From :func:`kinematics`.
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    Energy

    Raises
    ------
    ValueError
        If ``kin`` is not a :class:`Kinematics` or ``g`` is not finite and real.

    Examples
    --------
    >>> e = energy(kinematics(0.0))
    >>> round(float(e.kinetic), 6), round(float(e.potential), 5)
    (0.137069, 40.20726)
    """
    kin, g = _kinematics(kin), _validate.scalar(g, "g")
    pv = partial_velocities(kin)
    mass = _per_link([kin.mech.m2, kin.mech.m3, kin.mech.m4], kin)
    inertia = _per_link(kin.mech.inertias, kin)
    kinetic = 0.5 * np.sum(mass * np.abs(pv.v) ** 2 + inertia * pv.omega**2, axis=0) * kin.a_dot**2
    return Energy(kinetic, g * np.sum(mass * _centres(kin).imag, axis=0))


@dataclass(frozen=True)
class ForwardDynamics:
    """The motion that :func:`forward_dynamics` computes.

    Attributes
    ----------
    t : ndarray, shape (N,)
        The nodes (s).
    a, a_dot : ndarray, shape (N,)
        Stroke (m) and rate (m/s) at every node.
    """

    t: np.ndarray
    a: np.ndarray
    a_dot: np.ndarray


def forward_dynamics(force, t, a0, v0, mech=ANNEX, model="exact", g=G_MATHCAD):
    """The motion that a given actuator force produces, by RK4 (forward dynamics).

    Lagrange's equation solved for the acceleration,
    ``M(a) a_ddot = Q(t) - M'(a) a_dot**2 / 2 - V'(a)`` (:func:`lagrange_terms`), is integrated as
    the first-order system ``y = (a, a_dot)`` by :func:`mechnum.ode.rk4` on the nodes ``t``.

    Parameters
    ----------
    force : callable
        ``force(t) -> float``: the actuator force ``Q`` (N) at time ``t`` (s); it is called at
        the nodes and halfway between them.
    t : array_like, shape (N,)
        The nodes (s), ``N >= 2``, strictly monotone.
    a0, v0 : float
        Stroke (m) and rate (m/s) at ``t[0]``.
    mech : Actuator, optional
        The mechanism.
    model : {"exact", "annex"}, optional
        The velocity coefficients of ``M`` and ``V'`` (:func:`stroke_kinematics`).
    g : float, optional
        Gravity (m/s**2), acting along ``-y``; finite.

    Returns
    -------
    ForwardDynamics

    Raises
    ------
    ValueError
        If an input is not finite and real, ``t`` has fewer than two nodes or is not monotone,
        ``force`` is not callable or returns something other than one finite real number.
    UnreachablePoseError, SingularJacobianError
        If the motion leaves the mechanism's range or reaches a dead point.

    Examples
    --------
    The force of the prescribed stroke, applied to the mechanism, gives that stroke back:

    >>> t = np.linspace(0.0, 1.0, 101)
    >>> a0, v0, _ = ANNEX.stroke(0.0)
    >>> motion = forward_dynamics(lambda s: lagrange_force(kinematics(s)), t, a0, v0)
    >>> bool(np.max(np.abs(motion.a - ANNEX.stroke(t)[0])) < 1e-8)
    True
    """
    if not callable(force):
        raise ValueError(f"force must be a callable force(t), got {_validate._shown(force)}")
    t = _validate.array(t, "t", ndim=1)
    y0 = np.array([_validate.scalar(a0, "a0"), _validate.scalar(v0, "v0")])
    mech, g = _mechanism(mech), _validate.scalar(g, "g")
    model = _validate.choice(model, _MODELS, "model")

    def rate(time, y):
        q = _validate.scalar(force(time), "force(t)")
        terms = _lagrange_terms(_stroke_kinematics(y[0], y[1], 0.0, mech, model), g)
        acc = (q - 0.5 * terms.mass_slope * y[1] ** 2 - terms.potential_slope) / terms.mass
        return np.array([y[1], acc])

    y = rk4(rate, y0, t)
    return ForwardDynamics(t, y[:, 0], y[:, 1])


def draw(ax, a, mech=ANNEX, artists=None):
    """Draw the mechanism at the stroke ``a``, or move a drawing made before to it.

    The barrel (thick, from ``O2`` to its upper end ``ls``), the rod (from the piston to ``A``),
    the rocker (from ``O4`` through ``A`` to its centre of mass or beyond), the ground pivots and
    the centres of mass. A new drawing sets equal aspect and fits the limits; moving one keeps
    them. Labels and titles are the caller's.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where to draw.
    a : float
        Stroke (m).
    mech : Actuator, optional
        The mechanism.
    artists : dict, optional
        The artists returned by an earlier call on ``ax``: they are moved, nothing is added
        (for an animation).

    Returns
    -------
    dict
        The artists, keyed ``"barrel"``, ``"rod"``, ``"rocker"``, ``"pivots"``, ``"centres"``.

    Raises
    ------
    ValueError
        If ``a`` is not a finite real number, or ``artists`` lacks one of the keys.
    UnreachablePoseError
        If the loop cannot close at ``a``.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> parts = draw(ax, 0.6)
    >>> np.round(parts["rod"].get_xydata(), 6).tolist()      # from the piston to A
    [[0.0, 0.6], [0.0, 1.0]]
    >>> parts = draw(ax, 0.62, artists=parts)
    >>> plt.close(fig)
    """
    a = _validate.scalar(a, "a")
    mech = _mechanism(mech)
    th2, th4 = (float(x) for x in positions(a, mech))
    e2, e4 = np.exp(1j * th2), np.exp(1j * th4)
    o4 = complex(-mech.o2, mech.o4)
    points = {
        "barrel": [0.0, mech.ls * e2],
        "rod": [a * e2, (a + mech.l) * e2],
        "rocker": [o4, o4 + max(mech.b, mech.g4) * e4],
        "pivots": [0.0, o4],
        "centres": [mech.g2 * e2, (a + mech.g3) * e2, o4 + mech.g4 * e4],
    }
    new = artists is None
    if new:
        styles = {"barrel": dict(lw=9, color="tab:blue", alpha=0.5, solid_capstyle="butt",
                                 label="barrel (2)"),
                  "rod": dict(lw=3, color="tab:orange", zorder=3, label="rod (3)"),
                  "rocker": dict(lw=3, color="tab:green", label="rocker (4)"),
                  "pivots": dict(ls="none", marker="^", ms=10, color="k", label="pivots"),
                  "centres": dict(ls="none", marker="o", ms=4, color="k", zorder=4,
                                  label="centres of mass")}
        artists = {name: ax.plot([], [], **style)[0] for name, style in styles.items()}
        ax.set_aspect("equal")
    elif not isinstance(artists, dict) or set(artists) != set(points):
        raise ValueError(f"artists must be the dict that draw returned, with the keys "
                         f"{sorted(points)}, got {_validate._shown(artists)}")
    for name, ends in points.items():
        z = np.array(ends, dtype=complex)
        artists[name].set_data(z.real, z.imag)
    if new:  # fit a new drawing; a moving one keeps the limits (an animation's frame)
        ax.relim()
        ax.autoscale_view()
    return artists


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
    kin = kinematics(_ANNEX_GRID, mech, "annex")
    q_di = virtual_power_force(kin)
    q_dd = lagrange_force(kin)
    slip = float(np.max(np.abs(lagrange_force(kin, annex_slip=True) - q_di)))
    at = {t: int(np.argmin(np.abs(_ANNEX_GRID - t))) for t in (0.0, 0.01, 0.25, 0.75)}
    return {
        "S (annulus area)": np.pi * (_BORE_RADIUS**2 - _ROD_RADIUS**2),
        "hs (upper clearance)": mech.hs,
        "hi (lower clearance)": mech.hi,
        "Io2": mech.Io2,
        "d (pivot distance)": mech.d,
        "Ig3": mech.inertias[1],
        "Io4": mech.Io4,
        "vcil(0)": float(kin.a_dot[0]),
        "theta2(0)": float(kin.theta2[0]),
        "theta4(0)": float(kin.theta4[0]),
        "omega2(0)": float(kin.omega2[0]),
        "omega4(0)": float(kin.omega4[0]),
        **{f"Q_dd({t:g})": float(q_dd[i]) for t, i in at.items()},
        "Q_di(0)": float(q_di[0]),
        "Q_di(0.25)": float(q_di[at[0.25]]),
        "max |Q_dd - Q_di| (annex formulas)": slip,
        "relative error": slip / _ANNEX_FORCE_SCALE,
        "min Q_di (claim: always above 29 N)": float(np.min(q_di)),
        "difference is numerical (claim)": float(np.max(np.abs(q_dd - q_di))),
    }
