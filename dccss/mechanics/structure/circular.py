"""Two components: the circular interaction, u̇ and z vectors (``plane``, the kernel; ``plane_history``
runs it).

The sliding equation ü = -a_g - ω² (N/W) u - 2ζω u̇ - μ g (N/W) u̇ / |u̇| is integrated by DOP853
(``integrator``) with sticking as an event: a phase of sliding ends where |u̇| falls to REST_SPEED,
and sticking ends where |f|, a quadratic in t on an interval, reaches μ g (N/W) (exact). One component
with a vertical or a friction law runs here too, as the first of two.
"""

from __future__ import annotations

import math

import numpy as np

from .. import scalar
from ..friction import KIND, ROW, T0, TEMPERATURE, device_mu
from .exact import CHATTER, DONE, FAILED, MAX_PHASES, chatter
from .heat import plate_temperatures
from .inputs import G, Ground
from .integrator import (
    ATOL,
    HELD,
    MIN_STEP,
    NONE,
    RTOL,
    STOP,
    TOO_SHORT,
    demand,
    integrate,
    law_coefficient,
    normal_ratio,
    scratch,
    tableau,
)

#: the kind of a law whose friction follows the plates' temperatures (a row's KIND)
HEATED = float(TEMPERATURE.kind)
#: the cost of a sample interval interpreted, in the planar kernels' case-steps (``backend.choose``):
#: about 0.5 ms
INTERVAL_WORK = 25


@scalar.jit
def breakaway(d0x, d0y, d1x, d1y, friction, m0, m1, end):
    """The first tau in [0, end) where |d0 + d1 tau| reaches ``friction`` (m0 + m1 tau) (a quadratic;
    m0 + m1 tau = N/W >= 0 on the interval), or -1: 0 where it is past it already, or at it and growing."""
    f0, f1 = friction * m0, friction * m1
    a = d1x * d1x + d1y * d1y - f1 * f1
    b = 2 * (d0x * d1x + d0y * d1y - f0 * f1)
    c = (d0x * d0x + d0y * d0y) - f0 * f0
    if c > 0.0 or (c == 0.0 and b > 0.0):  # at the limit and growing: the root at 0 itself
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
def interval_drive(a0, a1, n0, n1, k, tau):
    """What drives a phase starting tau into sample interval k: the ground's acceleration b0 + b1 t and N/W
    n0 + n1 t from there, (b0x, b0y, b1x, b1y, n0, n1)."""
    return a0[k, 0] + a1[k, 0] * tau, a0[k, 1] + a1[k, 1] * tau, a1[k, 0], a1[k, 1], n0[k] + n1[k] * tau, n1[k]


