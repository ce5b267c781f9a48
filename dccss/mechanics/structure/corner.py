"""The articulated slider with both surfaces sliding: the equations and their implicit integration.

While both surfaces slide (``series``), the force F/W per unit normal force f is the same on both,
f = p_j + μ̄_j z_j with p_j = u_j / L_j, and each surface slides along its friction, u̇_j = s_j z_j
(s_j >= 0). Geometrically f is a corner of the two friction circles |f - p_j| = μ̄_j, and the stroke's
velocity u̇ = s_1 z_1 + s_3 z_3 lies in the cone of their directions. The state is described by
(u, u̇, δ, σ): δ the signed angle from z_3 to z_1, σ in [0, 1] where u̇ sits in that cone
(z_3 at the angle -σδ from u̇, z_1 at (1 - σ)δ), so that

    s_1 = |u̇| sin(σδ) / sin δ,   s_3 = |u̇| sin((1 - σ)δ) / sin δ,
    f = (u + L_1 μ̄_1 z_1 + L_3 μ̄_3 z_3) / L,   u_1 = L_1 (f - μ̄_1 z_1),

μ̄_j taken at the surface's speed s_j (its law), N/W and temperature. The flow u̇_j = s_j z_j, with
p_1 - p_3 = μ̄_3 z_3 - μ̄_1 z_1, gives two equations linear in (δ̇, σ̇):

    d/dt (μ̄_3 z_3 - μ̄_1 z_1) = s_1 z_1 / L_1 - s_3 z_3 / L_3,

written on u̇'s direction and its normal. Every coefficient is smooth through δ = 0 (the ratios
sin(σδ) / sin δ as sinc ratios). Where δ = 0 and the friction is Coulomb's, the first equation loses
σ̇ and becomes the algebraic condition s_1 / L_1 = s_3 / L_3 (the proportional split); near δ = 0, or
where a law's μ hardly changes with the speed, σ relaxes to that split within a time of order
δ² L / |u̇| (or L dμ̄/ds): the system is stiff, of index 1 at the collinear state. It is therefore
integrated as M(y) ẏ = F(y, t) by the three-stage Radau IIA method (order 5, stiffly accurate; Hairer
and Wanner's RADAU5 error estimate and step control, simplified Newton with a Jacobian by finite
differences), which takes both the stiff and the algebraic case in its stride. The phase ends where
|u̇| falls to REST_SPEED (a stop) or σ reaches 0 (surface 1 stops: s_1 = 0) or 1 (surface 3 stops),
located on the collocation polynomial and stepped to exactly.
"""

from __future__ import annotations

import math

import numpy as np

from .. import scalar
from ..friction import FACTOR, RATIO, WEIGHT, surface_mu, surface_mu_slopes

#: the state's size (u, u̇, δ, σ) and the stages
N, S = 6, 3
SQ6 = math.sqrt(6.0)
#: Radau IIA's nodes, the inverse of its matrix A, RADAU5's error weights and γ = 1 / its real eigenvalue
C = np.array([(4.0 - SQ6) / 10.0, (4.0 + SQ6) / 10.0, 1.0])
A = np.array([[(88.0 - 7.0 * SQ6) / 360.0, (296.0 - 169.0 * SQ6) / 1800.0, (-2.0 + 3.0 * SQ6) / 225.0],
              [(296.0 + 169.0 * SQ6) / 1800.0, (88.0 + 7.0 * SQ6) / 360.0, (-2.0 - 3.0 * SQ6) / 225.0],
              [(16.0 - SQ6) / 36.0, (16.0 + SQ6) / 36.0, 1.0 / 9.0]])
W = np.linalg.inv(A)


