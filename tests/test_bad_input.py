"""Bad input, tried on every public function of :mod:`mechnum`.

Each function is first called as its own docstring example calls it (the first call of the
example is recorded, not run); that call is the valid baseline. Then one argument at a time is
replaced by a family of bad values (NaN, infinity, a wrong shape, a string, ``None``, a negative,
zero or huge count, a nonsense option) and by an empty batch, and each call runs under a 2 s alarm.
Every outcome is classified:

* ``ok``: a ``ValueError``/``TypeError`` or a :class:`mechnum.errors.MechnumError` raised on
  purpose by ``mechnum`` (by a ``raise`` statement of the package, so its message is the
  package's own), or an empty result for an empty batch;
* ``raw``: any other exception (numpy's, Python's ``IndexError``, a leaked ``RuntimeWarning``);
* ``hang``: no answer within 2 s (a work argument without a bound);
* ``silent``: a result holding NaN or infinity that does not say it failed;
* ``accepted``: a finite result for bad input (not necessarily wrong: a family is a guess).

The counts are sampled evidence over the families below, not a proof. ``python
tests/test_bad_input.py`` prints the tally.
"""
import contextlib
import dataclasses
import doctest
import importlib
import inspect
import io
import os
import signal
import sys
import time
import traceback
import warnings

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import mechnum
from mechnum.errors import MechnumError
from mechnum.results import Result

MODULES = ("continuation", "newton", "linear", "ode", "homotopy", "polynomials", "certify",
           "published", "exercises", "plotting", "rods", "rods.assembly", "rods.profile",
           "rods.regular", "rods.growing", "mechanisms.actuator", "mechanisms.elastica",
           "mechanisms.finger", "mechanisms.hacksaw", "mechanisms.hacksaw.equations",
           "mechanisms.pfr3", "mechanisms.prr3", "mechanisms.rfr2")
LIMIT = 2.0  # seconds: a call that takes longer (or 5 times its valid baseline) is a hang
PACKAGE = os.path.dirname(mechnum.__file__)

# Arguments that set an amount of work: they get -1, 0 and a huge value (must hit a bound).
WORK = {"nodes", "segments", "n_psi", "n_k", "n_starts", "check", "maxiter", "max_boxes",
        "steps", "max_steps", "halvings", "directions", "levels", "divisions", "count", "m",
        "samples", "frames", "n"}
# Batches, emptied together: an empty batch is valid input and must give an empty result.
BATCH = {"poses": (0, 3), "inputs": None, "thetas": None, "points": None, "starts": None,
         "params": None, "theta_in": None, "theta_out": None, "psi": None, "k_rel": None}
# Arguments handed on untouched to the caller's own function (its business, not mechnum's).
PASSED_ON = {("plotting.animate", "mech"), ("plotting.animate", "states")}
# Files other engineers are rewriting now: their findings are expected failures, listed here.
ELSEWHERE = ("mechnum.mechanisms.rfr2", "mechnum.mechanisms.pfr3", "mechnum.rods.assembly",
             "mechnum.rods.growing", "mechnum.rods.regular", "mechnum.newton")
# Functions whose arrays are data, not batches: an empty one is bad input.
NOT_BATCHES = {"mechanisms.finger.synthesize"}  # a fit of at least 3 angle pairs
# Calls that block inside numpy (no alarm can stop them): not made, reported as hangs.
NOT_RUN = {("rods.growing.branch_shape", "nodes", "huge"): "np.linspace of 10**9 nodes"}


def public_functions():
    """``{qualified name: callable}`` of every public function and mechanism class."""
    found = {}
    for short in MODULES:
        module = importlib.import_module(f"mechnum.{short}")
        names = getattr(module, "__all__", None) or [
            n for n, v in vars(module).items() if not n.startswith("_")
            and getattr(v, "__module__", "") == module.__name__]
        for name in names:
            obj = getattr(module, name)
            if not callable(obj) or (inspect.isclass(obj) and issubclass(obj, (Result, Exception))):
                continue
            home = obj.__module__.startswith(module.__name__)
            if id(obj) not in found or home and not found[id(obj)][2]:
                found[id(obj)] = (f"{short}.{name}", obj, home)
    return {name: obj for name, obj, _ in found.values()}


