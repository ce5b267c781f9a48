"""One case in, one dataset out: time histories (planar or spatial, as the excitation has one or two
components; run by ``mechanics.runs``) and the breakaway (first-step) analysis."""

from __future__ import annotations

import warnings
from types import SimpleNamespace

import numpy as np
import xarray as xr

from .excitation import step_times, uncovered
from .mechanics import models, runs
from .mechanics.capacity import CapacityError
from .mechanics.geometry import Geometry
from .mechanics.newton import NewtonOptions
from .mechanics.structure import Structure, respond
from .results import articulated_dataset, breakaway_dataset, history_dataset, spatial_dataset, structure_variables


def simulate(geometry, excitation, *, model="compliant", dt, theta2_0=0.0, normals="signed",
             options: NewtonOptions = NewtonOptions(), capacity="continue", on_failure="error",
             attrs: dict | None = None, progress=None, structure: Structure | None = None,
             slider: str = "rigid", hinge: float = 0.0, friction=None) -> xr.Dataset:
    """Run one case and return its dataset.

    Parameters
    ----------
    geometry : Geometry
        The device (scalar fields).
    excitation : Sine, Table, PlaneTable, Record, RecordPair, or one of them Oriented, Scaled or a Component
        The ground motion: one component runs the planar models, two the spatial ones.
    model : str
        A model of the registry: 'compliant' or 'stick_slip'.
    dt : float
        Time step (s); the steps are t_n = t_start + n dt up to the excitation's end.
    theta2_0 : float
        Pad rotation at t_0 (rad); the start is the compatible configuration there.
    normals : str
        'signed' (consistent) or 'unsigned' (the authors' |alpha|).
    options : NewtonOptions
        Newton-Raphson tolerance and iteration cap (its ``on_failure`` is a sweep's: a history's
        failure policy is ``on_failure`` below).
    capacity : str
        What to do when the pad reaches a retaining ring: 'continue' (flag it), 'stop' (the dataset
        ends at that step) or 'error' (raise CapacityError; with on_failure 'mark' the history ends at
        that step, marked failed there, as a study marks such a case). In every case the attributes
        ``capacity_exceeded_at_s``, ``capacity_exceeded_plate`` (RB1 or RB3, the plate whose ring is
        reached first) and ``capacity_exceeded_by_m`` (how far the pad passes a ring at most) say when,
        where and by how much, and ``capacity_exceeded_displacement_m`` how far RB1 had moved from its
        start then (the ground's displacement, or the stroke); ``stopped_at_s`` says where 'stop' ended
        the history. A step with no compatible configuration (RB1 displaced from RB3 by L or more) is a
        failure under every capacity policy.
    on_failure : str
        'error' (a ConvergenceError) or 'mark': the dataset holds the history up to the last converged
        step, with the attributes ``failed`` = 1, ``failure_time_s`` (the step that failed),
        ``failure_kind`` ("solver"; "capacity" for a ring reached under capacity 'error') and
        ``failure_message``.
    attrs : dict, optional
        Extra global attributes (e.g. a case id).
    progress : callable, optional
        ``progress(n, N)``, called once, when the history is done (n of N steps: n < N where it
        stopped at a ring).
    structure : Structure, optional
        A superstructure (friction μ, damping ζ) on the device. None: the ground displacement is
        imposed on RB1 relative to RB3, the superstructure held still in space. A structure: the
        excitation's ground acceleration drives the superstructure (``mechanics.structure``), and its
        stroke u (the superstructure relative to the ground) is what the device undergoes: RB1 moves
        by -u relative to RB3. The dataset keeps the ground motion (``Xg``) beside the stroke, its
        velocity, the force ratio F/W, the friction state z and whether the structure sticks
        (``results.structure_variables``).
    slider, hinge, friction : optional
        The device's construction (``mechanics.structure.sliders``): ``rigid`` (the paper's pad, the
        default) or ``articulated`` (two halves on a hinge ``hinge`` m above the pad's centre, each surface
        sliding by its own friction). With a structure these are the structure's (its ``slider`` and
        ``hinge``). An articulated slider without a structure is driven quasi-statically by the imposed
        displacement (one component; its slider's mass neglected), its surfaces' Coulomb coefficients
        ``friction`` = (μ1, μ3) (each at its sliding surface, as a structure's ``friction_on: surfaces``).
        Its dataset (``results.articulated_dataset``) holds each surface's share of the stroke, the
        halves' and the hinge's rotations; ``model`` is not used (the halves stay seated on their surfaces).

    Returns
    -------
    xarray.Dataset
        The history (CF-1.11; variables and attributes: the documentation's Datasets reference).

    Notes
    -----
    A solver failure after the pad has passed a retaining ring says so first: beyond the ring
    the model describes no real device, and a smaller dt does not help.
    """
    _check_arguments(geometry, excitation, theta2_0, structure)  # options: runs.history checks them
    if structure is not None:
        slider, hinge = structure.slider, structure.hinge
    times = step_times(excitation, dt)
    short = uncovered(excitation, times, dt)
    if short:
        warnings.warn(short, stacklevel=2)
    if slider == "articulated":
        return articulated(geometry, excitation, times, dt=dt, structure=structure, hinge=hinge, friction=friction,
                           capacity=capacity, on_failure=on_failure, attrs=attrs, progress=progress)
    response, lifted, samples = None, None, len(times)
    if structure is None:
        imposed = excitation.displacement(times)
    else:
        response = respond(excitation.ground_acceleration(), times, geometry, structure)
        imposed = 0.0 - (response.stroke[:, 0] if excitation.components == 1 else response.stroke)
        lifted = _uplift(response, times, capacity, on_failure)
        if lifted is not None:  # the history ends before the structure lifts off
            times, imposed = times[:lifted], imposed[:lifted]
    run = runs.history(model, geometry, imposed, theta2_0,
                       azimuth=float(getattr(excitation, "azimuth", 0.0)), normals=normals, options=options,
                       capacity=capacity, on_failure=on_failure, times=times, progress=progress)
    if run.motion == "spatial":
        ds = spatial_dataset(model, run.history, geometry, times[:run.steps], excitation, theta2_0=theta2_0, dt=dt,
                             tol=options.tol, attrs=attrs)
    else:
        ds = history_dataset(model, run.history, geometry, times[:run.steps], excitation, theta2_0=theta2_0, dt=dt,
                             normals=normals, tol=options.tol, attrs=attrs)
    if response is not None:
        ds = ds.assign(structure_variables(response, excitation.components, run.steps))
        ds.attrs.update(structure.attrs(geometry), structure_stroke_max_abs_m=response.peaks[0],
                        structure_shear_ratio_max_abs=response.peaks[1])
        if response.normal is not None:
            ds.attrs["structure_normal_ratio_min"] = response.peaks[2]
        ds.attrs["imposed_motion"] = ("minus the stroke: RB1 relative to RB3 is -u, u the superstructure's "
                                      "displacement relative to the ground")
    ds.attrs["capacity_policy"] = capacity
    ds.attrs["failed"] = int(run.failure is not None)
    if run.failure is not None:
        at_ring = isinstance(run.failure, CapacityError)  # capacity "error", marked: the run ends at the ring
        ds.attrs.update(failure_time_s=run.reached["t"] if at_ring else float(times[run.steps]),
                        failure_kind="capacity" if at_ring else "solver", failure_message=str(run.failure))
    if run.reached:
        ds.attrs.update(capacity_exceeded_at_s=run.reached["t"], capacity_exceeded_plate=run.reached["plate"],
                        capacity_exceeded_by_m=run.reached["by"],
                        capacity_exceeded_displacement_m=run.reached["displacement"])
    if run.status == "stopped":
        ds.attrs["stopped_at_s"] = float(times[run.steps - 1])
    if response is not None and run.steps < samples:  # the structure's peaks of the history as cut
        ds.attrs.update(_peaks_until(response, run.steps))
    if response is not None and response.uplift:
        ds.attrs.update(uplift_attrs(response))
        if lifted is not None and run.steps == lifted and not ds.attrs["failed"]:
            if capacity == "stop":
                ds.attrs.update(stopped_at_s=float(times[-1]), stopped_by="uplift")
            else:  # capacity "error", marked
                ds.attrs.update(failed=1, failure_time_s=response.uplift[0][0], failure_kind="uplift",
                                failure_message=uplift_message(response))
    return ds


