"""The finger study's two other examples: an ill-conditioned system and a loop of vectors.

The study opens with a system whose matrix is nearly singular (its example 1.1,
:func:`ill_conditioned_example`) and a loop of nine vectors whose printed solution should close
(its Fig. 1, :func:`fig1_vectors`, :func:`loop_closure`).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, linear
from mechnum.errors import SingularJacobianError
from mechnum.mechanisms.finger._model import unit

#: The opening example of the study (its Fig. 1): the given lengths (m) and angles (degrees)
#: of its nine vectors ``p_i at theta_i``, as the study prints them (input data).
FIG1_GIVEN = {"p1": 2.0, "p2": 2.0, "p5": 6.0, "p6": 4.0, "p7": 6.0, "p8": 1.0,
              "theta1": 0.0, "theta7": 0.0, "theta8": -90.0, "theta9": 0.0}
#: The example's printed solution for its eight unknowns: the data under test (the registry
#: holds the same numbers; a test checks that the two agree).
FIG1_PRINTED = {"p3": 8.0, "p4": 8.0, "p9": 9.91, "theta2": 175.63, "theta3": 173.71,
                "theta4": 157.47, "theta5": 20.08, "theta6": 88.12}
MAX_VECTORS = 12
"""The most vectors of :func:`loop_closure`: it searches ``3^n`` sign patterns (531441 for 12,
some 50 MB)."""
# Machine epsilon: example 1.1's ``A`` is singular to working precision when
# ``cond_inf(A) * eps >= 1``.
_EPS = np.finfo(float).eps


def ill_conditioned_example(delta: float, rhs_shift: float) -> tuple[np.ndarray, float]:
    """The study's example 1.1: ``x - 2y = 1``, ``x - (2 + delta) y = 1 + rhs_shift``.

    Returns
    -------
    solution : ndarray, shape (2,)
    cond_inf : float
        ``||A||_inf ||A^-1||_inf``, equal to ``(3 + delta)(4 + delta) / delta`` for
        ``delta > 0`` (for the ``delta`` that the rounded ``2 + delta`` represents).

    Raises
    ------
    ValueError
        Non-finite input.
    SingularJacobianError
        ``delta`` so small that ``A`` is singular to working precision (``delta = 0``: the
        two equations are parallel).

    Examples
    --------
    >>> x, c = ill_conditioned_example(0.5, 0.5)
    >>> x.round(12).tolist(), round(c, 9)
    ([-1.0, -1.0], 31.5)
    """
    delta = _validate.scalar(delta, "delta")
    shift = _validate.scalar(rhs_shift, "rhs_shift")
    A = np.array([[1.0, -2.0], [1.0, -(2.0 + delta)]])
    cond = linear.condition_number(A, np.inf)
    if cond * _EPS >= 1:
        raise SingularJacobianError(
            f"delta = {delta!r} makes A singular to working precision (cond_inf = {cond:.3g}): "
            f"the two equations are parallel")
    return np.linalg.solve(A, [1.0, 1.0 + shift]), cond


def loop_closure(lengths: ArrayLike, angles: ArrayLike,
                 terms: tuple[int, int] = (3, 5)) -> tuple[float, np.ndarray, int]:
    """The signed sum of a few of the vectors ``lengths[i] at angles[i]`` closest to zero.

    A solution of a linkage's loop equations closes its loops: some sum of its vectors, each
    taken with sign +1, -1 or 0, vanishes. This searches every such sum of ``terms[0]`` to
    ``terms[1]`` vectors (``3^n`` sign patterns: at most :data:`MAX_VECTORS` vectors).

    Parameters
    ----------
    lengths : array_like, shape (n,)
        ``1 <= n <=`` :data:`MAX_VECTORS`.
    angles : array_like, shape (n,)
        Degrees.
    terms : (int, int), optional
        The smallest and largest number of vectors in a sum, ``1 <= terms[0] <= terms[1]``.

    Returns
    -------
    miss : float
        The smallest ``max(|sum_x|, |sum_y|)`` over the sums searched.
    signs : ndarray of int, shape (n,)
        The signs of that sum.
    count : int
        The number of sums searched.

    Raises
    ------
    ValueError
        If the vectors are not finite, their number is out of range, or ``terms`` is not two
        counts in order (none of the sums would be searched).

    Examples
    --------
    >>> miss, signs, count = loop_closure([1.0, 1.0, 2.0], [0.0, 0.0, 180.0])
    >>> round(miss, 12), signs.tolist(), count
    (0.0, [-1, -1, -1], 8)
    """
    lengths = _validate.array(lengths, "lengths", ndim=1)
    angles = _validate.array(angles, "angles", shape=lengths.shape)
    n = _validate.maxiter(lengths.size, "the number of vectors", maximum=MAX_VECTORS)
    try:
        low, high = (_validate.maxiter(t, "terms") for t in terms)
    except (TypeError, ValueError) as error:
        raise ValueError(f"terms must be two counts (fewest, most), got {terms!r:.80}: "
                         f"{error}") from None
    if not low <= high:
        raise ValueError(f"terms must be (fewest, most) with fewest <= most, got {terms!r}")
    vectors = lengths[:, None] * unit(np.radians(angles))
    signs = np.array(np.meshgrid(*[[-1, 0, 1]] * n)).reshape(n, -1).T
    used = np.abs(signs).sum(axis=1)
    signs = signs[(used >= low) & (used <= high)]
    if not len(signs):
        raise ValueError(f"no sum of {low} to {high} of the {n} vectors exists")
    misses = np.abs(signs @ vectors).max(axis=1)
    best = int(np.argmin(misses))
    return float(misses[best]), signs[best], len(signs)


def fig1_vectors(printed: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The lengths and angles (degrees) of the nine vectors of the study's Fig. 1 example.

    Parameters
    ----------
    printed : dict, optional
        The printed unknowns (``"p3"``, ..., ``"theta6"``) as numbers or printed text;
        :data:`FIG1_PRINTED` by default.

    Raises
    ------
    ValueError
        If ``printed`` is not a dict of the eight unknowns, each a finite number.

    Examples
    --------
    >>> lengths, angles = fig1_vectors()
    >>> lengths.tolist()[:4], angles.tolist()[-2:]
    ([2.0, 2.0, 8.0, 8.0], [-90.0, 0.0])
    """
    printed = FIG1_PRINTED if printed is None else printed
    if not isinstance(printed, dict) or set(printed) != set(FIG1_PRINTED):
        raise ValueError(f"printed must be a dict of the unknowns {sorted(FIG1_PRINTED)}, got "
                         f"{printed!r:.80}")
    try:
        values = FIG1_GIVEN | {name: float(v) for name, v in printed.items()}
    except (TypeError, ValueError) as error:
        raise ValueError(f"printed must hold numbers: {error}") from None
    lengths = _validate.array([values[f"p{i}"] for i in range(1, 10)], "the lengths")
    return lengths, _validate.array([values[f"theta{i}"] for i in range(1, 10)], "the angles")
