"""Independent check of the constraint equations and Jacobians against the paper.

Bianco, Monti & Belfiore (Buildings 2021, 11, 50): Section 3.1 (compliant sliding, Eqs. 5-30)
and Section 5 (stick-slip, Eqs. 31-48). The printed formulas are transcribed literally below as
plain numpy functions of the scalars R_x^i, R_y^i, theta^i, A, B, x-bar, y-bar, alpha, named
after their equation numbers; they are NOT derived from the package code. Known errata are
corrected where marked "ERRATUM". The package's analytic Jacobians are also compared with
central finite differences of its residuals, including geometries with unequal radii and caps
(for which the paper's single pad half-width A does not exist).

Package conventions used to feed the printed formulas: the contact data of a corner with side s
(-1 for A, C; +1 for B, D) on a plate with sign v (+1 RB1, -1 RB3) are a plate-frame point
x-bar + i y-bar and the plate-frame normal (-s sin alpha, v cos alpha) (complex numbers).
"""

from __future__ import annotations

import numpy as np
import pytest
from constraint_sets import Compliant, Slipping, Sticking, contact_point, diagonal
from numpy import cos, sin

from dccss.mechanics import compiled, models
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.kinematics import all_corners, contact_angle, frames
from dccss.paper.prototypes import DFP1, DFP2

N_CASES = 20
TOL = 1e-12
FD_STEP = 1e-6
FD_RTOL = 1e-7

SIDE = {"A": -1.0, "B": 1.0, "C": -1.0, "D": 1.0}
PLATE_SIGN = {"A": 1.0, "B": 1.0, "C": -1.0, "D": -1.0}

PRINTED = {"DFP1": DFP1, "DFP2": DFP2}  # equal radii and caps: A = A1 = A3 (Eq. 12)
_COMMON = dict(hr1=0.02, hr3=0.02, hmin1=0.10, hmin3=0.10, tr1=0.0258, tr3=0.0258)
UNEQUAL = {
    "R1<R3": Geometry.from_degrees(R1=1.0, R3=2.5, alpha1=21, alpha3=15, h2=0.12, alpha21=10,
                                   alpha23=6, **_COMMON),
    "R1>R3": Geometry.from_degrees(R1=3.0, R3=1.2, alpha1=12, alpha3=24, h2=0.18, alpha21=3,
                                   alpha23=13, **_COMMON),
}
ALL_GEOMETRIES = {**PRINTED, **UNEQUAL}


# --------------------------------------------------------------------------------------------
# Random configurations and contact data
# --------------------------------------------------------------------------------------------
def random_q(rng):
    """A random q (Eq. 4) with rotated plates and pad."""
    return np.array([
        rng.uniform(-0.3, 0.3), rng.uniform(-0.05, 0.05), rng.uniform(-0.3, 0.3),  # RB1
        rng.uniform(-0.3, 0.3), rng.uniform(0.5, 1.5), rng.uniform(-0.5, 0.5),     # RB2
        rng.uniform(-0.3, 0.3), rng.uniform(1.5, 2.5), rng.uniform(-0.3, 0.3),     # RB3
    ])


def normal(name, alpha):
    """Plate-frame unit normal (-s sin alpha, v cos alpha) of corner ``name``, as a complex."""
    return complex(-SIDE[name] * sin(alpha), PLATE_SIGN[name] * cos(alpha))


def random_contacts(rng, names):
    """Random contact angles (negative ones included) and arbitrary plate-frame points."""
    alphas = rng.uniform(-0.5, 0.5, len(names))
    points = [complex(rng.uniform(-0.3, 0.3), rng.uniform(-0.1, 1.5)) for _ in names]
    return alphas, points, [normal(n, a) for n, a in zip(names, alphas, strict=True)]


def cases(seed):
    rng = np.random.default_rng(seed)
    return [(random_q(rng), rng) for _ in range(N_CASES)]


def pad_half_width(g):
    assert g.A1 == pytest.approx(g.A3, abs=1e-15), "the printed forms need A1 = A3 (Eq. 12)"
    return g.A1, g.B


def central_differences(residual, q, columns):
    """Central finite differences of residual(q) over the given columns of q."""
    J = []
    for k in columns:
        dq = np.zeros_like(q)
        dq[k] = FD_STEP
        J.append((residual(q + dq) - residual(q - dq)) / (2 * FD_STEP))
    return np.stack(J, axis=-1)


def assert_fd(J, J_fd):
    scale = max(1.0, np.abs(J_fd).max())
    np.testing.assert_allclose(J, J_fd, rtol=0, atol=FD_RTOL * scale)


