"""The articulated slider's history in general: two components, any friction law, the vertical.

The device is two pendulums in series (``series``): surface j slides or holds by its own law, and the
phases are those of the exact one-component solution:

* **at rest** (``_from_rest``), surface j holds while |f - p_j| <= μ̄_j(0) (1 + RTOL), f = -a_g / (g N/W)
  the force per unit normal force the friction must supply, p_j = u_j / L_j; rest ends where f, the ratio
  of two straight lines in t, leaves a circle: the first root of a quadratic (``circular.breakaway``),
  exact. The surface whose circle it leaves slides, both where the other is within 1e-9 of its own;
* **one surface slides** (j, ``_alone``), the other holds: the rigid slider's circular interaction
  (``integrator``, DOP853) with the pendulum length L_j and surface j's law, the stroke's origin at the
  other surface's displacement; it ends at a stop (|u̇| falls to REST_SPEED; a start from rest takes the
  friction along the force until |u̇| reaches START_SPEED, as the rigid slider's), or where F/N reaches
  the other surface's circle (YIELD: both slide; where no split σ in [0, 1] balances the hinge, the
  surface that would slide backwards holds);
* **both slide** (``_sliding_both``): ``corner`` (Radau IIA on the state (u, u̇, δ, σ)), until |u̇| falls
  to REST_SPEED or one surface stops (σ reaches 0 or 1, at a step's end or inside it, found where a step
  to it goes past it). Both surfaces starting from rest together (a tie) start as the rigid slider of
  their proportional split until |u̇| reaches START_SPEED (``_together``); surfaces alike (their μ̄ equal
  wherever they slide in proportion: ``surfaces_alike``) slide as the rigid slider throughout, exactly.

The phases hand on a state record (UX ... TAU) from one to the next.

Under a temperature law each surface's plate heats by its own flux, from its own slider's travel
(``heat.plate_temperature``), at the record's samples. Written in the scalar subset Numba compiles: the
same bits compiled and interpreted.
"""

from __future__ import annotations

import math

import numpy as np

from .. import scalar
from ..friction import FACTOR, KIND, MU, RATIO, T0, WEIGHT, device_mu, surface_mu
from . import corner
from .circular import HEATED, breakaway, interval_drive, planar_ground
from .corner import (
    B0X,
    B0Y,
    B1X,
    B1Y,
    CONTRACTION,
    DAMPING,
    ERROR,
    GOES_ON,
    GRAVITY,
    KEPT,
    LAST,
    LENGTH1,
    LENGTH3,
    MASS,
    MEMO,
    N0,
    N1,
    PARAMETERS,
    PREVIOUS,
    RHS,
    SPAN,
    TEMPERATURE1,
    TEMPERATURE3,
)
from .exact import CHATTER, DONE, FAILED, MAX_PHASES
from .heat import plate_temperature
from .inputs import G
from .integrator import CAPPED, HELD, MOVING, NONE, REST_SPEED, STOP, TOO_SHORT, YIELD, integrate, law_coefficient
from .response import Response, Surfaces
from .series import BOTH, SLIDE1, SLIDE3, STUCK, series_line_history
from .sliders import SliderKind, register, ring_strokes

#: both surfaces start together where the other's force is within this (relative) of its friction
TOGETHER = 1e-9
#: Radau's tolerances for both surfaces sliding (relative; absolute, in m, m/s and rad)
RADAU_RTOL, RADAU_ATOL = 1e-6, 1e-8
#: Radau's step bounds: the shortest (s) before the phase fails, the first one tried
RADAU_MIN, RADAU_FIRST = 1e-12, 1e-4
#: Newton's contraction below which the next step keeps the Jacobian
THETA = 0.1
#: the kernel's status where a surface yields but no split of the sliding between the two balances the hinge
#: but one where it would slide backwards (``corner.consistent``), beside ``exact``'s DONE, CHATTER and FAILED
UNSPLIT = 3


#: the articulated slider's state from phase to phase, a record of floats (``articulated``): u, u̇, u_1, the
#: hinge's (δ, σ) while both surfaces slide, the phase, whether it starts from rest (1), the integrators' next
#: steps (DOP853's, Radau's) and the time into the sample interval
UX, UY, VX, VY, U1X, U1Y, DELTA, SIGMA, PHASE, STARTING, H_DOP, H_RADAU, TAU = range(13)
STATE = 13


@scalar.jit
def _rest(fx, fy, p1x, p1y, p3x, p3y, r1, r3, hold):
    """The phase at rest under the force f per unit normal force that the friction must supply: STUCK
    where f is within both circles |f - p_j| <= r_j hold, else by where the friction takes it, the point of
    the circles' intersection nearest to f: on circle 1 alone (SLIDE1), on circle 3 alone (SLIDE3), or on
    both (BOTH; within TOGETHER of the other circle counts as on it)."""
    d1 = math.sqrt((fx - p1x) ** 2 + (fy - p1y) ** 2)
    d3 = math.sqrt((fx - p3x) ** 2 + (fy - p3y) ** 2)
    if d1 <= r1 * hold and d3 <= r3 * hold:
        return STUCK
    on1 = _projected(fx, fy, p1x, p1y, r1, d1, p3x, p3y, r3, hold) if d1 > r1 * hold else OUTSIDE
    if on1 == EDGE:
        return BOTH
    on3 = _projected(fx, fy, p3x, p3y, r3, d3, p1x, p1y, r1, hold) if d3 > r3 * hold else OUTSIDE
    if on3 == EDGE:
        return BOTH
    if on1 == INSIDE and on3 != INSIDE:
        return SLIDE1
    if on3 == INSIDE and on1 != INSIDE:
        return SLIDE3
    return BOTH


#: where f's projection onto one friction circle lies (``_projected``): outside the other circle, within it, or on
#: its edge (within TOGETHER)
OUTSIDE, INSIDE, EDGE = 0, 1, 2


@scalar.jit
def _projected(fx, fy, px, py, r, d, ox, oy, ro, hold):
    """Where the projection of f (at the distance d > r hold from p) onto the circle |f - p| = r lies against the
    other circle |f - o| = ro hold: OUTSIDE, INSIDE or on its EDGE (within TOGETHER ro)."""
    qx, qy = px + r * (fx - px) / d, py + r * (fy - py) / d
    e = math.sqrt((qx - ox) ** 2 + (qy - oy) ** 2) - ro
    if e <= ro * (hold - 1.0):
        return EDGE if e >= -TOGETHER * ro else INSIDE
    return OUTSIDE