def _transform():
    """T with T^-1 W T = [[γ, 0, 0], [0, α, β], [0, -β, α]] (W's real and complex eigenvectors), T^-1, and
    that matrix: the simplified Newton iteration splits into a real N x N system and a real 2N x 2N one."""
    values, vectors = np.linalg.eig(W)
    real = int(np.argmin(np.abs(values.imag)))
    other = [k for k in range(3) if k != real and values[k].imag > 0][0]
    T = np.column_stack([vectors[:, real].real, vectors[:, other].real, vectors[:, other].imag])
    TI = np.linalg.inv(T)
    return T, TI, TI @ W @ T


T, TI, WT = _transform()
DD = np.array([-(13.0 + 7.0 * SQ6) / 3.0, (-13.0 + 7.0 * SQ6) / 3.0, -1.0 / 3.0])
GAMMA = 1.0 / ((6.0 + 81.0 ** (1.0 / 3.0) - 9.0 ** (1.0 / 3.0)) / 30.0)
#: Newton: at most this many iterations a step
NEWTON = 7
#: the entries of a phase's parameters p (``system``): the pendulums L_1 and L_3, g, 2ζω, the ground's
#: acceleration b0 + b1 t (from the phase's origin), N/W = n0 + n1 t and the surfaces' temperatures (°C)
LENGTH1, LENGTH3, GRAVITY, DAMPING, B0X, B0Y, B1X, B1Y, N0, N1, TEMPERATURE1, TEMPERATURE3 = range(12)
PARAMETERS = 12
#: the slots of ``workspace`` its callers use: F and M's (δ, σ) block (scratch), the last accepted step's start
#: and stages, its memo and a trial step's stages kept
RHS, MASS, LAST, PREVIOUS, MEMO, KEPT = 0, 1, 14, 15, 16, 18
#: the memo's entries: the last accepted step's length, whether the next step goes on from it (1) or starts
#: afresh (0), its error, Newton's convergence factor
SPAN, GOES_ON, ERROR, CONTRACTION = range(4)


@scalar.jit
def sincs(x, s, c):
    """sin x / x (1 at 0) and its derivative, s = sin x and c = cos x given."""
    if abs(x) < 1e-4:
        x2 = x * x
        return 1.0 - x2 / 6.0 + x2 * x2 / 120.0, -x / 3.0 + x * x2 / 30.0
    return s / x, (x * c - s) / (x * x)


@scalar.jit
def coefficient(r, s, n, T):
    """A surface's force-level coefficient μ̄ = weight λ μ(ratio s) at its hinge speed s = |u̇_j| (m/s), N/W n
    and temperature T (°C) (its law's row r: weight R^j / L_j, ratio R^j / L_j), and dμ̄/ds, dμ̄/dn."""
    scale = r[WEIGHT] * r[FACTOR]
    mu = surface_mu(r, r[RATIO] * s, n, T)
    ds, dn = surface_mu_slopes(r, r[RATIO] * s, n, T)
    return scale * mu, scale * r[RATIO] * ds, scale * dn


@scalar.jit
def shape(y, p, rows, t):
    """What the state y = (u, u̇, δ, σ) at t says: (n, z1x, z1y, z3x, z3y, s1, s3, μ̄1, μ̄3, fx, fy): N/W, the
    surfaces' friction directions and hinge speeds, their coefficients and f = F/W / (N/W)."""
    L1, L3 = p[LENGTH1], p[LENGTH3]
    n = max(p[N0] + p[N1] * t, 0.0)
    sp = math.sqrt(y[2] * y[2] + y[3] * y[3])
    ex, ey = y[2] / sp, y[3] / sp
    delta, sigma = y[4], y[5]
    a1, a3 = sigma * delta, (1.0 - sigma) * delta
    sa1, ca1, sa3, ca3 = math.sin(a1), math.cos(a1), math.sin(a3), math.cos(a3)
    z3x, z3y = ex * ca1 + ey * sa1, ey * ca1 - ex * sa1
    z1x, z1y = ex * ca3 - ey * sa3, ey * ca3 + ex * sa3
    sd = sincs(delta, sa1 * ca3 + ca1 * sa3, ca1 * ca3 - sa1 * sa3)[0]
    s1 = sp * sigma * sincs(a1, sa1, ca1)[0] / sd
    s3 = sp * (1.0 - sigma) * sincs(a3, sa3, ca3)[0] / sd
    m1 = coefficient(rows[0], s1, n, p[TEMPERATURE1])[0]
    m3 = coefficient(rows[1], s3, n, p[TEMPERATURE3])[0]
    L = L1 + L3
    fx = (y[0] + L1 * m1 * z1x + L3 * m3 * z3x) / L
    fy = (y[1] + L1 * m1 * z1y + L3 * m3 * z3y) / L
    return n, z1x, z1y, z3x, z3y, s1, s3, m1, m3, fx, fy


