"""Case files: one YAML document describing one run, validated key by key.

Format (lengths in m, angles in degrees, times in s)::

    prototype: {R1: 1.0, R3: 1.0, alpha1: 21.0, alpha3: 21.0, h2: 0.15, alpha21: 10.0,
                alpha23: 10.0, hr1: 0.02, hr3: 0.02, hmin1: 0.10, hmin3: 0.10,
                tr1: 0.0258, tr3: 0.0258}     # or the name of a Table 1 prototype: DFP1, DFP2
    excitation: {kind: sine, amplitude: 0.1908, omega: 30.0, duration: 1.0}
                # amplitude may be "capacity": R1 sin(alpha1 - alpha21), Table 1's X_g,max
                # or {kind: table, file: record.csv}  (CSV header `time, displacement` (m); path
                #     relative to the case file)
                # or {kind: record, file: rec.AT2, scale: 1.0, window: [t0, t1], baseline: linear,
                #     units: g}  (a PEER NGA .AT2/.VT2/.DT2 or a two-column text file with its units
                #     in a header or in `units`; see dccss.records)
                # any kind takes `scale: factor`; a record also `scale: {to: spectral_acceleration,
                #   period: T, damping: 0.05, target: Sa}` (g): scaled so that its Sa(T) is the target
                #   (a pair's RotD50, or `definition: geometric_mean`; dccss.spectra), or `scale: {to:
                #   spectrum, target: spectrum.csv, periods: [T_low, T_high], fraction: 1.0}`: over a
                #   period range, as codes scale a suite (a record alone is a suite of one)
                # Bidirectional ground motion (two horizontal components x, y):
                # - any of the above with `azimuth: 30.0` (degrees from +x towards +y): the motion
                #   applied along that direction, X(t) (cos az, sin az); without it, one component
                # - {kind: table, file: motion.csv}  with the CSV header `time, x, y` (m); a header
                #     with x but no y (or displacement and x/y) is refused
                # - {kind: record, file: [x.AT2, y.AT2], scale: .., window: [t0, t1], baseline: ..,
                #     units: .., pair_span: common}  a record pair (dccss.records.RecordPair): both
                #     files processed as one record, each with its own units header; files of
                #     different lengths (same dt) run over the time both cover (pair_span: common)
                #     or padded with zero acceleration (longest); never resampled
                # a record takes `vertical: V.AT2`, its vertical component (processed with it), or any
                #   kind `vertical: {kind: sine, amplitude: 3.0, omega: 12.0}` (m/s2): it acts on an
                #   isolated structure's normal force N = W (1 + a_v/g)
                # a record pair is placed x east, y north by its PEER files' component azimuths
                #   (line 2), whatever their order (else in file order), and `rotation: 30.0` turns it
                # a two-component table or record pair takes no `azimuth`, but may take
                #   `component: x` (or y: the other held at zero) or `both` (the default), to run
                #   the same input unidirectionally and bidirectionally
                # Two-component input runs the spatial models (dccss.mechanics.spatial); the dataset
                # then holds Xg_x, Xg_y, tilt, tilt_azimuth, rise, the pad centre and axis
    theta2_0: 0.0          # optional, default 0
    dt: 0.01
    model: compliant       # or stick_slip
    normals: signed        # optional: signed (default) or unsigned
    newton: {tol: 1.0e-12, max_iter: 25}   # optional
    capacity: continue     # optional: when the pad reaches a ring, continue (flagged), stop or error
    on_failure: error      # optional: a solver failure stops with an error (default), or mark: the
                           # history is written up to the failure and marked (failed, failure_time_s)
    id: my-case            # optional, recorded in the dataset
    structure: {friction: 0.05, damping: 0.0, friction_on: device}
                           # optional: a rigid superstructure on the device, driven by the ground's
                           # acceleration (dccss.mechanics.structure): the device undergoes its stroke
                           # (RB1 moves by minus the stroke relative to RB3); without it, the ground
                           # displacement itself is imposed, the superstructure held still in space;
                           # friction_on: surfaces reads friction as each sliding surface's coefficient
"""

from __future__ import annotations

import hashlib
import json
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import yaml

