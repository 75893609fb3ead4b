"""Polynomials: roots as eigenvalues, their conditioning, elimination, and counting solutions.

Univariate polynomials are coefficient arrays in *ascending* powers, ``c[0] + c[1] t + ...``
(numpy's ``np.polynomial`` order), with any leading axes for a batch:

* :func:`companion` and :func:`roots`: the roots of ``p`` are the eigenvalues of its companion
  matrix, which is how ``np.roots`` and Matlab's ``roots`` compute them; :func:`roots` does it
  for a whole batch of polynomials with one call of :func:`numpy.linalg.eigvals`;
* :func:`root_condition`: Wilkinson's condition number of a root, how far it moves when the
  coefficients move by a relative ``delta``;
* :func:`sylvester`: the Sylvester matrix, whose determinant (the resultant) vanishes exactly
  when two polynomials share a root: the general tool to eliminate one unknown from two
  polynomial equations.

Systems of polynomials in several unknowns are :class:`PolynomialSystem` objects (a list of
terms per equation), counted by :func:`bezout_bound` and :func:`mixed_volume` (the BKK bound)
and solved by :mod:`mechnum.homotopy`.
"""

import numbers
from collections.abc import Sequence
from dataclasses import dataclass
from itertools import combinations
from math import prod

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import NonFiniteError

__all__ = ["PolynomialSystem", "bezout_bound", "companion", "mixed_volume", "root_condition",
           "roots", "sylvester"]

MIXED_VOLUME_UNKNOWNS = 6
"""The most unknowns :func:`mixed_volume` takes: it computes ``2^n - 1`` convex hulls in ``n``
dimensions, whose cost grows steeply with ``n`` (a polyhedral method, by mixed cells, is the tool
beyond a mechanism's few unknowns)."""
MINKOWSKI_POINTS_LIMIT = 200_000
"""The most candidate points of one Minkowski sum in :func:`mixed_volume` (the products of the
summands' hull vertices): a bound on the memory and on the hull's work."""
_TINY = np.finfo(float).tiny  # below it a float is subnormal: it keeps fewer than 53 bits


def _coefficients(c, name="c"):
    """``c`` as a finite real (or complex) array of degree >= 1 and non-zero leading term."""
    c = np.asarray(c)
    if not np.iscomplexobj(c):
        c = _validate.array(c, name)
    elif not np.all(np.isfinite(c)):
        raise ValueError(f"{name} must be finite, got {c!r}")
    if c.ndim == 0 or c.shape[-1] < 2:
        raise ValueError(f"{name} must hold at least 2 coefficients along its last axis, "
                         f"got shape {c.shape}")
    if np.any(c[..., -1] == 0):
        raise ValueError(f"{name} has a zero leading coefficient: strip it (the degree is "
                         "lower), or treat the missing root as a root at infinity")
    return c


def companion(c: ArrayLike) -> np.ndarray:
    """The companion matrix of ``c[0] + c[1] t + ... + c[n] t^n``, batched.

    Its characteristic polynomial is ``p / c[n]``, so its eigenvalues are the roots of ``p``:
    ones on the subdiagonal, ``-c[:n] / c[n]`` in the last column.

    Parameters
    ----------
    c : array_like, shape (..., n + 1)
        Ascending coefficients, ``c[..., n] != 0``.

    Returns
    -------
    ndarray, shape (..., n, n)

    Raises
    ------
    ValueError
        If ``c`` is not finite, has fewer than 2 coefficients or a zero leading coefficient.

    Examples
    --------
    >>> companion([2.0, -3.0, 1.0]).tolist()     # t^2 - 3 t + 2 = (t - 1)(t - 2)
    [[0.0, -2.0], [1.0, 3.0]]
    """
    c = _coefficients(c)
    n = c.shape[-1] - 1
    out = np.zeros(c.shape[:-1] + (n, n), dtype=c.dtype)
    out[..., np.arange(1, n), np.arange(n - 1)] = 1
    out[..., :, -1] = -c[..., :-1] / c[..., -1:]
    return out