class UpliftError(CapacityError):
    """The superstructure lifts off its device (N = W (1 + a_v/g) <= 0) under capacity 'error'."""


def uplift_message(response) -> str:
    """What an uplift is: when it starts and ends, how often, the smallest N/W."""
    (start, end), count = response.uplift[0], len(response.uplift)
    return (f"the superstructure lifts off its device at t = {start:.6g} s (N/W = 1 + a_v/g <= 0 until "
            f"t = {end:.6g} s; {count} time{'s' if count > 1 else ''} in all, smallest N/W "
            f"{response.peaks[2]:.3g}): beyond it the model describes no real structure")


def uplift_attrs(response) -> dict:
    """The attributes of a structure's uplift: its first time, the total duration and the count."""
    return {"uplift_at_s": response.uplift[0][0], "uplift_duration_s": float(sum(b - a for a, b in response.uplift)),
            "uplift_count": len(response.uplift)}


def _uplift(response, times, capacity, on_failure) -> int | None:
    """How many steps a history keeps when its structure lifts off under ``capacity`` 'stop' or 'error'
    (those before the first uplift), None where it runs on (no uplift, or 'continue', which flags it).
    Under 'error' with on_failure 'error' it raises :class:`UpliftError`."""
    if not response.uplift:
        return None
    if capacity == "continue":
        warnings.warn(uplift_message(response) + "; the history goes on (capacity: continue), flagged",
                      stacklevel=3)
        return None
    if capacity == "error" and on_failure != "mark":
        raise UpliftError(uplift_message(response) + " (capacity: error)")
    return max(2, int(np.searchsorted(times, response.uplift[0][0], side="left")))


