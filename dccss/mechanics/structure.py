"""The isolated structure: a rigid superstructure on the device, driven by the ground's acceleration.

The superstructure (mass m, weight W = m g) rests on the device. Its displacement relative to the
ground, the device's **stroke** u (m; one component, or two: x, y), obeys

    m ü + c u̇ + F = -m a_g(t),      F = (W / L) u + μ W z,      c = 2 ζ m ω,   ω² = g / L,

the friction pendulum of Zayas, Low and Mahin, and of Fenz and Constantinou's double friction
pendulum with equal friction on both sliding surfaces (OpenSees' ``singleFPBearing``). L = |C¹C³|
(``Geometry.L``): under compliant sliding the pad lies on C¹C³, RB3 moves sideways by L sin θ² and
rises by L (1 - cos θ²) (Eq. 41, ``Geometry.compatible``), so the superstructure's weight does
work W L (1 - cos θ²) ≈ W u² / (2 L): a pendulum of length L, whose restoring force is W u / L to
first order in u / L. μ is the device's friction coefficient as OpenSees and the Fenz-Constantinou
model use it: the force at zero stroke while sliding is μ W. The friction state z (|z| <= 1) is
u̇ / |u̇| while the structure slides, and sticking (u̇ = 0) holds while the force the friction must
supply, |-m a_g - W u / L|, is at most μ W; then z is that force over μ W. Dividing by m, W drops
out: only μ, ζ, L and g = 9.80665 m/s² remain.

**The vertical component.** A vertical ground acceleration a_v (up positive) changes the normal force
on the device to N = W (1 + a_v / g): the superstructure, rigid and rigidly carried vertically by the
device, is accelerated upwards with the ground. Both the pendulum's restoring force N u / L and the
friction μ N scale with N, so

    ü + 2ζω u̇ + (1 + a_v/g) (ω² u + μ g z) = -a_g,

with c = 2ζmω from the nominal period (the damping does not follow N), and sticking holds while
|-a_g - (1 + a_v/g) ω² u| <= μ g (1 + a_v/g). A constant a_v is the horizontal problem with g replaced
by g + a_v. Where N <= 0 the superstructure lifts off: the device holds it neither way (no restoring
force, no friction) and u follows ü = -a_g - 2ζω u̇ until it lands; the intervals are found exactly on
the straight lines joining the samples (``Ground.uplift``) and what follows them describes no real
structure (the landing's impact is not modelled). Neglected: the vertical inertia of the pad and of a
flexible superstructure beyond the rigid-body term (the normal force is W (1 + a_v/g) exactly only for
a rigid mass on a rigid device), rocking, and the second-order N = W + F u / R of OpenSees'
``singleFPBearing``. With a vertical, one component is solved by the two-component integrator (below),
its second component without load.

The ground acceleration is given as ``Ground``: on each interval [t_k, t_k+1] a straight line
a0_k + a1_k (t - t_k) (one column per component), as a record's samples are joined (and a
displacement table's piecewise-constant acceleration).

* One component (``respond``, :func:`_line`): solved exactly. On each interval the sliding
  equation is linear with a linear right-hand side, solved in closed form (a damped oscillator
  with a linear load); the ends of sliding (u̇ = 0) are roots of that closed form, found by
  bisection to the last bit; sticking ends where a straight line reaches ±μ g (exact). The
  solution is exact to rounding: no time step, no elastic branch.
* Two components (the circular interaction, z a vector): the sliding equation is nonlinear
  (ü = -a_g - ω² u - 2 ζ ω u̇ - μ g u̇ / |u̇|), integrated by DOP853 (the Runge-Kutta pair of order 8
  of Hairer, Nørsett and Wanner, with scipy's tableau and step-size control; relative tolerance
  ``RTOL``, absolute ``ATOL`` in m and m/s), with sticking as an event: a phase of sliding ends
  where |u̇| falls to 1e-9 m/s (the rest of the way to rest takes at most 1e-9 / (μ g - |f|) s,
  and moves the structure less than 1e-17 m), and sticking ends where |f|, a quadratic in t on an
  interval, reaches μ g (exact; in two components sticking holds while |f| <= μ g (1 + ``RTOL``),
  so that a stop where the force equals the friction to within the integration's accuracy is
  not decided by rounding). The integrator (``plane``) is written for Numba like the device's
  kernels: compiled for a long record, interpreted for a short one, with the same bits, and no
  BLAS (whose kernels OpenBLAS chooses by processor).
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from . import scalar
from .friction import COULOMB, FACTOR, LAWS, ROW, T0, WEIGHT, FrictionError, device_mu, row, surface_mu

G = 9.80665  # standard gravity (m/s²)
#: a stop in two components: |u̇| (m/s) below which the structure is at rest
REST_SPEED = 1e-9
#: a start from rest in two components: the friction is along the force until |u̇| (m/s) reaches this
START_SPEED = 1e-7
#: the two-component integrator's tolerances (relative; absolute, in m and m/s)
RTOL, ATOL = 1e-12, 1e-14


class StructureError(ValueError):
    """A structure's parameters are out of range; each message names its key (``messages``)."""

    def __init__(self, *messages):
        self.messages = list(messages)
        super().__init__("; ".join(messages))


#: what a structure's ``friction`` is the coefficient of: the device (μ, the force at zero stroke is
#: μ W), or each of its two sliding surfaces (μs; the device's is then μs (R¹ + R³) / L)
FRICTION_ON = ("device", "surfaces")


