"""The one driver of runs: a history or a sweep, planar or spatial, on the backend that fits, with the
run policies applied as events.

The ground motion says which models run: X_g of shape (T,) for one case or (T, n) for a sweep moves
RB1 along a line (the planar models, ``models``; compiled where ``backend`` says), (T, 2) or
(T, n, 2) moves it in the plane (the spatial models, ``spatial``, compiled). The policies are
applied here:

* ``capacity``: "continue" flags the first step beyond a retaining ring (``Run.reached``); "stop"
  ends the run there, a terminal event as scipy's ``solve_ivp`` treats them (a later solver failure
  is then not one); "error" raises ``capacity.history_error`` (a sweep: ``capacity.case_error``), or
  with on_failure "mark" ends the run there as failed, as a sweep marks the case.
* ``on_failure``: "error" raises the solver's ConvergenceError, explained by the ring the pad passed
  before it if it did (beyond the ring the model describes no real device and a smaller dt does not
  help); "mark" keeps what converged and says where it failed.
* A step with no compatible configuration (RB1 displaced from RB3 by the pendulum length L or more,
  ``capacity.beyond_reach``) is a failure whatever ``capacity`` says: ``capacity.IncompatibleMotion``
  (a ConvergenceError), raised or marked as ``on_failure`` says; the run ends before it.

``history`` returns a ``Run``: the history up to where it ended, with its status and message, the
ring it reached and the failure; ``summaries`` the per-case summaries of a sweep
(``summaries.specs``), failures and rings marked per case.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from . import backend, registry, spatial
from .capacity import (
    CAPACITY_POLICIES,
    CapacityError,
    IncompatibleMotion,
    beyond_reach,
    capacity_message,
    case_error,
    history_error,
    mark_failures,
    reach_message,
    ring_reached,
)
from .geometry import Geometry
from .kinematics import NORMALS, corner_diagnostics
from .newton import FAILURE_POLICIES, ConvergenceError, NewtonOptions
from .summaries import summarize

MOTIONS = ("planar", "spatial")


@dataclass(frozen=True)
class Run:
    """A history and how it ended.

    history : the arrays of the stored steps, time first (``models.run``, ``spatial.run``).
    motion : "planar" or "spatial".
    status : "completed", "stopped" (at a ring, capacity "stop") or "failed" (on_failure "mark").
    message : what ended it early ("" when completed).
    reached : when, where and by how much the pad passed a ring (``capacity.ring_reached``), or None.
    failure : what ended it as failed under on_failure "mark": the solver's ConvergenceError, or the
        CapacityError of a ring reached under capacity "error"; None otherwise.
    """

    history: dict
    motion: str
    status: str
    message: str
    reached: dict | None
    failure: ConvergenceError | CapacityError | None

    @property
    def steps(self) -> int:
        """The number of steps stored (t_0 included)."""
        return len(self.history["q" if self.motion == "planar" else "G"])


def check_policies(capacity, on_failure):
    """A ValueError names a policy that is not one."""
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    if on_failure not in FAILURE_POLICIES:
        raise ValueError(f"on_failure must be one of {FAILURE_POLICIES}, got {on_failure!r}")


def check_start(theta2_0):
    """A ValueError names a start angle (rad, or a batch of them) that is not finite or not within
    (-pi/2, pi/2): no compatible configuration has the pad turned by 90 degrees or more."""
    theta = np.asarray(theta2_0, dtype=float)
    bad = ~(np.abs(theta) < np.pi / 2)
    if bad.any():
        value = float(theta[bad].flat[0])
        raise ValueError(f"theta2_0 must be a finite angle with |theta2_0| < pi/2 rad (90 degrees), got {value!r} rad")


def check_motion(Xg, times=None):
    """A ValueError names the first sample of X_g (m) that is not finite: no run starts on it."""
    bad = ~np.isfinite(Xg)
    if bad.any():
        n = int(np.argwhere(bad)[0][0])
        when = f" (t = {float(times[n]):.6g} s)" if times is not None else ""
        raise ValueError(f"Xg must be finite: step {n}{when} is {float(np.asarray(Xg)[bad].flat[0])!r}")


def motion_of(Xg) -> str:
    """"planar" for one case's X_g of shape (T,), "spatial" for (T, 2)."""
    if np.ndim(Xg) == 1:
        return "planar"
    if np.ndim(Xg) == 2 and np.shape(Xg)[-1] == 2:
        return "spatial"
    raise ValueError(f"Xg must have shape (T,) or (T, 2), got {np.shape(Xg)}")