def roots(c: ArrayLike) -> np.ndarray:
    """The roots of polynomials, as the eigenvalues of their companion matrices, batched.

    LAPACK balances the companion matrix and computes its eigenvalues by the QR algorithm, a
    backward-stable method: the roots are the exact roots of polynomials whose coefficients
    differ from ``c`` by a few units of round-off (relative to the largest coefficient). How
    far that moves each root is :func:`root_condition`.

    Where the companion matrix would overflow or underflow (coefficients of very different
    sizes, as ``1e300 + 1e-300 t``, or roots below ``1e-100``), the polynomial is first scaled,
    ``t = 2^e u`` with ``e`` from Fujiwara's bound on the roots' size, which is exact (only
    exponents change); its roots are then of order one.

    Parameters
    ----------
    c : array_like, shape (..., n + 1)
        Ascending coefficients, ``c[..., n] != 0``; a batch is one eigenvalue call.

    Returns
    -------
    ndarray of complex, shape (..., n)
        In no particular order.

    Raises
    ------
    ValueError
        As :func:`companion`.
    NonFiniteError
        If a root is beyond the largest float (``1e300 + 1e-300 t`` has the root ``-1e600``).

    Examples
    --------
    >>> import numpy as np
    >>> np.sort(roots([2.0, -3.0, 1.0]).real).tolist()
    [1.0, 2.0]
    >>> roots([[1.0, 0.0, 1.0], [-4.0, 0.0, 1.0]]).shape    # t^2 + 1 and t^2 - 4
    (2, 2)
    """
    c = _coefficients(c)
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        matrix = companion(c)
        # an entry -c_k / c_n that underflows (to zero, or to a subnormal with fewer digits)
        # loses the small roots it determines: t^3 - 2^-1200 became t^3
        lost = np.any((c[..., :-1] != 0) & (np.abs(c[..., :-1] / c[..., -1:]) < _TINY))
    if np.all(np.isfinite(matrix)) and not lost:
        return np.linalg.eigvals(matrix)
    e, scaled = _scaled(c)
    u = np.linalg.eigvals(companion(scaled))
    with np.errstate(over="ignore", invalid="ignore"):
        out = np.ldexp(u.real, e[..., None]) + 1j * np.ldexp(u.imag, e[..., None])
    if not np.all(np.isfinite(out)):
        raise NonFiniteError("a root of c is beyond the largest float (about "
                             f"2**{int(np.max(e))} in size)")
    return out


