"""The peers the benchmarks run beside the package, where a peer is more than one call."""

import numpy as np
from scipy.optimize import fsolve


def fsolve_each(fun, jac, in_chart, starts):
    """Every root that ``scipy.optimize.fsolve`` reaches from ``starts``, one start at a time.

    The plain multistart that :func:`mechnum.newton.solve_all` replaces, on the same batched
    residual ``fun`` and analytic Jacobian ``jac``, with the same test of a root: residual below
    1e-10, in the chart (``in_chart``; outside it the residual is large and the Jacobian the
    identity, so that fsolve goes on). Returns the roots rounded to 8 decimals, each once.
    """
    n = starts.shape[1]
    roots = []
    for z0 in starts:
        def f(z):
            return fun(z[None])[0] if in_chart(z[None])[0] else np.full(n, 1e3)

        def J(z):
            return jac(z[None])[0] if in_chart(z[None])[0] else np.eye(n)

        z, _, ier, _ = fsolve(f, z0, fprime=J, full_output=True, xtol=1e-12)
        if ier == 1 and np.linalg.norm(f(z)) < 1e-10:
            roots.append(z)
    return np.unique(np.round(np.array(roots).reshape(-1, n), 8), axis=0)