def clearances(history, geometry, motion):
    """The clearances to the rings of RB1 and RB3 (m, negative beyond a ring) of every stored step."""
    if motion == "spatial":
        return history["clearance_1"], history["clearance_3"]
    gap = corner_diagnostics(history["q"], geometry)[1]
    return gap[..., 0], gap[..., 1]


def history(model, geometry, Xg, theta2_0=0.0, *, azimuth=0.0, normals="signed", options=NewtonOptions(),
            capacity="continue", on_failure="error", times=None, progress=None) -> Run:
    """One case: ``model`` under X_g (m; (T,) planar, (T, 2) spatial), from the compatible start at
    theta2_0 (rad; in the vertical plane of ``azimuth`` (rad) in space), with the run policies
    (module docstring). ``times`` (s) are quoted in errors and events; ``progress(n, N)`` is called
    after each step (once, at the end, on the kernels)."""
    registry.model(model)  # a ValueError names the known models
    check_policies(capacity, on_failure)
    if not isinstance(options, NewtonOptions):
        raise TypeError(f"options must be a NewtonOptions, got {type(options).__name__} {options!r}")
    options = replace(options, on_failure="error")  # a sweep's policy: a history applies its own, on_failure
    check_start(theta2_0)
    if np.ndim(geometry.L) != 0:
        raise ValueError("a history runs one case: geometry fields must be scalars")
    Xg = np.asarray(Xg, dtype=float)
    motion = motion_of(Xg)
    if motion == "spatial":
        registry.model(model, spatial.in_space, " in space")
    if motion == "spatial" and normals != "signed":
        raise ValueError(f"normals: the spatial model (bidirectional ground motion) uses signed normals only, got "
                         f"{normals!r} (unsigned normals reproduce the planar paper's computation)")
    if normals not in NORMALS:
        raise ValueError(f"normals must be one of {NORMALS}, got {normals!r}")
    check_motion(Xg, times)
    times = np.arange(len(Xg), dtype=float) if times is None else np.asarray(times, dtype=float)
    stop = capacity != "continue"
    failure = None
    # a step with no compatible configuration ends the run, whatever the policies: nothing past it is a result
    limit = beyond_reach(geometry, Xg, theta2_0, azimuth, spatial=motion == "spatial")
    if 0 <= limit < 2:
        raise IncompatibleMotion(reach_message(geometry, Xg, limit, times[limit]))
    steps = len(Xg) if limit < 0 else limit
    try:
        if motion == "spatial":
            out = spatial.run(model, geometry, Xg[:steps], theta2_0, azimuth=azimuth, options=options,
                              times=times[:steps], stop_at_ring=stop)
        else:
            out = _planar(model, geometry, Xg[:steps], theta2_0, normals, options, times[:steps], stop, progress)
    except ConvergenceError as err:
        out = getattr(err, "history", None)
        failure = _explain(err, geometry, out, motion, times, Xg)
        if on_failure == "error" or out is None:
            raise failure from None
    run = Run(out, motion, "completed", "", None, failure)
    if motion == "spatial" and progress is not None:
        progress(run.steps - 1, len(Xg) - 1)
    reached = ring_reached(*clearances(out, geometry, motion), times[:run.steps], Xg[:run.steps])
    if reached and capacity == "error":
        if on_failure == "error":
            raise history_error(geometry, reached)
        failure = history_error(geometry, reached)  # marked: the history ends at the ring, as a sweep's case
        return Run(out, motion, "failed", str(failure), reached, failure)
    if failure is None and run.steps == limit:
        failure = IncompatibleMotion(reach_message(geometry, Xg, limit, times[limit]))
        if on_failure == "error":
            raise failure
    if failure is not None:
        status, message = "failed", str(failure)
    elif reached and capacity == "stop" and run.steps < len(Xg):
        status, message = "stopped", capacity_message(geometry, reached, "reached") + ": the run stopped there"
    else:
        status, message = "completed", ""
    return Run(out, motion, status, message, reached, failure)


