"""The self-checks of :mod:`mechnum.exercises`: each passes its reference (from the instructors'
package, ``mechnum_course``), fails typical wrong implementations (written here, independently
of the mistake models) with a message that names the mistake, fails a stub, never raises on a
wrong answer, and raises on a malformed call. The references are checked against the package's
own methods, and the stored public answers against the references."""

import re
import time
from pathlib import Path
from types import SimpleNamespace

import nbformat
import numpy as np
import pytest
import yaml
from numpy.testing import assert_allclose

import mechnum_course
from mechnum import exercises, linear, ode, rods
from mechnum.mechanisms import actuator, prr3
from mechnum.mechanisms import hacksaw as hs
from mechnum.mechanisms.actuator.study import ANNEX, G_MATHCAD

NUMBERS = sorted(exercises.CHECKS)
ROOT = Path(__file__).resolve().parents[1]
ref = mechnum_course.reference


def test_at_least_two_exercises_per_chapter_and_the_krawczyk_test():
    chapters = [n.split(".")[0] for n in NUMBERS]
    assert all(chapters.count(str(c)) >= 2 for c in range(1, 8)) and "5.3" in NUMBERS
    for c in range(1, 8):  # numbered N.1, N.2, ... so that they come first in the chapter
        own = sorted(int(n.split(".")[1]) for n in NUMBERS if n.startswith(f"{c}."))
        assert own == list(range(1, len(own) + 1))


@pytest.mark.parametrize("number", NUMBERS)
def test_the_reference_passes_and_a_stub_does_not(number):
    assert exercises.check(number, ref(number)).passed
    assert exercises.CHECKS[number](ref(number)).passed
    namespace = {}
    exec(exercises.starter(number), {"np": np}, namespace)  # the starter cell as it is
    result = exercises.check(number, namespace[ref(number).__name__])
    assert not result.passed and "not yet" in result.message and "None" in result.message
    full = mechnum_course.check(number, ref(number))
    assert full.passed and f"all {len(exercises.EXERCISES[number].cases())} cases" not in \
        full.message  # the grade's check runs the hidden cases too


def test_the_stored_public_answers_are_the_references():
    """``public.json`` holds what the references and the mistakes return on the public cases
    now (``python -m mechnum_course.public_data`` rewrites it): equal strings and integers,
    floats to 1e-12 (another machine's arithmetic may differ in the last bits)."""
    import json

    from mechnum.exercises import _data
    from mechnum_course import public_data

    stored = json.loads(_data.PATH.read_text(encoding="utf-8"))
    fresh = json.loads(json.dumps(public_data.build()))
    assert stored.keys() == fresh.keys()

    def same(a, b):
        if isinstance(a, float) and isinstance(b, float):
            return a == b or abs(a - b) <= 1e-12 * max(abs(a), abs(b)) + 1e-300
        if isinstance(a, dict) and isinstance(b, dict):
            return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
        if isinstance(a, list) and isinstance(b, list):
            return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
        return type(a) is type(b) and a == b
    for number in fresh:
        assert same(stored[number], fresh[number]), number
    assert not same({"x": [1.0]}, {"x": [1.0 + 1e-9]})  # the comparison can fail


@pytest.mark.parametrize("number", NUMBERS)
def test_starter_solution_and_cells_agree(number):
    starter, solution = exercises.starter(number), mechnum_course.solution(number)
    assert starter.rstrip().endswith("...") and "return" not in starter.split('"""')[-1]
    head = starter.rstrip()[:-3].rstrip()
    assert solution.startswith(head)  # the solution fills the starter in
    shown = exercises.cells(number)
    assert [c["metadata"].get("mechnum", {}).get("role") for c in shown] == [
        None, "starter", "check"]
    cells = mechnum_course.cells(number)
    assert [c["metadata"].get("mechnum", {}).get("role") for c in cells] == [
        None, "starter", None, "solution", None, "check"]
    assert cells[1]["source"] == starter.rstrip("\n")
    assert cells[5]["source"] == exercises.check_code(number)
    assert "{solution-start}" in cells[2]["source"] and "{solution-end}" in cells[4]["source"]
    assert exercises.statement(number) in cells[0]["source"]
    for cell in cells[1::2]:  # the code a lecture page shows: its lines fit its column
        assert max(len(line) for line in cell["source"].splitlines()) <= 76, cell["source"]


def test_a_malformed_call_raises_and_a_wrong_answer_does_not():
    with pytest.raises(ValueError, match="no self-checked exercise '9.9'"):
        exercises.check("9.9", ref("1.1"))
    with pytest.raises(ValueError):
        exercises.check(1.1, ref("1.1"))
    for answer in (None, 42, "newton"):
        result = exercises.check("1.2", answer)
        assert not result.passed and "Pass the function itself" in result.message

    def raises(*args):
        raise ZeroDivisionError("boom")
    result = exercises.check("2.1", raises)
    assert not result.passed and "raised ZeroDivisionError: boom" in result.message


def test_an_endless_loop_is_stopped():
    def loops(f, s, y, h):
        while True:
            pass
    began = time.perf_counter()
    result = exercises.check("3.1", loops)
    assert time.perf_counter() - began < 3 * exercises.TIME_LIMIT
    assert not result.passed and "endless loop" in result.message


def test_the_check_runs_outside_the_main_thread_too():
    import threading
    box = {}

    def loops(*args):
        while True:
            pass
    worker = threading.Thread(target=lambda: box.update(r=exercises.check("4.1", loops)))
    worker.start()
    worker.join(10)
    assert not box["r"].passed and "endless loop" in box["r"].message


def test_an_answer_that_changes_its_argument_fails():
    def in_place(A, b, x, omega):
        x[:] = ref("2.1")(A, b, x, omega)
        return x
    result = exercises.check("2.1", in_place)
    assert not result.passed and "changed its argument `x` in place" in result.message


class EqualToEverything:
    def __eq__(self, other):
        return True

    __ne__ = lambda self, other: False  # noqa: E731
    __hash__ = object.__hash__


def test_an_object_equal_to_everything_fails():
    for number in ("6.1", "5.3", "3.1"):
        result = exercises.check(number, lambda *args: EqualToEverything())
        assert not result.passed and "EqualToEverything, not numbers" in result.message
    result = exercises.check("5.3", lambda *args: (EqualToEverything(), (1.0, 2.0)))
    assert not result.passed and "not numbers" in result.message