@scalar.jit
def system(t, y, p, rows, F, M):
    """F(y, t) (6) and the 2 x 2 block M of (δ, σ) (row-major, 4) of M(y) ẏ = F at t (from the phase's
    origin); p = (L1, L3, g, 2ζω, b0x, b0y, b1x, b1y, n0, n1, T1, T3), the ground's acceleration
    b0 + b1 t and N/W = n0 + n1 t (0 where negative); ``rows`` the surfaces' laws (1, 3)."""
    L1, L3, g, damp = p[LENGTH1], p[LENGTH3], p[GRAVITY], p[DAMPING]
    raw = p[N0] + p[N1] * t
    n = max(raw, 0.0)
    dn = p[N1] if raw > 0.0 else 0.0
    sp = math.sqrt(y[2] * y[2] + y[3] * y[3])
    ex, ey = y[2] / sp, y[3] / sp
    qx, qy = -ey, ex
    delta, sigma = y[4], y[5]
    # z3 at the angle α3 = -σδ from e, z1 at α1 = (1 - σ)δ: two angles' sines and cosines in all
    a1, a3 = sigma * delta, (1.0 - sigma) * delta
    sa1, ca1, sa3, ca3 = math.sin(a1), math.cos(a1), math.sin(a3), math.cos(a3)
    c3, s3a, c1, s1a = ca1, -sa1, ca3, sa3
    z3x, z3y = ex * c3 - ey * s3a, ey * c3 + ex * s3a
    z1x, z1y = ex * c1 - ey * s1a, ey * c1 + ex * s1a
    sd, dsd = sincs(delta, sa1 * ca3 + ca1 * sa3, ca1 * ca3 - sa1 * sa3)  # δ = α1 + α3
    k1, dk1 = sincs(a1, sa1, ca1)
    k3, dk3 = sincs(a3, sa3, ca3)
    q1, q3 = k1 / sd, k3 / sd
    s1, s3 = sp * sigma * q1, sp * (1.0 - sigma) * q3
    m1, m1s, m1n = coefficient(rows[0], s1, n, p[TEMPERATURE1])
    m3, m3s, m3n = coefficient(rows[1], s3, n, p[TEMPERATURE3])
    L = L1 + L3
    fx = (y[0] + L1 * m1 * z1x + L3 * m3 * z3x) / L
    fy = (y[1] + L1 * m1 * z1y + L3 * m3 * z3y) / L
    accx = -(p[B0X] + p[B1X] * t) - damp * y[2] - g * n * fx
    accy = -(p[B0Y] + p[B1Y] * t) - damp * y[3] - g * n * fy
    dsp = ex * accx + ey * accy  # d|u̇|/dt
    dphi = (qx * accx + qy * accy) / sp  # how fast u̇ turns
    # the hinge speeds' derivatives: ṡ_j = (∂s_j/∂|u̇|) d|u̇|/dt + (∂s_j/∂σ) σ̇ + (∂s_j/∂δ) δ̇
    d1sig = sp * (q1 + a1 * dk1 / sd)
    d3sig = -sp * (q3 + a3 * dk3 / sd)
    d1del = sp * sigma * (sigma * dk1 * sd - k1 * dsd) / (sd * sd)
    d3del = sp * (1.0 - sigma) * ((1.0 - sigma) * dk3 * sd - k3 * dsd) / (sd * sd)
    # d/dt (μ̄3 z3 - μ̄1 z1) - (s1 z1 / L1 - s3 z3 / L3) = A_σ σ̇ + A_δ δ̇ + R0 = 0, written on e = u̇ / |u̇|
    # and q (e turned by 90 degrees), where z3 = (cos α3, sin α3), z1 = (cos α1, sin α1), z⊥ = (-sin α, cos α):
    # no cancellation at δ = 0, where the terms in dφ/dt vanish exactly
    r3 = m3s * (1.0 - sigma) * q3 * dsp + m3n * dn + s3 / L3
    r1 = m1s * sigma * q1 * dsp + m1n * dn + s1 / L1
    F[0], F[1], F[2], F[3] = y[2], y[3], accx, accy
    F[4] = -(r3 * c3 - r1 * c1 + dphi * (m1 * s1a - m3 * s3a))
    F[5] = -(r3 * s3a - r1 * s1a + dphi * (m3 * c3 - m1 * c1))
    M[0] = m3s * d3del * c3 + m3 * sigma * s3a - m1s * d1del * c1 + m1 * (1.0 - sigma) * s1a
    M[1] = m3s * d3sig * c3 + m3 * delta * s3a - m1s * d1sig * c1 - m1 * delta * s1a
    M[2] = m3s * d3del * s3a - m3 * sigma * c3 - m1s * d1del * s1a - m1 * (1.0 - sigma) * c1
    M[3] = m3s * d3sig * s3a - m3 * delta * c3 - m1s * d1sig * s1a + m1 * delta * c1


