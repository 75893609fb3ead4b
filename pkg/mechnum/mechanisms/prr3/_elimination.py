"""The direct problem's equations: the study's degree-8 polynomial, and the polynomial system.

Subtracting the circle of leg 1 from those of legs 2 and 3 leaves two equations linear in
``(x, y)`` (the radical axes, the study's equations 124-125); solving them by Cramer's rule and
substituting into leg 1 gives, with ``t = tan(psi/2)``, the study's polynomial of degree 8
(:func:`polynomial`). It always has the factor ``1 + t^2`` (:func:`deflate` removes it).
:func:`equations` writes the same problem as four quadratics in ``(x, y, cos psi, sin psi)``,
the form a homotopy solves.
"""

import math

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.prr3 import _kernels as kernels
from mechnum.mechanisms.prr3._geometry import Geometry, check, resolved, vectors
from mechnum.polynomials import PolynomialSystem

_ROOT3 = math.sqrt(3.0)  # a Python float: the arithmetic on one input stays in floats
# A real solution of :func:`equations` has cos^2 + sin^2 = 1; a homotopy's end points, taken
# real below an imaginary part of 1e-7, meet it to about 1e-14. Off by more than 1e-6, the
# point is no solution, and its angle would be a silent wrong answer.
UNIT_CIRCLE_TOL = 1e-6


def _times(p, q):
    """The product of two polynomials given as lists of ascending coefficients, each a number
    or an array (arrays broadcast): plain arithmetic, as fast on Python floats as on a batch."""
    out = [0.0] * (len(p) + len(q) - 1)
    for i, p_i in enumerate(p):
        for j, q_j in enumerate(q):
            out[i + j] = out[i + j] + p_i * q_j
    return out


def _minus(p, q):
    """The difference of two polynomials of one degree, as lists of coefficients."""
    return [u - v for u, v in zip(p, q)]


def _quadratic(k_sin, k_cos, k_one):
    """``(1 + t^2) (k_sin sin psi + k_cos cos psi + k_one)`` in ``t = tan(psi/2)``:
    ``[k_one + k_cos, 2 k_sin, k_one - k_cos]``."""
    return [k_one + k_cos, 2 * k_sin, k_one - k_cos]


def _f_and_g(l1, c2x, c3x, c3y, a):
    """``(1 + t^2)`` times the study's ``f1, f2, f3, g1, g2, g3`` (eq. 126-145), quadratics in t.

    The study's constants are written with the sliders ``C2 = (c2x, 0) = (B2 - lambda2, 0)``
    and ``C3 = (c3x, c3y) = (B3, H3 - lambda3)``; ``(1 + t^2)`` times ``sin psi``, ``cos psi``
    and ``1`` are ``2 t``, ``1 - t^2``, ``1 + t^2``.
    """
    return (_quadratic(0.0, 2 * a, 2 * l1 - 2 * c2x),
            _quadratic(2 * a, 0.0, 0.0),
            _quadratic(0.0, -2 * a * c2x, -l1 ** 2 + a ** 2 + c2x ** 2),
            _quadratic(-a * _ROOT3, a, 2 * (l1 - c3x)),
            _quadratic(a, a * _ROOT3, -2 * c3y),
            _quadratic(-a * c3y + a * _ROOT3 * c3x, -a * _ROOT3 * c3y - a * c3x,
                       -l1 ** 2 + c3x ** 2 + a ** 2 + c3y ** 2))


def _stacked(coefficients):
    """A list of coefficients (numbers, or arrays that broadcast) as one array, last axis."""
    if not np.broadcast_shapes(*map(np.shape, coefficients)):  # one input, in Python floats
        return np.array(coefficients, dtype=float)
    return np.stack(np.broadcast_arrays(*coefficients), axis=-1)


def _octic(l1, c2x, c3x, c3y, a, L):
    """The degree-8 polynomial's coefficients, as a list (see :func:`coefficients`)."""
    f1, f2, f3, g1, g2, g3 = _f_and_g(l1, c2x, c3x, c3y, a)
    nx = _minus(_times(f3, g2), _times(f2, g3))  # x_P = N_x / D, y_P = N_y / D (eq. 146-147)
    ny = _minus(_times(f1, g3), _times(f3, g1))
    d = _minus(_times(f2, g1), _times(f1, g2))
    e = [u - l1 * v for u, v in zip(nx, d)]
    return [u + v - L ** 2 * w for u, v, w in zip(_times(e, e), _times(ny, ny), _times(d, d))]


