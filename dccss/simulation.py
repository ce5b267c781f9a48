"""One case in, one dataset out: time histories and the breakaway (first-step) analysis."""

from __future__ import annotations

import numpy as np
import xarray as xr

from . import models
from ._version import __version__
from .constraints import Compliant
from .excitation import step_times
from .kinematics import CORNERS, all_corners, corner_diagnostics, interpenetration
from .newton import NewtonOptions
from .results import REFERENCE, _var, coordinates, geometry_attrs, history_dataset

CAPACITY_POLICIES = ("continue", "stop", "error")


class CapacityError(ValueError):
    """The pad reached a retaining ring (the excitation exceeds the device capacity)."""


def simulate(geometry, excitation, *, model="compliant", dt, theta2_0=0.0, normals="signed",
             options: NewtonOptions = NewtonOptions(), capacity="continue",
             attrs: dict | None = None) -> xr.Dataset:
    """Run one case and return its dataset.

    Parameters
    ----------
    geometry : Geometry (scalar fields).
    excitation : ``excitation.Sine`` or ``excitation.Table``.
    model : 'compliant' or 'stick_slip'.
    dt : time step (s); the steps are t_n = t_start + n dt up to the excitation's end.
    theta2_0 : pad rotation at t_0 (rad); the start is the compatible configuration there.
    normals : 'signed' (consistent) or 'unsigned' (the authors' |alpha|).
    options : Newton-Raphson tolerance and iteration cap.
    capacity : what to do when the pad reaches a retaining ring: 'continue' (flag it: the
        ``capacity_exceeded`` variable and the ``capacity_exceeded_at_s`` attribute), 'stop' (the
        dataset ends at that step, flagged) or 'error' (raise CapacityError).
    attrs : extra global attributes (e.g. a case id).
    """
    if model not in models.MODELS:
        raise ValueError(f"model must be one of {models.MODELS}, got {model!r}")
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    if np.ndim(geometry.L) != 0:
        raise ValueError("simulate runs one case: geometry fields must be scalars")
    times = step_times(excitation, dt)
    steps = []
    for step in models.steps(model, geometry, excitation.displacement(times), theta2_0, normals=normals,
                             options=options, times=times):
        steps.append(step)
        if capacity != "continue" and (corner_diagnostics(step["q"], geometry)[1] < 0).any():
            break  # the pad reaches a ring: stop here (or fail below) before solving further
    ds = history_dataset(model, models.collect(steps), geometry, times[:len(steps)], excitation,
                         theta2_0=theta2_0, dt=dt, normals=normals, tol=options.tol, attrs=attrs)
    exceeded = np.flatnonzero(ds["capacity_exceeded"].values)
    if exceeded.size:
        n = int(exceeded[0])
        t = float(times[n])
        plate = "RB1" if ds["clearance_1"].values[n] < 0 else "RB3"
        if capacity == "error":
            raise CapacityError(f"the pad reaches the retaining ring of {plate} at t = {t:.6g} s (step {n}): the "
                                f"excitation exceeds the device capacity (R1 sin(alpha1 - alpha21) = "
                                f"{geometry.capacity1:.4g} m); lower the amplitude or set capacity: continue")
        ds.attrs.update(capacity_exceeded_at_s=t, capacity_exceeded_plate=plate)
        if capacity == "stop":
            ds.attrs["capacity_policy"] = "stopped at the exceedance"
    return ds


def breakaway(geometry, theta2_0, dXg, *, normals="signed",
              options: NewtonOptions = NewtonOptions(), attrs: dict | None = None) -> xr.Dataset:
    """Fig. 7: one compliant step of size dXg (m) from the compatible configuration at each
    theta^2(t_0) (rad, 1-D array); interpenetration I_A..I_D after the step, |C_q| and the
    configurations before and after. A scalar dXg gives dimension ``theta2_0``; a 1-D array of
    step sizes adds a leading dimension ``dXg`` (all solved as one batch)."""
    theta2_0 = np.atleast_1d(np.asarray(theta2_0, dtype=float))
    if theta2_0.ndim != 1 or theta2_0.size == 0:
        raise ValueError("theta2_0 must be a non-empty 1-D grid of initial pad rotations")
    steps = np.asarray(dXg, dtype=float)
    if steps.ndim > 1 or steps.size == 0 or not np.all(np.isfinite(steps)):
        raise ValueError(f"dXg must be a finite number or a non-empty 1-D array, got {dXg!r}")
    sizes = np.atleast_1d(steps)
    Xg = np.zeros((2, sizes.size, theta2_0.size))
    Xg[1] = sizes[:, None]
    h = models.compliant(geometry, Xg, theta2_0, normals=normals, options=options)
    q, q0 = h["q"][1], h["q"][0]
    corners = all_corners(geometry)
    cset = Compliant(corners, q[..., 0], h["Rx3"], [h["point"][1][..., i] for i in range(4)],
                     [h["normal"][1][..., i] for i in range(4)])
    I = interpenetration(q, geometry)
    d = ("dXg", "theta2_0")
    data = {f"I_{c}": _var(d, I[..., i], "m", f"interpenetration at corner {c}2 after the first step")
            for i, c in enumerate(CORNERS)}
    data["det_Cq"] = _var(d, cset.determinant(q), "m", "determinant |C_q| (Eq. 29) of the first step")
    data["newton_iterations"] = _var(d, h["newton_iterations"][1], "1", "Newton-Raphson iterations")
    data.update(coordinates(q, d, "", " after the first step"))
    data.update(coordinates(q0, d, "_t0", " in the initial compatible configuration"))
    ds = xr.Dataset(data, coords={
        "theta2_0": _var(("theta2_0",), np.degrees(theta2_0), "degree", "initial pad rotation theta2(t0)"),
        "dXg": _var(("dXg",), sizes, "m", "imposed ground displacement of the first step")})
    ds.attrs = {"Conventions": "CF-1.11",
                "title": "DCCSS breakaway: interpenetration at the first compliant sliding step",
                "source": f"dccss {__version__}", "references": REFERENCE, "model": "compliant",
                "history": f"computed by dccss {__version__} (breakaway sweep)",
                "normals": normals, "dccss_version": __version__, **geometry_attrs(geometry), **(attrs or {})}
    if steps.ndim == 0:
        ds = ds.isel(dXg=0)
        ds.attrs["dXg_m"] = float(steps)
    return ds