@scalar.jit
def _residual(t, y, k, p, rows, F, M, out, at):
    """out[at:at + N] = M(y) k - F(y, t)."""
    system(t, y, p, rows, F, M)
    for i in range(4):
        out[at + i] = k[i] - F[i]
    out[at + 4] = M[0] * k[4] + M[1] * k[5] - F[4]
    out[at + 5] = M[2] * k[4] + M[3] * k[5] - F[5]


@scalar.jit
def lu(a, n, piv):
    """LU factors of the n x n a (row-major, in place) with partial pivoting; False where singular."""
    for c in range(n):
        best, p = abs(a[c * n + c]), c
        for r in range(c + 1, n):
            if abs(a[r * n + c]) > best:
                best, p = abs(a[r * n + c]), r
        piv[c] = p
        if best == 0.0:
            return False
        if p != c:
            for j in range(n):
                a[c * n + j], a[p * n + j] = a[p * n + j], a[c * n + j]
        inverse = 1.0 / a[c * n + c]
        for r in range(c + 1, n):
            f = a[r * n + c] * inverse
            a[r * n + c] = f
            if f != 0.0:
                for j in range(c + 1, n):
                    a[r * n + j] -= f * a[c * n + j]
    return True


@scalar.jit
def lu_solve(a, n, piv, b):
    """Solve with ``lu``'s factors, b overwritten."""
    for c in range(n):
        p = piv[c]
        if p != c:
            b[c], b[p] = b[p], b[c]
    for r in range(n):
        acc = b[r]
        for j in range(r):
            acc -= a[r * n + j] * b[j]
        b[r] = acc
    for r in range(n - 1, -1, -1):
        acc = b[r]
        for j in range(r + 1, n):
            acc -= a[r * n + j] * b[j]
        b[r] = acc / a[r * n + r]


@scalar.jit
def _norm(x, at, scale):
    """The root mean square of x[at:at + N] / scale."""
    acc = 0.0
    for i in range(N):
        e = x[at + i] / scale[i]
        acc += e * e
    return math.sqrt(acc / N)