@dataclass(frozen=True)
class Structure:
    """A rigid superstructure on the device: its friction (``friction``) on the device
    (``friction_on="device"``: the force at zero stroke is μ W) or on each sliding surface
    (``"surfaces"``, see :meth:`device_friction`), the viscous damping ratio ζ (``damping``, 0 <= ζ < 1,
    of the pendulum's frequency) and the property modification factor λ (``factor``, > 0) that
    multiplies every friction coefficient (a design code's bound).

    ``friction`` is a number μ (0 <= μ < 1; 0 a frictionless pendulum: Coulomb friction), a law
    ``{law: velocity, slow: ..., fast: ..., rate: ...}`` (``dccss.mechanics.friction.LAWS``), or with
    ``friction_on="surfaces"`` one number or law for both surfaces or a list of two, RB1's and RB3's."""

    friction: object
    damping: float = 0.0
    friction_on: str = "device"
    factor: float = 1.0
    laws: list = field(init=False, repr=False, compare=False)  # [(Law, values)]: the device's, or RB1's and RB3's

    def __post_init__(self):
        problems = []
        if self.friction_on not in FRICTION_ON:
            problems.append(f"structure.friction_on: must be one of {list(FRICTION_ON)}, got {self.friction_on!r}")
        try:
            object.__setattr__(self, "laws", _laws(self.friction, self.friction_on == "surfaces"))
        except StructureError as err:
            problems += err.messages
        for key, value, allowed, ok in (("damping", self.damping, "0 <= ζ < 1", lambda x: 0.0 <= x < 1.0),
                                        ("property", self.factor, "λ > 0", lambda x: x > 0.0)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                problems.append(f"structure.{key}: expected a number, got {type(value).__name__} {value!r}")
                continue
            if not (math.isfinite(float(value)) and ok(float(value))):
                problems.append(f"structure.{key}: {float(value)!r} is outside {allowed}")
            object.__setattr__(self, "factor" if key == "property" else key, float(value))
        if problems:
            raise StructureError(*problems)
        if isinstance(self.friction, (int, float, np.integer, np.floating)):
            object.__setattr__(self, "friction", float(self.friction))

    @property
    def coulomb(self) -> bool:
        """Whether the friction is Coulomb's, a constant μ (numbers, or the coulomb law)."""
        return all(law.name == "coulomb" for law, _ in self.laws)

    def device_friction(self, geometry) -> float:
        """The device's friction coefficient μ on ``geometry`` (its L, R1, R3), times λ: Coulomb's, or a
        law's breakaway value (at zero speed, N = W and the plates' starting temperature).

        With ``friction_on="surfaces"``, ``friction`` is each sliding surface's coefficient and
        μ = (μ1 R¹ + μ3 R³) / L: a rigid pad that turns by dθ about both sphere centres slides R¹ dθ on
        RB1 and R³ dθ on RB3 under the normal force W (to first order in the tilt), so friction
        does the work W (μ1 R¹ + μ3 R³) dθ while the stroke grows by L dθ."""
        if not self.coulomb:
            mu = float(sum(r[WEIGHT] * r[FACTOR] * surface_mu(r, 0.0, 1.0, r[T0]) for r in self.rows(geometry)))
        elif self.friction_on == "device":
            mu = self.laws[0][1]["mu"] * self.factor
        else:
            mu1, mu3 = (values["mu"] for _, values in self.laws)
            R1, R3, L = float(geometry.R1), float(geometry.R3), float(geometry.L)
            mu = (mu1 * float(geometry.R1 + geometry.R3) / L if mu1 == mu3 else (mu1 * R1 + mu3 * R3) / L) * self.factor
        if not mu < 1.0:
            raise StructureError(f"structure.friction: {self.friction!r} is a device friction {mu:.4g} = (μ1 R1 + "
                                 f"μ3 R3) / L times λ, outside 0 <= μ < 1")
        return mu

    def rows(self, geometry) -> np.ndarray:
        """The kernel's rows of the friction laws on ``geometry``: one for the device, or RB1's and RB3's
        surfaces weighted by R^j / L (their sliding speed R^j / L times the stroke's)."""
        if self.friction_on == "device":
            return np.array([row(law, values, factor=self.factor) for law, values in self.laws])
        ratios = [float(geometry.R1) / float(geometry.L), float(geometry.R3) / float(geometry.L)]
        return np.array([row(law, values, weight=r, ratio=r, factor=self.factor)
                         for (law, values), r in zip(self.laws, ratios)])

    def attrs(self, geometry) -> dict:
        """netCDF attributes of the structure on ``geometry`` (a device of pendulum length L)."""
        given = self.friction if isinstance(self.friction, float) else json.dumps(self.friction, sort_keys=True)
        out = {"structure_friction": self.device_friction(geometry), "structure_damping": self.damping,
               "structure_friction_on": self.friction_on, "structure_friction_given": given,
               "structure_friction_law": " + ".join(law.name for law, _ in self.laws),
               "structure_pendulum_length_m": float(geometry.L), "structure_period_s": period(geometry.L)}
        if self.factor != 1.0:
            out["structure_property_factor"] = self.factor
        return out


def _laws(friction, surfaces) -> list:
    """[(Law, values)] of ``friction``: one (the device's), or RB1's and RB3's with ``surfaces``."""
    if surfaces and isinstance(friction, list):
        if len(friction) != 2:
            raise StructureError(f"structure.friction: with friction_on: surfaces, one law or number for both "
                                 f"surfaces or a list of two (RB1's, RB3's), got {len(friction)}")
        return [_law(f, f"structure.friction[{i}]") for i, f in enumerate(friction)]
    one = _law(friction, "structure.friction")
    return [one, one] if surfaces else [one]


def _law(spec, key) -> tuple:
    """(Law, values) of a number (Coulomb's μ) or a law mapping; errors name ``key``."""
    if isinstance(spec, (int, float, np.integer, np.floating)) and not isinstance(spec, bool):
        if not (math.isfinite(float(spec)) and 0.0 <= float(spec) < 1.0):
            raise StructureError(f"{key}: {float(spec)!r} is outside 0 <= μ < 1")
        return COULOMB, {"mu": float(spec)}
    if not isinstance(spec, dict):
        raise StructureError(f"{key}: expected a number (Coulomb's μ) or a law {{law: {' | '.join(LAWS)}, ...}}, "
                             f"got {type(spec).__name__} {spec!r}")
    name = spec.get("law")
    if name not in LAWS:
        raise StructureError(f"{key}.law: must be one of {list(LAWS)}, got {name!r}")
    try:
        return LAWS[name], LAWS[name].values(spec, key)
    except FrictionError as err:
        raise StructureError(*err.messages) from None


def period(L) -> float:
    """The pendulum's period 2π √(L / g) (s)."""
    return float(2 * np.pi * np.sqrt(L / G))


class Ground(NamedTuple):
    """A piecewise-linear ground acceleration: a0[k] + a1[k] (t - time[k]) on [time[k], time[k+1]]
    (m/s², m/s³), with a column per component (shape (n, c)); and the vertical acceleration a_v
    (up positive) alike, v0[k] + v1[k] (t - time[k]) (shape (n,)), or None where there is none."""

    time: np.ndarray  # (n + 1,)
    a0: np.ndarray  # (n, c)
    a1: np.ndarray  # (n, c)
    v0: np.ndarray | None = None  # (n,)
    v1: np.ndarray | None = None  # (n,)

    @classmethod
    def from_samples(cls, time, acceleration, vertical=None) -> Ground:
        """Samples (n + 1,) or (n + 1, c) joined by straight lines; ``vertical`` (n + 1,) a_v, or None."""
        time = np.asarray(time, dtype=float)
        a = np.asarray(acceleration, dtype=float).reshape(time.size, -1)
        steps = np.diff(time)
        if vertical is None:
            return cls(time, a[:-1], np.diff(a, axis=0) / steps[:, None])
        v = np.asarray(vertical, dtype=float).reshape(time.size)
        return cls(time, a[:-1], np.diff(a, axis=0) / steps[:, None], v[:-1], np.diff(v) / steps)

    def scaled(self, factor, vertical=None) -> Ground:
        """The horizontal acceleration times ``factor`` (a number or one per component), the vertical
        times ``vertical`` (a number; None: as it is)."""
        out = self._replace(a0=self.a0 * factor, a1=self.a1 * factor)
        if vertical is None or self.v0 is None:
            return out
        return out._replace(v0=self.v0 * vertical, v1=self.v1 * vertical)

    @property
    def has_vertical(self) -> bool:
        """Whether a vertical acceleration other than zero acts (a_v = 0 is the horizontal problem)."""
        return self.v0 is not None and bool(np.any(self.v0) or np.any(self.v1))

    def normal(self, t=None) -> np.ndarray:
        """N/W = 1 + a_v/g at the interval ends (or at times ``t``), unclamped (<= 0: uplift)."""
        if self.v0 is None:
            return np.ones(self.time.size if t is None else np.size(t))
        if t is None:
            end = self.v0[-1] + self.v1[-1] * (self.time[-1] - self.time[-2])
            return 1.0 + np.append(self.v0, end) / G
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(self.time, t, side="right") - 1, 0, self.v0.size - 1)
        return 1.0 + (self.v0[k] + self.v1[k] * (np.clip(t, self.time[0], self.time[-1]) - self.time[k])) / G

    def uplift(self) -> list[tuple[float, float]]:
        """The intervals (start, end) (s) where N/W = 1 + a_v/g <= 0: the structure lifts off (exact on
        the straight lines joining the samples); [] without a vertical."""
        if self.v0 is None:
            return []
        ground, _ = self.refined(self.time)
        middle = 0.5 * (ground.time[:-1] + ground.time[1:])
        off = ground.normal(middle) <= 0.0
        out, start = [], None
        for k, flag in enumerate(off):
            if flag and start is None:
                start = float(ground.time[k])
            if not flag and start is not None:
                out.append((start, float(ground.time[k])))
                start = None
        if start is not None:
            out.append((start, float(ground.time[-1])))
        return out

    def at(self, t):
        """The acceleration at times t, shape (len(t), c); outside the span the end values hold."""
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(self.time, t, side="right") - 1, 0, self.a0.shape[0] - 1)
        tau = np.clip(t, self.time[0], self.time[-1]) - self.time[k]
        return self.a0[k] + self.a1[k] * tau[:, None]

    def refined(self, times) -> tuple[Ground, np.ndarray]:
        """The same acceleration with ``times`` (and, with a vertical, the times where N/W = 1 + a_v/g
        crosses 0) added as interval ends, and the index of each of ``times`` among the new ends
        (times within 1e-9 of an interval of an end count as on it)."""
        times = np.asarray(times, dtype=float)
        crossings = _uplift_crossings(self)
        if not crossings.size and np.array_equal(times, self.time):  # the samples themselves (a spectrum)
            return self, np.arange(times.size)
        near = 1e-9 * float(np.min(np.diff(self.time)))
        knots = np.union1d(np.union1d(self.time, times), crossings)
        keep = np.concatenate([[True], np.diff(knots) > near])
        knots = knots[keep]
        ground = self._at_knots(knots, near)
        index = np.clip(np.searchsorted(knots, times - near, side="left"), 0, knots.size - 1)
        return ground, index

    def _at_knots(self, knots, near) -> Ground:
        """The same acceleration on the interval ends ``knots`` (which hold the sample times)."""
        k = np.clip(np.searchsorted(self.time, knots[:-1] + near, side="right") - 1, 0, self.a0.shape[0] - 1)
        tau = knots[:-1] - self.time[k]
        ground = Ground(knots, self.a0[k] + self.a1[k] * tau[:, None], self.a1[k])
        if self.v0 is None:
            return ground
        return ground._replace(v0=self.v0[k] + self.v1[k] * tau, v1=self.v1[k])


