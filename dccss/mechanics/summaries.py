"""Batched runs reduced to per-case summaries on the fly (no time histories kept).

A sweep solves many cases at once (the models' kernels, ``dccss.mechanics.compiled``) and keeps, per
case, the quantities a design study asks for: the largest pad rotation, the largest sticking
rotation, the largest rise of RB3, the residual rise and rotation at the end, the largest
interpenetration at each corner, whether the pad reached a retaining ring, and the Newton
iterations. Memory is O(cases), whatever the number of steps.
"""

from __future__ import annotations

import numpy as np

from . import backend, registry
from .capacity import CAPACITY_POLICIES
from .kinematics import CORNERS
from .spatial import RIM_POINTS

#: summary variable -> (units, long_name) of every model (a model's own: its registry entry's; all: ``specs``)
COMMON = {
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
    "failed": ("1", "the solver failed for this case (its pad's summaries are NaN)"),
    "failure_time": ("s", "time of the step at which the solver failed (NaN if it did not)"),
}
#: the summaries that mean something else under bidirectional motion (``spatial.summary``): |theta2| is the
#: pad axis's tilt, and the corners are the rim points of each step's section (A, B, C, D for a step along +x)
TILT_SUMMARIES = {
    "theta2_max_abs": ("degree", "largest tilt of the pad axis from the vertical, at the end of a step"),
    "theta2_end": ("degree", "residual tilt of the pad axis at t_end"),
    **{f"I_{c}_max": ("m", f"largest interpenetration at the {name.replace('_', ' ')} rim point of a step's section "
                           f"(corner {c}2 of a step along +x; positive into the plate)")
       for c, name in zip(CORNERS, RIM_POINTS)},
}


def specs() -> dict:
    """Every summary variable -> (units, long_name): those of every model, then each registered model's
    own (read when called, so that a model registered later counts)."""
    return {**COMMON, **{name: spec for entry in registry.REGISTRY.values() for name, spec in entry.summaries.items()}}


def model_specific() -> tuple:
    """The summaries only some registered models have (NaN for the others in a combined study)."""
    return tuple(name for entry in registry.REGISTRY.values() for name in entry.summaries)


def summarize(model, geometry, Xg, theta2_0=0.0, *, capacity="continue", progress=None, **kw) -> dict:
    """Run ``model`` on the batch (X_g of shape (T, ...)) and return the summaries (...).

    With ``options=NewtonOptions(on_failure="mark")`` a case the solver fails on is reported
    (``failed``, ``failure_time``, NaN summaries) while the others complete.

    ``capacity`` is the policy of ``simulation.simulate`` applied per case: "continue" (flag
    the ring and go on), "stop" (the case's summaries are those of its history up to the step
    that reaches a ring: a later solver failure of that case is not one) or "error" (a case
    that reaches a ring is marked failed at that time with ``on_failure="mark"``; otherwise a
    CapacityError names its batch index). ``progress(n, N)`` is called once, when all N steps are
    done."""
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    Xg = np.asarray(Xg, dtype=float)
    kernels, compiled = backend.kernels(model, *backend.size(geometry, Xg, theta2_0))  # ``backend``
    return kernels.summarize(model, geometry, Xg, theta2_0, capacity=capacity, progress=progress,
                             compiled=compiled, **kw)
