"""The result contract: what every iterative method of :mod:`mechnum` returns.

Newton's method and its relatives, the stationary and Krylov methods, homotopy, continuation,
shooting and the interval search all answer in one shape, as scipy's ``OptimizeResult`` does:

* ``x``: the answer (the last iterate; for a batch, one row per system);
* ``status``: what happened, one word of :data:`STATUSES` (for a batch, one per system);
* ``converged``: whether the status is ``"converged"`` (a bool, or one per system);
* ``message``: the status in a sentence, with the numbers that explain it;
* ``iterations``, ``nfev``, ``njev``: the work done (iterations per system for a batch; calls of
  the residual and of the Jacobian).

A method adds its own fields to these (a history, the residual norms, a path), and a function that
must give one answer and cannot raises a named subclass of :class:`mechnum.errors.MechnumError`
instead of returning an unconverged result. When an iteration stops is one
:class:`StoppingRule` for every iterative method (Newton's, the stationary and Krylov methods).

Examples
--------
>>> import numpy as np
>>> from mechnum.results import Result
>>> r = Result(x=np.array([1.0]), status="converged", message="step below 1e-10",
...            iterations=5, nfev=6, njev=5)
>>> bool(r.converged)
True
>>> batch = Result(x=np.zeros((2, 1)), status=np.array(["converged", "maxiter"]),
...                message="1 of 2 converged", iterations=np.array([4, 50]), nfev=51, njev=50)
>>> batch.converged
array([ True, False])
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate

__all__ = ["STATUSES", "Assemblies", "Result", "StoppingRule", "status_counts"]

STATUSES = (
    "converged",
    "maxiter",
    "singular",
    "non-finite",
    "stagnated",
    "diverged",
    "left-domain",
    "branch-jump",
    "lost",
    "undecided",
)
"""The one vocabulary of ``status``, shared by every method:

* ``converged``: the method's stopping test was met (a direct method: it solved the problem);
* ``maxiter``: it ran out of iterations (or steps) first;
* ``singular``: a Jacobian (or a linear system) it had to solve was singular;
* ``non-finite``: a residual, a Jacobian or an iterate stopped being finite;
* ``stagnated``: no progress: a line search found no decrease, or a step length shrank below its
  floor;
* ``diverged``: the iterates grew without bound while still finite (a stationary method whose
  residual grew far beyond its start: its iteration matrix has a spectral radius above one).
  Added to the first seven words because neither ``non-finite`` (the numbers are still finite)
  nor ``stagnated`` (there is progress, the wrong way) says it, and the linear solvers detect it
  long before an overflow;
