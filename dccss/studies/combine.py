"""The chunks of every model combined into one dataset with a dimension per sweep axis."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..excitation import has_vertical, underlying
from ..mechanics.geometry import PARAMETERS, Geometry
from ..mechanics.models import REGISTRY
from ..mechanics.structure import SUMMARIES as STRUCTURE_SUMMARIES
from ..mechanics.structure import SURFACE_SUMMARIES, VERTICAL_SUMMARIES, G
from ..mechanics.summaries import model_specific, specs
from ..results import global_attrs, variable
from .fragility import fragility
from .spec import entry_files


def axis_variable(dims, name, values):
    """A sweep axis as a variable: CF units, or strings for the prototype axis."""
    from .spec import axis_units

    units = axis_units(name)
    if units is None:
        return xr.Variable(dims, np.asarray(values, dtype=object), {"long_name": f"sweep axis {name}"})
    return variable(dims, values, units, f"sweep axis {name}")


def study_attrs(study, model=None, record=None) -> dict:
    """Global attributes of a study's datasets (not the description: only the plots show it); with a
    record axis, the excitation's are those of ``record`` (a chunk's) or, combined, only its kind."""
    if study.records:
        ground = {"excitation": study.excitation.kind, "excitation_components": study.excitation.components,
                  "records": " ".join(study.records)}
        if record is not None:
            ground = {**study.records[record].attrs(), "record": record}
    else:
        ground = study.excitation.attrs()
    if study.intensity is not None:
        ground.update(study.intensity.attrs())
    out = global_attrs(f"dccss study {study.name}", f"study {study.name}", study=study.name, normals=study.normals,
                       theta2_0_deg=study.theta2_0, capacity_policy=study.capacity,
                       on_failure=study.options.on_failure, symmetric=int(study.symmetric),
                       sweep_axes=" ".join(study.axes),
                       **({"dt_s": study.dt} if study.dt is not None and "dt" not in study.axes else {}),
                       **{f"prototype_{k}": float(v) for k, v in study.prototype.items()}, **ground,
                       **structure_attrs(study))
    if model:
        out["model"] = model
    return out


def structure_attrs(study) -> dict:
    """A study's structure, as a history's attributes name it: ``structure_friction_on``, the file's
    ``structure_friction_given`` and ``structure_damping`` where they are not sweep axes, the
    device's ``structure_friction`` where it is that value (``friction_on`` "device"), and the
    pendulum's length and period where the study sweeps no device parameter."""
    if study.structure is None:
        return {}
    s, out = study.structure, {"structure_friction_on": study.structure.friction_on}
    if "friction" not in study.axes:
        given = s.attrs(Geometry.from_degrees(**study.prototype))["structure_friction_given"]
        out["structure_friction_given"] = given
        if s.friction_on == "device" and s.coulomb and "property" not in study.axes:
            out["structure_friction"] = s.friction * s.factor
    if "damping" not in study.axes:
        out["structure_damping"] = s.damping
    if not any(axis in study.axes for axis in ("prototype", *PARAMETERS)):  # one device: its pendulum
        device = s.attrs(Geometry.from_degrees(**study.prototype))
        out.update({k: device[k] for k in ("structure_pendulum_length_m", "structure_period_s")})
    return out


def combine(study, chunks: dict) -> xr.Dataset:
    """One dataset of all summaries: dimensions ``model`` and one per sweep axis. ``chunks`` maps
    each model to its chunk datasets (any order); a summary another model lacks is NaN. With a
    ``record`` axis, each chunk holds one record's cases (attribute ``record``, cases numbered within
    it); the dataset then also holds each record's peaks and the suite statistics (``statistics``)."""
    grid, dims = study.grid, tuple(study.axes)
    per_model = []
    for model in study.models:
        ds = _cases(study, model, chunks[model])
        ds = ds.drop_vars([n for n in study.axes if n in ds])
        variables = {}
        summaries = specs()
        for name in {**summaries, **STRUCTURE_SUMMARIES, **VERTICAL_SUMMARIES, **SURFACE_SUMMARIES}:
            if name in ds:
                variables[name] = xr.Variable(dims, ds[name].values.reshape(grid.shape), ds[name].attrs)
            elif name in model_specific():
                owners = ", ".join(e.title for e in REGISTRY.values() if name in e.summaries)
                units, long_name = summaries[name]
                variables[name] = xr.Variable(dims, np.full(grid.shape, np.nan),
                                              {"units": units, "long_name": f"{long_name} ({owners} only)"})
        per_model.append(xr.Dataset(variables))
    coords = {name: axis_variable((name,), name, vals) for name, vals in study.axes.items()}
    coords["model"] = xr.Variable(("model",), np.array(study.models, dtype=object), {"long_name": "kinematic model"})
    if study.intensity is not None:  # the levels in the file's units: g, or m/s
        unit, what = study.intensity.unit(), study.intensity.label(study.excitation.components == 2)
        coords["intensity"] = xr.Variable(("intensity",), np.asarray(study.axes["intensity"], dtype=float), {
            "units": "1" if unit == "g" else "m s-1",
            "long_name": f"sweep axis intensity: the level of {what}" + (", in g (9.80665 m s-2)" if unit == "g"
                                                                          else ", in m/s"),
            "label": f"{what} ({unit})"})
    out = xr.concat(per_model, dim="model").assign_coords(coords)
    if study.intensity is not None:
        out = out.assign(intensity_levels(study))
    if study.records:
        out = out.assign(record_peaks(study)).merge(statistics(out))
    if "property" in study.axes:
        out = out.assign(envelope(out))
    if study.limits:
        out = out.assign(fragility(out, study.limits, out["intensity"].attrs["units"]))
    out.attrs = study_attrs(study)
    return out