from .checks import CaseError, Problems, check_keys, choice, number
from .excitation import (
    COMPONENTS,
    Component,
    Oriented,
    Scaled,
    Sine,
    Vertical,
    VerticalSine,
    check_step,
    has_vertical,
    read_table,
)
from .mechanics import registry
from .mechanics.capacity import CAPACITY_POLICIES
from .mechanics.geometry import ANGLES, LENGTHS, PARAMETERS, Geometry
from .mechanics.kinematics import NORMALS
from .mechanics.newton import FAILURE_POLICIES, NewtonOptions
from .mechanics.structure import FRICTION_ON, SLIDERS, Structure, StructureError
from .mechanics.structure.sliders import hinge_problem
from .paper.prototypes import TABLE1
from .schema import errors as schema_errors
from .schema import load_yaml, schema

#: a case file's keys, the defaults of the optional ones and each excitation kind's keys: the schema
#: dccss/schemas/case.schema.yaml, which every case is also held to
SCHEMA = schema("case")
REQUIRED = tuple(SCHEMA["required"])
OPTIONAL = {k: spec.get("default") for k, spec in SCHEMA["properties"].items() if k not in REQUIRED}
EXCITATION_KEYS = {kind: tuple(k for k in SCHEMA["$defs"][kind]["required"] if k != "kind")
                   for kind in SCHEMA["properties"]["excitation"]["properties"]["kind"]["enum"]}
EXCITATION_OPTIONAL = {kind: tuple(k for k in SCHEMA["$defs"][kind]["properties"] if k not in ("kind", *keys))
                       for kind, keys in EXCITATION_KEYS.items()}


def geometry_from(value, key="prototype") -> Geometry:
    """A Geometry from a Table 1 prototype name or a mapping of its 13 parameters."""
    if isinstance(value, str):
        if value not in TABLE1:
            raise CaseError(f"{key}: unknown prototype {value!r}; known: {sorted(TABLE1)}")
        value = TABLE1[value]
    check_keys(value, key, PARAMETERS)
    problems = Problems(value)
    params = {k: problems.check(k, number, value[k], f"{key}.{k}") for k in PARAMETERS}
    problems.raise_if_any()
    try:
        geometry = Geometry.from_degrees(**params)
    except ValueError as err:
        raise CaseError(f"{key}: {err}") from None
    for message in _implausible(params, key):
        warnings.warn(message, DeviceWarning, stacklevel=2)
    return geometry


class DeviceWarning(UserWarning):
    """A device that is valid but whose numbers look like other units (mm for m, radians for degrees)."""


#: a length beyond which a device's parameter more likely is in mm or cm than in m
LONGEST = 50.0


def _implausible(params, key) -> list[str]:
    """Why a valid device's numbers look like other units: a length over LONGEST m, or every angle under 1
    degree (radians given for degrees)."""
    long = [f"{k} = {params[k]:g}" for k in LENGTHS if params[k] > LONGEST]
    out = [f"{key}: {', '.join(long)} m: lengths are in metres (a real device's radii are a few metres, its pad a "
           f"few tenths); are they in mm or cm?"] if long else []
    if all(abs(params[k]) < 1.0 for k in ANGLES):
        out.append(f"{key}: every angle is under 1 degree ({', '.join(f'{k} = {params[k]:g}' for k in ANGLES)}): "
                   f"angles are in degrees; are they in radians?")
    return out


def excitation_from(value, base: Path, geometry: Geometry, key="excitation"):
    """A Sine, Table, PlaneTable, Record or RecordPair excitation from its mapping (possibly
    Scaled, and Oriented by an ``azimuth``); files are relative to ``base``; a sine amplitude
    "capacity" is the device's R1 sin(alpha1 - alpha21)."""
    if not isinstance(value, dict):
        raise CaseError(f"{key}: expected a mapping, got {type(value).__name__} {value!r}")
    kind = choice(value.get("kind"), f"{key}.kind", EXCITATION_KEYS)
    check_keys(value, key, ("kind",) + EXCITATION_KEYS[kind], EXCITATION_OPTIONAL.get(kind, ()))
    excitation = _excitation(value, kind, base, geometry, key)
    if "component" not in value:
        return excitation
    which = choice(value["component"], f"{key}.component", COMPONENTS)
    try:
        return Component(excitation, which)
    except ValueError as err:
        raise CaseError(f"{key}.component: {str(err).split(': ', 1)[-1]}") from None


