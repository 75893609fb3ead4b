"""The 3PRR's direct problem (inputs -> poses), for one input or a batch of thousands at once."""

from dataclasses import dataclass

import numpy as np

from mechnum import _validate
from mechnum.mechanisms.prr3.elimination import coefficients, deflate
from mechnum.mechanisms.prr3.geometry import (SINGULAR_DET, _direct_jacobian, _jacobian_dets,
                                              _loop_residuals, _sliders, vectors)
from mechnum.newton import solve_batch
from mechnum.polynomials import roots

# A root is real when |Im psi| <= 1e-4 rad: round-off splits a double real root (a direct
# singularity) into a complex pair whose imaginary parts reach about sqrt(eps) kappa, up to
# 1e-6 here; the residual test below then rejects pairs that are truly complex.
IMAG_TOL = 1e-4
# A pose is accepted when it closes the three loops to 1e-6 L^2: a root taken real with
# |Im psi| <= 1e-4 closes them to about (1e-4)^2 = 1e-8, a spurious candidate misses by O(1).
RESIDUAL_TOL = 1e-6
# The sextic's degree: no input has more poses.
MAX_POSES = 6
# Poses closer than 1e-4 (in L and in radians) are one solution: the two ends of a double
# root blurred by round-off, as IMAG_TOL takes them.
SAME_POSE = 1e-4
# Candidates whose residual (relative to L^2) lies between these are polished by Newton:
# above _EXACT (16 units of round-off) the pose may lie residual / sigma_min(J) from the root,
# 1e-8 near a multiple root; above _CANDIDATE it is no root at all.
_EXACT, _CANDIDATE = 16 * np.finfo(float).eps, 1e-2
# Below this dimensionless determinant Cramer's rule would lose 9 of the 16 digits: the
# intersection of two circles gives the point instead.
_CRAMER_DET = 1e-9
# Polishing stops at a residual of _EXACT, after at most 6 Newton steps (quadratic convergence
# from 1e-2 needs 4); a pose that moves by more than 1e-2 went to another root: not polished.
_POLISH_STEPS, _POLISH_MOVE = 6, 1e-2
# An end coefficient of the sextic below eps^2 times the largest is raised to that: a double
# root at infinity (psi = pi) then lands within 2 sqrt(eps^2) = 2 eps of pi (eps alone would
# put it 1e-7 away), and the other roots move by round-off only.
_NEGLIGIBLE = np.finfo(float).eps ** 2
# An angle within 1e-12 rad below 2 pi is 0 (the roots are not that accurate, and psi = 0
# reads better than 6.283185307179585).
_FULL_TURN = 1e-12
# A sextic whose coefficients are all below 1e-13 of the size its terms can reach (lengths up
# to 1 + the sliders' spread, to the 8th power) vanishes identically but for round-off.
_CONTINUUM = 1e-13
# Sliders farther apart than 2 L + a cannot be joined: |C_i - C_j| <= |C_i - P_i| + |P_i - P_j|
# + |P_j - C_j| = L + a + L. The margin of 1e-12 keeps a pose with straight legs.
_REACH_MARGIN = 1e-12


@dataclass(frozen=True)
class DirectSolution:
    """The poses of the direct problem, with a report on each.

    Attributes
    ----------
    poses : ndarray, shape (n, 3)
        ``(x, y, psi)``, ``psi`` in ``[0, 2 pi)``; grouped by input, sorted by ``psi``.
    input_index : ndarray of int, shape (n,)
        The input (row of the batch) of each pose; all 0 for one input.
    counts : ndarray of int, shape of the batch
        The number of poses of each input (a 0-d array for one input).
    continuum : ndarray of bool, shape of the batch
        Inputs whose polynomial vanishes identically: the platform moves with the inputs
        locked (a self-motion, as when two sliders coincide), a continuum of poses and no
        isolated one; their count is 0.
    residuals : ndarray, shape (n,)
        ``max |loop_residuals| / L**2`` of each pose.
    elimination_det : ndarray, shape (n,)
        Dimensionless determinant of the two radical-axis equations at the pose's ``psi``,
        proportional to the study's denominator ``D`` (equation 76). Where it vanishes the
        elimination, not the mechanism, is singular: the pose then comes from intersecting two
        of the legs' circles instead of from ``x = N_x / D``.
    jacobian_det : ndarray, shape (n,)
        Determinant of the dimensionless direct Jacobian (:func:`jacobian_dets`): zero at a
        direct (type II) singularity.
    inverse_det : ndarray, shape (n,)
        Determinant of the dimensionless inverse Jacobian: zero at an inverse (type I)
        singularity, a leg tangent to its guide.
    """

    poses: np.ndarray
    input_index: np.ndarray
    counts: np.ndarray
    continuum: np.ndarray
    residuals: np.ndarray
    elimination_det: np.ndarray
    jacobian_det: np.ndarray
    inverse_det: np.ndarray

    @property
    def singular(self):
        """Poses at a direct singularity of the mechanism (``|jacobian_det| < 1e-6``)."""
        return np.abs(self.jacobian_det) < SINGULAR_DET

    @property
    def elimination_singular(self):
        """Poses where the study's back-substitution fails (``|elimination_det| < 1e-6``)."""
        return np.abs(self.elimination_det) < SINGULAR_DET


