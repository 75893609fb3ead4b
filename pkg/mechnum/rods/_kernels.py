"""The closed form of ``rods._regular``, compiled: the solvers' inner loop.

``rods._regular.closed_form`` evaluates rods of the regular chart on numpy arrays,
a few dozen array operations per call, each over the whole batch; a search from 2200 starts
calls it a hundred times, and most of its time is the arithmetic of the arrays and their
temporaries. Here the same formulas run row by row, compiled by numba (``cache=True``: the
machine code is kept beside the module and loaded by later processes), with Carlson's
symmetric integrals written out (numba cannot call ``scipy.special``; DLMF 19.36.1 and
19.36.2, the duplication theorem and the seventh-order series of Carlson, *Numer. Algorithms*
10 (1995) 13-26), so that a rod and its Jacobian cost a few microseconds.

The numpy closed form stays the reference: :func:`closed_form` and the joint systems
(:func:`meeting`, :func:`joined`) give its results to about ``1e-15`` relative (the tests ask
``1e-13`` over the chart, every mode, both branches, ``|k_rel|`` near 1), and inside
:func:`reference` every function of this module computes with numpy instead (what the
benchmarks report as "the numpy path").

The functions here check nothing (their callers, the solvers, keep their iterates in the chart
and check their inputs once): ``0 < psi < 2 pi``, ``0 < |t| <= T_MAX``, modes ``>= 1`` as
floats, ``EI, L > 0``.

Examples
--------
>>> from mechnum.rods import _regular as regular
>>> psi, t = np.array([2.0, 4.0]), np.array([0.5, -0.3])
>>> fast = closed_form(1.0, 1.0, psi, t, np.array([1.0, 2.0]))
>>> slow = regular.closed_form(1.0, 1.0, psi, t, np.array([1.0, 2.0]))
>>> bool(np.allclose(fast.jacobian, slow.jacobian, rtol=1e-13, atol=1e-14))
True
"""

from contextlib import contextmanager

import numba
import numpy as np

from mechnum.rods._growing import SERIES
from mechnum.rods._regular import T_MAX, RegularRod, place_at
from mechnum.rods._regular import closed_form as numpy_closed_form

_COMPILED = {"on": True}
# Carlson's stopping rule: iterate until 4**-n Q < |A_n| with Q = (3 r)**(-1/6) max|A_0 - x|
# for R_F and (r / 4)**(-1/6) max|A_0 - x| for R_D; r = 2**-53 leaves a truncation error of
# the series below the rounding of its terms
_EPS = 2.0 ** -53
_RF_Q = (3.0 * _EPS) ** (-1.0 / 6.0)
_RD_Q = (0.25 * _EPS) ** (-1.0 / 6.0)
_T_MAX = T_MAX
_OUT = 15   # per rod: tip (2), force (2), clamp moment, Jacobian (5 x 2, row by row)
_jit = numba.njit(cache=True, error_model="numpy")


@contextmanager
def reference():
    """Within it, this module's functions compute with numpy (the reference closed form of
    ``rods._regular``) instead of the compiled code, in this process.

    Examples
    --------
    >>> with reference():
    ...     rod = closed_form(1.0, 1.0, np.array([2.0]), np.array([0.5]), np.array([1.0]))
    >>> rod.tip.shape
    (1, 2)
    """
    before, _COMPILED["on"] = _COMPILED["on"], False
    try:
        yield
    finally:
        _COMPILED["on"] = before