* ``left-domain``: an iterate left the domain where the equations make sense;
* ``branch-jump``: a path-following method left the branch it followed (a sign change of the
  Jacobian's determinant, or a step in the unknowns beyond its bound): the point is not part of the
  path;
* ``lost``: a tracked path could not be followed to its end;
* ``undecided``: a proof (an interval test) could neither confirm nor exclude.
"""


def status_counts(status: ArrayLike) -> dict:
    """How many systems (paths, starts) ended in each word of :data:`STATUSES`.

    Examples
    --------
    >>> counts = status_counts(np.array(["converged", "maxiter", "converged"]))
    >>> counts["converged"], counts["maxiter"], counts["lost"]
    (2, 1, 0)
    """
    status = np.asarray(status)
    return {word: int(np.sum(status == word)) for word in STATUSES}


@dataclass(frozen=True, kw_only=True)
class Result:
    """The fields every iterative method returns; methods subclass it to add their own.

    Attributes
    ----------
    x : ndarray
        The answer: the last iterate, shape ``(n,)``, or one row per system of a batch.
    status : str or ndarray of str
        One word of :data:`STATUSES`, or one per system of a batch.
    message : str
        The status in a sentence, with the numbers that explain it.
    iterations : int or ndarray of int
        Iterations taken (one per system of a batch).
    nfev, njev : int
        Calls of the residual and of the Jacobian.
    """

    x: np.ndarray
    status: object
    message: str
    iterations: object
    nfev: int
    njev: int

    def __post_init__(self):
        status = np.ravel(self.status)
        # a batch whose systems all ended alike (the usual one) is one word to check
        words = ({str(status[0])} if status.size and (status == status[0]).all()
                 else set(status.tolist()))
        unknown = words - set(STATUSES)
        if unknown:
            raise ValueError(f"status must be one of {STATUSES}, not {sorted(unknown)}")

    @property
    def converged(self) -> bool | np.ndarray:
        """bool, or ndarray of bool for a batch: whether the status is ``"converged"``."""
        converged = np.asarray(self.status) == "converged"
        return bool(converged) if converged.ndim == 0 else converged


@dataclass(frozen=True, kw_only=True)
class Assemblies(Result):
    """Every assembly mode of a rigid mechanism at its inputs, from a closed form.

    What ``forward(mech, inputs)`` returns where a mechanism's forward problem has a closed
    form (the hacksaw, the finger, the actuator): each input gives the same number of
    assembly modes, or none (then the function raises
    :class:`~mechnum.errors.UnreachablePoseError`, naming the input).

    Attributes
    ----------
    x : ndarray, shape (..., modes, n), or (..., modes) for one unknown
        The ``n`` unknowns of every assembly mode (the study's mode first) at every input.
    status : str
        ``"converged"``: a closed form.
    message : str
        How many inputs and modes.
    iterations, nfev, njev : int
        Zero: nothing is iterated.
    inputs : ndarray, shape (...) or (..., k)
        The inputs, as the mechanism names them.

    Examples
    --------
    >>> out = Assemblies(x=np.zeros((4, 2, 3)), status="converged", message="4 inputs, 2 modes",
    ...                  iterations=0, nfev=0, njev=0, inputs=np.arange(4.0))
    >>> out.x[:, 0].shape, out.converged
    ((4, 3), True)
    """

    inputs: np.ndarray

    @classmethod
    def of(cls, x: np.ndarray, inputs: np.ndarray, count: int, modes: int) -> "Assemblies":
        """The result of a closed form's unknowns ``x`` at ``count`` inputs ``inputs``,
        ``modes`` assembly modes at each."""
        return cls(x=x, status="converged", iterations=0, nfev=0, njev=0, inputs=inputs,
                   message=f"{modes} assembly modes at each of {count} inputs, in closed form")


CRITERIA = ("step", "residual")
"""The stopping criteria: on the step, or on the residual."""
NORMS = (1, 2, np.inf)
"""The vector norms of a criterion (the ``ord`` of :func:`numpy.linalg.norm`)."""


@dataclass(frozen=True)
class StoppingRule:
    """When an iteration stops: the options every iterative method of :mod:`mechnum` takes.

    Each method says what its step and its residual are (Newton's full step, the step of SOR
    divided by ``omega``; ``f(x_k)`` or ``b - A x_k``), and what a relative test is relative to
    (``||x_{k+1}||`` for the step; ``||f(x_0)||`` or ``||b||`` for the residual).

    Attributes
    ----------
    tol : float
        The tolerance, positive.
    maxiter : int
        Most iterations (steps, sweeps), at least 1.
    criterion : {"step", "residual"}
        Stop on the size of a step, or on the size of the residual.
    norm : {2, 1, inf}
        The ``ord`` of :func:`numpy.linalg.norm` for the criterion.
    relative : bool
        Whether the test is relative (``||dx|| <= tol ||x||``) or absolute (``<= tol``).

    Examples
    --------
    >>> rule = StoppingRule.checked(1e-8, 20, "residual", 2, None, maxiter_limit=1000)
    >>> rule.relative, rule.norm
    (False, 2)
    >>> StoppingRule.checked(-1.0, 20, maxiter_limit=1000)
    Traceback (most recent call last):
    ...
    ValueError: tol must be positive, got -1.0
    """

    tol: float
    maxiter: int
    criterion: str = "step"
    norm: float = 2
    relative: bool = True

    @classmethod
    def checked(cls, tol: object, maxiter: object, criterion: object = "step",
                norm: object = 2, relative: object = None, *,
                maxiter_limit: int) -> "StoppingRule":
        """The rule of a solver's arguments, checked at its door.

        ``relative=None`` makes the step test relative (the iterates carry their scale) and the
        residual test absolute (the caller scales the equations); ``maxiter_limit`` is the
        solver's bound on ``maxiter``.

        Raises
        ------
        ValueError
            If ``tol`` is not positive, ``maxiter`` not an integer in
            ``[1, maxiter_limit]``, or ``criterion``, ``norm`` or ``relative`` not one of
            their options.
        """
        criterion = _validate.choice(criterion, CRITERIA, "criterion")
        relative = (criterion == "step" if relative is None
                    else _validate.flag(relative, "relative"))
        return cls(_validate.tolerance(tol),
                   _validate.maxiter(maxiter, maximum=maxiter_limit), criterion,
                   _validate.choice(norm, NORMS, "norm"), relative)
