"""New studies from a YAML file: a base case, the models, and sweep axes (cartesian product).

A study file (schema: ``workflow/schemas/study.schema.yaml``)::

    study: {name: pad_shape, description: "..."}
    prototypes: {MyBearing: {R1: ..., ...}}   # optional: devices of your own (13 parameters each)
    prototype: DFP1              # the base device: a name (Table 1 or prototypes) or the 13 parameters
    symmetric: true              # plate 3 and cap 23 follow plate 1 and cap 21
    excitation: {kind: sine, amplitude: 0.27, omega: 30.0, duration: 1.0}   # or table / record
    theta2_0: 0.0                # degrees
    dt: 0.01                     # s (or a sweep axis; then this is the histories' default)
    models: [compliant, stick_slip]
    normals: signed
    sweep:                       # each axis a list or {start, stop, num} (linspace)
      alpha21: {start: 4.0, stop: 14.0, num: 21}
      h2: [0.08, 0.10, 0.12]
    chunk_size: auto             # cases per job: auto (default) splits each model's sweep in 4 jobs
    on_failure: mark             # a case the solver fails on: mark it (NaN, flag) or stop
    capacity: continue           # the pad reaches a ring: continue (flag), stop (end there) or error
    marks: {DFP1: {alpha21: 10.0, h2: 0.15}}        # points drawn on the maps
    histories: [{alpha21: 10.0, h2: 0.15}]          # cases also run in full

Sweep axes: ``prototype`` (a list of device names), any geometry parameter (overriding the
device's), the excitation's ``amplitude`` and ``omega`` (sine),
``scale`` (multiplies X_g(t) of any excitation; recorded accelerations are processed
linearly, so this equals scaling the record), ``theta2_0`` and ``dt`` (the step; the cases of a
chunk are solved in one batch per step size). Every sweep point is checked when the study is
loaded, before any job runs.

What each job reads is a part of the study file (``Study.parts``): the sweep chunks read the
cases' definition, the histories their own case, the plots the description and marks, so a
workflow reruns only the jobs whose part changed.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import xarray as xr

from ._version import __version__
from .case import ON_FAILURE, Case, case_from, excitation_from, geometry_from, newton_from
from .checks import CaseError, check_keys, choice, number
from .excitation import step_times
from .geometry import ANGLES, Geometry
from .kinematics import NORMALS
from .models import MODELS
from .newton import ConvergenceError, NewtonOptions
from .prototypes import TABLE1
from .results import REFERENCE, _var
from .simulation import CAPACITY_POLICIES, CapacityError
from .sweep import STICK_ONLY, SUMMARIES, summarize

GEOMETRY_KEYS = tuple(TABLE1["DFP1"])
EXCITATION_AXES = ("amplitude", "omega", "scale")
AXES = ("prototype",) + GEOMETRY_KEYS + EXCITATION_AXES + ("theta2_0", "dt")
PLATE3_FOLLOWS = {"R3": "R1", "alpha3": "alpha1", "alpha23": "alpha21", "hr3": "hr1", "hmin3": "hmin1",
                  "tr3": "tr1"}
KEYS = {"study", "prototypes", "prototype", "symmetric", "excitation", "theta2_0", "dt", "models", "normals", "sweep",
        "chunk_size", "marks", "histories", "newton", "on_failure", "capacity"}
REQUIRED = ("study", "prototype", "excitation", "models", "sweep")
#: the keys that only the plots read: editing them reruns nothing else
PLOT_KEYS = ("marks",)
#: chunks per model when chunk_size is "auto" (both cores busy, progress in every chunk's log)
AUTO_CHUNKS = 4


class StudyError(CaseError):
    """A study file is invalid; the message names the key."""


def axis_units(name):
    if name == "prototype":
        return None
    if name in ANGLES or name == "theta2_0":
        return "degree"
    return {"omega": "rad s-1", "scale": "1", "dt": "s"}.get(name, "m")


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


@dataclass
class Study:
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
    capacity: str = "continue"
    marks: dict = field(default_factory=dict)
    histories: list = field(default_factory=list)
    options: NewtonOptions = field(default_factory=NewtonOptions)
    base: Path = Path(".")

    # --- loading ------------------------------------------------------------------------------
    @classmethod
    def from_config(cls, config: dict, base: Path = Path(".")) -> Study:
        """Validate a study mapping (keys, types, every sweep point's geometry); errors name the key."""
        check_keys(config, "study file", REQUIRED, KEYS - set(REQUIRED))
        meta = config["study"]
        check_keys(meta, "study", ("name",), ("description",))
        name = meta["name"]
        if not isinstance(name, str) or not name.replace("_", "").replace("-", "").isalnum():
            raise StudyError(f"study.name: expected a name of letters, digits, '-' or '_', got {name!r}")
        own = config.get("prototypes", {})
        if not isinstance(own, dict):
            raise StudyError(f"prototypes: expected a mapping of names to devices, got {own!r}")
        for label, params in own.items():
            geometry_from(params, f"prototypes.{label}")
        known = {**TABLE1, **own}
        proto = config["prototype"]
        if isinstance(proto, str):
            if proto not in known:
                raise StudyError(f"prototype: unknown prototype {proto!r}; known: {sorted(known)}")
            proto = known[proto]
        geometry_from(proto)  # validates keys and values of the base device
        symmetric = config.get("symmetric", False)
        if not isinstance(symmetric, bool):
            raise StudyError(f"symmetric: expected true or false, got {symmetric!r}")
        models = config["models"]
        if not isinstance(models, list) or not models:
            raise StudyError(f"models: expected a non-empty list of {list(MODELS)}, got {models!r}")
        for i, m in enumerate(models):
            choice(m, f"models[{i}]", MODELS)
        if not isinstance(config["sweep"], dict) or not config["sweep"]:
            raise StudyError("sweep: expected a mapping of at least one axis name to its values")
        axes = {}
        for key, spec in config["sweep"].items():
            if key not in AXES:
                raise StudyError(f"sweep: unknown axis {key!r}; allowed: {list(AXES)}")
            if symmetric and key in PLATE3_FOLLOWS:
                raise StudyError(f"sweep.{key}: with symmetric: true, {key} follows {PLATE3_FOLLOWS[key]}; "
                                 f"sweep {PLATE3_FOLLOWS[key]} instead")
            if key == "prototype":
                if not isinstance(spec, list) or not spec:
                    raise StudyError(f"sweep.prototype: expected a non-empty list of device names, got {spec!r}")
                for i, label in enumerate(spec):
                    if label not in known:
                        raise StudyError(f"sweep.prototype[{i}]: unknown prototype {label!r}; known: {sorted(known)}")
                axes[key] = np.array(spec, dtype=str)
            else:
                axes[key] = axis_values(spec, f"sweep.{key}")
        chunk = config.get("chunk_size", "auto")
        if chunk != "auto" and (isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1):
            raise StudyError(f"chunk_size: expected an integer >= 1 or 'auto', got {chunk!r}")
        if chunk == "auto":
            chunk = -(-int(np.prod([len(v) for v in axes.values()])) // AUTO_CHUNKS)
        geometry = geometry_from(proto)
        excitation = excitation_from(config["excitation"], base, geometry)
        kind = config["excitation"].get("kind")
        for key in ("amplitude", "omega"):
            if key in axes and kind != "sine":
                raise StudyError(f"sweep.{key}: only a sine excitation has an {key}; use 'scale' for {kind!r}")
        if "dt" not in config and "dt" not in axes:
            raise StudyError("dt: missing: give the time step (s), or sweep it (sweep.dt)")
        dt = number(config["dt"], "dt", positive=True) if "dt" in config else None
        span = excitation.t_end - excitation.t_start
        for key, value in ([("dt", dt)] if dt is not None else []) + [
                (f"sweep.dt[{i}]", float(v)) for i, v in enumerate(axes.get("dt", []))]:
            if value <= 0:
                raise StudyError(f"{key}: must be > 0, got {value!r}")
            if value > span:
                raise StudyError(f"{key}: {value!r} s is larger than the excitation's duration {span!r} s")
        options = newton_from(config.get("newton"))
        policy = choice(config.get("on_failure", "mark"), "on_failure", ON_FAILURE)
        options = NewtonOptions(tol=options.tol, max_iter=options.max_iter, on_failure=ON_FAILURE[policy])
        study = cls(name=name, description=str(meta.get("description", "")), prototype=dict(proto),
                    prototypes={k: dict(v) for k, v in known.items()},
                    symmetric=symmetric, excitation=excitation, excitation_spec=dict(config["excitation"]),
                    theta2_0=number(config.get("theta2_0", 0.0), "theta2_0"), dt=dt, models=list(models),
                    normals=choice(config.get("normals", "signed"), "normals", NORMALS), axes=axes,
                    chunk_size=chunk, options=options, base=base,
                    capacity=choice(config.get("capacity", "continue"), "capacity", CAPACITY_POLICIES))
        study.marks = study._points(config.get("marks", {}), "marks")
        histories = config.get("histories", [])
        if not isinstance(histories, list):
            raise StudyError(f"histories: expected a list of sweep points, got {histories!r}")
        study.histories = [study._point(p, f"histories[{i}]") for i, p in enumerate(histories)]
        for i, point in enumerate(study.histories):
            if dt is None and "dt" not in point:
                raise StudyError(f"histories[{i}]: no dt: give it in the point or as the study's dt")
        study._check_grid()
        return study

    def _points(self, marks, key):
        if not isinstance(marks, dict):
            raise StudyError(f"{key}: expected a mapping of labels to sweep points, got {marks!r}")
        return {str(label): self._point(p, f"{key}.{label}") for label, p in marks.items()}

    def _point(self, point, key):
        check_keys(point, key, (), tuple(self.axes))
        out = {}
        for name, v in point.items():
            if name == "prototype":
                if v not in self.axes["prototype"]:
                    raise StudyError(f"{key}.prototype: {v!r} is not on the sweep axis {list(self.axes['prototype'])}")
                out[name] = v
            else:
                out[name] = number(v, f"{key}.{name}")
        return out

    def _check_grid(self):
        try:
            self.geometry(np.arange(self.n_cases))
        except ValueError:
            for i in range(self.n_cases):
                try:
                    self.geometry(np.array([i]))
                except ValueError as err:
                    where = ", ".join(f"{k}={v}" for k, v in self.point(i).items())
                    raise StudyError(f"sweep point {where}: {str(err).split(' (at batch index')[0]}") from None

    # --- the grid -----------------------------------------------------------------------------
    @property
    def shape(self) -> tuple:
        return tuple(len(v) for v in self.axes.values())

    @property
    def n_cases(self) -> int:
        return int(np.prod(self.shape))

    @property
    def n_chunks(self) -> int:
        return -(-self.n_cases // self.chunk_size)

    def chunk(self, k) -> np.ndarray:
        """The flattened case indices of chunk k: consecutive in the sweep order, except that with a
        ``dt`` axis the cases are taken by step size first (a chunk then holds few step sizes,
        each solved as one batch)."""
        if not 0 <= k < self.n_chunks:
            raise ValueError(f"chunk {k} outside 0..{self.n_chunks - 1}")
        cases = np.arange(self.n_cases)
        if "dt" in self.axes:
            cases = cases[np.argsort(self.dt_of(cases), kind="stable")]
        return cases[k * self.chunk_size:(k + 1) * self.chunk_size]

    def values(self, cases) -> dict:
        """Axis values of the flattened case indices."""
        idx = np.unravel_index(np.asarray(cases), self.shape)
        return {name: vals[i] for (name, vals), i in zip(self.axes.items(), idx)}

    def point(self, case) -> dict:
        return {k: (str(v[0]) if k == "prototype" else float(v[0])) for k, v in self.values(np.array([case])).items()}

    def geometry(self, cases) -> Geometry:
        values = self.values(cases)
        if "prototype" in values:
            params = {k: np.array([float(self.prototypes[p][k]) for p in values["prototype"]]) for k in GEOMETRY_KEYS}
        else:
            params = {k: np.full(len(cases), float(self.prototype[k])) for k in GEOMETRY_KEYS}
        params.update({k: v for k, v in values.items() if k in GEOMETRY_KEYS})
        if self.symmetric:
            params.update({k: params[src] for k, src in PLATE3_FOLLOWS.items()})
        return Geometry.from_degrees(**params)

    def times(self, dt):
        return step_times(self.excitation, dt)

    def dt_of(self, cases) -> np.ndarray:
        """The time step of each case (s)."""
        return self.values(cases).get("dt", np.full(len(cases), self.dt))

    def ground_motion(self, cases, t):
        """X_g (T, n) of the cases at the step times t."""
        values = self.values(cases)
        n = len(cases)
        if "amplitude" in values or "omega" in values:
            amp = values.get("amplitude", np.full(n, self.excitation.amplitude))
            omega = values.get("omega", np.full(n, self.excitation.omega))
            Xg = amp * np.sin(omega * t[:, None])
        else:
            Xg = np.repeat(self.excitation.displacement(t)[:, None], n, axis=1)
        return Xg * values.get("scale", 1.0)

    def theta2_0_of(self, cases):
        return np.radians(self.values(cases).get("theta2_0", np.full(len(cases), self.theta2_0)))

    # --- running ------------------------------------------------------------------------------
    def run_chunk(self, model, k, progress=None) -> xr.Dataset:
        """Summaries of the cases of chunk k under ``model`` (dimension ``case``): one batch per
        time step; ``progress(done, total, dt)`` is called as cases are solved (for a log)."""
        cases = self.chunk(k)
        dts = self.dt_of(cases)
        out = {}
        for dt in np.unique(dts):
            mine = dts == dt
            group, times = cases[mine], self.times(dt)
            report = None if progress is None else (lambda n, N, g=group, dt=dt: progress(n, N, len(g), dt))
            try:
                part = summarize(model, self.geometry(group), self.ground_motion(group, times),
                                 self.theta2_0_of(group), normals=self.normals, options=self.options, times=times,
                                 capacity=self.capacity, progress=report)
            except (ConvergenceError, CapacityError) as err:
                index = getattr(err, "index", None)
                where = self.point(group[index[0]]) if index else {}
                raise type(err)(f"sweep point {where or 'of chunk ' + str(k)} ({model}): {err}") from None
            for name, values in part.items():
                out.setdefault(name, np.zeros(len(cases), np.asarray(values).dtype))[mine] = values
        data = {name: _var(("case",), np.asarray(v), *SUMMARIES[name]) for name, v in out.items()}
        for flag in ("capacity_exceeded", "failed"):
            data[flag].data = data[flag].data.astype(np.int8)
        for name, v in self.values(cases).items():
            data[name] = _axis_var(("case",), name, v)
        ds = xr.Dataset(data, coords={"case": _var(("case",), cases, "1", "flattened sweep index")})
        ds.attrs = self.attrs(model)
        return ds

    def combine(self, chunks: dict) -> xr.Dataset:
        """One dataset of all summaries: dimensions ``model`` and one per sweep axis."""
        per_model = []
        for model in self.models:
            ds = xr.concat(chunks[model], dim="case").sortby("case")
            if ds.sizes["case"] != self.n_cases:
                raise ValueError(f"{model}: {ds.sizes['case']} cases in the chunks, expected {self.n_cases}")
            ds = ds.drop_vars(list(self.axes))
            grid = {}
            for name in SUMMARIES:
                if name in ds:
                    v = ds[name]
                    grid[name] = xr.Variable(tuple(self.axes), v.values.reshape(self.shape), v.attrs)
                elif name in STICK_ONLY:
                    grid[name] = xr.Variable(tuple(self.axes), np.full(self.shape, np.nan), {
                        "units": SUMMARIES[name][0], "long_name": SUMMARIES[name][1] + " (stick-slip only)"})
            per_model.append(xr.Dataset(grid))
        coords = {name: _axis_var((name,), name, vals) for name, vals in self.axes.items()}
        coords["model"] = xr.Variable(("model",), np.array(self.models, dtype=object), {"long_name": "kinematic model"})
        out = xr.concat(per_model, dim="model").assign_coords(coords)
        out.attrs = self.attrs(None)
        return out

    def history_case(self, i, model) -> Case:
        """The i-th history point under ``model`` as a one-case Case (a full time history)."""
        return case_from(self.history_mapping(i, model), self.base)

    def history_mapping(self, i, model) -> dict:
        """The case mapping (``dccss.case``) of the i-th history point under ``model``: all that its
        result depends on (a workflow reruns the history when, and only when, this changes)."""
        point = self.histories[i]
        device = self.prototypes[point["prototype"]] if "prototype" in point else self.prototype
        full = {k: float(v) for k, v in device.items()}
        full.update({k: v for k, v in point.items() if k in GEOMETRY_KEYS})
        if self.symmetric:
            full.update({k: full[src] for k, src in PLATE3_FOLLOWS.items()})
        excitation = dict(self.excitation_spec)
        for key in ("amplitude", "omega", "scale"):
            if key in point:
                excitation[key] = point[key]
        dt = point.get("dt", self.dt)
        policy = {v: k for k, v in ON_FAILURE.items()}[self.options.on_failure]
        return {"id": f"{self.name}/history{i}_{model}", "prototype": full, "excitation": excitation,
                "theta2_0": point.get("theta2_0", self.theta2_0), "dt": dt, "model": model,
                "normals": self.normals, "newton": {"tol": self.options.tol, "max_iter": self.options.max_iter},
                "capacity": self.capacity, "on_failure": policy}

    def attrs(self, model) -> dict:
        """Global attributes of the study's datasets (not the description: only the plots show it)."""
        out = {"Conventions": "CF-1.11", "title": f"dccss study {self.name}",
               "source": f"dccss {__version__}", "references": REFERENCE, "dccss_version": __version__,
               "history": f"computed by dccss {__version__} (study {self.name})",
               "study": self.name, "normals": self.normals, "theta2_0_deg": self.theta2_0,
               "capacity_policy": self.capacity, "on_failure": self.options.on_failure,
               **({"dt_s": self.dt} if self.dt is not None and "dt" not in self.axes else {}),
               "symmetric": int(self.symmetric), "sweep_axes": " ".join(self.axes),
               **{f"prototype_{k}": float(v) for k, v in self.prototype.items()}, **self.excitation.attrs()}
        if model:
            out["model"] = model
        return out


def sweep_spec(config: dict, models=None) -> dict:
    """The part of a study file that the sweep's results depend on: all but the description, the
    marks and the histories (and, with ``models``, only those models)."""
    spec = {k: v for k, v in config.items() if k not in ("marks", "histories")}
    spec["study"] = {"name": config["study"]["name"]}
    if models is not None:
        spec["models"] = list(models)
    return spec


def _axis_var(dims, name, values):
    units = axis_units(name)
    if units is None:
        return xr.Variable(dims, np.asarray(values, dtype=object), {"long_name": f"sweep axis {name}"})
    return _var(dims, values, units, f"sweep axis {name}")
