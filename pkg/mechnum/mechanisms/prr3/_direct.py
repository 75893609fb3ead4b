"""The 3PRR's forward (direct) problem, inputs -> poses, for one input or thousands at once.

:func:`forward` finds every pose from the study's polynomial; :func:`forward_by_newton` runs
Newton from many seeds, as a check.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.mechanisms.prr3 import _kernels as kernels
from mechnum.mechanisms.prr3._elimination import sextic
from mechnum.mechanisms.prr3._geometry import SINGULAR_DET, Geometry, check, vectors
from mechnum.newton import solve_batch
from mechnum.polynomials import roots
from mechnum.results import Result

# A root is real when |Im psi| <= 1e-4 rad: round-off splits a double real root (a direct
# singularity) into a complex pair whose imaginary parts reach about sqrt(eps) kappa, up to
# 1e-6 here; the residual test below then rejects pairs that are truly complex.
IMAG_TOL = 1e-4
# A pose is accepted when it closes the three loops to 1e-6 L^2: a root taken real with
# |Im psi| <= 1e-4 closes them to about (1e-4)^2 = 1e-8, a spurious candidate misses by O(1).
RESIDUAL_TOL = 1e-6
# The sextic's degree: no input has more poses.
MAX_POSES = 6
MAX_INPUTS = 1_000_000
"""The most inputs of one call of :func:`forward`, or seeds of :func:`forward_by_newton` (the
forward problem holds some 2 kB per input while it works: 2 GB for the most)."""
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
# Polishing starts with one Newton step on every candidate at once. From a simple root's
# candidate (an error near 1e-13, from the companion matrix's eigenvalues) the step is that
# error and the pose is then exact to round-off; a step above 1e-10 (relative) is a multiple
# root's, where Newton converges only linearly: those candidates go on (solve_batch).
_SIMPLE_STEP = 1e-10
# A Jacobian whose determinant is below 1e-14 times its largest entry cubed is singular to
# working precision (its condition number above about 1e14): no step is taken from there.
_SINGULAR_STEP = 1e-14
# An end coefficient of the sextic below eps^2 times the largest is raised to that: a double
# root at infinity (psi = pi) then lands within 2 sqrt(eps^2) = 2 eps of pi (eps alone would
# put it 1e-7 away), and the other roots move by round-off only.
_NEGLIGIBLE = np.finfo(float).eps ** 2
# The sixth of a turn between the platform's sides P1 P2 and P1 P3, and the pairs of circles.
_SIXTH_TURN = np.exp(1j * np.pi / 3)
_PAIRS = np.array([[0, 1], [0, 2], [1, 2]])
# An angle within 1e-12 rad below 2 pi is 0 (the roots are not that accurate, and psi = 0
# reads better than 6.283185307179585).
_FULL_TURN = 1e-12
# A sextic whose coefficients are all below 1e-13 of the size its terms can reach (lengths up
# to 1 + the sliders' spread, to the 8th power) vanishes identically but for round-off.
_CONTINUUM = 1e-13
# Sliders farther apart than 2 L + a cannot be joined: |C_i - C_j| <= |C_i - P_i| + |P_i - P_j|
# + |P_j - C_j| = L + a + L. The margin of 1e-12 keeps a pose with straight legs.
_REACH_MARGIN = 1e-12


@dataclass(frozen=True, kw_only=True)
class DirectSolution(Result):
    """The poses of the direct problem, with a report on each.

    Attributes
    ----------
    x : ndarray, shape (n, 3)
        The poses ``(x, y, psi)``, ``psi`` in ``[0, 2 pi)``; grouped by input, sorted by
        ``psi``.
    status : str or ndarray of str, shape of the batch
        ``"converged"`` for an input whose poses are all found (possibly none: the sliders
        too far apart); ``"singular"`` for an input whose polynomial vanishes identically:
        the platform moves with the inputs locked (a self-motion, as when two sliders
        coincide), a continuum of poses and no isolated one, its count 0.
    message : str
        How many poses, and how many inputs have a continuum.
    iterations, nfev, njev : int
        Zero: the roots of a polynomial (a few Newton steps polish the roots that round-off
        blurs).
    input_index : ndarray of int, shape (n,)
        The input (row of the batch) of each pose; all 0 for one input.
    counts : ndarray of int, shape of the batch
        The number of poses of each input (a 0-d array for one input).
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

    input_index: np.ndarray
    counts: np.ndarray
    residuals: np.ndarray
    elimination_det: np.ndarray
    jacobian_det: np.ndarray
    inverse_det: np.ndarray

    @property
    def singular(self) -> np.ndarray:
        """Poses at a direct singularity of the mechanism (``|jacobian_det| < 1e-6``)."""
        return np.abs(self.jacobian_det) < SINGULAR_DET

    @property
    def elimination_singular(self) -> np.ndarray:
        """Poses where the study's back-substitution fails (``|elimination_det| < 1e-6``)."""
        return np.abs(self.elimination_det) < SINGULAR_DET


