"""The numpy reference of the planar models: an independent implementation of the same equations on
arrays, for one case or a batch, that the tests check the kernels against (``dccss.mechanics.models``'
kernels, interpreted and compiled).

It steps all the cases of a batch together with numpy: the constraint sets of
``constraint_sets`` (their rows as dicts of partial derivatives), Newton-Raphson on the
contact rows with the elimination of ``linear.solve4`` (one case) or its elementwise repetition
(``solve4_batch``), the same predictors, wrapping and slip set as the kernels, and sweep summaries
reduced with numpy. ``run``, ``steps`` and ``summarize`` take a model's name, as the package's.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
from constraint_sets import (
    Compliant,
    Slipping,
    Sticking,
    circle_centre,
    contact_point,
    diagonal,
    stack_jacobian,
    stack_residual,
)

from dccss.mechanics import newton
from dccss.mechanics.capacity import CAPACITY_POLICIES, case_error, mark_failures
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.kinematics import (
    CORNERS,
    RB3,
    all_corners,
    corner_diagnostics,
    dot,
    frames,
    local,
    start,
)
from dccss.mechanics.linear import solve4
from dccss.mechanics.newton import ConvergenceError, NewtonOptions, raise_not_converged, raise_singular


# --- the 4 x 4 solve on a stack -------------------------------------------------------------------
def solve4_batch(A, b):
    """``solve4`` on a stack: A (..., 4, 4), b (..., 4) -> ok (...,), x (..., 4), each system
    with the same operations as ``solve4`` (x is meaningless where ok is False)."""
    M = np.concatenate([np.asarray(A, dtype=float), np.asarray(b, dtype=float)[..., None]], axis=-1)
    ok = np.ones(M.shape[:-2], dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        for c in range(4):
            a = np.abs(M[..., c:, c])
            # pivot(): the first largest; a NaN is chosen only where it is the first entry
            p = c + np.where(np.isnan(a[..., 0]), 0, np.argmax(np.where(np.isnan(a), -1.0, a), axis=-1))
            perm = np.broadcast_to(np.arange(4), M.shape[:-2] + (4,)).copy()
            np.put_along_axis(perm, p[..., None], c, axis=-1)
            perm[..., c] = p
            M = np.take_along_axis(M, perm[..., None], axis=-2)
            ok &= M[..., c, c] != 0.0
            inverse = 1.0 / M[..., c, c]
            for r in range(c + 1, 4):
                f = M[..., r, c] * inverse
                M[..., r, c + 1:] = M[..., r, c + 1:] - f[..., None] * M[..., c, c + 1:]
        x3 = M[..., 3, 4] / M[..., 3, 3]
        x2 = (M[..., 2, 4] - M[..., 2, 3] * x3) / M[..., 2, 2]
        x1 = (M[..., 1, 4] - M[..., 1, 2] * x2 - M[..., 1, 3] * x3) / M[..., 1, 1]
        x0 = (M[..., 0, 4] - M[..., 0, 1] * x1 - M[..., 0, 2] * x2 - M[..., 0, 3] * x3) / M[..., 0, 0]
    return ok, np.stack([x0, x1, x2, x3], axis=-1)


# --- Newton-Raphson ------------------------------------------------------------------------------
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


# --- the steppers --------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class Step:
    """The configuration at t_n and how the solver got there (n = 0: the start, no solve)."""

    n: int
    q: np.ndarray  # (..., 9) configuration at t_n (end of the step)
    newton_iterations: object  # int or (...,) Newton updates of the step (its last phase)
    residual: object  # float or (...,) final max |constraint residual| (m)


@dataclass(frozen=True, slots=True)
class CompliantStep(Step):
    """A compliant sliding step: also the plate-frame positions of A..D at t_n (``local``) and the
    contact data of the step (plate-frame points and normals of A..D, complex)."""

    local: tuple
    point: tuple
    normal: tuple


@dataclass(frozen=True, slots=True)
class StickSlipStep(Step):
    """A stick-slip step: also the configuration at the end of its sticking phase (NaN at n = 0),
    the jammed diagonal (True: B-C) and the sticking phase's solver figures."""

    q_stick: np.ndarray
    diagonal_BC: object
    newton_iterations_stick: object
    residual_stick: object


def _wrapped(q):
    """q with theta2 in (-pi, pi]: Newton may land on theta2 + 2 pi k, the same configuration."""
    theta2 = q[..., 5]
    if (abs(float(theta2)) <= np.pi) if q.ndim == 1 else bool(np.all(np.abs(theta2) <= np.pi)):
        return q
    q = q.copy()
    q[..., 5] = theta2 - 2 * np.pi * np.round(theta2 / (2 * np.pi))
    return q


#: polynomial extrapolation weights from the last 1, 2, 3, 4 steps (oldest first)
_PREDICTOR = {1: (1,), 2: (-1, 2), 3: (1, -3, 3), 4: (-1, 4, -6, 4)}


def _extrapolate(history):
    """Initial guess for the next step: the cubic through the last four converged steps (lower
    orders at the start). Newton's iterates from it converge to the same solution."""
    return sum(w * q for w, q in zip(_PREDICTOR[len(history)], history))


