"""The paper's two kinematic models: their steps (kernels, and numpy reference steppers for one case
or a batch of cases) and their registry entries.

Each step t_{n-1} -> t_n starts from the converged q(t_{n-1}) and

* ``compliant``: projects the four corners radially onto their concave circles (the previous
  contact points of Eqs. 6-11) and solves Eq. 5 with X_g(t_n);
* ``stick_slip``: chooses the jammed diagonal by the sign of dX_g (A-D for dX_g >= 0, B-C
  otherwise), pins its corners where they are (Eq. 31) and solves; then projects them, builds
  C^1C^3 and Eq. 41 from the end of sticking and solves the slip set (Eq. 37). A step is
  committed only after both phases converge.

Both start from the compatible configuration at theta^2(t_0) (RB3 offset by L sin theta^2).
X_g is (T,) for one case or (T, ...) for a batch; geometry and theta^2(t_0) may be batches too.

``compliant_steps``/``stick_slip_steps`` yield one typed record per step (``CompliantStep``,
``StickSlipStep``; a sweep summarises them on the fly); ``collect`` stacks them into whole
histories as arrays, time first, which ``dccss.results`` turns into datasets.

Each model is written here once more, as kernels: its planar case (``compliant_case``,
``stick_slip_case``: the steps of one case on ``compiled``'s scalar helpers, interpreted or
compiled) and its spatial step (``*_spatial_step`` on ``spatial``'s phases). Those, not the step
generators, run the models (``backend``); the step generators stay as the numpy reference the
tests check the kernels against.

The models are data: each is a ``registry.Model`` entry, registered at the end of this module
(name, title, stepper, step record, the diagnostics its datasets carry, the summaries its sweeps
keep, its plot style and its kernels). Nothing outside this module names or branches on a model;
adding a model is registering an entry.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from . import backend, compiled, newton, scalar, spatial
from .compiled import RISE_STICK_MAX, STICK_TURN_MAX
from .constraints import Compliant, Slipping, Sticking, diagonal
from .kinematics import (
    CORNERS,
    RB3,
    all_corners,
    circle_centre,
    contact_angle,
    contact_point,
    dot,
    frames,
    interpenetration,
    local,
    start,
)
from .registry import REGISTRY, Model, PlanarKernels, model, register
from .scalar import jit


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
        result = newton.solve(cset, _extrapolate(history), options, newton.context(n, times, cset.phase))
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
        r1 = newton.solve(stick, stick_guess, options, newton.context(n, times, stick.phase))
        q_stick = _wrapped(r1.q)
        slip = slip_set(geometry, corners, q_stick, normals)
        slip_guess = q_stick if previous is None else (
            np.where(same, q_stick + q - previous[1], q_stick) if batch else
            (q_stick + q - previous[1] if same else q_stick))
        r2 = newton.solve(slip, slip_guess, options, newton.context(n, times, slip.phase))
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


# --- what each model's datasets and summaries carry --------------------------------------------
def _compliant_diagnostics(history, geometry) -> dict:
    """|C_q| at each step's solution (Eq. 29, the solver's own constraint set) and the contact
    angles at the previous contact points: {name: (values, units, long_name)}."""
    corners = all_corners(geometry)
    normals_ = [history["normal"][..., i] for i in range(4)]
    out = {"det_Cq": (determinant(history, geometry), "m",
                      "determinant |C_q| of the constraint Jacobian (Eq. 29) at the step's solution")}
    for i, c in enumerate(corners):
        out[f"alpha_{c.name}"] = (np.degrees(contact_angle(normals_[i], c)), "degree",
                                  f"contact angle alpha of {c.name}2 at the previous contact point")
    return out


def determinant(history, geometry):
    """|C_q| (Eq. 29) of the compliant steps of ``history`` at their solutions (m)."""
    corners = all_corners(geometry)
    cset = Compliant(corners, history["q"][..., 0], history["Rx3"],
                     [history["point"][..., i] for i in range(4)], [history["normal"][..., i] for i in range(4)])
    return cset.determinant(history["q"])


def _stick_slip_diagnostics(history, geometry) -> dict:
    """The end-of-sticking configuration's interpenetration and the jammed diagonal."""
    Is = interpenetration(history["q_stick"], geometry)
    out = {f"I_{c}_stick": (Is[..., i], "m", f"interpenetration at corner {c}2 at the end of the sticking phase")
           for i, c in enumerate(CORNERS)}
    out["sticking_diagonal"] = (history["diagonal_BC"].astype(np.int8), "1", "diagonal jammed in the sticking phase",
                                {"flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "A2D2 B2C2"})
    out["newton_iterations_stick"] = (history["newton_iterations_stick"], "1",
                                      "Newton-Raphson iterations of the sticking phase")
    out["newton_residual_stick"] = (history["residual_stick"], "m",
                                    "final max |constraint residual| of the sticking phase")
    return out


def _stick_slip_summary(step, previous_theta2, rise_of) -> dict:
    """Per-step values of the stick-slip summaries: the sticking rotation (deg) and rise (m)."""
    theta2_stick = np.degrees(step.q_stick[..., 5])
    turn = np.abs(theta2_stick - previous_theta2) if previous_theta2 is not None else np.nan * theta2_stick
    return {"sticking_rotation_max": turn, "rise_stick_max": rise_of(step.q_stick)}


# --- the kernels: each model's steps, on scalars -------------------------------------------------
@jit
def compliant_case(k, xg, q0, case, flags, history_out, summary_out, status_out):
    """``models.compliant_steps`` for case k (ground motion ``xg`` (T,), start ``q0``)."""
    pad, centre, radius, dims = case
    signed, tol, max_iter, mark, one_case, stop_at_ring = flags
    fail, fail_g, fail_J, done = status_out
    hq, hits, hres, hlocal, hpoint, hnormal = history_out  # the order of ``COMPLIANT_HISTORY``
    now, acc_all, count_all, capacity = summary_out
    record, summarise = hq.shape[0] > 0, acc_all.shape[0] > 0
    acc = acc_all[k].copy() if summarise else np.empty(0)  # this case's summaries, written back at the end
    count = count_all[k].copy() if summarise else np.empty(0, np.int64)
    q = (q0[0], q0[1], q0[2], q0[3], q0[4], q0[5], q0[6], q0[7], q0[8])
    Rx3 = q[6]
    u = compiled.plate_positions(compiled.frames(q), pad)
    points, normals, distance = compiled.contacts(u, centre, radius, signed)
    if record:
        for i in range(9):
            hq[0, k, i] = q[i]
        for i in range(4):
            hlocal[0, k, i], hpoint[0, k, i], hnormal[0, k, i] = u[i], points[i], normals[i]
        hits[0, k], hres[0, k] = 0, 0.0
    if summarise:
        compiled.summarise_step(acc, count, 0, now[0], q, u, distance, radius, dims, 0, capacity)
    h0 = h1 = h2 = h3 = q  # the last four converged configurations, newest last
    history = 1
    done[k] = 1
    T = 1 if stop_at_ring and compiled.beyond_ring(u, dims) else len(xg)  # a start beyond a ring: no step
    for n in range(1, T):
        guess = compiled.extrapolate(h0, h1, h2, h3, history)
        guess = (xg[n], 0.0, 0.0, guess[3], guess[4], guess[5], Rx3, guess[7], 0.0)  # Eq. 5 rows 1-3, 8, 9
        cset = (pad, points, normals, 0j, 0.0, 0.0)
        status, its, res, q, g, J, F = compiled.solve(compiled.COMPLIANT, guess, cset, tol, max_iter, mark, one_case)
        if compiled.fatal(status):
            compiled.record_failure(fail, fail_g, fail_J, k, n, 0, its, status, g, J)
            break
        q, F = compiled.wrapped(q, F)
        if record:
            for i in range(9):
                hq[n, k, i] = q[i]
            for i in range(4):
                hpoint[n, k, i], hnormal[n, k, i] = points[i], normals[i]
            hits[n, k], hres[n, k] = its, res
        h0, h1, h2, h3 = h1, h2, h3, q
        history = min(history + 1, 4)
        u = compiled.plate_positions(F, pad)  # the next step's contact data
        points, normals, distance = compiled.contacts(u, centre, radius, signed)
        if record:
            for i in range(4):
                hlocal[n, k, i] = u[i]
        if summarise:
            compiled.summarise_step(acc, count, n, now[n], q, u, distance, radius, dims, its, capacity)
        done[k] = n + 1
        if stop_at_ring and compiled.beyond_ring(u, dims):
            break
    if summarise:
        acc_all[k] = acc
        count_all[k] = count


@jit
def stick_slip_case(k, xg, q0, case, flags, history_out, summary_out, status_out):
    """``models.stick_slip_steps`` for case k (ground motion ``xg`` (T,), start ``q0``)."""
    pad, centre, radius, dims = case
    signed, tol, max_iter, mark, one_case, stop_at_ring = flags
    fail, fail_g, fail_J, done = status_out
    hq, hits, hres, hq_stick, hdiagonal, hits_stick, hres_stick = history_out  # ``STICK_SLIP_HISTORY``
    now, acc_all, count_all, capacity = summary_out
    record, summarise = hq.shape[0] > 0, acc_all.shape[0] > 0
    acc = acc_all[k].copy() if summarise else np.empty(0)  # this case's summaries, written back at the end
    count = count_all[k].copy() if summarise else np.empty(0, np.int64)
    q = (q0[0], q0[1], q0[2], q0[3], q0[4], q0[5], q0[6], q0[7], q0[8])
    Rx3 = q[6]
    if record:
        for i in range(9):
            hq[0, k, i], hq_stick[0, k, i] = q[i], compiled.NAN
        hdiagonal[0, k] = False
        hits_stick[0, k], hits[0, k], hres_stick[0, k], hres[0, k] = 0, 0, 0.0, 0.0
    F = compiled.frames(q)
    u = compiled.plate_positions(F, pad)
    if summarise:
        compiled.summarise_step(acc, count, 0, now[0], q, u, compiled.distances(u, centre), radius, dims, 0, capacity)
    q_previous = q_stick_previous = compiled.NAN9  # q(t_{n-2}) and q_stick(t_{n-1}), for the predictors
    started, down_previous = False, False
    done[k] = 1
    T = 1 if stop_at_ring and compiled.beyond_ring(u, dims) else len(xg)  # a start beyond a ring: no step
    for n in range(1, T):
        down = xg[n] < xg[n - 1]  # the jammed diagonal: A-D for dX_g >= 0, B-C otherwise
        c1, c3 = (compiled.CORNER_B, compiled.CORNER_C) if down else (compiled.CORNER_A, compiled.CORNER_D)
        same = started and down_previous == down
        # sticking (Eq. 31): the diagonal's corners pinned where they are at t_{n-1}
        R1, e1, R2, e2, R3, e3 = F
        pins = (compiled.local(R2, e2, pad[c1], R1, e1), compiled.local(R2, e2, pad[c3], R3, e3), 0j, 0j)
        cset = ((pad[c1], pad[c3], 0j, 0j), pins, pins, 0j, 0.0, 0.0)
        # the previous sticking increment
        guess = compiled.sub(compiled.add(q, q_stick_previous), q_previous) if same else q
        guess = (xg[n], 0.0, 0.0, guess[3], guess[4], guess[5], Rx3, guess[7], 0.0)
        status, its_stick, res_stick, q_stick, g, J, F = compiled.solve(compiled.STICKING, guess, cset, tol, max_iter,
                                                                         mark, one_case)
        if compiled.fatal(status):
            compiled.record_failure(fail, fail_g, fail_J, k, n, 0, its_stick, status, g, J)
            break
        q_stick, F = compiled.wrapped(q_stick, F)
        # slipping (Eq. 37) from the end of sticking
        cset, Ry3_rc = compiled.slip_set(F, pad, centre, radius, dims, c1, c3, signed)
        # the previous slipping increment
        guess = compiled.sub(compiled.add(q_stick, q), q_stick_previous) if same else q_stick
        guess = (q_stick[0], q_stick[1], q_stick[2], guess[3], guess[4], guess[5], guess[6], Ry3_rc, 0.0)
        status, its, res, q_new, g, J, F = compiled.solve(compiled.SLIPPING, guess, cset, tol, max_iter, mark, one_case)
        if compiled.fatal(status):
            compiled.record_failure(fail, fail_g, fail_J, k, n, 1, its, status, g, J)
            break
        q_previous, q_stick_previous = q, q_stick
        started, down_previous = True, down
        q, F = compiled.wrapped(q_new, F)
        if record:
            for i in range(9):
                hq[n, k, i], hq_stick[n, k, i] = q[i], q_stick[i]
            hdiagonal[n, k] = down
            hits_stick[n, k], hits[n, k], hres_stick[n, k], hres[n, k] = its_stick, its, res_stick, res
        if summarise or stop_at_ring:
            u = compiled.plate_positions(F, pad)
        if summarise:
            compiled.summarise_stick(acc, q_stick, q_previous[5] * compiled.DEGREES, dims)
            compiled.summarise_step(acc, count, n, now[n], q, u, compiled.distances(u, centre), radius, dims,
                                    its_stick + its, capacity)
        done[k] = n + 1
        if stop_at_ring and compiled.beyond_ring(u, dims):
            break
    if summarise:
        acc_all[k] = acc
        count_all[k] = count


def compliant_batch(Xg, q0, pad, centre, radius, dims, flags, history_out, summary_out, status_out):
    for k in scalar.prange(q0.shape[0]):
        xg = Xg[:, k] if Xg.shape[1] > 1 else Xg[:, 0]
        compliant_case(k, xg, q0[k], compiled.case_constants(k, pad, centre, radius, dims), flags, history_out,
                        summary_out, status_out)


def stick_slip_batch(Xg, q0, pad, centre, radius, dims, flags, history_out, summary_out, status_out):
    for k in scalar.prange(q0.shape[0]):
        xg = Xg[:, k] if Xg.shape[1] > 1 else Xg[:, 0]
        stick_slip_case(k, xg, q0[k], compiled.case_constants(k, pad, centre, radius, dims), flags, history_out,
                         summary_out, status_out)


#: the history arrays each planar case fills, in the order of ``history_out`` and of the histories:
#: name -> (trailing shape, dtype)
COMPLIANT_HISTORY = {"q": ((9,), float), "newton_iterations": ((), np.int64), "residual": ((), float),
                     "local": ((4,), complex), "point": ((4,), complex), "normal": ((4,), complex)}
STICK_SLIP_HISTORY = {"q": ((9,), float), "newton_iterations": ((), np.int64), "residual": ((), float),
                      "q_stick": ((9,), float), "diagonal_BC": ((), bool), "newton_iterations_stick": ((), np.int64),
                      "residual_stick": ((), float)}


def compliant_set(geometry, phase, down):
    """A compliant constraint set of ``geometry``, for an error's name and row labels."""
    return Compliant(all_corners(geometry), 0.0, 0.0, [0j] * 4, [0j] * 4)


def stick_slip_set(geometry, phase, down):
    """The sticking (phase 0) or slipping (1) set of the jammed diagonal (``down``: B-C), for an error's
    name and row labels."""
    corners = diagonal(geometry, down)
    if phase == 0:
        return Sticking(corners, 0.0, 0.0, [0j, 0j])
    return Slipping(corners, np.zeros(9), [0j, 0j], [0j, 0j], 1j, 0.0, 0.0, 0.0)


@jit
def compliant_spatial_step(dev, pose, R1, e1, m, guide, in_plane, tol, max_iter, work):
    """One compliant sliding step: (pose, end of sticking (none: NaN), its and residual of both
    phases, status, failing phase, its rows)."""
    up = spatial.unit(spatial.cross(m, e1)) if in_plane else spatial.Z
    phase = spatial.compliant_phase(dev, pose, R1, m, up)
    x, its, res, status, g = spatial.newton(spatial.compliant_rows, phase, spatial.guess(pose, R1), tol, max_iter, work)
    return spatial.compliant_pose(phase, x), spatial.NAN_POSE, 0, 0.0, its, res, status, spatial.COMPLIANT, g


@jit
def stick_slip_spatial_step(dev, pose, R1, e1, m, guide, in_plane, tol, max_iter, work):
    """One stick-slip step (as ``compliant_step``): sticking, then slipping from its end."""
    v1, v3 = spatial.pinned(pose, dev, m)
    stick = spatial.sticking_phase(dev, pose, R1, guide, v1, v3)
    x, its1, res1, status, g = spatial.newton(spatial.sticking_rows, stick, spatial.guess(pose, R1), tol, max_iter,
                                              work)
    if status != spatial.CONVERGED:
        return spatial.NAN_POSE, spatial.NAN_POSE, its1, res1, 0, 0.0, status, spatial.STICKING, g
    end = spatial.sticking_pose(stick, x)
    slip = spatial.slipping_phase(dev, end, e1, v1, v3)
    x, its, res, status, g = spatial.newton(spatial.slipping_rows, slip, (end.G[0], end.G[1], end.G[2], 0.0, 0.0, 0.0),
                                            tol, max_iter, work)
    return spatial.slipping_pose(slip, x), end, its1, res1, its, res, status, spatial.SLIPPING, g



def compliant_spatial_history(dev, Xg, theta2_0, azimuth, R3z, in_plane, tol, max_iter, stop_at_ring, ends, sticks,
                              planes, solver, failure):
    """``spatial.history`` of compliant sliding (compiled by ``spatial.run``; numba caches no function
    that takes a function)."""
    return spatial.history(compliant_spatial_step, dev, Xg, theta2_0, azimuth, R3z, in_plane, tol, max_iter,
                           stop_at_ring, ends, sticks, planes, solver, failure)


def stick_slip_spatial_history(dev, Xg, theta2_0, azimuth, R3z, in_plane, tol, max_iter, stop_at_ring, ends, sticks,
                               planes, solver, failure):
    """``spatial.history`` of stick-slip (as ``compliant_spatial_history``)."""
    return spatial.history(stick_slip_spatial_step, dev, Xg, theta2_0, azimuth, R3z, in_plane, tol, max_iter,
                           stop_at_ring, ends, sticks, planes, solver, failure)

# --- the registry entries -----------------------------------------------------------------------
# compliant sliding drawn wide and solid underneath, stick-slip narrow and dashed on top
register(Model(
    "compliant", "Compliant Sliding", compliant_steps, CompliantStep, _compliant_diagnostics, {}, {}, None,
    ("newton_iterations",), line=dict(color="tab:blue", ls="-", lw=2.6, zorder=2),
    marker=dict(marker="o", ms=8, mfc="none", mew=1.8),
    planar=PlanarKernels(compliant_case, compliant_batch, COMPLIANT_HISTORY, {}, compliant_set),
    spatial=compliant_spatial_history))
register(Model(
    "stick_slip", "Stick-Slip", stick_slip_steps, StickSlipStep, _stick_slip_diagnostics,
    {"_stick": " at the end of the sticking phase"},
    {"sticking_rotation_max": ("degree", "largest pad rotation within a sticking phase, "
                                         "|theta2_stick - theta2(t_n-1)|"),
     "rise_stick_max": ("m", "largest rise of RB3 at the end of a sticking phase")},
    _stick_slip_summary, ("newton_iterations", "newton_iterations_stick"),
    line=dict(color="tab:orange", ls=(0, (4, 2)), lw=1.3, zorder=3), marker=dict(marker="D", ms=4.5, mew=0.8),
    planar=PlanarKernels(stick_slip_case, stick_slip_batch, STICK_SLIP_HISTORY,
                         {"sticking_rotation_max": STICK_TURN_MAX, "rise_stick_max": RISE_STICK_MAX}, stick_slip_set),
    spatial=stick_slip_spatial_history))
MODELS = tuple(REGISTRY)


def run(name, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """The whole history of model ``name`` (arrays, time first; see ``collect``). Keywords as
    for the step generators. The kernels run it, compiled or interpreted (``backend``:
    DCCSS_BACKEND); the step generators are the numpy reference."""
    entry = model(name)
    found = backend.kernels(name, *backend.size(geometry, Xg, theta2_0))
    if found is not None:
        kernels, compiled = found
        return kernels.run(name, geometry, Xg, theta2_0, compiled=compiled, **kw)
    return collect(entry.steps(geometry, Xg, theta2_0, **kw))


def steps(name, geometry, Xg, theta2_0=0.0, **kw):
    """The step records of model ``name``, one per step."""
    return model(name).steps(geometry, Xg, theta2_0, **kw)


def compliant(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Compliant sliding history (``run("compliant", ...)``)."""
    return run("compliant", geometry, Xg, theta2_0, **kw)


def stick_slip(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Stick-slip history (``run("stick_slip", ...)``)."""
    return run("stick_slip", geometry, Xg, theta2_0, **kw)
