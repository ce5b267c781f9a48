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

``compliant_steps``/``stick_slip_steps`` yield one typed record per step (``CompliantStep``,
``StickSlipStep``; a sweep summarises them on the fly); ``collect`` stacks them into whole
histories as arrays, time first, which ``dccss.results`` turns into datasets.

The models are data: ``REGISTRY`` holds one ``Model`` per model (name, title, stepper, step
record, the diagnostics its datasets carry and the summaries its sweeps keep). Nothing outside
this module branches on a model's name; adding a model is adding an entry.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, fields

import numpy as np

from . import backend, newton
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


@dataclass(frozen=True)
class Model:
    """A kinematic model as data.

    name, title : identifier (files, configs) and the paper's name.
    steps : the step generator ``steps(geometry, Xg, theta2_0, *, normals, options, times)``.
    record : the type of its step records.
    diagnostics : ``diagnostics(history, geometry) -> {name: (values, units, long_name[, attrs])}``,
        the variables only this model's datasets carry (besides the configuration at the end
        of each step, which every model has).
    stages : the configurations a step stores besides its end (suffix -> long-name phrase).
    summaries : {name: (units, long_name)} of the sweep summaries only this model has, computed
        per step by ``summary(step, previous_theta2_deg, rise_of)`` and reduced by their max.
    iteration_fields : the step fields that count Newton iterations (summed per step).
    line, marker : how plots draw it (matplotlib line and marker properties; empty: a spare style).
    """

    name: str
    title: str
    steps: Callable
    record: type
    diagnostics: Callable
    stages: dict
    summaries: dict
    summary: Callable | None
    iteration_fields: tuple
    line: dict = field(default_factory=dict)
    marker: dict = field(default_factory=dict)

    @property
    def sticking(self) -> bool:
        """Whether its steps have a sticking phase (and store its end, ``stages``)."""
        return bool(self.stages)


REGISTRY = {m.name: m for m in (
    # compliant sliding drawn wide and solid underneath, stick-slip narrow and dashed on top
    Model("compliant", "Compliant Sliding", compliant_steps, CompliantStep, _compliant_diagnostics, {}, {}, None,
          ("newton_iterations",), line=dict(color="tab:blue", ls="-", lw=2.6, zorder=2),
          marker=dict(marker="o", ms=8, mfc="none", mew=1.8)),
    Model("stick_slip", "Stick-Slip", stick_slip_steps, StickSlipStep, _stick_slip_diagnostics,
          {"_stick": " at the end of the sticking phase"},
          {"sticking_rotation_max": ("degree", "largest pad rotation within a sticking phase, "
                                               "|theta2_stick - theta2(t_n-1)|"),
           "rise_stick_max": ("m", "largest rise of RB3 at the end of a sticking phase")},
          _stick_slip_summary, ("newton_iterations", "newton_iterations_stick"),
          line=dict(color="tab:orange", ls=(0, (4, 2)), lw=1.3, zorder=3), marker=dict(marker="D", ms=4.5, mew=0.8)),
)}
MODELS = tuple(REGISTRY)


def model(name) -> Model:
    """The registry entry of ``name``; a ValueError names the known models."""
    if name not in REGISTRY:
        raise ValueError(f"model must be one of {MODELS}, got {name!r}")
    return REGISTRY[name]


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
