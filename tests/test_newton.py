"""Tests of mechnum.newton: textbook systems, criteria, batches, and every failure mode."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechnum.errors import ConvergenceError, DivergenceError, NonFiniteError, SingularJacobianError
from mechnum.newton import broyden, fd_jacobian, solve, solve_all, solve_batch
from mechnum.results import STATUSES, Result


def circle_line(x):
    """Unit circle meets the line y = x: roots +-(1, 1)/sqrt(2)."""
    return np.array([x[0] ** 2 + x[1] ** 2 - 1.0, x[0] - x[1]])


def circle_line_jac(x):
    return np.array([[2 * x[0], 2 * x[1]], [1.0, -1.0]])


def test_textbook_system_converges_quadratically():
    res = solve(circle_line, [1.0, 0.5], circle_line_jac, tol=1e-14)
    assert res.converged
    # the root is 1/sqrt(2) to round-off: tol 1e-14 leaves an error far below it, so what remains is
    # a few ulps of 0.7 (eps 0.7 = 1.6e-16)
    np.testing.assert_allclose(res.x, [2 ** -0.5, 2 ** -0.5], rtol=0, atol=1e-15)
    assert res.history.shape == (res.iterations + 1, 2)
    assert res.residual_norms.shape == (res.iterations + 1,)
    assert res.step_norms.shape == (res.iterations,)
    e = res.step_norms
    # quadratic: once close, each step is at most a modest constant times the square of the last
    assert np.all(e[2:-1] <= 2.0 * e[1:-2] ** 2)


def test_result_is_frozen():
    res = solve(circle_line, [1.0, 0.5], circle_line_jac)
    with pytest.raises(AttributeError):
        res.x = None


def test_step_criterion_counts_the_confirming_step():
    # A linear system: the first step is exact, the second (of size ~0) confirms it.
    A, b = np.array([[3.0, 1.0], [1.0, 2.0]]), np.array([1.0, 1.0])
    step = solve(lambda x: A @ x - b, [5.0, -5.0], lambda x: A, tol=1e-8)
    residual = solve(lambda x: A @ x - b, [5.0, -5.0], lambda x: A, tol=1e-8,
                     criterion="residual")
    assert (step.iterations, residual.iterations) == (2, 1)
    # a 2 x 2 solve of condition about 2.6: its answer is exact to a few ulps of its O(1) entries
    np.testing.assert_allclose(step.x, np.linalg.solve(A, b), atol=1e-14, rtol=0)


def test_norm_choice_changes_the_test_not_the_iterates():
    # x_i^3 = 0, three equal components: Newton converges linearly (x -> 2x/3) and
    # ||dx||_1 = 3 ||dx||_inf, so the 1-norm test stops about log 3 / log 1.5 steps later.
    def cube(x):
        return x ** 3

    def cube_jac(x):
        return np.diag(3 * x ** 2)

    a = solve(cube, [1.0, 1.0, 1.0], cube_jac, tol=1e-6, norm=np.inf, maxiter=100,
              relative=False)  # a root at the origin: an absolute test
    b = solve(cube, [1.0, 1.0, 1.0], cube_jac, tol=1e-6, norm=1, maxiter=100, relative=False)
    assert a.converged and b.converged
    assert b.iterations >= a.iterations + 2
    np.testing.assert_array_equal(b.history[:len(a.history)], a.history)  # same iterates


def test_finite_difference_jacobian_is_the_default():
    res = solve(circle_line, [1.0, 0.5], tol=1e-12)
    # forward differences give J to about sqrt(eps) = 1.5e-8, which only slows convergence: the last
    # steps still shrink below tol 1e-12, and the root is O(1)
    np.testing.assert_allclose(res.x, [2 ** -0.5, 2 ** -0.5], atol=1e-12, rtol=0)
    J = fd_jacobian(circle_line, np.array([0.3, -0.7]))
    # a forward difference errs by about sqrt(eps) |f''| ~ 1e-8 here (second derivatives of 2): 1e-7
    # leaves a margin of ten
    np.testing.assert_allclose(J, circle_line_jac([0.3, -0.7]), atol=1e-7, rtol=0)


@pytest.mark.parametrize("x", [0.5, -0.25, 3.0, 1e6])
def test_fd_jacobian_step_is_sqrt_eps_relative(x):
    # What it protects: the forward-difference step h = sqrt(eps) max(1, |x|), which balances
    # truncation (h |f''| / 2) against round-off (eps |f| / h). For f = x^2 the difference
    # quotient is exactly 2 x + h: its error measures h itself, which must be sqrt(eps) for
    # |x| <= 1 and sqrt(eps) |x| beyond (a step that did not grow with x would vanish in x + h
    # at 1e6). The bound allows a quarter of h for the rounding of x + h and of the quotient.
    h = np.sqrt(np.finfo(float).eps) * max(1.0, abs(x))
    J = fd_jacobian(lambda z: z ** 2, np.array([x]))
    assert abs(J[0, 0] - 2 * x - h) <= 0.25 * h


BIG = np.sqrt(np.finfo(float).max) * (1 - 1e-9)  # BIG^2 is a float, (BIG (1 + 1.5e-8))^2 is not


@pytest.mark.parametrize("call, words", [
    (lambda: fd_jacobian(None, np.ones(2)), "fun must be"),
    (lambda: fd_jacobian(lambda z: z, np.ones((2, 2, 2))), "x must"),
    (lambda: fd_jacobian(lambda z: z, np.ones(0)), "x must have at least one unknown"),
    (lambda: fd_jacobian(lambda z: z[:1], np.ones(2)), "fun returned shape"),
    (lambda: fd_jacobian(lambda z: z ** 2, np.array([BIG, 1.0])), "not finite"),
])
def test_fd_jacobian_refuses_what_it_cannot_difference(call, words):
    # z^2 is finite at BIG, not at BIG + h (it passes the largest float): a named error, and no
    # overflow warning leaks (the mutation runs make RuntimeWarnings errors, as make explore does)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        with pytest.raises((ValueError, NonFiniteError), match=words):
            call()


def test_fd_jacobian_of_a_batch():
    x = np.array([[0.3, -0.7], [1.0, 2.0]])
    J = fd_jacobian(lambda z: np.stack([z[:, 0] ** 2, z[:, 0] * z[:, 1]], axis=-1), x)
    # forward differences err by about sqrt(eps) times the second derivatives (2 here): 1e-6 is a
    # margin of about a hundred
    np.testing.assert_allclose(J[1], [[2.0, 0.0], [2.0, 1.0]], atol=1e-6, rtol=0)


@pytest.mark.parametrize("seed", [[np.nan, 1.0], [np.inf, 0.0], [[1.0, 2.0]], [], 3.0])
def test_bad_initial_guess_is_a_value_error(seed):
    with pytest.raises(ValueError, match="seed must"):
        solve(circle_line, seed, circle_line_jac)


@pytest.mark.parametrize("kwargs, match", [({"criterion": "size"}, "criterion"),
                                           ({"tol": 0.0}, "tol"), ({"tol": np.nan}, "tol"),
                                           ({"maxiter": 0}, "maxiter"),
                                           ({"maxiter": 2.5}, "maxiter")])
def test_bad_options_are_value_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve(circle_line, [1.0, 0.5], circle_line_jac, **kwargs)


def test_wrong_shapes_from_the_callables_are_value_errors():
    with pytest.raises(ValueError, match="fun returned shape"):
        solve(lambda x: np.zeros(3), [1.0, 0.5], circle_line_jac)
    with pytest.raises(ValueError, match="jac returned shape"):
        solve(circle_line, [1.0, 0.5], lambda x: np.eye(3))


def test_singular_jacobian_is_named_with_its_iteration():
    parallel = lambda x: np.array([x[0] + x[1] - 1.0, 2 * x[0] + 2 * x[1] - 3.0])  # noqa: E731
    with pytest.raises(SingularJacobianError, match="iteration 0") as info:
        solve(parallel, [0.0, 0.0], lambda x: np.array([[1.0, 1.0], [2.0, 2.0]]))
    assert info.value.result.iterations == 0


def test_numerically_singular_jacobian_is_refused():
    J = np.array([[1.0, 1.0], [1.0, 1.0 + 1e-17]])  # rounds to exactly singular or nearly so
    with pytest.raises(SingularJacobianError, match="condition number"):
        solve(lambda x: J @ x - np.array([1.0, 2.0]), [0.0, 0.0], lambda x: J)


@pytest.mark.parametrize("d, delta, flagged", [(1e-3, 2.0 ** -52, True), (1.0, 1e-12, False)])
def test_the_trust_test_flags_a_step_of_no_digit_and_only_such_a_step(d, delta, flagged):
    # What it protects: the threshold of the singular-Jacobian test, a growth of the step past
    # 1/eps = 4.5e15 times the residual (no digit of the step is left). Rows (1, 1) and
    # d (1, 1 + delta) with f = (0, -1): the step is about 1/(d delta), so the measured growth
    # is 9e18 for d = 1e-3, delta = eps (a thousand times past the bound, a thousand times
    # short of a bound a million times laxer) and 2e12 for delta = 1e-12 (a thousand times
    # inside it, a thousand times past a bound a million times stricter): that honest step,
    # cond 4e12, is taken.
    A = np.array([[1.0, 1.0], [d, d * (1 + delta)]])
    b = np.array([0.0, -1.0])
    if flagged:
        with pytest.raises(SingularJacobianError, match=r"condition number >= 9\.\d+e\+18"):
            solve(lambda x: A @ x + b, [0.0, 0.0], lambda x: A)
    else:
        res = solve(lambda x: A @ x + b, [0.0, 0.0], lambda x: A, criterion="residual",
                    tol=1e-3)
        assert res.converged and res.iterations == 1


@pytest.mark.parametrize("scale", [1e-12, 1e12])
def test_the_relative_residual_rule_ignores_the_units_of_f(scale):
    # What it protects: relative=True measures ||f|| against ||f(x0)||, so a badly scaled
    # system stops where a well scaled one does. f = scale (x^2 - 2) from x0 = 1: with
    # scale 1e-12, |f(x0)| = 1e-12 is already below an absolute tol of 1e-8 (an absolute test
    # would return the seed, 41 % off); with scale 1e12, round-off in f is about 1e-3, so an
    # absolute 1e-8 is never met.
    res = solve(lambda x: scale * (x ** 2 - 2), [1.0], lambda x: np.diag(2 * scale * x),
                tol=1e-8, criterion="residual", relative=True)
    assert res.converged and res.iterations >= 3
    # the criterion itself: tol times ||f(x0)|| = scale
    assert res.residual_norms[-1] <= 1e-8 * scale
    # |x^2 - 2| <= 1e-8 bounds the error by 1e-8 / (2 sqrt 2) < 1e-8 sqrt 2
    np.testing.assert_allclose(res.x, [np.sqrt(2)], rtol=1e-8)


def atan_system(x):
    """Newton on arctan(x) = 0 diverges from |x0| > 1.39 (the iterates alternate and grow)."""
    return np.arctan(x)


def atan_jac(x):
    return np.diag(1.0 / (1.0 + x ** 2))


def test_maxiter_exceeded_raises_with_the_partial_result():
    with pytest.raises(ConvergenceError, match="did not converge in 4 iterations") as info:
        solve(atan_system, [2.0], atan_jac, maxiter=4)
    assert info.value.result.iterations == 4
    assert not info.value.result.converged
    assert np.all(np.abs(info.value.result.history[1:, 0]) > 2.0)


def test_non_finite_iterate_is_not_convergence():
    with pytest.raises(ConvergenceError):
        solve(lambda x: np.exp(x) * 0 + np.where(x > 10, np.nan, x - 20), [0.0],
              lambda x: np.eye(1))


def test_batch_has_per_system_convergence():
    c = np.array([2.0, 3.0, 400.0])
    res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((3, 1)), lambda x: 2 * x[:, :, None])
    # Newton's quadratic convergence to tol 1e-10 ends within round-off of sqrt(c) (<= 20): a few
    # ulps, relative
    np.testing.assert_allclose(res.x[:, 0], np.sqrt(c), rtol=1e-14)
    singles = [solve(lambda x, ci=ci: x ** 2 - ci, [1.0], lambda x: np.diag(2 * x)).iterations
               for ci in c]
    assert res.iterations.tolist() == singles
    assert res.iterations[2] > res.iterations[0]
    assert res.converged.all() and not res.singular.any()


def test_batch_with_fd_jacobian():
    c = np.array([2.0, 5.0])
    res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((2, 1)), tol=1e-12)
    # forward differences slow the last steps but the step test (tol 1e-12) still stops within 1e-12
    # relative of the root
    np.testing.assert_allclose(res.x[:, 0], np.sqrt(c), rtol=1e-12)


def test_batch_singular_system_does_not_stop_the_others():
    target = np.array([[4.0], [-1.0]])
    with pytest.raises(SingularJacobianError, match="1 of 3|2 of 3") as info:
        solve_batch(lambda x: x ** 2 - np.vstack([target, [[9.0]]]),
                    np.array([[1.0], [0.0], [1.0]]), lambda x: 2 * x[:, :, None])
    res = info.value.result
    assert res.singular[1] and not res.singular[0]
    # the two regular systems converge quadratically to their roots; 1e-12 relative is round-off
    # plus the last step's size
    np.testing.assert_allclose(res.x[[0, 2], 0], [2.0, 3.0], rtol=1e-12)
    assert res.converged[[0, 2]].all()


def test_batch_non_convergence_names_the_systems():
    fun = lambda x: np.stack([x[0] ** 2 - 4.0, np.arctan(x[1])])  # noqa: E731
    jac = lambda x: np.stack([np.diag(2 * x[0]), atan_jac(x[1])])  # noqa: E731
    with pytest.raises(ConvergenceError, match=r"1 of 2 systems .*\[1\]") as info:
        solve_batch(fun, np.array([[1.0], [2.0]]), jac, maxiter=6)
    assert info.value.result.converged.tolist() == [True, False]


@pytest.mark.parametrize("seeds", [np.ones(3), np.ones((2, 2, 2)), np.full((2, 1), np.nan)])
def test_batch_bad_initial_guess(seeds):
    with pytest.raises(ValueError, match="seeds must"):
        solve_batch(lambda x: x, seeds)


def test_batch_wrong_jacobian_shape():
    with pytest.raises(ValueError, match="jac returned shape"):
        solve_batch(lambda x: x, np.ones((2, 2)), lambda x: np.ones((2, 2)))


@pytest.mark.parametrize("shape", [(2, 2), (1, 1, 1), (3, 1, 2), (3, 1, 1, 1), (3,)])
@pytest.mark.parametrize("options", [{}, {"jac": True}, {"damping": True, "independent": True}])
def test_batch_checks_the_jacobian_shape_on_every_route(shape, options):
    # a Jacobian of another shape would broadcast (a (1, 1, 1) one to every system) or be read
    # wrongly: each route that evaluates J (jac, fun's pair, the stacked line search) checks it
    c = np.array([2.0, 3.0, 4.0])
    seeds = np.full((3, 1), 1.0)
    if options.get("jac"):
        def fun(x):
            return x ** 2 - c[:, None], np.ones(shape)
        jac, what = True, "fun's Jacobian"
    else:
        def fun(x):
            return x ** 2 - c[: len(x), None]
        jac, what = (lambda x: np.ones(shape)), "jac"
    extra = {k: v for k, v in options.items() if k != "jac"}
    with pytest.raises(ValueError, match=f"{what} returned shape"):
        solve_batch(fun, seeds, jac, **extra)


@settings(max_examples=60, deadline=None)
@given(a=st.floats(1e-3, 1e3), start=st.floats(0.5, 2.0))
def test_cube_root_from_anywhere_near(a, start):
    x0 = start * np.cbrt(a)
    res = solve(lambda x: x ** 3 - a, [x0], lambda x: np.diag(3 * x ** 2), tol=1e-13)
    # tol 1e-13 (relative step) bounds the error by about 1e-13 relative after the quadratic last
    # step; 1e-12 leaves a margin of ten
    assert abs(res.x[0] - np.cbrt(a)) <= 1e-12 * np.cbrt(a)


# --- damping, status, domain, empty batches -------------------------------------------------

def test_damping_rescues_a_start_that_plain_newton_loses():
    with pytest.raises((ConvergenceError, SingularJacobianError)), np.errstate(over="ignore"):
        solve(atan_system, [1.5], atan_jac)  # the iterates grow until J underflows
    res = solve(atan_system, [1.5], atan_jac, damping=True, tol=1e-14)
    # Newton on arctan converges cubically to 0 (x -> -2x^3/3) and lands on 0.0: a relative step
    # test cannot stop before (near 0 a step is about |x|); the bound asks for a root at round-off
    assert res.converged and abs(res.x[0]) < 1e-14
    assert np.all(np.diff(res.residual_norms) <= 0)  # the line search makes |f| decrease


def test_damping_reports_a_stagnated_start():
    with pytest.raises(ConvergenceError, match="line search stagnated"):
        solve(lambda x: x ** 2 + 1.0, [0.3], lambda x: np.diag(2 * x), damping=True)


def test_complex_residual_or_jacobian_is_refused():
    with pytest.raises(ValueError, match="complex"):
        solve(lambda x: x ** 2 - 2 + 1j, [1.0])
    with pytest.raises(ValueError, match="complex"):
        solve(lambda x: x ** 2 - 2, [1.0], lambda x: np.diag(2j * x))
    with pytest.raises(ValueError, match="seed must be real"):
        solve(lambda x: x ** 2 - 2, [1.0 + 0j])


@pytest.mark.parametrize("maxiter", [np.inf, np.nan, -3, True])
def test_bad_maxiter_is_a_value_error(maxiter):
    with pytest.raises(ValueError, match="maxiter"):
        solve(circle_line, [1.0, 0.5], circle_line_jac, maxiter=maxiter)


def test_batch_status_names_every_outcome():
    c = np.array([4.0, -1.0, 9.0, 1.0, 2.0])

    def fun(x):  # x**2 = c, and a NaN for the fourth system once it moves
        f = x ** 2 - c[:, None]
        f[3] = np.where(x[3] > 1.0, np.nan, f[3])
        return f

    x0 = np.array([[1.0], [0.0], [1.0], [0.5], [1.0]])
    res = solve_batch(fun, x0, lambda x: 2 * x[:, :, None], maxiter=40,
                      domain=lambda x: x[:, 0] < 3.5, raise_on_failure=False)
    assert res.status.tolist() == ["converged", "singular", "left-domain", "non-finite",
                                   "converged"]
    assert set(res.status) <= set(STATUSES)
    # two regular roots reached by quadratic steps: the error is a few ulps of 2 and sqrt(2)
    np.testing.assert_allclose(res.x[[0, 4], 0], [2.0, np.sqrt(2)], rtol=1e-14)
    assert res.njev >= 1 and res.nfev == res.njev + 1  # one fun per step, plus the start
    with pytest.raises(SingularJacobianError):
        solve_batch(fun, x0, lambda x: 2 * x[:, :, None], domain=lambda x: x[:, 0] < 3.5)


def test_batch_maxiter_status_and_its_error():
    res = solve_batch(atan_system, [[2.0]], lambda x: atan_jac(x[0])[None], maxiter=3,
                      raise_on_failure=False)
    assert res.status.tolist() == ["maxiter"] and res.iterations.tolist() == [3]


def test_damped_batch_stays_in_the_domain_by_backtracking():
    # sqrt(1 - x) = 0.5 has its root at x = 0.75; a start at -3 overshoots past x = 1
    # (where the residual is undefined) unless the step is shortened to stay in the domain.
    fun = lambda x: np.sqrt(np.maximum(1 - x, 0)) - 0.5  # noqa: E731
    jac = lambda x: (-0.5 / np.sqrt(np.maximum(1 - x, 1e-300)))[:, :, None]  # noqa: E731
    res = solve_batch(fun, [[-30.0]], jac, damping=True, domain=lambda x: x[:, 0] < 1,
                      raise_on_failure=False, tol=1e-13)
    assert res.status.tolist() == ["converged"]
    # tol 1e-13 relative on the step: the root 0.75 is met to about that, plus round-off
    np.testing.assert_allclose(res.x[0, 0], 0.75, rtol=1e-13)


def test_empty_batch_is_valid():
    res = solve_batch(lambda x: x ** 2 - 2.0, np.empty((0, 1)), lambda x: 2 * x[:, :, None])
    assert res.x.shape == (0, 1) and res.status.shape == (0,) and res.iterations.shape == (0,)
    assert res.converged.all()


# --- all solutions ----------------------------------------------------------------------------

def cubic_pair(z):
    """x**3 = x and y**2 = 1: six roots, (-1, 0, 1) x (-1, 1)."""
    return np.stack([z[:, 0] ** 3 - z[:, 0], z[:, 1] ** 2 - 1.0], axis=-1)


def cubic_pair_jac(z):
    zero = np.zeros(len(z))
    return np.stack([np.stack([3 * z[:, 0] ** 2 - 1, zero], -1),
                     np.stack([zero, 2 * z[:, 1]], -1)], axis=1)


def test_solve_all_accounts_for_its_work():
    # What it protects: a search's evidence is its accounting. n_starts and n_check starts were
    # run (a status each), fun and jac were called nfev and njev times (the final residual check
    # included), and the message says how many roots from how many starts, by status.
    calls = {"fun": 0, "jac": 0}

    def fun(z):
        calls["fun"] += 1
        return cubic_pair(z)

    def jac(z):
        calls["jac"] += 1
        return cubic_pair_jac(z)

    sample = lambda rng, m: rng.uniform(-2, 2, (m, 2))  # noqa: E731
    found = solve_all(fun, sample, jac, n_starts=30, check=2, rng=5)
    assert (found.n_starts, found.n_check, len(found.status), found.iterations.shape) == (
        30, 60, 90, (90,))
    assert (found.nfev, found.njev) == (calls["fun"], calls["jac"])
    counts = {str(s): int(c) for s, c in zip(*np.unique(found.status, return_counts=True))}
    assert found.message == (f"6 roots from 90 starts ({counts}); "
                             f"{found.new_in_check} new in the check")
    assert found.new_in_check == 0 and found.complete
    # the defaults: a thousand starts and ten times as many in the check
    assert solve_all(cubic_pair, sample, cubic_pair_jac, rng=5).n_starts == 1000


def test_solve_all_finds_every_root_of_a_polynomial_system():
    found = solve_all(cubic_pair, lambda rng, m: rng.uniform(-2, 2, (m, 2)), cubic_pair_jac,
                      n_starts=300, rng=1)
    expected = np.array([[a, b] for a in (-1, 0, 1) for b in (-1, 1)], dtype=float)
    # each root is met by quadratic convergence and deduplicated; round-off of roots of size 1 is
    # ~1e-16, 1e-12 allows for the last step's size
    np.testing.assert_allclose(found.x, expected, atol=1e-12, rtol=0)
    assert found.complete and found.new_in_check == 0 and found.n_check == 3000
    assert found.hits.sum() == found.status_counts["converged"] and found.hits.min() > 10
    # the polished roots of O(1) cubics have residuals at round-off (about 1e-15); 1e-12 is the
    # deduplication tolerance's scale
    assert np.all(found.residual_norms < 1e-12)


def test_completeness_check_counts_what_the_search_missed():
    # the search's starts reach only the root (1, 1); the check's (ten times more) reach all six
    sample = lambda rng, m: (rng.uniform(0.6, 2, (m, 2)) if m < 100  # noqa: E731
                             else rng.uniform(-2, 2, (m, 2)))
    found = solve_all(cubic_pair, sample, cubic_pair_jac, n_starts=50, rng=2)
    assert len(found.x) == 6 and found.new_in_check == 5 and not found.complete


def test_solve_all_seeds_and_domain():
    sample = lambda rng, m: rng.uniform(0.6, 2, (m, 2))  # noqa: E731
    found = solve_all(cubic_pair, sample, cubic_pair_jac, n_starts=20, check=0, rng=3,
                      seeds=[[-1.1, -1.1]], domain=lambda z: z[:, 0] > -0.5)
    assert found.x.tolist() == [[1.0, 1.0]]  # the extra start leaves the domain
    assert found.status_counts["left-domain"] >= 1 and found.n_check == 0
    found = solve_all(cubic_pair, sample, cubic_pair_jac, n_starts=20, check=0, rng=3,
                      seeds=[[-1.1, -1.1]])
    # the roots +-(1, 1) are met to round-off of O(1) numbers; 1e-12 allows for the last step's size
    np.testing.assert_allclose(found.x, [[-1.0, -1.0], [1.0, 1.0]], atol=1e-12, rtol=0)
    assert found.hits.tolist() == [1, 20]


def test_solve_all_with_no_root_returns_an_empty_set():
    found = solve_all(lambda z: z ** 2 + 1.0, lambda rng, m: rng.uniform(-2, 2, (m, 1)),
                      lambda z: 2 * z[:, :, None], n_starts=10, check=1, rng=4)
    assert found.x.shape == (0, 1) and found.hits.shape == (0,) and found.complete
    assert found.status_counts["stagnated"] + found.status_counts["singular"] == 20


# --- the valid domain and just outside it (issue 13) -------------------------------------------

@settings(max_examples=200, deadline=None)
@given(a=st.floats(1e-6, 1e6), start=st.floats(-50.0, 50.0).filter(lambda s: abs(s) > 1e-3))
def test_damped_newton_finds_the_cube_root_from_far_away(a, start):
    # plain Newton on x**3 = a can leap far from a bad start; damped Newton converges to the
    # one real root from any nonzero start, or says why it stopped
    try:
        res = solve(lambda x: x ** 3 - a, [start * np.cbrt(a)], lambda x: np.diag(3 * x ** 2),
                    tol=1e-13, maxiter=200, damping=True)
    except (ConvergenceError, SingularJacobianError) as error:
        assert error.result is not None and str(error)
        return
    # damping only changes the path: the last steps are Newton's, so the relative step test (tol
    # 1e-13) leaves an error below 1e-12 relative
    np.testing.assert_allclose(res.x[0], np.cbrt(a), rtol=1e-12)
    assert res.history.shape == (res.iterations + 1, 1)


@settings(max_examples=200, deadline=None)
@given(c=st.lists(st.floats(-1e3, 1e3), min_size=0, max_size=6),
       damping=st.booleans())
def test_batch_statuses_are_consistent_with_the_roots(c, damping):
    c = np.array(c, dtype=float)
    res = solve_batch(lambda x: x ** 2 - c[:, None], np.ones((len(c), 1)),
                      lambda x: 2 * x[:, :, None], damping=damping, tol=1e-12,
                      raise_on_failure=False)
    assert res.x.shape == (len(c), 1) and res.status.shape == (len(c),)
    assert set(res.status) <= set(STATUSES)
    ok = res.converged
    residual = np.abs(res.x[ok, 0] ** 2 - c[ok])
    assert np.all(residual <= 1e-9 * np.maximum(1.0, np.abs(c[ok])))  # the defining property
    assert not np.any(ok[c < -1e-6])  # no convergence where no real root is near


@pytest.mark.parametrize("kwargs, match", [
    ({"tol": -1.0}, "tol must be positive"), ({"tol": np.inf}, "tol must be finite"),
    ({"maxiter": np.inf}, "maxiter"), ({"criterion": "size"}, "criterion"),
    ({"norm": 3}, "norm"), ({"seeds": np.ones((2, 2, 1))}, "seeds must have 2"),
    ({"seeds": [[1.0], [np.nan]]}, "seeds must be finite"), ({"seeds": np.ones((2, 0))}, "n >= 1"),
    ({"seeds": [[1j]]}, "seeds must be real")])
def test_batch_bad_inputs_name_the_argument(kwargs, match):
    args = {"seeds": np.ones((2, 1))} | kwargs
    with pytest.raises(ValueError, match=match):
        solve_batch(lambda x: x ** 2 - 2, args.pop("seeds"), lambda x: 2 * x[:, :, None], **args)


@pytest.mark.parametrize("kwargs, match", [
    ({"n_starts": 0}, "n_starts"), ({"check": -1}, "check"), ({"same": 0.0}, "same"),
    ({"seeds": [[np.nan, 0.0]]}, "seeds must be finite"), ({"seeds": [1.0, 2.0]}, "seeds")])
def test_solve_all_bad_inputs_name_the_argument(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve_all(cubic_pair, lambda rng, m: rng.uniform(-2, 2, (m, 2)), cubic_pair_jac, **kwargs)


def test_fd_jacobian_refuses_non_finite_points():
    with pytest.raises(ValueError, match="x must be finite"):
        fd_jacobian(circle_line, [np.nan, 1.0])


def test_damping_calls_a_single_system_with_vectors_only():
    def fun(x):
        assert x.shape == (1,), f"fun was called with shape {x.shape}"
        return np.arctan(x)

    res = solve(fun, [1.5], lambda x: np.diag(1 / (1 + x ** 2)), damping=True, tol=1e-14)
    # Newton on arctan converges cubically to 0 (x -> -2x^3/3) and lands on 0.0: a relative step
    # test cannot stop before (near 0 a step is about |x|); the bound asks for a root at round-off
    assert res.converged and abs(res.x[0]) < 1e-14
# --- Broyden's method -------------------------------------------------------------------------

def test_broyden_converges_superlinearly_with_one_jacobian():
    calls = {"jac": 0}

    def jac(x):
        calls["jac"] += 1
        return circle_line_jac(x)

    res = broyden(circle_line, [1.0, 0.5], jac, tol=1e-14)
    newton = solve(circle_line, [1.0, 0.5], circle_line_jac, tol=1e-14)
    # Broyden's last step is a full Newton step here (same Jacobian at the start, same test): it
    # ends at the same root to a few ulps of 0.7
    np.testing.assert_allclose(res.x, newton.x, rtol=0, atol=1e-15)
    assert calls["jac"] == 1 and res.iterations > newton.iterations
    e = np.linalg.norm(res.history[:-1] - res.x, axis=1)
    ratios = e[1:] / e[:-1]
    assert ratios[-3:].max() < 0.1 and ratios[-1] < ratios[1]  # faster than linear at the end


def test_broyden_keeps_an_exact_jacobian_of_a_linear_system():
    # y = A s for every step: the update vanishes, so Broyden is Newton (one step, one check)
    A, b = np.array([[3.0, 1.0], [1.0, 2.0]]), np.array([1.0, 1.0])
    res = broyden(lambda x: A @ x - b, [5.0, -5.0], lambda x: A, tol=1e-8)
    assert res.iterations == 2
    # the linear system's solution to a few ulps (condition 2.6, entries O(1))
    np.testing.assert_allclose(res.x, np.linalg.solve(A, b), atol=1e-14, rtol=0)


def test_broyden_without_a_jacobian_uses_differences():
    res = broyden(circle_line, [1.0, 0.5], tol=1e-13)
    # Broyden with differences converges superlinearly to tol 1e-13: the root 1/sqrt(2) to within
    # 1e-12
    np.testing.assert_allclose(res.x, [2 ** -0.5, 2 ** -0.5], atol=1e-12, rtol=0)


@pytest.mark.parametrize("seed, kwargs, error, match", [
    ([np.nan, 1.0], {}, ValueError, "seed must be finite"),
    ([1.0, 0.5], {"tol": -1.0}, ValueError, "tol must be positive"),
    ([1.0, 0.5], {"maxiter": 0}, ValueError, "maxiter"),
    ([1.0, 0.5], {"criterion": "size"}, ValueError, "criterion"),
    ([0.0, 0.0], {}, SingularJacobianError, "singular Broyden matrix at iteration 0"),
    ([1.0, 0.5], {"maxiter": 2}, ConvergenceError, "Broyden's method did not converge in 2"),
])
def test_broyden_rejects_bad_input_with_named_errors(seed, kwargs, error, match):
    with pytest.raises(error, match=match):
        broyden(circle_line, seed, circle_line_jac, **kwargs)


def test_broyden_refuses_a_complex_residual():
    with pytest.raises(ValueError, match="complex"):
        broyden(lambda x: x ** 2 - 2 + 1j, [1.0])


@settings(max_examples=200, deadline=None)
@given(a=st.floats(1e-3, 1e3), b=st.floats(1e-3, 1e3), start=st.floats(0.8, 1.25))
def test_broyden_finds_cube_roots_from_nearby(a, b, start):
    roots = np.cbrt([a, b])
    fun = lambda x: np.array([x[0] ** 3 - a, x[1] ** 3 + x[0] - b - roots[0]])  # noqa: E731
    jac = lambda x: np.array([[3 * x[0] ** 2, 0.0], [1.0, 3 * x[1] ** 2]])  # noqa: E731
    x0 = start * roots
    try:
        res = broyden(fun, x0, jac, tol=1e-12 * roots.max())
    except (ConvergenceError, SingularJacobianError) as error:
        assert error.result is not None  # a named failure carries the partial result
        return
    assert res.x.shape == (2,) and res.converged
    # the tolerance 1e-12 max(roots) on the step bounds the error by about that, relative; 1e-9 is a
    # generous margin for Broyden's superlinear (not quadratic) last step
    np.testing.assert_allclose(res.x, roots, rtol=1e-9)


def test_max_step_bounds_every_step():
    res = solve(atan_system, [1.5], atan_jac, max_step=0.5, tol=1e-14)
    # Newton on arctan converges cubically to 0 (x -> -2x^3/3) and lands on 0.0: a relative step
    # test cannot stop before (near 0 a step is about |x|); the bound asks for a root at round-off
    assert res.converged and abs(res.x[0]) < 1e-14
    # max_step 0.5 is applied in floating point (step * (0.5 / largest)): a rounding of 0.5 may
    # exceed it by an ulp (1e-16)
    assert np.all(res.step_norms <= 0.5 + 1e-15) and res.step_norms[0] == pytest.approx(0.5)
    batch = solve_batch(lambda x: np.arctan(x), [[1.5], [-3.0]],
                        lambda x: (1 / (1 + x ** 2))[:, :, None], max_step=0.5, tol=1e-14)
    # as above: an ulp of 0.5 of rounding in the shortening
    assert batch.converged.all() and np.nanmax(batch.step_norms) <= 0.5 + 1e-15
    with pytest.raises(ValueError, match="max_step must be positive"):
        solve(atan_system, [1.5], atan_jac, max_step=0.0)
# --- independent systems, stacked backtracking ----------------------------------------------

def test_independent_batch_gives_the_same_iterates_with_fewer_calls():
    rng = np.random.default_rng(7)
    x0 = rng.uniform(-3, 3, (200, 2))
    kwargs = dict(tol=1e-12, damping=True, raise_on_failure=False, halvings=8)
    a = solve_batch(cubic_pair, x0, cubic_pair_jac, **kwargs)
    b = solve_batch(cubic_pair, x0, cubic_pair_jac, independent=True, **kwargs)
    np.testing.assert_array_equal(a.status, b.status)
    # the same arithmetic in another grouping of the batch: the iterates agree to round-off of O(1)
    # numbers
    np.testing.assert_allclose(a.x, b.x, rtol=0, atol=1e-14)
    assert b.nfev < a.nfev


def test_fewer_halvings_drop_hard_starts():
    res = solve_batch(atan_system, [[1.5], [20.0]], lambda x: atan_jac(x[0])[None] if len(x) == 1
                      else np.stack([atan_jac(xi) for xi in x]), damping=True, halvings=1,
                      raise_on_failure=False)
    assert res.status.tolist() == ["converged", "stagnated"]


# --- issue 23: the step criterion, relative tests, jac=True, bad input, bounds -----------------

def test_a_max_step_below_tol_cannot_fake_convergence():
    # D2: the criterion tests Newton's full step (4.95 at the start), not the step shortened to
    # max_step = 1e-4, so nothing converges at x = 9.9999 where f = 98
    square = (lambda x: x ** 2 - 2, lambda x: np.diag(2 * x))
    with pytest.raises(ConvergenceError, match="did not converge in 50") as info:
        solve(*square[:1], [10.0], square[1], tol=1e-3, max_step=1e-4)
    assert info.value.result.status == "maxiter" and info.value.result.x[0] > 9.99
    batch = solve_batch(lambda x: x ** 2 - 2, [[10.0]], lambda x: 2 * x[:, :, None], tol=1e-3,
                        max_step=1e-4, raise_on_failure=False)
    assert batch.status.tolist() == ["maxiter"]
    # with room to walk there, it converges, and only where the full step is small
    res = solve(*square[:1], [10.0], square[1], tol=1e-3, max_step=0.5, maxiter=100)
    # with tol 1e-3 on the relative step, the error after that step is far smaller than 1e-3
    # relative (quadratic convergence): the test only asks that it meet its tolerance
    assert abs(res.x[0] - np.sqrt(2)) < 1e-3 * np.sqrt(2)
    # the criterion itself (tol 1e-3 on the relative step)
    assert res.full_step_norms[-1] <= 1e-3 * abs(res.x[0]) < res.full_step_norms[0]


def test_damping_with_max_step_measures_armijo_against_the_full_step():
    # D14: from 50 on arctan, steps of 0.1 decrease |f| by about 4e-5 each, less than the
    # 1e-4 |f| Armijo would ask of a full step: the shortened step must be judged as such
    res = solve(atan_system, [50.0], atan_jac, damping=True, max_step=0.1, maxiter=1000,
                tol=1e-12)
    # the bounded steps bring x near 0, then Newton's cubic convergence on arctan lands on 0.0: the
    # bound only asks for a root at round-off
    assert res.converged and abs(res.x[0]) < 1e-12
    # max_step 0.1 up to the rounding of the shortening (a few ulps, relative)
    assert res.step_norms.max() <= 0.1 * (1 + 1e-12) and res.iterations > 490


def test_damping_refuses_a_full_step_that_increases_the_residual():
    # What it protects: Armijo's sufficient decrease, ||f|| <= (1 - 1e-4 alpha) ||f(x)||.
    # arctan's Newton iteration has a 2-cycle at +-1.3917452; from 1e-5 beyond it the full step
    # lands at -(1.3917452 + 2.6e-5), where |f| is larger by a relative 6e-6 only: a line
    # search that accepted a step that does not decrease ||f|| would take it (and cycle
    # outwards); Armijo's halves it, to about 0, the root.
    res = solve(atan_system, [1.3917452002707 + 1e-5], atan_jac, damping=True)
    # the halved step lands near 0, then Newton's cubic convergence on arctan lands on 0.0 (the
    # residuals above end at exactly 0): the bound only asks for a root at round-off
    assert res.converged and abs(res.x[0]) < 1e-12
    assert res.residual_norms[1] < res.residual_norms[0]
    assert np.all(np.diff(res.residual_norms) <= 0)
    assert res.step_norms[0] < 0.6 * res.full_step_norms[0]  # the first step was halved


def test_the_default_step_test_is_relative():
    # the root of (x / s)^3 = 1 is s = 1e-13: an absolute test with tol 1e-10 stops after one
    # step, 42 % off; the relative test finds s to ten digits
    s = 1e-13
    res = solve(lambda x: (x / s) ** 3 - 1, [2 * s], lambda x: np.diag(3 * x ** 2 / s ** 3))
    # the relative step test with the default tol 1e-10 finds s to about ten digits
    assert abs(res.x[0] - s) <= 1e-10 * s
    absolute = solve(lambda x: (x / s) ** 3 - 1, [2 * s], lambda x: np.diag(3 * x ** 2 / s ** 3),
                     relative=False)
    assert absolute.iterations == 1 and abs(absolute.x[0] - s) > 0.4 * s


def pair(x):
    """circle_line's residual and Jacobian from one call."""
    return circle_line(x), circle_line_jac(x)