def _radical_axes(psi, sliders, A):
    """The centres of the three unit circles that ``P`` lies on (complex, units of ``L``), the
    radical axes' normals ``d_j = centre_j - centre_0``, their determinant, and that
    determinant made dimensionless (``det / max(|d|, 1)^2``)."""
    turn = A * np.exp(1j * psi)
    centres = sliders.copy()
    centres[:, 1] -= turn
    centres[:, 2] -= turn * _SIXTH_TURN
    d = centres[:, 1:] - centres[:, :1]  # the radical axes: Re(conj(d_j) P) = b_j
    det = d[:, 0].real * d[:, 1].imag - d[:, 0].imag * d[:, 1].real
    scaled = det / np.maximum(np.maximum(np.abs(d.real), np.abs(d.imag)).max(axis=-1), 1.0) ** 2
    return centres, d, det, scaled


def _candidates(psi, sliders, A):
    """Candidate positions of ``P`` for each angle ``psi``, their residuals, and the
    dimensionless determinant of the radical-axis equations (``det / max(|d|, 1)^2``).

    Points are complex numbers here, in units of ``L`` (``sliders``: shape ``(r, 3)``, ``A``:
    the platform's side). ``P`` lies on three unit circles, centred at the sliders moved back
    by the platform's sides (at ``psi`` and ``psi + pi/3``). Candidate 0 solves their two
    radical-axis equations (the study's equations 146-147) by Cramer's rule, unless the
    dimensionless determinant is below :data:`_CRAMER_DET` (then it is NaN); candidates 1 and 2
    are the intersections of the two circles whose centres are farthest apart, which still
    works where the radical axes are parallel (the study's "singular position"). The residual
    of a candidate is ``max_i | |P - centre_i|^2 - 1 |`` (``inf`` for NaN): the loop equations
    relative to ``L^2``.
    """
    centres, d, det, scaled = _radical_axes(psi, sliders, A)
    square = centres.real ** 2 + centres.imag ** 2
    b = (square[:, 1:] - square[:, :1]) / 2
    points = np.empty((len(psi), 3), dtype=complex)
    points[:, 0] = 1j * (b[:, 1] * d[:, 0] - b[:, 0] * d[:, 1]) / np.where(
        np.abs(scaled) <= _CRAMER_DET, np.nan, det)
    gaps = centres[:, _PAIRS[:, 1]] - centres[:, _PAIRS[:, 0]]
    best = np.argmax(np.abs(gaps), axis=-1)
    rows = np.arange(len(psi))
    gap = gaps[rows, best]
    half = np.abs(gap) / 2
    h = np.sqrt(np.maximum(1.0 - half ** 2, 0.0)) / np.maximum(2 * half, np.finfo(float).tiny)
    points[:, 1] = centres[rows, _PAIRS[best, 0]] + gap / 2
    points[:, 2] = points[:, 1] - 1j * h * gap
    points[:, 1] += 1j * h * gap
    residuals = np.abs(np.abs(points[:, :, None] - centres[:, None, :]) ** 2 - 1).max(-1)
    return points, np.where(np.isnan(residuals), np.inf, residuals), scaled


