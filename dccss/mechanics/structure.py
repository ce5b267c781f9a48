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
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from . import scalar

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
    """A rigid superstructure on the device: the friction coefficient (``friction``, 0 < μ < 1) of the
    device (``friction_on="device"``: the force at zero stroke is μ W) or of each sliding surface
    (``"surfaces"``, see :meth:`device_friction`), and the viscous damping ratio ζ (``damping``,
    0 <= ζ < 1, of the pendulum's frequency)."""

    friction: float
    damping: float = 0.0
    friction_on: str = "device"

    def __post_init__(self):
        problems = []
        for key, value, low_ok in (("friction", self.friction, False), ("damping", self.damping, True)):
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                problems.append(f"structure.{key}: expected a number, got {type(value).__name__} {value!r}")
                continue
            value = float(value)
            inside = (value >= 0.0 if low_ok else value > 0.0) and value < 1.0
            if not (math.isfinite(value) and inside):
                allowed = "0 <= ζ < 1" if low_ok else "0 < μ < 1"
                problems.append(f"structure.{key}: {value!r} is outside {allowed}")
            object.__setattr__(self, key, value)
        if self.friction_on not in FRICTION_ON:
            problems.append(f"structure.friction_on: must be one of {list(FRICTION_ON)}, got {self.friction_on!r}")
        if problems:
            raise StructureError(*problems)

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
        if np.array_equal(times, self.time):  # the samples themselves (a spectrum): nothing to add
            return self, np.arange(times.size)
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
    friction state z and the force ratio F/W, each (T, c); ``sticking`` (T,) whether u̇ = 0 there;
    ``peaks``: the largest |u| (m) and |F/W| over the record's samples and the requested times, from
    the first of these to the record's end (a coarse step would miss the peaks between its times, and
    a step that does not divide the record the peaks after its last time)."""

    stroke: np.ndarray
    velocity: np.ndarray
    z: np.ndarray
    shear_ratio: np.ndarray
    sticking: np.ndarray
    peaks: tuple = (math.nan, math.nan)


#: a structure's summaries of one history: name -> (units, long_name)
SUMMARIES = {
    "stroke_max_abs": ("m", "largest |stroke| (the superstructure's displacement relative to the ground) over the "
                            "whole record, whatever became of the pad"),
    "stroke_end": ("m", "residual stroke u(t_end) (its size |u| for two components)"),
    "shear_ratio_max_abs": ("1", "largest |F/W| of the device"),
}


def summarize(response: Response) -> dict:
    """The :data:`SUMMARIES` of a response: vector sizes for two components, u(t_end) signed for one; the
    peaks over the record's samples too (``Response.peaks``)."""
    stroke = np.linalg.norm(response.stroke, axis=1)
    end = response.stroke[-1, 0] if response.stroke.shape[1] == 1 else stroke[-1]
    return {"stroke_max_abs": response.peaks[0], "stroke_end": float(end), "shear_ratio_max_abs": response.peaks[1]}


def respond(ground: Ground, times, geometry, structure: Structure) -> Response:
    """The structure's response to ``ground`` at ``times`` (s, within the ground's span), on the device
    ``geometry`` (its pendulum length L, and R1, R3 for a surfaces' friction); at rest (u = u̇ = 0) at
    ``ground.time[0]``."""
    return solve(ground, times, float(geometry.L), structure.device_friction(geometry), structure.damping)


def solve(ground: Ground, times, L, mu, zeta, compiled=None) -> Response:
    """:func:`respond` for any μ >= 0 (μ = 0: free sliding, the pendulum alone) and 0 <= ζ < 1;
    ``compiled`` None: the kernels compiled for a long record, interpreted for a short one."""
    refined, index = ground.refined(times)
    omega = math.sqrt(G / L)
    components = refined.a0.shape[1]
    if components == 1:
        u, v, z, stick = _line(refined.time, refined.a0[:, 0], refined.a1[:, 0], omega, zeta, mu * G, compiled)
        u, v, z = u[:, None], v[:, None], z[:, None]
    else:
        u, v, z, stick = _plane(refined, omega, zeta, mu * G, compiled)
    span = slice(index[0], None)  # to the record's end, past the last requested time
    peaks = tuple(float(np.max(np.linalg.norm(x[span], axis=1))) for x in (u, u / L + mu * z))
    u, v, z, stick = u[index], v[index], z[index], stick[index]
    return Response(u, v, z, u / L + mu * z, stick, peaks)


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


