"""An independent integration of the articulated slider (two pendulums in series, the slider massless),
for the tests: implicit (backward Euler) time stepping, each step the exact minimiser of its
incremental energy.

It uses nothing of the library's: not its kernels, its phases or its (δ, σ) description of two sliding
surfaces. Each step of length h finds the surfaces' velocities v_1, v_3 (the stroke's V = v_1 + v_3)
minimising the strictly convex

    J = (1 + 2ζω h) |V|² / 2 - b·V + Σ_j [ g n |u_j + h v_j|² / (2 L_j) + h g n μ̄_j |v_j| ],

b = v - h a_g, whose optimality conditions are the step's balance (1 + 2ζω h) V = b - h g n F/W with
F/W = (u_j + h v_j) / L_j + μ̄_j v_j / |v_j| on each sliding surface and |F/W - (u_j + h v_j) / L_j| <= μ̄_j
on a holding one (Moreau and Jean's time stepping). The minimiser is found through its dual: the step's force
minimises a strongly convex function of two variables (``step``), and each surface's travel follows from
it. A speed law's μ̄_j is taken at the surface's own speed in the step (implicit: with μ̄_j lagged a step,
the two surfaces of a speed law trade the sliding from step to step and the friction stays near its slow
value). The error is of first order in h (the stick-slip transitions), so the
tests compare at two steps and check that the difference from the library falls in proportion.
Compiled with Numba (a 20 s record at h = 1e-5 s takes under 1 s).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

G = 9.80665


@njit(cache=True)
def _mu(slow, fast, rate, speed):
    """μ̄ = fast - (fast - slow) exp(-rate v) (Coulomb: fast = slow)."""
    return fast - (fast - slow) * math.exp(-rate * speed)


@njit(cache=True)
def _speed(size, gh, n, law, guess):
    """A surface's speed s >= 0 under c (|c| = ``size``): g_j h s + n g μ̄(s) = |c| (0 where |c| <= n g μ̄(0)),
    and ds/d|c|; μ̄(s) = scale (fast - (fast - slow) exp(-rate ratio s)), law = (slow, fast, rate, scale,
    ratio). Bisection safeguarded Newton from ``guess`` (the left side increases with s)."""
    slow, fast, rate, scale, ratio = law[0], law[1], law[2], law[3], law[4]
    r0 = n * G * scale * slow
    if size <= r0:
        return 0.0, 0.0
    if fast == slow or rate == 0.0:  # Coulomb's: linear
        return (size - r0) / gh, 1.0 / gh
    lo, hi = 0.0, (size - r0) / gh  # μ̄(s) >= μ̄(0): the root lies below
    s = guess if 0.0 < guess < hi else hi
    slope = gh
    for _ in range(200):
        decay = math.exp(-rate * ratio * s)
        phi = gh * s + n * G * scale * (fast - (fast - slow) * decay) - size
        slope = gh + n * G * scale * (fast - slow) * rate * ratio * decay
        if abs(phi) <= 4e-16 * size:  # the balance to the rounding of its terms
            break
        if phi > 0.0:
            hi = s
        else:
            lo = s
        nxt = s - phi / slope
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        if abs(nxt - s) <= 4e-16 * s or hi - lo <= 4e-16 * hi:
            s = nxt
            break
        s = nxt
    return s, 1.0 / slope


@njit(cache=True)
def _gradient(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, n, law1, law3, H, guess):
    """∇D(Q) and (into H: H00, H01, H11) its Jacobian: hQ - b + a Σ_j v_j(Q), the gradient of the dual
    D(Q) = h |Q|² / 2 - b·Q + a Σ_j Φ_j(|c_j|), Φ_j(ρ) = ∫ s dρ (s the surface's speed at ρ)."""
    grad0, grad1 = h * q0 - b[0], h * q1 - b[1]
    H[0], H[1], H[2] = h, 0.0, h
    for j in range(2):
        gj, law = (g1, law1) if j == 0 else (g3, law3)
        cx = q0 - gj * (u1[0] if j == 0 else u3x)
        cy = q1 - gj * (u1[1] if j == 0 else u3y)
        size = math.sqrt(cx * cx + cy * cy)
        speed, ds = _speed(size, gj * h, n, law, guess[j])
        if speed == 0.0:
            continue
        guess[j] = speed
        ex, ey = cx / size, cy / size
        grad0 += a * speed * ex
        grad1 += a * speed * ey
        e = speed / size
        H[0] += a * (ds * ex * ex + e * (1.0 - ex * ex))
        H[1] += a * (ds - e) * ex * ey
        H[2] += a * (ds * ey * ey + e * (1.0 - ey * ey))
    return grad0, grad1


@njit(cache=True)
def step(u, u1, b, h, n, L1, L3, law1, law3, damp, Q, guess, H, V):
    """One step: (u, u_1) overwritten, the new velocity into V; returns which surfaces slide. b = v - h a_g,
    damp = 2ζω, ``law_j`` (``_speed``). The step's force per unit mass Q = g n F/W solves
    hQ - b + a Σ_j v_j(Q) = 0 (a = 1 + 2ζω h), v_j(Q) the surface's velocity under c_j = Q - g_j u_j
    (g_j = g n / L_j): along c_j, of the speed s with g_j h s + n g μ̄_j(s) = |c_j| (0 where |c_j| holds it;
    ``guess`` the surfaces' last speeds, where its root is sought from):
    the gradient of a strongly convex dual, whose zero Newton finds from the last step's Q (overwritten),
    minimising the dual along a step that does not lower the gradient's size. Surface j then moves by h v_j,
    with μ̄_j at the step's own speed (implicit)."""
    a = 1.0 + damp * h
    g1, g3 = n * G / L1, n * G / L3
    u3x, u3y = u[0] - u1[0], u[1] - u1[1]
    V[0], V[1] = 0.0, 0.0
    grad0, grad1 = _gradient(Q[0], Q[1], u1, u3x, u3y, b, h, a, g1, g3, n, law1, law3, H, guess)
    scale = 1e-15 * (abs(b[0]) + abs(b[1]) + h * (abs(Q[0]) + abs(Q[1]))) + 1e-300
    for _ in range(100):
        if abs(grad0) + abs(grad1) <= scale:  # converged to rounding
            break
        det = H[0] * H[2] - H[1] * H[1]
        d0 = -(H[2] * grad0 - H[1] * grad1) / det
        d1 = -(H[0] * grad1 - H[1] * grad0) / det
        if abs(d0) + abs(d1) <= 1e-14 * (abs(Q[0]) + abs(Q[1])):  # a step at the gradient's rounding: converged
            Q[0], Q[1] = Q[0] + d0, Q[1] + d1
            break
        norm = math.sqrt(grad0 * grad0 + grad1 * grad1)
        # a Newton step where it lowers the gradient's size; else (a kink of the piecewise Hessian: from a holding
        # surface's side Newton overshoots the steep sliding side) the minimum of D along it: the zero of the
        # increasing φ'(t) = ∇D(Q + t d)·d in (0, 1), by Newton on φ' (φ'' = dᵀ H d) kept inside its bracket
        t, slope0 = 1.0, grad0 * d0 + grad1 * d1
        q0, q1 = Q[0] + d0, Q[1] + d1
        g0, g1_ = _gradient(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, n, law1, law3, H, guess)
        slope = g0 * d0 + g1_ * d1
        if math.sqrt(g0 * g0 + g1_ * g1_) >= norm * (1.0 - 1e-4) and slope > 0.0:
            lo, hi = 0.0, 1.0
            for _ in range(200):
                curve = d0 * (H[0] * d0 + H[1] * d1) + d1 * (H[1] * d0 + H[2] * d1)
                if slope > 0.0:
                    hi = t
                else:
                    lo = t
                nxt = t - slope / curve if curve > 0.0 else 0.5 * (lo + hi)
                if not (lo < nxt < hi):
                    nxt = 0.5 * (lo + hi)
                if hi - lo <= 1e-12 * hi or nxt == t:  # the next Newton step refines
                    break
                t = nxt
                q0, q1 = Q[0] + t * d0, Q[1] + t * d1
                g0, g1_ = _gradient(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, n, law1, law3, H, guess)
                slope = g0 * d0 + g1_ * d1
                if abs(slope) <= 1e-10 * abs(slope0):
                    break
        Q[0], Q[1] = q0, q1
        grad0, grad1 = g0, g1_
        if abs(t * d0) + abs(t * d1) <= 1e-15 * (abs(Q[0]) + abs(Q[1])) + 1e-300:
            break
    slid1, slid3 = False, False
    for j in range(2):
        gj, law = (g1, law1) if j == 0 else (g3, law3)
        cx = Q[0] - gj * (u1[0] if j == 0 else u3x)
        cy = Q[1] - gj * (u1[1] if j == 0 else u3y)
        size = math.sqrt(cx * cx + cy * cy)
        speed = _speed(size, gj * h, n, law, guess[j])[0]
        if speed == 0.0:
            continue
        if j == 0:
            slid1 = True
        else:
            slid3 = True
        dx, dy = h * speed * cx / size, h * speed * cy / size
        u[0] += dx
        u[1] += dy
        if j == 0:
            u1[0] += dx
            u1[1] += dy
        V[0] += dx / h
        V[1] += dy / h
    return slid1, slid3


@njit(cache=True)
def _run(time, ag, vertical, L1, L3, law1, law3, damp, h, out_u, out_u1, flags, state):
    u, u1, v = state[0:2].copy(), state[2:4].copy(), state[4:6].copy()
    out_u[0], out_u1[0] = u, u1
    b, Q, guess, H, V = np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(3), np.zeros(2)
    for k in range(len(time) - 1):
        steps = max(1, int(round((time[k + 1] - time[k]) / h)))
        dt = (time[k + 1] - time[k]) / steps
        f1 = f3 = False
        for i in range(1, steps + 1):
            s = i / steps
            n = max(1.0 + (vertical[k] * (1 - s) + vertical[k + 1] * s) / G, 0.0)
            b[0] = v[0] - dt * (ag[k, 0] * (1 - s) + ag[k + 1, 0] * s)
            b[1] = v[1] - dt * (ag[k, 1] * (1 - s) + ag[k + 1, 1] * s)
            f1, f3 = step(u, u1, b, dt, n, L1, L3, law1, law3, damp, Q, guess, H, V)
            v[0], v[1] = V[0], V[1]
        out_u[k + 1] = u
        out_u1[k + 1] = u1
        flags[k + 1, 0], flags[k + 1, 1] = f1, f3


def integrate(time, ag, L1, L3, law1, law3, zeta, h, vertical=None, state=None):
    """The history at the samples ``time`` of a record ``ag`` (n, 2) (m/s², joined by straight lines) by
    steps of length about h: u, u_1 (n, 2) and which surfaces slide (n, 2). ``law_j`` = (slow, fast, rate,
    scale, ratio): μ̄_j = scale (fast - (fast - slow) exp(-rate ratio |u̇_j|)) (Coulomb: slow = fast);
    ``state`` (u, u_1, u̇) at time[0] (default: at rest, centred)."""
    ag = np.ascontiguousarray(np.asarray(ag, dtype=float).reshape(len(time), -1))
    if ag.shape[1] == 1:
        ag = np.column_stack([ag[:, 0], np.zeros(len(time))])
    vertical = np.zeros(len(time)) if vertical is None else np.asarray(vertical, dtype=float)
    out_u, out_u1 = np.zeros((len(time), 2)), np.zeros((len(time), 2))
    flags = np.zeros((len(time), 2), dtype=np.bool_)
    damp = 2.0 * zeta * math.sqrt(G / (L1 + L3))
    _run(np.asarray(time, dtype=float), ag, vertical, float(L1), float(L3), np.asarray(law1, dtype=float),
         np.asarray(law3, dtype=float), damp, float(h), out_u, out_u1, flags,
         np.zeros(6) if state is None else np.asarray(state, dtype=float).ravel())
    return out_u, out_u1, flags
