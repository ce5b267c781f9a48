"""The retaining rings: when, where and by how much a history passes one, and what to do then.

A plate's ring is reached when the clearance between the pad and the ring (``kinematics.
corner_diagnostics``) becomes negative; the capacity of plate j is R^j sin(alpha^j - alpha^2j)
(Table 1's X_g,max). ``CAPACITY_POLICIES`` are what a run does then: continue (flag it), stop
(end the history there) or error.
"""

from __future__ import annotations

import numpy as np

from .newton import ConvergenceError

CAPACITY_POLICIES = ("continue", "stop", "error")
PLATES = ("RB1", "RB3")


class CapacityError(ValueError):
    """The pad reached a retaining ring (the excitation exceeds the device capacity)."""


class IncompatibleMotion(ConvergenceError):
    """No compatible configuration exists: RB1 is displaced from RB3 by the pendulum length L or more
    (the pad would have to turn past 90 degrees); no policy writes such a step as a result."""


def beyond_reach(geometry, Xg, theta2_0=0.0, azimuth=0.0, *, spatial=False):
    """The first step at which |R3 - X_g(t_n)| >= L, R3 the horizontal place of RB3 at the start
    (X_g(t_0) + L sin theta2_0 along ``azimuth``): no compatible configuration exists there. X_g is
    (T, ...) planar or (T, ..., 2) ``spatial``, the cases (if any) broadcast against the geometry's
    fields; returns -1 where every step is within reach (an int for one case)."""
    Xg = np.asarray(Xg, dtype=float)
    L, s = np.asarray(geometry.L, dtype=float), np.sin(np.asarray(theta2_0, dtype=float))
    if spatial:
        h = np.stack(np.broadcast_arrays(np.cos(azimuth), np.sin(azimuth)), axis=-1)
        distance = np.linalg.norm(Xg[0] + (L * s)[..., None] * h - Xg, axis=-1)
        out = np.where((distance >= L).any(axis=0), np.argmax(distance >= L, axis=0), -1)
        return int(out) if out.ndim == 0 else out
    # planar: the farthest the motion gets from RB3 first, without a (T, cases) temporary
    centre = Xg[0] + L * s
    far = np.maximum(centre - Xg.min(axis=0), Xg.max(axis=0) - centre) >= L
    out = np.full(np.shape(far), -1)
    for index in zip(*np.nonzero(far)) if np.ndim(far) else ([()] if far else []):
        column = Xg[(slice(None), *index)] if Xg.ndim > 1 else Xg
        c = np.broadcast_to(centre, np.shape(far))[index]
        out[index] = int(np.argmax(np.abs(c - column) >= np.broadcast_to(L, np.shape(far))[index]))
    return int(out) if out.ndim == 0 else out


def reach_message(geometry, Xg, n, t) -> str:
    """Why step n (at time t) has no compatible configuration, and what the device can take."""
    Xg = np.asarray(Xg, dtype=float)
    moved = float(np.linalg.norm(np.atleast_1d(Xg[n] - Xg[0])))
    return (f"at t = {float(t):.6g} s (step {n}) RB1 is displaced by {100 * moved:.4g} cm from its start, the "
            f"device's pendulum length L = |C1C3| = {100 * float(geometry.L):.4g} cm or more from RB3: no compatible "
            f"configuration exists (the pad would have to turn past 90 degrees). The motion is beyond what the "
            f"device's geometry can take, far past its retaining rings (plate capacities R1 sin(alpha1 - alpha21) = "
            f"{100 * float(geometry.capacity1):.4g} cm and R3 sin(alpha3 - alpha23) = "
            f"{100 * float(geometry.capacity3):.4g} cm): lower the excitation.")


def ring_reached(clearance_1, clearance_3, t, Xg=None) -> dict | None:
    """When, where and by how much a history passes a retaining ring (None if it does not).

    Returns {"t": first time a clearance is < 0 (s), "plate": "RB1" or "RB3" (the one passed
    first; the deeper one if both at once), "by": the largest distance beyond a ring over the
    history (m), "step": the index of that first time} and, given the imposed motion X_g (T,) or
    (T, 2), "displacement": how far RB1 had moved from its start then (m; the ground's, or the
    stroke of a structure).
    """
    gap = np.stack([clearance_1, clearance_3], axis=-1)
    beyond = (gap < 0).any(axis=-1)
    if not beyond.any():
        return None
    n = int(np.argmax(beyond))
    out = {"t": float(t[n]), "step": n, "plate": PLATES[int(np.argmin(gap[n]))], "by": float(-np.nanmin(gap))}
    if Xg is not None:
        Xg = np.asarray(Xg, dtype=float)
        out["displacement"] = float(np.linalg.norm(np.atleast_1d(Xg[n] - Xg[0])))
    return out


def capacity_message(geometry, reached, tense="reaches") -> str:
    """'the pad reaches the retaining ring of RB3 at t = ... s (step ..., RB1 moved by ... cm; the ring
    is where the pad has turned by alpha3 - alpha23, which compliant sliding reaches at
    L sin(alpha3 - alpha23) = ... cm; one surface's capacity R3 sin(alpha3 - alpha23) = ... cm) and
    passes it by up to ... mm' (``tense="reached"``: the same in the past).

    RB1's displacement from RB3 is what a ring limits: L sin(theta2) under compliant sliding, the pad on
    C^1C^3, whose corner touches the ring of plate j at theta2 = alpha^j - alpha^2j. Table 1's X_g,max,
    R^j sin(alpha^j - alpha^2j), is the same limit on one sliding surface (a single pendulum of radius R^j)."""
    j = reached["plate"][-1]
    turn = (geometry.alpha1 - geometry.alpha21) if j == "1" else (geometry.alpha3 - geometry.alpha23)
    surface = geometry.capacity1 if j == "1" else geometry.capacity3
    passes = "passes" if tense == "reaches" else "passed"
    moved = f", RB1 moved by {100 * reached['displacement']:.4g} cm" if "displacement" in reached else ""
    return (f"the pad {tense} the retaining ring of {reached['plate']} at t = {reached['t']:.6g} s "
            f"(step {reached['step']}{moved}; the ring is where the pad has turned by alpha{j} - alpha2{j}, which "
            f"compliant sliding reaches at L sin(alpha{j} - alpha2{j}) = {100 * geometry.L * np.sin(turn):.4g} cm; one "
            f"surface's capacity R{j} sin(alpha{j} - alpha2{j}) = {100 * surface:.4g} cm) "
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
    such a failure; otherwise a ring reached before the failure stays flagged, with its time. Adds
    ``failed``, ``failure_time`` and ``capacity_time``."""
    if capacity == "error":
        failure = np.where(np.isnan(failure) | (reached < failure), reached, failure)
    failed = ~np.isnan(failure)
    out = {k: np.where(failed, np.nan, v) if np.issubdtype(np.asarray(v).dtype, np.floating) else v
           for k, v in summaries.items()}
    before = reached < failure  # a ring the pad reached before the solver failed is kept, as a history keeps it
    out["capacity_exceeded"] = np.where(failed & (capacity != "error"), before, out["capacity_exceeded"])
    return out | {"failed": failed, "failure_time": failure,
                  "capacity_time": np.where(failed & (capacity != "error") & ~before, np.nan, reached)}
