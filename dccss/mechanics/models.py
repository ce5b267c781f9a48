"""The paper's two kinematic models, written once as kernels, and their registry entries.

Each step t_{n-1} -> t_n starts from the converged q(t_{n-1}) and

* ``compliant``: projects the four corners radially onto their concave circles (the previous
  contact points of Eqs. 6-11) and solves Eq. 5 with X_g(t_n);
* ``stick_slip``: chooses the jammed diagonal by the sign of dX_g (A-D for dX_g >= 0, B-C
  otherwise), pins its corners where they are (Eq. 31) and solves; then projects them, builds
  C^1C^3 and Eq. 41 from the end of sticking and solves the slip set (Eq. 37). A step is
  committed only after both phases converge.

Both start from the compatible configuration at theta^2(t_0) (RB3 offset by L sin theta^2).
X_g is (T,) for one case or (T, ...) for a batch; geometry and theta^2(t_0) may be batches too.

A model's planar steps are one case's kernel (``compliant_case``, ``stick_slip_case``: on
``compiled``'s scalar helpers, interpreted or compiled) and its spatial steps one step function
(``*_spatial_step``, on ``spatial``'s phases). ``run`` gives a whole history as arrays, time
first, which ``dccss.results`` turns into datasets. The tests check the kernels against an
independent numpy implementation of the same equations (``tests/oracle.py``).

The models are data: each is a ``registry.Model`` entry, registered at the end of this module
(name, title, kernels, the diagnostics its datasets carry, the summaries its sweeps keep and its
plot style). Nothing outside this module names or branches on a model; adding a model is
registering an entry.
"""

from __future__ import annotations

import numpy as np

from . import backend, compiled, scalar, spatial
from .compiled import RISE_STICK_MAX, STICK_TURN_MAX
from .kinematics import CORNERS, all_corners, contact_angle, dot, frames, interpenetration, turn
from .linear import det
from .newton import Rows
from .registry import REGISTRY, Model, PlanarKernels, model, register
from .scalar import jit


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
    """|C_q| (Eq. 29) of the compliant steps of ``history`` at their solutions (m): the 9 x 9 Jacobian
    of Eq. 5 in the paper's row and column order, the unit rows of R_x^1, R_y^1, theta^1, then the
    tangency rows of A, B, C, D at the previous contact points (Eqs. 16-28), then the unit rows of
    R_x^3 and theta^3."""
    q = history["q"]
    (_, _), (R2, e2), _ = F = frames(q)
    J = np.zeros(q.shape[:-1] + (9, 9))
    for k, row in ((0, 0), (1, 1), (2, 2), (6, 7), (8, 8)):
        J[..., row, k] = 1.0
    for i, c in enumerate(all_corners(geometry)):
        Rj, ej = F[c.body // 3]
        arm, n = e2 * c.u2, turn(ej, history["normal"][..., i])
        b, row = c.body, J[..., 3 + i, :]
        row[..., 3], row[..., 4], row[..., 5] = n.real, n.imag, dot(1j * arm, n)
        row[..., b], row[..., b + 1], row[..., b + 2] = -n.real, -n.imag, dot(R2 + arm - Rj, 1j * n)
    return det(J)


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


# --- the kernels: each model's steps, on scalars -------------------------------------------------
@jit
def compliant_case(k, xg, q0, case, flags, history_out, summary_out, status_out):
    """All the compliant sliding steps of case k (ground motion ``xg`` (T,), start ``q0``; the module docstring)."""
    pad, centre, radius, dims = case
    signed, tol, max_iter, mark, one_case, stop_at_ring = flags
    fail, fail_g, fail_J, done = status_out
    hq, hits, hres, hlocal, hpoint, hnormal = history_out  # the order of ``COMPLIANT_HISTORY``
    now, acc_all, count_all, capacity = summary_out
    record = hq.shape[0] > 0
    acc, count, summarise = compiled.case_summaries(k, acc_all, count_all)
    q = compiled.configuration(q0)
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
        acc, count = compiled.summarise_step(acc, count, 0, now[0], q, u, distance, radius, dims, 0, capacity)
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
            acc, count = compiled.summarise_step(acc, count, n, now[n], q, u, distance, radius, dims, its, capacity)
        done[k] = n + 1
        if stop_at_ring and compiled.beyond_ring(u, dims):
            break
    compiled.keep_summaries(k, acc_all, count_all, acc, count)


@jit
def stick_slip_case(k, xg, q0, case, flags, history_out, summary_out, status_out):
    """All the stick-slip steps of case k (ground motion ``xg`` (T,), start ``q0``; the module docstring)."""
    pad, centre, radius, dims = case
    signed, tol, max_iter, mark, one_case, stop_at_ring = flags
    fail, fail_g, fail_J, done = status_out
    hq, hits, hres, hq_stick, hdiagonal, hits_stick, hres_stick = history_out  # ``STICK_SLIP_HISTORY``
    now, acc_all, count_all, capacity = summary_out
    record = hq.shape[0] > 0
    acc, count, summarise = compiled.case_summaries(k, acc_all, count_all)
    q = compiled.configuration(q0)
    Rx3 = q[6]
    if record:
        for i in range(9):
            hq[0, k, i], hq_stick[0, k, i] = q[i], compiled.NAN
        hdiagonal[0, k] = False
        hits_stick[0, k], hits[0, k], hres_stick[0, k], hres[0, k] = 0, 0, 0.0, 0.0
    F = compiled.frames(q)
    u = compiled.plate_positions(F, pad)
    if summarise:
        acc, count = compiled.summarise_step(acc, count, 0, now[0], q, u, compiled.distances(u, centre), radius,
                                             dims, 0, capacity)
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
            acc = compiled.summarise_stick(acc, q_stick, q_previous[5] * compiled.DEGREES, dims)
            acc, count = compiled.summarise_step(acc, count, n, now[n], q, u, compiled.distances(u, centre), radius,
                                                 dims, its_stick + its, capacity)
        done[k] = n + 1
        if stop_at_ring and compiled.beyond_ring(u, dims):
            break
    compiled.keep_summaries(k, acc_all, count_all, acc, count)


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


#: the free coordinates of a phase (Eq. 4 indices): R_x^2, R_y^2, theta^2 and R_y^3, or R_x^3 when slipping
FREE, FREE_SLIPPING = (3, 4, 5, 7), (3, 4, 5, 6)


def compliant_rows(phase, down):
    """The compliant set (Eq. 5), for an error's name and row labels."""
    return Rows("compliant sliding", FREE, tuple(
        f"row {4 + i} (Eq. {8 + i}: {c}^2 sliding on the tangent to C_nf^{1 if i < 2 else 3})"
        for i, c in enumerate(CORNERS)))


def stick_slip_rows(phase, down):
    """The sticking (phase 0, Eq. 31) or slipping (1, Eq. 37) set of the jammed diagonal, B-C if ``down``
    (None: a batch, which names both), for an error's name and row labels."""
    p1, p3 = {False: ("A", "D"), True: ("B", "C"), None: ("A/B", "D/C")}[down]
    if phase == 0:
        return Rows("sticking", FREE, tuple(f"row {r} (Eq. 32: {x} of {p}^2 pinned to RB{j})" for r, (x, p, j) in
                                            enumerate((("x", p1, 1), ("y", p1, 1), ("x", p3, 3), ("y", p3, 3)), 4)))
    return Rows("slipping", FREE_SLIPPING, (f"row 1 (Eq. 37: {p1}^2 sliding on the tangent to C_nf^1)",
                                            f"row 2 (Eq. 37: {p3}^2 sliding on the tangent to C_nf^3)",
                                            "row 3 (Eq. 38: G^2 on the line C^1C^3)",
                                            "row 4 (Eq. 39: RB3 translating along C^1C^3)"))


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
    """One stick-slip step (as ``compliant_spatial_step``): sticking, then slipping from its end."""
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
    "compliant", "Compliant Sliding",
    PlanarKernels(compliant_case, compliant_batch, COMPLIANT_HISTORY, {}, compliant_rows), _compliant_diagnostics,
    line=dict(color="tab:blue", ls="-", lw=2.6, zorder=2), marker=dict(marker="o", ms=8, mfc="none", mew=1.8),
    spatial=compliant_spatial_history))
