"""Compile (or load) every kernel into the on-disk cache, ahead of the runs: the module above the
kernels it warms (``compiled``, ``spatial``, ``structure``), which import nothing of it.

Each kernel is a part of its own (``parts``), so that the parts can compile in parallel processes
(``warm(jobs=...)``: about 30 s of compilation in all, 16 s on two cores); ``cold`` says, without
importing numba, which parts the cache does not hold yet.
"""

from __future__ import annotations

import os

import numpy as np

from . import compiled, registry, scalar, spatial, structure
from .geometry import Geometry
from .structure import articulated, circular, exact, series


def _device():
    """Any valid device: every device compiles the same kernels."""
    return Geometry.from_degrees(R1=3.0, R3=3.0, alpha1=6.0, alpha3=6.0, h2=0.1, alpha21=2.0, alpha23=2.0, hr1=0.02,
                                 hr3=0.02, hmin1=0.03, hmin3=0.03, tr1=0.03, tr3=0.03)


def parts() -> dict:
    """{part: (kernel function, run compiling it)} of every registered model, planar and spatial, and of
    the isolated structure, the longest to compile first (planar 9 s, the structure's two-component
    kernels 9 s (rigid) and 28 s (articulated), spatial 6 s, one-component 2-3 s, each alone on the project's
    two-core machine)."""
    planar = {f"planar {name}": (registry.model(name).planar.batch,
                                 lambda name=name: compiled.run(name, _device(), np.array([0.0, 1e-3])))
              for name in registry.names(lambda entry: entry.planar is not None)}
    space = {f"spatial {name}": (registry.model(name).spatial,
                                 lambda name=name: spatial.run(name, _device(), np.array([[0.0, 0.0], [1e-3, 0.0]])))
             for name in registry.names(lambda entry: entry.spatial is not None)}
    return {**planar, "structure plane": (circular.plane, lambda: structure.warm(("plane",))),
            "structure articulated": (articulated.articulated, lambda: structure.warm(("articulated",))), **space,
            "structure line": (exact.line, lambda: structure.warm(("line",))),
            "structure series": (series.series_line, lambda: structure.warm(("series",)))}


def cold() -> list:
    """The parts whose kernel has no index in the on-disk cache (their first run would compile them),
    found without importing numba; [] where the cache's folder is numba's own choice (not writable)."""
    folder = scalar.cache_folder(os.environ.get("NUMBA_CACHE_DIR", ""))
    if folder is None:
        return []
    return [part for part, (function, _) in parts().items() if not scalar.is_cached(function, folder)]


def warm_part(part: str) -> str:
    """Compile (or load) the kernel of one part (a name from ``parts``)."""
    parts()[part][1]()
    return part


def warm(jobs: int = 1, only=None) -> list:
    """Compile (or load) the kernels of every registered model, planar and spatial, and the isolated
    structure's (or of the parts ``only``), into the on-disk cache, in up to ``jobs`` processes: e.g.
    once before parallel runs that would each compile them (``python -m dccss.mechanics``). Returns the
    parts warmed."""
    todo = list(parts()) if only is None else list(only)
    if jobs <= 1 or len(todo) <= 1:
        return [warm_part(part) for part in todo]
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    # spawned processes: no numba state or threads inherited; each takes the next part as it ends one
    with ProcessPoolExecutor(min(jobs, len(todo)), mp_context=multiprocessing.get_context("spawn")) as pool:
        return list(pool.map(warm_part, todo))
