"""The spatial (bidirectional) models: planar limit, rotation invariance, closed forms, Jacobians."""

import math

import numpy as np
import pytest

from dccss.mechanics import models, registry, spatial
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import ConvergenceError, NewtonOptions
from dccss.paper.prototypes import DFP1, DFP2, TABLE1

#: unequal radii and caps: no symmetry hides a wrong sign
UNEQUAL = Geometry.from_degrees(**{**TABLE1["DFP1"], "R3": 2.2, "alpha3": 9.0, "alpha23": 5.0, "alpha21": 7.0})
DEVICES = {"DFP1": DFP1, "DFP2": DFP2, "unequal": UNEQUAL}
MODELS = registry.names(spatial.in_space)


def sine(dt=0.01, amplitude=0.2, period=1.0, duration=1.0):
    t = np.arange(int(round(duration / dt)) + 1) * dt
    return t, amplitude * np.sin(2 * np.pi * t / period)


def circle(dt, radius=0.095, period=2.0, turns=1.0):
    """A circular ground orbit through the origin, back at the origin after ``turns``."""
    t = np.arange(int(round(turns * period / dt)) + 1) * dt
    phase = 2 * np.pi * t / period
    return t, np.stack([radius * (1 - np.cos(phase)), radius * np.sin(phase)], axis=-1)


def ellipse(dt=0.01):
    """A closed, off-centre, non-circular orbit (three turns of an ellipse with a drift back)."""
    t = np.arange(int(round(3.0 / dt)) + 1) * dt
    phase = 2 * np.pi * t / 1.0
    return t, np.stack([0.12 * np.sin(phase) + 0.03 * np.sin(np.pi * t / 3.0), 0.05 * (1 - np.cos(phase))], axis=-1)


def along(x, azimuth_deg):
    a = math.radians(azimuth_deg)
    return np.stack([x * math.cos(a), x * math.sin(a)], axis=-1)


# --- the planar limit --------------------------------------------------------------------------
@pytest.mark.parametrize("device", list(DEVICES))
@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("azimuth", [0.0, 30.0, 137.0, 240.0])
def test_motion_along_an_azimuth_is_the_planar_run(model, device, azimuth):
    g = DEVICES[device]
    _, x = sine(amplitude=0.8 * float(g.capacity1))
    theta2_0 = math.radians(1.5) if device == "unequal" else 0.0
    planar = models.run(model, g, x, theta2_0)
    h = spatial.run(model, g, along(x, azimuth), theta2_0, azimuth=math.radians(azimuth))
    d = spatial.diagnostics(h, g)
    theta2 = planar["q"][:, 5]
    assert np.max(np.abs(d["tilt"] - np.abs(theta2))) < 1e-9
    assert np.max(np.abs(d["rise"] - (planar["q"][:, 7] - g.Ry3_compatible(0.0)))) < 1e-9
    # the pad leans away from the side it rotates towards: azimuth + 180 deg for theta2 > 0
    lean = np.where(theta2 > 0, azimuth + 180.0, azimuth) % 360.0
    moving = np.abs(theta2) > 1e-6
    diff = (np.degrees(d["tilt_azimuth"][moving]) - lean[moving] + 180.0) % 360.0 - 180.0
    assert np.max(np.abs(diff)) < 1e-6
    # the pad centre and RB3 in the vertical plane of the azimuth, at the planar coordinates
    h_dir = np.array([math.cos(math.radians(azimuth)), math.sin(math.radians(azimuth)), 0.0])
    G = planar["q"][:, 3, None] * h_dir + planar["q"][:, 4, None] * spatial.Z
    assert np.max(np.abs(h["G"] - G)) < 1e-9
    if model == "stick_slip":
        assert np.max(np.abs(h["stick_G"][1:] - (planar["q_stick"][1:, 3, None] * h_dir
                                                 + planar["q_stick"][1:, 4, None] * spatial.Z))) < 1e-9
        assert np.max(np.abs(spatial.tilt(h["stick_Q"][1:])[0] - np.abs(planar["q_stick"][1:, 5]))) < 1e-9


