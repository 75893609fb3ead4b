"""Tests of mechnum.mechanisms._assembly (what the 2RFR and the 3PFR share) and of the layering of
the
mechanisms built on it."""

import ast
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from mechnum.mechanisms import _assembly as assembly
from mechnum.rods import _profile as profile
from mechnum.rods import chart_from_clamps, peak_moment

PACKAGE = Path(assembly.__file__).resolve().parents[2]


def _quadratic(x, p):
    return x ** 2 - (p - 1.0) ** 2, 2.0 * x[:, :, None]


def test_follow_reports_a_sign_change_of_the_determinant_as_a_branch_jump():
    # x**2 = (p - 1)**2 from x = 1: the branch x = 1 - p meets x = p - 1 at p = 1; the secant
    # prediction carries Newton across to x = 1 - p < 0, where det = 2 x has the other sign
    trace = assembly.follow(_quadratic, np.array([1.0]), np.array([[0.0], [0.5], [1.5], [2.0]]),
                            tol=1e-12)
    assert trace.status.tolist() == ["converged", "converged", "branch-jump", "branch-jump"]
    # the path's Newton (tol 1e-12 on the residual, quadratic) lands on x = 1 - p to round-off
    np.testing.assert_allclose(trace.x[:2, 0], [1.0, 0.5], rtol=1e-12)
    assert trace.nfev > 0 and trace.njev > 0


def test_follow_keeps_the_signs_of_a_chart():
    # (psi, t) with t = p - 1: the root's t changes sign at p = 1, det stays 1
    def fun(u, p):
        return (np.stack((u[:, 0] - 1.0, u[:, 1] - (p[:, 0] - 1.0)), axis=-1),
                np.broadcast_to(np.eye(2), (len(u), 2, 2)))

    params = np.linspace(0.0, 2.0, 5)[:, None]
    free = assembly.follow(fun, np.array([1.0, -1.0]), params, tol=1e-12)
    chart = assembly.follow(fun, np.array([1.0, -1.0]), params, tol=1e-12, chart=2)
    assert (free.status == "converged").all()
    assert chart.status.tolist() == ["converged"] * 2 + ["branch-jump"] * 3


def test_follow_of_an_empty_path_and_of_a_batch():
    empty = assembly.follow(_quadratic, np.ones((2, 1)), np.empty((0, 2, 1)), tol=1e-12)
    assert empty.x.shape == (0, 2, 1) and empty.status.shape == (0, 2)
    p = np.linspace(0.0, -3.0, 7)[:, None, None] * [[1.0], [2.0]]        # two paths at once
    both = assembly.follow(_quadratic, np.array([[1.0], [1.0]]), p, tol=1e-12)
    np.testing.assert_allclose(both.x[..., 0], 1.0 - p[..., 0], rtol=1e-12)


def test_follow_grid_reaches_every_point_it_can_and_no_other():
    # u**2 + |p|**2 = 1: a solution only inside the unit disc, which continuation cannot leave
    def fun(u, p):
        return u ** 2 + np.sum(p ** 2, axis=-1, keepdims=True) - 1.0, 2.0 * u[:, :, None]

    def trace(params, u0):
        return assembly.follow(fun, u0, params, tol=1e-12, resume=False)

    g = np.linspace(-1.1, 1.1, 12)
    grid = np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1)
    result = assembly.follow_grid(trace, grid, (5, 5), np.array([1.0]))
    inside = np.sum(grid ** 2, axis=-1) < 1.0
    ok = result.status == "converged"
    assert not (ok & ~inside).any() and ok.sum() > 0.8 * inside.sum()
    assert ok[5, 1:11].all() and ok[1:11, 5].all()         # the lines through the start
    np.testing.assert_allclose(result.x[ok, 0], np.sqrt(1 - np.sum(grid[ok] ** 2, -1)),
                               rtol=1e-10)


def test_workspace_edge_finds_the_fold():
    def fun(x, p):
        return x ** 2 + np.sum(p ** 2, -1, keepdims=True) - 1.0, 2.0 * x[:, :, None]

    def trace(params, u):
        return assembly.follow(fun, u, params, tol=1e-12, resume=False)

    edge, _, status, nfev, _ = assembly.workspace_edge(
        trace, np.zeros(2), np.array([1.0]), directions=5, step=0.1, reach=2.0, levels=4)
    radius = np.hypot(*edge.T)
    assert (status == "converged").all() and nfev > 0
    # the rays stop within the last bisection's step (0.1 / 4^4) inside the unit circle; 1e-12
    # allows for the rounding of the radius
    assert ((radius > 1.0 - 0.1 / 4 ** 4 - 1e-12) & (radius <= 1.0)).all()
    with pytest.raises(ValueError, match="bound on the work"):
        assembly.workspace_edge(trace, np.zeros(2), np.array([1.0]), directions=5, step=1e-5,
                                reach=1.0, levels=1)


