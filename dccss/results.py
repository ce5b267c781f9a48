"""Model histories as CF-style ``xarray.Dataset`` objects, with per-step diagnostics.

Diagnostics are computed after the run, vectorised over time, from the stored configurations
and contact data: interpenetration at A, B, C, D, |C_q| (compliant sliding), the contact
angles, the clearance to the retaining rings and the capacity flag.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ._version import __version__
from .constraints import Q_NAMES, Compliant
from .geometry import Geometry
from .kinematics import CORNERS, all_corners, contact_angle, corner_diagnostics, interpenetration

DOI = "10.3390/buildings11020050"
#: The time coordinate is ``t``: seconds elapsed since the start of the imposed ground motion.
#: It is deliberately not a CF time coordinate (no ``standard_name``/``axis``, no reference date):
#: CF requires "seconds since <date>" for those, which xarray decodes to dates. A coordinate
#: named ``t`` in units of ``s`` passes the CF checker and reads back as float seconds with plain
#: ``xarray.open_dataset``.
TIME = "t"
TIME_UNITS = "s"
REFERENCE = (
    "Bianco, V.; Monti, G.; Belfiore, N.P. Advanced Multi-Body Modelling of DCCSS Isolators: "
    f"Geometrical Compatibility and Kinematics. Buildings 2021, 11, 50. https://doi.org/{DOI}"
)
MODEL_TITLES = {"compliant": "Compliant Sliding", "stick_slip": "Stick-Slip"}
GEOMETRY_KEYS = ("R1", "R3", "alpha1", "alpha3", "h2", "alpha21", "alpha23", "hr1", "hr3", "hmin1",
                 "hmin3", "tr1", "tr3")
_COORD_LONG = {
    "Rx1": "abscissa of the lower plate RB1", "Ry1": "ordinate of the lower plate RB1",
    "theta1": "rotation of the lower plate RB1", "Rx2": "abscissa of the pad RB2 centroid",
    "Ry2": "ordinate of the pad RB2 centroid", "theta2": "rotation of the pad RB2",
    "Rx3": "abscissa of the upper plate RB3", "Ry3": "ordinate of the upper plate RB3",
    "theta3": "rotation of the upper plate RB3",
}


def _var(dims, data, units, long_name, **attrs):
    return xr.Variable(dims, data, {"units": units, "long_name": long_name, **attrs})


def coordinates(q, dims, suffix="", when=""):
    out = {}
    for k, name in enumerate(Q_NAMES):
        angle = name.startswith("theta")
        data = np.degrees(q[..., k]) if angle else q[..., k]
        out[name + suffix] = _var(dims, data, "degree" if angle else "m", _COORD_LONG[name] + when)
    return out


def time_coordinate(times):
    """The time coordinate ``t``: seconds elapsed since the start of the ground motion (see TIME)."""
    return xr.Variable((TIME,), np.asarray(times, dtype=float), {
        "units": TIME_UNITS, "long_name": "time since the start of the imposed ground motion"})


def load(path) -> xr.Dataset:
    """Read a dccss netCDF file into memory (the same as ``xarray.load_dataset(path)``)."""
    return xr.load_dataset(path)


def geometry_attrs(geometry) -> dict:
    """Table 1 parameters and derived lengths as global attributes (m, degrees)."""
    attrs = {}
    for name, value in geometry.as_degrees().items():
        attrs[f"{name}_{'deg' if name.startswith('alpha') else 'm'}"] = float(value)
    attrs.update(L_m=float(geometry.L), A1_m=float(geometry.A1), A3_m=float(geometry.A3),
                 B_m=float(geometry.B), hs1_m=float(geometry.hs1), hs3_m=float(geometry.hs3),
                 capacity1_m=float(geometry.capacity1), capacity3_m=float(geometry.capacity3))
    return attrs


def geometry_from_attrs(attrs) -> Geometry:
    """Rebuild the Geometry recorded in a dataset's global attributes."""
    return Geometry.from_degrees(**{name: attrs[f"{name}_{'deg' if name.startswith('alpha') else 'm'}"]
                                    for name in GEOMETRY_KEYS})


