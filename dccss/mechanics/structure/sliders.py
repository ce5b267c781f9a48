"""The slider kinds: how the device's two sliding surfaces share the stroke.

A curved surface slider with two sliding surfaces comes in two constructions (the draft EN 15129-6 names
both):

* ``rigid``: one body with two convex caps (the paper's RB2). Seated on both surfaces it has one degree
  of freedom: it turns by the same angle about both sphere centres, so the surfaces slide in proportion
  (R¹ θ and R³ θ) whatever their frictions, and the device is one pendulum of length L whose friction
  the work argument gives, (μ1 R¹ + μ3 R³) / L (``Structure.device_friction``). Its per-surface
  quantities follow from that proportion: u_j = L_j u / L.
* ``articulated``: two halves joined by a spherical hinge (Fenz and Constantinou's double friction
  pendulum). Each surface slides or holds by its own friction: two pendulums in series
  (``structure.series``).

A kind is an entry of :data:`SLIDERS` (``register``): its name, what it is, and its ``respond`` (the
structure's history on the device: ``response.Response``). The kinds register themselves where they are
written (``response``: rigid; ``articulated``), as the models and the friction laws do.

The hinge sits at the pad's centre G² unless its height above G² is given (``hinge``, m): surface j is a
pendulum of length L_j = |C^j H| (``pendulums``), L_1 = R¹ cos α²¹ - h²/2 - hinge and
L_3 = R³ cos α²³ - h²/2 + hinge, L_1 + L_3 = L. Written as Fenz and Constantinou's L_j = R^j - h_j, h_j is
the height of the hinge above the cap's apex on surface j.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SliderKind:
    """A slider kind: its ``name`` (the ``slider`` key), its ``doc``, its ``respond(ground, times, geometry,
    structure) -> Response``, and whether its surfaces slide in proportion (``proportional``: the per-surface
    outputs follow from the stroke)."""

    name: str
    doc: str
    respond: Callable
    proportional: bool


#: the slider kinds, by name
SLIDERS: dict[str, SliderKind] = {}


def register(kind: SliderKind) -> SliderKind:
    """Add ``kind`` to :data:`SLIDERS` (its name not taken)."""
    if kind.name in SLIDERS:
        raise ValueError(f"a slider kind named {kind.name!r} is registered already")
    SLIDERS[kind.name] = kind
    return kind


def pendulums(geometry, hinge=0.0) -> tuple[float, float]:
    """(L_1, L_3) (m): the distances from the sphere centres C¹ and C³ to the hinge ``hinge`` m above the
    pad's centre G² in the centred configuration (the module docstring)."""
    B = 0.5 * float(geometry.h2)
    return (float(geometry.R1 * np.cos(geometry.alpha21)) - B - float(hinge),
            float(geometry.R3 * np.cos(geometry.alpha23)) - B + float(hinge))


def hinge_problem(geometry, hinge, key="slider.hinge") -> str | None:
    """What is wrong with an articulated slider's ``hinge`` (m above the pad's centre) on ``geometry``, or None:
    the hinge joins the two halves inside the pad, strictly between its caps' apexes, |hinge| < h²/2 (then both
    pendulum lengths L_j are positive: each sphere centre lies beyond its cap)."""
    if isinstance(hinge, bool) or not isinstance(hinge, (int, float, np.integer, np.floating)) \
            or not np.isfinite(float(hinge)):
        return f"{key}: expected a finite number (m, the hinge's height above the pad's centre), got {hinge!r}"
    half = 0.5 * float(geometry.h2)
    if not abs(float(hinge)) < half:
        return (f"{key}: {float(hinge)!r} m above the pad's centre puts the hinge outside the pad: it joins the two "
                f"halves inside it, -h2/2 < hinge < h2/2 = {half:.4g} m")
    return None


def ring_strokes(geometry, hinge=0.0) -> tuple[float, float]:
    """Each surface's displacement (m) at which its half reaches the plate's ring: the half turns by
    α^j - α^2j about C^j, u_j = L_j sin(α^j - α^2j)."""
    L1, L3 = pendulums(geometry, hinge)
    return (L1 * float(np.sin(geometry.alpha1 - geometry.alpha21)),
            L3 * float(np.sin(geometry.alpha3 - geometry.alpha23)))
