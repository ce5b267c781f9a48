"""Friction laws of the isolated structure's sliding surfaces: the coefficient μ as a function of the
sliding speed, the contact pressure and the surface temperature.

A law is an entry of :data:`LAWS` (registered with :func:`register`, as the models are): its name,
its parameters (units, defaults, what each is), its documentation, and its μ, evaluated by the
structure's kernels from one row of numbers (:func:`row`) and by numpy for the figures
(:meth:`Law.mu`). The laws, μ dimensionless, v the surface's sliding speed (m/s), p its contact
pressure (Pa), T its temperature (°C):

* ``coulomb``: μ = ``mu`` (a number given as ``structure.friction`` is this law).
* ``velocity`` (OpenSees' ``VelDependent``; Constantinou, Mokha and Reinhorn 1990):
  μ = fast − (fast − slow) exp(−rate v).
* ``velocity_pressure`` (OpenSees' ``VelPressureDep``, read from its source): the fast value falls with
  the pressure, fast(p) = fast0 − delta tanh(alpha p) for p > 0 (fast0 otherwise), and
  μ = fast(p) − (fast(p) − slow) exp(−rate v); p = N / area (N the normal force: the supported
  ``load`` times N/W, which a vertical component changes), or ``pressure`` × N/W.
* ``temperature`` (OpenSees' ``FPBearingPTV``, Kumar, Whittaker and Constantinou 2015):
  μ = mu_ref k_p k_T k_v with k_p = 0.7^(0.02 (p − p_ref) / 1 MPa) (``pressure_factor``),
  k_T = 0.789 (0.7^(T / 50 °C) + 0.4) (``temperature_factor``), k_v = 1 − 0.5 exp(−rate v)
  (``speed_factor``); T is the temperature at the centre of the sliding plate, T0 plus the
  half-space solution for the frictional heat flux q = μ p v it receives while the slider covers
  it (|u_s| < r_c √π / 2): ΔT(t) = √(D / π) / k ∫ q(τ) / √(t − τ) dτ, q constant over each sample
  interval of the record (its mean over the interval, from the slide there, whatever times are asked
  for between the samples), the integral exact for it:
  ΔT(t_n) = (2 / k) √(D / π) Σ_j q_j (√(t_n − t_j) − √(t_n − t_j+1)). The temperature of an
  interval is the one at its start (the friction lags the heat by one interval, as OpenSees'
  element's lags by one step).

At zero speed every law gives its breakaway value (``slow``; for the temperature law mu_ref k_p k_T
/ 2 with the speed factor), at which sticking ends: an exact event as for Coulomb friction.

**Two surfaces.** With ``friction_on: surfaces`` each sliding surface has its own law (or one law for
both). Under compliant sliding the pad turns by θ about both sphere centres: it slides R¹ θ on RB1
and R³ θ on RB3 while the stroke is L θ, so surface j slides at v_j = (R^j / L) |u̇| and, by the work
argument, the device's coefficient is μ = (μ1(v_1) R¹ + μ3(v_3) R³) / L (``row``'s weight and speed
ratio: R^j / L both).

**Bounds.** ``property`` multiplies every friction coefficient of the law (ASCE 7-22 §17.2.8.4's
property modification factors λ, EN 15129's λ factors): μ → λ μ, the heat too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import scalar

#: the kernel's row of a surface's law: [kind, weight, speed ratio, λ, then the law's own numbers]
ROW = 18
KIND, WEIGHT, RATIO, FACTOR = 0, 1, 2, 3
#: the laws' own numbers in a row: μ (or slow, or mu_ref), fast (fast0), rate, p at N = W, delta, alpha,
#: p_ref, the three factors' switches, D, k, r_c, T0
MU, FAST, RATE, PRESSURE, DELTA, ALPHA, P_REF, KP, KV, KT, DIFFUSIVITY, CONDUCTIVITY, RADIUS, T0 = range(4, ROW)
MPA = 1e6


class FrictionError(ValueError):
    """A friction law's parameters are wrong; each message names its key (``messages``)."""

    def __init__(self, *messages):
        self.messages = list(messages)
        super().__init__("; ".join(messages))