def _check_arguments(geometry, excitation, theta2_0, structure):
    """A TypeError or ValueError names an argument of ``simulate`` that is not what it takes."""
    if not isinstance(geometry, Geometry):
        raise TypeError(f"geometry must be a Geometry (e.g. Geometry.from_degrees(...) or a Table 1 prototype), got "
                        f"{type(geometry).__name__} {geometry!r:.80}")
    if np.ndim(geometry.L) != 0:
        raise ValueError("geometry: a history runs one device: its fields must be scalars")
    if not all(hasattr(excitation, a) for a in ("displacement", "t_start", "t_end")):
        raise TypeError(f"excitation must be a Sine, Table, PlaneTable, Record, RecordPair or one of them Oriented, "
                        f"Scaled or as a Component, got {type(excitation).__name__} {excitation!r:.80}")
    if isinstance(theta2_0, (bool, str)) or np.ndim(theta2_0) != 0 or not isinstance(
            np.asarray(theta2_0).item(), (int, float)):
        raise TypeError(f"theta2_0 must be a number (rad), got {type(theta2_0).__name__} {theta2_0!r:.80}")
    if structure is not None and not isinstance(structure, Structure):
        raise TypeError(f"structure must be a Structure (e.g. Structure(friction=0.05)) or None, got "
                        f"{type(structure).__name__} {structure!r:.80}")


