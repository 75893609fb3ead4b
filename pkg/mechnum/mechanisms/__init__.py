"""The mechanisms of the book's source studies, one subpackage each.

Every mechanism follows one protocol (CONTRIBUTING.md, "How to add a mechanism"): a frozen
dataclass of its parameters passed first, ``forward(mech, inputs)`` returning a result of
:mod:`mechnum.results`, ``draw(ax, mech, state, *, artists=None)``, and the study's data and
reproduction in its ``study`` module. ``thesis`` holds the constants that the flexible
mechanisms' thesis (Chapters 5 and 6) shares. Each is imported on its first use.

The two mechanisms built of rods (:mod:`~mechnum.mechanisms.rfr2`,
:mod:`~mechnum.mechanisms.pfr3`) share their results, given here as attributes (returned, never
called: not in ``__all__``): :class:`Equilibria` (every equilibrium of an all-solutions
search), :class:`Path` (one followed along a path or over a grid), :class:`ShotEquilibria`
(equilibria by RK4 shooting), :class:`Atlas` (the equilibria over a grid of the inputs),
:class:`Jacobians` (both problems' determinants); and the one name a user makes,
:class:`State` (one equilibrium, as their ``draw`` and ``workspace`` take it).

Examples
--------
>>> from mechnum import mechanisms
>>> mechanisms.hacksaw.study.STUDY.r2
0.075
"""

import importlib

_MECHANISMS = ("actuator", "elastica", "finger", "hacksaw", "pfr3", "prr3", "rfr2", "thesis")
_SHARED = ("State",)
_RESULTS = ("Atlas", "Equilibria", "Jacobians", "Path", "ShotEquilibria")

__all__ = [*_MECHANISMS, *_SHARED]


def __getattr__(name: str) -> object:
    """The mechanism ``name``, or a result the rod mechanisms share, imported on first use."""
    if name in _MECHANISMS:
        return importlib.import_module(f"{__name__}.{name}")
    if name in _SHARED + _RESULTS:
        return getattr(importlib.import_module(f"{__name__}._assembly"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list:
    return sorted(set(globals()) | set(__all__) | set(_RESULTS))
