"""dccss: kinematics of Double Concave Curved Surface Sliders (double friction pendulum isolators).

The three-rigid-body model of a DCCSS of Bianco, Monti & Belfiore (Buildings 2021, 11, 50), solved by
Newton-Raphson on its nonlinear constraint equations under two hypotheses, Compliant Sliding and
Stick-Slip: in the plane under one ground component, as the paper, and in space under two. The device
undergoes the ground's displacement, or the stroke of an isolated structure on it driven by a recorded
ground acceleration (``Structure``); records are read, processed and scaled to a spectrum
(``Record``, ``RecordPair``, ``spectra``).

Typical use::

    from dccss import Geometry, Sine, simulate
    g = Geometry.from_degrees(R1=1.0, R3=1.0, alpha1=21, alpha3=21, h2=0.15, alpha21=10,
                              alpha23=10, hr1=0.02, hr3=0.02, hmin1=0.10, hmin3=0.10,
                              tr1=0.0258, tr3=0.0258)
    ds = simulate(g, Sine(amplitude=0.27, omega=30.0, duration=1.0), model="stick_slip", dt=0.001)
    from dccss.files import write_netcdf
    write_netcdf(ds, "dfp1.nc")  # as ``dccss run`` writes it (CF-compliant; atomic)
    # bidirectional: the same sine along 30 degrees, or a record pair / time, x, y table
    from dccss import Oriented
    ds3 = simulate(g, Oriented(Sine(0.2, 6.28, 2.0), 30.0), model="stick_slip", dt=0.005)

Layout (imports flow downwards only):

* ``mechanics/`` - the model (nothing above it is imported): ``geometry``, ``kinematics``,
  ``newton``, ``linear`` (the 4 x 4 solve and determinants), ``registry`` and ``models`` (the models
  as registry entries, written once as kernels), ``scalar`` (how kernels compile and are cached),
  ``capacity`` (the retaining rings and their errors), ``summaries`` (the per-case reductions of a
  sweep), ``compiled`` (the planar kernels' helpers and driver, compiled with Numba or interpreted),
  ``backend`` (which of the two runs), ``spatial`` (both models in space, for bidirectional ground
  motion), ``structure`` (the isolated structure's response) and ``runs`` (the one driver: planar or
  spatial, the backend, the capacity and failure policies);
* top level - one case in, one dataset out: ``excitation`` and ``records`` (X_g(t)), ``results``
  (CF datasets), ``simulation``, ``checks``/``schema``/``case``/``cli`` (input checks, JSON Schemas,
  case files, ``dccss run``/``animate``), ``files`` (atomic writes), ``drawing`` (figures and the
  device to scale), ``viewer`` (what the drawing commands share), ``animation``, ``plan`` (plan view
  and sections of a history in space, ``dccss plot``);
* ``studies/`` - study files: ``spec``, ``grid``, ``run``, ``combine``, ``plots``;
* ``paper/`` - what is specific to the paper: ``prototypes`` (Table 1), ``figures``, ``validation``.
"""

import importlib

from ._version import __version__

# the public names, imported on first use so that e.g. `dccss.drawing` loads no solver code
_LAZY = {"Sine": "excitation", "Table": "excitation", "Geometry": "mechanics.geometry",
         "NewtonOptions": "mechanics.newton", "ConvergenceError": "mechanics.newton",
         "SingularJacobianError": "mechanics.newton", "simulate": "simulation",
         "breakaway": "simulation", "CapacityError": "mechanics.capacity", "Record": "records",
         "RecordWarning": "records", "Scaled": "excitation", "Oriented": "excitation", "PlaneTable": "excitation",
         "Component": "excitation", "RecordPair": "records", "Structure": "mechanics.structure",
         "load_case": "case"}
__all__ = ["__version__", *_LAZY]


def __getattr__(name):
    if name in _LAZY:
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module 'dccss' has no attribute {name!r}")