def _uplift_crossings(ground: Ground) -> np.ndarray:
    """The times where a_v crosses -g inside an interval (N/W changes sign there; none without a vertical)."""
    if ground.v0 is None:
        return np.zeros(0)
    h = np.diff(ground.time)
    start, end = ground.v0 + G, ground.v0 + ground.v1 * h + G  # g + a_v at each interval's ends
    inside = ((start < 0.0) & (end > 0.0)) | ((start > 0.0) & (end < 0.0))
    return ground.time[:-1][inside] + start[inside] / (start[inside] - end[inside]) * h[inside]


class Response(NamedTuple):
    """The structure's response at the requested times: stroke u (m), its velocity (m/s), the
    friction state z and the force ratio F/W, each (T, c); ``sticking`` (T,) whether u̇ = 0 there;
    ``peaks``: the largest |u| (m) and |F/W| over the record's samples and the requested times, from
    the first of these to the record's end (a coarse step would miss the peaks between its times, and
    a step that does not divide the record the peaks after its last time); ``normal`` (T,) N/W = 1 +
    a_v/g (ones without a vertical) and ``uplift`` the intervals (start, end) (s) where N/W <= 0, from
    the first requested time on (None without a vertical)."""

    stroke: np.ndarray
    velocity: np.ndarray
    z: np.ndarray
    shear_ratio: np.ndarray
    sticking: np.ndarray
    peaks: tuple = (math.nan, math.nan)
    normal: np.ndarray | None = None
    uplift: list | None = None
    friction: np.ndarray | None = None  # (T,) μ(t) of a friction law (None: Coulomb's constant μ)
    temperature: np.ndarray | None = None  # (T, surfaces) the plates' temperatures (°C) of a temperature law


#: a structure's summaries of one history: name -> (units, long_name)
SUMMARIES = {
    "stroke_max_abs": ("m", "largest |stroke| (the superstructure's displacement relative to the ground) over the "
                            "whole record, whatever became of the pad"),
    "stroke_end": ("m", "residual stroke u(t_end) (its size |u| for two components)"),
    "shear_ratio_max_abs": ("1", "largest |F/W| of the device"),
}
#: the summaries of a structure under a vertical component too
VERTICAL_SUMMARIES = {
    "normal_ratio_min": ("1", "smallest N/W = 1 + a_v/g over the whole record"),
    "uplift_duration": ("s", "how long the superstructure lifts off its device (N/W <= 0) in all"),
    "uplift_count": ("1", "how many times the superstructure lifts off its device (N/W <= 0)"),
}


def summarize(response: Response) -> dict:
    """The :data:`SUMMARIES` of a response: vector sizes for two components, u(t_end) signed for one; the
    peaks over the record's samples too (``Response.peaks``); with a vertical, :data:`VERTICAL_SUMMARIES`."""
    stroke = np.linalg.norm(response.stroke, axis=1)
    end = response.stroke[-1, 0] if response.stroke.shape[1] == 1 else stroke[-1]
    out = {"stroke_max_abs": response.peaks[0], "stroke_end": float(end), "shear_ratio_max_abs": response.peaks[1]}
    if response.uplift is not None:
        out.update(normal_ratio_min=response.peaks[2], uplift_duration=float(sum(b - a for a, b in response.uplift)),
                   uplift_count=len(response.uplift))
    return out


def respond(ground: Ground, times, geometry, structure: Structure) -> Response:
    """The structure's response to ``ground`` at ``times`` (s, within the ground's span), on the device
    ``geometry`` (its pendulum length L, and R1, R3 for a surfaces' friction); at rest (u = u̇ = 0) at
    ``ground.time[0]``."""
    if structure.coulomb:
        return solve(ground, times, float(geometry.L), structure.device_friction(geometry), structure.damping)
    return solve(ground, times, float(geometry.L), math.nan, structure.damping, law=structure.rows(geometry))


