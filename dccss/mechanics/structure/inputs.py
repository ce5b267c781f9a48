"""What an isolated structure's run is given: the superstructure on the device (``Structure``:
its friction, damping, property factor and slider kind) and the ground's acceleration (``Ground``),
each validated once."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ..friction import COULOMB, FACTOR, LAWS, T0, WEIGHT, FrictionError, row, surface_mu
from .sliders import SLIDERS, hinge_problem, pendulums

G = 9.80665  # standard gravity (m/s²)


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
    ``friction_on="surfaces"`` one number or law for both surfaces or a list of two, RB1's and RB3's.

    ``slider`` is the device's construction (``sliders.SLIDERS``): ``rigid`` (one body, the surfaces
    sliding in proportion) or ``articulated`` (two halves on a hinge ``hinge`` m above the pad's centre,
    each surface sliding by its own friction: ``friction_on="surfaces"``, each μ > 0 at rest)."""

    friction: object
    damping: float = 0.0
    friction_on: str = "device"
    factor: float = 1.0
    slider: str = "rigid"
    hinge: float = 0.0
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
        problems += self._slider_problems()
        if problems:
            raise StructureError(*problems)
        if isinstance(self.friction, (int, float, np.integer, np.floating)):
            object.__setattr__(self, "friction", float(self.friction))

    def _slider_problems(self) -> list[str]:
        """What is wrong with ``slider`` and ``hinge`` (and, for an articulated slider, its friction)."""
        if self.slider not in SLIDERS:
            return [f"structure.slider: must be one of {list(SLIDERS)}, got {self.slider!r}"]
        if isinstance(self.hinge, bool) or not isinstance(self.hinge, (int, float, np.integer, np.floating)) \
                or not math.isfinite(float(self.hinge)):
            return [f"structure.hinge: expected a finite number (m, the hinge's height above the pad's centre), "
                    f"got {self.hinge!r}"]
        object.__setattr__(self, "hinge", float(self.hinge))
        if self.slider != "articulated":
            return []
        if self.friction_on != "surfaces":
            return ["structure.friction_on: an articulated slider's surfaces slide each by its own friction: give "
                    "it as friction_on: surfaces (one number or law for both, or a list of two, RB1's and RB3's)"]
        out = []
        for i, (law, values) in enumerate(getattr(self, "laws", [])):
            r = row(law, values)
            if not surface_mu(r, 0.0, 1.0, r[T0]) > 0.0:
                out.append(f"structure.friction{f'[{i}]' if isinstance(self.friction, list) else ''}: an articulated "
                           f"slider's surfaces need friction at rest (μ > 0): with none, which surface slides is "
                           f"not decided")
        return out

    def pendulums(self, geometry) -> tuple[float, float]:
        """(L_1, L_3) (m) of the device's surfaces with this structure's hinge (``sliders.pendulums``); a
        StructureError where the hinge is not inside the pad (``sliders.hinge_problem``)."""
        problem = hinge_problem(geometry, self.hinge, "structure.hinge")
        if problem:
            raise StructureError(problem)
        return pendulums(geometry, self.hinge)

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

    def rows(self, geometry, proportional=True) -> np.ndarray:
        """The kernel's rows of the friction laws on ``geometry``: one for the device, or RB1's and RB3's
        surfaces weighted by R^j / L (their sliding speed R^j / L times the stroke's: the surfaces sliding in
        proportion), or not ``proportional`` by R^j / L_j (an articulated slider's surfaces, each a pendulum of
        length L_j: μ̄_j = μ_j R^j / L_j, its speed R^j / L_j times the hinge's)."""
        if self.friction_on == "device":
            return np.array([row(law, values, factor=self.factor) for law, values in self.laws])
        ratios = [float(geometry.R1) / float(geometry.L), float(geometry.R3) / float(geometry.L)]
        if not proportional:
            L1, L3 = self.pendulums(geometry)
            ratios = [float(geometry.R1) / L1, float(geometry.R3) / L3]
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
        if self.slider != "rigid":
            L1, L3 = self.pendulums(geometry)
            out.update(structure_slider=self.slider, structure_hinge_m=self.hinge, structure_pendulum_lengths_m=
                       np.array([L1, L3]))
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

