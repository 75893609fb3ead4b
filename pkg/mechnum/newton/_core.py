"""What every Newton solver of :mod:`mechnum.newton` shares: equations, step, line search.

* :class:`Equations` wraps the caller's ``fun`` and ``jac`` (a callable, ``True`` when ``fun``
  returns ``(f, J)`` together, or ``None`` for forward differences), checks what they return and
  counts the calls;
* :func:`newton_step` solves ``J dx = -f`` for one system or a stack, and flags a Jacobian that
  is singular to working precision;
* :func:`line_search` backtracks along a step until Armijo's rule holds (damped Newton);
* :func:`describe` puts a :class:`~mechnum.results.StoppingRule` in words.

Examples
--------
>>> import numpy as np
>>> dx, singular, _ = newton_step(np.array([[2.0, 0.0], [0.0, 4.0]]), np.array([2.0, -4.0]))
>>> dx.tolist(), bool(singular)
([-1.0, 1.0], False)
"""

import functools
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate
from mechnum.errors import NonFiniteError
from mechnum.results import StoppingRule

TOL = 1e-10
"""Default tolerance of the step criterion, relative: stop after the first full Newton step with
``||dx|| <= TOL ||x_{k+1}||``. Newton's error after a step of relative size ``d`` is about
``C d**2``, so the accepted iterate is at round-off for any ``C`` below ``1e5``; a smaller value
would ask the step to fall below its own round-off floor (``eps cond(J)``), which a Jacobian of
condition ``1e6`` cannot meet."""
ROOT_TOL = 1e-12
"""Default tolerance of :func:`~mechnum.newton.solve_all` (relative step): two digits beyond
:data:`TOL`, so that the converged ends of two starts at one root agree far better than the
``same`` (``1e-8``) that groups them, even for a root whose Newton constant ``C`` is large."""
MAXITER_LIMIT = 100_000
"""The most iterations any Newton solver accepts: a converging Newton iteration needs tens; a
larger request is a typing slip that would run for hours."""
HALVINGS_LIMIT = 52
"""The most halvings of a damped step: ``2**-52`` of a step moves ``x`` by round-off."""
MAX_HALVINGS = 20
"""Default halvings of :func:`~mechnum.newton.solve` with damping: a start whose step must be cut
below ``2**-20`` of Newton's has stagnated (it sits near a local minimum of ``||f||``)."""
SEARCH_HALVINGS = 4
"""Default halvings in an all-solutions search (``alpha >= 1/16``): a start whose Newton step
must be cut further lies where Newton's linear model is poor, and dropping it costs hits, not
roots (other starts reach them), while its 20 halvings per step would dominate the run (on the
2RFR of Chapter 5, 4 halvings keep half the converging starts for 1/30 of the time)."""
ARMIJO = 1e-4
"""Armijo's sufficient decrease: accept ``alpha`` when ``||f||`` falls by at least ``ARMIJO alpha``
of itself (the customary constant: any decrease counts, but not a vanishing one)."""
_SQRT_EPS = np.sqrt(np.finfo(float).eps)  # the forward-difference step that balances errors
_MAX_COND = 1.0 / np.finfo(float).eps  # a condition number past which no digit is left
_TINY = np.finfo(float).tiny
_SQRT_TINY = np.sqrt(_TINY)  # a 2-norm below it was summed from squares that lost digits


def describe(rule: StoppingRule) -> str:
    """A Newton iteration's stopping test in words, for messages.

    Examples
    --------
    >>> describe(StoppingRule(1e-10, 50, "step", 2, True))
    'full step <= 1e-10 ||x||'
    """
    if rule.criterion == "step":
        return f"full step <= {rule.tol:g}" + (" ||x||" if rule.relative else "")
    return f"residual <= {rule.tol:g}" + (" ||f(x0)||" if rule.relative else "")


