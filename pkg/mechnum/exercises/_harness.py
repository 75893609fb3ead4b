"""How a self-check runs a student's function: cases, a time limit per case, and the feedback.

An :class:`Exercise` holds its reference solution, the cases the check runs (never shown to the
student), a comparison of a student's answer with the reference's, and the typical mistakes, each
a mistaken implementation with a hint. When an answer disagrees on a case, the check runs every
mistaken implementation on that case too: the one the answer agrees with names the likely mistake.
"""

import ast
import copy
import inspect
import signal
import textwrap
import threading
from dataclasses import dataclass

import numpy as np

TIME_LIMIT = 2.0
"""Seconds a student's function may take on one case (the references take milliseconds): beyond
it the check stops the function and reports an endless loop instead of hanging."""


class TimeUp(BaseException):
    """Raised inside a student's function when its time is up (a BaseException, so that a
    student's ``except Exception`` cannot swallow it)."""


@dataclass(frozen=True)
class Case:
    """One input of a check: what it is, in words, and the arguments of the function."""

    label: str
    args: tuple


@dataclass(frozen=True)
class Mistake:
    """A typical wrong implementation, named, with the hint that a student who made it needs."""

    name: str
    hint: str
    function: object


@dataclass(frozen=True)
class Exercise:
    """An implement-it-yourself exercise and its self-check.

    ``compare(expected, got)`` returns ``None`` when ``got`` is right, else what is wrong, in
    words; it may raise on an answer of the wrong kind (the check reports that). ``probes()``
    gives extra cases that only serve to tell the mistakes apart (one Newton step, say, where a
    whole iteration diverges in a way that depends on rounding). ``forbidden`` names the
    library functions the statement rules out, ``"numpy.linalg.lstsq"``: the check runs the
    student's function with them made unavailable. ``expected(*args)``, when given, is the
    right answer of a case (the reference's otherwise): for an answer that a reference can
    only approximate, such as the tightest enclosure of an interval computation; then
    ``agree(mistaken, got)`` says whether an answer is a mistake's (``compare`` by default).
    """

    number: str
    label: str
    title: str
    statement: str
    reference: object
    cases: object
    compare: object
    mistakes: tuple = ()
    hint: str = ""
    time_limit: float = TIME_LIMIT
    probes: object = tuple
    forbidden: tuple = ()
    expected: object = None
    agree: object = None

    @property
    def name(self):
        """The name of the function the student writes (the reference's)."""
        return self.reference.__name__


@dataclass(frozen=True)
class Result:
    """The verdict of a check: ``passed`` and a ``message`` that says what failed, on which
    input, and the likely mistake. It displays as its message."""

    number: str
    passed: bool
    message: str

    def __repr__(self):
        return self.message

    __str__ = __repr__


def call_with_limit(function, args, seconds):
    """``function(*args)``, stopped with :class:`TimeUp` after ``seconds``.

    In the main thread (a notebook's cells run there) a timer signal interrupts the function;
    elsewhere it runs in a daemon thread that is abandoned when its time is up.
    """
    if threading.current_thread() is threading.main_thread() and hasattr(signal, "setitimer"):
        def stop(signum, frame):
            raise TimeUp
        previous = signal.signal(signal.SIGALRM, stop)
        signal.setitimer(signal.ITIMER_REAL, seconds)
        try:
            return function(*args)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
    box = {}

    def run():
        try:
            box["value"] = function(*args)
        except BaseException as error:  # handed over to the caller's thread
            box["error"] = error

    worker = threading.Thread(target=run, daemon=True)
    worker.start()
    worker.join(seconds)
    if worker.is_alive():
        raise TimeUp
    if "error" in box:
        raise box["error"]
    return box["value"]


class Forbidden(BaseException):
    """Raised by a library function that an exercise rules out, when the student's function
    calls it (a BaseException, so that a student's ``except Exception`` cannot swallow it)."""


def _forbid(names, function):
    """Make the library functions ``names`` (``"numpy.linalg.lstsq"``) unavailable: in their
    modules, and under any name in ``function``'s globals (``from numpy.linalg import lstsq``).
    Returns a callable that restores them."""
    import importlib

    undo = []
    for name in names:
        module_name, attribute = name.rsplit(".", 1)
        try:
            module = importlib.import_module(module_name)
            original = getattr(module, attribute)
        except (ImportError, AttributeError):
            continue

        def stub(*args, name=name, **kwargs):
            raise Forbidden(name)
        undo.append((module, attribute, original))
        setattr(module, attribute, stub)
        namespace = getattr(function, "__globals__", {})
        for key, value in list(namespace.items()):
            if value is original:
                undo.append((namespace, key, original))
                namespace[key] = stub

    def restore():
        for target, key, original in reversed(undo):
            if isinstance(target, dict):
                target[key] = original
            else:
                setattr(target, key, original)
    return restore


