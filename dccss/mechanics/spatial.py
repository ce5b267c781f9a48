"""Bidirectional ground motion: the three bodies in space, one case, compiled.

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

How it is written
-----------------
The equations are written once, in the scalar subset of Python that Numba compiles: vectors are
3-tuples, a rotation is the tuple of its three columns, a pose is a ``Pose`` (R^1, G^2, Q, R^3)
and a phase is a named tuple of what its rows hold fixed (``CompliantPhase``, ``StickingPhase``,
``SlippingPhase``), with ``*_rows(phase, x)`` returning the residual g and the Jacobian dg/dx as
tuples. Every phase has six unknowns x = (G^2, w_1, w_2, R^3_z); slipping, whose RB3 is fixed by
Eq. 41, carries x_6 with the unit row x_6 = 0 so that one Newton loop and one 6 x 6 solve
(Gaussian elimination with partial pivoting) serve all three. A model's step is written with
these phases in ``models`` (its registry entry's ``spatial`` history calls ``history`` with it). A
whole history runs in one compiled call (``run``), which also evaluates per step the section's
interpenetration and the clearances to the rings (the ring test of ``capacity="stop"``). The
kernels are compiled once per machine and source version and cached on disk (``scalar.kernel``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from . import registry, scalar
from .newton import STALLED, ConvergenceError, NewtonOptions, SingularJacobianError
from .scalar import jit, max_abs

Z = (0.0, 0.0, 1.0)
#: the section's rim points, in the order of the step's rows: lower trailing, lower leading,
#: upper trailing, upper leading (the planar A, B, C, D for a positive increment along +x)
RIM_POINTS = ("lower_trailing", "lower_leading", "upper_trailing", "upper_leading")
#: the phases of a step (a failure names one)
COMPLIANT, STICKING, SLIPPING = 0, 1, 2
PHASE_NAMES = ("compliant sliding", "sticking", "slipping")
#: Newton outcomes
CONVERGED, NOT_CONVERGED, SINGULAR = 0, 1, 2
LABELS = (
    tuple(f"{p} rim point on the tangent plane at its previous contact point" for p in RIM_POINTS)
    + ("out-of-plane compatibility of C^21 with C^1", "out-of-plane compatibility of C^23 with C^3"),
    ("x of the trailing lower rim point pinned to RB1", "y of the trailing lower rim point pinned to RB1",
     "z of the trailing lower rim point pinned to RB1", "x of the leading upper rim point pinned to RB3",
     "y of the leading upper rim point pinned to RB3", "z of the leading upper rim point pinned to RB3"),
    ("trailing lower rim point on its tangent plane", "leading upper rim point on its tangent plane",
     "G^2 on the line C^1C^3 (Eq. 38)", "axis in the slip plane: C^21 with C^1",
     "axis in the slip plane: C^23 with C^3", "RB3 held at Eq. 41 (a unit row)"),
)


# --- vectors (3-tuples) and rotations (tuples of columns) ----------------------------------------
@jit
def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


@jit
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


@jit
def scale(s, a):
    return (s * a[0], s * a[1], s * a[2])


@jit
def axpy(a, s, b):
    """a + s b."""
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


@jit
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@jit
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@jit
def norm(a):
    return math.sqrt(dot(a, a))


@jit
def unit(a):
    return scale(1.0 / norm(a), a)


@jit
def apply(Q, v):
    """Q v, Q given by its columns."""
    return axpy(axpy(scale(v[0], Q[0]), v[1], Q[1]), v[2], Q[2])


@jit
def apply_t(Q, v):
    """Q^T v."""
    return (dot(Q[0], v), dot(Q[1], v), dot(Q[2], v))


@jit
def rotate(w, v):
    """Exp(w) v: v turned by |w| about w / |w| (Rodrigues)."""
    angle = norm(w)
    if angle == 0.0:
        return v
    k = scale(1.0 / angle, w)
    c, s = math.cos(angle), math.sin(angle)
    return axpy(axpy(scale(c, v), s, cross(k, v)), (1.0 - c) * dot(k, v), k)


@jit
def rotation(w):
    """Exp(w) as its columns."""
    return (rotate(w, (1.0, 0.0, 0.0)), rotate(w, (0.0, 1.0, 0.0)), rotate(w, (0.0, 0.0, 1.0)))


@jit
def left_jacobian(w, k):
    """J_l(w) k, with J_l the left Jacobian of SO(3): Exp(w + d) = Exp(J_l(w) d) Exp(w) + O(|d|^2)."""
    angle2 = dot(w, w)
    wk = cross(w, k)
    wwk = cross(w, wk)
    if angle2 < 1e-16:
        return axpy(axpy(k, 0.5, wk), 1.0 / 6.0, wwk)
    angle = math.sqrt(angle2)
    return axpy(axpy(k, (1.0 - math.cos(angle)) / angle2, wk), (angle - math.sin(angle)) / (angle2 * angle), wwk)


@jit
def normal_basis(v):
    """Two unit vectors k_1, k_2 with (k_1, k_2, v/|v|) orthonormal."""
    v = unit(v)
    helper = (1.0, 0.0, 0.0) if abs(v[0]) < 0.9 else (0.0, 1.0, 0.0)
    k1 = unit(cross(v, helper))
    return k1, cross(v, k1)


@jit
def orientation(Q_ref, k1, k2, w1, w2):
    """Q = Exp(w_1 k_1 + w_2 k_2) Q_ref and dQ/dw_j as the axes c_j: dv/dw_j = c_j x v."""
    w = axpy(scale(w1, k1), w2, k2)
    Q = (rotate(w, Q_ref[0]), rotate(w, Q_ref[1]), rotate(w, Q_ref[2]))
    return Q, left_jacobian(w, k1), left_jacobian(w, k2)


# --- the device and its configurations -----------------------------------------------------------
class Device(NamedTuple):
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


def device(geometry) -> Device:
    """The spatial model's lengths of a one-case Geometry."""
    if np.ndim(geometry.L) != 0:
        raise ValueError("the spatial model runs one case: geometry fields must be scalars")
    (_, c1z), (_, c3z) = geometry.circle_centres
    (_, y21), (_, y23) = geometry.pad_cap_centres
    ring1, ring3 = geometry.ring_inner_x
    return Device(*(float(v) for v in (geometry.R1, geometry.R3, geometry.A1, geometry.A3, geometry.B, c1z, c3z,
                                       y21, y23, geometry.L, ring1, ring3, geometry.Ry3_compatible(0.0))))


