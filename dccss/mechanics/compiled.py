"""The planar models' kernels: the scalar helpers every model's steps are written with, and the
driver that runs a model's kernels (its registry entry's ``PlanarKernels``; the paper's two are in
``models``) for one case or a batch: compiled with Numba, or the same functions interpreted
(``compiled=False``; small runs), with the same results to the last bit.

The entry points take a model's name and return what the numpy reference of the tests
(``tests/oracle.py``) does:

* ``run``: the histories (same keys, shapes, dtypes; the same ConvergenceError /
  SingularJacobianError messages);
* ``summarize``: the per-case summaries (``dccss.mechanics.summaries``: the same keys, dtypes, NaN
  and flag conventions, capacity policies), reduced on the fly inside the compiled loop: memory
  O(cases), no (T, N, 9) arrays.

The algorithm (the helpers here, the steps in ``models``) is the reference's, row for row: the
same constraint rows (the tests' ``constraint_sets``: the tangency rows of Eqs. 6-11, the pin rows of Eq. 32,
the slip rows of Eq. 37), the prescribed rows set first and Newton on the contact rows over the
free coordinates (``newton``) with the same written-out 4 x 4 solve (``linear.solve4``), the same
test max|g| <= tol and iteration cap, the same predictors (the reference's ``_extrapolate`` cubic
for compliant sliding; the previous sticking and slipping increments of ``stick_slip_steps``), the
same theta2 wrapping, contact projection (signed or unsigned normals), jammed diagonal (A-D, or
B-C when X_g decreases) and slip set built from the end of sticking (``slip_set``).

Layout
------
A run of batch shape S (the broadcast of the geometry fields, X_g[1:] and theta2(t_0)) is
flattened to N = prod(S) cases, indexed k, and the cases run in parallel (``prange``), each
through all its steps. The inputs, per case (``_Batch``):

* ``q0[k]`` (9,): the compatible start of ``kinematics.start``;
* ``pad[k]`` (4,) complex: the pad-frame positions u^2 of the corners A, B, C, D;
* ``centre[k]`` (2,) complex, ``radius[k]`` (2,): the concave circles of RB1 and RB3 in their
  plate frames (C^1, R^1; C^3, R^3);
* ``dims[k]`` (5,): L, h_s^3, the theta2 = 0 rest ordinate of RB3 (Eq. 41) and the ring
  abscissae R^1 sin(alpha^1), R^3 sin(alpha^3);
* ``Xg[n, k]`` (T, N), or (T, 1) when all cases share the ground motion.

Inside a case the state is held in tuples, not arrays (no allocation or reference counting in
the loop): a configuration q is a 9-tuple ordered as Eq. 4, [R_x^1, R_y^1, theta^1, R_x^2,
R_y^2, theta^2, R_x^3, R_y^3, theta^3]; its frames F = (R^1, e^1, R^2, e^2, R^3, e^3) hold each
body's position and e^{i theta} as complex numbers (``kinematics.frames``: points and vectors
of the plane are x + iy). A constraint set is ``cset`` = (u2, points, normals, n12, k1, k3): the
corners of its rows, their plate-frame contact points and normals (the pinned points when
sticking) and, when slipping, the unit normal to C^1C^3 and k_1, k_3 (Eqs. 38, 39). The contact
rows g (4-tuple) and their Jacobian J (4 x 4) are on the free coordinates (R_x^2, R_y^2,
theta^2, R_y^3), or (R_x^2, R_y^2, theta^2, R_x^3) when slipping, in the reference's order.

The outputs: histories in (T, N, ...) arrays; summaries in ``acc`` (N, 14) floats and
``count`` (N, 4) integers (columns named below); per case a failure to raise, ``fail`` (N, 4)
[step, phase, iteration, status] with its residual and Jacobian, and the steps done. The
Python side raises the error of the first failure the reference would meet (it steps all
cases together), with the reference's message builders.

Failed cases follow the reference's two paths: the one-case path (geometry, X_g[1:] and
theta2(t_0) all scalars; also a batch of one in ``summarize``) and the batch path differ in
what a failed case reports afterwards (``solve``).

The kernels compile on first use and are cached on disk (``scalar.kernel``: a folder named by a
digest of the mechanics' sources); other processes load them from there.
"""

from __future__ import annotations

import math
from dataclasses import fields

import numpy as np

from . import linear, newton, registry, scalar
from .capacity import CAPACITY_POLICIES, case_error, mark_failures
from .geometry import Geometry
from .kinematics import CORNERS, NORMALS, RB3, all_corners, start
from .newton import NewtonOptions
from .scalar import compilable, jit, max_abs

