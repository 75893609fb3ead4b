"""The finger study's data, in metres, its examples, and its numbers recomputed, in its
millimetres.

The study prints its points and lengths in millimetres; the package works in metres, so its
tables are stored here converted (:data:`MM` metres per millimetre), and :func:`reproduce` gives
its numbers back in the study's units, keyed by the registry's ``quantity``, for the chapter's
reproduction table. :func:`published_points` reads a table of points as the study prints it
(from the registry) into metres, and :func:`column_shifts` compares two tables.

The study opens with two other examples: a system whose matrix is nearly singular (its example
1.1, :func:`ill_conditioned_example`) and a loop of nine vectors whose printed solution should
close (its Fig. 1: :data:`FIG1_GIVEN`, :data:`FIG1_PRINTED`, :func:`fig1_vectors`,
:func:`loop_closure`).
"""

import numpy as np
from numpy.typing import ArrayLike

from mechnum import _validate, linear
from mechnum.mechanisms.finger._examples import (
    FIG1_GIVEN,
    FIG1_PRINTED,
    fig1_vectors,
    ill_conditioned_example,
    loop_closure,
)
from mechnum.mechanisms.finger._model import (
    Linkage,
    angles_from_points,
    forward,
    inverse,
    place_links,
    workspace,
)
from mechnum.mechanisms.finger._synthesis import design_matrix, synthesize

__all__ = ["FIG1_GIVEN", "FIG1_PRINTED", "MM", "STUDY_OMEGAS", "TABLE1_EI", "TABLE1_R4",
           "TABLE2_THETA_IN", "TABLE2_THETA_IN_UNROUNDED", "TABLE2_THETA_OUT", "TABLE3_LINKAGE",
           "column_shifts", "fig1_vectors", "ill_conditioned_example", "loop_closure",
           "published_points", "reproduce", "table1_linkage"]

MM = 1e-3
"""Metres per millimetre: the study's unit of length, converted at the edges."""
#: Table 1 of the study: measured E (x, y) and I (x, y), ten positions, in metres (printed in
#: mm; input data).
TABLE1_EI = MM * np.array([
    [-18.9749, 24.0306, -11.9795, 24.2845], [-21.5732, 21.7281, -14.8085, 23.5277],
    [-23.8943, 19.1463, -17.6810, 22.5277], [-25.9081, 16.3183, -20.5152, 20.7811],
    [-27.5888, 13.2805, -23.2178, 18.7481], [-28.6413, 10.8254, -25.1450, 16.8897],
    [-29.4758, 8.2880, -26.8912, 14.7933], [-30.0860, 5.6875, -28.4154, 12.4852],
    [-30.4672, 3.0437, -29.6827, 9.9995], [-30.6166, 0.3767, -30.6660, 7.3765]])
#: Table 1: the length of the ground link DH, metres (H = (-6.9989, 0) mm, D = (0, 0)).
TABLE1_R4 = 6.9989 * MM
#: Table 2 of the study: input angles theta_3 and output angles theta_1, rad (input data).
TABLE2_THETA_IN = np.array([3.9357, 4.1277, 4.3197, 4.5117, 4.7037, 4.8956, 5.0876, 5.2796,
                            5.4716, 5.6636, 5.8556, 6.0474, 6.2396])
TABLE2_THETA_OUT = np.array([1.0400, 1.2574, 1.5410, 1.7736, 2.0165, 2.2205, 2.4094, 2.5722,
                             2.7305, 2.8828, 3.0331, 3.1822, 3.3298])
#: Table 2's input angles before rounding: 225.5 degrees and then steps of 11 degrees. Each
#: printed value rounds from it, except 6.0474 (a typo for 6.0476); Table 4 was computed from
#: these unrounded angles (the chapter shows both).
TABLE2_THETA_IN_UNROUNDED = np.radians(225.5 + 11.0 * np.arange(13))
#: The study's SOR relaxation factors (Tables 5 and 7 to 11).
STUDY_OMEGAS = (0.33, 0.28, 0.309, 0.2889, 0.3289)
#: Table 3's link lengths, metres (printed in mm; input data: the study builds Tables 4 and 11
#: from them).
TABLE3_LINKAGE = Linkage(30.6130 * MM, 6.9973 * MM, 24.7825 * MM, TABLE1_R4)
_POINT_TABLES = (1, 4, 5, 7, 8, 9, 10)  # the tables of points I and E the registry holds