@scalar.jit
def _corner(wx, wy, ex, ey, m1, m3, L1, L3):
    """(phase, δ, σ) of both surfaces sliding with p_1 - p_3 = w and u̇ along e: the triangle
    μ̄_3 z_3 - μ̄_1 z_1 = w oriented so that e lies between z_3 and z_1 (BOTH), or SLIDE1 / SLIDE3 where e
    lies outside both orientations' cones (beyond z_1's side: surface 3 holds). At δ = 0 σ is the
    proportional split L_1 / L (``corner.consistent`` then decides)."""
    w2 = wx * wx + wy * wy
    c = (m1 * m1 + m3 * m3 - w2) / (2.0 * m1 * m3)
    c = min(1.0, max(-1.0, c))
    size = math.acos(c)
    if size == 0.0:
        # z_1 = z_3 = z = w / (m3 - m1) (any z where m1 = m3, w = 0): both slide where e is along z; against it
        # the surface of the smaller friction slides alone (the other's circle lies beyond)
        if m1 != m3 and (wx * ex + wy * ey) * (m3 - m1) < 0.0:
            return (SLIDE1 if m1 < m3 else SLIDE3), 0.0, (1.0 if m1 < m3 else 0.0)
        return BOTH, 0.0, L1 / (L1 + L3)
    best, best_sigma, best_delta = -1.0, 0.0, 0.0
    for orientation in (1.0, -1.0):
        delta = orientation * size
        cd, sd = math.cos(delta), math.sin(delta)
        # (m3 I - m1 R(δ)) z3 = w
        a, b = m3 - m1 * cd, m1 * sd  # matrix [[a, b], [-b, a]]
        det = a * a + b * b
        z3x, z3y = (a * wx - b * wy) / det, (b * wx + a * wy) / det
        # the angle from z3 to e, as a fraction of δ
        ang = math.atan2(z3x * ey - z3y * ex, z3x * ex + z3y * ey)
        sigma = ang / delta
        if 0.0 <= sigma <= 1.0:
            return BOTH, delta, sigma
        # how far outside: keep the nearer for the one-surface decision
        miss = -sigma if sigma < 0.0 else sigma - 1.0
        if best < 0.0 or miss < best:
            best, best_sigma, best_delta = miss, sigma, delta
    return (SLIDE1 if best_sigma > 1.0 else SLIDE3), best_delta, best_sigma


def articulated(time, a0, a1, n0, n1, samples, rows, rigid_rows, alike, p, dop, radau, history):
    """The articulated slider's history at the interval ends (the module docstring); ``rows`` the surfaces'
    laws (weight and ratio R^j / L_j), ``rigid_rows`` the same laws as the rigid slider's (R^j / L: both
    surfaces starting together, and sliding together throughout where ``alike``: ``surfaces_alike``), N/W on
    interval k n0[k] + n1[k] (t - t_k); ``p`` a phase's parameters (``corner``) with the device's set (L_1,
    L_3, g, 2ζω); ``dop`` DOP853's (rtol, atol, A, B, C, E3, E5, K, out, trial, y) (``integrate``), ``radau``
    Radau's (work, Z, y, y0, k0) (``_both``); ``history`` (u, u̇, u_1, u̇_1, the phase, F/W, each surface's
    coefficient μ_j (λ included, at its sliding speed), the heat intervals, each surface's temperature), written
    at the interval ends: (DONE, 0), or (CHATTER, FAILED or UNSPLIT, the interval)."""
    u, v, u1, v1, phase, force, mu, heat, temperature = history
    n = time.size
    g, hold = p[GRAVITY], 1.0 + dop[0]
    heats = rows[0][KIND] == HEATED or rows[1][KIND] == HEATED
    t1, t3 = rows[0][T0], rows[1][T0]
    temperature[0, 0], temperature[0, 1] = t1, t3
    s = np.zeros(STATE)
    heated, since = 0, 0
    m = max(n0[0], 0.0)
    if m > 0.0:
        s[PHASE] = _rest(-a0[0, 0] / (g * m), -a0[0, 1] / (g * m), 0.0, 0.0, 0.0, 0.0,
                         device_mu(rows[0:1], 0.0, m, t1, t1), device_mu(rows[1:2], 0.0, m, t3, t3), hold)
        s[STARTING] = 1.0 if s[PHASE] != STUCK else 0.0
    _record(0, s, -a0[0, 0], -a0[0, 1], m, p, rows, t1, t3, radau[3], history)
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        s[TAU], phases = 0.0, 0
        p[TEMPERATURE1], p[TEMPERATURE3] = t1, t3
        while s[TAU] < h:
            phases += 1
            if phases > MAX_PHASES:
                return CHATTER, k
            drive = interval_drive(a0, a1, n0, n1, k, s[TAU])
            if s[PHASE] == STUCK:
                status = _from_rest(s, drive, h, p, rows, hold)
            elif s[PHASE] != BOTH:
                status = _alone(s, drive, h, p, rows, hold, dop, radau)
            elif s[STARTING] != 0.0 or alike:
                status = _together(s, drive, h, p, rows, rigid_rows, alike, hold, dop, radau)
            else:
                status = _sliding_both(s, drive, h, p, rows, hold, radau)
            if status != DONE:
                return status, k
        m = max(n0[k] + n1[k] * h, 0.0)
        if heats:
            temperature[k + 1, 0], temperature[k + 1, 1] = t1, t3
            if samples[k + 1] or k + 2 == n:  # the end of a heat interval
                normal = max(0.5 * (n0[since] + m), 0.0)
                if rows[0][KIND] == HEATED:
                    t1 = plate_temperature(heated, time[since], time[k + 1], u1[since, 0], u1[since, 1], s[U1X],
                                           s[U1Y], normal, rows[0], 0, heat, temperature, k + 1)
                if rows[1][KIND] == HEATED:
                    t3 = plate_temperature(heated, time[since], time[k + 1], u[since, 0] - u1[since, 0],
                                           u[since, 1] - u1[since, 1], s[UX] - s[U1X], s[UY] - s[U1Y], normal, rows[1],
                                           1, heat, temperature, k + 1)
                heated, since = heated + 1, k + 1
        _record(k + 1, s, -(a0[k, 0] + a1[k, 0] * h), -(a0[k, 1] + a1[k, 1] * h), m, p, rows, t1, t3, radau[3],
                history)
    return DONE, 0