class _Recorded(Exception):
    """Stops a docstring example at the first call of the function under test."""


def baseline(obj):
    """The ``(args, kwargs)`` of the first call of ``obj`` in its docstring example, or None."""
    module = sys.modules[obj.__module__]
    tests = doctest.DocTestFinder(recurse=False).find(obj, obj.__name__, module=module,
                                                       globs=vars(module).copy())
    seen = []

    def recorder(*args, **kwargs):
        seen.append((args, kwargs))
        raise _Recorded

    homes = [m for m in list(sys.modules.values()) if m is not None and
             m.__name__.startswith("mechnum") and vars(m).get(obj.__name__) is obj]
    for home in homes:
        setattr(home, obj.__name__, recorder)
    try:
        for test in tests:
            test.globs[obj.__name__] = recorder
            for example in test.examples:
                with contextlib.redirect_stdout(io.StringIO()), warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    try:
                        exec(compile(example.source, "<example>", "exec"), test.globs)
                    except _Recorded:
                        return seen[0]
                    except Exception:  # noqa: BLE001 (a setup line that needs what it lacks)
                        return None
    finally:
        for home in homes:
            setattr(home, obj.__name__, obj)
    return None


def families(name, value, default):
    """The bad values tried for argument ``name`` whose valid baseline value is ``value``."""
    out = {} if default is None else {"None": None}
    if isinstance(value, (bool, np.bool_)):
        return {**out, "truthy str": "yes"}
    if isinstance(value, str):
        return {**out, "unknown option": "no such option", "number": 1}
    if isinstance(value, (int, np.integer)) and name in WORK:
        return {**out, "negative": -1, "zero": 0, "huge": 10**9, "fraction": 2.5, "nan": np.nan}
    if callable(value) and not isinstance(value, np.ndarray):
        return {**out, "str": "a"}
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return {**out, "str": "a"}  # an object: a mechanism, an axes, a result
    out |= {"str": "a", "nan": np.full(arr.shape, np.nan), "inf": np.full(arr.shape, np.inf),
            "wrong shape": np.ones(arr.shape[:-1] + (arr.shape[-1] + 1,) if arr.ndim else (3,))}
    if arr.ndim == 0 and float(arr) >= 0:
        out["negative"] = -1.0
    return out


def emptied(arguments):
    """``arguments`` with every batch emptied, or None if it has no batch."""
    empty = {}
    for name, value in arguments.items():
        if name in BATCH and np.ndim(value) >= 1 and not isinstance(value, str):
            shape = BATCH[name] or (0,) + np.shape(value)[1:]
            empty[name] = np.empty(shape)
    return dict(arguments, **empty) if empty else None


def nonfinite(value, depth=0):
    """Whether ``value`` (an array, a number, a dataclass or container of them) holds NaN/inf."""
    if depth > 3:
        return False
    if isinstance(value, (float, np.floating, np.ndarray)):
        arr = np.asarray(value)
        return arr.dtype.kind in "fc" and not np.isfinite(arr).all()
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        value = [getattr(value, f.name) for f in dataclasses.fields(value)]
    if isinstance(value, dict):
        value = list(value.values())
    if isinstance(value, (list, tuple)):
        return any(nonfinite(v, depth + 1) for v in value[:50])
    return False


def says_failed(value):
    """Whether a result reports a failure in its ``status`` (or ``converged``)."""
    status = getattr(value, "status", None)
    if status is None:
        return False
    return not np.all(np.asarray(status) == "converged")


def deliberate(error):
    """Whether ``error`` was raised by a ``raise`` (or ``assert``) of mechnum: its own message."""
    if isinstance(error, FileNotFoundError):
        return True  # names the file
    frames = traceback.extract_tb(error.__traceback__)
    return bool(frames) and frames[-1].filename.startswith(PACKAGE) and \
        (frames[-1].line or "").lstrip().startswith(("raise", "assert"))


def _alarm(signum, frame):
    raise TimeoutError


def call(obj, arguments, limit):
    """``obj(**arguments)`` under an alarm of ``limit`` s, warnings as errors: (value, error)."""
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, limit)
    try:
        with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("error", RuntimeWarning)
            warnings.simplefilter("error", np.exceptions.ComplexWarning)
            bound = inspect.signature(obj).bind_partial(**arguments)
            return obj(*bound.args, **bound.kwargs), None
    except Exception as error:  # noqa: BLE001 (the point: which ones escape)
        return None, error
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        plt.close("all")


