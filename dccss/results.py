"""Model histories as CF-style ``xarray.Dataset`` objects, with per-step diagnostics.

Diagnostics are computed after the run, vectorised over time, from the stored configurations
and contact data: interpenetration at A, B, C, D, |C_q| (compliant sliding), the contact
angles, the clearance to the retaining rings and the capacity flag.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ._version import __version__
from .mechanics import models
from .mechanics.geometry import PARAMETERS, Geometry
from .mechanics.kinematics import CORNERS, Q_NAMES, corner_diagnostics, interpenetration
from .mechanics.structure import G

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
MODEL_TITLES = {name: entry.title for name, entry in models.REGISTRY.items()}
_COORD_LONG = {
    "Rx1": "abscissa of the lower plate RB1", "Ry1": "ordinate of the lower plate RB1",
    "theta1": "rotation of the lower plate RB1", "Rx2": "abscissa of the pad RB2 centroid",
    "Ry2": "ordinate of the pad RB2 centroid", "theta2": "rotation of the pad RB2",
    "Rx3": "abscissa of the upper plate RB3", "Ry3": "ordinate of the upper plate RB3",
    "theta3": "rotation of the upper plate RB3",
}


def variable(dims, data, units, long_name, **attrs):
    """A CF variable: ``data`` on ``dims`` with its ``units`` and ``long_name`` (and any other attributes)."""
    return xr.Variable(dims, data, {"units": units, "long_name": long_name, **attrs})


def coordinates(q, dims, suffix="", when=""):
    out = {}
    for k, name in enumerate(Q_NAMES):
        angle = name.startswith("theta")
        data = np.degrees(q[..., k]) if angle else q[..., k]
        out[name + suffix] = variable(dims, data, "degree" if angle else "m", _COORD_LONG[name] + when)
    return out


def time_coordinate(times):
    """The time coordinate ``t``: seconds since the start of the ground motion (see TIME); a record cut by a
    window keeps its own times (t starts at the window's start)."""
    return xr.Variable((TIME,), np.asarray(times, dtype=float), {
        "units": TIME_UNITS, "long_name": "time since the start of the ground motion (a record's own time)"})


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
                                    for name in PARAMETERS})


def global_attrs(title, history, **extra) -> dict:
    """The CF global attributes every dccss dataset carries, plus ``extra``."""
    return {"Conventions": "CF-1.11", "title": title, "source": f"dccss {__version__}",
            "references": REFERENCE, "history": f"computed by dccss {__version__} ({history})",
            "dccss_version": __version__, **extra}


def _variables(table, dims) -> dict:
    """xarray variables from {name: (values, units, long_name[, attrs])}."""
    return {name: variable(dims, values, units, long_name, **(rest[0] if rest else {}))
            for name, (values, units, long_name, *rest) in table.items()}


def history_dataset(model, history, geometry, times, excitation, *, theta2_0, dt, normals,
                    tol, attrs=None) -> xr.Dataset:
    """Dataset of one case from a history of ``dccss.mechanics.models`` (time first, no batch dims):
    the configuration, ground motion, rise, interpenetration and clearances of every step, and
    what the model's registry entry adds (its diagnostics and the configurations of its stages)."""
    entry = models.model(model)
    t = (TIME,)
    q = history["q"]
    data = {
        "Xg": variable(t, excitation.displacement(times), "m", "imposed ground displacement X_g"),
        "Xg_dot": variable(t, excitation.velocity(times), "m s-1", "imposed ground velocity dX_g/dt"),
        **coordinates(q, t),
        "rise": variable(t, q[:, 7] - geometry.Ry3_compatible(0.0), "m",
                     "rise of RB3 above its theta2 = 0 rest position (Eq. 41)"),
    }
    I, gap = corner_diagnostics(q, geometry)
    for i, c in enumerate(CORNERS):
        data[f"I_{c}"] = variable(t, I[:, i], "m", f"interpenetration at corner {c}2 (positive into the plate)")
    for j, plate in enumerate(("1", "3")):
        data[f"clearance_{plate}"] = variable(t, gap[:, j], "m",
                                          f"clearance between the pad and the retaining ring of RB{plate}")
    data["capacity_exceeded"] = variable(
        t, (gap < 0).any(axis=-1).astype(np.int8), "1", "pad beyond a retaining ring",
        flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="within_capacity capacity_exceeded")
    last = " (its last phase)" if entry.stages else ""
    data["newton_iterations"] = variable(t, history["newton_iterations"], "1",
                                     f"Newton-Raphson iterations of the step{last}")
    data["newton_residual"] = variable(t, history["residual"], "m", f"final max |constraint residual|{last}")
    for suffix, when in entry.stages.items():
        data.update(coordinates(history["q" + suffix], t, suffix, when))
    data.update(_variables(entry.diagnostics(history, geometry), t))
    ds = xr.Dataset(data, coords={TIME: time_coordinate(times)})
    ds.attrs = global_attrs(f"DCCSS kinematics, {entry.title} model",
                            f"{entry.title} model", model=model, normals=normals,
                            theta2_0_deg=float(np.degrees(theta2_0)), dt_s=float(dt), newton_tol_m=float(tol),
                            **geometry_attrs(geometry), **excitation.attrs(), **(attrs or {}))
    ds.attrs["source"] += ", planar three-rigid-body kinematic model"
    return ds