def compliant_steps(geometry, Xg, theta2_0=0.0, *, normals="signed", options=newton.NewtonOptions(),
                    times=None):
    """Yield, for n = 0..T-1, {"n", "q", "local", "point", "normal", "newton_iterations",
    "residual"}: the configuration at t_n, the plate-frame positions of A..D there, and the
    contact data (plate-frame points and normals of A..D, complex) of the step that ends there;
    at n = 0 those of q(t_0) itself (for |C_q| at rest)."""
    q, Xg, Rx3 = start(geometry, Xg, theta2_0)
    corners = all_corners(geometry)
    F = frames(q)
    locals_ = tuple(local(F, c) for c in corners)
    points, normals_ = zip(*(contact_point(F, c, normals, u) for c, u in zip(corners, locals_)))
    yield CompliantStep(0, q, 0, 0.0, locals_, points, normals_)
    history = [q]  # the last converged configurations, newest last, for the predictor
    for n in range(1, len(Xg)):
        cset = Compliant(corners, Xg[n], Rx3, points, normals_)
        result = solve(cset, _extrapolate(history), options, newton.context(n, times, cset.phase))
        q = _wrapped(result.q)
        history = history[-3:] + [q]
        F = frames(q)  # the next step's contact data
        locals_ = tuple(local(F, c) for c in corners)
        step_points, step_normals = points, normals_
        points, normals_ = zip(*(contact_point(F, c, normals, u) for c, u in zip(corners, locals_)))
        yield CompliantStep(n, q, result.iterations, result.residual, locals_, step_points, step_normals)


def slip_set(geometry, corners, q_stick, normals="signed") -> Slipping:
    """The slipping constraints (Eq. 37) built from the end-of-sticking configuration."""
    F = frames(q_stick)
    points, normals_ = zip(*(contact_point(F, c, normals) for c in corners))
    C1, C3 = (circle_centre(F, c) for c in corners)
    e = (C3 - C1) / abs(C3 - C1)
    n12 = 1j * e
    R3 = F[2][0]
    cos_theta = -e.imag  # C^3 lies below C^1: e = (sin theta, -cos theta)
    Ry3_rc = C1.imag - geometry.L * cos_theta + geometry.hs3 + geometry.R3  # Eq. 41
    # k1: G^2 moves on the line through C^1 and C^3 (for a symmetric pad G^2 is already on it
    # at the end of sticking, so this equals Eq. 38's G^2 . n12; for unequal caps it does not)
    return Slipping(corners, q_stick, points, normals_, n12, dot(C1, n12), dot(R3, n12), Ry3_rc)


def stick_slip_steps(geometry, Xg, theta2_0=0.0, *, normals="signed", options=newton.NewtonOptions(),
                     times=None):
    """Yield, for n = 0..T-1, {"n", "q", "q_stick", "diagonal_BC", "newton_iterations(_stick)",
    "residual(_stick)"}: the configuration at t_n (end of slipping) and at the end of the
    sticking phase of the step ending there (NaN at n = 0); diagonal_BC is True where B-C jammed."""
    q, Xg, Rx3 = start(geometry, Xg, theta2_0)
    batch = np.ndim(Xg) > 1
    fixed = {False: diagonal(geometry, False), True: diagonal(geometry, True)}
    yield StickSlipStep(0, q, 0, 0.0, np.full_like(q, np.nan), np.zeros(np.shape(q)[:-1], bool), 0, 0.0)
    previous = None  # (q(t_{n-2}), q_stick(t_{n-1}), diagonal) for the predictors
    for n in range(1, len(Xg)):
        down = Xg[n] < Xg[n - 1]
        corners = diagonal(geometry, down) if batch else fixed[down]
        F = frames(q)
        stick = Sticking(corners, Xg[n], Rx3, [local(F, c) for c in corners])
        # predictors: the previous step's sticking and slipping increments, if on the same diagonal
        if previous is None:
            same, stick_guess = False, q
        else:
            same = (previous[2] == down)[..., None] if batch else previous[2] == down
            stick_guess = np.where(same, q + previous[1] - previous[0], q) if batch else (
                q + previous[1] - previous[0] if same else q)
        r1 = solve(stick, stick_guess, options, newton.context(n, times, stick.phase))
        q_stick = _wrapped(r1.q)
        slip = slip_set(geometry, corners, q_stick, normals)
        slip_guess = q_stick if previous is None else (
            np.where(same, q_stick + q - previous[1], q_stick) if batch else
            (q_stick + q - previous[1] if same else q_stick))
        r2 = solve(slip, slip_guess, options, newton.context(n, times, slip.phase))
        previous = (q, q_stick, down)
        q = _wrapped(r2.q)
        yield StickSlipStep(n, q, r2.iterations, r2.residual, q_stick, down, r1.iterations, r1.residual)


