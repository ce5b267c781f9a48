"""Newton-Raphson on a constraint set (Eqs. 13-15), for one case or a batch.

The prescribed unit rows of a set are linear, so one Newton step solves them exactly; the
solver applies it first and then iterates C_q[contact, free] dq = -g on the contact rows. This
is block elimination of Eq. 13, not a different method: the iterates are Newton's.

One case (q0 of shape (9,)) runs on Python scalars, avoiding numpy's per-call overhead on the
small arrays of the rows; a batch (q0 of shape (..., 9)) stacks the Jacobians. Both evaluate the
same constraint rows and solve with the written-out elimination of ``linear`` (the compiled
kernels' own), not LAPACK, whose rounding depends on the CPU.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constraints import Q_NAMES, stack_jacobian, stack_residual
from .kinematics import frames
from .linear import solve4, solve4_batch


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
    (a ConvergenceError) or "mark" (the failed cases of a batch become NaN and are reported in
    ``NewtonResult.failed``; the others go on)."""

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


@dataclass
class NewtonResult:
    q: np.ndarray  # (..., 9) solution
    iterations: np.ndarray  # (...,) Newton updates taken per case
    residual: np.ndarray  # (...,) final max |contact residual| (m)
    failed: np.ndarray | bool = False  # (...,) cases marked failed (NaN), with on_failure="mark"


def solve(cset, q0, options: NewtonOptions = NewtonOptions(), context: dict | None = None):
    """Solve the constraint set ``cset`` from the initial guess ``q0`` (..., 9).

    ``context`` (step, time, phase, case) is quoted in error messages.

    Raises
    ------
    SingularJacobianError
        If the Jacobian on the free coordinates is singular for some case.
    ConvergenceError
        If some case does not reach ``options.tol`` within ``options.max_iter`` iterations;
        the message names the case, step, time, phase, residual and the worst constraint row.
    """
    q = cset.prescribe(q0)
    return (_solve_batch if q.ndim > 1 else _solve_one)(cset, q, options, context)


def _solve_one(cset, q, options, context):
    x, free, tol = q.tolist(), cset.free, options.tol
    rotations = bool({2, 8} & set(free))  # plate rotations are prescribed in every set
    for it in range(options.max_iter + 1):
        rows = cset.rows(frames(x), rotations=rotations)
        g = [gi for gi, _ in rows]
        if all(abs(gi) <= tol for gi in g):  # NaN fails
            return NewtonResult(np.array(x), it, max(abs(gi) for gi in g))
        if it == options.max_iter:
            break
        J = tuple(tuple(entries.get(c, 0.0) for c in free) for _, entries in rows)
        ok, dq = solve4(J, g)
        if not ok:
            raise_singular(cset, np.array(J), context, ())
        for c, d in zip(free, dq):
            x[c] -= d
    if options.on_failure == "mark":
        return NewtonResult(np.full(9, np.nan), it, float("nan"), True)
    raise_not_converged(cset, np.array(g), options, context, ())


def _solve_batch(cset, q, options, context):
    free, columns = cset.free, np.array(cset.free)
    iterations = np.zeros(q.shape[:-1], dtype=np.int32)
    shape, rotations = q.shape[:-1], bool({2, 8} & set(free))
    mark = options.on_failure == "mark"
    failed = np.isnan(q).any(axis=-1)  # cases that failed in an earlier phase or step
    for it in range(options.max_iter + 1):
        rows = cset.rows(frames(q), rotations=rotations)
        g = stack_residual(rows, shape)
        norm = np.abs(g).max(axis=-1)
        active = ~(norm <= options.tol) & ~failed  # NaN counts as not converged
        if not active.any():
            return NewtonResult(q, iterations, norm, failed)
        if it == options.max_iter:
            break
        J = stack_jacobian(rows, free, shape)  # only when a step is taken
        ok, dq = solve4_batch(J, g)
        singular = active & ~ok
        if singular.any():
            if not mark:
                raise_singular(cset, J, context, tuple(int(i) for i in np.argwhere(singular)[0]))
            failed |= singular
            q[singular] = np.nan
            active &= ~singular
        dq[~active] = 0.0
        q[..., columns] -= dq
        iterations += active
    if mark:
        q[active] = np.nan
        return NewtonResult(q, iterations, norm, failed | active)
    score = np.where(active, np.where(np.isnan(norm), np.inf, norm), -np.inf)
    index = tuple(int(i) for i in np.unravel_index(np.argmax(score), score.shape))
    raise_not_converged(cset, g[index], options, context, index)


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


def raise_singular(cset, J, context, index):
    raise SingularJacobianError(
        f"singular constraint Jacobian in {cset.phase} ({_where(context, index)}): "
        f"|C_q| = {float(np.linalg.det(J[index])):.3e}. The constraints do not fix the free "
        f"coordinates {[Q_NAMES[k] for k in cset.free]} here.",
        "Check the geometry (pad wider than its plate, tan alpha = A/B) and the step size.", index)


#: a residual within this factor of the tolerance has stalled at round-off, not diverged
STALLED = 100.0


def raise_not_converged(cset, g, options, context, index):
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
        f"{options.tol:.1e} m; largest: {cset.row_labels()[row]} = {float(g[row]):.3e}.", hint, index)
