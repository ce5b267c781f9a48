"""Bidirectional ground motion: the three bodies in space, both models, one case.

The paper's planar model (``models``) moves RB1 along one line. Under a horizontal ground
displacement X_g(t) in R^2 the pad tilts out of any fixed plane. This module is the
consistent three-dimensional generalisation of both models (the paper's Sec. 4 and Fig. 15
sketch it for one stick-slip step):

* RB1 translates with the ground, R^1 = (X_g,x, X_g,y, 0); RB3 is guided horizontally at its
  start and free to rise (R^3_z free); neither plate rotates. The pad RB2 is a rigid body with
  centre G^2 and rotation matrix Q (pad frame: x', y' across, z' its axis, up).
* Each step t_{n-1} -> t_n has a plane pi: through the sphere centres C^1, C^3 at the start of
  the step and along the ground increment dX_g (its unit vector e1; a zero increment uses the
  reference azimuth of the input). Its normal is m = e1 x (C^1 - C^3) / |...|. The pad's
  section by pi has four rim points, the paper's corners: the lower rim (radius A_1, at -B on
  the axis) and the upper rim (A_3, at +B) each give centre -/+ A u, u = a x m / |a x m| (a the
  pad axis; u is along +e1 when a lies in pi): "-" trails, "+" leads.
* Compliant sliding (Eqs. 6-11 in pi): the four rim points slide on the tangent planes at their
  previous contact points (the radial projections of the rim points at t_{n-1} onto the
  spheres), plus two out-of-plane compatibility rows: the cap centres C^21, C^23 lie on the
  plane through C^1 (resp. C^3) normal to m. Unknowns: G^2, the tilt of the axis (two
  angles; spin about the axis changes nothing for an axisymmetric pad and is not moved) and
  R^3_z. Six rows, six unknowns.
* Stick-slip: sticking pins the trailing lower and the leading upper rim points (the diagonal
  A-D or B-C of the section, Eq. 31) to their plates, with RB3 back on its guide and free to
  rise; the one rotation left, about that diagonal, is closed by the smallest rotation (the
  rotation vector of the phase is normal to the diagonal). Slipping (Eqs. 37-41 in space): RB3
  moves along C^1C^3 to put C^3 at distance L from C^1; the two pinned rim points slide on the
  tangent planes at their projections; G^2 lies on the line C^1C^3 (Eq. 38, in the slip plane
  through C^1C^3 along e1, and across it) with the axis in that plane; no spin.

Along a fixed azimuth every plane pi is the same vertical plane, the out-of-plane rows hold
trivially and both models reduce row for row to the planar ones: |tilt| = |theta^2| and the
rise equal the planar run's to the solver tolerance (tests/test_spatial.py).

Rotations are parametrised per phase as Q = Exp(w_1 k_1 + w_2 k_2) Q_ref, with k_1, k_2
orthonormal and normal to the pad axis (compliant sliding, slipping: no spin) or to the pinned
diagonal (sticking: the smallest rotation). Derivatives of a rotated vector use the left
Jacobian of SO(3): d/dw_j [Exp(w) v] = (J_l(w) k_j) x Exp(w) v. Every row is a length (m) and
Newton-Raphson stops at max |g| <= tol, as the planar solver does.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields

import numpy as np

from .newton import STALLED, ConvergenceError, NewtonOptions, SingularJacobianError

Z = np.array([0.0, 0.0, 1.0])
SPATIAL_MODELS = ("compliant", "stick_slip")
#: the section's rim points, in the order of the step's rows: lower trailing, lower leading,
#: upper trailing, upper leading (the planar A, B, C, D for a positive increment along +x)
RIM_POINTS = ("lower_trailing", "lower_leading", "upper_trailing", "upper_leading")


# --- rotations ---------------------------------------------------------------------------------
def cross(a, b):
    """a x b of two 3-vectors (numpy.cross is slow on single vectors)."""
    a0, a1, a2 = a.tolist()
    b0, b1, b2 = b.tolist()
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def skew(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def rotation(w) -> np.ndarray:
    """Exp(w): the rotation by |w| about w / |w| (Rodrigues)."""
    angle = math.sqrt(float(w @ w))
    if angle == 0.0:
        return np.eye(3)
    K = skew(w / angle)
    return np.eye(3) + math.sin(angle) * K + (1.0 - math.cos(angle)) * (K @ K)


def left_jacobian(w) -> np.ndarray:
    """J_l(w) of SO(3): Exp(w + d) = Exp(J_l(w) d) Exp(w) + O(|d|^2)."""
    angle2 = float(w @ w)
    K = skew(w)
    if angle2 < 1e-16:
        return np.eye(3) + 0.5 * K + (K @ K) / 6.0
    angle = math.sqrt(angle2)
    return np.eye(3) + (1.0 - math.cos(angle)) / angle2 * K + (angle - math.sin(angle)) / (angle2 * angle) * (K @ K)


def normal_basis(v):
    """Two unit vectors k_1, k_2 with (k_1, k_2, v/|v|) orthonormal."""
    v = v / np.linalg.norm(v)
    helper = np.array([1.0, 0.0, 0.0]) if abs(v[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    k1 = cross(v, helper)
    k1 /= np.linalg.norm(k1)
    return k1, cross(v, k1)


def rotation_about(axis, angle) -> np.ndarray:
    return rotation(np.asarray(axis, float) / np.linalg.norm(axis) * angle)


def unit(v):
    return v / np.linalg.norm(v)


# --- the device in space -----------------------------------------------------------------------
@dataclass(frozen=True)
class Device:
    """The lengths of a Geometry (scalar fields) that the spatial model uses (m)."""

    R1: float
    R3: float
    A1: float
    A3: float
    B: float
    c1: float  # height of C^1 above R^1 (h_s^1 + R^1)
    c3: float  # height of C^3 above R^3 (-(h_s^3 + R^3))
    y21: float  # pad-frame height of C^21 (R^1 cos alpha^21 - B)
    y23: float  # pad-frame height of C^23 (B - R^3 cos alpha^23)
    L: float
    ring1: float  # R^1 sin(alpha^1)
    ring3: float  # R^3 sin(alpha^3)
    rest3: float  # R^3_z at theta^2 = 0 (Eq. 41)

    @classmethod
    def of(cls, geometry) -> Device:
        if np.ndim(geometry.L) != 0:
            raise ValueError("the spatial model runs one case: geometry fields must be scalars")
        (_, c1z), (_, c3z) = geometry.circle_centres
        (_, y21), (_, y23) = geometry.pad_cap_centres
        ring1, ring3 = geometry.ring_inner_x
        return cls(float(geometry.R1), float(geometry.R3), float(geometry.A1), float(geometry.A3), float(geometry.B),
                   float(c1z), float(c3z), float(y21), float(y23), float(geometry.L), float(ring1), float(ring3),
                   float(geometry.Ry3_compatible(0.0)))


@dataclass(frozen=True)
class Pose:
    """A configuration in space: plate positions R^1, R^3 (3,), pad centre G^2 (3,) and rotation Q (3, 3)."""

    R1: np.ndarray
    G: np.ndarray
    Q: np.ndarray
    R3: np.ndarray

    def C1(self, dev):
        return self.R1 + dev.c1 * Z

    def C3(self, dev):
        return self.R3 + dev.c3 * Z

    @property
    def axis(self):
        return self.Q[:, 2]


def start(geometry, Xg0, theta2_0=0.0, azimuth=0.0) -> Pose:
    """The compatible configuration at t_0: RB1 at X_g(t_0) (2,), the pad tilted by theta^2(t_0)
    (rad) in the vertical plane of ``azimuth`` (rad) as the planar model's Eq. 5 start."""
    dev = Device.of(geometry)
    h = np.array([math.cos(azimuth), math.sin(azimuth), 0.0])
    R1 = np.array([Xg0[0], Xg0[1], 0.0])
    s, c = math.sin(theta2_0), math.cos(theta2_0)
    G = R1 + dev.y21 * s * h + (dev.c1 - dev.y21 * c) * Z
    R3 = R1 + dev.L * s * h + float(geometry.Ry3_compatible(theta2_0)) * Z
    Q = rotation_about(cross(h, Z), theta2_0)
    return Pose(R1, G, Q, R3)


