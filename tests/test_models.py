"""Model claims of the two time steppers, against closed forms and independent physics."""

import numpy as np
import oracle
import pytest
from constraint_sets import Sticking, circle_centre, diagonal

from dccss.excitation import Sine, step_times
from dccss.mechanics import models, newton
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.kinematics import CORNERS, all_corners, frames, interpenetration, local
from dccss.paper.prototypes import DFP1, DFP2, TABLE1

UNEQUAL = Geometry.from_degrees(**{**TABLE1["DFP1"], "R3": 1.3, "alpha23": 8.0})


def history(model, geometry, amplitude=0.27, dt=0.01, theta2_0=0.0, **kw):
    ex = Sine(amplitude, 30.0, 1.0)
    t = step_times(ex, dt)
    return t, ex.displacement(t), models.run(model, geometry, ex.displacement(t), theta2_0, times=t, **kw)


@pytest.mark.parametrize("geometry", [DFP1, DFP2], ids=["DFP1", "DFP2"])
@pytest.mark.parametrize("theta2_0", [0.0, np.radians(-4.0)])
def test_compliant_follows_double_pendulum_relation(geometry, theta2_0):
    """sin th2(t) = sin th2(t0) - (Xg(t) - Xg(t0))/L to O(dX^2/R): the error shrinks ~x100
    when dt shrinks x10 (each step's tangent error is ~dX^2/R, and there are 10x more steps)."""
    errors = []
    for dt in (0.01, 0.001):
        _, Xg, h = history("compliant", geometry, amplitude=0.1, dt=dt, theta2_0=theta2_0)
        exact = np.sin(theta2_0) - (Xg - Xg[0]) / geometry.L
        errors.append(np.abs(np.sin(h["q"][:, 5]) - exact).max())
    dX = 0.1 * 30 * 0.01
    assert errors[0] < 5 * dX**2 / geometry.R1  # O(dX^2/R)
    assert 30 < errors[0] / errors[1] < 300, errors


def test_compliant_rise_follows_pendulum_height():
    """R_y^3 - rest = L (1 - cos th2) to within the corner interpenetration: the pad sinks into
    each plate by the radial interpenetration, at most I / cos(alpha^1) vertically."""
    _, _, h = history("compliant", DFP1, dt=0.001)
    q = h["q"]
    rise = q[:, 7] - DFP1.Ry3_compatible(0.0)
    interp = np.abs(interpenetration(q, DFP1)).max()
    assert np.abs(rise - DFP1.L * (1 - np.cos(q[:, 5]))).max() < 2 * interp / np.cos(DFP1.alpha1)


@pytest.mark.parametrize("model", models.MODELS)
@pytest.mark.parametrize("normals", ["signed", "unsigned"])
@pytest.mark.parametrize("geometry", [DFP1, DFP2], ids=["DFP1", "DFP2"])
def test_symmetric_pad_diagonal_endpoints_equal(model, normals, geometry):
    """For a symmetric pad I_A = I_D and I_B = I_C (the configuration is point-symmetric
    about G^2 and the plates move only relative to each other)."""
    _, _, h = history(model, geometry, normals=normals, theta2_0=np.radians(-3.0))
    I = interpenetration(h["q"], geometry)
    scale = np.abs(I).max()
    assert scale > 1e-9  # the check is not vacuous
    assert np.abs(I[:, 0] - I[:, 3]).max() < 1e-9 * max(scale, 1e-3)
    assert np.abs(I[:, 1] - I[:, 2]).max() < 1e-9 * max(scale, 1e-3)


def test_symmetry_breaks_for_unequal_radii():
    """The I_A = I_D identity is a symmetry, not an artefact: unequal radii break it."""
    _, _, h = history("compliant", UNEQUAL, amplitude=0.15)
    I = interpenetration(h["q"], UNEQUAL)
    assert np.abs(I[:, 0] - I[:, 3]).max() > 1e-7


@pytest.mark.parametrize("geometry", [DFP1, DFP2, UNEQUAL], ids=["DFP1", "DFP2", "unequal"])
def test_sticking_pins_corners_to_plates(geometry):
    """During sticking the pinned corners move exactly with their plates (zero slip)."""
    _, _, h = history("stick_slip", geometry, amplitude=0.15)
    for n in range(1, len(h["q"])):
        corners = diagonal(geometry, bool(h["diagonal_BC"][n]))
        before, after = frames(h["q"][n - 1]), frames(h["q_stick"][n])
        for c in corners:
            assert abs(local(after, c) - local(before, c)) < 1e-11


@pytest.mark.parametrize("geometry", [DFP1, DFP2, UNEQUAL], ids=["DFP1", "DFP2", "unequal"])
def test_after_slipping_pad_axis_on_centre_line(geometry):
    """After slipping, C^1C^3 has length L (Eq. 41) and the pad axis lies on it to within the
    tangent error of the step (the pad's cap centres coincide with the circle centres)."""
    _, _, h = history("stick_slip", geometry, amplitude=0.15, dt=0.001)
    q = h["q"]
    A, B, C, D = all_corners(geometry)
    F = frames(q)
    C1, C3 = circle_centre(F, A), circle_centre(F, D)
    assert np.abs(np.abs(C3 - C1) - geometry.L).max() < 1e-10
    e = (C3 - C1) / np.abs(C3 - C1)
    axis = np.exp(1j * q[:, 5]) * -1j  # pad axis pointing from C^21 to C^23 (downward at rest)
    misalignment = np.abs(np.angle(axis / e))
    tangent_error = np.abs(interpenetration(q, geometry)).max() / geometry.A1
    assert misalignment.max() < 10 * tangent_error
    assert misalignment.max() < 1e-4


