"""Tests of mechnum.certify: roots proven on systems with known roots, certificates, definite.

Each system's test must fail on a broken Krawczyk operator: ``test_a_broken_krawczyk_is_caught``
runs every system again with two broken operators (one that drops the ``(I - Y J(X)) (X - y)``
term, one that uses the Jacobian at the midpoint instead of its enclosure over the box) and
checks that each system's own check then fails.
"""

import math

import numpy as np
import pytest
from flint import arb

from mechnum import certify
from mechnum.certify import _krawczyk as kr
from mechnum.certify import balls as B


def circle_hyperbola():
    """``x**2 + y**2 = 4``, ``x y = 1``: four roots, ``x**2 = 2 +- sqrt(3)``."""
    def f(X):
        return [X[0] * X[0] + X[1] * X[1] - 4, X[0] * X[1] - 1]

    def J(X):
        return [[2 * X[0], 2 * X[1]], [X[1], X[0]]]

    xs = [math.sqrt(2 + math.sqrt(3)), math.sqrt(2 - math.sqrt(3))]
    exact = [(s * x, s / x) for x in xs for s in (1, -1)]
    return f, J, [[-3.0, 3.0], [-3.0, 3.0]], exact


def trigonometric():
    """``sin x = 0``, ``cos y = 0`` on ``[-4, 4] x [-2, 2]``: six roots."""
    def f(X):
        return [B.sin(X[0]), B.cos(X[1])]

    def J(X):
        return [[B.cos(X[0]), arb(0)], [arb(0), -B.sin(X[1])]]

    exact = [(k * math.pi, s * math.pi / 2) for k in (-1, 0, 1) for s in (-1, 1)]
    return f, J, [[-4.0, 4.0], [-2.0, 2.0]], exact


def near_a_face():
    """``(x**3 + x - y, x + y + y**2 / 2)`` on ``[-0.5, 0.5]**2``: the one root ``(0, 0)`` lies
    on the face of the first cut, where Krawczyk is retried on a box enlarged (inside the
    searched box) around it."""
    return _face_system() + ([[-0.5, 0.5], [-0.5, 0.5]], [(0.0, 0.0)])


def _face_system():
    def f(X):
        return [X[0] ** 3 + X[0] - X[1], X[0] + X[1] + X[1] * X[1] / 2]

    def J(X):
        return [[3 * X[0] ** 2 + 1, arb(-1)], [arb(1), 1 + X[1]]]

    return f, J


def none_inside():
    """``x**2 + y**2 + 1 = 0``, ``x = y``: no real root."""
    def f(X):
        return [X[0] * X[0] + X[1] * X[1] + 1, X[0] - X[1]]

    def J(X):
        return [[2 * X[0], 2 * X[1]], [1, -1]]

    return f, J, [[-2.0, 2.0], [-2.0, 2.0]], []


SYSTEMS = {"polynomial": circle_hyperbola, "trigonometric": trigonometric,
           "root near a face": near_a_face, "no root": none_inside}


def proves_exactly(result, exact):
    """The search is complete, counts the exact roots, and each enclosure holds one of them."""
    if not result.complete or result.count != len(exact):
        return False
    for root in exact:
        inside = [bool(np.all((E[:, 0] <= root) & (root <= E[:, 1]))) for E in result.roots]
        if sum(inside) != 1:
            return False
    return True


@pytest.mark.parametrize("name", SYSTEMS)
def test_known_roots_are_proven(name):
    f, J, box, exact = SYSTEMS[name]()
    result = certify.roots(f, J, box, max_boxes=5000)
    assert proves_exactly(result, exact), result.message
    assert result.status == "converged" and result.converged
    assert result.iterations == result.boxes and result.nfev > 0 and result.njev >= 0
    widths = result.roots[:, :, 1] - result.roots[:, :, 0]
    assert np.all(widths < 1e-10)            # the enclosures are tightened to the rounding


def double_root():
    """``((x - 1/4)**2, y - 1/8)``: a double root at ``(1/4, 1/8)``, where Krawczyk's test can
    never pass (the Jacobian is singular there)."""
    def f(X):
        return [(X[0] - 0.25) ** 2, X[1] - 0.125]

    def J(X):
        return [[2 * (X[0] - 0.25), arb(0)], [arb(0), arb(1)]]

    return f, J, [[-1.0, 1.0], [-1.0, 1.0]]


