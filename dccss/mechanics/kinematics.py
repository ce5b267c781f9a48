"""Planar rigid-body kinematics of the three bodies (Eqs. 1-3) and the pad-plate contacts.

Configurations are real arrays q of shape (..., 9) ordered as Eq. 4:
[R_x^1, R_y^1, theta^1, R_x^2, R_y^2, theta^2, R_x^3, R_y^3, theta^3]; leading dimensions
are a batch. Points and vectors of the plane are complex numbers x + iy, so that Eq. 1,
r = R + A(theta) u, reads r = R + e^{i theta} u, and a . b = Re(a conj(b)).

The functions work on one corner at a time, with components that are scalars (one case: the
fast path) or arrays (a batch): the same expressions serve both.
"""

from __future__ import annotations

import cmath
from dataclasses import dataclass

import numpy as np

#: the coordinates q of Eq. 4, in order
Q_NAMES = ("Rx1", "Ry1", "theta1", "Rx2", "Ry2", "theta2", "Rx3", "Ry3", "theta3")
CORNERS = ("A", "B", "C", "D")
RB1, RB2, RB3 = 0, 3, 6  # index of each body's R_x in q
NORMALS = ("signed", "unsigned")
_CORNER_DEF = {"A": (RB1, -1.0), "B": (RB1, 1.0), "C": (RB3, -1.0), "D": (RB3, 1.0)}


def dot(a, b):
    """Scalar product of planar vectors given as complex numbers, Re(a conj(b))."""
    return a.real * b.real + a.imag * b.imag


def frames(q):
    """Positions R (complex) and e^{i theta} of RB1, RB2, RB3: [(R^1, e^1), (R^2, e^2), (R^3, e^3)].

    For one configuration (q of shape (9,), or a list) the values are Python scalars, for speed.
    """
    if isinstance(q, list) or q.ndim == 1:
        x = q if isinstance(q, list) else q.tolist()
        return [(complex(x[b], x[b + 1]), cmath.exp(1j * x[b + 2])) for b in (RB1, RB2, RB3)]
    return [(q[..., b] + 1j * q[..., b + 1], _expi_batch(q[..., b + 2])) for b in (RB1, RB2, RB3)]


#: e^{i theta} of a batch whose rotations are all exactly zero (the plates, in every set)
UNIT = 1.0 + 0.0j


def _expi_batch(theta):
    return np.exp(1j * theta) if theta.any() else UNIT


def turn(e, z):
    """e z, skipping the product when e is exactly UNIT (a batch of unrotated plates)."""
    return z if e is UNIT else e * z


@dataclass(frozen=True, eq=False)
class Corner:
    """A pad corner and the terms of the plate it bears on, derived once.

    body : RB1 or RB3; side : -1 (left) or +1 (right); u2 : pad-frame position (complex);
    radius, centre : the plate's concave circle (centre in the plate frame, complex);
    sign : +1 on RB1 (circle centre above the face), -1 on RB3. Fields may be batch arrays.
    """

    name: str
    body: int
    side: object
    u2: object
    radius: object
    centre: object
    sign: float

    @classmethod
    def of(cls, geometry, name) -> Corner:
        body, side = _CORNER_DEF[name]
        lower = body == RB1
        half = geometry.A1 if lower else geometry.A3
        y = -geometry.B if lower else geometry.B
        centre = geometry.circle_centres[..., 0 if lower else 1, 1] * 1j
        radius = geometry.R1 if lower else geometry.R3
        return cls(name, body, side, _scalar(side * half + 1j * y), radius, _scalar(centre),
                   1.0 if lower else -1.0)

    def where(self, mask, other: Corner) -> Corner:
        """Per case: ``other`` where mask is True, self elsewhere (same plate)."""
        if np.ndim(mask) == 0:
            return other if mask else self
        return Corner(f"{self.name}/{other.name}", self.body, np.where(mask, other.side, self.side),
                      np.where(mask, other.u2, self.u2), self.radius,
                      np.where(mask, other.centre, self.centre), self.sign)


def _scalar(x):
    return complex(x) if np.ndim(x) == 0 else x


def all_corners(geometry) -> tuple[Corner, ...]:
    return tuple(Corner.of(geometry, name) for name in CORNERS)


def position(F, corner: Corner):
    """Global position of the corner (complex); F = frames(q)."""
    R2, e2 = F[1]
    return R2 + e2 * corner.u2


def local(F, corner: Corner):
    """The corner's position in its plate's frame (complex)."""
    R, e = F[corner.body // 3]
    d = position(F, corner) - R
    return d if e is UNIT else d * e.conjugate()


def interpenetration(q, geometry):
    """Signed interpenetration I_A, I_B, I_C, I_D (..., 4) (m), positive into the plate,
    measured along the radius through the corner: |r_P - C^j| - R^j."""
    return corner_diagnostics(q, geometry)[0]


def corner_diagnostics(q, geometry, locals_=None):
    """Interpenetration (..., 4) and clearance to the rings (..., 2), from one pass over the
    corners (or from their plate-frame positions ``locals_``, if already known)."""
    corners = all_corners(geometry)
    if locals_ is None:
        F = frames(q)
        locals_ = [local(F, c) for c in corners]
    interp = [np.abs(u - c.centre) - c.radius for u, c in zip(locals_, corners)]
    reach = [np.abs(np.real(u)) for u in locals_]
    gap = geometry.ring_inner_x - np.stack([np.maximum(reach[0], reach[1]), np.maximum(reach[2], reach[3])], -1)
    return np.stack(interp, axis=-1), gap


def contact_angle(normal, corner: Corner):
    """Contact angle alpha (rad) of Eqs. 8-11 from the plate-frame normal
    n = (-s sin alpha, v cos alpha), v = +1 on RB1, -1 on RB3: positive towards the corner's side."""
    return np.arctan2(-corner.side * np.real(normal), corner.sign * np.imag(normal))


def start(geometry, Xg, theta2_0):
    """The compatible start of a run at theta^2(t_0) with RB1 at X_g[0] (``geometry.compatible``),
    X_g broadcast to (T, batch...) and R_x^3 (RB3's guided abscissa); one case as Python scalars."""
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
