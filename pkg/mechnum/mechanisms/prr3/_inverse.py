"""The 3PRR's inverse problem (pose -> inputs) and its workspace: one line-circle cut per leg."""

from itertools import product

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.prr3 import _kernels as kernels
from mechnum.mechanisms.prr3._geometry import Geometry, check, resolved, vectors

# A radicand within 1e-12 L^2 of zero is a tangent leg: the two values of its input then
# differ by 2 sqrt(1e-12) L = 2e-6 L, the study's own merging distance (1e-6 L) in size,
# and far above the round-off (~1e-16 L^2) of a radicand computed from unit-sized lengths.
TANGENT_TOL = 1e-12
STUDY_ORDER = (1, -1, -1)
"""The signs of the study's first solution (equations 53, 57, 61): ``+`` for ``lambda1``."""


def _tangent_roots(rad, tol, L):
    """``sqrt(rad)``, 0 where ``|rad| <= tol L^2`` (tangent), NaN where ``rad < -tol L^2``."""
    band = tol * L ** 2
    with np.errstate(invalid="ignore"):
        return np.where(np.abs(rad) <= band, 0.0, np.where(rad < -band, np.nan, np.sqrt(rad)))


def branch_inputs(mech: Geometry, poses: ArrayLike, signs: ArrayLike = STUDY_ORDER, *,
                  tol: float = TANGENT_TOL) -> np.ndarray:
    """The inputs of one working mode (one branch of each leg), vectorised over poses.

    ``lambda1 = x_P + s1 r1``, ``lambda2 = B2 - x_P2 + s2 r2``, ``lambda3 = H3 - y_P3 + s3 r3``
    with ``r_i`` the square roots of :func:`radicands` (zero for a tangent leg): equations 53,
    57 and 61 of the study, whose first solution is ``signs = (1, -1, -1)``. A working mode is
    a continuous function of the pose inside the workspace, as a path or a singularity map needs.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    poses : array_like, shape (..., 3)
    signs : array_like of +-1, shape (3,)
        The branch of each leg.
    tol : float, optional
        A radicand down to ``-tol * L**2`` counts as zero (:data:`TANGENT_TOL`).

    Returns
    -------
    ndarray, shape (..., 3)
        NaN for the legs that cannot reach their guide.

    Raises
    ------
    ValueError
        If ``poses`` is ill-shaped, not finite or beyond ``1e100`` m, ``signs`` are not three
        values +-1, or ``tol`` is not a positive number.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> branch_inputs(g, [[0.6, 0.4, 0.0], [0.6, 1.4, 0.0]]).round(4).tolist()
    [[1.5165, 0.4835, -0.1825], [nan, nan, -1.1825]]
    """
    signs = _validate.array(signs, "signs", shape=(3,))
    if not np.all(np.abs(signs) == 1):
        raise ValueError(f"signs must be three values +1 or -1, got {signs.tolist()}")
    tol = _validate.tolerance(tol)
    return _branch_inputs(check(mech), resolved(vectors(poses, "poses"), "poses"), signs, tol)


def _branch_inputs(mech, poses, signs, tol):
    """:func:`branch_inputs` on checked input, any finite pose (NaN where a leg cannot reach:
    all of them far away)."""
    root = _tangent_roots(kernels.radicands(mech, poses), tol, mech.L)
    v = kernels.vertices(mech, poses)
    centre = np.stack([v[..., 0, 0], mech.B2 - v[..., 1, 0], mech.H3 - v[..., 2, 1]], -1)
    return centre + signs * root


def inverse(mech: Geometry, pose: ArrayLike, *, tol: float = TANGENT_TOL) -> np.ndarray:
    """All the inputs ``(lambda1, lambda2, lambda3)`` that assemble the mechanism in ``pose``.

    Each leg gives two values of its input (line-circle intersection, equations 53, 57, 61 of the
    study), one when the leg is tangent to its guide (``|radicand| <= tol * L**2``: an inverse
    singularity, reported by :func:`radicands`), none when the pose is out of its reach. The
    solutions are all the combinations, in the order of the study's tables: ``lambda1`` with
    ``+`` first, ``lambda2`` and ``lambda3`` with ``-`` first.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    pose : array_like, shape (3,)
        ``(x, y, psi)`` in metres and radians.
    tol : float, optional
        Relative tolerance of tangency (:data:`TANGENT_TOL`).

    Returns
    -------
    ndarray, shape (n, 3)
        ``n = 8`` in general, 4, 2 or 1 with tangent legs, 0 for an unreachable pose.

    Raises
    ------
    ValueError
        If ``pose`` is not three finite numbers, or ``tol`` not a positive number.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> inverse(g, [0.6, 0.4, 0.0])[:2].round(5).tolist()
    [[1.51652, 0.48348, -0.18254], [1.51652, 0.48348, 1.65049]]
    >>> inverse(g, [0.6, 1.4, 0.0]).shape
    (0, 3)
    """
    pose = _validate.array(pose, "pose", shape=(3,))
    tol = _validate.tolerance(tol)
    mech = check(mech)
    first = _branch_inputs(mech, pose, np.array(STUDY_ORDER, dtype=float), tol)
    if np.any(np.isnan(first)):
        return np.empty((0, 3))
    second = _branch_inputs(mech, pose, np.negative(STUDY_ORDER, dtype=float), tol)
    values = [(f,) if f == s else (f, s) for f, s in zip(first, second)]  # equal: tangent
    return np.array(list(product(*values)))


def workspace(mech: Geometry, poses: ArrayLike, *, tol: float = TANGENT_TOL) -> np.ndarray:
    """Reachability of every pose of a grid: can the inverse problem be solved there?

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    poses : array_like, shape (..., 3)
        The poses ``(x, y, psi)``: coordinates (m) and orientation (rad) (stack the arrays of
        :func:`numpy.meshgrid` with ``indexing="ij"`` on a last axis for a full grid). Empty
        arrays are valid.
    tol : float, optional
        A radicand down to ``-tol * L**2`` counts as zero (a tangent leg is reachable).

    Returns
    -------
    ndarray of bool, shape (...)
        True where all three legs can be assembled.

    Raises
    ------
    ValueError
        If a pose is not finite and real, ``poses`` has no last axis of 3, or ``tol`` is not a
        positive number.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=1.5, H3=2)
    >>> workspace(g, [[0.6, 0.4, 0.0], [0.6, 1.2, 0.0]]).tolist()
    [True, False]
    """
    check(mech)
    poses = _validate.array(np.reshape(poses, (0, 3)) if np.size(poses) == 0 else poses,
                            "poses")
    if poses.shape[-1:] != (3,):
        raise ValueError(f"poses must have a last axis of 3 (x, y, psi), got shape {poses.shape}")
    tol = _validate.tolerance(tol)
    return np.all(kernels.radicands(mech, poses) >= -tol * mech.L ** 2, axis=-1)