def _excitation(value, kind, base, geometry, key):
    azimuth = number(value["azimuth"], f"{key}.azimuth") if "azimuth" in value else None
    if kind == "record":
        if azimuth is not None and isinstance(value["file"], list):
            raise CaseError(f"{key}.azimuth: a record pair (file: [x, y]) has two components already; azimuth "
                            f"orients a one-component excitation: remove it, or give one file")
        return _oriented(record_from(value, base, key), azimuth, key)
    if "vertical" in value and not isinstance(value["vertical"], dict):
        raise CaseError(f"{key}.vertical: a vertical file is a record's component (kind: record); a {kind} takes a "
                        f"vertical sine {{kind: sine, amplitude, omega}}, got {value['vertical']!r}")
    if kind == "sine":
        problems = Problems(value)
        amplitude = geometry.capacity1 if value["amplitude"] == "capacity" else \
            problems.check("amplitude", _amplitude, value["amplitude"], f"{key}.amplitude")
        omega = problems.check("omega", number, value["omega"], f"{key}.omega")
        duration = problems.check("duration", number, value["duration"], f"{key}.duration", positive=True)
        scale = problems.check("scale", number, value["scale"], f"{key}.scale") if "scale" in value else None
        problems.raise_if_any()
        excitation = Sine(amplitude, omega, duration)
    else:
        if not isinstance(value["file"], str):
            raise CaseError(f"{key}.file: expected a path string, got {value['file']!r}")
        try:
            excitation = read_table(base / value["file"])
        except ValueError as err:
            raise CaseError(f"{key}.file: {err}") from None
        if azimuth is not None and excitation.components != 1:
            raise CaseError(f"{key}.azimuth: the table {value['file']!r} has two components (columns time, x, y) "
                            f"already; azimuth orients a one-component table (time, displacement): remove it")
        scale = number(value["scale"], f"{key}.scale") if "scale" in value else None
    excitation = excitation if scale is None else Scaled(excitation, scale)
    if "vertical" in value:
        excitation = Vertical(excitation, _vertical_sine(value["vertical"], excitation.t_start, f"{key}.vertical"))
    return _oriented(excitation, azimuth, key)


def _vertical_sine(value, t_start, key) -> VerticalSine:
    """A vertical sine {kind: sine, amplitude (m/s²), omega (rad/s)} starting at t_start; errors name ``key``."""
    if not isinstance(value, dict):
        raise CaseError(f"{key}: expected a file or a sine {{kind: sine, amplitude, omega}}, got {value!r}")
    check_keys(value, key, ("kind", "amplitude", "omega"), ())
    choice(value["kind"], f"{key}.kind", ("sine",))
    try:
        return VerticalSine(value["amplitude"], value["omega"], t_start)
    except CaseError as err:
        raise CaseError(str(err).replace("excitation.vertical", key)) from None


def _amplitude(value, key):
    """A sine's amplitude (m), other than the word "capacity" (an error names both)."""
    if isinstance(value, str):
        raise CaseError(f"{key}: expected a number (m) or the word 'capacity' (the device's R1 sin(alpha1 - "
                        f"alpha21)), got the string {value!r}")
    return number(value, key)


def _oriented(excitation, azimuth, key):
    """``excitation`` applied along ``azimuth`` (degrees), or as it is when azimuth is None."""
    if azimuth is None:
        return excitation
    try:
        return Oriented(excitation, azimuth)
    except ValueError as err:
        raise CaseError(f"{key}.azimuth: {err}") from None