def test_answers_are_converted_exactly():
    def counted(F, J, x0, tol=1e-6, maxiter=50):
        x, k = ref("1.2")(F, J, x0, tol, maxiter)
        return x, k + 0.7  # int() would truncate 4.7 to 4
    result = exercises.check("1.2", counted)
    assert not result.passed and "is 4.7, a float; it must be an integer" in result.message
    result = exercises.check("1.2", lambda *a: (ref("1.2")(*a)[0], float(ref("1.2")(*a)[1])))
    assert not result.passed and "is 4.0, a float" in result.message
    result = exercises.check("6.1", lambda H, A: float(ref("6.1")(H, A)))
    assert not result.passed and "a float; it must be an integer" in result.message
    result = exercises.check("6.1", lambda H, A: True)  # a bool is not an integer
    assert not result.passed and "not an integer" in result.message
    for number, complex_answer in (
            ("7.1", lambda *a: tuple(v + 0j for v in ref("7.1")(*a))),
            ("4.1", lambda c: ref("4.1")(c).astype(complex)),
            ("5.3", lambda *a: (ref("5.3")(*a)[0], np.array(ref("5.3")(*a)[1]) + 0j))):
        result = exercises.check(number, complex_answer)
        assert not result.passed and "complex" in result.message, result.message
    result = exercises.check("5.3", lambda *a: ("Unique", ref("5.3")(*a)[1]))
    assert not result.passed and "must be one of 'unique', 'none', 'undecided'" in \
        result.message
    result = exercises.check("3.1", lambda f, s, y, h: np.full_like(y, np.nan))
    assert not result.passed and "not finite" in result.message
    assert exercises.check("7.1", lambda *a: list(ref("7.1")(*a))).passed  # a list is a pair


def test_the_answer_cannot_reach_the_check():
    def patches(f, s, y, h):
        from mechnum.exercises import _answers, _ch3, _harness
        _answers.close = _ch3.close = lambda *args, **kwargs: None
        _harness.judge = lambda *args, **kwargs: exercises.Result("3.1", True, "passed")
        return y
    result = exercises.check("3.1", patches)
    assert not result.passed and "y(s + h)" in result.message
    from mechnum.exercises import _ch3, _harness
    assert _ch3.close is not None and _harness.judge.__module__ == "mechnum.exercises._harness"
    assert exercises.check("3.1", ref("3.1")).passed


def test_system_exit_and_keyboard_interrupt_are_reported():
    import sys

    result = exercises.check("3.1", lambda f, s, y, h: sys.exit(3))
    assert not result.passed and "raised SystemExit (it called sys.exit" in result.message

    def interrupted(f, s, y, h):
        raise KeyboardInterrupt
    result = exercises.check("3.1", interrupted)
    assert not result.passed and "raised KeyboardInterrupt" in result.message


def test_a_long_c_call_is_stopped():
    def slow(c):
        while True:
            np.linalg.eigvals(np.random.default_rng(0).normal(size=(400, 400)))
    began = time.perf_counter()
    result = exercises.check("4.1", slow)
    assert time.perf_counter() - began < 3 * exercises.TIME_LIMIT
    assert "endless loop" in result.message


# Wrong implementations a student writes, named after the mistake; each check must fail them
# and name the mistake (a word of the expected phrase is enough).
def loop_typo(q, theta2, r1y, r2, r3):
    r1, t1, t3 = q
    F = np.array([r1 * np.sin(t1) - r1y, -r1 * np.cos(t1) + r2 * np.cos(theta2) + r3 *
                  np.cos(theta2), r1 * np.sin(t1) - r2 * np.sin(theta2) - r3 * np.sin(theta2)])
    return F, ref("1.1")(q, theta2, r1y, r2, r3)[1]


def loop_transposed(*args):
    F, J = ref("1.1")(*args)
    return F, np.array(J).T


def loop_sign(q, theta2, r1y, r2, r3):
    F, J = ref("1.1")(q, theta2, r1y, r2, r3)
    J = J.copy()
    J[1, 1] = -q[0] * np.sin(q[1])
    return F, J


def _damped(F, J, x0, tol, maxiter, test="newton", armijo=1e-4, count=0):
    x = np.asarray(x0, float)
    size = np.linalg.norm(F(x))
    for k in range(1, maxiter + 1):
        dx = np.linalg.solve(J(x), -F(x))
        lam = 1.0
        while np.linalg.norm(F(x + lam * dx)) > (1 - armijo * lam) * size:
            lam /= 2
            if lam < 2.0 ** -20:
                raise RuntimeError("stagnated")
        x = x + lam * dx
        size = np.linalg.norm(F(x))
        if {"newton": np.linalg.norm(dx), "damped": np.linalg.norm(lam * dx),
                "residual": size}[test] < tol:
            return x, k + count
    raise RuntimeError("maxiter")


def newton_undamped(F, J, x0, tol=1e-6, maxiter=50):  # the chapter's ten lines
    x = x0
    for k in range(1, maxiter + 1):
        dx = np.linalg.solve(J(x), -F(x))
        x = x + dx
        if np.linalg.norm(dx) < tol:
            return x, k
    raise RuntimeError(f"no step below {tol} in {maxiter} steps")


def newton_residual_test(F, J, x0, tol=1e-6, maxiter=50):
    return _damped(F, J, x0, tol, maxiter, test="residual")


def newton_damped_step_test(F, J, x0, tol=1e-6, maxiter=50):
    return _damped(F, J, x0, tol, maxiter, test="damped")


def newton_uncounted(F, J, x0, tol=1e-6, maxiter=50):
    return _damped(F, J, x0, tol, maxiter, count=-1)


def inverse_bad_broyden(H, s, y):
    return H + np.outer(s - H @ y, y) / (y @ y)


def inverse_without_h(H, s, y):
    return H + np.outer(s - H @ y, s) / (s @ H @ y)


def inverse_direct_formula(H, s, y):
    return H + np.outer(y - H @ s, s) / (s @ s)


def sor_jacobi(A, b, x, omega):
    D = np.diag(A)
    return (1 - omega) * x + omega * (b - (A @ x - D * x)) / D


