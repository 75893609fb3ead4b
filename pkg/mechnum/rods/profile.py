"""Shapes of clamped-pinned rods in any tension: the names that Chapter 6 and the 3PFR use.

Until release 0.2 this module held its own shape of the rods of the regular chart, accurate in
strong tension (from the complementary modulus), beside :func:`mechnum.rods.regular.shape`,
which lost digits there and at ``psi = pi``. There is now one shape, accurate in any tension
and at any load: :func:`shape` is :func:`mechnum.rods.regular.shape`, and :func:`amplitude`
is :func:`mechnum.rods.jacobi.amplitude`. Both names stay valid.

Examples
--------
>>> from mechnum.rods import regular
>>> shape is regular.shape
True
"""

from mechnum.rods.jacobi import amplitude
from mechnum.rods.regular import shape

__all__ = ["amplitude", "shape"]
