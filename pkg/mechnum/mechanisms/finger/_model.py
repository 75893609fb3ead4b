"""The finger's four-bar: its links, its two assembly modes, and where it assembles.

:class:`Linkage` holds the link lengths (metres); :func:`forward` gives the output angle of each
assembly mode for input angles, :func:`inverse` the input angle for output angles,
:func:`workspace` the angles at which the linkage assembles, and :func:`place_links` the points
of given angles (a :class:`Pose`).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import GeometryError, UnreachablePoseError
from mechnum.results import Assemblies

#: Sign of the circle-intersection branch of the study's (crossed) assembly, and of the other.
CROSSED, OPEN = 1, -1
MODES = (CROSSED, OPEN)
"""The assembly modes, in the order of the columns of :func:`forward` and :func:`inverse`."""


@dataclass(frozen=True)
class Linkage:
    """The four-bar: its link lengths in metres, rockers ``r1 = DE``, ``r3 = HI``, coupler
    ``r2 = EI``, ground ``r4 = DH``; the first argument of every function of the package.

    Raises
    ------
    ValueError
        A length that is not a finite real number.
    GeometryError
        A length that is not positive.

    Examples
    --------
    >>> Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989).r2
    0.0069973
    >>> Linkage(1.0, -2.0, 3.0, 1.0)
    Traceback (most recent call last):
    ...
    mechnum.errors.GeometryError: link lengths must be positive, got [1.0, -2.0, 3.0, 1.0]
    """

    r1: float
    r2: float
    r3: float
    r4: float

    def __post_init__(self):
        values = [_validate.scalar(getattr(self, name), name) for name in ("r1", "r2", "r3", "r4")]
        for name, value in zip(("r1", "r2", "r3", "r4"), values):
            object.__setattr__(self, name, value)  # frozen: store the checked floats
        if min(values) <= 0:
            raise GeometryError(f"link lengths must be positive, got {values}")


def checked(mech: object) -> Linkage:
    """``mech`` if it is a :class:`Linkage`; else :class:`ValueError` naming it.

    Examples
    --------
    >>> checked(Linkage(2.0, 3.0, 4.0, 1.0)).r3
    4.0
    """
    return _validate.instance(mech, Linkage, "mech", "a finger.Linkage")


@dataclass(frozen=True)
class Pose:
    """Points of the linkage at ``n`` poses (arrays of shape ``(n, 2)``) and its two angles."""

    theta_in: np.ndarray
    theta_out: np.ndarray
    E: np.ndarray
    I: np.ndarray  # noqa: E741  (the study's name of the point)
    H: np.ndarray
    D: np.ndarray


def freudenstein_coefficients(mech: Linkage) -> np.ndarray:
    """Freudenstein coefficients ``(k1, k2, k3)`` of a linkage.

    Examples
    --------
    >>> freudenstein_coefficients(Linkage(2.0, 3.0, 4.0, 1.0)).tolist()
    [-0.25, -0.5, -0.75]
    """
    L = checked(mech)
    return np.array([-L.r4 / L.r3, -L.r4 / L.r1,
                     (L.r2 ** 2 - L.r1 ** 2 - L.r3 ** 2 - L.r4 ** 2) / (2 * L.r1 * L.r3)])


def wrap(theta: ArrayLike) -> np.ndarray:
    """Angles in ``[0, 2 pi)``: ``x % (2 pi)`` of a tiny negative ``x`` rounds to ``2 pi``.

    Examples
    --------
    >>> wrap([-1e-17, 7.0]).round(6).tolist()
    [0.0, 0.716815]
    """
    theta = np.mod(theta, 2 * np.pi)
    return np.where(theta < 2 * np.pi, theta, 0.0)


def unit(theta: np.ndarray) -> np.ndarray:
    """The unit vectors ``(cos, sin)`` of angles, shape ``(n, 2)``."""
    return np.column_stack([np.cos(theta), np.sin(theta)])


def _intersect(P, rP, Q, rQ, angles):
    """The two intersections of circles (P, rP) and (Q, rQ), on sides ``+1`` and ``-1`` of the
    line P -> Q: shape ``(2, n, 2)``."""
    d = np.linalg.norm(Q - P, axis=1)
    bad = (d > rP + rQ) | (d < abs(rP - rQ))
    if bad.any():
        raise UnreachablePoseError(
            f"the linkage cannot be assembled at angle(s) {np.round(angles[bad], 6).tolist()} "
            f"rad: pivot distance {np.round(d[bad], 4).tolist()} outside "
            f"[{abs(rP - rQ):.4f}, {rP + rQ:.4f}]")
    u = (Q - P) / d[:, None]
    a = (rP ** 2 - rQ ** 2 + d ** 2) / (2 * d)
    h = np.sqrt(np.maximum(rP ** 2 - a ** 2, 0.0))
    across = h[:, None] * np.column_stack([-u[:, 1], u[:, 0]])
    return np.stack([P + a[:, None] * u + side * across for side in MODES])


def _pivots(mech):
    return np.array([-mech.r4, 0.0]), np.zeros(2)


def forward(mech: Linkage, theta_in: ArrayLike) -> Assemblies:
    """The output angles of both assembly modes for input angles: the forward problem.

    The input rocker ``HI`` at ``theta_in`` puts ``I``; ``E`` is where the circles of radius
    ``r1`` about ``D`` and ``r2`` about ``I`` meet, on side ``+1`` of the line ``D -> I``
    (:data:`CROSSED`, the study's assembly, where ``DE`` and ``HI`` cross) or ``-1``
    (:data:`OPEN`).

    Parameters
    ----------
    mech : Linkage
    theta_in : array_like, shape (n,)
        The study's theta_3, rad (an empty array is valid).

    Returns
    -------
    mechnum.results.Assemblies
        ``x``, shape (n, 2): the output angles theta_out (the study's theta_1), rad in
        ``[0, 2 pi)``, column 0 of the crossed assembly, column 1 of the open one;
        ``inputs``: ``theta_in``.

    Raises
    ------
    UnreachablePoseError
        If some angle cannot be assembled; the message names the angles and distances.

    Examples
    --------
    >>> L = Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989)
    >>> forward(L, [5.0]).x.round(6).tolist()
    [[2.32172, 1.88642]]
    """
    mech = checked(mech)
    theta_in = _validate.array(theta_in, "theta_in", ndim=1)
    H, D = _pivots(mech)
    I = H - mech.r3 * unit(theta_in)  # noqa: E741
    E = _intersect(np.broadcast_to(D, I.shape), mech.r1, I, mech.r2, theta_in)
    return Assemblies.of(wrap(np.arctan2(E[..., 1], E[..., 0])).T, theta_in, theta_in.size,
                         len(MODES))


def inverse(mech: Linkage, theta_out: ArrayLike) -> np.ndarray:
    """The input angles of both assembly modes for output angles: the inverse problem.

    The output rocker ``DE`` at ``theta_out`` puts ``E``; ``I`` is where the circles of radius
    ``r3`` about ``H`` and ``r2`` about ``E`` meet, on side ``-1`` (column 0) or ``+1``
    (column 1) of the line ``H -> E``. On the study's linkage over its range of motion,
    column 0 is the crossed assembly, and the two problems invert each other mode by mode; for
    another linkage the sides need not correspond (one of the two columns inverts
    :func:`forward`).

    Parameters
    ----------
    mech : Linkage
    theta_out : array_like, shape (n,)
        The study's theta_1, rad.

    Returns
    -------
    ndarray, shape (n, 2)
        The input angles theta_in, rad in ``[0, 2 pi)``.

    Raises
    ------
    UnreachablePoseError
        If some angle cannot be assembled.

    Examples
    --------
    >>> L = Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989)
    >>> round(float(inverse(L, forward(L, [5.0]).x[:, 0])[0, 0]), 12)
    5.0
    """
    mech = checked(mech)
    theta_out = _validate.array(theta_out, "theta_out", ndim=1)
    H, _ = _pivots(mech)
    E = mech.r1 * unit(theta_out)
    I = _intersect(np.broadcast_to(H, E.shape), mech.r3, E, mech.r2, theta_out)[::-1]  # noqa
    return wrap(np.arctan2(H[1] - I[..., 1], H[0] - I[..., 0])).T


def workspace(mech: Linkage, theta: ArrayLike, *, driver: str = "input") -> np.ndarray:
    """Whether the linkage can be assembled at each angle of its driving rocker.

    Parameters
    ----------
    mech : Linkage
    theta : array_like, shape (n,)
        Angles of the driving rocker, rad.
    driver : {"input", "output"}, optional
        ``"input"``: ``theta`` is theta_3 (rocker HI), and ``|DI|`` must lie in
        ``[|r1 - r2|, r1 + r2]``; ``"output"``: ``theta`` is theta_1 (rocker DE), and ``|HE|``
        must lie in ``[|r3 - r2|, r3 + r2]``.

    Returns
    -------
    ndarray of bool, shape (n,)

    Examples
    --------
    >>> workspace(Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989), [4.0, 5.0]).tolist()
    [False, True]
    """
    mech, theta = checked(mech), _validate.array(theta, "theta", ndim=1)
    _validate.choice(driver, ("input", "output"), "driver")
    H, _ = _pivots(mech)
    if driver == "input":
        d, r = np.linalg.norm(H - mech.r3 * unit(theta), axis=1), mech.r1
    else:
        d, r = np.linalg.norm(mech.r1 * unit(theta) - H, axis=1), mech.r3
    return (d <= r + mech.r2) & (d >= abs(r - mech.r2))


def angle_pairs(theta_in: ArrayLike, theta_out: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Input and output angles, checked: two finite 1-D arrays of one length."""
    theta_in = _validate.array(theta_in, "theta_in", ndim=1)
    theta_out = _validate.array(theta_out, "theta_out", ndim=1)
    if theta_in.shape != theta_out.shape:
        raise ValueError(f"theta_in and theta_out differ in shape: {theta_in.shape}, "
                         f"{theta_out.shape}")
    return theta_in, theta_out