@_jit
def rf(x, y, z):
    """Carlson's ``R_F(x, y, z)`` (DLMF 19.36.1): ``x, y, z >= 0``, at most one of them 0.

    Examples
    --------
    >>> from scipy.special import elliprf
    >>> bool(abs(rf(0.5, 1.0, 2.0) / elliprf(0.5, 1.0, 2.0) - 1) < 1e-15)
    True
    """
    A0 = (x + y + z) / 3.0
    xn, yn, zn, A = x, y, z, A0
    Q, scale = _RF_Q * max(abs(A0 - x), abs(A0 - y), abs(A0 - z)), 1.0
    while scale * Q >= abs(A):
        sx, sy, sz = np.sqrt(xn), np.sqrt(yn), np.sqrt(zn)
        lam = sx * sy + sy * sz + sz * sx
        xn, yn, zn = 0.25 * (xn + lam), 0.25 * (yn + lam), 0.25 * (zn + lam)
        A, scale = 0.25 * (A + lam), 0.25 * scale
    X, Y = (A0 - x) * scale / A, (A0 - y) * scale / A
    Z = -(X + Y)
    E2, E3 = X * Y - Z * Z, X * Y * Z
    return (1.0 - E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0
            - 5.0 * E2 * E2 * E2 / 208.0 + 3.0 * E3 * E3 / 104.0 + E2 * E2 * E3 / 16.0
            ) / np.sqrt(A)


@_jit
def rd(x, y, z):
    """Carlson's ``R_D(x, y, z)`` (DLMF 19.36.2): ``x, y >= 0`` (at most one 0), ``z > 0``.

    Examples
    --------
    >>> from scipy.special import elliprd
    >>> bool(abs(rd(0.5, 1.0, 2.0) / elliprd(0.5, 1.0, 2.0) - 1) < 1e-15)
    True
    """
    A0 = (x + y + 3.0 * z) / 5.0
    xn, yn, zn, A = x, y, z, A0
    Q, scale, total = _RD_Q * max(abs(A0 - x), abs(A0 - y), abs(A0 - z)), 1.0, 0.0
    while scale * Q >= abs(A):
        sx, sy, sz = np.sqrt(xn), np.sqrt(yn), np.sqrt(zn)
        lam = sx * sy + sy * sz + sz * sx
        total += scale / (sz * (zn + lam))
        xn, yn, zn = 0.25 * (xn + lam), 0.25 * (yn + lam), 0.25 * (zn + lam)
        A, scale = 0.25 * (A + lam), 0.25 * scale
    X, Y = (A0 - x) * scale / A, (A0 - y) * scale / A
    Z = -(X + Y) / 3.0
    XY, ZZ = X * Y, Z * Z
    E2, E3, E4, E5 = XY - 6.0 * ZZ, (3.0 * XY - 8.0 * ZZ) * Z, 3.0 * (XY - ZZ) * ZZ, XY * ZZ * Z
    series = (1.0 - 3.0 * E2 / 14.0 + E3 / 6.0 + 9.0 * E2 * E2 / 88.0 - 3.0 * E4 / 22.0
              - 9.0 * E2 * E3 / 52.0 + 3.0 * E5 / 26.0)
    return scale * series / (A * np.sqrt(A)) + 3.0 * total


@_jit
def _excess(a, b, v, w):
    """``|a| lambda L / v - 1`` of the growing branch (``rods._growing._rf_excess``,
    one rod)."""
    if a == 0.0:
        return -1.0
    d0, d1, d2 = -(v * a) ** 2, (v * b) ** 2, v * v * (b * b * w - a * a)
    mean = (d0 + d1 + d2) / 3.0
    A = a * a + mean
    X, Y = (mean - d0) / A, (mean - d1) / A
    aa = abs(a)
    if max(abs(X), abs(Y), abs(X + Y)) > SERIES:
        k2 = a * a + (b * v) ** 2
        return aa * rf(w * a * a, k2, w * k2) - 1.0
    Z = -X - Y
    E2, E3 = X * Y - Z * Z, X * Y * Z
    series = (-E2 / 10.0 + E3 / 14.0 + E2 * E2 / 24.0 - 3.0 * E2 * E3 / 44.0
              - 5.0 * E2 ** 3 / 208.0 + 3.0 * E3 * E3 / 104.0 + E2 * E2 * E3 / 16.0)
    root = np.sqrt(A)
    return (aa * series - mean / (aa + root)) / root


