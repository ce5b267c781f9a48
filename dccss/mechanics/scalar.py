"""What the compiled kernels (``compiled``: planar, ``spatial``) share: how they are compiled and the
residual norm of their Newton loops.

The kernels' helpers stay plain Python functions (``jit`` marks them): the same functions run
interpreted where a run is too small to pay for compiling, without importing numba, and are
registered with Numba (``compile_helpers``) the first time a kernel is compiled (``kernel``), which
then compiles them inlined.

Numba's on-disk cache of a kernel would be invalidated by a change of the kernel's own file only, not
of the helpers it inlines from other modules. ``kernel`` therefore caches in a folder named by a
digest of every module of ``dccss.mechanics`` (``__pycache__/kernels-<digest>`` beside this file,
under ``NUMBA_CACHE_DIR`` when it is set, or in the user's cache for an installation that is not
writable; ``cache_folder``): any change of the mechanics compiles afresh.
"""

from __future__ import annotations

import functools
import hashlib
import logging
import math
import os
import shutil
from pathlib import Path

#: says when a kernel is compiled rather than loaded from the cache (INFO; ``dccss run`` shows it on a terminal)
log = logging.getLogger("dccss.kernels")

#: IEEE semantics for a division by zero (as numpy), no Python-style checks in the loops; kernels
#: cached on disk
OPTIONS = dict(cache=True, error_model="numpy")


#: helpers marked by ``jit`` and not yet registered with Numba
_PENDING = []
#: ``range`` for the kernels' loops over cases, ``numba.prange`` once a kernel is compiled (``kernel``)
prange = range
#: the compiled kernels, by function
_KERNELS = {}


def jit(function=None, *, inline=True):
    """Mark a kernels' helper: the plain Python function (it runs interpreted), registered with
    Numba by ``compile_helpers`` so that a kernel calling it compiles it, inlined; or, ``jit(inline=False)``,
    as a function of its own (a long helper called from several places: compiled once, not at each)."""
    if function is None:
        return lambda f: jit(f, inline=inline)
    _PENDING.append((function, inline))
    return function


def compilable(*functions):
    """``jit`` for the helpers of modules that know nothing of the kernels (``linear``)."""
    for function in functions:
        jit(function)


def compile_helpers():
    """Register the marked helpers with Numba (imports numba): before a kernel is first compiled."""
    from numba.extending import register_jitable

    while _PENDING:
        function, inline = _PENDING.pop()
        register_jitable(error_model=OPTIONS["error_model"], forceinline=inline)(function)


def kernel(function, parallel=False):
    """``function`` compiled with Numba (or loaded from the on-disk cache), once per process: numba is
    imported, the helpers registered and ``prange`` made numba's."""
    if function not in _KERNELS:
        try:
            import numba
        except ImportError as err:  # a dependency; an installation without it (pip --no-deps) runs interpreted
            raise ImportError("the compiled kernels need numba (pip install numba)") from err
        global prange
        prange = numba.prange
        compile_helpers()
        saved = numba.config.CACHE_DIR
        folder = cache_folder(saved)
        if folder is not None:  # numba's locator reads the setting when the function is wrapped
            numba.config.CACHE_DIR = str(folder)
        try:
            _KERNELS[function] = numba.njit(parallel=parallel, **OPTIONS)(function)
        finally:
            numba.config.CACHE_DIR = saved
        if folder is not None and not is_cached(function, folder):
            log.info("compiling %s: once for this machine and version of dccss (10-30 s; cached in %s)",
                     function.__qualname__, folder)
    return _KERNELS[function]


def is_cached(function, folder) -> bool:
    """Whether the cache ``folder`` holds numba's index of ``function`` (its first call then loads it)."""
    return any(folder.rglob(f"*.{function.__qualname__}-*.nbi"))


def source_digest(folder=Path(__file__).parent) -> str:
    """A digest of the Python sources in ``folder`` (the mechanics: every module a kernel may inline)."""
    digest = hashlib.sha256()
    for source in sorted(folder.rglob("*.py")):
        digest.update(source.relative_to(folder).as_posix().encode() + b"\0" + source.read_bytes())
    return digest.hexdigest()[:16]


@functools.cache
def _package_digest() -> str:
    """``source_digest`` of this package's mechanics, read once per process."""
    return source_digest()


def cache_folder(user=""):
    """The kernels' cache folder, ``kernels-<source_digest()>``: under ``user`` (NUMBA_CACHE_DIR), else
    in this package's ``__pycache__``, else (an installation that is not writable) in the user's
    cache, ``$XDG_CACHE_HOME/dccss`` or ``~/.cache/dccss``. Older digests are removed there; None
    where no folder is writable (numba's own choice then)."""
    name = f"kernels-{_package_digest()}"
    if user:
        return Path(user) / name
    home = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "dccss"
    for parent in (Path(__file__).parent / "__pycache__", home):
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError:
            continue
        if os.access(parent, os.W_OK):
            for old in parent.glob("kernels-*"):
                if old.name != name:
                    shutil.rmtree(old, ignore_errors=True)
            return parent / name
    return None


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