def norms(v: np.ndarray, norm: float) -> np.ndarray:
    """``np.linalg.norm(v, norm, axis=-1)``, several times faster for a stack of short vectors
    (the sums over the short last axis are products with a vector of ones), and without
    overflow or underflow: a 2-norm whose squares overflow, or underflow (entries below
    ``sqrt(tiny)``, about ``1.5e-154``, square to subnormals or zero), is computed again from
    ``v`` scaled by its largest entry.

    Examples
    --------
    >>> round(float(norms(np.array([3e200, 4e200]), 2)) / 1e200, 12)
    5.0
    >>> round(float(norms(np.array([3e-200, 4e-200]), 2)) / 1e-200, 12)
    5.0
    """
    if v.ndim == 1 and norm != 2:
        return np.linalg.norm(v, norm)
    if norm == np.inf:
        return largest(np.abs(v))
    ones = _ones(v.shape[-1])
    if norm == 1:
        return np.abs(v) @ ones
    with np.errstate(over="ignore"):   # as np.linalg.norm: the root of the sum of squares
        out = np.sqrt(v.dot(v) if v.ndim == 1 else (v * v) @ ones)
    # squares that overflow (inf), or underflow (a norm below sqrt(tiny), zero for a non-zero v,
    # was summed from squares that lost digits): computed again from v scaled by its largest entry
    lost = np.isinf(out) | (out < _SQRT_TINY)
    if not lost.any():
        return out
    a = np.abs(v)
    top = largest(a)
    lost &= (top > 0) & np.isfinite(a).all(axis=-1)
    if not lost.any():
        return out
    scaled = np.sqrt((a / np.where(top > 0, top, 1.0)[..., None]) ** 2 @ ones) * top
    return np.where(lost, scaled, out)


@functools.cache
def _ones(n):
    """A vector of ``n`` ones, made once (read-only)."""
    out = np.ones(n)
    out.flags.writeable = False
    return out


def largest(a: np.ndarray) -> np.ndarray:
    """The largest entry along the last axis. (NumPy reduces a short last axis slowly, one row
    at a time: reduce the transposed copy along its first axis, many rows at once.)"""
    return np.ascontiguousarray(a.reshape(-1, a.shape[-1]).T).max(axis=0).reshape(a.shape[:-1])


def _real(value, what, shape):
    """``value`` as a real float array of ``shape``, or a ValueError naming ``what``."""
    out = np.asarray(value)
    if np.iscomplexobj(out):
        raise ValueError(f"{what} returned complex values: the Newton solvers are real "
                         f"(split a complex system into real and imaginary parts)")
    if out.dtype.kind not in "biuf":
        raise ValueError(f"{what} returned a non-numeric array (dtype {out.dtype})")
    out = out.astype(float, copy=False)
    if out.shape != shape:
        raise ValueError(f"{what} returned shape {out.shape}, expected {shape}")
    return out


def fd_jacobian(fun: Callable, x: ArrayLike, fx: ArrayLike | None = None) -> np.ndarray:
    """Forward-difference Jacobian of ``fun`` at ``x``, for one system or a batch.

    Column ``j`` is ``(f(x + h_j e_j) - f(x)) / h_j`` with ``h_j = sqrt(eps) max(1, |x_j|)``,
    accurate to about half the digits of ``f``, which still gives Newton a fast (no longer
    quadratic) rate.

    Parameters
    ----------
    fun : callable
        ``fun(x)`` with ``x`` of shape ``(n,)`` or ``(batch, n)``, returning the same shape.
    x : array_like, shape (n,) or (batch, n)
        Where to differentiate; finite, and small enough that ``x + h`` is finite.
    fx : array_like, optional
        ``fun(x)``, if already known (same shape as ``x``, finite).

    Returns
    -------
    ndarray, shape (n, n) or (batch, n, n)
        ``J[..., i, j] ~= d fun_i / d x_j``.

    Raises
    ------
    ValueError
        If ``x`` or ``fx`` is not finite or has the wrong shape, or ``fun`` returns the wrong
        shape or complex values.
    NonFiniteError
        If a difference is not finite (``fun`` is NaN or infinite near ``x``, or ``x`` is so
        large that the differences overflow).

    Examples
    --------
    >>> import numpy as np
    >>> J = fd_jacobian(lambda x: np.array([x[0] ** 2, x[0] * x[1]]), np.array([1.0, 2.0]))
    >>> np.round(J, 6)
    array([[2., 0.],
           [2., 1.]])
    """
    fun, x = _validate.function(fun, "fun"), _validate.array(x, "x", ndim=(1, 2))
    if x.shape[-1] == 0:
        raise ValueError(f"x must have at least one unknown, got shape {x.shape}")
    fx = (_real(fun(x), "fun", x.shape) if fx is None
          else _validate.array(fx, "fx", shape=x.shape))
    jac = differences(lambda z: _real(fun(z), "fun", x.shape), x, fx)
    if not np.all(np.isfinite(jac)):
        raise NonFiniteError(f"the forward differences of fun are not finite at x = "
                             f"{_validate.shown(x)} (fun is not finite near x, or x is too "
                             f"large for steps of sqrt(eps) |x|)")
    return jac


