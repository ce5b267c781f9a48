"""One case in, one dataset out: time histories and the breakaway (first-step) analysis."""

from __future__ import annotations

import numpy as np
import xarray as xr

from .excitation import step_times
from .mechanics import backend, models
from .mechanics.capacity import CAPACITY_POLICIES, capacity_message, history_error, ring_reached
from .mechanics.kinematics import corner_diagnostics
from .mechanics.newton import FAILURE_POLICIES, ConvergenceError, NewtonOptions
from .results import breakaway_dataset, history_dataset


def simulate(geometry, excitation, *, model="compliant", dt, theta2_0=0.0, normals="signed",
             options: NewtonOptions = NewtonOptions(), capacity="continue", on_failure="error",
             attrs: dict | None = None, progress=None) -> xr.Dataset:
    """Run one case and return its dataset.

    Parameters
    ----------
    geometry : Geometry (scalar fields).
    excitation : ``excitation.Sine``, ``excitation.Table`` or ``records.Record``.
    model : 'compliant' or 'stick_slip'.
    dt : time step (s); the steps are t_n = t_start + n dt up to the excitation's end.
    theta2_0 : pad rotation at t_0 (rad); the start is the compatible configuration there.
    normals : 'signed' (consistent) or 'unsigned' (the authors' |alpha|).
    options : Newton-Raphson tolerance and iteration cap.
    capacity : what to do when the pad reaches a retaining ring: 'continue' (flag it), 'stop'
        (the dataset ends at that step) or 'error' (raise CapacityError). In every case the
        attributes ``capacity_exceeded_at_s``, ``capacity_exceeded_plate`` (RB1 or RB3, the
        plate whose ring is reached first) and ``capacity_exceeded_by_m`` (how far the pad
        passes a ring at most) say when, where and by how much; ``stopped_at_s`` says where
        'stop' ended the history.
    on_failure : 'error' (a ConvergenceError) or 'mark': the dataset holds the history up to
        the last converged step, with the attributes ``failed`` = 1, ``failure_time_s`` (the
        step that failed) and ``failure_message``.
    attrs : extra global attributes (e.g. a case id).
    progress : optional callable ``progress(n, N)`` called after each step n of N (once, when the
        history is done, where compiled kernels run it: long planar runs and every spatial run).

    A solver failure after the pad has passed a retaining ring says so first: beyond the ring
    the model describes no real device, and a smaller dt does not help.
    """
    if getattr(excitation, "components", 1) == 2:  # bidirectional: the spatial models
        return simulate_spatial(geometry, excitation, model=model, dt=dt, theta2_0=theta2_0, normals=normals,
                                options=options, capacity=capacity, on_failure=on_failure, attrs=attrs,
                                progress=progress)
    models.model(model)  # a ValueError names the known models
    _check_policies(capacity, on_failure)
    if np.ndim(geometry.L) != 0:
        raise ValueError("simulate runs one case: geometry fields must be scalars")
    times = step_times(excitation, dt)
    try:
        history = _history(model, geometry, excitation.displacement(times), theta2_0, normals, options, times,
                           capacity != "continue", progress)
        failure = None
    except ConvergenceError as err:
        history = getattr(err, "history", None)
        gaps = None if history is None else corner_diagnostics(history["q"], geometry)[1]
        failure = _explain(err, geometry, None if gaps is None else (gaps[:, 0], gaps[:, 1]), times)
        if on_failure == "error" or history is None:
            raise failure from None
    steps = history["q"]
    ds = history_dataset(model, history, geometry, times[:len(steps)], excitation,
                         theta2_0=theta2_0, dt=dt, normals=normals, tol=options.tol, attrs=attrs)
    return _settle(ds, geometry, capacity, failure, times, len(steps))


def _check_policies(capacity, on_failure):
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    if on_failure not in FAILURE_POLICIES:
        raise ValueError(f"on_failure must be one of {FAILURE_POLICIES}, got {on_failure!r}")