def _centres(psi, c, A):
    """Centres, in the plane of ``P``, of the three unit circles that ``P`` lies on, for
    sliders ``c`` (shape ``(..., 3, 2)``) and platform side ``A``, both in units of ``L``."""
    shifts = [np.zeros(psi.shape + (2,)),
              A * np.stack([np.cos(psi), np.sin(psi)], -1),
              A * np.stack([np.cos(psi + np.pi / 3), np.sin(psi + np.pi / 3)], -1)]
    return c - np.stack(shifts, axis=-2)


def _radical_axes(centres):
    """The radical-axis equations ``A P = b`` of three unit circles, and ``det A`` scaled to
    be dimensionless (``det A / max(|A|, 1)^2``)."""
    A = centres[..., 1:, :] - centres[..., :1, :]
    b = (np.sum(centres[..., 1:, :] ** 2, -1) - np.sum(centres[..., :1, :] ** 2, -1)) / 2
    det = A[..., 0, 0] * A[..., 1, 1] - A[..., 0, 1] * A[..., 1, 0]
    return A, b, det, det / np.maximum(np.abs(A).max(axis=(-2, -1)), 1.0) ** 2


def _candidates(psi, c, A):
    """Candidate positions of ``P`` (units of ``L``) for each angle, shape ``(..., 3, 2)``.

    Candidate 0 solves the two radical-axis equations (the study's equations 146-147), unless
    their dimensionless determinant is below :data:`_CRAMER_DET` (then it is NaN); candidates
    1 and 2 are the intersections of the two circles whose centres are farthest apart, which
    still works where the radical axes are parallel (the study's "singular position"). The
    caller keeps those that close all three loops. The dimensionless determinant is returned too.
    """
    centres = _centres(psi, c, A)
    M, b, det, scaled = _radical_axes(centres)
    det = np.where(np.abs(scaled) <= _CRAMER_DET, np.nan, det)
    linear = np.stack([b[..., 0] * M[..., 1, 1] - b[..., 1] * M[..., 0, 1],  # Cramer's rule
                       M[..., 0, 0] * b[..., 1] - M[..., 1, 0] * b[..., 0]], -1) / det[..., None]
    pairs = np.array([[0, 1], [0, 2], [1, 2]])
    gaps = centres[..., pairs[:, 1], :] - centres[..., pairs[:, 0], :]
    best = np.argmax(np.sum(gaps ** 2, -1), axis=-1)[..., None, None]
    d = np.take_along_axis(gaps, best, axis=-2)[..., 0, :]
    start = np.take_along_axis(centres, pairs[:, 0][best], axis=-2)[..., 0, :]
    half = np.linalg.norm(d, axis=-1) / 2
    h = np.sqrt(np.maximum(1.0 - half ** 2, 0.0)) / np.maximum(2 * half, np.finfo(float).tiny)
    normal = np.stack([-d[..., 1], d[..., 0]], -1) * h[..., None]
    mid = start + d / 2
    return np.stack([linear, mid + normal, mid - normal], axis=-2), scaled


def _wrap(psi):
    """Angles in ``[0, 2 pi)``; those within :data:`_FULL_TURN` below ``2 pi`` become 0."""
    psi = np.mod(psi, 2 * np.pi)
    return np.where(psi >= 2 * np.pi - _FULL_TURN, 0.0, psi)


def _residual_norms(poses, lambdas, geometry):
    """``max_i |F_i| / L**2`` of each pose (``inf`` for a NaN candidate)."""
    res = np.abs(_loop_residuals(poses, lambdas, geometry)).max(axis=-1) / geometry.L ** 2
    return np.where(np.isnan(res), np.inf, res)