# --------------------------------------------------------------------------------------------
# Section 3.1, compliant sliding: Eqs. 8-11 (rows 4-7 of Eq. 5), transcribed as printed
# --------------------------------------------------------------------------------------------
def eq8(q, A, B, xb, yb, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 - A * cos(t2) + B * sin(t2) - Rx1 - xb * cos(t1) + yb * sin(t1))
            * (sin(a) * cos(t1) - cos(a) * sin(t1))
            + (Ry2 - A * sin(t2) - B * cos(t2) - Ry1 - xb * sin(t1) - yb * cos(t1))
            * (sin(a) * sin(t1) + cos(a) * cos(t1)))


def eq9(q, A, B, xb, yb, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 + A * cos(t2) + B * sin(t2) - Rx1 - xb * cos(t1) + yb * sin(t1))
            * (-sin(a) * cos(t1) - cos(a) * sin(t1))
            + (Ry2 + A * sin(t2) - B * cos(t2) - Ry1 - xb * sin(t1) - yb * cos(t1))
            * (-sin(a) * sin(t1) + cos(a) * cos(t1)))


def eq10(q, A, B, xb, yb, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 - A * cos(t2) - B * sin(t2) - Rx3 - xb * cos(t3) + yb * sin(t3))
            * (sin(a) * cos(t3) + cos(a) * sin(t3))
            + (Ry2 - A * sin(t2) + B * cos(t2) - Ry3 - xb * sin(t3) - yb * cos(t3))
            * (sin(a) * sin(t3) - cos(a) * cos(t3)))


def eq11(q, A, B, xb, yb, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 + A * cos(t2) - B * sin(t2) - Rx3 - xb * cos(t3) + yb * sin(t3))
            * (-sin(a) * cos(t3) + cos(a) * sin(t3))
            + (Ry2 + A * sin(t2) + B * cos(t2) - Ry3 - xb * sin(t3) - yb * cos(t3))
            * (-sin(a) * sin(t3) - cos(a) * cos(t3)))


# Jacobian, Eqs. 16-28 (as printed; Eqs. 18, 21, 25, 28 have no x-bar, y-bar terms: they cancel)
def eq17(t1, a):
    """[c41, c42, c44, c45]."""
    return np.array([[cos(a), -sin(a)], [-sin(a), -cos(a)], [-cos(a), sin(a)], [sin(a), cos(a)]]) \
        @ [sin(t1), cos(t1)]


def eq18(q, A, B, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 - A * cos(t2) + B * sin(t2) - Rx1) * (-sin(a) * sin(t1) - cos(a) * cos(t1))
            + (Ry2 - A * sin(t2) - B * cos(t2) - Ry1) * (sin(a) * cos(t1) - cos(a) * sin(t1)))


def eq19(q, A, B, a):
    t1, t2 = q[2], q[5]
    return ((A * sin(t2) + B * cos(t2)) * (sin(a) * cos(t1) - cos(a) * sin(t1))
            + (-A * cos(t2) + B * sin(t2)) * (sin(a) * sin(t1) + cos(a) * cos(t1)))


def eq20(t1, a):
    """[c51, c52, c54, c55]."""
    return np.array([[cos(a), sin(a)], [sin(a), -cos(a)], [-cos(a), -sin(a)], [-sin(a), cos(a)]]) \
        @ [sin(t1), cos(t1)]


def eq21(q, A, B, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 + A * cos(t2) + B * sin(t2) - Rx1) * (sin(a) * sin(t1) - cos(a) * cos(t1))
            + (Ry2 + A * sin(t2) - B * cos(t2) - Ry1) * (-sin(a) * cos(t1) - cos(a) * sin(t1)))


def eq22(q, A, B, a):
    t1, t2 = q[2], q[5]
    return ((-A * sin(t2) + B * cos(t2)) * (-sin(a) * cos(t1) - cos(a) * sin(t1))
            + (A * cos(t2) + B * sin(t2)) * (-sin(a) * sin(t1) + cos(a) * cos(t1)))


def eq23(t3, a):
    """[c64, c65, c67, c68]."""
    return np.array([[cos(a), sin(a)], [sin(a), -cos(a)], [-cos(a), -sin(a)], [-sin(a), cos(a)]]) \
        @ [sin(t3), cos(t3)]


def eq24(q, A, B, a):
    t2, t3 = q[5], q[8]
    return ((A * sin(t2) - B * cos(t2)) * (sin(a) * cos(t3) + cos(a) * sin(t3))
            - (A * cos(t2) + B * sin(t2)) * (sin(a) * sin(t3) - cos(a) * cos(t3)))


def eq25(q, A, B, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 - A * cos(t2) - B * sin(t2) - Rx3) * (-sin(a) * sin(t3) + cos(a) * cos(t3))
            + (Ry2 - A * sin(t2) + B * cos(t2) - Ry3) * (sin(a) * cos(t3) + cos(a) * sin(t3)))