compilable(*linear.SCALAR)
solve4 = linear.solve4

# --- names ---------------------------------------------------------------------------------
CORNER_A, CORNER_B, CORNER_C, CORNER_D = 0, 1, 2, 3
#: -1 for the left corners A, C; +1 for the right corners B, D
SIDE = (-1.0, 1.0, -1.0, 1.0)
#: the constraint sets (a failure's phase is 0 for compliant sliding and sticking, 1 for slipping)
COMPLIANT, STICKING, SLIPPING = 0, 1, 2
#: Newton outcomes; FAILED: a case marked failed (NaN) that goes on
CONVERGED, NOT_CONVERGED, SINGULAR, FAILED = 0, 1, 2, 3
#: columns of ``dims``
L_, HS3, REST, RING1, RING3 = range(5)
#: columns of the summary accumulators ``acc`` (floats; I_A .. I_D at 2 .. 5; STOPPED is 1.0
#: once a capacity policy other than "continue" froze the summaries) and ``count`` (integers)
THETA2_MAX_ABS, RISE_MAX, I_A_MAX, CLEARANCE_MIN, THETA2_END, RISE_END = 0, 1, 2, 6, 7, 8
STICK_TURN_MAX, RISE_STICK_MAX, FAILURE, REACHED, STOPPED = 9, 10, 11, 12, 13
N_ACC = 14
ITERATIONS_MAX, ITERATIONS_SUM, STEPS, REACHED_STEP = 0, 1, 2, 3
N_COUNT = 4
#: capacity policies of a summary, in the order of ``simulation.CAPACITY_POLICIES``
CONTINUE, STOP, ERROR = 0, 1, 2

DEGREES = 180.0 / np.pi  # numpy's degrees(x) is x * (180 / pi)
TWO_PI = 2 * np.pi
NAN = np.nan



# --- configurations as 9-tuples (Eq. 4) ----------------------------------------------------
@jit
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4], a[5] + b[5], a[6] + b[6],
            a[7] + b[7], a[8] + b[8])


@jit
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3], a[4] - b[4], a[5] - b[5], a[6] - b[6],
            a[7] - b[7], a[8] - b[8])


@jit
def _scale(w, a):
    return (w * a[0], w * a[1], w * a[2], w * a[3], w * a[4], w * a[5], w * a[6], w * a[7], w * a[8])


@jit
def _has_nan(q):
    for v in q:
        if v != v:
            return True
    return False


NAN9 = (NAN,) * 9
NAN_ACC = (NAN,) * N_ACC


@jit
def wrapped(q, F):
    """q with theta2 in (-pi, pi] (the reference's ``_wrapped``) and its frames ``F``."""
    if abs(q[5]) <= np.pi:
        return q, F
    theta2 = q[5] - TWO_PI * np.rint(q[5] / TWO_PI)
    q = (q[0], q[1], q[2], q[3], q[4], theta2, q[6], q[7], q[8])
    return q, frames(q)


@jit
def extrapolate(h0, h1, h2, h3, count):
    """The cubic through the last ``count`` converged configurations h0..h3 (newest last;
    lower orders at the start): the reference's ``_extrapolate``, same weights and order of sums."""
    if count == 1:
        return h3
    if count == 2:
        return add(_scale(-1.0, h2), _scale(2.0, h3))
    if count == 3:
        return add(add(h1, _scale(-3.0, h2)), _scale(3.0, h3))
    return add(add(add(_scale(-1.0, h0), _scale(4.0, h1)), _scale(-6.0, h2)), _scale(4.0, h3))


# --- planar kinematics (kinematics.py) -----------------------------------------------------
@jit
def _expi(theta):
    """e^{i theta}; exactly 1 for an unrotated body (the plates, in every set)."""
    if theta == 0.0:
        return 1.0 + 0.0j
    return complex(math.cos(theta), math.sin(theta))


@jit
def _is_unit(e):
    return e.real == 1.0 and e.imag == 0.0


@jit
def _turn(e, z):
    """e z, skipping the product for e = 1 (``kinematics.turn``)."""
    return z if _is_unit(e) else e * z


@jit
def _dot(a, b):
    """Scalar product of planar vectors, Re(a conj(b))."""
    return a.real * b.real + a.imag * b.imag


@jit
def _perp(z):
    """1j z: z turned by +90 degrees."""
    return complex(-z.imag, z.real)


