"""The articulated slider: two pendulums in series (Fenz and Constantinou 2006), one component, exact.

An articulated slider is two halves joined by a spherical hinge: half j is seated on sliding surface
j (j = 1, the lower, RB1; j = 3, the upper, RB3) and turns about that sphere's centre C^j, the hinge
at the distance L_j from it (``Series``). The stroke u (RB3 relative to RB1, the superstructure's
displacement relative to the ground) is the sum of the hinge's displacement relative to C¹, u_1, and
C³'s relative to the hinge, u_3: u = u_1 + u_3. Each half is massless: its moment balance about C^j,
the friction acting at the sliding radius R^j, gives the horizontal force it carries,

    F = N u_j / L_j + μ̄_j N z_j,    μ̄_j = μ_j R^j / L_j,    |z_j| <= 1,

the same F on both halves (the hinge passes it on); z_j = sign(u̇_j) while surface j slides. μ_j is
the surface's own coefficient (friction at R^j, the rigid slider's convention), μ̄_j the force-level
coefficient of Fenz and Constantinou and of OpenSees' ``singleFPBearing`` (with R_eff = L_j). In
acceleration units (per unit mass, N = W): g F/W = ω_j² u_j + m_j z_j with ω_j² = g / L_j and
m_j = g μ̄_j. The superstructure obeys ü + 2ζω u̇ + g F/W = -a_g, ω² = g / L, L = L_1 + L_3 (the
damping from the nominal period, as the rigid slider's).

Which surfaces slide is decided by the force (the thresholds T_j(z) = ω_j² u_j + z m_j):

* **at rest** both hold while the demand d = -a_g lies in [max_j T_j(-1), min_j T_j(+1)]; it ends where
  d, a straight line on a sample interval, reaches a bound (exact), or at once where it is at or past one
  and growing (a bound reached at a sample, ``exact.rest_end``): the surface whose threshold it reaches
  slides, both where their thresholds are equal (to 1e-12 of the larger m_j);
* **one surface slides** (j), the other holds: a pendulum of length L_j, ü_j + 2ζω u̇_j + ω_j² u_j =
  -a_g - m_j z, solved in closed form; it ends where u̇ falls to 0 (a stop, then the rest test) or where
  F reaches the other surface's threshold, u_j = (ω_i² u_i + (m_i - m_j) z) / ω_j² (both then slide);
* **both slide**: F/W the same on both, so u̇_1 / L_1 = u̇_3 / L_3 (u_1 / L_1 - u_3 / L_3 stays
  (μ̄_3 - μ̄_1) z) and the device is a pendulum of length L with μ_eff = (μ̄_1 L_1 + μ̄_3 L_3) / L;
  closed form again, until u̇ falls to 0.

Each phase is the rigid slider's exact solution (``exact``) with other constants: exact to rounding.
With μ̄_1 = μ̄_3 the surfaces yield together and slide in proportion: the rigid slider of friction
μ̄_1 (``Structure.device_friction``).
"""

from __future__ import annotations

import math

import numpy as np

from .. import scalar
from .exact import CHATTER, DONE, MAX_PHASES, first_stop, leaving, reach, rest_end, run_line, slide, slide_on

#: a phase of the device: both surfaces hold, surface 1 slides alone, surface 3 alone, both slide
STUCK, SLIDE1, SLIDE3, BOTH = 0, 1, 2, 3
#: two thresholds this close (relative to the larger m_j) are reached together
TIE = 1e-12


@scalar.jit
def _starting(direction, up1, up3, lo1, lo3, m1, m3):
    """The phase that starts from rest in ``direction`` (±1), the thresholds up_j = T_j(+1), lo_j = T_j(-1):
    the surface whose threshold the demand passes first, BOTH where the two are equal (to TIE)."""
    tie = TIE * max(m1, m3)
    if direction > 0.0:
        if abs(up1 - up3) <= tie:
            return BOTH
        return SLIDE1 if up1 < up3 else SLIDE3
    if abs(lo1 - lo3) <= tie:
        return BOTH
    return SLIDE1 if lo1 > lo3 else SLIDE3