register(Model(
    "stick_slip", "Stick-Slip",
    PlanarKernels(stick_slip_case, stick_slip_batch, STICK_SLIP_HISTORY,
                  {"sticking_rotation_max": STICK_TURN_MAX, "rise_stick_max": RISE_STICK_MAX}, stick_slip_rows),
    _stick_slip_diagnostics, stages={"_stick": " at the end of the sticking phase"},
    summaries={"sticking_rotation_max": ("degree", "largest pad rotation within a sticking phase, "
                                                   "|theta2_stick - theta2(t_n-1)|"),
               "rise_stick_max": ("m", "largest rise of RB3 at the end of a sticking phase")},
    line=dict(color="tab:orange", ls=(0, (4, 2)), lw=1.3, zorder=3), marker=dict(marker="D", ms=4.5, mew=0.8),
    spatial=stick_slip_spatial_history))
MODELS = tuple(REGISTRY)


def run(name, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """The whole history of model ``name``: arrays, time first (``compiled.run``: keys, keywords and
    errors), which ``dccss.results`` turns into datasets. The kernels run it, compiled or interpreted
    (``backend``: DCCSS_BACKEND)."""
    model(name)  # a ValueError names the known models
    kernels, compiled = backend.kernels(name, *backend.size(geometry, Xg, theta2_0))
    return kernels.run(name, geometry, Xg, theta2_0, compiled=compiled, **kw)


def compliant(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Compliant sliding history (``run("compliant", ...)``)."""
    return run("compliant", geometry, Xg, theta2_0, **kw)


def stick_slip(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Stick-slip history (``run("stick_slip", ...)``)."""
    return run("stick_slip", geometry, Xg, theta2_0, **kw)