def collect(steps) -> dict:
    """A history from step records: each field stacked into an array, time first (contact data:
    last axis of 4), plus ``Rx3``, the guided abscissa of RB3."""
    rows = list(steps)
    out = {}
    one_case = np.ndim(rows[-1].q) == 1
    for f in fields(rows[0]):
        if f.name == "n":
            continue
        values = [getattr(r, f.name) for r in rows]
        if one_case:  # scalars, (9,) arrays or 4-tuples: one call
            out[f.name] = np.array(values)
            continue
        if isinstance(values[-1], tuple):  # contact data: one complex array per corner
            values = [np.stack(np.broadcast_arrays(*v), axis=-1) for v in values]
        shape = np.shape(values[-1])  # step 0 may hold scalars where later steps hold batch arrays
        out[f.name] = np.stack([np.broadcast_to(v, shape) for v in values])
    out["Rx3"] = out["q"][0, ..., RB3]
    return out


def _stick_slip_summary(step, previous_theta2, rise_of) -> dict:
    """Per-step values of the stick-slip summaries: the sticking rotation (deg) and rise (m)."""
    theta2_stick = np.degrees(step.q_stick[..., 5])
    turn = np.abs(theta2_stick - previous_theta2) if previous_theta2 is not None else np.nan * theta2_stick
    return {"sticking_rotation_max": turn, "rise_stick_max": rise_of(step.q_stick)}


#: each model's stepper, the step fields that count Newton iterations and its own per-step summaries
STEPS = {"compliant": compliant_steps, "stick_slip": stick_slip_steps}
ITERATION_FIELDS = {"compliant": ("newton_iterations",),
                    "stick_slip": ("newton_iterations", "newton_iterations_stick")}
SUMMARY = {"compliant": None, "stick_slip": _stick_slip_summary}
OWN_SUMMARIES = {"compliant": (), "stick_slip": ("sticking_rotation_max", "rise_stick_max")}


def steps(name, geometry, Xg, theta2_0=0.0, **kw):
    """The step records of model ``name``, one per step."""
    return STEPS[name](geometry, Xg, theta2_0, **kw)


def run(name, geometry, Xg, theta2_0=0.0, *, stop_at_ring=False, compiled=None, **kw) -> dict:
    """The whole history of model ``name`` (arrays, time first; ``collect``), as
    ``dccss.mechanics.compiled.run``: with ``stop_at_ring`` it ends at the first step where the pad
    has passed a retaining ring; a ConvergenceError carries the history up to the last converged
    step as ``err.history``. (``compiled`` is the kernels' keyword, and ignored.)"""
    done = []
    try:
        for step in steps(name, geometry, Xg, theta2_0, **kw):
            done.append(step)
            if stop_at_ring and (corner_diagnostics(step.q, geometry)[1] < 0).any():
                break  # the pad reaches a ring: stop here (or fail below) before solving further
    except ConvergenceError as err:
        if done:
            err.history = collect(done)
        raise
    return collect(done)


# --- sweep summaries -----------------------------------------------------------------------------
#: how each per-step value is reduced over the steps (fmax/fmin skip the NaN of step 0; a model's
#: own summaries are maxima); others keep their last value
_REDUCE = {"theta2_max_abs": np.fmax, "rise_max": np.fmax, "I_max": np.fmax, "clearance_min": np.fmin,
           "newton_iterations_max": np.maximum, "iterations": np.add,
           "sticking_rotation_max": np.fmax, "rise_stick_max": np.fmax}


def _last(old, new):
    return new


def summarize(model, geometry, Xg, theta2_0=0.0, *, capacity="continue", progress=None, compiled=None,
              **kw) -> dict:
    """``dccss.mechanics.summaries.summarize`` on the numpy reference (``compiled`` ignored);
    ``progress(n, N)`` is called after each step."""
    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    Xg = np.asarray(Xg, dtype=float)
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
    rest = geometry.Ry3_compatible(0.0)
    times = kw.get("times")
    mark = kw.get("options", NewtonOptions()).on_failure == "mark"
    acc, previous = None, None
    failure, reached = np.full(shape, np.nan), np.full(shape, np.nan)
    stopped = np.zeros(shape, dtype=bool)  # cases whose history ended at a ring (capacity stop/error)
    for step in steps(model, geometry, Xg, theta2_0, **kw):
        q, n = step.q, step.n
        now = times[n] if times is not None else n
        failure = np.where(np.isnan(failure) & ~stopped & np.isnan(q).any(axis=-1), now, failure)
        theta2, rise = np.degrees(q[..., 5]), q[..., 7] - rest
        interp, gap = corner_diagnostics(q, geometry, getattr(step, "local", None))
        its = sum(np.asarray(getattr(step, name)) for name in ITERATION_FIELDS[model])
        current = {"theta2_max_abs": np.abs(theta2), "rise_max": rise, "I_max": interp,
                   "clearance_min": gap.min(axis=-1), "newton_iterations_max": its, "iterations": its,
                   "theta2_end": theta2, "rise_end": rise, "steps": np.full(shape, n)}
        if SUMMARY[model] is not None:
            current.update(SUMMARY[model](step, previous, lambda q: q[..., 7] - rest))
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
    out.update({name: acc[name] for name in OWN_SUMMARIES[model]})
    return mark_failures(out, failure, reached, capacity)