def eq26(t3, a):
    """[c74, c75, c77, c78]."""
    return np.array([[cos(a), -sin(a)], [-sin(a), -cos(a)], [-cos(a), sin(a)], [sin(a), cos(a)]]) \
        @ [sin(t3), cos(t3)]


def eq27(q, A, B, a):
    t2, t3 = q[5], q[8]
    return (-(A * sin(t2) + B * cos(t2)) * (-sin(a) * cos(t3) + cos(a) * sin(t3))
            - (A * cos(t2) - B * sin(t2)) * (sin(a) * sin(t3) + cos(a) * cos(t3)))


def eq28(q, A, B, a):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 + A * cos(t2) - B * sin(t2) - Rx3) * (sin(a) * sin(t3) + cos(a) * cos(t3))
            + (Ry2 + A * sin(t2) + B * cos(t2) - Ry3) * (-sin(a) * cos(t3) + cos(a) * sin(t3)))


def compliant_jacobian_printed(q, A, B, alphas):
    """C_q (9 x 9) assembled from Eqs. 16-28; all other entries null."""
    aA, aB, aC, aD = alphas
    t1, t3 = q[2], q[8]
    C = np.zeros((9, 9))

    def c(i, j, value):  # 1-based indices, as in the paper
        C[i - 1, j - 1] = value

    for i, j in ((1, 1), (2, 2), (3, 3), (8, 7), (9, 9)):  # Eq. 16
        c(i, j, 1.0)
    for j, v in zip((1, 2, 4, 5), eq17(t1, aA), strict=True):
        c(4, j, v)
    c(4, 3, eq18(q, A, B, aA))
    c(4, 6, eq19(q, A, B, aA))
    for j, v in zip((1, 2, 4, 5), eq20(t1, aB), strict=True):
        c(5, j, v)
    c(5, 3, eq21(q, A, B, aB))
    c(5, 6, eq22(q, A, B, aB))
    for j, v in zip((4, 5, 7, 8), eq23(t3, aC), strict=True):
        c(6, j, v)
    c(6, 6, eq24(q, A, B, aC))
    c(6, 9, eq25(q, A, B, aC))
    for j, v in zip((4, 5, 7, 8), eq26(t3, aD), strict=True):
        c(7, j, v)
    c(7, 6, eq27(q, A, B, aD))
    c(7, 9, eq28(q, A, B, aD))
    return C


def eq29(C):
    """|C_q| as printed (Eq. 29), from the entries of C_q (1-based c(i, j))."""
    def c(i, j):
        return C[i - 1, j - 1]
    return ((-c(4, 4) * c(5, 5) + c(4, 5) * c(5, 4)) * (c(6, 6) * c(7, 8) - c(6, 8) * c(7, 6))
            + (c(4, 4) * c(5, 6) - c(4, 6) * c(5, 4)) * (c(6, 5) * c(7, 8) - c(6, 8) * c(7, 5))
            + (-c(4, 5) * c(5, 6) + c(4, 6) * c(5, 5)) * (c(6, 4) * c(7, 8) - c(6, 8) * c(7, 4)))


def eq30_printed(A, B, a, t2):
    """Eq. 30 AS PRINTED (wrong sign inside the bracket)."""
    return 8 * sin(a) * cos(a) ** 2 * (B * sin(a) + A * cos(a)) * cos(t2)


def eq30_corrected(A, B, a, t2):
    """ERRATUM: Eq. 30 follows from Eqs. 16-29 only with B sin(alpha) - A cos(alpha)."""
    return 8 * sin(a) * cos(a) ** 2 * (B * sin(a) - A * cos(a)) * cos(t2)


# --------------------------------------------------------------------------------------------
# Section 5.1, sticking: Eq. 32 and Jacobian Eqs. 33-36
# --------------------------------------------------------------------------------------------
def eq32(q, A, B, xA, yA, xD, yD):
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return np.array([
        Rx2 - A * cos(t2) + B * sin(t2) - Rx1 - xA * cos(t1) + yA * sin(t1),
        Ry2 - A * sin(t2) - B * cos(t2) - Ry1 - xA * sin(t1) - yA * cos(t1),
        Rx2 + A * cos(t2) - B * sin(t2) - Rx3 - xD * cos(t3) + yD * sin(t3),
        Ry2 + A * sin(t2) + B * cos(t2) - Ry3 - xD * sin(t3) - yD * cos(t3),
    ])


def eq34(t1, xA, yA):
    """[c43, c53]."""
    return np.array([[xA, yA], [yA, -xA]]) @ [sin(t1), cos(t1)]