def test_jac_true_takes_the_jacobian_from_fun():
    calls = {"fun": 0}

    def counted(x):
        calls["fun"] += 1
        return pair(x)

    res = solve(counted, [1.0, 0.5], jac=True, tol=1e-14)
    ref = solve(circle_line, [1.0, 0.5], circle_line_jac, tol=1e-14)
    np.testing.assert_array_equal(res.history, ref.history)
    assert res.nfev == res.njev == calls["fun"] == res.iterations + 1
    # damped: the Jacobian of a point the line search accepts is not computed again
    calls["fun"] = 0
    damped = solve(lambda x: (np.arctan(x), atan_jac(x)), [1.5], jac=True, damping=True, tol=1e-14)
    assert damped.converged and damped.nfev == damped.njev
    assert broyden(counted, [1.0, 0.5], jac=True, tol=1e-14).converged
    batch = solve_batch(lambda z: (cubic_pair(z), cubic_pair_jac(z)), [[0.8, 0.7], [-2.0, -3.0]],
                        jac=True, tol=1e-14)
    # both roots (+-1, +-1) to a few ulps after quadratic convergence to tol 1e-14
    np.testing.assert_allclose(batch.x, [[1.0, 1.0], [-1.0, -1.0]], rtol=1e-14)
    found = solve_all(lambda z: (cubic_pair(z), cubic_pair_jac(z)),
                      lambda rng, m: rng.uniform(-2, 2, (m, 2)), True, n_starts=100, rng=1)
    assert len(found.x) == 6
    with pytest.raises(ValueError, match="pair"):
        solve(circle_line, [1.0, 0.5], jac=True)
    with pytest.raises(ValueError, match="jac must be"):
        solve(circle_line, [1.0, 0.5], jac="exact")