def sor_no_relaxation_term(A, b, x, omega):
    x = x.copy()
    for i in range(len(b)):
        x[i] = omega * (b[i] - A[i] @ x + A[i, i] * x[i]) / A[i, i]
    return x


def sor_off_by_one(A, b, x, omega):
    x = x.copy()
    for i in range(len(b) - 1):
        x[i] += omega * (b[i] - A[i] @ x) / A[i, i]
    return x


def lstsq_normal(A, b):
    return np.linalg.solve(A.T @ A, A.T @ b)


def _householder(A, b, sign=1.0, reflect_b=True):
    R, y = np.array(A, float), np.array(b, float)
    for k in range(R.shape[1]):
        v = R[k:, k].copy()
        v[0] += sign * np.copysign(np.linalg.norm(v), v[0])
        v /= np.linalg.norm(v)
        R[k:] -= 2 * np.outer(v, v @ R[k:])
        if reflect_b:
            y[k:] -= 2 * v * (v @ y[k:])
    return np.triu(R[:R.shape[1]]), y[:R.shape[1]]


def lstsq_no_qt(A, b):
    return np.linalg.solve(*_householder(A, b, reflect_b=False))


def lstsq_transposed_r(A, b):
    R, y = _householder(A, b)
    return np.linalg.solve(R.T, y)


def lstsq_cancelling(A, b):
    return np.linalg.solve(*_householder(A, b, sign=-1.0))


def rk4_stages_at_s(f, s, y, h):
    k1 = f(s, y)
    k2 = f(s, y + h / 2 * k1)
    k3 = f(s, y + h / 2 * k2)
    k4 = f(s, y + h * k3)
    return y + h * (k1 + 2 * k2 + 2 * k3 + k4) / 6


def rk4_equal_weights(f, s, y, h):
    k1 = f(s, y)
    k2 = f(s + h / 2, y + h / 2 * k1)
    k3 = f(s + h / 2, y + h / 2 * k2)
    k4 = f(s + h, y + h * k3)
    return y + h * (k1 + k2 + k3 + k4) / 4


def rk4_full_steps(f, s, y, h):
    k1 = f(s, y)
    k2 = f(s + h / 2, y + h * k1)
    k3 = f(s + h / 2, y + h * k2)
    k4 = f(s + h, y + h * k3)
    return y + h * (k1 + 2 * k2 + 2 * k3 + k4) / 6


def _rod_tip(q, EI, L, nodes, moment_sign=1):
    m0, nx, ny = q

    def f(s, y):
        return np.array([np.cos(y[2]), np.sin(y[2]), y[3] / EI,
                         moment_sign * (nx * np.sin(y[2]) - ny * np.cos(y[2]))])

    return ode.rk4(f, np.array([0.0, 0.0, 0.0, m0]), np.linspace(0, L, nodes))[-1]


def shooting_moment_sign(q, EI, L, target, nodes):
    y = _rod_tip(q, EI, L, nodes, -1)
    return np.array([y[0] - target[0], y[1] - target[1], y[3]])


def shooting_target_minus_tip(q, EI, L, target, nodes):
    y = _rod_tip(q, EI, L, nodes)
    return np.array([target[0] - y[0], target[1] - y[1], y[3]])


def shooting_off_by_one(q, EI, L, target, nodes):
    y = _rod_tip(q, EI, L, nodes + 1)
    return np.array([y[0] - target[0], y[1] - target[1], y[3]])


def companion_monic_only(c):
    n = len(c) - 1
    return np.column_stack([np.vstack([np.zeros(n - 1), np.eye(n - 1)]), -np.asarray(c[:-1])])


def companion_descending(c):
    c = np.asarray(c)[::-1]
    n = len(c) - 1
    return np.column_stack([np.vstack([np.zeros(n - 1), np.eye(n - 1)]), -c[:-1] / c[-1]])


def companion_sign(c):
    n = len(c) - 1
    return np.column_stack([np.vstack([np.zeros(n - 1), np.eye(n - 1)]),
                            np.asarray(c[:-1]) / c[-1]])


def _prr3_system(pose, lam, g):
    x, y, psi = pose
    P = np.array([[x, y], [x + g.a * np.cos(psi), y + g.a * np.sin(psi)],
                  [x + g.a * np.cos(psi + np.pi / 3), y + g.a * np.sin(psi + np.pi / 3)]])
    C = np.array([[lam[0], 0], [g.B2 - lam[1], 0], [g.B3, g.H3 - lam[2]]])
    u = P - C
    n = np.column_stack((y - P[:, 1], P[:, 0] - x))
    return (u ** 2).sum(1) - g.L ** 2, 2 * np.column_stack((u, (u * n).sum(1)))


def prr3_transposed(pose, lam, g):
    F, J = _prr3_system(pose, lam, g)
    return pose - np.linalg.solve(J.T, F)


def prr3_no_two(pose, lam, g):
    F, J = _prr3_system(pose, lam, g)
    return pose - np.linalg.solve(J / 2, F)


def prr3_sign(pose, lam, g):
    F, J = _prr3_system(pose, lam, g)
    return pose + np.linalg.solve(J, F)


def _tip(EI, L, psi, k_rel, mode, m_of_k=lambda k: k * k, phi2=None, ysign=-1):
    from scipy.special import ellipeinc, ellipkinc
    kmin = abs(np.cos(psi / 2))
    k = np.sign(k_rel) * kmin + (1 - kmin) * k_rel
    p1 = np.arcsin(np.cos(psi / 2) / k)
    p2 = (mode - 0.5) * np.pi if phi2 is None else phi2(mode)
    m = m_of_k(k)
    F = ellipkinc(p2, m) - ellipkinc(p1, m)
    E = ellipeinc(p2, m) - ellipeinc(p1, m)
    C = np.cos(p2) - np.cos(p1)
    lam = F / L
    return np.array([-(np.cos(psi) * (2 * E - F) + 2 * k * np.sin(psi) * C) / lam,
                     -(np.sin(psi) * (2 * E - F) + ysign * 2 * k * np.cos(psi) * C) / lam])


def tip_modulus(EI, L, psi, k_rel, mode):
    return _tip(EI, L, psi, k_rel, mode, m_of_k=lambda k: k)


def tip_mode_pi(EI, L, psi, k_rel, mode):
    return _tip(EI, L, psi, k_rel, mode, phi2=lambda mode: mode * np.pi)