def eq35(t2, A, B):
    """[c46, c56, c66, c76]."""
    return np.array([[A, B], [B, -A], [-A, -B], [-B, A]]) @ [sin(t2), cos(t2)]


def eq36(t3, xD, yD):
    """[c69, c79]."""
    return np.array([[xD, yD], [yD, -xD]]) @ [sin(t3), cos(t3)]


def sticking_jacobian_printed(q, A, B, xA, yA, xD, yD):
    C = np.zeros((9, 9))

    def c(i, j, value):
        C[i - 1, j - 1] = value

    # Eq. 33. ERRATUM (notation): the entries printed "-c41, -c52, -c67, -c78 = 1" mean -1.
    for i, j in ((1, 1), (2, 2), (3, 3), (4, 4), (5, 5), (8, 7), (6, 4), (7, 5), (9, 9)):
        c(i, j, 1.0)
    for i, j in ((4, 1), (5, 2), (6, 7), (7, 8)):
        c(i, j, -1.0)
    for i, v in zip((4, 5), eq34(q[2], xA, yA), strict=True):
        c(i, 3, v)
    for i, v in zip((4, 5, 6, 7), eq35(q[5], A, B), strict=True):
        c(i, 6, v)
    for i, v in zip((6, 7), eq36(q[8], xD, yD), strict=True):
        c(i, 9, v)
    return C


# --------------------------------------------------------------------------------------------
# Section 5.2, slipping: Eqs. 37-48 over the columns (R_x^2, R_y^2, theta^2, R_x^3, R_y^3, theta^3)
# --------------------------------------------------------------------------------------------
def eq38(q, nx, ny, k1):
    return q[3] * nx + q[4] * ny - k1


def eq39(q, nx, ny, k3):
    return q[6] * nx + q[7] * ny - k3


def eq40(q, Ry3_rc):
    return q[7] - Ry3_rc


def eq37(q, A, B, xA, yA, aA, xD, yD, aD, nx, ny, k1, k3, Ry3_rc):
    """Eq. 37; ERRATUM: row 2 uses n_D^3 (D slides), not n_C^3, i.e. it is Eq. 11; rows 3-4 are
    Eqs. 38-39 (Eq. 37 writes k_2 and F^3 where Eq. 39 has k_3 and R^3)."""
    return np.array([eq8(q, A, B, xA, yA, aA), eq11(q, A, B, xD, yD, aD), eq38(q, nx, ny, k1),
                     eq39(q, nx, ny, k3), eq40(q, Ry3_rc), q[8]])


def eq42(t1, a):
    """[c11, c12]."""
    return np.array([[-cos(a), sin(a)], [sin(a), cos(a)]]) @ [sin(t1), cos(t1)]


def eq43(q, A, B, a):
    t1, t2 = q[2], q[5]
    return ((A * sin(t2) + B * cos(t2)) * (sin(a) * cos(t1) - cos(a) * sin(t1))
            + (B * sin(t2) - A * cos(t2)) * (sin(a) * sin(t1) + cos(a) * cos(t1)))


def eq44(t3, a):
    """[c21, c22, c24, c25] (alpha = alpha_D^3)."""
    return np.array([[cos(a), -sin(a)], [-sin(a), -cos(a)], [-cos(a), sin(a)], [sin(a), cos(a)]]) \
        @ [sin(t3), cos(t3)]


def eq45(q, A, B, a):
    """c23 (printed with the 'c' missing)."""
    t2, t3 = q[5], q[8]
    return (-(A * sin(t2) + B * cos(t2)) * (-sin(a) * cos(t3) + cos(a) * sin(t3))
            - (A * cos(t2) - B * sin(t2)) * (sin(a) * sin(t3) + cos(a) * cos(t3)))


def eq46(q, A, B, a):
    """c26 (printed with the 'c' missing; the x-bar, y-bar terms cancel)."""
    Rx1, Ry1, t1, Rx2, Ry2, t2, Rx3, Ry3, t3 = q
    return ((Rx2 + A * cos(t2) - B * sin(t2) - Rx3) * (sin(a) * sin(t3) + cos(a) * cos(t3))
            + (Ry2 + A * sin(t2) + B * cos(t2) - Ry3) * (-sin(a) * cos(t3) + cos(a) * sin(t3)))


def slipping_jacobian_printed(q, A, B, aA, aD, nx, ny):
    C = np.zeros((6, 6))

    def c(i, j, value):
        C[i - 1, j - 1] = value

    for j, v in zip((1, 2), eq42(q[2], aA), strict=True):
        c(1, j, v)
    c(1, 3, eq43(q, A, B, aA))
    for j, v in zip((1, 2, 4, 5), eq44(q[8], aD), strict=True):
        c(2, j, v)
    c(2, 3, eq45(q, A, B, aD))
    c(2, 6, eq46(q, A, B, aD))
    c(3, 1, nx), c(3, 2, ny), c(4, 4, nx), c(4, 5, ny)  # Eq. 47
    c(5, 5, 1.0), c(6, 6, 1.0)  # Eq. 48
    return C