def _polish(poses, lambdas, geometry):
    """A few Newton steps on the loop equations from each pose (shape ``(k, 3)``, inputs
    broadcast). A pose that moves by more than ``_POLISH_MOVE`` (relative), or whose system
    does not converge (a singular Jacobian: a pose at a direct singularity), is returned
    unchanged."""
    L2 = geometry.L ** 2  # the equations relative to L^2: no overflow at any scale
    result = solve_batch(lambda p: _loop_residuals(p, lambdas, geometry) / L2, poses,
                         lambda p: _direct_jacobian(p, lambdas, geometry) / L2, tol=_EXACT,
                         criterion="residual", maxiter=_POLISH_STEPS, raise_on_failure=False)
    moved = np.hypot(*(result.x - poses)[:, :2].T) / geometry.L + np.abs(result.x - poses)[:, 2]
    keep = (moved <= _POLISH_MOVE) & (result.status != "singular") & \
        (result.status != "non-finite")
    return np.where(keep[:, None], result.x, poses)


def direct(lambdas, geometry, *, imag_tol=IMAG_TOL, residual_tol=RESIDUAL_TOL):
    """Every pose of the mechanism for inputs ``lambdas``: the study's polynomial, robustly.

    For one input or a batch (shape ``(m, 3)``, processed with no Python loop over inputs):

    1. Sliders farther apart than ``2 L + a`` cannot be joined: no pose.
    2. The degree-8 polynomial of :func:`polynomial` is built in a frame centred on slider 1,
       in units of ``max(L, a)`` (the poses do not depend on the frame, the coefficients then
       stay of order 1), and divided by its factor ``1 + t^2`` (roots ``t = +-i`` for every
       input, never poses).
    3. The sextic's roots are the eigenvalues of its companion matrix
       (:func:`mechnum.polynomials.roots`, one call for the whole batch), as ``np.roots`` does.
       A vanishing leading coefficient means a root at ``t = infinity``, ``psi = pi`` (the
       substitution's blind spot, where the study's code loses the pose): it is replaced by
       ``eps`` times the largest coefficient, which puts that root near ``psi = pi``.
    4. A root is real when ``|Im psi| <= imag_tol``. Each real ``psi`` gives three candidate
       points: the radical-axis solution (146-147), unless its determinant ``D`` vanishes (the
       study's "singular position", equation 76), and the two intersections of the two legs'
       circles whose centres are farthest apart.
    5. The candidates that close the three loops to ``residual_tol * L**2`` are the poses;
       poses within :data:`SAME_POSE` count as one (a double root finds the same pose twice).
       Candidates that miss by ``4e-15`` to ``1e-2`` get a few Newton steps first: a root of
       multiplicity ``m`` moves by about ``eps**(1/m)`` under round-off (:func:`root_condition`),
       so a double root is only good to about ``1e-8``; Newton cannot sharpen a pose *at* a
       direct singularity (two assembly modes meeting), where its Jacobian is singular.

    Parameters
    ----------
    lambdas : array_like, shape (3,) or (m, 3)
        The inputs ``(lambda1, lambda2, lambda3)``, metres; an empty batch is valid.
    geometry : ~mechnum.mechanisms.prr3.geometry.Geometry
    imag_tol : float, optional
        Largest ``|Im psi|`` (radians) of a root taken as real (:data:`IMAG_TOL`).
    residual_tol : float, optional
        Relative tolerance of the loop residual of an accepted pose (:data:`RESIDUAL_TOL`).

    Returns
    -------
    DirectSolution
        ``poses`` of shape ``(n, 3)`` with ``n`` from 0 to 6 per input.

    Raises
    ------
    ValueError
        If ``lambdas`` is not finite with last axis 3 (or has more than 2 dimensions), or a
        tolerance is not a positive number.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> sol = direct([0.4, 0.1, 0.6], g)
    >>> sol.poses[:, :2].round(5).tolist(), np.degrees(sol.poses[:, 2]).round(4).tolist()
    ([[1.23123, 0.55593], [1.05352, 0.7569]], [9.9967, 341.5164])
    >>> direct([[0.4, 0.1, 0.6], [1e100, 0.1, 0.6]], g).counts.tolist()
    [2, 0]
    """
    lam = vectors(lambdas, "lambdas")
    if lam.ndim > 2:
        raise ValueError(f"lambdas must have shape (3,) or (m, 3), got shape {lam.shape}")
    imag_tol = _validate.tolerance(imag_tol, "imag_tol")
    residual_tol = _validate.tolerance(residual_tol, "residual_tol")
    batch = lam.reshape(-1, 3)
    c = _sliders(batch, geometry)
    with np.errstate(over="ignore", invalid="ignore"):
        spread = np.linalg.norm(c[:, :, None] - c[:, None], axis=-1).max(axis=(1, 2))
    reach = (2 * geometry.L + geometry.a) * (1 + _REACH_MARGIN)
    rows = np.flatnonzero(spread <= reach)
    scale = max(geometry.L, geometry.a)
    local = (c[rows] - c[rows, :1]) / scale  # slider 1 at the origin, unit size
    A, ell = geometry.a / scale, geometry.L / scale
    sextic = deflate(coefficients(0.0, local[:, 1, 0], local[:, 2, 0], local[:, 2, 1], A, ell))
    size = _CONTINUUM * (1 + np.abs(local).max(axis=(1, 2), initial=0.0)) ** 8
    continuum = np.zeros(len(batch), dtype=bool)
    continuum[rows] = np.abs(sextic).max(axis=1, initial=0.0) <= size
    sextic[continuum[rows]] = 0.0  # no isolated root: _angles gives NaN
    psi = _angles(sextic)  # (k, 6)
    real = np.abs(psi.imag) <= imag_tol
    root_row = np.nonzero(real)[0]  # the input of each real root, flattened
    psi = _wrap(psi[real].real)
    points, elimination = _candidates(psi, local[root_row] / ell, A / ell)
    points = points * geometry.L + c[rows[root_row], None, 0, :]  # back to the fixed frame
    flat = np.concatenate([points, np.broadcast_to(psi[:, None, None], (len(psi), 3, 1))], -1)
    own = batch[rows[root_row], None, :]
    flat_res = _residual_norms(flat, own, geometry)
    # Each root keeps its best candidate; all three only where the elimination is singular (to
    # the angle's uncertainty, IMAG_TOL): there alone can two poses share an angle. The others
    # are copies of the best or miss; polishing them could land on a neighbouring root's pose.
    kept = (np.arange(3) == np.argmin(flat_res, axis=1)[:, None]) | \
        (np.abs(elimination) <= IMAG_TOL)[:, None]
    near = kept & (flat_res > _EXACT) & (flat_res < _CANDIDATE)
    if near.any():  # roots blurred by round-off or a multiple root: polish on the loop equations
        which = np.nonzero(near)
        polished = _polish(flat[which], own[which[0], 0], geometry)
        polished[:, 2] = _wrap(polished[:, 2])
        flat[which] = polished
        flat_res[which] = _residual_norms(polished, own[which[0], 0], geometry)
    valid = kept & (flat_res <= residual_tol)
    found, res, index = flat[valid], flat_res[valid], rows[root_row][np.nonzero(valid)[0]]
    keep = _distinct(found, res, index, geometry.L)
    order = np.lexsort((found[keep, 2], index[keep]))
    found, res, index = found[keep][order], res[keep][order], index[keep][order]
    inverse_det, jacobian_det = _jacobian_dets(found, batch[index], geometry)
    psi_found = found[:, 2]
    centres = _centres(psi_found, _sliders(batch[index], geometry) / geometry.L,
                       geometry.a / geometry.L)
    counts = np.bincount(index, minlength=len(batch)).reshape(lam.shape[:-1])
    return DirectSolution(found, index, counts, continuum.reshape(lam.shape[:-1]), res,
                          _radical_axes(centres)[3], jacobian_det, inverse_det)


