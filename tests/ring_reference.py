"""An independent integration of an isolated structure on a friction pendulum whose travel is bounded by a
retaining ring, one horizontal component, for the tests: implicit (backward Euler, Moreau and Jean's) time
stepping on a uniform sub-step of each sample interval, each step's friction and rings solved exactly as a
monotone problem in one unknown, the rings' contacts and the superstructure's stops located inside the step,
and Richardson's extrapolation over halved sub-steps (``richardson``).

It uses nothing of the library's: not its closed forms, its events or its phases. Per unit mass, u the stroke
(the superstructure's displacement relative to the ground), v = u̇, the ground's acceleration a_g a straight
line on each sample interval (a0[k] at its start, a1[k] its slope, as ``Ground``):

* ``rigid``: one pendulum of length L, ω² = g / L, ü + 2ζω u̇ + ω² u = -a_g - μ g z, z = sign(u̇) while it
  slides, |z| <= 1 while it sticks; μ Coulomb's, or the speed law μ(|u̇|) = fast - (fast - slow) exp(-rate |u̇|)
  (``dccss.mechanics.friction``'s ``velocity`` law with friction on the device: at the stroke's speed). The
  ring bounds |u| <= d: reaching it, a perfectly plastic impact (v -> 0, v² / 2 lost); it stays there while
  the demand -a_g - ω² d pushes outward or the friction holds it, and slides back once the demand pulls
  inward past the friction (at +d: -a_g - ω² d < -μ g). There F/W = -a_g / g and the ring carries
  max(0, -a_g - ω² d - μ g) per unit mass (``ring_force``: the friction at its limit holding outward first,
  the split being otherwise undetermined).
* ``series``: the articulated slider, two massless halves in series on surfaces j = 1, 3 (pendulums L_j,
  ω_j² = g / L_j, force-level frictions m_j = g μ̄_j, each half's travel |u_j| <= d_j, u = u_1 + u_3). The
  same force f = F/W on both: g f = ω_j² u_j + m_j z_j + r_j, z_j = sign(u̇_j) while surface j slides, r_j the
  ring's reaction (>= 0 at +d_j, <= 0 at -d_j, 0 inside); ü + 2ζω u̇ + g f = -a_g, ω² = g / (L_1 + L_3). A
  speed law's μ̄_j is taken at the surface's own speed |u̇_j|.

**The step.** Over a step of length τ from (u_j, v), backward Euler's balance (1 + 2ζωτ) V = b - τ F (b = v -
τ a_g at the step's end, V the new velocity, F = g f) and each surface's law decide the step: under F,
surface j holds where |F - ω_j² u_j| <= m_j(0), else slides by τ s_j in the direction of F - ω_j² u_j, its
speed s_j the root of ω_j² τ s + m_j(s) = |F - ω_j² u_j| (the new u_j on its friction, μ at the new speed);
a surface at its ring is clipped to it (the ring takes the excess). Each new u_j(F) is non-decreasing in F,
so the step's one equation Σ_j Δu_j(F) + (τ² / (1 + 2ζωτ)) F = τ b / (1 + 2ζωτ) is strictly increasing in F:
a unique root (``_solve``: exact on Coulomb's linear pieces, to rounding). It is the minimiser of the step's
incremental energy (Moreau and Jean): no regularisation. Then V = Σ Δu_j / τ.

**Events.** A half that is not at its ring is not clipped: where a step takes it past its ring, the step is cut
where it reaches it, at the length τ of the backward Euler step that lands it there (bisection, to the last
bit); it is then at its ring (|u_j| = d_j exactly) and the rest of the step goes on from there. Where every
half is then at its ring on the side the superstructure moves to, that is the impact: v -> 0, v² / 2 lost,
recorded with its time and |v|. A half of an articulated slider reaching its ring while the other surface
holds does not lock the bearing: the force that would stop the superstructure at once is an impulse, which no
friction holds; the other surface slides at once (the step's F jumps to its threshold), the superstructure's
velocity goes on (no loss), and the half stays at its ring while F pushes it outward. The same holds for a
half landing while the other is at its ring on the other side: no impact, the impulse pulls that one off.
A step in which the superstructure stops (its velocity reaching 0 or reversing) is cut likewise where the
backward Euler step first stops it: at a reversal the friction's force jumps by 2 μ g, and a step across it
leaves a velocity error of 2 μ g θ h (θ where in the step it fell), first order and erratic in h, which
Richardson's extrapolation cannot remove (measured without it, the record × 2, μ = 0.05, no ring: the
extrapolated stroke 8e-6, 7e-6, 4e-6 m off the exact one from 250, 500, 1000 steps a sample; with it 7e-8,
8e-9, 2.5e-9 m). Stick-slip starts need no such care: the velocity is continuous there.

Clipping the step at its end instead (``locate=False``: the step's u_j clipped to [-d_j, d_j], the velocity
that of the clipped displacement, Moreau's catching-up, the rings' work counted as the impacts') restarts
after an impact at the step's end, again a first-order error erratic in h: kept to show it (on 6 s of the
synthetic record × 4, the spread between extrapolations is 1e-4 m clipped, 7e-8 m located).

**Rounding.** F is of the order of ω² u while a sliding surface's Δu_j follows from F - ω_j² u_j, of the
order of its friction: F's rounding alone leaves Δu_j wrong by about ulp(u_j), with a sign set by the side
Newton's iterations come from, a bias of 1e-12 m/s in the velocity at each of millions of steps, 4e-7 m over
20 s. The last residual, below F's rounding, is therefore taken up by the travels themselves (``_solve``);
then a frictionless pendulum's extrapolation converges at second order (3e-7, 8e-8, 2e-8 m).

**Accuracy.** The error is of first order in the step, smooth in it across the located events, with an erratic
remainder of second order (a landing step's own error): ``richardson`` extrapolates from three runs at
halved steps to second order and reports the spread between the two first-order extrapolations. On the
synthetic record × 4 (20 s, DFP1, five or six impacts), from 250, 500 and 1000 steps a 0.01 s sample: spread
3e-8 to 1.2e-7 m, the second-order result within 7e-9 to 7e-8 m of that from 500, 1000 and 2000
(``test_ring_reference``'s table). Without rings it equals the library's closed forms to 3e-8 m (6 s of the
record × 2), its speed-law rigid slider to 3e-9 m, and tests/series_reference.py's speed laws to its own
accuracy (5e-7 m); a push into the ring, a release at the impact and a half handing the stroke to the other
surface equal their closed forms to 1e-9 (times, s; speeds, m/s; strokes, m).

**Energy** (per unit mass, m²/s²): the input ∫ -a_g u̇ dt equals the kinetic v² / 2, the potential Σ ω_j² u_j² / 2,
the damping ∫ 2ζω u̇² dt, the friction Σ ∫ m_j |u̇_j| dt and the impacts' Σ v² / 2, plus the scheme's own loss
(``scheme``: Σ ((ΔV)² + Σ ω_j² Δu_j²) / 2 over the steps), first order in h: the discrete balance closes to
rounding, the extrapolated physical one to the scheme's accuracy.

Compiled with Numba: a 20 s record at 1000 steps a 0.01 s sample (h = 1e-5 s) takes about 1 s with Coulomb
friction (rigid or articulated), 3.5 s (rigid) to 5 s (articulated) with speed laws; the three runs of an
extrapolation from 250, 500 and 1000 steps, 1.75 times that.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

G = 9.80665
#: the energy terms, in the order of the returned ``energy`` columns
ENERGY = ("input", "kinetic", "potential", "damping", "friction", "impacts", "scheme")
#: the events recorded at most (more are counted, not kept)
EVENTS = 100_000


# --- friction -------------------------------------------------------------------------------------------

@njit(cache=True, inline="always")
def _friction(law, j, s, g):
    """m_j(s) (m/s²) and dm_j/ds of surface j at the speed s: g Σ_k scale (fast - (fast - slow) exp(-rate ratio
    s)) over its rows law[j, k] = (slow, fast, rate, scale, ratio)."""
    total, slope = 0.0, 0.0
    for k in range(law.shape[1]):
        slow, fast, rate, scale, ratio = law[j, k, 0], law[j, k, 1], law[j, k, 2], law[j, k, 3], law[j, k, 4]
        if scale == 0.0:
            continue
        decay = math.exp(-rate * ratio * s)
        total += scale * (fast - (fast - slow) * decay)
        slope += scale * (fast - slow) * rate * ratio * decay
    return g * total, g * slope


@njit(cache=True, inline="always")
def _speed(size, kt, law, j, g, m0, mfast, coulomb, guess):
    """The speed s >= 0 of surface j under |F - ω_j² u_j| = ``size``: kt s + m_j(s) = size (kt = ω_j² τ), 0
    where size <= m_j(0); and ds/d(size). The left side increases (fast >= slow) and is concave in s: Newton
    from the guess, kept inside [(size - m(∞)) / kt, (size - m(0)) / kt]."""
    if size <= m0:
        return 0.0, 0.0
    if coulomb:
        return (size - m0) / kt, 1.0 / kt
    lo, hi = max(0.0, (size - mfast) / kt), (size - m0) / kt
    s = guess if lo < guess < hi else hi
    slope = kt
    for _ in range(100):
        m, dm = _friction(law, j, s, g)
        phi = kt * s + m - size
        slope = kt + dm
        if phi == 0.0 or abs(phi) <= 4e-16 * size:
            break
        if phi > 0.0:
            hi = s
        else:
            lo = s
        nxt = s - phi / slope
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if nxt == s or hi - lo <= 4e-16 * hi:
            s = nxt
            break
        s = nxt
    return s, 1.0 / slope


# --- one implicit step ----------------------------------------------------------------------------------

@njit(cache=True, inline="always")
def _phi(F, u, w2, d, clip, law, m0, mfast, coulomb, g, tau, c2, rhs, guess, dx, slopes):
    """The step's residual Σ_j Δu_j(F) + c2 F - rhs under the force F, its slope in F and its scale; each
    Δu_j(F) into ``dx``, dΔu_j/dF into ``slopes``."""
    total, slope, size = c2 * F, c2, abs(c2 * F) + abs(rhs)
    for j in range(u.size):
        c = F - w2[j] * u[j]
        s, ds = _speed(abs(c), w2[j] * tau, law, j, g, m0[j], mfast[j], coulomb[j], guess[j])
        step = tau * s if c > 0.0 else -tau * s
        deriv = tau * ds
        if clip[j] and u[j] + step > d[j]:
            step, deriv = d[j] - u[j], 0.0
        elif clip[j] and u[j] + step < -d[j]:
            step, deriv = -d[j] - u[j], 0.0
        if s > 0.0:
            guess[j] = s
        dx[j], slopes[j] = step, deriv
        total += step
        slope += deriv
        size += abs(step)
    return total - rhs, slope, size


@njit(cache=True)
def _kinks(u, w2, d, clip, law, m0, g, tau, out):
    """The forces where the step's residual has a kink, sorted into ``out`` (their number returned): where
    each surface starts to slide either way, ω_j² u_j ± m_j(0), and where a clipped one's travel reaches its
    ring, ±(ω_j² d_j + m_j((d_j ∓ u_j) / τ))."""
    count = 0
    for j in range(u.size):
        out[count], out[count + 1] = w2[j] * u[j] - m0[j], w2[j] * u[j] + m0[j]
        count += 2
        if clip[j]:
            out[count] = w2[j] * d[j] + _friction(law, j, (d[j] - u[j]) / tau, g)[0]
            out[count + 1] = -w2[j] * d[j] - _friction(law, j, (d[j] + u[j]) / tau, g)[0]
            count += 2
    for i in range(1, count):  # insertion sort
        x, k = out[i], i - 1
        while k >= 0 and out[k] > x:
            out[k + 1] = out[k]
            k -= 1
        out[k + 1] = x
    return count


@njit(cache=True)
def _solve(u, w2, d, clip, law, m0, mfast, coulomb, g, tau, b, a, F, guess, dx, slopes, kinks):
    """The step of length τ under b = v - τ a_g and a = 1 + 2ζωτ: the force F (m/s², from the guess ``F``)
    with Σ_j Δu_j(F) + (τ² / a) F = τ b / a, each Δu_j(F) into ``dx`` and dΔu_j/dF into ``slopes`` (surface j
    clipped to its ring where ``clip[j]``).

    Newton's method from the guess (the last step's force: two evaluations where the step stays on the same
    piece); where it has not converged after two steps, the bracket it has built is narrowed to one smooth
    piece by the residual's kinks (``_kinks``: a holding or clipped surface leaves only the slope τ² / a, 1e-10,
    where Newton's steps would be huge), in which Newton's method, kept inside the bracket by bisection,
    converges (in one step on Coulomb's linear pieces).

    F is of the order of ω² u while a sliding surface's Δu_j follows from F - ω_j² u_j, of the order of its
    friction: F's rounding alone would leave Δu_j wrong by about ω_j^-2 ulp(F) ~ ulp(u_j), with a sign set by
    the side Newton's iterations come from, and that bias, 1e-12 m/s in the velocity at each of millions of
    steps, shows at 1e-7 m. So the last residual, below F's rounding, is taken up by the travels themselves
    (one more Newton step on Δu_j, exact on a linear piece)."""
    c2, rhs = tau * tau / a, tau * b / a
    lo, hi = -math.inf, math.inf
    narrowed = False
    r, slope, size = _phi(F, u, w2, d, clip, law, m0, mfast, coulomb, g, tau, c2, rhs, guess, dx, slopes)
    for it in range(200):
        if r == 0.0:
            break
        if r < 0.0:
            lo = F
        else:
            hi = F
        step = -r / slope
        closed = lo > -math.inf and hi < math.inf and hi - lo <= 4e-16 * (abs(lo) + abs(hi))
        if abs(step) <= 4e-16 * abs(F) or abs(r) <= 4e-16 * size or closed:
            break  # converged to F's rounding: the last shift below (or the bracket closed on a kink)
        nxt = F + step
        if it >= 2 and not narrowed:
            narrowed = True
            count = _kinks(u, w2, d, clip, law, m0, g, tau, kinks)
            for i in range(count):
                if not (lo < kinks[i] < hi):
                    continue
                F = kinks[i]
                r, slope, size = _phi(F, u, w2, d, clip, law, m0, mfast, coulomb, g, tau, c2, rhs, guess, dx,
                                      slopes)
                if r == 0.0:
                    break
                if r < 0.0:
                    lo = F
                else:
                    hi = F
                    break
            if r == 0.0:
                break
            # a point inside the one smooth piece left
            if lo > -math.inf and hi < math.inf:
                nxt = 0.5 * (lo + hi)
            elif lo > -math.inf:
                nxt = lo + max(1.0, abs(lo))
            else:
                nxt = hi - max(1.0, abs(hi))
        elif not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if nxt == F:
            break
        F = nxt
        r, slope, size = _phi(F, u, w2, d, clip, law, m0, mfast, coulomb, g, tau, c2, rhs, guess, dx, slopes)
    shift = -r / slope
    if r != 0.0 and abs(shift) <= 1e-14 * (abs(F) + 1.0):
        for j in range(u.size):
            dx[j] += slopes[j] * shift
        F += shift
    return F


@njit(cache=True, inline="always")
def _event(u, d, clip, dx, v):
    """Whether a step (``dx``) from the velocity v takes a half that is not clipped past its ring, or stops the
    superstructure (its new velocity Σ dx / τ zero or reversed)."""
    total = 0.0
    for j in range(u.size):
        total += dx[j]
        if not clip[j] and abs(u[j] + dx[j]) > d[j]:
            return True
    return v != 0.0 and total * v <= 0.0


@njit(cache=True)
def _record(events, count, t, surface, speed, impact):
    """A contact into the next row of ``events`` (counted beyond its rows)."""
    i = count[0]
    if i < events.shape[0]:
        events[i, 0], events[i, 1], events[i, 2], events[i, 3] = t, surface, speed, impact
    count[0] = i + 1


@njit(cache=True)
def _run(time, a0, a1, w2, d, law, damp, g, substeps, locate, start,
         out_u, out_v, out_f, out_ring, out_at, out_slide, out_energy, events, count):
    """The history at the samples (the module docstring) into the ``out_*`` arrays; the rings' contacts into
    ``events`` rows (time, surface, |v|, impact), their number into count[0], the steps left unfinished (more
    events in one than can be) into count[1]."""
    n = w2.size
    u, dx, slopes, guess, kinks = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(4 * n)
    clip, coulomb = np.zeros(n, dtype=np.bool_), np.zeros(n, dtype=np.bool_)
    m0, mfast = np.zeros(n), np.zeros(n)
    for j in range(n):
        m0[j] = _friction(law, j, 0.0, g)[0]
        for k in range(law.shape[1]):  # m_j as the speed grows without bound (its slow value where rate = 0)
            mfast[j] += g * law[j, k, 3] * (law[j, k, 1] if law[j, k, 2] * law[j, k, 4] > 0.0 else law[j, k, 0])
        coulomb[j] = m0[j] == mfast[j]
    for j in range(n):
        u[j] = start[j]
    v, F = start[n], -a0[0]
    e_in, e_damp, e_fric, e_imp, e_num = 0.0, 0.0, 0.0, 0.0, 0.0
    slid = np.zeros(n, dtype=np.bool_)
    for k in range(time.size):
        if k > 0:
            span = time[k] - time[k - 1]
            h = span / substeps
            for i in range(1, substeps + 1):
                t = span * (i - 1) / substeps  # from the interval's start
                end = span * i / substeps
                done = False
                for _ in range(8 * n + 8):  # the step, cut at each event
                    tau = end - t
                    for j in range(n):
                        clip[j] = (not locate) or abs(u[j]) >= d[j]
                    ag = a0[k - 1] + a1[k - 1] * (t + tau)
                    F = _solve(u, w2, d, clip, law, m0, mfast, coulomb, g, tau, v - tau * ag, 1.0 + damp * tau, F,
                               guess, dx, slopes, kinks)
                    cut = locate and _event(u, d, clip, dx, v)
                    total = 0.0
                    if cut:  # the shortest step that lands a half on its ring or stops the superstructure
                        lo, hi = 0.0, tau
                        for _ in range(200):
                            mid = 0.5 * (lo + hi)
                            if mid <= lo or mid >= hi:
                                break
                            ag = a0[k - 1] + a1[k - 1] * (t + mid)
                            _solve(u, w2, d, clip, law, m0, mfast, coulomb, g, mid, v - mid * ag,
                                   1.0 + damp * mid, F, guess, dx, slopes, kinks)
                            if _event(u, d, clip, dx, v):
                                hi = mid
                            else:
                                lo = mid
                        tau = hi
                        ag = a0[k - 1] + a1[k - 1] * (t + tau)
                        F = _solve(u, w2, d, clip, law, m0, mfast, coulomb, g, tau, v - tau * ag, 1.0 + damp * tau,
                                   F, guess, dx, slopes, kinks)
                    for j in range(n):
                        total += dx[j]
                    vn = total / tau
                    before = v
                    loss = 0.5 * (vn - v) * (vn - v)  # backward Euler's own (Σ over the steps: first order in h)
                    for j in range(n):
                        if dx[j] != 0.0:
                            m = m0[j] if coulomb[j] else _friction(law, j, abs(dx[j]) / tau, g)[0]
                            e_fric += m * abs(dx[j])
                            loss += 0.5 * w2[j] * dx[j] * dx[j]
                            if clip[j] and abs(u[j] + dx[j]) >= d[j]:  # the ring's work in a clipped step: the impact's
                                e_imp += (F - w2[j] * (u[j] + dx[j])) * dx[j] - m * abs(dx[j])
                        slid[j] = dx[j] != 0.0
                        u[j] += dx[j]
                    e_num += loss
                    e_in -= ag * total
                    e_damp += damp * vn * vn * tau
                    v = vn
                    t += tau
                    if not locate:
                        landed = True
                        for j in range(n):
                            landed = landed and abs(u[j]) >= d[j] and u[j] * v > 0.0
                        if landed:
                            _record(events, count, time[k - 1] + t, -1.0, abs(before), 1.0)
                        done = True
                        break
                    if not cut:
                        done = True
                        break
                    landed = False
                    for j in range(n):
                        if not clip[j] and abs(u[j]) >= d[j] * (1.0 - 1e-12):  # on its ring (to rounding)
                            u[j] = math.copysign(d[j], u[j])
                            _record(events, count, time[k - 1] + t, j, abs(v), 0.0)
                            landed = True
                    if not landed or v * before <= 0.0:  # the superstructure stopped (v: 1e-21 m/s of rounding)
                        e_num += 0.5 * v * v
                        v = 0.0
                    impact = v != 0.0
                    for j in range(n):
                        impact = impact and abs(u[j]) >= d[j] and u[j] * v > 0.0
                    if impact:  # every half at its ring on the side it moves to: a plastic impact
                        if count[0] <= events.shape[0]:
                            events[count[0] - 1, 3] = 1.0
                        e_imp += 0.5 * v * v
                        v = 0.0
                    if end - t <= 1e-12 * h:
                        done = True
                        break
                if not done:  # more events in one step than the halves can have: a chatter
                    count[1] += 1
        out_v[k], out_f[k] = v, F / g
        kinetic, potential = 0.5 * v * v, 0.0
        for j in range(n):
            out_u[k, j] = u[j]
            potential += 0.5 * w2[j] * u[j] * u[j]
            at = abs(u[j]) >= d[j]
            out_at[k, j], out_slide[k, j] = at, slid[j]
            out_ring[k, j] = max(0.0, math.copysign(1.0, u[j]) * (F - w2[j] * u[j]) - m0[j]) if at else 0.0
        out_energy[k, 0], out_energy[k, 1], out_energy[k, 2] = e_in, kinetic, potential
        out_energy[k, 3], out_energy[k, 4], out_energy[k, 5], out_energy[k, 6] = e_damp, e_fric, e_imp, e_num


# --- the API --------------------------------------------------------------------------------------------

def _rows(law, coulomb):
    """A surface's law rows (k, 5) = (slow, fast, rate, scale, ratio) from None (Coulomb: ``coulomb``, the
    coefficient), a triple (slow, fast, rate) (scale = ratio = 1), a 5-tuple, or a sequence of 5-tuples
    (their sum)."""
    if law is None:
        if coulomb is None or not coulomb >= 0.0:
            raise ValueError(f"a Coulomb friction >= 0 or a law, got {coulomb!r}")
        return np.array([[coulomb, coulomb, 0.0, 1.0, 1.0]])
    rows = np.atleast_2d(np.asarray(law, dtype=float))
    if rows.shape[1] == 3:
        rows = np.column_stack([rows, np.ones((len(rows), 2))])
    if rows.shape[1] != 5 or np.any(rows[:, 1] < rows[:, 0]) or np.any(rows < 0.0):
        raise ValueError(f"a law is (slow, fast, rate[, scale, ratio]) >= 0 with fast >= slow, got {law!r}")
    return rows


def _integrate(time, a0, a1, w2, d, laws, zeta, omega, g, substeps, locate, state):
    time = np.ascontiguousarray(time, dtype=float)
    a0 = np.ascontiguousarray(a0, dtype=float).ravel()
    a1 = np.ascontiguousarray(a1, dtype=float).ravel()
    if a0.size < time.size - 1 or a1.size < time.size - 1:
        raise ValueError("a0 and a1 need one value per sample interval")
    n, m = time.size, len(w2)
    law = np.zeros((m, max(len(r) for r in laws), 5))
    for j, rows in enumerate(laws):
        law[j, :len(rows)] = rows
    out = {"u_j": np.zeros((n, m)), "v": np.zeros(n), "force": np.zeros(n), "ring_force": np.zeros((n, m)),
           "at_ring": np.zeros((n, m), dtype=bool), "sliding": np.zeros((n, m), dtype=bool),
           "energy": np.zeros((n, len(ENERGY)))}
    events, count = np.zeros((EVENTS, 4)), np.zeros(2, dtype=np.int64)
    start = np.zeros(m + 1) if state is None else np.asarray(state, dtype=float).ravel()
    if start.size != m + 1 or np.any(np.abs(start[:m]) > np.asarray(d)):
        raise ValueError(f"state: u_j ({m}, within the rings) then v, got {state!r}")
    _run(time, a0, a1, np.asarray(w2, dtype=float), np.asarray(d, dtype=float), law, 2.0 * zeta * omega, float(g),
         int(substeps), bool(locate), start, out["u_j"], out["v"], out["force"],
         out["ring_force"], out["at_ring"], out["sliding"], out["energy"], events, count)
    if count[1]:
        raise RuntimeError(f"ring_reference: {int(count[1])} steps with more events than the halves can have")
    out["u"] = out["u_j"].sum(axis=1)
    kept = events[:min(int(count[0]), EVENTS)]
    out["contacts"] = kept  # (time, surface index or -1, |v|, impact 1/0)
    out["impacts"] = kept[kept[:, 3] == 1.0][:, [0, 2]]  # (time, |v| before)
    out["events"] = int(count[0])
    out["substeps"] = int(substeps)
    return out


def rigid(time, a0, a1, L, zeta, mu, d, g=G, law=None, substeps=1000, locate=True, state=None) -> dict:
    """The rigid slider (one pendulum of length L, m) with its ring at the stroke d (m) under the ground
    a0[k] + a1[k] (t - time[k]) (m/s², m/s³) on each interval, by ``substeps`` uniform steps per interval:
    Coulomb friction ``mu`` (the coefficient), or ``law`` (slow, fast, rate): μ = fast - (fast - slow)
    exp(-rate |u̇|), or rows (slow, fast, rate, scale, ratio) summed (μ = Σ scale μ_k(ratio |u̇|): friction on
    the surfaces of a rigid slider, scale = ratio = R^j / L). Returns a dict of arrays at the samples: u, v,
    u_j (n, 1), force (F/W), ring_force (n, 1: the ring's force per unit mass, outward positive, with the
    friction at its limit holding outward first), at_ring, sliding (the last step moved) (n, 1), energy (n, 7:
    ``ENERGY``, cumulative), impacts (k, 2: time, |v| before), contacts (k, 4: time, -, |v|, impact)."""
    omega = math.sqrt(g / L)
    return _integrate(time, a0, a1, [g / L], [d], [_rows(law, mu)], zeta, omega, g, substeps, locate, state)


def series(time, a0, a1, L1, L3, zeta, m1, m3, d1, d3, g=G, law1=None, law3=None, substeps=1000,
           locate=True, state=None) -> dict:
    """The articulated slider (``rigid``'s arguments and returns): halves of pendulums L1, L3 (m) with their
    rings at u_j = ±d_j (m), Coulomb's force-level frictions m1, m3 (m/s²: g μ̄_j), or ``law1``, ``law3``
    (slow, fast, rate[, scale, ratio]): μ̄_j = scale (fast - (fast - slow) exp(-rate ratio |u̇_j|)) at the
    surface's own speed |u̇_j| (m_j = g μ̄_j; ``series_reference``'s convention). u_j has a column per surface
    (u_1, u_3), so do at_ring, sliding and ring_force; ``contacts`` rows name the surface (0: RB1, 1: RB3)
    that reached its ring, and whether it was an impact."""
    omega = math.sqrt(g / (L1 + L3))
    laws = [_rows(law1, None if m1 is None else m1 / g), _rows(law3, None if m3 is None else m3 / g)]
    return _integrate(time, a0, a1, [g / L1, g / L3], [d1, d3], laws, zeta, omega, g, substeps, locate, state)


#: the arrays ``richardson`` extrapolates
SMOOTH = ("u", "v", "u_j", "energy")


def richardson(runs) -> dict:
    """Richardson's extrapolation of runs at halved steps (``substeps`` n, 2n[, 4n]): u, v, u_j and the energies
    (and the impacts' times and speeds where the runs have as many). Two runs: the first-order 2 r(h/2) - r(h).
    Three: A and B, those of (h, h/2) and (h/2, h/4), and the second-order (4 B - A) / 3, returned; ``spread``
    is the largest difference of u between A and B (m; ``spread_v`` of v, ``spread_impacts`` of the impacts'
    times and speeds): A's error, roughly, and a bound on the returned one's, smaller by far (the remainder
    after A is of second order in h). v differs more where an impact falls within a few steps of a sample (the
    impact's time is first order in h: a sample can fall before it in one run and after it in the next)."""
    if len(runs) not in (2, 3) or any(b["substeps"] != 2 * a["substeps"] for a, b in zip(runs, runs[1:])):
        raise ValueError("richardson: two or three runs, each at twice the last's substeps")
    alike = len({len(r["impacts"]) for r in runs}) == 1
    keys = SMOOTH + (("impacts",) if alike else ())
    first = [{key: 2.0 * fine[key] - coarse[key] for key in keys} for coarse, fine in zip(runs, runs[1:])]
    if len(runs) == 2:
        out = first[0]
    else:
        A, B = first
        out = {key: (4.0 * B[key] - A[key]) / 3.0 for key in keys}
        out["spread"] = float(np.max(np.abs(B["u"] - A["u"])))
        out["spread_v"] = float(np.max(np.abs(B["v"] - A["v"])))
        if alike:
            out["spread_impacts"] = np.max(np.abs(B["impacts"] - A["impacts"]), axis=0, initial=0.0)
    out.setdefault("impacts", None)
    out["at_ring"], out["contacts"] = runs[-1]["at_ring"], runs[-1]["contacts"]
    return out