def test_planar_interpenetration_and_clearance_are_the_planar_ones():
    _, x = sine(amplitude=float(DFP1.capacity1) * 2.2)  # passes the rings
    planar = models.run("compliant", DFP1, x)
    h = spatial.run("compliant", DFP1, along(x, 0.0))
    d = spatial.diagnostics(h, DFP1)
    from dccss.mechanics.kinematics import corner_diagnostics

    interp, gap = corner_diagnostics(planar["q"], DFP1)
    # A, B, C, D are trailing / leading by the sign of the step: the section is the same pair
    forward = np.concatenate([[True], np.diff(x) >= 0])
    expected = np.where(forward[:, None], interp, interp[:, [1, 0, 3, 2]])
    assert np.max(np.abs(d["interpenetration"][1:] - expected[1:])) < 1e-12
    assert np.max(np.abs(d["clearance_1"] - gap[:, 0])) < 1e-12
    assert np.max(np.abs(d["clearance_3"] - gap[:, 1])) < 1e-12
    assert (d["clearance_1"] < 0).any()


# --- symmetry ----------------------------------------------------------------------------------
@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("beta", [25.0, -160.0])
def test_rotating_the_input_rotates_the_output(model, beta):
    _, X = ellipse()
    b = math.radians(beta)
    rot = np.array([[math.cos(b), -math.sin(b)], [math.sin(b), math.cos(b)]])
    h0 = spatial.run(model, UNEQUAL, X)
    h1 = spatial.run(model, UNEQUAL, X @ rot.T, azimuth=b)
    d0, d1 = spatial.diagnostics(h0, UNEQUAL), spatial.diagnostics(h1, UNEQUAL)
    assert np.max(np.abs(d0["tilt"] - d1["tilt"])) < 1e-9
    assert np.max(np.abs(d0["rise"] - d1["rise"])) < 1e-9
    leaning = d0["tilt"] > 1e-6
    diff = (d1["tilt_azimuth"][leaning] - d0["tilt_azimuth"][leaning] - b + np.pi) % (2 * np.pi) - np.pi
    assert np.max(np.abs(diff)) < 1e-8
    assert np.max(np.abs(h1["G"][:, :2] - h0["G"][:, :2] @ rot.T)) < 1e-9
    assert np.max(np.abs(d0["tilt"])) > math.radians(2.0)  # the test moves the pad


@pytest.mark.parametrize("model", MODELS)
def test_mirrored_input_gives_the_mirrored_tilt(model):
    _, X = ellipse()
    h0 = spatial.run(model, DFP2, X)
    h1 = spatial.run(model, DFP2, X * np.array([1.0, -1.0]))
    d0, d1 = spatial.diagnostics(h0, DFP2), spatial.diagnostics(h1, DFP2)
    assert np.max(np.abs(d0["tilt"] - d1["tilt"])) < 1e-9
    assert np.max(np.abs(h0["G"] * [1, -1, 1] - h1["G"])) < 1e-9


# --- closed forms and what no plane can show ---------------------------------------------------
def test_compliant_tilt_is_the_closed_form_within_the_interpenetration_order():
    errors = []
    for dt in (0.01, 0.005):
        _, X = circle(dt)
        h = spatial.run("compliant", DFP1, X)
        d = spatial.diagnostics(h, DFP1)
        dev = spatial.device(DFP1)
        horizontal = np.linalg.norm((h["R1"] - h["R3"])[:, :2], axis=-1)
        exact = np.arcsin(horizontal / dev.L)
        error = np.max(np.abs(d["tilt"] - exact))
        # the interpenetration order: the cap centres miss the sphere centres by gap_1, gap_3
        order = np.max(d["gap_1"] + d["gap_3"]) / dev.L
        assert error < 2 * order
        errors.append(error)
    assert np.max(spatial.diagnostics(h, DFP1)["tilt"]) > math.radians(5.0)
    assert errors[1] < errors[0] / 3  # second order in dt


@pytest.mark.parametrize("model", MODELS)
def test_a_closed_orbit_returns_to_its_start_as_dt_shrinks(model):
    residual = []
    for dt in (0.02, 0.01, 0.005):
        _, X = circle(dt)
        d = spatial.diagnostics(spatial.run(model, DFP1, X), DFP1)
        residual.append(abs(d["tilt"][-1]) + abs(d["rise"][-1]) / float(DFP1.L))
    assert residual[0] > 0 or model == "compliant"
    assert residual[2] < residual[1] < residual[0] or max(residual) < 1e-12
    assert residual[2] < residual[0] / 10  # no ratcheting: O(dt^2)


