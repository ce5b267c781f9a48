"""Check the numbers the paper states against the computed datasets.

``config/paper_values.yaml`` lists each number: value, unit, tolerance, source, the quantity to
compute (a ``kind`` below with its parameters) and the variants expected to reproduce it. A
variant is a case set (time histories) or a normal convention (breakaway sweeps). Every
quantity is computed from the netCDF results only.

Loading (``load_values``) checks every entry against a ``Catalogue`` of what the workflow
computes: the kind exists, its parameters match the kind's signature, each parameter value is
one the workflow computes, the expected variants exist and run the entry's prototypes, the unit
measures what the kind returns. Any mistake raises ``ValueError`` naming the entry.

Status of an entry: "reproduced" (with the primary variant: Table 1 as printed, or the
consistent signed normals), "reproduced with <variant>" (only with another variant, e.g. the
reported inputs), "reproduced as <label>" (the stated quantity does not reproduce it, the
entry's ``reading`` of the number does), or "not reproduced" with the reason. An entry fails
the validation when a variant it expects does not reproduce it (or its reading, when the
reading expects it).

The ``readings`` list states how some numbers are read (a ratio of two stated numbers, a
coefficient implied by a stated number); each compares the paper-implied value with the one
computed for one variant, and is reported apart from the stated numbers.

Evaluation skips a variant only when ``Results`` has no dataset for it (``MissingDataset``:
the workflow does not compute that case); any other error propagates, naming the entry.

Round-off: kinds whose value is exactly zero in exact arithmetic declare a round-off floor
(``ROUND_OFF``, in SI units); values below it are printed as ``< floor`` in every output, and
the check is made on the true value.
"""

from __future__ import annotations

import csv
import inspect
import io
import json
from dataclasses import dataclass

import numpy as np

from ..schema import errors as schema_errors
from ..schema import load_yaml, schema

#: factor from the SI unit of the quantity's dimension to the unit
UNITS = {"m": 1.0, "cm": 1e2, "mm": 1e3, "um": 1e6, "deg": 1.0, "cm/s": 1e2, "1": 1.0, "bool": 1.0,
         "1e-5 mm/cm3": 1e2}
DIMENSIONS = {"m": "length", "cm": "length", "mm": "length", "um": "length", "deg": "angle",
              "cm/s": "velocity", "1": "1", "bool": "1", "1e-5 mm/cm3": "1/area"}
CORNERS = ("A", "B", "C", "D")
PHASES = ("start", "stick", "end")
STATISTICS = ("mean", "max")
RELATIONS = tuple(schema("paper_values")["$defs"]["value"]["properties"]["relation"]["enum"])
#: how a reading derives the paper-implied value from the stated number(s) it reads
LAWS = tuple(schema("paper_values")["$defs"]["reading"]["properties"]["law"]["enum"])
#: what a reading expects of the data
READING_EXPECT = tuple(schema("paper_values")["$defs"]["reading"]["properties"]["expect"]["enum"])
#: the first step of the cyclic part of a history: step 1 is the breakaway from rest (Fig. 7)
FIRST_CYCLIC_STEP = 2
#: Round-off floor (SI) of the kinds that are exactly zero in exact arithmetic. Interpenetrations
#: are |corner - centre| - R with coordinates of order 1 m, each good to a few units of 2.2e-16 m;
#: 1e-14 m (about 50 of those units) stays two orders below the Newton tolerance of 1e-12 m, the
#: smallest real mismatch a broken symmetry could show.
ROUND_OFF = {"diagonal_endpoint_mismatch": 1e-14, "breakaway_endpoint_mismatch": 1e-14}
_VARIANT_NAMES = {"as_reported": "reported inputs", "as_printed": "Table 1 as printed",
                  "unsigned": "unsigned normals", "signed": "signed normals"}

QUANTITIES = {}
CASE_KINDS = set()
BREAKAWAY_KINDS = set()
KIND_DIMENSIONS = {}


def quantity(kind_set, dimension):
    """Register a quantity kind: a function ``(results, variant, **parameters)`` returning SI."""

    def register(fn):
        QUANTITIES[fn.__name__] = fn
        KIND_DIMENSIONS[fn.__name__] = dimension
        kind_set.add(fn.__name__)
        return fn

    return register


# --- the results ----------------------------------------------------------------------------------
class MissingDataset(LookupError):
    """The workflow computes no dataset for this key (e.g. a case set that does not run a prototype)."""


@dataclass
class Results:
    """Datasets by key: cases[(variant, proto, model, dt)], breakaway[(variant, proto)] (with a
    ``dXg`` dimension).

    Raises
    ------
    MissingDataset
        For a key that has no dataset.
    """

    cases: dict
    breakaway: dict

    def case(self, variant, prototype, model, dt):
        key = (variant, prototype, model, float(dt))
        if key not in self.cases:
            raise MissingDataset(f"no time history for {key}")
        ds = self.cases[key]
        if ds.attrs.get("failed"):
            raise ValueError(f"the time history {key} stopped early (failed at "
                             f"{ds.attrs.get('failure_time_s')} s): no stated number is checked against it")
        return ds

    def sweep(self, variant, prototype, dXg):
        key = (variant, prototype)
        if key not in self.breakaway:
            raise MissingDataset(f"no breakaway sweep for {key}")
        ds = self.breakaway[key]
        if float(dXg) not in ds["dXg"].values:
            raise ValueError(f"the breakaway sweep {key} has no dXg = {dXg} m (it has {ds['dXg'].values.tolist()})")
        return ds.sel(dXg=float(dXg))


