"""Intensity levels: each record of a study scaled to given levels of an intensity measure (incremental dynamic
analysis, multiple-stripe analysis).

A study's ``intensity`` key names the measure (``spectra.MEASURES``): the spectral acceleration Sa(T) at a period
(the device's isolated period T = 2π sqrt(L/g) by default), the peak ground acceleration or the peak ground
velocity, a pair's by a definition (RotD50, RotD100 or the geometric mean of its components). Its sweep axis
``intensity`` gives the levels, in g for Sa and PGA, in m/s for PGV. Record r at level x runs at the factor
x / IM_r, both in one unit (x g / IM_r with IM_r in m/s² for Sa and PGA), IM_r its own intensity as processed at
scale 1: the very record ``dccss run`` reads with ``scale`` that factor (the same bits).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import CaseError, check_keys, choice, number
from ..mechanics.structure import G
from ..spectra import MEASURES, PAIR_DEFINITIONS

#: the keys of a study's ``intensity`` and their defaults
DEFAULTS = {"measure": "sa", "period": "isolated", "damping": 0.05, "definition": "rotd50"}
#: what the levels of each measure are given in: (the factor to SI, CF units, the unit's text)
LEVEL_UNITS = {"sa": (G, "1", "g"), "pga": (G, "1", "g"), "pgv": (1.0, "m s-1", "m/s")}


@dataclass(frozen=True)
class Intensity:
    """An intensity measure: ``measure`` (sa, pga, pgv), ``period`` (s; Sa's), ``damping`` (Sa's) and
    ``definition`` (a pair's: rotd50, rotd100, geometric_mean)."""

    measure: str = "sa"
    period: float | None = None
    damping: float = 0.05
    definition: str = "rotd50"

    @property
    def to_si(self) -> float:
        """The factor from a level (g, or m/s for PGV) to SI units."""
        return LEVEL_UNITS[self.measure][0]

    def label(self, pair=True) -> str:
        """'Sa(T = 2.71 s, 5 %, RotD50)', 'PGA (RotD50)' (a pair's definition only for a pair)."""
        how = {"rotd50": "RotD50", "rotd100": "RotD100", "geometric_mean": "geometric mean"}[self.definition]
        if self.measure == "sa":
            return f"Sa(T = {self.period:.3g} s, {100 * self.damping:g} %" + (f", {how})" if pair else ")")
        return self.measure.upper() + (f" ({how})" if pair else "")

    def unit(self) -> str:
        return LEVEL_UNITS[self.measure][2]

    def attrs(self) -> dict:
        """The measure as a dataset's attributes."""
        out = {"intensity_measure": self.measure, "intensity_definition": self.definition,
               "intensity_units": self.unit()}
        if self.measure == "sa":
            out.update(intensity_period_s=self.period, intensity_damping=self.damping)
        return out


def intensity_from(value, axes, pendulum) -> Intensity | None:
    """A study's intensity measure (its ``intensity`` key, the defaults where it gives none) where it sweeps
    ``intensity``, else None; ``pendulum`` the base device's L (m), or None where the study sweeps the device
    (then an Sa needs its period). Errors name the key."""
    if "intensity" not in axes:
        if value is not None:
            raise CaseError("intensity: names the measure of the intensity levels, but the study has none: sweep "
                            "them (sweep.intensity: [levels])")
        return None
    value = {} if value is None else value
    if not isinstance(value, dict):
        raise CaseError(f"intensity: expected a mapping {{measure, period, damping, definition}}, got {value!r}")
    check_keys(value, "intensity", (), tuple(DEFAULTS))
    given = {**DEFAULTS, **value}
    measure = choice(given["measure"], "intensity.measure", MEASURES)
    definition = choice(given["definition"], "intensity.definition", PAIR_DEFINITIONS)
    damping = number(given["damping"], "intensity.damping")
    if not 0 <= damping < 1:
        raise CaseError(f"intensity.damping: {damping!r} is outside 0 <= damping < 1")
    period = None
    if measure == "sa":
        if given["period"] == "isolated":
            if pendulum is None:
                raise CaseError("intensity.period: the isolated period differs between the devices the study sweeps; "
                                "give the period (s) of the spectral acceleration")
            period = 2.0 * math.pi * math.sqrt(pendulum / G)
        else:
            period = number(given["period"], "intensity.period", positive=True)
    elif "period" in value or "damping" in value:
        key = "period" if "period" in value else "damping"
        raise CaseError(f"intensity.{key}: a spectral acceleration's (measure: sa); {measure} has none")
    for i, level in enumerate(axes["intensity"]):
        if not level > 0:
            raise CaseError(f"sweep.intensity[{i}]: a level is an intensity > 0, got {float(level)!r}")
    return Intensity(measure, period, damping, definition)