# --------------------------------------------------------------------------------------------
# Builders of the package's constraint sets from random data
# --------------------------------------------------------------------------------------------
def make_compliant(g, rng):
    alphas, points, normals = random_contacts(rng, "ABCD")
    Xg, Rx3 = rng.uniform(-0.3, 0.3, 2)
    return Compliant(all_corners(g), Xg, Rx3, points, normals), alphas, points, (Xg, Rx3)


def make_sticking(g, rng, bc):
    points = [complex(rng.uniform(-0.3, 0.3), rng.uniform(-0.1, 1.5)) for _ in range(2)]
    Xg, Rx3 = rng.uniform(-0.3, 0.3, 2)
    return Sticking(diagonal(g, bc), Xg, Rx3, points), points, (Xg, Rx3)


def make_slipping(g, rng, bc, q):
    names = "BC" if bc else "AD"
    alphas, points, normals = random_contacts(rng, names)
    phi = rng.uniform(-0.4, 0.4)
    n12 = complex(cos(phi), sin(phi))
    k1, k3, Ry3_rc = rng.uniform(-1.0, 2.0, 3)
    q_stick = q.copy()
    s = Slipping(diagonal(g, bc), q_stick, points, normals, n12, k1, k3, Ry3_rc)
    return s, alphas, points, (n12.real, n12.imag, k1, k3, Ry3_rc)


# --------------------------------------------------------------------------------------------
# 1-2. Compliant sliding: Eqs. 5, 8-11 and 16-29
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("case", range(N_CASES))
def test_compliant_residual_is_eqs_5_and_8_to_11(name, case):
    g = PRINTED[name]
    A, B = pad_half_width(g)
    rng = np.random.default_rng([1, case])
    q = random_q(rng)
    cset, alphas, points, (Xg, Rx3) = make_compliant(g, rng)
    r = cset.residual(q)
    eqs = (eq8, eq9, eq10, eq11)
    expected = [q[0] - Xg, q[1], q[2]] + [
        eq(q, A, B, p.real, p.imag, a) for eq, p, a in zip(eqs, points, alphas, strict=True)
    ] + [q[6] - Rx3, q[8]]
    np.testing.assert_allclose(r, expected, rtol=0, atol=TOL)


@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("case", range(N_CASES))
def test_compliant_jacobian_is_eqs_16_to_28(name, case):
    g = PRINTED[name]
    A, B = pad_half_width(g)
    rng = np.random.default_rng([2, case])
    q = random_q(rng)
    cset, alphas, _, _ = make_compliant(g, rng)
    printed = compliant_jacobian_printed(q, A, B, alphas)
    np.testing.assert_allclose(cset.jacobian(q), printed, rtol=0, atol=TOL)
    # Eq. 29, the printed expansion of |C_q|, agrees with the full determinant
    assert eq29(printed) == pytest.approx(np.linalg.det(printed), abs=TOL)
    assert cset.determinant(q) == pytest.approx(eq29(printed), abs=TOL)


def test_compliant_batch_matches_printed():
    """Batches (N, 9) with contact data of shape (N,) give the printed forms case by case."""
    g = DFP1
    A, B = pad_half_width(g)
    rng = np.random.default_rng(3)
    q = np.stack([random_q(rng) for _ in range(N_CASES)])
    alphas = rng.uniform(-0.5, 0.5, (4, N_CASES))
    points = [rng.uniform(-0.3, 0.3, N_CASES) + 1j * rng.uniform(-0.1, 1.5, N_CASES) for _ in range(4)]
    normals = [np.vectorize(normal)(n, a) for n, a in zip("ABCD", alphas, strict=True)]
    Xg, Rx3 = rng.uniform(-0.3, 0.3, (2, N_CASES))
    cset = Compliant(all_corners(g), Xg, Rx3, points, normals)
    r, J = cset.residual(q), cset.jacobian(q)
    assert r.shape == (N_CASES, 9) and J.shape == (N_CASES, 9, 9)
    for k in range(N_CASES):
        rows = [eq(q[k], A, B, p[k].real, p[k].imag, a[k])
                for eq, p, a in zip((eq8, eq9, eq10, eq11), points, alphas, strict=True)]
        np.testing.assert_allclose(r[k, 3:7], rows, rtol=0, atol=TOL)
        np.testing.assert_allclose(J[k], compliant_jacobian_printed(q[k], A, B, alphas[:, k]),
                                   rtol=0, atol=TOL)