def _planar(model, geometry, Xg, theta2_0, normals, options, times, stop_at_ring, progress):
    """The planar history (``models.run``); with ``stop_at_ring`` it ends at the first step where the
    pad has passed a retaining ring. A ConvergenceError carries the history up to the last
    converged step as ``err.history``. The kernels run it, compiled or interpreted (``backend``);
    ``progress`` is called once, at the end."""
    kernels, compiled = backend.kernels(model, len(Xg) - 1)
    out = None
    try:
        out = kernels.run(model, geometry, Xg, theta2_0, normals=normals, options=options, times=times,
                          stop_at_ring=stop_at_ring, compiled=compiled)
    except ConvergenceError as err:
        out = getattr(err, "history", None)
        raise
    finally:
        if progress is not None and out is not None:
            progress(len(out["q"]) - 1, len(Xg) - 1)
    return out


def oscillation(x, window=8, last=3) -> float:
    """How many times per step a step-to-step oscillation of ``x`` (a history, time first) grows over its
    ``last`` steps: the second differences less their level over the ``window`` steps before alternate in
    sign and grow, to more than ten times that window's spread. 0 where they do not (a smooth history)."""
    d2 = np.diff(np.asarray(x, dtype=float), 2, axis=0)
    if len(d2) < window + last:
        return 0.0
    before, tail = d2[-window - last:-last], d2[-last:]
    r = tail - np.median(before, axis=0)
    spread = np.median(np.abs(before - np.median(before, axis=0)), axis=0)
    alternating = np.all(np.sign(r[1:]) == -np.sign(r[:-1]), axis=0)
    growing = alternating & np.all(np.abs(r[1:]) > np.abs(r[:-1]), axis=0) & (np.abs(r[-1]) > 10 * spread)
    if not growing.any():
        return 0.0
    return float(np.max(np.abs(r[-1][growing] / r[-2][growing])))


def _explain(err, geometry, out, motion, times, Xg):
    """A solver failure, prefixed with the ring the pad passed before it (if it did), or explained by the
    steps before it oscillating with a growing amplitude (where a smaller dt does not help either)."""
    if out is None:
        return err
    gaps = clearances(out, geometry, motion)
    reached = ring_reached(gaps[0], gaps[1], times[:len(gaps[0])], Xg[:len(gaps[0])])
    if reached is None:
        growth = oscillation(out["q"][:, 3:5] if motion == "planar" else out["G"][:, :2])
        if growth:
            return err.with_hint(
                f"The steps before it oscillate from step to step, growing about {growth:.2g} times a step (the pad "
                "centre's second differences alternate in sign): the model's steps have lost their stability at "
                "this rotation of this device, and a smaller dt fails earlier, not later. Lower the excitation, or "
                "use a model that is stable there (docs: Failures, capacity and exit codes).")
        return err
    return err.with_hint(
        "Beyond the ring the model describes no real device and a smaller dt does not help: set capacity: "
        "stop to end the history at the ring, or lower the excitation.",
        prefix=f"Before the solver failed, {capacity_message(geometry, reached, 'reached')}.")


def summaries(model, geometry, Xg, theta2_0=0.0, *, azimuth=0.0, normals="signed", options=NewtonOptions(),
              capacity="continue", times=None, progress=None) -> dict:
    """Per-case summaries of a sweep (``summaries.specs``): X_g (T, n) planar (or (T, ...) with
    the cases broadcast) or (T, n, 2) spatial; geometry fields, theta2_0 and (in space) ``azimuth``
    broadcast over the cases. Policies as for ``history``, per case (``options.on_failure``: "error"
    raises the first failure, naming its case as the error's ``index``; "mark" marks it and goes on).
    ``progress(n, N)`` is called after the cases' steps."""
    check_start(theta2_0)
    Xg = np.asarray(Xg, dtype=float)
    check_motion(Xg, times)
    if Xg.ndim == 3:
        return _spatial_summaries(model, geometry, Xg, theta2_0, azimuth, options, capacity, times, progress)
    now = np.arange(len(Xg), dtype=float) if times is None else np.asarray(times, dtype=float)
    limit = beyond_reach(geometry, Xg, theta2_0)
    if options.on_failure == "error" and capacity == "continue" and (limit >= 0).any():
        raise _unreachable(geometry, Xg, limit, now)
    out = summarize(model, geometry, Xg, theta2_0, normals=normals, options=options, times=times,
                    capacity=capacity, progress=progress)
    return _past_reach(out, geometry, Xg, limit, now, capacity, options.on_failure)


