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
The functions return plain arrays, time first; ``dccss.results`` turns them into datasets.
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
    # one case runs on Python scalars (fast); a batch on arrays
    steps = Xg.tolist() if not shape else Xg
    return np.broadcast_to(q0, shape + (9,)), shape, steps


def _context(n, times, phase):
    ctx = {"step": n, "phase": phase}
    if times is not None:
        ctx["time"] = float(times[n])
    return ctx


def compliant(geometry, Xg, theta2_0=0.0, *, normals="signed", options=newton.NewtonOptions(),
              times=None) -> dict:
    """Compliant sliding history for the imposed X_g at the step times.

    Returns a dict of arrays: ``q`` (T, ..., 9); ``point``, ``normal`` (T, ..., 4) complex, the
    contact data of the step ending at t_n (entry 0: that of q(t_0), for |C_q| at rest);
    ``newton_iterations``, ``residual`` (T, ...); ``Rx3`` the guided abscissa of RB3.
    """
    q0, shape, Xg = _start(geometry, Xg, theta2_0)
    T = len(Xg)
    Rx3 = q0[..., RB3] if shape else float(q0[RB3])
    corners = all_corners(geometry)
    q = np.empty((T,) + shape + (9,))
    point = np.empty((T,) + shape + (4,), dtype=complex)
    normal = np.empty_like(point)
    iterations = np.zeros((T,) + shape, dtype=np.int32)
    residual = np.zeros((T,) + shape)
    q[0] = q0
    for n in range(T):
        F = frames(q[max(n - 1, 0)])
        data = [contact_point(F, c, normals) for c in corners]
        for i, (p, nn) in enumerate(data):
            point[n, ..., i], normal[n, ..., i] = p, nn
        if n == 0:
            continue
        cset = Compliant(corners, Xg[n], Rx3, *zip(*data))
        guess = 2 * q[n - 1] - q[n - 2] if n > 1 else q[n - 1]  # linear predictor
        result = newton.solve(cset, guess, options, _context(n, times, cset.phase))
        q[n], iterations[n], residual[n] = result.q, result.iterations, result.residual
    return {"q": q, "point": point, "normal": normal, "newton_iterations": iterations,
            "residual": residual, "Rx3": Rx3}


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


def stick_slip(geometry, Xg, theta2_0=0.0, *, normals="signed", options=newton.NewtonOptions(),
               times=None) -> dict:
    """Stick-slip history for the imposed X_g at the step times.

    Returns a dict of arrays: ``q`` (T, ..., 9) at the end of each step (after slipping),
    ``q_stick`` (T, ..., 9) at the end of its sticking phase (NaN at n = 0), ``diagonal_BC``
    (T, ...) True where B-C jammed, ``newton_iterations(_stick)`` and ``residual(_stick)``.
    """
    q0, shape, Xg = _start(geometry, Xg, theta2_0)
    T = len(Xg)
    Rx3 = q0[..., RB3] if shape else float(q0[RB3])
    q = np.empty((T,) + shape + (9,))
    q_stick = np.full_like(q, np.nan)
    bc = np.zeros((T,) + shape, dtype=bool)
    its = {p: np.zeros((T,) + shape, dtype=np.int32) for p in ("stick", "slip")}
    res = {p: np.zeros((T,) + shape) for p in ("stick", "slip")}
    fixed = {d: diagonal(geometry, d == "BC") for d in ("AD", "BC")}
    q[0] = q0
    for n in range(1, T):
        down = Xg[n] < Xg[n - 1]
        bc[n] = down
        corners = (fixed["BC"] if down else fixed["AD"]) if not shape else diagonal(geometry, down)
        F = frames(q[n - 1])
        stick = Sticking(corners, Xg[n], Rx3, [local(F, c) for c in corners])
        # predictors: the previous step's sticking and slipping increments, if on the same diagonal
        same = (bc[n] == bc[n - 1])[..., None] if n > 1 else False
        guess = np.where(same, q[n - 1] + q_stick[n - 1] - q[n - 2], q[n - 1]) if shape else (
            q[n - 1] + q_stick[n - 1] - q[n - 2] if same else q[n - 1])
        r1 = newton.solve(stick, guess, options, _context(n, times, stick.phase))
        slip = slip_set(geometry, corners, r1.q, normals)
        guess = np.where(same, r1.q + q[n - 1] - q_stick[n - 1], r1.q) if shape else (
            r1.q + q[n - 1] - q_stick[n - 1] if same else r1.q)
        r2 = newton.solve(slip, guess, options, _context(n, times, slip.phase))
        q_stick[n], q[n] = r1.q, r2.q
        its["stick"][n], its["slip"][n] = r1.iterations, r2.iterations
        res["stick"][n], res["slip"][n] = r1.residual, r2.residual
    return {"q": q, "q_stick": q_stick, "diagonal_BC": bc,
            "newton_iterations_stick": its["stick"], "newton_iterations": its["slip"],
            "residual_stick": res["stick"], "residual": res["slip"], "Rx3": Rx3}


def run(model, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    """Dispatch to ``compliant`` or ``stick_slip`` by name."""
    if model not in MODELS:
        raise ValueError(f"model must be one of {MODELS}, got {model!r}")
    return (compliant if model == "compliant" else stick_slip)(geometry, Xg, theta2_0, **kw)