@scalar.jit
def _from_rest(s, drive, h, p, rows, hold):
    """At rest: where the force leaves a surface's circle first in the interval's rest (``breakaway``), that
    surface starts from rest; the other within TOGETHER of its own friction then, both; lifted off, the upper
    half goes with the superstructure (surface 3 slides). ``drive`` the ground's acceleration b0 + b1 τ and N/W
    n0 + n1 τ from the phase's start (``interval_drive``), h the interval's length: DONE."""
    b00, b01, b10, b11, m0, m1 = drive
    end = h - s[TAU]
    L1, L3, g, t1, t3 = p[LENGTH1], p[LENGTH3], p[GRAVITY], p[TEMPERATURE1], p[TEMPERATURE3]
    r1 = g * device_mu(rows[0:1], 0.0, max(m0, 0.0), t1, t1) * hold
    r3 = g * device_mu(rows[1:2], 0.0, max(m0, 0.0), t3, t3) * hold
    g1, g3 = g / L1, g / L3
    y1x, y1y, y3x, y3y = s[U1X], s[U1Y], s[UX] - s[U1X], s[UY] - s[U1Y]
    when1 = breakaway(-b00 - g1 * m0 * y1x, -b01 - g1 * m0 * y1y, -b10 - g1 * m1 * y1x, -b11 - g1 * m1 * y1y, r1, m0,
                      m1, end)
    when3 = breakaway(-b00 - g3 * m0 * y3x, -b01 - g3 * m0 * y3y, -b10 - g3 * m1 * y3x, -b11 - g3 * m1 * y3y, r3, m0,
                      m1, end)
    if when1 < 0.0 and when3 < 0.0:
        s[TAU] = h
        return DONE
    first = SLIDE1 if when3 < 0.0 or (0.0 <= when1 <= when3) else SLIDE3
    when = when1 if first == SLIDE1 else when3
    s[TAU] += when
    mm = max(m0 + m1 * when, 0.0)
    s[PHASE], s[STARTING], s[H_DOP] = first, 1.0, 0.0
    if mm <= 0.0:  # lifted off: the upper half goes with the superstructure
        s[PHASE] = SLIDE3
        return DONE
    # the other surface within TOGETHER of its friction: both start together
    fx, fy = -(b00 + b10 * when) / (g * mm), -(b01 + b11 * when) / (g * mm)
    ox, oy, Lo, ro = (y3x, y3y, L3, r3) if first == SLIDE1 else (y1x, y1y, L1, r1)
    radius = ro / (g * hold)
    if math.sqrt((fx - ox / Lo) ** 2 + (fy - oy / Lo) ** 2) >= radius * (1.0 - TOGETHER):
        s[PHASE] = BOTH
    return DONE


@scalar.jit
def _alone(s, drive, h, p, rows, hold, dop, radau):
    """One surface slides (SLIDE1 or SLIDE3), the other holds: the rigid slider's interaction (``integrate``)
    with the pendulum L_j and surface j's law, the stroke's origin at the holding surface's displacement, until
    a stop, the end of a start from rest, or the force reaching the other surface's circle (YIELD: both slide,
    the hinge's δ from the two friction directions, σ made consistent; or the one that was sliding holds):
    DONE, FAILED (the step too short) or UNSPLIT (no split of the sliding balances the hinge)."""
    rtol, atol, A, B, C, E3, E5, K, out, trial, y4 = dop
    work, y6 = radau[0], radau[2]
    b00, b01, b10, b11, m0, m1 = drive
    end = h - s[TAU]
    L1, L3, g, damp = p[LENGTH1], p[LENGTH3], p[GRAVITY], p[DAMPING]
    x0, x1, w0, w1, q0, q1 = s[UX], s[UY], s[VX], s[VY], s[U1X], s[U1Y]
    starting = s[STARTING] != 0.0
    lower = s[PHASE] == SLIDE1
    Lj = L1 if lower else L3
    Li = L3 if lower else L1
    ix, iy = (x0 - q0, x1 - q1) if lower else (q0, q1)  # the holding surface's displacement
    y4[0], y4[1] = x0 - ix, x1 - iy
    y4[2], y4[3] = w0, w1
    tj, ti = (p[TEMPERATURE1], p[TEMPERATURE3]) if lower else (p[TEMPERATURE3], p[TEMPERATURE1])
    law = rows[0:1] if lower else rows[1:2]
    other = rows[1:2] if lower else rows[0:1]
    mm = max(m0, 0.0)
    if starting and mm > 0.0:  # from rest: short of its friction by more than the state's accuracy, at rest
        fx, fy = -b00 / (g * mm) - (x0 - ix) / Lj, -b01 / (g * mm) - (x1 - iy) / Lj
        if math.sqrt(fx * fx + fy * fy) < device_mu(law, 0.0, mm, tj, tj) * (1.0 - RADAU_RTOL):
            s[VX], s[VY], s[PHASE], s[STARTING] = 0.0, 0.0, STUCK, 0.0
            return DONE
    load = (b00, b01, b10, b11, g / Lj, damp, g, m0, m1, tj, tj, ix / Li, iy / Li, ti)
    ended, when, s[H_DOP] = integrate(y4, end, s[H_DOP] if not starting else 0.0, load, law, CAPPED if starting else 0,
                                      not starting, rtol, atol, A, B, C, E3, E5, K, out, trial, other)
    if ended == TOO_SHORT:
        return FAILED
    x0, x1, w0, w1 = y4[0] + ix, y4[1] + iy, y4[2], y4[3]
    s[UX], s[UY], s[VX], s[VY] = x0, x1, w0, w1
    if lower:
        s[U1X], s[U1Y] = y4[0], y4[1]
    s[TAU] += when
    if ended == NONE:
        s[TAU] = h
        return DONE
    mm = max(m0 + m1 * when, 0.0)
    if ended == HELD:
        s[VX], s[VY], s[PHASE], s[STARTING], s[H_DOP] = 0.0, 0.0, STUCK, 0.0, 0.0
        return DONE
    if ended == MOVING:
        s[STARTING], s[H_DOP] = 0.0, 0.0
        return DONE
    if ended == STOP:  # at rest (the last REST_SPEED's travel, under 1e-17 m, left out)
        _stopped(s, b00 + b10 * when, b01 + b11 * when, mm, p, rows, hold)
        return DONE
    # YIELD: both slide
    if starting:  # still starting from rest: both start together
        s[PHASE], s[H_DOP] = BOTH, 0.0
        return DONE
    speed = math.sqrt(w0 * w0 + w1 * w1)
    ex, ey = w0 / speed, w1 / speed
    mj = law_coefficient(when, y4, load, law)
    fx, fy = y4[0] / Lj + mj * ex, y4[1] / Lj + mj * ey
    zix, ziy = fx - ix / Li, fy - iy / Li
    size = math.sqrt(zix * zix + ziy * ziy)
    zix, ziy = zix / size, ziy / size
    z1x, z1y, z3x, z3y = (ex, ey, zix, ziy) if lower else (zix, ziy, ex, ey)
    delta = math.atan2(z3x * z1y - z3y * z1x, z3x * z1x + z3y * z1y)
    y6[0], y6[1], y6[2], y6[3], y6[4], y6[5] = s[UX], s[UY], w0, w1, delta, 1.0 if lower else 0.0
    p[B0X], p[B0Y], p[B1X], p[B1Y], p[N0], p[N1] = b00 + b10 * when, b01 + b11 * when, b10, b11, mm, m1
    held = corner.consistent(y6, p, rows, 0.0, work[RHS], work[MASS])
    if held == (1 if lower else -1):  # the surface that yields would slide backwards
        return UNSPLIT
    s[DELTA], s[SIGMA] = delta, y6[5]
    # both slide, or the one that was sliding holds (its friction outgrows the force: a law of N/W)
    s[PHASE] = BOTH if held == 0 else (SLIDE3 if lower else SLIDE1)
    s[STARTING], s[H_RADAU] = 0.0, 0.0
    if held != 0:
        s[H_DOP] = 0.0
    return DONE


