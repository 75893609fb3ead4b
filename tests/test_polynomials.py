"""Tests of mechnum.polynomials: companion roots, conditioning, Sylvester, counting bounds."""

import itertools

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose
from strategies import separated

from mechnum import polynomials as poly
from mechnum.errors import NonFiniteError
from mechnum.polynomials import PolynomialSystem

MANY = settings(max_examples=200, deadline=None)
P = np.polynomial.polynomial
# well separated, so well conditioned
roots_strategy = separated(st.integers(1, 6), -10, 10, gap=0.5)


@MANY
@given(r=roots_strategy, lead=st.floats(0.1, 10), batch=st.integers(1, 3))
def test_roots_are_the_companion_eigenvalues_and_match_the_true_roots(r, lead, batch):
    c = lead * P.polyfromroots(r)
    C = np.tile(c, (batch, 1))
    found = poly.roots(C)
    assert found.shape == (batch, len(r))
    for row in found:
        # the roots' sensitivity to the coefficients grows with their size to the power of the
        # degree (Wilkinson): round-off of the companion's eigenvalues, eps |c| scaled by that, is
        # below 1e-6 of it for these small degrees
        assert_allclose(np.sort(row.real), r, atol=1e-6 * (1 + np.abs(r).max()) ** len(r), rtol=0)
    M = poly.companion(c)
    # np.poly rebuilds the characteristic polynomial from the companion's eigenvalues: round-off of
    # the coefficients' size, amplified by the eigenvalues' conditioning (at most degree 5 here)
    assert_allclose(np.poly(M)[::-1] * c[-1], c, atol=1e-9 * np.abs(c).max(), rtol=0)


@MANY
@given(r=roots_strategy, delta=st.floats(1e-12, 1e-8), seed=st.integers(0, 1000))
def test_root_condition_bounds_how_far_a_simple_root_moves(r, delta, seed):
    c = P.polyfromroots(r)
    kappa = poly.root_condition(c, r)
    rng = np.random.default_rng(seed)
    moved = poly.roots(c * (1 + delta * rng.uniform(-1, 1, c.shape)))
    for root, k in zip(r, kappa):
        gap = np.abs(moved - root).min()
        # first order in delta, plus the eigensolver's own round-off (relative to the largest
        # coefficient, so absolute in the root: a root near 0 is not known relatively)
        assert gap <= 2 * k * delta + 1e-12 * (1 + k) * (1 + np.abs(r).max())


def test_a_double_root_moves_by_the_square_root_of_the_perturbation():
    c = P.polyfromroots([1.0, 1.0, 3.0])
    assert np.isinf(poly.root_condition(c, [1.0])[0])
    moved = poly.roots(c + [1e-10, 0, 0, 0])
    assert 1e-6 < np.abs(moved - 1.0).min() < 1e-4  # sqrt(1e-10) = 1e-5


@MANY
@given(p=st.lists(st.integers(-5, 5), min_size=1, max_size=4),
       q=st.lists(st.integers(-5, 5), min_size=1, max_size=4))
def test_sylvester_determinant_is_the_product_of_root_differences(p, q):
    a, b = P.polyfromroots(p), P.polyfromroots(q)  # integer coefficients, exact in floats
    S = poly.sylvester(a, b)
    assert S.shape == (len(p) + len(q),) * 2
    exact = sp.Matrix(poly.sylvester([int(v) for v in a], [int(v) for v in b])).det()
    # Res(p, q) = prod (p_i - q_j) for monic p, q: zero exactly when a root is shared
    assert exact == np.prod([pi - qj for pi in p for qj in q], dtype=object)
    hadamard = np.prod(np.linalg.norm(S, axis=1))  # bounds |det S|; round-off is eps of it
    # the determinant of a matrix with integer entries, computed by LU in floating point: its
    # round-off is a small multiple of eps times Hadamard's bound (eps = 2.2e-16)
    assert_allclose(np.linalg.det(S), float(exact), atol=1e-13 * hadamard, rtol=0)


def test_sylvester_with_symbolic_coefficients_eliminates_a_variable():
    x, y = sp.symbols("x y")
    # x^2 + y^2 - 1 and x - y, as polynomials in x with coefficients in y
    S = poly.sylvester([y ** 2 - 1, 0, 1], [-y, 1])
    assert S.dtype == object
    assert sp.expand(sp.Matrix(S).det() - (2 * y ** 2 - 1)) == 0


