"""A folder of submissions read as hostile input: regular files only, each within a size bound.

Nothing a student hands in is followed or opened as it claims to be: a symbolic link (to the
instructors' package, to another student's notebook, to ``/dev/zero``), a FIFO, a device or a
socket is refused with its reason and never read; a regular file is opened without following a
link and read up to a bound; a student's folder is copied within a bound on its files, its
bytes and its depth.
"""

import os
import stat
from pathlib import Path

MAX_FILE = 64 * 2 ** 20
"""The largest file (bytes) read from a submission (a notebook or a file beside it)."""
MAX_FOLDER = 256 * 2 ** 20
"""The most bytes copied from one student's folder."""
MAX_ENTRIES = 2000
"""The most files and folders copied from one student's folder."""
MAX_DEPTH = 16
"""The deepest folder copied from one student's folder."""


def kind(mode):
    """What a file of mode ``mode`` is, in words."""
    return ("a symbolic link" if stat.S_ISLNK(mode) else "a folder" if stat.S_ISDIR(mode) else
            "a FIFO" if stat.S_ISFIFO(mode) else "a socket" if stat.S_ISSOCK(mode) else
            "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else "a regular file")


def read(path, cap=MAX_FILE):
    """The bytes of the regular file ``path`` (no link followed, at most ``cap`` bytes), or
    the reason it is refused (a string).

    Examples
    --------
    >>> read("/dev/zero")
    'zero is a device, not a regular file'
    """
    path = Path(path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as error:
        mode = path.lstat().st_mode if os.path.lexists(path) else 0
        return (f"{path.name} is {kind(mode)}, not a regular file" if mode and
                not stat.S_ISREG(mode) else f"{path.name} cannot be read ({error.strerror})")
    with os.fdopen(fd, "rb") as file:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            return f"{path.name} is {kind(mode)}, not a regular file"
        data = file.read(cap + 1)
    if len(data) > cap:
        return f"{path.name} is larger than {cap // 2 ** 20} MB"
    return data


def entry_problem(entry):
    """Why the entry ``entry`` of the submissions folder is no student's work (or "")."""
    mode = entry.lstat().st_mode
    if stat.S_ISDIR(mode) or (stat.S_ISREG(mode) and entry.suffix == ".ipynb"):
        return ""
    return f"{entry.name} is {kind(mode)}, not a notebook or a folder of notebooks"


def walk(folder):
    """``(files, refused)``: the regular files under ``folder`` (paths relative to it, no link
    followed, within :data:`MAX_ENTRIES` and :data:`MAX_DEPTH`) and the reasons the rest was
    refused."""
    files, refused, todo, count = [], [], [(Path(folder), 0)], 0
    while todo:
        here, depth = todo.pop()
        for item in sorted(os.scandir(here), key=lambda item: item.name):
            relative = Path(item.path).relative_to(folder)
            count += 1
            if count > MAX_ENTRIES:
                return files, [*refused, f"more than {MAX_ENTRIES} files: the rest was "
                                         "not copied"]
            mode = item.stat(follow_symlinks=False).st_mode
            if stat.S_ISDIR(mode) and depth < MAX_DEPTH:
                todo.append((Path(item.path), depth + 1))
            elif stat.S_ISREG(mode):
                files.append(relative)
            else:
                refused.append(f"{relative} is {kind(mode)}" + (
                    f" deeper than {MAX_DEPTH} folders" if stat.S_ISDIR(mode) else "") +
                    ": refused")
    return files, refused


def copy(entry, target):
    """Copy the student's entry (a notebook or a folder) into ``target``, regular files
    only, within the bounds; the reasons anything was refused."""
    if entry.is_file() and not entry.is_symlink():
        data = read(entry)
        if isinstance(data, str):
            return [data]
        target.write_bytes(data)
        return []
    files, refused = walk(entry)
    target.mkdir()
    left = MAX_FOLDER
    for relative in files:
        data = read(entry / relative, min(MAX_FILE, left))
        if isinstance(data, str):
            refused.append(f"{relative}: {data}")
            continue
        left -= len(data)
        (target / relative).parent.mkdir(parents=True, exist_ok=True)
        (target / relative).write_bytes(data)
    return refused