# --- the step's plane and section --------------------------------------------------------------
def step_plane(pose, dev, increment, reference):
    """(e1, m): the unit increment (``reference`` for a zero one) and the unit normal of pi."""
    length = math.hypot(increment[0], increment[1])
    e1 = np.array([increment[0] / length, increment[1] / length, 0.0]) if length > 0 else reference
    return e1, unit(cross(e1, pose.C1(dev) - pose.C3(dev)))


def section(Q, G, dev, m):
    """The four rim points of the section by the plane normal m (order RIM_POINTS), in space."""
    a = Q[:, 2]
    u = unit(cross(a, m))
    low, up = G - dev.B * a, G + dev.B * a
    return (low - dev.A1 * u, low + dev.A1 * u, up - dev.A3 * u, up + dev.A3 * u)


def project(point, centre, radius):
    """Radial projection of ``point`` onto the sphere (centre, radius): the contact point and the
    unit normal from it to the centre (Eq. 7)."""
    d = point - centre
    n = -d / np.linalg.norm(d)
    return centre - radius * n, n


# --- constraint sets ---------------------------------------------------------------------------
class Phase:
    """Rows g(x) (all lengths, m) on the unknowns x = (G^2 (3), w_1, w_2[, R^3_z]), with
    Q = Exp(w_1 k_1 + w_2 k_2) Q_ref; ``rows(x)`` returns g (m,) and dg/dx (m, len(x))."""

    name: str
    labels: tuple

    def __init__(self, Q_ref, spin_axis):
        self.Q_ref = Q_ref
        self.k = normal_basis(spin_axis)

    def orientation(self, x):
        w = x[3] * self.k[0] + x[4] * self.k[1]
        Jl = left_jacobian(w)
        return rotation(w) @ self.Q_ref, (Jl @ self.k[0], Jl @ self.k[1])

    def rows(self, x):
        raise NotImplementedError