def test_zero_crossings_lie_on_the_grid_lines():
    g = np.linspace(-1.0, 1.0, 21)
    X, Y = np.meshgrid(g, g, indexing="ij")
    points = assembly.zero_crossings(g, g, X + 2 * Y - 0.33)
    # the crossings are interpolated linearly along grid lines of a linear function: exact up to
    # round-off
    np.testing.assert_allclose(points[:, 0] + 2 * points[:, 1], 0.33, rtol=1e-12)
    # a crossing lies on a grid line (a multiple of 0.1 in one coordinate) up to the rounding of the
    # grid (linspace) and of the division by 0.1
    on_lines = np.isclose(np.remainder(points / 0.1 + 0.5, 1.0) - 0.5, 0.0, atol=1e-9)
    assert on_lines.any(axis=1).all() and len(points) > 10


@given(psi=st.floats(0.05, 2 * np.pi - 0.05), t=st.floats(0.02, 0.99),
       sign=st.sampled_from([-1.0, 1.0]), mode=st.integers(1, 3),
       angle=st.floats(-np.pi, np.pi))
def test_peak_moment_is_the_supremum_of_the_moment(psi, t, sign, mode, angle):
    rod = profile.shape(1.0, 1.0, psi, sign * t, mode, nodes=4001)
    c, s = np.cos(angle), np.sin(angle)
    force = np.array([c * rod.force[0] - s * rod.force[1], s * rod.force[0] + c * rod.force[1]])
    peak = peak_moment(1.0, rod.m[0], force, angle, mode)
    sampled = np.abs(rod.m).max()
    # never below a sample; above the largest only by what the grid misses near a crest,
    # where |m| is flat: |m''| h**2 / 8 with |m''| <= |n| |m| / EI
    assert sampled <= peak * (1 + 1e-9) + 1e-12
    assert peak - sampled <= np.hypot(*force) * peak / 4000 ** 2 / 8 * 1.5 + 1e-9 * peak


def test_chart_from_clamps_gives_no_chart_on_the_edge_psi_2_pi():
    # a straight rod pulled along its clamped tangent, as shooting leaves it under another
    # machine's arithmetic: psi rounds to 2 pi, where the chart has no t
    EI = 0.05218602640386952
    chart, _ = chart_from_clamps(EI, 1.0, [0.0, 0.0], [-2.50542746e-17, 0.01],
                                          [[0.202746622, -5.13381724e-17], [0.0, -0.05]])
    assert chart[0] == 2 * np.pi and np.isnan(chart[1])
    assert 0 < chart[2] < 2 * np.pi and -1 < chart[3] < 1


def test_checks():
    assert assembly.check_segments([200, 400]) == (200, 400)
    with pytest.raises(ValueError, match="pair"):
        assembly.check_segments((1, 2, 3))
    with pytest.raises(ValueError, match="pair"):
        assembly.check_segments((300,))
    with pytest.raises(ValueError, match="modes"):
        assembly.check_modes((1.5, 1), 2)
    with pytest.raises(ValueError, match="more than"):
        assembly.points(np.zeros((assembly.MAX_POINTS + 1, 1)), "poses", 1)
    assert assembly.points([], "poses", 3).shape == (0, 3)


def test_results_follow_the_contract():
    from mechnum.results import STATUSES
    trace = assembly.trace_of(np.zeros((3, 2)), np.array(["converged", "branch-jump", "lost"]),
                              np.zeros(3, int), 1, 1)
    lay = assembly.Layout(rods=1, inputs=1, pose=1)
    path = assembly.path_of(trace, np.zeros((3, 1)), lay, lambda x, p: (
        p, p, x, np.ones((len(x), 1), int), np.ones(len(x)), np.ones(len(x)),
        np.ones((len(x), 1, 1))))
    assert set(path.status) <= set(STATUSES) and path.converged.tolist() == [True, False, False]
    assert np.isnan(path.chart[1:]).all() and (path.modes[1:] == 0).all()
    assert path.message == "1 of 3 points converged; 1 branch-jump, 1 lost"
    assert len(path.states()) == 1


# --- layering (issue 22): no mechanism imports another, no private name crosses subpackages --

def _imports(path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            yield node.module, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, []


FLEXIBLE = [*(PACKAGE / "mechanisms" / "rfr2").glob("*.py"),
            *(PACKAGE / "mechanisms" / "pfr3").glob("*.py"),
            *(PACKAGE / "mechanisms" / "_assembly").glob("*.py"),
            PACKAGE / "mechanisms" / "thesis.py"]


@pytest.mark.parametrize("path", FLEXIBLE, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_no_mechanism_imports_another_nor_a_private_name_of_another(path):
    own = path.parent.name
    for module, names in _imports(path):
        parts = module.split(".")
        if parts[:2] == ["mechnum", "mechanisms"] and len(parts) > 2:
            assert parts[2] in (own, "thesis", "_assembly"), f"{path.name} imports {module}"
        private = [n for n in names + parts if n.startswith("_") and n != "_validate"]
        if private and parts[0] == "mechnum":    # its own subpackage's only: the mechanisms'
            assert parts[:2] == ["mechnum", "mechanisms"], \
                f"{path.name} imports {private} from {module}"


def test_the_rods_layer_imports_no_mechanism():
    for path in (PACKAGE / "rods").glob("*.py"):
        for module, _ in _imports(path):
            assert not module.startswith("mechnum.mechanisms"), f"{path.name} imports {module}"