@scalar.jit
def _together(s, drive, h, p, rows, rigid_rows, alike, hold, dop, radau):
    """Both surfaces slide as the rigid slider of their proportional split: from rest together until |u̇|
    reaches START_SPEED, or throughout where ``alike``; then (not alike) both surfaces' corner (``_corner``,
    σ made consistent) or one surface alone: DONE or FAILED (the step too short)."""
    rtol, atol, A, B, C, E3, E5, K, out, trial, y4 = dop
    work, y6 = radau[0], radau[2]
    b00, b01, b10, b11, m0, m1 = drive
    end = h - s[TAU]
    L1, L3, g, damp = p[LENGTH1], p[LENGTH3], p[GRAVITY], p[DAMPING]
    t1, t3 = p[TEMPERATURE1], p[TEMPERATURE3]
    L = L1 + L3
    x0, x1, w0, w1, q0, q1 = s[UX], s[UY], s[VX], s[VY], s[U1X], s[U1Y]
    starting = s[STARTING] != 0.0
    y4[0], y4[1], y4[2], y4[3] = x0, x1, w0, w1
    if starting:
        # from rest: where the force is short of the pair's friction by more than the state's accuracy (a stop's
        # state after Radau: RADAU_RTOL), at rest; a rounding short, the start holds until it is not (CAPPED)
        mm = max(m0, 0.0)
        if mm > 0.0:
            fx, fy = -b00 / (g * mm) - x0 / L, -b01 / (g * mm) - x1 / L
            if math.sqrt(fx * fx + fy * fy) < device_mu(rigid_rows, 0.0, mm, t1, t3) * (1.0 - RADAU_RTOL):
                s[PHASE], s[STARTING] = STUCK, 0.0
                return DONE
    load = (b00, b01, b10, b11, g / L, damp, g, m0, m1, t1, t3, 0.0, 0.0, 0.0)
    ended, when, s[H_DOP] = integrate(y4, end, 0.0 if starting else s[H_DOP], load, rigid_rows,
                                      CAPPED if starting else 0, not starting, rtol, atol, A, B, C, E3, E5, K, out,
                                      trial, rigid_rows[:0])
    if ended == TOO_SHORT:
        return FAILED
    dx, dy = y4[0] - x0, y4[1] - x1
    q0, q1 = q0 + L1 / L * dx, q1 + L1 / L * dy
    x0, x1, w0, w1 = y4[0], y4[1], y4[2], y4[3]
    s[UX], s[UY], s[VX], s[VY], s[U1X], s[U1Y] = x0, x1, w0, w1, q0, q1
    s[DELTA], s[SIGMA] = 0.0, L1 / L
    s[TAU] += when
    if ended == NONE:
        s[TAU] = h
        return DONE
    if ended == HELD:
        s[VX], s[VY], s[PHASE], s[STARTING] = 0.0, 0.0, STUCK, 0.0
        return DONE
    if ended == STOP:
        _stopped(s, b00 + b10 * when, b01 + b11 * when, max(m0 + m1 * when, 0.0), p, rows, hold)
        return DONE
    if alike:
        s[STARTING] = 0.0
        return DONE
    # moving: both surfaces' corner, or one surface only
    speed = math.sqrt(w0 * w0 + w1 * w1)
    mm = max(m0 + m1 * when, 0.0)
    c1m = device_mu(rows[0:1], 0.0, mm, t1, t1)
    c3m = device_mu(rows[1:2], 0.0, mm, t3, t3)
    state, delta, sigma = _corner(q0 / L1 - (x0 - q0) / L3, q1 / L1 - (x1 - q1) / L3, w0 / speed, w1 / speed, c1m,
                                  c3m, L1, L3)
    if state == BOTH:
        y6[0], y6[1], y6[2], y6[3], y6[4], y6[5] = x0, x1, w0, w1, delta, sigma
        p[B0X], p[B0Y], p[B1X], p[B1Y], p[N0], p[N1] = b00 + b10 * when, b01 + b11 * when, b10, b11, mm, m1
        held = corner.consistent(y6, p, rows, 0.0, work[RHS], work[MASS])
        sigma = y6[5]
        if held != 0:  # no split balances the hinge: the surface that would slide backwards holds
            state = SLIDE3 if held < 0 else SLIDE1
    s[PHASE], s[DELTA], s[SIGMA] = state, delta, sigma
    s[STARTING], s[H_RADAU], s[H_DOP] = 0.0, 0.0, 0.0
    return DONE


@scalar.jit
def _sliding_both(s, drive, h, p, rows, hold, radau):
    """Both surfaces slide: Radau on the corner equations (``_both``), until a stop or one surface stopping (σ
    reaches 1: surface 3 holds, or 0: surface 1 holds): DONE or FAILED (the step too short)."""
    work, Z, y6, ys, k6 = radau
    b00, b01, b10, b11, m0, m1 = drive
    y6[0], y6[1], y6[2], y6[3], y6[4], y6[5] = s[UX], s[UY], s[VX], s[VY], s[DELTA], s[SIGMA]
    p[B0X], p[B0Y], p[B1X], p[B1Y], p[N0], p[N1] = b00, b01, b10, b11, m0, m1
    ended, when, s[H_RADAU] = _both(y6, ys, h - s[TAU], s[H_RADAU], p, rows, k6, work, Z)
    if ended == TOO_SHORT:
        return FAILED
    s[UX], s[UY], s[VX], s[VY], s[DELTA], s[SIGMA] = y6[0], y6[1], y6[2], y6[3], y6[4], y6[5]
    _, z1x, z1y, _, _, _, _, mu1, _, fx, fy = corner.shape(y6, p, rows, when)
    L1 = p[LENGTH1]
    s[U1X], s[U1Y] = L1 * (fx - mu1 * z1x), L1 * (fy - mu1 * z1y)
    s[TAU] += when
    if ended == NONE:
        s[TAU] = h
        return DONE
    if ended == STOP:
        _stopped(s, b00 + b10 * when, b01 + b11 * when, max(m0 + m1 * when, 0.0), p, rows, hold)
        return DONE
    # one surface stopped: σ = 1 (surface 3 holds) or 0 (surface 1 holds)
    s[PHASE] = SLIDE1 if s[SIGMA] >= 1.0 else SLIDE3
    s[STARTING], s[H_DOP] = 0.0, 0.0
    return DONE


