"""Independent tasks in parallel: on this machine's cores (joblib), or on a cluster (dask).

:func:`run` is what every ``executor`` argument of the package means (the mechanism protocol's
``atlas(..., executor=None)``): ``None`` runs the tasks on all local cores through joblib's
process pool, a positive integer on that many local workers (1: one after another, in this
process), and a ``dask.distributed.Client`` on its cluster's workers (``pip install
mechnum[dask]``). The tasks and their function travel to the workers by pickling: the function
must be importable (a module's function, or a ``functools.partial`` of one), and a task
holds arrays and numbers only. The results come back in the order of the tasks, whatever ran
them, so that a result does not depend on the executor.
"""

from __future__ import annotations

import numbers
import os
import warnings


def local_cores() -> int:
    """The cores this process may run on: the most local workers :func:`run` starts (more
    processes than cores would only share them).

    Examples
    --------
    >>> local_cores() >= 1
    True
    """
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # no affinity outside Linux
        return os.cpu_count() or 1


def workers(executor) -> int:
    """How many tasks ``executor`` runs at once: the local cores for None, the integer itself,
    a dask cluster's threads (at least 1).

    Examples
    --------
    >>> workers(1), workers(None) == local_cores()
    (1, True)
    """
    executor = checked(executor)
    if executor is None:
        return local_cores()
    if isinstance(executor, int):
        return executor
    return max(1, sum(executor.nthreads().values()))


def checked(executor):
    """``executor`` if it is one that :func:`run` takes, else a ValueError that names it. A
    number of workers larger than :func:`local_cores` is cut to it, with a warning.

    Examples
    --------
    >>> checked(0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: executor must be None (all local cores), a number of workers ..., got 0
    """
    usage = ("executor must be None (all local cores), a number of workers >= 1, or a "
             f"dask.distributed.Client, got {executor!r:.80}")
    if executor is None:
        return None
    if isinstance(executor, numbers.Integral) and not isinstance(executor, bool):
        if executor < 1:
            raise ValueError(usage)
        if executor > (cores := local_cores()):
            warnings.warn(f"executor={executor} asks for more workers than the {cores} cores "
                          f"this process may use: running {cores}", stacklevel=3)
            return cores
        return int(executor)
    if all(callable(getattr(executor, name, None)) for name in ("map", "gather", "nthreads")):
        return executor
    raise ValueError(usage)


def run(function, tasks, executor=None) -> list:
    """``[function(task) for task in tasks]``, the tasks run in parallel by ``executor``.

    Parameters
    ----------
    function : callable
        Importable (pickled to the workers); ``function(task)`` returns a picklable value.
    tasks : list
        The tasks; an empty list gives an empty list, one task runs in this process.
    executor : None, int or dask.distributed.Client, optional
        None: joblib's processes on all local cores; ``n``: ``n`` local workers (1: here, one
        task after another); a dask Client: its cluster.

    Returns
    -------
    list
        The results, in the order of ``tasks``.

    Raises
    ------
    ValueError
        If ``executor`` is none of these.

    Examples
    --------
    >>> run(abs, [-1, 2, -3], executor=1)
    [1, 2, 3]
    """
    executor, tasks = checked(executor), list(tasks)
    if executor is not None and not isinstance(executor, int):    # a dask Client
        return executor.gather(executor.map(function, tasks, pure=False))
    if len(tasks) <= 1 or executor == 1:
        return [function(task) for task in tasks]
    from joblib import Parallel, delayed

    return Parallel(n_jobs=-1 if executor is None else executor)(
        delayed(function)(task) for task in tasks)


def chunks(items: list, executor) -> list:
    """``items`` cut into consecutive chunks, a few per worker of ``executor`` (so that a slow
    chunk does not keep the others waiting), at least one item each.

    Examples
    --------
    >>> chunks(list(range(5)), 2)
    [[0], [1], [2], [3], [4]]
    >>> [len(c) for c in chunks(list(range(100)), 2)]
    [13, 13, 13, 13, 12, 12, 12, 12]
    """
    parts = min(len(items), 4 * workers(executor))
    if not parts:
        return []
    size, extra = divmod(len(items), parts)
    bounds = [0]
    for k in range(parts):
        bounds.append(bounds[-1] + size + (k < extra))
    return [items[a:b] for a, b in zip(bounds[:-1], bounds[1:])]