def table1_linkage() -> Linkage:
    """One link-length set for Table 1: the medians of ``|DE|``, ``|EI|``, ``|HI|`` over its
    ten measured positions (the median ignores one corrupted row), metres.

    Examples
    --------
    >>> L = table1_linkage()
    >>> round(L.r1 / MM, 4), round(L.r2 / MM, 4), round(L.r3 / MM, 4)
    (30.6189, 7.0, 24.79)
    """
    E, I = TABLE1_EI[:, :2], TABLE1_EI[:, 2:]  # noqa: E741
    H = np.array([-TABLE1_R4, 0.0])
    return Linkage(float(np.median(np.linalg.norm(E, axis=1))),
                   float(np.median(np.linalg.norm(I - E, axis=1))),
                   float(np.median(np.linalg.norm(I - H, axis=1))), TABLE1_R4)


def published_points(published: dict, table: int,
                     positions: int = 13) -> tuple[np.ndarray, np.ndarray]:
    """A table of points as the study prints it, in metres: ``(I, E)``, shape ``(n, 2)`` each.

    Parameters
    ----------
    published : dict
        ``{quantity: printed text}`` of the registry (``read_published`` of the book's
        ``published`` module),
        with keys ``"Table <t> pos <i> <I|E> <x|y>"`` (printed in millimetres).
    table : int
        One of the tables of points: 1, 4, 5, 7, 8, 9, 10.
    positions : int, optional
        How many positions, 1 to 13.

    Raises
    ------
    ValueError
        If ``table`` is not a table of points, ``positions`` is out of range, or a point is
        missing from ``published`` or is no number.

    Examples
    --------
    >>> cells = {f"Table 4 pos 1 {p} {a}": v for p, a, v in
    ...          [("I", "x", "1"), ("I", "y", "2"), ("E", "x", "3"), ("E", "y", "4")]}
    >>> [(x / MM).round(12).tolist() for x in published_points(cells, 4, positions=1)]
    [[[1.0, 2.0]], [[3.0, 4.0]]]
    """
    table = _validate.choice(table, _POINT_TABLES, "table")
    positions = _validate.maxiter(positions, "positions", maximum=13)
    if not isinstance(published, dict):
        raise ValueError(f"published must be the registry's dict, got {published!r:.80}")
    keys = [[[f"Table {table} pos {i} {point} {axis}" for axis in "xy"]
             for i in range(1, positions + 1)] for point in "IE"]
    missing = [key for rows in keys for pair in rows for key in pair if key not in published]
    if missing:
        raise ValueError(f"published lacks {len(missing)} of the points, first {missing[0]!r}")
    try:
        values = np.array([[[float(published[k]) for k in pair] for pair in rows]
                           for rows in keys])
    except ValueError as error:
        raise ValueError(f"a printed point of table {table} is no number: {error}") from None
    return MM * values[0], MM * values[1]