def test_sticking_diagonal_follows_sign_of_ground_step():
    t, Xg, h = history("stick_slip", DFP1)
    dX = np.diff(Xg)
    assert np.array_equal(h["diagonal_BC"][1:], dX < 0)


def test_sticking_resets_rx3_to_initial_value():
    """The R_x^3 row of Eq. 31 is absolute: a sideways slip of RB3 is undone by the next stick."""
    _, _, h = history("stick_slip", DFP2, theta2_0=np.radians(2.0))
    Rx3_0 = h["q"][0, 6]
    assert np.abs(h["q_stick"][1:, 6] - Rx3_0).max() < 1e-12
    assert np.abs(h["q"][1:, 6] - Rx3_0).max() > 1e-6  # slipping does move RB3 sideways


@pytest.mark.parametrize("model", models.MODELS)
def test_signed_and_unsigned_agree_until_rotation_exceeds_cap_angle(model):
    """The two normal conventions differ only once a contact angle changes sign, i.e. once
    |theta2| passes alpha21 (DFP2: 5 deg); before that they are identical."""
    runs = {n: history(model, DFP2, normals=n, dt=0.001)[2]["q"] for n in ("signed", "unsigned")}
    theta2 = np.abs(runs["signed"][:, 5])
    first = np.argmax(theta2 > DFP2.alpha21)
    assert first > 0
    assert np.abs(runs["signed"][:first] - runs["unsigned"][:first]).max() == 0.0
    assert np.abs(runs["signed"][first:] - runs["unsigned"][first:]).max() > 1e-7


def test_signed_and_unsigned_identical_when_rotation_stays_small():
    runs = [history("compliant", DFP1, normals=n)[2]["q"] for n in ("signed", "unsigned")]
    assert np.abs(runs[0][:, 5]).max() < DFP1.alpha21
    assert np.array_equal(runs[0], runs[1])


@pytest.mark.parametrize("model", models.MODELS)
def test_batch_equals_one_case(model):
    """The stacked (batched) Newton path equals the one-case path to 1e-12."""
    ex = Sine(0.2, 30.0, 0.5)
    t = step_times(ex, 0.01)
    amplitudes = np.array([0.27, 0.1, -0.2])
    params = {**TABLE1["DFP1"], "alpha21": np.array([8.0, 10.0, 12.0])}
    batch_geometry = Geometry.from_degrees(**params)
    theta2_0 = np.radians([0.0, 1.5, -2.0])
    Xg = ex.displacement(t)[:, None] / 0.2 * amplitudes
    hb = models.run(model, batch_geometry, Xg, theta2_0, times=t)
    for k in range(3):
        g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": params["alpha21"][k]})
        h1 = models.run(model, g, Xg[:, k], theta2_0[k], times=t)
        assert np.abs(hb["q"][:, k] - h1["q"]).max() < 1e-12
        assert np.array_equal(hb["newton_iterations"][:, k], h1["newton_iterations"])


def test_start_is_compatible_with_offset_rb3():
    _, _, h = history("compliant", DFP1, theta2_0=np.radians(2.0))
    q0 = h["q"][0]
    assert q0[6] == pytest.approx(DFP1.L * np.sin(np.radians(2.0)), abs=1e-15)
    assert np.abs(interpenetration(q0, DFP1)).max() < 1e-12


def test_convergence_error_names_step_time_phase_and_row():
    """An impossible tolerance makes Newton fail; the message says where and what."""
    ex = Sine(0.27, 30.0, 1.0)
    t = step_times(ex, 0.01)
    with pytest.raises(newton.ConvergenceError) as err:
        models.compliant(DFP1, ex.displacement(t), times=t,
                         options=newton.NewtonOptions(tol=1e-30, max_iter=3))
    msg = str(err.value)
    for part in ("compliant sliding", "step 1", "time 0.01 s", "residual", "row ", "Eq. "):
        assert part in msg, msg


def test_singular_jacobian_is_reported():
    """Contrive a singular sticking set: corner A pinned twice (duplicate rows), D not at all."""
    g = DFP1
    corners = diagonal(g, False)
    q = g.compatible(0.0)
    F = frames(q)
    pins = [local(F, c) for c in corners]
    stick = Sticking((corners[0], corners[0]), 0.01, q[6], [pins[0], pins[0]])
    with pytest.raises(newton.SingularJacobianError, match="singular constraint Jacobian in sticking"):
        oracle.solve(stick, q, context={"step": 7, "time": 0.07})


def test_newton_options_validated():
    with pytest.raises(ValueError, match="tol"):
        newton.NewtonOptions(tol=-1.0)
    with pytest.raises(ValueError, match="max_iter"):
        newton.NewtonOptions(max_iter=0)


def test_corner_names_order():
    assert CORNERS == ("A", "B", "C", "D")
    assert [c.name for c in all_corners(DFP1)] == list(CORNERS)
