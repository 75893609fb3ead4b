"""Errors raised by :mod:`mechnum`.

Every failure to produce the one answer a function promises raises a subclass of
:class:`MechnumError` whose message names the cause and the numbers involved. Non-finite or
ill-shaped input raises the built-in :class:`ValueError` at the entry point instead.
"""

__all__ = ["ConvergenceError", "DivergenceError", "GeometryError", "MechnumError",
           "NonFiniteError", "RelaxationFactorError", "SingularJacobianError",
           "UnreachablePoseError"]


class MechnumError(Exception):
    """Base class of every error that :mod:`mechnum` raises on purpose.

    Parameters
    ----------
    message : str
        What happened, with the numbers involved (iteration count, norms, offending input).
    result : object, optional
        The partial result where there is one (for example a :class:`mechnum.newton.NewtonResult`),
        kept so that the caller can inspect the history.
    """

    def __init__(self, message: str, result: object = None) -> None:
        super().__init__(message)
        self.result = result


class ConvergenceError(MechnumError):
    """An iteration stopped without meeting its tolerance."""


class DivergenceError(ConvergenceError):
    """An iteration was detected to diverge (growing residual or overflow)."""


class NonFiniteError(MechnumError):
    """A computation from finite input produced NaN or infinity: a user function returned a
    non-finite value at a finite argument, or the numbers overflowed (an integration step far
    too large for the equation, a root beyond the largest float)."""


class SingularJacobianError(MechnumError):
    """A Jacobian (or a system matrix) is singular, or numerically so, where it must be inverted."""


class UnreachablePoseError(MechnumError):
    """A mechanism cannot be assembled in the requested pose."""


class GeometryError(MechnumError):
    """A mechanism's geometry is degenerate (zero or negative lengths, coincident pivots, ...)."""


class RelaxationFactorError(MechnumError, ValueError):
    """An SOR relaxation factor lies outside (0, 2), where SOR cannot converge (Kahan)."""
