"""Jacobi's amplitude from the modulus and its complement, exact to rounding for any ``k' > 0``.

Along a clamped-pinned rod the amplitude ``phi(s) = am(F(phi1, k) + lambda s | k)`` of the study's
(86), (87), (37) and (42) gives the shape. In strong tension ``1 - k**2`` is far below the
rounding of ``k**2`` (``1e-34`` for rods of the 3PFR of Chapter 6, whose forces are ~100 times
their buckling loads), and a routine that receives the parameter ``m = k**2`` (scipy's
``ellipj``) sees ``m = 1 - 1e-16`` instead: its error grows like ``1e-16 sinh(u)`` along the rod,
up to ``1e-16 / k'``. :func:`amplitude` takes the complementary modulus
``k' = sqrt(1 - k**2)`` itself, which the regular chart (``rods``'s regular module) gives to
full precision, and runs the arithmetic-geometric mean from ``(1, k')`` (Abramowitz and Stegun
16.4; DLMF 22.20.1).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate

# The AGM's c_n falls quadratically once a_n ~ b_n; from b_0 = k' >= 1e-131 (the regular chart's
# least, q = 600) it needs at most ~log2(131 log2(10)) + 6 = 15 steps to reach round-off; it stops
# when every c_n / a_n is below AGM_TOL (the next step would change phi by ~AGM_TOL**2).
AGM_STEPS = 20
AGM_TOL = 1e-10
CONSISTENCY = 1e-12
"""Largest ``|k**2 + k'**2 - 1|`` accepted: a complement computed to full precision and a
modulus rounded from it agree to a few ulps; more is two different moduli."""


def amplitude(u: ArrayLike, k: ArrayLike, complement: ArrayLike) -> np.ndarray:
    """Jacobi's amplitude ``am(u | k)`` from ``k`` and its complement ``k' = sqrt(1 - k**2)``.

    The AGM ``a_{n+1} = (a_n + b_n) / 2``, ``b_{n+1} = sqrt(a_n b_n)``, ``c_{n+1} = (a_n - b_n) /
    2`` from ``(1, k', k)``, then ``phi_{n-1} = (phi_n + arcsin(c_n sin(phi_n) / a_n)) / 2`` from
    ``phi_N = 2**N a_N u``. Where the arcsine's argument ``x`` nears +-1 (``k -> 1`` and
    ``phi`` near an odd multiple of ``pi / 2``: a rod's straight part in tension) it is taken as
    ``atan2(|x|, sqrt((1 - |x|)(1 + |x|)))`` with ``1 - |x| = b_{n-1} / a_n + (c_n / a_n) 2
    sin(delta / 2)**2`` (``1 - c_n / a_n = b_{n-1} / a_n``, ``delta`` the distance of ``phi`` to
    the nearest odd multiple of ``pi / 2``): no cancellation, where ``arcsin`` would lose half
    the digits.

    Parameters
    ----------
    u, k, complement : array_like
        Broadcast together, finite; ``|k| <= 1`` and ``k' >= 0`` given to full precision, with
        ``k**2 + k'**2 = 1`` to :data:`CONSISTENCY` (the sign of ``k`` does not matter).

    Returns
    -------
    ndarray
        ``am(u | k)``, the broadcast shape.

    Raises
    ------
    ValueError
        If an input is not finite, out of range, or ``k`` and ``k'`` are not complements.

    Examples
    --------
    >>> from scipy.special import ellipj
    >>> u = np.linspace(-3.0, 9.0, 7)
    >>> bool(np.allclose(amplitude(u, 0.8, 0.6), ellipj(u, 0.64)[3], rtol=0, atol=1e-14))
    True
    >>> phi = amplitude(30.0, 1.0, 1e-20)       # k' -> 0: am(u) -> gd(u), cos = sech(30)
    >>> bool(abs(np.cos(phi) * np.cosh(30.0) - 1) < 1e-3)
    True
    """
    u, k, kp = (_validate.array(v, name) for v, name in ((u, "u"), (k, "k"),
                                                         (complement, "complement")))
    if np.any(np.abs(k) > 1) or np.any((kp < 0) | (kp > 1)):
        raise ValueError(f"amplitude needs |k| <= 1 and 0 <= complement <= 1, got k = "
                         f"{_validate.shown(k)}, complement = {_validate.shown(kp)}")
    if np.any(np.abs((k * k - 1.0) + kp * kp) > CONSISTENCY):
        raise ValueError(f"k and complement must satisfy k**2 + complement**2 = 1, got k = "
                         f"{_validate.shown(k)}, complement = {_validate.shown(kp)}")
    u, kp = np.broadcast_arrays(u, kp * np.ones_like(k))
    a, b = np.ones_like(u), kp.copy()
    steps = []                                   # (c_n / a_n, 1 - c_n / a_n)
    for _ in range(AGM_STEPS):
        a, b, c, previous_b = 0.5 * (a + b), np.sqrt(a * b), 0.5 * (a - b), b
        steps.append((c / a, previous_b / a))
        if np.all(c / a < AGM_TOL):
            break
    phi = 2.0 ** len(steps) * a * u
    for ratio, one_minus_ratio in steps[::-1]:
        delta = phi - (np.round(phi / np.pi - 0.5) + 0.5) * np.pi
        x = np.abs(ratio * np.sin(phi))
        one_minus_x = one_minus_ratio + 2.0 * ratio * np.sin(0.5 * delta) ** 2
        arcsin = np.sign(np.sin(phi)) * np.arctan2(x, np.sqrt(one_minus_x * (1.0 + x)))
        phi = 0.5 * (phi + arcsin)
    return phi
