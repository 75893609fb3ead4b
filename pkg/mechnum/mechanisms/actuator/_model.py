"""The actuator mechanism's parameters: geometry, masses, inertias and stroke law.

:class:`Actuator` holds them (SI units); :data:`ANNEX` is the mechanism as the study's Annex 3.2
prints it. The centroidal moments of inertia are derived from each link's own mass unless given,
so that a mechanism built with another mass gets its inertia from it.
"""

from dataclasses import dataclass, field, fields

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError

G_MATHCAD = 9.80665
"""Standard gravity (m/s**2), Mathcad's built-in ``g``, the value the annex uses."""

# Lengths and masses must be positive; these may be zero (a pivot on an axis, a centre of mass
# at the piston, a cylinder at rest, a lower stop at O2, a thin piston).
_MAY_BE_ZERO = ("o2", "o4", "li", "e", "g3", "amplitude")


@dataclass(frozen=True)
class Actuator:
    """The actuator mechanism: its geometry, masses, inertias and stroke law (SI units), the
    first argument of every function of the package.

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
        If a length, mass or frequency is not positive, an inertia is negative, the pivots
        coincide, or the cylinder's upper end ``ls`` is not above its lower stop ``li``.

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
        if not self.ls > self.li:
            raise GeometryError(f"the cylinder's upper end ls = {self.ls!r} m must lie above "
                                f"its lower stop li = {self.li!r} m")
        bars = (self.m2 * (2 * self.g2) ** 2 / 12, self.m3 * self.l**2 / 12,
                self.m4 * (2 * self.g4) ** 2 / 12)
        given = (self.Ig2, self.Ig3, self.Ig4)
        object.__setattr__(self, "inertias",
                           tuple(bar if i is None else i for bar, i in zip(bars, given)))

    @property
    def d(self) -> float:
        """Distance between the ground pivots ``O2`` and ``O4``."""
        return float(np.hypot(self.o2, self.o4))

    @property
    def Io2(self) -> float:
        """Moment of inertia of the barrel about ``O2``."""
        return self.inertias[0] + self.m2 * self.g2**2

    @property
    def Io4(self) -> float:
        """Moment of inertia of the rocker about ``O4``."""
        return self.inertias[2] + self.m4 * self.g4**2

    @property
    def hs(self) -> float:
        """Upper clearance of the piston at ``a0``: ``ls - e/2 - a0``."""
        return self.ls - self.e / 2 - self.a0

    @property
    def hi(self) -> float:
        """Lower clearance of the piston at ``a0``: ``a0 - e/2 - li``."""
        return self.a0 - self.e / 2 - self.li

    def stroke(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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


ANNEX = Actuator(Ig4=Actuator.g4**2 * Actuator.m2 / 3)  # the annex: m2 where m4 belongs
"""The mechanism as the annex prints it: ``I_G4 := g4**2 m2 / 3``, with the barrel's mass."""


def checked(mech: object) -> Actuator:
    """``mech`` if it is an :class:`Actuator`; else :class:`ValueError` naming it.

    Examples
    --------
    >>> checked(ANNEX).m4
    1.0
    """
    return _validate.instance(mech, Actuator, "mech", "an Actuator")