def _deflated(c):
    """Synthetic division of a list of 9 coefficients by ``1 + t^2`` (see :func:`deflate`)."""
    rest, q = list(c), [0.0] * 7
    for k in range(8, 1, -1):
        q[k - 2] = rest[k]
        rest[k - 2] = rest[k - 2] - rest[k]
    return q


def coefficients(l1, c2x, c3x, c3y, a, L):
    """The degree-8 polynomial from the sliders' coordinates: see :func:`polynomial`.

    ``l1`` is slider 1's abscissa, ``(c2x, 0)`` slider 2 and ``(c3x, c3y)`` slider 3; numbers
    or arrays that broadcast (the result has their shape plus a last axis of 9). The forward
    solver calls it in a frame centred on slider 1 and scaled to unit size (the poses do not
    depend on the frame, and the coefficients stay of order 1); its arithmetic is plain, as
    fast on the Python floats of one input as on the arrays of a batch.

    Examples
    --------
    >>> coefficients(0.4, 2.9, 2.0, 2.4, 1.0, 1.0).round(2).tolist()[:3]  # sliders of polynomial()
    [-4.12, 19.2, 257.57]
    """
    return _stacked(_octic(l1, c2x, c3x, c3y, a, L))


def sextic(l1, c2x, c3x, c3y, a, L):
    """The sextic of :func:`coefficients` divided by ``1 + t^2`` (:func:`deflate`), in one go.

    Examples
    --------
    >>> bool(np.all(sextic(0.0, 3.0, 2.0, 3.0, 1.0, 1.0)
    ...             == deflate(coefficients(0.0, 3.0, 2.0, 3.0, 1.0, 1.0))))
    True
    """
    return _stacked(_deflated(_octic(l1, c2x, c3x, c3y, a, L)))


def polynomial(mech: Geometry, lambdas: ArrayLike) -> np.ndarray:
    """Coefficients ``C0 ... C8`` of the study's degree-8 polynomial in ``t = tan(psi/2)``.

    It is equation 148 of the study, ``(N_x - lambda1 D)^2 + N_y^2 - L^2 D^2 = 0``, with
    ``x_P = N_x / D`` and ``y_P = N_y / D`` the radical-axis solution (equations 146-147)
    multiplied through by ``(1 + t^2)^4``. It is computed here by multiplying the quadratics
    ``(1 + t^2) f_i`` and ``(1 + t^2) g_i``, not from the printed expansion of Annex I.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    lambdas : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 9)
        ``C0, C1, ..., C8`` (ascending powers of ``t``).

    Raises
    ------
    ValueError
        If ``lambdas`` is ill-shaped or not finite, or so large that a coefficient overflows
        (:func:`~mechnum.mechanisms.prr3.forward` works in a local frame and has no such limit).

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> C = polynomial(g, [0.4, 0.1, 0.6])
    >>> C.round(2).tolist()
    [-4.12, 19.2, 257.57, 409.42, 3157.17, 1836.44, 10133.14, 1446.22, 7237.66]
    >>> bool(abs(np.polynomial.polynomial.polyval(1j, C)) < 1e-14 * abs(C).sum())
    True
    """
    c = kernels.sliders(check(mech), vectors(lambdas, "lambdas"))
    with np.errstate(over="ignore", invalid="ignore"):
        out = coefficients(c[..., 0, 0], c[..., 1, 0], c[..., 2, 0], c[..., 2, 1], mech.a, mech.L)
    if not np.all(np.isfinite(out)):
        raise ValueError(f"the polynomial's coefficients overflow for lambdas = {lambdas!r}: "
                         "they grow as the 8th power of the lengths")
    return out


def deflate(c: ArrayLike) -> np.ndarray:
    """Divide degree-8 polynomials by their factor ``1 + t^2``: the sextic quotients.

    Synthetic division from the top: ``q[k - 2] = r[k]``, ``r[k - 2] -= r[k]``. The remainder
    (``r[0], r[1]``) is zero in exact arithmetic and dropped.

    Parameters
    ----------
    c : array_like, shape (..., 9)
        Ascending coefficients (:func:`polynomial`).

    Returns
    -------
    ndarray, shape (..., 7)

    Examples
    --------
    >>> deflate([1.0, 0, 2, 0, 2, 0, 2, 0, 1]).tolist()   # (1 + t^2)(1 + t^2 + t^4 + t^6)
    [1.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0]
    """
    c = _validate.array(c, "c")
    if c.ndim == 0 or c.shape[-1] != 9:
        raise ValueError(f"c must have shape (..., 9), got shape {c.shape}")
    return _stacked(_deflated(np.moveaxis(c, -1, 0))).reshape(c.shape[:-1] + (7,))