def tip_y_sign(EI, L, psi, k_rel, mode):
    return _tip(EI, L, psi, k_rel, mode, ysign=1)


def _rot(t):
    return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


def pin_plus_load(tips, forces, origins, theta, load):
    p = [origins[i] + _rot(theta[i]) @ tips[i] for i in (0, 1)]
    n = [_rot(theta[i]) @ forces[i] for i in (0, 1)]
    return np.r_[p[0] - p[1], n[0] + n[1] + load]


def pin_transposed_rotation(tips, forces, origins, theta, load):
    p = [origins[i] + _rot(theta[i]).T @ tips[i] for i in (0, 1)]
    n = [_rot(theta[i]).T @ forces[i] for i in (0, 1)]
    return np.r_[p[0] - p[1], n[0] + n[1] - load]


def pin_no_origins(tips, forces, origins, theta, load):
    p = [_rot(theta[i]) @ tips[i] for i in (0, 1)]
    n = [_rot(theta[i]) @ forces[i] for i in (0, 1)]
    return np.r_[p[0] - p[1], n[0] + n[1] - load]


def _K(f, df, lo, hi, sign=-1, centre=True, spread=True):
    m = (lo + hi) / 2
    dlo, dhi = df(lo, hi)
    y = 2 / (dlo + dhi)
    fm = f(m)
    c = sorted([m + sign * y * fm[0], m + sign * y * fm[1]])
    s = sorted([1 - y * dlo, 1 - y * dhi])
    X = (lo - m, hi - m) if centre else (lo, hi)
    p = [a * b for a in s for b in X] if spread else [0.0]
    return (np.nextafter(c[0] + min(p), -np.inf), np.nextafter(c[1] + max(p), np.inf))


def _K_nearest(f, df, lo, hi):  # every end rounded to nearest, none outwards
    m = lo + (hi - lo) / 2
    dlo, dhi = df(lo, hi)
    y = 2 / (dlo + dhi)
    fm = f(m)
    c = sorted([m - y * fm[0], m - y * fm[1]])
    s = sorted([1 - y * dlo, 1 - y * dhi])
    p = [a * b for a in s for b in (lo - m, hi - m)]
    return c[0] + min(p), c[1] + max(p)


def _verdict(K, lo, hi):
    if lo < K[0] and K[1] < hi:
        return "unique", K
    return ("none" if K[1] < lo or K[0] > hi else "undecided"), K


def krawczyk_sign(f, df, lo, hi):
    return _verdict(_K(f, df, lo, hi, sign=1), lo, hi)


def krawczyk_uncentred(f, df, lo, hi):
    return _verdict(_K(f, df, lo, hi, centre=False), lo, hi)


def krawczyk_newton_point(f, df, lo, hi):
    return _verdict(_K(f, df, lo, hi, spread=False), lo, hi)


def krawczyk_nearest(f, df, lo, hi):
    return _verdict(_K_nearest(f, df, lo, hi), lo, hi)


def krawczyk_none_when_not_inside(f, df, lo, hi):
    verdict, K = _verdict(_K(f, df, lo, hi), lo, hi)
    return ("none" if verdict == "undecided" else verdict), K


def index_unconstrained(H, A):
    return int((np.linalg.eigvalsh(H) < 0).sum())


def index_row_space(H, A):
    if len(A) == 0:
        return int((np.linalg.eigvalsh(H) < 0).sum())
    Z = np.linalg.qr(np.asarray(A).T)[0]
    return int((np.linalg.eigvalsh(Z.T @ H @ Z) < 0).sum())


def index_non_positive(H, A):
    from scipy.linalg import null_space
    Z = null_space(A) if len(A) else np.eye(len(H))
    return int((np.linalg.eigvalsh(Z.T @ H @ Z) <= 0).sum())


def rigid_side_lengths(pins, a):
    return np.array([np.linalg.norm(pins[i] - pins[j]) - a for i, j in ((0, 1), (1, 2), (2, 0))])


def rigid_clockwise(pins, a):
    z = pins[:, 0] + 1j * pins[:, 1]
    d = z - z.mean()
    b = a / np.sqrt(3) * np.exp(1j * np.radians([-30.0, -150.0, 90.0]))
    w = d / b
    return np.array([(w[0] - w[1]).real, (w[0] - w[1]).imag, abs(w[0]) - 1])


def rigid_not_centred(pins, a):
    z = pins[:, 0] + 1j * pins[:, 1]
    d = z - z[0]
    b = a / np.sqrt(3) * np.exp(1j * np.radians([-150.0, -30.0, 90.0]))
    w = d / b
    return np.array([(w[0] - w[1]).real, (w[0] - w[1]).imag, abs(w[0]) - 1])


def coefficients_sheet(theta2, theta4, a, l, b):
    d = theta2 - theta4
    return np.sin(d) * np.cos(d) / (a + l), np.sin(d) / b


def coefficients_reversed(theta2, theta4, a, l, b):
    d = theta4 - theta2
    return np.cos(d) / ((a + l) * np.sin(d)), 1 / (b * np.sin(d))


def coefficients_no_l(theta2, theta4, a, l, b):
    d = theta2 - theta4
    return np.cos(d) / (a * np.sin(d)), 1 / (b * np.sin(d))


def _force(kin, mech, g, coriolis=True, gravity=1.0, couples=True):
    e2, e4 = np.exp(1j * kin.theta2), np.exp(1j * kin.theta4)
    r3 = kin.a + mech.g3
    cor = 2 * kin.omega2 * kin.a_dot if coriolis else 0.0
    terms = [(mech.m2, mech.inertias[0], mech.g2 * (1j * kin.eps2 - kin.omega2 ** 2) * e2,
              1j * mech.g2 * kin.k2 * e2, kin.eps2 * kin.k2),
             (mech.m3, mech.inertias[1],
              (kin.a_ddot - r3 * kin.omega2 ** 2 + 1j * (r3 * kin.eps2 + cor)) * e2,
              (1 + 1j * r3 * kin.k2) * e2, kin.eps2 * kin.k2),
             (mech.m4, mech.inertias[2], mech.g4 * (1j * kin.eps4 - kin.omega4 ** 2) * e4,
              1j * mech.g4 * kin.k4 * e4, kin.eps4 * kin.k4)]
    Q = 0.0
    for mass, I, a_G, J, ek in terms:
        Q += mass * (a_G * np.conj(J)).real + (I * ek if couples else 0) + \
            gravity * mass * g * J.imag
    return Q


