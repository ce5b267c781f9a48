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

The ground acceleration is given as ``Ground``: on each interval [t_k, t_k+1] a straight line
a0_k + a1_k (t - t_k) (one column per component), as a record's samples are joined (and a
displacement table's piecewise-constant acceleration).

* One component (``respond``, :func:`_line`): solved exactly. On each interval the sliding
  equation is linear with a linear right-hand side, solved in closed form (a damped oscillator
  with a linear load); the ends of sliding (u̇ = 0) are roots of that closed form, found by
  bisection to the last bit; sticking ends where a straight line reaches ±μ g (exact). The
  solution is exact to rounding: no time step, no elastic branch.
* Two components (the circular interaction, z a vector): the sliding equation is nonlinear
  (ü = -a_g - ω² u - 2 ζ ω u̇ - μ g u̇ / |u̇|), integrated by scipy's DOP853 (relative tolerance
  1e-11, absolute 1e-13 m and m/s) on each interval, with sticking as an event: a phase of
  sliding ends where |u̇| falls to 1e-9 m/s (the rest of the way to rest takes at most
  1e-9 / (μ g - |f|) s, and moves the structure less than 1e-17 m), and sticking ends where |f|,
  a quadratic in t on an interval, reaches μ g (exact).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

G = 9.80665  # standard gravity (m/s²)
#: a stop in two components: |u̇| (m/s) below which the structure is at rest
REST_SPEED = 1e-9
#: a start from rest in two components: the friction is along the force until |u̇| (m/s) reaches this
START_SPEED = 1e-7
#: the two-component integrator's tolerances (relative; absolute, in m and m/s)
RTOL, ATOL = 1e-12, 1e-14


class StructureError(ValueError):
    """A structure's parameters are out of range; the message names the key."""


#: what a structure's ``friction`` is the coefficient of: the device (μ, the force at zero stroke is
#: μ W), or each of its two sliding surfaces (μs; the device's is then μs (R¹ + R³) / L)
FRICTION_ON = ("device", "surfaces")