@jit
def frames(q):
    """R^1, e^1, R^2, e^2, R^3, e^3 of a configuration (``kinematics.frames``)."""
    return (complex(q[0], q[1]), _expi(q[2]), complex(q[3], q[4]), _expi(q[5]),
            complex(q[6], q[7]), _expi(q[8]))


@jit
def local(R2, e2, u2, Rj, ej):
    """A pad corner's position in its plate's frame (``kinematics.local``)."""
    d = R2 + e2 * u2 - Rj
    return d if _is_unit(ej) else d * ej.conjugate()


@jit
def plate_positions(F, pad):
    """Plate-frame positions of A, B (on RB1) and C, D (on RB3); F = frames(q)."""
    R1, e1, R2, e2, R3, e3 = F
    return (local(R2, e2, pad[0], R1, e1), local(R2, e2, pad[1], R1, e1),
            local(R2, e2, pad[2], R3, e3), local(R2, e2, pad[3], R3, e3))


@jit
def _contact(u, centre, radius, side, signed):
    """Radial projection of a corner (plate frame ``u``) onto its concave circle (the tests'
    ``constraint_sets.contact_point``): the contact point, the unit normal towards the centre (from
    |alpha| if not ``signed``) and the corner's distance to the centre."""
    d = u - centre
    a = abs(d)
    n = complex(-d.real / a, -d.imag / a)
    point = centre - radius * n
    if not signed:
        n = complex(-side * abs(n.real), n.imag)
    return point, n, a


@jit
def contacts(u, centre, radius, signed):
    """Contact points, normals and centre distances of A, B, C, D."""
    pA, nA, aA = _contact(u[0], centre[0], radius[0], SIDE[0], signed)
    pB, nB, aB = _contact(u[1], centre[0], radius[0], SIDE[1], signed)
    pC, nC, aC = _contact(u[2], centre[1], radius[1], SIDE[2], signed)
    pD, nD, aD = _contact(u[3], centre[1], radius[1], SIDE[3], signed)
    return (pA, pB, pC, pD), (nA, nB, nC, nD), (aA, aB, aC, aD)


# --- constraint rows (the tests' constraint_sets.py) -----------------------------------------
@jit
def _tangent(R2, e2, Rj, ej, u2, point, normal):
    """Tangency row (r_P^2 - r_P^j) . n_P^j (Eqs. 6-11): g, the global normal n and
    dg/dtheta^2 (Eqs. 17-28); dg/dR^2 = n, dg/dR^j = -n."""
    arm = e2 * u2
    n = _turn(ej, normal)
    lever = R2 + arm - Rj
    return _dot(lever - _turn(ej, point), n), n, _dot(_perp(arm), n)


@jit
def _pin(R2, e2, Rj, ej, u2, point):
    """Pin rows r_P^2 - r_P^j (Eq. 32) as a complex number h (x row, y row) and the
    dh/dtheta^2 column (Eqs. 33-36); dh/dR^2 = 1, dh/dR^j = -1."""
    arm = _perp(e2) * u2
    pin = _perp(_turn(ej, point))
    h = R2 - _perp(arm) - Rj + _perp(pin)
    return h, arm


@jit
def _rows(kind, F, cset):
    """Contact rows g (4-tuple) and their Jacobian J (4 rows) on the free coordinates, at the
    configuration whose frames are F (``frames``).

    ``cset`` = (u2, points, normals, n12, k1, k3): the corners of the rows (pad frame), their
    contact points and normals (plate frames; the pinned points when sticking) and, when
    slipping, the unit normal to C^1C^3 and k_1, k_3.

    COMPLIANT (Eq. 5): A, B, C, D on their tangents; free (R_x^2, R_y^2, theta^2, R_y^3).
    STICKING (Eq. 31): the diagonal's corners u2[0] (on RB1) and u2[1] (on RB3) pinned; same free.
    SLIPPING (Eq. 37): u2[0], u2[1] on their tangents, G^2 on C^1C^3, RB3 along C^1C^3; free
    (R_x^2, R_y^2, theta^2, R_x^3).
    """
    u2, points, normals, n12, k1, k3 = cset
    R1, e1, R2, e2, R3, e3 = F
    if kind == STICKING:
        h1, arm1 = _pin(R2, e2, R1, e1, u2[0], points[0])
        h3, arm3 = _pin(R2, e2, R3, e3, u2[1], points[1])
        return (h1.real, h1.imag, h3.real, h3.imag), ((1.0, 0.0, arm1.real, 0.0), (0.0, 1.0, arm1.imag, 0.0),
                                                      (1.0, 0.0, arm3.real, 0.0), (0.0, 1.0, arm3.imag, -1.0))
    gA, nA, tA = _tangent(R2, e2, R1, e1, u2[0], points[0], normals[0])
    if kind == SLIPPING:
        gD, nD, tD = _tangent(R2, e2, R3, e3, u2[1], points[1], normals[1])
        return (gA, gD, _dot(R2, n12) - k1, _dot(R3, n12) - k3), (
            (nA.real, nA.imag, tA, 0.0), (nD.real, nD.imag, tD, -nD.real),
            (n12.real, n12.imag, 0.0, 0.0), (0.0, 0.0, 0.0, n12.real))
    gB, nB, tB = _tangent(R2, e2, R1, e1, u2[1], points[1], normals[1])
    gC, nC, tC = _tangent(R2, e2, R3, e3, u2[2], points[2], normals[2])
    gD, nD, tD = _tangent(R2, e2, R3, e3, u2[3], points[3], normals[3])
    return (gA, gB, gC, gD), ((nA.real, nA.imag, tA, 0.0), (nB.real, nB.imag, tB, 0.0),
                              (nC.real, nC.imag, tC, -nC.imag), (nD.real, nD.imag, tD, -nD.imag))