@scalar.jit
def _stopped(s, bx, by, mm, p, rows, hold):
    """u̇ = 0: the phase at rest (``_at_rest``) under the ground's acceleration b and N/W mm, a start from rest
    where it is not STUCK."""
    s[VX], s[VY] = 0.0, 0.0
    s[PHASE] = _at_rest(bx, by, mm, s[UX], s[UY], s[U1X], s[U1Y], p[LENGTH1], p[LENGTH3], p[GRAVITY], rows,
                        p[TEMPERATURE1], p[TEMPERATURE3], hold)
    s[STARTING], s[H_DOP] = 1.0 if s[PHASE] != STUCK else 0.0, 0.0


@scalar.jit
def _at_rest(bx, by, mm, x0, x1, q0, q1, L1, L3, g, rows, t1, t3, hold):
    """The phase at rest (u̇ = 0) under the ground's acceleration b, N/W mm."""
    if mm <= 0.0:
        return STUCK if bx == 0.0 and by == 0.0 else SLIDE3
    r1 = device_mu(rows[0:1], 0.0, mm, t1, t1)
    r3 = device_mu(rows[1:2], 0.0, mm, t3, t3)
    return _rest(-bx / (g * mm), -by / (g * mm), q0 / L1, q1 / L1, (x0 - q0) / L3, (x1 - q1) / L3, r1, r3, hold)


@scalar.jit(inline=False)
def _both(y, y0, end, h, p, rows, k0, work, Z):
    """Radau over [0, end] from y (overwritten): (what ended it: NONE, STOP, YIELD (σ reached 0 or 1) or
    TOO_SHORT, when, the next step). The Jacobian is kept from step to step while Newton converges fast
    (θ <= THETA); each step's Newton starts from the last step's collocation polynomial, extrapolated: across
    a sample interval's end too, where the phase goes on (``work``'s memo says so: a new phase (h <= 0)
    starts afresh)."""
    t = 0.0
    F, Mb = work[RHS], work[MASS]
    last, previous, memo = work[LAST], work[PREVIOUS], work[MEMO]  # the last accepted step
    if h <= 0.0:
        h = min(RADAU_FIRST, end)
        memo[GOES_ON], memo[CONTRACTION] = 0.0, 1.0
    goes_on = memo[GOES_ON] != 0.0
    if not goes_on:
        corner.system(t, y, p, rows, F, Mb)
        for i in range(4):
            k0[i] = F[i]
        k0[4], k0[5] = 0.0, 0.0
    # RADAU5's second error estimate (filtering the stiff components) on the interval's first step, where
    # the ground's jerk jumps (σ's fast relaxation takes up the change), and after a rejected step
    first, refresh, guessed, span = True, 1 if goes_on else 2, goes_on, memo[SPAN]  # factors afresh
    current = False  # whether the Jacobian is the one at the step's start
    while t < end:
        taken = min(h, end - t)
        if taken < RADAU_MIN:
            return TOO_SHORT, t, h
        for i in range(corner.N):
            y0[i] = y[i]
        if guessed:  # the last polynomial at this step's stages, from y0
            for i in range(corner.S):
                l1, l2, l3 = corner.weights(1.0 + corner.C[i] * taken / span)
                for j in range(corner.N):
                    Z[i * corner.N + j] = (last[j] + l1 * previous[j] + l2 * previous[corner.N + j]
                                           + l3 * previous[2 * corner.N + j] - y0[j])
        status, error, iterations, theta = corner.radau_step(t, y0, taken, p, rows, k0, RADAU_RTOL, RADAU_ATOL,
                                                             first, refresh, Z, work, guessed)
        current = current or refresh == 2
        if status != 0:
            h, refresh, guessed = 0.5 * taken, (1 if current else 2), False
            continue
        factor = 0.9 * (1.0 + 2.0 * corner.NEWTON) / (iterations + 2.0 * corner.NEWTON)
        quotient = max(1.0 / 8.0, min(5.0, error ** 0.25 / factor))
        # the events within the step, looked for before its error is judged (across a stop the friction turns
        # about: the step over it is inaccurate, and would be cut down to nothing): a stop (|u̇| down to
        # REST_SPEED on the collocation polynomial, whose u̇ may pass through zero between the step's ends, as
        # it does along a line), or a surface stopping (σ out of [0, 1] at the step's end)
        slowest, bound = _slowest(y0, Z)
        stops, sig = slowest <= REST_SPEED, y0[5] + Z[17]
        ends_out = sig <= 0.0 or sig >= 1.0
        reached, length = False, 0.0
        if not ends_out and _share_leaves(y0, Z, 1.0) and (not stops or _located(YIELD, 1.0, y0, Z, True)[1]
                                                            < _located(STOP, bound, y0, Z, False)[1]):
            # σ out of [0, 1] inside the step alone (before any stop), back by its end: a surface stopping, where
            # a step to it goes past it (σ's fast relaxation, stiff, makes the polynomial overshoot inside the
            # step, where only its end is accurate: then the trial step stands)
            kept, faccon = work[KEPT], memo[CONTRACTION]
            for i in range(corner.S * corner.N):
                kept[i] = Z[i]
            reached, length, seen = _to_event(YIELD, 1.0, True, t, y, y0, taken, p, rows, k0, work, Z)
            if reached:
                memo[GOES_ON] = 0.0
                return YIELD, t + length, h
            if seen >= 0.0:  # the step to it too long for the tolerance: a shorter one, then look again
                quotient = max(1.0 / 8.0, min(5.0, seen ** 0.25 / factor))
                h, refresh, first, guessed = length / quotient, (1 if current else 2), True, False
                continue
            for i in range(corner.S * corner.N):
                Z[i] = kept[i]
            memo[CONTRACTION] = faccon
        event = NONE
        if stops:
            event = STOP
        elif ends_out:
            event = YIELD
        if event != NONE:
            reached, length, error = _to_event(event, bound, False, t, y, y0, taken, p, rows, k0, work, Z)
            if reached:
                memo[GOES_ON] = 0.0
                return event, t + length, h
            error = 2.0 ** 4 if error < 0.0 else error
            # the step to it is too long for the tolerance: a shorter one, then look again
            quotient = max(1.0 / 8.0, min(5.0, error ** 0.25 / factor))
            h, refresh, first, guessed = length / quotient, (1 if current else 2), True, False
            continue
        if error > 1.0:
            h, refresh, first, guessed = taken / quotient, (1 if current else 2), True, False
            continue
        if guessed:  # Gustafsson's predictive control (RADAU5's), from the last accepted step
            quotient = max(quotient, max(1.0 / 8.0, min(5.0, span / taken * (error * error / memo[ERROR]) ** 0.25
                                                        / 0.9)))
        memo[ERROR] = max(1e-2, error)
        memo[CONTRACTION] = max(memo[CONTRACTION], 2.220446049250313e-16) ** 0.8
        first = False
        for i in range(corner.N):
            y[i] = y0[i] + Z[2 * corner.N + i]
            last[i] = y0[i]
            acc = 0.0
            for j in range(corner.S):
                acc += corner.W[2, j] * Z[j * corner.N + i]
                previous[j * corner.N + i] = Z[j * corner.N + i]
            k0[i] = acc / taken
        t += taken
        current, guessed, span = False, True, taken
        h, refresh = taken / quotient, (1 if theta <= THETA else 2)
        memo[SPAN], memo[GOES_ON] = span, 1.0 if refresh < 2 else 0.0  # a new Jacobian next: the next phase afresh
    return NONE, end, h