@dataclass(frozen=True)
class Structure:
    """A rigid superstructure on the device: the friction coefficient (``friction``, 0 < μ < 1) of the
    device (``friction_on="device"``: the force at zero stroke is μ W) or of each sliding surface
    (``"surfaces"``, see :meth:`device_friction`), and the viscous damping ratio ζ (``damping``,
    0 <= ζ < 1, of the pendulum's frequency)."""

    friction: float
    damping: float = 0.0
    friction_on: str = "device"

    def __post_init__(self):
        for key, value, low_ok in (("friction", self.friction, False), ("damping", self.damping, True)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                raise StructureError(f"structure.{key}: expected a number, got {type(value).__name__} {value!r}")
            value = float(value)
            inside = (value >= 0.0 if low_ok else value > 0.0) and value < 1.0
            if not (math.isfinite(value) and inside):
                allowed = "0 <= ζ < 1" if low_ok else "0 < μ < 1"
                raise StructureError(f"structure.{key}: {value!r} is outside {allowed}")
            object.__setattr__(self, key, value)
        if self.friction_on not in FRICTION_ON:
            raise StructureError(f"structure.friction_on: must be one of {list(FRICTION_ON)}, got {self.friction_on!r}")

    def device_friction(self, geometry) -> float:
        """The device's friction coefficient μ on ``geometry`` (its L, R1, R3).

        With ``friction_on="surfaces"``, ``friction`` is the coefficient μs of each sliding surface and
        μ = μs (R¹ + R³) / L: a rigid pad that turns by dθ about both sphere centres slides R¹ dθ on
        RB1 and R³ dθ on RB3 under the normal force W (to first order in the tilt), so friction
        does the work μs W (R¹ + R³) dθ while the stroke grows by L dθ."""
        if self.friction_on == "device":
            return self.friction
        mu = self.friction * float(geometry.R1 + geometry.R3) / float(geometry.L)
        if not mu < 1.0:
            raise StructureError(f"structure.friction: {self.friction!r} on each surface is a device friction "
                                 f"{mu:.4g} = μs (R1 + R3) / L, outside 0 < μ < 1")
        return mu

    def attrs(self, geometry) -> dict:
        """netCDF attributes of the structure on ``geometry`` (a device of pendulum length L)."""
        return {"structure_friction": self.device_friction(geometry), "structure_damping": self.damping,
                "structure_friction_on": self.friction_on, "structure_friction_given": self.friction,
                "structure_pendulum_length_m": float(geometry.L), "structure_period_s": period(geometry.L)}


def period(L) -> float:
    """The pendulum's period 2π √(L / g) (s)."""
    return float(2 * np.pi * np.sqrt(L / G))


class Ground(NamedTuple):
    """A piecewise-linear ground acceleration: a0[k] + a1[k] (t - time[k]) on [time[k], time[k+1]]
    (m/s², m/s³), with a column per component (shape (n, c))."""

    time: np.ndarray  # (n + 1,)
    a0: np.ndarray  # (n, c)
    a1: np.ndarray  # (n, c)

    @classmethod
    def from_samples(cls, time, acceleration) -> Ground:
        """Samples (n + 1,) or (n + 1, c) joined by straight lines."""
        time = np.asarray(time, dtype=float)
        a = np.asarray(acceleration, dtype=float).reshape(time.size, -1)
        return cls(time, a[:-1], np.diff(a, axis=0) / np.diff(time)[:, None])

    def at(self, t):
        """The acceleration at times t, shape (len(t), c); outside the span the end values hold."""
        t = np.asarray(t, dtype=float)
        k = np.clip(np.searchsorted(self.time, t, side="right") - 1, 0, self.a0.shape[0] - 1)
        tau = np.clip(t, self.time[0], self.time[-1]) - self.time[k]
        return self.a0[k] + self.a1[k] * tau[:, None]

    def refined(self, times) -> tuple[Ground, np.ndarray]:
        """The same acceleration with ``times`` added as interval ends, and the index of each of
        ``times`` among the new ends (times within 1e-9 of an interval of an end count as on it)."""
        times = np.asarray(times, dtype=float)
        near = 1e-9 * float(np.min(np.diff(self.time)))
        knots = np.union1d(self.time, times)
        keep = np.concatenate([[True], np.diff(knots) > near])
        knots = knots[keep]
        k = np.clip(np.searchsorted(self.time, knots[:-1] + near, side="right") - 1, 0, self.a0.shape[0] - 1)
        tau = knots[:-1] - self.time[k]
        ground = Ground(knots, self.a0[k] + self.a1[k] * tau[:, None], self.a1[k])
        index = np.clip(np.searchsorted(knots, times - near, side="left"), 0, knots.size - 1)
        return ground, index


class Response(NamedTuple):
    """The structure's response at the requested times: stroke u (m), its velocity (m/s), the
    friction state z and the force ratio F/W, each (T, c); ``sticking`` (T,) whether u̇ = 0 there."""

    stroke: np.ndarray
    velocity: np.ndarray
    z: np.ndarray
    shear_ratio: np.ndarray
    sticking: np.ndarray


#: a structure's summaries of one history: name -> (units, long_name)
SUMMARIES = {
    "stroke_max_abs": ("m", "largest |stroke| (the superstructure's displacement relative to the ground)"),
    "stroke_end": ("m", "residual stroke u(t_end) (its size |u| for two components)"),
    "shear_ratio_max_abs": ("1", "largest |F/W| of the device"),
}


def summarize(response: Response) -> dict:
    """The :data:`SUMMARIES` of a response: vector sizes for two components, u(t_end) signed for one."""
    stroke = np.linalg.norm(response.stroke, axis=1)
    end = response.stroke[-1, 0] if response.stroke.shape[1] == 1 else stroke[-1]
    return {"stroke_max_abs": float(np.max(stroke)), "stroke_end": float(end),
            "shear_ratio_max_abs": float(np.max(np.linalg.norm(response.shear_ratio, axis=1)))}


def respond(ground: Ground, times, geometry, structure: Structure) -> Response:
    """The structure's response to ``ground`` at ``times`` (s, within the ground's span), on the device
    ``geometry`` (its pendulum length L, and R1, R3 for a surfaces' friction); at rest (u = u̇ = 0) at
    ``ground.time[0]``."""
    return solve(ground, times, float(geometry.L), structure.device_friction(geometry), structure.damping)


def solve(ground: Ground, times, L, mu, zeta) -> Response:
    """:func:`respond` for any μ >= 0 (μ = 0: free sliding, the pendulum alone) and 0 <= ζ < 1."""
    refined, index = ground.refined(times)
    omega = math.sqrt(G / L)
    components = refined.a0.shape[1]
    if components == 1:
        u, v, z, stick = _line(refined.time, refined.a0[:, 0], refined.a1[:, 0], omega, zeta, mu * G)
        u, v, z = u[:, None], v[:, None], z[:, None]
    else:
        u, v, z, stick = _plane(refined, omega, zeta, mu * G)
    u, v, z, stick = u[index], v[index], z[index], stick[index]
    return Response(u, v, z, u / L + mu * z, stick)


#: stick/slip phases in one sample interval beyond which the solver gives up (a chatter it cannot resolve)
MAX_PHASES = 10_000


def _count(phases, t):
    if phases >= MAX_PHASES:
        raise RuntimeError(f"structure: more than {MAX_PHASES} stick/slip phases in the sample interval at "
                           f"t = {t:g} s: the friction chatters; report the record and the structure")
    return phases + 1


# --- one component: exact ----------------------------------------------------------------------

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


def _acceleration(u0, v0, p0, p1, omega, zeta, tau):
    u, v = _slide(u0, v0, p0, p1, omega, zeta, tau)
    return p0 + p1 * tau - 2 * zeta * omega * v - omega**2 * u


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


def _line(time, a0, a1, omega, zeta, friction):
    """Exact one-component history at the interval ends: u, u̇, z, sticking (see the module docstring);
    ``friction`` is μ g (m/s²)."""
    n = time.size
    u, v, z = np.zeros(n), np.zeros(n), np.zeros(n)
    stick = np.zeros(n, dtype=bool)
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
            phases = _count(phases, time[k])
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
    return u, v, z, stick


# --- two components: the circular interaction -------------------------------------------------

def _plane(ground: Ground, omega, zeta, friction):
    """Two-component history at the interval ends (see the module docstring): u, u̇, z (n, 2) and sticking."""
    time, a0, a1 = ground
    n = time.size
    u, v, z = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    stick = np.zeros(n, dtype=bool)
    x, w = np.zeros(2), np.zeros(2)
    demand = -a0[0]
    sliding = friction == 0.0 or math.hypot(*demand) > friction
    stick[0] = not sliding
    z[0] = demand / friction if not sliding else _direction(w, demand, friction)
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        tau, phases = 0.0, 0
        while tau < h:
            phases = _count(phases, time[k])
            b0, b1 = a0[k] + a1[k] * tau, a1[k]
            end = h - tau
            if not sliding:
                when = _breakaway(-b0 - omega**2 * x, -b1, friction, end)
                tau += when if when >= 0.0 else end
                sliding = when >= 0.0
                continue

            y0 = np.concatenate([x, w])
            if friction > 0.0 and not w.any():
                # a start from rest: u̇ grows along the force, whose direction u̇ / |u̇| takes within
                # a vanishing time; until |u̇| reaches START_SPEED the friction is taken along the
                # force (exact along a line), which spares the integrator the direction of a
                # velocity that is only rounding
                sol = _integrate(y0, b0, b1, omega, zeta, friction, end, start=True)
                if sol.status == 1 and sol.t_events[1].size:  # the force fell back within the cone: rest
                    when = float(sol.t_events[1][0])
                    x, tau, sliding = sol.y_events[1][0][:2].copy(), tau + when, False
                    continue
                if sol.status == 1:
                    when = float(sol.t_events[0][0])
                    y0, tau, end = sol.y_events[0][0].copy(), tau + when, end - when
                    b0 = b0 + b1 * when
                else:
                    x, w, tau = sol.y[:2, -1].copy(), sol.y[2:, -1].copy(), h
                    continue
            sol = _integrate(y0, b0, b1, omega, zeta, friction, end, start=False)
            if sol.status == 1:  # at rest: the last REST_SPEED at the deceleration there, to first order
                y = sol.y_events[0][0]
                when = float(sol.t_events[0][0])
                speed = math.hypot(y[2], y[3])
                force = -(b0 + b1 * when) - omega**2 * y[:2]
                slowing = friction + 2 * zeta * omega * speed - force @ y[2:] / speed
                last = min(speed / slowing, end - when) if slowing > 0.0 else 0.0
                x, w = y[:2] + 0.5 * last * y[2:], np.zeros(2)
                when += last
                tau += when
                force = -(b0 + b1 * when) - omega**2 * x
                sliding = math.hypot(*force) > friction
                continue
            x, w = sol.y[:2, -1].copy(), sol.y[2:, -1].copy()
            tau = h
        u[k + 1], v[k + 1] = x, w
        force = -(a0[k] + a1[k] * h) - omega**2 * x
        stick[k + 1] = not sliding
        z[k + 1] = force / friction if not sliding else _direction(w, force, friction)
    return u, v, z, stick


def _integrate(y0, b0, b1, omega, zeta, friction, end, *, start):
    """DOP853 over one interval of sliding from y0 = (u, u̇) (shifted to tau = 0 with the load
    -b0 - b1 tau), stopped at rest (|u̇| = REST_SPEED, falling) or, for a ``start`` from rest, where
    |u̇| reaches START_SPEED (event 0) or the force falls back to μ g (event 1)."""
    from scipy.integrate import solve_ivp

    def force(t, y):
        return -(b0 + b1 * t) - omega**2 * y[:2]

    def rhs(t, y):
        f = force(t, y)
        along = f if start else y[2:]
        size = math.hypot(along[0], along[1])
        z = along / size if size > 0.0 else along
        return np.concatenate([y[2:], f - 2 * zeta * omega * y[2:] - friction * z])

    def moving(t, y):
        return math.hypot(y[2], y[3]) - START_SPEED

    def held(t, y):
        f = force(t, y)
        return math.hypot(f[0], f[1]) - friction

    def rest(t, y):
        return math.hypot(y[2], y[3]) - REST_SPEED

    moving.terminal, moving.direction = True, 1
    held.terminal, held.direction = True, -1
    rest.terminal, rest.direction = True, -1
    events = (moving, held) if start else (rest if friction > 0.0 else None)
    return solve_ivp(rhs, (0.0, end), y0, method="DOP853", rtol=RTOL, atol=ATOL, events=events)


def _direction(velocity, force, friction):
    """The friction state z of sliding: u̇ / |u̇|, or at rest (the start of sliding) the force's direction."""
    if friction == 0.0:
        return np.zeros(2)
    speed = math.hypot(velocity[0], velocity[1])
    if speed > 0.0:
        return velocity / speed
    size = math.hypot(force[0], force[1])
    return force / size if size > 0.0 else np.zeros(2)


def _breakaway(d0, d1, friction, end):
    """The first tau in (0, end) where |d0 + d1 tau| reaches ``friction`` (a quadratic), or -1."""
    a = d1 @ d1
    b = 2 * (d0 @ d1)
    c = d0 @ d0 - friction**2
    if c > 0.0:
        return 0.0
    if a == 0.0:
        return -1.0
    disc = b * b - 4 * a * c
    if disc < 0.0:
        return -1.0
    root = (-b + math.sqrt(disc)) / (2 * a)  # c <= 0: the larger root is the exit
    return root if 0.0 < root < end else -1.0