def force_no_coriolis(kin, mech, g):
    return _force(kin, mech, g, coriolis=False)


def force_gravity_sign(kin, mech, g):
    return _force(kin, mech, g, gravity=-1.0)


def force_no_couples(kin, mech, g):
    return _force(kin, mech, g, couples=False)


WRONG = {
    "1.1": [("typo", loop_typo), ("transposed", loop_transposed), ("sign", loop_sign)],
    "1.2": [("no damping", newton_undamped), ("residual", newton_residual_test),
            ("damped step", newton_damped_step_test), ("counted", newton_uncounted)],
    "1.3": [("other update", inverse_bad_broyden), ("s^T H", inverse_without_h),
            ("update of B", inverse_direct_formula)],
    "2.1": [("Jacobi", sor_jacobi), ("(1 - omega)", sor_no_relaxation_term),
            ("off-by-one", sor_off_by_one)],
    "2.2": [("normal equations", lstsq_normal), ("without its reflections", lstsq_no_qt),
            ("transposed R", lstsq_transposed_r), ("cancelling sign", lstsq_cancelling)],
    "3.1": [("stages at s", rk4_stages_at_s), ("weights", rk4_equal_weights),
            ("full steps", rk4_full_steps)],
    "3.2": [("sign in m'", shooting_moment_sign), ("target minus tip", shooting_target_minus_tip),
            ("off-by-one", shooting_off_by_one)],
    "4.1": [("leading coefficient", companion_monic_only), ("descending", companion_descending),
            ("sign", companion_sign)],
    "4.2": [("transposed", prr3_transposed), ("factor 2", prr3_no_two), ("sign", prr3_sign)],
    "5.1": [("parameter", tip_modulus), ("phi2", tip_mode_pi), ("sign in y", tip_y_sign)],
    "5.2": [("sign of F", pin_plus_load), ("inverse rotation", pin_transposed_rotation),
            ("motors", pin_no_origins)],
    "5.3": [("sign", krawczyk_sign), ("X - m", krawczyk_uncentred),
            ("Newton point", krawczyk_newton_point), ("overlap", krawczyk_none_when_not_inside),
            ("no outward rounding", krawczyk_nearest)],
    "6.1": [("constraints ignored", index_unconstrained), ("row space", index_row_space),
            ("zero counted", index_non_positive)],
    "6.2": [("side lengths", rigid_side_lengths), ("clockwise", rigid_clockwise),
            ("centroid", rigid_not_centred)],
    "7.1": [("sheet", coefficients_sheet), ("delta", coefficients_reversed),
            ("a + l", coefficients_no_l)],
    "7.2": [("Coriolis", force_no_coriolis), ("gravity", force_gravity_sign),
            ("couples", force_no_couples)],
}


def test_every_exercise_has_three_wrong_implementations():
    assert sorted(WRONG) == NUMBERS and all(len(w) >= 3 for w in WRONG.values())


@pytest.mark.parametrize("number, mistake, wrong",
                         [(n, m, w) for n, ws in WRONG.items() for m, w in ws])
def test_a_wrong_implementation_fails_with_its_mistake_named(number, mistake, wrong):
    wrong.__name__ = ref(number).__name__
    result = exercises.check(number, wrong)
    assert not result.passed, result.message
    assert result.message.startswith(f"Exercise {number}: not yet. On ")
    assert mistake in result.message, result.message


# The references against the package's own methods
def test_references_of_chapter_1_agree_with_the_hacksaw():
    rng = np.random.default_rng(0)
    for q, theta2 in zip(rng.uniform(-2, 2, (5, 3)), rng.uniform(-3, 3, 5)):
        F, J = ref("1.1")(q, theta2, hs.study.STUDY.r1y, hs.study.STUDY.r2, hs.study.STUDY.r3)
        assert_allclose(F, hs.position_residual(hs.study.STUDY, q, theta2), rtol=1e-13, atol=1e-15)
        assert_allclose(J, hs.position_jacobian(hs.study.STUDY, q), rtol=1e-13, atol=1e-15)
    geometry = (hs.study.STUDY.r1y, hs.study.STUDY.r2, hs.study.STUDY.r3)
    x, k = ref("1.2")(lambda q: ref("1.1")(q, 0.0, *geometry)[0],
                      lambda q: ref("1.1")(q, 0.0, *geometry)[1], hs.study.STUDY_SEED[:3])
    solved = hs.solve_consecutive(hs.study.STUDY, (0.0, 0.0, 0.0), hs.study.STUDY_SEED).stages[0]
    assert k == solved.iterations == 4
    assert_allclose(x, solved.x, rtol=1e-13)


def test_references_of_chapter_2_agree_with_the_package():
    rng = np.random.default_rng(1)
    M = rng.normal(size=(5, 5))
    A, b, x = M @ M.T + 5 * np.eye(5), rng.normal(size=5), rng.normal(size=5)
    assert_allclose(ref("2.1")(A, b, x, 1.3), linear.sweep_by_components(A, b, x, 1.3),
                    rtol=1e-13)
    A, b = rng.normal(size=(13, 3)), rng.normal(size=13)
    assert_allclose(ref("2.2")(A, b), np.linalg.lstsq(A, b, rcond=None)[0], rtol=1e-12)


def test_references_of_chapter_3_agree_with_the_package():
    f = rods.equations(1.3, np.array([0.4, -2.0]))
    y0 = np.array([0.0, 0.0, 0.0, 0.7])
    s = np.linspace(0.0, 0.9, 11)
    y = y0
    for i in range(10):
        y = ref("3.1")(f, s[i], y, s[i + 1] - s[i])
    assert_allclose(y, ode.rk4(f, y0, s)[-1], rtol=1e-13)
    q, target = np.array([-0.6, -3.2, -1.2]), np.array([0.8, 0.1])
    rod = rods.integrate(0.164934, 1.0, q[0], q[1:], nodes=61)
    assert_allclose(ref("3.2")(q, 0.164934, 1.0, target, 61),
                    [*(rod.tip - target), rod.m[-1]], rtol=1e-12, atol=1e-13)


