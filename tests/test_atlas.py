"""The atlas of assemblies (mechnum.mechanisms._assembly: its atlas and parallel modules;
rfr2.atlas, pfr3.atlas).

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

from mechnum.mechanisms import _assembly as assembly  # noqa: E402
from mechnum.mechanisms import pfr3, rfr2  # noqa: E402
from mechnum.mechanisms._assembly import _atlas as atlases  # noqa: E402
from mechnum.mechanisms._assembly import _parallel as parallel  # noqa: E402
from mechnum.mechanisms._assembly._lockstep import track_paths  # noqa: E402


# ---------------------------------------------------------------- the cusp, x**3 - a x - b = 0
def cusp_search(task):
    """Every real root of the cusp at each point of a task, and which are minima."""
    out = []
    for _, (a, b) in zip(*task):               # (rngs, points): the cusp needs no random starts
        x = np.roots([1.0, 0.0, -a, -b])
        x = np.sort(x[np.abs(x.imag) < 1e-9].real)[:, None]
        out.append((x, 3 * x[:, 0] ** 2 - a > 0, True, 1))
    return out


def cusp_system(x, p):
    """The cusp's residual and derivative at rows ``x`` (n, 1) and inputs ``p`` (n, 2)."""
    return x ** 3 - p[:, :1] * x - p[:, 1:], (3 * x ** 2 - p[:, :1])[:, :, None]


CUSP = atlases.AtlasProblem(cusp_search, cusp_system, lambda x: np.ones(len(x), dtype=bool),
                            lambda p, x: x, 1)


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


@pytest.mark.parametrize("steps", [2, 9])
def test_the_flood_steps_all_its_edges_at_once_as_follow_steps_each(steps):
    """One lockstep step of the flood (all its paths in one damped Newton per point) decides as
    assembly.follow (solve_path and the branch tests) does path by path: the cusp's roots
    followed over random steps across its folds, as one step and as the REFINE short ones
    (statuses converged, branch-jump, stagnated, lost), and the 2RFR's (left-domain, maxiter
    too)."""
    rng = np.random.default_rng(0)
    a0, b0 = rng.uniform(0.2, 1.5, 400), rng.uniform(-0.3, 0.3, 400)
    u0 = np.array([[rng.choice(cusp_search(([0], [(a, b)]))[0][0][:, 0])] for a, b in
                   zip(a0, b0)])
    p0 = np.column_stack((a0, b0))
    params = np.linspace(p0, p0 + rng.uniform(-0.8, 0.8, (400, 2)), steps)
    follow = assembly.follow(cusp_system, u0, params, tol=atlases.STEP_TOL, resume=False,
                             criterion="step")
    status, x, iterations, _ = track_paths(CUSP.system, CUSP.domain, 1, params, u0,
                                           tol=atlases.STEP_TOL)
    assert np.array_equal(status, follow.status) and len(set(status.ravel())) >= 3
    assert np.array_equal(iterations, follow.iterations)
    assert np.array_equal(x, follow.x[-1], equal_nan=True)
    assert steps == 9 or "branch-jump" in status            # the one-step jumps across folds

    from mechnum.mechanisms.rfr2._continuation import grid_trace
    from mechnum.rods import _kernels as kernels
    from mechnum.rods import in_chart

    M, theta0 = rfr2.study.TABLE7, np.radians([40.0, 60.0])
    eq = rfr2.forward(M, theta0, rng=0)
    pick = rng.integers(0, len(eq.x), 200)
    u0 = np.concatenate((eq.x[pick], eq.pose[pick]), axis=1)
    params = np.linspace(np.broadcast_to(theta0, (200, 2)),
                         theta0 + np.radians(rng.uniform(-40.0, 40.0, (200, 2))), steps)

    def system(u, p):
        return kernels.joined(M.EI, M.L, M.origins, p, [1.0, 1.0], M.force, u)

    def domain(u):
        return in_chart(u[:, :4])

    with kernels.reference():           # the same arithmetic: the same numbers
        follow = grid_trace(M, np.ones(2), tol=atlases.STEP_TOL, criterion="step")(params, u0)
        status, x, iterations, _ = track_paths(system, domain, 4, params, u0,
                                               tol=atlases.STEP_TOL)
    assert np.array_equal(status, follow.status) and len(set(status.ravel())) >= 4
    assert np.array_equal(iterations, follow.iterations)
    assert np.array_equal(x, follow.x[-1], equal_nan=True)


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
            x = np.sort(at.x[i, j, :at.counts[i, j], 0])
            # the cusp's equilibria are polished roots of x^3 - a x - b with |x| of order one:
            # residual round-off
            assert np.abs(x ** 3 - a * x - b).max() < 1e-12
            order = np.argsort(at.x[i, j, :at.counts[i, j], 0])
            assert np.array_equal(at.stable[i, j, :at.counts[i, j]][order], 3 * x ** 2 - a > 0)