def intensity_levels(study) -> dict:
    """Each record's intensity as read (``record_intensity``, SI), and at each level the factor it runs at
    (``intensity_factor``) and the intensity it then has, measured on the record read at that factor
    (``intensity_achieved``, in the levels' units)."""
    from ..excitation import underlying
    from ..spectra import intensity_measure

    i, levels = study.intensity, np.asarray(study.axes["intensity"], dtype=float)
    names = list(study.records) or [None]
    factors = np.array([[study.intensity_factor(name, level) for level in levels] for name in names])
    achieved = np.array([[intensity_measure(underlying(study.excitation_at(name, f)), i.measure, i.period, i.damping,
                                            i.definition) / i.to_si for f in row] for name, row in zip(names, factors)])
    dims = ("record", "intensity") if study.records else ("intensity",)
    shape = (lambda a: a) if study.records else (lambda a: a[0])
    what = i.label(study.excitation.components == 2)
    si = "m s-2" if i.measure != "pgv" else "m s-1"
    out = {"intensity_factor": xr.Variable(dims, shape(factors), {
               "units": "1", "long_name": f"the factor the record runs at to reach the level of {what}: the level "
                                         f"in SI units ({si}) over record_intensity"}),
           "intensity_achieved": xr.Variable(dims, shape(achieved), {
               "units": "1" if i.measure != "pgv" else "m s-1",
               "long_name": f"{what} of the record as it runs (read at its factor), in the levels' units"})}
    if study.records:
        out["record_intensity"] = xr.Variable(("record",), np.array([study.record_intensity[n] for n in names]), {
            "units": si, "long_name": f"{what} of the record as read (at scale 1)"})
    return out


#: the demands whose envelope over the friction's bounds the design codes take, and the clause
ENVELOPE = {"stroke_max_abs": "the displacement demand (ASCE 7-22 17.2.8.4 and EN 15129: from the lower bound, "
                              "or whichever bound gives more)",
            "shear_ratio_max_abs": "the force demand (ASCE 7-22 17.2.8.4 and EN 15129: from the upper bound, or "
                                   "whichever bound gives more)"}


def envelope(ds) -> dict:
    """``<name>_envelope`` (and ``<name>_suite_envelope`` for a suite's statistics): the largest over the
    ``property`` axis (the friction's lower, nominal and upper bounds) of the structure's displacement and
    force demands (:data:`ENVELOPE`)."""
    out = {}
    for name, what in ENVELOPE.items():
        for full in (name, f"{name}_suite"):
            if full in ds:
                out[f"{full}_envelope"] = ds[full].max("property").assign_attrs(
                    units=ds[full].attrs.get("units", "1"),
                    long_name=f"{ds[full].attrs.get('long_name', full)}, largest over the friction's bounds: {what}")
    return out


def _cases(study, model, chunks) -> xr.Dataset:
    """A model's chunks as one dataset over the flattened sweep index (``case``), every case once."""
    grid = study.grid
    if study.records:  # chunks number their cases within their record
        pieces = []
        for chunk in chunks:  # a chunk of several records (``record_jobs``): a piece per record
            if "case_record" in chunk:
                for name in dict.fromkeys(chunk["case_record"].values.tolist()):
                    piece = chunk.isel(case=np.nonzero(chunk["case_record"].values == name)[0])
                    pieces.append(piece.drop_vars("case_record").assign_attrs(record=name))
            else:
                pieces.append(chunk)
        chunks = pieces
        by_record = {name: [c for c in chunks if c.attrs.get("record") == name] for name in grid.records}
        parts = []
        for r, name in enumerate(grid.records):
            if not by_record[name]:
                raise ValueError(f"{model}: no chunk of the record {name!r}")
            part = xr.concat(by_record[name], dim="case")
            parts.append(part.assign_coords(case=part["case"].values + r * grid.per_record))
        ds = xr.concat(parts, dim="case").sortby("case")
    else:
        ds = xr.concat(chunks, dim="case").sortby("case")
    if ds.sizes["case"] != grid.n_cases or not np.array_equal(ds["case"].values, np.arange(grid.n_cases)):
        raise ValueError(f"{model}: {ds.sizes['case']} cases in the chunks, expected each of {grid.n_cases} once")
    return ds