class Pose(NamedTuple):
    """A configuration in space: plate positions R^1, R^3, pad centre G^2 (3-tuples, m) and the pad's
    rotation Q (its three columns; the third is the pad axis)."""

    R1: tuple
    G: tuple
    Q: tuple
    R3: tuple


@jit
def C1(pose, dev):
    return axpy(pose.R1, dev.c1, Z)


@jit
def C3(pose, dev):
    return axpy(pose.R3, dev.c3, Z)


@jit
def start(dev, x, y, theta2_0, azimuth, R3z):
    """The compatible configuration at t_0: RB1 at X_g(t_0) = (x, y), the pad tilted by theta^2(t_0)
    (rad) in the vertical plane of ``azimuth`` (rad) as the planar model's Eq. 5 start, RB3 at height
    R3z (``Geometry.Ry3_compatible(theta2_0)``)."""
    h = (math.cos(azimuth), math.sin(azimuth), 0.0)
    R1 = (x, y, 0.0)
    s, c = math.sin(theta2_0), math.cos(theta2_0)
    G = axpy(axpy(R1, dev.y21 * s, h), dev.c1 - dev.y21 * c, Z)
    R3 = axpy(axpy(R1, dev.L * s, h), R3z, Z)
    return Pose(R1, G, rotation(scale(theta2_0, cross(h, Z))), R3)


# --- the step's plane and section ----------------------------------------------------------------
@jit
def step_plane(pose, dev, dx, dy, reference):
    """(e1, m): the unit increment (dx, dy) (``reference`` for a zero one) and the unit normal of pi."""
    length = math.hypot(dx, dy)
    e1 = (dx / length, dy / length, 0.0) if length > 0 else reference
    return e1, unit(cross(e1, sub(C1(pose, dev), C3(pose, dev))))


@jit
def section(Q, G, dev, m):
    """The four rim points of the section by the plane normal m (order RIM_POINTS), in space."""
    a = Q[2]
    u = unit(cross(a, m))
    low, up = axpy(G, -dev.B, a), axpy(G, dev.B, a)
    return axpy(low, -dev.A1, u), axpy(low, dev.A1, u), axpy(up, -dev.A3, u), axpy(up, dev.A3, u)


