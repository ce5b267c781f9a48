"""A start from rest at a sample in the exact one-component solvers (``exact.line``, the rigid slider;
``series.series_line``, the articulated one): where the demand on the friction reaches its limit exactly at a
sample, or within rounding of one, sliding starts there, as it does where the limit is crossed inside an
interval; no history holds a friction state past the limit (|z| > 1), and a slider at rest is within its
friction."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dccss.mechanics.structure import G, Ground
from dccss.mechanics.structure.exact import line_history
from dccss.mechanics.structure.series import SLIDE1, SLIDE3, STUCK, series_line_history

EPS = np.finfo(float).eps
TIMES = np.arange(5.0)  # s
OMEGA, ZETA = 2.0, 0.05  # the rigid slider's pendulum (rad/s) and damping
#: the crossing of the reference history: this far (relative) short of the limit at the sample, it reaches it
#: about OFFSET s after the sample, inside the interval
OFFSET = 1e-9


def _table(limit, at_sample, direction):
    """The ground acceleration [0, -a, -2 limit, -2 limit, -2 limit] (m/s², one second apart) times
    ``direction``: the demand -a_g on a slider at rest at the origin grows, reaches ``at_sample`` at t = 1 s
    and goes on growing to twice ``limit``."""
    return Ground.from_samples(TIMES, -direction * np.array([0.0, at_sample, 2 * limit, 2 * limit, 2 * limit]))


#: the demand at the sample t = 1 s: the limit itself, and one ulp past it (the limit reached within rounding
#: before the sample)
TIES = {"at the sample": lambda limit: limit, "one ulp before": lambda limit: np.nextafter(limit, np.inf)}


def _tolerance(limit, zeta, scale):
    """How far a history of the tie may lie from the reference (the limit reached OFFSET s later, the demand
    OFFSET * limit lower at the sample), at the samples: while both slide from rest,
    u = ∫ h(t - s) (load) ds with |h(s)| <= s and |h'(s)| <= 1 / √(1 - ζ²) for the pendulum in play, so
    loads OFFSET * limit apart give |Δu| <= OFFSET * limit T² / 2 and |Δu̇| <= OFFSET * limit T / √(1 - ζ²)
    (T = t - 1 s; the different start, O(OFFSET²)); doubled for the terms of second order (a stop, a
    change of phase a little earlier or later), and the closed form's rounding, a few ulps of its terms of
    size ``scale`` (m)."""
    T = np.maximum(TIMES - 1.0, 0.0)
    rounding = 16 * EPS * scale
    return (OFFSET * limit * T**2 + rounding,
            2 * OFFSET * limit * T / math.sqrt(1.0 - zeta * zeta) + rounding)


@pytest.mark.parametrize("direction", [1.0, -1.0])
@pytest.mark.parametrize("tie", TIES)
def test_a_rigid_slider_starts_where_the_demand_reaches_the_friction_at_a_sample(tie, direction):
    """The demand reaches μ g at t = 1 s and grows on: the rigid slider slides from there, as the limit of
    the same table crossing μ g inside the interval after the sample (the code before stayed at rest for
    the whole record, z = 2)."""
    friction = 0.05 * G
    u, v, z, stick = line_history(*_line(_table(friction, TIES[tie](friction), direction)), OMEGA, ZETA, friction)
    U, V, Z, STICK = line_history(*_line(_table(friction, friction * (1 - OFFSET), direction)), OMEGA, ZETA, friction)
    du, dv = _tolerance(friction, ZETA, friction / OMEGA**2)
    assert np.all(STICK[:2]) and not STICK[2]  # the reference slides from just after the sample
    assert not stick[2] and direction * u[2] > 0.0
    assert np.all(np.abs(u - U) <= du) and np.all(np.abs(v - V) <= dv)
    assert np.array_equal(stick[2:], STICK[2:])
    # at rest z = (demand - ω² u) / μ g: apart by ω² Δu / μ g, and OFFSET at the sample
    assert np.all(np.abs(z - Z) <= OMEGA**2 * du / friction + OFFSET)
    assert np.all(np.abs(z) <= 1.0)


def _line(ground):
    return ground.time, ground.a0[:, 0], ground.a1[:, 0]


#: articulated sliders: pendulums L_1, L_3 (m) and μ̄_1, μ̄_3: unequal (the lower surface yields first, the
#: upper one), equal frictions on unequal pendulums, and equal halves
HALVES = {"lower first": (1.2, 0.9, 0.03, 0.05), "upper first": (1.2, 0.9, 0.05, 0.03),
          "equal frictions": (1.2, 0.9, 0.04, 0.04), "equal halves": (1.0, 1.0, 0.04, 0.04)}


def _series(ground, L1, L3, m1, m3, zeta=ZETA):
    return series_line_history(*_line(ground), G / L1, G / L3, math.sqrt(G / (L1 + L3)), zeta, m1, m3)


@pytest.mark.parametrize("direction", [1.0, -1.0])
@pytest.mark.parametrize("tie", TIES)
@pytest.mark.parametrize("halves", HALVES)
def test_an_articulated_slider_starts_where_the_demand_reaches_a_surfaces_friction_at_a_sample(halves, tie,
                                                                                                direction):
    """The demand reaches the lower of the surfaces' thresholds g μ̄_j at t = 1 s and grows on: the surface
    (or both, at equal thresholds) slides from there, as the limit of the same table crossing it inside the
    interval after the sample (the code before stayed at rest for the whole record)."""
    L1, L3, mu1, mu3 = HALVES[halves]
    m1, m3 = G * mu1, G * mu3
    limit = min(m1, m3)
    u, v, u1, phase, force = _series(_table(limit, TIES[tie](limit), direction), L1, L3, m1, m3)
    U, V, U1, PHASE, FORCE = _series(_table(limit, limit * (1 - OFFSET), direction), L1, L3, m1, m3)
    du, dv = _tolerance(limit, ZETA, max(m1, m3) * (L1 + L3) / G)
    assert PHASE[1] == STUCK and PHASE[2] != STUCK  # the reference slides from just after the sample
    assert phase[2] != STUCK and direction * u[2] > 0.0
    assert np.all(np.abs(u - U) <= du) and np.all(np.abs(v - V) <= dv) and np.all(np.abs(u1 - U1) <= du)
    assert np.array_equal(phase[2:], PHASE[2:])
    assert np.all(np.abs(force - FORCE) <= G / min(L1, L3) * du + OFFSET * limit)


# --- the property: no friction state past the limit, at rest within the friction ---------------------------

def _random_case(rng):
    """A short record of random sample steps and values (within ±3 times the friction), the friction, the
    pendulum and the damping."""
    n = int(rng.integers(5, 10))
    time = np.concatenate([[0.0], np.cumsum(rng.uniform(0.02, 0.3, n - 1))])
    friction = G * rng.uniform(0.02, 0.1)
    return time, friction * rng.uniform(-3.0, 3.0, n), friction, rng.uniform(0.8, 4.0), rng.uniform(0.0, 0.3)


def _place_ties(rng, time, a, bounds_at_rest):
    """Ties at samples: at three random samples k, where the slider is at rest at k - 1 (``bounds_at_rest`` of
    the record up to k: the demand's bounds, -a_g, at rest at k - 1, or None), a[k] is set so that -a_g
    reaches one of them at k, to the bit or an ulp either side (the demand's straight line stays within the
    bounds up to it: the slider is still at rest there). The number of ties placed."""
    ties = 0
    for k in np.sort(rng.choice(np.arange(1, time.size), size=3, replace=False)):
        bounds = bounds_at_rest(Ground.from_samples(time[:k + 1], a[:k + 1]))  # at k - 1, a[k] is not yet felt
        if bounds is not None:
            bound = bounds[int(rng.integers(2))]
            a[k] = -[bound, np.nextafter(bound, np.inf), np.nextafter(bound, -np.inf)][int(rng.integers(3))]
            ties += 1
    return ties


def _rigid_ties(rng):
    """A random record (``_random_case``) with ties (``_place_ties``) where the demand -a_g - ω² u reaches ±μ g."""
    time, a, friction, L, zeta = _random_case(rng)
    omega = math.sqrt(G / L)

    def bounds_at_rest(ground):
        u, _, _, stick = line_history(*_line(ground), omega, zeta, friction)
        return (omega**2 * u[-2] - friction, omega**2 * u[-2] + friction) if stick[-2] else None

    ties = _place_ties(rng, time, a, bounds_at_rest)
    return Ground.from_samples(time, a), omega, zeta, friction, ties


def test_a_rigid_slider_never_holds_past_its_friction():
    """200 random records with ties at samples: |z| <= 1 throughout, and at rest the demand is within μ g
    (the code before held z = 2 where a tie was followed by a growing demand)."""
    rng = np.random.default_rng(43)
    ties = 0
    for _ in range(200):
        ground, omega, zeta, friction, placed = _rigid_ties(rng)
        time, a0, a1 = _line(ground)
        u, v, z, stick = line_history(time, a0, a1, omega, zeta, friction)
        assert np.all(np.abs(z) <= 1.0)
        demand = -np.append(a0[0], a0 + a1 * np.diff(time)) - omega**2 * u  # as the solver takes it at a sample
        assert np.all(np.abs(demand[stick]) <= friction)
        assert np.all(v[stick] == 0.0)
        ties += placed
    assert ties > 100  # the records hold ties: the property was put to them


def _series_ties(rng):
    """``_rigid_ties`` for an articulated slider of random pendulums and frictions: ties where the demand -a_g
    reaches a bound of the surfaces' thresholds ω_j² u_j ± g μ̄_j."""
    time, a, friction, L, zeta = _random_case(rng)
    L1 = L * rng.uniform(0.2, 0.8)
    m1, m3 = friction, friction * rng.choice([1.0, rng.uniform(0.5, 2.0)])
    case = (G / L1, G / (L - L1), math.sqrt(G / L), zeta, m1, m3)

    def bounds_at_rest(ground):
        u, _, u1, phase, _ = series_line_history(*_line(ground), *case)
        return _bounds(u[-2], u1[-2], *case) if phase[-2] == STUCK else None

    ties = _place_ties(rng, time, a, bounds_at_rest)
    return Ground.from_samples(time, a), case, ties


def _bounds(u, u1, w1sq, w3sq, omega, zeta, m1, m3):
    """The demand's bounds at rest, max_j (ω_j² u_j - m_j) and min_j (ω_j² u_j + m_j), as the solver takes
    them."""
    return (np.maximum(w1sq * u1 - m1, w3sq * (u - u1) - m3), np.minimum(w1sq * u1 + m1, w3sq * (u - u1) + m3))


def test_an_articulated_slider_never_holds_past_a_surfaces_friction():
    """200 random records with ties at samples: at rest the demand (the force) is within both surfaces'
    thresholds, as the solver takes them, and a surface that holds (at rest, or while the other slides alone)
    has its friction state z_j = (g F/W - ω_j² u_j) / m_j within ±1 up to the rounding of that difference
    and of the threshold (an ulp of each term); a sliding surface's z_j is ±1 by its phase (the code before
    held the demand past a threshold where a tie was followed by a growing demand)."""
    rng = np.random.default_rng(44)
    ties = 0
    for _ in range(200):
        ground, case, placed = _series_ties(rng)
        w1sq, w3sq, _, _, m1, m3 = case
        time, a0, a1 = _line(ground)
        u, v, u1, phase, force = series_line_history(time, a0, a1, *case)
        lower, upper = _bounds(u, u1, *case)
        rest = phase == STUCK
        assert np.all((lower[rest] <= force[rest]) & (force[rest] <= upper[rest]))
        assert np.all(force[rest] == -np.append(a0[0], a0 + a1 * np.diff(time))[rest])
        assert np.all(v[rest] == 0.0)
        for wsq, m, stroke, holding in ((w1sq, m1, u1, (STUCK, SLIDE3)), (w3sq, m3, u - u1, (STUCK, SLIDE1))):
            held = np.isin(phase, holding)
            z = (force[held] - wsq * stroke[held]) / m
            rounding = 4 * EPS * (np.abs(force[held]) + np.abs(wsq * stroke[held]) + m) / m
            assert np.all(np.abs(z) <= 1.0 + rounding)
        ties += placed
    assert ties > 100