def classify(value, error, family):
    """The outcome of one call: ``ok``, ``raw``, ``hang``, ``silent`` or ``accepted``."""
    if isinstance(error, TimeoutError):
        return "hang", "no answer in time"
    if error is not None:
        named = isinstance(error, (ValueError, TypeError, MechnumError, AssertionError, OSError))
        if named and deliberate(error) and family != "empty batch":
            return "ok", str(error)
        return "raw", f"{type(error).__name__}: {error}"
    if family == "empty batch":
        return ("silent", "non-finite") if nonfinite(value) else ("ok", "empty result")
    if nonfinite(value) and not says_failed(value):
        return "silent", "non-finite result, not reported as a failure"
    return "accepted", type(value).__name__


def fuzz(name, obj):
    """Every bad call of ``obj``: a list of ``(argument, family, outcome, detail)``, or None."""
    recorded = baseline(obj)
    if recorded is None:
        return None
    signature = inspect.signature(obj)
    arguments = signature.bind(*recorded[0], **recorded[1]).arguments
    if not arguments:  # nothing to spoil
        return []
    start = time.perf_counter()
    value, error = call(obj, arguments, 10 * LIMIT)
    if error is not None:  # the example's own call fails here: no valid baseline
        return None
    limit = max(LIMIT, 5 * (time.perf_counter() - start))
    trials = []
    for arg, value in arguments.items():
        parameter = signature.parameters[arg]
        if parameter.kind in (parameter.VAR_POSITIONAL, parameter.VAR_KEYWORD) or \
                (name, arg) in PASSED_ON:
            continue
        default = "required" if parameter.default is parameter.empty else parameter.default
        trials += [(arg, family, dict(arguments, **{arg: bad}))
                   for family, bad in families(arg, value, default).items()]
    if name not in NOT_BATCHES and (empty := emptied(arguments)) is not None:
        trials.append(("batches", "empty batch", empty))
    rows = []
    for arg, family, trial in trials:
        if (name, arg, family) in NOT_RUN:
            rows.append((arg, family, "hang", NOT_RUN[name, arg, family]))
            continue
        rows.append((arg, family, *classify(*call(obj, trial, limit), family)))
    return rows


FUNCTIONS = public_functions()
OUTCOMES = ("ok", "raw", "hang", "silent", "accepted")


@pytest.mark.parametrize("name", sorted(FUNCTIONS))
def test_bad_input_gets_a_named_error(name):
    rows = fuzz(name, FUNCTIONS[name])
    if rows is None:
        pytest.skip("no docstring example calls it")
    bad = [row for row in rows if row[2] in ("raw", "hang", "silent")]
    if bad and FUNCTIONS[name].__module__.startswith(ELSEWHERE):
        pytest.xfail(f"{FUNCTIONS[name].__module__} is being rewritten elsewhere: {bad}")
    assert not bad, "\n".join(map(str, bad))