def _unreachable(geometry, Xg, limit, now, cases=None) -> IncompatibleMotion:
    """The error of the first case of a batch (of ``cases``, a mask) that goes beyond reach, naming its index."""
    limit = np.asarray(limit)
    index = tuple(int(i) for i in np.argwhere(limit >= 0 if cases is None else cases)[0])
    one = Geometry(**{f.name: float(np.broadcast_to(getattr(geometry, f.name), limit.shape)[index])
                      for f in fields(geometry)})
    n = int(limit[index])
    err = IncompatibleMotion(f"in the case at batch index {index}: "
                             + reach_message(one, np.broadcast_to(Xg, (len(Xg),) + limit.shape)[(slice(None), *index)],
                                             n, now[n]))
    err.index = index
    return err


def _past_reach(out, geometry, Xg, limit, now, capacity, on_failure) -> dict:
    """Summaries with the cases that go beyond reach marked failed there (unless a ring stopped them first)."""
    beyond = np.broadcast_to(limit >= 0, np.shape(out["failed"]))
    if not beyond.any():
        return out
    when = np.where(beyond, now[np.maximum(limit, 0)], np.nan)
    stopped = (capacity != "continue") & (out["capacity_time"] <= when)
    later = beyond & ~stopped & ~(out["failure_time"] < when)
    if not later.any():
        return out
    if on_failure == "error":
        raise _unreachable(geometry, Xg, np.broadcast_to(limit, beyond.shape), now, later)
    out = {k: np.where(later, np.nan, v) if np.issubdtype(np.asarray(v).dtype, np.floating) else v
           for k, v in out.items()}
    out["failed"] = out["failed"] | later
    out["failure_time"] = np.where(later, when, out["failure_time"])
    out["capacity_time"] = np.where(later, np.nan, out["capacity_time"])
    out["capacity_exceeded"] = np.where(later, False, out["capacity_exceeded"])
    return out


def _spatial_summaries(model, geometry, Xg, theta2_0, azimuth, options, capacity, times, progress):
    """The spatial models case after case, each a ``history`` reduced by ``spatial.summary``."""

    check_policies(capacity, options.on_failure)
    T, n = Xg.shape[:2]
    now = np.arange(T, dtype=float) if times is None else np.asarray(times, dtype=float)
    theta2_0 = np.broadcast_to(np.asarray(theta2_0, dtype=float), (n,))
    azimuth = np.broadcast_to(np.asarray(azimuth, dtype=float), (n,))
    mark = options.on_failure == "mark"
    rows, failure, reached = [], np.full(n, np.nan), np.full(n, np.nan)
    for k in range(n):
        g = case_geometry(geometry, k, n)
        try:  # capacity "error" stops the case at the ring: the sweep's own error names the case
            run = history(model, g, Xg[:, k], float(theta2_0[k]), azimuth=float(azimuth[k]), options=options,
                          capacity="continue" if capacity == "continue" else "stop", on_failure=options.on_failure,
                          times=now)
        except ConvergenceError as err:
            err.index = (k,)
            raise
        if run.reached:
            reached[k] = run.reached["t"]
            if capacity == "error" and not mark:
                raise case_error(reached[k], (k,))
        if run.failure is not None:
            failure[k] = now[run.steps]
        rows.append(spatial.summary(run.history, g))
    if progress is not None:  # once, when every case is done (as the planar kernels)
        progress(T - 1, T - 1)
    out = {key: np.array([row[key] for row in rows]) for key in rows[0]} if rows else {}
    out["capacity_exceeded"] = ~np.isnan(reached)
    return mark_failures(out, failure, reached, capacity)


def case_geometry(geometry, k, n) -> Geometry:
    """Case k of a batch of n devices (fields broadcast to (n,)) as a one-case Geometry."""
    return Geometry(**{f.name: float(np.broadcast_to(getattr(geometry, f.name), (n,))[k]) for f in fields(geometry)})
