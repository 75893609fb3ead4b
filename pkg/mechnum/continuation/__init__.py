"""Continuation: a curve of solutions followed by its parameter, or traced through its folds.

*Natural-parameter continuation* (:func:`solve_path`) fixes the parameter at each of a given
sequence of values and corrects the state by Newton's method from a prediction. It stops at a
*fold*, where the curve turns back in the parameter and the Jacobian in the state is singular;
worse, Newton may leap across the fold onto another branch and converge there, which
:func:`solve_path` detects and reports as a ``"branch-jump"``.

Keller's *pseudo-arclength continuation* (:func:`pseudo_arclength`) treats the ``n`` equations
``F(u) = 0`` in the ``n + 1`` unknowns ``u = (state, parameter)`` alike, and steps along the
curve by its arclength ``h``:

1. the **tangent** ``t`` at a point ``u`` spans the null space of ``F'(u)`` (shape
   ``(n, n + 1)``); it is the solution of ``[F'(u); t_prev^T] t = [0; 1]``, normalised, so
   that it keeps the orientation of the previous tangent;
2. the **predictor** ``u + h t`` is corrected by Newton's method
   (:func:`mechnum.newton.solve`) on the bordered system ``F(v) = 0``, ``t . (v - u) = h``
   (the new point lies on the hyperplane at distance ``h`` along the tangent), whose Jacobian
   ``[F'(v); t^T]`` stays regular at a fold;
3. the step ``h`` is halved when Newton fails, and grows after an easy step.

A fold is where the parameter's component of the tangent changes sign; :func:`pseudo_arclength`
reports the intervals where it does and locates each fold on the curve by the secant method on
that component. Reference: H. B. Keller, *Numerical solution of bifurcation and nonlinear
eigenvalue problems* (1977); E. L. Allgower and K. Georg, *Introduction to Numerical
Continuation Methods* (2003), chapter 2.

Examples
--------
>>> import numpy as np
>>> path = solve_path(lambda x, p: x ** 2 - p[:, None], [1.0], [1.0, 4.0, 9.0])
>>> path.x[:, 0].round(12).tolist(), path.status.tolist()
([1.0, 2.0, 3.0], ['converged', 'converged', 'converged'])
"""

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.continuation._arclength import Branch as Branch
from mechnum.continuation._arclength import pseudo_arclength
from mechnum.continuation._natural import PathResult as PathResult
from mechnum.continuation._natural import solve_path

__all__ = ["pseudo_arclength", "solve_path"]
