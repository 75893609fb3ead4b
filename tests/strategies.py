"""Hypothesis strategies shared by several test modules."""

import numpy as np
from hypothesis import strategies as st


@st.composite
def separated(draw, size, low, high, gap):
    """``size`` sorted floats in ``[low, high]``, neighbours at least ``gap`` apart.

    Drawn directly rather than filtered: sorted values in ``[low, high - (n - 1) gap]``, the
    k-th then moved up by ``k gap``. ``size`` is an int or a strategy of ints.
    """
    n = draw(size) if isinstance(size, st.SearchStrategy) else size
    top = high - (n - 1) * gap
    u = np.sort(draw(st.lists(st.floats(low, top), min_size=n, max_size=n)))
    return u + gap * np.arange(n)