@pytest.mark.parametrize("call, message", [
    (lambda: poly.companion([1.0, 0.0]), "zero leading"),
    (lambda: poly.companion([1.0]), "at least 2"),
    (lambda: poly.roots([np.nan, 1.0]), "finite"),
    (lambda: poly.roots([[1.0, 1.0], [1.0, 0.0]]), "zero leading"),
    (lambda: poly.root_condition([1.0, 0.0], [1.0]), "zero leading"),
    (lambda: poly.sylvester([1.0], [1.0, 2.0]), "degree >= 1"),
    (lambda: poly.mixed_volume([[(0, 0)]]), "shape"),
    (lambda: PolynomialSystem.from_dicts([{}]), "no term"),
    (lambda: PolynomialSystem.from_dicts([{(1, 0): np.inf}]), "finite"),
    (lambda: PolynomialSystem.from_dicts([{(1, 0): 1}, {(1,): 1}]), "same length"),
    (lambda: PolynomialSystem.from_dicts([{(-1, 0): 1}]), "integers >= 0"),
])
def test_bad_input_raises_a_value_error_that_names_it(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@MANY
@given(d1=st.integers(1, 4), d2=st.integers(1, 4), seed=st.integers(0, 10 ** 6))
def test_mixed_volume_of_dense_supports_is_bezouts_number(d1, d2, seed):
    dense = [[(i, j) for i in range(d + 1) for j in range(d + 1 - i)] for d in (d1, d2)]
    assert poly.mixed_volume(dense) == d1 * d2
    rng = np.random.default_rng(seed)
    system = PolynomialSystem.from_dicts([{e: rng.normal() for e in s} for s in dense])
    assert poly.bezout_bound(system) == d1 * d2 and system.degrees == (d1, d2)


def test_mixed_volume_counts_the_solutions_of_sparse_systems():
    # a x y + b x + c y + d = 0 twice: 2 solutions, though Bezout says 4
    bilinear = [(0, 0), (1, 0), (0, 1), (1, 1)]
    assert poly.mixed_volume([bilinear, bilinear]) == 2
    # the unit simplex in 3-D: MV(P, P, P) = 3! vol(P) = 1
    simplex = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    assert poly.mixed_volume([simplex] * 3) == 1


@MANY
@given(seed=st.integers(0, 10 ** 6))
def test_system_evaluation_and_jacobian_agree_with_finite_differences(seed):
    rng = np.random.default_rng(seed)
    eqs = [{tuple(rng.integers(0, 3, 3)): rng.normal() for _ in range(4)} for _ in range(3)]
    system = PolynomialSystem.from_dicts(eqs)
    x = rng.normal(size=3) + 1j * rng.normal(size=3)
    J = system.jacobian(x)
    h = 1e-7
    fd = np.column_stack([(system(x + h * e) - system(x - h * e)) / (2 * h) for e in np.eye(3)])
    # central differences with h = 1e-7 err by h^2 |J''| ~ 1e-14 and by round-off eps |f| / h ~ 1e-9
    # relative: 1e-5 is a wide margin for polynomials of degree <= 6 with O(1) coefficients
    assert_allclose(J, fd, atol=1e-5 * (1 + np.abs(J).max()), rtol=0)
    H = system.homogenized()  # at x0 = 1 the homogenized system is the system
    # the same sums evaluated in another order (homogenized, x0 = 1): round-off of the terms' size
    assert_allclose(H(np.r_[1.0, x]), system(x), atol=1e-12 * (1 + np.abs(system(x)).max()), rtol=0)


# --- issue 23: non-integer exponents, overflow, unbounded work, bad input ------------------------

def test_a_non_integer_exponent_is_refused():
    # D9: {(1.5, 0): 1, (0, 0): -2} used to evaluate x - 2
    with pytest.raises(ValueError, match="integers >= 0"):
        PolynomialSystem.from_dicts([{(1.5, 0): 1, (0, 0): -2}, {(0, 1): 1}])
    with pytest.raises(ValueError, match="integers >= 0"):
        PolynomialSystem.from_dicts([{(np.nan,): 1}])
    assert PolynomialSystem.from_dicts([{(2.0,): 1, (0,): -4}]).degrees == (2,)


def test_roots_of_badly_scaled_polynomials():
    # 1e300 + t + 1e-10 t^2: the companion's -1e310 overflows, the roots do not; they are
    # -5e9 +- i sqrt(1e310 - 2.5e19) = -5e9 +- 1e155 i
    found = poly.roots([1e300, 1.0, 1e-10])
    # the roots of the rescaled polynomial, rescaled back (exact powers of two): a few ulps of 1e155
    assert_allclose(np.sort(found.imag), [-1e155, 1e155], rtol=1e-12)
    # the real part of a complex pair of the (scaled) 2 x 2 companion is half its trace, -b / (2 a),
    # exact here; it is 1e-145 of the roots' modulus, so round-off at the roots' scale would swamp
    # it: 1e-6 relative asks that it is not formed from the roots
    assert_allclose(found.real, -5e9, rtol=1e-6)
    with pytest.raises(NonFiniteError, match="beyond the largest float"):
        poly.roots([1e300, 1e-300])           # the root is -1e600
    batch = poly.roots([[1e300, 1.0, 1e-10], [2.0, -3.0, 1.0]])
    # simple roots of an O(1) quadratic: a few ulps
    assert_allclose(np.sort(batch[1].real), [1.0, 2.0], rtol=1e-14)


def test_five_dense_quadratics_have_a_mixed_volume_of_32():
    # H2: 31 Minkowski sums of 21-point supports in 5-D used to take minutes; their hull
    # vertices make them 31 hulls of at most 36 points
    dense = [e for e in itertools.product(range(3), repeat=5) if sum(e) <= 2]
    assert poly.mixed_volume([dense] * 5) == 2 ** 5
    with pytest.raises(ValueError, match="at most 6 unknowns"):
        poly.mixed_volume([[e + (0, 0) for e in dense]] * 7)


@pytest.mark.parametrize("call, error, message", [
    (lambda: poly.mixed_volume([[(0, 0), (np.nan, 1)], [(0, 0), (1, 0)]]), ValueError, "finite"),
    (lambda: poly.mixed_volume([[(0, 0), (0.5, 1)], [(0, 0), (1, 0)]]), ValueError, "integer"),
    (lambda: poly.mixed_volume("ab"), ValueError, "sequence"),
    (lambda: poly.root_condition([[1.0, 2.0], [1.0, 3.0]], [1.0]), ValueError, "one polynomial"),
    (lambda: poly.root_condition([2.0, -3.0, 1.0], [np.nan]), ValueError, "r must be finite"),
    (lambda: poly.root_condition([2.0, -3.0, 1.0], ["a"]), ValueError, "r must be numeric"),
    (lambda: poly.sylvester(["1", "2"], [1.0, 2.0]), ValueError, "numbers or sympy"),
    (lambda: poly.sylvester(None, [1.0, 2.0]), ValueError, "sequence"),
    (lambda: poly.sylvester([np.nan, 1.0], [1.0, 2.0]), ValueError, "finite"),
    (lambda: poly.sylvester([True, 1.0], [1.0, 2.0]), ValueError, "numbers or sympy"),
    (lambda: poly.bezout_bound([{(1,): 1}]), ValueError, "PolynomialSystem"),
])
def test_bad_input_of_the_new_checks(call, error, message):
    with pytest.raises(error, match=message):
        call()


@pytest.mark.parametrize("j", [-600, -400, 400, 600])
@pytest.mark.parametrize("unit", [
    [1.0, -2.0, 0.5],                  # three real roots of different signs and sizes
    [1.0, 1j, -0.5 + 0.25j],           # complex roots: complex coefficients
    [1.0, np.exp(2j * np.pi / 3), np.exp(-2j * np.pi / 3)],   # t^3 - 1: zero middle coefficients
])
def test_roots_beyond_the_companions_range_are_scaled_exactly(j, unit):
    # What it protects: the scaled route of roots, for polynomials whose companion entries
    # -c_k / c_n overflow or underflow (its roots R u_i are beyond 2^+-340 in size): t and the
    # coefficients are rescaled by powers of two, so only exponents change. Coefficients
    # a R^(3-k) with R = 2^j, a = 2^(-3j/2) are normal floats (2^+-900); the companion's entries
    # R^(3-k) are not (2^+-1200 and more). The roots found are R times those of the unscaled
    # polynomial, to the unscaled problem's round-off (1e-12 relative: simple roots, well apart).
    base = P.polyfromroots(np.array(unit, dtype=complex))
    powers = -3 * j // 2 + (3 - np.arange(4)) * j          # a R^(3-k) = 2^powers, exactly
    c = np.ldexp(base.real, powers) + 1j * np.ldexp(base.imag, powers)
    if np.all(c.imag == 0):
        c = c.real
    assert np.abs(c[c != 0]).min() > np.finfo(float).tiny and np.abs(c).max() < 2.0 ** 1000
    unscaled = poly.roots(base.real if np.all(base.imag == 0) else base)
    expected = np.sort_complex(np.ldexp(unscaled.real, j) + 1j * np.ldexp(unscaled.imag, j))
    assert_allclose(np.sort_complex(poly.roots(c)), expected, rtol=1e-12)  # round-off, above
    # in a batch with an ordinary polynomial, each row gets its own roots
    batch = poly.roots(np.stack([c, np.array([2.0, -3.0, 1.0, 1.0])]))
    assert_allclose(np.sort_complex(batch[0]), expected, rtol=1e-12)  # as above
    assert_allclose(np.sort_complex(batch[1]), np.sort_complex(poly.roots([2.0, -3.0, 1.0, 1.0])),
                    rtol=1e-12)


# --- what mutation testing found untested (bench/mutation.md) ------------------------------------

@pytest.mark.parametrize("call, message", [
    # each message starts with the argument's own name, as the caller spelled it
    (lambda: poly.companion([1.0]), r"^c must hold at least 2"),
    (lambda: poly.roots([np.nan, 1.0]), r"^c must be finite"),
    (lambda: poly.roots([1.0 + 1j, np.nan * 1j]), r"^c must be finite, got array\(\[ 1\. \+1\.j"),
    (lambda: poly.sylvester(3.0, [1.0, 2.0]), r"^p must be a sequence of coefficients, got 3\.0$"),
    (lambda: poly.sylvester([1.0, 2.0], 3.0), r"^q must be a sequence"),
    (lambda: poly.sylvester([np.nan, 1.0], [1.0, 2.0]), r"^p must be finite, got \[nan, 1\.0\]$"),
    (lambda: poly.sylvester([1.0, 2.0], [np.nan, 1.0]), r"^q must be finite, got \[nan, 1\.0\]$"),
    # a list of lists is not a polynomial (it is not flattened): the message shows the entry
    (lambda: poly.sylvester([[1.0, 2.0]], [1.0, 2.0]),
     r"^p must hold numbers or sympy expressions, got \[1\.0, 2\.0\] \(list\)$"),
    # a 0-d array is one number, not a polynomial of degree >= 1
    (lambda: poly.sylvester(np.array(2.0), [1.0, 2.0]), r"degree >= 1, got 1 and 2"),
    (lambda: poly.root_condition([2.0, -3.0, 1.0], ["a"]), r"^r must be numeric, got \['a'\]$"),
    (lambda: poly.root_condition([2.0, -3.0, 1.0], [np.nan]), r"^r must be finite, got \[nan"),
    (lambda: poly.bezout_bound([{(1,): 1}]), r"got list$"),
    (lambda: poly.mixed_volume("ab"), r"got 'ab'$"),
    (lambda: poly.mixed_volume([[(0, 0), (np.nan, 1)], [(0, 0), (1, 0)]]),
     r"^each support must be finite"),
    # a support must be a 2-D array of exponent rows, not one flat row
    (lambda: poly.mixed_volume([[0, 1], [1, 0]]), r"^each support must have 2 dimension"),
    (lambda: PolynomialSystem.from_dicts([{("a",): 1}]),
     r"^equation 0: exponents must be tuples of integers >= 0 and coefficients numbers, "
     r"got \{\('a',\): 1\}$"),
    # exponents that are plain integers, not tuples
    (lambda: PolynomialSystem.from_dicts([{1: 1, 0: -1}]),
     r"^equation 0: exponents must be tuples of integers >= 0, got \[1, 0\]$"),
    (lambda: PolynomialSystem.from_dicts([{(0, 0): 1}, {(-1, 0): 1}]),
     r"^equation 1: exponents must be tuples of integers >= 0, got \[\(-1, 0\)\]$"),
])
def test_bad_input_messages_name_the_argument_and_show_the_value(call, message):
    # What it protects: the words a student reads, the argument's name and the value it passed,
    # not only the exception's type (the tests above match a few words).
    with pytest.raises(ValueError, match=message):
        call()


def test_sylvester_keeps_double_precision_and_complex_coefficients():
    # What it protects: the matrix's dtype comes from both polynomials' coefficients, as Python
    # numbers: float32 input still gives a float64 matrix, and a complex coefficient in either
    # polynomial gives a complex one (no imaginary part dropped).
    S = poly.sylvester(np.array([-1.0, 1.0], dtype=np.float32), [2.0, -3.0, 1.0])
    assert S.dtype == np.float64
    for p, q in (([1j, 1.0], [1.0, 1.0]), ([1.0, 1.0], [1j, 1.0])):
        S = poly.sylvester(p, q)
        assert S.dtype == complex and S.tolist() == [[p[1], p[0]], [q[1], q[0]]]


def test_root_condition_of_complex_roots():
    # t^2 + 1 at +-i: kappa = (|c_0| + |c_2| |r|^2) / |2 r| = 2 / 2 = 1, exactly in floating point
    assert poly.root_condition([1.0, 0.0, 1.0], [1j, -1j]).tolist() == [1.0, 1.0]


def test_roots_of_a_polynomial_with_zero_coefficients_and_tiny_roots():
    # What it protects: the scaled route with zero coefficients (they have no exponent: they
    # must not decide the scale). 2^30 t^3 - 2^-1000: the companion's entry 2^-1030 is
    # subnormal, the roots are 2^(-1030/3) times the cube roots of unity.
    # 2^-40 t^3 - 2^-1070 has the same roots; there a zero coefficient's exponent (0) taken as
    # if it were a coefficient would ask for a scale of 2^39 and push 2^-1070 below the floats.
    expected = 2.0 ** (-1030 / 3) * np.exp(2j * np.pi * np.arange(3) / 3)
    for c in ([-(2.0 ** -1000), 0.0, 0.0, 2.0 ** 30], [-(2.0 ** -1070), 0.0, 0.0, 2.0 ** -40]):
        found = poly.roots(c)
        # the scaled polynomial is u^3 - 1/2 (times a power of two): the eigenvalues of its 3 x 3
        # companion matrix, to some dozens of ulps (LAPACK's QR on a non-normal matrix)
        assert_allclose(np.sort_complex(found), np.sort_complex(expected), rtol=1e-13)


def test_a_batch_is_scaled_row_by_row():
    # What it protects: each polynomial of a batch gets its own scale. Roots of size 2^673 beside
    # an ordinary cubic whose coefficients are 2^-100: one scale for both would push the small
    # row's coefficients below the smallest float.
    small = 2.0 ** -100 * np.array([2.0, -3.0, 1.0, 1.0])
    found = poly.roots(np.stack([[2.0 ** 1020, 0.0, 0.0, 2.0 ** -1000], small]))
    # the ordinary cubic on its own companion matrix, and scaled by powers of two: round-off
    assert_allclose(np.sort_complex(found[1]), np.sort_complex(poly.roots(small / 2.0 ** -100)),
                    rtol=1e-12)
    # roots of t^3 + 2^2020: 2^(2020/3) times the cube roots of -1, to round-off
    expected = 2.0 ** (2020 / 3) * np.exp(1j * np.pi * (2 * np.arange(3) + 1) / 3)
    assert_allclose(np.sort_complex(found[0]), np.sort_complex(expected), rtol=1e-12)


def test_roots_under_numpy_floating_point_errors_as_exceptions():
    # What it protects: roots handles its own overflow and underflow (errstate), so a caller
    # who turned numpy's floating-point warnings into exceptions still gets the roots.
    with np.errstate(all="raise"):
        assert_allclose(np.sort(poly.roots([1e300, 1.0, 1e-10]).imag), [-1e155, 1e155],
                        rtol=1e-12)  # as in test_roots_of_badly_scaled_polynomials
        # the companion's entry 2^-1030 / 3 is subnormal and rounded: an underflow
        assert np.abs(poly.roots([-(2.0 ** -1000) / 3, 0.0, 0.0, 2.0 ** 30])).min() > 0
        with pytest.raises(NonFiniteError):
            poly.roots([1e300, 1e-300])
        with pytest.raises(NonFiniteError):   # 1j times the infinite imaginary part: NaN
            poly.roots([1e300j, 1e-300])


def test_system_evaluation_is_in_complex_floating_point():
    # What it protects: integer points are not evaluated in integer arithmetic, where x^2 with
    # x = 2^33 would wrap around silently, and so would the derivative 3 x^2 of x^3; the
    # exponents are stored as integers (the documented type), so a power is a product, not
    # exp(e log x). Every value here is a float exactly (2^99 - 3 rounds to 2^99).
    system = PolynomialSystem.from_dicts([{(3, 0): 1, (0, 1): -1}, {(1, 1): 1}])
    assert all(e.dtype.kind == "i" for e, _ in system.terms)
    x = np.array([2 ** 33, 3])
    assert system(x).tolist() == [2.0 ** 99 - 3, 3.0 * 2 ** 33]
    assert system.jacobian(x).tolist() == [[3.0 * 2 ** 66, -1.0], [3.0, 2.0 ** 33]]


@MANY
@given(seed=st.integers(0, 10 ** 6), scale=st.floats(0.5, 2.0))
def test_homogenized_system_is_homogeneous_of_each_equations_degree(seed, scale):
    # What it protects: x0's exponent, degree minus the term's degree: H(s y) = s^d H(y)
    rng = np.random.default_rng(seed)
    eqs = [{tuple(rng.integers(0, 3, 2)): rng.normal() for _ in range(3)} for _ in range(2)]
    system = PolynomialSystem.from_dicts(eqs)
    H = system.homogenized()
    y = rng.normal(size=3) + 1j * rng.normal(size=3)
    # the same sums with every term multiplied by s^d: round-off of the terms' size
    assert_allclose(H(scale * y), scale ** np.array(system.degrees) * H(y),
                    atol=1e-12 * (1 + np.abs(H(y)).max()) * 4 ** max(system.degrees), rtol=0)


def test_mixed_volume_in_one_and_in_six_unknowns():
    # one unknown: the mixed volume is the length of the support's segment, the degree of a
    # polynomial whose constant term is non-zero (t^3 + t + 1 has 3 roots)
    assert poly.mixed_volume([[(0,), (1,), (3,)]]) == 3
    # six unknowns (the most allowed): the unit simplex, MV = 6! vol = 1 (a linear system)
    simplex = np.vstack([np.zeros(6, int), np.eye(6, dtype=int)])
    assert poly.mixed_volume([simplex] * 6) == 1


def test_a_monomial_equation_has_a_mixed_volume_of_zero():
    # a single-term support (x y = 0 has no solution with both coordinates non-zero): MV = 0
    assert poly.mixed_volume([[(1, 1)], [(0, 0), (1, 0)]]) == 0


def test_minkowski_points_limit_bounds_the_work(monkeypatch):
    # What it protects: the bound on one Minkowski sum's candidate points, at its edge; with the
    # limit lowered to 12, a sum of 3 x 4 vertices is computed and one of 4 x 4 is refused
    monkeypatch.setattr(poly, "MINKOWSKI_POINTS_LIMIT", 12)
    triangle, square = [(0, 0), (1, 0), (0, 1)], [(0, 0), (1, 0), (0, 1), (1, 1)]
    assert poly.mixed_volume([triangle, square]) == 2   # x + y + 1, with x y: 2 solutions
    with pytest.raises(ValueError, match=r"^a Minkowski sum of 16 candidate points exceeds 12 "):
        poly.mixed_volume([square, square])


def test_the_integer_check_of_the_mixed_volume(monkeypatch):
    # What it protects: the inclusion-exclusion sum is accepted within 1e-6 of its size of an
    # integer (qhull's round-off) and refused beyond. The hull's volumes are perturbed here (the
    # only way to reach the guard: integer supports give integer sums to round-off).
    hull = poly._hull
    dense = [[(i, j) for i in range(33) for j in range(33 - i)]] * 2   # MV = 32 * 32 = 1024
    monkeypatch.setattr(poly, "_hull", lambda p: (hull(p)[0], hull(p)[1] * (1 + 1e-9)))
    assert poly.mixed_volume(dense) == 1024     # off by about 1e-9 * 4000 = 4e-6, below 1e-3
    # two segments spanning the plane, MV 1 = vol(A + B) - vol(A) - vol(B) = 1 - 0 - 0; each
    # volume off by 0.25 makes the sum 1 + 0.25 - 2 * 0.25
    monkeypatch.setattr(poly, "_hull", lambda p: (hull(p)[0], hull(p)[1] + 0.25))
    with pytest.raises(ArithmeticError, match=r"^mixed volume 0\.75 is not an integer"):
        poly.mixed_volume([[(0, 0), (1, 0)], [(0, 0), (0, 1)]])
