"""Tests of mechnum.mechanisms.hacksaw: every public function, on bad input and on its domain.

For each public function: a test of its bad inputs (a named error whose message names the
input), and a hypothesis test of 200 examples or more over the valid domain and just outside it,
asserting the documented shape and the function's defining property (a residual that vanishes,
a derivative that finite differences confirm, a linearity, a known limit) or a named error.
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from hypothesis import HealthCheck, assume, example, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from published import check_row, read_registry  # noqa: E402

from mechnum import newton  # noqa: E402
from mechnum.errors import (  # noqa: E402
    ConvergenceError,
    GeometryError,
    MechnumError,
    SingularJacobianError,
    UnreachablePoseError,
)
from mechnum.mechanisms import hacksaw as hs  # noqa: E402
from mechnum.mechanisms import prr3  # noqa: E402  (another mechanism, passed by mistake)
from mechnum.mechanisms.hacksaw import study  # noqa: E402
from mechnum.mechanisms.hacksaw._equations import (  # noqa: E402  (internal: the rates' pieces)
    acceleration_residual,
    rate_jacobian,
    velocity_residual,
)
from mechnum.mechanisms.hacksaw._exact import solve_rates  # noqa: E402
from mechnum.mechanisms.hacksaw._kernels import MODES  # noqa: E402
from mechnum.mechanisms.hacksaw._model import FORMS  # noqa: E402
from mechnum.mechanisms.hacksaw._solvers import MAX_POINTS, METHODS, PREDICTORS  # noqa: E402
from mechnum.plotting import animate  # noqa: E402

S = study.STUDY
T = hs.first_revolution_time()
REGISTRY = {row["quantity"]: row for row in read_registry(
    Path(__file__).resolve().parents[1] / "book" / "published_values.csv", "01_newton_hacksaw")}
EXAMPLES = settings(max_examples=200, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
FEW = settings(max_examples=200, deadline=None)

# valid lengths from a micrometre to a kilometre, angles and rates of any size a saw may meet
lengths = st.floats(1e-6, 1e3)
geometries = st.builds(hs.Geometry, r1y=lengths, r2=lengths, r3=lengths)
angles = st.floats(-50.0, 50.0)
rates = st.floats(-1e3, 1e3)
motor_states = st.tuples(angles, rates, rates)
floats = st.floats(allow_nan=True, allow_infinity=True)  # anything, bad values included


def scaled_residual(x, state, g):
    """The nine residuals of states ``x`` (..., 9), each divided by the size of its terms."""
    th2, w2, a2 = state
    L = max(g.r1y, g.r2, g.r3)
    w = 1 + abs(w2) + np.abs(x[..., 4:6]).max(axis=-1, initial=0)
    a = 1 + abs(a2) + np.abs(x[..., 7:9]).max(axis=-1, initial=0)
    scale = L * np.stack(np.broadcast_arrays(*[1.0] * 3, *[w] * 3, *[w**2 + a] * 3), axis=-1)
    return np.abs(hs.residual(g, x, th2, w2, a2)) / scale


def central_differences(fun, x, h=1e-6):
    """Central differences of ``fun`` at ``x`` (1-D), column by column: an independent Jacobian."""
    cols = []
    for j in range(len(x)):
        e = np.zeros_like(x)
        e[j] = h
        cols.append((fun(x + e) - fun(x - e)) / (2 * h))
    return np.stack(cols, axis=-1)


# ---------------------------------------------------------------------------------- Geometry


@pytest.mark.parametrize("kwargs, match", [
    ({"r1y": 0.0}, "r1y must be positive"), ({"r2": -0.075}, "r2 must be positive"),
    ({"r3": np.nan}, "r3 must be finite"), ({"r3": np.inf}, "r3 must be finite"),
    ({"r2": 1j}, "r2 must be real"), ({"r1y": "long"}, "r1y must be numeric"),
    ({"r3": [0.1, 0.2]}, "r3 must have 0 dimension")])
def test_geometry_rejects_bad_lengths(kwargs, match):
    with pytest.raises(GeometryError, match=match):
        hs.Geometry(**kwargs)


@EXAMPLES
@given(value=floats, name=st.sampled_from(["r1y", "r2", "r3"]))
def test_geometry_holds_positive_finite_lengths(value, name):
    if np.isfinite(value) and value > 0:
        assert getattr(hs.Geometry(**{name: value}), name) == value
    else:
        with pytest.raises(GeometryError, match=name):
            hs.Geometry(**{name: value})


# ----------------------------------------------------------------------------- motor profile


@pytest.mark.parametrize("alpha_max, match", [(0.0, "positive"), (-5.0, "positive"),
                                              (np.inf, "finite"), (np.nan, "finite"),
                                              (1e-320, "too small"), (1j, "real")])
def test_first_revolution_time_rejects_bad_alpha(alpha_max, match):
    with pytest.raises(ValueError, match=match):
        hs.first_revolution_time(alpha_max)


@EXAMPLES
@given(alpha_max=st.floats(1e-12, 1e12))
def test_first_revolution_time_completes_a_revolution(alpha_max):
    T_ = hs.first_revolution_time(alpha_max)
    np.testing.assert_allclose(hs.motor(T_, alpha_max)[0], 2 * np.pi, rtol=1e-13)
    np.testing.assert_allclose(hs.motor(T_ / 3, alpha_max)[1], alpha_max * T_ / 6, rtol=1e-13)


@pytest.mark.parametrize("t, match", [(-1.0, "non-negative"), (np.nan, "t must be finite"),
                                      ([0.0, np.inf], "t must be finite"), (1e308, "too large"),
                                      ([[1j]], "t must be real"), ("now", "t must be numeric")])
def test_motor_rejects_bad_times(t, match):
    with pytest.raises(ValueError, match=match):
        hs.motor(t)


@EXAMPLES
@given(t=st.lists(st.floats(-1.0, 1e6) | floats, max_size=6), alpha_max=st.floats(0.1, 100))
@example(t=[2.0703082021323823e+307], alpha_max=1.0)  # theta < max float; 2 A T t was not
def test_motor_profile_keeps_its_bounds_and_cruises(t, alpha_max):
    t = np.array(t)
    if not np.all(np.isfinite(t)) or np.any(t < 0):
        with pytest.raises(ValueError, match="t "):
            hs.motor(t, alpha_max)
        return
    T_ = hs.first_revolution_time(alpha_max)
    w_max = 2 * alpha_max * T_ / 3
    with np.errstate(over="ignore"):
        overflows = not np.all(np.isfinite(w_max * (t - T_)))
    if overflows:  # a crank angle beyond the largest float: a named error
        with pytest.raises(ValueError, match="t is too large"):
            hs.motor(t, alpha_max)
        return
    theta, omega, alpha = hs.motor(t, alpha_max)
    assert theta.shape == omega.shape == alpha.shape == t.shape
    assert np.all((alpha >= 0) & (alpha <= alpha_max * (1 + 1e-12)))
    assert np.all((omega >= 0) & (omega <= w_max * (1 + 1e-12)))
    cruise = t >= T_
    np.testing.assert_allclose(theta[cruise], 2 * np.pi + w_max * (t[cruise] - T_), rtol=1e-12)
    assert np.all(theta[~cruise] <= 2 * np.pi * (1 + 1e-12))


def test_motor_profile_is_continuous_and_integrates():
    t = np.linspace(0, 2 * T, 200001)
    theta, omega, alpha = hs.motor(t)
    dt = t[1] - t[0]
    assert np.abs(np.diff(omega)).max() < 10 * dt  # |alpha| <= 5: no jump in speed
    np.testing.assert_allclose(np.gradient(theta, dt)[1:-1], omega[1:-1], rtol=0, atol=1e-6)
    np.testing.assert_allclose(np.gradient(omega, dt)[1:-1], alpha[1:-1], rtol=0, atol=1e-3)
    np.testing.assert_allclose([alpha.max(), omega[-1]], [5.0, 10 * T / 3], rtol=1e-12)


# ------------------------------------------------------------- equations and their Jacobians

BAD_EVALUATOR_CALLS = [
    (hs.position_residual, (S, np.ones(4), 0.0), "q must have shape"),
    (hs.position_residual, (S, np.ones(3), np.nan), "theta2 must be finite"),
    (hs.position_residual, (S, np.ones((2, 3)), np.zeros(3)), "do not broadcast"),
    (hs.position_residual, (S, np.ones(3), 0.0, "reduced"), "form must be one of"),
    (hs.position_residual, (None, np.ones(3), 0.0), "mech must be a hacksaw.Geometry"),
    (hs.position_residual, (S, [1, 2, 1j], 0.0), "q must be real"),
    (hs.position_residual, (S, np.array([1.0, 0.0, 0.0]), 0.0, "eliminated"),
     "not finite"),  # the eliminated form divides by sin(theta1) = 0
    (hs.position_jacobian, (S, np.ones(2)), "q must have shape"),
    (hs.position_jacobian, (S, np.ones(3), "elim"), "form must be one of"),
    (rate_jacobian, (S, [np.inf, 0, 0]), "q must be finite"),
    (velocity_residual, (S, np.ones((2, 3)), np.ones(3), 0.0, [1.0, 2.0, 3.0]),
     "do not broadcast"),
    (velocity_residual, (S, np.ones(3), np.ones(3), 0.0, np.nan), "omega2 must be finite"),
    (velocity_residual, (S, np.full(3, 1e200), [1e200, 1, 1], 0.0, 1.0), "not finite"),
    (acceleration_residual, (S, np.ones(3), np.ones(3), np.ones(2), 0, 0, 0), "q must have"),
    (acceleration_residual, (S, np.ones(3), np.ones(3), np.ones(3), 0, 0, None),
     "alpha2 must be numeric"),
    (hs.residual, (S, np.ones(8), 0, 0, 0), "x must have shape"),
    (hs.residual, (S, np.ones(9), 0, 0, np.inf), "alpha2 must be finite"),
    (hs.jacobian, (S, np.ones((3, 3))), "x must have shape"),
    (hs.jacobian, (S, np.full(9, 1e200)), "not finite"),
    (hs.jacobian, (prr3.study.EXAMPLES["Table 3"][0], np.ones(9)), "mech must be a hacksaw"),
]


@pytest.mark.parametrize("function, args, match", BAD_EVALUATOR_CALLS,
                         ids=lambda v: getattr(v, "__name__", None))
def test_evaluators_reject_bad_input(function, args, match):
    with pytest.raises(ValueError, match=match):
        function(*args)


@EXAMPLES
@given(g=geometries, state=motor_states, form=st.sampled_from(FORMS),
       batch=st.integers(0, 3))
def test_position_residual_vanishes_on_the_closed_form(g, state, form, batch):
    try:
        x = hs.closed_form(g, motor_state=np.broadcast_to(np.array(state)[:, None], (3, batch)))
    except MechnumError:
        return
    F = hs.position_residual(g, x[..., :3], state[0], form)
    assert F.shape == (batch, 3)
    L = max(g.r1y, g.r2, g.r3)
    scale = L if form == "loop" else L / np.abs(np.sin(x[..., 1:2]))
    assert np.all(np.abs(F) <= 1e-13 * scale)


@EXAMPLES
@given(g=geometries, q=st.tuples(st.floats(-2, 2), angles, angles), th2=angles,
       form=st.sampled_from(FORMS))
def test_position_jacobian_is_the_derivative(g, q, th2, form):
    q = np.array(q) * [max(g.r1y, g.r2, g.r3), 1, 1]
    assume(form == "loop" or abs(np.sin(q[1])) > 0.1)
    J = hs.position_jacobian(g, q, form)
    assert J.shape == (3, 3)
    fd = central_differences(lambda z: hs.position_residual(g, z, th2, form), q,
                             h=1e-6 * np.maximum(1, np.abs(q)).min())
    np.testing.assert_allclose(J, fd, rtol=0, atol=1e-6 * (1 + np.abs(J).max()))
    if form == "loop":
        np.testing.assert_allclose(np.linalg.det(J), -q[0] * g.r3 * np.cos(q[2]), rtol=0,
                                   atol=1e-12 * (abs(q[0]) * g.r3 + np.abs(J).max() ** 3))


@EXAMPLES
@given(g=geometries, q=st.tuples(st.floats(-2, 2), angles, angles),
       v=st.tuples(rates, rates, rates),
       th2=angles, w2=rates)
def test_velocity_residual_is_linear_with_the_rate_jacobian(g, q, v, th2, w2):
    q, v = np.array(q), np.array(v)
    F = velocity_residual(g, v, q, th2, w2)
    F0 = velocity_residual(g, np.zeros(3), q, th2, w2)
    Jr = rate_jacobian(g, q)
    assert F.shape == (3,) and Jr.shape == (3, 3)
    size = np.abs(Jr).max() * np.abs(v).max() + np.abs(F0).max() + 1
    np.testing.assert_allclose(F - F0, Jr @ v, rtol=0, atol=1e-13 * size)
    np.testing.assert_allclose(Jr[2], hs.position_jacobian(g, q)[0], rtol=0, atol=0)


@EXAMPLES
@given(g=geometries, x=st.lists(st.floats(-2, 2), min_size=9, max_size=9), state=motor_states)
def test_acceleration_residual_is_linear_with_the_position_jacobian(g, x, state):
    x = np.array(x)
    a, v, q = x[6:], x[3:6], x[:3]
    F = acceleration_residual(g, a, v, q, *state)
    F0 = acceleration_residual(g, np.zeros(3), v, q, *state)
    J = hs.position_jacobian(g, q)
    size = np.abs(J).max() * np.abs(a).max() + np.abs(F0).max() + 1
    np.testing.assert_allclose(F - F0, J @ a, rtol=0, atol=1e-13 * size)


@EXAMPLES
@given(g=geometries, state=motor_states, batch=st.integers(0, 3))
def test_residual_vanishes_on_the_closed_form_and_stacks_the_stages(g, state, batch):
    try:
        x = hs.closed_form(g, motor_state=tuple(np.full(batch, s) for s in state))
    except MechnumError:
        return
    F = hs.residual(g, x, *state)
    assert F.shape == (batch, 9)
    assert np.all(scaled_residual(x, state, g) < 1e-12)
    np.testing.assert_array_equal(F[:, :3], hs.position_residual(g, x[:, :3], state[0]))


@EXAMPLES
@given(g=geometries, x=st.lists(st.floats(-2, 2), min_size=9, max_size=9), state=motor_states)
def test_jacobian_is_the_derivative_of_the_residual(g, x, state):
    x = np.array(x)
    J = hs.jacobian(g, x)
    assert J.shape == (9, 9)
    assert not J[0:3, 3:].any() and not J[3:6, 6:].any()  # block lower triangular
    fd = central_differences(lambda z: hs.residual(g, z, *state), x)
    # differences of values of size |F| with a step 1e-6 carry errors of about 1e-10 |F|
    size = np.abs(hs.residual(g, x, *state)).max()
    np.testing.assert_allclose(J, fd, rtol=0, atol=1e-6 * (1 + np.abs(J).max()) + 1e-9 * size)


def test_batched_jacobian_is_the_stack_of_single_ones():
    x = hs.closed_form(S, np.linspace(0, 2 * T, 7))
    # a batch and a single state may take different SIMD paths of sin/cos: equal to round-off
    np.testing.assert_allclose(hs.jacobian(S, x)[3], hs.jacobian(S, x[3]), rtol=1e-14, atol=1e-15)


# ------------------------------------------------------------------------------- closed form


@pytest.mark.parametrize("kwargs, error, match", [
    ({}, ValueError, "either t or motor_state"),
    ({"mech": None, "t": 1.0}, ValueError, "mech must be a hacksaw.Geometry"),
    ({"t": 1.0, "motor_state": (0, 0, 0)}, ValueError, "either"),
    ({"motor_state": (np.nan, 0.0, 0.0)}, ValueError, "theta2 must be finite"),
    ({"motor_state": (0.0, 0.0)}, ValueError, "motor_state must be"),
    ({"motor_state": ([0.0, 1.0], [0.0, 1.0, 2.0], 0.0)}, ValueError, "do not broadcast"),
    ({"t": [0.0, np.nan]}, ValueError, "t must be finite"),
    ({"t": 1.0, "mech": 0.17}, ValueError, "mech must be"),
    ({"motor_state": (1.0, 1e200, 0.0)}, ValueError, "not finite"),
    ({"motor_state": (-np.pi / 2, 0.0, 0.0), "mech": hs.Geometry(r3=0.110)},
     UnreachablePoseError, r"r3 = 1.09091 > 1 at theta2 = -1.5708"),
    # the limiting coupler, r3 = r1y + r2: vertical at the crank's lowest point, alpha3 infinite
    ({"motor_state": (-np.pi / 2, 1.0, 0.0), "mech": hs.Geometry(r3=0.120)},
     SingularJacobianError, "dead point at theta2 = -1.57"),
])
def test_closed_form_rejects_bad_input_and_dead_points(kwargs, error, match):
    kwargs = {"mech": S} | kwargs
    with pytest.raises(error, match=match):
        hs.closed_form(**kwargs)


def test_closed_form_for_a_tiny_guide_offset():
    # r1y = 1e-300: theta1 underflowed to 0 and r1 = r1y / sin(theta1) was infinite
    g = hs.Geometry(r1y=1e-300)
    x = hs.closed_form(g, motor_state=(0.3, 1.0, 0.0))
    centred = hs.Geometry(r1y=1e-12)  # an offset 1e-12 m changes nothing visible
    np.testing.assert_allclose(x[[0, 2, 3, 5, 6, 8]],
                               hs.closed_form(centred, motor_state=(0.3, 1.0, 0.0))[
                                   [0, 2, 3, 5, 6, 8]], rtol=1e-9)
    assert np.isfinite(x).all() and x[0] * np.sin(x[1]) == pytest.approx(1e-300, rel=1e-12)


@EXAMPLES
@given(g=geometries, state=motor_states)
def test_closed_form_solves_all_nine_equations_on_the_studys_branch(g, state):
    try:
        x = hs.closed_form(g, motor_state=state)
    except UnreachablePoseError:
        assert abs(g.r1y - g.r2 * np.sin(state[0])) > g.r3 * (1 - 1e-12)
        return
    except SingularJacobianError:
        assert abs(abs(g.r1y - g.r2 * np.sin(state[0])) / g.r3 - 1) < 1e-7
        return
    assert x.shape == (9,)
    assert np.all(scaled_residual(x, state, g) < 1e-10 / np.abs(np.cos(x[2])) ** 2)
    assert np.cos(x[2]) < 0 and -np.pi / 2 < x[1] <= np.pi / 2  # the study's branch
    assert x[0] * np.sin(x[1]) > 0


# ---------------------------------------------------------------- both modes, singular points


@EXAMPLES
@given(g=geometries, state=motor_states)
def test_forward_gives_both_assembly_modes_and_the_first_is_the_closed_form(g, state):
    try:
        both = hs.forward(g, state).x
    except MechnumError:
        with pytest.raises(MechnumError):
            hs.closed_form(g, motor_state=state)
        return
    assert both.shape == (2, 9)
    np.testing.assert_array_equal(both[0], hs.closed_form(g, motor_state=state))
    for mode, x in zip(MODES, both):
        assert np.all(scaled_residual(x, state, g) < 1e-10 / np.abs(np.cos(x[2])) ** 2)
        assert (np.cos(x[2]) > 0) == (mode == 1)  # mode 1: the coupler points forward
    # the two modes share the crank pin and the guide, and differ in the slider
    O, A, B = hs.joints(g, both[:, :3], state[0])
    np.testing.assert_allclose(B[:, 1], g.r1y, rtol=1e-12)


def slider_x(g, theta2, mode):
    return hs.joints(g, hs.forward(g, (theta2, 0 * theta2, 0 * theta2)).x[..., mode, :3],
                     theta2)[2][..., 0]


@pytest.mark.parametrize("g", [S, hs.Geometry(r1y=0.05, r2=0.02, r3=0.1),
                               hs.Geometry(r1y=1e-3, r2=0.1, r3=0.3)])
def test_limit_positions_are_where_the_slider_stops(g):
    points = hs.singular_points(g)
    assert points.x.size == 0 and points.limits.shape == (2, 2)
    for mode in MODES:
        # an independent location: the slider's extreme abscissae on a fine grid of the crank
        grid = np.linspace(0, 2 * np.pi, 200001)
        x = slider_x(g, grid, mode)
        turns = grid[[np.argmin(x), np.argmax(x)]]
        assert np.all(np.min(np.abs(np.subtract.outer(points.limits[mode], turns) + np.pi)
                             % (2 * np.pi) - np.pi, axis=0) < 1e-4)
        # and the slider's velocity vanishes there (the rate equations, not the grid)
        v = hs.forward(g, (points.limits[mode], np.ones(2), np.zeros(2))).x[:, mode]
        np.testing.assert_allclose(v[:, 3], 0.0, rtol=0, atol=1e-12)


def test_dead_points_of_a_short_coupler_are_where_the_modes_meet():
    g = hs.Geometry(r3=0.1)  # r3 < r1y + r2 = 0.12: the crank cannot turn round
    points = hs.singular_points(g)
    assert points.x.size == 2 and points.limits.shape == (2, 1)  # only the extended one
    for theta2 in points.x:  # cos(theta3) = 0: r1y - r2 sin(theta2) = +-r3
        np.testing.assert_allclose(abs(g.r1y - g.r2 * np.sin(theta2)), g.r3, rtol=1e-14)
        with pytest.raises(SingularJacobianError, match="dead point"):
            hs.forward(g, (theta2, 1.0, 0.0))
    away = points.x.mean() + np.pi  # the middle of the motion's range, between the two
    assert hs.forward(g, (away, 0.0, 0.0)).x.shape == (2, 9)


def test_singular_points_refuse_what_is_not_a_mechanism():
    with pytest.raises(ValueError, match="mech must be a hacksaw.Geometry"):
        hs.singular_points(None)


# ------------------------------------------------------------------------------ the solvers

X1 = hs.closed_form(S, 1.0)
REST = (0.0, 0.0, 0.0)
BAD_SOLVER_CALLS = [  # function, arguments, keyword arguments, error, message
    (solve_rates, (S, X1[:4], hs.motor(1.0)), {}, ValueError, "q must have shape"),
    (solve_rates, (S, X1[:3], (0.0, 1.0)), {}, ValueError, "motor_state must be"),
    (solve_rates, (hs.Geometry(r3=0.12), [0.045, np.pi / 2, np.pi / 2],
                      (-np.pi / 2, 1.0, 0.0)), {}, SingularJacobianError, "dead point"),
    # positions off the constraints (the closed form at another time): no configuration
    (solve_rates, (S, X1[:3], hs.motor(1.2)), {}, ValueError,
     "q must satisfy the position constraints"),
    (hs.solve_consecutive, (S, REST, np.zeros(8)), {}, ValueError, "seed must have shape"),
    (hs.solve_consecutive, (S, REST, study.STUDY_SEED), {"tol": -1.0}, ValueError,
     "tol must be positive"),
    (hs.solve_consecutive, (S, REST, study.STUDY_SEED), {"form": "x"}, ValueError, "form must be"),
    (hs.solve_consecutive, (S, ([0.0, 1.0], 0.0, 0.0), np.tile(study.STUDY_SEED, (3, 1))), {},
     ValueError, "do not broadcast"),
    (hs.solve_consecutive, (S, REST, np.full(9, np.nan)), {}, ValueError,
     "seed must be finite"),
    (hs.solve_consecutive, (None, REST, study.STUDY_SEED), {}, ValueError, "mech must be"),
    (hs.solve_simultaneous, (S, REST, np.full(9, np.nan)), {}, ValueError,
     "seed must be finite"),
    (hs.solve_simultaneous, (S, ([0.0, 1.0], 0.0, 0.0), study.STUDY_SEED), {}, ValueError,
     "three scalars"),
    (hs.solve_simultaneous, (S, REST, np.tile(study.STUDY_SEED, (2, 1))), {}, ValueError,
     "seed must have 1 dimension"),
    (hs.solve_simultaneous, (S, REST, study.STUDY_SEED), {"tol": np.nan}, ValueError,
     "tol must be"),
    # a seed with theta3 = pi/2 makes the Jacobian singular at the start
    (hs.solve_simultaneous, (S, REST, [-0.1, -0.5, np.pi / 2, 0, 0, 0, 0, 0, 0]), {},
     SingularJacobianError, "singular Jacobian at iteration 0"),
    # the study's seed, with a tolerance below the round-off of the unknowns: no convergence
    (hs.solve_simultaneous, (S, (1.0, 5.0, 2.0), X1), {"tol": 1e-300}, ConvergenceError,
     "did not converge in 50 iterations"),
]


@pytest.mark.parametrize("function, args, kwargs, error, match", BAD_SOLVER_CALLS,
                         ids=lambda v: getattr(v, "__name__", None))
def test_solvers_reject_bad_input(function, args, kwargs, error, match):
    with pytest.raises(error, match=match):
        function(*args, **kwargs)


@EXAMPLES
@given(g=geometries, state=motor_states, batch=st.integers(0, 3))
def test_solve_rates_recovers_the_closed_form_rates(g, state, batch):
    states = tuple(np.full(batch, s) for s in state)
    try:
        x = hs.closed_form(g, motor_state=states)
    except MechnumError:
        return
    v, a = solve_rates(g, x[..., :3], states)
    assert v.shape == a.shape == (batch, 3)
    # two ways to the same rates agree to round-off times the condition number of J
    cond = np.linalg.cond(hs.position_jacobian(g, x[..., :3])).max(initial=1)
    size = 1 + np.abs(x[..., 3:]).max(initial=0)
    np.testing.assert_allclose(np.concatenate([v, a], axis=-1), x[..., 3:],
                               rtol=0, atol=1e-12 * cond**2 * size)


@EXAMPLES
@given(state=motor_states, seed=st.integers(0, 2**32 - 1),
       size=st.floats(0.0, 0.1), simultaneous=st.booleans())
@example(state=(0.0, 0.0, 0.0), seed=1628, size=0.078125, simultaneous=False)  # a turn off
def test_newton_from_a_perturbed_state_converges_back(state, seed, size, simultaneous):
    exact = hs.closed_form(S, motor_state=state)
    scale = np.maximum(1, np.abs(exact))
    x0 = exact + size * np.random.default_rng(seed).normal(size=9) * scale
    tol = 1e-12 * scale.max()  # a step tolerance above the round-off of the largest unknown
    try:
        if simultaneous:
            x = hs.solve_simultaneous(S, state, x0, tol=tol).x
        else:
            x = hs.solve_consecutive(S, state, x0, tol=tol).x
    except (ConvergenceError, SingularJacobianError):
        assert size > 0.01  # only a far start may fail, and then by a named error
        return
    assert x.shape == (9,)
    if np.cos(x[2]) < 0 and x[0] < 0:  # the study's root, not another assembly
        x[1:3] = exact[1:3] + np.angle(np.exp(1j * (x[1:3] - exact[1:3])))  # whole turns off
        np.testing.assert_allclose(x, exact, rtol=1e-9, atol=1e-9)
    assert np.all(scaled_residual(x, state, study.STUDY) < 1e-10)


@EXAMPLES
@given(state=motor_states, n=st.integers(0, 4), seed=st.integers(0, 2**32 - 1))
def test_batched_consecutive_solves_each_point(state, n, seed):
    states = tuple(np.full(n, s) for s in state)
    exact = hs.closed_form(S, motor_state=states)
    scale = np.maximum(1, np.abs(exact))
    x0 = exact + 0.001 * np.random.default_rng(seed).normal(size=(n, 9)) * scale
    stages = hs.solve_consecutive(S, states, x0, tol=1e-12 * scale.max(initial=1)).stages
    assert [r.x.shape for r in stages] == [(n, 3)] * 3
    np.testing.assert_allclose(np.concatenate([r.x for r in stages], axis=-1), exact,
                               rtol=1e-9, atol=1e-9)


def test_consecutive_and_simultaneous_at_rest_count_as_the_study():
    # the registry's rows: the study's counts (its acceleration count is a source error)
    stages = hs.solve_consecutive(S, (0.0, 0.0, 0.0), study.STUDY_SEED).stages
    for stage, res in zip(("position", "velocity", "acceleration"), stages):
        check_row(REGISTRY[f"iterations, {stage} stage at rest"], res.iterations)
    simultaneous = hs.solve_simultaneous(S, (0.0, 0.0, 0.0), study.STUDY_SEED)
    check_row(REGISTRY["iterations, simultaneous 9x9 at rest"], simultaneous.iterations)
    eliminated = hs.solve_consecutive(S, (0.0, 0.0, 0.0), study.STUDY_SEED,
                                      form="eliminated").stages
    assert eliminated[0].iterations == 4
    for res in (stages[0], eliminated[0]):
        np.testing.assert_allclose(res.x, hs.closed_form(S, 0.0)[:3], rtol=0, atol=1e-11)


@pytest.mark.parametrize("args, kwargs, match", [
    ((S, np.linspace(0, 1, 5), "parallel"), {}, "method must be one of"),
    ((S, np.zeros((2, 2)), "batched"), {}, "t must have 1 dimension"),
    ((S, np.linspace(0, 1, 5), "batched"), {"predictor": "velocity"}, "per-point loops"),
    ((S, np.linspace(0, 1, 5), "consecutive"), {"predictor": "taylor"}, "predictor must be"),
    ((S, np.linspace(0, 1, 5), "simultaneous"), {"seed": np.zeros(3)}, "seed must have shape"),
    ((S, np.linspace(0, 1, 5), "simultaneous"), {"tol": 0.0}, "tol must be positive"),
    ((S, [1.0, -1.0], "batched"), {}, "t must be non-negative"),
    ((None, [0.0], "batched"), {}, "mech must be"),
    ((S, np.zeros(MAX_POINTS + 1), "batched"), {}, "a bound on the work"),
])
def test_sweep_rejects_bad_input(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        hs.sweep(*args, **kwargs)


def test_sweep_stops_at_a_dead_point_with_a_named_error():
    g = hs.Geometry(r3=0.12)
    t = np.array([0.0, 1.0, 1.4])  # nowhere near the crank's lowest point: fine
    assert hs.sweep(g, t, "batched").x.shape == (3, 9)
    th_lowest = 3 * np.pi / 2  # the lowest point of the first revolution, reached at t below
    t_low = float(np.interp(th_lowest, hs.motor(np.linspace(0, T, 20001))[0],
                            np.linspace(0, T, 20001)))
    with pytest.raises(MechnumError):
        hs.sweep(g, np.array([t_low]), "batched", seed=hs.closed_form(g, t_low - 1e-3))


def study_iterations(g, t, seed, method, predictor, tol):
    """The Newton iterations of the study's scheme at every point, counted afresh with
    mechnum.newton on the public equations, each point seeded as ``predictor`` says."""
    th2, w2, a2 = hs.motor(t)
    rule = {"tol": tol, "criterion": "step", "norm": 2, "relative": False}  # the study's rule
    counts, x = [], np.asarray(seed, dtype=float)
    exact = hs.closed_form(g, t)
    for i in range(t.size):
        start = x
        if i and predictor == "velocity":
            start = x + (t[i] - t[i - 1]) * np.concatenate([x[3:], np.zeros(3)])
        m, q, v = (th2[i], w2[i], a2[i]), exact[i, :3], exact[i, 3:6]  # this point's
        if method == "simultaneous":
            counts.append([newton.solve(lambda z, m=m: hs.residual(g, z, *m), start,
                                        lambda z: hs.jacobian(g, z), **rule).iterations])
        else:
            counts.append([
                newton.solve(lambda z, m=m: hs.position_residual(g, z, m[0]), start[:3],
                             lambda z: hs.position_jacobian(g, z), **rule).iterations,
                newton.solve(lambda z, m=m, q=q: velocity_residual(g, z, q, *m[:2]),
                             start[3:6], lambda z, q=q: rate_jacobian(g, q),
                             **rule).iterations,
                newton.solve(lambda z, m=m, q=q, v=v: acceleration_residual(g, z, v, q, *m),
                             start[6:], lambda z, q=q: hs.position_jacobian(g, q),
                             **rule).iterations])
        x = exact[i]
    return np.array(counts, dtype=int).reshape(t.size, 1 if method == "simultaneous" else 3)


@FEW
@given(start=st.floats(0.0, 10.0), steps=st.lists(st.floats(0.0, 0.05), max_size=6),
       method=st.sampled_from(METHODS), predictor=st.sampled_from(PREDICTORS))
def test_sweep_follows_the_closed_form(start, steps, method, predictor):
    # steps of at most 0.05 s (the crank turns at most 0.33 rad): the seed stays on the branch
    t = start + np.cumsum([0.0] + steps)[: len(steps)]
    if method == "batched" and predictor == "velocity":
        with pytest.raises(ValueError, match="per-point loops"):
            hs.sweep(S, t, method, predictor=predictor)
        return
    seed = hs.closed_form(S, t[0] if t.size else 0.0)
    seed = seed + 1e-4 * np.arange(1, 10)  # a seed off the answer: every stage iterates
    res = hs.sweep(S, t, method, tol=1e-10, predictor=predictor, seed=seed)
    assert res.x.shape == (t.size, 9)
    assert res.iterations.shape == (t.size, 3 if method == "consecutive" else 1)
    np.testing.assert_allclose(res.x, hs.closed_form(S, t), rtol=0, atol=1e-9)
    if method != "batched" and t.size:  # the counts of Newton's iterations, recounted
        counts = study_iterations(S, t, seed, method, predictor, 1e-10)
        np.testing.assert_array_equal(res.iterations, counts)
    elif t.size:  # every point from the seed: the counts of one batch, recounted point by point
        th2 = hs.motor(t)[0]
        recount = [newton.solve(lambda z, a=a: hs.position_residual(S, z, a), seed[:3],
                                lambda z: hs.position_jacobian(S, z), tol=1e-10,
                                relative=False).iterations
                   for a in th2]
        np.testing.assert_array_equal(res.iterations[:, 0], recount)


def test_velocity_predictor_saves_iterations_and_keeps_the_answer():
    t = np.linspace(0, 2 * T, 200)
    for method in ("consecutive", "simultaneous"):
        previous, velocity = (hs.sweep(S, t, method, predictor=p) for p in PREDICTORS)
        assert velocity.iterations[:, 0].sum() < previous.iterations[:, 0].sum()
        np.testing.assert_allclose(velocity.x, previous.x, rtol=0, atol=1e-9)
        if method == "consecutive":
            # the rate stages are linear: two iterations (one step, one confirming step)
            # with either predictor, except at rest, where the seed's zero rates are exact
            for run in (previous, velocity):
                assert np.all(run.iterations[1:, 1:] == 2)
                assert np.all(run.iterations[0, 1:] == 1)


@pytest.mark.parametrize("method", ["consecutive", "simultaneous"])
def test_a_coarse_sweep_stays_in_its_assembly_mode(method):
    # four points 1.5 revolutions apart: the velocity predictor lands in the other mode (r1 >
    # 0, the coupler forward); the sweep solves such a point again from the previous one
    t = np.linspace(0, 6 * T, 5)
    res = hs.sweep(S, t, method, predictor="velocity")
    exact = hs.closed_form(S, t)
    np.testing.assert_allclose(res.x[:, 0], exact[:, 0], rtol=1e-9)
    np.testing.assert_allclose(np.cos(res.x[:, 2]), np.cos(exact[:, 2]), rtol=1e-9)


@pytest.mark.parametrize("method", METHODS)
def test_a_sweep_that_cannot_keep_its_mode_says_where(method):
    # a seed of the study's mode (r1 < 0, cos(theta3) < 0) by a hair: theta3 = 1.58, next to
    # the coupler's vertical. Newton goes to the other mode; the sweep says so, not answers.
    seed = np.array([-0.1, -0.5, 1.58, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    with pytest.raises(ConvergenceError, match="branch"):
        hs.sweep(S, [0.0, 0.01], method, seed=seed)


# --------------------------------------------------------------------------- joints and draw


@pytest.mark.parametrize("args, match", [((S, np.ones(5), 0.0), "x must have shape"),
                                         ((S, np.ones((2, 9)), [0.0, 1.0, 2.0]),
                                          "do not broadcast"),
                                         ((S, np.ones(9), np.nan), "theta2 must be finite"),
                                         ((None, np.ones(9), 0.0), "mech must be")])
def test_joints_reject_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        hs.joints(*args)


@EXAMPLES
@given(g=geometries, state=motor_states, batch=st.integers(0, 3), positions=st.booleans())
def test_joints_close_the_loop(g, state, batch, positions):
    try:
        x = hs.closed_form(g, motor_state=tuple(np.full(batch, s) for s in state))
    except MechnumError:
        return
    O, A, B = hs.joints(g, x[..., :3] if positions else x, state[0])
    assert O.shape == A.shape == B.shape == (batch, 2)
    L = max(g.r1y, g.r2, g.r3)
    np.testing.assert_allclose(np.linalg.norm(A - O, axis=-1), g.r2, rtol=1e-14)
    np.testing.assert_allclose(np.linalg.norm(B - A, axis=-1), g.r3, rtol=1e-12 * L / g.r3)
    np.testing.assert_allclose(B[:, 1], g.r1y, rtol=0, atol=1e-12 * L)


def test_draw_rejects_bad_input():
    fig, ax = plt.subplots()
    with pytest.raises(ValueError, match="one state"):
        hs.draw(ax, S, (0.0, hs.closed_form(S, [0.0, 1.0])))
    with pytest.raises(ValueError, match="x must be finite"):
        hs.draw(ax, S, (0.0, np.full(9, np.nan)))
    with pytest.raises(ValueError, match="ax must be a matplotlib Axes"):
        hs.draw(None, S, (0.0, hs.closed_form(S, 0.0)))
    with pytest.raises(ValueError, match="state must be"):
        hs.draw(ax, S, hs.closed_form(S, 0.0))
    with pytest.raises(ValueError, match="legend must be True or False"):
        hs.draw(ax, S, (0.0, hs.closed_form(S, 0.0)), legend="yes")
    with pytest.raises(ValueError, match="artists must be"):
        hs.draw(ax, S, (0.0, hs.closed_form(S, 0.0)), artists={"crank": None})
    plt.close(fig)


_FIG, _AX = plt.subplots()


@FEW
@given(t=st.floats(0.0, 10.0), legend=st.booleans())
def test_draw_shows_the_joints_inside_the_limits_and_moves_them(t, legend):
    _AX.clear()
    x, th2 = hs.closed_form(S, t), hs.motor(t)[0]
    parts = hs.draw(_AX, S, (th2, x), legend=legend)
    first = hs.closed_form(S, 0.0)
    moved = hs.draw(_AX, S, (0.0, first), artists=parts)
    assert moved == parts and len(_AX.lines) == 5  # the same artists, nothing added
    for (angle, state) in ((0.0, first),):
        O, A, B = hs.joints(S, state, angle)
        np.testing.assert_allclose(parts["crank"].get_xydata(), [O, A], rtol=1e-14, atol=1e-15)
        np.testing.assert_allclose(parts["coupler"].get_xydata(), [A, B], rtol=1e-14)
        np.testing.assert_allclose(parts["slider"].get_xydata()[0], B, rtol=1e-14)
    parts = hs.draw(_AX, S, (th2, x), artists=parts)
    O, A, B = hs.joints(S, x, th2)
    np.testing.assert_allclose(parts["coupler"].get_xydata(), [A, B], rtol=1e-14, atol=1e-15)
    assert parts["guide"].get_ydata()[0] == study.STUDY.r1y
    (x0, x1), (y0, y1) = _AX.get_xlim(), _AX.get_ylim()
    points = np.array([O, A, B])
    assert np.all((points[:, 0] > x0) & (points[:, 0] < x1))
    assert np.all((points[:, 1] > y0) & (points[:, 1] < y1))
    assert (_AX.get_legend() is not None) == legend


def test_animate_moves_the_saw_through_its_states():
    t = np.linspace(0, T, 4)
    html = animate(hs.draw, S, list(zip(hs.motor(t)[0], hs.closed_form(S, t))), legend=False)
    assert html.count("data:image/png;base64") == 4


# ----------------------------------------------------------------------------------- reproduce


def test_reproduce_recomputes_the_studys_numbers():
    values = study.reproduce()
    assert all(np.isfinite(v) for v in values.values())
    np.testing.assert_allclose(
        [values[f"{n} at rest (simultaneous)"] for n in hs.NAMES[:3]],
        hs.closed_form(S, 0.0)[:3], rtol=1e-12)
    stages = hs.solve_consecutive(S, (0.0, 0.0, 0.0), study.STUDY_SEED).stages
    assert [values[f"iterations, {s} stage at rest"] for s in ("position", "velocity",
                                                                "acceleration")] == \
        [r.iterations for r in stages]


def test_the_evaluators_broadcast_a_batch_of_motor_rates():
    # it raised numpy's "all the input arrays must have same number of dimensions" before
    x, (theta2, _, alpha2) = hs.closed_form(study.STUDY, 1.0), hs.motor(1.0)
    each = [hs.residual(study.STUDY, x, theta2, w, alpha2) for w in (-1.0, 0.0, 2.0)]
    np.testing.assert_array_equal(
        hs.residual(study.STUDY, x, theta2, np.array([-1.0, 0.0, 2.0]), alpha2), each)