def _history(model, geometry, Xg, theta2_0, normals, options, times, stop_at_ring, progress):
    """The history (``models.collect``); with ``stop_at_ring`` it ends at the first step
    where the pad has passed a retaining ring. A ConvergenceError carries the history up to the
    last converged step as ``err.history``. A long history runs on the compiled kernels
    (``backend``; ``progress`` is then called once, at the end)."""
    kernels, history = backend.compiled(model, len(Xg) - 1), None
    if kernels is not None:
        try:
            history = kernels.run(model, geometry, Xg, theta2_0, normals=normals, options=options, times=times,
                                  stop_at_ring=stop_at_ring)
        except ConvergenceError as err:
            history = getattr(err, "history", None)
            raise
        finally:
            if progress is not None and history is not None:
                progress(len(history["q"]) - 1, len(Xg) - 1)
        return history
    steps = []
    try:
        for step in models.steps(model, geometry, Xg, theta2_0, normals=normals, options=options, times=times):
            steps.append(step)
            if progress is not None:
                progress(step.n, len(Xg) - 1)
            if stop_at_ring and (corner_diagnostics(step.q, geometry)[1] < 0).any():
                break  # the pad reaches a ring: stop here (or fail below) before solving further
    except ConvergenceError as err:
        if steps:
            err.history = models.collect(steps)
        raise
    return models.collect(steps)


def _explain(err, geometry, gaps, times):
    """A solver failure, prefixed with the ring the pad passed before it (if it did); ``gaps``: the
    clearances to the rings of RB1 and RB3 of the converged steps (None: none converged)."""
    if gaps is None or len(gaps[0]) == 0:
        return err
    reached = ring_reached(gaps[0], gaps[1], times[:len(gaps[0])])
    if reached is None:
        return err
    return err.with_hint(
        "Beyond the ring the model describes no real device and a smaller dt does not help: set capacity: "
        "stop to end the history at the ring, or lower the excitation.",
        prefix=f"Before the solver failed, {capacity_message(geometry, reached, 'reached')}.")


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
    history = models.run("compliant", geometry, Xg, theta2_0, normals=normals, options=options)
    ds = breakaway_dataset(history, geometry, theta2_0, sizes, normals, attrs)
    if steps.ndim == 0:
        ds = ds.isel(dXg=0)
        ds.attrs["dXg_m"] = float(steps)
    return ds


def simulate_spatial(geometry, excitation, *, model="compliant", dt, theta2_0=0.0, normals="signed",
                     options: NewtonOptions = NewtonOptions(), capacity="continue", on_failure="error",
                     attrs: dict | None = None, progress=None) -> xr.Dataset:
    """Run one case under a bidirectional excitation (``excitation.components == 2``) with the
    spatial models (``dccss.mechanics.spatial``) and return its dataset
    (``results.spatial_dataset``). Parameters as ``simulate``; theta2_0 tilts the pad in the
    vertical plane of the excitation's ``azimuth``; only signed normals (the consistent ones)."""
    from .mechanics import spatial
    from .results import spatial_dataset

    if model not in spatial.STEPPERS:
        raise ValueError(f"model must be one of {spatial.SPATIAL_MODELS}, got {model!r}")
    if normals != "signed":
        raise ValueError(f"normals: the spatial model (bidirectional ground motion) uses signed normals only, got "
                         f"{normals!r} (unsigned normals reproduce the planar paper's computation)")
    _check_policies(capacity, on_failure)
    times = step_times(excitation, dt)
    failure = None
    try:
        history = spatial.run(model, geometry, excitation.displacement(times), theta2_0,
                              azimuth=float(excitation.azimuth), options=options, times=times,
                              stop_at_ring=capacity != "continue")
    except ConvergenceError as err:
        history = getattr(err, "history", None)
        gaps = None if history is None else (history["clearance_1"], history["clearance_3"])
        failure = _explain(err, geometry, gaps, times)
        if on_failure == "error" or history is None:
            raise failure from None
    steps = len(history["G"])
    if progress is not None:
        progress(steps - 1, len(times) - 1)
    ds = spatial_dataset(model, history, geometry, times[:steps], excitation, theta2_0=theta2_0, dt=dt,
                         tol=options.tol, attrs=attrs)
    return _settle(ds, geometry, capacity, failure, times, steps)


def _settle(ds, geometry, capacity, failure, times, n_steps):
    """The run's attributes: capacity policy, failure (time and message) and the ring reached (or
    CapacityError under capacity "error")."""
    ds.attrs["capacity_policy"] = capacity
    ds.attrs["failed"] = int(failure is not None)
    if failure is not None:
        ds.attrs.update(failure_time_s=float(times[n_steps]), failure_message=str(failure))
    reached = ring_reached(ds["clearance_1"].values, ds["clearance_3"].values, ds["t"].values)
    if reached:
        if capacity == "error":
            raise history_error(geometry, reached)
        ds.attrs.update(capacity_exceeded_at_s=reached["t"], capacity_exceeded_plate=reached["plate"],
                        capacity_exceeded_by_m=reached["by"])
        if capacity == "stop" and n_steps < len(times):
            ds.attrs["stopped_at_s"] = float(times[n_steps - 1])
    return ds
