"""One flexible rod: the mechanism of Chapter 3 and the flexible-mechanisms thesis's example.

A rod clamped at the origin along +x, its tip pinned at a point (:class:`Mechanism`; the study's
rod by default): :func:`forward` gives every equilibrium of the given modes through the point
(a :class:`PinnedRods`), and :func:`draw` draws one, as every mechanism of the package does.
The thesis's data, its own shooting loop and its reproduction are in
:mod:`mechnum.mechanisms.elastica.study`.

Examples
--------
>>> from mechnum.mechanisms import elastica
>>> found = elastica.forward(elastica.Mechanism(), [0.8, 0.1], modes=(1,))
>>> found.modes.tolist(), found.status.tolist()
([1], ['converged'])
"""

import importlib

from mechnum.mechanisms.elastica._model import Mechanism, draw, forward

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.mechanisms.elastica._model import PinnedRods as PinnedRods

__all__ = ["Mechanism", "draw", "forward"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.elastica.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
