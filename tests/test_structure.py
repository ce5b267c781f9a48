"""The isolated structure (dccss.mechanics.structure): closed forms, the circular interaction, the
ground acceleration of every excitation, and the stroke driving the pad."""

import math
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import scalar_at

from dccss.case import case_from
from dccss.checks import CaseError
from dccss.excitation import Component, Oriented, PlaneTable, Scaled, Sine, Table
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.structure import G, Ground, Structure, StructureError, period, respond, solve
from dccss.paper.prototypes import TABLE1
from dccss.records import Record, RecordPair
from dccss.simulation import simulate

RECORDS = "config/studies/records"
L = 1.8  # m: a pendulum of T = 2.69 s
OMEGA = math.sqrt(G / L)


def _record(name="synthetic.AT2", scale=2.0):
    return Record.from_file(f"{RECORDS}/{name}", scale=scale)


def _constant(a, duration=20.0, n=2001, components=1):
    t = np.linspace(0.0, duration, n)
    return t, Ground.from_samples(t, np.tile(np.atleast_1d(a), (n, 1)) if components == 2 else np.full(n, a))


# --- closed forms ------------------------------------------------------------------------------

@pytest.mark.parametrize("components", [1, 2])
def test_free_sliding_is_a_pendulum_of_length_L(components):
    """μ = 0: after a pulse the structure swings freely with the period 2π √(L / g)."""
    t = np.linspace(0.0, 30.0, 3001)
    pulse = np.where(t < 0.5, 1.0, 0.0)
    acc = pulse if components == 1 else np.column_stack([0.6 * pulse, 0.8 * pulse])
    r = solve(Ground.from_samples(t, acc), t, L, 0.0, 0.0)
    u = r.stroke[:, 0] if components == 1 else r.stroke @ np.array([0.6, 0.8])
    free = t > 1.0
    crossings = []
    for k in np.flatnonzero(free[:-1] & (np.sign(u[:-1]) != np.sign(u[1:]))):
        crossings.append(t[k] - u[k] * (t[k + 1] - t[k]) / (u[k + 1] - u[k]))
    measured = 2 * np.mean(np.diff(crossings))
    # linear interpolation of the crossings on a 0.01 s grid: O(1e-5) s
    assert measured == pytest.approx(period(L), abs=1e-4)
    assert period(L) == pytest.approx(2 * np.pi * np.sqrt(L / 9.80665))
    if components == 2:  # a pulse along one direction keeps the motion on it
        assert np.max(np.abs(r.stroke @ np.array([0.8, -0.6]))) < 1e-12


@pytest.mark.parametrize("components", [1, 2])
def test_a_harmonic_ground_motion_below_mu_g_never_moves_the_structure(components):
    mu = 0.05
    t = np.linspace(0.0, 10.0, 2001)
    a = 0.99 * mu * G * np.sin(3.0 * t)
    acc = a if components == 1 else np.column_stack([a * np.cos(0.3), a * np.sin(0.3)])
    r = solve(Ground.from_samples(t, acc), t, L, mu, 0.0)
    assert np.all(r.stroke == 0.0) and np.all(r.sticking)
    assert np.max(np.linalg.norm(r.z, axis=1)) <= 0.99 + 1e-12
    # the same just above mu g moves it
    r = solve(Ground.from_samples(t, acc / 0.99 * 1.05), t, L, mu, 0.0)
    assert np.max(np.abs(r.stroke)) > 1e-4


def _coulomb_rest(a, mu):
    """The undamped friction pendulum under a constant ground acceleration a > μ g, from rest at u = 0:
    half-cycles about the centres -(a ∓ μ g) / ω², each ending at rest; it stays where the demand
    |-a - ω² u| is at most μ g."""
    u, sign = 0.0, -1.0  # the first half-cycle slides towards -x
    for _ in range(1000):
        centre = -(a + sign * mu * G) / OMEGA**2
        u = 2 * centre - u
        if abs(-a - OMEGA**2 * u) <= mu * G:
            return u
        sign = -sign
    raise AssertionError("no rest")