@scalar.jit
def _share_leaves(y0, Z, theta):
    """Whether σ leaves [0, 1] on the step's collocation polynomial (a cubic) by the fraction theta of the step:
    there, or where it turns before (a surface stopping inside the step, though σ may be back by theta)."""
    s = corner.dense(y0, Z, theta, 5)
    if s <= 0.0 or s >= 1.0:
        return True
    for turn in corner.turning(Z, 5):
        if 0.0 < turn < theta:
            s = corner.dense(y0, Z, turn, 5)
            if s <= 0.0 or s >= 1.0:
                return True
    return False


@scalar.jit
def _located(event, bound, y0, Z, inside):
    """The event (STOP or YIELD) on the step's collocation polynomial: the fractions of the step (lo, hi) just
    before and past it, by bisection (a stop before the slowest point, ``bound``); a surface stopping inside
    the step alone (``inside``): its first occurrence (``_share_leaves``)."""
    lo, hi = 0.0, bound if event == STOP else 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if event == STOP:
            vx, vy = corner.dense(y0, Z, mid, 2), corner.dense(y0, Z, mid, 3)
            past = math.sqrt(vx * vx + vy * vy) <= REST_SPEED
        else:
            s = corner.dense(y0, Z, mid, 5)
            past = _share_leaves(y0, Z, mid) if inside else (s <= 0.0 or s >= 1.0)
        if past:
            hi = mid
        else:
            lo = mid
    return lo, hi


#: Newton's iterations on the length of the step to an event; bisection after them
EVENT_NEWTON = 40


@scalar.jit(inline=False)
def _to_event(event, bound, inside, t, y, y0, taken, p, rows, k0, work, Z):
    """The step from (t, y0) to the event (STOP or YIELD) that the trial step of length ``taken`` (its stages
    Z) shows (``inside``: a surface stopping inside the step alone): located on its collocation polynomial
    (``_located``), then the step there, its length corrected
    by Newton on the step's end (inside the step the polynomial is of a lower order than at its end: at a fast
    reversal the stop would be off by a little time), kept within a bracket of the event, and after
    EVENT_NEWTON iterations by bisection, which closes the bracket. (reached, its length, its error): reached
    where the event holds at the step's end (|u̇| along the way it went within REST_SPEED of zero; σ within
    1e-12 of 0 or 1), or the bracket closes on a step past it, and the step meets the tolerance; y the state
    there (at rest: u̇ a half REST_SPEED along the way it went; σ set to 0 or 1), else y0 (and where the
    bracket closes but no step went past the event, or a surface stops inside the step alone within RADAU_MIN
    of its start, not there: the error -1)."""
    lo, hi = _located(event, bound, y0, Z, inside)
    vx, vy = corner.dense(y0, Z, lo, 2), corner.dense(y0, Z, lo, 3)  # just before the event
    size = math.sqrt(vx * vx + vy * vy)
    dx, dy = vx / size, vy / size
    target = 0.0 if corner.dense(y0, Z, hi, 5) <= 0.5 else 1.0
    length = hi * taken
    reached, error = False, 0.0
    if length <= RADAU_MIN:  # at the step's start (inside alone: the polynomial's overshoot, σ relaxing fast)
        if inside:
            return False, 0.0, -1.0
        for i in range(corner.N):
            y[i] = corner.dense(y0, Z, hi, i)
        return True, 0.0, 0.0
    # whether the trial step went past the event by its end: the bracket's far end, seen
    if event == STOP:
        past = (y0[2] + Z[2 * corner.N + 2]) * dx + (y0[3] + Z[2 * corner.N + 3]) * dy <= 0.0
    else:
        past = (y0[5] + Z[2 * corner.N + 5] > target) == (target == 1.0)
    # Newton on the length, kept within a bracket [before, beyond] of the event (bisection where it leaves it)
    before, beyond, iteration = 0.0, taken, 0
    while True:
        iteration += 1
        status, error, iterations, theta = corner.radau_step(t, y0, length, p, rows, k0, RADAU_RTOL, RADAU_ATOL,
                                                             True, 1, Z, work)
        if status != 0:
            error = 2.0 ** 4
            break
        for i in range(corner.N):
            y[i] = y0[i] + Z[2 * corner.N + i]
        if error > 1.0:
            break
        if event == STOP:
            j, miss = 2, y[2] * dx + y[3] * dy
        else:
            j, miss = 5, y[5] - target
        rate = (corner.W[2, 0] * Z[j] + corner.W[2, 1] * Z[corner.N + j] + corner.W[2, 2] * Z[2 * corner.N + j])
        if event == STOP:
            rate = (rate * dx + dy * (corner.W[2, 0] * Z[3] + corner.W[2, 1] * Z[corner.N + 3]
                                      + corner.W[2, 2] * Z[2 * corner.N + 3]))
        rate /= length
        if abs(miss) <= (REST_SPEED if event == STOP else 1e-12):
            reached = True
            break
        short = miss > 0.0 if event == STOP else (miss > 0.0) == (target == 0.0)  # not yet there
        if short:
            before = length
        else:
            beyond, past = length, True
        if beyond - before <= 1e-15 * taken + RADAU_MIN:
            # (a stop where u̇ jumps through zero: the bracket's end); no step past the event: not there
            reached = past
            if not past:
                error = -1.0
            break
        following = length - miss / rate if rate != 0.0 else 0.5 * (before + beyond)
        newton = iteration < EVENT_NEWTON and before < following < beyond
        length = following if newton else 0.5 * (before + beyond)
    if not reached:  # the step's start kept
        for i in range(corner.N):
            y[i] = y0[i]
    elif event == YIELD:
        y[5] = target
    else:
        y[2], y[3] = 0.5 * REST_SPEED * dx, 0.5 * REST_SPEED * dy
    return reached, length, error