# --- helpers on one history -----------------------------------------------------------------------
def _step(ds, t):
    """Index of the step that ends at ``t`` (s)."""
    times = ds["t"].values
    n = int(np.argmin(np.abs(times - t)))
    if abs(times[n] - t) > 1e-9:
        raise ValueError(f"no step ends at t = {t} s (the nearest is {times[n]} s)")
    return n


def _ground_steps(ds):
    """X_g(t_n) - X_g(t_{n-1}) by step n (m); nan at n = 0."""
    return np.concatenate([[np.nan], np.diff(ds["Xg"].values)])


def _sticking_rotation(ds):
    """|theta2 at the end of sticking of step n - theta2 at the start of step n| by step (deg); nan at n = 0."""
    theta2 = ds["theta2"].values
    return np.concatenate([[np.nan], np.abs(ds["theta2_stick"].values[1:] - theta2[:-1])])


def _half_cycles(ds):
    """Complete half cycles of the ground motion: the runs of steps whose ground steps share a
    sign, bounded by a sign change at both ends (arrays of step indices). The first run holds
    the breakaway step; the first and last runs are incomplete and left out."""
    sign = np.sign(np.diff(ds["Xg"].values))  # sign[k]: step k + 1
    starts = np.flatnonzero(sign[1:] != sign[:-1]) + 1
    return [np.arange(a, b) + 1 for a, b in zip(starts[:-1], starts[1:])]


def _half_cycle_peaks(ds):
    """The largest sticking rotation in each complete half cycle (deg)."""
    rotation = _sticking_rotation(ds)
    return np.array([rotation[steps].max() for steps in _half_cycles(ds)])


def _peak_difference_step(ds):
    """The step of the largest |I_A - I_B| over the history."""
    n = int(np.argmax(np.abs(ds["I_A"] - ds["I_B"]).values))
    if n == 0:
        raise ValueError("|I_A - I_B| peaks at t_0, before any ground step")
    return n


# --- time histories (variants: case sets) -------------------------------------------------------
@quantity(CASE_KINDS, "angle")
def theta2_max(r, v, prototype, model, dt):
    """Largest pad rotation theta2 over the history (deg)."""
    return float(r.case(v, prototype, model, dt)["theta2"].max())


@quantity(CASE_KINDS, "angle")
def theta2_end(r, v, prototype, model, dt):
    """Pad rotation at the end of the motion, theta2(t_g) (deg)."""
    return float(r.case(v, prototype, model, dt)["theta2"][-1])


@quantity(CASE_KINDS, "length")
def rise_max(r, v, prototype, model, dt):
    """Maximum rise of RB3 above its theta2 = 0 rest position (m)."""
    return float(r.case(v, prototype, model, dt)["rise"].max())


@quantity(CASE_KINDS, "length")
def rise_end(r, v, prototype, model, dt):
    """Rise of RB3 at the end of the motion (m)."""
    return float(r.case(v, prototype, model, dt)["rise"][-1])


@quantity(CASE_KINDS, "length")
def interpenetration_difference(r, v, prototype, model, dt):
    """max |I_A - I_B| over the history (m) (equal to max |I_D - I_C| for symmetric pads)."""
    ds = r.case(v, prototype, model, dt)
    return float(np.abs(ds["I_A"] - ds["I_B"]).max())


@quantity(CASE_KINDS, "length")
def interpenetration_peak(r, v, prototype, model, dt):
    """Largest corner interpenetration over the history and the four corners (m), as Fig. 9 plots it
    (positive into the plate)."""
    ds = r.case(v, prototype, model, dt)
    return float(max(ds[f"I_{c}"].max() for c in CORNERS))


@quantity(CASE_KINDS, "1")
def dt_ratio(r, v, of, prototype, model, dt, other_dt):
    """The quantity ``of`` (a kind with parameters prototype, model, dt) at ``dt`` over its value at
    ``other_dt`` (1)."""
    return float(QUANTITIES[of](r, v, prototype, model, dt) / QUANTITIES[of](r, v, prototype, model, other_dt))


@quantity(CASE_KINDS, "length")
def difference_ground_step(r, v, prototype, model, dt):
    """|X_g(t_n) - X_g(t_{n-1})| of the step n at which |I_A - I_B| peaks (m)."""
    ds = r.case(v, prototype, model, dt)
    return float(abs(_ground_steps(ds)[_peak_difference_step(ds)]))


@quantity(CASE_KINDS, "1/area")
def cubic_coefficient(r, v, prototype, model, dt):
    """max |I_A - I_B| over the cube of the ground step of the step it occurs at (m / m^3)."""
    ds = r.case(v, prototype, model, dt)
    n = _peak_difference_step(ds)
    return float(abs(ds["I_A"][n] - ds["I_B"][n]) / abs(_ground_steps(ds)[n]) ** 3)


@quantity(CASE_KINDS, "velocity")
def velocity(r, v, prototype, model, dt, time):
    """Ground velocity X_g_dot at ``time`` (m/s)."""
    ds = r.case(v, prototype, model, dt)
    return float(ds["Xg_dot"][_step(ds, time)])