def _wrap(psi):
    """Angles in ``[0, 2 pi)``; those within :data:`_FULL_TURN` below ``2 pi`` become 0."""
    psi = np.mod(psi, 2 * np.pi)
    return np.where(psi >= 2 * np.pi - _FULL_TURN, 0.0, psi)


def _residual_norms(mech, poses, lambdas):
    """``max_i |F_i| / L**2`` of each pose (``inf`` for a NaN candidate)."""
    res = np.abs(kernels.loop_residuals(mech, poses, lambdas)).max(axis=-1) / mech.L ** 2
    return np.where(np.isnan(res), np.inf, res)


def _assess(mech, poses, lambdas):
    """The residual norms (:func:`_residual_norms`) and both Jacobian determinants of poses,
    from one evaluation of the bars."""
    bars, J = kernels.bars_and_jacobian(mech, poses, lambdas)
    res = np.abs(np.sum(bars ** 2, axis=-1) - mech.L ** 2).max(axis=-1) / mech.L ** 2
    inverse_det, direct_det = kernels.dets_of(mech, bars, J)
    return np.where(np.isnan(res), np.inf, res), inverse_det, direct_det


def _newton_step(mech, poses, lambdas):
    """One Newton step on the loop equations from each pose (shape ``(k, 3)``): the new poses
    and the step's size (relative to ``L`` and in radians; ``inf`` where ``J`` is singular to
    working precision, where no step is taken)."""
    bars, J = kernels.bars_and_jacobian(mech, poses, lambdas)
    F = np.sum(bars ** 2, axis=-1) - mech.L ** 2
    scale = np.maximum(np.abs(J).max(axis=(-2, -1), initial=0.0), np.finfo(float).tiny)
    regular = np.abs(np.linalg.det(J)) > _SINGULAR_STEP * scale ** 3
    step = np.linalg.solve(np.where(regular[:, None, None], J, np.eye(3)), F[..., None])[..., 0]
    size = np.hypot(step[:, 0], step[:, 1]) / mech.L + np.abs(step[:, 2])
    return poses - step, np.where(regular & np.isfinite(size), size, np.inf)


def _polish(mech, poses, lambdas):
    """A few Newton steps on the loop equations from each pose (shape ``(k, 3)``, inputs
    broadcast): one step for all (a simple root is then exact), more (:func:`solve_batch`) for
    those whose step says they converge slowly. A pose that moves by more than
    ``_POLISH_MOVE`` (relative), or whose system does not converge (a singular Jacobian: a pose
    at a direct singularity), is returned unchanged."""
    stepped, size = _newton_step(mech, poses, lambdas)
    out = np.where((size <= _POLISH_MOVE)[:, None], stepped, poses)
    slow = (size > _SIMPLE_STEP) & (size <= _POLISH_MOVE)
    if slow.any():  # a multiple root: Newton converges linearly, and may need all its steps
        L2 = mech.L ** 2  # the equations relative to L^2: no overflow at any scale
        own = np.broadcast_to(lambdas, poses.shape)[slow]
        result = solve_batch(lambda p: kernels.loop_residuals(mech, p, own) / L2, out[slow],
                             lambda p: kernels.direct_jacobian(mech, p, own) / L2,
                             tol=_EXACT, criterion="residual", maxiter=_POLISH_STEPS,
                             raise_on_failure=False)
        ok = (result.status != "singular") & (result.status != "non-finite")
        out[np.flatnonzero(slow)[ok]] = result.x[ok]
    moved = np.hypot(*(out - poses)[:, :2].T) / mech.L + np.abs(out - poses)[:, 2]
    return np.where((moved <= _POLISH_MOVE)[:, None], out, poses)