def _point_rows(J, i, c, r, n=None):
    """Fill row(s) i of J with d/dw_j of a body-fixed vector r (the point minus G^2), projected on
    n if given: (c_j x r) . n."""
    for j in range(2):
        d = cross(c[j], r)
        if n is None:
            J[i:i + 3, 3 + j] = d
        else:
            J[i, 3 + j] = d @ n


class Compliant(Phase):
    """Compliant sliding in the plane pi of the step (see the module docstring)."""

    name = "compliant sliding"
    labels = tuple(f"{p} rim point on the tangent plane at its previous contact point" for p in RIM_POINTS) + (
        "out-of-plane compatibility of C^21 with C^1", "out-of-plane compatibility of C^23 with C^3")

    def __init__(self, dev, pose, R1, m, contacts, up=Z):
        super().__init__(pose.Q, pose.axis)
        self.dev, self.R1, self.m, self.contacts = dev, R1, m, contacts
        # RB3 at R^3(t_{n-1}) + (x_5 - R^3_z(t_{n-1})) up: vertical on its guide, or (``up`` in pi) the
        # paper's step solved wholly in the plane pi
        self.up, self.R3_base = up, pose.R3 - pose.R3[2] * up

    def R3(self, x):
        return self.R3_base + x[5] * self.up

    def pose(self, x):
        return Pose(self.R1, x[:3].copy(), self.orientation(x)[0], self.R3(x))

    def rows(self, x):
        dev, m = self.dev, self.m
        G = x[:3]
        Q, c = self.orientation(x)
        a = Q[:, 2]
        w = cross(a, m)
        nw = np.linalg.norm(w)
        u = w / nw
        da = [cross(cj, a) for cj in c]
        du = []
        for daj in da:
            dw = cross(daj, m)
            du.append((dw - u * (u @ dw)) / nw)
        R3 = self.R3(x)
        g = np.empty(6)
        J = np.zeros((6, 6))
        plates = (self.R1, self.R1, R3, R3)
        along = (-dev.B, -dev.B, dev.B, dev.B)
        across = (-dev.A1, dev.A1, -dev.A3, dev.A3)
        for i in range(4):
            point, normal = self.contacts[i]
            P = G + along[i] * a + across[i] * u
            g[i] = (P - plates[i] - point) @ normal
            J[i, :3] = normal
            for j in range(2):
                J[i, 3 + j] = (along[i] * da[j] + across[i] * du[j]) @ normal
            if i >= 2:
                J[i, 5] = -(normal @ self.up)
        C1, C3 = self.R1 + dev.c1 * Z, R3 + dev.c3 * Z
        for i, (y, C) in enumerate(((dev.y21, C1), (dev.y23, C3))):
            g[4 + i] = (G + y * a - C) @ m
            J[4 + i, :3] = m
            for j in range(2):
                J[4 + i, 3 + j] = y * (da[j] @ m)
        J[5, 5] = -(m @ self.up)
        return g, J


