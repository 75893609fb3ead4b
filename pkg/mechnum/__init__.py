"""mechnum: numerical methods for mechanisms, the companion package of the book.

Layers, each importing only the one below it:

* methods: :mod:`mechnum.newton`, :mod:`mechnum.linear`, :mod:`mechnum.ode`, :mod:`mechnum.rods`;
* mechanisms: :mod:`mechnum.mechanisms`, one module per mechanism of the source studies.
"""

from mechnum.errors import (
    ConvergenceError,
    MechnumError,
    SingularJacobianError,
)

__all__ = ["ConvergenceError", "MechnumError", "SingularJacobianError"]
__version__ = "0.1.0"