@_jit
def rod(EI, L, psi, t, mode, jacobian, out):
    """One rod of the chart (``rods._regular.closed_form``), into ``out`` (15,):
    ``tip_x, tip_y, force_x, force_y, clamp_moment``, then (with ``jacobian``) the Jacobian
    ``d (tip, force, moment) / d (psi, t)`` row by row (10 values). (Straight-line code, with
    ``if`` statements: numba compiles conditional expressions and tuples indexed in loops
    several times more slowly.)

    Examples
    --------
    >>> out = np.empty(15)
    >>> rod(1.0, 1.0, 2.0, 0.5, 1.0, True, out)
    >>> bool(np.allclose(out[:2], closed_form(1.0, 1.0, 2.0, 0.5, 1.0).tip, rtol=1e-15))
    True
    """
    a, b = np.cos(0.5 * psi), np.sin(0.5 * psi)
    sign, sa = 1.0, 1.0
    if t < 0:
        sign = -1.0
    if a < 0:
        sa = -1.0
    q = t * t / ((1.0 - t) * (1.0 + t))
    ratio = 1.0
    if q > 0:
        ratio = -np.expm1(-q) / q
    v, w = abs(t) * np.sqrt(ratio / ((1.0 - t) * (1.0 + t))), np.exp(-q)
    j, sgn = 2.0 * mode - 1.0, sign * sa
    m, p = a * a + b * b * v * v, b * b * w
    k = np.sqrt(m)
    X = w * a * a / m
    RF, RD = rf(X, 1.0, w), rd(X, 1.0, w)
    Iw = v / k * RF
    G = p * v ** 3 / (3.0 * k ** 3) * RD
    Dp = p * Iw + m * G
    growing = j == sgn
    vb = sign * v * b
    c, s = np.cos(psi), np.sin(psi)
    aa = abs(a)
    K = Ek = D = vI = 0.0
    if growing:                   # Lambda = I: the straight rod and its deviations
        Lam = Iw
        vI = k / RF
        du = 2.0 * b * b * v * v * (1.0 - w * RD / (3.0 * RF))
        dw = -2.0 * sa * b * vI * _excess(a, b, v, w)
        u, w2 = c + du, s + dw
        x, y = 1.0 + (du * c + dw * s), du * s - dw * c
    else:
        K = rf(0.0, p, 1.0)
        Ek = K - m / 3.0 * rd(0.0, p, 1.0)
        Lam, D = (j - sgn) * K + sgn * Iw, (j - sgn) * Ek + sgn * Dp
        u, w2 = 1.0 - 2.0 * D / Lam, 2.0 * vb / Lam
        x, y = u * c + w2 * s, u * s - w2 * c
    R = EI * Lam * Lam / (L * L)
    out[0], out[1], out[2], out[3] = L * x, L * y, R * c, R * s
    out[4] = 2.0 * EI * vb * Lam / L
    if not jacobian:
        return
    q_t = 2.0 * t / ((1.0 - t) * (1.0 + t)) ** 2
    v_t = sign
    if v != 0:
        v_t = w * q_t / (2.0 * v)
    Lam_v, Lam_psi = (v * G + aa / m) / w, sa * (b * b * v / m - aa * G) / (2.0 * b)
    if growing:
        g1, g2 = p * v * v * RD / (3.0 * m * RF), p * v * RD / (3.0 * k * RF * RF)
        u_v = 2.0 * (v * p + m * v * g1 * g1 + aa * g2) / w
        u_psi = -sa * (b * vI * (1.0 - g1) + aa * b * w + m * aa * g1 * g1 / b)
        X_v = -2.0 * a * a * v * (m + b * b * w) / (m * m)
        vI_v = b * b * v / (k * RF) + k * (rd(1.0, w, X) * X_v - 2.0 * v * RD) / (6.0 * RF * RF)
        vI_psi = -vI * vI * sa * (b * b / m - aa * g1 / vI) / (2.0 * b)
        Lam_0, Lam_1 = Lam_psi, Lam_v * v_t
        u_0, u_1 = u_psi, u_v * v_t
        w2_0, w2_1 = sign * (a * vI + 2.0 * b * vI_psi), sign * 2.0 * b * vI_v * v_t
    else:
        n = j - sgn
        D_v = (v * p * (Dp - Iw) / w + aa * b * b) / m
        D_psi = sa * b * (v - aa * w * (Dp - Iw)) / (2.0 * m)
        Lam_0 = n * -a * (Ek - p * K) / (2.0 * m * b) + sgn * Lam_psi
        Lam_1 = (n * v * (Ek - p * K) / (m * w) + sgn * Lam_v) * v_t
        D_0 = n * -a * b * w * (Ek - K) / (2.0 * m) + sgn * D_psi
        D_1 = (n * v * b * b * (Ek - K) / m + sgn * D_v) * v_t
        vb_0, vb_1 = 0.5 * sign * v * a, sign * b * v_t
        u_0 = -2.0 * (D_0 * Lam - D * Lam_0) / (Lam * Lam)
        u_1 = -2.0 * (D_1 * Lam - D * Lam_1) / (Lam * Lam)
        w2_0 = 2.0 * (vb_0 * Lam - vb * Lam_0) / (Lam * Lam)
        w2_1 = 2.0 * (vb_1 * Lam - vb * Lam_1) / (Lam * Lam)
    u_0, w2_0 = u_0 + w2, w2_0 - u     # Rot(psi) and the force's direction depend on psi too
    dR0, dR1 = 2.0 * EI * Lam * Lam_0 / (L * L), 2.0 * EI * Lam * Lam_1 / (L * L)
    out[5], out[6] = L * (u_0 * c + w2_0 * s), L * (u_1 * c + w2_1 * s)
    out[7], out[8] = L * (u_0 * s - w2_0 * c), L * (u_1 * s - w2_1 * c)
    out[9], out[10] = dR0 * c - R * s, dR1 * c
    out[11], out[12] = dR0 * s + R * c, dR1 * s
    out[13] = 2.0 * EI * (0.5 * sign * v * a * Lam + vb * Lam_0) / L
    out[14] = 2.0 * EI * (sign * b * v_t * Lam + vb * Lam_1) / L