def _angles(sextic):
    """The six roots of each sextic as complex angles ``psi = 2 atan(t)``, shape ``(k, 6)``.

    Each sextic is solved in ``t`` or, where its constant term is the larger end coefficient,
    in ``u = 1/t = cot(psi/2)`` (the reversed polynomial, ``psi = pi - 2 atan(u)``), so the
    companion matrix is normalised by the larger of the two and a root at ``t = infinity``
    (``psi = pi``, a zero leading coefficient) is the accurate root ``u = 0``. An end
    coefficient below :data:`_NEGLIGIBLE` times the largest is raised to it (both ends
    vanish only for roots at ``psi = 0`` and ``pi`` at once); a polynomial that vanishes
    identically (a continuum of poses, no isolated one) gives NaN, and so does a root
    ``t = +-i`` (``1 + t**2`` a factor: complex, no pose), where ``atan`` has its poles.
    """
    largest = np.abs(sextic).max(axis=-1, initial=0.0)
    reverse = np.abs(sextic[:, 0]) > np.abs(sextic[:, 6])
    c = np.where(reverse[:, None], sextic[:, ::-1], sextic)
    floor = _NEGLIGIBLE * largest
    c[:, 6] = np.where(np.abs(c[:, 6]) < floor, np.where(c[:, 6] < 0, -floor, floor), c[:, 6])
    out = np.full(c.shape[:-1] + (6,), np.nan + 0j)
    ok = largest > 0
    if ok.any():
        z = roots(c[ok])
        with np.errstate(divide="ignore", invalid="ignore"):  # t = +-i: no pose, psi infinite
            out[ok] = np.where(reverse[ok, None], np.pi - 2 * np.arctan(z), 2 * np.arctan(z))
    return out