def place_links(mech: Linkage, theta_in: ArrayLike, theta_out: ArrayLike) -> Pose:
    """The points of the rockers at given angles, without assembling the coupler (as the
    study's Tables 4 and 5 do): ``E = r1 e(theta_out)``, ``I = H - r3 e(theta_in)``.

    Compare ``|I - E|`` with ``r2`` to see whether the pose can exist; at the angles of
    :func:`forward` it does.

    Examples
    --------
    >>> p = place_links(Linkage(3.0, 1.0, 2.0, 1.0), [np.pi], [0.0])
    >>> p.E.round(12).tolist(), (p.I.round(12) + 0.0).tolist()
    ([[3.0, 0.0]], [[1.0, 0.0]])
    """
    mech = checked(mech)
    theta_in, theta_out = angle_pairs(theta_in, theta_out)
    H, D = (np.tile(p, (theta_in.size, 1)) for p in _pivots(mech))
    return Pose(theta_in, theta_out, mech.r1 * unit(theta_out), H - mech.r3 * unit(theta_in), H,
                D)


def angles_from_points(E: ArrayLike, I: ArrayLike, r4: float  # noqa: E741
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The angles ``(theta_in, theta_out)`` of measured points E and I, rad in ``[0, 2 pi)``.

    Parameters
    ----------
    E, I : array_like, shape (n, 2)
        Points in the frame of the module (``D`` at the origin, ``H = (-r4, 0)``).
    r4 : float
        The ground link, positive.

    Examples
    --------
    >>> np.round(angles_from_points([[0.0, 2.0]], [[-1.0, -1.0]], 1.0), 6).tolist()
    [[1.570796], [1.570796]]
    """
    E = _validate.array(E, "E", shape=(None, 2))
    I = _validate.array(I, "I", shape=(E.shape[0], 2))  # noqa: E741
    r4 = _validate.scalar(r4, "r4", positive=True)
    return wrap(np.arctan2(-I[:, 1], -r4 - I[:, 0])), wrap(np.arctan2(E[:, 1], E[:, 0]))