def test_an_empty_grid_is_an_empty_atlas():
    at = cusp_atlas(np.zeros(0), B_AXIS)
    assert at.counts.shape == (0, 33) and at.folds.shape == (0, 2) and at.searched.sum() == 0
    empty = rfr2.atlas(rfr2.study.TABLE7, [], [0.1, 0.2], executor=1)
    assert empty.counts.shape == (0, 2) and empty.stable_counts.shape == (0, 2)
    assert pfr3.atlas(pfr3.study.TABLE8, [], [0.0, 0.1, 0.2], executor=1).counts.shape == (0, 3)


def test_the_anchors_are_block_centres_and_one_at_least():
    assert atlases.anchors(1, 1).tolist() == [0]
    assert sorted(atlases.anchors(16, 1).tolist()) == [4, 12]
    assert atlases.anchors(0, 5).size == 0


# ------------------------------------------------------------------------- the 2RFR's atlas
# 2.5 degrees apart, over a fold (3 equilibria to 2) and a corner with 4
WINDOW = (np.radians(np.linspace(50.0, 70.0, 9)), np.radians(np.linspace(40.0, 60.0, 9)))


@pytest.fixture(scope="module")
def rfr2_atlas():
    return rfr2.atlas(rfr2.study.TABLE7, *WINDOW, executor=1)      # serially, in this process


def _full_search(point):
    """The full search from other starts than the atlas's: 400, and a check of 400 more that
    must find nothing new (the search is sampled: a count it is unsure of proves nothing)."""
    eq = rfr2.forward(rfr2.study.TABLE7, point, n_starts=400, check=1, rng=0)
    assert eq.search.complete
    return len(eq.x), int(eq.stable.sum())


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
            assert np.abs(rfr2.residual(rfr2.study.TABLE7, s.inputs, s.chart)).max() < 1e-9
    with pytest.raises(ValueError, match="has 3 equilibria, no equilibrium 5"):
        at.state(*np.argwhere(at.counts == 3)[0], 5)


def test_the_atlas_draws_its_map_folds_and_a_trajectory(rfr2_atlas):
    fig, ax = plt.subplots()
    path = rfr2.study.TABLE7_THETA + rfr2.study.path("direct circles")
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
        on_cluster = rfr2.atlas(rfr2.study.TABLE7, *WINDOW, executor=client)
    serial = rfr2_atlas
    assert serial.searched.sum() > 2 * parallel.workers(2)      # several tasks per worker
    for name in ("counts", "stable_counts", "searched", "vouched", "stable", "folds"):
        assert np.array_equal(getattr(serial, name), getattr(on_cluster, name)), name
    assert np.array_equal(serial.x, on_cluster.x, equal_nan=True)


def test_joblib_on_two_workers_gives_the_serial_result():
    serial = cusp_atlas(A_AXIS[::2], B_AXIS[::2])
    pooled = cusp_atlas(A_AXIS[::2], B_AXIS[::2], executor=2)
    assert np.array_equal(serial.counts, pooled.counts)
    assert np.array_equal(serial.x, pooled.x, equal_nan=True)