@pytest.mark.parametrize("ratio", [1.5, 2.0, 2.9, 4.5, 7.0])
@pytest.mark.parametrize("components", [1, 2])
def test_a_constant_ground_acceleration_leaves_the_known_offset(ratio, components):
    """a = ratio μ g: for a <= 3 μ g the structure rests after one half-cycle at -2 (a - μ g) / ω²;
    beyond, each half-cycle loses 2 μ g / ω² of amplitude (the Coulomb oscillator)."""
    mu = 0.04
    a = ratio * mu * G
    direction = np.array([1.0]) if components == 1 else np.array([np.cos(1.1), np.sin(1.1)])
    t, ground = _constant(a * direction, duration=60.0, n=6001, components=components)
    r = solve(ground, t, L, mu, 0.0)
    expected = _coulomb_rest(a, mu)
    if ratio <= 3:
        assert expected == pytest.approx(-2 * (a - mu * G) / OMEGA**2, rel=1e-12)
    assert r.stroke[-1] == pytest.approx(expected * direction, abs=1e-12)
    assert r.sticking[-1] and not r.sticking[1:5].any()


def test_damping_brings_the_free_swing_to_rest_at_the_rate_of_a_damped_oscillator():
    """μ = 0, ζ = 0.05: successive peaks of the free swing decay by exp(-2π ζ / √(1 - ζ²))."""
    t = np.linspace(0.0, 40.0, 8001)
    acc = np.where(t < 0.5, 1.0, 0.0)
    zeta = 0.05
    u = solve(Ground.from_samples(t, acc), t, L, 0.0, zeta).stroke[:, 0]
    peaks = [abs(u[k]) for k in range(1, t.size - 1) if t[k] > 1.0 and abs(u[k]) >= abs(u[k - 1])
             and abs(u[k]) > abs(u[k + 1])]
    decay = np.array(peaks[2:8:2]) / np.array(peaks[0:6:2])  # peaks a period apart
    # the sampled peak is within (ω dt)² / 2 of the true one
    assert decay == pytest.approx(np.exp(-2 * np.pi * zeta / np.sqrt(1 - zeta**2)), rel=2e-5)


# --- one component: an independent event-driven integration ------------------------------------

def _reference_line(t, acc, mu, zeta):
    """The one-component history by scipy's Radau integrator between events (not the closed form):
    sliding until u̇ = 0, sticking until the demand reaches μ g (by bisection on the samples' lines)."""
    from scipy.integrate import solve_ivp

    ground = Ground.from_samples(t, acc)
    omega, f = OMEGA, mu * G

    a_g = scalar_at(ground)

    u, v, out, sticking = 0.0, 0.0, [0.0], True
    now = t[0]
    for k in range(1, t.size):
        while now < t[k]:
            if sticking:
                demand = np.array([-a_g(s) - omega**2 * u for s in (now, t[k])])
                if np.all(np.abs(demand) <= f):
                    now = t[k]
                    continue
                lo, hi = now, t[k]
                for _ in range(100):
                    mid = 0.5 * (lo + hi)
                    lo, hi = (mid, hi) if abs(-a_g(mid) - omega**2 * u) <= f else (lo, mid)
                now, sticking, sign = hi, False, np.sign(-a_g(hi) - omega**2 * u)
                continue

            def rhs(s, y, sign=sign):
                return [y[1], -a_g(s) - 2 * zeta * omega * y[1] - omega**2 * y[0] - f * sign]

            def stop(s, y, sign=sign):
                return sign * y[1]

            stop.terminal, stop.direction = True, -1
            sol = solve_ivp(rhs, (now, t[k]), [u, v], method="Radau", rtol=1e-12, atol=1e-14, events=stop,
                            first_step=1e-6)
            u, v, now = sol.y[0, -1], sol.y[1, -1], sol.t[-1]
            if sol.status == 1:
                v = 0.0
                demand = -a_g(now) - omega**2 * u
                sticking = abs(demand) <= f
                sign = np.sign(demand)
        out.append(u)
    return np.array(out)


def test_the_independent_integrations_read_the_ground_as_the_library_does():
    """``conftest.scalar_at`` (the references' fast ground) equals ``Ground.at`` bit for bit, outside the span too."""
    rec = _record()
    ground = Ground.from_samples(rec.time, rec.acceleration)
    probe = np.concatenate([[-1.0, rec.time[-1] + 1.0], rec.time, np.random.default_rng(5).uniform(-0.1, 10.1, 2000)])
    at = scalar_at(ground)
    assert np.array_equal([at(float(s)) for s in probe], ground.at(probe)[:, 0])


