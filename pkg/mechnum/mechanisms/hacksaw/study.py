"""The hacksaw study's data, and its numbers recomputed for the registry's rows of Chapter 1.

The study's saw (:data:`STUDY`), the three seeds it uses (:data:`STUDY_SEED`, the MATLAB
code's; :data:`REPORT_SEED`, the report's, the six rates' signs flipped;
:data:`TRAJECTORY_SEED`, the first trajectory point's, the rounded solution at rest) and its
tolerance on the Euclidean norm of the Newton step (:data:`TOL`); :func:`reproduce` returns
every number of the study that the registry holds, keyed by the registry's ``quantity``.
"""

import numpy as np

from mechnum.mechanisms.hacksaw._exact import closed_form
from mechnum.mechanisms.hacksaw._model import (
    NAMES,
    REPORT_SEED,
    STUDY,
    STUDY_SEED,
    TOL,
    TRAJECTORY_SEED,
    first_revolution_time,
    motor,
)
from mechnum.mechanisms.hacksaw._solvers import solve_consecutive, solve_simultaneous, sweep

__all__ = ["REPORT_SEED", "STUDY", "STUDY_SEED", "TOL", "TRAJECTORY_SEED", "reproduce"]


def reproduce() -> dict[str, float]:
    """Recompute every number of the study that the registry holds (``book/published_values.csv``).

    Returns
    -------
    dict
        ``{quantity: value}`` keyed by the registry's ``quantity`` column for Chapter 1.

    Examples
    --------
    >>> values = reproduce()
    >>> values["iterations, simultaneous 9x9 at rest"]
    5
    """
    T = first_revolution_time()
    speed = float(motor(T)[1])
    rest = (0.0, 0.0, 0.0)
    pos, vel, acc = solve_consecutive(STUDY, rest, STUDY_SEED).stages
    simultaneous = solve_simultaneous(STUDY, rest, STUDY_SEED)
    t = np.linspace(0.0, 2 * T, 1000)
    exact = closed_form(STUDY, t)
    by_stage = {m: sweep(STUDY, t, m).x for m in ("consecutive", "simultaneous")}
    error = np.abs(by_stage["simultaneous"] - exact).max(axis=0)
    largest = {m: np.linalg.norm(x - exact, axis=1).max() for m, x in by_stage.items()}
    rpm = speed * 60 / (2 * np.pi)
    largest_rate = float(np.abs(simultaneous.x[3:]).max())
    values = {
        "first revolution time T (report)": T,
        "first revolution time T (slides)": T,
        "final motor speed": speed,
        "final motor speed in rpm (report)": rpm,
        "final motor speed in rpm (slides)": rpm,
        "two revolutions 2T (rounded)": 2 * T,
        "two revolutions 2T": 2 * T,
        "iterations, position stage at rest": pos.iterations,
        "iterations, velocity stage at rest": vel.iterations,
        "iterations, acceleration stage at rest": acc.iterations,
        "iterations, simultaneous 9x9 at rest": simultaneous.iterations,
        "largest |velocity| at rest (consecutive)": float(np.abs(vel.x).max()),
        "largest |acceleration| at rest (consecutive)": float(np.abs(acc.x).max()),
        "largest |rate| at rest (simultaneous)": largest_rate,
        "largest |velocity| at rest (slides)": float(np.abs(vel.x).max()),
        "largest |acceleration| at rest (slides)": float(np.abs(acc.x).max()),
        "largest |rate| at rest (slides, simultaneous)": largest_rate,
        "largest |simultaneous - consecutive| over the trajectory": float(
            np.linalg.norm(by_stage["simultaneous"] - by_stage["consecutive"], axis=1).max()),
        "largest error, simultaneous / consecutive": float(largest["simultaneous"]
                                                           / largest["consecutive"]),
        "largest error of positions and velocities (simultaneous)": float(error[:6].max()),
        "largest error of accelerations (simultaneous)": float(error[6:].max()),
        "largest error of all nine unknowns (simultaneous)": float(error.max()),
        "largest error of all nine unknowns (slides)": float(error.max()),
    }
    for label, x in (("consecutive", pos.x), ("simultaneous", simultaneous.x), ("slides", pos.x)):
        for name, value in zip(NAMES[:3], x):
            values[f"{name} at rest ({label})"] = float(value)
    for name, value in zip(NAMES[:3], pos.x):  # the slides print the rounded rest solution
        values[f"first trajectory seed {name} (slides)"] = float(value)
    return values