def test_references_of_chapter_4_agree_with_the_package():
    geometry, lam = prr3.study.EXAMPLES["Table 6"]
    C = prr3.polynomial(geometry, lam)
    assert_allclose(np.sort_complex(np.linalg.eigvals(ref("4.1")(C))),
                    np.sort_complex(np.roots(C[::-1])), rtol=1e-9)
    poses = prr3.forward(geometry, lam).x
    pose = poses[0] + np.array([0.01, -0.02, 0.03])
    errors = []
    for _ in range(6):
        pose = ref("4.2")(pose, np.asarray(lam), geometry)
        errors.append(np.abs(pose - poses[0]).max())
    assert errors[-1] < 1e-13 and errors[2] < errors[1] ** 1.5  # quadratic convergence


def test_references_of_chapter_5_agree_with_the_package():
    for EI, L, psi, k_rel, mode in ((1.0, 1.0, 1.0, 0.5, 1), (0.16, 1.0, 3.49, -0.32, 2),
                                    (2.0, 0.7, 4.0, 0.8, 3)):
        assert_allclose(ref("5.1")(EI, L, psi, k_rel, mode),
                        rods.clamped_pinned(EI, L, psi, k_rel, mode).tip, rtol=1e-10,
                        atol=1e-12)
    rng = np.random.default_rng(5)  # two rods whose tips meet and whose forces balance
    theta, origins = rng.uniform(-3, 3, 2), rng.normal(size=(2, 2))
    P, n1, load = rng.normal(size=2), rng.normal(size=2), rng.normal(size=2)
    tips = np.array([_rot(-theta[i]) @ (P - origins[i]) for i in (0, 1)])
    forces = np.array([_rot(-theta[0]) @ n1, _rot(-theta[1]) @ (load - n1)])
    assert np.abs(ref("5.2")(tips, forces, origins, theta, load)).max() < 1e-14


def test_the_krawczyk_reference_proves_only_what_is_true():
    from mechnum.exercises._ch5 import Polynomial
    p = Polynomial((-2, 0, 1))  # x^2 - 2
    verdict, K = ref("5.3")(p.at, p.slope, 1.3, 1.5)
    assert verdict == "unique" and 1.3 < K[0] <= np.sqrt(2) <= K[1] < 1.5
    assert ref("5.3")(p.at, p.slope, 1.5, 2.0)[0] == "none"
    assert ref("5.3")(p.at, p.slope, -1.6, 1.7)[0] == "undecided"  # two roots
    double = Polynomial((1, -2, 1))
    assert ref("5.3")(double.at, double.slope, 0.9, 1.15)[0] == "undecided"


def test_references_of_chapter_6():
    from mechnum.exercises._ch6 import column, platform
    # the column pinned at its tip buckles at P L^2 / EI = 20.19; free, at pi^2 / 4
    assert [ref("6.1")(*column(P, 200)) for P in (19.0, 21.5)] == [0, 1]
    assert ref("6.1")(column(3.0, 200)[0], np.zeros((0, 200))) == 1
    turned = platform((0.3, -0.1), 2.0, 0.2)
    assert np.abs(ref("6.2")(turned, 0.2)).max() < 1e-14
    assert np.abs(ref("6.2")(platform((0.3, -0.1), 2.0, 0.2, mirror=True), 0.2)).max() > 0.1


def test_references_of_chapter_7_agree_with_the_package():
    for t in (0.1, 0.6):
        kin = actuator.kinematics(ANNEX, t)
        k2, k4 = ref("7.1")(float(kin.theta2), float(kin.theta4), float(kin.a),
                            ANNEX.l, ANNEX.b)
        assert_allclose([k2, k4], [float(kin.k2), float(kin.k4)], rtol=1e-12)
        state = SimpleNamespace(**{name: float(getattr(kin, name)) for name in (
            "theta2", "theta4", "k2", "k4", "omega2", "omega4", "eps2", "eps4", "a", "a_dot",
            "a_ddot")})
        assert_allclose(ref("7.2")(state, ANNEX, G_MATHCAD),
                        float(actuator.virtual_power_force(kin)), rtol=1e-12)


NOTEBOOKS = [*sorted((ROOT / "book").glob("*.ipynb")), ROOT / "tests" / "fixtures" /
             "exercise_chapter.ipynb"]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_the_notebooks_exercise_cells_are_the_packages(path):
    """A chapter's starter, solution and check cells equal the package's, in that order, with
    the exercise (its label and statement) and the gated solution's fences around them; the
    fixture has two such exercises."""
    cells = nbformat.read(path, as_version=4).cells
    for k, cell in enumerate(cells):
        meta = cell.metadata.get("mechnum", {})
        if meta.get("role") != "starter":
            continue
        number = meta["exercise"]
        expected = mechnum_course.cells(number)
        got = cells[k - 1:k + 5]
        for mine, theirs in zip(got, expected):
            if theirs["cell_type"] == "code":
                assert mine.source == theirs["source"], (path.name, number)
                assert mine.metadata["mechnum"] == theirs["metadata"]["mechnum"]
        label = re.search(r":label: ([\w-]+)", expected[0]["source"]).group(1)
        assert f":label: {label}" in got[0].source
        assert exercises.statement(number) in got[0].source
        assert f"{{solution-start}} {label}" in got[2].source
        assert "{solution-end}" in got[4].source
    if path.parent.name == "fixtures":
        assert sum(c.metadata.get("mechnum", {}).get("role") == "starter" for c in cells) == 2


def test_every_exercise_is_in_its_chapters_lecture_in_number_order():
    """Exercise N.k's starter is in the lecture page of chapter N (``_toc.yml``'s entry
    ``book/0N_*``), and a lecture's starters are its chapter's exercises, in number order."""
    toc = yaml.safe_load((ROOT / "_toc.yml").read_text(encoding="utf-8"))
    lectures = {entry["file"][6]: ROOT / f"{entry['file']}.ipynb"
                for part in toc["parts"] for entry in part["chapters"]
                if re.fullmatch(r"book/0\d_\w+", entry["file"])}
    for chapter, path in lectures.items():
        starters = [cell.metadata["mechnum"]["exercise"]
                    for cell in nbformat.read(path, as_version=4).cells
                    if cell.metadata.get("mechnum", {}).get("role") == "starter"]
        expected = sorted((n for n in exercises.CHECKS if n.split(".")[0] == chapter),
                          key=lambda n: int(n.split(".")[1]))
        assert starters == expected, (path.name, starters)


