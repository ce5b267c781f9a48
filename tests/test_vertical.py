"""The vertical component on the isolated structure (dccss.mechanics.structure): N(t)/W = 1 + a_v/g
scales the pendulum's restoring force and the friction; uplift (N <= 0) is found exactly; a frictionless
pendulum has its closed form."""

import math

import numpy as np
import pytest

from dccss.mechanics.structure import G, Ground, solve, summarize
from dccss.records import Record, RecordPair

RECORDS = "config/studies/records"
L = 1.8  # m
OMEGA = math.sqrt(G / L)


def _pair(scale=2.0, window=None):
    return RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=scale,
                                 window=window)


def _with_vertical(ground, a_v):
    """``ground`` with the vertical a_v (m/s²) at its interval ends (a number: constant)."""
    a_v = np.broadcast_to(np.asarray(a_v, dtype=float), ground.time.shape)
    return ground._replace(v0=a_v[:-1].copy(), v1=np.diff(a_v) / np.diff(ground.time))


@pytest.mark.parametrize("components", [1, 2])
@pytest.mark.parametrize(("a_v", "mu", "zeta"), [(0.3 * G, 0.04, 0.0), (-0.45 * G, 0.05, 0.05), (0.6 * G, 0.0, 0.02)])
def test_a_constant_vertical_acceleration_is_gravity_replaced_by_g_plus_a_v(components, a_v, mu, zeta):
    """ü + 2ζω u̇ + (g + a_v) u / L + μ (g + a_v) z = -a_g: the horizontal problem of a pendulum of length
    L g / (g + a_v), friction μ (1 + a_v / g) and the same damping coefficient 2ζω (ζ' = ζ ω / ω'). In one
    component the reference is the exact closed-form solution; the vertical's runs the integrator."""
    if components == 1:
        rec = Record.from_file(f"{RECORDS}/synthetic.AT2", scale=2.0)
    else:
        rec = _pair()
    ground = rec.ground_acceleration()
    t = rec.time[::4]
    n = 1.0 + a_v / G
    with_v = solve(_with_vertical(ground, a_v), t, L, mu, zeta)
    omega_v = OMEGA * math.sqrt(n)
    reference = solve(ground, t, L / n, mu * n, zeta * OMEGA / omega_v)
    assert np.max(np.abs(with_v.stroke - reference.stroke)) < 1e-9
    assert np.max(np.abs(with_v.stroke)) > 0.02  # it slides
    # F/W = N/W (u/L + μ z) = u/L' + μ' z: the reference's own
    assert np.allclose(with_v.shear_ratio, reference.shear_ratio, rtol=0, atol=1e-9)
    assert np.all(with_v.normal == pytest.approx(n, abs=1e-15))
    assert with_v.uplift == []


@pytest.mark.parametrize("components", [1, 2])
def test_a_vertical_of_zeros_is_the_horizontal_problem_bit_for_bit(components):
    rec = Record.from_file(f"{RECORDS}/synthetic.AT2", scale=2.0) if components == 1 else _pair()
    ground = rec.ground_acceleration()
    t = rec.time[::3]
    plain = solve(ground, t, L, 0.04, 0.03)
    zero = solve(_with_vertical(ground, 0.0), t, L, 0.04, 0.03)
    for a, b in zip(plain[:5], zero[:5]):
        assert np.array_equal(a, b)
    assert plain.peaks == zero.peaks[:2]
    assert np.all(zero.normal == 1.0) and zero.uplift == []


def test_the_integrator_with_a_constant_unit_normal_equals_todays_two_component_kernel_bit_for_bit():
    """In two components the same kernel serves both: N/W = 1 everywhere gives today's bits (the record's
    first 4 s: its largest strokes, sticking and sliding in turn)."""
    from dccss.mechanics import structure

    rec = _pair(window=(0.0, 4.0))
    ground = rec.ground_acceleration()
    refined, _ = ground.refined(rec.time)
    plain = structure.plane_history(refined, OMEGA, 0.02, 0.04 * G, compiled=False)[:4]
    assert 0 < np.count_nonzero(plain[3]) < refined.time.size  # sticking and sliding
    ones = structure.plane_history(refined._replace(v0=np.zeros(refined.a0.shape[0]), v1=np.zeros(refined.a0.shape[0])),
                                   OMEGA, 0.02, 0.04 * G, compiled=False)
    for a, b in zip(plain, ones):
        assert np.array_equal(a, b)


def _uplift_ground(components=1):
    """A ground shaking horizontally with a vertical that reaches -1.5 g twice: a_v = -1.5 g sin(2π t / 2)
    sampled at 0.01 s over 4 s (the sine's peaks at t = 0.5 s and 2.5 s)."""
    t = np.round(np.arange(0.0, 4.0 + 1e-9, 0.01), 10)
    a_h = 3.0 * np.sin(2 * np.pi * t / 1.3)
    acc = a_h if components == 1 else np.column_stack([a_h, 0.5 * a_h])
    return t, Ground.from_samples(t, acc, vertical=-1.5 * G * np.sin(np.pi * t))


