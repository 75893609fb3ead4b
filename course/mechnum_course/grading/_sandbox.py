"""The limits a student's code runs under, and the end of every process it started.

A sandboxed process (a notebook's kernel, or the runner of a student's function) is started in
its own session (``setsid``) by this module's command line, which limits it and then replaces
itself with the real command (``exec``), so that the limits hold for everything it starts:

* resource limits (``setrlimit``): CPU seconds, address space, the size of a file it writes,
  no core file, and (for an ordinary user) a bound on its processes;
* ``no_new_privs`` and, where the Linux kernel has it (Landlock, Linux 5.13 and later), a
  file-system sandbox: it reads only the system, the Python environment and the student's
  package, and writes only in its own temporary folder; it cannot read the instructors'
  package or the other submissions. From Landlock's ABI 4 the runner of a function opens and
  accepts no TCP connection (a kernel needs TCP on the loopback for its own threads); from ABI 6
  neither sends a signal to a process outside its sandbox.

The grader is a *child subreaper* (``prctl``): a process that leaves its session or its parent
(a double fork, ``setsid``) still belongs to the grader, and :func:`kill_descendants` ends them
all, the kernel included, after each notebook.

Command line: ``python -m mechnum_course.grading._sandbox CONFIG.json -- COMMAND ...``.
"""

import ctypes
import json
import os
import resource
import signal
import sys
import time
from pathlib import Path

_LIBC = ctypes.CDLL(None, use_errno=True)
_CREATE_RULESET, _ADD_RULE, _RESTRICT_SELF = 444, 445, 446  # x86-64 and aarch64 alike
_PR_SET_NO_NEW_PRIVS, _PR_SET_CHILD_SUBREAPER = 38, 36
_READ = 1 << 0 | 1 << 2 | 1 << 3  # execute, read a file, read a directory
_FILE_ONLY = 1 << 0 | 1 << 1 | 1 << 2 | 1 << 14 | 1 << 15


class _Ruleset(ctypes.Structure):
    _fields_ = [("fs", ctypes.c_uint64), ("net", ctypes.c_uint64), ("scoped", ctypes.c_uint64)]


