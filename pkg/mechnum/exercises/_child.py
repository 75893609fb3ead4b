"""Run a student's function in a child process: a hard time limit, and no way back into the check.

:func:`call` forks the process (a notebook's kernel, with everything the student defined), runs
the function on one case in the child and sends back what happened as an :class:`Outcome`: the
value (pickled, read by :func:`mechnum.exercises._answers.loads`), or the exception's name and
message, ``SystemExit`` and ``KeyboardInterrupt`` included. The child is killed when its time is
up, also inside a long C call; whatever the function changes (a module of the check, a global of
the notebook) changes only in the child, which then ends. Where ``fork`` does not exist
(Windows) the function runs in the calling process, stopped by a timer where one is available.
"""

import os
import pickle
import select
import signal
import sys
import threading
import time
import warnings
from dataclasses import dataclass

MAX_ANSWER_BYTES = 64 * 2 ** 20
"""The largest pickled answer read back (an exercise's answer is a few numbers)."""


@dataclass(frozen=True)
class Outcome:
    """What a student's function did on one case: ``kind`` is ``"value"`` (``value`` holds the
    pickled answer), ``"raised"`` (``error`` and ``message``), ``"timeout"`` or ``"died"``
    (``message`` says how); ``changed`` names the arguments it modified in place."""

    kind: str
    value: bytes = b""
    error: str = ""
    message: str = ""
    changed: tuple = ()


class Forbidden(BaseException):
    """Raised by a function that an exercise rules out, when the student's function calls it
    (a BaseException: a student's ``except Exception`` does not swallow it)."""


def forbid(names):
    """Make the functions ``names`` (dotted, ``"numpy.linalg.lstsq"``) unavailable wherever a
    loaded module holds them (``from numpy.linalg import lstsq`` too): each raises
    :class:`Forbidden`. Returns a callable that restores them."""
    import importlib

    undo = []
    for dotted in names:
        module, _, attribute = dotted.rpartition(".")
        try:
            original = getattr(importlib.import_module(module), attribute)
        except (ImportError, AttributeError):
            continue

        def refused(*args, dotted=dotted, **kwargs):
            raise Forbidden(dotted)
        for loaded in list(sys.modules.values()):
            space = getattr(loaded, "__dict__", None)
            if not isinstance(space, dict):
                continue
            for key, value in list(space.items()):
                if value is original:
                    undo.append((space, key, original))
                    space[key] = refused

    def restore():
        for space, key, original in reversed(undo):
            space[key] = original
    return restore


def report(function, args, names, changed_test, forbidden=()):
    """Run the function, with the functions ``forbidden`` made unavailable; the packed
    :class:`Outcome` (in the process that runs it)."""
    import copy

    before = copy.deepcopy(args)
    namespace = getattr(function, "__globals__", None)
    restore_own = (_forbid_in(namespace, forbidden) if isinstance(namespace, dict)
                   else lambda: None)  # first: forbid() replaces the originals it looks for
    restore = forbid(forbidden)
    try:
        value = function(*args)
    except Forbidden as error:
        return pack(Outcome("forbidden", message=str(error)))
    except BaseException as error:  # noqa: B036 -- SystemExit and KeyboardInterrupt included
        try:
            name, text = type(error).__name__, str(error)[:2000]
        except BaseException:  # noqa: B036 -- a hostile __str__
            name, text = "Exception", "(its message could not be read)"
        return pack(Outcome("raised", error=name, message=text))
    finally:
        restore_own()
        restore()
    changed = tuple(n for n, b, a in zip(names, before, args) if changed_test(b, a))
    try:
        data = pickle.dumps(value, protocol=4)
    except BaseException as error:  # noqa: B036
        return pack(Outcome("died", message=f"the answer, a {type(value).__name__}, "
                                    f"cannot be sent back ({type(error).__name__}): return "
                                    "numbers, arrays or tuples of them"))
    return pack(Outcome("value", value=data, changed=changed))


def _forbid_in(namespace, names):
    """The same for the names of one namespace that is not a module's (a notebook's)."""
    import importlib

    undo = []
    for dotted in names:
        module, _, attribute = dotted.rpartition(".")
        try:
            original = getattr(importlib.import_module(module), attribute)
        except (ImportError, AttributeError):
            continue
        for key, value in list(namespace.items()):
            if value is original:
                undo.append((key, value))
                namespace[key] = lambda *args, dotted=dotted, **kwargs: _refuse(dotted)

    def restore():
        for key, value in undo:
            namespace[key] = value
    return restore