def column_shifts(table: ArrayLike, reference: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """How far ``table`` is ``reference`` shifted by one constant per column.

    Parameters
    ----------
    table, reference : array_like, shape (m, k)
        Two tables of one shape, finite.

    Returns
    -------
    shifts : ndarray, shape (k,)
        The median difference of each column.
    spread : ndarray, shape (k,)
        The range (max - min) of each column's differences: zero, up to the rounding of the
        printed digits, if the table is the reference shifted.

    Raises
    ------
    ValueError
        If a table is not finite, not two-dimensional, empty, or the two differ in shape.

    Examples
    --------
    >>> shifts, spread = column_shifts([[1.5, 2.0], [2.5, 3.0]], [[1.0, 0.0], [2.0, 1.0]])
    >>> shifts.tolist(), spread.tolist()
    ([0.5, 2.0], [0.0, 0.0])
    """
    table = _validate.array(table, "table", ndim=2)
    reference = _validate.array(reference, "reference", shape=table.shape)
    if table.shape[0] == 0:
        raise ValueError("table must have at least one row")
    difference = table - reference
    return np.median(difference, axis=0), np.ptp(difference, axis=0)


def _table_rows(table, I, E):  # noqa: E741
    """Registry keys ``"Table <t> pos <i> <I|E> <x|y>"`` for the points (m) of a table, in mm."""
    return {f"Table {table} pos {i + 1} {name} {axis}": float(points[i, j] / MM)
            for i in range(len(I)) for name, points in (("I", I), ("E", E))
            for j, axis in enumerate("xy")}


def reproduce() -> dict[str, float]:
    """Every number of the registry's ``02_linear_systems_finger`` rows, computed afresh.

    Lengths and points in the study's millimetres, angles in radians.

    Returns
    -------
    dict of str to float

    Examples
    --------
    >>> round(reproduce()["Table 3 r1"], 4)
    35.0761
    """
    values = {}
    # Table 1: each point predicted from the other point's angle through one linkage.
    L1 = table1_linkage()
    theta_in, theta_out = angles_from_points(TABLE1_EI[:, :2], TABLE1_EI[:, 2:], TABLE1_R4)
    values.update(_table_rows(1, place_links(L1, inverse(L1, theta_out)[:, 0], theta_out).I,
                              place_links(L1, theta_in, forward(L1, theta_in).x[:, 0]).E))
    # Table 2: each angle from the other one through the published linkage (Table 3).
    published = TABLE3_LINKAGE
    ok = workspace(published, TABLE2_THETA_IN)
    for i, value in zip(np.flatnonzero(ok), forward(published, TABLE2_THETA_IN[ok]).x[:, 0]):
        values[f"Table 2 pos {i + 1} theta_1"] = float(value)
    ok = workspace(published, TABLE2_THETA_OUT, driver="output")
    for i, value in zip(np.flatnonzero(ok), inverse(published, TABLE2_THETA_OUT[ok])[:, 0]):
        values[f"Table 2 pos {i + 1} theta_3"] = float(value)
    # Table 3: the least-squares fit of Table 2. Table 4: the rockers of Table 3 placed at
    # Table 2's angles, the input ones unrounded (I depends on theta_in only, E on theta_out).
    fit = synthesize(TABLE2_THETA_IN, TABLE2_THETA_OUT, TABLE1_R4, "qr")
    for name in ("r1", "r2", "r3"):
        values[f"Table 3 {name}"] = getattr(fit.linkage, name) / MM
    placed = place_links(published, TABLE2_THETA_IN_UNROUNDED, TABLE2_THETA_OUT)
    values.update(_table_rows(4, placed.I, placed.E))
    # Tables 5 to 11: SOR on the normal equations for each omega, converged.
    for table, omega in zip((5, 7, 8, 9, 10), STUDY_OMEGAS):
        sol = synthesize(TABLE2_THETA_IN, TABLE2_THETA_OUT, TABLE1_R4, "sor", omega,
                         tol=1e-12, maxiter=20_000)
        placed = place_links(sol.linkage, TABLE2_THETA_IN, TABLE2_THETA_OUT)
        values.update(_table_rows(table, placed.I, placed.E))
        # r4 is the proposed input: every solution keeps it, so its error is zero
        for name in ("r1", "r2", "r3", "r4"):
            if omega == 0.33:
                values[f"Table 6 {name}"] = getattr(sol.linkage, name) / MM
            values[f"Table 11 omega={omega} {name}"] = abs(
                getattr(sol.linkage, name) - getattr(published, name)) / MM
    # The fixed pivots, D = (0, 0) and H = (-r4, 0), wherever the tables print them.
    for table in (4, 5):
        values[f"Table {table} H x"] = -TABLE1_R4 / MM
    for table in (7, 8, 9, 10):
        values.update({f"Table {table} H x": -TABLE1_R4 / MM, f"Table {table} H y": 0.0,
                       f"Table {table} D x": 0.0, f"Table {table} D y": 0.0})
    A, b = design_matrix(TABLE2_THETA_IN, TABLE2_THETA_OUT)
    values["best omega"] = linear.optimal_omega(A.T @ A).x
    # Example 1.1.
    (x, y), cond = ill_conditioned_example(1e-6, 1e-6)
    (x2, y2), _ = ill_conditioned_example(1e-6, 2e-6)
    values.update({"Example 1.1 x": x, "Example 1.1 y": y,
                   "Example 1.1 cond_inf(A), delta=1e-6": cond,
                   "Example 1.1 perturbed x": x2, "Example 1.1 perturbed y": y2})
    # The Fig. 1 example: how nearly its printed solution closes a loop (0 if it were one).
    values["Fig. 1 example loop closure"] = loop_closure(*fig1_vectors())[0]
    return {key: float(value) for key, value in values.items()}