def record_from(value, base: Path, key="excitation"):
    """A Record (a ground-motion file processed to displacement), or a RecordPair when ``file`` is
    a list of two files [x, y], from its mapping; ``units`` states the units of the files' motion
    when a file does not."""
    from .records import BASELINES, PAIR_SPANS, RecordPair, VerticalError, WindowError, read_components, units_from

    file = value["file"]
    if isinstance(file, list):
        if len(file) != 2:
            problem = ("one component is missing" if len(file) == 1 else
                       "a record has at most two horizontal components" if len(file) > 2 else "it is empty")
            raise CaseError(f"{key}.file: a record pair is a list of two files [x, y], got {len(file)} "
                            f"({file!r}): {problem}; for one component give a single file (a string)")
        for i, f in enumerate(file):
            if not isinstance(f, str):
                raise CaseError(f"{key}.file[{i}]: expected a path string, got {type(f).__name__} {f!r}")
    elif not isinstance(file, str):
        raise CaseError(f"{key}.file: expected a path string or a list of two [x, y], got "
                        f"{type(file).__name__} {file!r}")
    scale = value.get("scale", 1.0)
    spectral = scale if isinstance(scale, dict) else None
    scale = 1.0 if spectral is not None else number(scale, f"{key}.scale")
    window = value.get("window")
    if window is not None:
        if not isinstance(window, list) or len(window) != 2:
            raise CaseError(f"{key}.window: expected [t_start, t_end] in s, got {window!r}")
        window = tuple(number(w, f"{key}.window") for w in window)
    baseline = value.get("baseline")
    if baseline is not None:
        baseline = choice(baseline, f"{key}.baseline", BASELINES)
    rotation = number(value.get("rotation", 0.0), f"{key}.rotation")
    if "rotation" in value and not isinstance(file, list):
        raise CaseError(f"{key}.rotation: turns a record pair (file: [x, y]); one component is oriented by "
                        f"azimuth instead")
    units = value.get("units")
    if units is not None:
        if not isinstance(units, str):
            raise CaseError(f"{key}.units: expected units such as g, cm/s2, cm/s or cm, got {units!r}")
        try:
            units_from(units)
        except ValueError as err:
            raise CaseError(f"{key}.units: {err}") from None
    pair_span = choice(value.get("pair_span", "common"), f"{key}.pair_span", PAIR_SPANS)
    vertical = value.get("vertical")
    if vertical is not None and not isinstance(vertical, (str, dict)):
        raise CaseError(f"{key}.vertical: expected the vertical component's file or a sine {{kind: sine, amplitude, "
                        f"omega}}, got {type(vertical).__name__} {vertical!r}")
    files = [base / f for f in (file if isinstance(file, list) else [file])]
    up_file = base / vertical if isinstance(vertical, str) else None

    def read(factor, cut=window):
        """The horizontal motion (its vertical component kept as ``vertical``, None without one)."""
        try:
            horizontals, up = read_components(files, up_file, scale=factor, window=cut, baseline=baseline,
                                              units=units, pair_span=pair_span)
            motion = RecordPair.of(*horizontals, files, rotation) if isinstance(file, list) else horizontals[0]
        except ValueError as err:
            where = ("window" if isinstance(err, WindowError) else
                     "vertical" if isinstance(err, VerticalError) else "file")
            raise CaseError(f"{key}.{where}: {err}") from None
        motion.vertical = up
        return motion

    def whole(factor):
        """The record before its window (for its spectrum)."""
        return read(factor, None)

    if spectral is None:
        motion = read(scale)
    # the spectrum is the whole record's (as its processing), the scaled record then windowed
    elif spectral.get("to") == "spectrum":
        identity = (tuple(str(f) for f in files), baseline, units, rotation, window, pair_span)
        motion = _scaled_over_range(identity, read, whole, spectral, isinstance(file, list), f"{key}.scale", base)
    else:
        motion = _scaled_to_spectrum(whole(scale), read, spectral, isinstance(file, list), f"{key}.scale")
    if isinstance(vertical, dict):
        return Vertical(motion, _vertical_sine(vertical, motion.t_start, f"{key}.vertical"))
    return motion if motion.vertical is None else Vertical(motion, motion.vertical)


def _scaled_to_spectrum(record, read, spec, pair, key):
    """The record read again (windowed, if it is) at the scale that makes the spectral acceleration of
    ``record`` (the whole record) the target's."""
    from .records import G
    from .spectra import spectral_acceleration

    period, target, damping, definition = spectral_scaling(spec, pair, key)
    duration = record.t_end - record.t_start
    if period > duration:
        raise CaseError(f"{key}.period: {period:g} s is longer than the record ({duration:g} s): an oscillator of that "
                        f"period has not completed one cycle of response; give a period within the record")
    unscaled = spectral_acceleration(record, period, damping, definition)
    if not unscaled > 0:
        raise CaseError(f"{key}: the record's spectral acceleration at T = {period:g} s is {unscaled!r}: it cannot "
                        f"be scaled to a target")
    scaled = read(target * G / unscaled)
    scaled.scaling = {"record_scaled_to_sa_g": target, "record_scaling_period_s": period,
                      "record_scaling_damping": damping, "record_sa_unscaled_g": unscaled / G,
                      **({"record_scaling_definition": definition} if pair else {})}
    return scaled


def spectral_scaling(spec, pair, key="excitation.scale"):
    """The keys of a scaling to a spectral acceleration, checked: (period, target, damping, definition)."""
    from .spectra import PAIR_DEFINITIONS

    choice(spec.get("to"), f"{key}.to", ("spectral_acceleration", "spectrum"))
    check_keys(spec, key, ("to", "period", "target"), ("damping", "definition"))
    period = number(spec["period"], f"{key}.period", positive=True)
    target = number(spec["target"], f"{key}.target", positive=True)
    damping = number(spec.get("damping", 0.05), f"{key}.damping")
    if not 0 <= damping < 1:
        raise CaseError(f"{key}.damping: {damping!r} is outside 0 <= damping < 1")
    definition = choice(spec.get("definition", "rotd50"), f"{key}.definition", PAIR_DEFINITIONS)
    if not pair and "definition" in spec:
        raise CaseError(f"{key}.definition: says how a pair's spectral acceleration is taken; this record has one "
                        f"component")
    return period, target, damping, definition


