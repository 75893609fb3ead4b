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

from mechnum.mechanisms.elastica._model import Mechanism, PinnedRods, draw, forward

__all__ = ["Mechanism", "PinnedRods", "draw", "forward"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.elastica.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
