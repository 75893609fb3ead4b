"""The rigid 3PRR planar parallel mechanism of the thesis (its section 11.1, Annexes I and II).

Three legs carry a triangular platform of side ``a``. Each leg is a slider ``C_i`` on a fixed
guide (the prismatic input ``lambda_i``) and a bar of length ``L`` from ``C_i`` to a vertex
``P_i`` of the platform:

* leg 1: ``C1 = (lambda1, 0)``, bar to ``P1 = P = (x, y)``;
* leg 2: ``C2 = (B2 - lambda2, 0)``, bar to ``P2 = P + a (cos psi, sin psi)``;
* leg 3: ``C3 = (B3, H3 - lambda3)`` on the vertical guide ``x = B3``, bar to
  ``P3 = P + a (cos(psi + pi/3), sin(psi + pi/3))``.

The loop-closure equations, with the bar angles eliminated, are ``|P_i - C_i|^2 = L^2``
(:func:`loop_residuals`). Every function takes the mechanism, a :class:`Geometry`, first
(``f(mech, inputs, ...)``); poses are ``(x, y, psi)`` and inputs ``lambdas``; a state, what
:func:`draw` draws, is the pair ``(lambdas, pose)``. What the package holds:

* :class:`Geometry`, the vertices and sliders, the loop equations, their Jacobians in the
  pose and in the inputs, and the singularity measures (:func:`vertices`, :func:`sliders`,
  :func:`bars`, :func:`loop_residuals`, :func:`direct_jacobian`, :func:`inverse_jacobian`,
  :func:`jacobian_dets`, :func:`radicands`), each on checked input;
* the inverse problem (pose -> inputs), a line-circle cut per leg, up to 8 solutions
  (:func:`inverse`, :func:`branch_inputs`), and the workspace (:func:`workspace`);
* the study's degree-8 polynomial in ``t = tan(psi/2)`` (:func:`polynomial`), its factor
  ``1 + t^2`` (:func:`deflate`), and the same problem as four quadratics for a homotopy
  (:func:`equations`, :func:`solutions_from_equations`);
* the forward (direct) problem (inputs -> poses), at most 6 poses, for one input or
  thousands at once (:func:`forward`, a :class:`DirectSolution`), and Newton from many seeds
  as a check (:func:`forward_by_newton`);
* the singular poses along a segment (:func:`singular_points`), and a path of poses between
  two assembly modes of one input that crosses no singularity (:func:`mode_change_path`);
* :func:`draw`.

The study's examples, its Annex I as typeset, and its reproduction are in
:mod:`mechnum.mechanisms.prr3.study`.

Examples
--------
>>> from mechnum.mechanisms import prr3
>>> g = prr3.Geometry(L=1, a=1, B2=3, B3=2, H3=3)
>>> prr3.forward(g, [0.4, 0.1, 0.6]).counts.tolist()      # two poses for these inputs
2
"""

import importlib

# An import ``X as X``: a result that a function here returns, documented with it (book/api.md)
# but not in __all__ (returned, never called: mechnum.results.Result is its interface).
from mechnum.mechanisms.prr3._direct import DirectSolution as DirectSolution
from mechnum.mechanisms.prr3._direct import forward, forward_by_newton
from mechnum.mechanisms.prr3._drawing import draw
from mechnum.mechanisms.prr3._elimination import (
    deflate,
    equations,
    polynomial,
    solutions_from_equations,
)
from mechnum.mechanisms.prr3._geometry import (
    Geometry,
    jacobian_dets,
    radicands,
)
from mechnum.mechanisms.prr3._inverse import branch_inputs, inverse, workspace
from mechnum.mechanisms.prr3._paths import ModeChangePath as ModeChangePath
from mechnum.mechanisms.prr3._paths import mode_change_path
from mechnum.mechanisms.prr3._singularities import singular_points

__all__ = ["Geometry", "branch_inputs", "deflate", "draw", "equations", "forward",
           "forward_by_newton", "inverse", "jacobian_dets", "mode_change_path", "polynomial",
           "radicands", "singular_points", "solutions_from_equations", "workspace"]


def __getattr__(name: str) -> object:
    """The :mod:`~mechnum.mechanisms.prr3.study` module, imported on first use."""
    if name == "study":
        return importlib.import_module(f"{__name__}.study")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
