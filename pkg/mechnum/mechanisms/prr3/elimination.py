"""The direct problem's equations: the study's degree-8 polynomial, and the polynomial system.

Subtracting the circle of leg 1 from those of legs 2 and 3 leaves two equations linear in
``(x, y)`` (the radical axes, the study's equations 124-125); solving them by Cramer's rule and
substituting into leg 1 gives, with ``t = tan(psi/2)``, the study's polynomial of degree 8
(:func:`polynomial`). It always has the factor ``1 + t^2`` (:func:`deflate` removes it).
:func:`equations` writes the same problem as four quadratics in ``(x, y, cos psi, sin psi)``,
the form a homotopy solves.
"""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.prr3.geometry import sliders, vectors
from mechnum.polynomials import PolynomialSystem

_ROOT3 = np.sqrt(3.0)


def _poly_mul(p, q):
    """Product of polynomials with ascending coefficients along the last axis."""
    out = np.zeros(np.broadcast_shapes(p.shape[:-1], q.shape[:-1])
                   + (p.shape[-1] + q.shape[-1] - 1,))
    for i in range(p.shape[-1]):
        out[..., i:i + q.shape[-1]] += p[..., i, None] * q
    return out


def _f_and_g(l1, c2x, c3x, c3y, a):
    """``(1 + t^2)`` times the study's ``f1, f2, f3, g1, g2, g3`` (eq. 126-145), quadratics in t.

    The study's constants are written with the sliders ``C2 = (c2x, 0) = (B2 - lambda2, 0)``
    and ``C3 = (c3x, c3y) = (B3, H3 - lambda3)``; ``(1 + t^2)`` times ``sin psi``, ``cos psi``
    and ``1`` are ``2 t``, ``1 - t^2``, ``1 + t^2``.
    """
    K = [2 * a, 2 * l1 - 2 * c2x, 2 * a, -2 * a * c2x, -l1 ** 2 + a ** 2 + c2x ** 2]
    Q = [-a * _ROOT3, a, 2 * (l1 - c3x), a, a * _ROOT3, -2 * c3y,
         -a * c3y + a * _ROOT3 * c3x, -a * _ROOT3 * c3y - a * c3x,
         -l1 ** 2 + c3x ** 2 + a ** 2 + c3y ** 2]
    shape = np.broadcast_shapes(*(np.shape(v) for v in (l1, c2x, c3x, c3y)))

    def times(k_sin, k_cos, k_one):
        return sum(np.broadcast_to(k, shape)[..., None] * np.array(basis) for k, basis in
                   ((k_sin, [0.0, 2, 0]), (k_cos, [1.0, 0, -1]), (k_one, [1.0, 0, 1])))

    return (times(0, K[0], K[1]), times(K[2], 0, 0), times(0, K[3], K[4]),
            times(Q[0], Q[1], Q[2]), times(Q[3], Q[4], Q[5]), times(Q[6], Q[7], Q[8]))


def coefficients(l1, c2x, c3x, c3y, a, L):
    """The degree-8 polynomial from the sliders' coordinates: see :func:`polynomial`.

    ``l1`` is slider 1's abscissa, ``(c2x, 0)`` slider 2 and ``(c3x, c3y)`` slider 3; arrays
    broadcast. The direct solver calls it in a frame centred on slider 1 and scaled to unit
    size (the poses do not depend on the frame, and the coefficients stay of order 1).
    """
    f1, f2, f3, g1, g2, g3 = _f_and_g(l1, c2x, c3x, c3y, a)
    nx = _poly_mul(f3, g2) - _poly_mul(f2, g3)  # x_P = N_x / D, y_P = N_y / D (eq. 146-147)
    ny = _poly_mul(f1, g3) - _poly_mul(f3, g1)
    d = _poly_mul(f2, g1) - _poly_mul(f1, g2)
    e = nx - np.asarray(l1)[..., None] * d
    return _poly_mul(e, e) + _poly_mul(ny, ny) - L ** 2 * _poly_mul(d, d)