@jit
def project(point, centre, radius):
    """Radial projection of ``point`` onto the sphere (centre, radius): the contact point and the
    unit normal from it to the centre (Eq. 7)."""
    n = scale(-1.0 / norm(sub(point, centre)), sub(point, centre))
    return axpy(centre, -radius, n), n


@jit
def pinned(pose, dev, m):
    """Pad-frame positions of the trailing lower and leading upper rim points of the section by
    the plane normal m: the jammed diagonal of a stick-slip step (A-D or B-C in the plane)."""
    P1, _, _, P3 = section(pose.Q, pose.G, dev, m)
    return apply_t(pose.Q, sub(P1, pose.G)), apply_t(pose.Q, sub(P3, pose.G))


# --- the three phases: what each holds fixed, and its rows ---------------------------------------
class CompliantPhase(NamedTuple):
    """Compliant sliding in the plane pi of the step: rim points on the tangent planes at their
    previous contact points (``points`` relative to their plates, ``normals``), cap centres in the
    planes through C^1, C^3 normal to m; RB3 at R3_base + x_6 up."""

    dev: Device
    Q_ref: tuple
    k1: tuple
    k2: tuple
    R1: tuple
    m: tuple
    points: tuple
    normals: tuple
    up: tuple
    R3_base: tuple


class StickingPhase(NamedTuple):
    """The diagonal's rim points v1, v3 (pad frame) pinned to their plates (Eq. 31 in space): at
    ``target1`` (moving with RB1) and ``target3`` (relative to RB3); RB3 on its guide at height x_6."""

    dev: Device
    Q_ref: tuple
    k1: tuple
    k2: tuple
    R1: tuple
    guide: tuple
    v1: tuple
    v3: tuple
    target1: tuple
    target3: tuple


class SlippingPhase(NamedTuple):
    """Eqs. 37-41 in space: v1, v3 on the tangent planes at their projections (global ``points``,
    ``normals``), G^2 on the line C^1C^3 (normal ``n12``) with the axis in the slip plane (normal
    ``ms``); RB1 and RB3 fixed (R1, R3)."""

    dev: Device
    Q_ref: tuple
    k1: tuple
    k2: tuple
    R1: tuple
    R3: tuple
    C1: tuple
    C3: tuple
    ms: tuple
    n12: tuple
    v1: tuple
    v3: tuple
    points: tuple
    normals: tuple


@jit
def compliant_phase(dev, pose, R1, m, up):
    """The compliant step from ``pose`` to RB1 at R1 in the plane of normal m; ``up``: the direction
    RB3 moves in (Z: its guide)."""
    centres = (C1(pose, dev), C1(pose, dev), C3(pose, dev), C3(pose, dev))
    rim = section(pose.Q, pose.G, dev, m)
    p0, n0 = project(rim[0], centres[0], dev.R1)
    p1, n1 = project(rim[1], centres[1], dev.R1)
    p2, n2 = project(rim[2], centres[2], dev.R3)
    p3, n3 = project(rim[3], centres[3], dev.R3)
    # plate frames: the plates do not rotate
    points = (sub(p0, pose.R1), sub(p1, pose.R1), sub(p2, pose.R3), sub(p3, pose.R3))
    k1, k2 = normal_basis(pose.Q[2])
    return CompliantPhase(dev, pose.Q, k1, k2, R1, m, points, (n0, n1, n2, n3), up,
                          axpy(pose.R3, -pose.R3[2], up))


@jit
def unknowns(phase, x):
    """G^2 and Q at x = (G^2, w_1, w_2, ...), with the axes c_1, c_2 of dQ/dw_j (``orientation``)."""
    Q, c1, c2 = orientation(phase.Q_ref, phase.k1, phase.k2, x[3], x[4])
    return (x[0], x[1], x[2]), Q, c1, c2


@jit
def compliant_R3(phase, x):
    return axpy(phase.R3_base, x[5], phase.up)