def breakaway_dataset(history, geometry, theta2_0, sizes, normals, attrs=None) -> xr.Dataset:
    """Fig. 7 dataset from the two-step compliant history of a breakaway batch (dims dXg,
    theta2_0): interpenetration after the first step, |C_q|, the configurations before and after."""
    q, q0 = history["q"][1], history["q"][0]
    d = ("dXg", "theta2_0")
    I = interpenetration(q, geometry)
    data = {f"I_{c}": variable(d, I[..., i], "m", f"interpenetration at corner {c}2 after the first step")
            for i, c in enumerate(CORNERS)}
    data["det_Cq"] = variable(d, models.determinant(history, geometry)[1], "m",
                          "determinant |C_q| (Eq. 29) of the first step")
    data["newton_iterations"] = variable(d, history["newton_iterations"][1], "1", "Newton-Raphson iterations")
    data.update(coordinates(q, d, "", " after the first step"))
    data.update(coordinates(q0, d, "_t0", " in the initial compatible configuration"))
    ds = xr.Dataset(data, coords={
        "theta2_0": variable(("theta2_0",), np.degrees(theta2_0), "degree", "initial pad rotation theta2(t0)"),
        "dXg": variable(("dXg",), sizes, "m", "imposed ground displacement of the first step")})
    ds.attrs = global_attrs("DCCSS breakaway: interpenetration at the first compliant sliding step",
                            "breakaway sweep", model="compliant", normals=normals, **geometry_attrs(geometry),
                            **(attrs or {}))
    return ds


def _vector(name, values, units, long_name, dims, suffix="", when=""):
    """Three variables name_x, name_y, name_z of a (T, 3) array."""
    return {f"{name}_{axis}{suffix}": variable(dims, values[:, i], units, f"{long_name}, {axis} component{when}")
            for i, axis in enumerate("xyz")}


