"""The study file: keys, types and every sweep point checked before anything runs."""

from __future__ import annotations

import os
import re
import warnings
from dataclasses import dataclass, field, replace
from functools import cached_property
from pathlib import Path

import numpy as np

from ..case import (
    VERTICAL_WITHOUT_STRUCTURE,
    excitation_from,
    geometry_from,
    newton_from,
    range_scaling,
    slider_from,
    spectral_scaling,
    structure_from,
)
from ..checks import CaseError, Problems, check_keys, choice, number
from ..excitation import COMPONENTS, Component, Oriented, check_step, has_vertical, underlying
from ..mechanics import registry
from ..mechanics.capacity import CAPACITY_POLICIES
from ..mechanics.geometry import ANGLES, PARAMETERS
from ..mechanics.kinematics import NORMALS
from ..mechanics.newton import FAILURE_POLICIES, NewtonOptions
from ..mechanics.structure import SLIDERS, SURFACE_SUMMARIES, VERTICAL_SUMMARIES, Structure, StructureError
from ..mechanics.structure import SUMMARIES as STRUCTURE_SUMMARIES
from ..mechanics.summaries import specs
from ..paper.prototypes import TABLE1
from ..schema import errors as schema_errors
from ..schema import schema
from ..spectra import cached_spectrum, intensity_measure, suite_factors
from .fragility import limits_from
from .grid import CATEGORICAL, PLATE3_FOLLOWS, Grid
from .intensity import Intensity, intensity_from

#: what a study may sweep (the excitation's own parameters: see ``Sine.parameters``); ``azimuth``
#: (degrees) turns a one-component excitation into bidirectional motion along it, ``component``
#: (x, y or both) keeps one or both components of a two-component one
EXCITATION_AXES = ("amplitude", "omega", "scale", "azimuth", "rotation", "component")
#: the isolated structure's parameters (``structure``; sweeping one gives a study a structure); ``slider`` the
#: device's construction (rigid, articulated: a structure's)
STRUCTURE_AXES = ("friction", "damping", "property", "slider")
#: the friction's bounds a ``property`` axis takes (``structure.property`` gives lower's and upper's factors)
BOUNDS = ("lower", "nominal", "upper")
AXES = ("record", "prototype") + PARAMETERS + EXCITATION_AXES + STRUCTURE_AXES + ("theta2_0", "dt", "intensity")
#: the keys of a study file and those it must have: dccss/schemas/study.schema.yaml, which the workflow
#: checks a study against as well
KEYS = set(schema("study")["properties"])
REQUIRED = tuple(schema("study")["required"])
#: the defaults of the optional keys that have one
DEFAULTS = {k: v["default"] for k, v in schema("study")["properties"].items() if "default" in v}
#: the keys that only the plots and the histories read: the sweep's results do not depend on them
NOT_SWEPT = ("marks", "histories", "animate")
#: chunks per model when chunk_size is "auto" (both cores busy, progress in every chunk's log), each of at
#: least AUTO_LEAST cases (a job's start and imports cost about as much as 5-20 small cases); with a record
#: axis, "auto" is a chunk per record
AUTO_CHUNKS = 4
AUTO_LEAST = 16


class StudyError(CaseError):
    """A study file is invalid; the message names the key."""


def axis_units(name):
    """CF units of a sweep axis (None for the categorical prototype axis)."""
    if name in CATEGORICAL:
        return None
    if name in ANGLES or name in ("theta2_0", "azimuth", "rotation"):
        return "degree"
    return {"omega": "rad s-1", "scale": "1", "dt": "s", "friction": "1", "damping": "1"}.get(name, "m")


def axis_values(spec, key) -> np.ndarray:
    """A sweep axis from a list of numbers or {start, stop, num}."""
    if isinstance(spec, dict):
        check_keys(spec, key, ("start", "stop", "num"))
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise StudyError(f"{key}.num: expected an integer >= 1, got {num!r}")
        return np.linspace(number(spec["start"], f"{key}.start"), number(spec["stop"], f"{key}.stop"), num)
    if not isinstance(spec, list):
        raise StudyError(f"{key}: expected a list of values or {{start, stop, num}}, got {spec!r}")
    if not spec:
        raise StudyError(f"{key}: the sweep axis is empty")
    return np.array([number(v, f"{key}[{i}]") for i, v in enumerate(spec)])


def sweep_spec(config: dict, models=None, record=None, suite_factor=None) -> dict:
    """The part of a study file that the sweep's results depend on: all but the description, the
    marks and the histories (and, with ``models``, only those models; with ``record``, one entry of
    the ``record`` axis (``Study.record_entries``) or a list of them, only those records: what their jobs
    depend on, with the ``suite_factor`` of a suite scaled over a period range (``Study.suite_factor``),
    which the other records set)."""
    spec = {k: v for k, v in config.items() if k not in NOT_SWEPT}
    spec["study"] = {"name": config["study"]["name"]}
    if models is not None:
        spec["models"] = list(models)
    if record is not None:
        spec["sweep"] = {**config["sweep"], "record": record if isinstance(record, list) else [record]}
    if suite_factor is not None:
        scale = {**spec["excitation"]["scale"], "suite_factor": suite_factor}
        spec["excitation"] = {**spec["excitation"], "scale": scale}
    return spec