@pytest.mark.slow
def test_the_exact_one_component_solution_equals_an_independent_integration():
    rec = _record()
    n = 801  # 8 s of the record: stick, slip and reversals
    for mu, zeta in ((0.03, 0.0), (0.08, 0.1)):
        exact = solve(Ground.from_samples(rec.time[:n], rec.acceleration[:n]), rec.time[:n], L, mu, zeta)
        reference = _reference_line(rec.time[:n], rec.acceleration[:n], mu, zeta)
        assert np.max(np.abs(exact.stroke[:, 0] - reference)) < 1e-8
        assert exact.sticking.any() and not exact.sticking.all()


# --- two components ------------------------------------------------------------------------------

@pytest.mark.parametrize("azimuth", [30.0, 225.0])
@pytest.mark.parametrize(("mu", "zeta"), [(0.03, 0.0), (0.06, 0.1)])
def test_a_record_along_one_azimuth_gives_the_one_component_result_turned(azimuth, mu, zeta):
    rec = _record()
    one = solve(rec.ground_acceleration(), rec.time, L, mu, zeta)
    oriented = Oriented(rec, azimuth)
    two = solve(oriented.ground_acceleration(), rec.time, L, mu, zeta)
    d = oriented.direction
    assert np.max(np.abs(two.stroke - one.stroke * d)) < 1e-9
    assert np.max(np.abs(two.velocity - one.velocity * d)) < 1e-9
    assert np.array_equal(two.sticking, one.sticking)
    assert np.max(np.abs(two.shear_ratio - one.shear_ratio * d)) < 1e-6


@pytest.mark.parametrize(("mu", "zeta"), [(0.03, 0.0), (0.05, 0.05)])
def test_the_circular_interaction_holds_at_every_step(mu, zeta):
    pair = RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=2.0)
    r = solve(pair.ground_acceleration(), pair.time, L, mu, zeta)
    size = np.linalg.norm(r.z, axis=1)
    assert np.all(size <= 1 + 1e-12)
    sliding = ~r.sticking
    assert sliding.any() and r.sticking.any()
    assert np.allclose(size[sliding], 1.0, atol=1e-12)
    # sliding: z is along the velocity; sticking: the velocity is zero
    speed = np.linalg.norm(r.velocity, axis=1)
    moving = sliding & (speed > 1e-6)
    assert np.allclose(r.z[moving], r.velocity[moving] / speed[moving, None], atol=1e-9)
    assert np.all(r.velocity[r.sticking] == 0.0)
    # the force ratio is the pendulum's and the friction's
    assert np.allclose(r.shear_ratio, r.stroke / L + mu * r.z, rtol=0, atol=1e-15)
    # bidirectional motion is not two unidirectional ones: the interaction couples the components
    x = solve(pair.x.ground_acceleration(), pair.time, L, mu, zeta)
    assert np.max(np.abs(r.stroke[:, 0] - x.stroke[:, 0])) > 1e-3


def _slide_alone(y0, end, load, stop):
    """The two-component integrator alone over [0, end] from y0 = (u, u̇), interpreted."""

    from dccss.mechanics.structure import circular, integrator

    y, K = list(y0), [0.0] * ((integrator.STAGES + 1) * integrator.SIZE)
    ended, when, _ = integrator.integrate(y, end, 0.0, load, circular.UNIT_LAW.tolist(), False, stop,
                                          integrator.RTOL, integrator.ATOL,
                                          *integrator.tableau(False), K, [0.0] * 4, [0.0] * 4, [])
    return ended, when, np.array(y)


def _circular(load):
    """scipy's right-hand side of the circular interaction under the load (b0, b1, ω², 2ζω, μ g)."""
    b0, b1, w2, damp, friction = np.array(load[:2]), np.array(load[2:4]), *load[4:7]

    def rhs(t, y):
        f, v = -(b0 + b1 * t) - w2 * y[:2], y[2:]
        return np.concatenate([v, f - damp * v - friction * v / np.hypot(*v)])
    return rhs