# --- Newton-Raphson (newton.py) ------------------------------------------------------------
@jit
def _step(kind, q, dq):
    """q - dq on the free coordinates: R_x^2, R_y^2, theta^2 and R_x^3 (slipping) or R_y^3."""
    if kind == SLIPPING:
        return (q[0], q[1], q[2], q[3] - dq[0], q[4] - dq[1], q[5] - dq[2], q[6] - dq[3], q[7], q[8])
    return (q[0], q[1], q[2], q[3] - dq[0], q[4] - dq[1], q[5] - dq[2], q[6], q[7] - dq[3], q[8])


@jit
def _newton(kind, q, cset, tol, max_iter):
    """Newton-Raphson on the contact rows from q (prescribed coordinates set). Returns
    (status, updates taken, max|g| at the last evaluation, q, g, J, frames of q)."""
    F = frames(q)
    g, J = _rows(kind, F, cset)
    it = 0
    while True:
        norm = max_abs(g)
        if norm <= tol:
            return CONVERGED, it, norm, q, g, J, F
        if it == max_iter:
            return NOT_CONVERGED, it, norm, q, g, J, F
        ok, dq = solve4(J, g)
        if not ok:
            return SINGULAR, it, norm, q, g, J, F
        q = _step(kind, q, dq)
        it += 1
        F = frames(q)
        g, J = _rows(kind, F, cset)


@jit
def solve(kind, q, cset, tol, max_iter, mark, one_case):
    """``newton.solve`` on one case, with the reference's bookkeeping of failed cases.

    A case that failed earlier (NaN in q) is not solved: the batch path reports 0 updates and
    keeps q (its prescribed values set), the one-case path iterates NaN to the cap. With
    ``mark`` a failure makes q NaN and returns FAILED with the path's counts; otherwise (and
    for a singular Jacobian on the one-case path, which raises under both policies) the
    status is returned for the caller to raise. Returns (status, updates, residual, q, g, J,
    frames of q).
    """
    if _has_nan(q):
        if one_case:
            q = NAN9
        F = frames(q)
        g, J = _rows(kind, F, cset)
        return FAILED, max_iter if one_case else 0, NAN, q, g, J, F
    status, its, norm, q, g, J, F = _newton(kind, q, cset, tol, max_iter)
    if status == CONVERGED or not mark or (one_case and status == SINGULAR):
        return status, its, norm, q, g, J, F
    if one_case:
        its, norm = max_iter, NAN
    elif status == SINGULAR:
        norm = NAN
    else:
        its = max_iter
    return FAILED, its, norm, NAN9, g, J, frames(NAN9)


@jit
def fatal(status):
    return status == NOT_CONVERGED or status == SINGULAR


@jit
def record_failure(fail, fail_g, fail_J, k, n, phase, its, status, g, J):
    fail[k, 0], fail[k, 1], fail[k, 2], fail[k, 3] = n, phase, its, status
    for i in range(4):
        fail_g[k, i] = g[i]
        for j in range(4):
            fail_J[k, i, j] = J[i][j]