#: each record's peaks after processing (variable, attribute of ``Record.attrs``, units, long name)
PEAKS = (("record_pga", "pga_m_per_s2", "m s-2", "peak ground acceleration of the record, as processed"),
         ("record_pgv", "pgv_m_per_s", "m s-1", "peak ground velocity of the record, as processed"),
         ("record_pgd", "pgd_m", "m", "peak ground displacement of the record, as processed"))


def record_peaks(study) -> dict:
    """PGA, PGV and PGD of each record of the axis (a pair's: the larger of its components'; a
    displacement table's PGD only, its PGA and PGV NaN) and its source files."""
    out = {}
    for name, attr, units, long_name in PEAKS:
        values = []
        for excitation in study.records.values():
            a = excitation.attrs()
            keys = [k for k in a if k.endswith(attr) and k.startswith("record_") and "vertical" not in k]
            if keys:
                values.append(max(float(a[k]) for k in keys))
            elif attr == "pgd_m":  # a table: its samples (scaled as the study scales them)
                samples = np.reshape(excitation.displacement(underlying(excitation).time), (-1, excitation.components))
                values.append(float(np.max(np.linalg.norm(samples, axis=1))))
            else:
                values.append(np.nan)
        pair = " (the larger of a pair's components)" if study.excitation.components == 2 else ""
        out[name] = xr.Variable(("record",), np.array(values), {"units": units, "long_name": long_name + pair})
    sources = [" ".join(entry_files(e)) for e in study.record_entries.values()]
    out["record_source"] = xr.Variable(("record",), np.array(sources, dtype=object),
                                       {"long_name": "the record's file (a pair's two files, in the order given)"})
    attrs = [excitation.attrs() for excitation in study.records.values()]
    scales = [float(a.get("record_scale", a.get("record_1_scale", np.nan))) for a in attrs]
    out["record_scale"] = xr.Variable(("record",), np.array(scales), {
        "units": "1", "long_name": "the factor the record's accelerations are scaled by (before a sweep's scale)"})
    if "record_scaled_to_sa_g" in attrs[0]:  # each record's own factor, from its own spectrum
        keys = ("record_scaled_to_sa_g", "record_scaling_period_s", "record_scaling_damping",
                "record_scaling_definition")
        # in m s-2: to CF's units (UDUNITS) "g" is the gram
        sa = np.array([a["record_sa_unscaled_g"] for a in attrs]) * G
        out["record_sa_unscaled"] = xr.Variable(("record",), sa, {
            "units": "m s-2", "long_name": "the record's spectral acceleration before scaling (/ 9.80665 for g)",
            **{k.removeprefix("record_"): attrs[0][k] for k in keys if k in attrs[0]}})
    if attrs[0].get("record_scaled_to") == "spectrum":  # scaled over a period range, as a suite
        out.update(_suite_spectra(study, attrs, np.array(scales)))
    if any(has_vertical(e) for e in study.records.values()):  # each record's vertical: read as written or negated
        signs = [-1 if "record_vertical_sign" in a else (1 if "record_vertical_source" in a else 0) for a in attrs]
        out["record_vertical_sign"] = xr.Variable(("record",), np.array(signs, dtype=np.int8), {
            "units": "1", "long_name": "the sign the record's vertical file is read with: 1 as written (up positive), "
                                       "-1 negated (its channel down-positive, DWN on line 2), 0 no vertical file"})
    if "record_orientation" in attrs[0]:
        out["record_orientation"] = xr.Variable(("record",), np.array([a["record_orientation"] for a in attrs],
                                                                      dtype=object),
                                                {"long_name": "how the pair's components are placed as x and y"})
    return out