@_jit
def _rows(EI, L, psi, t, mode, jacobian, out):
    for i in range(psi.size):
        rod(EI[i], L[i], psi[i], t[i], mode[i], jacobian, out[i])


def closed_form(EI, L, psi, t, mode, *, jacobian=True) -> RegularRod:
    """``rods._regular.closed_form`` (with ``check=False``), compiled: the same
    ``rods._regular.RegularRod`` for inputs that broadcast together.

    Examples
    --------
    >>> rod = closed_form(1.0, 1.0, 2.0, 0.5, 1.0)
    >>> rod.tip.shape, rod.jacobian.shape
    ((2,), (5, 2))
    """
    if not _COMPILED["on"]:
        return numpy_closed_form(EI, L, psi, t, mode, jacobian=jacobian, check=False)
    arrays = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (EI, L, psi, t, mode)))
    shape = arrays[0].shape
    out = np.empty((arrays[0].size, _OUT))
    _rows(*(x.astype(float).reshape(-1) for x in arrays), bool(jacobian), out)
    out = out.reshape(shape + (_OUT,))
    J = out[..., 5:].reshape(shape + (5, 2)) if jacobian else None
    return RegularRod(out[..., 0:2], out[..., 2:4], out[..., 4], J)


@_jit
def _joint(EI, L, z, angles, origins, modes, load, jacobian, pinned, f, J):
    """Rows of rods clamped at ``origins`` with ``angles`` (one row of them, or one per row),
    their tips at one point: :func:`meeting` (``pinned`` False) or :func:`joined` (True)."""
    r = modes.size
    unit = EI / (L * L)
    buf, T = np.empty(_OUT), np.empty((r, 2))
    dT, dN = np.empty((r, 2, 2)), np.empty((r, 2, 2))
    step = 1
    if angles.shape[0] == 1:
        step = 0
    tips = r - 1                # equations of the tips: tip_i - tip_i+1, or tip_i - P
    if pinned:
        tips = r
    for row in range(z.shape[0]):
        nx = ny = 0.0
        for i in range(r):
            rod(EI, L, z[row, 2 * i], z[row, 2 * i + 1], modes[i], jacobian, buf)
            c, s = np.cos(angles[step * row, i]), np.sin(angles[step * row, i])
            T[i, 0] = (c * buf[0] - s * buf[1]) + origins[i, 0]
            T[i, 1] = (s * buf[0] + c * buf[1]) + origins[i, 1]
            nx += c * buf[2] - s * buf[3]
            ny += s * buf[2] + c * buf[3]
            for k in range(2):      # d (tip, force) / d (psi_i, t_i), turned by theta_i
                dT[i, 0, k] = c * buf[5 + k] - s * buf[7 + k]
                dT[i, 1, k] = s * buf[5 + k] + c * buf[7 + k]
                dN[i, 0, k] = c * buf[9 + k] - s * buf[11 + k]
                dN[i, 1, k] = s * buf[9 + k] + c * buf[11 + k]
        for i in range(tips):
            for d in range(2):
                if pinned:
                    f[row, 2 * i + d] = (T[i, d] - z[row, 2 * r + d]) / L
                else:
                    f[row, 2 * i + d] = (T[i, d] - T[i + 1, d]) / L
        f[row, 2 * tips] = (nx - load[0]) / unit
        f[row, 2 * tips + 1] = (ny - load[1]) / unit
        if not jacobian:
            continue
        for e in range(J.shape[1]):
            for col in range(J.shape[2]):
                J[row, e, col] = 0.0
        for i in range(r):
            for d in range(2):
                for k in range(2):
                    if i < tips:
                        J[row, 2 * i + d, 2 * i + k] = dT[i, d, k] / L
                    if not pinned and i > 0:
                        J[row, 2 * i - 2 + d, 2 * i + k] = -dT[i, d, k] / L
                    J[row, 2 * tips + d, 2 * i + k] = dN[i, d, k] / unit
                if pinned:
                    J[row, 2 * i + d, 2 * r + d] = -1.0 / L