def _solid_angle(axes):
    """Signed solid angle enclosed by a closed path of unit vectors (triangles from the first)."""
    a = axes[0]
    total = 0.0
    for b, c in zip(axes[1:-1], axes[2:]):
        total += 2 * math.atan2(a @ np.cross(b, c), 1 + a @ b + b @ c + c @ a)
    return total


@pytest.mark.parametrize("model", MODELS)
def test_the_spin_after_an_orbit_is_the_solid_angle_its_axis_encloses(model):
    _, X = circle(0.0025)
    h = spatial.run(model, DFP1, X)
    Q = h["Q"][-1]
    spin = math.atan2(Q[1, 0], Q[0, 0])  # the axis is back to vertical
    omega = _solid_angle(h["Q"][:, :, 2])
    assert abs(abs(spin) - math.radians(0.49)) < math.radians(0.01)
    # no spin: the pad turns by the solid angle its axis encloses (the holonomy of parallel transport);
    # exactly so for compliant sliding, whose steps turn the axis along great circles; the sticking
    # rotations of stick-slip turn it about axes normal to the diagonal instead
    assert abs(spin - omega) < (1e-9 if model == "compliant" else 1e-4) * abs(omega)


def pose(h, n, prefix=""):
    """Step n of a history as a ``spatial.Pose`` (tuples)."""
    return spatial.Pose(*(tuple(h[prefix + k][n]) for k in ("R1", "G")), tuple(map(tuple, h[prefix + "Q"][n].T)),
                        tuple(h[prefix + "R3"][n]))


@pytest.mark.parametrize("device", list(DEVICES))
def test_sticking_pins_the_diagonal_and_slipping_restores_L(device):
    g = DEVICES[device]
    dev = spatial.device(g)
    _, X = ellipse()
    h = spatial.run("stick_slip", g, X)
    for n in range(1, len(X)):
        v1, v3 = (np.array(v) for v in spatial.pinned(pose(h, n - 1), dev, tuple(h["m"][n])))
        Q0, G0, Qs, Gs = h["Q"][n - 1], h["G"][n - 1], h["stick_Q"][n], h["stick_G"][n]
        before = (G0 + Q0 @ v1, G0 + Q0 @ v3)
        after = (Gs + Qs @ v1, Gs + Qs @ v3)
        assert np.max(np.abs(after[0] - before[0] - (h["stick_R1"][n] - h["R1"][n - 1]))) < 1e-11
        assert np.max(np.abs(after[1] - before[1] - (h["stick_R3"][n] - h["R3"][n - 1]))) < 1e-11
        # the smallest rotation: none about the pinned diagonal
        turn = Qs @ Q0.T
        w = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]])
        diagonal = before[1] - before[0]
        assert abs(w @ diagonal / np.linalg.norm(diagonal)) < 1e-12
        assert np.array_equal(h["stick_R3"][n, :2], h["R3"][0, :2])
        C1, C3 = h["R1"][n] + dev.c1 * np.array(spatial.Z), h["R3"][n] + dev.c3 * np.array(spatial.Z)
        assert abs(np.linalg.norm(C3 - C1) - dev.L) < 1e-10
        # no spin in slipping
        turn = h["Q"][n] @ Qs.T
        w = np.array([turn[2, 1] - turn[1, 2], turn[0, 2] - turn[2, 0], turn[1, 0] - turn[0, 1]])
        assert abs(w @ Qs[:, 2]) < 1e-12


# --- Jacobians against finite differences ------------------------------------------------------
def _phases():
    """One phase of each kind, built mid-way through a bidirectional history of UNEQUAL."""
    dev = spatial.device(UNEQUAL)
    _, X = ellipse()
    h = spatial.run("stick_slip", UNEQUAL, X[:80])
    prev, n = pose(h, 78), 79
    R1, m, e1 = tuple(h["R1"][n]), tuple(h["m"][n]), tuple(h["e1"][n])
    v1, v3 = spatial.pinned(prev, dev, m)
    phases = {
        "compliant": (spatial.compliant_rows, spatial.compliant_phase(dev, prev, R1, m, spatial.Z)),
        "sticking": (spatial.sticking_rows, spatial.sticking_phase(dev, prev, R1, tuple(h["R3"][0, :2]), v1, v3)),
        "slipping": (spatial.slipping_rows, spatial.slipping_phase(dev, pose(h, n, "stick_"), e1, v1, v3)),
    }
    return phases, prev


