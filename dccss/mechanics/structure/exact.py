"""One component: the structure's history solved exactly.

On each sample interval the sliding equation ü + 2ζω u̇ + ω² u = -a_g - μ g z is linear with a
linear right-hand side, solved in closed form (a damped oscillator with a linear load); the ends of
sliding (u̇ = 0) are roots of that closed form, found by bisection to the last bit; sticking ends where
a straight line reaches ±μ g (exact). The solution is exact to rounding: no time step, no elastic
branch. A rest starts by asking whether the demand is already at or past the friction (``leaving``):
where it reaches it at a sample, or within rounding of one, sliding starts there.

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
        if left == 0.0 and v0 == 0.0 and sign * _start_acceleration(u0, p0, p1, omega, zeta, sign, right) >= 0.0:
            # a start from rest, sign * ü >= 0 at both ends of the piece: ü changes sign at most once on a
            # piece (``_start_acceleration``), so u̇ grows across it and does not stop, whatever the rounding
            # of u̇ while it is still tiny (a piece ending just after the start, or a load growing by a few ulps)
            left = right
            continue
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
def _start_acceleration(u0, p0, p1, omega, zeta, sign, tau):
    """ü at tau of a start from rest at u0 (u̇ = 0; sign * ü >= 0 there, as at a start, rounding aside): the
    load being linear, ü obeys the unloaded oscillator, a damped sinusoid (its zeros π / ω_d apart) from ü(0)
    and ü'(0) = p1 - 2ζω ü(0), in closed form without the rounding of u and u̇."""
    a0 = sign * max(sign * (p0 - omega**2 * u0), 0.0)
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    c, s = math.cos(wd * tau), math.sin(wd * tau)
    return math.exp(-zeta * omega * tau) * (a0 * c + (p1 - zeta * omega * a0) / wd * s)


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


@scalar.jit
def reach(y0, v0, p0, p1, omega, zeta, sign, target, end):
    """The first tau in [0, end] where sign * (y(tau) - target) reaches 0 (y monotone in the sign's
    direction over (0, end]: a slide up to its stop), by bisection; -1 where it is not reached."""
    if sign * (y0 - target) >= 0.0:
        return 0.0
    if sign * (slide(y0, v0, p0, p1, omega, zeta, end)[0] - target) < 0.0:
        return -1.0
    lo, hi = 0.0, end
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if sign * (slide(y0, v0, p0, p1, omega, zeta, mid)[0] - target) < 0.0:
            lo = mid
        else:
            hi = mid
    return hi


@scalar.jit
def leaving(demand, slope, lower, upper, past_upper, past_lower):
    """The direction in which a rest under ``demand`` (m/s²), changing at ``slope`` (m/s³), ends at once:
    +1 where it reaches ``upper`` and grows on, or lies past it and ``past_upper`` (a demand past the bound
    starts sliding there); -1 likewise at ``lower``; 0: it holds."""
    if demand >= upper and (slope > 0.0 or (past_upper and demand > upper)):
        return 1.0
    if demand <= lower and (slope < 0.0 or (past_lower and demand < lower)):
        return -1.0
    return 0.0


@scalar.jit
def rest_end(d0, d1, lower, upper, end):
    """Where a rest under the demand d0 + d1 tau, held within [lower, upper], ends in [0, end), and the
    direction sliding starts in: at once (0, ``leaving``) where the demand is at or past a bound and grows on,
    else where the straight line reaches a bound (exact); (end, 0) where it holds to the end.

    A rest starts where a stop or a sample has just found the demand within the bounds: one that lies past a
    bound here, by the rounding of the demand taken again, and does not grow on, is held (a start would stop
    again within that rounding, without the time moving on)."""
    direction = leaving(d0, d1, lower, upper, False, False)
    if direction != 0.0:
        return 0.0, direction
    if d1 > 0.0:
        when = (upper - d0) / d1
        if 0.0 < when < end:
            return when, 1.0
    elif d1 < 0.0:
        when = (lower - d0) / d1
        if 0.0 < when < end:
            return when, -1.0
    return end, 0.0


@scalar.jit
def slide_on(x, w, p0, p1, omega, zeta, sign, end, stops):
    """Slide from (x, w) in the direction ``sign`` under the load p0 + p1 tau (``slide``) until u̇ falls to
    0 (``first_stop``; only where the friction ``stops`` it) or to ``end``: (x, u̇, tau, stopped)."""
    when = first_stop(x, w, p0, p1, omega, zeta, sign, end) if stops else -1.0
    if when < 0.0:
        x, w = slide(x, w, p0, p1, omega, zeta, end)
        return x, w, end, False
    x, _ = slide(x, w, p0, p1, omega, zeta, when)
    return x, 0.0, when, True


