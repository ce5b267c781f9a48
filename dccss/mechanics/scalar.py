"""What the compiled kernels (``compiled``: planar, ``spatial``) share: how they are compiled and the
residual norm of their Newton loops.

The kernels' helpers stay plain Python functions (``jit`` marks them): the same functions run
interpreted where a run is too small to pay for compiling, without importing numba, and are
registered with Numba (``compile_helpers``) the first time a kernel is compiled, which then
compiles them inlined. Numba's on-disk cache of a kernel is invalidated by a change of the kernel's own
file only: after editing a helper in another module (this one, ``linear``), clear the cache
(``__pycache__/*.nbi``) or touch the kernel's file.
"""

from __future__ import annotations

import math

#: IEEE semantics for a division by zero (as numpy), no Python-style checks in the loops; kernels
#: cached on disk
OPTIONS = dict(cache=True, error_model="numpy")


#: helpers marked by ``jit`` and not yet registered with Numba
_PENDING = []


def jit(function):
    """Mark a kernels' helper: the plain Python function (it runs interpreted), registered with
    Numba by ``compile_helpers`` so that a kernel calling it compiles it, inlined."""
    _PENDING.append(function)
    return function


def compilable(*functions):
    """``jit`` for the helpers of modules that know nothing of the kernels (``linear``)."""
    for function in functions:
        jit(function)


def compile_helpers():
    """Register the marked helpers with Numba (imports numba): before a kernel is first compiled."""
    from numba.extending import register_jitable

    while _PENDING:
        register_jitable(error_model=OPTIONS["error_model"], forceinline=True)(_PENDING.pop())


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
