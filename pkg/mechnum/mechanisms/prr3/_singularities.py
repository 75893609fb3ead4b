"""Where the 3PRR is singular along a segment of poses: :func:`singular_points`.

A working mode (one branch of each leg, :func:`~mechnum.mechanisms.prr3.branch_inputs`)
maps poses to inputs. Along a segment of poses it meets a *direct* singularity where the direct
Jacobian's determinant changes sign (the bars' lines concurrent or parallel: two assembly modes
meet), and an *inverse* one where a leg becomes tangent to its guide (a radicand changes sign:
the edge of the workspace). Each is bracketed on a grid of the segment and located by Brent's
method, which converges on any bracket.
"""

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from mechnum import _validate
from mechnum.mechanisms.prr3 import _kernels as kernels
from mechnum.mechanisms.prr3._geometry import Geometry, check, radicands
from mechnum.mechanisms.prr3._inverse import STUDY_ORDER, branch_inputs

KINDS = ("direct", "inverse")
MAX_SAMPLES = 100_000
"""The most grid points of a segment (each costs one evaluation of the mode's inputs)."""
# Brent's method stops when the bracket is below this (in the segment's parameter, 0 to 1) or
# 4 eps relative: the pose is then located to round-off of a unit-sized segment.
_XTOL = 1e-15


def singular_points(mech: Geometry, segment: ArrayLike, *, signs: ArrayLike = STUDY_ORDER,
                    kind: str = "direct", samples: int = 200) -> np.ndarray:
    """The poses of a segment ``(start, end)`` where working mode ``signs`` is singular.

    The segment ``start + s (end - start)``, ``0 <= s <= 1``, is sampled at ``samples`` points;
    each sign change of the singularity's measure between two neighbours (both finite) is
    located by Brent's method. The measure is, for ``kind="direct"``, the direct Jacobian's
    dimensionless determinant (:func:`jacobian_dets`) at the inputs of working mode ``signs``
    (where the mode assembles), and for ``kind="inverse"``, each leg's radicand
    (:func:`radicands`; ``signs`` does not matter). A zero that does not change sign (a
    tangency) and two zeros closer than the grid's spacing are not found: sample finer.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    segment : array_like, shape (2, 3)
        The segment's ends ``start`` and ``end``, poses ``(x, y, psi)``.
    signs : array_like of +-1, shape (3,), optional
        The working mode (:func:`branch_inputs`).
    kind : {"direct", "inverse"}, optional
    samples : int, optional
        Grid points on the segment, 2 to :data:`MAX_SAMPLES`.

    Returns
    -------
    ndarray, shape (k, 3)
        The singular poses, from ``start`` towards ``end``.

    Raises
    ------
    ValueError
        If an argument is ill-shaped, not finite, or out of its range.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import jacobian_dets
    >>> from mechnum.mechanisms.prr3.study import EXAMPLES
    >>> g = EXAMPLES["Table 5"][0]
    >>> pose = singular_points(g, [[3.0, 0.3, 0.5], [3.4, 0.3, 0.5]], signs=(1, -1, -1))
    >>> pose.round(6).tolist()
    [[3.212775, 0.3, 0.5]]
    >>> lam = branch_inputs(g, pose[0], (1, -1, -1))
    >>> bool(abs(jacobian_dets(g, pose[0], lam)[1]) < 1e-12)
    True
    """
    check(mech)
    start, end = _validate.array(segment, "segment", shape=(2, 3))
    kind = _validate.choice(kind, KINDS, "kind")
    samples = _validate.maxiter(samples, "samples", minimum=2, maximum=MAX_SAMPLES)
    if kind == "direct":
        branch_inputs(mech, start, signs)  # checks signs

    def measure(s):
        poses = start + np.multiply.outer(s, end - start)
        if kind == "inverse":
            return radicands(mech, poses)
        lam = branch_inputs(mech, poses, signs)
        with np.errstate(invalid="ignore"):
            return kernels.jacobian_dets(mech, poses, lam)[1][..., None]

    grid = np.linspace(0.0, 1.0, samples)
    values = measure(grid)
    found = []
    for i, k in zip(*np.nonzero(values[:-1] * values[1:] <= 0)):
        if values[i, k] == 0:
            found.append(grid[i])
        elif values[i + 1, k] != 0:  # an exact zero at i + 1 is found as the next left end
            found.append(brentq(lambda s, k=k: float(measure(s)[k]), grid[i], grid[i + 1],
                                xtol=_XTOL))
    return start + np.multiply.outer(np.unique(found), end - start).reshape(-1, 3)