@pytest.mark.parametrize("name", ["compliant", "sticking", "slipping"])
def test_jacobian_matches_finite_differences(name):
    phases, start = _phases()
    rows, phase = phases[name]

    def g_J(x):
        g, J = rows(phase, tuple(x))
        return np.array(g), np.array(J)

    rng = np.random.default_rng(7)
    for _ in range(3):
        x = np.concatenate([np.array(start.G) + rng.normal(scale=2e-3, size=3), rng.normal(scale=0.05, size=2),
                            [start.R3[2] + 1e-3 if name != "slipping" else 0.0]])
        _, J = g_J(x)
        h = 1e-6
        fd = np.empty_like(J)
        for k in range(6):
            e = np.zeros(6)
            e[k] = h
            fd[:, k] = (g_J(x + e)[0] - g_J(x - e)[0]) / (2 * h)
        assert np.max(np.abs(J - fd)) < 1e-8 * max(1.0, np.max(np.abs(J)))
        assert np.linalg.matrix_rank(J) == 6


def test_left_jacobian_matches_finite_differences():
    rng = np.random.default_rng(3)
    for scale in (1e-9, 0.3, 2.0):
        w = rng.normal(scale=scale, size=3)
        v = tuple(rng.normal(size=3))

        def turned(w, v=v):
            return np.array(spatial.rotate(tuple(w), v))

        for k in range(3):
            e = np.zeros(3)
            e[k] = 1e-7
            fd = (turned(w + e) - turned(w - e)) / 2e-7
            Jk = np.array(spatial.left_jacobian(tuple(w), tuple(np.eye(3)[k])))
            assert np.max(np.abs(fd - np.cross(Jk, turned(w)))) < 1e-7
        # the columns of rotation(w) are the turned unit vectors, and Q is orthonormal
        Q = np.array(spatial.rotation(tuple(w))).T
        assert np.max(np.abs(Q.T @ Q - np.eye(3))) < 1e-14
        assert np.max(np.abs(Q @ np.array(v) - turned(w))) < 1e-14


# --- errors ------------------------------------------------------------------------------------
@pytest.mark.parametrize("Xg, message", [
    (np.zeros(10), r"shape \(T, 2\)"), (np.zeros((10, 3)), r"shape \(T, 2\)"), (np.zeros((1, 2)), "T >= 2"),
    (np.array([[0.0, 0.0], [np.nan, 0.0]]), "finite")])
def test_bad_ground_motion_is_refused(Xg, message):
    with pytest.raises(ValueError, match=message):
        spatial.run("compliant", DFP1, Xg)


def test_unknown_model_and_batch_geometry_are_refused():
    with pytest.raises(ValueError, match="model must be one of"):
        spatial.run("rolling", DFP1, np.zeros((3, 2)))
    batch = Geometry.from_degrees(**{**TABLE1["DFP1"], "R1": np.array([3.0, 3.1])})
    with pytest.raises(ValueError, match="one case"):
        spatial.run("compliant", batch, np.zeros((3, 2)))


def test_a_step_too_large_fails_with_the_step_and_phase():
    X = np.array([[0.0, 0.0], [0.9, 0.4]])
    with pytest.raises(ConvergenceError, match=r"step 1.*reduce dt") as err:
        spatial.run("stick_slip", DFP1, X, options=NewtonOptions(max_iter=3))
    assert "sticking" in str(err.value) or "slipping" in str(err.value)