def _reads(value) -> bool:
    """Whether a string reads as a number (YAML's exponent without a decimal point)."""
    try:
        float(value)
    except (TypeError, ValueError):
        return False
    return isinstance(value, str)


@dataclass(frozen=True)
class Law:
    """A friction law: its ``name`` (the ``law`` key), its kernel ``kind``, its ``parameters``
    {key: (default or None when required, units, description)} and ``doc``."""

    name: str
    kind: int
    doc: str
    parameters: dict = field(default_factory=dict)

    def values(self, given: dict, key="structure.friction") -> dict:
        """The law's parameters from ``given`` (defaults filled in), checked; errors name ``key``."""
        unknown = sorted(set(given) - set(self.parameters) - {"law"})
        missing = [k for k, (default, *_) in self.parameters.items() if default is None and k not in given]
        problems = [f"{key}: unknown key(s) {unknown} of the {self.name} law; allowed: {sorted(self.parameters)}"] \
            if unknown else []
        problems += [f"{key}.{k}: missing: {self.parameters[k][2]} ({self.parameters[k][1]})" for k in missing]
        out = {}
        for k, (default, units, what) in self.parameters.items():
            value = given.get(k, default)
            if value is None or value is OPTIONAL:
                continue
            if isinstance(default, bool) or k in BOOLEAN:
                if not isinstance(value, bool):
                    problems.append(f"{key}.{k}: expected true or false, got {value!r}")
                out[k] = value
                continue
            if isinstance(value, str) or isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                hint = " (YAML reads 1e-3 or 1.5e6 as a string: write 1.0e-3, 1.5e+6)" if _reads(value) else ""
                problems.append(f"{key}.{k}: expected a finite number ({units}), got {value!r}{hint}")
                continue
            if k in POSITIVE and not value > 0 or k not in POSITIVE and value < 0:
                problems.append(f"{key}.{k}: {value!r} must be {'> 0' if k in POSITIVE else '>= 0'} ({what})")
            out[k] = float(value)
        problems += _coherence(self.name, out, key)
        if problems:
            raise FrictionError(*problems)
        return out

    def mu(self, values: dict, speed, pressure=None, temperature=None, factor=1.0):
        """μ (numpy, broadcast) at ``speed`` (m/s), ``pressure`` (Pa; default the law's at N = W) and
        ``temperature`` (°C; default its T0)."""
        r = row(self, values, factor=factor)
        speed, normal, temp = np.broadcast_arrays(np.asarray(speed, float),
                                                  1.0 if pressure is None else np.asarray(pressure, float) /
                                                  max(r[PRESSURE], 1e-300),
                                                  r[T0] if temperature is None else np.asarray(temperature, float))
        out = np.empty(speed.shape)
        for i in np.ndindex(speed.shape):
            out[i] = surface_mu(r, float(speed[i]), float(normal[i]), float(temp[i]))
        return out


#: the default of a parameter that may be left out (one of several ways to give a quantity)
OPTIONAL = "optional"
#: parameters that are switches, and those that must be > 0
BOOLEAN = ("pressure_factor", "temperature_factor", "speed_factor")
POSITIVE = ("area", "load", "diffusivity", "conductivity", "contact_radius")
#: the laws, by name
LAWS: dict[str, Law] = {}


def register(law: Law) -> Law:
    """Add ``law`` to :data:`LAWS` (its name not taken)."""
    if law.name in LAWS:
        raise ValueError(f"a friction law named {law.name!r} is registered already")
    LAWS[law.name] = law
    return law


_PRESSURE = {"pressure": (OPTIONAL, "Pa", "the contact pressure at N = W (or give load and area)"),
             "load": (OPTIONAL, "N", "the weight W the device carries (with area: the pressure W / area)"),
             "area": (OPTIONAL, "m2", "the nominal contact area of the slider on the surface")}
COULOMB = register(Law("coulomb", 0, "μ constant: Coulomb friction", {"mu": (None, "1", "the coefficient μ")}))
VELOCITY = register(Law("velocity", 1, "μ = fast − (fast − slow) exp(−rate v) (OpenSees VelDependent)", {
    "slow": (None, "1", "μ at zero speed (the breakaway value)"),
    "fast": (None, "1", "μ at high speed"),
    "rate": (None, "s m-1", "how fast μ goes from slow to fast with the speed v")}))
