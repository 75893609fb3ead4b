"""Freudenstein's synthesis of the finger's four-bar: the link lengths that fit angle pairs.

Squaring the loop closure to eliminate the coupler angle gives Freudenstein's equation

    ``cos(theta_out - theta_in) = k1 cos(theta_out) + k2 cos(theta_in) + k3``,
    ``k1 = -r4 / r3``, ``k2 = -r4 / r1``, ``k3 = (r2^2 - r1^2 - r3^2 - r4^2) / (2 r1 r3)``,

which is linear in ``k``: ``m`` angle pairs give an ``m x 3`` least-squares problem
(:func:`design_matrix`), solved by :func:`mechnum.linear.least_squares` (:func:`synthesize`);
the lengths follow from ``k`` and a proposed ground link ``r4`` (:func:`linkage_from_coefficients`).
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, linear
from mechnum.errors import GeometryError, SingularJacobianError
from mechnum.mechanisms.finger._model import Linkage, angle_pairs
from mechnum.results import Result


@dataclass(frozen=True, kw_only=True)
class Synthesis(Result):
    """The outcome of :func:`synthesize`.

    Attributes
    ----------
    x : ndarray, shape (3,)
        The Freudenstein coefficients ``k1, k2, k3``.
    status, message, iterations, nfev, njev
        Those of the least-squares solve (:class:`mechnum.linear.LeastSquares`).
    linkage : Linkage
        The link lengths they give for the proposed ``r4``.
    residuals : ndarray, shape (m,)
        ``A k - b``: the misfit of Freudenstein's equation at every angle pair.
    solver : IterationResult or None
        The iterative solver's result (methods ``sor``, ``gauss_seidel``, ``jacobi``, ``cg``).
    """

    linkage: Linkage
    residuals: np.ndarray
    solver: object


def lengths_from_coefficients(k: ArrayLike, r4: float) -> np.ndarray:
    """The link lengths ``(r1, r2, r3)`` of Freudenstein coefficients, vectorised over ``k``.

    Parameters
    ----------
    k : array_like, shape (..., 3)
        Coefficients ``k1, k2, k3``, one set per row (the iterates of a solver, say).
    r4 : float
        The proposed ground link, positive.

    Returns
    -------
    ndarray, shape (..., 3)
        ``r1 = -r4 / k2``, ``r2 = sqrt(2 r1 r3 k3 + r1^2 + r3^2 + r4^2)``, ``r3 = -r4 / k1``;
        NaN in every row whose coefficients belong to no linkage (``k1`` or ``k2`` not
        negative, or ``r2^2 <= 0``).

    Examples
    --------
    >>> lengths_from_coefficients([[-0.25, -0.5, -0.75], [0.0, 0.0, 0.0]], 1.0).round(12)
    array([[ 2.,  3.,  4.],
           [nan, nan, nan]])
    """
    k = _validate.array(k, "k")
    if k.ndim == 0 or k.shape[-1] != 3:
        raise ValueError(f"k must have 3 coefficients in its last axis, got shape {k.shape}")
    r4 = _validate.scalar(r4, "r4", positive=True)
    k1, k2, k3 = np.moveaxis(k, -1, 0)
    valid = (k1 < 0) & (k2 < 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        r3, r1 = np.where(valid, -r4 / k1, np.nan), np.where(valid, -r4 / k2, np.nan)
        r2_squared = 2 * r1 * r3 * k3 + r1 ** 2 + r3 ** 2 + r4 ** 2
        r2 = np.where(r2_squared > 0, np.sqrt(r2_squared), np.nan)
    lengths = np.stack([r1, r2, r3], axis=-1)
    return np.where(np.isnan(lengths).any(axis=-1, keepdims=True), np.nan, lengths)


def linkage_from_coefficients(k: ArrayLike, r4: float) -> Linkage:
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
    r1, r2, r3 = lengths_from_coefficients(k, r4)
    if np.isnan(r2):
        raise GeometryError(f"k gives r2^2 = {2 * r1 * r3 * k[2] + r1 ** 2 + r3 ** 2 + r4 ** 2:.6g}"
                            " <= 0: no coupler fits")
    return Linkage(float(r1), float(r2), float(r3), r4)


def design_matrix(theta_in: ArrayLike, theta_out: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
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
    theta_in, theta_out = angle_pairs(theta_in, theta_out)
    A = np.column_stack([np.cos(theta_out), np.cos(theta_in), np.ones_like(theta_in)])
    return A, np.cos(theta_out - theta_in)


def synthesize(theta_in: ArrayLike, theta_out: ArrayLike, r4: float, method: str = "qr",
               omega: float | None = None, **solver_options: object) -> Synthesis:
    """Fit the Freudenstein coefficients and link lengths to angle pairs by least squares.

    Parameters
    ----------
    theta_in, theta_out : array_like, shape (m,)
        Angle pairs, rad, ``m >= 3``.
    r4 : float
        The proposed ground link, metres (it sets the scale).
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
    >>> from mechnum.mechanisms.finger import forward
    >>> true = Linkage(0.030, 0.007, 0.025, 0.007)
    >>> theta_in = np.linspace(4.6, 6.2, 6)
    >>> fit = synthesize(theta_in, forward(true, theta_in).x[:, 0], 0.007)
    >>> np.round([fit.linkage.r1, fit.linkage.r2, fit.linkage.r3], 12).tolist()
    [0.03, 0.007, 0.025]
    """
    A, b = design_matrix(theta_in, theta_out)
    if A.shape[0] < 3:
        raise ValueError(f"at least 3 angle pairs are needed, got {A.shape[0]}")
    r4 = _validate.scalar(r4, "r4", positive=True)
    try:
        fit = linear.least_squares(A, b, method, omega, **solver_options)
    except SingularJacobianError as error:
        raise SingularJacobianError(f"the angle pairs do not determine k: {error}") from None
    return Synthesis(x=fit.x, status=fit.status, message=fit.message, iterations=fit.iterations,
                     nfev=fit.nfev, njev=fit.njev, linkage=linkage_from_coefficients(fit.x, r4),
                     residuals=fit.residuals, solver=fit.solver)