def _suite_spectra(study, attrs, scales) -> dict:
    """A suite scaled over a period range: each record's own fit and its spectrum as scaled, the target
    (``spectrum_period``: the periods the scaling checks) and how it was scaled (attributes)."""
    spectra = [underlying(e).spectrum for e in study.records.values()]
    keys = ("record_scaling_periods_s", "record_scaling_damping", "record_scaling_fraction",
            "record_scaling_suite_factor", "record_scaling_definition")
    how = {k.removeprefix("record_"): attrs[0][k] for k in keys if k in attrs[0]}
    period = ("spectrum_period", spectra[0]["periods"], {"units": "s", "long_name": "the periods the scaling checks"})
    return {
        "spectrum_period": xr.Variable(*period),
        "record_scale_fit": xr.Variable(("record",), np.array([a["record_scaling_fit"] for a in attrs]), {
            "units": "1", "long_name": "the record's own fit to the target over the range (the geometric mean of "
                                       "target / Sa); record_scale is it times the suite's factor"}),
        "record_sa": xr.Variable(("record", "spectrum_period"),
                                 scales[:, None] * np.array([s["unscaled"] for s in spectra]), {
            "units": "m s-2", "long_name": "the record's spectral acceleration as scaled (its factor times its "
                                           "spectrum; / 9.80665 for g)", **how}),
        "target_sa": xr.Variable(("spectrum_period",), spectra[0]["target"], {
            "units": "m s-2", "long_name": "the target spectrum the suite is scaled to (/ 9.80665 for g)", **how}),
    }


#: the suite statistics over the ``record`` dimension (EN 1998-1 4.3.3.4.3 and ASCE 7-22 17.3.4: the
#: mean of the records' peaks; the 84th percentile of a lognormal fit, as fragility work uses)
STATISTICS = ("mean", "median", "p84_lognormal", "max", "min")


def statistics(ds) -> xr.Dataset:
    """Every summary but the event times (``capacity_time``, ``failure_time``) reduced over ``record``
    (each record's value is its own peak or end value):
    ``<name>_suite`` with a ``statistic`` coordinate (STATISTICS: the mean, the median, the 84th
    percentile of a lognormal fit exp(mean ln x + std ln x) (NaN where a value is not > 0), the
    largest and the smallest: the design value of a minimum, ``clearance_min``, is its smallest), the
    pad's over the records that did not fail, the structure's (``structure.SUMMARIES``: its response
    does not depend on the pad) over all records; an end value (``*_end``: a residual rotation, rise or
    stroke, signed for one component) by its size |x|, as a design value is one (signed, records
    pushed to either side would cancel in the mean); ``records_capacity_exceeded`` and
    ``records_failed``, the number of records whose pad reaches a ring or whose run fails, and
    ``records_counted``, the number the pad's statistics are over."""
    out = {}
    failed = ds["failed"].astype(bool)
    ok = ~failed
    for name, var in ds.data_vars.items():
        # flags, the records' own data and event times (NaN where the event did not happen) are no demand
        flag = (name in ("failed", "capacity_exceeded") or name.startswith(("record_", "intensity_"))
                or name.endswith("_time"))
        if flag or "record" not in var.dims or not np.issubdtype(var.dtype, np.floating):
            continue
        counted = xr.ones_like(ok) if name in {**STRUCTURE_SUMMARIES, **VERTICAL_SUMMARIES, **SURFACE_SUMMARIES} else ok
        size = name.endswith("_end")
        values = abs(var.where(counted)) if size else var.where(counted)
        logs = np.log(values.where(values > 0))
        lognormal = np.exp(logs.mean("record") + logs.std("record", ddof=1))
        lognormal = lognormal.where((values > 0).sum("record") == counted.sum("record"))
        stack = [values.mean("record"), values.median("record"), lognormal, values.max("record"), values.min("record")]
        out[f"{name}_suite"] = xr.concat(stack, dim="statistic").assign_attrs(
            units=var.attrs.get("units", "1"),
            long_name=f"{var.attrs.get('long_name', name)}{', its size' if size else ''}: suite statistic")
    out["records_capacity_exceeded"] = ds["capacity_exceeded"].astype(bool).sum("record").astype(np.int32).assign_attrs(
        units="1", long_name="number of records whose pad reaches a retaining ring")
    out["records_failed"] = failed.sum("record").astype(np.int32).assign_attrs(
        units="1", long_name="number of records whose run fails (left out of the pad's suite statistics)")
    out["records_counted"] = ok.sum("record").astype(np.int32).assign_attrs(
        units="1", long_name="number of records the suite statistics of the pad are over (the structure's: all)")
    if "uplift_count" in ds:
        out["records_uplift"] = (ds["uplift_count"] > 0).sum("record").astype(np.int32).assign_attrs(
            units="1", long_name="number of records under which the structure lifts off its device (N <= 0)")
    n = ds.sizes["record"]
    for what in ("capacity_exceeded", "failed"):
        out[f"records_{what}_fraction"] = (out[f"records_{what}"] / n).assign_attrs(
            units="1", long_name=f"{out[f'records_{what}'].attrs['long_name'].split(' (')[0]}, over all {n} records"
            .replace("number of", "fraction of"))
    result = xr.Dataset(out).assign_coords(statistic=xr.Variable(("statistic",), np.array(STATISTICS, dtype=object),
                                                                 {"long_name": "suite statistic over the records"}))
    return result