def differences(fun: Callable, x: np.ndarray, fx: np.ndarray) -> np.ndarray:
    """The forward differences of :func:`fd_jacobian`, unchecked (NaN or inf where ``fun`` is
    not finite: the solvers report that as a status)."""
    n = x.shape[-1]
    h = _SQRT_EPS * np.maximum(1.0, np.abs(x))
    jac = np.empty(x.shape[:-1] + (n, n))
    with np.errstate(over="ignore", invalid="ignore"):
        for j in range(n):
            xj = x.copy()
            xj[..., j] += h[..., j]
            jac[..., :, j] = (fun(xj) - fx) / h[..., j, None]
    return jac


class Equations:
    """The caller's ``fun`` and ``jac`` for one system ``(n,)`` or a batch ``(batch, n)``: their
    values checked (real, of the right shape), their calls counted.

    Parameters
    ----------
    fun : callable
        ``fun(x) -> f``, or ``fun(x) -> (f, J)`` when ``jac is True``.
    jac : callable, True or None
        ``jac(x) -> J``; ``True``: ``fun`` returns the Jacobian with the residual (as scipy's
        ``root(jac=True)``), so that work they share is done once; ``None``:
        :func:`fd_jacobian`.

    Examples
    --------
    >>> import numpy as np
    >>> eq = Equations(lambda x: (x ** 2 - 2.0, np.diag(2 * x)), True)
    >>> f, J = eq.value(np.array([1.0]))
    >>> f.tolist(), J.tolist(), eq.nfev, eq.njev
    ([-1.0], [[2.0]], 1, 1)
    """

    def __init__(self, fun: Callable, jac: Callable | bool | None) -> None:
        if not callable(fun):
            raise ValueError(f"fun must be callable, got {_validate.shown(fun)}")
        if not (jac is None or jac is True or callable(jac)):
            raise ValueError(f"jac must be a callable, True (fun returns (f, J)) or None "
                             f"(forward differences), got {_validate.shown(jac)}")
        self.fun, self.jac, self.nfev, self.njev = fun, jac, 0, 0

    def value(self, x: np.ndarray) -> tuple:
        """``(f(x), J(x))`` if ``fun`` returns both, else ``(f(x), None)``."""
        out = self.fun(x)
        self.nfev += 1
        if self.jac is not True:
            return _real(out, "fun", x.shape), None
        if not (isinstance(out, tuple) and len(out) == 2):
            raise ValueError("with jac=True, fun must return a pair (f, J), got "
                             f"{type(out).__name__}")
        self.njev += 1
        return (_real(out[0], "fun", x.shape),
                _real(out[1], "fun's Jacobian", x.shape + x.shape[-1:]))

    def jacobian(self, x: np.ndarray, f: np.ndarray, J: np.ndarray | None = None) -> np.ndarray:
        """The Jacobian at ``x`` (where ``fun`` is ``f``): ``J`` if already known, else
        ``jac(x)`` or forward differences."""
        if J is not None:
            return J
        if self.jac is None:
            self.nfev += x.shape[-1]
            return differences(lambda z: _real(self.fun(z), "fun", x.shape), x, f)
        self.njev += 1
        return _real(self.jac(x), "jac", x.shape + x.shape[-1:])