@quantity(CASE_KINDS, "angle")
def fig20_theta2(r, v, prototype, dt, time, phase):
    """theta2 of the step ending at ``time``: at its start, end of sticking or end (deg)."""
    ds = r.case(v, prototype, "stick_slip", dt)
    n = _step(ds, time)
    if n == 0:
        raise ValueError("time 0 ends no step")
    return float({"start": ds["theta2"][n - 1], "stick": ds["theta2_stick"][n], "end": ds["theta2"][n]}[phase])


@quantity(CASE_KINDS, "length")
def rest_determinant(r, v, prototype, dt):
    """|C_q| of the compliant model at t_0 (m): Eq. 30 when theta2(t0) = 0."""
    return float(r.case(v, prototype, "compliant", dt)["det_Cq"][0])


@quantity(CASE_KINDS, "length")
def eq30_printed(r, v, prototype, dt):
    """Eq. 30 as printed, 8 sin a cos^2 a (B sin a + A cos a) cos theta2, with the dataset's rest
    contact angle a and theta2(t_0) (m)."""
    return _eq30(r.case(v, prototype, "compliant", dt), +1)


@quantity(CASE_KINDS, "length")
def eq30_corrected(r, v, prototype, dt):
    """Eq. 30 with the sign corrected, 8 sin a cos^2 a (B sin a - A cos a) cos theta2 (m)."""
    return _eq30(r.case(v, prototype, "compliant", dt), -1)


@quantity(CASE_KINDS, "length")
def eq30_alpha_reversed(r, v, prototype, dt):
    """The corrected Eq. 30 with the sign of the contact angle reversed, a -> -a (m)."""
    return _eq30(r.case(v, prototype, "compliant", dt), -1, alpha_sign=-1)


def _eq30(ds, sign, alpha_sign=1):
    a = alpha_sign * np.radians(float(ds["alpha_A"][0]))
    A, B = ds.attrs["A1_m"], ds.attrs["B_m"]
    return float(8 * np.sin(a) * np.cos(a) ** 2 * (B * np.sin(a) + sign * A * np.cos(a))
                 * np.cos(np.radians(float(ds["theta2"][0]))))


@quantity(CASE_KINDS, "1")
def sticking_rotation_at_velocity_peak(r, v, prototype, dt):
    """In each complete half cycle of the ground motion, |X_g step| at the step of the largest
    sticking rotation over the half cycle's largest |X_g step|; the smallest over the half
    cycles (1). The velocity is the discrete one, X_g step / dt, as the paper defines it."""
    ds = r.case(v, prototype, "stick_slip", dt)
    rotation, ground = _sticking_rotation(ds), np.abs(_ground_steps(ds))
    cycles = _half_cycles(ds)
    if not cycles:
        raise ValueError("the history holds no complete half cycle of the ground motion")
    return float(min(ground[steps[np.argmax(rotation[steps])]] / ground[steps].max() for steps in cycles))


@quantity(CASE_KINDS, "1")
def sticking_rotation_ratio(r, v, prototype, dt, other_prototype, other_dt):
    """Largest sticking rotation of (prototype, dt) over that of (other_prototype, other_dt) in
    each complete half cycle of the ground motion; the smallest over the half cycles (1)."""
    mine = _half_cycle_peaks(r.case(v, prototype, "stick_slip", dt))
    other = _half_cycle_peaks(r.case(v, other_prototype, "stick_slip", other_dt))
    if len(mine) != len(other) or not len(mine):
        raise ValueError(f"{len(mine)} and {len(other)} complete half cycles: the histories do not pair")
    return float(np.min(mine / other))


@quantity(CASE_KINDS, "length")
def diagonal_endpoint_mismatch(r, v, prototype, model, dt):
    """max(|I_A - I_D|, |I_B - I_C|) over the history (m): 0 when the endpoints superimpose."""
    ds = r.case(v, prototype, model, dt)
    return float(max(np.abs(ds["I_A"] - ds["I_D"]).max(), np.abs(ds["I_B"] - ds["I_C"]).max()))


@quantity(CASE_KINDS, "1")
def opposite_working_diagonal(r, v, prototype, dt, threshold=0.1):
    """Over the cyclic part of the history (steps from FIRST_CYCLIC_STEP), the fraction of the steps
    with a working diagonal in compliant sliding (|I_B - I_A| above ``threshold`` times its peak
    over that part) whose stick-slip jammed diagonal is the other one (1); the paper: 'always the
    opposite'. The breakaway step is Fig. 7's (fig7_*_bc_larger_*)."""
    comp = r.case(v, prototype, "compliant", dt)
    ss = r.case(v, prototype, "stick_slip", dt)
    if not np.array_equal(comp["t"].values, ss["t"].values):
        raise ValueError("the compliant and stick-slip histories have different time steps")
    d = (comp["I_B"] - comp["I_A"]).values[FIRST_CYCLIC_STEP:]
    working = np.abs(d) > threshold * np.abs(d).max()
    jammed_bc = ss["sticking_diagonal"].values[FIRST_CYCLIC_STEP:] == 1
    return float(np.mean((d[working] > 0) != jammed_bc[working]))


