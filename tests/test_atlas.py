"""The atlas of assemblies (mechnum.rods.assembly.atlas and parallel; rfr2.atlas, pfr3.atlas).

The method is checked on the cusp, ``x**3 - a x - b = 0``, whose count is known everywhere
(three roots where ``4 a**3 > 27 b**2``, two of them stable minima of ``x**4/4 - a x**2/2 -
b x``; one elsewhere), then on the 2RFR against the full search at every point of a 9 x 9
subgrid, most of which the atlas did not search; on a dask cluster of two workers; on bad input.
"""

from functools import partial

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from mechnum.mechanisms import pfr3, rfr2  # noqa: E402
from mechnum.rods import assembly  # noqa: E402
from mechnum.rods.assembly import atlas as atlases  # noqa: E402
from mechnum.rods.assembly import parallel  # noqa: E402


# ---------------------------------------------------------------- the cusp, x**3 - a x - b = 0
def cusp_search(task):
    """Every real root of the cusp at each point of a task, and which are minima."""
    out = []
    for _, (a, b) in zip(*task):
        x = np.roots([1.0, 0.0, -a, -b])
        x = np.sort(x[np.abs(x.imag) < 1e-9].real)[:, None]
        out.append((x, 3 * x[:, 0] ** 2 - a > 0, True, 1))
    return out


def cusp_trace(params, u0):
    fun = lambda x, p: x ** 3 - p[:, :1] * x - p[:, 1:]              # noqa: E731
    jac = lambda x, p: (3 * x ** 2 - p[:, :1])[:, :, None]            # noqa: E731
    return assembly.follow(fun, jac, params, u0, tol=atlases.STEP_TOL, resume=False,
                           criterion="step")


CUSP = atlases.AtlasProblem(cusp_search, cusp_trace, lambda p, x: x, 1)


def cusp_atlas(a, b, executor=1, problem=CUSP):
    grid = np.stack(np.meshgrid(a, b, indexing="ij"), axis=-1)
    return atlases.atlas_of(problem, grid, ((a, b), np.zeros(2), np.eye(2)), ("a", "b"), 1.0,
                            (1,), executor)


def cusp_truth(a, b):
    A, B = np.meshgrid(a, b, indexing="ij")
    inside = 4 * A ** 3 > 27 * B ** 2
    return np.where(inside, 3, 1), np.where(inside, 2, 1)


# no grid point on the folds (4 a**3 = 27 b**2), where a double root makes the count ambiguous
A_AXIS, B_AXIS = np.linspace(-0.5, 1.5, 33) + 0.003, np.linspace(-1.0, 1.0, 33) + 0.01


def test_the_cusp_counts_are_exact_at_every_point_with_few_searches():
    at = cusp_atlas(A_AXIS, B_AXIS)
    counts, stable = cusp_truth(A_AXIS, B_AXIS)
    assert np.array_equal(at.counts, counts) and np.array_equal(at.stable_counts, stable)
    assert at.searched.sum() < 0.3 * at.counts.size           # continuation did most
    assert (at.vouched | at.searched).all() and at.converged.all()
    # the folds: the edges where the stable count changes, and only those
    changes = (stable[1:] != stable[:-1]).sum() + (stable[:, 1:] != stable[:, :-1]).sum()
    assert len(at.folds) == changes > 0
    A, B = at.folds.T
    assert np.abs(4 * A ** 3 - 27 * B ** 2).max() < 1.0      # near the cusp's two fold lines


def test_a_point_next_to_a_fold_is_searched_and_a_vouched_one_has_no_branch_ending():
    at = cusp_atlas(A_AXIS, B_AXIS)
    counts = at.counts
    # every point of the region of three roots that borders the region of one was searched
    border = np.zeros_like(counts, dtype=bool)
    border[1:] |= counts[1:] > counts[:-1]
    border[:-1] |= counts[:-1] > counts[1:]
    border[:, 1:] |= counts[:, 1:] > counts[:, :-1]
    border[:, :-1] |= counts[:, :-1] > counts[:, 1:]
    assert border.any() and at.searched[border].all()
    assert not (at.vouched & border).any()


def test_the_equilibria_and_their_stability_are_the_roots_and_the_minima():
    at = cusp_atlas(A_AXIS[::4], B_AXIS[::4])
    for i, a in enumerate(at.axes[0]):
        for j, b in enumerate(at.axes[1]):
            x = np.sort(at.chart[i, j, :at.counts[i, j], 0])
            # the cusp's equilibria are polished roots of x^3 - a x - b with |x| of order one:
            # residual round-off
            assert np.abs(x ** 3 - a * x - b).max() < 1e-12
            order = np.argsort(at.chart[i, j, :at.counts[i, j], 0])
            assert np.array_equal(at.stable[i, j, :at.counts[i, j]][order], 3 * x ** 2 - a > 0)