@jit
def compliant_rows(phase, x):
    """Rows g (6) and dg/dx (6 x 6) of compliant sliding at x = (G^2, w_1, w_2, R^3_z)."""
    dev, m = phase.dev, phase.m
    G, Q, c1, c2 = unknowns(phase, x)
    a = Q[2]
    w = cross(a, m)
    nw = norm(w)
    u = scale(1.0 / nw, w)
    da1, da2 = cross(c1, a), cross(c2, a)
    dw1, dw2 = cross(da1, m), cross(da2, m)
    du1 = scale(1.0 / nw, axpy(dw1, -dot(u, dw1), u))
    du2 = scale(1.0 / nw, axpy(dw2, -dot(u, dw2), u))
    R3 = compliant_R3(phase, x)
    up = phase.up

    def tangent(along, across, plate, point, normal, rises):
        P = axpy(axpy(G, along, a), across, u)
        g = dot(sub(sub(P, plate), point), normal)
        d3 = -dot(normal, up) if rises else 0.0
        return g, (normal[0], normal[1], normal[2], dot(axpy(scale(along, da1), across, du1), normal),
                   dot(axpy(scale(along, da2), across, du2), normal), d3)

    pts, nrm = phase.points, phase.normals
    g0, J0 = tangent(-dev.B, -dev.A1, phase.R1, pts[0], nrm[0], False)
    g1, J1 = tangent(-dev.B, dev.A1, phase.R1, pts[1], nrm[1], False)
    g2, J2 = tangent(dev.B, -dev.A3, R3, pts[2], nrm[2], True)
    g3, J3 = tangent(dev.B, dev.A3, R3, pts[3], nrm[3], True)
    g4 = dot(sub(axpy(G, dev.y21, a), axpy(phase.R1, dev.c1, Z)), m)
    g5 = dot(sub(axpy(G, dev.y23, a), axpy(R3, dev.c3, Z)), m)
    J4 = (m[0], m[1], m[2], dev.y21 * dot(da1, m), dev.y21 * dot(da2, m), 0.0)
    J5 = (m[0], m[1], m[2], dev.y23 * dot(da1, m), dev.y23 * dot(da2, m), -dot(m, up))
    return (g0, g1, g2, g3, g4, g5), (J0, J1, J2, J3, J4, J5)


@jit
def compliant_pose(phase, x):
    Q, _, _ = orientation(phase.Q_ref, phase.k1, phase.k2, x[3], x[4])
    return Pose(phase.R1, (x[0], x[1], x[2]), Q, compliant_R3(phase, x))


@jit
def sticking_phase(dev, pose, R1, guide, v1, v3):
    """The sticking phase from ``pose`` with RB1 moved to R1; RB3 back on its guide (x, y)."""
    # the smallest rotation: about axes normal to the pinned diagonal
    k1, k2 = normal_basis(apply(pose.Q, sub(v3, v1)))
    target1 = add(add(pose.G, apply(pose.Q, v1)), sub(R1, pose.R1))
    target3 = sub(add(pose.G, apply(pose.Q, v3)), pose.R3)
    return StickingPhase(dev, pose.Q, k1, k2, R1, guide, v1, v3, target1, target3)


@jit
def sticking_rows(phase, x):
    """Rows g (6) and dg/dx (6 x 6) of sticking at x = (G^2, w_1, w_2, R^3_z)."""
    G, Q, c1, c2 = unknowns(phase, x)
    r1, r3 = apply(Q, phase.v1), apply(Q, phase.v3)
    R3 = (phase.guide[0], phase.guide[1], x[5])
    h1 = sub(add(G, r1), phase.target1)
    h3 = sub(sub(add(G, r3), R3), phase.target3)
    a1, b1 = cross(c1, r1), cross(c2, r1)
    a3, b3 = cross(c1, r3), cross(c2, r3)
    return (h1[0], h1[1], h1[2], h3[0], h3[1], h3[2]), (
        (1.0, 0.0, 0.0, a1[0], b1[0], 0.0), (0.0, 1.0, 0.0, a1[1], b1[1], 0.0), (0.0, 0.0, 1.0, a1[2], b1[2], 0.0),
        (1.0, 0.0, 0.0, a3[0], b3[0], 0.0), (0.0, 1.0, 0.0, a3[1], b3[1], 0.0), (0.0, 0.0, 1.0, a3[2], b3[2], -1.0))


@jit
def sticking_pose(phase, x):
    Q, _, _ = orientation(phase.Q_ref, phase.k1, phase.k2, x[3], x[4])
    return Pose(phase.R1, (x[0], x[1], x[2]), Q, (phase.guide[0], phase.guide[1], x[5]))