def _changed(before, after):
    """Whether an argument was modified in place (arrays compared element by element)."""
    if isinstance(before, np.ndarray):
        return before.shape != after.shape or not np.array_equal(before, after, equal_nan=True)
    if isinstance(before, (list, tuple)):
        return any(_changed(b, a) for b, a in zip(before, after))
    return False


def _compare(exercise, expected, got):
    try:
        return exercise.compare(expected, got)
    except Exception as error:  # an answer of the wrong kind (shape, type)
        return f"the answer has the wrong form ({type(error).__name__}: {error})"


def _agrees(exercise, function, args, got):
    """Whether ``function(*args)`` gives the answer ``got``."""
    try:
        value = call_with_limit(function, copy.deepcopy(args), 5.0)
        if exercise.agree is not None:
            return value is not None and exercise.agree(value, got)
        return value is not None and exercise.compare(value, got) is None
    except Exception:
        return False


def _diagnose(exercise, case, got, answer):
    """The hint of the first mistaken implementation that gives the student's answer, on the
    failing case or else on every probe."""
    for mistake in exercise.mistakes:
        if _agrees(exercise, mistake.function, case.args, got):
            return f"Likely mistake, {mistake.name}: {mistake.hint}"
    probes = []
    for probe in exercise.probes():
        try:
            probes.append((probe, call_with_limit(answer, copy.deepcopy(probe.args), 5.0)))
        except (Exception, TimeUp):
            return f"Hint: {exercise.hint}"
    for mistake in exercise.mistakes:
        if probes and all(_agrees(exercise, mistake.function, probe.args, value)
                          for probe, value in probes):
            return f"Likely mistake, {mistake.name}: {mistake.hint}"
    return f"Hint: {exercise.hint}" if exercise.hint else ""


def run_check(exercise, answer):
    """Run ``answer`` on every case of ``exercise``; the :class:`Result`. Never raises on a
    wrong answer: an exception in the student's code is caught and reported."""
    head = f"Exercise {exercise.number}"
    if not callable(answer):
        return Result(exercise.number, False,
                      f"{head}: not yet. Pass the function itself, "
                      f"exercises.check({exercise.number!r}, {exercise.name}), "
                      f"not {type(answer).__name__!r}.")
    cases = exercise.cases()
    for case in cases:
        try:
            expected = (exercise.expected or exercise.reference)(*copy.deepcopy(case.args))
            raises = None
        except Exception as error:  # the statement asks for this exception here
            expected, raises = None, type(error)
        args = copy.deepcopy(case.args)
        where = f"On {case.label}"
        restore = _forbid(exercise.forbidden, answer)
        try:
            got = call_with_limit(answer, args, exercise.time_limit)
        except Forbidden as error:
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}, your function called {error}, which "
                          "this exercise rules out: write the method yourself.")
        except TimeUp:
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}, your function ran for more "
                          f"than {exercise.time_limit:g} s and was stopped: an endless loop? "
                          "Every loop needs a test that ends it, and an iteration a bound on "
                          "its count.")
        except Exception as error:
            if raises is not None and isinstance(error, raises):
                continue  # the exception the statement asks for
            expect = f", where it must raise {raises.__name__}" if raises else ""
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}, your function raised "
                          f"{type(error).__name__}: {error}{expect}")
        finally:
            restore()
        if raises is not None:
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}, your function returned where it must "
                          f"raise {raises.__name__} (the statement says when).")
        if got is None:
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}, `{exercise.name}` returned "
                          "None: its body is still `...` (or lacks a `return`). Write it, then "
                          "run this cell again.")
        for name, before, after in zip(inspect.signature(exercise.reference).parameters,
                                       case.args, args):
            if _changed(before, after):
                return Result(exercise.number, False,
                              f"{head}: not yet. {where}, your function changed its "
                              f"argument `{name}` in place; work on a copy.")
        problem = form(expected, got, "your answer")
        if problem:
            return Result(exercise.number, False, f"{head}: not yet. {where}: {problem}.")
        problem = _compare(exercise, expected, got)
        if problem:
            diagnosis = _diagnose(exercise, case, got, answer)
            return Result(exercise.number, False,
                          f"{head}: not yet. {where}: {problem}. {diagnosis}".rstrip())
    return Result(exercise.number, True,
                  f"Exercise {exercise.number}: passed, all {len(cases)} cases "
                  f"({exercise.title}).")


