"""Geometry of a DCCSS (double friction pendulum) derived from the Table 1 parameters.

Frames follow the paper (Fig. 3): X to the right, Y up, angles counter-clockwise.
Each body has a local frame at its centroid G^i:

* RB1, the lower plate: concave face up, circle centre C^1 = (0, h_s^1 + R^1).
* RB2, the pad: origin at mid-height of the straight part; corners
  A^2 = (-A_1, -B), B^2 = (+A_1, -B), C^2 = (-A_3, +B), D^2 = (+A_3, +B), with
  A_j = R^j sin(alpha^2j) and B = h^2 / 2; convex cap centres
  C^21 = (0, R^1 cos alpha^21 - B) and C^23 = (0, B - R^3 cos alpha^23).
* RB3, the upper plate: concave face down, circle centre C^3 = (0, -h_s^3 - R^3).

h_s^j is the distance from a plate's centroid (of its planar cross-section, rings included)
down (RB1) or up (RB3) to the most depressed point of its concave face. It only shifts
absolute R_y values.

Every field may be a float or an array: arrays broadcast, and a Geometry of arrays is a batch
of devices (used by parameter sweeps).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from functools import cached_property

import numpy as np

LENGTHS = ("R1", "R3", "h2", "hr1", "hr3", "hmin1", "hmin3", "tr1", "tr3")
ANGLES = ("alpha1", "alpha3", "alpha21", "alpha23")


def _first_bad(mask: np.ndarray, value: np.ndarray) -> str:
    """Describe the first offending element of a (possibly batched) parameter."""
    value = np.broadcast_to(value, mask.shape)
    if mask.ndim == 0:  # 12 digits: an angle's round trip through radians shows as given
        return f"{float(value):.12g}"
    index = tuple(int(i) for i in np.argwhere(mask)[0])
    return f"{float(value[index]):.12g} (at batch index {index})"


@dataclass(frozen=True, eq=False)
class Geometry:
    """Table 1 parameters of a DCCSS prototype, in SI units (m, rad).

    Parameters
    ----------
    R1, R3 : float
        Radii of the concave surfaces of RB1 and RB3 (m).
    alpha1, alpha3 : float
        Half opening angles of the concave surfaces (rad).
    h2 : float
        Height of the straight cylinder of the pad RB2 (m).
    alpha21, alpha23 : float
        Half opening angles of the pad's convex caps (rad).
    hr1, hr3 : float
        Heights of the retaining rings (m).
    hmin1, hmin3 : float
        Plate thickness under the most depressed point (m).
    tr1, tr3 : float
        Thicknesses of the retaining rings (m).

    Raises
    ------
    ValueError
        If a value is not finite, a length is not positive, an angle is outside
        0 < alpha^j < 90 deg, a cap is not narrower than its plate (alpha^2j < alpha^j), or
        the pad is too tall for the two concave centres to be apart (L <= 0).
    """

    R1: float
    R3: float
    alpha1: float
    alpha3: float
    h2: float
    alpha21: float
    alpha23: float
    hr1: float
    hr3: float
    hmin1: float
    hmin3: float
    tr1: float
    tr3: float

    def __post_init__(self):
        problems = []  # every mistake at once, each naming its parameter
        for f in fields(self):
            value = getattr(self, f.name)
            kind = np.asarray(value).dtype.kind if not isinstance(value, (str, bytes)) else "U"
            if value is None or kind not in "iuf":  # None, strings, booleans: not numbers (float() takes them)
                problems.append(f"geometry parameter {f.name!r} must be a number, got {value!r}")
                continue
            arr = np.asarray(value, dtype=float)
            object.__setattr__(self, f.name, arr if arr.ndim else float(arr))
            bad = ~np.isfinite(arr)
            if bad.any():
                problems.append(f"geometry parameter {f.name!r} must be finite, got {_first_bad(bad, arr)}")
        if problems:
            raise ValueError("; ".join(problems))
        for name in LENGTHS:
            arr = np.asarray(getattr(self, name))
            bad = arr <= 0
            if bad.any():
                problems.append(f"geometry parameter {name!r} is a length and must be > 0 m, "
                                f"got {_first_bad(bad, arr)}")
        for name in ("alpha1", "alpha3"):
            arr = np.asarray(getattr(self, name))
            bad = (arr <= 0) | (arr >= np.pi / 2)
            if bad.any():
                problems.append(f"geometry parameter {name!r} must lie in 0 < {name} < 90 deg, "
                                f"got {_first_bad(bad, np.degrees(arr))} deg")
        for cap, plate, radius in (("alpha21", "alpha1", "R1"), ("alpha23", "alpha3", "R3")):
            arr, lim = np.asarray(getattr(self, cap)), np.asarray(getattr(self, plate))
            bad = (arr <= 0) | (arr >= lim)
            if bad.any():
                problems.append(f"geometry parameter {cap!r} must lie in 0 < {cap} < {plate} (the pad cap must be "
                                f"narrower than its plate, {radius}·sin({cap}) < {radius}·sin({plate})), "
                                f"got {_first_bad(bad, np.degrees(arr))} deg")
        if problems:  # L is meaningful only for valid lengths and angles
            raise ValueError("; ".join(problems))
        bad = np.asarray(self.L) <= 0
        if bad.any():
            raise ValueError(
                "geometry: the pad is too tall: the centre distance "
                "L = R1 cos(alpha21) + R3 cos(alpha23) - h2 must be > 0 m, "
                f"got {_first_bad(bad, np.asarray(self.L))}"
            )

    @classmethod
    def from_degrees(cls, **params) -> Geometry:
        """Build from Table 1 style values: lengths in m, angles in degrees."""
        names = {f.name for f in fields(cls)}
        unknown = sorted(set(params) - names)
        if unknown:
            raise ValueError(f"unknown geometry parameter(s) {unknown}; allowed: {sorted(names)}")
        missing = sorted(names - set(params))
        if missing:
            raise ValueError(f"missing geometry parameter(s) {missing}")
        converted = {}
        for key, value in params.items():
            if key in ANGLES and value is not None and not isinstance(value, (str, bytes, bool)):
                try:
                    value = np.radians(np.asarray(value, dtype=float))
                except (TypeError, ValueError):
                    raise ValueError(
                        f"geometry parameter {key!r} must be a number, got {value!r}"
                    ) from None
            converted[key] = value
        return cls(**converted)

    def as_degrees(self) -> dict:
        """The parameters as given in Table 1 style (m, degrees)."""
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            out[f.name] = np.degrees(value) if f.name in ANGLES else value
        return out

    # --- pad (RB2) -------------------------------------------------------------------------
    @cached_property
    def A1(self):
        """Half width of the pad's lower cap, R^1 sin(alpha^21) (m)."""
        return self.R1 * np.sin(self.alpha21)

    @cached_property
    def A3(self):
        """Half width of the pad's upper cap, R^3 sin(alpha^23) (m)."""
        return self.R3 * np.sin(self.alpha23)

    @cached_property
    def B(self):
        """Half height of the pad's straight part, h^2 / 2 (m)."""
        return 0.5 * self.h2

    @cached_property
    def pad_corners(self) -> np.ndarray:
        """Local coordinates of A^2, B^2, C^2, D^2 in the pad frame, shape (..., 4, 2) (m)."""
        A1, A3, B = np.broadcast_arrays(self.A1, self.A3, self.B)
        x = np.stack([-A1, A1, -A3, A3], axis=-1)
        y = np.stack([-B, -B, B, B], axis=-1)
        return np.stack([x, y], axis=-1)

    @cached_property
    def pad_cap_centres(self) -> np.ndarray:
        """Local coordinates of C^21 and C^23 in the pad frame, shape (..., 2, 2) (m)."""
        y21 = self.R1 * np.cos(self.alpha21) - self.B
        y23 = self.B - self.R3 * np.cos(self.alpha23)
        y21, y23 = np.broadcast_arrays(y21, y23)
        zero = np.zeros_like(y21)
        return np.stack([np.stack([zero, y21], -1), np.stack([zero, y23], -1)], axis=-2)

    @cached_property
    def L(self):
        """Distance C^1 C^3 in a compatible configuration (bracket of Eq. 41) (m)."""
        return self.R1 * np.cos(self.alpha21) + self.R3 * np.cos(self.alpha23) - self.h2

    # --- plates (RB1, RB3) -----------------------------------------------------------------
    @cached_property
    def hs1(self):
        """Distance from RB1's centroid up to the most depressed point of its face (m)."""
        return -_section_centroid(self.R1, self.alpha1, self.hmin1, self.hr1, self.tr1)

    @cached_property
    def hs3(self):
        """Distance from RB3's centroid down to the most depressed point of its face (m)."""
        return -_section_centroid(self.R3, self.alpha3, self.hmin3, self.hr3, self.tr3)

    @cached_property
    def circle_centres(self) -> np.ndarray:
        """Local coordinates of C^1 (in RB1) and C^3 (in RB3), shape (..., 2, 2) (m)."""
        y1 = self.hs1 + self.R1
        y3 = -self.hs3 - self.R3
        y1, y3 = np.broadcast_arrays(y1, y3)
        zero = np.zeros_like(y1)
        return np.stack([np.stack([zero, y1], -1), np.stack([zero, y3], -1)], axis=-2)

    @cached_property
    def capacity1(self):
        """Displacement capacity of the lower sliding surface, R^1 sin(alpha^1 - alpha^21) (m): Table 1's
        X_g,max. The device's, RB1's displacement from RB3 when the pad reaches the ring of RB1, is
        L sin(alpha^1 - alpha^21) under compliant sliding (``capacity.capacity_message``)."""
        return self.R1 * np.sin(self.alpha1 - self.alpha21)

    @cached_property
    def capacity3(self):
        """Displacement capacity of the upper sliding surface, R^3 sin(alpha^3 - alpha^23) (m)."""
        return self.R3 * np.sin(self.alpha3 - self.alpha23)

    @cached_property
    def ring_inner_x(self) -> np.ndarray:
        """Half distance between the inner faces of the rings, R^j sin(alpha^j), shape (..., 2)."""
        a1, a3 = np.broadcast_arrays(self.R1 * np.sin(self.alpha1), self.R3 * np.sin(self.alpha3))
        return np.stack([a1, a3], axis=-1)

    def Ry3_compatible(self, theta):
        """Eq. 41: R_y^3 of a compatible configuration whose C^1C^3 is inclined by theta (rad),
        with RB1 at R_y^1 = 0 and theta^1 = theta^3 = 0."""
        return self.hs1 + self.R1 + self.hs3 + self.R3 - self.L * np.cos(theta)

    def compatible(self, theta2, Xg=0.0) -> np.ndarray:
        """Compatible configuration q (..., 9) at pad rotation theta2 (rad), RB1 at R_x^1 = Xg.

        The pad axis lies on C^1C^3 with C^21 = C^1 and C^23 = C^3; RB3 is offset sideways by
        L sin(theta2) (Eq. 5's R_x^3 = 0 only admits theta2 = 0).
        """
        theta2, Xg = np.broadcast_arrays(np.asarray(theta2, float), np.asarray(Xg, float))
        shape = np.broadcast_shapes(theta2.shape, np.shape(self.L))
        theta2, Xg = np.broadcast_to(theta2, shape), np.broadcast_to(Xg, shape)
        s, c = np.sin(theta2), np.cos(theta2)
        C1y = self.hs1 + self.R1
        y21 = self.R1 * np.cos(self.alpha21) - self.B
        q = np.zeros(shape + (9,))
        q[..., 0] = Xg
        q[..., 3] = Xg + y21 * s  # G^2 = C^1 - A(theta2) C^21
        q[..., 4] = C1y - y21 * c
        q[..., 5] = theta2
        q[..., 6] = Xg + self.L * s
        q[..., 7] = self.Ry3_compatible(theta2)
        return q

    # --- drawings --------------------------------------------------------------------------
    def plate_outline(self, plate: int, n_arc: int = 121) -> np.ndarray:
        """Closed outline of RB1 (plate=1) or RB3 (plate=3) in its local frame, shape (n, 2) (m).

        The plate is a block h_min thick under the most depressed point of a concave recess
        (radius R, half opening alpha), with retaining rings t_r thick rising h_r above the
        recess edge. Only for scalar geometries.
        """
        if plate not in (1, 3):
            raise ValueError(f"plate must be 1 or 3, got {plate!r}")
        R, alpha, hmin, hr, tr, hs = (
            (self.R1, self.alpha1, self.hmin1, self.hr1, self.tr1, self.hs1)
            if plate == 1
            else (self.R3, self.alpha3, self.hmin3, self.hr3, self.tr3, self.hs3)
        )
        a, f = R * np.sin(alpha), R * (1 - np.cos(alpha))
        phi = np.linspace(alpha, -alpha, n_arc)  # from the right edge through the bottom
        arc = np.column_stack([R * np.sin(phi), R - R * np.cos(phi)])
        outer = np.array(
            [
                [-a, f + hr],
                [-a - tr, f + hr],
                [-a - tr, -hmin],
                [a + tr, -hmin],
                [a + tr, f + hr],
                [a, f + hr],
            ]
        )
        pts = np.vstack([outer[3:], arc, outer[:3], outer[3:4]])
        pts[:, 1] += hs  # origin at the centroid, h_s below the most depressed point
        if plate == 3:
            pts[:, 1] *= -1
        return pts

    def pad_outline(self, n_arc: int = 61) -> np.ndarray:
        """Closed outline of the pad RB2 in its frame, shape (n, 2) (m). Only for scalars."""
        (c21, c23) = self.pad_cap_centres
        lower = np.linspace(-self.alpha21, self.alpha21, n_arc)
        upper = np.linspace(self.alpha23, -self.alpha23, n_arc)
        low = np.column_stack([self.R1 * np.sin(lower), c21[1] - self.R1 * np.cos(lower)])
        up = np.column_stack([self.R3 * np.sin(upper), c23[1] + self.R3 * np.cos(upper)])
        return np.vstack([low, up, low[:1]])


#: the 13 Table 1 parameters of a device, in order (lengths in m, angles in degrees in files)
PARAMETERS = tuple(f.name for f in fields(Geometry))


def _section_centroid(R, alpha, hmin, hr, tr):
    """Height of a plate section's centroid above the most depressed point of its recess.

    Section: |x| <= a = R sin(alpha), -hmin <= y <= R - sqrt(R^2 - x^2) (block under the
    recess) and a < |x| <= a + tr, -hmin <= y <= f + hr (rings), f = R(1 - cos alpha).
    """
    a, f = R * np.sin(alpha), R * (1 - np.cos(alpha))
    S = R**2 * (alpha + np.sin(alpha) * np.cos(alpha))  # integral of sqrt(R^2 - x^2) over |x|<=a
    area = 2 * a * R - S + 2 * a * hmin + 2 * tr * (f + hr + hmin)
    moment = 0.5 * (4 * a * R**2 - 2 * a**3 / 3 - 2 * R * S - 2 * a * hmin**2) + tr * (
        (f + hr) ** 2 - hmin**2
    )
    return moment / area