# --------------------------------------------------------------------------------------------
# 3. Sticking: Eqs. 31-36
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("case", range(N_CASES))
def test_sticking_AD_is_eqs_31_to_36(name, case):
    g = PRINTED[name]
    A, B = pad_half_width(g)
    rng = np.random.default_rng([4, case])
    q = random_q(rng)
    cset, (pA, pD), (Xg, Rx3) = make_sticking(g, rng, bc=False)
    # Eq. 31; R_x^3 is held at an absolute value (0 as printed, any value here)
    expected = np.concatenate([[q[0] - Xg, q[1], q[2]],
                               eq32(q, A, B, pA.real, pA.imag, pD.real, pD.imag),
                               [q[6] - Rx3, q[8]]])
    np.testing.assert_allclose(cset.residual(q), expected, rtol=0, atol=TOL)
    printed = sticking_jacobian_printed(q, A, B, pA.real, pA.imag, pD.real, pD.imag)
    np.testing.assert_allclose(cset.jacobian(q), printed, rtol=0, atol=TOL)


def test_sticking_eq33_signs_are_minus_one():
    """ERRATUM, Eq. 33: c41 = c52 = c67 = c78 = -1 (the plates' translations enter Eq. 32 with -)."""
    rng = np.random.default_rng(5)
    cset, _, _ = make_sticking(DFP1, rng, bc=False)
    J = cset.jacobian(random_q(rng))
    assert [J[3, 0], J[4, 1], J[5, 6], J[6, 7]] == [-1.0, -1.0, -1.0, -1.0]
    assert [J[3, 3], J[4, 4], J[5, 3], J[6, 4]] == [1.0, 1.0, 1.0, 1.0]


# --------------------------------------------------------------------------------------------
# 4. Slipping: Eqs. 37-48 (row 2 of Eq. 37 corrected to n_D^3)
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("case", range(N_CASES))
def test_slipping_AD_is_eqs_37_to_48(name, case):
    g = PRINTED[name]
    A, B = pad_half_width(g)
    rng = np.random.default_rng([6, case])
    q = random_q(rng)
    cset, (aA, aD), (pA, pD), (nx, ny, k1, k3, Ry3_rc) = make_slipping(g, rng, False, q)
    expected = eq37(q, A, B, pA.real, pA.imag, aA, pD.real, pD.imag, aD, nx, ny, k1, k3, Ry3_rc)
    np.testing.assert_allclose(cset.residual(q), expected, rtol=0, atol=TOL)
    printed = slipping_jacobian_printed(q, A, B, aA, aD, nx, ny)
    np.testing.assert_allclose(cset.jacobian(q), printed, rtol=0, atol=TOL)


def test_slipping_row2_uses_n_D_not_n_C():
    """ERRATUM, Eq. 37 row 2: with n_C^3 (normal (sin a, -cos a)) the row is not the package's."""
    g = DFP1
    A, B = pad_half_width(g)
    rng = np.random.default_rng(7)
    q = random_q(rng)
    cset, (aA, aD), (pA, pD), _ = make_slipping(g, rng, False, q)
    r2 = cset.residual(q)[1]
    assert r2 == pytest.approx(eq11(q, A, B, pD.real, pD.imag, aD), abs=TOL)
    # the printed n_C^3, i.e. D's lever projected on C's normal at the same angle
    t3 = q[8]
    nC = np.array([sin(aD) * cos(t3) + cos(aD) * sin(t3), sin(aD) * sin(t3) - cos(aD) * cos(t3)])
    lever = np.array([q[3] + A * cos(q[5]) - B * sin(q[5]) - q[6] - pD.real * cos(t3) + pD.imag * sin(t3),
                      q[4] + A * sin(q[5]) + B * cos(q[5]) - q[7] - pD.real * sin(t3) - pD.imag * cos(t3)])
    assert abs(lever @ nC - r2) > 1e-3


# --------------------------------------------------------------------------------------------
# 5. Every analytic Jacobian equals central finite differences of its residual
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ALL_GEOMETRIES)
@pytest.mark.parametrize("case", range(N_CASES))
def test_compliant_jacobian_fd(name, case):
    rng = np.random.default_rng([8, case])
    q = random_q(rng)
    cset, *_ = make_compliant(ALL_GEOMETRIES[name], rng)
    assert_fd(cset.jacobian(q), central_differences(cset.residual, q, range(9)))