@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_the_two_component_integrator_equals_scipy_on_a_curved_slide(zeta):
    """dccss's DOP853 against scipy's solve_ivp (DOP853, the same tolerances) on a slide whose velocity
    turns under a load across it, and on one that comes to rest along a curve: the same state to
    1e-12 m and m/s, and the same time of rest to 1e-10 s."""
    from scipy.integrate import solve_ivp

    from dccss.mechanics.structure.integrator import ATOL, NONE, REST_SPEED, RTOL, STOP

    load = (0.3, -1.2, 2.0, 0.5, OMEGA**2, 2 * zeta * OMEGA, 0.05 * G, 1.0, 0.0, 20.0, 20.0, 0.0, 0.0, 0.0)
    y0 = [0.01, -0.02, 0.3, 0.1]
    ended, when, y = _slide_alone(y0, 0.5, load, stop=False)
    ours = solve_ivp(_circular(load), (0.0, 0.5), y0, method="DOP853", rtol=RTOL, atol=ATOL)
    assert (ended, when) == (NONE, 0.5)
    assert np.max(np.abs(y - ours.y[:, -1])) < 1e-12
    turned = math.degrees(math.atan2(y[3], y[2]) - math.atan2(y0[3], y0[2]))
    assert abs(turned) > 30.0  # a curved path, not a line

    load = (0.0, 0.0, 0.0, 0.0, OMEGA**2, 2 * zeta * OMEGA, 0.05 * G, 1.0, 0.0, 20.0, 20.0, 0.0, 0.0, 0.0)
    y0 = [0.05, -0.03, 0.2, 0.1]

    def rest(t, y):
        return math.hypot(y[2], y[3]) - REST_SPEED
    rest.terminal, rest.direction = True, -1
    ended, when, y = _slide_alone(y0, 2.0, load, stop=True)
    ref = solve_ivp(_circular(load), (0.0, 2.0), y0, method="DOP853", rtol=RTOL, atol=ATOL, events=rest)
    assert ended == STOP and ref.status == 1
    assert abs(when - ref.t_events[0][0]) < 1e-10
    assert np.max(np.abs(y - ref.y_events[0][0])) < 1e-12
    assert abs(math.hypot(y[2], y[3]) - REST_SPEED) < 1e-14  # located on the event
    turned = math.degrees(math.atan2(y[3], y[2]) - math.atan2(y0[3], y0[2]))
    assert abs(turned) > 30.0


def _pair_response(scale=1.5, mu=0.04, zeta=0.02):
    pair = RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=scale)
    r = solve(pair.ground_acceleration(), pair.time, L, mu, zeta)
    return np.column_stack([r.stroke, r.velocity, r.z, r.sticking])


@pytest.mark.slow
def test_the_two_component_response_does_not_depend_on_the_processors_blas(monkeypatch):
    """No BLAS in the two-component integration (whose kernels OpenBLAS chooses by processor): the
    same bits under OpenBLAS' oldest kernels (Katmai) in another process."""
    import os
    import subprocess
    import sys

    monkeypatch.setenv("DCCSS_BACKEND", "python")
    ours = _pair_response()
    code = ("import sys; sys.path.insert(0, 'tests'); from test_structure import _pair_response; "
            "print(_pair_response().tobytes().hex())")
    env = {**os.environ, "OPENBLAS_CORETYPE": "Katmai", "DCCSS_BACKEND": "python"}
    other = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert other.stdout.strip() == ours.tobytes().hex()


@pytest.mark.slow
def test_the_two_component_response_compiled_equals_interpreted(monkeypatch):
    """The integrator compiled (a long record) and interpreted (a short one) give the same bits."""
    from dccss.mechanics import backend

    results = []
    for name in ("python", "numba"):
        monkeypatch.setenv("DCCSS_BACKEND", name)
        results.append([_pair_response(scale, mu, zeta) for scale, mu, zeta in ((1.5, 0.04, 0.0), (2.0, 0.1, 0.05))])
        assert backend.choose(1000, 25) == name
    for interpreted, compiled in zip(*results):
        assert np.array_equal(interpreted, compiled)


def test_the_one_component_response_compiled_equals_interpreted():
    """The exact one-component solution compiled (a long record, a spectrum's periods) and interpreted (a short
    one) gives the same bits: records with stops, long sticking, breakaways and free sliding (μ = 0)."""
    from dccss.mechanics import structure

    rng = np.random.default_rng(11)
    mixed = 0
    for trial in range(8):
        n = int(rng.integers(200, 1500))
        t = np.cumsum(np.r_[0.0, rng.uniform(0.004, 0.011, n - 1)])
        a = np.convolve(rng.normal(size=n), np.ones(15) / 15, "same") * rng.uniform(1.0, 12.0)
        ground = Ground.from_samples(t, a)
        for mu, zeta in ((0.0, 0.0), (0.0, 0.05), (0.03, 0.0), (0.08, 0.1)):
            args = (ground.time, ground.a0[:, 0], ground.a1[:, 0], 2.3, zeta, mu * G)
            interpreted = structure.line_history(*args, compiled=False)
            compiled = structure.line_history(*args, compiled=True)
            for x, y in zip(interpreted, compiled):
                assert np.array_equal(x, y), (trial, mu, zeta)
            mixed += bool(interpreted[3].any() and not interpreted[3].all())  # stops and breakaways both
    assert mixed >= 6