def test_an_empty_grid_is_an_empty_atlas():
    at = cusp_atlas(np.zeros(0), B_AXIS)
    assert at.counts.shape == (0, 33) and at.folds.shape == (0, 2) and at.searched.sum() == 0
    empty = rfr2.atlas(rfr2.TABLE7, [], [0.1, 0.2], executor=1)
    assert empty.counts.shape == (0, 2) and empty.stable_counts.shape == (0, 2)
    assert pfr3.atlas(pfr3.TABLE8, np.zeros((0, 3, 3)), executor=1).counts.shape == (0, 3)


def test_the_anchors_are_block_centres_and_one_at_least():
    assert atlases.anchors(1, 1).tolist() == [0]
    assert sorted(atlases.anchors(16, 1).tolist()) == [4, 12]
    assert atlases.anchors(0, 5).size == 0


# ------------------------------------------------------------------------- the 2RFR's atlas
# 2.5 degrees apart, over a fold (3 equilibria to 2) and a corner with 4
WINDOW = (np.radians(np.linspace(50.0, 70.0, 9)), np.radians(np.linspace(40.0, 60.0, 9)))


@pytest.fixture(scope="module")
def rfr2_atlas():
    return rfr2.atlas(rfr2.TABLE7, *WINDOW, executor=1)      # serially, in this process


def _full_search(point):
    """The full search from other starts than the atlas's: 400, and a check of 400 more that
    must find nothing new (the search is sampled: a count it is unsure of proves nothing)."""
    eq = rfr2.forward_elliptic(rfr2.TABLE7, point, n_starts=400, check=1, rng=0)
    assert eq.search.complete
    return len(eq.chart), int(eq.stable.sum())


def test_the_2rfr_atlas_equals_the_full_search_at_every_point_of_a_9x9_grid(rfr2_atlas):
    at = rfr2_atlas
    assert len(np.unique(at.counts)) == 3                      # the window holds folds
    # the full search (other starts than the atlas's) wherever the atlas did not search
    vouched = np.argwhere(~at.searched)
    assert len(vouched) >= 55 and at.vouched[~at.searched].all()   # few searches
    found = parallel.run(_full_search, [at.inputs[i, j] for i, j in vouched], 2)
    atlas_says = [(at.counts[i, j], at.stable_counts[i, j]) for i, j in vouched]
    assert atlas_says == found


def test_the_2rfr_atlas_holds_equilibria(rfr2_atlas):
    at = rfr2_atlas
    i, j = np.argwhere(at.counts > 0)[[0, -1]].T
    for i_, j_ in zip(i, j):
        for k in range(at.counts[i_, j_]):
            s = at.state(i_, j_, k)
            # the atlas's equilibria come from Newton stopped at STEP_TOL = 1e-10 on the
            # relative step, after a quadratic last step: residuals of an O(1) system far below
            # 1e-9
            assert np.abs(rfr2.residual(rfr2.TABLE7, s.inputs, s.chart)).max() < 1e-9
    with pytest.raises(ValueError, match="has 3 equilibria, no equilibrium 5"):
        at.state(*np.argwhere(at.counts == 3)[0], 5)


def test_the_atlas_draws_its_map_folds_and_a_trajectory(rfr2_atlas):
    fig, ax = plt.subplots()
    path = rfr2.TABLE7_THETA + rfr2.path("direct circles")
    artists = rfr2_atlas.draw(ax, trajectory=path)
    segments = artists["folds"].get_segments()
    assert len(segments) == len(rfr2_atlas.folds) > 0
    assert artists["map"].get_array().size == rfr2_atlas.counts.size
    # the trajectory drawn in degrees is np.degrees of the path: numpy's allclose default (rtol
    # 1e-5) is far above that conversion's round-off
    assert np.allclose(artists["trajectory"].get_xdata(), np.degrees(path[:, 0]))
    assert ax.get_xlabel() == "theta1 (deg)"
    with pytest.raises(ValueError, match="trajectory must have shape"):
        rfr2_atlas.draw(ax, trajectory=np.zeros((3, 3)))
    plt.close(fig)


