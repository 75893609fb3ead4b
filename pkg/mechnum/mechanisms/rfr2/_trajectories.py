"""The study's trajectories (Annex II 3.1 and 3.2), whose generators it does not list.

:func:`straight_path`, :func:`circles` and :func:`rectangles` give increments of the end
effector (or of the motor angles); :func:`~mechnum.mechanisms.rfr2.study.path` those of the
study's six trajectories (:data:`STUDY_PATHS`).
"""

import numpy as np

from mechnum import _validate
from mechnum.mechanisms._assembly import MAX_POINTS


def straight_path(length: float, angle: float, divisions: int) -> np.ndarray:
    """Increments along a straight line from the origin (the study's ``StraightPath``, whose
    code is not listed: ``divisions + 1`` equally spaced points, ``divisions`` at most
    :data:`~mechnum.mechanisms._assembly.MAX_POINTS`).

    Examples
    --------
    >>> straight_path(0.5, np.pi, 100).shape
    (101, 2)
    """
    s = np.linspace(0.0, _validate.scalar(length, "length"),
                    _validate.maxiter(divisions, "divisions", maximum=MAX_POINTS) + 1)
    angle = _validate.scalar(angle, "angle")
    return s[:, None] * [np.cos(angle), np.sin(angle)]


def circles(diameter: float, count: int, divisions: int) -> np.ndarray:
    """Increments on concentric circles (the study's ``Workspace_Circles``, not listed):
    the centre, then ``count`` circles of diameters ``diameter k / count``, each from angle 0
    in ``divisions`` points (``count divisions`` at most
    :data:`~mechnum.mechanisms._assembly.MAX_POINTS`).

    Examples
    --------
    >>> pts = circles(0.2, 5, 8)
    >>> pts.shape, round(float(2 * np.abs(pts).max()), 6)
    ((41, 2), 0.2)
    """
    count, divisions = _sizes(count, divisions)
    radius = 0.5 * _validate.scalar(diameter, "diameter") * np.arange(1, count + 1) / count
    angle = 2 * np.pi * np.arange(divisions) / divisions
    ring = radius[:, None, None] * np.stack((np.cos(angle), np.sin(angle)), -1)
    return np.concatenate((np.zeros((1, 2)), ring.reshape(-1, 2)))


def rectangles(base: float, height: float, count: int, divisions: int) -> np.ndarray:
    """Increments on concentric rectangles (the study's ``Workspace_Rectangles``, not listed):
    the centre, then ``count`` rectangles scaled by ``k / count``, each side in ``divisions``
    steps, anticlockwise from the middle of the right side (``4 count divisions`` at most
    :data:`~mechnum.mechanisms._assembly.MAX_POINTS`).

    Examples
    --------
    >>> rectangles(0.2, 0.2, 4, 4).shape
    (65, 2)
    """
    count, n = _sizes(count, 4 * _validate.maxiter(divisions, "divisions"))
    n //= 4
    b, h = _validate.scalar(base, "base") / 2, _validate.scalar(height, "height") / 2
    u = np.linspace(-1.0, 1.0, n + 1)[:-1]
    unit = np.concatenate((np.column_stack((np.ones(n), -u))[::-1][n // 2:],   # right, upwards
                           np.column_stack((-u, np.ones(n))),                   # top
                           np.column_stack((-np.ones(n), -u)),                  # left
                           np.column_stack((u, -np.ones(n))),                   # bottom
                           np.column_stack((np.ones(n), u))[:n // 2]))           # right, to start
    scales = np.arange(1, count + 1) / count
    ring = scales[:, None, None] * unit * [b, h]
    return np.concatenate((np.zeros((1, 2)), ring.reshape(-1, 2)))


def _sizes(count, points):
    """``count`` rings of ``points`` points each, checked against the bound on the work."""
    count = _validate.maxiter(count, "count")
    points = _validate.maxiter(points, "divisions")
    if count * points > MAX_POINTS:
        raise ValueError(f"{count} rings of {points} points are more than {MAX_POINTS} points "
                         "(a bound on the work)")
    return count, points


STUDY_PATHS = {
    "inverse line": (straight_path, (0.5, np.pi, 100)),
    "inverse circles": (circles, (0.2, 5, 8)),
    "inverse rectangles": (rectangles, (0.2, 0.2, 4, 4)),
    "direct line": (straight_path, (1.0, 0.0, 100)),
    "direct circles": (circles, (0.2, 5, 8)),
    "direct rectangles": (rectangles, (0.2, 0.2, 4, 4)),
}
"""The trajectories of Annex II 3.1 (inverse: increments of ``P``, m) and 3.2 (direct:
increments of ``theta``, rad): generator and the study's parameters."""


def path(kind: str) -> np.ndarray:
    """The increments of one of the study's trajectories
    (``STUDY_PATHS``: three straight lines, circles and rectangles).

    Examples
    --------
    >>> path("inverse circles").shape
    (41, 2)
    """
    generator, args = STUDY_PATHS[_validate.choice(kind, tuple(STUDY_PATHS), "kind")]
    return generator(*args)