class Sticking(Phase):
    """The diagonal's two rim points pinned to their plates (Eq. 31 in space), RB3 on its guide."""

    name = "sticking"

    def __init__(self, dev, pose, R1, R3_guide, v1, v3, labels):
        # the smallest rotation: about axes normal to the pinned diagonal
        super().__init__(pose.Q, pose.Q @ (v3 - v1))
        self.dev, self.R1, self.v1, self.v3 = dev, R1, v1, v3
        self.target1 = pose.G + pose.Q @ v1 + (R1 - pose.R1)  # moves with RB1
        self.target3 = pose.G + pose.Q @ v3 - pose.R3  # relative to RB3
        self.R3h = R3_guide
        self.labels = labels

    def R3(self, x):
        return np.array([self.R3h[0], self.R3h[1], x[5]])

    def pose(self, x):
        return Pose(self.R1, x[:3].copy(), self.orientation(x)[0], self.R3(x))

    def rows(self, x):
        G = x[:3]
        Q, c = self.orientation(x)
        g = np.empty(6)
        J = np.zeros((6, 6))
        r1, r3 = Q @ self.v1, Q @ self.v3
        g[:3] = G + r1 - self.target1
        g[3:] = G + r3 - self.R3(x) - self.target3
        J[:3, :3] = J[3:, :3] = np.eye(3)
        _point_rows(J, 0, c, r1)
        _point_rows(J, 3, c, r3)
        J[3:, 5] = -Z
        return g, J


class Slipping(Phase):
    """Eqs. 37-41 in space: the pad slides back onto the line C^1C^3, RB3 at distance L (no spin)."""

    name = "slipping"

    def __init__(self, dev, stick_pose, e1, v1, v3, labels):
        super().__init__(stick_pose.Q, stick_pose.axis)
        self.dev, self.v1, self.v3 = dev, v1, v3
        C1 = stick_pose.C1(dev)
        e = unit(stick_pose.C3(dev) - C1)
        self.R1 = stick_pose.R1
        self.R3 = C1 + dev.L * e - dev.c3 * Z  # Eq. 41 and RB3 along C^1C^3 (Eq. 39)
        self.C1, self.C3 = C1, self.R3 + dev.c3 * Z
        self.ms = unit(cross(e1, -e))
        self.n12 = cross(self.ms, e)
        P1 = stick_pose.G + stick_pose.Q @ v1
        P3 = stick_pose.G + stick_pose.Q @ v3
        p1, n1 = project(P1, C1, dev.R1)
        p3, n3 = project(P3, stick_pose.C3(dev), dev.R3)
        # contact points move with their plates: RB1 is frozen, RB3 translates to its new place
        self.contacts = ((p1, n1), (p3 - stick_pose.R3 + self.R3, n3))
        self.labels = labels + ("G^2 on the line C^1C^3 (Eq. 38)", "axis in the slip plane: C^21 with C^1",
                                "axis in the slip plane: C^23 with C^3")

    def pose(self, x):
        return Pose(self.R1, x[:3].copy(), self.orientation(x)[0], self.R3)

    def rows(self, x):
        dev, ms = self.dev, self.ms
        G = x[:3]
        Q, c = self.orientation(x)
        a = Q[:, 2]
        g = np.empty(5)
        J = np.zeros((5, 5))
        for i, v in enumerate((self.v1, self.v3)):
            point, normal = self.contacts[i]
            r = Q @ v
            g[i] = (G + r - point) @ normal
            J[i, :3] = normal
            _point_rows(J, i, c, r, normal)
        g[2] = (G - self.C1) @ self.n12
        J[2, :3] = self.n12
        da = [cross(cj, a) for cj in c]
        for i, (y, C) in enumerate(((dev.y21, self.C1), (dev.y23, self.C3))):
            g[3 + i] = (G + y * a - C) @ ms
            J[3 + i, :3] = ms
            for j in range(2):
                J[3 + i, 3 + j] = y * (da[j] @ ms)
        return g, J


# --- Newton-Raphson ----------------------------------------------------------------------------
@dataclass
class Solution:
    pose: Pose
    iterations: int
    residual: float