def _joint_numpy(EI, L, z, angles, origins, modes, load, jacobian, pinned):
    """:func:`_joint` with numpy (the reference): ``(f, J or None)``."""
    r = len(modes)
    rod = numpy_closed_form(EI, L, z[:, 0:2 * r:2], z[:, 1:2 * r:2], modes, jacobian=jacobian,
                            check=False)
    tip, force, d_chart, _ = place_at(rod, origins, angles)
    other = z[:, None, 2 * r:] if pinned else tip[:, 1:]
    tips = r if pinned else r - 1
    f = np.concatenate(((tip[:, :tips] - other).reshape(len(z), -1) / L,
                        (force.sum(axis=1) - load) / (EI / L ** 2)), axis=-1)
    if not jacobian:
        return f, None
    J = np.zeros(f.shape + f.shape[-1:])
    for i in range(r):
        cols = slice(2 * i, 2 * i + 2)
        if i < tips:
            J[:, 2 * i:2 * i + 2, cols] = d_chart[:, i, :2] / L
        if not pinned and i > 0:
            J[:, 2 * i - 2:2 * i, cols] = -d_chart[:, i, :2] / L
        J[:, 2 * tips:, cols] = d_chart[:, i, 2:] / (EI / L ** 2)
        if pinned:
            J[:, 2 * i:2 * i + 2, 2 * r:] = -np.eye(2) / L
    return f, J


def _joint_call(EI, L, origins, angles, modes, load, z, jacobian, pinned):
    z = np.ascontiguousarray(z, dtype=float)
    angles = np.ascontiguousarray(np.reshape(angles, (-1, len(modes))), dtype=float)
    if not _COMPILED["on"]:
        return _joint_numpy(EI, L, z, angles, origins, modes, load, jacobian, pinned)
    f = np.empty((len(z), 2 * len(modes) + 2 * pinned))
    J = np.empty(f.shape + f.shape[-1:]) if jacobian else np.empty((0, 0, 0))
    _joint(float(EI), float(L), z, angles, np.ascontiguousarray(origins, dtype=float),
           np.ascontiguousarray(modes, dtype=float), np.ascontiguousarray(load, dtype=float),
           bool(jacobian), pinned, f, J)
    return f, (J if jacobian else None)