@scalar.jit
def _slowest(y0, Z):
    """The smallest |u̇| over the step on its collocation polynomial and where (the fraction of the step): where
    at four points |u̇| stays above 1000 REST_SPEED and u̇ within 90 degrees of its start (a polynomial of this
    small degree cannot come within REST_SPEED of zero between them without turning past), the least of them;
    else the least of 16 points, refined by a golden-section search around it."""
    v0, x0, y0v = corner.speed(y0, Z, 0.0)
    best, at, plain = v0, 0.0, True
    for i in range(1, 5):
        size, vx, vy = corner.speed(y0, Z, i / 4.0)
        if size < best:
            best, at = size, i / 4.0
        plain = plain and size > 1e3 * REST_SPEED and vx * x0 + vy * y0v > 0.0
    if plain and v0 > 1e3 * REST_SPEED:
        return best, at
    best, at = v0, 0.0
    for i in range(1, 17):
        size = corner.speed(y0, Z, i / 16.0)[0]
        if size < best:
            best, at = size, i / 16.0
    lo, hi = max(at - 1.0 / 16.0, 0.0), min(at + 1.0 / 16.0, 1.0)
    for _ in range(40):
        a = hi - 0.6180339887498949 * (hi - lo)
        b = lo + 0.6180339887498949 * (hi - lo)
        va, vb = corner.speed(y0, Z, a)[0], corner.speed(y0, Z, b)[0]
        if va < vb:
            hi = b
        else:
            lo = a
        if va < best:
            best, at = va, a
        if vb < best:
            best, at = vb, b
    return best, at


@scalar.jit
def _record(k, s, dx, dy, m, p, rows, t1, t3, y, history):
    """Row k of the history (``articulated``) from the state record s: the state, u̇_1, F/W (the demand -a_g / g at
    rest) and each surface's μ_j."""
    u, v, u1, v1, phase, force, mu, _, _ = history
    x0, x1, w0, w1, q0, q1 = s[UX], s[UY], s[VX], s[VY], s[U1X], s[U1Y]
    state = int(s[PHASE])
    u[k, 0], u[k, 1], v[k, 0], v[k, 1], u1[k, 0], u1[k, 1] = x0, x1, w0, w1, q0, q1
    phase[k] = state
    v1[k, 0], v1[k, 1] = (w0, w1) if state == SLIDE1 else (0.0, 0.0)
    speed = math.sqrt(w0 * w0 + w1 * w1)
    L1, L3, g = p[LENGTH1], p[LENGTH3], p[GRAVITY]
    if state == STUCK:
        force[k, 0], force[k, 1] = dx / g, dy / g
        mu[k, 0] = rows[0][FACTOR] * surface_mu(rows[0], 0.0, m, t1)
        mu[k, 1] = rows[1][FACTOR] * surface_mu(rows[1], 0.0, m, t3)
        return
    if state == BOTH and speed > 0.0:
        y[0], y[1], y[2], y[3], y[4], y[5] = x0, x1, w0, w1, s[DELTA], s[SIGMA]
        p[N0], p[N1] = m, 0.0
        n, z1x, z1y, z3x, z3y, s1, s3, m1, m3, fx, fy = corner.shape(y, p, rows, 0.0)
        force[k, 0], force[k, 1] = m * fx, m * fy
        v1[k, 0], v1[k, 1] = s1 * z1x, s1 * z1y
        mu[k, 0] = rows[0][FACTOR] * surface_mu(rows[0], rows[0][RATIO] * s1, m, t1)
        mu[k, 1] = rows[1][FACTOR] * surface_mu(rows[1], rows[1][RATIO] * s3, m, t3)
        return
    lower = state == SLIDE1 or state == BOTH
    j = 0 if lower else 1
    Lj = L1 if lower else L3
    yx, yy = (q0, q1) if lower else (x0 - q0, x1 - q1)
    ex, ey = (w0 / speed, w1 / speed) if speed > 0.0 else (0.0, 0.0)
    tj = t1 if lower else t3
    cj = rows[j][WEIGHT] * rows[j][FACTOR] * surface_mu(rows[j], rows[j][RATIO] * speed, m, tj)
    force[k, 0], force[k, 1] = m * (yx / Lj + cj * ex), m * (yy / Lj + cj * ey)
    mu[k, j] = rows[j][FACTOR] * surface_mu(rows[j], rows[j][RATIO] * speed, m, tj)
    i = 1 - j
    mu[k, i] = rows[i][FACTOR] * surface_mu(rows[i], 0.0, m, t3 if i == 1 else t1)


#: the cost of a sample interval interpreted, in the planar kernels' case-steps (``backend.choose``)
INTERVAL_WORK = 100


def articulated_history(ground, L1, L3, zeta, rows, rigid_rows, samples=None, compiled=None):
    """The articulated slider's history at the interval ends of ``ground`` (``Ground``, one component run as
    the first of two): u, u̇, u_1 (n, 2), the phase (n), F/W (n, 2), each surface's μ_j and temperature (n, 2);
    ``rows`` the surfaces' laws (``Structure.rows``), ``rigid_rows`` the rigid slider's, ``samples`` whether
    each interval end is one of the record's samples (the heat intervals; default: all); ``compiled`` None:
    compiled for a long record (``backend``), interpreted for a short one."""
    from .. import backend
    from .integrator import ATOL, RTOL, scratch, tableau

    time, a0, a1, n0, n1 = planar_ground(ground)
    n = time.size
    rows = np.ascontiguousarray(rows, dtype=float)
    heats = bool(np.any(rows[:, KIND] == HEATED))
    if compiled is None:
        compiled = backend.choose(n - 1, INTERVAL_WORK + (n // 200 if heats else 0)) == "numba"
    run = scalar.kernel(articulated) if compiled else articulated
    u, v, u1, v1, force = np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2)), np.zeros((n, 2))
    phase = np.zeros(n, dtype=np.int64)
    heat, temperature, mu = np.zeros((n, 4)), np.zeros((n, 2)), np.zeros((n, 2))
    samples = np.ones(n, dtype=bool) if samples is None else np.asarray(samples, dtype=bool)
    rigid = np.ascontiguousarray(rigid_rows, dtype=float)
    p = np.zeros(PARAMETERS)
    p[LENGTH1], p[LENGTH3], p[GRAVITY], p[DAMPING] = L1, L3, G, 2.0 * float(zeta) * math.sqrt(G / (L1 + L3))
    K, y, out, trial = scratch(compiled)
    dop = (float(RTOL), float(ATOL), *tableau(compiled), K, out, trial, y)
    radau = (corner.workspace(), np.zeros(corner.S * corner.N), np.zeros(corner.N), np.zeros(corner.N),
             np.zeros(corner.N))
    history = (u, v, u1, v1, phase, force, mu, heat, temperature)
    status, k = run(time, a0, a1, n0, n1, samples, rows if compiled else rows.tolist(),
                    rigid if compiled else rigid.tolist(), surfaces_alike(rows, L1, L3), p, dop, radau, history)
    if status == CHATTER:
        from .exact import chatter

        raise chatter(time[k])
    if status == FAILED:
        raise RuntimeError(f"structure: the articulated slider's integration failed (its step fell below the "
                           f"smallest) in the sample interval at t = {time[k]:g} s; report the record and the "
                           f"structure")
    if status == UNSPLIT:
        raise RuntimeError(f"structure: a surface of the articulated slider yields in the sample interval at "
                           f"t = {time[k]:g} s, but no split of the sliding balances the hinge unless that surface "
                           f"slides backwards (the corner's algebraic condition, its share σ outside [0, 1]); report "
                           f"the record and the structure")
    return u, v, u1, v1, phase, force, mu, temperature


