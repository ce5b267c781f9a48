"""The cases of a sweep: the cartesian product of its axes, flattened in the sweep's order."""

from __future__ import annotations

import hashlib
from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from ..excitation import step_times
from ..mechanics import structure
from ..mechanics.geometry import PARAMETERS, Geometry

#: sweep axes whose values are names, not numbers
CATEGORICAL = ("record", "prototype", "component", "property", "slider")
#: with ``symmetric: true`` the plate-3 and cap-23 parameters follow those of plate 1 and cap 21
PLATE3_FOLLOWS = {"R3": "R1", "alpha3": "alpha1", "alpha23": "alpha21", "hr3": "hr1", "hmin3": "hmin1",
                  "tr3": "tr1"}


def record_group(name, jobs) -> int:
    """The job (0 .. jobs - 1) a record falls in: its name's SHA-256 modulo ``jobs`` (stable across runs and
    machines, and whatever the other records)."""
    return int.from_bytes(hashlib.sha256(name.encode()).digest()[:8], "big") % jobs


class Grid:
    """The sweep of a ``Study``: case k is the k-th point of the product of ``study.axes``.

    Every method takes flattened case indices (a 1-D integer array) and returns one value (or one
    column) per case.
    """

    def __init__(self, study):
        self.study = study
        self.axes = study.axes
        self.shape = tuple(len(v) for v in self.axes.values())
        self.n_cases = int(np.prod(self.shape))
        # a record axis comes first: each record's cases are a block, chunked on its own
        self.records = list(self.axes["record"]) if "record" in self.axes else [None]
        self.per_record = self.n_cases // len(self.records)
        jobs = getattr(study, "record_jobs", None)
        if jobs is None:
            self._chunks = [part for r in range(len(self.records)) for part in self._split(r)]
            self.groups = None
        else:  # a chunk per group of records, by the hash of their names: a record's group is its own affair
            members = {}
            for r, name in enumerate(self.records):
                members.setdefault(record_group(str(name), jobs), []).append(r)
            self.groups = {g: [str(self.records[r]) for r in rs] for g, rs in sorted(members.items())}
            self._chunks = [np.concatenate([r * self.per_record + np.arange(self.per_record) for r in rs])
                            for _, rs in sorted(members.items())]
        self.n_chunks = len(self._chunks)

    def _split(self, r) -> list:
        """The chunks of record r's block of cases (of all cases without a record axis): consecutive in
        the sweep order, except that with a ``dt`` axis the cases are taken by step size first (a
        chunk then holds few step sizes, each solved as one batch)."""
        cases = r * self.per_record + np.arange(self.per_record)
        if "dt" in self.axes:
            cases = cases[np.argsort(self.dt_of(cases), kind="stable")]
        size = self.study.chunk_size
        return [cases[k:k + size] for k in range(0, len(cases), size)]

    def chunk(self, k) -> np.ndarray:
        """The case indices of chunk k (a chunk holds one record's cases only)."""
        if not 0 <= k < self.n_chunks:
            raise ValueError(f"chunk {k} outside 0..{self.n_chunks - 1}")
        return self._chunks[k]

    def records_of(self, cases) -> list:
        """The records (names, in the sweep's order) of cases; [None] without a record axis."""
        if "record" not in self.axes:
            return [None]
        found = set(self.values(cases)["record"])
        return [str(r) for r in self.records if r in found]

    def record_of(self, cases) -> str | None:
        """The record (its name) of cases that share one, None without a record axis."""
        if "record" not in self.axes:
            return None
        names = set(self.values(cases)["record"])
        if len(names) != 1:
            raise ValueError(f"cases of several records at once: {sorted(names)}")
        return str(names.pop())

    def excitation(self, cases):
        """The excitation of cases that share one: the record's (processed once), or the study's."""
        name = self.record_of(cases)
        return self.study.excitation if name is None else self.study.records[name]

    def factors(self, cases) -> np.ndarray | None:
        """The factor each case's record is scaled by to its intensity level (``studies.intensity``), None
        without intensity levels."""
        if "intensity" not in self.axes:
            return None
        values = self.values(cases)
        records = values["record"] if "record" in values else [None] * len(cases)
        return np.array([self.study.intensity_factor(None if r is None else str(r), level)
                         for r, level in zip(records, values["intensity"])])

    def excitations(self, cases) -> list:
        """The excitation of each case: its record (or the study's) at its intensity level's factor, read as ``dccss
        run`` reads it; the one shared excitation for each case without intensity levels."""
        factors = self.factors(cases)
        if factors is None:
            return [self.excitation(cases)] * len(cases)
        record = self.record_of(cases)
        return [self.study.excitation_at(record, f) for f in factors]

    def values(self, cases) -> dict:
        """{axis: its value for each case}."""
        idx = np.unravel_index(np.asarray(cases), self.shape)
        return {name: vals[i] for (name, vals), i in zip(self.axes.items(), idx)}

    def own(self, cases, excitation) -> dict:
        """The excitation's swept parameters of each case: the sweep's values, and a sine's amplitude
        "capacity" as each case's own device's R1 sin(alpha1 - alpha21) (as the case file of a history
        takes it), not the base device's."""
        values = self.values(cases)
        own = {k: values[k] for k in excitation.parameters if k in values}
        if self.study.excitation_spec.get("amplitude") == "capacity" and "amplitude" not in own:
            own["amplitude"] = np.broadcast_to(self.geometry(cases).capacity1, (len(cases),)).astype(float)
        return own

    def point(self, case) -> dict:
        """{axis: value} of one case (str for prototype names, float otherwise)."""
        return {k: (str(v[0]) if k in CATEGORICAL else float(v[0]))
                for k, v in self.values(np.array([case])).items()}

    def geometry(self, cases) -> Geometry:
        """The devices of the cases, as one batched Geometry."""
        study, values = self.study, self.values(cases)
        if "prototype" in values:
            params = {k: np.array([float(study.prototypes[p][k]) for p in values["prototype"]]) for k in PARAMETERS}
        else:
            params = {k: np.full(len(cases), float(study.prototype[k])) for k in PARAMETERS}
        params.update({k: v for k, v in values.items() if k in PARAMETERS})
        if study.symmetric:
            params.update({k: params[src] for k, src in PLATE3_FOLLOWS.items()})
        return Geometry.from_degrees(**params)

    def dt_of(self, cases) -> np.ndarray:
        """The time step of each case (s)."""
        return self.values(cases).get("dt", np.full(len(cases), self.study.dt))

    def theta2_0_of(self, cases) -> np.ndarray:
        """The initial pad rotation of each case (rad)."""
        return np.radians(self.values(cases).get("theta2_0", np.full(len(cases), self.study.theta2_0)))

    def azimuth_of(self, cases) -> np.ndarray:
        """The reference azimuth of each case of a bidirectional study (rad): the direction its
        spatial model gives a zero ground increment (``excitation.azimuth`` of that case)."""
        excitation, values = self.excitation(cases), self.values(cases)
        if "azimuth" in values:
            return np.radians(values["azimuth"])
        base = np.full(len(cases), float(getattr(excitation, "azimuth", 0.0)))  # planar: unused
        if "component" in values:
            return np.where(values["component"] == "y", np.pi / 2, np.where(values["component"] == "x", 0.0, base))
        return base

    def structures(self, cases) -> list:
        """The structure of each case (``mechanics.structure.Structure``), or None where the study has none."""
        study, values = self.study, self.values(cases)
        if study.structure is None:
            return [None] * len(cases)
        return [replace(study.structure, **{k: float(values[k][i]) for k in ("friction", "damping") if k in values},
                        **({"factor": study.bounds[str(values["property"][i])]} if "property" in values else {}),
                        **({"slider": str(values["slider"][i])} if "slider" in values else {}))
                for i in range(len(cases))]

    def compares_sliders(self) -> bool:
        """Whether the study has an articulated slider (a slider axis, or the study's own): its summaries then
        hold each surface's (``structure.SURFACE_SUMMARIES``), the rigid slider's in proportion."""
        return "slider" in self.axes or (self.study.structure is not None and self.study.structure.slider != "rigid")

    def sliders(self, cases) -> np.ndarray:
        """The slider kind of each case (``rigid`` without a structure)."""
        if "slider" in self.axes:
            return np.asarray(self.values(cases)["slider"], dtype=str)
        kind = self.study.structure.slider if self.study.structure is not None else "rigid"
        return np.full(len(cases), kind)

    def pendulums(self, cases) -> list:
        """What a structure needs of each case's device: its pendulum length L, radii R1, R3 (m) and the rest of
        its parameters (an articulated slider's halves: ``sliders.pendulums``)."""
        devices = self.geometry(cases)
        names = ("L", "R1", "R3", "h2", "alpha1", "alpha3", "alpha21", "alpha23")
        values = {k: np.broadcast_to(getattr(devices, k), (len(cases),)) for k in names}
        return [SimpleNamespace(**{k: float(v[i]) for k, v in values.items()}) for i in range(len(cases))]

    def times(self, dt, cases=None) -> np.ndarray:
        """The step times at step size dt (s) of the cases' excitation (the study's without ``cases``)."""
        return step_times(self.study.excitation if cases is None else self.excitation(cases), dt)

    def imposed(self, cases, t) -> tuple[np.ndarray, list]:
        """The motion imposed on RB1 relative to RB3 at the step times t, (T, n) or (T, n, 2), and the
        structure's response of each case (``structure.Response``; [] without a structure): the
        ground motion, or minus the stroke of each case's structure, driven by that case's ground
        acceleration (its scale, component or azimuth, its sine's amplitude and omega) on a pendulum
        of its device's L."""
        if self.study.structure is None:
            return self.ground_motion(cases, t), []
        excitation, values = self.excitation(cases), self.values(cases)
        out = np.zeros((len(t), len(cases), excitation.components))
        responses, parameters = [], self.own(cases, excitation)
        for i, (mine, device, motion) in enumerate(zip(self.structures(cases), self.pendulums(cases),
                                                        self.excitations(cases))):
            own = {k: v[i] for k, v in parameters.items()}
            scale = float(values["scale"][i]) if "scale" in values else 1.0
            # a swept scale is the record's: its vertical's too, by its size (a negative scale mirrors the horizontal
            # motion, and gravity keeps its direction); a component keeps the vertical
            factor = scale
            if "component" in values:
                factor = factor * np.array([values["component"][i] != "y", values["component"][i] != "x"], float)
            ground = motion.ground_acceleration(**own).scaled(factor, vertical=abs(scale))
            response = structure.respond(ground, t, device, mine)
            out[:, i] = 0.0 - response.stroke
            responses.append(response)
        return (out[..., 0] if excitation.components == 1 else out), responses

    def ground_motion(self, cases, t) -> np.ndarray:
        """X_g (T, n) of the cases at the step times t, or (T, n, 2) for a bidirectional excitation:
        the excitation evaluates its own swept parameters for the batch; ``scale`` multiplies the
        result, ``component`` keeps x, y or both."""
        excitation, values = self.excitation(cases), self.values(cases)
        own = self.own(cases, excitation)
        if "intensity" in self.axes:  # each case its record at its level's factor
            Xg = np.stack([e.displacement(t, **{k: v[i] for k, v in own.items()})
                           for i, e in enumerate(self.excitations(cases))], axis=1)
        else:
            Xg = excitation.displacement(t[:, None], **own) if own else excitation.displacement(t)[:, None]
        scale = values.get("scale", np.ones(len(cases)))
        if excitation.components == 1:
            return np.broadcast_to(Xg, (len(t), len(cases))) * scale
        Xg = np.broadcast_to(Xg, (len(t), len(cases), 2)) * scale[:, None]
        if "component" in values:
            keep = np.stack([values["component"] != "y", values["component"] != "x"], axis=-1)
            Xg = Xg * keep
        return Xg