def _reproducers():
    """``{finding: (call, the words its error must say)}``: each failed with a raw error before."""
    from mechnum import certify, continuation, homotopy, ode, plotting, published, rods
    from mechnum.mechanisms import prr3
    f, J = (lambda x: [x[0] * x[0] - 2]), (lambda x: [[2 * x[0]]])
    row = dict(quantity="T", published="1.942", computed="1.941626", verdict="reproduced")
    g = prr3.EXAMPLES["Table 5"][0]
    return {
        "rk4 f str": (lambda: ode.rk4("a", [1.0], [0.0, 0.1]), "f must be a function"),
        "shooting bc None": (lambda: ode.multiple_shooting(
            lambda s, y: y, None, [0.0, 1.0], np.zeros((2, 2))), "bc must be a function"),
        "arclength fun None": (lambda: continuation.pseudo_arclength(None, f, [1.0, 0.0]),
                               "fun must be a function"),
        "path jac str": (lambda: continuation.solve_path(
            lambda x, p: x - p, [[1.0]], [0.0], jac="a"), "jac must be a function"),
        "path x0 too long": (lambda: continuation.solve_path(
            lambda x, c: x ** 2 - c[:, None], [1.0, 2.0], [1.0, 1.0],
            lambda x, c: 2 * x[:, :, None]), r"Jacobian in x must be square, \(2, 2\)"),
        "track None": (lambda: homotopy.track(None, [1.0 + 0j]), "homotopy must be a function"),
        "ball str": (lambda: certify.ball("a"), "two real numbers"),
        "ball array": (lambda: certify.ball([1.0, 2.0]), "two real numbers"),
        "definite None": (lambda: certify.definite(None), "hessian_ball must be a square"),
        "roots box str": (lambda: certify.roots(f, J, "a"), "box must be numeric"),
        "roots residual None": (lambda: certify.roots(None, J, [[-3.0, 3.0]]),
                                "residual must be a function"),
        "verify None": (lambda: certify.verify(None, f, J), "certificate must be a Certificate"),
        "deflate nan": (lambda: prr3.deflate([np.nan] * 9), "c must be finite"),
        "draw mech str": (lambda: prr3.draw(plt.subplots()[1], "a", ([1, 1, 1], [0, 0, 0])),
                          "mech must be a prr3.Geometry"),
        "voxels None": (lambda: prr3.mode_change_path(
            g, [2.2, 0.5, 3.0], [2.3, 0.5, 3.2], (1, 1, 1), bounds=[[1.5, 3.5], [0, 1]],
            shape=None),
            "shape must be numeric"),
        "parts None": (lambda: plotting.parts(plt.subplots()[1], None), "shapes must be a dict"),
        "below str": (lambda: published.below("a", 1e-13), "value must be numbers"),
        "registry None": (lambda: published.read_registry(None), "path must be a file name"),
        "row None": (lambda: published.check_row(None, 1.0), "row must be a registry row"),
        "row value str": (lambda: published.check_row(row, "a"), "value must be a real number"),
        "row value pair": (lambda: published.check_row(row, np.ones(2)),
                           "value must be a real number"),
        "table values None": (lambda: published.reproduction_table("01", None),
                              "values must be a dict"),
        "pinned modes None": (lambda: rods.pinned_equilibria(1.0, 1.0, [0.8, 0.1], None),
                              "modes must be an iterable"),
        "certified modes twice": (lambda: rods.certify_pinned(1.0, 1.0, [0.8, 0.1], (1, 1)),
                                  "distinct integers"),
        "elliptic_k shapes": (lambda: rods.elliptic_k([1.0, 2.0], [0.5, 0.5, 0.5]),
                              "do not broadcast"),
    }


@pytest.mark.parametrize("finding", sorted(_reproducers()))
def test_a_fixed_finding_gives_a_named_error(finding):
    run, words = _reproducers()[finding]
    with pytest.raises(ValueError, match=words):
        run()
    plt.close("all")


def test_hacksaw_residual_broadcasts_a_batch_of_motor_rates():
    from mechnum.mechanisms.hacksaw import STUDY, closed_form, motor, residual
    x, (theta2, _, alpha2) = closed_form(STUDY, 1.0), motor(1.0)
    omegas = np.array([-1.0, 0.0, 2.0])
    each = [residual(STUDY, x, theta2, w, alpha2) for w in omegas]
    np.testing.assert_array_equal(residual(STUDY, x, theta2, omegas, alpha2), each)


def main():
    tally = {o: 0 for o in OUTCOMES}
    uncovered, covered = [], 0
    only = [a for a in sys.argv[1:] if not a.startswith("-")]
    for name, obj in sorted(FUNCTIONS.items()):
        if only and not any(o in name for o in only):
            continue
        rows = fuzz(name, obj)
        if rows is None:
            uncovered.append(name)
            continue
        covered += 1
        for arg, family, outcome, detail in rows:
            tally[outcome] += 1
            if outcome in ("raw", "hang", "silent") or "-v" in sys.argv:
                print(f"{outcome:8} {name}({arg}={family}): {detail[:150]}")
    print(f"\n{covered} functions covered of {covered + len(uncovered)}, "
          f"{sum(tally.values())} calls")
    print(" | ".join(f"{o} {n}" for o, n in tally.items()))
    print("not covered (no docstring example call):", ", ".join(uncovered))


if __name__ == "__main__":
    main()