def line(time, a0, a1, omega, zeta, friction, ring, u, v, z, stick, held, impacts):
    """The exact one-component history at the interval ends into u, u̇, z, sticking, the ring's force ``held``
    (m/s², per unit mass, where the pad rests against a ring and the demand presses it on) and, per interval,
    ``impacts`` (n, 3): the impacts on a ring in the interval ending at the sample, the largest speed at
    impact (m/s) and the kinetic energy they take, Σ u̇²/2 (J/kg). ``friction`` is μ g (m/s²); ``ring`` the
    stroke at which the pad meets a ring (m; inf: no ring). Returns (DONE, n - 1), or (CHATTER, k) at an
    interval k of more than MAX_PHASES stick/slip phases.

    A ring is a stop: the slide that reaches it ends in a perfectly plastic impact (u̇ drops to 0) and the
    pad rests against it while the demand -a_g - ω² u presses it on or the friction holds it, whatever the
    demand outwards (the ring carries it); it leaves where the demand pulls it back past the friction."""
    n = len(time)
    x, w = 0.0, 0.0  # u, u̇
    at = 0.0  # the ring the pad rests against: +1, -1, or 0
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
                # sticking: the demand -a_g - ω² u is a straight line in t; it ends at ±μ g (against a ring:
                # only where it pulls back off it)
                lower = -math.inf if at < 0.0 else -friction
                upper = math.inf if at > 0.0 else friction
                when, direction = rest_end(-b0 - omega**2 * x, -b1, lower, upper, h - tau)
                tau += when
                if direction != 0.0:
                    sliding, sign, at = True, direction, 0.0
                continue
            p0 = -b0 - sign * friction
            x0, w0 = x, w
            x, w, when, stopped = slide_on(x, w, p0, -b1, omega, zeta, sign, h - tau, friction > 0.0)
            if sign * x >= ring:  # the ring is reached first: an impact, the pad held against it
                when = reach(x0, w0, p0, -b1, omega, zeta, sign, sign * ring, when)
                speed = abs(slide(x0, w0, p0, -b1, omega, zeta, when)[1])
                impacts[k + 1, 0] += 1.0
                impacts[k + 1, 1] = max(impacts[k + 1, 1], speed)
                impacts[k + 1, 2] += 0.5 * speed * speed
                x, w, at, sliding = sign * ring, 0.0, sign, False
                tau += when
                # a demand that already pulls the pad back past the friction takes it off the ring at once
                lower = -math.inf if at < 0.0 else -friction
                upper = math.inf if at > 0.0 else friction
                direction = leaving(-(b0 + b1 * when) - omega**2 * x, -b1, lower, upper, True, True)
                if direction != 0.0:
                    sliding, sign, at = True, direction, 0.0
                continue
            if not stopped:
                tau = h
                continue
            tau += when
            # at the stop: a demand past the other bound reverses the motion; at or past the bound it moved
            # towards, it goes on only where the demand grows on (else that is the rounding of the stop)
            direction = leaving(-(b0 + b1 * when) - omega**2 * x, -b1, -friction, friction, sign < 0.0, sign > 0.0)
            if direction == 0.0:
                sliding = False
            else:
                sign = direction
        u[k + 1], v[k + 1] = x, w
        demand = -(a0[k] + a1[k] * h) - omega**2 * x
        if not sliding and (demand > friction and at <= 0.0 or demand < -friction and at >= 0.0):
            # past the friction at the sample, within rounding of it: sliding starts there
            sliding, sign, at = True, math.copysign(1.0, demand), 0.0
        if sliding:
            stick[k + 1], z[k + 1] = False, (sign if friction > 0 else 0.0)
            continue
        stick[k + 1] = True
        pressed = at * demand - friction  # against a ring: what it carries beyond the friction
        if at != 0.0 and pressed > 0.0:
            held[k + 1], z[k + 1] = at * pressed, (at if friction > 0 else 0.0)
        else:
            z[k + 1] = demand / friction if friction > 0 else 0.0
    return DONE, n - 1


def line_history(time, a0, a1, omega, zeta, friction, compiled=None):
    """One-component history at the interval ends: u, u̇, z, sticking (``line``); ``compiled`` None:
    compiled for a long record (``backend``), interpreted for a short one."""
    n = time.size
    stick = np.zeros(n, dtype=bool)
    return run_line(line, time, a0, a1, (omega, zeta, friction, math.inf),
                    (np.zeros(n), np.zeros(n), np.zeros(n), stick, np.zeros(n), np.zeros((n, 3))), compiled)[:4]


def ring_history(time, a0, a1, omega, zeta, friction, ring, compiled=None):
    """One-component history against a ring ``ring`` m off the centre, at the interval ends: u, u̇, z,
    sticking, the ring's force (m/s², per unit mass) and the impacts per interval (n, 3) (``line``)."""
    n = time.size
    return run_line(line, time, a0, a1, (omega, zeta, friction, ring),
                    (np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n, dtype=bool), np.zeros(n), np.zeros((n, 3))),
                    compiled)


def run_line(kernel, time, a0, a1, constants, history, compiled=None):
    """Run a one-component exact kernel (``line``, ``series.series_line``) on the ground (time, a0, a1),
    its constants (floats) and its ``history`` arrays, which it fills and this returns; ``compiled`` None:
    compiled for a long record (``backend``), interpreted for a short one."""
    from .. import backend

    if compiled is None:
        compiled = backend.choose(time.size - 1, LINE_WORK) == "numba"
    run = scalar.kernel(kernel) if compiled else kernel
    status, k = run(np.ascontiguousarray(time, dtype=float), np.ascontiguousarray(a0, dtype=float),
                    np.ascontiguousarray(a1, dtype=float), *(float(c) for c in constants), *history)
    if status == CHATTER:
        raise chatter(time[k])
    return history


def chatter(t) -> RuntimeError:
    """The error of a sample interval (at t, s) of more than MAX_PHASES stick/slip phases."""
    return RuntimeError(f"structure: more than {MAX_PHASES} stick/slip phases in the sample interval at t = {t:g} s: "
                        f"the friction chatters; report the record and the structure")
