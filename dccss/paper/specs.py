"""The figures of a study configuration as data: which datasets each panel of a figure draws.

A ``figures:`` section (see config/config.yaml) names, for each paper figure, its kind (a key of
``KINDS``), one-line title and panels; ``figure_spec`` and ``figure_specs`` parse and check it,
naming the key of every mistake, and, given the ``Runs`` of a study, check that every panel asks
for a dataset the study computes. Parsing needs neither matplotlib nor the datasets: the workflow
checks its configuration with it before any job runs, and ``dccss.paper.figures`` draws the specs.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass


@dataclass(frozen=True)
class Panel:
    """One panel of a figure: the dataset it draws and, for some kinds, an instant or an angle.

    Attributes
    ----------
    prototype : name of the device.
    model, dt : model and time step (s) of a time history ("cases" kinds).
    dXg : ground step (m) of a breakaway sweep ("breakaway" kinds).
    theta2_0 : θ²(t₀) (deg) of the sweep point drawn (kind "breakaway_configurations").
    t : the step ending nearest this instant (s) is drawn (kinds "sticking", "two_phase").
    variant : case set ("cases") or normal convention ("breakaway") of the dataset; None for the
        variant the figure is drawn for.
    """

    prototype: str
    model: str | None = None
    dt: float | None = None
    dXg: float | None = None
    theta2_0: float | None = None
    t: float | None = None
    variant: str | None = None


@dataclass(frozen=True)
class FigureSpec:
    """A paper figure: its id ("fig07"), kind (a key of ``KINDS``), one-line title and panels."""

    id: str
    kind: str
    title: str
    panels: tuple[Panel, ...]

    @property
    def data(self) -> str:
        """The datasets the figure draws: "cases" or "breakaway"."""
        return KINDS[self.kind].data


# --- the registry of figure kinds -------------------------------------------------------------
MODELS = ("compliant", "stick_slip")


@dataclass(frozen=True)
class Kind:
    """What a kind of figure draws (its drawing function: ``dccss.paper.figures.DRAW``).

    Attributes
    ----------
    data : the datasets it draws, "cases" (time histories) or "breakaway" (sweeps).
    panels : (fewest, most) panels it lays out.
    needs : panel keys it needs besides those naming the dataset ("t", "theta2_0").
    models : models whose time histories it can draw.
    """

    data: str
    panels: tuple[int, int]
    needs: tuple[str, ...] = ()
    models: tuple[str, ...] = MODELS


KINDS: dict[str, Kind] = {
    "breakaway": Kind("breakaway", (1, 6)),
    "breakaway_configurations": Kind("breakaway", (1, 3), ("theta2_0",)),
    "diagonals": Kind("cases", (1, 4)),
    "differences": Kind("cases", (1, 4)),
    "global_coordinates": Kind("cases", (1, 1)),
    "interpenetration": Kind("cases", (1, 6)),
    "sticking": Kind("cases", (1, 1), ("t",), ("stick_slip",)),
    "two_phase": Kind("cases", (1, 3), ("t",), ("stick_slip",)),
}


# --- figure specs from a study configuration ----------------------------------------------------
FIGURE_ID = re.compile(r"fig[0-9]+")
#: keys of a ``figures:`` section that are not figures: the variants the unsuffixed files show
SECTION_KEYS = ("case_set", "breakaway_normals")
ENTRY_KEYS = ("kind", "title", "panels")
#: panel keys naming the dataset, and the key naming its variant, by the data a kind draws
DATASET_KEYS = {"cases": ("prototype", "model", "dt"), "breakaway": ("prototype", "dXg")}
VARIANT_KEYS = {"cases": "case_set", "breakaway": "normals"}
#: panel value checks: "name" (text), "positive" (> 0), "number" (finite)
PANEL_VALUES = {"prototype": "name", "model": "name", "case_set": "name", "normals": "name",
                "dt": "positive", "dXg": "positive", "t": "positive", "theta2_0": "number"}


class SpecError(ValueError):
    """A figure spec that cannot be drawn. ``errors``: one "<key>: <problem>" line per mistake,
    the key written as in the configuration (e.g. ``figures.fig10.panels[1].dt``)."""

    def __init__(self, errors):
        self.errors = list(errors)
        super().__init__("\n".join(self.errors))


@dataclass(frozen=True)
class Runs:
    """The datasets a study computes: what its figure specs may ask for.

    Attributes
    ----------
    prototypes : device names (a breakaway sweep is run for each).
    case_sets : {case set: its prototypes}, each run with every model and time step.
    models : models of the time histories.
    dt : time steps of the time histories (s).
    duration : length of the excitation (s).
    dXg : ground steps of the breakaway sweeps (m).
    normals : normal conventions of the breakaway sweeps (empty: no sweep is run).
    theta2_0 : (lowest, highest) θ²(t₀) of the sweeps (deg); None if the grid is empty.
    """

    prototypes: Sequence[str]
    case_sets: Mapping[str, Sequence[str]]
    models: Sequence[str]
    dt: Sequence[float]
    duration: float
    dXg: Sequence[float] = ()
    normals: Sequence[str] = ()
    theta2_0: tuple[float, float] | None = None


def figure_spec(fig_id: str, entry: Mapping, runs: Runs | None = None) -> FigureSpec:
    """Parse and check one figure of a ``figures:`` section.

    Parameters
    ----------
    fig_id : "fig" and the paper's figure number, e.g. "fig08".
    entry : {"kind": a key of ``KINDS``, "title": one line, "panels": [panel mapping, ...]}; a panel
        names its dataset (prototype, model and dt, or prototype and dXg), optionally its variant
        (case_set or normals), and the instant ``t`` or angle ``theta2_0`` its kind needs.
    runs : the datasets the study computes; if given, every panel must ask for one of them.

    Returns
    -------
    FigureSpec

    Raises
    ------
    SpecError : naming the key of every mistake.
    """
    key = f"figures.{fig_id}"
    errors = list(_entry_errors(key, fig_id, entry))
    if errors:
        raise SpecError(errors)
    kind = KINDS[entry["kind"]]
    panels = tuple(_panel(p, kind.data) for p in entry["panels"])
    spec = FigureSpec(fig_id, entry["kind"], entry["title"], panels)
    errors = list(_run_errors(key, spec, runs)) if runs is not None else []
    if errors:
        raise SpecError(errors)
    return spec


def figure_specs(section: Mapping, runs: Runs | None = None) -> dict[str, FigureSpec]:
    """Parse and check every figure of a ``figures:`` section, and the variants it names.

    ``case_set`` and ``breakaway_normals`` name the variant the unsuffixed figures show; each is
    required when a figure draws that kind of data and ``runs`` is given.

    Raises
    ------
    SpecError : every mistake of the section, each naming its key.
    """
    specs, errors = {}, []
    for fig_id, entry in section.items():
        if fig_id not in SECTION_KEYS:
            try:
                specs[fig_id] = figure_spec(fig_id, entry, runs)
            except SpecError as err:
                errors += err.errors
    if runs is not None:
        errors = [*_section_errors(section, specs, runs), *errors]
    if errors:
        raise SpecError(errors)
    return specs


def _entry_errors(key, fig_id, entry):
    if not FIGURE_ID.fullmatch(str(fig_id)):
        yield f"{key}: a figure is named 'fig' and its number, e.g. fig07"
    if not isinstance(entry, Mapping):
        yield f"{key}: expected a mapping with the keys {list(ENTRY_KEYS)}"
        return
    yield from _keys_errors(key, entry, ENTRY_KEYS, ENTRY_KEYS)
    kind = entry.get("kind")
    if "kind" in entry and kind not in KINDS:
        yield f"{key}.kind: unknown kind {kind!r}; known: {sorted(KINDS)}"
    if "title" in entry and (not isinstance(entry["title"], str) or not entry["title"].strip()
                             or "\n" in entry["title"]):
        yield f"{key}.title: expected one line of text"
    panels = entry.get("panels")
    if "panels" in entry and (not isinstance(panels, list) or not panels):
        yield f"{key}.panels: expected a list of panels"
    elif kind in KINDS and panels:
        yield from _panels_errors(f"{key}.panels", kind, panels)


def _panels_errors(key, kind, panels):
    fewest, most = KINDS[kind].panels
    if not fewest <= len(panels) <= most:
        span = f"{fewest}" if fewest == most else f"{fewest} to {most}"
        yield f"{key}: kind {kind!r} draws {span} panel(s), got {len(panels)}"
    for i, panel in enumerate(panels):
        yield from _panel_errors(f"{key}[{i}]", kind, panel)


def _panel_errors(key, kind, panel):
    if not isinstance(panel, Mapping):
        yield f"{key}: expected a mapping"
        return
    spec = KINDS[kind]
    required = (*DATASET_KEYS[spec.data], *spec.needs)
    yield from _keys_errors(key, panel, required, (*required, VARIANT_KEYS[spec.data]), f" of kind {kind!r}")
    for name, value in panel.items():
        if name in PANEL_VALUES and not _valid(PANEL_VALUES[name], value):
            yield f"{key}.{name}: expected {_EXPECTED[PANEL_VALUES[name]]}, got {value!r}"
    if spec.data == "cases" and isinstance(panel.get("model"), str) and panel["model"] not in spec.models:
        yield f"{key}.model: kind {kind!r} draws the {' or '.join(spec.models)} model, got {panel['model']!r}"


def _keys_errors(key, mapping, required, allowed, where=""):
    missing = [k for k in required if k not in mapping]
    unknown = sorted(str(k) for k in mapping if k not in allowed)
    if missing:
        yield f"{key}: missing key(s) {missing}{where}"
    if unknown:
        yield f"{key}: unknown key(s) {unknown}{where}; allowed: {list(allowed)}"


_EXPECTED = {"name": "a name", "positive": "a number > 0", "number": "a finite number"}


def _valid(check, value):
    if check == "name":
        return isinstance(value, str) and bool(value)
    number = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    return number and (check == "number" or value > 0)


def _panel(mapping, data):
    values = {name: mapping.get(name) for name in ("prototype", "model", "dt", "dXg", "theta2_0", "t")}
    numbers = {name: float(v) for name, v in values.items() if name not in ("prototype", "model") and v is not None}
    return Panel(**{**values, **numbers}, variant=mapping.get(VARIANT_KEYS[data]))


def _section_errors(section, specs, runs):
    drawn = {spec.data for spec in specs.values()}
    case_set, normals = section.get("case_set"), section.get("breakaway_normals")
    if case_set is None and "cases" in drawn:
        yield "figures.case_set: required: the case set the time-history figures show"
    elif case_set is not None and case_set not in runs.case_sets:
        yield f"figures.case_set: unknown case set {case_set!r}; defined: {sorted(runs.case_sets)}"
    if normals is None and "breakaway" in drawn and runs.normals:
        yield "figures.breakaway_normals: required: the normal convention the breakaway figures show"
    elif normals is not None and normals not in runs.normals:
        yield f"figures.breakaway_normals: {normals!r} is not among breakaway.normals {list(runs.normals)}"


def _run_errors(key, spec, runs):
    if spec.data == "breakaway" and not runs.normals:
        yield f"{key}.kind: {spec.kind!r} draws breakaway sweeps, and none is run (no breakaway section)"
        return
    check = _case_errors if spec.data == "cases" else _sweep_errors
    for i, panel in enumerate(spec.panels):
        yield from check(f"{key}.panels[{i}]", panel, runs)


def _prototype_errors(key, panel, runs):
    if panel.prototype not in runs.prototypes:
        yield f"{key}.prototype: unknown prototype {panel.prototype!r}; defined: {sorted(runs.prototypes)}"


def _case_errors(key, panel, runs):
    """A time history: its case set(s) run the prototype, with the model and time step."""
    yield from _prototype_errors(key, panel, runs)
    if panel.variant is not None and panel.variant not in runs.case_sets:
        yield f"{key}.case_set: unknown case set {panel.variant!r}; defined: {sorted(runs.case_sets)}"
    elif panel.prototype in runs.prototypes:
        sets = [panel.variant] if panel.variant else list(runs.case_sets)
        missing = [s for s in sets if panel.prototype not in runs.case_sets[s]]
        if missing:
            every = "" if panel.variant else " (the figure is drawn for every case set; a panel may name its own)"
            yield f"{key}.prototype: {panel.prototype!r} is not a case of case set(s) {missing}{every}"
    if panel.model not in runs.models:
        yield f"{key}.model: {panel.model!r} is not run; models: {list(runs.models)}"
    if f"{panel.dt:g}" not in {f"{dt:g}" for dt in runs.dt}:
        yield f"{key}.dt: {panel.dt:g} s is not run; dt: {list(runs.dt)}"
    if panel.t is not None and not 0 < panel.t <= runs.duration:
        yield f"{key}.t: {panel.t:g} s is outside the excitation, 0 < t <= duration = {runs.duration:g} s"


def _sweep_errors(key, panel, runs):
    """A breakaway sweep: run for the prototype, with the normals, ground step and angle."""
    yield from _prototype_errors(key, panel, runs)
    if panel.variant is not None and panel.variant not in runs.normals:
        yield f"{key}.normals: {panel.variant!r} is not run; breakaway.normals: {list(runs.normals)}"
    if panel.dXg not in runs.dXg:
        yield f"{key}.dXg: {panel.dXg:g} m is not a step of the breakaway sweeps; breakaway.dXg: {list(runs.dXg)}"
    if panel.theta2_0 is not None and runs.theta2_0 and not runs.theta2_0[0] <= panel.theta2_0 <= runs.theta2_0[1]:
        lo, hi = runs.theta2_0
        yield f"{key}.theta2_0: {panel.theta2_0:g}° is outside the breakaway grid, {lo:g}° to {hi:g}°"