# --- what the paper's plane pi gets wrong --------------------------------------------------------
def test_a_step_solved_wholly_in_pi_pushes_rb3_off_its_guide():
    """Solved in the plane pi (RB3 rising along pi's in-plane normal to the increment), a circular
    orbit of 9.5 cm moves RB3 0.8 mm sideways at every step size; the consistent step keeps it on
    its guide. pi leans by psi = atan(d_perp / w): 3.15 deg at d_perp = 10 cm for DFP1."""
    dev = spatial.device(DFP1)
    assert math.degrees(math.atan(0.1 / math.sqrt(dev.L ** 2 - 0.1 ** 2))) == pytest.approx(3.15, abs=0.01)
    drift = []
    for dt in (0.02, 0.005):
        _, X = circle(dt)
        paper = spatial.run("compliant", DFP1, X, in_plane=True)
        ours = spatial.run("compliant", DFP1, X)
        assert np.array_equal(ours["R3"][:, :2], np.zeros_like(ours["R3"][:, :2]))
        drift.append(np.linalg.norm(paper["R3"][-1, :2] - paper["R3"][0, :2]))
    assert drift[0] == pytest.approx(0.817e-3, abs=0.005e-3)
    assert drift[1] == pytest.approx(drift[0], rel=1e-3)  # not a discretisation error
    # along a fixed azimuth pi is vertical and the two coincide
    _, x = sine()
    paper = spatial.run("compliant", DFP1, along(x, 30.0), azimuth=math.radians(30.0), in_plane=True)
    ours = spatial.run("compliant", DFP1, along(x, 30.0), azimuth=math.radians(30.0))
    assert np.max(np.abs(paper["R3"] - ours["R3"])) < 1e-12


@pytest.mark.parametrize("device", ["DFP1", "DFP2"])
def test_slipping_restores_compatibility_in_space(device):
    """After each stick-slip step the cap centres are back on the sphere centres up to O(dt^2): the
    slip turns the axis into the plane of C^1C^3 as well (a slip turning the pad about the normal
    of pi only would leave them 0.6 mm (DFP1) and 1.2 mm (DFP2) apart on this orbit, at every dt)."""
    g = DEVICES[device]
    gaps = []
    for dt in (0.01, 0.005):
        _, X = circle(dt)
        d = spatial.diagnostics(spatial.run("stick_slip", g, X), g)
        gaps.append(max(d["gap_1"].max(), d["gap_3"].max()))
    assert gaps[0] < 2e-5
    assert gaps[1] < gaps[0] / 3.5


# --- the 6 x 6 solve -----------------------------------------------------------------------------
def test_the_six_by_six_solve_is_lapacks_to_round_off_and_flags_a_singular_matrix():
    rng = np.random.default_rng(11)
    work = np.empty((6, 7))
    for _ in range(20):
        J = rng.normal(size=(6, 6)) * rng.choice([1e-3, 1.0, 1e3], size=6)  # rows of unlike scale
        g = rng.normal(size=6)
        ok, x = spatial.solve6(tuple(map(tuple, J)), tuple(g), work)
        assert ok
        expected = np.linalg.solve(J, g)
        assert np.max(np.abs(np.array(x) - expected)) < 1e-10 * np.max(np.abs(expected))
    J[:, 5] = 0.0  # a zero column: an exactly zero pivot
    ok, _ = spatial.solve6(tuple(map(tuple, J)), tuple(g), work)
    assert not ok


@pytest.mark.parametrize("model", MODELS)
def test_compiled_equals_the_same_functions_interpreted_on_random_devices(model):
    """A broken compiled kernel (a Numba typing or lowering that changes a result) is caught in the quick
    loop: the compiled history of random devices under an elliptical two-component motion equals the
    interpreted one to round-off."""
    from test_properties import random_device

    rng = np.random.default_rng(25)
    for k in range(3):
        g = random_device(rng, k % 2 == 0)
        a = 0.3 * min(g.capacity1, g.capacity3)
        t = np.linspace(0.0, 1.0, 41)
        Xg = np.stack([a * np.sin(2 * np.pi * t), 0.5 * a * (1.0 - np.cos(2 * np.pi * t))], axis=-1)
        ours, interpreted = (spatial.run(model, g, Xg, np.radians(1.0), azimuth=0.3, compiled=c) for c in (True, False))
        assert ours.keys() == interpreted.keys()
        for key, value in interpreted.items():
            if value.dtype.kind == "f":
                np.testing.assert_allclose(ours[key], value, rtol=0, atol=1e-12, err_msg=f"{model} {k} {key}")
            else:
                assert np.array_equal(ours[key], value), (model, k, key)