#: the keys of a suite's record given as a mapping: its file(s) and its own settings, which replace the
#: study's ``excitation`` keys for it; ``peer_scale`` and ``peer_rsn`` are what a PEER download's
#: records carry (``{peer: _SearchResults.csv}``)
RECORD_KEYS = ("file", "name", "window", "scale", "rotation", "vertical", "pair_span", "peer_scale", "peer_rsn")
#: the keys of a PEER download entry of a suite
PEER_KEYS = ("peer", "vertical")


def record_entries(spec, base: Path) -> dict:
    """{name: entry} of a ``record`` sweep axis: a list of files, pairs [x, y] of files, glob patterns
    (relative to ``base``; a pattern gives its matches in sorted order), mappings of one record's file
    and own settings (:data:`RECORD_KEYS`), or PEER downloads ``{peer: .../_SearchResults.csv,
    vertical: true}`` (each of its records a mapping, named ``RSN<number>_<station>``,
    ``dccss.peer.suite_entries``). A file is named by its stem, a pair by its station: the stems'
    common start (without trailing separators, nor a digit the two components' three-digit azimuth
    codes share, as 000 and 090), else 'x+y'; a mapping by its ``name``, else by its file(s)."""
    if not isinstance(spec, list) or not spec:
        raise StudyError(f"sweep.record: expected a non-empty list of files, pairs [x, y], patterns, mappings or "
                         f"PEER downloads, got {spec!r}")
    out = {}
    for i, entry in enumerate(spec):
        key = f"sweep.record[{i}]"
        if isinstance(entry, dict) and "peer" in entry:
            items = _peer_items(entry, key, base)
        elif isinstance(entry, dict):
            check_keys(entry, key, ("file",), tuple(k for k in RECORD_KEYS if k != "file"))
            name = entry.get("name")
            if name is not None and not isinstance(name, str):
                raise StudyError(f"{key}.name: expected a string, got {name!r}")
            if "peer_scale" in entry:  # as a download's search results give it: a factor > 0
                number(entry["peer_scale"], f"{key}.peer_scale", positive=True)
            items = [(name or _entry_name(entry["file"], f"{key}.file", base)[0][0], entry)]
        else:
            items = _entry_name(entry, key, base)
        for name, value in items:
            name = re.sub(r"[^A-Za-z0-9_.+-]", "_", name)
            if name in out:
                raise StudyError(f"{key}: two records are named {name!r} ({out[name]!r} and {value!r}); records are "
                                 f"named by their file stems (a pair by its station): rename one")
            out[name] = value
    return out


def _entry_name(entry, key, base) -> list:
    """[(name, entry)] of a file, a pair [x, y] or a pattern (its matches)."""
    if isinstance(entry, list):
        if len(entry) != 2 or not all(isinstance(f, str) for f in entry):
            raise StudyError(f"{key}: a pair is a list of two files [x, y], got {entry!r}")
        stems = [Path(f).stem for f in entry]
        codes = [re.fullmatch(r"(.*?)\d{3}", stem) for stem in stems]  # azimuth codes: ..._000, ..._090
        starts = [c.group(1) for c in codes] if all(codes) else stems  # 000 and 090 share a digit, not a name
        common = os.path.commonprefix(starts).rstrip("_-. ")
        return [(common if common and common not in stems else "+".join(stems), entry)]
    if isinstance(entry, str):
        if any(c in entry for c in "*?["):
            matches = sorted(str(p.relative_to(base)) for p in base.glob(entry) if p.is_file())
            if not matches:
                raise StudyError(f"{key}: the pattern {entry!r} matches no file under {str(base)!r}")
            return [(Path(m).stem, m) for m in matches]
        return [(Path(entry).stem, entry)]
    raise StudyError(f"{key}: expected a file, a pair [x, y], a pattern, a mapping {{file, window, scale, ...}} or "
                     f"a PEER download {{peer: _SearchResults.csv}}, got {type(entry).__name__} {entry!r}")


def _peer_items(entry, key, base) -> list:
    """[(name, mapping)] of the records of a PEER download (``{peer: csv, vertical: bool}``)."""
    from ..peer import suite_entries

    check_keys(entry, key, ("peer",), ("vertical",))
    if not isinstance(entry["peer"], str):
        raise StudyError(f"{key}.peer: expected the path of a download's _SearchResults.csv, got {entry['peer']!r}")
    vertical = entry.get("vertical", False)
    if not isinstance(vertical, bool):
        raise StudyError(f"{key}.vertical: expected true (each record's vertical component too) or false, got "
                         f"{vertical!r}")
    try:
        found = suite_entries(entry["peer"], base, vertical=vertical)
    except ValueError as err:
        raise StudyError(f"{key}.peer: {err}") from None
    return [(name, {"name": name, **record}) for name, record in found.items()]


def entry_files(entry) -> list:
    """The files of a record entry: its file or pair, and its vertical component's file."""
    own = entry if isinstance(entry, dict) else {"file": entry}
    files = own["file"] if isinstance(own["file"], list) else [own["file"]]
    return files + ([own["vertical"]] if isinstance(own.get("vertical"), str) else [])