def breakaway(geometry, theta2_0=None, dXg=None, *, theta2_0_deg=None, normals="signed",
              options: NewtonOptions = NewtonOptions(), attrs: dict | None = None) -> xr.Dataset:
    """Fig. 7: one compliant step of size dXg from the compatible configuration at each initial pad
    rotation θ²(t₀): the interpenetration I_A..I_D after the step, |C_q| and the configurations
    before and after.

    The angles follow the library's rule: arguments in radians (as ``simulate``'s ``theta2_0`` and a
    ``Geometry``'s angles), datasets in degrees (as every angle a dataset holds, with ``units``
    "degree"); ``theta2_0_deg`` takes the grid in the dataset's unit instead.

    Parameters
    ----------
    geometry : Geometry (scalar fields).
    theta2_0 : the initial pad rotations θ²(t₀) in radians: a number or a non-empty 1-D array.
    dXg : the ground step (m): a number, or a 1-D array of steps (all solved as one batch).
    theta2_0_deg : the initial pad rotations in degrees, instead of ``theta2_0`` (give one of the
        two); the dataset's coordinate then holds these very values.
    normals : 'signed' (consistent) or 'unsigned' (the authors' |alpha|).
    options : Newton-Raphson tolerance and iteration cap.
    attrs : extra global attributes (e.g. a case id).

    Returns
    -------
    xarray.Dataset
        Dimension ``theta2_0``, the coordinate in degrees (``units`` "degree") whichever argument
        gave it; an array dXg adds a leading dimension ``dXg`` (m), a scalar one is the attribute
        ``dXg_m``.

    Raises
    ------
    TypeError
        Both or neither of ``theta2_0`` and ``theta2_0_deg``, or no ``dXg``.
    ValueError
        An empty or 2-D grid, an angle not within (-90, 90) degrees, a non-finite or 2-D ``dXg``.
    """
    if (theta2_0 is None) == (theta2_0_deg is None):
        raise TypeError("breakaway() takes the initial pad rotations once: theta2_0 (radians) or theta2_0_deg "
                        f"(degrees), got {'both' if theta2_0 is not None else 'neither'}")
    if dXg is None:
        raise TypeError("breakaway() needs the ground step dXg (m)")
    if not isinstance(geometry, Geometry) or np.ndim(geometry.L) != 0:
        raise TypeError(f"geometry must be a Geometry of scalar fields (one device), got {type(geometry).__name__}")
    key = "theta2_0" if theta2_0_deg is None else "theta2_0_deg"
    try:
        grid = np.atleast_1d(np.asarray(theta2_0 if theta2_0_deg is None else theta2_0_deg, dtype=float))
        steps = np.asarray(dXg, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{key} and dXg must be numbers or 1-D arrays of numbers, got {key} = "
                         f"{theta2_0 if theta2_0_deg is None else theta2_0_deg!r}, dXg = {dXg!r}") from None
    if grid.ndim != 1 or grid.size == 0:
        raise ValueError(f"{key} must be a non-empty 1-D grid of initial pad rotations")
    if theta2_0_deg is not None and not np.all(np.abs(grid) < 90.0):  # named in the unit it was given in
        raise ValueError(f"theta2_0_deg must be finite angles within (-90, 90) degrees, got "
                         f"{float(grid[~(np.abs(grid) < 90.0)][0])!r}")
    theta2_0 = grid if theta2_0_deg is None else np.radians(grid)
    runs.check_start(theta2_0)
    if steps.ndim > 1 or steps.size == 0 or not np.all(np.isfinite(steps)):
        raise ValueError(f"dXg must be a finite number or a non-empty 1-D array, got {dXg!r}")
    sizes = np.atleast_1d(steps)
    if np.any(np.abs(sizes) >= geometry.L):
        raise ValueError(f"dXg: a step of {float(sizes[np.abs(sizes) >= geometry.L][0]):g} m moves RB1 from RB3 by the "
                         f"pendulum length L = {float(geometry.L):.4g} m or more: no compatible configuration exists")
    Xg = np.zeros((2, sizes.size, theta2_0.size))
    Xg[1] = sizes[:, None]
    history = models.run("compliant", geometry, Xg, theta2_0, normals=normals, options=options)
    ds = breakaway_dataset(history, geometry, theta2_0, sizes, normals, attrs)
    if theta2_0_deg is not None:  # the grid as given, not its round trip through radians
        ds = ds.assign_coords(theta2_0=("theta2_0", grid, ds["theta2_0"].attrs))
    if steps.ndim == 0:
        ds = ds.isel(dXg=0)
        ds.attrs["dXg_m"] = float(steps)
    return ds