def test_a_double_root_stays_undecided():
    f, J, box = double_root()
    result = certify.roots(f, J, box, max_boxes=2000, min_width=1e-8)
    assert result.count == 0 and not result.complete and result.status == "undecided"
    assert len(result.undecided) > 0
    assert all(np.all((U[:, 0] <= [0.25, 0.125]) | (U[:, 1] >= [0.25, 0.125]))
               for U in result.undecided)
    held = [bool(np.all((U[:, 0] <= [0.25, 0.125]) & ([0.25, 0.125] <= U[:, 1])))
            for U in result.undecided]
    assert any(held)                          # the root is in an undecided box, not dropped


def test_the_budget_leaves_boxes_undecided_not_dropped():
    f, J, box, exact = circle_hyperbola()
    result = certify.roots(f, J, box, max_boxes=10)
    assert not result.complete and len(result.undecided) > 0
    volume = sum(np.prod(L.box[:, 1] - L.box[:, 0]) for part in result.leaves for L in part)
    assert volume == pytest.approx(36.0, rel=1e-12)     # the leaves still cover the box


REAL_KRAWCZYK = kr.krawczyk


def _broken_no_contraction(fy, J, X, yb, Y):
    """Krawczyk's operator without its ``(I - Y J(X)) (X - y)`` term: Newton's point only."""
    n = len(X)
    step = [sum((arb(float(Y[i, j])) * fy[j] for j in range(n)), arb(0)) for i in range(n)]
    return [y - s for y, s in zip(yb, step)], 0.0


def _broken_point_jacobian(fy, J, X, yb, Y):
    """Krawczyk's operator with the Jacobian at the midpoint, not over the box."""
    return REAL_KRAWCZYK(fy, [[arb(v.mid()) for v in row] for row in J], X, yb, Y)


@pytest.mark.parametrize("broken", [_broken_no_contraction, _broken_point_jacobian])
def test_a_broken_krawczyk_is_caught(monkeypatch, broken):
    """With a broken operator, every system's check above fails (and the double root is said
    to be one root, or the search complete): the tests catch the bug."""
    monkeypatch.setattr(kr, "krawczyk", broken)
    caught = {}
    for name, system in SYSTEMS.items():
        f, J, box, exact = system()
        caught[name] = not proves_exactly(certify.roots(f, J, box, max_boxes=5000), exact)
    f, J, box = double_root()
    result = certify.roots(f, J, box, max_boxes=2000, min_width=1e-8)
    caught["double root"] = result.count > 0 or result.complete
    assert all(caught.values()), caught


def test_a_root_on_the_face_between_two_searched_boxes_stays_undecided():
    """No test box leaves its searched box (the function may be another beyond it): a root on
    the face between two boxes cannot be proven inside either, and stays in an undecided
    leaf; searched as one box, it is proven."""
    f, J = _face_system()
    boxes = [[[-0.5, 0.0], [-0.5, 0.5]], [[0.0, 0.5], [-0.5, 0.5]]]
    result = certify.roots(f, J, boxes, max_boxes=5000)
    assert not result.complete and result.count == 0 and result.status == "undecided"
    assert any(np.all((U[:, 0] <= 0.0) & (0.0 <= U[:, 1])) for U in result.undecided)
    tested = [leaf.test_box for part in result.leaves for leaf in part
              if leaf.test == "krawczyk"]
    assert all(np.all(T[:, 0] >= -0.5) and np.all(T[:, 1] <= 0.5) for T in tested)
    assert proves_exactly(certify.roots(f, J, [[-0.5, 0.5], [-0.5, 0.5]]), [(0.0, 0.0)])


def test_overlapping_searched_boxes_are_refused():
    f, J, box, _ = circle_hyperbola()
    with pytest.raises(ValueError, match="overlap"):
        certify.roots(f, J, [box, [[2.0, 4.0], [2.0, 4.0]]])
    result = certify.roots(f, J, [box, [[3.0, 4.0], [-3.0, 3.0]]])     # faces may touch
    assert result.count == 4 and result.complete


def test_an_existence_search_is_never_complete():
    f, J, box, _ = circle_hyperbola()
    result = certify.roots(f, J, [[1.8, 2.0], [0.4, 0.6]], scope="existence")
    assert result.count == 1 and result.scope == "existence" and not result.complete
    assert result.status == "converged" and "exist" in result.message
    with pytest.raises(ValueError, match="scope"):
        certify.roots(f, J, box, scope="some")


