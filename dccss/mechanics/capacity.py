"""The retaining rings: when, where and by how much a history passes one, and what to do then.

A plate's ring is reached when the clearance between the pad and the ring (``kinematics.
corner_diagnostics``) becomes negative; the capacity of plate j is R^j sin(alpha^j - alpha^2j)
(Table 1's X_g,max). ``CAPACITY_POLICIES`` are what a run does then: continue (flag it), stop
(end the history there) or error.
"""

from __future__ import annotations

import numpy as np

CAPACITY_POLICIES = ("continue", "stop", "error")
PLATES = ("RB1", "RB3")


class CapacityError(ValueError):
    """The pad reached a retaining ring (the excitation exceeds the device capacity)."""


def ring_reached(clearance_1, clearance_3, t) -> dict | None:
    """When, where and by how much a history passes a retaining ring (None if it does not).

    Returns {"t": first time a clearance is < 0 (s), "plate": "RB1" or "RB3" (the one passed
    first; the deeper one if both at once), "by": the largest distance beyond a ring over the
    history (m), "step": the index of that first time}.
    """
    gap = np.stack([clearance_1, clearance_3], axis=-1)
    beyond = (gap < 0).any(axis=-1)
    if not beyond.any():
        return None
    n = int(np.argmax(beyond))
    return {"t": float(t[n]), "step": n, "plate": PLATES[int(np.argmin(gap[n]))],
            "by": float(-np.nanmin(gap))}


def capacity_message(geometry, reached, tense="reaches") -> str:
    """'the pad reaches the retaining ring of RB3 at t = ... s (capacity R3 sin(alpha3 - alpha23)
    = ... cm) and passes it by up to ... mm' (``tense="reached"``: the same in the past)."""
    j = reached["plate"][-1]
    capacity = geometry.capacity1 if j == "1" else geometry.capacity3
    passes = "passes" if tense == "reaches" else "passed"
    return (f"the pad {tense} the retaining ring of {reached['plate']} at t = {reached['t']:.6g} s "
            f"(step {reached['step']}; capacity R{j} sin(alpha{j} - alpha2{j}) = {100 * capacity:.4g} cm) "
            f"and {passes} it by up to {1e3 * reached['by']:.3g} mm")


def case_error(t, index) -> CapacityError:
    """The error of a sweep case that reaches a ring under capacity "error" (without on_failure "mark"):
    when, and which case (``index`` in the batch, also the error's ``index``)."""
    err = CapacityError(f"the pad reaches a retaining ring at t = {float(t):.6g} s in the case at batch index "
                        f"{index} (capacity: error)")
    err.index = index
    return err


def history_error(geometry, reached) -> CapacityError:
    """The error of a history that reaches a ring under capacity "error": when, where, by how much
    (``ring_reached``) and what to do."""
    return CapacityError(capacity_message(geometry, reached) + ": the excitation exceeds the device capacity; "
                         "lower it, or set capacity: continue (flag it) or stop (end the history there)")


def mark_failures(summaries, failure, reached, capacity) -> dict:
    """Per-case summaries with their failures marked: the cases that failed (``failure``: the time,
    NaN if none) have NaN summaries; under ``capacity="error"`` reaching a ring (``reached``) is
    such a failure. Adds ``failed``, ``failure_time`` and ``capacity_time``."""
    if capacity == "error":
        failure = np.where(np.isnan(failure) | (reached < failure), reached, failure)
    failed = ~np.isnan(failure)
    out = {k: np.where(failed, np.nan, v) if np.issubdtype(np.asarray(v).dtype, np.floating) else v
           for k, v in summaries.items()}
    out["capacity_exceeded"] = np.where(failed & (capacity != "error"), False, out["capacity_exceeded"])
    return out | {"failed": failed, "failure_time": failure,
                  "capacity_time": np.where(failed & (capacity != "error"), np.nan, reached)}
