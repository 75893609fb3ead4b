"""The peers the benchmarks run beside the package, where a peer is more than one call."""

import numpy as np
from scipy.optimize import fsolve


def fsolve_each(system, in_chart, starts):
    """Every root that ``scipy.optimize.fsolve`` reaches from ``starts``, one start at a time.

    The plain multistart that :func:`mechnum.newton.solve_all` replaces, on the same batched
    system ``system(z) -> (f, J)`` (residual and analytic Jacobian from one evaluation, which
    fsolve asks for apart: the last one is kept), with the same test of a root: residual below
    1e-10, in the chart (``in_chart``; outside it the residual is large and the Jacobian the
    identity, so that fsolve goes on). Returns the roots rounded to 8 decimals, each once.
    """
    n = starts.shape[1]
    roots = []
    last = {}

    def both(z):
        if last.get("z") is None or not np.array_equal(last["z"], z):
            inside = bool(in_chart(z[None])[0])
            f, J = system(z[None]) if inside else (None, None)
            last.update(z=z.copy(), f=f[0] if inside else np.full(n, 1e3),
                        J=J[0] if inside else np.eye(n))
        return last["f"], last["J"]

    for z0 in starts:
        z, _, ier, _ = fsolve(lambda z: both(z)[0], z0, fprime=lambda z: both(z)[1],
                              full_output=True, xtol=1e-12)
        if ier == 1 and np.linalg.norm(both(z)[0]) < 1e-10:
            roots.append(z)
    return np.unique(np.round(np.array(roots).reshape(-1, n), 8), axis=0)