def surfaces_alike(rows, L1, L3, rel=1e-12):
    """Whether the surfaces' coefficients are equal (to ``rel``) wherever they slide in proportion (s_j = L_j ω):
    μ̄_1 = μ̄_3 under Coulomb friction; under a law, the same law and values, pendulums and weights. Then the
    hinge never turns (p_1 = p_3 from rest, z_1 = z_3, u̇_j = L_j u̇ / L: the flow's equations hold) and both
    surfaces slide as the rigid slider, exactly; a relative difference ``rel`` in μ̄ turns the hinge by about
    rel μ̄, of no account."""
    r1, r3 = np.asarray(rows, dtype=float)
    if r1[KIND] != r3[KIND]:
        return False
    close = lambda a, b: abs(a - b) <= rel * max(abs(a), abs(b))  # noqa: E731
    if r1[KIND] == 0.0:
        return close(r1[WEIGHT] * r1[FACTOR] * r1[MU], r3[WEIGHT] * r3[FACTOR] * r3[MU])
    return (close(L1, L3) and close(r1[WEIGHT] * r1[FACTOR], r3[WEIGHT] * r3[FACTOR]) and close(r1[RATIO], r3[RATIO])
            and np.array_equal(r1[MU:], r3[MU:]))


def respond(ground, times, geometry, structure) -> Response:
    """The response of a structure on an articulated slider (``Response`` with its ``Surfaces``): exact in one
    component under Coulomb friction without a vertical (``series``), else ``articulated_history``."""
    refined, index = ground.refined(times)
    L1, L3 = structure.pendulums(geometry)
    L = L1 + L3
    rows = structure.rows(geometry, proportional=False)
    components = refined.a0.shape[1]
    temperature = None
    if components == 1 and not refined.has_vertical and structure.coulomb:
        m1, m3 = (G * r[WEIGHT] * r[FACTOR] * r[MU] for r in rows)
        u, v, u1, phase, force = series_line_history(refined.time, refined.a0[:, 0], refined.a1[:, 0], G / L1, G / L3,
                                                     math.sqrt(G / L), structure.damping, m1, m3)
        u, v, u1, force = u[:, None], v[:, None], u1[:, None], force[:, None] / G
        v1 = np.where(phase == SLIDE1, 1.0, np.where(phase == BOTH, L1 / L, 0.0))[:, None] * v
        mu = np.broadcast_to([r[FACTOR] * r[MU] for r in rows], (u.shape[0], 2))
    else:
        u, v, u1, v1, phase, force, mu, temperature = articulated_history(
            refined, L1, L3, structure.damping, rows, structure.rows(geometry), np.isin(refined.time, ground.time))
        u, v, u1, v1, force = (x[:, :components] for x in (u, v, u1, v1, force))
        if not np.any(rows[:, KIND] == HEATED):
            temperature = None
    normal = refined.normal()
    load = np.maximum(normal, 0.0)[:, None]
    weights = rows[:, WEIGHT]
    stroke = np.stack([u1, u - u1], axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(load[..., None] > 0.0, (force[..., None] / load[..., None] - stroke / np.array([L1, L3]))
                     / (weights * mu)[:, None, :], 0.0)
    sliding = np.stack([(phase == SLIDE1) | (phase == BOTH), (phase == SLIDE3) | (phase == BOTH)], axis=-1)
    hinge = _hinge(stroke, L1, L3)
    span = slice(index[0], None)  # to the record's end, past the last requested time
    peaks = tuple(float(np.max(np.linalg.norm(x[span], axis=1))) for x in (u, force))
    size = np.linalg.norm(stroke[span], axis=1)  # (T', 2)
    rings = ring_strokes(geometry, structure.hinge)
    ring = []
    for j in range(2):
        beyond = np.nonzero(size[:, j] >= rings[j])[0]
        ring.append((float(refined.time[span][beyond[0]]) if beyond.size else math.nan,
                     float(max(size[:, j].max() - rings[j], 0.0))))
    uplift = None
    if refined.v0 is not None:
        peaks += (float(np.min(normal[span])),)
        uplift = [(max(a, float(times[0])), b) for a, b in refined.uplift() if b > times[0]]
    surfaces = Surfaces(stroke[index], np.stack([v1, v - v1], axis=-1)[index], z[index], sliding[index],
                        np.asarray(mu)[index], hinge[index], (L1, L3), rings,
                        tuple(float(x) for x in size.max(axis=0)), float(np.max(np.abs(hinge[span]))), tuple(ring))
    return Response(u[index], v[index], None, force[index], (phase == STUCK)[index], peaks,
                    None if uplift is None else normal[index], uplift, None,
                    None if temperature is None else temperature[index], surfaces)


def _hinge(stroke, L1, L3):
    """The hinge rotation (rad) of the surfaces' displacements ``stroke`` (T, c, 2): θ_1 - θ_3 (sin θ_j = u_j /
    L_j) in one component, the angle between the two halves' axes in two."""
    t1, t3 = stroke[..., 0] / L1, stroke[..., 1] / L3
    if stroke.shape[1] == 1:
        return np.arcsin(np.clip(t1[:, 0], -1, 1)) - np.arcsin(np.clip(t3[:, 0], -1, 1))
    a1 = np.column_stack([t1, np.sqrt(np.maximum(1.0 - np.sum(t1 * t1, axis=1), 0.0))])
    a3 = np.column_stack([t3, np.sqrt(np.maximum(1.0 - np.sum(t3 * t3, axis=1), 0.0))])
    cross = np.linalg.norm(np.cross(a1, a3), axis=1)
    return np.arctan2(cross, np.sum(a1 * a3, axis=1))


ARTICULATED = register(SliderKind("articulated", "two halves joined by a spherical hinge (Fenz and Constantinou's "
                                  "double friction pendulum): each surface slides or holds by its own friction, two "
                                  "pendulums in series", respond, proportional=False))