@functools.cache
def _tableau(compiled):
    """DOP853's A (row-major), B, C, E3 and E5 (scipy.integrate.DOP853's): numpy arrays for the compiled
    kernel, lists (faster to index) interpreted."""
    from scipy.integrate import DOP853

    arrays = [np.ascontiguousarray(c, dtype=float).ravel() for c in (DOP853.A, DOP853.B, DOP853.C, DOP853.E3,
                                                                      DOP853.E5)]
    if [a.size for a in arrays] != [STAGES * STAGES, STAGES, STAGES, STAGES + 1, STAGES + 1]:
        raise RuntimeError(f"scipy.integrate.DOP853's tableau is not of {STAGES} stages: scipy changed it")
    return tuple(arrays) if compiled else tuple(a.tolist() for a in arrays)


@scalar.jit
def _force(t, y, load):
    """f = -a_g - ω² u at t (from the slide's start) and y, the ground's acceleration from there
    b0 + b1 t; load = (b0x, b0y, b1x, b1y, ω², 2ζω, μ g)."""
    return -(load[0] + load[2] * t) - load[4] * y[0], -(load[1] + load[3] * t) - load[4] * y[1]


@scalar.jit
def _rhs(t, y, row, K, load, start):
    """K[row] = dy/dt: u̇ and ü = f - 2ζω u̇ - μ g z, z the direction of u̇ (of f for a ``start`` from rest)."""
    f0, f1 = _force(t, y, load)
    d0, d1 = (f0, f1) if start else (y[2], y[3])
    size = math.sqrt(d0 * d0 + d1 * d1)
    if size > 0.0:
        d0, d1 = d0 / size, d1 / size
    at = row * SIZE
    K[at] = y[2]
    K[at + 1] = y[3]
    K[at + 2] = f0 - load[5] * y[2] - load[6] * d0
    K[at + 3] = f1 - load[5] * y[3] - load[6] * d1


@scalar.jit
def _step(t, y, h, K, out, trial, load, start, A, B, C):
    """One DOP853 step of length h from (t, y), K[0] the derivative there: out = y(t + h), the stages in
    K, K[STAGES] the derivative at t + h."""
    for s in range(1, STAGES):
        for c in range(SIZE):
            acc = 0.0
            for j in range(s):
                acc += K[j * SIZE + c] * A[s * STAGES + j]
            trial[c] = y[c] + acc * h
        _rhs(t + C[s] * h, trial, s, K, load, start)
    for c in range(SIZE):
        acc = 0.0
        for j in range(STAGES):
            acc += K[j * SIZE + c] * B[j]
        out[c] = y[c] + h * acc
    _rhs(t + h, out, STAGES, K, load, start)


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
def _first_step(y, end, K, trial, load, start, rtol, atol):
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
    _rhs(h0, trial, STAGES, K, load, start)  # K[STAGES] is scratch here
    d2 = 0.0
    for c in range(SIZE):
        g = (K[STAGES * SIZE + c] - K[c]) / (atol + abs(y[c]) * rtol)
        d2 += g * g
    d2 = math.sqrt(d2 / SIZE) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** (1.0 / 9.0)
    return min(100.0 * h0, h1, end)


@scalar.jit
def _g(event, t, y, load):
    """The event's function: |u̇| - REST_SPEED (STOP), |u̇| - START_SPEED (MOVING), |f| - μ g (HELD)."""
    if event == HELD:
        f0, f1 = _force(t, y, load)
        return math.sqrt(f0 * f0 + f1 * f1) - load[6]
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
def _locate(event, t, y, h, K, out, trial, load, start, A, B, C):
    """The length s in (0, h] of the step from (t, y) that reaches the event (bisection to BRACKET), the
    event being past at h and not at 0; ``out`` is scratch."""
    lo, hi = 0.0, h
    while hi - lo > BRACKET:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        _step(t, y, mid, K, out, trial, load, start, A, B, C)
        if _beyond(event, _g(event, t + mid, out, load)):
            hi = mid
        else:
            lo = mid
    return hi


