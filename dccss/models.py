"""The two kinematic models as time steppers, for one case or a batch of cases.

Each step t_{n-1} -> t_n starts from the converged q(t_{n-1}) and

* ``compliant``: projects the four corners radially onto their concave circles (the previous
  contact points of Eqs. 6-11) and solves Eq. 5 with X_g(t_n);
* ``stick_slip``: chooses the jammed diagonal by the sign of dX_g (A-D for dX_g >= 0, B-C
  otherwise), pins its corners where they are (Eq. 31) and solves; then projects them, builds
  C^1C^3 and Eq. 41 from the end of sticking and solves the slip set (Eq. 37). A step is
  committed only after both phases converge.

Both start from the compatible configuration at theta^2(t_0) (RB3 offset by L sin theta^2).
X_g is (T,) for one case or (T, ...) for a batch; geometry and theta^2(t_0) may be batches too.

``compliant_steps``/``stick_slip_steps`` yield one dict per step (a sweep summarises them on
the fly); ``compliant``/``stick_slip`` collect whole histories as arrays, time first, which
``dccss.results`` turns into datasets.
"""

from __future__ import annotations

import numpy as np

from . import newton
from .constraints import Compliant, Slipping, Sticking, diagonal
from .kinematics import RB3, all_corners, circle_centre, contact_point, dot, frames, local

MODELS = ("compliant", "stick_slip")


def _start(geometry, Xg, theta2_0):
    Xg = np.asarray(Xg, dtype=float)
    if Xg.ndim < 1 or Xg.shape[0] < 2:
        raise ValueError(f"Xg must hold at least two step values along its first axis, got shape {Xg.shape}")
    q0 = geometry.compatible(theta2_0, Xg[0])
    shape = np.broadcast_shapes(q0.shape[:-1], Xg.shape[1:])
    T = Xg.shape[0]
    Xg = np.broadcast_to(Xg.reshape((T,) + (1,) * (len(shape) + 1 - Xg.ndim) + Xg.shape[1:]), (T,) + shape)
    q0 = np.broadcast_to(q0, shape + (9,))
    # one case runs on Python scalars (fast); a batch on arrays
    if not shape:
        return q0, Xg.tolist(), float(q0[RB3])
    return q0, Xg, q0[..., RB3]


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


def _context(n, times, phase):
    ctx = {"step": n, "phase": phase}
    if times is not None:
        ctx["time"] = float(times[n])
    return ctx


def compliant_steps(geometry, Xg, theta2_0=0.0, *, normals="signed", options=newton.NewtonOptions(),
                    times=None):
    """Yield, for n = 0..T-1, {"n", "q", "local", "point", "normal", "newton_iterations",
    "residual"}: the configuration at t_n, the plate-frame positions of A..D there, and the
    contact data (plate-frame points and normals of A..D, complex) of the step that ends there;
    at n = 0 those of q(t_0) itself (for |C_q| at rest)."""
    q, Xg, Rx3 = _start(geometry, Xg, theta2_0)
    corners = all_corners(geometry)
    F = frames(q)
    locals_ = [local(F, c) for c in corners]
    points, normals_ = zip(*(contact_point(F, c, normals, u) for c, u in zip(corners, locals_)))
    yield {"n": 0, "q": q, "local": locals_, "point": points, "normal": normals_, "newton_iterations": 0,
           "residual": 0.0}
    history = [q]  # the last converged configurations, newest last, for the predictor
    for n in range(1, len(Xg)):
        cset = Compliant(corners, Xg[n], Rx3, points, normals_)
        result = newton.solve(cset, _extrapolate(history), options, _context(n, times, cset.phase))
        step = {"n": n, "q": _wrapped(result.q), "point": points, "normal": normals_,
                "newton_iterations": result.iterations, "residual": result.residual}
        q = step["q"]
        history = history[-3:] + [q]
        F = frames(q)  # the next step's contact data
        locals_ = [local(F, c) for c in corners]
        points, normals_ = zip(*(contact_point(F, c, normals, u) for c, u in zip(corners, locals_)))
        yield step | {"local": locals_}


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
    q, Xg, Rx3 = _start(geometry, Xg, theta2_0)
    batch = np.ndim(Xg) > 1
    fixed = {False: diagonal(geometry, False), True: diagonal(geometry, True)}
    yield {"n": 0, "q": q, "q_stick": np.full_like(q, np.nan), "diagonal_BC": np.zeros(np.shape(q)[:-1], bool),
           "newton_iterations_stick": 0, "newton_iterations": 0, "residual_stick": 0.0, "residual": 0.0}
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
        r1 = newton.solve(stick, stick_guess, options, _context(n, times, stick.phase))
        q_stick = _wrapped(r1.q)
        slip = slip_set(geometry, corners, q_stick, normals)
        slip_guess = q_stick if previous is None else (
            np.where(same, q_stick + q - previous[1], q_stick) if batch else
            (q_stick + q - previous[1] if same else q_stick))
        r2 = newton.solve(slip, slip_guess, options, _context(n, times, slip.phase))
        previous = (q, q_stick, down)
        q = _wrapped(r2.q)
        yield {"n": n, "q": q, "q_stick": q_stick, "diagonal_BC": down,
               "newton_iterations_stick": r1.iterations, "newton_iterations": r2.iterations,
               "residual_stick": r1.residual, "residual": r2.residual}


def _collect(steps, complex_keys=()) -> dict:
    """Stack the per-step dicts into arrays, time first (contact data: last axis of 4)."""
    rows = list(steps)
    out = {}
    one_case = np.ndim(rows[-1]["q"]) == 1
    for key in rows[0]:
        if key == "n":
            continue
        values = [r[key] for r in rows]
        if one_case:  # scalars, (9,) arrays or 4-tuples: one call
            out[key] = np.array(values)
            continue
        if key in complex_keys:
            values = [np.stack(np.broadcast_arrays(*v), axis=-1) for v in values]
        shape = np.shape(values[-1])  # step 0 may hold scalars where later steps hold batch arrays
        out[key] = np.stack([np.broadcast_to(v, shape) for v in values])
    return out


def collect(steps) -> dict:
    """A history from per-step dicts (of ``compliant_steps`` or ``stick_slip_steps``), plus ``Rx3``."""
    out = _collect(steps, complex_keys=("point", "normal", "local"))
    out["Rx3"] = out["q"][0, ..., RB3]
    return out


def compliant(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Compliant sliding history: arrays ``q`` (T, ..., 9); ``point``, ``normal`` (T, ..., 4)
    complex; ``newton_iterations``, ``residual`` (T, ...); ``Rx3`` the guided abscissa of RB3.
    Keywords as for ``compliant_steps``."""
    return collect(compliant_steps(geometry, Xg, theta2_0, **kw))


def stick_slip(geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Stick-slip history: arrays ``q``, ``q_stick`` (T, ..., 9), ``diagonal_BC``,
    ``newton_iterations(_stick)``, ``residual(_stick)`` (T, ...) and ``Rx3``.
    Keywords as for ``stick_slip_steps``."""
    return collect(stick_slip_steps(geometry, Xg, theta2_0, **kw))


def run(model, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Dispatch to ``compliant`` or ``stick_slip`` by name."""
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}, got {model!r}")
    return (compliant if model == "compliant" else stick_slip)(geometry, Xg, theta2_0, **kw)


def steps(model, geometry, Xg, theta2_0=0.0, **kw):
    """Dispatch to ``compliant_steps`` or ``stick_slip_steps`` by name."""
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}, got {model!r}")
    return (compliant_steps if model == "compliant" else stick_slip_steps)(geometry, Xg, theta2_0, **kw)