def entry_excitation(spec, name, entry) -> dict:
    """The excitation mapping of a suite's record ``name``: the study's ``excitation`` keys with the
    record's file and own settings; ``scale: peer`` takes its factor from its PEER search results."""
    own = entry if isinstance(entry, dict) else {"file": entry}
    mapping = {**spec, **{k: v for k, v in own.items() if k not in ("name", "peer_scale", "peer_rsn")}}
    if mapping.get("scale") == "peer":
        if "peer_scale" not in own:
            raise StudyError(f"excitation.scale: 'peer' takes each record's factor from the PEER search results it "
                             f"comes from (sweep.record: [{{peer: .../_SearchResults.csv}}]), but record {name!r} "
                             f"is not from one: give it a scale of its own ({{file: ..., scale: ...}})")
        mapping["scale"] = own["peer_scale"]
    return mapping


@dataclass
class Study:
    """A validated study file (see the package docstring); ``grid`` holds its cases."""

    name: str
    description: str
    prototype: dict  # the base device's 13 parameters, m and degrees
    prototypes: dict  # name -> 13 parameters: Table 1 and the study's own
    symmetric: bool
    excitation: object  # Sine, Table or Record (unscaled)
    excitation_spec: dict
    theta2_0: float  # degrees
    dt: float | None  # s; None if only a sweep axis gives it
    models: list
    normals: str
    axes: dict  # name -> values (ordered)
    chunk_size: int
    record_jobs: int | None = None  # a suite's records spread over this many jobs per model (``Grid``)
    capacity: str = "continue"
    options: NewtonOptions = field(default_factory=NewtonOptions)
    base: Path = Path(".")
    marks: dict = field(default_factory=dict)
    histories: list = field(default_factory=list)
    animate: list = field(default_factory=list)  # indices of the histories to animate
    structure: Structure | None = None  # the base structure (None: the ground displacement is imposed)
    bounds: dict = field(default_factory=lambda: {"nominal": 1.0})  # property axis label -> the friction's factor λ
    records: dict = field(default_factory=dict)  # a record axis: name -> its excitation (processed once)
    record_entries: dict = field(default_factory=dict)  # name -> its file or pair [x, y], as in the study file
    intensity: Intensity | None = None  # the measure of an intensity axis (``studies.intensity``)
    limits: list | None = None  # the limit states whose fragility is fitted (``studies.fragility``)

    @cached_property
    def record_intensity(self) -> dict:
        """{record name (None for the study's own excitation): its intensity (SI) as processed at scale 1}, where
        the study has intensity levels."""
        if self.intensity is None:
            return {}
        i = self.intensity
        out = {}
        for name, excitation in (self.records or {None: self.excitation}).items():
            record = underlying(excitation)
            if i.measure == "sa":
                value = float(cached_spectrum(record, [i.period], i.damping, i.definition)[0])
            else:
                value = intensity_measure(record, i.measure, definition=i.definition)
            if not value > 0:
                raise StudyError(f"sweep.intensity: the intensity of record {name!r} is {value!r}: it cannot be "
                                 f"scaled to a level")
            out[name] = value
        return out

    def intensity_factor(self, record, level) -> float:
        """The factor that scales ``record`` (its name; None for the study's own) to ``level`` (g, or m/s)."""
        return float(level) * self.intensity.to_si / self.record_intensity[record]

    def excitation_at(self, record, factor):
        """The excitation of ``record`` (None: the study's own) read at scale ``factor``: as ``dccss run`` reads it
        with that scale (processed once per record and factor)."""
        cache = self.__dict__.setdefault("_scaled", {})
        key = (record, float(factor))
        if key not in cache:
            spec = {**self.excitation_spec, "scale": float(factor)}
            if record is None:
                found = _swept_excitation(excitation_from(spec, self.base, geometry_from(self.prototype)), self.axes,
                                          spec)
            else:
                found = _record_excitation(record, self.record_entries[record], spec, self.axes, self.base,
                                           geometry_from(self.prototype))
            if len(cache) > 64:  # a chunk's records at its levels; a long suite's others dropped
                cache.clear()
            cache[key] = found
        return cache[key]

    @cached_property
    def grid(self) -> Grid:
        return Grid(self)

    @property
    def suite_factor(self) -> float | None:
        """The factor of a suite scaled over a period range (``dccss.spectra.suite_factors``), else None."""
        if not self.records:
            return None
        return next(iter(self.records.values())).attrs().get("record_scaling_suite_factor")

    @classmethod
    def from_config(cls, config: dict, base: Path = Path(".")) -> Study:
        """Validate a study mapping (keys, types, every sweep point's geometry); errors name the key.

        Every mistake is reported at once (one StudyError listing them, in the order of the file):
        each key is checked on its own, a key that depends on others (the excitation on the device and
        the sweep, dt on the excitation) once they have passed, the sweep points' devices once all
        keys have, and the schema adds its errors about the keys whose checks passed."""
        base = Path(base)  # the folder file names are relative to (a str is taken too)
        if not isinstance(config, dict):
            check_keys(config, "study file", REQUIRED, KEYS - set(REQUIRED))  # raises: not a mapping
        problems = Problems(config, StudyError)
        problems.check("", check_keys, config, "study file", REQUIRED, KEYS - set(REQUIRED))
        meta = problems.check("study", _meta, config["study"]) if "study" in config else None
        known = problems.check("prototypes", _devices, config.get("prototypes", {}))
        proto = geometry = None
        if known is not None and "prototype" in config:
            proto = problems.check("prototype", _device, config["prototype"], known)
            geometry = problems.check("prototype", geometry_from, proto) if proto is not None else None
        given = {**DEFAULTS, **config}  # the file's values and the schema's defaults of the others
        symmetric = given["symmetric"]
        if not isinstance(symmetric, bool):
            problems.add("symmetric", f"symmetric: expected true or false, got {symmetric!r}")
        models = problems.check("models", _models, config["models"]) if "models" in config else None
        axes = (problems.check("sweep", _axes, config["sweep"], known, symmetric is True)
                if known is not None and "sweep" in config else None)
        excitation, records = None, {}
        if geometry is not None and axes is not None and "excitation" in config:
            found = problems.check("excitation", _excitations, config, axes, base, geometry)
            if found is not None:
                excitation, records, axes = found
        if excitation is not None and excitation.components == 2 and given["normals"] != "signed":
            problems.add("normals", "normals: bidirectional ground motion runs the spatial models, which use signed "
                                    f"normals only; got {given['normals']!r}")
        if axes is not None:
            dt = problems.check("dt", _steps, config, axes, excitation)
        else:
            dt = problems.check("dt", number, config["dt"], "dt", positive=True) if "dt" in config else None
        slider = problems.check("slider", slider_from, given["slider"])
        structure = (problems.check("structure", _structure, config.get("structure"), axes, slider)
                     if axes is not None and slider is not None else None)
        intensity = None
        if axes is not None and geometry is not None:
            swept_device = any(k in axes for k in ("prototype", *PARAMETERS))
            intensity = problems.check("intensity", intensity_from, config.get("intensity"), axes,
                                       None if swept_device else float(geometry.L))
            if intensity is not None:
                problems.check("sweep", _levels_alone, config, axes)
            if intensity is not None and excitation is not None:
                problems.check("intensity", _definition_of_pairs, config.get("intensity"), excitation)
        if "fragility" in config and (intensity is None and not problems.failed("intensity")):
            problems.add("fragility", "fragility: is fitted on the stripes of intensity levels: sweep them "
                                      "(sweep.intensity) or drop fragility")
        limits = None
        if intensity is not None and excitation is not None and not problems.failed("structure"):
            limits = problems.check("fragility", limits_from, config.get("fragility"),
                                    _summaries(structure, excitation, records, axes))
        bounds = problems.check("structure", _bounds, config.get("structure"), axes) if axes is not None else None
        if (excitation is not None and structure is None and not problems.failed("structure")
                and any(has_vertical(e) for e in ({**records, "": excitation}).values())):
            problems.add("excitation", "sweep.record: the records' vertical components act on an isolated structure's "
                                       "normal force (structure); the imposed ground displacement (no structure) "
                                       "would ignore them: give structure, or drop their vertical"
                         if records else VERTICAL_WITHOUT_STRUCTURE)
        options = problems.check("newton", newton_from, config.get("newton"))
        policy = problems.check("on_failure", choice, given["on_failure"], "on_failure", FAILURE_POLICIES)
        theta2_0 = problems.check("theta2_0", number, given["theta2_0"], "theta2_0")
        normals = problems.check("normals", choice, given["normals"], "normals", NORMALS)
        chunk_size = problems.check("chunk_size", _chunk_size, given["chunk_size"], axes or {})
        record_jobs = problems.check("record_jobs", _record_jobs, config.get("record_jobs"), config, axes or {})
        capacity = problems.check("capacity", choice, given["capacity"], "capacity",
                                  CAPACITY_POLICIES)
        # the points below are on the axes a record axis completes: checked once the excitation has passed
        marks = problems.check("marks", _marks, config.get("marks", {}), axes) if excitation is not None else None
        histories, animate = config.get("histories", []), None
        if histories != "all" and excitation is not None and not problems.failed("dt"):
            histories = problems.check("histories", _histories, histories, axes, dt)
            if histories is not None:
                animate = problems.check("animate", _animations, config.get("animate", []), histories, axes)
        problems.raise_if_any(schema_errors("study", config))
        study = cls(name=meta[0], description=meta[1], prototype=dict(proto),
                    prototypes={k: dict(v) for k, v in known.items()}, symmetric=symmetric, excitation=excitation,
                    excitation_spec=dict(config["excitation"]), theta2_0=theta2_0, dt=dt, models=list(models),
                    normals=normals, axes=axes, chunk_size=chunk_size, record_jobs=record_jobs, capacity=capacity,
                    options=NewtonOptions(tol=options.tol, max_iter=options.max_iter, on_failure=policy),
                    base=base, structure=structure, bounds=bounds, records=records,
                    record_entries=record_entries(config["sweep"]["record"], base) if records else {},
                    intensity=intensity, limits=limits)
        study.marks = marks
        _check_grid(study.grid)
        _check_frictions(study.grid)
        if histories == "all":
            histories = _histories([study.grid.point(i) for i in range(study.grid.n_cases)], axes, dt)
            animate = _animations(config.get("animate", []), histories, axes)
        study.histories, study.animate = histories, animate
        return study