class _PathBeneath(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


def landlock_abi():
    """The Landlock ABI version this Linux kernel offers (0: none)."""
    if not sys.platform.startswith("linux"):
        return 0
    version = _LIBC.syscall(_CREATE_RULESET, None, ctypes.c_size_t(0), ctypes.c_uint32(1))
    return max(int(version), 0)


def _write_rights(abi):
    rights = sum(1 << k for k in range(1, 13) if k not in (2, 3))  # write, remove, make
    rights |= (1 << 13 if abi >= 2 else 0) | (1 << 14 if abi >= 3 else 0)
    return rights | (1 << 15 if abi >= 5 else 0)


def landlock(read, write, tcp=False):
    """Restrict this process (and what it starts) to reading ``read`` and ``read`` + ``write``
    paths and writing ``write`` paths; no TCP unless ``tcp`` (ABI >= 4), no signal or abstract
    socket out of the sandbox (ABI >= 6). The ABI used (0: Landlock is missing, nothing is
    restricted)."""
    abi = landlock_abi()
    if not abi:
        return 0
    handled = _READ | _write_rights(abi)
    attr = _Ruleset(handled, 3 if abi >= 4 and not tcp else 0, 3 if abi >= 6 else 0)
    size = 24 if abi >= 6 else 16 if abi >= 4 else 8
    ruleset = _LIBC.syscall(_CREATE_RULESET, ctypes.byref(attr), ctypes.c_size_t(size),
                            ctypes.c_uint32(0))
    if ruleset < 0:
        raise OSError(ctypes.get_errno(), "landlock_create_ruleset failed")
    try:
        for paths, rights in ((read, _READ), (write, _READ | _write_rights(abi))):
            for path in paths:
                if not os.path.exists(path):
                    continue
                fd = os.open(path, os.O_PATH | os.O_CLOEXEC)
                try:
                    allowed = rights if os.path.isdir(path) else rights & _FILE_ONLY
                    rule = _PathBeneath(allowed & handled, fd)
                    if _LIBC.syscall(_ADD_RULE, ruleset, 1, ctypes.byref(rule),
                                     ctypes.c_uint32(0)) < 0:
                        raise OSError(ctypes.get_errno(), f"landlock_add_rule {path}")
                finally:
                    os.close(fd)
        if _LIBC.prctl(_PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) or _LIBC.syscall(
                _RESTRICT_SELF, ruleset, ctypes.c_uint32(0)) < 0:
            raise OSError(ctypes.get_errno(), "landlock_restrict_self failed")
    finally:
        os.close(ruleset)
    return abi


def system_paths():
    """What any Python process reads: the system's folders and the Python environment."""
    import sysconfig

    paths = {"/usr", "/lib", "/lib64", "/bin", "/etc", "/proc", "/sys", "/dev", "/opt",
             sys.prefix, sys.base_prefix, sysconfig.get_paths()["purelib"]}
    return sorted(paths)


def exposed(paths):
    """The instructors' files a confined process could read through ``paths`` (when this
    package is installed under the system's or the environment's folders, not in ``course/``
    beside the book, as ``environment.txt`` installs it)."""
    here = Path(__file__).resolve().parents[1]
    return [p for p in paths if here.is_relative_to(Path(p).resolve())]


def set_limits(cpu, memory, file_size):
    """The resource limits of this process (seconds, bytes, bytes)."""
    for kind, value in ((resource.RLIMIT_CPU, cpu), (resource.RLIMIT_AS, memory),
                        (resource.RLIMIT_FSIZE, file_size), (resource.RLIMIT_CORE, 0)):
        value = int(value)
        resource.setrlimit(kind, (value, value))
    if os.getuid() != 0:  # a bound on processes counts all of this user's (root is exempt)
        mine = sum(1 for p in Path("/proc").iterdir() if p.name.isdigit() and
                   _owner(p) == os.getuid())
        resource.setrlimit(resource.RLIMIT_NPROC, (mine + 256, mine + 256))


def _owner(path):
    try:
        return path.stat().st_uid
    except OSError:
        return -1


def confine(config):
    """Limit this process as ``config`` says (see :func:`config`); the Landlock ABI used."""
    set_limits(config["cpu"], config["memory"], config["file_size"])
    return landlock(config["read"], config["write"], config.get("tcp", False))


def config(folder, *, cpu, memory, file_size, read=(), tcp=False):
    """The confinement of a process working in ``folder``: its limits, what it may read (the
    system, the Python environment, the student's package ``mechnum``) and write, and whether
    it may use TCP (a Jupyter kernel's threads talk through TCP on the loopback)."""
    import mechnum

    package = str(Path(mechnum.__file__).resolve().parents[1])
    return {"cpu": cpu, "memory": memory, "file_size": file_size, "tcp": tcp,
            "read": [*system_paths(), package, *read],
            "write": [str(folder), os.devnull, "/dev/shm"]}  # joblib's semaphores


def become_subreaper():
    """Make this process the reaper of every orphaned descendant (Linux; else nothing)."""
    if sys.platform.startswith("linux"):
        _LIBC.prctl(_PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)


def descendants(root=None):
    """The ids of every descendant of ``root`` (this process), from ``/proc``."""
    root, children = root or os.getpid(), {}
    if not Path("/proc").is_dir():  # not Linux: nothing to sweep
        return []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                stat = (entry / "stat").read_text()
            except OSError:
                continue
            parent = int(stat.rsplit(")", 1)[1].split()[1])
            children.setdefault(parent, []).append(int(entry.name))
    found, todo = [], list(children.get(root, []))
    while todo:
        pid = todo.pop()
        found.append(pid)
        todo.extend(children.get(pid, []))
    return found


def kill_descendants(keep=(), rounds=50):
    """SIGKILL every descendant of this process but ``keep``, until none is left (processes
    that fork while they are killed are caught by the next round); reap them. The number
    killed."""
    killed = set()
    for _ in range(rounds):
        alive = [pid for pid in descendants() if pid not in keep]
        if not alive:
            break
        for pid in alive:
            try:
                os.kill(pid, signal.SIGKILL)
                killed.add(pid)
            except (ProcessLookupError, PermissionError):
                pass
        time.sleep(0.02)
        reap(keep)
    return len(killed)


def reap(keep=()):
    """Collect the exit status of every ended child but ``keep``."""
    for pid in descendants():
        if pid in keep:
            continue
        try:
            os.waitpid(pid, os.WNOHANG)
        except ChildProcessError:
            pass


def main(argv):
    """Confine this process as the configuration file says, then become the command."""
    split = argv.index("--")
    settings = json.loads(Path(argv[0]).read_text(encoding="utf-8"))
    os.environ["MECHNUM_SANDBOX"] = str(confine(settings))
    os.execv(argv[split + 1], argv[split + 1:])


if __name__ == "__main__":
    main(sys.argv[1:])
