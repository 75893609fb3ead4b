"""Linear systems: least squares, stationary iterations, conjugate gradients, conditioning.

A stationary method splits ``A = P - N`` and sweeps ``x <- P^{-1} (N x + b)`` until its stopping
rule is met; it converges from every start if and only if the spectral radius of the iteration
matrix ``M = P^{-1} N`` is below 1. The package's modules, in the order a course meets them:

* what the solvers accept (a finite real matrix, dense or sparse, and not singular to working
  precision), and the :func:`condition_number`;
* one sweep of Jacobi, Gauss-Seidel or SOR, as the textbook loop component by component
  (:func:`sweep_by_components`); the solvers run it compiled over the matrix's non-zeros;
* whether and how fast they converge: the iteration matrix (:func:`iteration_matrix`), spectral
  radii (:func:`spectral_radius`, :func:`sor_spectral_radii`) and the best relaxation factor
  (:func:`young_omega`, :func:`optimal_omega`);
* the solvers :func:`sor`, :func:`gauss_seidel` and :func:`jacobi`, which stop by a
  :class:`~mechnum.results.StoppingRule` and return an :class:`IterationResult`, and SOR over
  many relaxation factors (:func:`sor_sweep`);
* :func:`conjugate_gradient`, and the model problems :func:`poisson2d` and :func:`poisson3d`;
* :func:`least_squares` (QR, the SVD, the normal equations) and :func:`iterative_refinement`.
"""

from mechnum.linear._checks import condition_number

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.linear._direct import LeastSquares as LeastSquares
from mechnum.linear._direct import iterative_refinement, least_squares
from mechnum.linear._krylov import conjugate_gradient, poisson2d, poisson3d
from mechnum.linear._spectra import OptimalOmega as OptimalOmega
from mechnum.linear._spectra import (
    optimal_omega,
    sor_spectral_radii,
    young_omega,
)
from mechnum.linear._stationary import IterationResult as IterationResult
from mechnum.linear._stationary import SorSweep as SorSweep
from mechnum.linear._stationary import (
    gauss_seidel,
    jacobi,
    sor,
    sor_sweep,
)
from mechnum.linear._sweeps import sweep_by_components

__all__ = ["condition_number", "conjugate_gradient", "gauss_seidel", "iterative_refinement",
           "jacobi", "least_squares", "optimal_omega", "poisson2d", "poisson3d", "sor",
           "sor_spectral_radii", "sor_sweep", "sweep_by_components", "young_omega"]
