"""The mechanisms of the book's source studies, one subpackage each.

Every mechanism follows one protocol (CONTRIBUTING.md, "How to add a mechanism"): a frozen
dataclass of its parameters passed first, ``forward(mech, inputs)`` returning a result of
:mod:`mechnum.results`, ``draw(ax, mech, state, *, artists=None)``, and the study's data and
reproduction in its ``study`` module. ``thesis`` holds the constants that the flexible
mechanisms' thesis (Chapters 5 and 6) shares. Each is imported on its first use.

Examples
--------
>>> from mechnum import mechanisms
>>> mechanisms.hacksaw.STUDY.r2
0.075
"""

import importlib

__all__ = ["actuator", "elastica", "finger", "hacksaw", "pfr3", "prr3", "rfr2", "thesis"]


def __getattr__(name: str) -> object:
    """The mechanism ``name``, imported on first use."""
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list:
    return sorted(set(globals()) | set(__all__))