def polynomial(lambdas, geometry):
    """Coefficients ``C0 ... C8`` of the study's degree-8 polynomial in ``t = tan(psi/2)``.

    It is equation 148 of the study, ``(N_x - lambda1 D)^2 + N_y^2 - L^2 D^2 = 0``, with
    ``x_P = N_x / D`` and ``y_P = N_y / D`` the radical-axis solution (equations 146-147)
    multiplied through by ``(1 + t^2)^4``. It is computed here by multiplying the quadratics
    ``(1 + t^2) f_i`` and ``(1 + t^2) g_i``, not from the printed expansion of Annex I.

    Parameters
    ----------
    lambdas : array_like, shape (..., 3)
    geometry : ~mechnum.mechanisms.prr3.geometry.Geometry

    Returns
    -------
    ndarray, shape (..., 9)
        ``C0, C1, ..., C8`` (ascending powers of ``t``).

    Raises
    ------
    ValueError
        If ``lambdas`` is ill-shaped or not finite, or so large that a coefficient overflows
        (:func:`~mechnum.mechanisms.prr3.direct` works in a local frame and has no such limit).

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> C = polynomial([0.4, 0.1, 0.6], g)
    >>> C.round(2).tolist()
    [-4.12, 19.2, 257.57, 409.42, 3157.17, 1836.44, 10133.14, 1446.22, 7237.66]
    >>> bool(abs(np.polynomial.polynomial.polyval(1j, C)) < 1e-14 * abs(C).sum())
    True
    """
    c = sliders(lambdas, geometry)
    with np.errstate(over="ignore", invalid="ignore"):
        out = coefficients(c[..., 0, 0], c[..., 1, 0], c[..., 2, 0], c[..., 2, 1], geometry.a,
                           geometry.L)
    if not np.all(np.isfinite(out)):
        raise ValueError(f"the polynomial's coefficients overflow for lambdas = {lambdas!r}: "
                         "they grow as the 8th power of the lengths")
    return out


def deflate(c):
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
    rest = np.array(c, dtype=float)
    if rest.ndim == 0 or rest.shape[-1] != 9:
        raise ValueError(f"c must have shape (..., 9), got shape {rest.shape}")
    q = np.zeros(rest.shape[:-1] + (7,))
    for k in range(8, 1, -1):
        q[..., k - 2] = rest[..., k]
        rest[..., k - 2] -= rest[..., k]
    return q


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


def equations(lambdas, geometry):
    """The direct problem as four quadratics in ``(x/L, y/L, cos psi, sin psi)``.

    ``|P_i - C_i|^2 / L^2 - 1 = 0`` for the three legs, and ``cos^2 + sin^2 - 1 = 0``. Bezout
    bounds the solutions by ``2^4 = 16``; the real ones with ``(cos, sin)`` on the unit circle
    are the poses, at most 6.

    Parameters
    ----------
    lambdas : array_like, shape (3,)
    geometry : ~mechnum.mechanisms.prr3.geometry.Geometry

    Returns
    -------
    mechnum.polynomials.PolynomialSystem

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> system = equations([0.4, 0.1, 0.6], g)
    >>> system.degrees
    (2, 2, 2, 2)
    """
    lam = _validate.array(lambdas, "lambdas", shape=(3,))
    (c1, c2, c3) = sliders(lam, geometry) / geometry.L
    A = geometry.a / geometry.L
    x, y, c, s = ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1))
    one = (0, 0, 0, 0)
    legs = [({x: 1.0, one: -c1[0]}, {y: 1.0, one: -c1[1]}),
            ({x: 1.0, c: A, one: -c2[0]}, {y: 1.0, s: A, one: -c2[1]}),
            ({x: 1.0, c: A / 2, s: -A * _ROOT3 / 2, one: -c3[0]},
             {y: 1.0, s: A / 2, c: A * _ROOT3 / 2, one: -c3[1]})]
    rows = [_circle(X, Y, 1.0) for X, Y in legs] + [{(0, 0, 2, 0): 1.0, (0, 0, 0, 2): 1.0,
                                                      one: -1.0}]
    return PolynomialSystem.from_dicts(rows)


def solutions_from_equations(points, geometry):
    """Poses ``(x, y, psi)`` from real solutions ``(x/L, y/L, cos psi, sin psi)`` of
    :func:`equations`, ``psi`` in ``[0, 2 pi)``.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=2, a=1, B2=3, B3=2, H3=3)
    >>> solutions_from_equations([[0.5, 0.25, 0.0, 1.0]], g).round(4).tolist()
    [[1.0, 0.5, 1.5708]]
    """
    points = np.asarray(points, dtype=float).reshape(-1, 4)
    psi = np.mod(np.arctan2(points[:, 3], points[:, 2]), 2 * np.pi)
    return np.column_stack([points[:, :2] * geometry.L, psi])
