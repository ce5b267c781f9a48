"""The retaining ring as a stop in the exact one-component solution (``exact.line``, ``exact.ring_history``):
the impact where the closed form of the damped oscillator reaches the ring, the ring's force while the pad is held
against it, the release where the demand pulls it back past the friction, and no change without a ring."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from dccss.mechanics.structure.exact import line_history, ring_history

G = 9.80665
L, RING = 1.8196, 1.8196 * math.sin(math.radians(11.0))  # DFP1's rigid slider: its ring at L sin 11°
OMEGA = math.sqrt(G / L)


def _table(times, values):
    """(time, a0, a1) of a ground acceleration joined by straight lines between (times, values)."""
    t, a = np.asarray(times, float), np.asarray(values, float)
    a1 = np.append(np.diff(a) / np.diff(t), 0.0)
    return t, a, a1


def _closed_form(p, zeta):
    """u(t), u̇(t) from rest under the constant load p (m/s²): ü + 2ζω u̇ + ω² u = p."""
    wd = OMEGA * math.sqrt(1.0 - zeta**2)

    def u(t):
        return p / OMEGA**2 * (1.0 - math.exp(-zeta * OMEGA * t) * (math.cos(wd * t) + zeta * OMEGA / wd
                                                                       * math.sin(wd * t)))

    def v(t):
        return p / wd * math.exp(-zeta * OMEGA * t) * math.sin(wd * t)

    return u, v


@pytest.mark.parametrize(("zeta", "mu"), [(0.0, 0.03), (0.05, 0.05), (0.02, 0.0)])
def test_a_constant_push_hits_the_ring_where_the_closed_form_reaches_it(zeta, mu):
    """A ground acceleration -A held from t = 0 drives the pendulum (its load A - μ g) into the ring: the impact
    comes where the closed form reaches the ring, at its speed there (1e-9 relative); the pad then rests against
    the ring, which carries the demand beyond the pendulum and the friction, A - ω² d - μ g."""
    A = 0.6 * G
    time, a0, a1 = _table([0.0, 0.5, 1.0, 1.5, 2.0, 3.0], [-A] * 6)
    u, v, z, stick, held, impacts = ring_history(time, a0, a1, OMEGA, zeta, mu * G, RING, compiled=False)
    closed_u, closed_v = _closed_form(A - mu * G, zeta)
    hit = brentq(lambda t: closed_u(t) - RING, 1e-9, 1.0, xtol=1e-15)
    interval = int(np.searchsorted(time, hit))
    assert impacts[:, 0].sum() == 1 and impacts[interval, 0] == 1
    assert impacts[interval, 1] == pytest.approx(closed_v(hit), rel=1e-9)
    assert impacts[interval, 2] == pytest.approx(0.5 * closed_v(hit) ** 2, rel=1e-9)
    after = time > hit
    assert np.all(u[after] == RING) and np.all(v[after] == 0.0) and np.all(stick[after])
    assert held[after] == pytest.approx(A - OMEGA**2 * RING - mu * G, rel=1e-12)
    assert np.all(np.abs(z) <= 1.0)


def test_the_pad_leaves_the_ring_where_the_demand_pulls_it_back_past_the_friction():
    """Held against the ring, then the ground stops accelerating: the demand -ω² d pulls the pad back past the
    friction (ω² d = g sin 11° > μ g), so it slides back from that instant, as the free closed form does."""
    A, mu = 0.6 * G, 0.03
    time, a0, a1 = _table([0.0, 2.0, 2.0 + 1e-12, 3.0], [-A, -A, 0.0, 0.0])
    u, v, z, stick, held, impacts = ring_history(time, a0, a1, OMEGA, 0.0, mu * G, RING, compiled=False)
    assert u[1] == RING and held[1] > 0.0
    # from rest at d under the load -ω² d + μ g (sliding back, z = -1): u(t) = d - (ω² d - μ g)(1 - cos ω t) / ω²
    dt = time[-1] - time[2]
    expected = RING - (OMEGA**2 * RING - mu * G) * (1.0 - math.cos(OMEGA * dt)) / OMEGA**2
    assert u[-1] == pytest.approx(expected, abs=1e-9) and not stick[-1] and z[-1] == -1.0


def test_a_friction_that_holds_the_pad_against_the_ring_keeps_it_there():
    """At the ring the demand -ω² d + ... within the friction: held, the ring carrying nothing, z = demand / μ g."""
    mu = 0.25  # μ g above ω² d = g sin 11°: the friction alone holds the pad at the ring
    A = 1.0 * G
    time, a0, a1 = _table([0.0, 2.0, 2.0 + 1e-12, 4.0], [-A, -A, 0.0, 0.0])
    u, v, z, stick, held, impacts = ring_history(time, a0, a1, OMEGA, 0.0, mu * G, RING, compiled=False)
    assert impacts[:, 0].sum() == 1 and np.all(u[1:] == RING) and held[-1] == 0.0
    assert z[-1] == pytest.approx(-OMEGA**2 * RING / (mu * G), rel=1e-12)


@pytest.mark.parametrize("mu", [0.0, 0.03, 0.05])
def test_without_a_ring_reached_the_history_is_the_free_ones_bit_for_bit(mu):
    from dccss.records import read_at2

    dt, acc = read_at2("config/studies/records/synthetic.AT2")
    time, a0, a1 = _table(dt * np.arange(acc.size), 2.2 * G * acc)
    free = line_history(time, a0, a1, OMEGA, 0.02, mu * G, compiled=False)
    far = ring_history(time, a0, a1, OMEGA, 0.02, mu * G, 10.0, compiled=False)
    assert all(np.array_equal(a, b) for a, b in zip(free, far[:4]))
    assert not far[4].any() and not far[5].any()
    ringed = ring_history(time, a0, a1, OMEGA, 0.02, mu * G, RING, compiled=False)
    assert np.abs(ringed[0]).max() <= RING  # at the samples; it may reach the ring and leave it between them
    assert (ringed[5][:, 0].sum() >= 1) == (np.abs(free[0]).max() > RING)


def test_a_demand_that_pulls_back_at_the_impact_takes_the_pad_off_the_ring_at_once():
    """Pushed at 6 m/s² to 0.3 s, then 0.5 m/s²: at the impact the demand 0.5 - ω² d already pulls the pad back
    past the friction, so it leaves the ring there (it was held to the next sample): the closed form from (d, 0)
    at the impact."""
    mu = 0.05
    time = np.round(np.arange(0.0, 1.0001, 0.01), 12)
    ag = np.where(time < 0.3 - 1e-9, -6.0, -0.5)
    a0, a1 = ag.copy(), np.zeros_like(ag)
    u, v, z, stick, held, impacts = ring_history(time, a0, a1, OMEGA, 0.0, mu * G, RING, compiled=False)
    (k,) = np.nonzero(impacts[:, 0])
    # the impact: the closed form from the state at 0.3 s under the load 0.5 - μ g
    u3, v3 = u[30], v[30]
    p = 0.5 - mu * G
    hit = brentq(lambda t: p / OMEGA**2 + (u3 - p / OMEGA**2) * math.cos(OMEGA * t) + v3 / OMEGA
                 * math.sin(OMEGA * t) - RING, 0.0, time[k[0]] - 0.3 + 1e-12, xtol=1e-15)
    back = 0.5 + mu * G  # sliding back, z = -1, from (d, 0)
    after = time > 0.3 + hit
    expected = back / OMEGA**2 + (RING - back / OMEGA**2) * np.cos(OMEGA * (time[after] - 0.3 - hit))
    assert u[after] == pytest.approx(expected, abs=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize(("scale", "mu"), [(4.0, 0.03), (4.0, 0.05)])
def test_the_ring_equals_the_independent_integration_to_a_micrometre(scale, mu):
    """The synthetic record scaled to five or six impacts on DFP1's rigid slider (20 s): the stroke at every sample
    against tests/ring_reference.py (implicit Moreau steps, each contact located, extrapolated from 250, 500 and
    1000 steps a sample: its own spread below 2e-7 m), to 1e-6 m; the impacts as many, at the same speeds."""
    from ring_reference import richardson, rigid

    from dccss.records import read_at2

    dt, acc = read_at2("config/studies/records/synthetic.AT2")
    a = acc * G * scale
    time, a0, a1 = dt * np.arange(a.size), a[:-1], np.diff(a) / dt
    runs = [rigid(time, a0, a1, L, 0.02, mu, RING, substeps=n) for n in (250, 500, 1000)]
    reference = richardson(runs)
    assert reference["spread"] < 2e-7
    u, v, z, stick, held, impacts = ring_history(time, np.append(a0, a[-1]), np.append(a1, 0.0), OMEGA, 0.02,
                                                 mu * G, RING, compiled=False)
    assert np.max(np.abs(u - reference["u"])) < 1e-6
    assert impacts[:, 0].sum() == len(runs[-1]["impacts"]) >= 5
    assert impacts[impacts[:, 0] > 0, 1] == pytest.approx(reference["impacts"][:, 1], abs=1e-6)  # one an interval