# --- the sets of a step (models.py) --------------------------------------------------------
@jit
def slip_set(F, pad, centre, radius, dims, c1, c3, signed):
    """The slip set (the reference's ``slip_set``) of the diagonal c1 (on RB1), c3 (on RB3) from the
    end of sticking (frames F): the set's data and R_y^3 of Eq. 41."""
    R1, e1, R2, e2, R3, e3 = F
    p1, n1, _ = _contact(local(R2, e2, pad[c1], R1, e1), centre[0], radius[0], SIDE[c1], signed)
    p3, n3, _ = _contact(local(R2, e2, pad[c3], R3, e3), centre[1], radius[1], SIDE[c3], signed)
    C1 = R1 + _turn(e1, centre[0])
    C3 = R3 + _turn(e3, centre[1])
    d = C3 - C1
    a = abs(d)
    e = complex(d.real / a, d.imag / a)
    n12 = _perp(e)
    cos_theta = -e.imag  # C^3 lies below C^1: e = (sin theta, -cos theta)
    Ry3_rc = C1.imag - dims[L_] * cos_theta + dims[HS3] + radius[1]  # Eq. 41
    cset = ((pad[c1], pad[c3], 0j, 0j), (p1, p3, 0j, 0j), (n1, n3, 0j, 0j), n12, _dot(C1, n12), _dot(R3, n12))
    return cset, Ry3_rc


# --- summaries (summaries.py) ------------------------------------------------------------------
@jit
def _fmax(a, b):
    if b != b:
        return a
    if a != a:
        return b
    return a if a >= b else b


@jit
def _fmin(a, b):
    if b != b:
        return a
    if a != a:
        return b
    return a if a <= b else b


@jit
def _nanmax(a, b):
    """np.maximum: NaN if either is."""
    if a != a or b != b:
        return NAN
    return a if a >= b else b


@jit
def _nanmin(a, b):
    if a != a or b != b:
        return NAN
    return a if a <= b else b


@jit
def summarise_step(acc, count, n, now, q, u, distance, radius, dims, its, capacity):
    """A case's summaries ``acc`` (N_ACC floats), ``count`` (N_COUNT integers) with step n folded in
    (configuration q, corner positions u and their distances to the circle centres): the new
    (acc, count). The stick-slip entries are folded by the caller. Once the pad has reached a ring
    under a capacity policy other than "continue" the summaries stay as they were at that step.
    (Tuples, not arrays: no reference counting in the step loop.)"""
    (theta2_max, rise_max, i_a, i_b, i_c, i_d, clearance, theta2_end, rise_end, stick_turn, rise_stick, failure,
     reached, stopped) = acc
    if stopped == 1.0:
        return acc, count
    if failure != failure and _has_nan(q):
        failure = now
    theta2 = q[5] * DEGREES
    rise = q[7] - dims[REST]
    reach1 = _nanmax(abs(u[0].real), abs(u[1].real))
    reach3 = _nanmax(abs(u[2].real), abs(u[3].real))
    gap = _nanmin(dims[RING1] - reach1, dims[RING3] - reach3)
    iterations_max, iterations_sum, _, reached_step = count
    if reached != reached and gap < 0:
        reached, reached_step = now, n
        if capacity != CONTINUE:
            stopped = 1.0
    return ((_fmax(theta2_max, abs(theta2)), _fmax(rise_max, rise), _fmax(i_a, distance[0] - radius[0]),
             _fmax(i_b, distance[1] - radius[0]), _fmax(i_c, distance[2] - radius[1]),
             _fmax(i_d, distance[3] - radius[1]), _fmin(clearance, gap), theta2, rise, stick_turn, rise_stick,
             failure, reached, stopped),
            (max(iterations_max, its), iterations_sum + its, n, reached_step))


@jit
def summarise_stick(acc, q_stick, theta2_previous, dims):
    """``acc`` with the stick-slip entries folded in: the rotation within the sticking phase and RB3's
    rise at its end."""
    if acc[STOPPED] == 1.0:
        return acc
    return (acc[0], acc[1], acc[2], acc[3], acc[4], acc[5], acc[6], acc[7], acc[8],
            _fmax(acc[STICK_TURN_MAX], abs(q_stick[5] * DEGREES - theta2_previous)),
            _fmax(acc[RISE_STICK_MAX], q_stick[7] - dims[REST]), acc[11], acc[12], acc[13])


@jit
def beyond_ring(u, dims):
    """The pad has passed a retaining ring (a clearance < 0, as ``simulation.simulate``)."""
    gap1 = dims[RING1] - _nanmax(abs(u[0].real), abs(u[1].real))
    gap3 = dims[RING3] - _nanmax(abs(u[2].real), abs(u[3].real))
    return gap1 < 0 or gap3 < 0


@jit
def distances(u, centre):
    return (abs(u[0] - centre[0]), abs(u[1] - centre[0]), abs(u[2] - centre[1]), abs(u[3] - centre[1]))