def solve(phase: Phase, x0, options: NewtonOptions = NewtonOptions(), context: dict | None = None) -> Solution:
    """Newton-Raphson on the phase's rows from x0; errors as ``newton.solve``'s."""
    x = np.array(x0, dtype=float)
    for it in range(options.max_iter + 1):
        g, J = phase.rows(x)
        norm = float(np.max(np.abs(g)))
        if norm <= options.tol:  # NaN fails
            return Solution(phase.pose(x), it, norm)
        if it == options.max_iter:
            break
        try:
            x -= np.linalg.solve(J, g)
        except np.linalg.LinAlgError:
            raise SingularJacobianError(
                f"singular constraint Jacobian in {phase.name} ({_where(context)}): the rows do not fix the pad "
                "here.", "Check the geometry and the step size.") from None
    a = np.where(np.isnan(g), np.inf, np.abs(g))
    row = int(np.argmax(a))
    hint = (f"The residual stalls within {STALLED:g} times the tolerance: round-off, not divergence; raise newton.tol."
            if a[row] <= STALLED * options.tol else
            "Likely cause: a step too large for the geometry (the constraints cannot follow the ground increment): "
            "reduce dt or the amplitude.")
    raise ConvergenceError(
        f"Newton-Raphson did not converge in {phase.name} ({_where(context)}): after {options.max_iter} iterations "
        f"the residual is {a[row]:.3e} m > tol {options.tol:.1e} m; largest: {phase.labels[row]} = {g[row]:.3e}.",
        hint)


def _where(context) -> str:
    ctx = context or {}
    parts = [f"step {ctx['step']}"] if "step" in ctx else []
    if "time" in ctx:
        parts.append(f"time {ctx['time']:.6g} s")
    return ", ".join(parts)


def _context(n, times):
    return {"step": n} if times is None else {"step": n, "time": float(times[n])}


# --- steppers ----------------------------------------------------------------------------------
@dataclass(frozen=True, slots=True)
class SpatialStep:
    """The configuration at t_n and how the solver got there (n = 0: the start, no solve); the
    step's direction e1 and plane normal m; for stick-slip also the end of its sticking phase
    (None for compliant sliding, and at n = 0) and whether the trailing rim point is pinned."""

    n: int
    pose: Pose
    e1: np.ndarray
    m: np.ndarray
    newton_iterations: int
    residual: float
    stick: Pose | None = None
    newton_iterations_stick: int = 0
    residual_stick: float = 0.0


def _ground(Xg):
    Xg = np.asarray(Xg, dtype=float)
    if Xg.ndim != 2 or Xg.shape[1] != 2 or Xg.shape[0] < 2:
        raise ValueError(f"Xg must have shape (T, 2) with T >= 2 (x, y of each step), got {Xg.shape}")
    if not np.isfinite(Xg).all():
        raise ValueError("Xg must be finite")
    return Xg


def _reference(azimuth):
    return np.array([math.cos(azimuth), math.sin(azimuth), 0.0])


def compliant_steps(geometry, Xg, theta2_0=0.0, *, azimuth=0.0, options=NewtonOptions(), times=None,
                    in_plane=False):
    """Yield a ``SpatialStep`` per step of compliant sliding under X_g (T, 2) (m); ``azimuth``
    (rad): the plane of theta2_0 and the direction of a zero increment. ``in_plane=True`` solves
    each step wholly in its plane pi, as the paper's Sec. 4 reads: RB3 rises along the direction
    in pi normal to the increment, which leans from the vertical once the device is displaced
    across the increment, and RB3 leaves its guide (kept to measure that; not a model to use)."""
    Xg = _ground(Xg)
    dev = Device.of(geometry)
    pose = start(geometry, Xg[0], theta2_0, azimuth)
    reference = _reference(azimuth)
    e1, m = step_plane(pose, dev, Xg[1] - Xg[0], reference)
    yield SpatialStep(0, pose, e1, m, 0, 0.0)
    for n in range(1, len(Xg)):
        e1, m = step_plane(pose, dev, Xg[n] - Xg[n - 1], reference)
        centres = (pose.C1(dev), pose.C1(dev), pose.C3(dev), pose.C3(dev))
        radii = (dev.R1, dev.R1, dev.R3, dev.R3)
        plates = (pose.R1, pose.R1, pose.R3, pose.R3)
        contacts = []
        for P, C, r, R in zip(section(pose.Q, pose.G, dev, m), centres, radii, plates):
            p, normal = project(P, C, r)
            contacts.append((p - R, normal))  # plate frames: the plates do not rotate
        R1 = np.array([Xg[n, 0], Xg[n, 1], 0.0])
        up = unit(cross(m, e1)) if in_plane else Z
        phase = Compliant(dev, pose, R1, m, contacts, up)
        guess = np.concatenate([pose.G + 0.5 * (R1 - pose.R1), [0.0, 0.0, pose.R3[2]]])
        sol = solve(phase, guess, options, _context(n, times))
        pose = sol.pose
        yield SpatialStep(n, pose, e1, m, sol.iterations, sol.residual)


