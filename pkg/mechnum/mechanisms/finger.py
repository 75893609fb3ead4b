"""The crossed four-bar of a robotic finger's proximal phalanx (the finger study).

Frame and names of the study's tables: the output pivot ``D`` is the origin, the input pivot
``H = (-r4, 0)``; ``DE`` (length ``r1``) and ``HI`` (length ``r3``) are the two rockers, ``EI``
(length ``r2``) the coupler. The loop closure is ``r1 + r2 + r3 = r4`` as vectors, with

* ``theta_out`` (the study's theta_1): the angle of ``D -> E``, ``E = r1 (cos, sin)(theta_out)``;
* ``theta_in`` (the study's theta_3): the angle of ``I -> H``, ``I = H - r3 (cos, sin)(theta_in)``;
* the ground vector ``r4`` points along ``-x`` (theta_4 = pi).

Squaring the closure to eliminate the coupler angle gives Freudenstein's equation

    ``cos(theta_out - theta_in) = k1 cos(theta_out) + k2 cos(theta_in) + k3``,
    ``k1 = -r4 / r3``, ``k2 = -r4 / r1``, ``k3 = (r2^2 - r1^2 - r3^2 - r4^2) / (2 r1 r3)``,

which is linear in ``k``: ``m`` angle pairs give an ``m x 3`` least-squares problem, solved by
:func:`mechnum.linear.least_squares`.
"""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate, linear
from mechnum.errors import GeometryError, SingularJacobianError, UnreachablePoseError

#: Table 1 of the study: measured E (x, y) and I (x, y) in mm, ten positions (input data).
TABLE1_EI = np.array([
    [-18.9749, 24.0306, -11.9795, 24.2845], [-21.5732, 21.7281, -14.8085, 23.5277],
    [-23.8943, 19.1463, -17.6810, 22.5277], [-25.9081, 16.3183, -20.5152, 20.7811],
    [-27.5888, 13.2805, -23.2178, 18.7481], [-28.6413, 10.8254, -25.1450, 16.8897],
    [-29.4758, 8.2880, -26.8912, 14.7933], [-30.0860, 5.6875, -28.4154, 12.4852],
    [-30.4672, 3.0437, -29.6827, 9.9995], [-30.6166, 0.3767, -30.6660, 7.3765]])
#: Table 1: the length of the ground link DH in mm (H = (-6.9989, 0), D = (0, 0)).
TABLE1_R4 = 6.9989
#: Table 2 of the study: input angles theta_3 and output angles theta_1, rad (input data).
TABLE2_THETA_IN = np.array([3.9357, 4.1277, 4.3197, 4.5117, 4.7037, 4.8956, 5.0876, 5.2796,
                            5.4716, 5.6636, 5.8556, 6.0474, 6.2396])
TABLE2_THETA_OUT = np.array([1.0400, 1.2574, 1.5410, 1.7736, 2.0165, 2.2205, 2.4094, 2.5722,
                             2.7305, 2.8828, 3.0331, 3.1822, 3.3298])
#: Table 2's input angles before rounding: 225.5 degrees and then steps of 11 degrees. Each
#: printed value rounds from it, except 6.0474 (a typo for 6.0476); Table 4 was computed from
#: these unrounded angles (the chapter shows both).
TABLE2_THETA_IN_UNROUNDED = np.radians(225.5 + 11.0 * np.arange(13))
#: The study's SOR relaxation factors (Tables 5 and 7 to 11).
STUDY_OMEGAS = (0.33, 0.28, 0.309, 0.2889, 0.3289)
#: Sign of the circle-intersection branch of the study's (crossed) assembly.
CROSSED, OPEN = 1, -1
#: Machine epsilon: example 1.1's ``A`` is singular to working precision when
#: ``cond_inf(A) * eps >= 1``.
_EPS = np.finfo(float).eps