@jit
def slipping_phase(dev, stick, e1, v1, v3):
    """The slipping phase from the end of sticking ``stick`` in a step along e1."""
    k1, k2 = normal_basis(stick.Q[2])
    c1 = C1(stick, dev)
    e = unit(sub(C3(stick, dev), c1))
    R3 = axpy(axpy(c1, dev.L, e), -dev.c3, Z)  # Eq. 41 and RB3 along C^1C^3 (Eq. 39)
    ms = unit(cross(e1, scale(-1.0, e)))
    p1, n1 = project(add(stick.G, apply(stick.Q, v1)), c1, dev.R1)
    p3, n3 = project(add(stick.G, apply(stick.Q, v3)), C3(stick, dev), dev.R3)
    # contact points move with their plates: RB1 is frozen, RB3 translates to its new place
    points = (p1, add(sub(p3, stick.R3), R3))
    return SlippingPhase(dev, stick.Q, k1, k2, stick.R1, R3, c1, axpy(R3, dev.c3, Z), ms, cross(ms, e), v1, v3,
                         points, (n1, n3))


@jit
def slipping_rows(phase, x):
    """Rows g (6) and dg/dx (6 x 6) of slipping at x = (G^2, w_1, w_2, x_6): five rows, and x_6 = 0."""
    dev, ms = phase.dev, phase.ms
    G, Q, c1, c2 = unknowns(phase, x)
    a = Q[2]

    def tangent(v, point, normal):
        r = apply(Q, v)
        return dot(sub(add(G, r), point), normal), (normal[0], normal[1], normal[2], dot(cross(c1, r), normal),
                                                    dot(cross(c2, r), normal), 0.0)

    g0, J0 = tangent(phase.v1, phase.points[0], phase.normals[0])
    g1, J1 = tangent(phase.v3, phase.points[1], phase.normals[1])
    n12 = phase.n12
    g2 = dot(sub(G, phase.C1), n12)
    da1, da2 = cross(c1, a), cross(c2, a)
    g3 = dot(sub(axpy(G, dev.y21, a), phase.C1), ms)
    g4 = dot(sub(axpy(G, dev.y23, a), phase.C3), ms)
    return (g0, g1, g2, g3, g4, x[5]), (
        J0, J1, (n12[0], n12[1], n12[2], 0.0, 0.0, 0.0),
        (ms[0], ms[1], ms[2], dev.y21 * dot(da1, ms), dev.y21 * dot(da2, ms), 0.0),
        (ms[0], ms[1], ms[2], dev.y23 * dot(da1, ms), dev.y23 * dot(da2, ms), 0.0),
        (0.0, 0.0, 0.0, 0.0, 0.0, 1.0))


@jit
def slipping_pose(phase, x):
    Q, _, _ = orientation(phase.Q_ref, phase.k1, phase.k2, x[3], x[4])
    return Pose(phase.R1, (x[0], x[1], x[2]), Q, phase.R3)


# --- Newton-Raphson ------------------------------------------------------------------------------
@jit
def solve6(J, g, work):
    """Solve J x = g (6 x 6, rows as tuples) by Gaussian elimination with partial pivoting in the
    (6, 7) array ``work``; ok is False when a pivot is exactly zero (a singular Jacobian)."""
    n = 6
    for i in range(n):
        row = J[i]
        for j in range(n):
            work[i, j] = row[j]
        work[i, n] = g[i]
    for c in range(n):
        p, best = c, abs(work[c, c])
        for r in range(c + 1, n):
            if abs(work[r, c]) > best:
                p, best = r, abs(work[r, c])
        if best == 0.0:
            return False, g
        if p != c:
            for j in range(c, n + 1):
                work[c, j], work[p, j] = work[p, j], work[c, j]
        inverse = 1.0 / work[c, c]
        for r in range(c + 1, n):
            f = work[r, c] * inverse
            if f != 0.0:
                for j in range(c + 1, n + 1):
                    work[r, j] -= f * work[c, j]
    for i in range(n - 1, -1, -1):
        s = work[i, n]
        for j in range(i + 1, n):
            s -= work[i, j] * work[j, n]
        work[i, n] = s / work[i, i]
    return True, (work[0, n], work[1, n], work[2, n], work[3, n], work[4, n], work[5, n])


@jit
def newton(rows, phase, x, tol, max_iter, work):
    """Newton-Raphson on ``rows(phase, x)`` from x: (x, iterations, max |g|, status, g)."""
    for it in range(max_iter + 1):
        g, J = rows(phase, x)
        residual = max_abs(g)
        if residual <= tol:  # NaN fails
            return x, it, residual, CONVERGED, g
        if it == max_iter:
            break
        ok, dx = solve6(J, g, work)
        if not ok:
            return x, it, residual, SINGULAR, g
        x = (x[0] - dx[0], x[1] - dx[1], x[2] - dx[2], x[3] - dx[3], x[4] - dx[4], x[5] - dx[5])
    return x, max_iter, residual, NOT_CONVERGED, g