def solve(ground: Ground, times, L, mu, zeta, compiled=None, law=None) -> Response:
    """:func:`respond` for any μ >= 0 (μ = 0: free sliding, the pendulum alone) and 0 <= ζ < 1, or a
    friction ``law`` (its kernel rows, ``friction.row``: then ``mu`` is not used); ``compiled`` None: the
    kernels compiled for a long record, interpreted for a short one.

    With a vertical acceleration a_v (``ground.v0``), the normal force is N = W (1 + a_v/g) and both the
    restoring force and the friction scale with it (N/W <= 0: the superstructure lifts off, and the
    device holds it neither way: u follows ü = -a_g - 2ζω u̇ until it lands); solved in one component
    as in two, by the two-component integrator, as is a friction law."""
    refined, index = ground.refined(times)
    omega = math.sqrt(G / L)
    components = refined.a0.shape[1]
    vertical = refined.has_vertical
    temperature = None
    if components == 1 and not vertical and law is None:
        u, v, z, stick = _line(refined.time, refined.a0[:, 0], refined.a1[:, 0], omega, zeta, mu * G, compiled)
        u, v, z = u[:, None], v[:, None], z[:, None]
        coefficient = np.full(u.shape[0], float(mu))
    elif law is None:
        u, v, z, stick, _, _ = _plane(refined, omega, zeta, mu * G, compiled)
        u, v, z = u[:, :components], v[:, :components], z[:, :components]
        coefficient = np.full(u.shape[0], float(mu))
    else:
        u, v, z, stick, temperature, coefficient = _plane(refined, omega, zeta, G, compiled, law,
                                                          np.isin(refined.time, ground.time))
        u, v, z = u[:, :components], v[:, :components], z[:, :components]
        temperature = temperature[:, :len(law)] if np.any(np.asarray(law)[:, 0] == 3.0) else None
    normal = refined.normal()
    if law is None:
        force = (u / L + mu * z) * np.maximum(normal, 0.0)[:, None] if vertical else u / L + mu * z
    else:
        force = (u / L + coefficient[:, None] * z) * np.maximum(normal, 0.0)[:, None]
    span = slice(index[0], None)  # to the record's end, past the last requested time
    peaks = tuple(float(np.max(np.linalg.norm(x[span], axis=1))) for x in (u, force))
    uplift = None
    if refined.v0 is not None:
        peaks += (float(np.min(normal[span])),)
        uplift = [(max(a, float(times[0])), b) for a, b in refined.uplift() if b > times[0]]
    u, v, z, stick = u[index], v[index], z[index], stick[index]
    return Response(u, v, z, force[index], stick, peaks, None if uplift is None else normal[index], uplift,
                    None if law is None else coefficient[index],
                    None if temperature is None else temperature[index])


#: stick/slip phases in one sample interval beyond which the solver gives up (a chatter it cannot resolve)
MAX_PHASES = 10_000


# --- one component: exact ----------------------------------------------------------------------
#
# ``line`` is written in the scalar subset Numba compiles, as ``plane`` below: compiled for a long
# record (or many, a spectrum's periods), interpreted for a short one, with the same bits.

@scalar.jit
def _slide(u0, v0, p0, p1, omega, zeta, tau):
    """(u, v) at tau of ü + 2ζω u̇ + ω² u = p0 + p1 t from (u0, v0) at t = 0 (0 <= ζ < 1)."""
    beta = p1 / omega**2
    alpha = (p0 - 2 * zeta * omega * beta) / omega**2
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    A = u0 - alpha
    B = (v0 - beta + zeta * omega * A) / wd
    e, c, s = math.exp(-zeta * omega * tau), math.cos(wd * tau), math.sin(wd * tau)
    u = alpha + beta * tau + e * (A * c + B * s)
    v = beta + e * ((B * wd - zeta * omega * A) * c - (A * wd + zeta * omega * B) * s)
    return u, v


@scalar.jit
def _stop(u0, v0, p0, p1, omega, zeta, sign, tau_end):
    """The first tau in (0, tau_end] where sign * u̇ falls to 0 while sliding (sign = ±1), or -1."""
    pieces = max(1, math.ceil(omega * tau_end / 0.25))
    left = 0.0
    for i in range(1, pieces + 1):
        right = tau_end * i / pieces
        if sign * _slide(u0, v0, p0, p1, omega, zeta, right)[1] <= 0.0:
            return _bisect(u0, v0, p0, p1, omega, zeta, sign, left, right)
        # a dip to zero inside a piece: sign * ü changes from - to + within it (a start from rest
        # starts with sign * ü >= 0: at a breakaway it is 0 and growing, rounding aside)
        acc_left = sign * _acceleration(u0, v0, p0, p1, omega, zeta, left)
        if left == 0.0 and v0 == 0.0:
            acc_left = max(acc_left, 0.0)
        acc_right = sign * _acceleration(u0, v0, p0, p1, omega, zeta, right)
        if acc_left < 0.0 < acc_right:
            lo, hi = left, right
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if sign * _acceleration(u0, v0, p0, p1, omega, zeta, mid) < 0.0:
                    lo = mid
                else:
                    hi = mid
            if sign * _slide(u0, v0, p0, p1, omega, zeta, lo)[1] <= 0.0:
                return _bisect(u0, v0, p0, p1, omega, zeta, sign, left, lo)
        left = right
    return -1.0


@scalar.jit
def _acceleration(u0, v0, p0, p1, omega, zeta, tau):
    u, v = _slide(u0, v0, p0, p1, omega, zeta, tau)
    return p0 + p1 * tau - 2 * zeta * omega * v - omega**2 * u