def _summaries(structure, excitation, records, axes) -> dict:
    """{summary: whether the pad's run decides it} of a study's cases: the pad models', and its structure's
    (a vertical's, each surface's) where it has them."""
    out = dict.fromkeys(specs(), True)
    if structure is not None and structure.slider == "articulated" and "slider" not in axes:
        # no pad: its summaries are NaN but for the halves' ring (capacity) and the run's failure
        out = {k: v for k, v in out.items() if k in ("capacity_exceeded", "capacity_time", "failed", "failure_time")}
    if structure is not None:
        out.update(dict.fromkeys(STRUCTURE_SUMMARIES, False))
        if any(has_vertical(e) for e in ({**records, "": excitation}).values()):
            out.update(dict.fromkeys(VERTICAL_SUMMARIES, False))
        if "slider" in axes or structure.slider != "rigid":
            out.update(dict.fromkeys(SURFACE_SUMMARIES, False))
    return out


def _definition_of_pairs(value, excitation):
    """``intensity.definition`` combines a pair's two components: refused for records of one component."""
    if isinstance(value, dict) and "definition" in value and excitation.components == 1:
        raise StudyError(f"intensity.definition: {value['definition']!r} combines the two horizontal components of "
                         f"record pairs; these records have one component (their own spectrum is the intensity): "
                         f"drop the key")