@scalar.jit
def _jacobian(t0, y0, p, rows, k0, F, Mb, R, J, y):
    """J = d(F - M k0)/dy at (t0, y0) by forward differences (N x N, row-major)."""
    _residual(t0, y0, k0, p, rows, F, Mb, R, 0)
    for j in range(N):
        step = math.sqrt(2.220446049250313e-16 * max(1e-5, abs(y0[j])))
        for i in range(N):
            y[i] = y0[i]
        y[j] += step
        _residual(t0, y, k0, p, rows, F, Mb, R, N)
        for i in range(N):
            J[i * N + j] = -(R[N + i] - R[i]) / step


@scalar.jit
def _mass(Mb, i, j):
    """Entry (i, j) of M (the identity on u and u̇, Mb on (δ, σ))."""
    if i < 4:
        return 1.0 if i == j else 0.0
    if j < 4:
        return 0.0
    return Mb[(i - 4) * 2 + (j - 4)]


@scalar.jit
def _factor(h, J, M0, E1, piv1, E2, piv2):
    """The LU factors of the transformed Newton matrices: E1 = γ/h M0 - J (N x N) and
    E2 = [[α/h M0 - J, β/h M0], [-β/h M0, α/h M0 - J]] (2N x 2N); False where one is singular."""
    g, a, b = WT[0, 0] / h, WT[1, 1] / h, WT[1, 2] / h
    n2 = 2 * N
    for i in range(N):
        for j in range(N):
            m = _mass(M0, i, j)
            E1[i * N + j] = g * m - J[i * N + j]
            E2[i * n2 + j] = a * m - J[i * N + j]
            E2[(i + N) * n2 + j + N] = a * m - J[i * N + j]
            E2[i * n2 + j + N] = b * m
            E2[(i + N) * n2 + j] = -b * m
    return lu(E1, N, piv1) and lu(E2, n2, piv2)


@scalar.jit
def radau_step(t0, y0, h, p, rows, k0, rtol, atol, first, refresh, Z, work, guessed=False):
    """One Radau IIA step of length h from (t0, y0) (``system``), k0 an estimate of ẏ there: (status, error
    norm, Newton iterations, the Newton's contraction θ); status 0 converged (the stages' increments in Z
    (3 N), the new state y0 + Z[2N:]), 1 Newton failed. Newton starts from Z where ``guessed`` (the last
    step's collocation polynomial extrapolated), else from the stages along k0. ``refresh`` 2: a new
    Jacobian, else the last step's; the Newton matrices are factored afresh with M at y0 (M changes fast
    where the system is stiff: keeping their factors, as RADAU5 does for a constant M, made more Newton
    iterations and rejected steps, 20 % more time in all). ``work`` holds the Jacobian, the factors and
    scratch arrays (``workspace``)."""
    F, Mb, R, J, M0, E1, piv1, E2, piv2, y, scale, kk, cont, V, _, _, memo, F0, _ = work
    fnewt = max(10.0 * 2.220446049250313e-16 / rtol, min(0.03, math.sqrt(rtol)))
    for i in range(N):
        scale[i] = atol + rtol * abs(y0[i])
    if refresh >= 2:
        _jacobian(t0, y0, p, rows, k0, F, Mb, R, J, y)
    system(t0, y0, p, rows, F0, M0)
    if not _factor(h, J, M0, E1, piv1, E2, piv2):
        return 1, 0.0, 0, 1.0
    if not guessed:
        for i in range(S):
            for j in range(N):
                Z[i * N + j] = C[i] * h * k0[j]
    # RADAU5's Newton: converged where the contraction's bound θ / (1 - θ) times the last increment is below
    # fnewt, θ from this step's iterations, on the first from the steps before (its caller's memo)
    previous, theta, ratio, iterations = 0.0, 0.0, 0.0, 0
    faccon = memo[CONTRACTION]
    converged = False
    while iterations < NEWTON:
        iterations += 1
        for i in range(S):
            for j in range(N):
                y[j] = y0[j] + Z[i * N + j]
                acc = 0.0
                for m in range(S):
                    acc += W[i, m] * Z[m * N + j]
                kk[j] = acc / h
            _residual(t0 + C[i] * h, y, kk, p, rows, F, Mb, R, i * N)
        # transformed: V = (T^-1 x I)(-R), E1 V1 = ..., E2 (V2, V3) = ...
        for j in range(N):
            for i in range(S):
                V[i * N + j] = -(TI[i, 0] * R[j] + TI[i, 1] * R[N + j] + TI[i, 2] * R[2 * N + j])
        for j in range(N):
            cont[j] = V[j]
        lu_solve(E1, N, piv1, cont)
        for j in range(N):
            V[j] = cont[j]
        lu_solve(E2, 2 * N, piv2, V[N:])
        for j in range(N):  # back: dZ = (T x I) V
            for i in range(S):
                R[i * N + j] = T[i, 0] * V[j] + T[i, 1] * V[N + j] + T[i, 2] * V[2 * N + j]
        norm = 0.0
        for i in range(S):
            norm = max(norm, _norm(R, i * N, scale))
        for i in range(S * N):
            Z[i] += R[i]
        if not (norm == norm):
            return 1, 0.0, iterations, 1.0
        if iterations > 1:
            quotient = norm / previous
            theta = quotient if iterations == 2 else math.sqrt(quotient * ratio)
            ratio = quotient
            if theta >= 0.99:
                return 1, 0.0, iterations, theta
            faccon = theta / (1.0 - theta)
        previous = max(norm, 2.220446049250313e-16)
        if faccon * norm <= fnewt and (iterations > 1 or norm <= 1e-3 * fnewt):
            converged = True
            break
    memo[CONTRACTION] = faccon
    if not converged:
        return 1, 0.0, iterations, theta
    # RADAU5's error estimate: (γ/h M0 - J)^-1 (F(y0) + M0 (dd Z) / h), F(y0) kept from the step's start
    _estimate(F0, M0, Z, h, cont)
    lu_solve(E1, N, piv1, cont)
    for i in range(N):
        scale[i] = atol + rtol * max(abs(y0[i]), abs(y0[i] + Z[2 * N + i]))
    error = max(_norm(cont, 0, scale), 1e-10)
    if error >= 1.0 and first:
        for i in range(N):
            y[i] = y0[i] + cont[i]
        system(t0, y, p, rows, F, Mb)
        _estimate(F, M0, Z, h, cont)
        lu_solve(E1, N, piv1, cont)
        error = max(_norm(cont, 0, scale), 1e-10)
    return 0, error, iterations, theta