def pinned(pose, dev, m):
    """Pad-frame positions of the trailing lower and leading upper rim points of the section by
    the plane normal m: the jammed diagonal of a stick-slip step (A-D or B-C in the plane)."""
    P1, _, _, P3 = section(pose.Q, pose.G, dev, m)
    return pose.Q.T @ (P1 - pose.G), pose.Q.T @ (P3 - pose.G)


STICK_LABELS = ("x of the trailing lower rim point pinned to RB1", "y of the trailing lower rim point pinned to RB1",
                "z of the trailing lower rim point pinned to RB1", "x of the leading upper rim point pinned to RB3",
                "y of the leading upper rim point pinned to RB3", "z of the leading upper rim point pinned to RB3")
SLIP_LABELS = ("trailing lower rim point on its tangent plane", "leading upper rim point on its tangent plane")


def stick_slip_steps(geometry, Xg, theta2_0=0.0, *, azimuth=0.0, options=NewtonOptions(), times=None):
    """Yield a ``SpatialStep`` per stick-slip step under X_g (T, 2) (m), with the end of its
    sticking phase; ``azimuth`` as for ``compliant_steps``."""
    Xg = _ground(Xg)
    dev = Device.of(geometry)
    pose = start(geometry, Xg[0], theta2_0, azimuth)
    guide = pose.R3[:2].copy()
    reference = _reference(azimuth)
    e1, m = step_plane(pose, dev, Xg[1] - Xg[0], reference)
    yield SpatialStep(0, pose, e1, m, 0, 0.0)
    for n in range(1, len(Xg)):
        e1, m = step_plane(pose, dev, Xg[n] - Xg[n - 1], reference)
        v1, v3 = pinned(pose, dev, m)
        R1 = np.array([Xg[n, 0], Xg[n, 1], 0.0])
        stick = Sticking(dev, pose, R1, guide, v1, v3, STICK_LABELS)
        guess = np.concatenate([pose.G + 0.5 * (R1 - pose.R1), [0.0, 0.0, pose.R3[2]]])
        s1 = solve(stick, guess, options, _context(n, times))
        slip = Slipping(dev, s1.pose, e1, v1, v3, SLIP_LABELS)
        s2 = solve(slip, np.concatenate([s1.pose.G, [0.0, 0.0]]), options, _context(n, times))
        pose = s2.pose
        yield SpatialStep(n, pose, e1, m, s2.iterations, s2.residual, s1.pose, s1.iterations, s1.residual)


@dataclass(frozen=True)
class SpatialModel:
    name: str
    title: str
    steps: Callable


REGISTRY = {m.name: m for m in (SpatialModel("compliant", "Compliant Sliding", compliant_steps),
                                SpatialModel("stick_slip", "Stick-Slip", stick_slip_steps))}


def steps(name, geometry, Xg, theta2_0=0.0, **kw):
    if name not in REGISTRY:
        raise ValueError(f"model must be one of {SPATIAL_MODELS}, got {name!r}")
    return REGISTRY[name].steps(geometry, Xg, theta2_0, **kw)


# --- histories and what they show --------------------------------------------------------------
def _poses(poses, prefix=""):
    return {prefix + "R1": np.array([p.R1 for p in poses]), prefix + "G": np.array([p.G for p in poses]),
            prefix + "Q": np.array([p.Q for p in poses]), prefix + "R3": np.array([p.R3 for p in poses])}


def collect(records) -> dict:
    """A history as arrays, time first: R1, G, R3 (T, 3), Q (T, 3, 3), e1, m (T, 3), the solver
    figures and, for stick-slip, the same of the end of sticking (``stick_`` prefix; NaN at n = 0)."""
    rows = list(records)
    out = _poses([r.pose for r in rows])
    out["e1"] = np.array([r.e1 for r in rows])
    out["m"] = np.array([r.m for r in rows])
    out["newton_iterations"] = np.array([r.newton_iterations for r in rows])
    out["residual"] = np.array([r.residual for r in rows])
    if len(rows) > 1 and rows[-1].stick is not None:
        nan = Pose(*(np.full_like(getattr(rows[0].pose, f.name), np.nan) for f in fields(Pose)))
        out.update(_poses([r.stick if r.stick is not None else nan for r in rows], "stick_"))
        out["newton_iterations_stick"] = np.array([r.newton_iterations_stick for r in rows])
        out["residual_stick"] = np.array([r.residual_stick for r in rows])
    return out


def run(name, geometry, Xg, theta2_0=0.0, **kw) -> dict:
    return collect(steps(name, geometry, Xg, theta2_0, **kw))