VELOCITY_PRESSURE = register(Law("velocity_pressure", 2, "μ = fast(p) − (fast(p) − slow) exp(−rate v), "
                                 "fast(p) = fast0 − delta tanh(alpha p) (OpenSees VelPressureDep)", {
    "slow": (None, "1", "μ at zero speed"),
    "fast0": (None, "1", "μ at high speed and zero pressure"),
    "delta": (None, "1", "how much the fast value falls at high pressure"),
    "alpha": (None, "Pa-1", "how fast the fast value falls with the pressure"),
    "rate": (None, "s m-1", "how fast μ goes from slow to fast with the speed v"),
    **_PRESSURE}))
TEMPERATURE = register(Law("temperature", 3, "μ = mu_ref k_p k_T k_v, T from the frictional heat flux into the "
                           "sliding plate (OpenSees FPBearingPTV)", {
    "mu_ref": (None, "1", "μ at the reference pressure, 20 °C and high speed"),
    "contact_radius": (None, "m", "the radius of the slider's contact area (its heat and its pressure)"),
    "rate": (100.0, "s m-1", "the speed factor's rate"),
    "p_ref": (0.0, "Pa", "the reference pressure of the pressure factor"),
    "pressure": (OPTIONAL, "Pa", "the contact pressure at N = W (or give load)"),
    "load": (OPTIONAL, "N", "the weight W the device carries (the pressure W / (π r_c²))"),
    "diffusivity": (4.44e-6, "m2 s-1", "the thermal diffusivity of the sliding plate (steel: 4.44e-6)"),
    "conductivity": (18.0, "W m-1 K-1", "the thermal conductivity of the sliding plate (steel: 18)"),
    "temperature0": (20.0, "degC", "the plate's temperature at the start"),
    "pressure_factor": (True, "1", "μ follows the pressure (k_p)"),
    "temperature_factor": (True, "1", "μ follows the temperature (k_T)"),
    "speed_factor": (True, "1", "μ follows the speed (k_v)")}))


def _coherence(name, v, key) -> list[str]:
    """What a law's parameters must hold together."""
    out = []
    if name == "velocity_pressure" or name == "temperature":
        ways = [k for k in ("pressure", "load") if k in v]
        if name == "velocity_pressure" and ("pressure" in v) == ("load" in v and "area" in v):
            out.append(f"{key}: give the contact pressure at N = W as pressure, or as load and area (not both)")
        if name == "velocity_pressure" and "pressure" not in v and ("load" in v) != ("area" in v):
            out.append(f"{key}: load and area go together (the pressure load / area)")
        if name == "temperature" and len(ways) != 1:
            out.append(f"{key}: give the contact pressure at N = W as pressure, or the load it spreads over the "
                       f"contact area (one of them)")
    for k in ("mu", "slow", "fast", "fast0", "mu_ref"):
        if k in v and not 0.0 <= v[k] < 1.0:
            out.append(f"{key}.{k}: {v[k]!r} is outside 0 <= μ < 1")
    if name == "velocity_pressure" and "delta" in v and "fast0" in v and v["delta"] > v["fast0"]:
        out.append(f"{key}.delta: {v['delta']!r} exceeds fast0 {v['fast0']!r}: μ would fall below zero")
    return out


def contact_pressure(name, v) -> float:
    """A law's contact pressure at N = W (Pa; 0 for the laws without one)."""
    if "pressure" in v:
        return v["pressure"]
    if name == "velocity_pressure":
        return v["load"] / v["area"]
    if name == "temperature":
        return v["load"] / (math.pi * v["contact_radius"] ** 2)
    return 0.0