# --- the steps of the two models -----------------------------------------------------------------
NAN3 = (math.nan,) * 3
NAN_POSE = Pose(NAN3, NAN3, (NAN3, NAN3, NAN3), NAN3)


@jit
def guess(pose, R1):
    G = axpy(pose.G, 0.5, sub(R1, pose.R1))
    return (G[0], G[1], G[2], 0.0, 0.0, pose.R3[2])


# --- what a history shows ------------------------------------------------------------------------
@jit
def _reach(centre, a, radius, plate):
    """Largest horizontal distance from the plate's axis of a rim (centre, radius, normal a): at the
    rim's two points in the vertical plane through the axis a (the radial section, where the rim
    reaches furthest whenever the pad is near compatible), or along the rim centre's offset
    where the axis is vertical."""
    offset = sub(centre, plate)
    if math.hypot(a[0], a[1]) > 0:
        direction = (a[0], a[1], 0.0)
    elif math.hypot(offset[0], offset[1]) > 0:
        direction = (offset[0], offset[1], 0.0)
    else:
        direction = (1.0, 0.0, 0.0)
    # the in-rim direction of steepest horizontal extent: direction projected normal to a
    u = unit(axpy(direction, -dot(direction, a), a))
    p, q = axpy(offset, -radius, u), axpy(offset, radius, u)
    return max(math.hypot(p[0], p[1]), math.hypot(q[0], q[1]))


@jit
def clearances(pose, dev):
    """Clearance (m) between the pad and the retaining rings of RB1 and RB3 (negative beyond a
    ring): R^j sin(alpha^j) minus the largest horizontal distance of the pad's rim on that plate
    from the plate's axis."""
    a = pose.Q[2]
    return (dev.ring1 - _reach(axpy(pose.G, -dev.B, a), a, dev.A1, pose.R1),
            dev.ring3 - _reach(axpy(pose.G, dev.B, a), a, dev.A3, pose.R3))


@jit
def _store(out, n, pose, dev, m):
    """Row n of ``out`` (T, 24): R^1, G^2, the columns of Q, R^3, the interpenetration of the
    section's four rim points (positive into the plate) and the two clearances."""
    for i in range(3):
        out[n, i], out[n, 3 + i], out[n, 15 + i] = pose.R1[i], pose.G[i], pose.R3[i]
        for j in range(3):
            out[n, 6 + 3 * j + i] = pose.Q[j][i]
    rim = section(pose.Q, pose.G, dev, m)
    c1, c3 = C1(pose, dev), C3(pose, dev)
    out[n, 18] = norm(sub(rim[0], c1)) - dev.R1
    out[n, 19] = norm(sub(rim[1], c1)) - dev.R1
    out[n, 20] = norm(sub(rim[2], c3)) - dev.R3
    out[n, 21] = norm(sub(rim[3], c3)) - dev.R3
    out[n, 22], out[n, 23] = clearances(pose, dev)


@jit
def history(step, dev, Xg, theta2_0, azimuth, R3z, in_plane, tol, max_iter, stop_at_ring, ends, sticks, planes,
             solver, failure):
    """All the steps of one case: rows of ``ends``, ``sticks`` (T, 24; ``_store``), ``planes`` (T, 6:
    e1, m) and ``solver`` (T, 4: iterations and residual of sticking, then of the step's last
    phase). Starts from ``start`` at X_g[0]; ``azimuth`` also gives the direction of a zero ground
    increment. Returns the number of steps stored; a failed step fills ``failure`` (status, phase,
    then its six rows; status CONVERGED: none failed) and ends the history before it."""
    work = np.empty((6, 7))
    pose = start(dev, Xg[0, 0], Xg[0, 1], theta2_0, azimuth, R3z)
    reference = (math.cos(azimuth), math.sin(azimuth), 0.0)
    guide = (pose.R3[0], pose.R3[1])
    e1, m = step_plane(pose, dev, Xg[1, 0] - Xg[0, 0], Xg[1, 1] - Xg[0, 1], reference)
    for n in range(Xg.shape[0]):
        if n > 0:
            e1, m = step_plane(pose, dev, Xg[n, 0] - Xg[n - 1, 0], Xg[n, 1] - Xg[n - 1, 1], reference)
            R1 = (Xg[n, 0], Xg[n, 1], 0.0)
            end, stick, its1, res1, its, res, status, phase, g = step(dev, pose, R1, e1, m, guide, in_plane, tol,
                                                                      max_iter, work)
            if status != CONVERGED:
                failure[0], failure[1] = status, phase
                for i in range(6):
                    failure[2 + i] = g[i]
                return n
            pose = end
            solver[n, 0], solver[n, 1], solver[n, 2], solver[n, 3] = its1, res1, its, res
        else:
            stick = NAN_POSE
            solver[n, 0], solver[n, 1], solver[n, 2], solver[n, 3] = 0, 0.0, 0, 0.0
        _store(ends, n, pose, dev, m)
        _store(sticks, n, stick, dev, m)
        for i in range(3):
            planes[n, i], planes[n, 3 + i] = e1[i], m[i]
        if stop_at_ring and (ends[n, 22] < 0 or ends[n, 23] < 0):
            return n + 1
    return Xg.shape[0]