@scalar.jit
def _bisect(u0, v0, p0, p1, omega, zeta, sign, lo, hi):
    """The root of sign * u̇ in (lo, hi], where it is > 0 at lo (or lo = 0) and <= 0 at hi."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if sign * _slide(u0, v0, p0, p1, omega, zeta, mid)[1] > 0.0:
            lo = mid
        else:
            hi = mid
    return hi


def line(time, a0, a1, omega, zeta, friction, u, v, z, stick):
    """The exact one-component history at the interval ends into u, u̇, z and sticking (see the module
    docstring; ``friction`` is μ g, m/s²): (DONE, n - 1), or (CHATTER, k) at an interval k of more than
    MAX_PHASES stick/slip phases."""
    n = len(time)
    x, w = 0.0, 0.0  # u, u̇
    sliding, sign = friction == 0.0, 1.0
    demand = -a0[0]
    if not sliding and abs(demand) > friction:
        sliding, sign = True, math.copysign(1.0, demand)
    stick[0] = not sliding
    z[0] = demand / friction if not sliding else (sign if friction > 0 else 0.0)
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        tau, phases = 0.0, 0
        while tau < h:
            if phases >= MAX_PHASES:
                return CHATTER, k
            phases += 1
            b0, b1 = a0[k] + a1[k] * tau, a1[k]  # the ground's acceleration from tau on
            if not sliding:
                # sticking: the demand -a_g - ω² u is a straight line in t; it ends at ±μ g
                d0 = -b0 - omega**2 * x
                end = h - tau
                if b1 != 0.0:
                    for level in (friction, -friction):
                        when = (d0 - level) / b1
                        if 0.0 < when < end:
                            end = when
                tau += end
                if tau < h:
                    sliding, sign = True, (1.0 if d0 - b1 * end > 0.0 else -1.0)
                continue
            force = sign * friction
            p0, p1 = -b0 - force, -b1
            end = h - tau
            when = -1.0 if friction == 0.0 else _stop(x, w, p0, p1, omega, zeta, sign, end)
            if when < 0.0:
                x, w = _slide(x, w, p0, p1, omega, zeta, end)
                tau = h
                continue
            x, _ = _slide(x, w, p0, p1, omega, zeta, when)
            w = 0.0
            tau += when
            demand = -(b0 + b1 * when) - omega**2 * x
            if abs(demand) <= friction:
                sliding = False
            else:
                sign = math.copysign(1.0, demand)
        u[k + 1], v[k + 1] = x, w
        b = a0[k] + a1[k] * h
        if sliding:
            stick[k + 1], z[k + 1] = False, (sign if friction > 0 else 0.0)
        else:
            stick[k + 1], z[k + 1] = True, (-b - omega**2 * x) / friction
    return DONE, n - 1


def _line(time, a0, a1, omega, zeta, friction, compiled=None):
    """One-component history at the interval ends: u, u̇, z, sticking (``line``); ``compiled`` None:
    compiled for a long record (``backend``), interpreted for a short one."""
    from . import backend

    n = time.size
    if compiled is None:
        compiled = backend.choose(n - 1, LINE_WORK) == "numba"
    run = scalar.kernel(line) if compiled else line
    u, v, z = np.zeros(n), np.zeros(n), np.zeros(n)
    stick = np.zeros(n, dtype=bool)
    status, k = run(np.ascontiguousarray(time, dtype=float), np.ascontiguousarray(a0, dtype=float),
                    np.ascontiguousarray(a1, dtype=float), float(omega), float(zeta), float(friction), u, v, z, stick)
    if status == CHATTER:
        raise _chatter(time[k])
    return u, v, z, stick


def _chatter(t) -> RuntimeError:
    """The error of a sample interval (at t, s) of more than MAX_PHASES stick/slip phases."""
    return RuntimeError(f"structure: more than {MAX_PHASES} stick/slip phases in the sample interval at t = {t:g} s: "
                        f"the friction chatters; report the record and the structure")


# --- two components: the circular interaction -------------------------------------------------
#
# ``plane`` is written in the scalar subset Numba compiles (``scalar.jit``): the same function runs
# interpreted for a short record and compiled for a long one (``backend``), with the same result to
# the last bit: plain IEEE arithmetic in a fixed order, no BLAS (whose kernels the processor
# chooses) and no libm but ``pow``. Its integrator is DOP853 (Hairer, Nørsett and Wanner: 12 stages
# of order 8, with error estimators of orders 5 and 3; scipy's tableau and step-size control), its
# step carried from one sample interval to the next while the structure slides; an event (rest, or
# the end of a start from rest) is located by bisecting the step's length to 4 ε s, each trial a
# DOP853 step from the step's start.

#: DOP853's stages, and the size of the state y = (u, u̇) in two components
STAGES, SIZE = 12, 4
#: what ends a slide: none (the interval's end), |u̇| falling to REST_SPEED (stop), or for a start from
#: rest |u̇| reaching START_SPEED (moving) or the force falling back to μ g (held); a step too short
NONE, STOP, MOVING, HELD, TOO_SHORT = 0, 1, 2, 3, 4
#: the step-size control (scipy's): safety factor, the bounds of a step's change, the error's exponent
SAFETY, MIN_FACTOR, MAX_FACTOR, EXPONENT = 0.9, 0.2, 10.0, -1.0 / 8.0
#: a step shorter than this (s) is a failure; an event is located to within BRACKET (s)
MIN_STEP, BRACKET = 1e-14, 4 * 2.220446049250313e-16
#: the cost of a sample interval interpreted, in the planar kernels' case-steps (``backend.choose``):
#: about 0.5 ms
INTERVAL_WORK = 25
#: the same of one component's sample interval (``line``): about 5 µs sliding, more at a stop
LINE_WORK = 1
#: plane's status: done, the friction chatters (MAX_PHASES), a step too short
DONE, CHATTER, FAILED = 0, 1, 2


def _dop853():
    """scipy's DOP853 coefficients (A, B, C, E3, E5 as ``scipy.integrate.DOP853`` takes them): read from
    their module's file, which imports numpy alone; importing it, or the class, imports all of
    ``scipy.integrate`` (0.3-0.5 s, in every workflow job with a two-component structure). The class's
    attributes where the file is not found."""
    import importlib.util
    from pathlib import Path

    scipy_spec = importlib.util.find_spec("scipy")
    path = Path(scipy_spec.origin).parent / "integrate" / "_ivp" / "dop853_coefficients.py"
    if path.is_file():
        spec = importlib.util.spec_from_file_location("_dccss_dop853_coefficients", path)
        table = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(table)
        n = table.N_STAGES
        return table.A[:n, :n], table.B, table.C[:n], table.E3, table.E5
    from scipy.integrate import DOP853

    return DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5


@functools.cache
def _tableau(compiled):
    """DOP853's A (row-major), B, C, E3 and E5 (scipy.integrate.DOP853's: ``_dop853``): numpy arrays for the
    compiled kernel, lists (faster to index) interpreted."""
    arrays = [np.ascontiguousarray(c, dtype=float).ravel() for c in _dop853()]
    if [a.size for a in arrays] != [STAGES * STAGES, STAGES, STAGES, STAGES + 1, STAGES + 1]:
        raise RuntimeError(f"scipy.integrate.DOP853's tableau is not of {STAGES} stages: scipy changed it")
    return tuple(arrays) if compiled else tuple(a.tolist() for a in arrays)


@scalar.jit
def _normal(t, load):
    """N/W at t (from the slide's start): n0 + n1 t, 0 where the superstructure lifts off."""
    return max(load[7] + load[8] * t, 0.0)


@scalar.jit
def _coefficient(t, y, load, law):
    """The friction law's coefficient at t (from the slide's start) and y: exactly 1 for Coulomb friction
    (whose μ g is load[6]); a law's μ at the speed |u̇|, N/W and the surfaces' temperatures load[9:11]."""
    speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
    return device_mu(law, speed, _normal(t, load), load[9], load[10])


@scalar.jit
def _force(t, y, load):
    """f = -a_g - ω² (N/W) u at t (from the slide's start) and y, the ground's acceleration from there
    b0 + b1 t; load = (b0x, b0y, b1x, b1y, ω², 2ζω, μ g, n0, n1), N/W = n0 + n1 t."""
    n = _normal(t, load)
    return -(load[0] + load[2] * t) - load[4] * n * y[0], -(load[1] + load[3] * t) - load[4] * n * y[1]


@scalar.jit
def _rhs(t, y, row, K, load, law, start):
    """K[row] = dy/dt: u̇ and ü = f - 2ζω u̇ - μ g (N/W) z, z the direction of u̇ (of f for a ``start`` from
    rest)."""
    f0, f1 = _force(t, y, load)
    friction = load[6] * _coefficient(t, y, load, law) * _normal(t, load)
    d0, d1 = (f0, f1) if start else (y[2], y[3])
    size = math.sqrt(d0 * d0 + d1 * d1)
    if size > 0.0:
        d0, d1 = d0 / size, d1 / size
    at = row * SIZE
    K[at] = y[2]
    K[at + 1] = y[3]
    K[at + 2] = f0 - load[5] * y[2] - friction * d0
    K[at + 3] = f1 - load[5] * y[3] - friction * d1


@scalar.jit
def _step(t, y, h, K, out, trial, load, law, start, A, B, C):
    """One DOP853 step of length h from (t, y), K[0] the derivative there: out = y(t + h), the stages in
    K, K[STAGES] the derivative at t + h."""
    for s in range(1, STAGES):
        for c in range(SIZE):
            acc = 0.0
            for j in range(s):
                acc += K[j * SIZE + c] * A[s * STAGES + j]
            trial[c] = y[c] + acc * h
        _rhs(t + C[s] * h, trial, s, K, load, law, start)
    for c in range(SIZE):
        acc = 0.0
        for j in range(STAGES):
            acc += K[j * SIZE + c] * B[j]
        out[c] = y[c] + h * acc
    _rhs(t + h, out, STAGES, K, load, law, start)


@scalar.jit
def _error(y, out, h, K, rtol, atol, E3, E5):
    """The step's error norm (scipy's DOP853: the order-5 estimate, damped by the order-3 one)."""
    e5, e3 = 0.0, 0.0
    for c in range(SIZE):
        scale = atol + max(abs(y[c]), abs(out[c])) * rtol
        s5, s3 = 0.0, 0.0
        for j in range(STAGES + 1):
            s5 += K[j * SIZE + c] * E5[j]
            s3 += K[j * SIZE + c] * E3[j]
        s5, s3 = s5 / scale, s3 / scale
        e5 += s5 * s5
        e3 += s3 * s3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3) * SIZE)