# --- what every model's case kernel starts and ends with --------------------------------------
@jit
def case_constants(k, pad, centre, radius, dims):
    """Case k's geometry as tuples (module docstring)."""
    return ((pad[k, 0], pad[k, 1], pad[k, 2], pad[k, 3]), (centre[k, 0], centre[k, 1]),
            (radius[k, 0], radius[k, 1]), (dims[k, 0], dims[k, 1], dims[k, 2], dims[k, 3], dims[k, 4]))


@jit
def configuration(q0):
    """A start q0 (9,) as the 9-tuple the kernels step."""
    return (q0[0], q0[1], q0[2], q0[3], q0[4], q0[5], q0[6], q0[7], q0[8])


@jit
def case_summaries(k, acc_all, count_all):
    """Case k's summaries as the tuples ``summarise_step`` folds, and whether the run keeps summaries:
    (acc, count, summarise)."""
    if acc_all.shape[0] > 0:
        a, c = acc_all[k], count_all[k]
        return ((a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11], a[12], a[13]),
                (c[0], c[1], c[2], c[3]), True)
    return NAN_ACC, (0, 0, 0, -1), False


@jit
def keep_summaries(k, acc_all, count_all, acc, count):
    """Write case k's summaries back (nothing where the run keeps no summaries)."""
    if acc_all.shape[0] > 0:
        for i in range(N_ACC):
            acc_all[k, i] = acc[i]
        for i in range(N_COUNT):
            count_all[k, i] = count[i]


