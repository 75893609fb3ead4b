"""Linear systems: least squares, stationary iterations, conjugate gradients, conditioning.

A stationary method splits ``A = P - N`` and sweeps ``x <- P^{-1} (N x + b)`` until its stopping
rule is met; it converges from every start if and only if the spectral radius of the iteration
matrix ``M = P^{-1} N`` is below 1. The package's modules, in the order a course meets them:

* :mod:`~mechnum.linear.checks`: what the solvers accept (:func:`check_matrix`), and the
  :func:`condition_number`;
* :mod:`~mechnum.linear.sweeps`: one sweep of Jacobi, Gauss-Seidel or SOR, as the textbook loop
  component by component (:func:`sweep_by_components`) and as the solvers run it, compiled over
  the non-zeros of a :class:`Splitting` (:func:`splitting`);
* :mod:`~mechnum.linear.spectra`: whether and how fast they converge: the iteration matrix
  (:func:`iteration_matrix`), spectral radii (:func:`spectral_radius`,
  :func:`sor_spectral_radii`) and the best relaxation factor (:func:`young_omega`,
  :func:`optimal_omega`);
* :mod:`~mechnum.linear.stationary`: the solvers :func:`sor`, :func:`gauss_seidel` and
  :func:`jacobi`, their :class:`StoppingRule` and :class:`IterationResult`, and SOR over many
  relaxation factors (:func:`sor_sweep`);
* :mod:`~mechnum.linear.krylov`: :func:`conjugate_gradient`, and the model problems
  :func:`poisson2d` and :func:`poisson3d`;
* :mod:`~mechnum.linear.direct`: :func:`least_squares` (QR, the SVD, the normal equations) and
  :func:`iterative_refinement`.
"""

from mechnum.linear.checks import OMEGAS_LIMIT, SUBNORMAL_FLOOR, check_matrix, condition_number
from mechnum.linear.direct import (
                                   LEAST_SQUARES_METHODS,
                                   REFINEMENT_CONTRACTION,
                                   REFINEMENT_MAXITER,
                                   REFINEMENT_TOL,
                                   LeastSquares,
                                   iterative_refinement,
                                   least_squares,
)
from mechnum.linear.krylov import (
                                   POISSON3D_LIMIT,
                                   POISSON_LIMIT,
                                   SYMMETRY_RTOL,
                                   conjugate_gradient,
                                   poisson2d,
                                   poisson3d,
)
from mechnum.linear.spectra import (
                                   BLOCK_ENTRIES,
                                   OMEGA_GRID,
                                   OMEGA_XTOL,
                                   OptimalOmega,
                                   iteration_matrix,
                                   optimal_omega,
                                   sor_spectral_radii,
                                   spectral_radius,
                                   young_omega,
)
from mechnum.linear.stationary import (
                                   CHUNK,
                                   CRITERIA,
                                   DIAGNOSTIC_ORDER,
                                   DIVERGENCE_GROWTH,
                                   MAXITER_LIMIT,
                                   NORMS,
                                   TOL,
                                   IterationResult,
                                   SorSweep,
                                   StoppingRule,
                                   gauss_seidel,
                                   jacobi,
                                   sor,
                                   sor_sweep,
)
from mechnum.linear.sweeps import METHODS, Splitting, splitting, sweep_by_components

__all__ = [
    # checks
    "check_matrix", "condition_number", "OMEGAS_LIMIT", "SUBNORMAL_FLOOR",
    # sweeps
    "METHODS", "sweep_by_components", "Splitting", "splitting",
    # spectra
    "OMEGA_GRID", "OMEGA_XTOL", "BLOCK_ENTRIES", "iteration_matrix", "spectral_radius",
    "sor_spectral_radii", "young_omega", "OptimalOmega", "optimal_omega",
    # stationary
    "TOL", "MAXITER_LIMIT", "CRITERIA", "NORMS", "DIVERGENCE_GROWTH", "CHUNK",
    "DIAGNOSTIC_ORDER", "StoppingRule",
    "IterationResult", "sor", "gauss_seidel", "jacobi", "SorSweep", "sor_sweep",
    # krylov
    "SYMMETRY_RTOL", "POISSON_LIMIT", "POISSON3D_LIMIT", "conjugate_gradient", "poisson2d",
    "poisson3d",
    # direct
    "LEAST_SQUARES_METHODS", "REFINEMENT_CONTRACTION", "REFINEMENT_TOL", "REFINEMENT_MAXITER",
    "LeastSquares", "least_squares",
    "iterative_refinement",
]