@pytest.mark.parametrize("diag", ["AD", "BC"])
@pytest.mark.parametrize("name", ALL_GEOMETRIES)
@pytest.mark.parametrize("case", range(N_CASES))
def test_sticking_jacobian_fd(diag, name, case):
    rng = np.random.default_rng([9, case])
    q = random_q(rng)
    cset, *_ = make_sticking(ALL_GEOMETRIES[name], rng, bc=diag == "BC")
    assert_fd(cset.jacobian(q), central_differences(cset.residual, q, range(9)))


@pytest.mark.parametrize("diag", ["AD", "BC"])
@pytest.mark.parametrize("name", ALL_GEOMETRIES)
@pytest.mark.parametrize("case", range(N_CASES))
def test_slipping_jacobian_fd(diag, name, case):
    rng = np.random.default_rng([10, case])
    q = random_q(rng)
    cset, *_ = make_slipping(ALL_GEOMETRIES[name], rng, diag == "BC", q)
    # RB1 is frozen in the slipping phase: C_q (6 x 6) is over (R_x^2 ... theta^3)
    assert_fd(cset.jacobian(q), central_differences(cset.residual, q, range(3, 9)))


KINDS = {"compliant": compiled.COMPLIANT, "sticking": compiled.STICKING, "slipping": compiled.SLIPPING}


def kernel_rows(kind, g, rng, bc, q):
    """The library kernels' contact rows (``compiled._rows``, interpreted) as a function of the free
    coordinates, and the tests' constraint set of the same data."""
    if kind == "compliant":
        cset = make_compliant(g, rng)[0]
    elif kind == "sticking":
        cset = make_sticking(g, rng, bc)[0]
    else:
        cset = make_slipping(g, rng, bc, q)[0]
    pad = tuple(c.u2 for c in cset.corners)
    normals = getattr(cset, "normals", [0j] * len(pad))
    n12, k1, k3 = (cset.n12, cset.k1, cset.k3) if kind == "slipping" else (1j, 0.0, 0.0)
    data = (pad, tuple(cset.points), tuple(normals), n12, k1, k3)
    q = cset.prescribe(q)

    def rows(x):
        qx = q.copy()
        qx[list(cset.free)] = x
        g, J = compiled._rows(KINDS[kind], compiled.frames(tuple(qx.tolist())), data)
        return np.array(g), np.array(J)
    return rows, cset, q


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("diag", ["AD", "BC"])
@pytest.mark.parametrize("name", ALL_GEOMETRIES)
@pytest.mark.parametrize("case", range(5))
def test_kernel_rows_are_the_constraint_sets_and_their_jacobian_fd(kind, diag, name, case):
    """The kernels' rows (the library's only statement of them) equal this module's constraint sets on
    the free coordinates, and their Jacobian central differences of their residual."""
    rng = np.random.default_rng([11, case])
    rows, cset, q = kernel_rows(kind, ALL_GEOMETRIES[name], rng, diag == "BC", random_q(rng))
    x = q[list(cset.free)]
    g, J = rows(x)
    g_ref, J_ref = cset.contact(q, cset.free)
    np.testing.assert_allclose(g, g_ref, rtol=0, atol=1e-15)
    np.testing.assert_allclose(J, J_ref, rtol=0, atol=1e-15)
    assert_fd(J, central_differences(lambda x: rows(x)[0], x, range(len(x))))


def test_determinant_diagnostic_is_the_compliant_sets():
    """det_Cq of a history (``models.determinant``) is |C_q| of the tests' compliant set at each step."""
    g = ALL_GEOMETRIES["R1>R3"]
    h = models.run("compliant", g, 0.2 * np.sin(np.linspace(0.0, 6.0, 200)), theta2_0=0.02)
    corners = all_corners(g)
    cset = Compliant(corners, h["q"][..., 0], h["Rx3"], [h["point"][..., i] for i in range(4)],
                     [h["normal"][..., i] for i in range(4)])
    assert np.abs(cset.determinant(h["q"])).min() > 1e-3
    np.testing.assert_array_equal(models.determinant(h, g), cset.determinant(h["q"]))


@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("case", range(N_CASES))
def test_sticking_BC_mirror_of_eq32(name, case):
    """The mirrored (B-C) pin rows: B^2 = (A, -B) pinned to RB1, C^2 = (-A, B) pinned to RB3."""
    g = PRINTED[name]
    A, B = pad_half_width(g)
    rng = np.random.default_rng([11, case])
    q = random_q(rng)
    cset, (pB, pC), _ = make_sticking(g, rng, bc=True)
    # Eq. 32 with A -> -A (B^2 and C^2 are A^2 and D^2 mirrored about the pad axis)
    np.testing.assert_allclose(cset.residual(q)[3:7],
                               eq32(q, -A, B, pB.real, pB.imag, pC.real, pC.imag), rtol=0, atol=TOL)