def test_bad_input_is_refused():
    f, J, box, _ = circle_hyperbola()
    with pytest.raises(ValueError, match="max_boxes"):
        certify.roots(f, J, box, max_boxes=certify.MAX_BOXES_LIMIT + 1)
    with pytest.raises(ValueError, match="min_width"):
        certify.roots(f, J, box, min_width=0.9)
    with pytest.raises(ValueError, match="lo <= hi"):
        certify.roots(f, J, [[1.0, 0.0], [0.0, 1.0]])
    with pytest.raises(ValueError, match="at least one coordinate"):
        certify.roots(f, J, np.zeros((1, 0, 2)))


def test_definite():
    assert certify.definite([[arb(2, 0.5), arb(1)], [arb(1), arb(2, 0.5)]]) is True
    assert certify.definite([[arb(1), arb(2)], [arb(2), arb(1)]]) is False
    assert certify.definite([[arb(1), arb(1, 0.5)], [arb(1, 0.5), arb(1)]]) is None
    assert certify.definite([[4.0, 2.0, 0.0], [2.0, 3.0, 1.0], [0.0, 1.0, -0.5]]) is False
    assert certify.definite([]) is True
    with pytest.raises(ValueError, match="square"):
        certify.definite([[1.0, 2.0]])


def test_definite_needs_a_symmetric_matrix():
    """Entries (i, j) and (j, i) that cannot hold the same number are refused, naming them;
    entries that overlap are met: the verdict is for the symmetric matrices in both."""
    with pytest.raises(ValueError, match=r"\(0, 1\) = 0 and \(1, 0\) = 2"):
        certify.definite([[1.0, 0.0], [2.0, 1.0]])         # the lower triangle is definite
    with pytest.raises(ValueError, match=r"\(1, 2\) = .* and \(2, 1\) = "):
        certify.definite([[2.0, 0.0, 0.0], [0.0, 2.0, arb(1, 0.1)], [0.0, arb(-1, 0.1), 2.0]])
    # (1, 0) in [0, 4] and (0, 1) in [1.5, 2.5]: the symmetric members have a_01 in
    # [1.5, 2.5], so det = 1 - a_01**2 < 0 for all of them (the lower ball alone would not say)
    assert certify.definite([[1.0, arb(2, 0.5)], [arb(2, 2), 1.0]]) is False
    assert certify.definite([[1.0, arb(2, 2)], [arb(2, 2), 1.0]]) is None


def test_balls_enclose_wide_intervals():
    x = certify.balls.ball(-1.0, 4.0)
    lo, hi = certify.balls.bounds(B.cos(x))
    # cos over [-1, 4] contains [-1, 1]; Arb's enclosure is wider by round-off only (a few ulps of
    # 1), far below 1e-8
    assert lo <= -1.0 and hi >= 1.0 and hi - lo < 2.0 + 1e-8
    lo, hi = certify.balls.bounds(B.sin(certify.balls.ball(0.1, 0.2)))
    assert lo <= math.sin(0.1) and math.sin(0.2) <= hi and hi - lo < 0.1
    lo, hi = B.bounds(B.mul(B.ball(10.0, 1e5), B.ball(0.96, 1.0)))
    assert 0.0 < lo <= 9.6 and 1e5 <= hi


def test_a_point_box_at_a_subnormal_keeps_its_root():
    """``x = 3 * 2**-1074``, a root of ``(2**1074 x - 3)**2`` and the box's only point: the
    halves of its ends round up, and a midpoint taken outside the box once made the
    mean-value form exclude it ("complete, 0 roots"). In 1-D and as a slice of a 2-D box."""
    tiny = 3 * 5e-324
    scale = arb(2) ** 1074
    f = lambda X: [(X[0] * scale - 3) ** 2]                      # noqa: E731
    J = lambda X: [[2 * scale * (X[0] * scale - 3)]]             # noqa: E731
    for y in (np.array([[tiny, tiny]]), np.array([[tiny, tiny], [-1.0, 1.0]])):
        assert np.all((y[:, 0] <= kr.midpoint(y)[1]) & (kr.midpoint(y)[1] <= y[:, 1]))
    result = certify.roots(f, J, [[tiny, tiny]])
    assert not (result.complete and result.count == 0)
    f2 = lambda X: [(X[0] * scale - 3) ** 2 + X[1] * 0, X[1]]   # noqa: E731
    J2 = lambda X: [[2 * scale * (X[0] * scale - 3), X[1] * 0],  # noqa: E731
                    [X[0] * 0, X[1] * 0 + 1]]
    result = certify.roots(f2, J2, [[tiny, tiny], [-1.0, 1.0]])
    assert not (result.complete and result.count == 0)
