"""The crossed four-bar of a robotic finger's proximal phalanx (the finger study, Chapter 2).

Frame and names of the study's tables: the output pivot ``D`` is the origin, the input pivot
``H = (-r4, 0)``; ``DE`` (length ``r1``) and ``HI`` (length ``r3``) are the two rockers, ``EI``
(length ``r2``) the coupler. The loop closure is ``r1 + r2 + r3 = r4`` as vectors, with

* ``theta_out`` (the study's theta_1): the angle of ``D -> E``, ``E = r1 (cos, sin)(theta_out)``;
* ``theta_in`` (the study's theta_3): the angle of ``I -> H``, ``I = H - r3 (cos, sin)(theta_in)``;
* the ground vector ``r4`` points along ``-x`` (theta_4 = pi).

Every function takes the mechanism, a :class:`Linkage` in metres, first (``f(mech, inputs,
...)``); ``theta_in`` is the input, ``theta_out`` the output, and a state, what :func:`draw`
draws, is the pair ``(theta_in, theta_out)``. The study's millimetres appear only in
:mod:`~mechnum.mechanisms.finger.study`'s :func:`reproduce` (its printed units) and in the
conversion :data:`MM`. The package's modules:

* :mod:`~mechnum.mechanisms.finger.model`: :class:`Linkage`, the assembly modes
  (:func:`forward`, :func:`inverse`), where the linkage assembles (:func:`workspace`), the
  points of given angles (:func:`place_links`, a :class:`Pose`);
* :mod:`~mechnum.mechanisms.finger.synthesis`: Freudenstein's equation by least squares
  (:func:`design_matrix`, :func:`synthesize`, :func:`linkage_from_coefficients`);
* :mod:`~mechnum.mechanisms.finger.drawing`: :func:`draw`;
* :mod:`~mechnum.mechanisms.finger.examples`: the study's example 1.1 and its Fig. 1 loop;
* :mod:`~mechnum.mechanisms.finger.study`: the study's tables (in metres) and
  :func:`reproduce`.

Version 0.1's ``pose``, ``pose_from_output``, ``reachable``, the order with the linkage after
the angles, ``draw(ax, pose, index, lines=)`` and its millimetre tables are gone or deprecated
(CHANGELOG.md).
"""

from mechnum.mechanisms.finger.drawing import draw
from mechnum.mechanisms.finger.examples import (
                                                FIG1_GIVEN,
                                                FIG1_PRINTED,
                                                MAX_VECTORS,
                                                fig1_vectors,
                                                ill_conditioned_example,
                                                loop_closure,
)
from mechnum.mechanisms.finger.model import (
                                                CROSSED,
                                                MODES,
                                                OPEN,
                                                Linkage,
                                                Pose,
                                                angles_from_points,
                                                forward,
                                                freudenstein_coefficients,
                                                inverse,
                                                place_links,
                                                pose,
                                                pose_from_output,
                                                reachable,
                                                workspace,
)
from mechnum.mechanisms.finger.study import (
                                                MM,
                                                STUDY_OMEGAS,
                                                TABLE1_EI,
                                                TABLE1_R4,
                                                TABLE2_THETA_IN,
                                                TABLE2_THETA_IN_UNROUNDED,
                                                TABLE2_THETA_OUT,
                                                TABLE3_LINKAGE,
                                                column_shifts,
                                                published_points,
                                                reproduce,
                                                table1_linkage,
)
from mechnum.mechanisms.finger.synthesis import (
                                                Synthesis,
                                                design_matrix,
                                                lengths_from_coefficients,
                                                linkage_from_coefficients,
                                                synthesize,
)

__all__ = [
    # model
    "CROSSED", "OPEN", "MODES", "Linkage", "Pose", "freudenstein_coefficients", "forward",
    "inverse", "workspace", "place_links", "angles_from_points", "pose", "pose_from_output",
    "reachable",
    # synthesis
    "Synthesis", "design_matrix", "synthesize", "lengths_from_coefficients",
    "linkage_from_coefficients",
    # drawing
    "draw",
    # examples
    "FIG1_GIVEN", "FIG1_PRINTED", "MAX_VECTORS", "ill_conditioned_example", "loop_closure",
    "fig1_vectors",
    # study
    "MM", "TABLE1_EI", "TABLE1_R4", "TABLE2_THETA_IN", "TABLE2_THETA_OUT",
    "TABLE2_THETA_IN_UNROUNDED", "STUDY_OMEGAS", "TABLE3_LINKAGE", "table1_linkage",
    "published_points", "column_shifts", "reproduce",
]