@dataclass(frozen=True)
class Linkage:
    """Link lengths (any one length unit): rockers ``r1 = DE``, ``r3 = HI``, coupler
    ``r2 = EI``, ground ``r4 = DH``.

    Raises
    ------
    ValueError
        A length that is not a finite real number.
    GeometryError
        A length that is not positive.

    Examples
    --------
    >>> Linkage(30.613, 6.9973, 24.7825, 6.9989).r2
    6.9973
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


#: Table 3's link lengths, mm (input data: the study builds Tables 4 and 11 from them).
TABLE3_LINKAGE = Linkage(30.6130, 6.9973, 24.7825, TABLE1_R4)


def _linkage(value):
    if not isinstance(value, Linkage):
        raise ValueError(f"linkage must be a Linkage, got {value!r}")
    return value


@dataclass(frozen=True)
class Pose:
    """Points of the linkage at ``n`` poses (arrays of shape ``(n, 2)``) and its two angles."""

    theta_in: np.ndarray
    theta_out: np.ndarray
    E: np.ndarray
    I: np.ndarray
    H: np.ndarray
    D: np.ndarray


@dataclass(frozen=True)
class Synthesis:
    """The outcome of :func:`synthesize`.

    Attributes
    ----------
    k : ndarray, shape (3,)
        Freudenstein coefficients ``k1, k2, k3``.
    linkage : Linkage
        The link lengths they give for the proposed ``r4``.
    residuals : ndarray, shape (m,)
        ``A k - b``: the misfit of Freudenstein's equation at every angle pair.
    solver : IterationResult or None
        The iterative solver's result (methods ``sor``, ``gauss_seidel``, ``jacobi``, ``cg``).
    """

    k: np.ndarray
    linkage: Linkage
    residuals: np.ndarray
    solver: object


def freudenstein_coefficients(linkage):
    """Freudenstein coefficients ``(k1, k2, k3)`` of a linkage.

    Examples
    --------
    >>> freudenstein_coefficients(Linkage(2.0, 3.0, 4.0, 1.0)).tolist()
    [-0.25, -0.5, -0.75]
    """
    L = _linkage(linkage)
    return np.array([-L.r4 / L.r3, -L.r4 / L.r1,
                     (L.r2 ** 2 - L.r1 ** 2 - L.r3 ** 2 - L.r4 ** 2) / (2 * L.r1 * L.r3)])


def linkage_from_coefficients(k, r4):
    """The link lengths of Freudenstein coefficients ``k`` for a proposed ground link ``r4``.

    Raises
    ------
    ValueError
        If ``k`` is not three finite numbers or ``r4`` not a positive one.
    GeometryError
        If ``k1`` or ``k2`` is not negative, or ``r2^2 <= 0``: no linkage has these coefficients.

    Examples
    --------
    >>> L = linkage_from_coefficients([-0.25, -0.5, -0.75], 1.0)
    >>> np.round([L.r1, L.r2, L.r3, L.r4], 12).tolist()
    [2.0, 3.0, 4.0, 1.0]
    """
    k = _validate.array(k, "k", shape=(3,))
    r4 = _validate.scalar(r4, "r4", positive=True)
    if k[0] >= 0 or k[1] >= 0:
        raise GeometryError(f"k1 = {k[0]:.6g} and k2 = {k[1]:.6g} must be negative")
    r3, r1 = -r4 / k[0], -r4 / k[1]
    r2_squared = 2 * r1 * r3 * k[2] + r1 ** 2 + r3 ** 2 + r4 ** 2
    if not r2_squared > 0:
        raise GeometryError(f"k gives r2^2 = {r2_squared:.6g} <= 0: no coupler fits")
    return Linkage(float(r1), float(np.sqrt(r2_squared)), float(r3), r4)


def _wrap(theta):
    """Angles in ``[0, 2 pi)``: ``x % (2 pi)`` of a tiny negative ``x`` rounds to ``2 pi``."""
    theta = np.mod(theta, 2 * np.pi)
    return np.where(theta < 2 * np.pi, theta, 0.0)


def _unit(theta):
    return np.column_stack([np.cos(theta), np.sin(theta)])


def _angle_pairs(theta_in, theta_out):
    theta_in = _validate.array(theta_in, "theta_in", ndim=1)
    theta_out = _validate.array(theta_out, "theta_out", ndim=1)
    if theta_in.shape != theta_out.shape:
        raise ValueError(f"theta_in and theta_out differ in shape: {theta_in.shape}, "
                         f"{theta_out.shape}")
    return theta_in, theta_out


def design_matrix(theta_in, theta_out):
    """The least-squares system ``A k ~= b`` of Freudenstein's equation.

    Returns
    -------
    A : ndarray, shape (m, 3)
        Rows ``(cos theta_out, cos theta_in, 1)``.
    b : ndarray, shape (m,)
        ``cos(theta_out - theta_in)``.

    Examples
    --------
    >>> A, b = design_matrix([0.0], [np.pi])
    >>> np.round(A, 12).tolist(), np.round(b, 12).tolist()
    ([[-1.0, 1.0, 1.0]], [-1.0])
    """
    theta_in, theta_out = _angle_pairs(theta_in, theta_out)
    A = np.column_stack([np.cos(theta_out), np.cos(theta_in), np.ones_like(theta_in)])
    return A, np.cos(theta_out - theta_in)


def synthesize(theta_in, theta_out, r4, method="qr", omega=None, **solver_options):
    """Fit the Freudenstein coefficients and link lengths to angle pairs by least squares.

    Parameters
    ----------
    theta_in, theta_out : array_like, shape (m,)
        Angle pairs, rad, ``m >= 3``.
    r4 : float
        The proposed ground link (it sets the scale).
    method : str, optional
        A method of :func:`mechnum.linear.least_squares`: ``"qr"`` (default), ``"svd"``, the
        normal equations by ``"cholesky"`` or ``"lu"``, or iteratively by ``"jacobi"``,
        ``"gauss_seidel"``, ``"sor"`` (with ``omega``) or ``"cg"``.
    omega : float, optional
        The SOR relaxation factor (required by ``method="sor"``).
    **solver_options
        Options of the iterative solver (``tol``, ``maxiter``, ...).

    Returns
    -------
    Synthesis

    Raises
    ------
    ValueError
        Bad angles or ``r4``, fewer than 3 pairs, an unknown method or option.
    SingularJacobianError
        The pairs do not determine ``k`` (rank below 3, e.g. coincident angles).
    RelaxationFactorError
        ``method="sor"`` without ``omega`` in ``(0, 2)``.
    GeometryError
        The fitted ``k`` belongs to no linkage.

    Examples
    --------
    >>> true = Linkage(30.0, 7.0, 25.0, 7.0)
    >>> theta_in = np.linspace(4.6, 6.2, 6)
    >>> fit = synthesize(theta_in, pose(theta_in, true).theta_out, 7.0)
    >>> np.round([fit.linkage.r1, fit.linkage.r2, fit.linkage.r3], 9).tolist()
    [30.0, 7.0, 25.0]
    """
    A, b = design_matrix(theta_in, theta_out)
    if A.shape[0] < 3:
        raise ValueError(f"at least 3 angle pairs are needed, got {A.shape[0]}")
    r4 = _validate.scalar(r4, "r4", positive=True)
    try:
        fit = linear.least_squares(A, b, method, omega, **solver_options)
    except SingularJacobianError as error:
        raise SingularJacobianError(f"the angle pairs do not determine k: {error}") from None
    return Synthesis(fit.x, linkage_from_coefficients(fit.x, r4), fit.residuals, fit.solver)


def _intersect(P, rP, Q, rQ, sign, angles):
    """The intersection of circles (P, rP) and (Q, rQ) on side ``sign`` of the line P -> Q."""
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
    return P + a[:, None] * u + sign * h[:, None] * np.column_stack([-u[:, 1], u[:, 0]])


def reachable(theta, linkage, driver="input"):
    """Whether the linkage can be assembled at each angle of its driving rocker.

    Parameters
    ----------
    theta : array_like, shape (n,)
        Angles of the driving rocker, rad.
    linkage : Linkage
    driver : {"input", "output"}, optional
        ``"input"``: ``theta`` is theta_3 (rocker HI), and ``|DI|`` must lie in
        ``[|r1 - r2|, r1 + r2]``; ``"output"``: ``theta`` is theta_1 (rocker DE), and ``|HE|``
        must lie in ``[|r3 - r2|, r3 + r2]``.

    Returns
    -------
    ndarray of bool, shape (n,)

    Examples
    --------
    >>> reachable([4.0, 5.0], Linkage(30.613, 6.9973, 24.7825, 6.9989)).tolist()
    [False, True]
    """
    theta, L = _validate.array(theta, "theta", ndim=1), _linkage(linkage)
    _validate.choice(driver, ("input", "output"), "driver")
    H = np.array([-L.r4, 0.0])
    if driver == "input":
        d, r = np.linalg.norm(H - L.r3 * _unit(theta), axis=1), L.r1
    else:
        d, r = np.linalg.norm(L.r1 * _unit(theta) - H, axis=1), L.r3
    return (d <= r + L.r2) & (d >= abs(r - L.r2))


def _pivots(n, linkage):
    return np.tile([-linkage.r4, 0.0], (n, 1)), np.zeros((n, 2))


def pose(theta_in, linkage, branch=CROSSED):
    """Position analysis driven by the input rocker HI.

    Parameters
    ----------
    theta_in : array_like, shape (n,)
        The study's theta_3, rad (an empty array gives an empty pose).
    linkage : Linkage
    branch : {CROSSED, OPEN}, optional
        The assembly: ``CROSSED`` (the study's, where DE and HI cross) or ``OPEN``.

    Returns
    -------
    Pose

    Raises
    ------
    UnreachablePoseError
        If some angle cannot be assembled; the message names the angles and distances.

    Examples
    --------
    >>> p = pose([5.0], Linkage(30.613, 6.9973, 24.7825, 6.9989))
    >>> p.E.round(4).tolist(), round(float(p.theta_out[0]), 6)
    ([[-20.8877, 22.3799]], 2.32172)
    """
    theta_in, L = _validate.array(theta_in, "theta_in", ndim=1), _linkage(linkage)
    branch = _validate.choice(branch, (CROSSED, OPEN), "branch")
    H, D = _pivots(theta_in.size, L)
    I = H - L.r3 * _unit(theta_in)
    E = _intersect(D, L.r1, I, L.r2, branch, theta_in)
    return Pose(theta_in, _wrap(np.arctan2(E[:, 1], E[:, 0])), E, I, H, D)


def pose_from_output(theta_out, linkage, branch=CROSSED):
    """Position analysis driven by the output rocker DE (arguments as :func:`pose`).

    ``branch`` puts ``I`` on side ``-branch`` of the line ``H -> E``. On the study's linkage
    over its range of motion this is the assembly that :func:`pose` calls ``branch``, so the
    two analyses invert each other; for another linkage the two sides need not correspond
    (one of the two branches inverts :func:`pose`).

    Examples
    --------
    >>> L = Linkage(30.613, 6.9973, 24.7825, 6.9989)
    >>> p = pose_from_output(pose([5.0], L).theta_out, L)
    >>> round(float(p.theta_in[0]), 12)
    5.0
    """
    theta_out, L = _validate.array(theta_out, "theta_out", ndim=1), _linkage(linkage)
    branch = _validate.choice(branch, (CROSSED, OPEN), "branch")
    H, D = _pivots(theta_out.size, L)
    E = L.r1 * _unit(theta_out)
    I = _intersect(H, L.r3, E, L.r2, -branch, theta_out)  # seen from H, not D
    theta_in = _wrap(np.arctan2(H[:, 1] - I[:, 1], H[:, 0] - I[:, 0]))
    return Pose(theta_in, theta_out, E, I, H, D)


def place_links(theta_in, theta_out, linkage):
    """Put the rockers at given angles without assembling the coupler (as the study's
    Tables 4 and 5 do): ``E = r1 e(theta_out)``, ``I = H - r3 e(theta_in)``.

    Compare ``|I - E|`` with ``r2`` to see whether the pose can exist.

    Examples
    --------
    >>> p = place_links([np.pi], [0.0], Linkage(3.0, 1.0, 2.0, 1.0))
    >>> p.E.round(12).tolist(), (p.I.round(12) + 0.0).tolist()
    ([[3.0, 0.0]], [[1.0, 0.0]])
    """
    theta_in, theta_out = _angle_pairs(theta_in, theta_out)
    L = _linkage(linkage)
    H, D = _pivots(theta_in.size, L)
    return Pose(theta_in, theta_out, L.r1 * _unit(theta_out), H - L.r3 * _unit(theta_in), H, D)


def angles_from_points(E, I, r4):
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
    I = _validate.array(I, "I", shape=(E.shape[0], 2))
    r4 = _validate.scalar(r4, "r4", positive=True)
    theta_out = _wrap(np.arctan2(E[:, 1], E[:, 0]))
    theta_in = _wrap(np.arctan2(-I[:, 1], -r4 - I[:, 0]))
    return theta_in, theta_out


def table1_linkage():
    """One link-length set for Table 1: the medians of ``|DE|``, ``|EI|``, ``|HI|`` over its
    ten measured positions (the median ignores one corrupted row).

    Examples
    --------
    >>> L = table1_linkage()
    >>> round(L.r1, 4), round(L.r2, 4), round(L.r3, 4)
    (30.6189, 7.0, 24.79)
    """
    E, I = TABLE1_EI[:, :2], TABLE1_EI[:, 2:]
    H = np.array([-TABLE1_R4, 0.0])
    return Linkage(float(np.median(np.linalg.norm(E, axis=1))),
                   float(np.median(np.linalg.norm(I - E, axis=1))),
                   float(np.median(np.linalg.norm(I - H, axis=1))), TABLE1_R4)


def draw(ax, state, index=0, *, lines=None, color="C0"):
    """Draw the linkage of ``state`` at pose ``index``: ground ``DH``, rockers, coupler.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    state : Pose
    index : int, optional
        Which of the poses of ``state``.
    lines : tuple of Line2D, optional
        The artists of an earlier call, moved to the new pose (for an animation).
    color : str, optional
        Colour of the moving links.

    Returns
    -------
    tuple of Line2D
        ``(links, ground)``: the chain ``D-E-I-H`` and the ground link.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots()
    >>> L = Linkage(30.613, 6.9973, 24.7825, 6.9989)
    >>> links, ground = draw(ax, pose([5.0, 5.5], L))
    >>> links.get_xydata().round(2).tolist()[1]     # E of the first pose
    [-20.89, 22.38]
    >>> _ = draw(ax, pose([5.0, 5.5], L), 1, lines=(links, ground)); plt.close(fig)
    """
    if not isinstance(state, Pose):
        raise ValueError(f"state must be a Pose, got {state!r}")
    index = _validate.maxiter(index, "index", minimum=0)
    if index >= state.E.shape[0]:
        raise ValueError(f"index {index} is out of range for {state.E.shape[0]} poses")
    chain = np.array([state.D[index], state.E[index], state.I[index], state.H[index]])
    ground = chain[[0, 3]]
    if lines is None:
        (links,) = ax.plot(*chain.T, "o-", color=color, lw=2, label="links D-E-I-H")
        (base,) = ax.plot(*ground.T, "k^--", ms=9, label="ground D-H")
        return links, base
    links, base = lines
    links.set_data(*chain.T)
    base.set_data(*ground.T)
    return links, base


def ill_conditioned_example(delta, rhs_shift):
    """The study's example 1.1: ``x - 2y = 1``, ``x - (2 + delta) y = 1 + rhs_shift``.

    Returns
    -------
    solution : ndarray, shape (2,)
    cond_inf : float
        ``||A||_inf ||A^-1||_inf``, equal to ``(3 + delta)(4 + delta) / delta`` for
        ``delta > 0`` (for the ``delta`` that the rounded ``2 + delta`` represents).

    Raises
    ------
    ValueError
        Non-finite input.
    SingularJacobianError
        ``delta`` so small that ``A`` is singular to working precision (``delta = 0``: the
        two equations are parallel).

    Examples
    --------
    >>> x, c = ill_conditioned_example(0.5, 0.5)
    >>> x.round(12).tolist(), round(c, 9)
    ([-1.0, -1.0], 31.5)
    """
    delta = _validate.scalar(delta, "delta")
    shift = _validate.scalar(rhs_shift, "rhs_shift")
    A = np.array([[1.0, -2.0], [1.0, -(2.0 + delta)]])
    cond = linear.condition_number(A, np.inf)
    if cond * _EPS >= 1:
        raise SingularJacobianError(
            f"delta = {delta!r} makes A singular to working precision (cond_inf = {cond:.3g}): "
            f"the two equations are parallel")
    return np.linalg.solve(A, [1.0, 1.0 + shift]), cond


def _table_rows(prefix, I, E):
    """Registry keys ``"<prefix> pos <i> <I|E> <x|y>"`` for the points of a table."""
    return {f"{prefix} pos {i + 1} {name} {axis}": float(points[i, j])
            for i in range(len(I)) for name, points in (("I", I), ("E", E))
            for j, axis in enumerate("xy")}


def reproduce():
    """Every number of the registry's ``02_linear_systems_finger`` rows, computed afresh.

    Returns
    -------
    dict of str to float

    Examples
    --------
    >>> round(reproduce()["Tabla 3 r1"], 4)
    35.0761
    """
    values = {}
    # Table 1: each point predicted from the other point's angle through one linkage.
    L1 = table1_linkage()
    theta_in, theta_out = angles_from_points(TABLE1_EI[:, :2], TABLE1_EI[:, 2:], TABLE1_R4)
    values.update(_table_rows("Tabla 1", pose_from_output(theta_out, L1).I,
                              pose(theta_in, L1).E))
    # Table 2: each angle from the other one through the published linkage (Table 3).
    published = TABLE3_LINKAGE
    ok = reachable(TABLE2_THETA_IN, published)
    out = pose(TABLE2_THETA_IN[ok], published).theta_out
    for i, value in zip(np.flatnonzero(ok), out):
        values[f"Tabla 2 pos {i + 1} theta_1"] = float(value)
    ok = reachable(TABLE2_THETA_OUT, published, "output")
    back = pose_from_output(TABLE2_THETA_OUT[ok], published).theta_in
    for i, value in zip(np.flatnonzero(ok), back):
        values[f"Tabla 2 pos {i + 1} theta_3"] = float(value)
    # Table 3: the least-squares fit of Table 2. Table 4: the rockers of Table 3 placed at
    # Table 2's angles, the input ones unrounded (I depends on theta_in only, E on theta_out).
    fit = synthesize(TABLE2_THETA_IN, TABLE2_THETA_OUT, TABLE1_R4, "qr")
    for name in ("r1", "r2", "r3"):
        values[f"Tabla 3 {name}"] = getattr(fit.linkage, name)
    placed = place_links(TABLE2_THETA_IN_UNROUNDED, TABLE2_THETA_OUT, published)
    values.update(_table_rows("Tabla 4", placed.I, placed.E))
    # Tables 5 to 11: SOR on the normal equations for each omega, converged.
    for table, omega in zip((5, 7, 8, 9, 10), STUDY_OMEGAS):
        sol = synthesize(TABLE2_THETA_IN, TABLE2_THETA_OUT, TABLE1_R4, "sor", omega,
                         tol=1e-12, maxiter=20_000)
        placed = place_links(TABLE2_THETA_IN, TABLE2_THETA_OUT, sol.linkage)
        values.update(_table_rows(f"Tabla {table}", placed.I, placed.E))
        for name in ("r1", "r2", "r3"):
            if omega == 0.33:
                values[f"Tabla 6 {name}"] = getattr(sol.linkage, name)
            values[f"Tabla 11 omega={omega} {name}"] = abs(
                getattr(sol.linkage, name) - getattr(published, name))
    A, b = design_matrix(TABLE2_THETA_IN, TABLE2_THETA_OUT)
    values["best omega"] = linear.optimal_omega(A.T @ A).omega
    # Example 1.1.
    (x, y), cond = ill_conditioned_example(1e-6, 1e-6)
    (x2, y2), _ = ill_conditioned_example(1e-6, 2e-6)
    values.update({"Ej. 1.1 x": x, "Ej. 1.1 y": y, "Ej. 1.1 cond_inf(A), delta=1e-6": cond,
                   "Ej. 1.1 perturbed x": x2, "Ej. 1.1 perturbed y": y2})
    return {key: float(value) for key, value in values.items()}