def _scaled_over_range(identity, read, whole, spec, pair, key, base):
    """The record read again (windowed, if it is) at the factor that scales it over a period range
    (``dccss.spectra.suite_factors``): its own fit to the target times the suite's factor
    (``suite_factor``; without it the record is a suite of one, scaled so that its spectrum is
    nowhere in the range below ``fraction`` × target). ``identity``: the files and processing whose
    spectrum is computed (once per process); ``whole(factor)``: the record before its window."""
    from .records import G
    from .spectra import range_periods, suite_factors

    table, periods, damping, definition, fraction, individual, suite = range_scaling(spec, pair, key, base)
    grid = range_periods(*periods, table[0])
    unscaled = _range_spectrum(identity, tuple(grid), damping, definition, key, whole)
    target = np.interp(grid, *table) * G
    if not (unscaled > 0).all():
        raise CaseError(f"{key}: the record's spectral acceleration is {unscaled.min()!r} at a period of the range: it "
                        f"cannot be scaled to a target")
    factors, fitted, own = suite_factors(unscaled[None], target, fraction, individual)
    if suite is None:
        suite, factor = own, float(factors[0])
    else:
        factor = suite * float(fitted[0])  # as suite_factors does
    scaled = read(factor)
    scaled.scaling = {"record_scaled_to": "spectrum", "record_scaling_periods_s": np.array(periods),
                      "record_scaling_damping": damping, "record_scaling_fraction": fraction,
                      "record_scaling_fit": float(fitted[0]), "record_scaling_suite_factor": suite,
                      **({"record_scaling_definition": definition} if pair else {})}
    scaled.spectrum = {"periods": grid, "unscaled": unscaled, "target": target}  # m/s²
    return scaled


def range_scaling(spec, pair, key="excitation.scale", base=Path(".")):
    """The keys of a scaling over a period range, checked (every mistake at once): (the target's periods
    and Sa in g, the range, damping, definition, fraction, individual, the suite's factor or None);
    ``pair``: whether the record is a pair (a definition is a pair's)."""
    from .spectra import PAIR_DEFINITIONS

    check_keys(spec, key, ("to", "target", "periods"),
               ("damping", "definition", "fraction", "individual", "suite_factor"))
    problems = Problems(spec)
    table = problems.check("target", _target_spectrum, spec["target"], f"{key}.target", base)
    periods = problems.check("periods", _period_range, spec["periods"], f"{key}.periods")
    damping = problems.check("damping", number, spec.get("damping", 0.05), f"{key}.damping")
    if damping is not None and not 0 <= damping < 1:
        problems.add("damping", f"{key}.damping: {damping!r} is outside 0 <= damping < 1")
    definition = problems.check("definition", choice, spec.get("definition", "rotd50"), f"{key}.definition",
                                PAIR_DEFINITIONS)
    if not pair and "definition" in spec:
        problems.add("definition", f"{key}.definition: says how a pair's spectral acceleration is taken; this record "
                                   f"has one component")
    fraction = problems.check("fraction", number, spec.get("fraction", 1.0), f"{key}.fraction", positive=True)
    individual = spec.get("individual", True)
    if not isinstance(individual, bool):
        problems.add("individual", f"{key}.individual: expected true (each record fitted to the target first) or "
                                   f"false (one factor for the whole suite), got {individual!r}")
    suite = spec.get("suite_factor")
    if suite is not None:
        suite = problems.check("suite_factor", number, suite, f"{key}.suite_factor", positive=True)
    if table is not None and periods is not None and not table[0][0] <= periods[0] < periods[1] <= table[0][-1]:
        problems.add("periods", f"{key}.periods: the range {list(periods)} s is not within the target's periods "
                                f"{table[0][0]:g} to {table[0][-1]:g} s")
    problems.raise_if_any()
    return table, periods, damping, definition, fraction, individual, suite


#: the spectra of records over a period range, by the record's files and processing and the range
_SPECTRA = {}


