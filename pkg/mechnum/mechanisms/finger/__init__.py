"""The crossed four-bar of a robotic finger's proximal phalanx (the finger study, Chapter 2).

Frame and names of the study's tables: the output pivot ``D`` is the origin, the input pivot
``H = (-r4, 0)``; ``DE`` (length ``r1``) and ``HI`` (length ``r3``) are the two rockers, ``EI``
(length ``r2``) the coupler. The loop closure is ``r1 + r2 + r3 = r4`` as vectors, with

* ``theta_out`` (the study's theta_1): the angle of ``D -> E``, ``E = r1 (cos, sin)(theta_out)``;
* ``theta_in`` (the study's theta_3): the angle of ``I -> H``, ``I = H - r3 (cos, sin)(theta_in)``;
* the ground vector ``r4`` points along ``-x`` (theta_4 = pi).

Every function takes the mechanism, a :class:`Linkage` in metres, first (``f(mech, inputs,
...)``); ``theta_in`` is the input, ``theta_out`` the output, and a state, what :func:`draw`
draws, is the pair ``(theta_in, theta_out)``. What the package holds:

* :class:`Linkage`, the assembly modes (:func:`forward`, :func:`inverse`), where the linkage
  assembles (:func:`workspace`), the points of given angles (:func:`place_links`, a
  :class:`Pose`) and the angles of given points (:func:`angles_from_points`);
* Freudenstein's equation by least squares (:func:`freudenstein_coefficients`,
  :func:`design_matrix`, :func:`synthesize`, :func:`lengths_from_coefficients`,
  :func:`linkage_from_coefficients`);
* :func:`draw`.

The study's tables (in metres; it prints millimetres), its two other examples and its
reproduction are in :mod:`mechnum.mechanisms.finger.study`.

Examples
--------
>>> from mechnum.mechanisms import finger
>>> L = finger.Linkage(0.030613, 0.0069973, 0.0247825, 0.0069989)
>>> finger.forward(L, [5.0]).x.round(6).tolist()    # the crossed and the open assembly
[[2.32172, 1.88642]]
"""

import importlib

from mechnum.mechanisms.finger._drawing import draw
from mechnum.mechanisms.finger._model import (
    Linkage,
    angles_from_points,
    forward,
    freudenstein_coefficients,
    inverse,
    place_links,
    workspace,
)

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called): the points of a pose, and the synthesis (a Result).
from mechnum.mechanisms.finger._model import Pose as Pose
from mechnum.mechanisms.finger._synthesis import Synthesis as Synthesis
from mechnum.mechanisms.finger._synthesis import (
    design_matrix,
    lengths_from_coefficients,
    linkage_from_coefficients,
    synthesize,
)

__all__ = ["Linkage", "angles_from_points", "design_matrix", "draw", "forward",
           "freudenstein_coefficients", "inverse", "lengths_from_coefficients",
           "linkage_from_coefficients", "place_links", "synthesize", "workspace"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.finger.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