# Issue 31: each check enforces its statement; each wrong answer below fails with its reason.
def _named(number, function):
    function.__name__ = ref(number).__name__
    return exercises.check(number, function)


def test_the_chapters_newton_loop_does_not_pass_exercise_1_2():
    """The chapter's own "Newton in ten lines", run under the exercise's name, fails: the
    exercise asks for the damping that the chapter only describes."""
    cells = nbformat.read(ROOT / "book" / "01_newton_hacksaw.ipynb", as_version=4).cells
    source = next(c.source for c in cells if c.source.startswith("def newton_loop("))
    namespace = {"np": np, "norm": np.linalg.norm}
    exec(source.split("\n\n\n")[0], namespace)
    result = _named("1.2", namespace["newton_loop"])
    assert not result.passed and "Likely mistake, no damping" in result.message


def test_exercise_1_2_requires_its_runtime_error():
    def returns_instead(F, J, x0, tol=1e-6, maxiter=50):
        try:
            return ref("1.2")(F, J, x0, tol, maxiter)
        except RuntimeError:
            return np.asarray(x0, float), maxiter

    def raises_another(F, J, x0, tol=1e-6, maxiter=50):
        try:
            return ref("1.2")(F, J, x0, tol, maxiter)
        except RuntimeError as error:
            raise ValueError(str(error)) from None
    for wrong, reason in ((returns_instead, "returned where it must raise RuntimeError"),
                          (raises_another, "raised ValueError")):
        result = _named("1.2", wrong)
        assert not result.passed and reason in result.message, result.message
        assert "maxiter = 2" in result.message


def test_the_chapters_householder_qr_does_not_pass_exercise_2_2():
    """The chapter's own ``householder_qr``, which forms Q and each m x m reflection, fails:
    the exercise asks for reflections applied in place, and its tall case has no room for an
    m x m matrix."""
    cells = nbformat.read(ROOT / "book" / "02_linear_systems_finger.ipynb", as_version=4).cells
    source = next(c.source for c in cells if c.source.startswith("def householder_qr("))
    namespace = {"np": np}
    exec(source.split("\n\n\n")[0], namespace)
    qr = namespace["householder_qr"]

    def lstsq_householder(A, b):
        Q, R = qr(A)
        n = A.shape[1]
        return np.linalg.solve(R[:n], (Q.T @ b)[:n])
    A, b = exercises.EXERCISES["2.2"].cases()[0].args  # the method is right where m is small
    assert_allclose(lstsq_householder(A, b), ref("2.2")(A, b), rtol=1e-7)
    result = exercises.check("2.2", lstsq_householder)
    assert not result.passed and "100000 x 3" in result.message, result.message


@pytest.mark.parametrize("call", [
    lambda A, b: np.linalg.lstsq(A, b, rcond=None)[0],
    lambda A, b: np.linalg.pinv(A) @ b,
    lambda A, b: np.linalg.solve(np.linalg.qr(A)[1], np.linalg.qr(A)[0].T @ b),
    lambda A, b: __import__("scipy.linalg").linalg.lstsq(A, b)[0],
    lambda A, b: (lambda u, s, vt: vt.T @ ((u.T @ b) / s))(*np.linalg.svd(A, False))],
    ids=["lstsq", "pinv", "qr", "scipy lstsq", "svd"])
def test_exercise_2_2_runs_the_answer_without_the_library_solvers(call):
    result = _named("2.2", call)
    assert not result.passed and "which this exercise rules out" in result.message


def test_a_forbidden_call_cannot_hide_behind_its_own_name_or_an_except():
    namespace = {"np": np}
    exec("from numpy.linalg import lstsq\n"
         "def lstsq_householder(A, b):\n"
         "    try:\n"
         "        return lstsq(A, b, rcond=None)[0]\n"
         "    except Exception:\n"
         "        return np.zeros(A.shape[1])\n", namespace)
    result = exercises.check("2.2", namespace["lstsq_householder"])
    assert not result.passed and "numpy.linalg.lstsq" in result.message
    assert np.linalg.lstsq.__name__ == "lstsq"  # restored after the check
    assert namespace["lstsq"] is np.linalg.lstsq


def test_exercise_2_2_has_a_case_that_only_the_stable_sign_gets_right():
    A, b = exercises.EXERCISES["2.2"].cases()[-1].args
    exact = np.linalg.lstsq(A, b, rcond=None)[0]
    assert np.abs(lstsq_cancelling(A, b) / exact - 1).max() > 1e3 * 1e-7  # the check's rtol
    assert np.abs(ref("2.2")(A, b) / exact - 1).max() < 1e-3 * 1e-7


def test_chapter_3s_printed_tip_does_not_pass_exercise_5_1():
    """Chapter 3's study codes the tip as printed (differences of integrals from 0); it agrees
    at ordinary loads and fails the exercise's small load, where it loses digits."""
    from scipy.special import ellipeinc, ellipkinc
    cells = nbformat.read(ROOT / "book" / "03_elastica_study.ipynb", as_version=4).cells
    source = next(c.source for c in cells if c.source.startswith("def printed_tip("))
    namespace = {"np": np, "rods": rods, "ellipkinc": ellipkinc, "ellipeinc": ellipeinc}
    exec(source, namespace)

    def elliptic_tip(EI, L, psi, k_rel, mode):
        return namespace["printed_tip"](psi, k_rel, mode, EI, L)
    EI, L, psi, k_rel, mode = exercises.EXERCISES["5.1"].cases()[0].args
    # at the ordinary case the printed formulas lose only a few digits: 1e-12 relative
    assert_allclose(elliptic_tip(EI, L, psi, k_rel, mode),
                    rods.clamped_pinned(EI, L, psi, k_rel, mode).tip, rtol=1e-12)
    result = exercises.check("5.1", elliptic_tip)
    assert not result.passed and "k_rel = 1e-14" in result.message, result.message
    assert "Likely mistake, the printed formulas" in result.message
    small = exercises.EXERCISES["5.1"].cases()[-1].args  # the reference agrees with the package
    assert_allclose(ref("5.1")(*small), rods.clamped_pinned(*small).tip, rtol=0, atol=1e-15)


