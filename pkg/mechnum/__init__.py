"""mechnum: numerical methods for mechanisms, the companion package of the book.

Layers, each importing only the ones below it:

* methods: :mod:`mechnum.newton`, :mod:`mechnum.linear`, :mod:`mechnum.ode`,
  :mod:`mechnum.continuation`, :mod:`mechnum.homotopy`, :mod:`mechnum.polynomials`,
  :mod:`mechnum.certify` and :mod:`mechnum.rods` (the elastica, and
  :mod:`mechnum.mechanisms._assembly`, what every mechanism built of rods shares);
* mechanisms: :mod:`mechnum.mechanisms`, one subpackage per mechanism of the source studies.

Beside them: :mod:`mechnum.results` (the result contract), :mod:`mechnum.errors`,
:mod:`mechnum.plotting` and :mod:`mechnum.exercises`. Each public module lists its API in
``__all__``; the implementation lives in modules whose names start with an underscore.
``import mechnum`` is cheap: every subpackage is imported on its first use
(``mechnum.newton``), as :pep:`562` allows.

Examples
--------
>>> import mechnum
>>> mechnum.newton.solve(lambda x: x ** 2 - 4.0, [1.0]).x.round(12).tolist()
[2.0]
"""

import importlib

__all__ = ["certify", "continuation", "errors", "exercises", "homotopy", "linear", "mechanisms",
           "newton", "ode", "plotting", "polynomials", "results", "rods"]
__version__ = "0.1.0"


def __getattr__(name: str) -> object:
    """The subpackage ``name``, imported on first use."""
    if name in __all__:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list:
    return sorted(set(globals()) | set(__all__))
