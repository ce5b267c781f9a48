"""What the compiled kernels (``compiled``: planar, ``spatial``) share: how they are compiled and the
residual norm of their Newton loops."""

from __future__ import annotations

import math

from numba import njit
from numba.extending import register_jitable

#: IEEE semantics for a division by zero (as numpy), no Python-style checks in the loops; kernels
#: cached on disk
OPTIONS = dict(cache=True, error_model="numpy")
#: the helpers, inlined by LLVM into the kernels that call them
jit = njit(forceinline=True, **OPTIONS)


def compilable(*functions):
    """Let the kernels call these plain Python functions (modules that do not import numba: they
    run interpreted too), compiled with the helpers' options."""
    for function in functions:
        register_jitable(error_model=OPTIONS["error_model"], forceinline=True)(function)


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
