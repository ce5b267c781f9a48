"""Compile (or load) every kernel into the on-disk cache, ahead of the runs: the module above the
kernels it warms (``compiled``, ``spatial``, ``structure``), which import nothing of it."""

from __future__ import annotations

import numpy as np

from . import compiled, registry, spatial, structure
from .geometry import Geometry


def warm():
    """Compile (or load) the kernels of every registered model, planar and spatial, and the isolated
    structure's, into the on-disk cache: e.g. once before parallel jobs that would each compile them
    (``python -m dccss.mechanics``)."""
    structure.warm()
    # any valid device compiles the same kernels
    device = Geometry.from_degrees(R1=3.0, R3=3.0, alpha1=6.0, alpha3=6.0, h2=0.1, alpha21=2.0, alpha23=2.0, hr1=0.02,
                                   hr3=0.02, hmin1=0.03, hmin3=0.03, tr1=0.03, tr3=0.03)
    for name in registry.names(lambda entry: entry.planar is not None):
        compiled.run(name, device, np.array([0.0, 1e-3]))
    for name in registry.names(lambda entry: entry.spatial is not None):
        spatial.run(name, device, np.array([[0.0, 0.0], [1e-3, 0.0]]))
