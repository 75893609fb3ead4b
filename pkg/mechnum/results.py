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
instead of returning an unconverged result.

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

* ``converged``: the method's stopping test was met;
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
        unknown = set(np.ravel(self.status).tolist()) - set(STATUSES)
        if unknown:
            raise ValueError(f"status must be one of {STATUSES}, not {sorted(unknown)}")

    @property
    def converged(self) -> bool | np.ndarray:
        """bool, or ndarray of bool for a batch: whether the status is ``"converged"``."""
        converged = np.asarray(self.status) == "converged"
        return bool(converged) if converged.ndim == 0 else converged