def meeting(EI, L, origins, angles, modes, load, z, *, jacobian=True):
    """Rods clamped at ``origins`` (r, 2) at ``angles`` ((r,), or (batch, r): one row per
    system) whose tips meet at one point under the ``load`` (2,) there: the residual of the
    chart points ``z`` (batch, 2 r) and its Jacobian.

    ``f = ((tip_1 - tip_2) / L, ..., (tip_{r-1} - tip_r) / L, (n_1 + ... + n_r - load) L**2 /
    EI)``, the direct problem of a mechanism whose rods hold a load at their joined tips (the
    2RFR's :func:`~mechnum.mechanisms.rfr2.forward_system`).

    Returns
    -------
    f : ndarray, shape (batch, 2 r)
    J : ndarray, shape (batch, 2 r, 2 r), or None without ``jacobian``

    Examples
    --------
    >>> z = np.array([[1.0, 0.5, 2.0, -0.5]])
    >>> f, J = meeting(1.0, 1.0, [[-0.3, 0.0], [0.3, 0.0]], [0.7, 1.0], [1.0, 1.0],
    ...                [0.3, -0.1], z)
    >>> with reference():
    ...     g, K = meeting(1.0, 1.0, [[-0.3, 0.0], [0.3, 0.0]], [0.7, 1.0], [1.0, 1.0],
    ...                    [0.3, -0.1], z)
    >>> bool(np.allclose(f, g, rtol=1e-13, atol=1e-15)), J.shape
    (True, (1, 4, 4))
    """
    return _joint_call(EI, L, origins, angles, modes, load, z, jacobian, False)


def joined(EI, L, origins, angles, modes, load, u, *, jacobian=True):
    """The rods of :func:`meeting` with their joint ``P`` an unknown too: the residual of
    ``u = (z, P)`` (batch, 2 r + 2), ``G = ((tip_1 - P) / L, ..., (tip_r - P) / L,
    (n_1 + ... + n_r - load) L**2 / EI)``, and its Jacobian in ``u`` (the system that
    continuation follows as the angles change, the 2RFR's
    ``full_system`` of the 2RFR in the chart and ``P``).

    Returns
    -------
    G : ndarray, shape (batch, 2 r + 2)
    D : ndarray, shape (batch, 2 r + 2, 2 r + 2), or None without ``jacobian``

    Examples
    --------
    The joint at the tip of the first rod: its rows of ``G`` vanish.

    >>> origins, z = [[-0.3, 0.0], [0.3, 0.0]], np.array([[1.0, 0.5, 2.0, -0.5]])
    >>> tip = closed_form(1.0, 1.0, 1.0, 0.5, 1.0).tip        # rod 1 at the angle 0
    >>> u = np.concatenate((z, [tip + [-0.3, 0.0]]), axis=1)
    >>> G, D = joined(1.0, 1.0, origins, [0.0, 1.0], [1.0, 1.0], [0.0, 0.0], u)
    >>> bool(np.abs(G[0, :2]).max() < 1e-15), D.shape
    (True, (1, 6, 6))
    """
    return _joint_call(EI, L, origins, angles, modes, load, u, jacobian, True)