def _scaled(c):
    """``e`` and the coefficients of ``p(2^e u)``, normalised to a largest entry below one,
    with ``2^e`` Fujiwara's bound ``max_k |c_k / c_n|^(1 / (n - k))`` on the roots' size
    (rounded to a power of two): only exponents change, exactly."""
    n = c.shape[-1] - 1
    size = np.abs(c)
    _, exponent = np.frexp(size)                   # |c_k| = m 2^exponent, m in [0.5, 1)
    k = np.arange(n + 1)
    with np.errstate(divide="ignore"):
        ratio = (exponent[..., :-1] - exponent[..., -1:]) / (n - k[:-1])
    ratio = np.where(size[..., :-1] > 0, ratio, -np.inf)
    e = np.ceil(ratio.max(axis=-1)).astype(int)
    shifted = np.where(size > 0, exponent + k * e[..., None], np.iinfo(int).min // 2)
    shift = k * e[..., None] - shifted.max(axis=-1, keepdims=True)
    if np.iscomplexobj(c):
        return e, np.ldexp(c.real, shift) + 1j * np.ldexp(c.imag, shift)
    return e, np.ldexp(c, shift)


def root_condition(c: ArrayLike, r: ArrayLike) -> np.ndarray:
    """Wilkinson's condition number of the simple roots ``r`` of ``c``.

    If every coefficient moves by at most a relative ``delta`` (``|dc_k| <= delta |c_k|``), a
    simple root moves by at most about ``kappa * delta`` with
    ``kappa = sum_k |c_k| |r|^k / |p'(r)|``. A root of multiplicity ``m`` has ``p'(r) = 0``:
    it moves by about ``delta**(1/m)`` instead, so round-off (``delta ~ 1e-16``) blurs a
    double root to about ``1e-8``.

    Parameters
    ----------
    c : array_like, shape (n + 1,)
        Ascending coefficients, one polynomial.
    r : array_like of complex
        Roots of ``c``, finite.

    Returns
    -------
    ndarray, the shape of ``r``
        ``inf`` at a multiple root.

    Examples
    --------
    >>> import numpy as np
    >>> c = np.polynomial.polynomial.polyfromroots([1.0, 2.0, 3.0])
    >>> root_condition(c, [1.0, 2.0, 3.0]).round(1).tolist()
    [12.0, 60.0, 60.0]
    """
    c = _coefficients(c)
    if c.ndim != 1:
        raise ValueError(f"c must hold one polynomial, shape (n + 1,), got shape {c.shape}")
    r = np.asarray(r)
    if r.dtype.kind not in "biufc":
        raise ValueError(f"r must be numeric, got {_validate.shown(r)}")
    r = r.astype(complex)
    if not np.all(np.isfinite(r)):
        raise ValueError(f"r must be finite, got {_validate.shown(r)}")
    size = np.polynomial.polynomial.polyval(np.abs(r), np.abs(c))
    slope = np.abs(np.polynomial.polynomial.polyval(r, np.polynomial.polynomial.polyder(c)))
    with np.errstate(divide="ignore"):
        return size / slope


def sylvester(p: Sequence, q: Sequence) -> np.ndarray:
    """The Sylvester matrix of two polynomials; its determinant is their resultant.

    For ``p`` of degree ``m`` and ``q`` of degree ``n`` (ascending coefficients), it is the
    ``(m + n) x (m + n)`` matrix whose first ``n`` rows hold the coefficients of ``p``
    (highest power first) shifted by one column each, and whose last ``m`` rows hold those
    of ``q``. Its rows are the coefficients of ``t^j p`` (``j < n``) and ``t^i q`` (``i < m``):
    they are dependent, and the determinant zero, exactly when ``p`` and ``q`` have a common
    root (or both leading coefficients vanish). With coefficients that are themselves
    polynomials in other unknowns (sympy expressions: the matrix then has ``dtype=object``),
    the determinant eliminates ``t``: the textbook route from a system to one equation.

    Parameters
    ----------
    p, q : sequence
        Ascending coefficients: numbers or sympy expressions; degree >= 1 each.

    Returns
    -------
    ndarray, shape (m + n, m + n)

    Raises
    ------
    ValueError
        If a polynomial is not a sequence of numbers or expressions, a number is not finite, or
        a polynomial has fewer than 2 coefficients.

    Examples
    --------
    >>> import numpy as np
    >>> S = sylvester([-1.0, 1.0], [2.0, -3.0, 1.0])     # t - 1 and (t - 1)(t - 2)
    >>> S.tolist(), abs(float(np.linalg.det(S))) < 1e-15
    ([[1.0, -1.0, 0.0], [0.0, 1.0, -1.0], [1.0, -3.0, 2.0]], True)
    """
    p, q = _entries(p, "p"), _entries(q, "q")
    if len(p) < 2 or len(q) < 2:
        raise ValueError(f"sylvester needs two polynomials of degree >= 1, got {len(p)} and "
                         f"{len(q)} coefficients")
    m, n = len(p) - 1, len(q) - 1
    numeric = all(isinstance(v, (int, float, complex, np.number)) for v in p + q)
    out = np.zeros((m + n, m + n), dtype=np.result_type(*p, *q) if numeric else object)
    for j in range(n):
        out[j, j:j + m + 1] = p[::-1]
    for i in range(m):
        out[n + i, i:i + n + 1] = q[::-1]
    return out


def _entries(p, name):
    """The coefficients of ``p`` as a list: finite numbers, or symbolic expressions (anything
    with sympy's ``free_symbols``); strings, None, booleans are refused."""
    if isinstance(p, (str, bytes)) or not hasattr(p, "__iter__"):
        raise ValueError(f"{name} must be a sequence of coefficients, got {_validate.shown(p)}")
    out = list(np.asarray(p, dtype=object).ravel()) if isinstance(p, np.ndarray) else list(p)
    for v in out:
        if isinstance(v, numbers.Number) and not isinstance(v, (bool, np.bool_)):
            if not np.isfinite(complex(v)):
                raise ValueError(f"{name} must be finite, got {_validate.shown(p)}")
        elif not hasattr(v, "free_symbols"):
            raise ValueError(f"{name} must hold numbers or sympy expressions, got "
                             f"{_validate.shown(v)} ({type(v).__name__})")
    return out


@dataclass(frozen=True)
class PolynomialSystem:
    """A system of ``len(terms)`` polynomial equations in ``n`` unknowns.

    Attributes
    ----------
    terms : tuple of (exponents, coefficients)
        For each equation, an int array of shape ``(k, n)`` (one monomial per row) and a
        complex array of shape ``(k,)``.

    Examples
    --------
    >>> circle = {(2, 0): 1, (0, 2): 1, (0, 0): -4}    # x^2 + y^2 - 4
    >>> system = PolynomialSystem.from_dicts([circle, {(1, 1): 1, (0, 0): -1}])
    >>> system.n, system.degrees
    (2, (2, 2))
    >>> system([[1.0, 1.0]]).real.tolist()
    [[-2.0, 0.0]]
    """

    terms: tuple

    @classmethod
    def from_dicts(cls, equations: Sequence[dict]) -> "PolynomialSystem":
        """Build from one ``{exponent tuple: coefficient}`` per equation (sympy's
        ``Poly.as_dict()`` gives exactly that)."""
        terms = []
        for i, eq in enumerate(equations):
            if not eq:
                raise ValueError(f"equation {i} has no term")
            try:
                raw = np.array(list(eq.keys()), dtype=float)
                coefficients = np.array([complex(v) for v in eq.values()])
            except (TypeError, ValueError):
                raise ValueError(f"equation {i}: exponents must be tuples of integers >= 0 and "
                                 f"coefficients numbers, got {_validate.shown(eq)}") from None
            if raw.ndim != 2 or not np.all(np.isfinite(raw)) or np.any(raw < 0) or \
                    np.any(raw != np.round(raw)):
                raise ValueError(f"equation {i}: exponents must be tuples of integers >= 0, got "
                                 f"{_validate.shown(list(eq.keys()))}")
            exponents = raw.astype(int)
            if not np.all(np.isfinite(coefficients)):
                raise ValueError(f"equation {i}: coefficients must be finite")
            terms.append((exponents, coefficients))
        widths = {e.shape[1] for e, _ in terms}
        if len(widths) != 1:
            raise ValueError(f"every exponent tuple must have the same length, got {widths}")
        return cls(tuple(terms))

    def __post_init__(self):
        # all the terms of all the equations stacked, so that evaluating the system is a few
        # array operations: exponents (T, n), coefficients (T,), and which equation (E, T)
        exponents = np.concatenate([e for e, _ in self.terms])
        which = np.repeat(np.arange(len(self.terms)), [len(c) for _, c in self.terms])
        object.__setattr__(self, "_exponents", exponents)
        object.__setattr__(self, "_coefficients", np.concatenate([c for _, c in self.terms]))
        object.__setattr__(self, "_sum", (which == np.arange(len(self.terms))[:, None]) * 1.0)

    @property
    def n(self) -> int:
        """The number of unknowns."""
        return self.terms[0][0].shape[1]

    @property
    def degrees(self) -> tuple:
        """The total degree of each equation."""
        return tuple(int(e.sum(axis=1).max()) for e, _ in self.terms)

    @property
    def supports(self) -> list:
        """The exponent vectors of each equation (its Newton polytope's points)."""
        return [e for e, _ in self.terms]

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """The equations at ``x`` of shape ``(..., n)``: shape ``(..., len(terms))``."""
        x = np.asarray(x, dtype=complex)
        monomials = np.prod(x[..., None, :] ** self._exponents, axis=-1)
        return (monomials * self._coefficients) @ self._sum.T

    def jacobian(self, x: ArrayLike) -> np.ndarray:
        """The Jacobian at ``x`` of shape ``(..., n)``: shape ``(..., len(terms), n)``."""
        x = np.asarray(x, dtype=complex)
        E = self._exponents
        powers = x[..., None, :] ** E  # (..., T, n)
        lower = x[..., None, :] ** np.maximum(E - 1, 0)
        # d/dx_j of a monomial: E_j x_j^(E_j - 1) times the other factors, for every j at once
        factors = np.where(np.eye(self.n, dtype=bool), lower[..., :, None, :],
                           powers[..., :, None, :])  # (..., T, j, k)
        slopes = E * np.prod(factors, axis=-1) * self._coefficients[:, None]
        return np.einsum("et,...tj->...ej", self._sum, slopes)

    def homogenized(self) -> "PolynomialSystem":
        """The system in ``n + 1`` unknowns ``(x0, x1, ..., xn)``, each term multiplied by
        ``x0`` to the power that makes its equation homogeneous of its degree."""
        return PolynomialSystem(tuple(
            (np.column_stack([d - e.sum(axis=1), e]), c)
            for (e, c), d in zip(self.terms, self.degrees)))


def bezout_bound(system: "PolynomialSystem") -> int:
    """Bezout's bound: a system of ``n`` equations of degrees ``d_i`` in ``n`` unknowns has at
    most ``d_1 d_2 ... d_n`` isolated solutions in complex space (counted with multiplicity),
    exactly that many in projective space when they are all isolated.

    Examples
    --------
    >>> bezout_bound(PolynomialSystem.from_dicts([{(2, 0): 1, (0, 0): -1},
    ...                                           {(1, 1): 1, (0, 0): -1}]))
    4
    """
    if not isinstance(system, PolynomialSystem):
        raise ValueError(f"system must be a PolynomialSystem, got {type(system).__name__}")
    return prod(system.degrees)


def _hull(points):
    """The convex hull of ``points`` (unique rows): its vertices and volume, or the points
    themselves and volume 0 if they span less than full dimension."""
    from scipy.spatial import ConvexHull, QhullError

    points = np.unique(points, axis=0)
    dim = points.shape[1]
    if dim == 1:
        return points[[points.argmin(), points.argmax()]], float(np.ptp(points))
    if len(points) <= dim or np.linalg.matrix_rank(points - points[0]) < dim:
        return points, 0.0
    try:
        hull = ConvexHull(points)
    except QhullError:  # qhull's own verdict that the points are flat
        return points, 0.0
    return points[hull.vertices], hull.volume


def mixed_volume(supports: Sequence) -> int:
    """The mixed volume of the Newton polytopes of ``n`` supports in ``n`` unknowns: the BKK bound.

    Bernstein, Khovanskii and Kushnirenko: a system whose equations have these supports has at
    most this many isolated solutions with no zero coordinate, and exactly this many for
    generic coefficients; when every support contains the origin (a constant term) it bounds
    all the isolated solutions in complex space (Li and Wang). It is never above Bezout's
    bound, and far below it for sparse systems. Computed by inclusion and exclusion over the
    Minkowski sums, ``MV = sum over subsets S of (-1)^(n - |S|) vol(sum_{i in S} P_i)``, with
    ``MV(P, ..., P) = n! vol(P)``: ``2^n - 1`` convex hulls, fine for the small ``n`` of a
    mechanism. A Minkowski sum is formed from the summands' hull vertices only (the vertices of
    a sum are sums of vertices), so five dense quadratics cost 31 hulls of at most 36 points.

    Parameters
    ----------
    supports : sequence of array_like of int, each of shape (k_i, n)
        The exponent vectors of each equation (:attr:`PolynomialSystem.supports`): finite
        integers, ``n`` at most :data:`MIXED_VOLUME_UNKNOWNS`.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        If the supports are not ``n`` integer arrays of shape ``(k, n)``, ``n`` exceeds
        :data:`MIXED_VOLUME_UNKNOWNS`, or a Minkowski sum would have more than
        :data:`MINKOWSKI_POINTS_LIMIT` candidate points.
    ArithmeticError
        If the inclusion-exclusion sum is not an integer to round-off (degenerate hulls).

    Examples
    --------
    >>> dense = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)]    # two dense quadratics
    >>> mixed_volume([dense, dense])
    4
    >>> mixed_volume([[(0, 0), (1, 1)], [(0, 0), (1, 0), (0, 1)]])   # x y = 1, x + y = c
    2
    """
    if isinstance(supports, (str, bytes)) or not hasattr(supports, "__iter__"):
        raise ValueError(f"supports must be a sequence of n arrays of shape (k, n), got "
                         f"{_validate.shown(supports)}")
    supports = [_validate.array(s, "each support", ndim=2) for s in supports]
    n = len(supports)
    if n == 0 or any(s.shape[1] != n or len(s) == 0 for s in supports):
        raise ValueError(f"mixed_volume needs n supports of shape (k, n), got shapes "
                         f"{[s.shape for s in supports]}")
    if n > MIXED_VOLUME_UNKNOWNS:
        raise ValueError(f"mixed_volume takes at most {MIXED_VOLUME_UNKNOWNS} unknowns (a bound "
                         f"on the work: 2^n - 1 hulls in n dimensions), got {n}")
    if any(np.any(s != np.round(s)) for s in supports):
        raise ValueError("the supports must hold integer exponents")
    vertices = [_hull(s)[0] for s in supports]
    total = 0.0
    for size in range(1, n + 1):
        for subset in combinations(vertices, size):
            minkowski = subset[0]
            for s in subset[1:]:
                if len(minkowski) * len(s) > MINKOWSKI_POINTS_LIMIT:
                    raise ValueError(f"a Minkowski sum of {len(minkowski) * len(s)} candidate "
                                     f"points exceeds {MINKOWSKI_POINTS_LIMIT} (a bound on the "
                                     "work)")
                minkowski = _hull((minkowski[:, None, :] + s[None, :, :]).reshape(-1, n))[0]
            total += (-1) ** (n - size) * _hull(minkowski)[1]
    value = round(total)
    # the volumes are rational with denominator n!, and qhull's round-off is far below 0.5
    if abs(total - value) > 1e-6 * max(1.0, abs(total)):
        raise ArithmeticError(f"mixed volume {total} is not an integer: the hulls are "
                              "numerically degenerate")
    return int(value)
