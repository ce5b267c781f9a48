"""What the compiled kernels (``compiled``: planar, ``spatial``) share: how they are compiled and the
residual norm of their Newton loops."""

from __future__ import annotations

import math

from numba import njit

#: IEEE semantics for a division by zero (as numpy), no Python-style checks in the loops; kernels
#: cached on disk
OPTIONS = dict(cache=True, error_model="numpy")
#: the helpers, inlined by LLVM into the kernels that call them
jit = njit(forceinline=True, **OPTIONS)


@jit
def max_abs(g):
    """max |g_i|, NaN if any is NaN."""
    m = 0.0
    for v in g:
        a = abs(v)
        if a != a:
            return math.nan
        if a > m:
            m = a
    return m
