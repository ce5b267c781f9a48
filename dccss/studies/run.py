"""Running a study: one chunk under one model reduced to summaries, and histories in full."""

from __future__ import annotations

import warnings

import numpy as np
import xarray as xr

from ..case import Case, case_from
from ..excitation import uncovered
from ..mechanics import runs, structure
from ..mechanics.capacity import CapacityError
from ..mechanics.geometry import PARAMETERS
from ..mechanics.newton import ConvergenceError
from ..mechanics.structure import SUMMARIES as STRUCTURE_SUMMARIES
from ..mechanics.summaries import TILT_SUMMARIES, specs
from ..results import variable
from ..simulation import UpliftError, uplift_message
from .combine import axis_variable, study_attrs
from .grid import PLATE3_FOLLOWS
from .spec import entry_excitation


def structure_summaries(responses, devices=None, hinge=0.0) -> dict:
    """The structure's summaries of each case (``structure.SUMMARIES``; {} without a structure): its
    response to the whole record, the demand on the device, whatever became of the pad (it does not
    depend on it: a case whose pad reached a ring, stopped there or failed keeps them); with ``devices``
    (a study comparing slider kinds) each surface's too (``structure.SURFACE_SUMMARIES``)."""
    out = {name: np.full(len(responses), np.nan) for name in STRUCTURE_SUMMARIES} if responses else {}
    for i, response in enumerate(responses):
        found = structure.summarize(response)
        if devices is not None:
            found.update(structure.surface_summaries(response, devices[i], hinge))
        for name, value in found.items():
            out.setdefault(name, np.full(len(responses), np.nan))[i] = value
    return out


def articulated_summaries(names, responses, dtypes) -> dict:
    """The pad's summaries of articulated sliders' cases: the paper's pad models are the rigid slider's, so
    NaN (a failure flag 0), but a ring reached by either surface's half (its first time) is the capacity's."""
    out = {}
    for name in names:
        if name == "capacity_exceeded":
            out[name] = np.array([any(np.isfinite(when) for when, _ in r.surfaces.ring) for r in responses],
                                 dtype=dtypes.get(name, np.int8))
        elif name == "capacity_time":
            out[name] = np.array([min((w for w, _ in r.surfaces.ring if np.isfinite(w)), default=np.nan)
                                  for r in responses])
        elif name == "failed":
            out[name] = np.zeros(len(responses), dtype=dtypes.get(name, np.int8))
        else:
            out[name] = np.full(len(responses), np.nan)
    return out


def _lifted_off(part, responses, study, model, points) -> dict:
    """The pad's summaries with the cases whose structure lifts off (N <= 0) under capacity 'stop' or 'error'
    marked failed at their first uplift (NaN summaries, as a failed case): such a run is no ordinary
    result. Under 'error' with on_failure 'error' the study stops, naming the sweep point."""
    lifted = [i for i, r in enumerate(responses) if r.uplift]
    if not lifted or study.capacity == "continue":
        return part
    if study.capacity == "error" and study.options.on_failure != "mark":
        where = ", ".join(f"{k}={v}" for k, v in points[lifted[0]].items())
        raise UpliftError(f"sweep point {where} ({model}): " + uplift_message(responses[lifted[0]]) +
                          " (capacity: error)")
    part = {name: np.array(values, copy=True) for name, values in part.items()}
    for i in lifted:
        for name, values in part.items():
            if name == "failed":
                values[i] = 1
            elif name == "failure_time":
                values[i] = responses[i].uplift[0][0]
            elif name != "capacity_exceeded" and name != "capacity_time" and np.issubdtype(values.dtype, np.floating):
                values[i] = np.nan
    return part


def run_chunk(study, model, k, progress=None) -> xr.Dataset:
    """Summaries of the cases of chunk k under ``model`` (dimension ``case``): one batch per step
    size; ``progress(done, total, cases, dt)`` is called after each step (for a log). A failure
    that stops the study (``on_failure: error``) names the sweep point. A chunk of several records
    (``record_jobs``) runs each record's cases as a chunk of its own would, one after the other: its
    dataset holds each case's record (``case_record``) and the case's index within it."""
    grid = study.grid
    cases = grid.chunk(k)
    records = grid.records_of(cases)
    if len(records) > 1:
        parts = []
        for name in records:
            mine = cases[grid.values(cases)["record"] == name]
            part = _run_cases(study, model, mine, progress)
            parts.append(part.assign(case_record=("case", np.full(mine.size, name, dtype=object), {
                "long_name": "the record of the case (the chunk holds several)"})))
        ds = xr.concat(parts, dim="case", combine_attrs="override")
        ds.attrs = study_attrs(study, model)
        return ds
    return _run_cases(study, model, cases, progress)


