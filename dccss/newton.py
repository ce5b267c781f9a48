"""Newton-Raphson on a constraint set (Eqs. 13-15), batched over leading dimensions.

The prescribed unit rows of a set are linear, so one Newton step solves them exactly; the
solver applies it first and then iterates C_q[contact, free] dq = -g on the contact rows. This
is block elimination of Eq. 13, not a different method: the iterates are Newton's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .constraints import Q_NAMES


class ConvergenceError(RuntimeError):
    """Newton-Raphson did not reach the tolerance within the iteration cap."""


class SingularJacobianError(ConvergenceError):
    """The constraint Jacobian is singular: the constraint set has no unique solution here."""


@dataclass(frozen=True)
class NewtonOptions:
    """tol: max |contact residual| accepted (m); max_iter: iteration cap."""

    tol: float = 1e-12
    max_iter: int = 25

    def __post_init__(self):
        if not (np.isfinite(self.tol) and self.tol > 0):
            raise ValueError(f"Newton tolerance 'tol' must be a finite number > 0, got {self.tol!r}")
        if not (isinstance(self.max_iter, (int, np.integer)) and self.max_iter >= 1):
            raise ValueError(f"Newton 'max_iter' must be an integer >= 1, got {self.max_iter!r}")


@dataclass
class NewtonResult:
    q: np.ndarray  # (..., 9) solution
    iterations: np.ndarray  # (...,) Newton updates taken per case
    residual: np.ndarray  # (...,) final max |contact residual| (m)


def _where(context: dict | None, index) -> str:
    parts = []
    ctx = dict(context or {})
    if index:
        parts.append(f"case {index}")
    for key in ("case", "step", "time", "phase"):
        if key in ctx:
            value = ctx[key]
            parts.append(f"{key} {value:.6g} s" if key == "time" else f"{key} {value}")
    return ", ".join(parts)


def solve(cset, q0, options: NewtonOptions = NewtonOptions(), context: dict | None = None):
    """Solve the constraint set ``cset`` from the initial guess ``q0`` (..., 9).

    Raises
    ------
    SingularJacobianError
        If the Jacobian on the free coordinates is singular for some case.
    ConvergenceError
        If some case does not reach ``options.tol`` within ``options.max_iter`` iterations;
        the message names the case, step, time, phase, residual and the worst constraint row.
    """
    q = cset.prescribe(q0)
    free = list(cset.free)
    iterations = np.zeros(q.shape[:-1], dtype=np.int32)
    for it in range(options.max_iter + 1):
        g, J = cset.contact(q)
        norm = np.max(np.abs(g), axis=-1)
        active = ~(norm <= options.tol)  # NaN counts as not converged
        if not active.any():
            return NewtonResult(q, iterations, norm)
        if it == options.max_iter:
            break
        Jf = J[..., free]
        try:
            dq = np.linalg.solve(Jf, -g[..., None])[..., 0]
        except np.linalg.LinAlgError:
            det = np.linalg.det(Jf)
            index = np.unravel_index(np.argmin(np.abs(det)), det.shape) if det.ndim else ()
            raise SingularJacobianError(
                f"singular constraint Jacobian in {cset.phase} ({_where(context, index)}): "
                f"|C_q| = {float(det[index]):.3e}. The constraints do not fix the free "
                f"coordinates {[Q_NAMES[k] for k in free]} here; check the geometry (pad wider "
                "than its plate, tan alpha = A/B) and the step size."
            ) from None
        dq = np.where(active[..., None], dq, 0.0)
        q[..., free] += dq
        iterations += active
    index = np.unravel_index(np.argmax(np.where(np.isnan(norm), np.inf, norm)), norm.shape)
    row = int(np.nanargmax(np.abs(g[index]))) if np.isfinite(g[index]).any() else 0
    labels = cset.row_labels()
    raise ConvergenceError(
        f"Newton-Raphson did not converge in {cset.phase} ({_where(context, index)}): after "
        f"{options.max_iter} iterations the residual is {float(norm[index]):.3e} m > tol "
        f"{options.tol:.1e} m; largest: {labels[row]} = {float(g[index][row]):.3e}. Likely "
        "causes: a step too large for the geometry (reduce dt or the amplitude), the pad "
        "beyond the plate capacity, or a tolerance below round-off (raise tol)."
    )