@scalar.jit
def _estimate(F, Mb, Z, h, cont):
    """cont = F + M (DD·Z) / h."""
    for i in range(N):
        cont[i] = (DD[0] * Z[i] + DD[1] * Z[N + i] + DD[2] * Z[2 * N + i]) / h
    m4 = Mb[0] * cont[4] + Mb[1] * cont[5]
    m5 = Mb[2] * cont[4] + Mb[3] * cont[5]
    cont[4], cont[5] = m4, m5
    for i in range(N):
        cont[i] += F[i]


def workspace():
    """The arrays of ``radau_step``: F, M, residuals, the Jacobian, M0, the two factors and their pivots,
    scratch; then the last accepted step's start and stages and (its length, whether the next step continues
    it, its error, Newton's convergence factor) (its caller's, for the next step's guess, Jacobian, length and
    Newton); F at the step's start; a trial step's stages, kept (its caller's, while it looks for an event)."""
    size = S * N
    memo = np.array([0.0, 0.0, 0.0, 1.0])
    return (np.zeros(N), np.zeros(4), np.zeros(size), np.zeros(N * N), np.zeros(4), np.zeros(N * N),
            np.zeros(N, dtype=np.int64), np.zeros(4 * N * N), np.zeros(2 * N, dtype=np.int64), np.zeros(N),
            np.zeros(N), np.zeros(N), np.zeros(N), np.zeros(size), np.zeros(N), np.zeros(size), memo, np.zeros(N),
            np.zeros(size))