@scalar.jit
def _integrate(y, end, h, load, start, stop, rtol, atol, A, B, C, E3, E5, K, out, trial):
    """DOP853 over [0, end] from y (overwritten with the state reached): (what ended it, when, the next
    step). Events: STOP if ``stop``; MOVING and HELD for a ``start``; the earliest ends the slide."""
    t = 0.0
    _rhs(t, y, 0, K, load, start)
    if h <= 0.0:
        h = _first_step(y, end, K, trial, load, start, rtol, atol)
    carry = h
    while t < end:
        rejected = False
        while True:
            if h < MIN_STEP:
                return TOO_SHORT, t, h
            t_new = min(t + h, end)
            taken = t_new - t
            _step(t, y, taken, K, out, trial, load, start, A, B, C)
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
        crossed = (stop and _crosses(STOP, _g(STOP, t, y, load), _g(STOP, t_new, out, load)),
                   start and _crosses(MOVING, _g(MOVING, t, y, load), _g(MOVING, t_new, out, load)),
                   start and _crosses(HELD, _g(HELD, t, y, load), _g(HELD, t_new, out, load)))
        first, length = NONE, taken
        for event in (STOP, MOVING, HELD):
            if crossed[event - 1]:
                s = _locate(event, t, y, taken, K, out, trial, load, start, A, B, C)
                if first == NONE or s < length:
                    first, length = event, s
        if first != NONE:
            _step(t, y, length, K, out, trial, load, start, A, B, C)
            for c in range(SIZE):
                y[c] = out[c]
            return first, t + length, carry
        for c in range(SIZE):
            y[c] = out[c]
            K[c] = K[STAGES * SIZE + c]
        t = t_new
    return NONE, end, carry


@scalar.jit
def _breakaway(d0x, d0y, d1x, d1y, friction, end):
    """The first tau in (0, end) where |d0 + d1 tau| reaches ``friction`` (a quadratic), or -1."""
    a = d1x * d1x + d1y * d1y
    b = 2 * (d0x * d1x + d0y * d1y)
    c = (d0x * d0x + d0y * d0y) - friction * friction
    if c > 0.0:
        return 0.0
    if a == 0.0:
        return -1.0
    disc = b * b - 4 * a * c
    if disc < 0.0:
        return -1.0
    root = (-b + math.sqrt(disc)) / (2 * a)  # c <= 0: the larger root is the exit
    return root if 0.0 < root < end else -1.0


@scalar.jit
def _state(k, x0, x1, w0, w1, f0, f1, sliding, friction, u, v, z, stick):
    """Row k of the history: u, u̇, and z (f / μ g sticking; sliding, the direction of u̇, or at rest
    that of the force)."""
    u[k, 0], u[k, 1], v[k, 0], v[k, 1] = x0, x1, w0, w1
    stick[k] = not sliding
    if not sliding:
        z[k, 0], z[k, 1] = f0 / friction, f1 / friction
        return
    z[k, 0], z[k, 1] = 0.0, 0.0
    if friction == 0.0:
        return
    d0, d1 = (w0, w1) if w0 != 0.0 or w1 != 0.0 else (f0, f1)
    size = math.sqrt(d0 * d0 + d1 * d1)
    if size > 0.0:
        z[k, 0], z[k, 1] = d0 / size, d1 / size