@pytest.mark.parametrize("kwargs, match", [
    ({"damping": "yes"}, "damping must be True or False"),
    ({"damping": np.nan}, "damping must be True or False"),
    ({"relative": 1}, "relative must be True or False"),
    ({"maxiter": 10 ** 9}, "bound on the work"),
    ({"halvings": 100}, "bound on the work"),
])
def test_solve_refuses_bad_flags_and_unbounded_work(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve(circle_line, [1.0, 0.5], circle_line_jac, **kwargs)


@pytest.mark.parametrize("kwargs, match", [
    ({"raise_on_failure": "no"}, "raise_on_failure must be True or False"),
    ({"independent": 1}, "independent must be True or False"),
    ({"damping": "yes"}, "damping must be True or False"),
    ({"domain": lambda x: np.ones(3, bool)}, r"domain returned shape \(3,\)"),
])
def test_solve_batch_refuses_bad_flags_and_domains(kwargs, match):
    with pytest.raises(ValueError, match=match):
        solve_batch(lambda x: x ** 2 - 2, np.ones((2, 1)), lambda x: 2 * x[:, :, None],
                    **({"damping": True} if "domain" in kwargs else {}) | kwargs)


@pytest.mark.parametrize("kwargs, match", [
    ({"rng": "a"}, "rng must be"), ({"rng": -1}, "rng must be"),
    ({"domain": lambda z: np.ones(2, bool)}, "domain returned shape"),
    ({"n_starts": 10 ** 8}, "bound on the work"), ({"check": 10 ** 6}, "bound on the work"),
    ({"n_starts": 10_000_001}, "n_starts must"),
    ({"n_starts": 1000, "check": 10_000}, "check must"),
    ({"halvings": 53}, "halvings must"), ({"same": 0.0}, "same must"),
    ({"sample": "a"}, "sample must be callable"),
    ({"sample": lambda rng, m: np.empty((0, 2))},
     r"sample\(rng, 10\) must return 10 starts, shape \(10, n\), got shape \(0, 2\)"),
    ({"sample": lambda rng, m: np.ones((m, 3)), "seeds": [[0.5, 0.5]]},
     r"must return 10 starts, shape \(10, 2\), got shape \(10, 3\)"),
    ({"sample": lambda rng, m: np.full((m, 2), np.nan)}, "must be finite"),
])
def test_solve_all_refuses_bad_input(kwargs, match):
    args = {"sample": lambda rng, m: rng.uniform(-2, 2, (m, 2)), "n_starts": 10} | kwargs
    with pytest.raises(ValueError, match=match):
        solve_all(cubic_pair, args.pop("sample"), cubic_pair_jac, **args)


def test_fd_jacobian_checks_its_inputs_and_its_differences():
    with pytest.raises(ValueError, match="fx must be finite"):
        fd_jacobian(circle_line, [1.0, 0.5], fx=[np.nan, 0.0])
    with pytest.raises(ValueError, match=r"fx must have shape \(2,\)"):
        fd_jacobian(circle_line, [1.0, 0.5], fx=[0.0, 0.0, 0.0])
    with pytest.raises(NonFiniteError, match="not finite"), np.errstate(over="ignore"):
        fd_jacobian(lambda x: x ** 2, [1e200])     # fun overflows next to x
    with pytest.raises(NonFiniteError), np.errstate(invalid="ignore"):
        fd_jacobian(lambda x: np.sqrt(1.0 - x), [1.0])  # NaN one step beyond x


def test_failures_leak_no_runtime_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        # every system non-finite: the message's largest residual has no finite value
        res = solve_batch(lambda x: np.full_like(x, np.nan), np.ones((3, 1)),
                          lambda x: np.ones((len(x), 1, 1)), raise_on_failure=False)
        assert res.status.tolist() == ["non-finite"] * 3 and "none finite" in res.message
        with pytest.raises(DivergenceError, match="Jacobian is not finite"):
            solve(lambda x: x - 1.0, [3.0], lambda x: np.full((1, 1), np.inf))
        # plain Newton on x / (1 + x^2): the iterates grow until the step overflows
        with pytest.raises((ConvergenceError, SingularJacobianError)):
            solve(lambda x: x / (1 + x * x) if abs(x[0]) < 1e150 else 1 / x, [2.0],
                  lambda x: np.diag((1 - x * x) / (1 + x * x) ** 2) if abs(x[0]) < 1e150
                  else np.diag(-1 / x ** 2))


def test_results_follow_the_contract():
    res = solve(circle_line, [1.0, 0.5], circle_line_jac)
    assert isinstance(res, Result) and res.status == "converged" and res.converged is True
    assert res.nfev == res.iterations + 1 and res.njev == res.iterations and res.message
    batch = solve_batch(lambda x: x ** 2 - np.array([[4.0], [-1.0]]), np.ones((2, 1)),
                        lambda x: 2 * x[:, :, None], raise_on_failure=False, damping=True)
    assert isinstance(batch, Result) and batch.converged.tolist() == [True, False]
    assert "1 of 2 systems converged" in batch.message
    found = solve_all(cubic_pair, lambda rng, m: rng.uniform(-2, 2, (m, 2)), cubic_pair_jac,
                      n_starts=50, check=1, rng=0)
    assert isinstance(found, Result) and found.status.shape == found.iterations.shape == (100,)
    assert sum(found.status_counts.values()) == 100
    with pytest.raises(ConvergenceError) as info:
        solve(atan_system, [2.0], atan_jac, maxiter=4)
    assert info.value.result.status == "maxiter" and not info.value.result.converged


# --- property tests: the documented tolerance, or a failure reported ----------------------------

@st.composite
def dominant_systems(draw, batch=None):
    """``A x + c s sin(x / s) = b`` with its root ``x*`` known and a start near it.

    ``A`` is strictly diagonally dominant by a margin of 1 and ``c <= 0.5``, so the Jacobian
    ``A + c diag(cos(x / s))`` is regular everywhere; the scale ``s`` (1e-12 to 1e6) sizes the
    root, which is what a relative test must be indifferent to.
    """
    n = draw(st.integers(1, 4))
    rows = batch or 1
    floats = st.floats(-1.0, 1.0)
    A = np.array(draw(st.lists(floats, min_size=rows * n * n, max_size=rows * n * n)))
    A = A.reshape(rows, n, n)
    A[:, np.arange(n), np.arange(n)] = np.abs(A).sum(axis=2) + 1.0
    c = draw(st.floats(0.0, 0.5))
    s = draw(st.sampled_from([1e-12, 1e-6, 1.0, 1e6]))
    unit = st.floats(-10.0, 10.0).filter(lambda v: abs(v) > 0.1)
    root = s * np.array(draw(st.lists(unit, min_size=rows * n, max_size=rows * n)))
    root = root.reshape(rows, n)
    shift = s * np.array(draw(st.lists(floats, min_size=rows * n, max_size=rows * n)))
    b = np.einsum("bij,bj->bi", A, root) + c * s * np.sin(root / s)

    def fun(x):
        return np.einsum("...ij,...j->...i", A if x.ndim == 2 else A[0], x) + \
            c * s * np.sin(x / s) - (b if x.ndim == 2 else b[0])

    def jac(x):
        return (A if x.ndim == 2 else A[0]) + c * np.cos(x / s)[..., None] * np.eye(n)

    start = root + shift.reshape(rows, n)
    return fun, jac, (start if batch else start[0]), (root if batch else root[0])


def close_to_the_root(x, root, tol):
    """The documented guarantee of the relative step test, with a margin of ten: the last full
    step is below tol ||x||, and Newton's next error is far below that step."""
    return np.linalg.norm(x - root) <= 10 * tol * max(np.linalg.norm(x), np.linalg.norm(root))


@settings(max_examples=150, deadline=None)
@given(system=dominant_systems(), damping=st.booleans())
def test_solve_meets_its_tolerance_or_says_why(system, damping):
    fun, jac, x0, root = system
    try:
        res = solve(fun, x0, jac, damping=damping)
    except (ConvergenceError, SingularJacobianError) as error:
        assert error.result.status in STATUSES and error.result.status != "converged"
        return
    assert res.converged and close_to_the_root(res.x, root, 1e-10)
    # the criterion itself, with the default tol 1e-10 and the relative step
    assert res.full_step_norms[-1] <= 1e-10 * np.linalg.norm(res.x)


@settings(max_examples=150, deadline=None)
@given(system=dominant_systems())
def test_solve_residual_criterion_meets_its_tolerance_or_says_why(system):
    fun, jac, x0, root = system
    try:
        res = solve(fun, x0, jac, criterion="residual", tol=1e-8 * max(1.0, np.abs(root).max()))
    except (ConvergenceError, SingularJacobianError) as error:
        assert error.result.status in STATUSES and error.result.status != "converged"
        return
    # the criterion itself: the residual tolerance the call asked for
    assert np.linalg.norm(fun(res.x)) <= 1e-8 * max(1.0, np.abs(root).max())


@settings(max_examples=150, deadline=None)
@given(system=dominant_systems())
def test_broyden_meets_its_tolerance_or_says_why(system):
    fun, jac, x0, root = system
    try:
        res = broyden(fun, x0, jac)
    except (ConvergenceError, SingularJacobianError) as error:
        assert error.result.status in STATUSES and error.result.status != "converged"
        return
    assert res.converged and close_to_the_root(res.x, root, 1e-10)


@settings(max_examples=100, deadline=None)
@given(system=dominant_systems(batch=5), damping=st.booleans())
def test_solve_batch_meets_its_tolerance_or_says_why(system, damping):
    fun, jac, x0, root = system
    res = solve_batch(fun, x0, jac, damping=damping, raise_on_failure=False)
    assert set(res.status) <= set(STATUSES)
    for x, r, ok in zip(res.x, root, res.converged):
        assert not ok or close_to_the_root(x, r, 1e-10)


@settings(max_examples=40, deadline=None)
@given(r=st.lists(st.floats(-3.0, 3.0), min_size=4, max_size=4).filter(
    lambda v: abs(v[0] - v[1]) > 0.2 and abs(v[2] - v[3]) > 0.2), seed=st.integers(0, 1000))
def test_solve_all_roots_meet_the_tolerance(r, seed):
    # (x - r0)(x - r1) = 0 and (y - r2)(y - r3) = 0: four roots, each residual round-off
    def fun(z):
        return np.stack([(z[:, 0] - r[0]) * (z[:, 0] - r[1]),
                         (z[:, 1] - r[2]) * (z[:, 1] - r[3])], axis=-1)

    found = solve_all(fun, lambda rng, m: rng.uniform(-4, 4, (m, 2)), n_starts=100, check=1,
                      rng=seed)
    known = np.array([[a, b] for a in r[:2] for b in r[2:]])
    assert set(found.status) <= set(STATUSES)
    for root in found.x:
        # every root returned is one of the known roots to the deduplication tolerance (1e-10
        # relative) of solve_all
        assert np.abs(known - root).max(axis=1).min() <= 1e-10 * (1 + np.abs(root).max())
    # residuals of polished roots are round-off: about eps times the terms of the cubics, which grow
    # as the square of the roots' size
    assert np.all(found.residual_norms <= 1e-12 * (1 + np.abs(known).max()) ** 2)


# --- what mutation testing found untested (bench/mutation.md) ------------------------------------

SMALL = 2.0 ** -560  # a unit whose squares (2^-1120) are below the smallest float


def small_circle_line(x):
    """circle_line in a unit of 2^-560 (the same equations of y = x / SMALL, exactly), batched."""
    y = x / SMALL
    return np.stack([y[..., 0] ** 2 + y[..., 1] ** 2 - 1.0, y[..., 0] - y[..., 1]], axis=-1)


def small_circle_line_jac(x):
    y = x / SMALL
    rows = [np.stack([2 * y[..., 0], 2 * y[..., 1]], axis=-1),
            np.stack([np.ones_like(y[..., 0]), -np.ones_like(y[..., 0])], axis=-1)]
    return np.stack(rows, axis=-2) / SMALL


@pytest.mark.parametrize("method", [solve, broyden])
def test_steps_whose_squares_underflow_are_still_measured(method):
    # What it protects: the 2-norm of a step of size 2^-560 (its squares underflow to zero). It
    # was 0, so the relative step test took the first step as converged, 25 % from the root; and
    # Broyden's update divided by s^T s = 0 was skipped (a chord method, linear). The same
    # problem in a unit of 2^-560 must take the same iterations to the same root.
    big = method(circle_line, [1.0, 0.5], circle_line_jac, tol=1e-12)
    small = method(small_circle_line, [SMALL, 0.5 * SMALL], small_circle_line_jac, tol=1e-12)
    assert small.iterations == big.iterations
    # powers of two scale every iterate exactly but for the norms' own round-off (Broyden's update
    # divides by one): the roots agree to a few ulps
    np.testing.assert_allclose(small.x / SMALL, big.x, rtol=1e-15)
    batch = solve_batch(small_circle_line, np.array([[SMALL, 0.5 * SMALL]]), small_circle_line_jac,
                        tol=1e-12)
    if method is solve:  # the batch's step test on the same stack of tiny steps
        assert batch.iterations[0] == big.iterations
        np.testing.assert_allclose(batch.x[0] / SMALL, big.x, rtol=1e-15)  # as above


def test_broyden_gives_up_after_100_iterations_by_default():
    # exp(x) has no root: the iterates march to -inf with steps of ln 2 (documented default 100)
    with pytest.raises(ConvergenceError, match="did not converge in 100 iterations") as info:
        broyden(lambda x: np.exp(x), [0.0], lambda x: np.exp(x)[None])
    assert info.value.result.iterations == 100


def test_fd_jacobian_names_fun_and_x_in_its_errors():
    # What it protects: a function well-behaved at x but not at x + h e_j is named as fun, with
    # what it returned, and the non-finite differences show the x they were taken at
    def wrong_shape_near(z):
        return np.array([z[0] - 1.0]) if z[0] == 2.0 else np.array([z[0], 1.0])

    with pytest.raises(ValueError, match=r"^fun returned shape \(2,\), expected \(1,\)$"):
        fd_jacobian(wrong_shape_near, [2.0])
    with pytest.raises(NonFiniteError, match=r"^the forward differences of fun are not finite at "
                                             r"x = \[2\.\] \(fun is not finite near x"):
        fd_jacobian(lambda z: np.array([0.0 if z[0] == 2.0 else np.inf]), [2.0])