def forward(mech: Geometry, lambdas: ArrayLike, *, imag_tol: float = IMAG_TOL,
            residual_tol: float = RESIDUAL_TOL) -> DirectSolution:
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
       Candidates that miss by ``4e-15`` to ``1e-2`` get a Newton step first (more where the
       step shows slow convergence): a root of multiplicity ``m`` moves by about
       ``eps**(1/m)`` under round-off (:func:`root_condition`), so a double root is only good
       to about ``1e-8``; Newton cannot sharpen a pose *at* a direct singularity (two assembly
       modes meeting), where its Jacobian is singular.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    lambdas : array_like, shape (3,) or (m, 3)
        The inputs ``(lambda1, lambda2, lambda3)``, metres; an empty batch is valid, and at
        most :data:`MAX_INPUTS`.
    imag_tol : float, optional
        Largest ``|Im psi|`` (radians) of a root taken as real (:data:`IMAG_TOL`).
    residual_tol : float, optional
        Relative tolerance of the loop residual of an accepted pose (:data:`RESIDUAL_TOL`).

    Returns
    -------
    DirectSolution
        The poses ``x``, of shape ``(n, 3)`` with ``n`` from 0 to 6 per input.

    Raises
    ------
    ValueError
        If ``mech`` is not a Geometry, ``lambdas`` is not finite with last axis 3 (or has more
        than 2 dimensions), or a tolerance is not a positive number.

    Examples
    --------
    >>> import numpy as np
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2, H3=3)
    >>> sol = forward(g, [0.4, 0.1, 0.6])
    >>> sol.x[:, :2].round(5).tolist(), np.degrees(sol.x[:, 2]).round(4).tolist()
    ([[1.23123, 0.55593], [1.05352, 0.7569]], [9.9967, 341.5164])
    >>> forward(g, [[0.4, 0.1, 0.6], [1e100, 0.1, 0.6]]).counts.tolist()
    [2, 0]
    """
    check(mech)
    lam = vectors(lambdas, "lambdas")
    if lam.ndim > 2:
        raise ValueError(f"lambdas must have shape (3,) or (m, 3), got shape {lam.shape}")
    _validate.maxiter(lam.size // 3, "the number of inputs", minimum=0, maximum=MAX_INPUTS)
    imag_tol = _validate.tolerance(imag_tol, "imag_tol")
    residual_tol = _validate.tolerance(residual_tol, "residual_tol")
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        return _forward(mech, lam, imag_tol, residual_tol)


def _forward(mech, lam, imag_tol, residual_tol):
    """:func:`forward` on checked input (NaN and inf in the pipeline are expected, and
    removed: a candidate at a singular elimination, a root t = +-i, a far-away slider)."""
    batch = lam.reshape(-1, 3)
    z = kernels.slider_points(mech, batch)  # complex, (m, 3)
    spread = np.abs(z[:, [1, 2, 2]] - z[:, [0, 0, 1]]).max(axis=1, initial=0.0)
    rows = np.flatnonzero(spread <= (2 * mech.L + mech.a) * (1 + _REACH_MARGIN))
    scale = max(mech.L, mech.a)
    local = (z[rows] - z[rows, :1]) / scale  # slider 1 at the origin, unit size
    A, ell = mech.a / scale, mech.L / scale
    sliders = (local[:, 1].real, local[:, 2].real, local[:, 2].imag)
    if len(rows) == 1:  # one input: the polynomial's arithmetic in Python floats is faster
        sliders = tuple(float(v[0]) for v in sliders)
    polynomials = sextic(0.0, *sliders, A, ell).reshape(-1, 7)
    size = _CONTINUUM * (1 + np.maximum(np.abs(local.real), np.abs(local.imag)).max(
        axis=1, initial=0.0)) ** 8
    continuum = np.zeros(len(batch), dtype=bool)
    continuum[rows] = np.abs(polynomials).max(axis=1, initial=0.0) <= size
    polynomials[continuum[rows]] = 0.0  # no isolated root: _angles gives NaN
    psi = _angles(polynomials)  # (k, 6)
    real = np.abs(psi.imag) <= imag_tol
    root_row = np.nonzero(real)[0]  # the input of each real root, flattened
    psi = _wrap(psi[real].real)
    points, residuals, elimination = _candidates(psi, local[root_row] / ell, A / ell)
    # Each root keeps its best candidate; all three only where the elimination is singular (to
    # the angle's uncertainty, IMAG_TOL): there alone can two poses share an angle. The others
    # are copies of the best or miss; polishing them could land on a neighbouring root's pose.
    kept = (np.arange(3) == np.argmin(residuals, axis=1)[:, None]) | \
        (np.abs(elimination) <= IMAG_TOL)[:, None]
    root, which = np.nonzero(kept)
    found = points[root, which] * mech.L + z[rows[root_row[root]], 0]  # the fixed frame
    poses = np.column_stack([found.real, found.imag, psi[root]])
    index = rows[root_row[root]]
    near = (residuals[root, which] > _EXACT) & (residuals[root, which] < _CANDIDATE)
    if near.any():  # roots blurred by round-off or a multiple root: polish on the loop equations
        polished = _polish(mech, poses[near], batch[index[near]])
        polished[:, 2] = _wrap(polished[:, 2])
        poses[near] = polished
    res, inverse_det, jacobian_det = _assess(mech, poses, batch[index])
    valid = res <= residual_tol
    keep = np.flatnonzero(valid)[_distinct(poses[valid], res[valid], index[valid], mech.L)]
    keep = keep[np.lexsort((poses[keep, 2], index[keep]))]
    counts = np.bincount(index[keep], minlength=len(batch)).reshape(lam.shape[:-1])
    own = kernels.slider_points(mech, batch[index[keep]]) / mech.L  # the elimination at the
    elimination = _radical_axes(poses[keep, 2], own, mech.a / mech.L)[3]  # poses' own angles
    status = np.where(continuum, "singular", "converged").reshape(lam.shape[:-1])
    return DirectSolution(
        x=poses[keep], status=status if status.ndim else str(status), iterations=0, nfev=0,
        njev=0, message=f"{keep.size} poses of {len(batch)} inputs; a continuum of poses at "
                        f"{int(continuum.sum())}", input_index=index[keep], counts=counts,
        residuals=res[keep], elimination_det=elimination, jacobian_det=jacobian_det[keep],
        inverse_det=inverse_det[keep])




def _angles(polynomials):
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
    largest = np.abs(polynomials).max(axis=-1, initial=0.0)
    reverse = np.abs(polynomials[:, 0]) > np.abs(polynomials[:, 6])
    c = np.where(reverse[:, None], polynomials[:, ::-1], polynomials)
    floor = _NEGLIGIBLE * largest
    c[:, 6] = np.where(np.abs(c[:, 6]) < floor, np.where(c[:, 6] < 0, -floor, floor), c[:, 6])
    ok = largest > 0
    if ok.all():
        z = roots(c)
    else:
        z = np.full(c.shape[:-1] + (6,), np.nan + 0j)
        z[ok] = roots(c[ok])
    with np.errstate(divide="ignore", invalid="ignore"):  # t = +-i: no pose, psi infinite
        angle = 2 * np.arctan(z)
    return np.where(reverse[:, None], np.pi - angle, angle)


def _distinct(poses, residuals, groups, L):
    """Which of the poses (shape ``(n, 3)``) to keep: all but those within :data:`SAME_POSE` of
    a pose of the same group (input) with a smaller residual, and at most the best
    :data:`MAX_POSES` of a group (near a singularity, blurred copies of a pose can lie
    farther apart than SAME_POSE; the sextic has no more roots)."""
    order = np.lexsort((residuals, groups))
    ranked, group = poses[order], groups[order]
    duplicate = np.zeros(len(order), dtype=bool)
    sizes = np.bincount(groups)
    rows = np.arange(len(order))
    for shift in range(1, int(sizes.max(initial=0))):  # earlier in the same group
        rows = rows[sizes[group[rows]] > shift]  # the poses of groups with more than shift
        later = rows[rows >= shift]
        later = later[group[later] == group[later - shift]]
        delta = ranked[later] - ranked[later - shift]
        gap = (np.hypot(delta[:, 0], delta[:, 1]) / L
               + np.abs(np.mod(delta[:, 2] + np.pi, 2 * np.pi) - np.pi))
        duplicate[later] |= gap <= SAME_POSE
    kept = ~duplicate
    if np.bincount(group[kept], minlength=len(sizes)).max(initial=0) > MAX_POSES:
        count = np.cumsum(kept)
        first = np.ones(len(group), dtype=bool)
        first[1:] = group[1:] != group[:-1]  # where each group starts
        before = np.maximum.accumulate(np.where(first, count - kept, 0))  # in earlier groups
        kept &= count - before - 1 < MAX_POSES  # the rank of each kept pose in its group
    keep = np.empty_like(duplicate)
    keep[order] = kept
    return keep


def forward_by_newton(mech: Geometry, lambdas: ArrayLike, seeds: ArrayLike, *,
                      tol: float = 1e-12) -> np.ndarray:
    """The distinct poses that Newton-Raphson reaches from many seeds.

    Each seed is iterated on the loop equations (:func:`loop_residuals`, with the analytic
    :func:`direct_jacobian`) by :func:`mechnum.newton.solve_batch`; the seeds whose status is
    not "converged" (50 steps, a singular Jacobian) are ignored. It finds only the solutions
    whose basins the seeds hit: a check on :func:`forward`, not a replacement.

    Parameters
    ----------
    mech : ~mechnum.mechanisms.prr3.Geometry
    lambdas : array_like, shape (3,)
    seeds : array_like, shape (m, 3)
        Starting poses ``(x, y, psi)``; an empty batch gives no pose; at most
        :data:`MAX_INPUTS`.
    tol : float, optional
        Newton's step tolerance.

    Returns
    -------
    ndarray, shape (n, 3)
        The distinct converged poses, ``psi`` in ``[0, 2 pi)``, sorted by ``psi``.

    Raises
    ------
    ValueError
        If ``lambdas`` or ``seeds`` are ill-shaped or not finite, or ``tol`` not positive.

    Examples
    --------
    >>> from mechnum.mechanisms.prr3 import Geometry
    >>> g = Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8)
    >>> seeds = [[2.0, 1.0, 6.0], [1.5, 1.0, 0.2]]
    >>> forward_by_newton(g, [2, 0.5, 0.2], seeds)[:, 2].round(4).tolist()
    [0.1251, 6.0322]
    """
    check(mech)
    lam = _validate.array(lambdas, "lambdas", shape=(3,))
    seeds = _validate.array(seeds, "seeds", shape=(None, 3))
    _validate.maxiter(len(seeds), "the number of seeds", minimum=0, maximum=MAX_INPUTS)
    tol = _validate.tolerance(tol)
    if len(seeds) == 0:
        return np.empty((0, 3))
    result = solve_batch(lambda p: kernels.loop_residuals(mech, p, lam), seeds,
                         lambda p: kernels.direct_jacobian(mech, p, lam), tol=tol,
                         raise_on_failure=False)
    poses = result.x[result.converged]
    poses[:, 2] = _wrap(poses[:, 2])
    keep = _distinct(poses, _residual_norms(mech, poses, lam), np.zeros(len(poses), int),
                     mech.L)
    poses = poses[keep]
    return poses[np.argsort(poses[:, 2])]