@_jit
def _starts(X, Y, n0, n1, tol, maxiter, halvings, jacobian, out):
    """For each point ``(X, Y)``: damped Newton (Armijo's rule, ``halvings`` halvings at most)
    on ``tip(n) = (X, Y)`` for the force ``n`` of the growing-branch rod of mode 1 (``EI = L
    = 1``), from ``(n0, n1)``, to the residual ``tol``; ``(m0, n_x, n_y)`` of its last (and
    best) iterate into ``out``. Each trial force's rod comes from the chart: ``psi`` its
    direction, ``t`` on the branch (``sign(t) = sign(cos(psi / 2))``) solved from ``lambda L
    = |n|**(1/2)`` by Newton safeguarded with bisection, from the last ``t``. (One loop: each
    function that calls :func:`rod` compiles it anew; ``jacobian``, always True, is a flag
    rather than a constant so that it is compiled once for every caller.)"""
    rod_, best = np.empty(_OUT), np.empty(_OUT)
    for i in range(X.size):
        t, r, d0, d1, nx, ny = 0.5, np.inf, 0.0, 0.0, n0[i], n1[i]
        alpha, tries, steps = 1.0, 0, 0
        while True:        # each pass: the rod of one trial force n + alpha d (d = 0 first)
            mx, my = nx + alpha * d0, ny + alpha * d1
            psi = np.arctan2(my, mx)
            psi = min(psi + 2.0 * np.pi if psi <= 0.0 else psi,
                      2.0 * np.pi * (1.0 - 2.0 * _EPS))          # pure tension: the edge
            side = 1.0 if np.cos(0.5 * psi) >= 0.0 else -1.0
            lam, lo, hi = np.sqrt(np.hypot(mx, my)), 0.0, _T_MAX
            s = min(max(t, 1e-300), hi)
            for _ in range(100):
                rod(1.0, 1.0, psi, side * s, 1.0, jacobian, rod_)
                R = np.hypot(rod_[2], rod_[3])
                gap = np.sqrt(R) - lam
                if gap < 0.0:
                    lo = s
                else:
                    hi = s
                if abs(gap) <= 8.0 * _EPS * lam or hi - lo <= 8.0 * _EPS * hi:
                    break
                slope = side * (rod_[10] * rod_[2] + rod_[12] * rod_[3]) / (2.0 * R * np.sqrt(R))
                s = s - gap / slope
                if not lo < s < hi:
                    s = 0.5 * (lo + hi)
            r_trial = np.hypot(rod_[0] - X[i], rod_[1] - Y[i])
            if r_trial <= (1.0 - 1e-4 * alpha) * r or steps == 0:       # Armijo's rule
                nx, ny, t, r = mx, my, s, r_trial
                for k in range(_OUT):
                    best[k] = rod_[k]
                if r <= tol or steps == maxiter:
                    break
                # d tip / d n = (d tip / d z) (d n / d z)**-1: the step is -(d n / d z) w
                # with (d tip / d z) w = tip - point
                a, b, c, d = best[5], best[6], best[7], best[8]
                det = a * d - b * c
                if not (abs(det) > 0.0 and np.isfinite(det)):
                    break
                fx, fy = best[0] - X[i], best[1] - Y[i]
                w0, w1 = (d * fx - b * fy) / det, (a * fy - c * fx) / det
                d0, d1 = -(best[9] * w0 + best[10] * w1), -(best[11] * w0 + best[12] * w1)
                alpha, tries, steps = 1.0, 0, steps + 1
            elif tries == halvings:
                break
            else:
                alpha, tries = 0.5 * alpha, tries + 1
        out[i, 0], out[i, 1], out[i, 2] = best[4], best[2], best[3]


def pinned_starts(points, forces, *, tol, maxiter, halvings):
    """The growing-branch cantilevers of mode 1 (``EI = L = 1``) whose tips reach ``points``
    (batch, 2), in the clamp's frame: damped Newton in the tip force from ``forces`` (batch, 2)
    (its Jacobian from the regular chart's), to the residual ``tol``; ``(m0, n_x, n_y)`` of
    each (batch, 3), of the last iterate where Newton stops short (the start of
    ``rods._pinned.pinned_start``, which scales and turns them).

    Examples
    --------
    >>> from mechnum.rods._growing import growing_rod
    >>> tip = growing_rod(1.0, 1.0, [0.0, 1.0]).tip     # P L**2 / EI = 1, transverse
    >>> start = pinned_starts(tip[None], np.array([[0.0, 0.9]]), tol=1e-9, maxiter=60,
    ...                       halvings=20)
    >>> (np.round(start, 6) + 0.0).tolist()
    [[0.943567, 0.0, 1.0]]
    """
    points, forces = (np.ascontiguousarray(x, dtype=float) for x in (points, forces))
    out = np.empty((len(points), 3))
    _starts(points[:, 0].copy(), points[:, 1].copy(), forces[:, 0].copy(), forces[:, 1].copy(),
            float(tol), int(maxiter), int(halvings), True, out)
    return out