def articulated(geometry, excitation, times, *, dt, structure=None, hinge=0.0, friction=None, capacity="continue",
                on_failure="error", attrs=None, progress=None) -> xr.Dataset:
    """One case of an articulated slider (``simulate``): driven by its structure (``respond``), or without one
    quasi-statically by the imposed displacement (``series.quasi_static``, one component). A half that reaches
    its plate's ring (|u_j| = L_j sin(α^j - α^2j)) is flagged in the attributes (``ring_<j>_reached_at_s``,
    ``ring_<j>_exceeded_by_m``) and handled by ``capacity`` as the rigid pad's ring is."""
    from .mechanics.structure import sliders
    from .mechanics.structure.series import BOTH, SLIDE1, SLIDE3, quasi_static

    lifted = None
    if structure is None:
        if excitation.components != 1:
            raise ValueError("an articulated slider under an imposed displacement is modelled in one component: for "
                             "two, drive it through a structure (structure: {friction: [mu1, mu3], friction_on: "
                             "surfaces})")
        mu1, mu3 = _surfaces_friction(friction)
        problem = sliders.hinge_problem(geometry, hinge)
        if problem:
            raise ValueError(problem)
        L1, L3 = sliders.pendulums(geometry, hinge)
        m1, m3 = mu1 * float(geometry.R1) / L1, mu3 * float(geometry.R3) / L3
        u = 0.0 - excitation.displacement(times)
        u1, f, phase = quasi_static(u, L1, L3, m1, m3)
        split = np.stack([u1, u - u1], axis=-1)[:, None, :]
        surfaces = SimpleNamespace(
            stroke=split, pendulums=(L1, L3), hinge=np.arcsin(np.clip(u1 / L1, -1, 1)) -
            np.arcsin(np.clip((u - u1) / L3, -1, 1)),
            sliding=np.stack([(phase == SLIDE1) | (phase == BOTH), (phase == SLIDE3) | (phase == BOTH)], axis=-1))
        stroke, force, response = u[:, None], f[:, None], None
        slider_attrs = {"slider": "articulated", "slider_hinge_m": float(hinge), "friction_surfaces": np.array(
            [mu1, mu3]), "friction_force_level": np.array([m1, m3]), "motion_imposed": "quasi-static"}
    else:
        response = respond(excitation.ground_acceleration(), times, geometry, structure)
        lifted = _uplift(response, times, capacity, on_failure)
        surfaces, stroke, force = response.surfaces, response.stroke, response.shear_ratio
        L1, L3 = surfaces.pendulums
        slider_attrs = {**structure.attrs(geometry), "slider": "articulated", "slider_hinge_m": float(hinge),
                        "structure_stroke_max_abs_m": response.peaks[0],
                        "structure_shear_ratio_max_abs": response.peaks[1],
                        "stroke_1_max_abs_m": surfaces.peaks[0], "stroke_3_max_abs_m": surfaces.peaks[1],
                        "hinge_rotation_max_abs_deg": float(np.degrees(surfaces.hinge_peak))}
        if response.normal is not None:
            slider_attrs["structure_normal_ratio_min"] = response.peaks[2]
    rings = sliders.ring_strokes(geometry, hinge)
    slider_attrs.update(pendulum_length_1_m=L1, pendulum_length_3_m=L3, ring_stroke_1_m=rings[0],
                        ring_stroke_3_m=rings[1])
    steps = len(times) if lifted is None else lifted
    size = np.linalg.norm(surfaces.stroke[:steps], axis=1)  # (T, 2)
    reached = {plate: int(np.argmax(size[:, j] >= rings[j])) for j, plate in enumerate((1, 3))
               if np.any(size[:, j] >= rings[j])}
    failed = None
    if reached and capacity in ("stop", "error"):
        plate = min(reached, key=reached.get)
        j, first = (0 if plate == 1 else 1), reached[plate]
        message = (f"the half on surface {plate} reaches the ring of RB{plate} at t = {times[first]:.6g} s "
                   f"(u_{plate} = {size[first, j]:.4g} m, its ring at {rings[j]:.4g} m)")
        if capacity == "error" and on_failure != "mark":
            raise CapacityError(message + " (capacity: error)")
        failed = message if capacity == "error" else None
        slider_attrs["stopped_at_s" if capacity == "stop" else "failure_time_s"] = float(times[first])
        steps = first + 1
    for j, plate in enumerate((1, 3)):  # the rings as the history (as cut) reaches them
        if reached.get(plate, steps) < steps:
            slider_attrs[f"ring_{plate}_reached_at_s"] = float(times[reached[plate]])
            slider_attrs[f"ring_{plate}_exceeded_by_m"] = float(size[:steps, j].max() - rings[j])
    if response is not None and steps < len(times):  # the peaks of the history as cut
        slider_attrs.update(_peaks_until(response, steps))
        slider_attrs.update(stroke_1_max_abs_m=float(size[:steps, 0].max()),
                            stroke_3_max_abs_m=float(size[:steps, 1].max()),
                            hinge_rotation_max_abs_deg=float(np.degrees(np.abs(surfaces.hinge[:steps]).max())))
    if progress is not None:
        progress(steps, len(times))
    ds = articulated_dataset(times, excitation, geometry, stroke, surfaces, force, dt=dt, slider_attrs=slider_attrs,
                             response=response, steps=steps, attrs=attrs)
    ds.attrs["capacity_policy"] = capacity
    ds.attrs["failed"] = int(failed is not None)
    if failed is not None:
        ds.attrs.update(failure_kind="capacity", failure_message=failed)
    if response is not None and response.uplift:
        ds.attrs.update(uplift_attrs(response))
    return ds