@scalar.jit
def weights(theta):
    """The collocation polynomial's Lagrange weights of the stages at theta (the step's fraction; beyond 1:
    extrapolated)."""
    c1, c2 = C[0], C[1]
    return (theta * (theta - c2) * (theta - 1.0) / (c1 * (c1 - c2) * (c1 - 1.0)),
            theta * (theta - c1) * (theta - 1.0) / (c2 * (c2 - c1) * (c2 - 1.0)),
            theta * (theta - c1) * (theta - c2) / ((1.0 - c1) * (1.0 - c2)))


@scalar.jit
def dense(y0, Z, theta, i):
    """Component i of the collocation polynomial at theta in [0, 1] of the step (y0 and the stages' Z)."""
    l1, l2, l3 = weights(theta)
    return y0[i] + l1 * Z[i] + l2 * Z[N + i] + l3 * Z[2 * N + i]


@scalar.jit
def turning(Z, i):
    """The fractions of the step where component i of the collocation polynomial turns: the roots of its
    derivative, a quadratic (each weight is θ (θ - a)(θ - b) over a constant); -1 where there is none."""
    c1, c2 = C[0], C[1]
    w1 = Z[i] / (c1 * (c1 - c2) * (c1 - 1.0))
    w2 = Z[N + i] / (c2 * (c2 - c1) * (c2 - 1.0))
    w3 = Z[2 * N + i] / ((1.0 - c1) * (1.0 - c2))
    a = 3.0 * (w1 + w2 + w3)
    b = -2.0 * (w1 * (c2 + 1.0) + w2 * (c1 + 1.0) + w3 * (c1 + c2))
    c = w1 * c2 + w2 * c1 + w3 * c1 * c2
    if a == 0.0:
        return (-c / b if b != 0.0 else -1.0), -1.0
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return -1.0, -1.0
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    return q / a, (c / q if q != 0.0 else -1.0)


@scalar.jit
def speed(y0, Z, theta):
    """|u̇| on the collocation polynomial at theta."""
    l1, l2, l3 = weights(theta)
    vx = y0[2] + l1 * Z[2] + l2 * Z[N + 2] + l3 * Z[2 * N + 2]
    vy = y0[3] + l1 * Z[3] + l2 * Z[N + 3] + l3 * Z[2 * N + 3]
    return math.sqrt(vx * vx + vy * vy), vx, vy


@scalar.jit
def consistent(y, p, rows, t, F, M):
    """y[5] = σ made consistent where σ relaxes within a nanosecond (its column of M nearly zero: the surfaces'
    split decided by the algebraic condition, Coulomb friction along one line or a law that no longer changes
    with the speed): the root in [0, 1] of the first equation, by bisection. Elsewhere σ is kept (its
    relaxation, a real transient, is integrated). 0, or where the first equation has the same sign at σ = 0 and
    1 (no split of the sliding balances the hinge; σ kept), the side its root lies on (it is linear in σ at
    δ = 0): -1 below 0 (surface 1 would slide backwards: it holds), 1 above 1 (surface 3 holds)."""
    sigma = y[5]
    system(t, y, p, rows, F, M)
    f = F[4]
    step = 1e-6 if sigma < 0.5 else -1e-6
    y[5] = sigma + step
    system(t, y, p, rows, F, M)
    slope = (F[4] - f) / step
    y[5] = sigma
    system(t, y, p, rows, F, M)
    if slope == 0.0 or abs(M[1] / slope) > 1e-9:
        return 0
    lo, hi = 0.0, 1.0
    y[5] = hi
    system(t, y, p, rows, F, M)
    high = F[4]
    y[5] = lo
    system(t, y, p, rows, F, M)
    low = F[4]
    if low * high > 0.0:
        y[5] = sigma
        return -1 if abs(low) < abs(high) else 1
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        y[5] = mid
        system(t, y, p, rows, F, M)
        if (F[4] < 0.0) == (low < 0.0):
            lo, low = mid, F[4]
        else:
            hi = mid
    y[5] = 0.5 * (lo + hi)
    return 0