def spatial_dataset(model, history, geometry, times, excitation, *, theta2_0, dt, tol, attrs=None) -> xr.Dataset:
    """Dataset of one bidirectional case from a history of ``dccss.mechanics.spatial`` (time first):
    the ground motion, the pad's tilt, tilt azimuth, centre and axis, the rise and horizontal place
    of RB3, the interpenetration of each step's four section points, the cap-centre gaps, the
    clearance to each ring and, for stick-slip, the same at the end of each sticking phase."""
    from .mechanics import spatial

    t = (TIME,)
    ground, velocity = excitation.displacement(times), excitation.velocity(times)
    d = spatial.diagnostics(history, geometry)
    axis = history["Q"][:, :, 2]
    data = {
        "Xg_x": variable(t, ground[:, 0], "m", "imposed ground displacement X_g, x component"),
        "Xg_y": variable(t, ground[:, 1], "m", "imposed ground displacement X_g, y component"),
        "Xg_dot_x": variable(t, velocity[:, 0], "m s-1", "imposed ground velocity, x component"),
        "Xg_dot_y": variable(t, velocity[:, 1], "m s-1", "imposed ground velocity, y component"),
        "tilt": variable(t, np.degrees(d["tilt"]), "degree", "tilt of the pad axis from the vertical"),
        "tilt_azimuth": variable(t, np.degrees(d["tilt_azimuth"]), "degree",
                             "azimuth the pad axis leans towards, from x towards y (NaN where the axis is vertical)"),
        "rise": variable(t, d["rise"], "m", "rise of RB3 above its theta2 = 0 rest position (Eq. 41)"),
        **_vector("G2", history["G"], "m", "centre of the pad RB2", t),
        **_vector("axis", axis, "1", "unit axis of the pad RB2 (up)", t),
        **_vector("R3", history["R3"], "m", "position of the upper plate RB3", t),
        "step_azimuth": variable(t, np.degrees(np.arctan2(history["e1"][:, 1], history["e1"][:, 0])), "degree",
                             "azimuth of the ground increment of the step ending here (the plane pi of the step)"),
        "gap_1": variable(t, d["gap_1"], "m", "distance between the lower cap centre C21 and the sphere centre C1"),
        "gap_3": variable(t, d["gap_3"], "m", "distance between the upper cap centre C23 and the sphere centre C3"),
    }
    for i, name in enumerate(spatial.RIM_POINTS):
        data[f"I_{name}"] = variable(t, d["interpenetration"][:, i], "m",
                                 f"interpenetration at the {name.replace('_', ' ')} rim point of the step's section "
                                 "(positive into the plate)")
    for plate in ("1", "3"):
        data[f"clearance_{plate}"] = variable(t, d[f"clearance_{plate}"], "m",
                                          f"clearance between the pad and the retaining ring of RB{plate}")
    beyond = (d["clearance_1"] < 0) | (d["clearance_3"] < 0)
    data["capacity_exceeded"] = variable(
        t, beyond.astype(np.int8), "1", "pad beyond a retaining ring",
        flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="within_capacity capacity_exceeded")
    stages = "stick_G" in history
    last = " (its last phase)" if stages else ""
    data["newton_iterations"] = variable(t, history["newton_iterations"], "1",
                                     f"Newton-Raphson iterations of the step{last}")
    data["newton_residual"] = variable(t, history["residual"], "m", f"final max |constraint residual|{last}")
    if stages:
        when = " at the end of the sticking phase"
        s = spatial.diagnostics(history, geometry, prefix="stick_")
        data["tilt_stick"] = variable(t, np.degrees(s["tilt"]), "degree", "tilt of the pad axis" + when)
        data["tilt_azimuth_stick"] = variable(t, np.degrees(s["tilt_azimuth"]), "degree",
                                          "azimuth the pad axis leans towards" + when)
        data["rise_stick"] = variable(t, s["rise"], "m", "rise of RB3" + when)
        data.update(_vector("G2", history["stick_G"], "m", "centre of the pad RB2", t, "_stick", when))
        data.update(_vector("axis", history["stick_Q"][:, :, 2], "1", "unit axis of the pad RB2", t, "_stick", when))
        turn = np.full(len(times), np.nan)
        for k in range(1, len(times)):  # the angle of the rotation of each sticking phase
            R = history["stick_Q"][k] @ history["Q"][k - 1].T
            turn[k] = np.degrees(np.arccos(np.clip(0.5 * (np.trace(R) - 1.0), -1.0, 1.0)))
        data["sticking_rotation"] = variable(t, turn, "degree", "angle the pad turns through in the sticking phase")
        data["newton_iterations_stick"] = variable(t, history["newton_iterations_stick"], "1",
                                               "Newton-Raphson iterations of the sticking phase")
        data["newton_residual_stick"] = variable(t, history["residual_stick"], "m",
                                             "final max |constraint residual| of the sticking phase")
    title = models.model(model).title
    ds = xr.Dataset(data, coords={TIME: time_coordinate(times)})
    ds.attrs = global_attrs(f"DCCSS kinematics under bidirectional ground motion, {title} model",
                            f"{title} model, spatial", model=model, motion="bidirectional", normals="signed",
                            theta2_0_deg=float(np.degrees(theta2_0)), dt_s=float(dt), newton_tol_m=float(tol),
                            **geometry_attrs(geometry), **excitation.attrs(), **(attrs or {}))
    ds.attrs["source"] += ", spatial three-rigid-body kinematic model (bidirectional ground motion)"
    return ds