def in_space(entry) -> bool:
    """Whether a registry entry runs in space (has a spatial history)."""
    return entry.spatial is not None


#: the per-step quantities of a history, by column of the ``_store`` rows: name -> (columns, shape)
COLUMNS = {"R1": (slice(0, 3), (3,)), "G": (slice(3, 6), (3,)), "Q": (slice(6, 15), (3, 3)),
           "R3": (slice(15, 18), (3,)), "interpenetration": (slice(18, 22), (4,)),
           "clearance_1": (22, ()), "clearance_3": (23, ())}


def _ground(Xg):
    Xg = np.asarray(Xg, dtype=float)
    if Xg.ndim != 2 or Xg.shape[1] != 2 or Xg.shape[0] < 2:
        raise ValueError(f"Xg must have shape (T, 2) with T >= 2 (x, y of each step), got {Xg.shape}")
    if not np.isfinite(Xg).all():
        raise ValueError("Xg must be finite")
    return np.ascontiguousarray(Xg)


def _unpack(rows, prefix=""):
    out = {}
    for name, (cols, shape) in COLUMNS.items():
        values = rows[:, cols].reshape((len(rows),) + shape)
        out[prefix + name] = values.transpose(0, 2, 1) if name == "Q" else values  # stored by columns
    return out


def run(name, geometry, Xg, theta2_0=0.0, *, azimuth=0.0, options=NewtonOptions(), times=None, in_plane=False,
        stop_at_ring=False, compiled=True) -> dict:
    """The history of model ``name`` under X_g (T, 2) (m), as arrays, time first.

    ``azimuth`` (rad): the plane of theta2_0 and the direction of a zero increment. Keys: R1, G, R3
    (T, 3), Q (T, 3, 3), e1, m (T, 3), the solver figures, the interpenetration of the step's four
    rim points (T, 4; order RIM_POINTS) and the clearances to the rings (``clearance_1``,
    ``clearance_3``); for stick-slip the same of the end of sticking (``stick_`` prefix; NaN at
    n = 0). ``stop_at_ring``: end the history at the first step where the pad has passed a ring.
    ``in_plane=True`` solves each compliant step wholly in its plane pi, as the paper's Sec. 4
    reads: RB3 rises along the direction in pi normal to the increment, which leans from the
    vertical once the device is displaced across the increment, and RB3 leaves its guide (kept to
    measure that; not a model to use).

    A ConvergenceError (SingularJacobianError) names the step, time, phase and largest row and
    carries the history up to the last converged step as ``err.history``. ``compiled=False`` runs
    the same functions interpreted (about 2000 steps per second: a check of the compiled kernels,
    which agree with it to round-off, not a way to run).
    """
    entry = registry.model(name, in_space, " in space")
    Xg = _ground(Xg)
    dev = device(geometry)
    T = len(Xg)
    ends, sticks, planes = np.empty((T, 24)), np.empty((T, 24)), np.empty((T, 6))
    solver, failure = np.empty((T, 4)), np.zeros(8)
    kernel = scalar.kernel(entry.spatial) if compiled else entry.spatial
    done = kernel(dev, Xg, float(theta2_0), float(azimuth), float(geometry.Ry3_compatible(theta2_0)), bool(in_plane),
                   float(options.tol), int(options.max_iter), bool(stop_at_ring), ends, sticks, planes, solver, failure)
    history = _unpack(ends[:done])
    history["e1"], history["m"] = planes[:done, :3], planes[:done, 3:]
    history["newton_iterations"] = solver[:done, 2].astype(np.int64)
    history["residual"] = solver[:done, 3]
    if entry.sticking:
        history.update(_unpack(sticks[:done], "stick_"))
        history["newton_iterations_stick"] = solver[:done, 0].astype(np.int64)
        history["residual_stick"] = solver[:done, 1]
    if failure[0] != CONVERGED:  # else a history shorter than Xg stopped at a ring
        err = _failure(failure, done, times, options)
        err.history = history if done else None
        raise err
    return history