def _range_spectrum(identity, grid, damping, definition, key, whole):
    """The whole record's (unwindowed, unscaled) spectrum (m/s²) at the periods ``grid``, computed once
    per process (a study reads a suite's records twice: on their own, then with the suite's factor)
    and kept on disk (``spectra.cached_spectrum``)."""
    from .spectra import cached_spectrum

    files = identity[0]
    stamp = tuple((Path(f).stat().st_mtime_ns, Path(f).stat().st_size) for f in files if Path(f).exists())
    cache = (identity, stamp, grid, damping, definition)
    if cache not in _SPECTRA:
        record = whole(1.0)
        duration = record.t_end - record.t_start
        if grid[-1] > duration:
            raise CaseError(f"{key}.periods: {grid[-1]:g} s is longer than the record ({duration:g} s): an oscillator "
                            f"of that period has not completed one cycle of response; give periods within the record")
        _SPECTRA[cache] = cached_spectrum(record, grid, damping, definition)
    return _SPECTRA[cache]


def _period_range(value, key):
    """[T_low, T_high] (s), 0 < T_low < T_high."""
    if not isinstance(value, list) or len(value) != 2:
        raise CaseError(f"{key}: expected the period range [T_low, T_high] in s, got {value!r}")
    low, high = (number(v, key, positive=True) for v in value)
    if not low < high:
        raise CaseError(f"{key}: expected T_low < T_high, got {value!r}")
    return low, high


def _target_spectrum(value, key, base):
    """The target spectrum (periods in s, increasing; Sa in g): a mapping {period: [...], sa: [...]} or a
    text file of two columns, period (s) and Sa (g), comma- or space-separated, with an optional header
    line and # comments; straight lines between its points."""
    if isinstance(value, str):
        try:
            lines = (base / value).read_text().splitlines()
        except OSError as err:
            raise CaseError(f"{key}: cannot read the target spectrum {value!r}: {err.strerror}") from None
        rows = [line.split("#")[0].replace(",", " ").split() for line in lines]
        rows = [r for r in rows if r]
        if rows and not _numeric(rows[0]):
            rows = rows[1:]  # a header
        if not rows or any(len(r) != 2 or not _numeric(r) for r in rows):
            raise CaseError(f"{key}: {value!r} is not a table of two columns, period (s) and Sa (g), one row per "
                            f"period")
        periods, sa = np.array(rows, dtype=float).T
    elif isinstance(value, dict):
        check_keys(value, key, ("period", "sa"))
        if not all(isinstance(value[k], list) for k in ("period", "sa")) or len(value["period"]) != len(value["sa"]):
            raise CaseError(f"{key}: expected lists period (s) and sa (g) of the same length, got {value!r}")
        periods = np.array([number(v, f"{key}.period") for v in value["period"]])
        sa = np.array([number(v, f"{key}.sa") for v in value["sa"]])
    else:
        raise CaseError(f"{key}: expected a file of periods (s) and Sa (g), or {{period: [...], sa: [...]}}, got "
                        f"{value!r}")
    if len(periods) < 2 or not (periods > 0).all() or not (np.diff(periods) > 0).all():
        raise CaseError(f"{key}: the periods must be at least two, > 0 and increasing, got {periods.tolist()}")
    if not (np.isfinite(sa) & (sa > 0)).all():
        raise CaseError(f"{key}: every Sa must be a number > 0 (g), got {sa.tolist()}")
    return periods, sa


def _numeric(row):
    try:
        [float(v) for v in row]
    except ValueError:
        return False
    return True


@dataclass
class Case:
    geometry: Geometry
    excitation: object
    dt: float
    model: str
    theta2_0: float = 0.0  # rad
    normals: str = "signed"
    options: NewtonOptions = field(default_factory=NewtonOptions)
    id: str | None = None
    parameters_hash: str | None = None
    capacity: str = "continue"
    on_failure: str = "error"
    structure: Structure | None = None
    slider: str = "rigid"
    hinge: float = 0.0
    friction: tuple | None = None

    def run(self, progress=None):
        """Simulate the case: an xarray.Dataset (``progress(n, N)``: as ``simulate``'s)."""
        from .simulation import simulate  # xarray: not imported to read and check a case (the workflow's DAG)

        attrs = {"case_id": self.id or "", "case_parameters_sha256": self.parameters_hash or ""}
        return simulate(self.geometry, self.excitation, model=self.model, dt=self.dt,
                        theta2_0=self.theta2_0, normals=self.normals, options=self.options,
                        capacity=self.capacity, on_failure=self.on_failure, attrs=attrs, progress=progress,
                        structure=self.structure, slider=self.slider, hinge=self.hinge, friction=self.friction)


