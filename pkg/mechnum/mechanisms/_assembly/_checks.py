"""The bounds and checks of the inputs of the mechanisms built of rods.

Every argument that sets an amount of work has its bound here (checked at the mechanisms' entry
points, so that a slip such as ``nodes=1e7`` fails at once instead of running for hours), and
the checks every such mechanism makes of its input: the mechanism's type, the modes, the
resolutions of a stability test, that a chart is an equilibrium, the points of a path.
"""

from __future__ import annotations

import numpy as np

from mechnum import _validate

# Bounds on the arguments that set an amount of work (each checked at the mechanisms' entry
# points, so that a slip such as nodes=1e7 fails at once instead of running for hours):
MAX_NODES = 100_000
"""Most RK4 nodes (or polyline points) per rod."""
MAX_STARTS = 100_000
"""Most starts of one all-solutions search (before its check)."""
MAX_CHECK = 100
"""Most starts of a completeness check, in multiples of the search's."""
MAX_POINTS = 1_000_000
"""Most points of a path or of a map."""
MAX_SEGMENTS = 20_000
"""Most segments per rod of a second variation (banded: O(N) work)."""
MAX_DENSE_SEGMENTS = 1_000
"""Most segments per rod of a dense eigenproblem (O(N**2) memory)."""
MAX_RAY_STEPS = 10_000
"""Most steps of one ray of :func:`workspace_edge` (``reach / step``)."""
MAX_DIRECTIONS = 3_600
"""Most rays of :func:`workspace_edge`."""
MAX_LEVELS = 20
"""Most refinements of :func:`workspace_edge` (its step shrinks by ``4**levels``)."""
STATUS_DTYPE = "<U16"
"""The dtype of the statuses of paths and maps (the longest word of the vocabulary fits)."""
PATH_TOL = 1e-12
"""Newton's tolerance per step of closed-form continuation (a dimensionless residual)."""
PATH_MAXITER = 10
"""Newton's most iterations per step of continuation: from a good prediction a few reach
round-off; more means the branch is lost."""


def check_type(value, kind, name: str = "mech"):
    """``value`` if it is a ``kind``, else a :class:`ValueError` that names both.

    Examples
    --------
    >>> check_type(None, tuple, "mech")
    Traceback (most recent call last):
    ...
    ValueError: mech must be a tuple, got NoneType None
    """
    if not isinstance(value, kind):    # bad input: the package's ValueError (results.py)
        raise ValueError(  # noqa: TRY004
            f"{name} must be a {kind.__name__}, got {type(value).__name__} {value!r:.60}")
    return value


def check_modes(modes, rods: int) -> np.ndarray:
    """The buckling modes of ``rods`` rods, checked: integers ``>= 1``.

    Examples
    --------
    >>> check_modes((1, 2), 2).tolist()
    [1.0, 2.0]
    >>> check_modes((1, 0), 2)
    Traceback (most recent call last):
    ...
    ValueError: modes must be 2 integers >= 1, got [1.0, 0.0]
    """
    out = _validate.array(modes, "modes", shape=(_validate.maxiter(rods, "rods"),))
    if np.any(out < 1) or np.any(out != np.round(out)):
        raise ValueError(f"modes must be {rods} integers >= 1, got {out.tolist()}")
    return out


def check_segments(segments) -> tuple:
    """The resolutions of a stability test: a pair ``(coarse, fine)`` of segments per rod, each
    ``2 <= n <= MAX_SEGMENTS`` (a single index is no evidence that it is settled; the
    mechanisms' ``index`` gives the index at one resolution).

    Examples
    --------
    >>> check_segments((200, 400.0))
    (200, 400)
    >>> check_segments(200)
    Traceback (most recent call last):
    ...
    ValueError: segments must be a pair of integers (coarse, fine), got 200
    """
    try:
        given = tuple(segments)
    except TypeError:
        raise ValueError(f"segments must be a pair of integers (coarse, fine), got "
                         f"{segments!r}") from None
    if len(given) != 2:
        raise ValueError(f"segments must be a pair of integers (coarse, fine), got {given!r}")
    return tuple(_validate.maxiter(n, "segments", minimum=2, maximum=MAX_SEGMENTS)
                 for n in given)


def check_equilibrium(residual, tol: float):
    """Raise :class:`ValueError` if a dimensionless ``residual`` exceeds ``tol``: a stability
    test of a point that is no equilibrium would describe nothing.

    Examples
    --------
    >>> check_equilibrium([0.3, 1e-9], 1e-2)
    Traceback (most recent call last):
    ...
    ValueError: the chart is no equilibrium: its dimensionless residual is 0.3 (above 0.01)
    """
    worst = float(np.max(np.abs(residual)))
    if not worst <= tol:
        raise ValueError(f"the chart is no equilibrium: its dimensionless residual is "
                         f"{worst:.3g} (above {tol:g})")