def row(law: Law, v: dict, weight=1.0, ratio=1.0, factor=1.0) -> np.ndarray:
    """The kernel's row of a surface's law with values ``v``: the device's coefficient is the sum over the
    surfaces of weight × factor × μ(ratio × |u̇|)."""
    r = np.zeros(ROW)
    r[[KIND, WEIGHT, RATIO, FACTOR]] = law.kind, weight, ratio, factor
    r[MU] = v.get("mu", v.get("slow", v.get("mu_ref", 0.0)))
    r[FAST] = v.get("fast", v.get("fast0", 0.0))
    r[RATE] = v.get("rate", 0.0)
    r[PRESSURE] = contact_pressure(law.name, v)
    r[DELTA], r[ALPHA], r[P_REF] = v.get("delta", 0.0), v.get("alpha", 0.0), v.get("p_ref", 0.0)
    r[KP], r[KV], r[KT] = (float(v.get(k, False)) for k in ("pressure_factor", "speed_factor", "temperature_factor"))
    r[DIFFUSIVITY], r[CONDUCTIVITY] = v.get("diffusivity", 0.0), v.get("conductivity", 1.0)
    r[RADIUS], r[T0] = v.get("contact_radius", 0.0), v.get("temperature0", 20.0)
    return r


#: the largest x whose exp(x) is a finite double (ln of the largest double)
EXP_MAX = 709.782712893384


@scalar.jit
def _exp(x):
    """exp(x), inf past the largest double as compiled code gives it (Python's math.exp raises there: a Newton
    trial at a large negative speed made an interpreted run fail where the compiled one went on)."""
    return math.inf if x > EXP_MAX else math.exp(x)


@scalar.jit
def surface_mu(r, speed, normal, temperature):
    """μ of one surface's law (its row ``r``) at the surface's sliding ``speed`` (m/s), N/W = ``normal``
    (>= 0) and ``temperature`` (°C); the factor λ not applied."""
    kind = r[0]
    if kind == 0.0:
        return r[4]
    if kind == 1.0:
        return r[5] - (r[5] - r[4]) * _exp(-r[6] * speed)
    pressure = r[7] * normal
    if kind == 2.0:
        fast = r[5] - r[8] * math.tanh(r[9] * pressure) if pressure > 0.0 else r[5]
        return fast - (fast - r[4]) * _exp(-r[6] * speed)
    mu = r[4]
    if r[11] != 0.0:
        mu = mu * 0.7 ** (0.02 * (pressure - r[10]) / 1e6)
    if r[13] != 0.0:
        mu = mu * (0.789 * (0.7 ** (temperature / 50.0) + 0.4))
    if r[12] != 0.0:
        mu = mu * (1.0 - 0.5 * _exp(-r[6] * speed))
    return mu


@scalar.jit
def device_mu(law, speed, normal, t0, t1):
    """The device's coefficient at the stroke's speed |u̇| (m/s) and N/W: Σ_s weight_s λ_s μ_s(ratio_s |u̇|),
    surface s at temperature t_s (``law`` one row per surface, one or two)."""
    mu = 0.0
    for s in range(len(law)):
        r = law[s]
        mu += r[1] * r[3] * surface_mu(r, r[2] * speed, normal, t0 if s == 0 else t1)
    return mu


@scalar.jit
def surface_mu_slopes(r, speed, normal, temperature):
    """dμ/dv (s/m) and dμ/d(N/W) of one surface's law (``surface_mu``'s arguments), the factor λ not applied:
    what the articulated slider's two sliding surfaces need to share the stroke under a law."""
    kind = r[0]
    if kind == 0.0:
        return 0.0, 0.0
    decay = _exp(-r[6] * speed)
    if kind == 1.0:
        return (r[5] - r[4]) * r[6] * decay, 0.0
    pressure = r[7] * normal
    if kind == 2.0:
        fast, dfast = r[5], 0.0
        if pressure > 0.0:
            t = math.tanh(r[9] * pressure)
            fast, dfast = r[5] - r[8] * t, -r[8] * r[9] * r[7] * (1.0 - t * t)
        return (fast - r[4]) * r[6] * decay, dfast * (1.0 - decay)
    kp, dkp = 1.0, 0.0
    if r[11] != 0.0:
        kp = 0.7 ** (0.02 * (pressure - r[10]) / 1e6)
        dkp = kp * math.log(0.7) * 0.02 * r[7] / 1e6
    kt = 0.789 * (0.7 ** (temperature / 50.0) + 0.4) if r[13] != 0.0 else 1.0
    kv, dkv = 1.0, 0.0
    if r[12] != 0.0:
        kv, dkv = 1.0 - 0.5 * decay, 0.5 * r[6] * decay
    return r[4] * kp * kt * dkv, r[4] * dkp * kt * kv