def test_a_one_component_chatter_is_an_error_naming_the_time(monkeypatch):
    from dccss.mechanics import structure

    monkeypatch.setattr(structure.exact, "MAX_PHASES", 0)
    ground = Ground.from_samples([0.0, 0.01, 0.02], [0.0, 1.0, 0.0])
    with pytest.raises(RuntimeError, match=r"more than 0 stick/slip phases in the sample interval at t = 0 s"):
        structure.line_history(ground.time, ground.a0[:, 0], ground.a1[:, 0], 2.0, 0.0, 0.05 * G, compiled=False)


def test_a_two_component_step_that_cannot_meet_the_tolerance_is_an_error_naming_the_time(monkeypatch):
    from dccss.mechanics import structure

    monkeypatch.setenv("DCCSS_BACKEND", "python")
    monkeypatch.setattr(structure.circular, "RTOL", 1e-30)
    monkeypatch.setattr(structure.circular, "ATOL", 1e-40)
    with pytest.raises(RuntimeError, match=r"step fell below 1e-14 s in the sample interval at t = [0-9.]+ s"):
        _pair_response()


# --- the ground acceleration of each excitation --------------------------------------------------

def test_a_sine_drives_the_structure_with_its_second_derivative():
    sine = Sine(0.1, 3.0, 5.0)
    ground = sine.ground_acceleration()
    t = np.linspace(0.0, 5.0, 777)
    exact = -0.1 * 9.0 * np.sin(3.0 * t)
    # linear interpolation between 4000 samples a period: (2π / 4000)² / 8 of the peak
    assert np.max(np.abs(ground.at(t)[:, 0] - exact)) <= 0.9 * (2 * np.pi / 4000) ** 2 / 8 * 1.0001
    # a displacement below the threshold a = μ g never moves it; the structure starts at rest
    r = respond(ground, t, SimpleNamespace(L=L), Structure(0.1))
    assert np.all(r.stroke == 0.0)


def test_a_table_drives_the_structure_with_the_derivative_of_its_velocity():
    t = np.linspace(0.0, 2.0, 41)
    x = 0.05 * np.sin(2.0 * t) ** 2
    table = Table(t, x)
    ground = table.ground_acceleration()
    mid = 0.5 * (t[:-1] + t[1:])
    slope = np.diff(table.velocity(t)) / np.diff(t)
    assert np.allclose(ground.at(mid)[:, 0], slope, rtol=0, atol=1e-14)
    plane = PlaneTable(t, x, -2 * x)
    assert np.allclose(plane.ground_acceleration().at(mid), np.column_stack([slope, -2 * slope]), atol=1e-14)


def test_wrappers_carry_the_ground_acceleration():
    rec = _record(scale=1.0)
    base = rec.ground_acceleration()
    assert np.array_equal(base.a0[:, 0], rec.acceleration[:-1])
    assert np.allclose(Scaled(rec, -2.0).ground_acceleration().a0, -2 * base.a0, rtol=0, atol=0)
    turned = Oriented(rec, 90.0).ground_acceleration()
    assert np.array_equal(turned.a0[:, 0], 0 * base.a0[:, 0]) and np.array_equal(turned.a0[:, 1], base.a0[:, 0])
    pair = RecordPair(rec, _record("synthetic_y.AT2", scale=1.0))
    only_y = Component(pair, "y").ground_acceleration()
    assert np.all(only_y.a0[:, 0] == 0) and np.array_equal(only_y.a0[:, 1], pair.y.acceleration[:-1])


def test_refining_the_ground_keeps_its_acceleration():
    rec = _record()
    ground = rec.ground_acceleration()
    times = np.arange(rec.t_start, rec.t_end, 0.0037)
    fine, index = ground.refined(times)
    assert np.allclose(fine.time[index], times, rtol=0, atol=1e-12)
    probe = np.linspace(rec.t_start, rec.t_end, 9999)
    assert np.allclose(fine.at(probe), ground.at(probe), rtol=0, atol=1e-12)
    # output between the samples is the same history
    r = solve(ground, times, L, 0.04, 0.0)
    on_samples = solve(ground, rec.time, L, 0.04, 0.0)
    common = np.isin(np.round(times, 9), np.round(rec.time, 9))
    assert common.sum() > 10
    k = np.searchsorted(np.round(rec.time, 9), np.round(times[common], 9))
    assert np.allclose(r.stroke[common], on_samples.stroke[k], rtol=0, atol=1e-12)