def history_dataset(model, history, geometry, times, excitation, *, theta2_0, dt, normals,
                    tol, attrs=None) -> xr.Dataset:
    """Dataset of one case from the arrays of ``dccss.models`` (time first, no batch dims)."""
    t = (TIME,)
    q = history["q"]
    Xg = excitation.displacement(times)
    data = {
        "Xg": _var(t, Xg, "m", "imposed ground displacement X_g"),
        "Xg_dot": _var(t, excitation.velocity(times), "m s-1", "imposed ground velocity dX_g/dt"),
        **coordinates(q, t),
        "rise": _var(t, q[:, 7] - geometry.Ry3_compatible(0.0), "m",
                     "rise of RB3 above its theta2 = 0 rest position (Eq. 41)"),
    }
    I, gap = corner_diagnostics(q, geometry)
    for i, c in enumerate(CORNERS):
        data[f"I_{c}"] = _var(t, I[:, i], "m", f"interpenetration at corner {c}2 (positive into the plate)")
    for j, plate in enumerate(("1", "3")):
        data[f"clearance_{plate}"] = _var(t, gap[:, j], "m",
                                          f"clearance between the pad and the retaining ring of RB{plate}")
    data["capacity_exceeded"] = _var(
        t, (gap < 0).any(axis=-1).astype(np.int8), "1", "pad beyond a retaining ring",
        flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="within_capacity capacity_exceeded")
    data["newton_iterations"] = _var(t, history["newton_iterations"], "1",
                                     "Newton-Raphson iterations of the step" +
                                     (" (slipping phase)" if model == "stick_slip" else ""))
    data["newton_residual"] = _var(t, history["residual"], "m", "final max |constraint residual|")
    if model == "compliant":
        corners = all_corners(geometry)
        points = [history["point"][..., i] for i in range(4)]
        normals_ = [history["normal"][..., i] for i in range(4)]
        cset = Compliant(corners, q[:, 0], history["Rx3"], points, normals_)
        data["det_Cq"] = _var(t, cset.determinant(q), "m",
                              "determinant |C_q| of the constraint Jacobian (Eq. 29) at the step's solution")
        for i, c in enumerate(corners):
            data[f"alpha_{c.name}"] = _var(t, np.degrees(contact_angle(normals_[i], c)), "degree",
                                           f"contact angle alpha of {c.name}2 at the previous contact point")
    else:
        qs = history["q_stick"]
        data.update(coordinates(qs, t, "_stick", " at the end of the sticking phase"))
        Is = interpenetration(qs, geometry)
        for i, c in enumerate(CORNERS):
            data[f"I_{c}_stick"] = _var(t, Is[:, i], "m",
                                        f"interpenetration at corner {c}2 at the end of the sticking phase")
        diag = history["diagonal_BC"].astype(np.int8)
        data["sticking_diagonal"] = _var(t, diag, "1", "diagonal jammed in the sticking phase",
                                         flag_values=np.array([0, 1], dtype=np.int8),
                                         flag_meanings="A2D2 B2C2")
        data["newton_iterations_stick"] = _var(t, history["newton_iterations_stick"], "1",
                                               "Newton-Raphson iterations of the sticking phase")
        data["newton_residual_stick"] = _var(t, history["residual_stick"], "m",
                                             "final max |constraint residual| of the sticking phase")
    ds = xr.Dataset(data, coords={TIME: time_coordinate(times)})
    ds.attrs = {
        "Conventions": "CF-1.11",
        "title": f"DCCSS kinematics, {MODEL_TITLES[model]} model",
        "source": f"dccss {__version__}, planar three-rigid-body kinematic model",
        "references": REFERENCE,
        "history": f"computed by dccss {__version__} ({MODEL_TITLES[model]} model)",
        "model": model,
        "normals": normals,
        "theta2_0_deg": float(np.degrees(theta2_0)),
        "dt_s": float(dt),
        "newton_tol_m": float(tol),
        "dccss_version": __version__,
        **geometry_attrs(geometry),
        **excitation.attrs(),
        **(attrs or {}),
    }
    return ds
