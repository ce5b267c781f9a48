"""Newton-Raphson (Eqs. 13-15): its options, its errors and their messages.

The prescribed unit rows of a constraint set are linear, so one Newton step solves them exactly;
the kernels (``compiled.newton``) apply it first and then iterate C_q[contact, free] dq = -g on the
contact rows. This is block elimination of Eq. 13, not a different method: the iterates are
Newton's. A failure is raised here, named by its constraint set (``Rows``: the phase, the free
coordinates and the row labels).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from .kinematics import Q_NAMES
from .linear import det


class ConvergenceError(RuntimeError):
    """Newton-Raphson did not reach the tolerance within the iteration cap.

    ``detail`` says where and how it failed; ``hint`` what is likely to help. A caller that knows
    more (e.g. that the pad had already passed a retaining ring) replaces the hint with
    ``with_hint``.
    """

    def __init__(self, detail: str, hint: str = "", index: tuple = ()):
        self.detail, self.hint, self.index = detail, hint, index  # index: the failing case in a batch
        super().__init__(f"{detail} {hint}".strip())

    def with_hint(self, hint: str, prefix: str = "") -> ConvergenceError:
        """The same error with another hint (and an optional sentence before the detail)."""
        return type(self)(f"{prefix} {self.detail}".strip(), hint)


class SingularJacobianError(ConvergenceError):
    """The constraint Jacobian is singular: the constraint set has no unique solution here."""


#: what a solver failure does: "error" (raise a ConvergenceError) or "mark" (the failed case is marked
#: and the others go on); the same words in files and in the library
FAILURE_POLICIES = ("error", "mark")


@dataclass(frozen=True)
class NewtonOptions:
    """tol: max |contact residual| accepted (m); max_iter: iteration cap; on_failure: "error"
    (a ConvergenceError) or "mark" (the failed cases of a batch become NaN and are reported as
    failed; the others go on)."""

    tol: float = 1e-12
    max_iter: int = 25
    on_failure: str = "error"

    def __post_init__(self):
        if isinstance(self.tol, bool) or not isinstance(self.tol, (int, float)) or not (
            np.isfinite(self.tol) and self.tol > 0
        ):
            raise ValueError(f"Newton tolerance 'tol' must be a finite number > 0, got {self.tol!r}")
        if isinstance(self.max_iter, bool) or not isinstance(self.max_iter, (int, np.integer)) or self.max_iter < 1:
            raise ValueError(f"Newton 'max_iter' must be an integer >= 1, got {self.max_iter!r}")
        if self.on_failure not in FAILURE_POLICIES:
            raise ValueError(f"Newton 'on_failure' must be one of {FAILURE_POLICIES}, got {self.on_failure!r}")


class Rows(NamedTuple):
    """What a failure says of its constraint set: the phase, the free coordinates (indices of q,
    Eq. 4) and the labels of the contact rows, in the paper's terms."""

    phase: str
    free: tuple[int, ...]
    labels: tuple[str, ...]


def context(n, times, phase):
    """The context of an error at step n (its time, if ``times`` is given) in ``phase``."""
    ctx = {"step": n, "phase": phase}
    if times is not None:
        ctx["time"] = float(times[n])
    return ctx


def _where(context, index) -> str:
    ctx = dict(context or {})
    parts = [f"batch index {index}"] if index else []
    for key in ("case", "step", "time", "phase"):
        if key in ctx:
            parts.append(f"time {ctx[key]:.6g} s" if key == "time" else f"{key} {ctx[key]}")
    return ", ".join(parts)


def raise_singular(cset: Rows, J, context, index):
    raise SingularJacobianError(
        f"singular constraint Jacobian in {cset.phase} ({_where(context, index)}): "
        f"|C_q| = {float(det(J[index])):.3e}. The constraints do not fix the free "
        f"coordinates {[Q_NAMES[k] for k in cset.free]} here.",
        "Check the geometry (pad wider than its plate, tan alpha = A/B) and the step size.", index)


#: a residual within this factor of the tolerance has stalled at round-off, not diverged
STALLED = 100.0


def raise_not_converged(cset: Rows, g, options, context, index):
    a = np.where(np.isnan(g), np.inf, np.abs(g))
    row = int(np.argmax(a))
    residual = float(a[row])
    if residual <= STALLED * options.tol:
        hint = (f"The residual stalls within {STALLED:g} times the tolerance: round-off, not divergence; "
                "raise newton.tol.")
    else:
        hint = ("Likely cause: a step too large for the geometry (the constraints cannot follow the ground "
                "increment): reduce dt or the amplitude.")
    raise ConvergenceError(
        f"Newton-Raphson did not converge in {cset.phase} ({_where(context, index)}): after "
        f"{options.max_iter} iterations the residual is {residual:.3e} m > tol "
        f"{options.tol:.1e} m; largest: {cset.labels[row]} = {float(g[row]):.3e}.", hint, index)