def points(value, name: str, width: int, *, batch: bool = False) -> np.ndarray:
    """A path's parameters ``(steps, width)`` (or ``(steps, batch, width)``), checked; an empty
    path is valid, a path of more than :data:`MAX_POINTS` points is not.

    Examples
    --------
    >>> points([], "thetas", 2).shape
    (0, 2)
    """
    width = _validate.maxiter(width, "width")
    out = _validate.array(np.reshape(value, (0, width)) if np.size(value) == 0 else value,
                          name, ndim=(2, 3) if batch else 2)
    if out.shape[-1] != width:
        raise ValueError(f"{name} must have a last axis of {width}, got shape {out.shape}")
    if out.size // width > MAX_POINTS:
        raise ValueError(f"{name} has {out.size // width} points, more than {MAX_POINTS} "
                         "(a bound on the work)")
    return out


def grid_axes(x, y, names=("x", "y"), *, monotonic: bool = False):
    """The axes ``x`` (nx,) and ``y`` (ny,) of a map, checked: an empty axis is valid, a grid of
    more than :data:`MAX_POINTS` points is not; with ``monotonic``, each axis must be strictly
    increasing or decreasing (the neighbours of an atlas are distinct points).

    Examples
    --------
    >>> [a.shape for a in grid_axes([], [0.0, 1.0])]
    [(0,), (2,)]
    >>> grid_axes([0.0, 1.0], [1.0, 1.0], monotonic=True)
    Traceback (most recent call last):
    ...
    ValueError: y must be strictly increasing or decreasing, got [1. 1.]
    """
    x, y = (_validate.array(np.reshape(v, (0,)) if np.size(v) == 0 else v, name, ndim=1)
            for v, name in zip((x, y), names))
    if len(x) * len(y) > MAX_POINTS:
        raise ValueError(f"a grid of {len(x)} x {len(y)} points is more than {MAX_POINTS} "
                         "(a bound on the work)")
    for v, name in zip((x, y), names):
        steps = np.diff(v)
        if monotonic and not (np.all(steps > 0) or np.all(steps < 0)):
            raise ValueError(f"{name} must be strictly increasing or decreasing, "
                             f"got {_validate.shown(v)}")
    return x, y


def plane_grid(a, b, origin, directions, width: int, bound: tuple = (np.inf, "", "")) -> tuple:
    """The grid of an atlas, ``inputs[i, j] = origin + a[i] directions[0] + b[j]
    directions[1]``, checked: ``(inputs (nx, ny, width), (a, b), origin, directions)``.

    ``origin`` (width,) defaults to zero, ``directions`` (2, width) to the first two axes of
    the inputs; the two directions must be finite and independent. Each axis must be strictly
    increasing or decreasing (:func:`grid_axes`). ``bound = (limit, words, reason)``: every
    input of the grid must lie within ``limit`` (``words`` in the message) of zero.

    Examples
    --------
    >>> inputs, axes, origin, directions = plane_grid([0.0, 0.1], [0.0, 0.2, 0.4], [1.0, 2.0, 3.0],
    ...                                               [[1.0, 0.0, 0.0], [0.0, 1.0, 1.0]], 3)
    >>> inputs.shape, inputs[1, 2].tolist()
    ((2, 3, 3), [1.1, 2.4, 3.4])
    """
    width = _validate.maxiter(width, "width", minimum=2)
    a, b = grid_axes(a, b, ("a", "b"), monotonic=True)
    origin = np.zeros(width) if origin is None else _validate.array(origin, "origin",
                                                                    shape=(width,))
    directions = (np.eye(width)[:2] if directions is None
                  else _validate.array(directions, "directions", shape=(2, width)))
    if np.linalg.matrix_rank(directions) < 2:
        raise ValueError(f"directions must be two independent directions, got "
                         f"{_validate.shown(directions)}")
    with np.errstate(over="ignore", invalid="ignore"):
        inputs = origin + a[:, None, None] * directions[0] + b[None, :, None] * directions[1]
        largest = np.abs(inputs).max() if inputs.size else 0.0
    limit, words, reason = bound
    if not largest <= limit:
        raise ValueError(f"the grid's inputs must lie within {words} of zero ({reason}), got "
                         f"up to {largest:.3g}")
    return inputs, (a, b), origin, directions