def planar_ground(ground: Ground):
    """A ground as the two-component kernels take it: the times, the acceleration on each interval a0 + a1 (t - t_k)
    in two components (one runs as the first of two, the second without load) and N/W n0 + n1 (t - t_k) (ones and
    zeros without a vertical)."""
    time, a0, a1 = ground.time, ground.a0, ground.a1
    if a0.shape[1] == 1:
        a0, a1 = np.column_stack([a0, np.zeros_like(a0)]), np.column_stack([a1, np.zeros_like(a1)])
    if ground.v0 is None:
        n0, n1 = np.ones(time.size - 1), np.zeros(time.size - 1)
    else:
        n0, n1 = 1.0 + ground.v0 / G, ground.v1 / G
    return tuple(np.ascontiguousarray(x, dtype=float) for x in (time, a0, a1, n0, n1))


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
        temperature[0, s] = law[s][T0]
        heats = heats or law[s][KIND] == HEATED
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
            b00, b01, b10, b11, m0, m1 = interval_drive(a0, a1, n0, n1, k, tau)
            end = h - tau
            if not sliding:
                # the breakaway value at the phase's start (it moves with N/W only under a pressure factor)
                rest = device_mu(law, 0.0, max(m0, 0.0), t0, t1)
                when = breakaway(-b00 - w2 * m0 * x0, -b01 - w2 * m0 * x1, -b10 - w2 * m1 * x0, -b11 - w2 * m1 * x1,
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
                load = (b00, b01, b10, b11, w2, damp, friction, m0, m1, t0, t1, 0.0, 0.0, 0.0)
                ended, when, h_next = integrate(y, end, 0.0, load, law, True, False, rtol, atol, A, B, C, E3, E5,
                                                 K, out, trial, law[:0])
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
            load = (b00, b01, b10, b11, w2, damp, friction, m0, m1, t0, t1, 0.0, 0.0, 0.0)
            ended, when, h_next = integrate(y, end, h_next, load, law, False, friction > 0.0, rtol, atol, A, B, C,
                                             E3, E5, K, out, trial, law[:0])
            if ended == TOO_SHORT:
                return FAILED, k
            if ended == STOP:  # at rest: the last REST_SPEED at the deceleration there, to first order
                speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
                g0, g1 = demand(when, y, load)
                slowing = (friction * law_coefficient(when, y, load, law) * normal_ratio(when, load) + damp * speed
                           - (g0 * y[2] + g1 * y[3]) / speed)
                last = min(speed / slowing, end - when) if slowing > 0.0 else 0.0
                x0, x1, w0, w1 = y[0] + 0.5 * last * y[2], y[1] + 0.5 * last * y[3], 0.0, 0.0
                when += last
                tau += when
                m = normal_ratio(when, load)
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
                t0, t1 = plate_temperatures(heated, time[since], time[k + 1], u[since, 0], u[since, 1], x0, x1,
                                            normal, law, heat, temperature, k + 1)
                heated, since = heated + 1, k + 1
        f0 = -(a0[k, 0] + a1[k, 0] * h) - w2 * m * x0
        f1 = -(a0[k, 1] + a1[k, 1] * h) - w2 * m * x1
        mu[k + 1] = device_mu(law, 0.0 if not sliding else math.sqrt(w0 * w0 + w1 * w1), m, t0, t1)
        rest = device_mu(law, 0.0, m, t0, t1)
        _state(k + 1, x0, x1, w0, w1, f0, f1, sliding, friction * rest * m, u, v, z, stick)
    return DONE, 0



#: the law of Coulomb friction in the kernels: a coefficient of exactly 1 times ``friction`` = μ g
UNIT_LAW = np.array([[0.0, 1.0, 1.0, 1.0, 1.0] + [0.0] * (ROW - 5)])


def plane_history(ground: Ground, omega, zeta, friction, compiled=None, law=UNIT_LAW, samples=None):
    """Two-component history at the interval ends (see the module docstring): u, u̇, z (n, 2), sticking,
    the plates' temperatures (n, 2) and the law's coefficient (n,); one component runs as the first of
    two, the second without load; ``friction`` is μ g for Coulomb friction (``law`` UNIT_LAW), g for a
    law (its rows, ``friction.row``); ``samples`` whether each interval end is one of the record's samples
    (default: all are), the ends of the plates' heat intervals; ``compiled`` None: compiled for a long
    record (``backend``), interpreted for a short one."""
    from .. import backend

    time, a0, a1, n0, n1 = planar_ground(ground)
    n = time.size
    if compiled is None:  # the plates' heat sums over the intervals before: about n / 200 case-steps more each
        heats = bool(np.any(np.asarray(law)[:, KIND] == HEATED))
        compiled = backend.choose(n - 1, INTERVAL_WORK + (n // 200 if heats else 0)) == "numba"
    run = scalar.kernel(plane) if compiled else plane
    K, y, out, trial = scratch(compiled)
    u, v, z = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    stick = np.zeros(n, dtype=bool)
    heat, temperature, mu = np.zeros((n, 4)), np.zeros((n, 2)), np.zeros(n)
    samples = np.ones(n, dtype=bool) if samples is None else np.asarray(samples, dtype=bool)
    law = np.ascontiguousarray(law, dtype=float) if compiled else np.asarray(law, dtype=float).tolist()
    status, k = run(time, a0, a1, n0, n1, law, samples, float(omega), float(zeta), float(friction), float(RTOL),
                    float(ATOL), *tableau(compiled), K, y, out, trial, u, v, z, stick, heat, temperature, mu)
    if status == CHATTER:
        raise chatter(time[k])
    if status == FAILED:
        raise RuntimeError(f"structure: the two-component integration's step fell below {MIN_STEP:g} s in the "
                           f"sample interval at t = {time[k]:g} s; report the record and the structure")
    return u, v, z, stick, temperature, mu

