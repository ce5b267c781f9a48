"""Which implementation runs the models: the numpy reference or the compiled (Numba) kernels.

The environment variable ``DCCSS_BACKEND`` selects it:

* ``auto`` (the default): the compiled kernels (``dccss.mechanics.compiled``) where numba is
  installed and the run is large enough for them to pay, the numpy reference otherwise. A run
  is large when ``steps * (cases + STEP_OVERHEAD) >= AUTO_THRESHOLD``: the numpy reference
  costs about 1-2 microseconds per case-step plus as much as ``STEP_OVERHEAD`` case-steps per
  step, so this is a run the numpy reference takes 1-2 s or more over, while a process that
  loads the cached kernels pays about 0.7 s (importing numba and loading the kernels) and one
  that compiles them about 20 s, once: the kernels are cached on disk. Small runs (the paper's
  1000-step histories, the breakaway sweeps, small study chunks) run on numpy, so a cold cache
  never slows them. The choice depends on the run's size only, never on the state of the
  cache, so the same run uses the same backend on every machine that has numba.
* ``numba``: always the compiled kernels (an error where numba is not installed);
* ``numpy``: always the numpy reference.

Where numba is not installed, ``auto`` runs large runs on numpy and says so once (a
``BackendWarning``). The two backends agree to 1e-10 (tests/test_compiled.py, test_backend.py;
about 1e-13 in practice): the backend used is logged (logger ``dccss.backend``; ``last`` holds
the latest), not written into the datasets, whose bytes thus do not depend on it.

The numpy step generators (``models.steps``) stay the reference, and are what runs wherever
per-step records are needed.
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import os
import warnings

import numpy as np

ENV = "DCCSS_BACKEND"
BACKENDS = ("auto", "numba", "numpy")
#: the numpy reference's cost per step, in case-steps (measured: 0.09 ms per compliant step and
#: 0.19 ms per stick-slip step for one case, against 1.0 and 2.2 microseconds per case-step in
#: batches of 10 000)
STEP_OVERHEAD = 100
#: ``auto`` runs the compiled kernels from this many weighted case-steps on (README, Performance)
AUTO_THRESHOLD = 1_000_000
INSTALL = "pip install numba (or the package's `compiled` extra: pip install -e '.[compiled]')"

log = logging.getLogger("dccss.backend")
_warned = False
#: the backend of the last run dispatched in this process ("numba" or "numpy"; None before any)
last = None


class BackendError(ImportError):
    """DCCSS_BACKEND=numba where numba is not installed."""


class BackendWarning(UserWarning):
    """The compiled backend would run, but numba is not installed: the numpy reference runs."""


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
        raise BackendError(f"{ENV}=numba needs numba, which is not installed: {INSTALL}; or set {ENV}=numpy")
    return wanted


def numba_installed() -> bool:
    try:
        return importlib.util.find_spec("numba") is not None
    except (ImportError, ValueError):
        return False


def work(steps, cases=1) -> int:
    """The size of a run of ``cases`` cases over ``steps`` steps, in weighted case-steps."""
    return int(steps) * (int(cases) + STEP_OVERHEAD)


def choose(steps, cases=1) -> str:
    """'numba' or 'numpy' for a run of ``cases`` cases over ``steps`` steps (module docstring)."""
    wanted = check()
    if wanted != "auto":
        return wanted
    if work(steps, cases) < AUTO_THRESHOLD:
        return "numpy"
    if numba_installed():
        return "numba"
    _warn_once()
    return "numpy"


def _warn_once():
    global _warned
    if not _warned:
        _warned = True
        warnings.warn(f"numba is not installed, so large runs use the slower numpy backend: {INSTALL} for the "
                      f"compiled one (set {ENV}=numpy to silence this)", BackendWarning, stacklevel=4)


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


def compiled(model, steps, cases=1):
    """The compiled module if it should run ``model`` over this run, else None (numpy)."""
    global last
    last = "numpy"
    if choose(steps, cases) == "numpy":
        log.info("backend numpy: %s, %d case(s) x %d step(s)", model, cases, steps)
        return None
    try:
        module = _load()
    except ImportError:
        if requested() == "numba":
            raise
        _warn_once()
        return None
    if model not in module.HISTORY:  # a model the kernels do not have
        log.info("backend numpy: %s has no compiled kernel", model)
        return None
    log.info("backend numba: %s, %d case(s) x %d step(s)", model, cases, steps)
    last = "numba"
    return module