def _levels_alone(config, axes):
    """An intensity axis scales recorded motions, by the factors its levels give: no other scale multiplies them
    (a scale axis, the excitation's scale, a record's own or PEER's factor)."""
    spec, why = config["excitation"], "the intensity levels set each record's factor"
    if spec.get("kind") != "record":
        raise StudyError(f"sweep.intensity: scales recorded ground motions (excitation kind: record) to levels of an "
                         f"intensity measure; a {spec.get('kind')} is scaled by sweep.scale")
    if "scale" in axes:
        raise StudyError(f"sweep.scale: {why}; a scale axis would multiply them: give one of the two")
    if "scale" in spec:
        raise StudyError(f"excitation.scale: {why}; drop the excitation's scale (the records run as read, times the "
                         f"level's factor)")
    for i, entry in enumerate(config["sweep"].get("record", [])):
        if isinstance(entry, dict) and "scale" in entry:
            raise StudyError(f"sweep.record[{i}].scale: {why}; drop the record's own scale")


def _device(proto, known):
    """The base device's 13 parameters: a name among ``known`` or the parameters themselves."""
    if isinstance(proto, str):
        if proto not in known:
            raise StudyError(f"prototype: unknown prototype {proto!r}; known: {sorted(known)}")
        return known[proto]
    return proto


def _models(models):
    """The study's models, each one of the registry's."""
    if not isinstance(models, list) or not models:
        raise StudyError(f"models: expected a non-empty list of {list(registry.names())}, got {models!r}")
    problems = Problems(dict.fromkeys(range(len(models))), StudyError)
    for i, m in enumerate(models):
        problems.check(i, choice, m, f"models[{i}]", registry.names())
    problems.raise_if_any()
    return models


def _excitations(config, axes, base, geometry):
    """(the excitation a sweep evaluates, {record name: its excitation} of a record axis, the axes with
    the record axis first)."""
    spec = config["excitation"]
    if not isinstance(spec, dict):
        raise StudyError(f"excitation: expected a mapping, got {type(spec).__name__} {spec!r}")
    if "scale" in axes and isinstance(spec.get("scale"), dict):
        raise StudyError("sweep.scale: the records are scaled to a target spectrum or spectral acceleration "
                         "(excitation.scale); a scale axis would multiply that again: give the target you want, "
                         "or one study per target")
    if "record" not in config["sweep"]:
        return _swept_excitation(excitation_from(spec, base, geometry), axes, spec), {}, axes
    if "file" in spec:
        raise StudyError("excitation.file: the records are the sweep's (sweep.record); give the excitation's "
                         "kind and processing (scale, window, baseline, units) without a file")
    entries = record_entries(config["sweep"]["record"], base)
    axes = {"record": np.array(list(entries), dtype=str), **axes}  # a record's cases come together
    scale = spec.get("scale")
    ranged = isinstance(scale, dict) and scale.get("to") == "spectrum"
    if isinstance(scale, dict):  # the suite's scaling, checked once: its mistakes are no record's
        try:
            (range_scaling if ranged else spectral_scaling)(scale, _pairs(entries), "excitation.scale",
                                                            *([base] if ranged else []))
        except CaseError as err:
            raise StudyError(*err.messages) from None
    first = ranged and "suite_factor" not in scale
    with warnings.catch_warnings():
        if first:  # each record read as a suite of one: what it says of its scale is said again of the suite's
            warnings.simplefilter("ignore")
        records = {name: _record_excitation(name, entry, spec, axes, base, geometry) for name, entry in entries.items()}
    if len({e.components for e in records.values()}) > 1:
        raise StudyError("sweep.record: mixes one- and two-component records; a suite is one or the other")
    if first:
        # each record was scaled as a suite of one: now all of them with the suite's factor
        spectra = [underlying(e).spectrum for e in records.values()]
        suite = suite_factors([s["unscaled"] for s in spectra], spectra[0]["target"], scale.get("fraction", 1.0),
                              scale.get("individual", True))[2]
        spec = {**spec, "scale": {**scale, "suite_factor": suite}}
        records = {name: _record_excitation(name, entry, spec, axes, base, geometry) for name, entry in entries.items()}
    return next(iter(records.values())), records, axes