def newton_from(value, key="newton") -> NewtonOptions:
    """Newton-Raphson options from an optional mapping {tol, max_iter}."""
    options = NewtonOptions()
    if value is None:
        return options
    check_keys(value, key, (), ("tol", "max_iter"))
    problems = Problems(value)
    tol = problems.check("tol", number, value.get("tol", options.tol), f"{key}.tol", positive=True)
    max_iter = value.get("max_iter", options.max_iter)
    if isinstance(max_iter, bool) or not isinstance(max_iter, int) or max_iter < 1:
        problems.add("max_iter", f"{key}.max_iter: expected an integer >= 1, got {max_iter!r}")
    problems.raise_if_any()
    return NewtonOptions(tol=tol, max_iter=max_iter)


#: the keys of ``structure`` and the defaults of the optional ones
STRUCTURE = SCHEMA["$defs"]["structure"]
STRUCTURE_OPTIONAL = {k: v["default"] for k, v in STRUCTURE["properties"].items() if k not in STRUCTURE["required"]}


def slider_from(value, key="slider") -> tuple[str, float]:
    """(kind, hinge) of a ``slider``: a kind's name, or {kind, hinge}; errors name the key."""
    if isinstance(value, dict):
        check_keys(value, key, ("kind",), ("hinge",))
        problems = Problems(value)
        kind = problems.check("kind", choice, value["kind"], f"{key}.kind", tuple(SLIDERS))
        hinge = problems.check("hinge", number, value.get("hinge", 0.0), f"{key}.hinge")
        problems.raise_if_any()
        return kind, hinge
    return choice(value, key, tuple(SLIDERS)), 0.0


def structure_from(value, key="structure", slider="rigid", hinge=0.0) -> Structure | None:
    """A Structure from its mapping {friction, damping} (None stays None) on a ``slider`` with its ``hinge``;
    errors name the key."""
    if value is None:
        return None
    check_keys(value, key, tuple(STRUCTURE["required"]), STRUCTURE_OPTIONAL)
    value = {**STRUCTURE_OPTIONAL, **value}
    problems = Problems(value)
    friction = value["friction"]
    if not isinstance(friction, (dict, list)):
        friction = problems.check("friction", number, friction, f"{key}.friction")
    damping = problems.check("damping", number, value["damping"], f"{key}.damping")
    factor = problems.check("property", number, value["property"], f"{key}.property")
    friction_on = problems.check("friction_on", choice, value["friction_on"], f"{key}.friction_on", FRICTION_ON)
    problems.raise_if_any()
    try:
        return Structure(friction, damping, friction_on=friction_on, factor=factor, slider=slider, hinge=hinge)
    except StructureError as err:
        raise CaseError(*(m.replace("structure.", f"{key}.", 1) for m in err.messages)) from None


def parameters_hash(mapping) -> str:
    """SHA-256 of a case mapping in canonical JSON (sorted keys): the provenance of a result."""
    return hashlib.sha256(json.dumps(mapping, sort_keys=True, default=str).encode()).hexdigest()