def _product(p, q):
    """Product of two polynomials given as ``{exponent tuple: coefficient}``."""
    out = {}
    for ep, cp in p.items():
        for eq, cq in q.items():
            e = tuple(i + j for i, j in zip(ep, eq))
            out[e] = out.get(e, 0.0) + cp * cq
    return out


def _circle(linear_x, linear_y, radius):
    """``X^2 + Y^2 - radius^2`` for ``X, Y`` linear forms ``{exponent: coefficient}``."""
    out = {(0, 0, 0, 0): -radius ** 2}
    for form in (linear_x, linear_y):
        for e, c in _product(form, form).items():
            out[e] = out.get(e, 0.0) + c
    return {e: c for e, c in out.items() if c != 0.0}


def equations(mech: Geometry, lambdas: ArrayLike) -> PolynomialSystem:
    """The direct problem as four quadratics in ``(x/L, y/L, cos psi, sin psi)``.

    ``|P_i - C_i|^2 / L^2 - 1 = 0`` for the three legs, and ``cos^2 + sin^2 - 1 = 0``. Bezout
    bounds the solutions by ``2^4 = 16``; the real ones with ``(cos, sin)`` on the unit circle
    are the poses, at most 6.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    lambdas : array_like, shape (3,)

    Returns
    -------
    mechnum.polynomials.PolynomialSystem

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> system = equations(g, [0.4, 0.1, 0.6])
    >>> system.degrees
    (2, 2, 2, 2)
    """
    lam = resolved(_validate.array(lambdas, "lambdas", shape=(3,)), "lambdas")
    (c1, c2, c3) = kernels.sliders(check(mech), lam) / mech.L
    A = mech.a / mech.L
    x, y, c, s = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))
    one = (0, 0, 0, 0)
    legs = [({x: 1.0, one: -c1[0]}, {y: 1.0, one: -c1[1]}),
            ({x: 1.0, c: A, one: -c2[0]}, {y: 1.0, s: A, one: -c2[1]}),
            ({x: 1.0, c: A / 2, s: -A * _ROOT3 / 2, one: -c3[0]},
             {y: 1.0, s: A / 2, c: A * _ROOT3 / 2, one: -c3[1]})]
    rows = [_circle(X, Y, 1.0) for X, Y in legs] + [{(0, 0, 2, 0): 1.0, (0, 0, 0, 2): 1.0,
                                                      one: -1.0}]
    return PolynomialSystem.from_dicts(rows)


def solutions_from_equations(mech: Geometry, points: ArrayLike) -> np.ndarray:
    """Poses ``(x, y, psi)`` from real solutions ``(x/L, y/L, cos psi, sin psi)`` of
    :func:`equations`, ``psi`` in ``[0, 2 pi)``.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    points : array_like, shape (n, 4) or (4,)
        Real solutions; an empty batch gives no pose.

    Returns
    -------
    ndarray, shape (n, 3)

    Raises
    ------
    ValueError
        If ``points`` is not finite, has no last axis of 4, or has ``|cos^2 + sin^2 - 1|``
        above :data:`UNIT_CIRCLE_TOL` (no solution of the equations).

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=2, a=1, B2=3, B3=2, H3=3)
    >>> solutions_from_equations(g, [[0.5, 0.25, 0.0, 1.0]]).round(4).tolist()
    [[1.0, 0.5, 1.5708]]
    """
    check(mech)
    points = resolved(_validate.array(points, "points", ndim=(1, 2)), "points")
    if points.shape[-1] != 4:
        raise ValueError(f"points must have shape (n, 4), got shape {points.shape}")
    points = points.reshape(-1, 4)
    off = np.abs(points[:, 2] ** 2 + points[:, 3] ** 2 - 1)
    if np.any(off > UNIT_CIRCLE_TOL):
        raise ValueError(f"points must have cos^2 + sin^2 = 1 (to {UNIT_CIRCLE_TOL:g}), got "
                         f"{float(off.max()):.3g} off: no solution of the equations")
    psi = np.mod(np.arctan2(points[:, 3], points[:, 2]), 2 * np.pi)
    return np.column_stack([points[:, :2] * mech.L, psi])
