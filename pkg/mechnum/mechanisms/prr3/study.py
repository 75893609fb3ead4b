"""The study's worked examples (Tables 3 to 6 of the thesis), its Annex I as typeset, and the
chapter's registry values.

:data:`EXAMPLES` and :data:`WORKSPACE_GEOMETRY` are the study's inputs; :func:`annex_i_terms`
reads the polynomial's coefficients as the study's Annex I typesets them, term by term, for the
chapter's audit; :func:`reproduce` recomputes every number of the registry's rows.
"""

import numpy as np

from mechnum.mechanisms.prr3._annex_i import annex_i_terms
from mechnum.mechanisms.prr3._direct import forward
from mechnum.mechanisms.prr3._elimination import polynomial
from mechnum.mechanisms.prr3._geometry import Geometry
from mechnum.mechanisms.prr3._inverse import inverse

__all__ = ["EXAMPLES", "WORKSPACE_GEOMETRY", "annex_i_terms", "reproduce"]

#: The study's worked examples (Tables 3 to 6 of its section 13.1): geometry and input of each
#: (a pose ``(x, y, psi)`` for the inverse problem, inputs ``lambdas`` for the direct one).
EXAMPLES = {
    "Table 3": (Geometry(L=1, a=1, B2=3, B3=1.5, H3=2), (0.6, 0.4, 0.0)),
    "Table 4": (Geometry(L=1, a=0.3, B2=3, B3=3, H3=3), (3.0, 0.3, np.pi / 4)),
    "Table 5": (Geometry(L=1, a=1, B2=3, B3=2.5, H3=2.8), (2.0, 0.5, 0.2)),
    "Table 6": (Geometry(L=1, a=1, B2=3, B3=2, H3=3), (0.4, 0.1, 0.6)),
}
#: The geometry of the study's workspace script (Annex II, section 2.1).
WORKSPACE_GEOMETRY = Geometry(L=1, a=1, B2=3, B3=2, H3=2)


def reproduce() -> dict[str, float]:
    """Every number of the registry rows of chapter ``04_rigid_3prr``, computed by this package.

    Tables 3 and 4 (inverse problem): the two values of each input (``+``: the branch adding the
    square root in equations 53, 57 and 61, the larger value), and the number of solutions.
    Tables 5 and 6 (direct problem): the two poses (``psi`` in degrees; solution 1 is the one
    with ``psi > 180``, listed first by the study) and their number.
    The count of roots of the degree-8 polynomial that can be real (Table 6's inputs): the roots
    other than ``t = +-i``.

    Returns
    -------
    dict of str to float

    Examples
    --------
    >>> values = reproduce()
    >>> values["Table 3 number of solutions"], round(values["Table 5 solution 2 x"], 4)
    (8.0, 1.5162)
    """
    values = {}
    for table in ("Table 3", "Table 4"):
        geometry, pose = EXAMPLES[table]
        lam = inverse(geometry, pose)
        values[f"{table} number of solutions"] = float(len(lam))
        for i in range(3):  # the + branch (adding the square root) gives the larger value
            values[f"{table} lambda{i + 1} (+)"] = float(lam[:, i].max())
            values[f"{table} lambda{i + 1} (-)"] = float(lam[:, i].min())
    for table in ("Table 5", "Table 6"):
        geometry, lam = EXAMPLES[table]
        poses = forward(geometry, lam).x
        values[f"{table} number of solutions"] = float(len(poses))
        study_order = (poses[poses[:, 2] > np.pi][0], poses[poses[:, 2] < np.pi][0])
        for number, pose in enumerate(study_order, start=1):
            for name, value in zip(("x", "y", "psi"), (pose[0], pose[1], np.degrees(pose[2]))):
                values[f"{table} solution {number} {name}"] = float(value)
    geometry, lam = EXAMPLES["Table 6"]
    roots = np.roots(polynomial(geometry, lam)[::-1])
    values["Annex I roots that can be real"] = float(np.sum(np.abs(np.abs(roots.imag) - 1)
                                                        + np.abs(roots.real) > 1e-6))
    return values
