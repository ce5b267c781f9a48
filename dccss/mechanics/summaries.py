"""Batched runs reduced to per-case summaries on the fly (no time histories kept).

A sweep solves many cases at once (``dccss.mechanics.models`` steppers on batch arrays) and keeps, per
case, the quantities a design study asks for: the largest pad rotation, the largest sticking
rotation, the largest rise of RB3, the residual rise and rotation at the end, the largest
interpenetration at each corner, whether the pad reached a retaining ring, and the Newton
iterations. Memory is O(cases), whatever the number of steps.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

from . import backend, models
from .capacity import CAPACITY_POLICIES, case_error, mark_failures
from .geometry import Geometry
from .kinematics import CORNERS, corner_diagnostics
from .newton import NewtonOptions

#: summary variable -> (units, long_name): those of every model, then each model's own
SUMMARIES = {
    "theta2_max_abs": ("degree", "largest |theta2| at the end of a step"),
    "theta2_end": ("degree", "residual pad rotation theta2(t_end)"),
    "rise_max": ("m", "largest rise of RB3 above its theta2 = 0 rest position, at the end of a step"),
    "rise_end": ("m", "residual rise of RB3 at t_end"),
    **{f"I_{c}_max": ("m", f"largest interpenetration at corner {c}2 (positive into the plate)") for c in CORNERS},
    "clearance_min": ("m", "smallest clearance between the pad and a retaining ring"),
    "capacity_exceeded": ("1", "pad beyond a retaining ring at some step"),
    "capacity_time": ("s", "time at which the pad first reaches a retaining ring (NaN if it does not)"),
    "newton_iterations_max": ("1", "most Newton-Raphson iterations in a step"),
    "newton_iterations_mean": ("1", "mean Newton-Raphson iterations per step"),
    "failed": ("1", "the solver failed for this case (its summaries are NaN)"),
    "failure_time": ("s", "time of the step at which the solver failed (NaN if it did not)"),
    **{name: spec for entry in models.REGISTRY.values() for name, spec in entry.summaries.items()},
}
#: the rotation summaries under bidirectional motion, where |theta2| is the pad axis's tilt (``spatial.summary``)
TILT_SUMMARIES = {
    "theta2_max_abs": ("degree", "largest tilt of the pad axis from the vertical, at the end of a step"),
    "theta2_end": ("degree", "residual tilt of the pad axis at t_end"),
}
#: summaries that only some models have (NaN for the others in a combined study)
MODEL_SPECIFIC = tuple(name for entry in models.REGISTRY.values() for name in entry.summaries)


#: how each per-step value is reduced over the steps (fmax/fmin skip the NaN of step 0; a model's
#: own summaries are maxima); others keep their last value
_REDUCE = {"theta2_max_abs": np.fmax, "rise_max": np.fmax, "I_max": np.fmax, "clearance_min": np.fmin,
           "newton_iterations_max": np.maximum, "iterations": np.add,
           **{name: np.fmax for name in MODEL_SPECIFIC}}


def _last(old, new):
    return new


def summarize(model, geometry, Xg, theta2_0=0.0, *, capacity="continue", progress=None, **kw) -> dict:
    """Run ``model`` on the batch (X_g of shape (T, ...)) and return the summaries (...).

    With ``options=NewtonOptions(on_failure="mark")`` a case the solver fails on is reported
    (``failed``, ``failure_time``, NaN summaries) while the others complete.

    ``capacity`` is the policy of ``simulation.simulate`` applied per case: "continue" (flag
    the ring and go on), "stop" (the case's summaries are those of its history up to the step
    that reaches a ring: a later solver failure of that case is not one) or "error" (a case
    that reaches a ring is marked failed at that time with ``on_failure="mark"``; otherwise a
    CapacityError names its batch index). ``progress(n, N)`` is called after each step (once, at
    the end, when the kernels run it: ``dccss.mechanics.backend``)."""
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    Xg = np.asarray(Xg, dtype=float)
    found = backend.kernels(model, *backend.size(geometry, Xg, theta2_0))
    if found is not None:  # the kernels, compiled or interpreted (``backend``)
        kernels, compiled = found
        return kernels.summarize(model, geometry, Xg, theta2_0, capacity=capacity, progress=progress,
                                 compiled=compiled, **kw)
    shape = np.broadcast_shapes(np.shape(geometry.L), Xg.shape[1:], np.shape(theta2_0))
    if shape and np.prod(shape) == 1:  # a batch of one: the one-case path, reshaped back
        one = Geometry(**{f.name: float(np.ravel(getattr(geometry, f.name))[0]) for f in fields(geometry)})
        out = summarize(model, one, Xg.reshape(Xg.shape[0]), float(np.ravel(theta2_0)[0]), capacity=capacity,
                        progress=progress, **kw)
        return {k: np.reshape(v, shape) for k, v in out.items()}
    with np.errstate(invalid="ignore", divide="ignore"):  # failed cases are NaN by design
        return _summarize(model, geometry, Xg, theta2_0, shape, capacity, progress, **kw)


def _keep(mask, old, new):
    """``new`` where ``mask`` is False, ``old`` where it is True (mask broadcast over trailing axes)."""
    mask = np.reshape(mask, np.shape(mask) + (1,) * (np.ndim(new) - np.ndim(mask)))
    return np.where(mask, old, new)


def _summarize(model, geometry, Xg, theta2_0, shape, capacity, progress, **kw):
    entry = models.model(model)
    rest = geometry.Ry3_compatible(0.0)
    times = kw.get("times")
    mark = kw.get("options", NewtonOptions()).on_failure == "mark"
    acc, previous = None, None
    failure, reached = np.full(shape, np.nan), np.full(shape, np.nan)
    stopped = np.zeros(shape, dtype=bool)  # cases whose history ended at a ring (capacity stop/error)
    for step in entry.steps(geometry, Xg, theta2_0, **kw):
        q, n = step.q, step.n
        now = times[n] if times is not None else n
        failure = np.where(np.isnan(failure) & ~stopped & np.isnan(q).any(axis=-1), now, failure)
        theta2, rise = np.degrees(q[..., 5]), q[..., 7] - rest
        interp, gap = corner_diagnostics(q, geometry, getattr(step, "local", None))
        its = sum(np.asarray(getattr(step, name)) for name in entry.iteration_fields)
        current = {"theta2_max_abs": np.abs(theta2), "rise_max": rise, "I_max": interp,
                   "clearance_min": gap.min(axis=-1), "newton_iterations_max": its, "iterations": its,
                   "theta2_end": theta2, "rise_end": rise, "steps": np.full(shape, n)}
        if entry.summary is not None:
            current.update(entry.summary(step, previous, lambda q: q[..., 7] - rest))
        previous = theta2
        if acc is None:
            acc = current
        else:
            acc = {k: _keep(stopped, acc[k], _REDUCE.get(k, _last)(acc[k], v)) for k, v in current.items()}
        first = np.isnan(reached) & ~stopped & (gap.min(axis=-1) < 0)
        if capacity == "error" and first.any() and not mark:
            index = tuple(int(i) for i in np.argwhere(np.broadcast_to(first, shape))[0]) if shape else ()
            raise case_error(now, index)
        reached = np.where(first, now, reached)
        if capacity != "continue":
            stopped = stopped | ~np.isnan(reached)
        if progress is not None:
            progress(n, Xg.shape[0] - 1)
    out = {"theta2_max_abs": acc["theta2_max_abs"], "theta2_end": acc["theta2_end"], "rise_max": acc["rise_max"],
           "rise_end": acc["rise_end"], "clearance_min": acc["clearance_min"],
           "capacity_exceeded": ~np.isnan(reached),
           "newton_iterations_max": np.asarray(acc["newton_iterations_max"], dtype=np.int32),
           "newton_iterations_mean": np.asarray(acc["iterations"]) / np.maximum(acc["steps"], 1)}
    for i, c in enumerate(CORNERS):
        out[f"I_{c}_max"] = acc["I_max"][..., i]
    out.update({name: acc[name] for name in entry.summaries})
    return mark_failures(out, failure, reached, capacity)
