"""How a planar run is computed: the kernels compiled, or the same kernels interpreted.

The planar models are written once, as kernels (``dccss.mechanics.models``, on the helpers of
``compiled``): functions on Python numbers and tuples that Numba compiles and that also run as they
are, interpreted. Both give the same results to the last bit (the same operations in the same
order; tests/test_compiled.py), so the choice between them is one of speed only. The
environment variable ``DCCSS_BACKEND`` selects it:

* ``auto`` (the default): the kernels, compiled where the run is large enough for them to pay,
  interpreted otherwise. A run of N cases over T steps is large when ``T * N >= AUTO_THRESHOLD``:
  interpreted, the kernels take about 20 microseconds per case-step (compliant sliding) or 40-50
  (stick-slip), so this is a run they take about half a second or more over, while a process that
  loads the compiled kernels from the on-disk cache pays about 0.7 s (importing numba and loading
  them) and one that compiles them about 20 s, once per machine. Small runs (the paper's
  histories and breakaway sweeps) thus never wait for a compiler.
* ``numba``: always compiled; ``python``: always interpreted.

(An independent numpy implementation of the same equations, which checks the kernels, is the
tests' ``tests/oracle.py``.)

The interpreted kernels do not import numba: where it is not installed, ``auto`` runs every run
interpreted and says so once for a large one (a ``BackendWarning``).

The backend used is logged (logger ``dccss.backend``; ``last`` holds the latest: "numba" or
"python"), not written into the datasets.
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import os
import warnings

import numpy as np

ENV = "DCCSS_BACKEND"
BACKENDS = ("auto", "numba", "python")
#: ``auto`` compiles the kernels from this many case-steps on (module docstring; benchmarks/README.md)
AUTO_THRESHOLD = 20_000
INSTALL = "pip install numba (or the package's `compiled` extra: pip install -e '.[compiled]')"

log = logging.getLogger("dccss.backend")
_warned = False
#: the backend of the last run dispatched in this process ("numba" or "python"; None before any)
last = None


class BackendError(ImportError):
    """DCCSS_BACKEND=numba where numba is not installed."""


class BackendWarning(UserWarning):
    """The compiled kernels would run, but numba is not installed: they run interpreted."""


def requested() -> str:
    """The value of DCCSS_BACKEND (default ``auto``); a ValueError names the allowed values."""
    raw = os.environ.get(ENV, "auto")
    value = raw.strip().lower() or "auto"
    if value not in BACKENDS:
        raise ValueError(f"{ENV}={raw!r} is not a backend: set it to one of {', '.join(BACKENDS)} "
                         f"(unset: auto)")
    return value


def check() -> str:
    """The requested backend, checked: a ValueError for an unknown value, a BackendError for
    ``numba`` where numba is not installed."""
    wanted = requested()
    if wanted == "numba" and not numba_installed():
        raise BackendError(f"{ENV}=numba needs numba, which is not installed: {INSTALL}; or set {ENV}=python")
    return wanted


def numba_installed() -> bool:
    try:
        return importlib.util.find_spec("numba") is not None
    except (ImportError, ValueError):
        return False


def work(steps, cases=1) -> int:
    """The size of a run of ``cases`` cases over ``steps`` steps, in case-steps."""
    return int(steps) * int(cases)


def choose(steps, cases=1) -> str:
    """'numba' or 'python' for a run of ``cases`` cases over ``steps`` steps (module docstring)."""
    wanted = check()
    if wanted != "auto":
        return wanted
    if work(steps, cases) < AUTO_THRESHOLD:
        return "python"
    if numba_installed():
        return "numba"
    _warn_once()
    return "python"


def _warn_once():
    global _warned
    if not _warned:
        _warned = True
        warnings.warn(f"numba is not installed, so large runs run interpreted, slowly: {INSTALL} to compile "
                      f"them (set {ENV}=python to silence this)", BackendWarning, stacklevel=4)


def size(geometry, Xg, theta2_0=0.0):
    """(steps, cases) of a run: X_g is (T, ...); the cases are the broadcast batch."""
    shape = np.shape(Xg)
    try:
        batch = np.broadcast_shapes(np.shape(geometry.L), shape[1:], np.shape(theta2_0))
    except ValueError:  # the solver's own checks report it
        batch = shape[1:]
    return max(shape[0] - 1, 0) if shape else 0, int(np.prod(batch, dtype=np.int64))


def _load():
    return importlib.import_module("dccss.mechanics.compiled")


def kernels(model, steps, cases=1):
    """``(module, compiled)``: the kernels' driver (``compiled``) and whether to run ``model``'s kernels
    compiled over this run."""
    global last
    choice = choose(steps, cases)
    if choice == "numba":
        try:
            importlib.import_module("numba")
        except ImportError:  # found, but its import fails
            if requested() == "numba":
                raise
            _warn_once()
            choice = "python"
    last = choice
    log.info("backend %s: %s, %d case(s) x %d step(s)", choice, model, cases, steps)
    return _load(), choice == "numba"