@pytest.mark.parametrize("components", [1, 2])
def test_uplift_is_found_where_the_sampled_vertical_passes_minus_g(components):
    t, ground = _uplift_ground(components)
    r = solve(ground, t, L, 0.05, 0.0)
    # on the straight lines between samples a_v = -g where -1.5 sin(π t) crosses -1: the exact times from
    # the samples either side
    a_v = -1.5 * G * np.sin(np.pi * t)
    expected = []
    for k in np.flatnonzero(np.diff(np.sign(a_v + G)) != 0):
        expected.append(t[k] + (a_v[k] + G) / (a_v[k] - a_v[k + 1]) * (t[k + 1] - t[k]))
    assert len(expected) == 4  # 1 + a_v/g < 0 around the sine's negative peaks at t = 0.5 s and 2.5 s
    assert len(r.uplift) == 2
    for (start, end), exact in zip(r.uplift, (expected[:2], expected[2:])):
        assert (start, end) == pytest.approx(tuple(exact), abs=1e-12)
    # ... the continuous sine's crossings, to the sampling's accuracy
    assert r.uplift[0][0] == pytest.approx(math.asin(1 / 1.5) / math.pi, abs=1e-3)
    s = summarize(r)
    assert s["uplift_count"] == 2
    assert s["uplift_duration"] == pytest.approx(expected[1] - expected[0] + expected[3] - expected[2], abs=1e-12)
    assert s["normal_ratio_min"] == pytest.approx(-0.5, abs=1e-4)
    # no restoring force nor friction while lifted: u follows ü = -a_g alone (ζ = 0) between the crossings
    lifted = np.zeros(t.size, bool)
    for start, end in r.uplift:
        lifted |= (t > start + 1e-9) & (t < end - 1e-9)
    assert np.all(r.shear_ratio[lifted] == 0.0) and not r.sticking[lifted].any()


def test_free_flight_while_lifted_follows_the_ground_acceleration_alone():
    """Between the uplift's ends the horizontal equation is ü = -a_g: u'' integrated exactly over the
    piecewise-linear a_g (a cubic per interval) from the state at lift-off."""
    t, ground = _uplift_ground()
    r = solve(ground, t, L, 0.05, 0.0)
    start, end = r.uplift[0]
    inside = np.flatnonzero((t > start) & (t < end))
    k0 = inside[0]
    u, v = r.stroke[k0, 0], r.velocity[k0, 0]
    a = -ground.at(t)[:, 0]
    for k in inside[1:]:
        h = t[k] - t[k - 1]
        u = u + v * h + h * h * (2 * a[k - 1] + a[k]) / 6
        v = v + h * (a[k - 1] + a[k]) / 2
        assert r.stroke[k, 0] == pytest.approx(u, abs=1e-10)


@pytest.mark.parametrize("zeta", [0.0, 0.05])
def test_a_frictionless_pendulum_has_its_closed_form(zeta):
    """μ = 0: ü + 2ζω u̇ + ω² u = -A sin(Ω t) from rest, the damped oscillator's closed form."""
    A, Omega = 0.8, 2.1
    t = np.linspace(0.0, 12.0, 6001)
    r = solve(Ground.from_samples(t, A * np.sin(Omega * t)), t, L, 0.0, zeta)
    # particular solution U sin + V cos, then the free part matching u(0) = u'(0) = 0
    w2, c = OMEGA**2, 2 * zeta * OMEGA
    det = (w2 - Omega**2) ** 2 + (c * Omega) ** 2
    U, V = -A * (w2 - Omega**2) / det, A * c * Omega / det
    wd = OMEGA * math.sqrt(1 - zeta**2)
    P = -V
    Q = (-U * Omega + zeta * OMEGA * P) / wd
    exact = U * np.sin(Omega * t) + V * np.cos(Omega * t) + np.exp(-zeta * OMEGA * t) * (P * np.cos(wd * t)
                                                                                          + Q * np.sin(wd * t))
    # the ground acceleration is the sine joined by straight lines every 2 ms: O(h²) of its amplitude
    assert np.max(np.abs(r.stroke[:, 0] - exact)) < 2e-6 * np.max(np.abs(exact))
    assert not r.sticking.any()


def test_the_ground_keeps_its_vertical_when_refined_scaled_or_evaluated():
    t, ground = _uplift_ground()
    fine, index = ground.refined(np.linspace(0.0, 4.0, 1001))
    assert np.allclose(fine.normal()[index], ground.normal(np.linspace(0.0, 4.0, 1001)), rtol=0, atol=1e-13)
    assert np.allclose(ground.normal(), 1.0 - 1.5 * np.sin(np.pi * t), rtol=0, atol=1e-13)
    doubled = ground.scaled(2.0, vertical=2.0)
    assert np.array_equal(doubled.v0, 2 * ground.v0) and np.array_equal(doubled.a0, 2 * ground.a0)
    assert np.array_equal(ground.scaled(np.array([0.0])).v0, ground.v0)
    assert not Ground.from_samples(t, t, vertical=0 * t).has_vertical and ground.has_vertical