def tilt(Q):
    """Tilt of the pad axis from the vertical and the azimuth it leans towards (rad; azimuth NaN
    where the axis is vertical): Q (..., 3, 3)."""
    a = Q[..., :, 2]
    horizontal = np.hypot(a[..., 0], a[..., 1])
    with np.errstate(invalid="ignore"):
        azimuth = np.where(horizontal > 0, np.arctan2(a[..., 1], a[..., 0]), np.nan)
    return np.arctan2(horizontal, a[..., 2]), azimuth


def diagnostics(history, geometry, prefix="") -> dict:
    """Per step (arrays, time first): tilt and its azimuth (rad), rise of RB3 above its theta2 = 0
    rest position (m), the cap-centre gaps |C^21 - C^1|, |C^23 - C^3| (m), the interpenetration of
    the step's four rim points (m, positive into the plate; order RIM_POINTS) and the clearance to
    each retaining ring (m; negative beyond it)."""
    dev = Device.of(geometry)
    G, Q, R1, R3 = (history[prefix + k] for k in ("G", "Q", "R1", "R3"))
    a = Q[..., :, 2]
    C1, C3 = R1 + dev.c1 * Z, R3 + dev.c3 * Z
    out = {}
    out["tilt"], out["tilt_azimuth"] = tilt(Q)
    out["rise"] = R3[:, 2] - dev.rest3
    out["gap_1"] = np.linalg.norm(G + dev.y21 * a - C1, axis=-1)
    out["gap_3"] = np.linalg.norm(G + dev.y23 * a - C3, axis=-1)
    m = history["m"]
    interp = np.empty(G.shape[:1] + (4,))
    for k in range(len(G)):
        if np.isnan(G[k]).any():
            interp[k] = np.nan
            continue
        points = section(Q[k], G[k], dev, m[k])
        for i, P in enumerate(points):
            centre, radius = (C1[k], dev.R1) if i < 2 else (C3[k], dev.R3)
            interp[k, i] = np.linalg.norm(P - centre) - radius
    out["interpenetration"] = interp
    out["clearance_1"], out["clearance_3"] = clearances(G, Q, R1, R3, dev)
    return out


def clearances(G, Q, R1, R3, dev):
    """Clearance (m) between the pad and the retaining rings of RB1 and RB3 (negative beyond a ring):
    R^j sin(alpha^j) minus the largest horizontal distance of the pad's rim on that plate from
    the plate's axis. G, R1, R3 (..., 3), Q (..., 3, 3)."""
    a = Q[..., :, 2]
    return (dev.ring1 - _reach(G - dev.B * a, a, dev.A1, R1), dev.ring3 - _reach(G + dev.B * a, a, dev.A3, R3))


def beyond_ring(pose, dev) -> bool:
    """Whether the pad has passed a retaining ring in ``pose``."""
    gaps = clearances(pose.G[None], pose.Q[None], pose.R1[None], pose.R3[None], dev)
    return bool(gaps[0][0] < 0 or gaps[1][0] < 0)


def _reach(centre, a, radius, plate):
    """Largest horizontal distance from the plate's axis of a rim (centre, radius, normal a): at the
    rim's two points in the vertical plane through the axis a (the radial section, where the rim
    reaches furthest whenever the pad is near compatible), or along the rim centre's offset
    where the axis is vertical."""
    offset = centre - plate
    lean = a.copy()
    lean[..., 2] = 0.0
    horizontal = np.linalg.norm(lean, axis=-1)
    fallback = offset.copy()
    fallback[..., 2] = 0.0
    fallback[..., 0] = np.where(np.linalg.norm(fallback, axis=-1) > 0, fallback[..., 0], 1.0)
    direction = np.where(horizontal[..., None] > 0, lean, fallback)
    # the in-rim direction of steepest horizontal extent: direction projected normal to a
    u = direction - a * np.sum(direction * a, axis=-1, keepdims=True)
    u /= np.linalg.norm(u, axis=-1, keepdims=True)
    reach = [np.hypot(*(offset + s * radius * u)[..., :2].T) for s in (-1.0, 1.0)]
    return np.maximum(*reach)


# --- sweeps ------------------------------------------------------------------------------------
def _case_geometry(geometry, k, n):
    from .geometry import Geometry

    return Geometry(**{f.name: float(np.broadcast_to(getattr(geometry, f.name), (n,))[k]) for f in fields(geometry)})