# --- Python entry points -------------------------------------------------------------------
class _Batch:
    """The flattened per-case inputs of a run and its status (see the module docstring)."""

    def __init__(self, geometry, Xg, theta2_0):
        q0, _, _ = start(geometry, Xg, theta2_0)  # the reference's checks and start
        self.shape = shape = q0.shape[:-1]
        self.one_case = not shape
        self.N = N = int(np.prod(shape, dtype=np.int64))
        Xg = np.asarray(Xg, dtype=float)
        T = self.T = Xg.shape[0]
        Xg = Xg.reshape((T,) + (1,) * (len(shape) + 1 - Xg.ndim) + Xg.shape[1:])  # as kinematics.start
        if all(d == 1 for d in Xg.shape[1:]):  # one ground motion for all cases
            self.Xg = np.array(Xg.reshape(T, 1), dtype=float, order="C")
        else:
            # a copy, writable as the one above: a read-only view (a case's own record) would compile the
            # batch kernel a second time, for read-only arrays
            self.Xg = np.array(np.broadcast_to(Xg, (T,) + shape).reshape(T, N), dtype=float, order="C")
        self.q0 = np.array(q0.reshape(N, 9), dtype=float, order="C")

        def flat(x, dtype=float):
            return np.array(np.broadcast_to(np.asarray(x, dtype=dtype), shape).reshape(N), order="C")

        corners = all_corners(geometry)
        lower, upper = corners[0], corners[3]
        self.pad = np.stack([flat(c.u2, complex) for c in corners], axis=-1)
        self.centre = np.stack([flat(lower.centre, complex), flat(upper.centre, complex)], axis=-1)
        self.radius = np.stack([flat(lower.radius), flat(upper.radius)], axis=-1)
        ring = geometry.ring_inner_x
        self.dims = np.stack([flat(geometry.L), flat(geometry.hs3), flat(geometry.Ry3_compatible(0.0)),
                              flat(ring[..., 0]), flat(ring[..., 1])], axis=-1)
        # per case: the failure to raise [step, phase, iteration, status] (step -1: none), its
        # contact residual and Jacobian, and the number of steps done
        self.fail = np.full((N, 4), -1, dtype=np.int64)
        self.fail_g = np.zeros((N, 4))
        self.fail_J = np.zeros((N, 4, 4))
        self.done = np.zeros(N, dtype=np.int64)

    def run(self, kernels, options, normals, history_out, summary_out, stop_at_ring=False, compiled=True):
        """Run every case through a model's ``kernels`` (``registry.PlanarKernels``): compiled, in
        parallel, or (``compiled`` False) the same functions interpreted, one case after the other,
        on Python numbers."""
        flags = (normals == "signed", float(options.tol), int(options.max_iter), options.on_failure == "mark",
                 self.one_case, bool(stop_at_ring))
        status_out = (self.fail, self.fail_g, self.fail_J, self.done)
        if not compiled:
            case = kernels.case
            for k in range(self.N):
                constants = (tuple(complex(z) for z in self.pad[k]), tuple(complex(z) for z in self.centre[k]),
                             tuple(float(r) for r in self.radius[k]), tuple(float(d) for d in self.dims[k]))
                xg = self.Xg[:, k if self.Xg.shape[1] > 1 else 0].tolist()
                case(k, xg, self.q0[k].tolist(), constants, flags, history_out, summary_out, status_out)
            return
        import numba  # imported by ``scalar.kernel``

        kernel = scalar.kernel(kernels.batch, parallel=True)
        # dynamic scheduling: cases cost alike, but a core may be shared
        with numba.parallel_chunksize(max(1, self.N // (16 * numba.get_num_threads()))):
            kernel(self.Xg, self.q0, self.pad, self.centre, self.radius, self.dims, flags, history_out,
                   summary_out, status_out)

    def raise_failure(self, kernels, geometry, options, times, history=None):
        """Raise the reference's error for the first failure it would meet, if any.

        The reference steps all cases together: the first (step, phase, iteration) fails; a
        singular Jacobian names the first such case, non-convergence the largest residual.
        ``history`` (one case) is attached to the error, up to the last converged step."""
        failing = np.flatnonzero(self.fail[:, 0] >= 0)
        if failing.size == 0:
            return
        step, phase, its, status = (self.fail[failing, j] for j in range(4))
        when = np.where(status == NOT_CONVERGED, options.max_iter, its)
        first = np.lexsort((when, phase, step))[0]
        tied = failing[(step == step[first]) & (phase == phase[first]) & (when == when[first])]
        n, phase = int(step[first]), int(phase[first])
        if status[first] == SINGULAR:
            k = int(tied.min())
        else:
            norms = np.abs(self.fail_g[tied])
            score = np.where(np.isnan(norms).any(axis=-1), np.inf, norms.max(axis=-1))
            k = int(tied[np.argmax(score)])
        if self.one_case:  # the one-case path names the step's diagonal, the batch path both
            down = bool(self.Xg[n, 0] < self.Xg[n - 1, 0])
        else:
            down = None
        cset = kernels.rows(phase, down)
        context = newton.context(n, times, cset.phase)
        index = () if self.one_case else tuple(int(i) for i in np.unravel_index(k, self.shape))
        try:
            if status[first] == SINGULAR:
                J = self.fail_J[k] if self.one_case else np.broadcast_to(self.fail_J[k], self.shape + (4, 4))
                newton.raise_singular(cset, J, context, index)
            newton.raise_not_converged(cset, self.fail_g[k], options, context, index)
        except newton.ConvergenceError as err:
            if history is not None:
                err.history = history
            raise


def _kernels(model, normals, options):
    """The planar kernels of ``model`` (a ValueError names the registered models), inputs checked."""
    entry = registry.model(model)
    if normals not in NORMALS:
        raise ValueError(f"normals must be one of {NORMALS}, got {normals!r}")
    if not isinstance(options, NewtonOptions):
        raise TypeError(f"options must be a NewtonOptions, got {options!r}")
    return entry.planar


def _no_summary():
    return np.zeros(1), np.zeros((0, N_ACC)), np.zeros((0, N_COUNT), dtype=np.int64), CONTINUE


def _no_history(kernels):
    return tuple(np.empty((0, 0) + shape, dtype) for shape, dtype in kernels.history.values())


def run(model, geometry, Xg, theta2_0=0.0, *, normals="signed", options=NewtonOptions(), times=None,
        stop_at_ring=False, compiled=True) -> dict:
    """The history of ``model`` (``dccss.mechanics.models.run``), as the numpy reference's: the same
    keys, shapes and dtypes (compliant sliding: ``q`` (T, ..., 9); ``newton_iterations``, ``residual``
    (T, ...); ``local``, ``point``, ``normal`` (T, ..., 4) complex; ``Rx3``).

    ``stop_at_ring`` (one case): end the history at the first step where the pad has passed a
    retaining ring, before solving further (``simulation.simulate``'s capacity "stop" and
    "error"). A ConvergenceError of one case carries the history up to the last converged
    step as ``err.history``. ``compiled`` False runs the same functions interpreted (small runs:
    ``backend``), with the same results to the last bit."""
    kernels = _kernels(model, normals, options)
    batch = _Batch(geometry, Xg, theta2_0)
    T, N, shape = batch.T, batch.N, batch.shape
    if stop_at_ring and not batch.one_case:
        raise ValueError("stop_at_ring runs one case: geometry, Xg[1:] and theta2_0 must be scalars")
    arrays = {key: np.empty((T, N) + tail, dtype) for key, (tail, dtype) in kernels.history.items()}
    batch.run(kernels, options, normals, tuple(arrays.values()), _no_summary(), stop_at_ring, compiled)
    steps = int(batch.done.min()) if batch.one_case else T

    def history():
        out = {key: value[:steps].reshape((steps,) + shape + value.shape[2:]) for key, value in arrays.items()}
        out["Rx3"] = out["q"][0, ..., RB3]
        return out

    batch.raise_failure(kernels, geometry, options, times, history() if batch.one_case else None)
    return history()


def summarize(model, geometry, Xg, theta2_0=0.0, *, capacity="continue", progress=None, normals="signed",
              options=NewtonOptions(), times=None, compiled=True) -> dict:
    """The per-case summaries of ``dccss.mechanics.summaries.summarize`` (same keys, dtypes and NaN / flag
    conventions, the same ``capacity`` policies), reduced inside the compiled loop: memory
    O(cases). ``progress(n, N)`` is called once, when all N steps are done; ``compiled`` as for
    ``run``."""

    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    kernels = _kernels(model, normals, options)
    Xg = np.asarray(Xg, dtype=float)
    shape = np.broadcast_shapes(np.shape(geometry.L), Xg.shape[1:], np.shape(theta2_0))
    if shape and np.prod(shape) == 1:  # a batch of one: the one-case path, reshaped back
        one = Geometry(**{f.name: float(np.ravel(getattr(geometry, f.name))[0]) for f in fields(geometry)})
        out = summarize(model, one, Xg.reshape(Xg.shape[0]), float(np.ravel(theta2_0)[0]), capacity=capacity,
                        progress=progress, normals=normals, options=options, times=times, compiled=compiled)
        return {k: np.reshape(v, shape) for k, v in out.items()}
    batch = _Batch(geometry, Xg, theta2_0)
    T, N, shape = batch.T, batch.N, batch.shape
    now = np.array(times if times is not None else np.arange(T), dtype=float, order="C")
    acc = np.full((N, N_ACC), np.nan)
    acc[:, STOPPED] = 0.0
    count = np.zeros((N, N_COUNT), dtype=np.int64)
    count[:, REACHED_STEP] = -1
    # "stop" and "error" end a case at its ring, as its history ends (``run``'s stop_at_ring): it is not
    # stepped beyond it, so a solver failure there is not one
    batch.run(kernels, options, normals, _no_history(kernels), (now, acc, count, CAPACITY_POLICIES.index(capacity)),
              stop_at_ring=capacity != "continue", compiled=compiled)
    if capacity == "error" and options.on_failure != "mark":
        _raise_capacity(batch, acc, count, shape)
    batch.raise_failure(kernels, geometry, options, times)
    if progress is not None:
        progress(T - 1, T - 1)
    with np.errstate(invalid="ignore", divide="ignore"):  # failed cases are NaN by design
        return _summaries(kernels, acc.reshape(shape + (N_ACC,)), count.reshape(shape + (N_COUNT,)), capacity)


def _raise_capacity(batch, acc, count, shape):
    """capacity "error" without "mark": the reference raises at the first step a case reaches
    a ring (the first such case), unless a solver failure comes at or before that step."""

    steps = count[:, REACHED_STEP]
    if (steps < 0).all():
        return
    n = steps[steps >= 0].min()
    failing = batch.fail[:, 0] >= 0
    if failing.any() and batch.fail[failing, 0].min() <= n:
        return  # the solver's error comes first
    k = int(np.flatnonzero(steps == n)[0])
    index = tuple(int(i) for i in np.unravel_index(k, shape)) if shape else ()
    raise case_error(acc[k, REACHED], index)


def _summaries(kernels, acc, count, capacity):
    """The summary dict from the accumulators, as the end of the reference's ``_summarize``."""
    failure, reached = acc[..., FAILURE], acc[..., REACHED]
    out = {"theta2_max_abs": acc[..., THETA2_MAX_ABS], "theta2_end": acc[..., THETA2_END],
           "rise_max": acc[..., RISE_MAX], "rise_end": acc[..., RISE_END],
           "clearance_min": acc[..., CLEARANCE_MIN], "capacity_exceeded": ~np.isnan(reached),
           "newton_iterations_max": np.asarray(count[..., ITERATIONS_MAX], dtype=np.int32),
           "newton_iterations_mean": np.asarray(count[..., ITERATIONS_SUM]) / np.maximum(count[..., STEPS], 1)}
    for i, c in enumerate(CORNERS):
        out[f"I_{c}_max"] = acc[..., I_A_MAX + i]
    for name, column in kernels.summary_columns.items():
        out[name] = acc[..., column]
    return mark_failures(out, failure, reached, capacity)