# --- parameters ----------------------------------------------------------------------------------

@pytest.mark.parametrize(("friction", "damping", "key"), [(-1e-9, 0.0, "friction"), (1.0, 0.0, "friction"),
                                                         (-0.1, 0.0, "friction"), (0.05, -0.01, "damping"),
                                                         (0.05, 1.0, "damping"), (float("nan"), 0.0, "friction"),
                                                         ("0.05", 0.0, "friction")])
def test_bad_structure_parameters_are_refused_naming_the_key(friction, damping, key):
    with pytest.raises(StructureError, match=rf"structure\.{key}"):
        Structure(friction, damping)


CASE = {"prototype": "DFP1", "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": 2.0}, "dt": 0.01,
        "model": "compliant"}


@pytest.mark.parametrize(("structure", "message"), [
    ({"friction": -0.01}, r"structure\.friction: -0\.01 is outside 0 <= μ < 1"),
    ({"friction": 1.2}, r"structure\.friction: 1\.2 is outside"),
    ({"friction": 0.05, "damping": -0.1}, r"structure\.damping: -0\.1 is outside 0 <= ζ < 1"),
    ({"friction": 0.05, "mass": 1.0},
     r"structure: unknown key\(s\) \['mass'\]; allowed: \['damping', 'friction', 'friction_on', 'property'\]"),
    ({"damping": 0.05}, r"structure: missing key\(s\) \['friction'\]"),
    ({"friction": 0.05, "friction_on": "pad"}, r"structure\.friction_on: must be one of \['device', 'surfaces'\]"),
    ({"friction": 0.95, "friction_on": "surfaces"}, r"structure\.friction: 0\.95 is a device friction "
                                                    r"1\.044 = \(μ1 R1 \+ μ3 R3\) / L times λ, outside 0 <= μ < 1"),
    (0.05, r"structure: expected a mapping"),
])
def test_a_case_file_refuses_a_bad_structure_naming_the_key(structure, message):
    from pathlib import Path

    with pytest.raises(CaseError, match=message):
        case_from({**CASE, "structure": structure}, Path(RECORDS))


def test_a_surfaces_friction_is_the_device_friction_times_R1_plus_R3_over_L():
    from pathlib import Path

    geometry = Geometry.from_degrees(**TABLE1["DFP1"])
    surfaces = Structure(0.04, friction_on="surfaces")
    assert surfaces.device_friction(geometry) == pytest.approx(0.04 * (geometry.R1 + geometry.R3) / geometry.L,
                                                               rel=1e-15)
    a = case_from({**CASE, "structure": {"friction": 0.04, "friction_on": "surfaces"}}, Path(RECORDS)).run()
    mu = 0.04 * 2.0 / geometry.L
    b = case_from({**CASE, "structure": {"friction": mu}}, Path(RECORDS)).run()
    assert np.array_equal(a["stroke"].values, b["stroke"].values)
    assert a.attrs["structure_friction"] == mu and a.attrs["structure_friction_given"] == 0.04
    assert a.attrs["structure_friction_on"] == "surfaces"


def test_the_work_argument_behind_the_surfaces_reading_holds_on_the_compliant_model():
    """Friction on the surfaces works on the arcs the pad slides, (R1 + R3) |dθ²|; the device's on the
    stroke |du|. Along a compliant history the two agree to the pad's tilt: (R1 + R3) Σ|Δθ²| = Σ|Δu|
    (R1 + R3) / L up to the factor 1 / cos θ² (at most 1 / cos of the largest tilt)."""
    from pathlib import Path

    geometry = Geometry.from_degrees(**TABLE1["DFP1"])
    ds = case_from({**CASE, "structure": {"friction": 0.05}}, Path(RECORDS)).run()
    arcs = (geometry.R1 + geometry.R3) * np.sum(np.abs(np.diff(np.radians(ds["theta2"].values))))
    stroke = (geometry.R1 + geometry.R3) / geometry.L * np.sum(np.abs(np.diff(ds["stroke"].values)))
    largest = np.radians(np.max(np.abs(ds["theta2"].values)))
    assert stroke <= arcs * (1 + 1e-6) and arcs <= stroke / np.cos(largest)
    assert arcs / stroke - 1 > 1e-4  # the tilt's share is seen