def source(function):
    """The source of a reference function, as the solution cell shows it."""
    return textwrap.dedent(inspect.getsource(function))


def starter(function):
    """The starter cell of a reference function: its signature and docstring, and ``...``."""
    text = source(function)
    body = ast.parse(text).body[0].body
    docstring = body[0]
    lines = text.splitlines()[:docstring.end_lineno]
    return "\n".join(lines) + "\n" + " " * docstring.col_offset + "...\n"


def _kind(value):
    """The kind of an expected answer, in words."""
    if isinstance(value, tuple):
        return f"a tuple of {len(value)} values"
    if isinstance(value, np.ndarray):
        return f"an array of shape {value.shape}"
    if isinstance(value, str):
        return "a string"
    if isinstance(value, (bool, np.bool_)):
        return "True or False"
    if isinstance(value, (int, np.integer)):
        return "an integer"
    return "a real number"


def form(expected, got, what):
    """``None`` when ``got`` has the kind of ``expected`` (a tuple of as many values, an array
    of numbers of its shape, a string, an integer, a real number), else what is wrong with it,
    in words: an answer of the wrong type gets a message about its type, not about numbers.

    Examples
    --------
    >>> form((np.zeros(3), 4), [np.zeros(3), 4], "your answer")
    >>> form((np.zeros(3), 4), np.zeros(3), "your answer")
    'your answer is an array of shape (3,); it must be a tuple of 2 values'
    >>> form((np.zeros(3), 4), (np.zeros(3), 4.0), "your answer")
    'your answer[1] is a float (4.0); it must be an integer'
    """
    def shown(value):
        if isinstance(value, np.ndarray):
            return f"an array of shape {value.shape}"
        if isinstance(value, (list, tuple)):
            return f"a {type(value).__name__} of {len(value)} values"
        text = repr(value)
        return f"a {type(value).__name__}" + (f" ({text})" if len(text) < 40 else "")
    wrong = f"{what} is {shown(got)}; it must be {_kind(expected)}"
    if isinstance(expected, tuple):
        if not isinstance(got, (tuple, list)) or len(got) != len(expected):
            return wrong
        return next((problem for k, (e, g) in enumerate(zip(expected, got))
                     if (problem := form(e, g, f"{what}[{k}]"))), None)
    if isinstance(expected, str):
        return None if isinstance(got, str) else wrong
    if isinstance(expected, (bool, np.bool_)):
        return None if isinstance(got, (bool, np.bool_)) else wrong
    if isinstance(expected, (int, np.integer)):
        return None if isinstance(got, (int, np.integer)) and not isinstance(
            got, (bool, np.bool_)) else wrong
    if isinstance(got, (str, bytes, bool, np.bool_, dict, set)) or got is None:
        return wrong
    try:
        values = np.asarray(got, dtype=float)
    except (TypeError, ValueError):
        return wrong
    if isinstance(expected, np.ndarray):
        return None if values.shape == expected.shape else (
            f"{what} has shape {values.shape}; it must have shape {expected.shape}")
    return None if values.ndim == 0 else wrong


def differ(got, expected):
    """``got`` and ``expected`` with the digits that tell them apart, and their difference:
    ``"1.2458637, expected 1.2458612 (off by 2.5e-06)"``.

    Examples
    --------
    >>> differ(1.24586371, 1.24586123)
    '1.245864, expected 1.245861 (off by 2.5e-06)'
    >>> differ(2.0, 3.0)
    '2, expected 3 (off by 1)'
    """
    digits = 6
    while digits < 17 and f"{got:.{digits}g}" == f"{expected:.{digits}g}":
        digits += 1
    return (f"{got:.{digits}g}, expected {expected:.{digits}g} "
            f"(off by {abs(got - expected):.2g})")


def close(expected, got, *, rtol, atol, what):
    """``None`` when the arrays agree within ``atol + rtol |expected|``, else the largest
    difference in words, with the digits that tell the two values apart."""
    expected, got = np.asarray(expected), np.asarray(got)
    if got.shape != expected.shape:
        return f"{what} has shape {got.shape}, expected {expected.shape}"
    if not np.all(np.isfinite(got)):
        return f"{what} is not finite: {np.array2string(got, precision=4)}"
    error = np.abs(got - expected)
    if np.all(error <= atol + rtol * np.abs(expected)):
        return None
    worst = np.unravel_index(np.argmax(error - rtol * np.abs(expected)), error.shape)
    at = f" at index {tuple(int(i) for i in worst)}" if expected.ndim else ""
    return (f"{what}{at} is "
            + differ(float(np.real(got[worst])), float(np.real(expected[worst]))))