def _peaks_until(response, steps) -> dict:
    """The structure's peak attributes of a history cut at ``steps`` samples (a ring reached under ``capacity:
    stop`` or ``error``, an uplift): over the samples kept, not the whole record (``Response.peaks``)."""
    out = {"structure_stroke_max_abs_m": float(np.linalg.norm(response.stroke[:steps], axis=1).max()),
           "structure_shear_ratio_max_abs": float(np.linalg.norm(response.shear_ratio[:steps], axis=1).max())}
    if response.normal is not None:
        out["structure_normal_ratio_min"] = float(np.min(response.normal[:steps]))
    return out


def _surfaces_friction(friction) -> tuple[float, float]:
    """(μ1, μ3) of an articulated slider under the imposed displacement; a ValueError names ``friction``."""
    if friction is None:
        raise ValueError("friction: an articulated slider without a structure needs its surfaces' Coulomb "
                         "coefficients, friction: [mu1, mu3] (each at its sliding surface)")
    try:
        mu1, mu3 = (float(x) for x in friction)
    except (TypeError, ValueError):
        raise ValueError(f"friction: expected two numbers [mu1, mu3], got {friction!r}") from None
    if not all(0.0 < x < 1.0 for x in (mu1, mu3)):
        raise ValueError(f"friction: each surface's mu must lie in 0 < mu < 1 (with none, which surface slides is "
                         f"not decided), got {[mu1, mu3]}")
    return mu1, mu3