# --------------------------------------------------------------------------------------------
# 6. The determinant at the symmetric rest position (Eq. 30, corrected)
# --------------------------------------------------------------------------------------------
def rest_compliant(g, alpha, theta2):
    """Compliant set at theta^1 = theta^3 = 0, all four contact angles alpha, the contact points
    on the concave circles at +-alpha."""
    (c1, c3) = g.circle_centres
    centre = {"A": complex(*c1), "B": complex(*c1), "C": complex(*c3), "D": complex(*c3)}
    radius = {"A": g.R1, "B": g.R1, "C": g.R3, "D": g.R3}
    normals = [normal(n, alpha) for n in "ABCD"]
    points = [centre[n] - radius[n] * nn for n, nn in zip("ABCD", normals, strict=True)]
    q = g.compatible(theta2)
    assert q[2] == 0.0 and q[8] == 0.0
    return Compliant(all_corners(g), q[0], q[6], points, normals), q


@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("alpha_deg", [-12.0, -3.0, 2.0, 5.0, 10.0, 17.0, 30.0])
@pytest.mark.parametrize("theta2", [-0.4, -0.1, 0.0, 0.25])
def test_eq30_determinant_at_symmetric_rest(name, alpha_deg, theta2):
    g = PRINTED[name]
    A, B = pad_half_width(g)
    a = np.radians(alpha_deg)
    cset, q = rest_compliant(g, a, theta2)
    corrected = eq30_corrected(A, B, a, theta2)
    assert cset.determinant(q) == pytest.approx(corrected, rel=1e-10, abs=1e-14)
    # the printed Jacobian (Eqs. 16-28) itself leads to the corrected form, not to Eq. 30
    printed = compliant_jacobian_printed(q, A, B, [a] * 4)
    assert np.linalg.det(printed) == pytest.approx(corrected, rel=1e-10, abs=1e-14)
    assert eq29(printed) == pytest.approx(corrected, rel=1e-10, abs=1e-14)
    # ERRATUM pinned: the printed Eq. 30 (B sin a + A cos a) does not match
    assert abs(cset.determinant(q) - eq30_printed(A, B, a, theta2)) > 1e-3 * abs(cos(theta2))


def test_eq30_dfp1_value():
    """DFP1, theta^2 = 0, alpha = alpha^21 = 10 deg: |C_q| = -0.2129 m, not the printed +0.248 m."""
    g = DFP1
    A, B = pad_half_width(g)
    cset, q = rest_compliant(g, g.alpha21, 0.0)
    det = cset.determinant(q)
    assert det == pytest.approx(-0.2129, abs=1e-4)
    assert eq30_printed(A, B, g.alpha21, 0.0) == pytest.approx(0.248, abs=1e-3)
    assert abs(det - eq30_printed(A, B, g.alpha21, 0.0)) > 0.4
    # the same with the package's own contact points at the compatible rest configuration
    q = g.compatible(0.0)
    corners = all_corners(g)
    F = frames(q)
    data = [contact_point(F, c) for c in corners]
    for c, (_, n) in zip(corners, data, strict=True):
        assert contact_angle(n, c) == pytest.approx(g.alpha21, abs=1e-12)
    cset = Compliant(corners, q[0], q[6], [p for p, _ in data], [n for _, n in data])
    assert cset.determinant(q) == pytest.approx(eq30_corrected(A, B, g.alpha21, 0.0), rel=1e-10)


@pytest.mark.parametrize("name", PRINTED)
@pytest.mark.parametrize("theta2", [0.0, -0.1, 0.25])
def test_eq30_as_printed_is_the_determinant_with_alpha_reversed(name, theta2):
    """The reading of the sign erratum: the printed Eq. 30 is the determinant of the compliant set
    at rest (Eqs. 16-29) when the contact normals are mirrored, alpha -> -alpha (+0.24795 m for
    DFP1): the closed form was derived with the opposite sign of alpha, not simulated with it."""
    g = PRINTED[name]
    A, B = pad_half_width(g)
    cset, q = rest_compliant(g, -g.alpha21, theta2)
    assert cset.determinant(q) == pytest.approx(eq30_printed(A, B, g.alpha21, theta2), rel=1e-10)
    if name == "DFP1" and theta2 == 0.0:
        assert cset.determinant(q) == pytest.approx(0.24795, abs=1e-5)


@pytest.mark.parametrize("name", PRINTED)
def test_eq30_also_vanishes_at_tan_alpha_A_over_B(name):
    """A zero missing from the paper's list after Eq. 30: tan(alpha) = A / B."""
    g = PRINTED[name]
    A, B = pad_half_width(g)
    cset, q = rest_compliant(g, np.arctan2(A, B), 0.1)
    assert abs(cset.determinant(q)) < 1e-14