def newton_step(jac: np.ndarray, fx: np.ndarray) -> tuple:
    """Solve ``J dx = -f`` for one system or a stack; flag the (numerically) singular ``J``.

    Besides an exactly singular ``J`` (LAPACK's zero pivot), a step is flagged when
    ``max|J_ij| ||dx||_1 / ||f||_1``, a lower bound of the condition number ``||J||_1
    ||J^-1||_1`` (since ``||J||_1 >= max|J_ij|`` and ``||J^-1||_1 >= ||dx||_1 / ||f||_1``),
    exceeds ``1/eps``: then no digit of ``dx`` can be trusted. A system with ``f = 0`` is never
    flagged. ``J`` and ``f`` must be finite.

    Parameters
    ----------
    jac : ndarray, shape (n, n) or (..., n, n)
    fx : ndarray, shape (n,) or (..., n)

    Returns
    -------
    dx : ndarray
        The steps (zero where flagged).
    singular : ndarray of bool
        The flags, one per system.
    cond : ndarray or None
        The lower bounds of the condition numbers (``inf`` where ``J`` is exactly singular),
        or None when nothing is flagged.

    Examples
    --------
    >>> dx, singular, cond = newton_step(np.ones((2, 2)), np.array([1.0, 2.0]))
    >>> bool(singular), float(cond)
    (True, inf)
    """
    exact = np.zeros(fx.shape[:-1], dtype=bool)
    try:  # a 1-D right-hand side for one system, a stack of columns for a batch
        dx = (np.linalg.solve(jac, -fx) if fx.ndim == 1
              else np.linalg.solve(jac, -fx[..., None])[..., 0])
    except np.linalg.LinAlgError:  # some J is exactly singular: find which
        dx = np.zeros_like(fx)
        for i in np.ndindex(fx.shape[:-1]):
            try:
                dx[i] = np.linalg.solve(jac[i], -fx[i])
            except np.linalg.LinAlgError:
                exact[i] = True
    fsize, size = norms(fx, 1), norms(dx, 1)
    with np.errstate(over="ignore", invalid="ignore"):  # inf or NaN growth is flagged below
        # the stack's largest entry bounds every J's: where that bound is trusted, all are
        entry = np.abs(jac)
        if not exact.any() and (entry.max() * size <= _MAX_COND * fsize).all():
            return dx, exact, None
        growth = largest(entry.reshape(jac.shape[:-2] + (-1,))) * size
        trusted = growth <= _MAX_COND * fsize  # False where growth is inf or NaN
    if trusted.all() and not exact.any():
        return dx, exact, None
    singular = (exact | ~trusted) & (fsize > 0)
    cond = np.where(exact, np.inf, growth / np.maximum(fsize, _TINY))
    return np.where(singular[..., None], 0.0, dx), singular, cond


def bounded(dx: np.ndarray, max_step: float | None) -> tuple:
    """The steps ``dx`` (one per row), each shortened to at most ``max_step`` in its largest
    component, and the factor (``<= 1``) by which each was shortened.

    Examples
    --------
    >>> step, factor = bounded(np.array([[4.0, -2.0]]), 1.0)
    >>> step.tolist(), factor.tolist()
    ([[1.0, -0.5]], [0.25])
    """
    if max_step is None:
        return dx, np.ones(dx.shape[:-1])
    factor = np.minimum(1.0, max_step / np.maximum(largest(np.abs(dx)), _TINY))
    return dx * factor[..., None], factor


@dataclass
class Trial:
    """The state of a line search over a batch: the accepted points, their residuals (and
    Jacobians, when ``fun`` returns them), and the systems still looking for a step."""

    x: np.ndarray
    f: np.ndarray
    J: np.ndarray | None
    pending: np.ndarray

    def take(self, ok: np.ndarray, x: np.ndarray, f: np.ndarray, J: np.ndarray | None) -> None:
        """Accept the rows ``ok`` of the trial points ``x``, ``f``, ``J``."""
        self.x[ok], self.f[ok] = x[ok], f[ok]
        if self.J is not None and J is not None:
            self.J[ok] = J[ok]
        self.pending &= ~ok