def plane(time, a0, a1, omega, zeta, friction, rtol, atol, A, B, C, E3, E5, K, y, out, trial, u, v, z, stick):
    """The two-component history at the interval ends (the module docstring) into u, u̇, z (n, 2) and
    sticking (n,): (DONE, 0), or (CHATTER or FAILED, the interval where the run stopped)."""
    n = time.size
    w2, damp = omega * omega, 2 * zeta * omega
    x0, x1, w0, w1 = 0.0, 0.0, 0.0, 0.0
    # sticking holds while |f| <= μ g (1 + rtol): a stop where the force equals the friction to within
    # the integration's own accuracy (as a Coulomb oscillator's last stop under a constant load) is
    # not left to the rounding of the state there
    hold = friction * (1.0 + rtol)
    f0, f1 = -a0[0, 0], -a0[0, 1]
    sliding = friction == 0.0 or math.sqrt(f0 * f0 + f1 * f1) > hold
    starting = sliding and friction > 0.0  # a start from rest, until |u̇| reaches START_SPEED
    _state(0, x0, x1, w0, w1, f0, f1, sliding, friction, u, v, z, stick)
    h_next = 0.0  # the integrator's step, carried while the structure slides on
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        tau, phases = 0.0, 0
        while tau < h:
            phases += 1
            if phases > MAX_PHASES:
                return CHATTER, k
            b00, b01 = a0[k, 0] + a1[k, 0] * tau, a0[k, 1] + a1[k, 1] * tau
            b10, b11 = a1[k, 0], a1[k, 1]
            end = h - tau
            if not sliding:
                when = _breakaway(-b00 - w2 * x0, -b01 - w2 * x1, -b10, -b11, hold, end)
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
                load = (b00, b01, b10, b11, w2, damp, friction)
                ended, when, h_next = _integrate(y, end, 0.0, load, True, False, rtol, atol, A, B, C, E3, E5, K,
                                                 out, trial)
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
            load = (b00, b01, b10, b11, w2, damp, friction)
            ended, when, h_next = _integrate(y, end, h_next, load, False, friction > 0.0, rtol, atol, A, B, C, E3,
                                             E5, K, out, trial)
            if ended == TOO_SHORT:
                return FAILED, k
            if ended == STOP:  # at rest: the last REST_SPEED at the deceleration there, to first order
                speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
                g0, g1 = _force(when, y, load)
                slowing = friction + damp * speed - (g0 * y[2] + g1 * y[3]) / speed
                last = min(speed / slowing, end - when) if slowing > 0.0 else 0.0
                x0, x1, w0, w1 = y[0] + 0.5 * last * y[2], y[1] + 0.5 * last * y[3], 0.0, 0.0
                when += last
                tau += when
                g0 = -(b00 + b10 * when) - w2 * x0
                g1 = -(b01 + b11 * when) - w2 * x1
                sliding = starting = math.sqrt(g0 * g0 + g1 * g1) > hold
                h_next = 0.0
                continue
            x0, x1, w0, w1, tau = y[0], y[1], y[2], y[3], h
        f0 = -(a0[k, 0] + a1[k, 0] * h) - w2 * x0
        f1 = -(a0[k, 1] + a1[k, 1] * h) - w2 * x1
        _state(k + 1, x0, x1, w0, w1, f0, f1, sliding, friction, u, v, z, stick)
    return DONE, 0


def _plane(ground: Ground, omega, zeta, friction, compiled=None):
    """Two-component history at the interval ends (see the module docstring): u, u̇, z (n, 2) and
    sticking; ``compiled`` None: compiled for a long record (``backend``), interpreted for a short one."""
    from . import backend

    time, a0, a1 = ground
    n = time.size
    if compiled is None:
        compiled = backend.choose(n - 1, INTERVAL_WORK) == "numba"
    run = scalar.kernel(plane) if compiled else plane
    work = (np.zeros((STAGES + 1) * SIZE), np.zeros(SIZE), np.zeros(SIZE), np.zeros(SIZE))
    if not compiled:
        work = tuple(w.tolist() for w in work)
    u, v, z = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    stick = np.zeros(n, dtype=bool)
    status, k = run(np.ascontiguousarray(time, dtype=float), np.ascontiguousarray(a0, dtype=float),
                    np.ascontiguousarray(a1, dtype=float), float(omega), float(zeta), float(friction), float(RTOL),
                    float(ATOL), *_tableau(compiled), *work, u, v, z, stick)
    if status == CHATTER:
        raise _chatter(time[k])
    if status == FAILED:
        raise RuntimeError(f"structure: the two-component integration's step fell below {MIN_STEP:g} s in the "
                           f"sample interval at t = {time[k]:g} s; report the record and the structure")
    return u, v, z, stick


def warm():
    """Compile (or load) the one- and two-component kernels into the on-disk cache."""
    ground = Ground.from_samples([0.0, 0.01, 0.02], [[0.0, 0.0], [1.0, 0.5], [0.0, 0.0]])
    _plane(ground, 2.0, 0.0, 0.05 * G, compiled=True)
    _line(ground.time, ground.a0[:, 0], ground.a1[:, 0], 2.0, 0.0, 0.05 * G, compiled=True)