# --- breakaway sweeps (variants: normal conventions) ----------------------------------------------
@quantity(BREAKAWAY_KINDS, "length")
def breakaway_difference(r, v, prototype, dXg, statistic):
    """mean or max over theta2(t0) of I_B - I_A after the first step (m)."""
    ds = r.sweep(v, prototype, dXg)
    return float(getattr(np, statistic)((ds["I_B"] - ds["I_A"]).values))


@quantity(BREAKAWAY_KINDS, "1/area")
def breakaway_cubic_coefficient(r, v, prototype, dXg, statistic):
    """breakaway_difference over dXg^3 (m / m^3)."""
    return breakaway_difference(r, v, prototype, dXg, statistic) / float(dXg) ** 3


@quantity(BREAKAWAY_KINDS, "length")
def breakaway_ground_step(r, v, prototype, dXg):
    """The ground step of the sweep, dXg (m), read from the dataset."""
    return float(r.sweep(v, prototype, dXg)["dXg"])


@quantity(BREAKAWAY_KINDS, "length")
def breakaway_endpoint_mismatch(r, v, prototype, dXg):
    """max(|I_A - I_D|, |I_B - I_C|) over theta2(t0) (m): 0 when the endpoints superimpose."""
    ds = r.sweep(v, prototype, dXg)
    return float(max(np.abs(ds["I_A"] - ds["I_D"]).max(), np.abs(ds["I_B"] - ds["I_C"]).max()))


@quantity(BREAKAWAY_KINDS, "1")
def breakaway_bc_larger(r, v, prototype, dXg):
    """Fraction of theta2(t0) where the B2C2 diagonal penetrates more than A2D2 (1)."""
    ds = r.sweep(v, prototype, dXg)
    return float(np.mean((ds["I_B"] - ds["I_A"]).values > 0))


@quantity(BREAKAWAY_KINDS, "length")
def breakaway_min_determinant(r, v, prototype, dXg):
    """Smallest |C_q| over theta2(t0) (m)."""
    return float(np.abs(r.sweep(v, prototype, dXg)["det_Cq"]).min())


@quantity(BREAKAWAY_KINDS, "1")
def breakaway_scaling(r, v, prototype, dXg, other_dXg, corner):
    """mean I_corner at dXg / mean I_corner at other_dXg (1): 'almost doubles' in the paper."""
    big = r.sweep(v, prototype, dXg)[f"I_{corner}"].mean()
    small = r.sweep(v, prototype, other_dXg)[f"I_{corner}"].mean()
    return float(big / small)


# --- what the workflow computes ------------------------------------------------------------------
@dataclass(frozen=True)
class Catalogue:
    """What the workflow computes, to check the paper values against.

    Parameters
    ----------
    prototypes, models, dt, case_variants, breakaway_variants, dXg
        Names and values the workflow runs (dt and dXg in s and m).
    duration : float, optional
        Length of the ground motion (s); times are checked against it when given.
    case_prototypes : tuple of (str, tuple of str), optional
        The prototypes each case set runs; empty: every case set runs every prototype.
    """

    prototypes: tuple
    models: tuple
    dt: tuple
    case_variants: tuple
    breakaway_variants: tuple
    dXg: tuple
    duration: float | None = None
    case_prototypes: tuple = ()

    def __post_init__(self):
        for name in ("prototypes", "models", "case_variants", "breakaway_variants"):
            object.__setattr__(self, name, tuple(getattr(self, name)))
        object.__setattr__(self, "dt", tuple(float(x) for x in self.dt))
        object.__setattr__(self, "dXg", tuple(float(x) for x in self.dXg))
        object.__setattr__(self, "case_prototypes", tuple((k, tuple(p)) for k, p in self.case_prototypes))

    def runs(self, case_variant, prototype):
        """Whether the case set ``case_variant`` runs ``prototype``."""
        runs = dict(self.case_prototypes)
        return case_variant not in runs or prototype in runs[case_variant]


def catalogue_from_config(config) -> Catalogue:
    """The Catalogue of a paper-study configuration (``config/config.yaml``)."""
    case_sets = config.get("case_sets") or {}
    breakaway = config.get("breakaway") or {}
    return Catalogue(
        prototypes=tuple(config.get("prototypes") or {}), models=tuple(config.get("models") or ()),
        dt=tuple(config.get("dt") or ()), case_variants=tuple(case_sets),
        breakaway_variants=tuple(breakaway.get("normals") or ()), dXg=tuple(breakaway.get("dXg") or ()),
        duration=float(config["duration"]) if "duration" in config else None,
        case_prototypes=tuple((name, tuple(spec.get("cases") or ())) for name, spec in case_sets.items()))


# --- loading -------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PaperValues:
    """The checked contents of ``paper_values.yaml``: the stated numbers and the readings."""

    entries: tuple
    readings: tuple = ()