def case_from(mapping, base: Path = Path(".")) -> Case:
    """Validate a case mapping (as loaded from YAML); errors name the key.

    Every mistake is reported at once (one CaseError listing them, in the order of the file): each key
    is checked on its own, a key that depends on another (the excitation on the prototype, dt on the
    excitation) once that one has passed, and the schema adds its errors about the other keys."""
    if not isinstance(mapping, dict):
        check_keys(mapping, "case", REQUIRED, OPTIONAL)  # raises: not a mapping
    problems = Problems(mapping)
    problems.check("", check_keys, mapping, "case", REQUIRED, OPTIONAL)
    m, dt = {**OPTIONAL, **mapping}, None
    options = problems.check("newton", newton_from, m["newton"])
    if m["id"] is not None and not isinstance(m["id"], str):
        problems.add("id", f"id: expected a string, got {m['id']!r}")
    geometry = problems.check("prototype", geometry_from, m["prototype"]) if "prototype" in m else None
    excitation = (problems.check("excitation", excitation_from, m["excitation"], base, geometry)
                  if geometry is not None and "excitation" in m else None)
    if "dt" in m:
        dt = (problems.check("dt", check_step, m["dt"], excitation, "dt") if excitation is not None else
              problems.check("dt", number, m["dt"], "dt", positive=True))
    if excitation is not None and excitation.components == 2 and m["normals"] != "signed":
        problems.add("normals", f"normals: two-component ground motion runs the spatial models, which use signed "
                                f"normals only; got {m['normals']!r} (unsigned normals reproduce the paper's planar "
                                f"computation)")
    slider = problems.check("slider", slider_from, m["slider"])
    kind, hinge = slider if slider is not None else ("rigid", 0.0)
    structure = problems.check("structure", structure_from, m["structure"], "structure", kind, hinge)
    if structure is not None and geometry is not None:
        problems.check("structure", _device_friction, structure, geometry)
    if kind == "articulated" and geometry is not None:
        problems.check("slider", _hinge, geometry, hinge)
    friction = (None if problems.failed("slider") else  # its meaning depends on the slider's kind
                problems.check("friction", _imposed_friction, m["friction"], kind, m["structure"] is not None))
    if excitation is not None and has_vertical(excitation) and m["structure"] is None:
        problems.add("excitation", VERTICAL_WITHOUT_STRUCTURE)
    model = problems.check("model", choice, m["model"], "model", registry.names()) if "model" in m else None
    if kind == "articulated" and model not in (None, "compliant"):
        problems.add("model", f"model: an articulated slider's halves stay seated on their surfaces (compliant sliding "
                              f"by construction); the paper's {model} is the rigid pad's: give model: compliant")
    theta2_0 = problems.check("theta2_0", number, m["theta2_0"], "theta2_0")
    normals = problems.check("normals", choice, m["normals"], "normals", NORMALS)
    capacity = problems.check("capacity", choice, m["capacity"], "capacity", CAPACITY_POLICIES)
    on_failure = problems.check("on_failure", choice, m["on_failure"], "on_failure", FAILURE_POLICIES)
    problems.raise_if_any(schema_errors("case", mapping))
    return Case(geometry=geometry, excitation=excitation, dt=dt, model=model, theta2_0=np.radians(theta2_0),
                normals=normals, options=options, id=m["id"], parameters_hash=parameters_hash(mapping),
                capacity=capacity, on_failure=on_failure, structure=structure, slider=kind, hinge=hinge,
                friction=friction)


#: a vertical component without a structure: the imposed ground displacement has no normal force to act on
VERTICAL_WITHOUT_STRUCTURE = ("excitation.vertical: a vertical ground acceleration acts on an isolated structure's "
                              "normal force (structure); the imposed ground displacement (no structure) would ignore "
                              "it: give structure, or drop vertical")


def _imposed_friction(value, kind, structure) -> tuple | None:
    """The surfaces' friction of an articulated slider under the imposed displacement (``friction``)."""
    if value is None:
        if kind == "articulated" and not structure:
            raise CaseError("friction: an articulated slider without a structure needs its surfaces' Coulomb "
                            "coefficients, friction: [mu1, mu3] (each at its sliding surface, each above 0)")
        return None
    if kind != "articulated" or structure:
        raise CaseError("friction: only an articulated slider under the imposed displacement takes it (with a "
                        "structure, its friction is structure.friction with friction_on: surfaces)")
    if not (isinstance(value, list) and len(value) == 2 and all(
            isinstance(x, (int, float)) and not isinstance(x, bool) and 0.0 < x < 1.0 for x in value)):
        raise CaseError(f"friction: expected [mu1, mu3], two numbers each in 0 < mu < 1, got {value!r}")
    return tuple(float(x) for x in value)


def _hinge(geometry, hinge):
    """An articulated slider's hinge on ``geometry``, checked (a CaseError otherwise)."""
    problem = hinge_problem(geometry, hinge)
    if problem:
        raise CaseError(problem)


def _device_friction(structure, geometry):
    """The structure's device friction on ``geometry``, checked (a CaseError otherwise)."""
    try:
        return structure.device_friction(geometry)
    except StructureError as err:
        raise CaseError(str(err)) from None


def read_yaml(path, what="file"):
    """The content of the YAML file ``path`` (a CaseError, naming it as ``what``, if it is missing or not YAML)."""
    path = Path(path)
    if not path.is_file():
        raise CaseError(f"{what} {str(path)!r} does not exist")
    try:
        return load_yaml(path.read_text())
    except yaml.YAMLError as err:
        raise CaseError(f"{what} {str(path)!r} is not valid YAML: {err}") from None


def load_case(path) -> Case:
    """Read and validate a YAML case file."""
    return case_from(read_yaml(path, "case file"), Path(path).parent)
