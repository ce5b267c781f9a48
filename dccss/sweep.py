"""Batched runs reduced to per-case summaries on the fly (no time histories kept).

A sweep solves many cases at once (``dccss.models`` steppers on batch arrays) and keeps, per
case, the quantities a design study asks for: the largest pad rotation, the largest sticking
rotation, the largest rise of RB3, the residual rise and rotation at the end, the largest
interpenetration at each corner, whether the pad reached a retaining ring, and the Newton
iterations. Memory is O(cases), whatever the number of steps.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

from . import models
from .geometry import Geometry
from .kinematics import CORNERS, corner_diagnostics

#: summary variable -> (units, long_name); "stick" entries exist for stick-slip only
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
    "sticking_rotation_max": ("degree", "largest pad rotation within a sticking phase, |theta2_stick - theta2(t_n-1)|"),
    "rise_stick_max": ("m", "largest rise of RB3 at the end of a sticking phase"),
    "failed": ("1", "the solver failed for this case (its summaries are NaN)"),
    "failure_time": ("s", "time of the step at which the solver failed (NaN if it did not)"),
}
STICK_ONLY = ("sticking_rotation_max", "rise_stick_max")


#: how each per-step value is reduced over the steps (fmax/fmin skip the NaN of step 0)
_REDUCE = {"theta2_max_abs": np.fmax, "rise_max": np.fmax, "I_max": np.fmax, "clearance_min": np.fmin,
           "newton_iterations_max": np.maximum, "iterations": np.add, "sticking_rotation_max": np.fmax,
           "rise_stick_max": np.fmax}


def summarize(model, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Run ``model`` on the batch (X_g of shape (T, ...)) and return the summaries (...).

    With ``options=NewtonOptions(on_failure="mark")`` a case the solver fails on is reported
    (``failed``, ``failure_time``, NaN summaries) while the others complete."""
    Xg = np.asarray(Xg, dtype=float)
    shape = np.broadcast_shapes(np.shape(geometry.L), Xg.shape[1:], np.shape(theta2_0))
    if shape and np.prod(shape) == 1:  # a batch of one: the one-case path, reshaped back
        one = Geometry(**{f.name: float(np.ravel(getattr(geometry, f.name))[0]) for f in fields(geometry)})
        out = summarize(model, one, Xg.reshape(Xg.shape[0]), float(np.ravel(theta2_0)[0]), **kw)
        return {k: np.reshape(v, shape) for k, v in out.items()}
    with np.errstate(invalid="ignore", divide="ignore"):  # failed cases are NaN by design
        return _summarize(model, geometry, Xg, theta2_0, shape, **kw)


def _summarize(model, geometry, Xg, theta2_0, shape, **kw):
    rest = geometry.Ry3_compatible(0.0)
    times = kw.get("times")
    acc, previous, failure, reached = None, None, np.full(shape, np.nan), np.full(shape, np.nan)
    for step in models.steps(model, geometry, Xg, theta2_0, **kw):
        q = step["q"]
        now = times[step["n"]] if times is not None else step["n"]
        failure = np.where(np.isnan(failure) & np.isnan(q).any(axis=-1), now, failure)
        theta2, rise = np.degrees(q[..., 5]), q[..., 7] - rest
        interp, gap = corner_diagnostics(q, geometry, step.get("local"))
        reached = np.where(np.isnan(reached) & (gap.min(axis=-1) < 0), now, reached)
        its = np.asarray(step["newton_iterations"]) + np.asarray(step.get("newton_iterations_stick", 0))
        current = {"theta2_max_abs": np.abs(theta2), "rise_max": rise, "I_max": interp,
                   "clearance_min": gap.min(axis=-1), "newton_iterations_max": its, "iterations": its}
        if model == "stick_slip":
            qs = step["q_stick"]
            turn = np.abs(np.degrees(qs[..., 5]) - previous) if previous is not None else np.nan * theta2
            current.update(sticking_rotation_max=turn, rise_stick_max=qs[..., 7] - rest)
        acc = current if acc is None else {k: _REDUCE[k](acc[k], v) for k, v in current.items()}
        previous = theta2
    out = {"theta2_max_abs": acc["theta2_max_abs"], "theta2_end": theta2, "rise_max": acc["rise_max"],
           "rise_end": rise, "clearance_min": acc["clearance_min"],
           "capacity_exceeded": acc["clearance_min"] < 0,
           "newton_iterations_max": np.asarray(acc["newton_iterations_max"], dtype=np.int32),
           "newton_iterations_mean": np.asarray(acc["iterations"]) / max(step["n"], 1)}
    for i, c in enumerate(CORNERS):
        out[f"I_{c}_max"] = acc["I_max"][..., i]
    if model == "stick_slip":
        out.update(sticking_rotation_max=acc["sticking_rotation_max"], rise_stick_max=acc["rise_stick_max"])
    failed = ~np.isnan(failure)
    out = {k: np.where(failed, np.nan, v) if np.issubdtype(np.asarray(v).dtype, np.floating) else v
           for k, v in out.items()}
    out["capacity_exceeded"] = np.where(failed, False, out["capacity_exceeded"])
    return out | {"failed": failed, "failure_time": failure, "capacity_time": np.where(failed, np.nan, reached)}