def _run_cases(study, model, cases, progress=None) -> xr.Dataset:
    """``run_chunk`` of cases of one record (or of a study without a record axis)."""
    grid = study.grid
    dts = grid.dt_of(cases)
    out = {}
    for dt in np.unique(dts):
        mine = dts == dt
        group = cases[mine]
        times = grid.times(dt, group)
        short = uncovered(grid.excitation(group), times, dt)
        if short:  # as dccss run says it of a case
            record = grid.record_of(group)
            warnings.warn(short if record is None else f"record {record!r}: {short}", stacklevel=2)
        report = None if progress is None else (lambda n, N, g=group, dt=dt: progress(n, N, len(g), dt))
        ground, responses = grid.imposed(group, times)
        # the pad's models run on the rigid sliders' cases; an articulated slider's halves have their own kinematics
        rigid = grid.sliders(group) == "rigid"
        part = {}
        if rigid.any():
            cases_rigid = group[rigid]
            try:
                part = runs.summaries(model, grid.geometry(cases_rigid), ground[:, rigid],
                                      grid.theta2_0_of(cases_rigid),
                                      azimuth=grid.azimuth_of(cases_rigid), normals=study.normals,
                                      options=study.options, times=times, capacity=study.capacity, progress=report)
            except (ConvergenceError, CapacityError) as err:
                index = getattr(err, "index", None)
                where = grid.point(cases_rigid[index[0]]) if index else "of the chunk"
                raise type(err)(f"sweep point {where} ({model}): {err}") from None
        if not rigid.all():
            names = list(part) or [*specs(), *(TILT_SUMMARIES if study.excitation.components == 2 else {})]
            dtypes = {name: np.asarray(v).dtype for name, v in part.items()}
            others = articulated_summaries(names, [r for r, keep in zip(responses, rigid) if not keep], dtypes)
            merged = {}
            for name in names:
                kinds = (np.asarray(part[name]).dtype, others[name].dtype) if part else (others[name].dtype,)
                values = np.zeros(len(group), dtype=np.result_type(*kinds))  # an iteration count beside NaN: float
                if part:
                    values[rigid] = part[name]
                values[~rigid] = others[name]
                merged[name] = values
            part = merged
            if progress is not None and not rigid.any():
                report(len(times) - 1, len(times) - 1)
        compared = grid.compares_sliders()
        own = structure_summaries(responses, grid.pendulums(group) if compared else None,
                                  study.structure.hinge if compared else 0.0)
        part = _lifted_off(part, responses, study, model, [grid.point(c) for c in group])
        for name, values in {**part, **own}.items():
            out.setdefault(name, np.zeros(len(cases), np.asarray(values).dtype))[mine] = values
    names = {**specs(), **STRUCTURE_SUMMARIES, **structure.VERTICAL_SUMMARIES, **structure.SURFACE_SUMMARIES,
             **(TILT_SUMMARIES if study.excitation.components == 2 else {})}
    data = {name: variable(("case",), v, *names[name]) for name, v in out.items()}
    for flag in ("capacity_exceeded", "failed"):
        data[flag].data = data[flag].data.astype(np.int8)
    for name, v in grid.values(cases).items():
        data[name] = axis_variable(("case",), name, v)
    record = grid.record_of(cases)
    if record is None:
        ds = xr.Dataset(data, coords={"case": variable(("case",), cases, "1", "flattened sweep index")})
    else:  # the index within the record's cases: a chunk does not depend on the other records
        ds = xr.Dataset(data, coords={"case": variable(("case",), cases % grid.per_record, "1",
                                                       "flattened sweep index within the record")})
    ds.attrs = study_attrs(study, model, record)
    return ds


def history_mapping(study, i, model) -> dict:
    """The case mapping (``dccss.case``) of the i-th history point under ``model``: all that its
    result depends on (a workflow reruns the history when, and only when, this changes)."""
    point = study.histories[i]
    device = study.prototypes[point["prototype"]] if "prototype" in point else study.prototype
    full = {k: float(v) for k, v in device.items()}
    full.update({k: v for k, v in point.items() if k in PARAMETERS})
    if study.symmetric:
        full.update({k: full[src] for k, src in PLATE3_FOLLOWS.items()})
    excitation = dict(study.excitation_spec)
    if "record" in point:
        excitation = entry_excitation(excitation, point["record"], study.record_entries[point["record"]])
    if study.suite_factor is not None:  # a suite scaled over a period range: the factor all its records set
        excitation["scale"] = {**excitation["scale"], "suite_factor": study.suite_factor}
    for key in (*study.excitation.parameters, "scale", "azimuth", "component"):
        if key in point:
            excitation[key] = point[key]
    if "intensity" in point:  # the record at its level's factor
        excitation["scale"] = study.intensity_factor(point.get("record"), point["intensity"])
    mapping = {"id": f"{study.name}/history{i}_{model}", "prototype": full, "excitation": excitation,
               "theta2_0": point.get("theta2_0", study.theta2_0), "dt": point.get("dt", study.dt), "model": model,
               "normals": study.normals, "newton": {"tol": study.options.tol, "max_iter": study.options.max_iter},
               "capacity": study.capacity, "on_failure": study.options.on_failure}
    if study.structure is not None:
        s = study.structure
        factor = study.bounds[point["property"]] if "property" in point else s.factor
        mapping["structure"] = {"friction": float(point["friction"]) if "friction" in point else s.friction,
                                "damping": float(point.get("damping", s.damping)), "friction_on": s.friction_on,
                                **({"property": factor} if factor != 1.0 else {})}
        kind = point.get("slider", s.slider)
        if kind != "rigid":  # an articulated slider's halves stay seated: its history is the same under every model
            mapping["slider"] = {"kind": kind, "hinge": s.hinge}
            mapping["model"] = "compliant"
    return mapping


def history_case(study, i, model) -> Case:
    """The i-th history point under ``model`` as a one-case Case (a full time history)."""
    return case_from(history_mapping(study, i, model), study.base)
