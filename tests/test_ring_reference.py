"""The independent integration of a friction pendulum bounded by a retaining ring (tests/ring_reference.py),
checked on its own before any comparison with the library's rings: without rings it is the library's exact
one-component solution (the rigid slider's ``exact.line_history``, the articulated slider's
``series.series_line_history``, both closed forms), a constant push into the ring impacts when and as fast as
the damped oscillator's closed form says, the energy balance closes, and on the synthetic record scaled to
five or six impacts its extrapolations converge.

Closed forms (``_oscillator``): under a constant load p, ü + 2ζω u̇ + ω² u = p from (u0, v0) is
u = p / ω² + e^(-ζωt) (A cos ω_d t + B sin ω_d t), A = u0 - p / ω², B = (v0 + ζω A) / ω_d, ω_d = ω √(1 - ζ²);
the ring is reached at the first root of u = d before u̇ falls to 0, found by bisection to the last bit.

Measured on the synthetic record × 4 (PGA 1.4 g, 20 s; DFP1: L = 1.8196 m, the rings at L_j sin 11°, ζ = 0.02;
the articulated halves with μ̄ 0.03 on RB1 and 0.06 on RB3): R2 the second-order extrapolation from 250, 500
and 1000 steps a 0.01 s sample, R2' that from 500, 1000 and 2000, the spread between the two first-order
extrapolations under R2 (``richardson``), and the run time of 1000 steps a sample (the slow tests):

==============================================  =======  ========  ======  ========  ======  ============
slider                                          impacts  contacts  spread  |R2-R2'|  1000 s  impacts' |ΔR2|
==============================================  =======  ========  ======  ========  ======  ============
rigid, μ = 0.03                                 6        6         1.2e-7  6.8e-9    0.9 s   3e-9 s, 1e-8 m/s
rigid, μ = 0.05                                 5        5         3.2e-8  1.0e-8    0.8 s   1e-8 s, 6e-8 m/s
articulated, L_j = 0.9098 m                     6        14        4.0e-8  8.2e-9    1.1 s   1e-8 s, 1e-8 m/s
articulated, hinge 5 cm (L_j = 0.860, 0.960 m)  5        14        7.8e-8  7.0e-8    1.0 s   1e-7 s, 2e-7 m/s
==============================================  =======  ========  ======  ========  ======  ============

The library's own ring (``exact.ring_history``, the rigid slider) was within 5e-9 m (μ = 0.03) and 1.4e-8 m
(μ = 0.05) of R2 there, impact for impact (its ring force signed, this one's outward positive).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from ring_reference import ENERGY, G, richardson, rigid, series
from series_reference import integrate

from dccss.mechanics.structure import Ground, Structure, respond
from dccss.mechanics.structure.exact import line_history
from dccss.mechanics.structure.series import BOTH, SLIDE1, series_line_history
from dccss.mechanics.structure.sliders import pendulums, ring_strokes
from dccss.paper.prototypes import DFP1
from dccss.records import read_at2

RECORD = Path(__file__).resolve().parent.parent / "config/studies/records/synthetic.AT2"
#: DFP1's rigid slider: its pendulum (1.8196 m) and the stroke at which it meets the ring, L sin 11°
L = float(DFP1.L)
D = L * math.sin(math.radians(11.0))
INPUT, KINETIC, POTENTIAL, DAMPING, FRICTION, IMPACTS, SCHEME = range(len(ENERGY))


def _ground(scale, seconds):
    """The synthetic record (in g) × ``scale`` over its first ``seconds``: time, a0, a1 (m/s², m/s³)."""
    dt, acc = read_at2(RECORD)
    a = acc[:int(round(seconds / dt)) + 1] * G * scale
    return np.arange(a.size) * dt, a[:-1], np.diff(a) / dt


def _oscillator(u0, v0, p, omega, zeta, t):
    """u and u̇ at t of ü + 2ζω u̇ + ω² u = p (constant) from (u0, v0) (the module docstring)."""
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    A = u0 - p / omega**2
    B = (v0 + zeta * omega * A) / wd
    e, c, s = math.exp(-zeta * omega * t), math.cos(wd * t), math.sin(wd * t)
    return p / omega**2 + e * (A * c + B * s), e * ((B * wd - zeta * omega * A) * c - (A * wd + zeta * omega * B) * s)


def _bisect(past, lo, hi):
    """The first point of (lo, hi] where ``past`` holds (it holds at hi, not at lo), to the last bit."""
    while True:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            return hi
        lo, hi = (lo, mid) if past(mid) else (mid, hi)


def _reach(u0, v0, p, omega, zeta, target):
    """When the oscillator under p from (u0, v0 >= 0) first reaches ``target`` > u0, and its speed there; it must
    do so before it stops."""
    wd = omega * math.sqrt(1.0 - zeta * zeta)
    stop = _bisect(lambda t: _oscillator(u0, v0, p, omega, zeta, t)[1] <= 0.0, 1e-9, math.pi / wd)
    assert _oscillator(u0, v0, p, omega, zeta, stop)[0] > target
    when = _bisect(lambda t: _oscillator(u0, v0, p, omega, zeta, t)[0] >= target, 0.0, stop)
    return when, _oscillator(u0, v0, p, omega, zeta, when)[1]


def _push(A, seconds=1.5):
    """A constant push: a_g = -A (m/s²) from rest, sampled every 0.01 s."""
    n = int(round(seconds / 0.01))
    return np.linspace(0.0, seconds, n + 1), np.full(n, -A), np.zeros(n)


# --- without rings: the library's exact solutions -----------------------------------------------------

def test_far_from_its_ring_the_rigid_slider_is_the_exact_one():
    """d = 10 m, never reached: Coulomb friction on 6 s of the record × 2 equals the closed-form exact solution;
    the raw error halves with the step, the second-order extrapolation is within 1e-7 m (measured 2.6e-8 m)."""
    time, a0, a1 = _ground(2.0, 6.0)
    zeta, mu = 0.02, 0.05
    u, v, _, stick = line_history(time, a0, a1, math.sqrt(G / L), zeta, mu * G)
    runs = [rigid(time, a0, a1, L, zeta, mu, 10.0, substeps=n) for n in (100, 200, 400)]
    errors = [np.max(np.abs(r["u"] - u)) for r in runs]
    assert 1.8 < errors[0] / errors[1] < 2.2 and 1.8 < errors[1] / errors[2] < 2.2
    best = richardson(runs)
    assert np.max(np.abs(best["u"] - u)) < 1e-7 and np.max(np.abs(best["v"] - v)) < 3e-7
    assert best["spread"] < 1e-6 and all(r["events"] == 0 for r in runs)
    assert stick.any() and not stick.all()  # it sticks and slides in turn
    # the steps' own rounding: the energy balance of the scheme closes
    E = runs[-1]["energy"]
    assert np.max(np.abs(E[:, INPUT] - E[:, KINETIC:].sum(axis=1))) < 1e-11


def test_far_from_their_rings_the_articulated_slider_is_the_exact_one():
    """The halves of DFP1 with the hinge 5 cm above the pad's centre (L_1 = 0.860, L_3 = 0.960 m), μ̄ 0.03 and
    0.06, rings never reached: the stroke and the lower surface's share equal the closed-form series solution,
    whose surfaces slide alone and together, within 1e-7 m (measured 2e-8 m)."""
    time, a0, a1 = _ground(2.0, 6.0)
    zeta, m1, m3 = 0.02, 0.03 * G, 0.06 * G
    L1, L3 = pendulums(DFP1, 0.05)
    u, v, u1, phase, _ = series_line_history(time, a0, a1, G / L1, G / L3, math.sqrt(G / (L1 + L3)), zeta, m1, m3)
    assert {SLIDE1, BOTH} <= set(phase.tolist())
    runs = [series(time, a0, a1, L1, L3, zeta, m1, m3, 10.0, 10.0, substeps=n) for n in (100, 200, 400)]
    best = richardson(runs)
    assert np.max(np.abs(best["u"] - u)) < 1e-7 and np.max(np.abs(best["u_j"][:, 0] - u1)) < 1e-7
    assert np.max(np.abs(best["v"] - v)) < 3e-7


# --- closed forms: a constant push into the ring --------------------------------------------------------

def test_a_constant_push_meets_the_ring_when_the_damped_oscillator_does():
    """The rigid slider pushed by a constant 0.4 g (μ = 0.05, ζ = 0.05) slides as the oscillator under
    p = 0.4 g - μ g until u = d: the impact's time and speed to 1e-8 (measured 2e-11 s, 1.3e-10 m/s). Then it
    stays: the demand 0.4 g - ω² d pushes outward, F/W = 0.4 and the ring carries 0.4 g - ω² d - μ g."""
    zeta, mu, A = 0.05, 0.05, 0.4 * G
    omega = math.sqrt(G / L)
    when, speed = _reach(0.0, 0.0, A - mu * G, omega, zeta, D)
    runs = [rigid(*_push(A), L, zeta, mu, D, substeps=n) for n in (100, 200, 400)]
    best = richardson(runs)
    assert best["impacts"].shape == (1, 2)
    assert abs(best["impacts"][0, 0] - when) < 1e-8 and abs(best["impacts"][0, 1] - speed) < 1e-8
    end = runs[-1]
    assert end["at_ring"][-1, 0] and end["u"][-1] == D and end["v"][-1] == 0.0
    assert end["force"][-1] == pytest.approx(A / G, abs=1e-12)
    assert end["ring_force"][-1, 0] == pytest.approx(A - omega**2 * D - mu * G, abs=1e-12)
    before = np.searchsorted(np.linspace(0.0, 1.5, 151), when) - 1
    assert not end["at_ring"][before, 0] and end["at_ring"][before + 2:, 0].all()


def test_a_pad_the_demand_pulls_back_leaves_the_ring_at_the_impact():
    """Pushed by 6 m/s² for 0.3 s, then by 0.5 m/s² only (a step of the ground: a0 jumps between intervals), the
    rigid slider meets the ring where the oscillator under 0.5 - μ g says, while the demand 0.5 - ω² d pulls it
    back past the friction: it leaves at once, the oscillator under 0.5 + μ g from (d, 0) at the impact. The
    impact to 1e-8 and the stroke after it to 1e-9 m (measured 4e-10 s, 3e-9 m/s, 2e-10 m)."""
    zeta, mu = 0.05, 0.05
    omega = math.sqrt(G / L)
    time = np.linspace(0.0, 1.0, 101)
    a0, a1 = np.where(time[:-1] < 0.3 - 1e-9, -6.0, -0.5), np.zeros(100)
    assert 0.5 - omega**2 * D < -mu * G
    u1, v1 = _oscillator(0.0, 0.0, 6.0 - mu * G, omega, zeta, 0.3)
    when, speed = _reach(u1, v1, 0.5 - mu * G, omega, zeta, D)
    when += 0.3
    runs = [rigid(time, a0, a1, L, zeta, mu, D, substeps=n) for n in (100, 200, 400)]
    best = richardson(runs)
    assert np.max(np.abs(best["impacts"] - [[when, speed]])) < 1e-8
    after = time > when
    back = [_oscillator(D, 0.0, 0.5 + mu * G, omega, zeta, t - when) for t in time[after]]
    assert max(v for _, v in back) < 0.0  # still sliding back at the end
    assert np.max(np.abs(best["u"][after] - [u for u, _ in back])) < 1e-9
    assert not runs[-1]["at_ring"][after].any()


def test_a_half_reaching_its_ring_hands_the_stroke_to_the_other_surface():
    """DFP1's halves (L_j = 0.9098 m), μ̄_1 = 0.03, μ̄_3 = 0.25, pushed by 3.5 m/s²: surface 1 slides alone (the
    force ω_1² u_1 + m_1 stays below m_3 up to its ring) until its half meets the ring; that is no impact, the
    velocity goes on: surface 3 takes over from rest, its pendulum alone under 3.5 - m_3, until its half meets
    its ring, the impact. Both from closed forms, to 1e-8 (measured 1e-10 s, 1e-9 m/s). Locked there, the ring
    of RB1 carries 3.5 - ω_1² d_1 - m_1; RB3's friction holds its half alone. The energy terms are the closed
    forms': the input A (d_1 + d_3), the friction m_1 d_1 + m_3 d_3, the impact's v² / 2, the damping ∫ 2ζω u̇²."""
    L1, L3 = pendulums(DFP1)
    d1, d3 = ring_strokes(DFP1)
    zeta, m1, m3, A = 0.05, 0.03 * G, 0.25 * G, 3.5
    omega, w1, w3 = math.sqrt(G / (L1 + L3)), math.sqrt(G / L1), math.sqrt(G / L3)
    assert w1**2 * d1 + m1 < m3  # surface 3 holds while surface 1 slides to its ring
    z1, z3 = zeta * omega / w1, zeta * omega / w3  # the same damping 2ζω on each pendulum alone
    t1, v1 = _reach(0.0, 0.0, A - m1, w1, z1, d1)
    t3, v3 = _reach(0.0, v1, A - m3, w3, z3, d3)
    runs = [series(*_push(A), L1, L3, zeta, m1, m3, d1, d3, substeps=n) for n in (100, 200, 400)]
    contacts = np.array([r["contacts"] for r in runs])  # each run: RB1's ring, then RB3's (the impact)
    assert contacts.shape == (3, 2, 4) and (contacts[:, :, 1] == [0, 1]).all() and (contacts[:, :, 3] == [0, 1]).all()
    first = 2 * contacts[1:] - contacts[:-1]
    best = (4 * first[1] - first[0]) / 3
    expected = [[t1, v1], [t1 + t3, v3]]
    assert np.max(np.abs(best[:, [0, 2]] - expected)) < 1e-8
    end = runs[-1]
    assert end["at_ring"][-1].all() and end["v"][-1] == 0.0 and end["force"][-1] * G == pytest.approx(A, abs=1e-12)
    assert end["ring_force"][-1] == pytest.approx([A - w1**2 * d1 - m1, 0.0], abs=1e-12)
    # energies, closed forms: the damping from the closed-form velocities (Simpson's rule, 2e4 panels a phase)
    E = richardson(runs)["energy"][-1]
    damping = 0.0
    for start, p, w, z, span in ((0.0, A - m1, w1, z1, t1), (v1, A - m3, w3, z3, t3)):
        t = np.linspace(0.0, span, 40001)
        speed = np.array([_oscillator(0.0, start, p, w, z, s)[1] for s in t])
        weights = np.ones(t.size)
        weights[1:-1:2], weights[2:-1:2] = 4.0, 2.0
        damping += 2 * zeta * omega * np.sum(weights * speed**2) * (t[1] - t[0]) / 3
    assert E[INPUT] == pytest.approx(A * (d1 + d3), abs=1e-12)
    assert E[FRICTION] == pytest.approx(m1 * d1 + m3 * d3, abs=1e-12)
    assert E[POTENTIAL] == pytest.approx(0.5 * (w1**2 * d1**2 + w3**2 * d3**2), abs=1e-12)
    assert E[KINETIC] == 0.0 and E[IMPACTS] == pytest.approx(0.5 * v3**2, abs=1e-8)
    assert E[DAMPING] == pytest.approx(damping, abs=1e-8)
    assert abs(E[SCHEME]) < 1e-8  # the scheme's own loss extrapolates away


# --- the scheme -----------------------------------------------------------------------------------------

def test_the_energy_balance_closes_through_the_impacts():
    """6 s of the record × 4, the rigid slider (three impacts): the balance of each run closes to rounding (1e-11) with
    the scheme's own loss (first order in h: it halves), and the extrapolated physical terms close without it
    to 1e-7 of the input."""
    time, a0, a1 = _ground(4.0, 6.0)
    runs = [rigid(time, a0, a1, L, 0.02, 0.04, D, substeps=n) for n in (100, 200, 400)]
    assert [len(r["impacts"]) for r in runs] == [3, 3, 3]
    for r in runs:
        E = r["energy"]
        assert np.max(np.abs(E[:, INPUT] - E[:, KINETIC:].sum(axis=1))) < 1e-11 * E[-1, INPUT]
    lost = [r["energy"][-1, SCHEME] for r in runs]
    assert 1.8 < lost[0] / lost[1] < 2.2 and 1.8 < lost[1] / lost[2] < 2.2
    E = richardson(runs)["energy"]
    assert E[-1, IMPACTS] > 0.1 * E[-1, INPUT]  # the impacts take their share
    assert np.max(np.abs(E[:, INPUT] - E[:, KINETIC:SCHEME].sum(axis=1))) < 1e-7 * E[-1, INPUT]


def test_equal_halves_are_the_rigid_slider_impacts_and_all():
    """Halves of L / 2 with equal frictions and rings at (L / 2) sin 11° slide in proportion and reach their rings
    together: the rigid slider of L, to rounding (measured 4e-13 m, 1e-12 m/s), impact for impact."""
    time, a0, a1 = _ground(4.0, 6.0)
    one = rigid(time, a0, a1, L, 0.02, 0.04, D, substeps=100)
    two = series(time, a0, a1, L / 2, L / 2, 0.02, 0.04 * G, 0.04 * G, D / 2, D / 2, substeps=100)
    assert len(one["impacts"]) == 3 and np.max(np.abs(one["impacts"] - two["impacts"])) < 1e-10
    assert np.max(np.abs(one["u"] - two["u"])) < 1e-10 and np.array_equal(two["u_j"][:, 0], two["u_j"][:, 1])
    assert np.array_equal(one["at_ring"][:, 0], two["at_ring"][:, 0])


def test_clipping_at_the_step_end_defeats_the_extrapolation():
    """The rings clipped at the step's end (Moreau's catching-up, ``locate=False``) restart after each impact at a
    step's end: extrapolations from (50, 100, 200) steps a sample differ by 1e-4 m, where the located contacts'
    differ by 1e-7 m (4 s of the record × 4, two impacts)."""
    time, a0, a1 = _ground(4.0, 4.0)
    spreads = {}
    for locate in (True, False):
        runs = [rigid(time, a0, a1, L, 0.02, 0.04, D, substeps=n, locate=locate) for n in (50, 100, 200)]
        assert [len(r["impacts"]) for r in runs] == [2, 2, 2]
        spreads[locate] = richardson(runs)["spread"]
    assert spreads[True] < 1e-6 and spreads[False] > 100 * spreads[True]


# --- the synthetic record: five impacts and more --------------------------------------------------------

CASES = {
    "rigid-0.03": ("rigid", 0.03, None),
    "rigid-0.05": ("rigid", 0.05, None),
    "articulated-equal": ("series", (0.03, 0.06), 0.0),
    "articulated-unequal": ("series", (0.03, 0.06), 0.05),
}


@pytest.mark.slow
@pytest.mark.parametrize("case", [c for c in CASES if CASES[c][0] == "series"])  # the rigid ones: test_ring_contact
def test_on_the_record_the_extrapolations_converge_through_five_impacts(case):
    """DFP1 under the record × 4 (20 s): five or six impacts, as many at each step; the second-order
    extrapolation from 250, 500 and 1000 steps a sample agrees with that from 500, 1000 and 2000 within 2e-7 m
    (the impacts' times and speeds within 1e-6), and the first-order ones' spread is below 1e-6 m (the table in
    the module docstring). The articulated slider
    hands the stroke from one surface to the other at its rings (contacts that are no impacts)."""
    kind, friction, hinge = CASES[case]
    time, a0, a1 = _ground(4.0, 20.0)
    if kind == "rigid":
        runs = [rigid(time, a0, a1, L, 0.02, friction, D, substeps=n) for n in (250, 500, 1000, 2000)]
    else:
        (L1, L3), (d1, d3) = pendulums(DFP1, hinge), ring_strokes(DFP1, hinge)
        m1, m3 = (mu * G for mu in friction)
        runs = [series(time, a0, a1, L1, L3, 0.02, m1, m3, d1, d3, substeps=n) for n in (250, 500, 1000, 2000)]
    counts = {len(r["impacts"]) for r in runs}
    assert len(counts) == 1 and counts.pop() >= 5
    coarse, fine = richardson(runs[:3]), richardson(runs[1:])
    assert coarse["spread"] < 1e-6
    assert np.max(np.abs(coarse["u"] - fine["u"])) < 2e-7
    assert np.max(np.abs(coarse["impacts"] - fine["impacts"]), axis=0).tolist() < [1e-6, 1e-6]
    if kind == "series":
        contacts = runs[-1]["contacts"]
        assert (contacts[:, 3] == 0.0).any()  # a half at its ring, the other surface sliding on


# --- speed laws, far from the rings: the library's and the other independent reference ------------------

@pytest.mark.slow
def test_far_from_its_ring_a_speed_law_rigid_slider_is_the_librarys():
    """μ = 0.06 - 0.03 exp(-20 |u̇|) at the stroke's speed (friction on the device), the whole record × 2, no
    ring reached: the library's rigid slider (its integrator, events located) within 3e-8 m (measured 3e-9 m)."""
    time, a0, a1 = _ground(2.0, 20.0)
    law = {"law": "velocity", "slow": 0.03, "fast": 0.06, "rate": 20.0}
    ground = Ground.from_samples(time, np.append(a0, a0[-1] + a1[-1] * (time[-1] - time[-2])))
    theirs = respond(ground, time, DFP1, Structure(law, 0.02)).stroke[:, 0]
    runs = [rigid(time, a0, a1, L, 0.02, None, 10.0, law=(0.03, 0.06, 20.0), substeps=n) for n in (125, 250, 500)]
    best = richardson(runs)
    assert best["spread"] < 1e-7 and np.max(np.abs(best["u"] - theirs)) < 3e-8


@pytest.mark.slow
@pytest.mark.parametrize("hinge", [0.05])  # unequal pendulums: equal ones are its special case
def test_far_from_their_rings_speed_laws_agree_with_the_series_reference(hinge):
    """Speed laws on each surface at its own speed (μ from 0.02 to 0.04 on RB1, 0.04 to 0.08 on RB3, rate 20 s/m,
    μ̄_j = R^j / L_j μ_j(R^j / L_j |u̇_j|)), 8 s of the record × 2, no ring reached: tests/series_reference.py's
    extrapolation from 5e-6 and 2.5e-6 s (its own accuracy: 5e-7 m) within 1e-6 m (measured 3e-7, 5e-7 m), the
    surfaces sliding alone and together in turn."""
    time, a0, a1 = _ground(2.0, 8.0)
    L1, L3 = pendulums(DFP1, hinge)
    r1, r3 = float(DFP1.R1) / L1, float(DFP1.R3) / L3
    laws = [(0.02, 0.04, 20.0, r1, r1), (0.04, 0.08, 20.0, r3, r3)]
    ag = np.append(a0, a0[-1] + a1[-1] * (time[-1] - time[-2]))
    coarse, fine = (integrate(time, ag, L1, L3, *laws, 0.02, h) for h in (5e-6, 2.5e-6))
    runs = [series(time, a0, a1, L1, L3, 0.02, None, None, 10.0, 10.0, law1=laws[0], law3=laws[1], substeps=n)
            for n in (100, 200, 400)]
    best = richardson(runs)
    assert np.max(np.abs(best["u"] - (2 * fine[0][:, 0] - coarse[0][:, 0]))) < 1e-6
    assert np.max(np.abs(best["u_j"][:, 0] - (2 * fine[1][:, 0] - coarse[1][:, 0]))) < 1e-6
    sliding = runs[-1]["sliding"]
    assert (sliding[:, 0] ^ sliding[:, 1]).any() and sliding.all(axis=1).any()
