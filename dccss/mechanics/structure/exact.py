"""One component: the structure's history solved exactly.

On each sample interval the sliding equation ü + 2ζω u̇ + ω² u = -a_g - μ g z is linear with a
linear right-hand side, solved in closed form (a damped oscillator with a linear load); the ends of
sliding (u̇ = 0) are roots of that closed form, found by bisection to the last bit; sticking ends where
a straight line reaches ±μ g (exact). The solution is exact to rounding: no time step, no elastic
branch.

``line`` is written in the scalar subset Numba compiles, as the two-component kernel
(``circular.plane``): compiled for a long record (or many, a spectrum's periods), interpreted for a
short one, with the same bits.
"""

from __future__ import annotations

import math

import numpy as np

from .. import scalar

#: stick/slip phases in one sample interval beyond which the solver gives up (a chatter it cannot resolve)
MAX_PHASES = 10_000
#: the same of one component's sample interval (``line``): about 5 µs sliding, more at a stop
LINE_WORK = 1
#: a kernel's status: done, the friction chatters (MAX_PHASES), a step too short
DONE, CHATTER, FAILED = 0, 1, 2


#: stick/slip phases in one sample interval beyond which the solver gives up (a chatter it cannot resolve)
MAX_PHASES = 10_000


@scalar.jit
def slide(u0, v0, p0, p1, omega, zeta, tau):
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
def first_stop(u0, v0, p0, p1, omega, zeta, sign, tau_end):
    """The first tau in (0, tau_end] where sign * u̇ falls to 0 while sliding (sign = ±1), or -1."""
    pieces = max(1, math.ceil(omega * tau_end / 0.25))
    left = 0.0
    for i in range(1, pieces + 1):
        right = tau_end * i / pieces
        if sign * slide(u0, v0, p0, p1, omega, zeta, right)[1] <= 0.0:
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
            if sign * slide(u0, v0, p0, p1, omega, zeta, lo)[1] <= 0.0:
                return _bisect(u0, v0, p0, p1, omega, zeta, sign, left, lo)
        left = right
    return -1.0


@scalar.jit
def _acceleration(u0, v0, p0, p1, omega, zeta, tau):
    u, v = slide(u0, v0, p0, p1, omega, zeta, tau)
    return p0 + p1 * tau - 2 * zeta * omega * v - omega**2 * u


@scalar.jit
def _bisect(u0, v0, p0, p1, omega, zeta, sign, lo, hi):
    """The root of sign * u̇ in (lo, hi], where it is > 0 at lo (or lo = 0) and <= 0 at hi."""
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if sign * slide(u0, v0, p0, p1, omega, zeta, mid)[1] > 0.0:
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
            when = -1.0 if friction == 0.0 else first_stop(x, w, p0, p1, omega, zeta, sign, end)
            if when < 0.0:
                x, w = slide(x, w, p0, p1, omega, zeta, end)
                tau = h
                continue
            x, _ = slide(x, w, p0, p1, omega, zeta, when)
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


def line_history(time, a0, a1, omega, zeta, friction, compiled=None):
    """One-component history at the interval ends: u, u̇, z, sticking (``line``); ``compiled`` None:
    compiled for a long record (``backend``), interpreted for a short one."""
    from .. import backend

    n = time.size
    if compiled is None:
        compiled = backend.choose(n - 1, LINE_WORK) == "numba"
    run = scalar.kernel(line) if compiled else line
    u, v, z = np.zeros(n), np.zeros(n), np.zeros(n)
    stick = np.zeros(n, dtype=bool)
    status, k = run(np.ascontiguousarray(time, dtype=float), np.ascontiguousarray(a0, dtype=float),
                    np.ascontiguousarray(a1, dtype=float), float(omega), float(zeta), float(friction), u, v, z, stick)
    if status == CHATTER:
        raise chatter(time[k])
    return u, v, z, stick


def chatter(t) -> RuntimeError:
    """The error of a sample interval (at t, s) of more than MAX_PHASES stick/slip phases."""
    return RuntimeError(f"structure: more than {MAX_PHASES} stick/slip phases in the sample interval at t = {t:g} s: "
                        f"the friction chatters; report the record and the structure")
