"""The constants of the flexible-mechanisms study (seed 001), once, for the 2RFR and the 3PFR.

The study's programs for both mechanisms (Annex II 3.1 and 4.1) build their rods of the same
steel: length ``L = 1`` m, Young's modulus ``E = 210`` GPa, a circular section of diameter
``1.5`` mm (so ``EI = E pi d**4 / 64``), integrated by RK4 on 41 nodes.

The study names no material beyond ``E``, and no strength. A rod that must bend this far and
spring back is spring wire; for a steel wire of 1.5 mm the common one is **music wire**, ASTM
A228 (cold-drawn high-carbon spring steel). Its bending elastic limit, from Budynas and
Nisbett, *Shigley's Mechanical Engineering Design* (9th ed., McGraw-Hill, 2011), chapter 10,
*Mechanical springs*:

* minimum tensile strength ``S_ut = A / d**m`` with ``A = 2211`` MPa mm^m and ``m = 0.145``
  for music wire of 0.10 to 6.5 mm (its Table 10-4): 2085 MPa at ``d = 1.5`` mm;
* yield strength in bending of music wire and cold-drawn carbon steel ``S_y = 0.78 S_ut``
  (its section on helical coil torsion springs, whose wire is loaded in bending): 1626 MPa.

The largest bending strain a rod of the model can take elastically is then ``S_y / E``: the
stress the model implies, ``E (d / 2) |kappa|``, stays below ``S_y``. That is
:data:`STRAIN_LIMIT`, 0.77 %. A rod bent beyond it yields on its first use: the equilibrium is
not buildable with this wire (a stronger wire, or a thinner one, changes the verdict: the limit
is a property of the material, the strain one of the geometry).

Examples
--------
>>> round(EI, 6), STUDY_NODES
(0.052186, 41)
>>> round(TENSILE_STRENGTH / 1e6), round(YIELD_STRENGTH / 1e6), round(100 * STRAIN_LIMIT, 3)
(2085, 1626, 0.774)
"""

import numpy as np

__all__ = ["DIAMETER", "EI", "LENGTH", "MATERIAL", "STRAIN_LIMIT", "STUDY_NODES",
           "TENSILE_STRENGTH", "YIELD_STRENGTH", "YOUNG"]

LENGTH = 1.0
"""Length of every rod (m), Annex II 3.1 and 4.1."""
YOUNG = 210e9
"""Young's modulus of the rods (Pa), Annex II 3.1 and 4.1."""
DIAMETER = 1.5e-3
"""Diameter of the rods' circular section (m), Annex II 3.1 and 4.1."""
EI = YOUNG * np.pi * DIAMETER ** 4 / 64.0
"""Bending stiffness of every rod (N m^2): ``E I`` with ``I = pi d**4 / 64``."""
STUDY_NODES = 41
"""RK4 nodes per rod of the study's shooting programs (Annex II 3.1 and 4.1)."""

MATERIAL = "music wire, ASTM A228"
"""The rods' material: the study gives only ``E = 210`` GPa (see the module)."""
_A_MPA, _M = 2211.0, 0.145     # S_ut = A / d**m (MPa, d in mm): Shigley, Table 10-4, A228
_BENDING_YIELD = 0.78          # S_y / S_ut in bending, music wire: Shigley, torsion springs
TENSILE_STRENGTH = _A_MPA / (DIAMETER * 1e3) ** _M * 1e6
"""Minimum tensile strength of the rods' wire (Pa), ``A / d**m`` of Shigley's Table 10-4."""
YIELD_STRENGTH = _BENDING_YIELD * TENSILE_STRENGTH
"""Bending yield strength of the rods' wire (Pa), ``0.78 S_ut`` (Shigley, torsion springs)."""
STRAIN_LIMIT = YIELD_STRENGTH / YOUNG
"""The largest bending strain ``(d / 2) max |kappa|`` a rod takes elastically: ``S_y / E``."""