def structure_variables(response, components, steps) -> dict:
    """The isolated structure's variables (``mechanics.structure.Response``) of the first ``steps``
    steps: stroke, its velocity, F/W and z (``_x``, ``_y`` for two components) and the sticking flag."""
    t = (TIME,)
    out = {}
    table = (("stroke", response.stroke, "m", "stroke u: displacement of the superstructure relative to the ground"),
             ("stroke_velocity", response.velocity, "m s-1", "stroke velocity du/dt"),
             ("shear_ratio", response.shear_ratio, "1", "device force over the supported weight F/W"),
             ("z", response.z, "1", "friction state z of the device (|z| <= 1; du/dt over |du/dt| while sliding)"))
    for name, values, units, long_name in table:
        if values is None:  # an articulated slider's device has no one friction state: each surface's
            continue
        if components == 1:
            out[name] = variable(t, values[:steps, 0], units, long_name)
        else:
            for i, axis in enumerate("xy"):
                out[f"{name}_{axis}"] = variable(t, values[:steps, i], units, f"{long_name}, {axis} component")
    out["structure_sticking"] = variable(
        t, response.sticking[:steps].astype(np.int8), "1", "the superstructure sticks on the device (du/dt = 0)",
        flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="sliding sticking")
    if response.friction is not None:
        out["friction_coefficient"] = variable(t, response.friction[:steps], "1", "the device's friction coefficient "
                                               "mu(t) of its law (at zero speed while the superstructure sticks)")
        speed = np.linalg.norm(response.velocity[:steps], axis=1)
        out["sliding_speed"] = variable(t, speed, "m s-1", "the stroke's speed |du/dt| (surface j slides at R^j / L "
                                                           "times it)")
    if response.temperature is not None:
        surfaces = response.temperature.shape[1]
        for i in range(surfaces):
            name = "surface_temperature" if surfaces == 1 else f"surface_temperature_{'13'[i]}"
            where = "" if surfaces == 1 else f" of RB{'13'[i]}"
            out[name] = variable(t, response.temperature[:steps, i], "degC",
                                 f"the temperature at the centre of the sliding plate{where}")
    if response.normal is not None:
        normal = response.normal[:steps]
        out["vertical_acceleration"] = variable(t, (normal - 1.0) * G, "m s-2",
                                                "vertical ground acceleration a_v (up positive)")
        out["normal_ratio"] = variable(t, normal, "1", "normal force on the device over the supported weight, "
                                                       "N/W = 1 + a_v/g (<= 0: the superstructure lifts off)")
        out["uplift"] = variable(t, (normal <= 0.0).astype(np.int8), "1", "the superstructure lifts off its device "
                                 "(N <= 0)", flag_values=np.array([0, 1], dtype=np.int8),
                                 flag_meanings="seated lifted_off")
    return out


def failure_of(attrs) -> str | None:
    """What marked a history failed (its ``failed`` attribute): "solver", or "capacity" for a ring reached
    under capacity 'error' (``failure_kind``); None where it did not fail."""
    if not int(attrs.get("failed", 0)):
        return None
    return attrs.get("failure_kind", "solver")


def friction_text(attrs, surfaces_given=False) -> str:
    """A structure's friction in words from a dataset's attributes: "μ = 0.05" (Coulomb's; with
    ``surfaces_given`` a surfaces' friction as given, "$μ_s$ = 0.05 on each surface"), or its law and its
    breakaway value ("velocity law, μ = 0.03 at rest"); a property factor other than 1 follows ("λ = 1.3")."""
    law = attrs.get("structure_friction_law", "coulomb")
    if law.replace(" + ", "") != "coulomb" * (law.count("+") + 1):
        text = f"{law} law, μ = {attrs['structure_friction']:.3g} at rest"
    elif surfaces_given and attrs.get("structure_friction_on") == "surfaces" and is_real(
            attrs.get("structure_friction_given")):
        text = f"$μ_s$ = {attrs['structure_friction_given']:g} on each surface"
    else:
        text = f"μ = {attrs['structure_friction']:g}"
    if "structure_property_factor" in attrs:
        text += f", λ = {attrs['structure_property_factor']:g}"
    return text


def is_real(value) -> bool:
    """A finite int or float (not a bool)."""
    return (isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)
            and math.isfinite(value))


def has_structure(ds) -> bool:
    """Whether a dccss dataset holds a history driven by an isolated structure (a stroke)."""
    return "structure_friction" in ds.attrs


def imposed(ds) -> np.ndarray:
    """The motion imposed on RB1 relative to RB3 (m): the ground displacement, or minus the stroke
    of a structure; (T,) for one component, (T, 2) for two."""
    two = is_bidirectional(ds)
    if has_structure(ds):
        return 0.0 - (np.stack([ds["stroke_x"].values, ds["stroke_y"].values], axis=-1) if two else ds["stroke"].values)
    return np.stack([ds["Xg_x"].values, ds["Xg_y"].values], axis=-1) if two else ds["Xg"].values