@scalar.jit
def _first_step(y, end, K, trial, load, law, start, rtol, atol):
    """Hairer's first step for order 8 (scipy's ``select_initial_step``); K[0] the derivative at y."""
    d0, d1 = 0.0, 0.0
    for c in range(SIZE):
        scale = atol + abs(y[c]) * rtol
        d0 += (y[c] / scale) * (y[c] / scale)
        d1 += (K[c] / scale) * (K[c] / scale)
    d0, d1 = math.sqrt(d0 / SIZE), math.sqrt(d1 / SIZE)
    h0 = min(1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1, end)
    for c in range(SIZE):
        trial[c] = y[c] + h0 * K[c]
    _rhs(h0, trial, STAGES, K, load, law, start)  # K[STAGES] is scratch here
    d2 = 0.0
    for c in range(SIZE):
        g = (K[STAGES * SIZE + c] - K[c]) / (atol + abs(y[c]) * rtol)
        d2 += g * g
    d2 = math.sqrt(d2 / SIZE) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** (1.0 / 9.0)
    return min(100.0 * h0, h1, end)


@scalar.jit
def _g(event, t, y, load, law):
    """The event's function: |u̇| - REST_SPEED (STOP), |u̇| - START_SPEED (MOVING), |f| - μ g N/W (HELD)."""
    if event == HELD:
        f0, f1 = _force(t, y, load)
        return math.sqrt(f0 * f0 + f1 * f1) - load[6] * _coefficient(t, y, load, law) * _normal(t, load)
    speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
    return speed - (REST_SPEED if event == STOP else START_SPEED)


@scalar.jit
def _beyond(event, g):
    """Whether g is past the event: STOP and HELD fall through zero, MOVING rises through it."""
    return g >= 0.0 if event == MOVING else g <= 0.0


@scalar.jit
def _crosses(event, g_old, g_new):
    """Whether a step crosses the event (scipy's test: from the event's near side or zero to its far
    side or zero)."""
    return _beyond(event, g_new) and (g_old == 0.0 or not _beyond(event, g_old))


@scalar.jit
def _locate(event, t, y, h, K, out, trial, load, law, start, A, B, C):
    """The length s in (0, h] of the step from (t, y) that reaches the event (bisection to BRACKET), the
    event being past at h and not at 0; ``out`` is scratch."""
    lo, hi = 0.0, h
    while hi - lo > BRACKET:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        _step(t, y, mid, K, out, trial, load, law, start, A, B, C)
        if _beyond(event, _g(event, t + mid, out, load, law)):
            hi = mid
        else:
            lo = mid
    return hi


@scalar.jit
def _integrate(y, end, h, load, law, start, stop, rtol, atol, A, B, C, E3, E5, K, out, trial):
    """DOP853 over [0, end] from y (overwritten with the state reached): (what ended it, when, the next
    step). Events: STOP if ``stop``; MOVING and HELD for a ``start``; the earliest ends the slide."""
    t = 0.0
    _rhs(t, y, 0, K, load, law, start)
    if h <= 0.0:
        h = _first_step(y, end, K, trial, load, law, start, rtol, atol)
    carry = h
    while t < end:
        rejected = False
        while True:
            if h < MIN_STEP:
                return TOO_SHORT, t, h
            t_new = min(t + h, end)
            taken = t_new - t
            _step(t, y, taken, K, out, trial, load, law, start, A, B, C)
            error = _error(y, out, taken, K, rtol, atol, E3, E5)
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error ** EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                carry = max(taken * factor, h) if t_new == end and taken < h else taken * factor
                h = taken * factor
                break
            h = taken * max(MIN_FACTOR, SAFETY * error ** EXPONENT)
            rejected = True
        crossed = (stop and _crosses(STOP, _g(STOP, t, y, load, law), _g(STOP, t_new, out, load, law)),
                   start and _crosses(MOVING, _g(MOVING, t, y, load, law), _g(MOVING, t_new, out, load, law)),
                   start and _crosses(HELD, _g(HELD, t, y, load, law), _g(HELD, t_new, out, load, law)))
        first, length = NONE, taken
        for event in (STOP, MOVING, HELD):
            if crossed[event - 1]:
                s = _locate(event, t, y, taken, K, out, trial, load, law, start, A, B, C)
                if first == NONE or s < length:
                    first, length = event, s
        if first != NONE:
            _step(t, y, length, K, out, trial, load, law, start, A, B, C)
            for c in range(SIZE):
                y[c] = out[c]
            return first, t + length, carry
        for c in range(SIZE):
            y[c] = out[c]
            K[c] = K[STAGES * SIZE + c]
        t = t_new
    return NONE, end, carry