@scalar.jit
def _yielding(d, slope, past_upper, past_lower, u1, u3, w1sq, w3sq, m1, m3):
    """The phase at rest under the demand d (m/s²), changing at ``slope`` (m/s³), and its direction: the
    phase starting (``_starting``) where d leaves both surfaces' friction (``exact.leaving``: at or past a
    bound and growing on, or past it where ``past_upper``, ``past_lower``), else (STUCK, 0)."""
    up1, up3 = w1sq * u1 + m1, w3sq * u3 + m3
    lo1, lo3 = w1sq * u1 - m1, w3sq * u3 - m3
    direction = leaving(d, slope, max(lo1, lo3), min(up1, up3), past_upper, past_lower)
    if direction == 0.0:
        return STUCK, 0.0
    return _starting(direction, up1, up3, lo1, lo3, m1, m3), direction


def series_line(time, a0, a1, w1sq, w3sq, omega, zeta, m1, m3, u, v, u1, phase, force):
    """The exact one-component history of an articulated slider at the interval ends (the module
    docstring) into u, u̇, u_1, the phase (STUCK, SLIDE1, SLIDE3, BOTH) and g F/W (m/s²): (DONE, n - 1),
    or (CHATTER, k) at an interval k of more than MAX_PHASES phases. ``w1sq``, ``w3sq`` are g / L_j,
    ``omega`` √(g / L), ``m1``, ``m3`` g μ̄_j (> 0)."""
    n = len(time)
    r1 = w3sq / (w1sq + w3sq)  # L_1 / L: the share of the stroke surface 1 takes while both slide
    x, w, x1 = 0.0, 0.0, 0.0  # u, u̇, u_1
    state, sign = _yielding(-a0[0], 0.0, True, True, 0.0, 0.0, w1sq, w3sq, m1, m3)
    phase[0] = state
    force[0] = -a0[0] if state == STUCK else (m3 if state == SLIDE3 else m1) * sign
    for k in range(n - 1):
        h = time[k + 1] - time[k]
        tau, phases = 0.0, 0
        while tau < h:
            if phases >= MAX_PHASES:
                return CHATTER, k
            phases += 1
            b0, b1 = a0[k] + a1[k] * tau, a1[k]  # the ground's acceleration from tau on
            end = h - tau
            if state == STUCK:
                # the demand -a_g is a straight line in t; rest ends where it leaves [lower, upper]
                up1, up3 = w1sq * x1 + m1, w3sq * (x - x1) + m3
                lo1, lo3 = w1sq * x1 - m1, w3sq * (x - x1) - m3
                when, direction = rest_end(-b0, -b1, max(lo1, lo3), min(up1, up3), end)
                tau += when
                if direction != 0.0:
                    state, sign = _starting(direction, up1, up3, lo1, lo3, m1, m3), direction
                continue
            if state == BOTH:
                # g F/W = ω_1² u_1 + m_1 z, u_1 = x1 + r1 (u - x): ü + 2ζω u̇ + ω² u = -a_g - c0
                c0 = w1sq * x1 - omega * omega * x + m1 * sign
                start = x
                x, w, when, stopped = slide_on(x, w, -b0 - c0, -b1, omega, zeta, sign, end, True)
                x1 += r1 * (x - start)
                if not stopped:
                    tau = h
                    continue
                tau += when
                state, sign = _yielding(-b0 - b1 * when, -b1, sign < 0.0, sign > 0.0, x1, x - x1, w1sq, w3sq, m1, m3)
                continue
            # one surface slides (j), the other holds (i): y = u_j, ÿ + 2ζω ẏ + ω_j² y = -a_g - m_j z
            lower_slides = state == SLIDE1
            if lower_slides:
                wj, mj, y, other, wi, mi = w1sq, m1, x1, x - x1, w3sq, m3
            else:
                wj, mj, y, other, wi, mi = w3sq, m3, x - x1, x1, w1sq, m1
            omega_j = math.sqrt(wj)
            zeta_j = zeta * omega / omega_j  # the same damping 2ζω
            p0, p1 = -b0 - mj * sign, -b1
            stop = first_stop(y, w, p0, p1, omega_j, zeta_j, sign, end)
            limit = stop if stop >= 0.0 else end
            target = (wi * other + (mi - mj) * sign) / wj  # where F reaches the other surface's threshold
            when = reach(y, w, p0, p1, omega_j, zeta_j, sign, target, limit)
            stopped = False
            if when >= 0.0:
                y, w = slide(y, w, p0, p1, omega_j, zeta_j, when)
                state = BOTH
            elif stop < 0.0:
                y, w = slide(y, w, p0, p1, omega_j, zeta_j, end)
                when = end
            else:
                y, _ = slide(y, w, p0, p1, omega_j, zeta_j, stop)
                w, when, stopped = 0.0, stop, True
            x = y + other
            if lower_slides:
                x1 = y
            tau += when
            if stopped:
                state, sign = _yielding(-b0 - b1 * when, -b1, sign < 0.0, sign > 0.0, x1, x - x1, w1sq, w3sq, m1, m3)
        u[k + 1], v[k + 1], u1[k + 1] = x, w, x1
        b = a0[k] + a1[k] * h
        if state == STUCK:  # past a threshold at the sample, within rounding of it: sliding starts there
            state, sign = _yielding(-b, 0.0, True, True, x1, x - x1, w1sq, w3sq, m1, m3)
        phase[k + 1] = state
        if state == STUCK:
            force[k + 1] = -b
        elif state == SLIDE3:
            force[k + 1] = w3sq * (x - x1) + m3 * sign
        else:
            force[k + 1] = w1sq * x1 + m1 * sign
    return DONE, n - 1