# --- the stroke drives the pad -------------------------------------------------------------------

@pytest.fixture(scope="module")
def device():
    return Geometry.from_degrees(**TABLE1["DFP1"])


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_the_pad_under_the_stroke_equals_the_stroke_given_as_a_table(model, device, tmp_path):
    """RB1 moves by minus the stroke; the same motion as a table gives the same kinematics, bit for bit."""
    from pathlib import Path

    case = case_from({**CASE, "model": model, "structure": {"friction": 0.04, "damping": 0.02}}, Path(RECORDS))
    ds = case.run()
    assert np.array_equal(ds["Rx1"].values, -ds["stroke"].values + 0.0)
    table = tmp_path / "stroke.csv"
    np.savetxt(table, np.column_stack([ds["t"].values, -ds["stroke"].values]), delimiter=",",
               header="time,displacement", comments="", fmt="%.17g")
    again = case_from({**CASE, "model": model, "excitation": {"kind": "table", "file": str(table)}}, Path("."))
    other = again.run()
    for name in ("theta2", "Rx2", "Ry3", "rise", "I_A", "I_D"):
        assert np.array_equal(ds[name].values, other[name].values), name
    # the ground motion is kept beside it
    assert np.array_equal(ds["Xg"].values, case.excitation.displacement(ds["t"].values))


def test_compliant_sliding_under_a_stroke_is_a_pendulum_of_length_L(device):
    """The device's pendulum length is |C1C3| = L: in the compatible configuration at θ² the plates
    are L sin θ² apart sideways and RB3 has risen by L (1 - cos θ²) (Eq. 41); the compliant model
    follows it up to the interpenetration it lets through (a pad rotation off by at most I / L)."""
    from pathlib import Path

    theta = np.linspace(-0.2, 0.2, 41)
    q = device.compatible(theta)
    assert np.allclose(q[:, 6] - q[:, 0], device.L * np.sin(theta), rtol=0, atol=1e-15)
    assert np.allclose(q[:, 7] - device.Ry3_compatible(0.0), device.L * (1 - np.cos(theta)), rtol=0, atol=1e-15)
    ds = case_from({**CASE, "structure": {"friction": 0.05}}, Path(RECORDS)).run()
    u = ds["stroke"].values
    theta = np.radians(ds["theta2"].values)
    interpenetration = max(np.max(np.abs(ds[f"I_{c}"].values)) for c in "ABCD")
    assert 0 < interpenetration < 1e-4
    assert np.max(np.abs(np.sin(theta) - u / device.L)) <= interpenetration / device.L
    assert ds.attrs["structure_pendulum_length_m"] == device.L


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_a_two_component_structure_drives_the_spatial_models(model, tmp_path):
    from pathlib import Path

    spec = {**CASE, "model": model, "excitation": {"kind": "record", "file": ["synthetic.AT2", "synthetic_y.AT2"],
                                                    "scale": 1.5}, "structure": {"friction": 0.05}}
    ds = case_from(spec, Path(RECORDS)).run()
    for name in ("stroke_x", "stroke_y", "stroke_velocity_x", "shear_ratio_y", "z_x", "z_y", "structure_sticking"):
        assert name in ds, name
    assert ds["stroke_x"].attrs["units"] == "m" and ds["shear_ratio_x"].attrs["units"] == "1"
    assert ds.attrs["motion"] == "bidirectional" and ds.attrs["structure_friction"] == 0.05
    assert "minus the stroke" in ds.attrs["imposed_motion"]
    # the same stroke as a two-component table
    table = tmp_path / "stroke.csv"
    np.savetxt(table, np.column_stack([ds["t"].values, -ds["stroke_x"].values, -ds["stroke_y"].values]),
               delimiter=",", header="time,x,y", comments="", fmt="%.17g")
    other = case_from({**CASE, "model": model, "excitation": {"kind": "table", "file": str(table)}}, Path(".")).run()
    for name in ("tilt", "rise", "G2_x", "G2_y"):
        assert np.allclose(ds[name].values, other[name].values, rtol=0, atol=1e-12, equal_nan=True), name


def test_without_a_structure_the_ground_displacement_is_imposed(device):
    from pathlib import Path

    ds = case_from(CASE, Path(RECORDS)).run()
    assert "stroke" not in ds and "structure_friction" not in ds.attrs
    assert np.array_equal(ds["Rx1"].values, ds["Xg"].values)