def load_values(path, catalogue: Catalogue) -> PaperValues:
    """Read and check ``paper_values.yaml`` against what the workflow computes.

    Raises
    ------
    ValueError
        Listing every mistake, each naming its entry id.
    """
    with open(path) as f:
        data = load_yaml(f)
    problems = schema_errors("paper_values", data)  # the file's structure: dccss/schemas/paper_values.schema.yaml
    top = [p for p in problems if len(p.owner) < 2]
    if top:
        raise ValueError("\n".join(f"{path}: {p.message}" for p in top))
    entries, readings = data["values"], data.get("readings") or []
    ids = [e.get("id", "?") if isinstance(e, dict) else "?" for e in [*entries, *readings]]
    errors = [f"paper value {i!r} is listed {ids.count(i)} times" for i in dict.fromkeys(ids) if ids.count(i) > 1]
    stated = {e.get("id"): e for e in entries if isinstance(e, dict)}
    for section, items, check in (("values", entries, lambda e: _entry_errors(e, catalogue)),
                                  ("readings", readings, lambda g: _reading_errors(g, catalogue, stated))):
        for i, item in enumerate(items):
            mine = [p for p in problems if p.owner == (section, i)]
            label = "paper value" if section == "values" else "reading"
            if not isinstance(item, dict):
                errors.append(f"{label} {item!r} is not a mapping")
            elif mine:  # what the schema finds first, then the rest once the structure holds
                errors += [f"{label} {item.get('id', '?')!r}: {p.message}" for p in mine]
            else:
                errors += check(item)
    if errors:
        raise ValueError("\n".join(errors))
    return PaperValues(tuple(entries), tuple(readings))


def _entry_errors(e, catalogue):
    """What the schema cannot say of a paper value."""
    name = f"paper value {e['id']!r}"
    errors = []
    if not e["expect"] and not e.get("reason"):
        errors.append(f"{name}: a value expected not to reproduce needs a 'reason'")
    errors += _quantity_errors(name, "quantity", e["quantity"], catalogue, e["unit"])
    errors += _expect_errors(name, "expect", e["expect"], e["quantity"], catalogue)
    if "reading" in e:
        errors += _entry_reading_errors(name, e["reading"], e["unit"], catalogue)
    return errors


def _entry_reading_errors(name, reading, unit, catalogue):
    errors = _quantity_errors(name, "reading.quantity", reading["quantity"], catalogue, unit)
    return errors + _expect_errors(name, "reading.expect", reading["expect"], reading["quantity"], catalogue)


def _reading_errors(g, catalogue, stated):
    """What the schema cannot say of a reading."""
    name = f"reading {g['id']!r}"
    errors = []
    reads = g["reads"] if isinstance(g["reads"], list) else [g["reads"]]
    unknown = [i for i in reads if i not in stated]
    if unknown:
        return [f"{name}: reads unknown paper value(s) {unknown}"]
    if len(reads) != (2 if g["law"] == "ratio" else 1):
        errors.append(f"{name}: law {g['law']!r} reads {2 if g['law'] == 'ratio' else 1} paper value(s), "
                      f"not {len(reads)}")
    errors += _quantity_errors(name, "quantity", g["quantity"], catalogue, g["unit"])
    errors += _expect_errors(name, "variant", [g["variant"]], g["quantity"], catalogue)
    if g["expect"] != "holds" and not g.get("reason"):
        errors.append(f"{name}: a reading expected not to hold needs a 'reason'")
    return errors + _law_errors(name, g, [stated[i] for i in reads], catalogue)


def _law_errors(name, g, read, catalogue):
    """The units of a reading against its law and the paper values it reads."""
    dims = [DIMENSIONS.get(e["unit"]) for e in read]
    want = {"value": dims[0], "ratio": "1", "per_cubed_step": "1/area"}[g["law"]]
    errors = []
    if DIMENSIONS.get(g["unit"]) != want:
        errors.append(f"{name}: law {g['law']!r} gives {want}, not {DIMENSIONS.get(g['unit'])} ({g['unit']!r})")
    if g["law"] == "ratio" and dims[0] != dims[-1]:
        errors.append(f"{name}: the ratio of a {dims[0]} and a {dims[-1]}")
    if g["law"] == "per_cubed_step":
        if dims[0] != "length":
            errors.append(f"{name}: law 'per_cubed_step' reads a length, not a {dims[0]}")
        if "ground_step" not in g:
            errors.append(f"{name}: law 'per_cubed_step' needs a ground_step quantity")
        else:
            errors += _quantity_errors(name, "ground_step", g["ground_step"], catalogue, "m")
    elif "ground_step" in g:
        errors.append(f"{name}: ground_step is used only by law 'per_cubed_step'")
    return errors