@scalar.jit
def _breakaway(d0x, d0y, d1x, d1y, friction, m0, m1, end):
    """The first tau in (0, end) where |d0 + d1 tau| reaches ``friction`` (m0 + m1 tau) (a quadratic;
    m0 + m1 tau = N/W >= 0 on the interval), or -1."""
    f0, f1 = friction * m0, friction * m1
    a = d1x * d1x + d1y * d1y - f1 * f1
    b = 2 * (d0x * d1x + d0y * d1y - f0 * f1)
    c = (d0x * d0x + d0y * d0y) - f0 * f0
    if c > 0.0:
        return 0.0
    if a == 0.0:
        if b > 0.0:  # a straight line from c <= 0
            root = -c / b
            return root if 0.0 < root < end else -1.0
        return -1.0
    disc = b * b - 4 * a * c
    if disc < 0.0:
        return -1.0
    if a > 0.0:
        root = (-b + math.sqrt(disc)) / (2 * a)  # c <= 0: the larger root is the exit
    else:  # opening downwards from c <= 0: the first root where it rises through 0, if it does
        if b <= 0.0:
            return -1.0
        root = (-b + math.sqrt(disc)) / (2 * a)
    return root if 0.0 < root < end else -1.0


@scalar.jit
def _state(k, x0, x1, w0, w1, f0, f1, sliding, friction, u, v, z, stick):
    """Row k of the history: u, u̇, and z (f / μ g (N/W) sticking, ``friction`` being μ g (N/W) there;
    sliding, the direction of u̇, or at rest that of the force)."""
    u[k, 0], u[k, 1], v[k, 0], v[k, 1] = x0, x1, w0, w1
    stick[k] = not sliding
    if not sliding:
        if friction > 0.0:
            z[k, 0], z[k, 1] = f0 / friction, f1 / friction
        else:
            z[k, 0], z[k, 1] = 0.0, 0.0
        return
    z[k, 0], z[k, 1] = 0.0, 0.0
    if friction == 0.0:
        return
    d0, d1 = (w0, w1) if w0 != 0.0 or w1 != 0.0 else (f0, f1)
    size = math.sqrt(d0 * d0 + d1 * d1)
    if size > 0.0:
        z[k, 0], z[k, 1] = d0 / size, d1 / size


def plane(time, a0, a1, n0, n1, law, samples, omega, zeta, friction, rtol, atol, A, B, C, E3, E5, K, y, out, trial, u,
          v, z, stick, heat, temperature, mu):
    """The two-component history at the interval ends (the module docstring) into u, u̇, z (n, 2),
    sticking (n,), the surfaces' temperatures (n, 2) and the friction coefficient (n,), N/W on interval
    k being n0[k] + n1[k] (t - t_k) (0 where that is negative) and the friction ``friction`` times the
    law's coefficient (``law``: a row per surface, ``friction.row``; Coulomb's is 1 and ``friction``
    its μ g); ``heat`` (n, 4) holds each heat interval's start, end and heat flux into each surface's
    plate, a heat interval running from one of the record's samples to the next (``samples``: whether an
    interval end is one, so that the heat does not depend on the times asked for between them): (DONE, 0),
    or (CHATTER or FAILED, the interval where the run stopped)."""
    n = time.size
    w2, damp = omega * omega, 2 * zeta * omega
    x0, x1, w0, w1 = 0.0, 0.0, 0.0, 0.0
    # sticking holds while |f| <= μ g (N/W) (1 + rtol): a stop where the force equals the friction to
    # within the integration's own accuracy (as a Coulomb oscillator's last stop under a constant load)
    # is not left to the rounding of the state there (the law's coefficient multiplies ``friction`` first:
    # Coulomb's μ g times 1 and g times a law's μ give the same bits)
    hold = 1.0 + rtol
    heats = False  # a law whose friction follows the plates' temperatures
    for s in range(len(law)):
        temperature[0, s] = law[s][17]
        heats = heats or law[s][0] == 3.0
    t0, t1 = temperature[0, 0], temperature[0, 1]
    m = max(n0[0], 0.0)
    rest = device_mu(law, 0.0, m, t0, t1)
    f0, f1 = -a0[0, 0], -a0[0, 1]
    sliding = friction == 0.0 or math.sqrt(f0 * f0 + f1 * f1) > friction * rest * hold * m
    starting = sliding and friction > 0.0  # a start from rest, until |u̇| reaches START_SPEED
    _state(0, x0, x1, w0, w1, f0, f1, sliding, friction * rest * m, u, v, z, stick)
    mu[0] = rest
    h_next = 0.0  # the integrator's step, carried while the structure slides on
    heated, since = 0, 0  # the heat intervals so far, and where the current one started
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        tau, phases = 0.0, 0
        while tau < h:
            phases += 1
            if phases > MAX_PHASES:
                return CHATTER, k
            b00, b01 = a0[k, 0] + a1[k, 0] * tau, a0[k, 1] + a1[k, 1] * tau
            b10, b11 = a1[k, 0], a1[k, 1]
            m0, m1 = n0[k] + n1[k] * tau, n1[k]
            end = h - tau
            if not sliding:
                # the breakaway value at the phase's start (it moves with N/W only under a pressure factor)
                rest = device_mu(law, 0.0, max(m0, 0.0), t0, t1)
                when = _breakaway(-b00 - w2 * m0 * x0, -b01 - w2 * m0 * x1, -b10 - w2 * m1 * x0, -b11 - w2 * m1 * x1,
                                  friction * rest * hold, m0, m1, end)
                tau += when if when >= 0.0 else end
                sliding = starting = when >= 0.0
                h_next = 0.0
                continue
            y[0], y[1], y[2], y[3] = x0, x1, w0, w1
            if starting:
                # a start from rest: u̇ grows along the force, whose direction u̇ / |u̇| takes within a
                # vanishing time; until |u̇| reaches START_SPEED (in this interval or a later one) the
                # friction is taken along the force (exact along a line), which spares the integrator
                # the direction of a velocity that is only rounding
                load = (b00, b01, b10, b11, w2, damp, friction, m0, m1, t0, t1)
                ended, when, h_next = _integrate(y, end, 0.0, load, law, True, False, rtol, atol, A, B, C, E3, E5,
                                                 K, out, trial)
                if ended == TOO_SHORT:
                    return FAILED, k
                if ended == HELD:  # the force fell back within the friction: at rest again
                    x0, x1, w0, w1, tau, h_next = y[0], y[1], 0.0, 0.0, tau + when, 0.0
                    sliding = starting = False
                    continue
                if ended == NONE:
                    x0, x1, w0, w1, tau = y[0], y[1], y[2], y[3], h
                    continue
                tau, end, h_next, starting = tau + when, end - when, 0.0, False  # moving
                b00, b01 = b00 + b10 * when, b01 + b11 * when
                m0 = m0 + m1 * when
            load = (b00, b01, b10, b11, w2, damp, friction, m0, m1, t0, t1)
            ended, when, h_next = _integrate(y, end, h_next, load, law, False, friction > 0.0, rtol, atol, A, B, C,
                                             E3, E5, K, out, trial)
            if ended == TOO_SHORT:
                return FAILED, k
            if ended == STOP:  # at rest: the last REST_SPEED at the deceleration there, to first order
                speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
                g0, g1 = _force(when, y, load)
                slowing = (friction * _coefficient(when, y, load, law) * _normal(when, load) + damp * speed
                           - (g0 * y[2] + g1 * y[3]) / speed)
                last = min(speed / slowing, end - when) if slowing > 0.0 else 0.0
                x0, x1, w0, w1 = y[0] + 0.5 * last * y[2], y[1] + 0.5 * last * y[3], 0.0, 0.0
                when += last
                tau += when
                m = _normal(when, load)
                g0 = -(b00 + b10 * when) - w2 * m * x0
                g1 = -(b01 + b11 * when) - w2 * m * x1
                sliding = starting = math.sqrt(g0 * g0 + g1 * g1) > friction * device_mu(law, 0.0, m, t0, t1) * hold * m
                h_next = 0.0
                continue
            x0, x1, w0, w1, tau = y[0], y[1], y[2], y[3], h
        m = max(n0[k] + n1[k] * h, 0.0)
        if heats:
            temperature[k + 1, 0], temperature[k + 1, 1] = t0, t1
            if samples[k + 1] or k + 2 == n:  # the end of a heat interval
                normal = max(0.5 * (n0[since] + m), 0.0)
                t0, t1 = _heated(heated, time[since], time[k + 1], u[since, 0], u[since, 1], x0, x1, normal, law,
                                 heat, temperature, k + 1)
                heated, since = heated + 1, k + 1
        f0 = -(a0[k, 0] + a1[k, 0] * h) - w2 * m * x0
        f1 = -(a0[k, 1] + a1[k, 1] * h) - w2 * m * x1
        mu[k + 1] = device_mu(law, 0.0 if not sliding else math.sqrt(w0 * w0 + w1 * w1), m, t0, t1)
        rest = device_mu(law, 0.0, m, t0, t1)
        _state(k + 1, x0, x1, w0, w1, f0, f1, sliding, friction * rest * m, u, v, z, stick)
    return DONE, 0