def test_simulate_takes_a_structure(device):
    sine = Sine(0.05, 2.0, 6.0)
    ds = simulate(device, sine, model="compliant", dt=0.01, structure=Structure(0.02, 0.05))
    # the sine's acceleration 0.2 m/s² is above μ g = 0.196 m/s²: it slides, a little
    assert 0 < np.max(np.abs(ds["stroke"].values)) < 0.05
    assert ds.attrs["structure_damping"] == 0.05
    assert ds.attrs["structure_period_s"] == pytest.approx(2 * np.pi * np.sqrt(device.L / G))


def test_the_two_component_integration_converges_with_its_tolerance(monkeypatch):
    """The circular interaction has no closed form: DOP853 at relative tolerance 1e-12 (the default)
    and 1e-9 agree to far below a millimetre, so the default is exact for every practical purpose."""
    from dccss.mechanics import structure

    pair = RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=1.5)
    tight = solve(pair.ground_acceleration(), pair.time, L, 0.04, 0.02)
    monkeypatch.setattr(structure.circular, "RTOL", 1e-9)
    monkeypatch.setattr(structure.circular, "ATOL", 1e-11)
    loose = solve(pair.ground_acceleration(), pair.time, L, 0.04, 0.02)
    difference = np.max(np.abs(tight.stroke - loose.stroke))
    assert 0 < difference < 1e-7


@pytest.mark.parametrize("components", [1, 2])
def test_the_peaks_are_over_the_records_samples_not_only_the_steps(components):
    """A structure that never slides carries F/W = -a_g / g: its peak is the record's PGA / g whatever the
    steps the pad is solved at (before, the peak was read at the steps only: 22 % low at Δt = 0.05 s on a
    0.005 s record)."""
    from dccss.mechanics.structure import summarize

    t = np.arange(0.0, 2.0 + 1e-9, 0.005)
    acc = 0.35 * G * np.sin(2 * np.pi * 3.3 * t) * np.exp(-t)
    ground = Ground.from_samples(t, acc if components == 1 else np.stack([acc, 0.5 * acc], axis=1))
    peak = np.max(np.abs(acc)) / G * (1.0 if components == 1 else math.hypot(1.0, 0.5))
    coarse = np.arange(0.0, 2.0 + 1e-9, 0.05)
    response = solve(ground, coarse, 1.8, 0.9, 0.0)
    assert response.sticking.all() and np.max(np.abs(response.stroke)) == 0.0  # it sticks throughout
    assert np.max(np.linalg.norm(response.shear_ratio, axis=1)) < 0.95 * peak  # the steps miss the peak
    assert summarize(response)["shear_ratio_max_abs"] == pytest.approx(peak, rel=1e-12)
    assert response.peaks[0] == 0.0


@pytest.mark.parametrize("components", [1, 2])
def test_the_peaks_reach_the_records_end_when_the_step_does_not(components):
    """A pulse in the record's last 0.05 s: a step of 0.04 s ends the requested times 0.03 s before the
    record does; the peaks are still the whole record's, as with a step that divides it (before, they
    stopped at the last step: 0.0016 m against 0.0080 m)."""
    t = np.arange(1001) * 0.01
    a = np.where(t > 9.95, 0.6 * G, 0.0)
    acceleration = a if components == 1 else np.column_stack([a, 0.5 * a])
    ground = Ground.from_samples(t, acceleration)
    fine = solve(ground, t, 1.8, 0.05, 0.0)
    coarse = solve(ground, np.arange(250) * 0.04, 1.8, 0.05, 0.0)
    assert fine.peaks[0] > 5e-3 and coarse.peaks == pytest.approx(fine.peaks, rel=1e-12)
    assert np.max(np.linalg.norm(coarse.stroke, axis=1)) < 0.5 * fine.peaks[0]  # the steps alone miss the pulse


def test_the_tableau_is_scipys_dop853_read_without_importing_scipy_integrate():
    """The two-component integration's coefficients are scipy.integrate.DOP853's, bit for bit, read from
    their file in a process that does not import scipy.integrate (0.3-0.5 s in every job)."""
    import subprocess
    import sys

    from scipy.integrate import DOP853

    from dccss.mechanics.structure.integrator import dop853_coefficients

    for ours, theirs in zip(dop853_coefficients(), (DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5), strict=True):
        assert ours.dtype == theirs.dtype and np.array_equal(ours, theirs)
    probe = ("import sys; from dccss.mechanics.structure.integrator import tableau; tableau(False); "
             "print('scipy.integrate' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True).stdout == "False\n"