# ----------------------------------------------------------------------- the 3PFR's atlas
def test_the_3pfr_plane_and_its_atlas():
    s = np.linspace(-0.002, 0.002, 3)
    at = pfr3.atlas(pfr3.study.TABLE8, s, s, directions=[[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
                    executor=1)
    point = at.inputs[2, 0]
    # the grid's point is origin + 0.002 e1 - 0.002 e3, computed exactly but for one rounding
    np.testing.assert_allclose(point, [0.002, 0.0, -0.002], rtol=0, atol=1e-15)
    eq = pfr3.forward(pfr3.study.TABLE8, point, rng=0)
    assert (at.counts[2, 0], at.stable_counts[2, 0]) == (len(eq.x), eq.stable.sum())
    # the plane's coordinates of grid points built from multiples of 0.002: round-off, within
    # numpy's default rtol 1e-5
    assert np.allclose(at.coordinates(point), [0.002, -0.002])
    # unit directions recovered from the grid's first row and column: round-off, within numpy's
    # default
    assert np.allclose(at.directions, [[1, 0, 0], [0, 0, 1]])


@pytest.mark.parametrize("kwargs, message", [
    ({"origin": [0.0, 0.0]}, "origin must have shape"),
    ({"directions": [[1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]}, "two independent directions"),
    ({"directions": [[1.0, 0.0, 0.0]]}, "directions must have shape"),
    ({"origin": [np.nan, 0.0, 0.0]}, "finite"),
    ({"a": [0.0, 0.0]}, "a must be strictly increasing or decreasing"),
])
def test_the_3pfr_atlas_refuses_a_grid_that_is_no_plane(kwargs, message):
    args = {"a": [0.0, 0.001], "b": [0.0, 0.001]} | kwargs
    with pytest.raises(ValueError, match=message):
        pfr3.atlas(pfr3.study.TABLE8, args.pop("a"), args.pop("b"), executor=1, **args)


@pytest.mark.parametrize("mech, modes, executor, message", [
    (rfr2.study.TABLE7, (1, 1, 1), 1, "mech must be a Mechanism"),
    (pfr3.study.TABLE8, (1, 1), 1, "modes must have shape"),
    (pfr3.study.TABLE8, (1, 1, 1), -2, "executor must be None"),
])
def test_the_3pfr_atlas_names_bad_input(mech, modes, executor, message):
    with pytest.raises(ValueError, match=message):
        pfr3.atlas(mech, [0.0, 0.001], [0.0, 0.001], modes=modes, executor=executor)


# ---------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, message", [
    ({"mech": None}, "mech must be a Mechanism"),
    ({"a": [[0.1]]}, "a must"),
    ({"b": [np.nan]}, "b must be finite"),
    ({"b": [0.1, 0.1]}, "b must be strictly increasing or decreasing"),
    ({"modes": (1, 0)}, "modes must be 2 integers"),
    ({"executor": 0}, "executor must be None"),
    ({"executor": True}, "executor must be None"),
    ({"executor": "dask"}, "executor must be None"),
    ({"a": np.zeros(1001), "b": np.zeros(1000)}, "a bound on the work"),
])
def test_the_2rfr_atlas_names_bad_input(kwargs, message):
    args = {"mech": rfr2.study.TABLE7, "a": [0.7], "b": [1.0], "modes": (1, 1),
            "executor": 1} | kwargs
    with pytest.raises(ValueError, match=message):
        rfr2.atlas(args.pop("mech"), args.pop("a"), args.pop("b"), **args)


def test_parallel_runs_in_order_on_every_executor():
    tasks = list(range(7))
    assert parallel.run(partial(pow, 2), tasks, 1) == [2 ** t for t in tasks]
    assert parallel.run(partial(pow, 2), tasks, 2) == [2 ** t for t in tasks]
    assert parallel.run(abs, [], None) == []
    assert [len(c) for c in parallel.chunks(list(range(9)), 1)] == [3, 2, 2, 2]
    assert parallel.chunks([], None) == []


def test_two_ends_on_each_side_of_an_edge_pair_up_crosswise():
    # two equilibria at each of two points, listed in opposite orders, the same past the
    # chart (their last unknown) within a step: each has its partner, whatever the order
    store = atlases._Store(2, 2, 1)
    store.insert(np.array([0, 0, 1, 1]), np.array([[0.1, 5.0], [0.2, 7.0], [0.3, 7.01],
                                                   [0.4, 5.01]]),
                 np.array([True, False, False, True]))
    store.move = 0.1
    assert atlases._paired(store, 0, np.array([0, 1]), 1, np.array([0, 1]))
    store.stable[1] = [True, False]                 # the verdicts no longer match: no pairs
    assert not atlases._paired(store, 0, np.array([0, 1]), 1, np.array([0, 1]))