def _pairs(entries) -> bool:
    """Whether every entry of a record axis is a pair [x, y] (a file or a mapping's)."""
    return all(isinstance(e["file"] if isinstance(e, dict) else e, list) for e in entries.values())


def _record_excitation(name, entry, spec, axes, base, geometry):
    """The excitation of a suite's record ``name`` (its file(s) ``entry`` with the study's ``excitation``
    keys, or a mapping's own); an error names the key the file has (``sweep.record`` for the file,
    ``excitation.<key>`` for the others) and the record."""
    try:
        excitation = excitation_from(entry_excitation(spec, name, entry), base, geometry)
    except CaseError as err:
        raise StudyError(*(re.sub(r"^excitation\.file\b", "sweep.record", m) + f" (record {name!r})"
                           for m in err.messages)) from None
    return _swept_excitation(excitation, axes, spec)


def _meta(meta):
    check_keys(meta, "study", ("name",), ("description",))
    name = meta["name"]
    if not isinstance(name, str) or not name.replace("_", "").replace("-", "").isalnum():
        raise StudyError(f"study.name: expected a name of letters, digits, '-' or '_', got {name!r}")
    return name, str(meta.get("description", ""))


def _devices(own) -> dict:
    """Table 1 and the study's own devices, each validated."""
    if not isinstance(own, dict):
        raise StudyError(f"prototypes: expected a mapping of names to devices, got {own!r}")
    problems = Problems(own, StudyError)
    for label, params in own.items():
        problems.check(label, geometry_from, params, f"prototypes.{label}")
    problems.raise_if_any()
    return {**TABLE1, **own}


def _axes(sweep, known, symmetric) -> dict:
    if not isinstance(sweep, dict) or not sweep:
        raise StudyError("sweep: expected a mapping of at least one axis name to its values")
    problems, axes = Problems(sweep, StudyError), {}
    for key, spec in sweep.items():
        values = problems.check(key, _axis, key, spec, known, symmetric)
        if values is not None:
            axes[key] = values
    problems.raise_if_any()
    return axes


def _axis(key, spec, known, symmetric):
    """The values of sweep axis ``key`` (a record axis: None, its entries are read with the excitation),
    each once."""
    values = _axis_values(key, spec, known, symmetric)
    listed = [] if values is None else values.tolist()
    twice = [v for i, v in enumerate(listed) if v in listed[:i]]
    if twice:
        raise StudyError(f"sweep.{key}: {twice[0]!r} is given twice; give each value once")
    return values


def _axis_values(key, spec, known, symmetric):
    if key not in AXES:
        raise StudyError(f"sweep: unknown axis {key!r}; allowed: {list(AXES)}")
    if symmetric and key in PLATE3_FOLLOWS:
        raise StudyError(f"sweep.{key}: with symmetric: true, {key} follows {PLATE3_FOLLOWS[key]}; "
                         f"sweep {PLATE3_FOLLOWS[key]} instead")
    if key == "record":
        return None  # read with the excitation (``record_entries``)
    if key in ("component", "property", "slider"):  # labels of a fixed set
        allowed = {"component": COMPONENTS, "property": BOUNDS, "slider": tuple(SLIDERS)}[key]
        if not isinstance(spec, list) or not spec:
            raise StudyError(f"sweep.{key}: expected a non-empty list of {list(allowed)}, got {spec!r}")
        for i, label in enumerate(spec):
            choice(label, f"sweep.{key}[{i}]", allowed)
        return np.array(spec, dtype=str)
    if key == "theta2_0":
        values = axis_values(spec, "sweep.theta2_0")
        for i, v in enumerate(values):
            if not abs(v) < 90.0:
                raise StudyError(f"sweep.theta2_0[{i}]: a compatible start needs |theta2_0| < 90 degrees, got {v:g}")
        return values
    if key != "prototype":
        return axis_values(spec, f"sweep.{key}")
    if not isinstance(spec, list) or not spec:
        raise StudyError(f"sweep.prototype: expected a non-empty list of device names, got {spec!r}")
    for i, label in enumerate(spec):
        if label not in known:
            raise StudyError(f"sweep.prototype[{i}]: unknown prototype {label!r}; known: {sorted(known)}")
    return np.array(spec, dtype=str)


def _swept_excitation(excitation, axes, spec):
    """The excitation a sweep evaluates: a swept azimuth orients a one-component excitation, a swept
    component selects among the two of a two-component one; each axis checked against the input."""
    kind = spec.get("kind")
    for key in ("amplitude", "omega"):
        if key in axes and key not in excitation.parameters:
            raise StudyError(f"sweep.{key}: only a sine excitation has an {key}; use 'scale' for {kind!r}")
    if "rotation" in axes and "rotation" not in excitation.parameters:
        raise StudyError("sweep.rotation: turns a record pair (file: [x, y]); a one-component excitation is "
                         "oriented by sweep.azimuth")
    if "rotation" in axes and "rotation" in spec:
        raise StudyError("sweep.rotation: the excitation gives a rotation itself (excitation.rotation), which the "
                         "sweep would override: give one of the two")
    if "azimuth" in axes and "azimuth" not in excitation.parameters:
        if excitation.components != 1:
            raise StudyError("sweep.azimuth: orients a one-component excitation, but this one has two components "
                             "(a record pair or a time, x, y table); sweep 'component' instead")
        excitation = Oriented(excitation, 0.0)
    if "component" in axes:
        if excitation.components != 2 or "component" in spec:
            raise StudyError("sweep.component: selects the components of a two-component excitation (a record pair "
                             "or a time, x, y table) that gives no 'component' itself")
        excitation = Component(excitation, "both")
    return excitation