def series_line_history(time, a0, a1, w1sq, w3sq, omega, zeta, m1, m3, compiled=None):
    """One-component history of an articulated slider at the interval ends: u, u̇, u_1, the phase and
    g F/W (``series_line``); ``compiled`` None: compiled for a long record (``backend``), interpreted
    for a short one."""
    n = time.size
    history = (np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n, dtype=np.int64), np.zeros(n))
    return run_line(series_line, time, a0, a1, (w1sq, w3sq, omega, zeta, m1, m3), history, compiled)


def quasi_static(u, L1, L3, m1, m3):
    """An articulated slider under an imposed stroke u (m, one component, straight lines between its samples),
    the slider's mass neglected and no superstructure: each surface's share u_1 (u_3 = u - u_1), the force
    per unit normal force f = F/N and the phase at each sample, from rest centred; m_j = μ̄_j (force-level
    coefficients, Coulomb).

    Fenz and Constantinou's regimes, rate-independent: moving in the direction z, surface j slides where
    f reaches its threshold p_j + z μ̄_j (p_j = u_j / L_j), the lower one first; while one slides, f grows by
    du / L_j (its pendulum alone) until it reaches the other's threshold; then both slide, u̇_1 / L_1 =
    u̇_3 / L_3, and f grows by du / L. On a reversal both hold and f falls at a fixed stroke (the loop's
    vertical unloading, by 2 μ̄_j for the surface that slides back first) until a threshold of the new
    direction is reached. Exact: the pieces are straight lines in u."""
    u = np.asarray(u, dtype=float)
    n = u.size
    u1, f = np.zeros(n), np.zeros(n)
    phase = np.full(n, STUCK, dtype=np.int64)
    x1, x, force, state = 0.0, 0.0, 0.0, STUCK
    for k in range(1, n):
        du = u[k] - x
        if du == 0.0:
            u1[k], f[k], phase[k] = x1, force, state
            continue
        z = 1.0 if du > 0.0 else -1.0
        while z * (u[k] - x) > 0.0:
            t1, t3 = x1 / L1 + z * m1, (x - x1) / L3 + z * m3  # the thresholds in the direction of motion
            if abs(t1 - t3) <= TIE * max(m1, m3):
                # both slide in proportion to the sample
                x1 += L1 / (L1 + L3) * (u[k] - x)
                x, state = u[k], BOTH
                force = x1 / L1 + z * m1
                continue
            if z * (t1 - t3) < 0.0:  # surface 1 first, until its threshold reaches surface 3's
                reach = x + L1 * (t3 - t1)
                end = u[k] if z * (u[k] - reach) <= 0.0 else reach
                x1 += end - x
                x, state = end, SLIDE1
                force = x1 / L1 + z * m1
            else:
                reach = x + L3 * (t1 - t3)
                end = u[k] if z * (u[k] - reach) <= 0.0 else reach
                x, state = end, SLIDE3
                force = (x - x1) / L3 + z * m3
        u1[k], f[k], phase[k] = x1, force, state
    return u1, f, phase
