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
:func:`draw` draws, is the pair ``(lambdas, pose)``. The package's modules:

* :mod:`~mechnum.mechanisms.prr3.geometry`: :class:`Geometry`, the vertices, the loop
  equations, their Jacobians in the pose and in the inputs, and the singularity measures, each
  on checked input; :mod:`~mechnum.mechanisms.prr3.kernels` holds their formulas;
* :mod:`~mechnum.mechanisms.prr3.inverse`: the inverse problem (pose -> inputs), a line-circle
  cut per leg, up to 8 solutions (:func:`inverse`, :func:`branch_inputs`), and the workspace;
* :mod:`~mechnum.mechanisms.prr3.elimination`: the study's degree-8 polynomial in
  ``t = tan(psi/2)`` (:func:`polynomial`), its factor ``1 + t^2`` (:func:`deflate`), and the
  same problem as four quadratics for a homotopy (:func:`equations`);
* :mod:`~mechnum.mechanisms.prr3.direct`: the forward (direct) problem (inputs -> poses), at
  most 6 poses, for one input or thousands at once (:func:`forward`), and Newton from many
  seeds as a check (:func:`forward_by_newton`);
* :mod:`~mechnum.mechanisms.prr3.singularities`: the singular poses along a segment
  (:func:`singular_points`);
* :mod:`~mechnum.mechanisms.prr3.paths`: a path of poses between two assembly modes of one
  input that crosses no singularity (:func:`mode_change_path`);
* :mod:`~mechnum.mechanisms.prr3.drawing`: :func:`draw`;
* :mod:`~mechnum.mechanisms.prr3.study`: the study's examples (:data:`EXAMPLES`) and
  :func:`reproduce`;
* :mod:`~mechnum.mechanisms.prr3.annex_i`: the polynomial's coefficients as typeset in the
  study's Annex I, term by term (:func:`annex_i_terms`), for the chapter's audit.

The names of version 0.1, ``direct`` and ``direct_by_newton``, and the argument order with the
geometry last, are deprecated (CHANGELOG.md).
"""

from mechnum.mechanisms.prr3.annex_i import annex_i_terms
from mechnum.mechanisms.prr3.direct import (
                                            DirectSolution,
                                            direct,
                                            direct_by_newton,
                                            forward,
                                            forward_by_newton,
)
from mechnum.mechanisms.prr3.drawing import draw
from mechnum.mechanisms.prr3.elimination import (
                                            deflate,
                                            equations,
                                            polynomial,
                                            solutions_from_equations,
)
from mechnum.mechanisms.prr3.geometry import (
                                            Geometry,
                                            bars,
                                            direct_jacobian,
                                            inverse_jacobian,
                                            jacobian_dets,
                                            loop_residuals,
                                            radicands,
                                            sliders,
                                            vertices,
)
from mechnum.mechanisms.prr3.inverse import branch_inputs, inverse, workspace
from mechnum.mechanisms.prr3.paths import mode_change_path
from mechnum.mechanisms.prr3.singularities import singular_points
from mechnum.mechanisms.prr3.study import EXAMPLES, WORKSPACE_GEOMETRY, reproduce

__all__ = ["DirectSolution", "EXAMPLES", "Geometry", "WORKSPACE_GEOMETRY", "annex_i_terms",
           "bars", "branch_inputs", "deflate", "direct", "direct_by_newton", "direct_jacobian",
           "draw", "equations", "forward", "forward_by_newton", "inverse", "inverse_jacobian",
           "jacobian_dets", "loop_residuals", "mode_change_path", "polynomial", "radicands",
           "reproduce", "singular_points", "sliders", "solutions_from_equations", "vertices",
           "workspace"]
