"""Newton-Raphson for systems of nonlinear equations, one, many, and all solutions.

Four solvers share one step rule:

* :func:`solve` solves one system ``f(x) = 0`` of ``n`` equations in ``n`` unknowns and keeps
  its whole history;
* :func:`solve_batch` solves ``batch`` independent systems of the same size at once, with
  arrays of shape ``(batch, n)``; each system stops when it converges, the others go on, and
  each reports a ``status``;
* :func:`solve_all` looks for every root of one system: :func:`solve_batch` from many starts,
  the roots deduplicated and counted, and a completeness check (ten times more starts that find
  no new root);
* :func:`broyden` replaces the Jacobian of :func:`solve` after the first by rank-one updates
  (Broyden's method): no Jacobian evaluations, superlinear instead of quadratic convergence.

Following a root while a parameter changes is :mod:`mechnum.continuation`, built on these.

Every one returns a result of the contract of :mod:`mechnum.results` (``x``, ``status``,
``converged``, ``message``, ``iterations``, ``nfev``, ``njev``) with its own fields added.

The Newton step solves ``J(x_k) dx = -f(x_k)`` and sets ``x_{k+1} = x_k + dx``. With
``damping=True`` the step is shortened, ``x_{k+1} = x_k + alpha dx`` with ``alpha = 1, 1/2,
1/4, ...``, until the residual norm decreases enough (Armijo's rule,
``||f(x_k + alpha dx)|| <= (1 - 1e-4 alpha) ||f(x_k)||``): a backtracking line search, which
keeps a bad start from being thrown far away. A start whose line search finds no such
``alpha`` has *stagnated* (it sits near a local minimum of ``||f||`` that is no root) and is
dropped instead of being iterated to ``maxiter``. ``max_step`` bounds every step before the line
search (Armijo's rule then measures ``alpha`` against Newton's full step). An optional
``domain`` (a test of the iterates) keeps the iterates where the equations make sense; a step
that leaves it is shortened too (with damping) or the system is dropped.

The stopping criterion is explicit because iteration counts depend on it:

* ``criterion="step"`` stops after the first full Newton step with
  ``||dx|| <= tol ||x_{k+1}||`` (relative, the default) or ``||dx|| <= tol`` (``relative=False``,
  the rule of most course codes, the hacksaw study's included); the step tested is Newton's
  full step, before ``max_step`` or damping shortens it, and the accepted ``x`` is the one
  after that step;
* ``criterion="residual"`` stops as soon as ``||f(x_k)|| <= tol`` (absolute by default: the
  caller scales the equations).

``norm`` is the ``ord`` of :func:`numpy.linalg.norm` (default 2, the Euclidean norm); the
options make one :class:`mechnum.results.StoppingRule`. The default tolerances are named
constants, each with its reason: ``1e-10`` for one root (:func:`solve`), ``1e-12`` for a search
(:func:`solve_all`, two digits beyond, so that the ends of two starts at one root agree far
better than the ``1e-8`` that groups them).

Without an analytic Jacobian, a forward-difference one is used (:func:`fd_jacobian`); with
``jac=True``, ``fun`` returns the residual and the Jacobian together (as scipy's
``root(jac=True)``), so a caller whose two share work (an integration, a factorisation) does
it once, with no cache of its own. The methods here are real: a residual or a Jacobian with
complex values is refused.

Examples
--------
>>> import numpy as np
>>> from mechnum import newton
>>> newton.solve(lambda x: x ** 3 - 8.0, [1.0], lambda x: np.diag(3 * x ** 2)).x.round(12)
array([2.])
"""

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.newton._batch import BatchNewtonResult as BatchNewtonResult
from mechnum.newton._batch import solve_batch
from mechnum.newton._core import MAXITER_LIMIT, fd_jacobian
from mechnum.newton._search import RootSet as RootSet
from mechnum.newton._search import solve_all
from mechnum.newton._single import NewtonResult as NewtonResult
from mechnum.newton._single import broyden, solve

__all__ = ["MAXITER_LIMIT", "broyden", "fd_jacobian", "solve", "solve_all", "solve_batch"]