def line_search(call: Callable, x: np.ndarray, fx: np.ndarray, J: np.ndarray | None,
                dx: np.ndarray, moving: np.ndarray, rnorm: np.ndarray, sure: np.ndarray,
                norm: float, domain: Callable | None, *, shrink: np.ndarray | None = None,
                stacked: bool = False, halvings: int = MAX_HALVINGS) -> tuple:
    """Backtracking for the systems ``moving`` of a batch.

    ``alpha`` is halved from 1 until the trial point ``x + alpha dx`` lies in the ``domain``
    and Armijo's rule ``||f|| <= (1 - ARMIJO alpha s) ||f(x)||`` holds, where ``s`` (``shrink``)
    is the factor by which ``max_step`` shortened Newton's step: the decrease Newton's linear
    model promises for ``alpha s`` of its full step. A system whose step is ``sure`` (it
    already meets the stopping test) takes it whole. ``call(points, rows)`` returns
    ``(f, J or None)`` at ``points`` (at least of the systems ``rows``). With ``stacked`` (the
    systems do not depend on their position), the step lengths ``1/2, 1/4, ...`` of the
    systems that refuse ``alpha = 1`` are all tried in one call, with the same outcome as one
    halving at a time.

    Returns
    -------
    Trial
        The new points (the old ones where no step was found).
    failed : ndarray of str
        ``"stagnated"`` or ``"left-domain"`` for the systems that found no step, ``""``
        elsewhere.
    calls : int
        The calls of ``call``.
    """
    shrink = np.ones(len(x)) if shrink is None else shrink
    alpha = np.ones(len(x))
    state = Trial(x.copy(), fx.copy(), None if J is None else J.copy(), moving.copy())
    outside = np.zeros(len(x), dtype=bool)
    calls = 0
    for calls in range(1, halvings + 2):
        if stacked and calls == 2:
            return _all_halvings(call, x, dx, state, rnorm, shrink, norm, domain, halvings)
        trial = np.where(state.pending[:, None], x + alpha[:, None] * dx, state.x)
        within = inside(domain, trial)
        # fun is never evaluated outside the domain (where it may be undefined or raise)
        f_trial, J_trial = call(np.where(within[:, None], trial, state.x),
                                state.pending & within)
        t_norm = norms(f_trial, norm)
        with np.errstate(invalid="ignore"):
            ok = state.pending & within & np.isfinite(t_norm) & (
                (t_norm <= (1 - ARMIJO * alpha * shrink) * rnorm) | (sure & (alpha == 1)))
        state.take(ok, trial, f_trial, J_trial)
        outside = state.pending & ~within
        if not state.pending.any():
            break
        alpha[state.pending] /= 2
    failed = np.where(outside, "left-domain", "stagnated")
    return state, np.where(state.pending, failed, ""), calls


def inside(domain: Callable | None, points: np.ndarray) -> np.ndarray:
    """``domain(points)`` checked: one bool per row (all True without a domain).

    Examples
    --------
    >>> inside(lambda x: x[:, 0] > 0, np.array([[1.0], [-1.0]])).tolist()
    [True, False]
    """
    if domain is None:
        return np.ones(len(points), dtype=bool)
    out = np.asarray(domain(points))
    if out.shape != (len(points),):
        raise ValueError(f"domain returned shape {out.shape}, expected ({len(points)},): "
                         "one bool per system")
    return out.astype(bool)


def _all_halvings(call, x, dx, state, rnorm, shrink, norm, domain, halvings):
    """The rest of :func:`line_search` for position-free systems: ``alpha = 2**-1, ...,
    2**-halvings`` of every pending system in one call (at the trial points inside the
    domain only); each takes its largest acceptable ``alpha``, as the halving loop would."""
    rows = np.flatnonzero(state.pending)
    n = x.shape[1]
    alpha = 0.5 ** np.arange(1, halvings + 1)
    trial = x[rows, None, :] + alpha[:, None] * dx[rows, None, :]       # (rows, alphas, n)
    flat = trial.reshape(-1, n)
    within = inside(domain, flat)
    inner = np.flatnonzero(within)
    ok = np.zeros(len(flat), dtype=bool)
    if inner.size:
        f_in, J_in = call(flat[inner], np.ones(inner.size, dtype=bool))
        t_norm = norms(f_in, norm)
        row, step = np.divmod(inner, halvings)
        with np.errstate(invalid="ignore"):
            ok[inner] = np.isfinite(t_norm) & (
                t_norm <= (1 - ARMIJO * alpha[step] * shrink[rows[row]]) * rnorm[rows[row]])
    ok = ok.reshape(len(rows), halvings)
    first = ok.argmax(axis=1)
    found = ok[np.arange(len(rows)), first]
    take, pick = rows[found], np.flatnonzero(found) * halvings + first[found]
    if take.size:
        at = np.searchsorted(inner, pick)          # the picked points among those evaluated
        state.x[take], state.f[take] = flat[pick], f_in[at]
        if state.J is not None:
            state.J[take] = J_in[at]
    state.pending[take] = False
    status = np.full(len(x), "", dtype="<U11")
    status[rows[~found]] = np.where(within.reshape(len(rows), -1)[~found, -1], "stagnated",
                                    "left-domain")
    return state, status, 2