@scalar.jit
def _heated(m, start, end, ux, uy, x0, x1, normal, law, heat, temperature, k):
    """The plates' temperatures at ``end`` (time[k]) after heat interval m from ``start``, the stroke going
    from (ux, uy) to (x0, x1): its heat flux q = λ μ p v (its mean sliding speed v, N/W ``normal``, the
    plates' temperatures held over it, temperature[k]) into each surface's plate while the slider covers
    the plate's centre; the half-space's surface temperature for a flux constant over each heat interval
    (the module docstring of ``friction``)."""
    h = end - start
    d0, d1 = x0 - ux, x1 - uy
    c0, c1 = 0.5 * (x0 + ux), 0.5 * (x1 + uy)
    moved, middle = math.sqrt(d0 * d0 + d1 * d1), math.sqrt(c0 * c0 + c1 * c1)
    heat[m, 0], heat[m, 1] = start, end
    for s in range(len(law)):
        r = law[s]
        if r[0] != 3.0:
            continue
        speed = r[2] * moved / h
        covered = r[2] * middle < r[16] * 0.8862269254527580  # √π / 2: the contact circle's equal square
        heat[m, 2 + s] = r[3] * surface_mu(r, speed, normal, temperature[k, s]) * r[7] * normal * speed \
            if covered else 0.0
        rise = 0.0
        for j in range(m + 1):
            rise += heat[j, 2 + s] * (math.sqrt(end - heat[j, 0]) - math.sqrt(end - heat[j, 1]))
        temperature[k, s] = r[17] + 2.0 * math.sqrt(r[14] / math.pi) / r[15] * rise
    return temperature[k, 0], temperature[k, 1]


#: the law of Coulomb friction in the kernels: a coefficient of exactly 1 times ``friction`` = μ g
UNIT_LAW = np.array([[0.0, 1.0, 1.0, 1.0, 1.0] + [0.0] * (ROW - 5)])


def _plane(ground: Ground, omega, zeta, friction, compiled=None, law=UNIT_LAW, samples=None):
    """Two-component history at the interval ends (see the module docstring): u, u̇, z (n, 2), sticking,
    the plates' temperatures (n, 2) and the law's coefficient (n,); one component runs as the first of
    two, the second without load; ``friction`` is μ g for Coulomb friction (``law`` UNIT_LAW), g for a
    law (its rows, ``friction.row``); ``samples`` whether each interval end is one of the record's samples
    (default: all are), the ends of the plates' heat intervals; ``compiled`` None: compiled for a long
    record (``backend``), interpreted for a short one."""
    from . import backend

    time, a0, a1 = ground.time, ground.a0, ground.a1
    if a0.shape[1] == 1:
        a0, a1 = np.column_stack([a0, np.zeros_like(a0)]), np.column_stack([a1, np.zeros_like(a1)])
    if ground.v0 is None:
        n0, n1 = np.ones(time.size - 1), np.zeros(time.size - 1)
    else:
        n0, n1 = 1.0 + ground.v0 / G, ground.v1 / G
    n = time.size
    if compiled is None:  # the plates' heat sums over the intervals before: about n / 200 case-steps more each
        heats = bool(np.any(np.asarray(law)[:, 0] == 3.0))
        compiled = backend.choose(n - 1, INTERVAL_WORK + (n // 200 if heats else 0)) == "numba"
    run = scalar.kernel(plane) if compiled else plane
    work = (np.zeros((STAGES + 1) * SIZE), np.zeros(SIZE), np.zeros(SIZE), np.zeros(SIZE))
    if not compiled:
        work = tuple(w.tolist() for w in work)
    u, v, z = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    stick = np.zeros(n, dtype=bool)
    heat, temperature, mu = np.zeros((n, 4)), np.zeros((n, 2)), np.zeros(n)
    samples = np.ones(n, dtype=bool) if samples is None else np.asarray(samples, dtype=bool)
    law = np.ascontiguousarray(law, dtype=float) if compiled else np.asarray(law, dtype=float).tolist()
    status, k = run(np.ascontiguousarray(time, dtype=float), np.ascontiguousarray(a0, dtype=float),
                    np.ascontiguousarray(a1, dtype=float), np.ascontiguousarray(n0, dtype=float),
                    np.ascontiguousarray(n1, dtype=float), law, samples, float(omega), float(zeta), float(friction),
                    float(RTOL), float(ATOL), *_tableau(compiled), *work, u, v, z, stick, heat, temperature, mu)
    if status == CHATTER:
        raise _chatter(time[k])
    if status == FAILED:
        raise RuntimeError(f"structure: the two-component integration's step fell below {MIN_STEP:g} s in the "
                           f"sample interval at t = {time[k]:g} s; report the record and the structure")
    return u, v, z, stick, temperature, mu


def warm(kernels=("plane", "line")):
    """Compile (or load) the two-component (``plane``) and one-component (``line``) kernels into the
    on-disk cache."""
    ground = Ground.from_samples([0.0, 0.01, 0.02], [[0.0, 0.0], [1.0, 0.5], [0.0, 0.0]])
    if "plane" in kernels:
        _plane(ground, 2.0, 0.0, 0.05 * G, compiled=True)
    if "line" in kernels:
        _line(ground.time, ground.a0[:, 0], ground.a1[:, 0], 2.0, 0.0, 0.05 * G, compiled=True)
