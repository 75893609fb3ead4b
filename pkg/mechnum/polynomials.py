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

from dataclasses import dataclass
from itertools import combinations
from math import prod

import numpy as np

from mechnum import _validate


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


def companion(c):
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


def roots(c):
    """The roots of polynomials, as the eigenvalues of their companion matrices, batched.

    LAPACK balances the companion matrix and computes its eigenvalues by the QR algorithm, a
    backward-stable method: the roots are the exact roots of polynomials whose coefficients
    differ from ``c`` by a few units of round-off (relative to the largest coefficient). How
    far that moves each root is :func:`root_condition`.

    Parameters
    ----------
    c : array_like, shape (..., n + 1)
        Ascending coefficients, ``c[..., n] != 0``; a batch is one eigenvalue call.

    Returns
    -------
    ndarray of complex, shape (..., n)
        In no particular order.

    Examples
    --------
    >>> import numpy as np
    >>> np.sort(roots([2.0, -3.0, 1.0]).real).tolist()
    [1.0, 2.0]
    >>> roots([[1.0, 0.0, 1.0], [-4.0, 0.0, 1.0]]).shape    # t^2 + 1 and t^2 - 4
    (2, 2)
    """
    return np.linalg.eigvals(companion(c))


def root_condition(c, r):
    """Wilkinson's condition number of the simple roots ``r`` of ``c``.

    If every coefficient moves by at most a relative ``delta`` (``|dc_k| <= delta |c_k|``), a
    simple root moves by at most about ``kappa * delta`` with
    ``kappa = sum_k |c_k| |r|^k / |p'(r)|``. A root of multiplicity ``m`` has ``p'(r) = 0``:
    it moves by about ``delta**(1/m)`` instead, so round-off (``delta ~ 1e-16``) blurs a
    double root to about ``1e-8``.

    Parameters
    ----------
    c : array_like, shape (n + 1,)
        Ascending coefficients.
    r : array_like of complex
        Roots of ``c``.

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
    r = np.asarray(r, dtype=complex)
    size = np.polynomial.polynomial.polyval(np.abs(r), np.abs(c))
    slope = np.abs(np.polynomial.polynomial.polyval(r, np.polynomial.polynomial.polyder(c)))
    with np.errstate(divide="ignore"):
        return size / slope


def sylvester(p, q):
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
        If a polynomial has fewer than 2 coefficients.

    Examples
    --------
    >>> import numpy as np
    >>> S = sylvester([-1.0, 1.0], [2.0, -3.0, 1.0])     # t - 1 and (t - 1)(t - 2)
    >>> S.tolist(), abs(float(np.linalg.det(S))) < 1e-15
    ([[1.0, -1.0, 0.0], [0.0, 1.0, -1.0], [1.0, -3.0, 2.0]], True)
    """
    p, q = list(p), list(q)
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
    def from_dicts(cls, equations):
        """Build from one ``{exponent tuple: coefficient}`` per equation (sympy's
        ``Poly.as_dict()`` gives exactly that)."""
        terms = []
        for i, eq in enumerate(equations):
            if not eq:
                raise ValueError(f"equation {i} has no term")
            exponents = np.array(list(eq.keys()), dtype=int)
            coefficients = np.array([complex(v) for v in eq.values()])
            if exponents.ndim != 2 or np.any(exponents < 0):
                raise ValueError(f"equation {i}: exponents must be tuples of integers >= 0")
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
    def n(self):
        """The number of unknowns."""
        return self.terms[0][0].shape[1]

    @property
    def degrees(self):
        """The total degree of each equation."""
        return tuple(int(e.sum(axis=1).max()) for e, _ in self.terms)

    @property
    def supports(self):
        """The exponent vectors of each equation (its Newton polytope's points)."""
        return [e for e, _ in self.terms]

    def __call__(self, x):
        """The equations at ``x`` of shape ``(..., n)``: shape ``(..., len(terms))``."""
        x = np.asarray(x, dtype=complex)
        monomials = np.prod(x[..., None, :] ** self._exponents, axis=-1)
        return (monomials * self._coefficients) @ self._sum.T

    def jacobian(self, x):
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

    def homogenized(self):
        """The system in ``n + 1`` unknowns ``(x0, x1, ..., xn)``, each term multiplied by
        ``x0`` to the power that makes its equation homogeneous of its degree."""
        return PolynomialSystem(tuple(
            (np.column_stack([d - e.sum(axis=1), e]), c)
            for (e, c), d in zip(self.terms, self.degrees)))