def summarize(model, geometry, Xg, theta2_0=0.0, *, azimuth=0.0, capacity="continue", progress=None,
              options=NewtonOptions(), times=None) -> dict:
    """Per-case summaries of a batch of bidirectional cases, with the keys and conventions of
    ``dccss.studies.sweep.summarize`` (one case after another: histories in space are not batched).

    Xg is (T, n, 2); geometry fields, theta2_0 and the reference azimuth (rad) broadcast to (n,).
    Under bidirectional motion |theta2| is the tilt: ``theta2_max_abs`` is the largest tilt and
    ``theta2_end`` the residual tilt (>= 0); the corners A, B, C, D are the trailing and leading
    rim points of each step's section on RB1 and on RB3 (for motion along +x, the planar corners);
    ``sticking_rotation_max`` is the largest angle the pad turns through in a sticking phase."""
    from .capacity import CAPACITY_POLICIES, CapacityError, mark_failures

    if capacity not in CAPACITY_POLICIES:
        raise ValueError(f"capacity must be one of {CAPACITY_POLICIES}, got {capacity!r}")
    Xg = np.asarray(Xg, dtype=float)
    if Xg.ndim != 3 or Xg.shape[-1] != 2:
        raise ValueError(f"Xg must have shape (T, n, 2), got {Xg.shape}")
    T, n = Xg.shape[:2]
    now = np.asarray(times, dtype=float) if times is not None else np.arange(T, dtype=float)
    theta2_0 = np.broadcast_to(np.asarray(theta2_0, dtype=float), (n,))
    azimuth = np.broadcast_to(np.asarray(azimuth, dtype=float), (n,))
    keys = ["theta2_max_abs", "theta2_end", "rise_max", "rise_end", "clearance_min", "I_A_max", "I_B_max", "I_C_max",
            "I_D_max", "newton_iterations_mean"] + (["sticking_rotation_max", "rise_stick_max"] if model == "stick_slip"
                                                    else [])
    out = {k: np.full(n, np.nan) for k in keys}
    out["newton_iterations_max"] = np.zeros(n, dtype=np.int32)
    failure, reached = np.full(n, np.nan), np.full(n, np.nan)
    for k in range(n):
        g = _case_geometry(geometry, k, n)
        dev = Device.of(g)
        records = []
        try:
            for step in steps(model, g, Xg[:, k], float(theta2_0[k]), azimuth=float(azimuth[k]), options=options,
                              times=times):
                records.append(step)
                if beyond_ring(step.pose, dev):
                    if np.isnan(reached[k]):
                        reached[k] = now[step.n]
                        if capacity == "error" and options.on_failure != "mark":
                            err = CapacityError(f"the pad reaches a retaining ring at t = {now[step.n]:.6g} s in the "
                                                f"case at batch index {(k,)} (capacity: error)")
                            err.index = (k,)
                            raise err
                    if capacity != "continue":
                        break
        except ConvergenceError as err:
            if options.on_failure != "mark":
                err.index = (k,)
                raise
            failure[k] = now[len(records)]
        if progress is not None:
            progress(T - 1, T - 1)
        if not records:
            continue
        h = collect(records)
        d = diagnostics(h, g)
        tilt = np.degrees(d["tilt"])
        out["theta2_max_abs"][k], out["theta2_end"][k] = tilt.max(), tilt[-1]
        out["rise_max"][k], out["rise_end"][k] = d["rise"].max(), d["rise"][-1]
        out["clearance_min"][k] = min(d["clearance_1"].min(), d["clearance_3"].min())
        for i, c in enumerate("ABCD"):
            out[f"I_{c}_max"][k] = np.nanmax(d["interpenetration"][1:, i]) if len(records) > 1 else np.nan
        its = h["newton_iterations"] + h.get("newton_iterations_stick", 0)
        out["newton_iterations_max"][k] = its.max()
        out["newton_iterations_mean"][k] = its.sum() / max(len(records) - 1, 1)
        if model == "stick_slip" and len(records) > 1:
            turn = [np.arccos(np.clip(0.5 * (np.trace(h["stick_Q"][j] @ h["Q"][j - 1].T) - 1.0), -1.0, 1.0))
                    for j in range(1, len(records))]
            out["sticking_rotation_max"][k] = np.degrees(max(turn))
            out["rise_stick_max"][k] = np.nanmax(h["stick_R3"][1:, 2] - dev.rest3)
    out["capacity_exceeded"] = ~np.isnan(reached)
    return mark_failures(out, failure, reached, capacity)