def _steps(config, axes, excitation) -> float | None:
    """The study's dt (None if only the sweep gives it); every step size checked (against the
    excitation's duration when the excitation is not None)."""
    if "dt" not in config and "dt" not in axes:
        raise StudyError("dt: missing: give the time step (s), or sweep it (sweep.dt)")

    def step(value, key):
        return number(value, key, positive=True) if excitation is None else check_step(value, excitation, key)

    for i, value in enumerate(axes.get("dt", [])):
        step(float(value), f"sweep.dt[{i}]")
    return step(config["dt"], "dt") if "dt" in config else None


def _structure(value, axes, slider=("rigid", 0.0)) -> Structure | None:
    """The study's base structure: its ``structure`` key, or one made by sweeping friction (with damping
    0 unless given), on the study's ``slider`` (kind, hinge); every swept value checked; each slider a
    ``slider`` axis takes too."""
    swept = [k for k in ("friction", "damping") if k in axes]
    kinds = list(axes.get("slider", [])) or [slider[0]]
    if value is None and not swept:
        if "property" in axes:
            raise StudyError("sweep.property: the friction's bounds are a structure's: give structure (its friction "
                             "and property: {lower: ..., upper: ...})")
        if "articulated" in kinds:
            raise StudyError(f"{'sweep.slider' if 'slider' in axes else 'slider'}: an articulated slider in a study is "
                             f"driven by its structure: give structure (its friction on each surface, friction_on: "
                             f"surfaces)")
        return None
    if value is None:
        value = {}
    if not isinstance(value, dict):
        raise StudyError(f"structure: expected a mapping {{friction, damping}}, got {value!r}")
    value = {k: v for k, v in value.items() if not (k == "property" and isinstance(v, dict))}  # the bounds
    if "friction" not in value:
        if "friction" not in axes:
            raise StudyError("structure.friction: missing: give the device's friction coefficient, or sweep it "
                             "(sweep.friction)")
        value = {**value, "friction": float(axes["friction"][0])}
        try:
            base = structure_from(value, "structure", *slider)
        except CaseError as err:  # the value taken from the sweep is named there
            raise StudyError(str(err).replace("structure.friction", "sweep.friction[0]", 1)) from None
    else:
        base = structure_from(value, "structure", *slider)
    for i, kind in enumerate(kinds):  # each slider of the axis on this structure
        try:
            replace(base, slider=kind)
        except StructureError as err:
            where = f"sweep.slider[{i}] ({kind}) on " if "slider" in axes else ""
            raise StudyError(*(where + m for m in err.messages)) from None
    for key in swept:
        for i, v in enumerate(axes[key]):
            try:
                replace(base, **{key: float(v)})
            except StructureError as err:
                raise StudyError(str(err).replace(f"structure.{key}", f"sweep.{key}[{i}]")) from None
    return base


def _bounds(value, axes) -> dict:
    """The friction's property modification factors by bound: nominal 1, lower and upper from
    ``structure.property: {lower: λ_min, upper: λ_max}``; each one a ``property`` axis takes must be given."""
    given = value.get("property") if isinstance(value, dict) else None
    if given is not None and not isinstance(given, dict):
        if "property" in axes:
            raise StudyError(f"structure.property: a property axis takes its bounds from {{lower: λ_min, upper: "
                             f"λ_max}}, got {given!r}")
        return {"nominal": 1.0}
    given = given or {}
    check_keys(given, "structure.property", (), ("lower", "upper"))
    bounds = {"nominal": 1.0, **{k: number(v, f"structure.property.{k}", positive=True) for k, v in given.items()}}
    for label, side in (("lower", "above"), ("upper", "below")):
        if label in bounds and (bounds[label] > 1.0 if label == "lower" else bounds[label] < 1.0):
            raise StudyError(f"structure.property.{label}: {bounds[label]!r} is {side} the nominal 1: the {label} "
                             f"bound's factor is λ_{'min' if label == 'lower' else 'max'} "
                             f"{'<=' if label == 'lower' else '>='} 1 (EN 15129, ASCE 7-22 17.2.8.4)")
    for i, label in enumerate(axes.get("property", [])):
        if label not in bounds:
            raise StudyError(f"sweep.property[{i}]: {str(label)!r} needs its factor, structure.property.{label} (the "
                             f"code's and the manufacturer's λ)")
    return bounds