def _refuse(dotted):
    raise Forbidden(dotted)


def pack(outcome):
    return pickle.dumps((outcome.kind, outcome.value, outcome.error, outcome.message,
                         tuple(outcome.changed)), protocol=4)


def unpack(data):
    """The :class:`Outcome` a child sent, read without rebuilding any object of the child's
    choosing; an unreadable report is an Outcome ``"died"``."""
    from mechnum.exercises._answers import loads

    try:
        kind, value, error, message, changed = loads(data)
        if not (kind in ("value", "raised", "died", "forbidden") and type(value) is bytes and
                type(error) is str and type(message) is str and type(changed) is tuple and
                all(type(name) is str for name in changed)):
            raise ValueError
    except Exception:
        return Outcome("died", message="the process running your function sent no answer "
                       "that can be read")
    return Outcome(kind, value, error, message, changed)


def _in_child(function, args, names, changed_test, write, forbidden=()):
    try:
        import faulthandler

        faulthandler.disable()  # a crash of the function is reported by the parent, once
        os.setpgid(0, 0)
        sys.stdout = open(1, "w", buffering=1, closefd=False)  # noqa: SIM115
        sys.stderr = open(2, "w", buffering=1, closefd=False)  # noqa: SIM115
        data = report(function, args, names, changed_test, forbidden)
        sys.stdout.flush()
        view = memoryview(data)
        while view:
            view = view[os.write(write, view):]
    finally:
        os._exit(0)


def _read(read, pid, seconds):
    """The child's report, or ``None`` when its time is up (the child and its group killed)."""
    chunks, size, deadline = [], 0, time.monotonic() + seconds
    while True:
        left = deadline - time.monotonic()
        if left <= 0 or not select.select([read], [], [], left)[0]:
            return None
        chunk = os.read(read, 1 << 20)
        if not chunk:
            return b"".join(chunks)
        size += len(chunk)
        if size > MAX_ANSWER_BYTES:
            return b""
        chunks.append(chunk)


def _kill(pid):
    for target in (lambda: os.killpg(pid, signal.SIGKILL), lambda: os.kill(pid, signal.SIGKILL)):
        try:
            target()
        except (ProcessLookupError, PermissionError):
            pass


def call(function, args, seconds, names=(), changed_test=lambda before, after: False,
         forbidden=()):
    """``function(*args)`` in a forked child, within ``seconds``, the functions ``forbidden``
    unavailable to it: an :class:`Outcome`."""
    if not hasattr(os, "fork"):
        return _call_here(function, args, seconds, names, changed_test, forbidden)
    read, write = os.pipe()
    with warnings.catch_warnings():  # Python 3.12 warns about forking a threaded process
        warnings.filterwarnings("ignore", message=r".*multi-threaded, use of fork\(\)")
        pid = os.fork()
    if pid == 0:
        os.close(read)
        _in_child(function, args, names, changed_test, write, forbidden)
    os.close(write)
    try:
        data = _read(read, pid, seconds)
    finally:
        os.close(read)
        if data is None or not data:
            _kill(pid)
        _, status = os.waitpid(pid, 0)
    if data is None:
        return Outcome("timeout")
    return unpack(data) if data else Outcome("died", message=_death(status))


def _death(status):
    if os.WIFSIGNALED(status):
        name = signal.Signals(os.WTERMSIG(status)).name
        return f"the process running your function was killed by {name}"
    return ("the process running your function ended without an answer (os._exit, or an "
            "answer larger than 64 MB)")


class _TimeUp(BaseException):
    pass


def _call_here(function, args, seconds, names, changed_test, forbidden=()):
    """The fallback without ``fork``: in this process, a timer where there is one."""
    if threading.current_thread() is threading.main_thread() and hasattr(signal, "setitimer"):
        def stop(signum, frame):
            raise _TimeUp
        previous = signal.signal(signal.SIGALRM, stop)
        signal.setitimer(signal.ITIMER_REAL, seconds)
        try:
            outcome = unpack(report(function, args, names, changed_test, forbidden))
        except _TimeUp:
            outcome = Outcome("timeout")
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
        return Outcome("timeout") if outcome.error == "_TimeUp" else outcome
    return unpack(report(function, args, names, changed_test, forbidden))
