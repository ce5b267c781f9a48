"""The chunks of every model combined into one dataset with a dimension per sweep axis."""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..mechanics.models import REGISTRY
from ..mechanics.structure import SUMMARIES as STRUCTURE_SUMMARIES
from ..mechanics.summaries import MODEL_SPECIFIC, SUMMARIES
from ..results import global_attrs, variable


def axis_variable(dims, name, values):
    """A sweep axis as a variable: CF units, or strings for the prototype axis."""
    from .spec import axis_units

    units = axis_units(name)
    if units is None:
        return xr.Variable(dims, np.asarray(values, dtype=object), {"long_name": f"sweep axis {name}"})
    return variable(dims, values, units, f"sweep axis {name}")


def study_attrs(study, model=None) -> dict:
    """Global attributes of a study's datasets (not the description: only the plots show it)."""
    out = global_attrs(f"dccss study {study.name}", f"study {study.name}", study=study.name, normals=study.normals,
                       theta2_0_deg=study.theta2_0, capacity_policy=study.capacity,
                       on_failure=study.options.on_failure, symmetric=int(study.symmetric),
                       sweep_axes=" ".join(study.axes),
                       **({"dt_s": study.dt} if study.dt is not None and "dt" not in study.axes else {}),
                       **{f"prototype_{k}": float(v) for k, v in study.prototype.items()}, **study.excitation.attrs(),
                       **({} if study.structure is None else
                          {f"structure_{k}": v for k, v in vars(study.structure).items()}))
    if model:
        out["model"] = model
    return out


def combine(study, chunks: dict) -> xr.Dataset:
    """One dataset of all summaries: dimensions ``model`` and one per sweep axis. ``chunks`` maps
    each model to its chunk datasets (any order); a summary another model lacks is NaN."""
    grid, dims = study.grid, tuple(study.axes)
    per_model = []
    for model in study.models:
        ds = xr.concat(chunks[model], dim="case").sortby("case")
        if ds.sizes["case"] != grid.n_cases:
            raise ValueError(f"{model}: {ds.sizes['case']} cases in the chunks, expected {grid.n_cases}")
        ds = ds.drop_vars(list(study.axes))
        variables = {}
        for name in {**SUMMARIES, **STRUCTURE_SUMMARIES}:
            if name in ds:
                variables[name] = xr.Variable(dims, ds[name].values.reshape(grid.shape), ds[name].attrs)
            elif name in MODEL_SPECIFIC:
                owners = ", ".join(e.title for e in REGISTRY.values() if name in e.summaries)
                units, long_name = SUMMARIES[name]
                variables[name] = xr.Variable(dims, np.full(grid.shape, np.nan),
                                              {"units": units, "long_name": f"{long_name} ({owners} only)"})
        per_model.append(xr.Dataset(variables))
    coords = {name: axis_variable((name,), name, vals) for name, vals in study.axes.items()}
    coords["model"] = xr.Variable(("model",), np.array(study.models, dtype=object), {"long_name": "kinematic model"})
    out = xr.concat(per_model, dim="model").assign_coords(coords)
    out.attrs = study_attrs(study)
    return out