def _is_number(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _quantity_errors(name, where, q, catalogue, unit):
    """The kind, its parameters, their values, and the unit against the kind's dimension."""
    if not isinstance(q, dict) or q.get("kind") not in QUANTITIES:
        kind = q.get("kind") if isinstance(q, dict) else q
        return [f"{name}: {where}.kind {kind!r} is not a known kind; known: {sorted(QUANTITIES)}"]
    kind = q["kind"]
    errors = []
    if DIMENSIONS[unit] != KIND_DIMENSIONS[kind]:
        errors.append(f"{name}: unit {unit!r} measures {DIMENSIONS[unit]}; {where}.kind {kind!r} gives "
                      f"{KIND_DIMENSIONS[kind]}")
    params = list(inspect.signature(QUANTITIES[kind]).parameters.values())[2:]
    given = set(q) - {"kind"}
    required = {p.name for p in params if p.default is inspect.Parameter.empty}
    known = {p.name for p in params}
    signature = ", ".join(p.name for p in params)
    if required - given:
        errors.append(f"{name}: {where} is missing parameter(s) {sorted(required - given)} of kind {kind!r} "
                      f"({signature})")
    if given - known:
        errors.append(f"{name}: {where} has unknown parameter(s) {sorted(given - known)} for kind {kind!r} "
                      f"({signature})")
    for key in sorted(given & known):
        message = _parameter_error(key, q[key], q, catalogue)
        if message:
            errors.append(f"{name}: {where}.{key} {message}")
    return errors


def _allowed(key, catalogue):
    """The values a parameter may take, or None for the parameters checked otherwise."""
    return {"prototype": catalogue.prototypes, "other_prototype": catalogue.prototypes,
            "model": catalogue.models, "dt": catalogue.dt, "other_dt": catalogue.dt,
            "dXg": catalogue.dXg, "other_dXg": catalogue.dXg, "corner": CORNERS, "phase": PHASES,
            "statistic": STATISTICS}.get(key)


def _parameter_error(key, value, q, catalogue):
    """Why ``value`` is not allowed for parameter ``key`` of quantity ``q``, or None."""
    allowed = _allowed(key, catalogue)
    if allowed is not None:
        return None if _member(value, allowed) else f"{value!r} is not one of {list(allowed)}"
    if key == "time":
        return _time_error(value, q.get("dt"), catalogue.duration)
    if key == "threshold":
        return None if _is_number(value) and 0 < value < 1 else f"{value!r} is not a number between 0 and 1"
    if key == "of":
        fits = sorted(k for k in CASE_KINDS if _parameter_names(k) == ["prototype", "model", "dt"])
        return None if value in fits else f"{value!r} is not one of {fits}"
    raise ValueError(f"parameter {key!r} has no check")


def _member(value, allowed):
    if isinstance(value, bool):
        return False
    return value in allowed


def _parameter_names(kind):
    return list(inspect.signature(QUANTITIES[kind]).parameters)[2:]


def _time_error(time, dt, duration):
    if not _is_number(time):
        return f"{time!r} is not a number"
    if time <= 0 or (duration is not None and time > duration):
        return f"{time!r} is not inside the motion (0, {duration}] s"
    if _is_number(dt) and dt > 0 and abs(time / dt - round(time / dt)) > 1e-6:
        return f"{time!r} is not the end of a step of {dt} s"
    return None


def _expect_errors(name, where, expect, q, catalogue):
    """Expected variants: variants of the quantity's kind whose case sets run its prototypes."""
    if not isinstance(expect, list) or not isinstance(q, dict) or q.get("kind") not in QUANTITIES:
        return []
    variants = catalogue.case_variants if q["kind"] in CASE_KINDS else catalogue.breakaway_variants
    errors = []
    for v in expect:
        if v not in variants:
            errors.append(f"{name}: {where} {v!r} is not one of {list(variants)}")
        elif q["kind"] in CASE_KINDS:
            for key in ("prototype", "other_prototype"):
                if key in q and q[key] in catalogue.prototypes and not catalogue.runs(v, q[key]):
                    errors.append(f"{name}: {where} {v!r} does not run prototype {q[key]!r}")
    return errors


# --- evaluation ---------------------------------------------------------------------------------
def evaluate(values, results: Results, case_variants, breakaway_variants) -> list[dict]:
    """Compute every entry for every variant, then every reading; statuses as in the module docstring.

    Parameters
    ----------
    values : PaperValues or list of dict
        From ``load_values`` (a plain list: entries without readings).
    results : Results
    case_variants, breakaway_variants : sequence of str
        The variants, the primary one first.

    Returns
    -------
    list of dict
        One row per entry (``section`` "paper value"), then one per reading (``section`` "reading").
    """
    entries, readings = (values.entries, values.readings) if isinstance(values, PaperValues) else (values, ())
    variants = {"case": tuple(case_variants), "breakaway": tuple(breakaway_variants)}
    rows = [_evaluate_entry(e, results, variants) for e in entries]
    stated = {r["id"]: r for r in rows}
    return rows + [_evaluate_reading(g, results, stated) for g in readings]


def _variants_of(kind, variants):
    return variants["case" if kind in CASE_KINDS else "breakaway"]


def _compute(name, q, results, variants, scale):
    """{variant: value in the entry's unit} for every variant that has the datasets."""
    computed = {}
    for v in _variants_of(q["kind"], variants):
        try:
            computed[v] = _compute_one(name, q, results, v) * scale
        except MissingDataset:
            continue  # the workflow does not compute this variant of the case
    if not computed:
        raise ValueError(f"{name}: no dataset for {q['kind']} in any of {list(_variants_of(q['kind'], variants))}")
    return computed


def _compute_one(name, q, results, variant):
    """The quantity for one variant (SI), which must have the datasets."""
    params = dict(q)
    kind = params.pop("kind")
    try:
        return QUANTITIES[kind](results, variant, **params)
    except Exception as err:
        err.add_note(f"while computing {name} ({kind}) for variant {variant!r}")
        raise


def _passing(name, e, q, computed, expect):
    """The variants within the check, after making sure every expected one was computed."""
    absent = [v for v in expect if v not in computed]
    if absent:
        raise ValueError(f"{name}: expected variant(s) {absent} have no dataset for {q['kind']}")
    return [v for v, x in computed.items() if _holds(e.get("relation", "within"), x, e["value"], e["tolerance"])]


def _evaluate_entry(e, results, variants):
    name = f"paper value {e['id']!r}"
    scale = UNITS[e["unit"]]
    computed = _compute(name, e["quantity"], results, variants, scale)
    passed = _passing(name, e, e["quantity"], computed, e["expect"])
    failing = [v for v in e["expect"] if v not in passed]
    status = _status(passed, _variants_of(e["quantity"]["kind"], variants))
    reading = None
    if "reading" in e:
        reading = _evaluate_entry_reading(name, e, results, variants, scale)
        failing += [v for v in e["reading"]["expect"] if v not in reading["passed"]]
        if status is None and reading["passed"]:
            status = _status(reading["passed"], _variants_of(e["reading"]["quantity"]["kind"], variants),
                             e["reading"]["label"])
    best = min(computed.values(), key=lambda x: abs(x - e["value"]))
    base = e.get("reason", "") if not passed or failing else e.get("note", "")
    return {
        "section": "paper value", "id": e["id"], "description": e["description"], "source": e["source"],
        "paper_value": e["value"], "unit": e["unit"], "tolerance": e["tolerance"],
        "relation": e.get("relation", "within"), "computed": computed, "deviation": best - e["value"],
        "status": status or "not reproduced", "under_reading": status is not None and not passed,
        "expected": list(e["expect"]), "ok": not failing, "reading": reading,
        "round_off": _round_off(e["quantity"]["kind"], scale), "reason": base,
    }


def _evaluate_entry_reading(name, e, results, variants, scale):
    q = e["reading"]["quantity"]
    computed = _compute(f"{name} (reading)", q, results, variants, scale)
    return {"label": e["reading"]["label"], "computed": computed, "expected": list(e["reading"]["expect"]),
            "passed": _passing(f"{name} (reading)", e, q, computed, e["reading"]["expect"])}


def _status(passed, variants, label=None):
    """'reproduced[ as <label>][ with <variants>]', or None when nothing passed."""
    if not passed:
        return None
    head = "reproduced" + (f" as {label}" if label else "")
    return head if passed[0] == variants[0] else head + " with " + ", ".join(_variant_name(v) for v in passed)


def _round_off(kind, scale):
    return ROUND_OFF[kind] * scale if kind in ROUND_OFF else None


def _holds(relation, value, paper, tol):
    """within: |value - paper| <= tol; greater / less: value beyond paper by more than tol."""
    if relation == "within":
        return abs(value - paper) <= tol
    if relation == "greater":
        return value > paper + tol
    if relation == "less":
        return value < paper - tol
    raise ValueError(f"relation must be within, greater or less, got {relation!r}")


def _variant_name(v):
    return _VARIANT_NAMES.get(v, v)


# --- readings -----------------------------------------------------------------------------------
def _evaluate_reading(g, results, stated):
    """Paper-implied against computed, for the reading's variant."""
    name = f"reading {g['id']!r}"
    reads = g["reads"] if isinstance(g["reads"], list) else [g["reads"]]
    scale, v = UNITS[g["unit"]], g["variant"]
    computed = _compute_one(name, g["quantity"], results, v) * scale
    step = _compute_one(name, g["ground_step"], results, v) if g["law"] == "per_cubed_step" else None
    implied, low, high = _implied(g["law"], [stated[i] for i in reads], step, scale)
    holds = low <= computed <= high
    deviation = implied / computed - 1 if computed else None
    status = "holds" if holds else "off" + (f" by {100 * deviation:+.1f} %" if deviation is not None else "")
    return {
        "section": "reading", "id": g["id"], "description": g["description"],
        "source": "reading of " + ", ".join(reads), "reads": reads, "law": g["law"],
        "stated": [[stated[i]["paper_value"], stated[i]["unit"]] for i in reads], "paper_value": implied,
        "range": [low, high], "unit": g["unit"], "variant": v, "computed": {v: computed},
        "ground_step_m": step, "deviation": deviation, "status": status,
        "expected": [v] if g["expect"] == "holds" else [], "ok": holds or g["expect"] != "holds",
        "round_off": _round_off(g["quantity"]["kind"], scale),
        "reason": g.get("reason", "") if not holds else g.get("note", ""),
    }


def _implied(law, read, step, scale):
    """The paper-implied value and its range from the printed precision, in the reading's unit."""
    si = [(r["paper_value"] / UNITS[r["unit"]], r["tolerance"] / UNITS[r["unit"]]) for r in read]
    if law == "value":
        (x, tol), = si
        return x * scale, (x - tol) * scale, (x + tol) * scale
    if law == "ratio":
        (a, ta), (b, tb) = si
        return a / b * scale, (a - ta) / (b + tb) * scale, (a + ta) / (b - tb) * scale
    (x, tol), = si
    return x / step ** 3 * scale, (x - tol) / step ** 3 * scale, (x + tol) / step ** 3 * scale


# --- reports ------------------------------------------------------------------------------------
def _fmt(x):
    return f"{x:.6g}" if isinstance(x, float) else str(x)


def _floor_text(floor):
    mantissa, exponent = f"{floor:.0e}".split("e")
    return f"< {mantissa}e{int(exponent)}"


def _value_text(x, floor):
    """A computed value as printed: ``< floor`` below the round-off floor of its quantity."""
    return _floor_text(floor) if floor is not None and abs(x) < floor else _fmt(x)


def _json_value(x, floor):
    return _floor_text(floor) if floor is not None and abs(x) < floor else x


def _check_text(r, plus_minus="±"):
    return {"within": f"{plus_minus} {_fmt(r['tolerance'])}", "greater": "greater", "less": "less"}[r["relation"]]


def _entry_note(r):
    """The reason or note, with the reading's values when the entry has one."""
    if not r["reading"]:
        return r["reason"]
    reading = r["reading"]
    values = ", ".join(f"{_value_text(x, r['round_off'])} ({v})" for v, x in reading["computed"].items())
    text = f"as {reading['label']}: {values} {r['unit']}"
    return f"{r['reason']}; {text}" if r["reason"] else text


def _entry_cells(r, variants, plus_minus="±", fail="**FAIL** "):
    return [r["id"], r["description"], r["source"], _fmt(r["paper_value"]), r["unit"], _check_text(r, plus_minus),
            *[_value_text(r["computed"][v], r["round_off"]) if v in r["computed"] else "" for v in variants],
            ("" if r["ok"] else fail) + r["status"], _entry_note(r)]


def _reading_cells(r, fail="**FAIL** "):
    stated = " / ".join(f"{_fmt(x)} {unit}" for x, unit in r["stated"])
    note = r["reason"]
    if r["ground_step_m"] is not None:
        note = f"dX_g = {_fmt(100 * r['ground_step_m'])} cm" + (f"; {note}" if note else "")
    return [r["id"], r["description"], ", ".join(r["reads"]), stated, _fmt(r["paper_value"]),
            f"{_fmt(r['range'][0])} to {_fmt(r['range'][1])}", _value_text(r["computed"][r["variant"]], r["round_off"]),
            r["unit"], r["variant"], ("" if r["ok"] else fail) + r["status"], note]


def _table(head, rows):
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    return lines + ["| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |" for cells in rows]


def summary(rows) -> str:
    """'N of M stated numbers reproduced[, k of them only under a reading]; ...'."""
    stated = [r for r in rows if r["section"] == "paper value"]
    n_ok = sum(r["status"] != "not reproduced" for r in stated)
    k = sum(r["under_reading"] for r in stated)
    failing = [r["id"] for r in rows if not r["ok"]]
    return (f"{n_ok} of {len(stated)} stated numbers reproduced"
            + (f", {k} of them only under a reading" if k else "") + "; "
            + (f"FAILED (expected to reproduce, did not): {', '.join(failing)}" if failing
               else "every number expected to reproduce does."))


def markdown(rows, case_variants, breakaway_variants) -> str:
    """The report: the summary, the table of stated numbers, and the readings."""
    variants = list(dict.fromkeys([*case_variants, *breakaway_variants]))
    stated = [r for r in rows if r["section"] == "paper value"]
    readings = [r for r in rows if r["section"] == "reading"]
    head = ["id", "what", "source", "paper", "unit", "check", *variants, "status", "note"]
    text = "# Validation against the paper\n\n" + summary(rows) + "\n\n"
    text += "\n".join(_table(head, [_entry_cells(r, variants) for r in stated])) + "\n"
    floors = sorted({(r["unit"], r["round_off"]) for r in rows if r["round_off"] is not None})
    if floors:
        text += ("\nValues below the round-off floor of their quantity are printed as such ("
                 + ", ".join(f"{_floor_text(f)} {unit}" for unit, f in floors)
                 + "); their checks use the computed values.\n")
    if readings:
        text += ("\n## Readings\n\nHow some stated numbers are read, not counted above: the value each reading "
                 "implies from the paper's numbers, the range their printed precision allows, and the value "
                 "computed for one variant.\n\n")
        head = ["id", "what", "reads", "stated", "implied", "range", "computed", "unit", "variant", "status", "note"]
        text += "\n".join(_table(head, [_reading_cells(r) for r in readings])) + "\n"
    return text


def to_csv(rows, case_variants, breakaway_variants) -> str:
    """The stated numbers of ``markdown`` as CSV (for the Snakemake report), then the readings
    (paper: the implied value; check: its range; the computed value in its variant's column)."""
    variants = list(dict.fromkeys([*case_variants, *breakaway_variants]))
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(["id", "what", "source", "paper", "unit", "check", *variants, "status", "note"])
    for r in rows:
        if r["section"] == "paper value":
            writer.writerow(_entry_cells(r, variants, plus_minus="+/-", fail="FAIL "))
            continue
        cells = [_value_text(r["computed"][v], r["round_off"]) if v in r["computed"] else "" for v in variants]
        writer.writerow([r["id"], r["description"], r["source"], _fmt(r["paper_value"]), r["unit"],
                         f"{_fmt(r['range'][0])} to {_fmt(r['range'][1])}", *cells,
                         ("" if r["ok"] else "FAIL ") + r["status"], _reading_cells(r)[-1]])
    return out.getvalue()


def to_json(rows) -> str:
    """The rows as JSON, values below their round-off floor as ``< floor``."""
    out = []
    for r in rows:
        r = dict(r)
        floor = r["round_off"]
        r["computed"] = {v: _json_value(x, floor) for v, x in r["computed"].items()}
        r["deviation"] = None if r["deviation"] is None else _json_value(r["deviation"], floor)
        if r.get("reading"):
            r["reading"] = {**r["reading"], "computed": {v: _json_value(x, floor)
                                                         for v, x in r["reading"]["computed"].items()}}
        r["round_off"] = None if floor is None else _floor_text(floor)
        out.append(r)
    return json.dumps(out, indent=1, sort_keys=True)