def _check_frictions(grid):
    """Every case's device friction is below 1 (a surfaces' friction grows by (R1 + R3) / L) and an articulated
    slider's hinge lies inside each case's pad; the first case where not is named."""
    if grid.study.structure is None or grid.study.structure.friction_on == "device":
        return
    cases = np.arange(grid.n_cases)
    for i, (structure, device) in enumerate(zip(grid.structures(cases), grid.pendulums(cases))):
        try:
            structure.device_friction(device)
            if structure.slider == "articulated":
                structure.pendulums(device)
        except StructureError as err:
            where = ", ".join(f"{k}={v}" for k, v in grid.point(i).items())
            raise StudyError(f"sweep point {where}: {str(err).replace('structure.hinge', 'slider.hinge')}") from None


def _record_jobs(value, config, axes) -> int | None:
    """The number of jobs per model a suite's records are spread over (None: a job per record)."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise StudyError(f"record_jobs: expected an integer >= 1, got {value!r}")
    if "record" not in (config.get("sweep") or {}) and "record" not in axes:
        raise StudyError("record_jobs: spreads a suite's records over jobs; this study has no record axis")
    if config.get("chunk_size", "auto") != "auto":
        raise StudyError("record_jobs: a job then runs its records' cases together: leave chunk_size auto")
    return value


def _chunk_size(chunk, axes) -> int:
    if chunk == "auto":  # with a record axis, a chunk per record (its jobs then depend on it alone)
        others = int(np.prod([len(v) for k, v in axes.items() if k != "record"]))
        return others if "record" in axes else max(-(-others // AUTO_CHUNKS), min(others, AUTO_LEAST))
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise StudyError(f"chunk_size: expected an integer >= 1 or 'auto', got {chunk!r}")
    return chunk


def _point(point, key, axes) -> dict:
    """A point of the sweep ({axis: value}), each value checked."""
    check_keys(point, key, (), tuple(axes))
    out = {}
    for name, v in point.items():
        if name in CATEGORICAL:
            if v not in axes[name]:
                allowed = np.asarray(axes[name]).tolist()
                raise StudyError(f"{key}.{name}: {v!r} is not on the sweep axis {allowed}")
            out[name] = v
        else:
            out[name] = number(v, f"{key}.{name}")
    return out


def layout(sizes: dict, categorical) -> tuple[str, list]:
    """(kind, drawn axes) of a study's summary plots, from its axes' sizes (in sweep order) and which of
    them are categorical: axes of one value are never drawn; two numeric axes make maps over the
    first two, one numeric axis curves against it (a categorical axis then gives one curve per
    category), categorical axes alone marks per category of the first (a second's categories side by side
    in each)."""
    names = list(sizes)
    spread = [n for n in names if sizes[n] > 1]
    numeric = [n for n in spread if n not in categorical]
    groups = [n for n in spread if n in categorical]
    if len(numeric) >= 2:
        return "map", numeric[:2]
    if numeric:
        return "lines", numeric + groups[:1]
    if groups:
        return "categories", groups[:2]
    return ("categories" if names[0] in categorical else "lines"), names[:1]


def _marks(marks, axes) -> dict:
    if not isinstance(marks, dict):
        raise StudyError(f"marks: expected a mapping of labels to sweep points, got {marks!r}")
    kind, drawn = layout({k: len(v) for k, v in axes.items()}, CATEGORICAL)
    placed = drawn if kind == "map" else drawn[:1]  # where a mark goes: a point on a map, a line at an x value
    out = {}
    for label, p in marks.items():
        point = _point(p, f"marks.{label}", axes)
        missing = [name for name in placed if name not in point]
        if missing:
            raise StudyError(f"marks.{label}: gives {sorted(point)} but the plots draw the summaries over {placed}; "
                             f"give a value for {missing} too (a mark is drawn where all of them are given)")
        out[str(label)] = point
    return out


def _histories(histories, axes, dt) -> list:
    if not isinstance(histories, list):
        raise StudyError(f"histories: expected a list of sweep points or 'all', got {histories!r}")
    points = [_point(p, f"histories[{i}]", axes) for i, p in enumerate(histories)]
    for i, point in enumerate(points):
        if dt is None and "dt" not in point:
            raise StudyError(f"histories[{i}]: no dt: give it in the point or as the study's dt")
        if "record" in axes and "record" not in point:  # a suite has no base record to default to
            raise StudyError(f"histories[{i}]: no record: a suite's history names one of its records "
                             f"{np.asarray(axes['record']).tolist()}")
    return points


def _animations(points, histories, axes) -> list:
    """The indices of the histories to animate: ``all`` or a list of history points."""
    if points == "all":
        return list(range(len(histories)))
    if not isinstance(points, list):
        raise StudyError(f"animate: expected a list of history points or 'all', got {points!r}")
    out = []
    for i, point in enumerate(points):
        point = _point(point, f"animate[{i}]", axes)
        if point not in histories:
            raise StudyError(f"animate[{i}]: {point} is not one of the histories {histories}; add it to histories")
        out.append(histories.index(point))
    return out


def _check_grid(grid):
    """Every sweep point's geometry is valid; the first bad one is named."""
    try:
        grid.geometry(np.arange(grid.n_cases))
    except ValueError:
        for i in range(grid.n_cases):
            try:
                grid.geometry(np.array([i]))
            except ValueError as err:
                where = ", ".join(f"{k}={v}" for k, v in grid.point(i).items())
                raise StudyError(f"sweep point {where}: {str(err).split(' (at batch index')[0]}") from None