def test_exercise_1_3_runs_the_answer_without_inverting():
    def inverted(H, s, y):
        B = np.linalg.inv(H)
        return np.linalg.inv(B + np.outer(y - B @ s, s) / (s @ s))
    result = _named("1.3", inverted)
    assert not result.passed and "numpy.linalg.inv, which this exercise rules out" in \
        result.message
    H, s, y = exercises.EXERCISES["1.3"].cases()[0].args  # the reference meets the secant condition
    assert_allclose(ref("1.3")(H, s, y) @ y, s, rtol=1e-12)


def _prr3_loop(pose, lam, g):  # the three loop equations, F_i = |P_i - C_i|^2 - L^2
    x, y, psi = pose
    P = np.array([[x, y], [x + g.a * np.cos(psi), y + g.a * np.sin(psi)],
                  [x + g.a * np.cos(psi + np.pi / 3), y + g.a * np.sin(psi + np.pi / 3)]])
    C = np.array([[lam[0], 0.0], [g.B2 - lam[1], 0.0], [g.B3, g.H3 - lam[2]]])
    return ((P - C) ** 2).sum(axis=1) - g.L ** 2


@pytest.mark.parametrize("h", [1e-9, 1e-8, 1e-7, 1e-6])
def test_exercise_4_2_accepts_a_forward_difference_jacobian(h):
    """A Newton step with a forward-difference Jacobian passes, within 0.7 of the tolerance
    (the margin the tolerance's docstring states); the mistakes miss it by more than 1e5."""
    from mechnum.exercises._ch4 import STEP_ATOL, STEP_RTOL

    def prr3_newton_step(pose, lam, g):
        F = _prr3_loop(pose, lam, g)
        J = np.column_stack([(_prr3_loop(pose + h * e, lam, g) - F) / h for e in np.eye(3)])
        return pose - np.linalg.solve(J, F)
    assert exercises.check("4.2", prr3_newton_step).passed
    for case in exercises.EXERCISES["4.2"].cases():
        exact = ref("4.2")(*case.args)
        allowed = STEP_ATOL + STEP_RTOL * np.abs(exact)
        assert (np.abs(prr3_newton_step(*case.args) - exact) < 0.7 * allowed).all()
        for wrong in (prr3_transposed, prr3_no_two, prr3_sign):
            assert (np.abs(wrong(*case.args) - exact) > 1e5 * allowed).any()


def test_exercise_5_3_asks_for_outward_rounding():
    """Rounded to nearest, K(X) misses the exact set at both ends on a case built for it, and
    fails; so does a K(X) collapsed to a point."""
    from fractions import Fraction

    from mechnum_course.solutions._ch5 import exact_krawczyk
    case = exercises.EXERCISES["5.3"].cases()[6]
    exact = exact_krawczyk(*case.args)[1]
    nearest = _K_nearest(*case.args)
    assert Fraction(nearest[0]) > Fraction(exact[0]) and Fraction(nearest[1]) < Fraction(exact[1])
    result = _named("5.3", krawczyk_nearest)
    assert not result.passed and "does not enclose the exact K(X)" in result.message
    assert "no outward rounding" in result.message

    def collapsed(f, df, lo, hi):
        verdict, K = ref("5.3")(f, df, lo, hi)
        return verdict, (sum(K) / 2, sum(K) / 2)
    result = _named("5.3", collapsed)
    assert not result.passed and "a single point" in result.message


def test_exercise_5_3_rejects_unique_where_k_touches_the_edge():
    """With the tightest rounding and the closed interval's test, K(X) = [1.5, 2] of X = [1, 2]
    is called "unique": the check says that it must be undecided."""
    from mechnum_course.solutions._ch5 import exact_krawczyk

    def tight_and_closed(f, df, lo, hi):
        verdict, K = exact_krawczyk(f, df, lo, hi)
        return ("unique" if lo <= K[0] and K[1] <= hi else verdict), K
    result = _named("5.3", tight_and_closed)
    assert not result.passed and "K(X) = [1.5, 2] exactly" in result.message
    assert "the verdict is 'unique', expected 'undecided'" in result.message
    assert "closed X" in result.message


def test_exercise_5_3_cases_have_one_verdict_for_every_correct_rounding():
    from mechnum_course.solutions._ch5 import exact_krawczyk
    for case in exercises.EXERCISES["5.3"].cases() + mechnum_course.HIDDEN["5.3"]():
        assert ref("5.3")(*case.args)[0] == exact_krawczyk(*case.args)[0], case.label


@pytest.mark.parametrize("number, scale", [("1.2", 1 + 3e-7), ("3.2", 1 + 3e-7),
                                           ("4.2", 1 + 2e-4)])
def test_a_message_shows_the_digits_that_differ(number, scale):
    """An answer off in the 6th or 7th digit is shown with the digits that tell it from the
    expected one, and the difference."""
    def off(*args):
        value = ref(number)(*args)
        if isinstance(value, tuple):
            return (value[0] * scale, *value[1:])
        return value * scale
    message = _named(number, off).message
    shown = re.search(r" is (\S+), expected (\S+) \(off by", message)
    assert shown and shown[1] != shown[2], message


@pytest.mark.parametrize("number, answer, said", [
    ("1.2", lambda F, J, x0, tol=1e-6, maxiter=50: "converged",
     "your answer is a str; it must be 2 values, x, the number of steps"),
    ("1.2", lambda F, J, x0, tol=1e-6, maxiter=50: (ref("1.2")(F, J, x0, tol, maxiter)[0],
                                                     4.0),
     "the number of steps is 4.0, a float; it must be an integer"),
    ("4.2", lambda pose, lam, g: list(ref("4.2")(pose, lam, g))[:2],
     "the next pose has shape (2,); it must have shape (3,)"),
    ("5.3", lambda f, df, lo, hi: ref("5.3")(f, df, lo, hi)[1],
     "the verdict is a float64; it must be one of 'unique', 'none', 'undecided'"),
])
def test_a_wrong_type_gets_a_message_about_its_type(number, answer, said):
    result = _named(number, answer)
    assert not result.passed and said in result.message, result.message
    assert "Likely mistake" not in result.message and "Hint" not in result.message
