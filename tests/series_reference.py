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
it in closed form. A speed law's μ̄_j is taken at the surface's speed of the step before (explicit in
μ, implicit in everything else). The error is of first order in h (the stick-slip transitions), so the
tests compare at two steps and check that the difference from the library falls in proportion.
Compiled with Numba (a 20 s record at h = 1e-5 s takes about 10 s).
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
def step(u, u1, b, h, n, L1, L3, f1, f3, damp, Q):
    """One step: (u, u_1) overwritten; returns the new velocity V and which surfaces slide. b = v - h a_g,
    f_j = g μ̄_j (m/s²), damp = 2ζω. The step's force per unit mass Q = g n F/W minimises the dual of J,
    D(Q) = h |Q|² / 2 - b·Q + a Σ_j (|Q - g_j u_j| - r_j)_+² / (2 g_j h) (a = 1 + 2ζω h, g_j = g n / L_j,
    r_j = n f_j): strongly convex, piecewise twice differentiable, minimised by Newton from the last
    step's Q (overwritten) with an Armijo line search; surface j then moves by
    h v_j = (|c_j| - r_j)_+ c_j / (|c_j| g_j), c_j = Q - g_j u_j (it holds where |c_j| <= r_j)."""
    a = 1.0 + damp * h
    g1, g3 = n * G / L1, n * G / L3
    r1, r3 = n * f1, n * f3
    u3x, u3y = u[0] - u1[0], u[1] - u1[1]
    V = np.zeros(2)
    for _ in range(100):
        grad0, grad1 = h * Q[0] - b[0], h * Q[1] - b[1]
        H00, H01, H11 = h, 0.0, h
        for j in range(2):
            gj, rj = (g1, r1) if j == 0 else (g3, r3)
            cx = Q[0] - gj * (u1[0] if j == 0 else u3x)
            cy = Q[1] - gj * (u1[1] if j == 0 else u3y)
            size = math.sqrt(cx * cx + cy * cy)
            if size <= rj:
                continue
            k = a / (gj * h)
            e = (size - rj) / size
            grad0 += k * e * cx
            grad1 += k * e * cy
            ex, ey = cx / size, cy / size
            H00 += k * (ex * ex + e * (1.0 - ex * ex))
            H01 += k * (ex * ey - e * ex * ey)
            H11 += k * (ey * ey + e * (1.0 - ey * ey))
        det = H00 * H11 - H01 * H01
        d0 = -(H11 * grad0 - H01 * grad1) / det
        d1 = -(H00 * grad1 - H01 * grad0) / det
        # the dual is C¹ with a piecewise Hessian: a Newton step, halved until it lowers D enough (Armijo) or,
        # once D's changes are below its rounding, its gradient
        t = 1.0
        d_now = _dual(Q[0], Q[1], u1, u3x, u3y, b, h, a, g1, g3, r1, r3)
        slope = grad0 * d0 + grad1 * d1
        norm = math.sqrt(grad0 * grad0 + grad1 * grad1)
        while t > 1e-12:
            q0, q1 = Q[0] + t * d0, Q[1] + t * d1
            if _dual(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, r1, r3) <= d_now + 1e-4 * t * slope or \
                    _gradient_norm(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, r1, r3) < norm * (1.0 - 1e-4 * t):
                break
            t *= 0.5
        Q[0] += t * d0
        Q[1] += t * d1
        if abs(t * d0) + abs(t * d1) <= 1e-15 * (abs(Q[0]) + abs(Q[1])) + 1e-300:
            break
    slid = [False, False]
    for j in range(2):
        gj, rj = (g1, r1) if j == 0 else (g3, r3)
        cx = Q[0] - gj * (u1[0] if j == 0 else u3x)
        cy = Q[1] - gj * (u1[1] if j == 0 else u3y)
        size = math.sqrt(cx * cx + cy * cy)
        if size <= rj:
            continue
        slid[j] = True
        dx, dy = (size - rj) / size * cx / gj, (size - rj) / size * cy / gj  # h v_j
        u[0] += dx
        u[1] += dy
        if j == 0:
            u1[0] += dx
            u1[1] += dy
        V[0] += dx / h
        V[1] += dy / h
    return V, slid[0], slid[1]


@njit(cache=True)
def _gradient_norm(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, r1, r3):
    """|∇D(Q)|."""
    grad0, grad1 = h * q0 - b[0], h * q1 - b[1]
    for j in range(2):
        gj, rj = (g1, r1) if j == 0 else (g3, r3)
        cx = q0 - gj * (u1[0] if j == 0 else u3x)
        cy = q1 - gj * (u1[1] if j == 0 else u3y)
        size = math.sqrt(cx * cx + cy * cy)
        if size > rj:
            k = a / (gj * h) * (size - rj) / size
            grad0 += k * cx
            grad1 += k * cy
    return math.sqrt(grad0 * grad0 + grad1 * grad1)


@njit(cache=True)
def _dual(q0, q1, u1, u3x, u3y, b, h, a, g1, g3, r1, r3):
    """D(Q) (``step``)."""
    out = 0.5 * h * (q0 * q0 + q1 * q1) - b[0] * q0 - b[1] * q1
    for j in range(2):
        gj, rj = (g1, r1) if j == 0 else (g3, r3)
        cx = q0 - gj * (u1[0] if j == 0 else u3x)
        cy = q1 - gj * (u1[1] if j == 0 else u3y)
        excess = math.sqrt(cx * cx + cy * cy) - rj
        if excess > 0.0:
            out += a * excess * excess / (2.0 * gj * h)
    return out


@njit(cache=True)
def _run(time, ag, vertical, L1, L3, law1, law3, damp, h, out_u, out_u1, flags, state):
    u, u1, v = state[0:2].copy(), state[2:4].copy(), state[4:6].copy()
    out_u[0], out_u1[0] = u, u1
    s1, s3 = 0.0, 0.0
    b, Q = np.zeros(2), np.zeros(2)
    for k in range(len(time) - 1):
        steps = max(1, int(round((time[k + 1] - time[k]) / h)))
        dt = (time[k + 1] - time[k]) / steps
        f1 = f3 = False
        for i in range(1, steps + 1):
            s = i / steps
            n = max(1.0 + (vertical[k] * (1 - s) + vertical[k + 1] * s) / G, 0.0)
            b[0] = v[0] - dt * (ag[k, 0] * (1 - s) + ag[k + 1, 0] * s)
            b[1] = v[1] - dt * (ag[k, 1] * (1 - s) + ag[k + 1, 1] * s)
            m1 = G * law1[3] * _mu(law1[0], law1[1], law1[2], law1[4] * s1)  # g λ μ̄ at the last speed
            m3 = G * law3[3] * _mu(law3[0], law3[1], law3[2], law3[4] * s3)
            old1 = u1.copy()
            old3 = u - u1
            V, f1, f3 = step(u, u1, b, dt, n, L1, L3, m1, m3, damp, Q)
            v[0], v[1] = V[0], V[1]
            s1 = math.sqrt((u1[0] - old1[0]) ** 2 + (u1[1] - old1[1]) ** 2) / dt
            s3 = math.sqrt((u[0] - u1[0] - old3[0]) ** 2 + (u[1] - u1[1] - old3[1]) ** 2) / dt
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