def _failure(failure, n, times, options) -> ConvergenceError:
    """The error of a failed step n (``failure``: status, phase, then its six rows)."""
    status, phase, g = int(failure[0]), int(failure[1]), failure[2:]
    where = f"step {n}" + ("" if times is None else f", time {float(times[n]):.6g} s")
    if status == SINGULAR:
        return SingularJacobianError(f"singular constraint Jacobian in {PHASE_NAMES[phase]} ({where}): the rows do "
                                     "not fix the pad here.", "Check the geometry and the step size.")
    a = np.where(np.isnan(g), np.inf, np.abs(g))
    row = int(np.argmax(a))
    hint = (f"The residual stalls within {STALLED:g} times the tolerance: round-off, not divergence; raise newton.tol."
            if a[row] <= STALLED * options.tol else
            "Likely cause: a step too large for the geometry (the constraints cannot follow the ground increment): "
            "reduce dt or the amplitude.")
    return ConvergenceError(
        f"Newton-Raphson did not converge in {PHASE_NAMES[phase]} ({where}): after {options.max_iter} iterations "
        f"the residual is {a[row]:.3e} m > tol {options.tol:.1e} m; largest: {LABELS[phase][row]} = {g[row]:.3e}.",
        hint)


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
    dev = device(geometry)
    G, Q, R1, R3 = (history[prefix + k] for k in ("G", "Q", "R1", "R3"))
    a = Q[..., :, 2]
    up = np.array(Z)
    out = {}
    out["tilt"], out["tilt_azimuth"] = tilt(Q)
    out["rise"] = R3[:, 2] - dev.rest3
    out["gap_1"] = np.linalg.norm(G + dev.y21 * a - (R1 + dev.c1 * up), axis=-1)
    out["gap_3"] = np.linalg.norm(G + dev.y23 * a - (R3 + dev.c3 * up), axis=-1)
    for key in ("interpenetration", "clearance_1", "clearance_3"):
        out[key] = history[prefix + key]
    return out


# --- what a sweep keeps of a history --------------------------------------------------------------
def summary(history, geometry) -> dict:
    """The per-case summaries of a history (``dccss.mechanics.summaries.specs``; ``runs.summaries``
    applies the run policies). Under bidirectional motion |theta2| is the tilt: ``theta2_max_abs`` is
    the largest tilt and ``theta2_end`` the residual tilt (>= 0); the corners A, B, C, D are the
    trailing and leading rim points of each step's section on RB1 and on RB3 (for motion along +x,
    the planar corners); ``sticking_rotation_max`` is the largest angle the pad turns through in a
    sticking phase."""
    d = diagnostics(history, geometry)
    tilt_deg = np.degrees(d["tilt"])
    steps = len(tilt_deg)
    its = history["newton_iterations"] + history.get("newton_iterations_stick", 0)
    out = {"theta2_max_abs": tilt_deg.max(), "theta2_end": tilt_deg[-1], "rise_max": d["rise"].max(),
           "rise_end": d["rise"][-1], "clearance_min": min(d["clearance_1"].min(), d["clearance_3"].min()),
           **{f"I_{c}_max": np.nanmax(d["interpenetration"][1:, i]) if steps > 1 else np.nan
              for i, c in enumerate("ABCD")},
           "newton_iterations_max": np.int32(its.max()), "newton_iterations_mean": its.sum() / max(steps - 1, 1)}
    if "stick_Q" in history:
        turn = np.full(1, np.nan)
        if steps > 1:
            relative = np.einsum("tij,tkj->tik", history["stick_Q"][1:], history["Q"][:-1])
            turn = np.arccos(np.clip(0.5 * (np.trace(relative, axis1=1, axis2=2) - 1.0), -1.0, 1.0))
        out["sticking_rotation_max"] = np.degrees(turn.max())
        out["rise_stick_max"] = np.nanmax(history["stick_R3"][1:, 2] - device(geometry).rest3) if steps > 1 else np.nan
    return out

