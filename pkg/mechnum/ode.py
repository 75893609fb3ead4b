"""Fixed-step integration of ordinary differential equations.

:func:`rk4` is the classical fourth-order Runge-Kutta method on a given grid of nodes,
the integrator of the flexible-rod study (its equations (81) to (85)). It is vectorised: the
state may carry any leading batch shape, so many initial-value problems (many rods, many
Newton perturbations) advance together in one sweep over the grid.
"""

import numpy as np


def rk4(f, y0, s):
    """Integrate ``dy/ds = f(s, y)`` from ``y(s[0]) = y0`` by classical RK4 on the nodes ``s``.

    One step from ``s_i`` to ``s_{i+1}`` with ``h = s_{i+1} - s_i`` is::

        k1 = f(s_i, y_i)
        k2 = f(s_i + h/2, y_i + h/2 k1)
        k3 = f(s_i + h/2, y_i + h/2 k2)
        k4 = f(s_i + h, y_i + h k3)
        y_{i+1} = y_i + h/6 (k1 + 2 k2 + 2 k3 + k4)

    and the global error is ``O(h**4)`` for a smooth ``f``.

    Parameters
    ----------
    f : callable
        ``f(s, y) -> ndarray`` of ``y``'s shape; ``s`` is a float, ``y`` has shape
        ``y0.shape`` (for example ``(batch, n)``: the last axis is the state, the leading
        ones a batch of independent problems).
    y0 : array_like
        The initial state (or batch of states), real or complex; must be finite.
    s : array_like, shape (N,)
        The nodes, ``N >= 2``, strictly monotone (increasing or decreasing); the grid may be
        non-uniform.

    Returns
    -------
    ndarray, shape (N,) + y0.shape
        The state at every node; ``[0]`` is ``y0``.

    Raises
    ------
    ValueError
        If ``y0`` or ``s`` are not finite, ``s`` has fewer than two nodes or is not
        strictly monotone, or ``f`` returns the wrong shape.

    Examples
    --------
    >>> import numpy as np
    >>> y = rk4(lambda s, y: -y, [1.0, 2.0], np.linspace(0.0, 1.0, 11))
    >>> y.shape, np.round(y[-1] / np.exp(-1.0), 6).tolist()    # exact: [1, 2]
    ((11, 2), [1.000001, 2.000002])
    """
    y = np.array(y0)
    y = y.astype(np.result_type(y.dtype, float))     # real or complex
    s = np.asarray(s, dtype=float)
    if not np.all(np.isfinite(y)):
        raise ValueError(f"y0 must be finite, got {y0!r}")
    if s.ndim != 1 or s.size < 2 or not np.all(np.isfinite(s)):
        raise ValueError(f"s must be a finite 1-D array of at least 2 nodes, got {s!r}")
    h = np.diff(s)
    if not (np.all(h > 0) or np.all(h < 0)):
        raise ValueError("the nodes s must be strictly increasing or strictly decreasing")
    out = np.empty((s.size,) + y.shape, dtype=y.dtype)
    out[0] = y
    k1 = np.asarray(f(s[0], y))
    if k1.shape != y.shape:
        raise ValueError(f"f returned shape {k1.shape}, expected {y.shape}")
    nodes = s.tolist()  # Python floats: cheaper than numpy scalars in this loop
    for i in range(len(nodes) - 1):
        si, hi = nodes[i], nodes[i + 1] - nodes[i]
        half = 0.5 * hi
        k2 = f(si + half, y + half * k1)
        k3 = f(si + half, y + half * k2)
        k4 = f(nodes[i + 1], y + hi * k3)
        y = y + (hi / 6.0) * (k1 + 2.0 * (k2 + k3) + k4)
        out[i + 1] = y
        if i + 2 < len(nodes):
            k1 = f(nodes[i + 1], y)
    return out
