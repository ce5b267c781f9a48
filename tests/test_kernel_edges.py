"""Edges of the kernels' helpers where the interpreted and compiled runs must agree: a two-component breakaway
that starts exactly at a sample, and a friction law taken at a speed whose exponential overflows."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dccss.mechanics.friction import _exp, surface_mu, surface_mu_slopes
from dccss.mechanics.structure.circular import breakaway


def test_a_demand_at_the_friction_and_growing_breaks_away_at_once():
    """|d0| equals the friction at the interval's start and grows: the breakaway is at 0 (it was missed: the
    root at 0 was refused as not inside (0, end), so the rest held for the whole interval)."""
    friction = 0.05 * 9.80665
    d0x, d0y = 0.0, friction  # |d0| = friction: c = 0 exactly
    assert breakaway(d0x, d0y, 0.1, 0.4, friction, 1.0, 0.0, 0.01) == 0.0
    assert breakaway(d0x, d0y, 0.1, -0.4, friction, 1.0, 0.0, 0.01) == -1.0  # at it, falling back within it
    assert breakaway(d0x, 1.0000001 * friction, 0.1, -0.4, friction, 1.0, 0.0, 0.01) == 0.0  # past it


@pytest.mark.parametrize("kind", [1.0, 2.0])
def test_a_speed_law_at_a_speed_whose_exponential_overflows_is_what_compiled_code_gives(kind):
    """A Newton trial at a large negative speed: math.exp raised OverflowError in an interpreted run, where the
    compiled one gives inf (and its Newton recovers)."""
    r = np.zeros(14)
    r[0], r[4], r[5], r[6] = kind, 0.03, 0.07, 20.0
    assert _exp(800.0) == math.inf and _exp(1.0) == math.exp(1.0) and _exp(709.0) == math.exp(709.0)
    assert surface_mu(r, -100.0, 1.0, 20.0) == -math.inf
    slope, _ = surface_mu_slopes(r, -100.0, 1.0, 20.0)
    assert slope == math.inf