def is_bidirectional(ds) -> bool:
    """Whether a dccss dataset holds a bidirectional (spatial) history."""
    return ds.attrs.get("motion") == "bidirectional"


def articulated_dataset(times, excitation, geometry, stroke, surfaces, force, *, dt, slider_attrs, response=None,
                        steps=None, attrs=None) -> xr.Dataset:
    """Dataset of one case of an articulated slider (``mechanics.structure.sliders``): the ground displacement Xg
    (imposed on the device, or with a structure beside its stroke, as a rigid slider's history keeps it), each
    surface's displacement u_j (the hinge relative
    to C¹, C³ relative to the hinge; u_1 + u_3 = u), each half's rotation about its sphere centre, the hinge
    rotation, F/W and which surfaces slide; with a structure (``response``) its variables too
    (``structure_variables``) and each surface's friction state and coefficient. ``stroke`` (T, c),
    ``surfaces`` a ``Surfaces`` (or the same fields), ``force`` F/W (T, c)."""
    t = (TIME,)
    n = len(times) if steps is None else steps
    two = stroke.shape[1] == 2
    L1, L3 = surfaces.pendulums
    data = {}

    def vector(name, values, units, long_name):
        if two:
            for i, axis in enumerate("xy"):
                data[f"{name}_{axis}"] = variable(t, values[:n, i], units, f"{long_name}, {axis} component")
        else:
            data[name] = variable(t, values[:n, 0], units, long_name)

    if response is None:
        vector("Xg", 0.0 - stroke, "m", "imposed ground displacement X_g (RB1 relative to RB3: minus the stroke)")
        vector("stroke", stroke, "m", "stroke u: RB3 relative to RB1 (the superstructure's displacement relative to "
                                      "the ground)")
        vector("shear_ratio", force, "1", "device force over the supported weight F/W (quasi-static)")
    for j, (plate, Lj) in enumerate(((1, L1), (3, L3))):
        what = "the hinge relative to C1" if plate == 1 else "C3 relative to the hinge"
        vector(f"stroke_{plate}", surfaces.stroke[..., j], "m", f"displacement u_{plate} on surface {plate} ({what})")
        size = np.linalg.norm(surfaces.stroke[:n, :, j], axis=1)
        tilt = np.degrees(np.arcsin(np.clip(surfaces.stroke[:n, 0, j] / Lj, -1, 1))) if not two else \
            np.degrees(np.arcsin(np.clip(size / Lj, -1, 1)))
        data[f"theta_{plate}" if not two else f"tilt_{plate}"] = variable(
            t, tilt, "degree", f"rotation of the half on surface {plate} about C{plate}" +
            (" (sin = u_j / L_j)" if not two else ": its tilt from the vertical"))
        data[f"sliding_{plate}"] = variable(
            t, surfaces.sliding[:n, j].astype(np.int8), "1", f"surface {plate} slides",
            flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="holds slides")
    data["hinge_rotation"] = variable(t, np.degrees(surfaces.hinge[:n]), "degree",
                                      "rotation of the hinge, the angle between the two halves" +
                                      (" (theta_1 - theta_3)" if not two else " (>= 0)"))
    if response is not None:
        vector("Xg", np.reshape(excitation.displacement(np.asarray(times)[:n]), (n, -1)), "m",
               "ground displacement X_g (the device undergoes minus the stroke)")
        data.update(structure_variables(response, stroke.shape[1], n))
        for j, plate in enumerate((1, 3)):
            vector(f"z_{plate}", surfaces.z[..., j], "1", f"friction state z_{plate} of surface {plate} (|z| <= 1; "
                                                         f"along its sliding while it slides)")
            data[f"friction_coefficient_{plate}"] = variable(
                t, surfaces.friction[:n, j], "1", f"friction coefficient mu_{plate} of surface {plate} (at its "
                                                   f"sliding speed; at rest while it holds)")
    ds = xr.Dataset(data, coords={TIME: time_coordinate(np.asarray(times)[:n])})
    ds.attrs = global_attrs("DCCSS articulated slider: two pendulums in series", "articulated slider",
                            model="articulated", motion="bidirectional" if two else "unidirectional",
                            dt_s=float(dt), **geometry_attrs(geometry), **excitation.attrs(), **slider_attrs,
                            **(attrs or {}))
    ds.attrs["source"] += ", articulated slider (two pendulums in series, Fenz and Constantinou 2006)"
    return ds