def _distinct(poses, residuals, groups, L):
    """Which of the poses (shape ``(n, 3)``) to keep: all but those within :data:`SAME_POSE` of
    a pose of the same group (input) with a smaller residual, and at most the best
    :data:`MAX_POSES` of a group (near a singularity, blurred copies of a pose can lie
    farther apart than SAME_POSE; the sextic has no more roots)."""
    order = np.lexsort((residuals, groups))
    ranked, group = poses[order], groups[order]
    duplicate = np.zeros(len(order), dtype=bool)
    for shift in range(1, int(np.bincount(groups).max(initial=0))):  # earlier in the group
        delta = ranked[shift:] - ranked[:-shift]
        gap = (np.hypot(delta[:, 0], delta[:, 1]) / L
               + np.abs(np.mod(delta[:, 2] + np.pi, 2 * np.pi) - np.pi))
        duplicate[shift:] |= (gap <= SAME_POSE) & (group[shift:] == group[:-shift])
    kept = ~duplicate
    count = np.cumsum(kept)
    first = np.r_[True, group[1:] != group[:-1]][:len(group)]  # where each group starts
    before = np.maximum.accumulate(np.where(first, count - kept, 0))  # kept in earlier groups
    rank = count - before - 1  # rank of each kept pose in its group, by residual
    keep = np.empty_like(duplicate)
    keep[order] = kept & (rank < MAX_POSES)
    return keep


def direct_by_newton(lambdas, geometry, starts, *, tol=1e-12):
    """The distinct poses that Newton-Raphson reaches from many starting poses.

    Each start is iterated on the loop equations (:func:`loop_residuals`, with the analytic
    :func:`direct_jacobian`) by :func:`mechnum.newton.solve_batch`; the starts whose status is
    not "converged" (50 steps, a singular Jacobian) are ignored. It finds only the solutions
    whose basins the starts hit: a check on :func:`direct`, not a replacement.

    Parameters
    ----------
    lambdas : array_like, shape (3,)
    geometry : ~mechnum.mechanisms.prr3.geometry.Geometry
    starts : array_like, shape (m, 3)
        Starting poses ``(x, y, psi)``; an empty batch gives no pose.
    tol : float, optional
        Newton's step tolerance.

    Returns
    -------
    ndarray, shape (n, 3)
        The distinct converged poses, ``psi`` in ``[0, 2 pi)``, sorted by ``psi``.

    Raises
    ------
    ValueError
        If ``lambdas`` or ``starts`` are ill-shaped or not finite, or ``tol`` not positive.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8)
    >>> starts = [[2.0, 1.0, 6.0], [1.5, 1.0, 0.2]]
    >>> direct_by_newton([2, 0.5, 0.2], g, starts)[:, 2].round(4).tolist()
    [0.1251, 6.0322]
    """
    lam = _validate.array(lambdas, "lambdas", shape=(3,))
    starts = _validate.array(starts, "starts", shape=(None, 3))
    tol = _validate.tolerance(tol)
    if len(starts) == 0:
        return np.empty((0, 3))
    result = solve_batch(lambda p: _loop_residuals(p, lam, geometry), starts,
                         lambda p: _direct_jacobian(p, lam, geometry), tol=tol,
                         raise_on_failure=False)
    poses = result.x[result.converged]
    poses[:, 2] = _wrap(poses[:, 2])
    keep = _distinct(poses, _residual_norms(poses, lam, geometry), np.zeros(len(poses), int),
                     geometry.L)
    poses = poses[keep]
    return poses[np.argsort(poses[:, 2])]