def test_the_atlas_runs_the_same_on_a_dask_cluster_of_two_workers(rfr2_atlas):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        assert parallel.workers(client) == 2
        on_cluster = rfr2.atlas(rfr2.TABLE7, *WINDOW, executor=client)
    serial = rfr2_atlas
    assert serial.searched.sum() > 2 * parallel.workers(2)      # several tasks per worker
    for name in ("counts", "stable_counts", "searched", "vouched", "stable", "folds"):
        assert np.array_equal(getattr(serial, name), getattr(on_cluster, name)), name
    assert np.array_equal(serial.chart, on_cluster.chart, equal_nan=True)


def test_joblib_on_two_workers_gives_the_serial_result():
    serial = cusp_atlas(A_AXIS[::2], B_AXIS[::2])
    pooled = cusp_atlas(A_AXIS[::2], B_AXIS[::2], executor=2)
    assert np.array_equal(serial.counts, pooled.counts)
    assert np.array_equal(serial.chart, pooled.chart, equal_nan=True)


# ----------------------------------------------------------------------- the 3PFR's atlas
def test_the_3pfr_plane_and_its_atlas():
    s = np.linspace(-0.002, 0.002, 3)
    grid = s[:, None, None] * [1.0, 0.0, 0.0] + s[None, :, None] * [0.0, 0.0, 1.0]
    at = pfr3.atlas(pfr3.TABLE8, grid, executor=1)
    eq = pfr3.forward_elliptic(pfr3.TABLE8, grid[2, 0], rng=0)
    assert (at.counts[2, 0], at.stable_counts[2, 0]) == (len(eq.chart), eq.stable.sum())
    # the plane's coordinates of grid points built from multiples of 0.002: round-off, within
    # numpy's default rtol 1e-5
    assert np.allclose(at.coordinates(grid[2, 0]), [0.004, 0.0])
    # unit directions recovered from the grid's first row and column: round-off, within numpy's
    # default
    assert np.allclose(at.directions, [[1, 0, 0], [0, 0, 1]])


@pytest.mark.parametrize("grid, message", [
    (np.zeros((3, 3, 2)), "must have shape"),
    (np.zeros((3, 3)), "must have shape"),
    (np.ones((3, 3, 3)), "span a plane"),
    (np.linspace(0, 0.01, 27).reshape(3, 3, 3) ** 2, "lies .* from the plane"),
    (np.full((3, 3, 3), np.nan), "finite"),
])
def test_the_3pfr_atlas_refuses_a_grid_that_is_no_plane(grid, message):
    with pytest.raises(ValueError, match=message):
        pfr3.atlas(pfr3.TABLE8, grid, executor=1)


@pytest.mark.parametrize("mech, modes, executor, message", [
    (rfr2.TABLE7, (1, 1, 1), 1, "mech must be a Mechanism"),
    (pfr3.TABLE8, (1, 1), 1, "modes must have shape"),
    (pfr3.TABLE8, (1, 1, 1), -2, "executor must be None"),
])
def test_the_3pfr_atlas_names_bad_input(mech, modes, executor, message):
    with pytest.raises(ValueError, match=message):
        pfr3.atlas(mech, np.zeros((2, 2, 3)) + [0.0, 0.0, 0.001] * np.arange(2)[:, None, None],
                   modes=modes, executor=executor)


# ---------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, message", [
    ({"mech": None}, "mech must be a Mechanism"),
    ({"theta1": [[0.1]]}, "theta1"),
    ({"theta2": [np.nan]}, "theta2"),
    ({"theta2": [0.1, 0.1]}, "theta2 must be strictly increasing or decreasing"),
    ({"modes": (1, 0)}, "modes must be 2 integers"),
    ({"executor": 0}, "executor must be None"),
    ({"executor": True}, "executor must be None"),
    ({"executor": "dask"}, "executor must be None"),
    ({"theta1": np.zeros(1001), "theta2": np.zeros(1000)}, "a bound on the work"),
])
def test_the_2rfr_atlas_names_bad_input(kwargs, message):
    args = {"mech": rfr2.TABLE7, "theta1": [0.7], "theta2": [1.0], "modes": (1, 1),
            "executor": 1} | kwargs
    with pytest.raises(ValueError, match=message):
        rfr2.atlas(args.pop("mech"), args.pop("theta1"), args.pop("theta2"), **args)


def test_parallel_runs_in_order_on_every_executor():
    tasks = list(range(7))
    assert parallel.run(partial(pow, 2), tasks, 1) == [2 ** t for t in tasks]
    assert parallel.run(partial(pow, 2), tasks, 2) == [2 ** t for t in tasks]
    assert parallel.run(abs, [], None) == []
    assert [len(c) for c in parallel.chunks(list(range(9)), 1)] == [3, 2, 2, 2]
    assert parallel.chunks([], None) == []