def bezout_bound(system):
    """Bezout's bound: a system of ``n`` equations of degrees ``d_i`` in ``n`` unknowns has at
    most ``d_1 d_2 ... d_n`` isolated solutions in complex space (counted with multiplicity),
    exactly that many in projective space when they are all isolated.

    Examples
    --------
    >>> bezout_bound(PolynomialSystem.from_dicts([{(2, 0): 1, (0, 0): -1},
    ...                                           {(1, 1): 1, (0, 0): -1}]))
    4
    """
    return prod(system.degrees)


def _volume(points):
    """The volume of the convex hull of ``points`` (0 if they span less than full dimension)."""
    from scipy.spatial import ConvexHull, QhullError

    points = np.unique(points, axis=0)
    if points.shape[1] == 1:
        return float(np.ptp(points))
    if len(points) <= points.shape[1] or np.linalg.matrix_rank(points - points[0]) < \
            points.shape[1]:
        return 0.0
    try:
        return ConvexHull(points).volume
    except QhullError:  # qhull's own verdict that the points are flat
        return 0.0


def mixed_volume(supports):
    """The mixed volume of the Newton polytopes of ``n`` supports in ``n`` unknowns: the BKK bound.

    Bernstein, Khovanskii and Kushnirenko: a system whose equations have these supports has at
    most this many isolated solutions with no zero coordinate, and exactly this many for
    generic coefficients; when every support contains the origin (a constant term) it bounds
    all the isolated solutions in complex space (Li and Wang). It is never above Bezout's
    bound, and far below it for sparse systems. Computed by inclusion and exclusion over the
    Minkowski sums, ``MV = sum over subsets S of (-1)^(n - |S|) vol(sum_{i in S} P_i)``, with
    ``MV(P, ..., P) = n! vol(P)``: ``2^n - 1`` convex hulls, fine for the small ``n`` of a
    mechanism.

    Parameters
    ----------
    supports : sequence of array_like of int, each of shape (k_i, n)
        The exponent vectors of each equation (:attr:`PolynomialSystem.supports`).

    Returns
    -------
    int

    Examples
    --------
    >>> dense = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)]    # two dense quadratics
    >>> mixed_volume([dense, dense])
    4
    >>> mixed_volume([[(0, 0), (1, 1)], [(0, 0), (1, 0), (0, 1)]])   # x y = 1, x + y = c
    2
    """
    supports = [np.asarray(s, dtype=float) for s in supports]
    n = len(supports)
    if n == 0 or any(s.ndim != 2 or s.shape[1] != n for s in supports):
        raise ValueError(f"mixed_volume needs n supports of shape (k, n), got shapes "
                         f"{[s.shape for s in supports]}")
    total = 0.0
    for size in range(1, n + 1):
        for subset in combinations(supports, size):
            minkowski = subset[0]
            for s in subset[1:]:
                minkowski = (minkowski[:, None, :] + s[None, :, :]).reshape(-1, n)
            total += (-1) ** (n - size) * _volume(minkowski)
    value = round(total)
    # the volumes are rational with denominator n!, and qhull's round-off is far below 0.5
    if abs(total - value) > 1e-6 * max(1.0, abs(total)):
        raise ArithmeticError(f"mixed volume {total} is not an integer: the hulls are "
                              "numerically degenerate")
    return int(value)
