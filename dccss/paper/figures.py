"""Figures 7-12 and 17-20 of Bianco, Monti & Belfiore (2021), drawn from result datasets only.

What each figure shows is data: a ``FigureSpec`` (parsed from the ``figures:`` section of a study
configuration by ``figure_spec``) names its kind, title and panels, and ``KINDS`` maps each kind
to the function that draws it. Each figure is a plain ``matplotlib.figure.Figure`` (no pyplot, no
global state; freed when unreferenced). Datasets are those of ``dccss.simulate`` ("cases") and
``dccss.breakaway`` ("breakaway"); their values are SI (angles in degrees) and are converted to
cm, mm or µm only for plotting.

Typical use::

    spec = figure_spec("fig09", config["figures"]["fig09"])   # kind, title and panels
    fig = render(spec, datasets, "case set: as_reported")      # one dataset per panel, in order
    save(fig, "fig09.png", "fig09.pdf")
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from string import ascii_lowercase

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from ..drawing import (
    CORNER_STYLE,
    I_LABEL,
    _corner_inset,
    _corners,
    _device,
    _drop_unused,
    _figure,
    _frame,
    _grid,
    _headroom,
    _legend,
    _length_unit,
    _q,
    _shapes,
    _step_path,
    _twin,
    caption_line,
    freeze,
)
from ..mechanics.kinematics import CORNERS
from ..results import geometry_from_attrs


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


def _finish(fig, fig_id, caption, title=None):
    """Heading "Figure N. <title>" (N from ``fig_id`` "figNN"), caption line; freeze the layout."""
    number = re.fullmatch(r"fig([0-9]+)", fig_id)
    heading = f"Figure {int(number[1])}." if number else fig_id
    fig.suptitle(f"{heading} {title}" if title else heading, fontsize=12)
    caption_line(fig, caption)
    return freeze(fig)


def _case_label(panel):
    """"DFP1, Δt = 0.01 s" (and the case set, if the panel names its own)."""
    label = f"{panel.prototype}, Δt = {panel.dt:g} s"
    return f"{label}, {panel.variant}" if panel.variant else label


def _sweep_label(panel):
    """"DFP1" (and the normal convention, if the panel names its own)."""
    return f"{panel.prototype}, {panel.variant} normals" if panel.variant else panel.prototype


def _sweep(ds, panel):
    """The panel's ground step of a breakaway sweep (a dataset with or without a dXg dimension)."""
    return ds.sel(dXg=panel.dXg) if "dXg" in ds.dims else ds


# --- figures: (spec, one dataset per panel, caption line) -> Figure --------------------------------
def _breakaway(spec, datasets, caption):
    """Fig. 7: corner interpenetration and |C_q| after the first step vs θ²(t₀); panels fill the
    columns of a two-row grid."""
    nrows, ncols = _grid(len(spec.panels), rows=2)
    fig, axes = _figure((13, 4.5 * nrows), nrows, ncols)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ds, ax = _sweep(ds, panel), axes[k % nrows, k // nrows]
        th = ds["theta2_0"].values
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for c in CORNERS:
            ax.plot(th, factor * ds[f"I_{c}"].values, label=I_LABEL[c], **CORNER_STYLE[c])
        ax.set_ylabel(f"interpenetration ({unit})")
        ax.set_xlabel(r"$\theta^2(t_0)$ (°)")
        tw = _twin(ax, "0.3", r"$|\mathbf{C_q}|$ (m)")
        tw.plot(th, ds["det_Cq"].values, color="0.3", ls=":", lw=1.4, marker=".", ms=4, label=r"$|\mathbf{C_q}|$")
        ax.set_title(f"({ascii_lowercase[k]}) {_sweep_label(panel)}, ΔX$_g(t_1)$ = {100 * panel.dXg:g} cm", loc="left")
        ax.margins(y=0.15)
        _headroom(ax, tw)  # keep the legend clear of both curves
        _legend(ax, tw, ncols=5, loc="upper center")
    _drop_unused(axes, len(spec.panels), by_columns=True)
    return _finish(fig, spec.id, caption, spec.title)


def _breakaway_configurations(spec, datasets, caption):
    """Fig. 8: initial and displaced configurations at the sweep point nearest each panel's θ²(t₀),
    with the four corners zoomed; panels side by side."""
    fig, axes = _figure((13, 7.6), 1, len(spec.panels))
    places = {"A": [0.01, 0.01, 0.40, 0.27], "B": [0.59, 0.01, 0.40, 0.27],
              "C": [0.01, 0.70, 0.40, 0.27], "D": [0.59, 0.70, 0.40, 0.27]}
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ds, ax = _sweep(ds, panel).sel(theta2_0=panel.theta2_0, method="nearest"), axes[0, k]
        g = geometry_from_attrs(ds.attrs)
        shapes = _shapes(g)
        q0, q1 = _q(ds, "_t0"), _q(ds)
        points = _device(ax, g, q1, shapes, corners=True, label="displaced, $t_1$")
        points = np.vstack([points, _device(ax, g, q0, shapes, fill=False, colour="0.35", ls="--",
                                            label="initial, $t_0$")])
        _frame(ax, points, extra_y=(30, 30))
        values = {c: float(ds[f"I_{c}"]) for c in CORNERS}
        loaded = "BC" if values["B"] + values["C"] > values["A"] + values["D"] else "AD"
        for c in CORNERS:
            _corner_inset(ax, g, q1, shapes, c, values[c], places[c], c in loaded)
        ax.set_title(f"({ascii_lowercase[k]}) {_sweep_label(panel)}, $\\theta^2(t_0)$ = "
                     f"{float(ds['theta2_0']):.1f}°, ΔX$_g(t_1)$ = {100 * panel.dXg:g} cm, "
                     f"$\\theta^2(t_1)$ = {q1['theta2']:.2f}°", loc="left")
        ax.legend(fontsize=8, loc="upper center")
    return _finish(fig, spec.id, caption, spec.title)


def _diagonals(spec, datasets, caption):
    """Fig. 9: interpenetration histories on diagonal A²D² (top) and B²C² (bottom), a column per panel."""
    fig, axes = _figure((14, 7.5), 2, len(spec.panels), sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        t = ds["t"].values
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for row, pair in enumerate(("AD", "BC")):
            _corners(axes[row, k], t, ds, pair, factor, unit,
                     f"diagonal ${pair[0]}^2{pair[1]}^2$\ninterpenetration, < 0: gap")
        axes[0, k].set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}", loc="left")
        axes[1, k].set_xlabel("t (s)")
    return _finish(fig, spec.id, caption, spec.title)


def _differences(spec, datasets, caption):
    """Fig. 10: I_A − I_B (top) and I_D − I_C (bottom), corners sliding on the same surface; a column
    per panel."""
    fig, axes = _figure((12, 7), 2, len(spec.panels), sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        t = ds["t"].values
        for row, (a, b) in enumerate((("A", "B"), ("D", "C"))):
            ax, diff = axes[row, k], 1e6 * (ds[f"I_{a}"] - ds[f"I_{b}"]).values
            ax.plot(t, diff, color=CORNER_STYLE[a]["color"], lw=1.4, label=f"{I_LABEL[a]} − {I_LABEL[b]}")
            ax.axhline(0, color="0.6", lw=0.6)
            ax.set_ylabel(f"{I_LABEL[a]} − {I_LABEL[b]} (µm)")
            ax.ticklabel_format(axis="y", style="plain", useOffset=False)
            _headroom(ax)
            ax.legend(fontsize=8, loc="upper right")
            _cyclic_inset(ax, t, diff, CORNER_STYLE[a]["color"])
        axes[0, k].set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}", loc="left")
        axes[1, k].set_xlabel("t (s)")
    return _finish(fig, spec.id, caption, spec.title)


def _cyclic_inset(ax, t, values, colour):
    """Inset without the first two steps when their transient dwarfs the cyclic trend."""
    if values.size < 4 or np.nanmax(np.abs(values[:2])) < 5 * np.nanmax(np.abs(values[2:])):
        return
    ins = ax.inset_axes([0.2, 0.06, 0.78, 0.42])
    ins.plot(t[2:], values[2:], color=colour, lw=1.0)
    ins.axhline(0, color="0.6", lw=0.6)
    ins.ticklabel_format(axis="y", style="plain", useOffset=False)
    ins.tick_params(labelsize=7)
    ins.set_title(f"from t = {t[2]:g} s, without the first-step transient (µm)", fontsize=8, pad=2)


def _global_coordinates(spec, datasets, caption):
    """Figs. 11, 12: X_g, dX_g/dt; theta2, rise; initial and final configurations (one panel)."""
    panel, ds = spec.panels[0], datasets[0]
    g = geometry_from_attrs(ds.attrs)
    shapes = _shapes(g)
    t = ds["t"].values
    fig, axes = _figure((13, 8.6), 2, 2, height_ratios=(1, 0.95))
    ax = axes[0, 0]
    ax.plot(t, 100 * ds["Xg"].values, color="k", lw=1.6, label="$X_g$")
    ax.set_ylabel("$X_g$ (cm)")
    tw = _twin(ax, "tab:purple", r"$\dot X_g$ (cm/s)")
    tw.plot(t, 100 * ds["Xg_dot"].values, color="tab:purple", ls="--", lw=1.2, label=r"$\dot X_g$")
    _headroom(ax, tw)
    _legend(ax, tw, loc="upper center", ncols=2)
    ax.set_title(f"(a) imposed ground motion, {_case_label(panel)}", loc="left")
    ax = axes[0, 1]
    ax.plot(t, ds["theta2"].values, color="tab:blue", lw=1.6, label=r"$\theta^2$")
    ax.set_ylabel(r"$\theta^2$ (°)", color="tab:blue")
    tw = _twin(ax, "tab:brown", r"$R_y^3$ rise above rest (cm)")
    tw.plot(t, 100 * ds["rise"].values, color="tab:brown", ls="--", lw=1.4, label=r"$R_y^3$ rise")
    _headroom(ax, tw)
    _legend(ax, tw, loc="upper center", ncols=2)
    ax.set_title("(b) pad rotation and upper-plate rise", loc="left")
    for ax in axes[0]:
        ax.set_xlabel("t (s)")
    points = []
    for k, (n, name) in enumerate(((0, "initial"), (-1, "final"))):
        ax, q = axes[1, k], _q(ds.isel(t=n))
        points.append(_device(ax, g, q, shapes, corners=True))
        ax.set_title(f"({'cd'[k]}) {name} configuration, t = {t[n]:.2f} s: $X_g$ = {100 * q['Rx1']:.1f} cm, "
                     f"$\\theta^2$ = {q['theta2']:.2f}°, rise = {100 * float(ds['rise'][n]):.2f} cm",
                     loc="left", fontsize=10)
    for ax in axes[1]:  # same limits: both drawings at the same scale
        _frame(ax, np.vstack(points))
    return _finish(fig, spec.id, caption, spec.title)


def _interpenetration(spec, datasets, caption):
    """Fig. 17: interpenetration histories at the four corners; panels fill the rows of a
    two-column grid."""
    n = len(spec.panels)
    nrows, ncols = _grid(n, cols=2)
    fig, axes = _figure((13, 4.25 * nrows), nrows, ncols, sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ax = axes[k // ncols, k % ncols]
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        _corners(ax, ds["t"].values, ds, CORNERS, factor, unit)
        ax.set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}", loc="left")
    for k in range(max(0, n - ncols), n):  # the lowest panel of each column
        axes[k // ncols, k % ncols].set_xlabel("t (s)")
        if k // ncols < nrows - 1:
            axes[k // ncols, k % ncols].xaxis.set_tick_params(labelbottom=True)
    _drop_unused(axes, n)
    return _finish(fig, spec.id, caption, spec.title)


def _sticking(spec, datasets, caption):
    """Figs. 18, 19: theta2 and R_y^3 at the end of each step and of each sticking phase, zoomed on
    the step ending nearest the panel's t (one stick-slip panel)."""
    panel, ds = spec.panels[0], datasets[0]
    t = ds["t"].values
    mid = 0.5 * (t[1:] + t[:-1])
    rest = ds["Ry3"].values - ds["rise"].values
    series = {"theta2": (ds["theta2"].values, ds["theta2_stick"].values, r"$\theta^2$ (°)"),
              "rise": (100 * ds["rise"].values, 100 * (ds["Ry3_stick"].values - rest), r"$R_y^3$ rise (cm)")}
    n = max(1, int(np.abs(t - panel.t).argmin()))
    half = 6.5 * (t[n] - t[n - 1])
    fig = _figure((13, 10), None)
    axd = fig.subplot_mosaic([["a", "b"], ["c", "d"], ["e", "e"]], width_ratios=(2.6, 1))
    for (main, zoom), (end, stick, label) in zip((("a", "b"), ("c", "d")), series.values()):
        tt, vv = _step_path(t, end, stick)
        for ax in (axd[main], axd[zoom]):
            ax.plot(tt, vv, color="tab:red", lw=0.6, alpha=0.6, label="path through the end of sticking")
            ax.plot(t, end, color="k", lw=1.5, label="end of step")
            ax.set_ylabel(label)
            ax.set_xlabel("t (s)")
        axd[zoom].plot(mid, stick[1:], "o", color="tab:red", ms=3)
        axd[zoom].plot(t, end, "s", color="k", ms=3)
        sel = (tt > t[n] - half) & (tt < t[n] + half)
        lo, hi = np.nanmin(vv[sel]), np.nanmax(vv[sel])
        axd[zoom].set_xlim(t[n] - half, t[n] + half)
        axd[zoom].set_ylim(lo - 0.08 * (hi - lo), hi + 0.08 * (hi - lo))
        axd[zoom].xaxis.set_major_locator(MaxNLocator(4))
        axd[main].axvspan(t[n] - half, t[n] + half, color="gold", alpha=0.5, lw=0)
        axd[main].legend(fontsize=8, loc="lower right", bbox_to_anchor=(1, 1), ncols=2, borderaxespad=0.2)
    axd["a"].set_title(f"(a) pad rotation, {_case_label(panel)}", loc="left")
    axd["c"].set_title("(c) rise of the upper plate RB3", loc="left")
    for z, m in (("b", "a"), ("d", "c")):
        axd[z].set_title(f"({z}) zoom of ({m}), step ending at t = {t[n]:.3g} s", loc="left", fontsize=10)
    ax = axd["e"]
    stick_rotation = ds["theta2_stick"].values[1:] - ds["theta2"].values[:-1]
    ax.plot(mid, stick_rotation, color="tab:red", lw=1.2, label=r"$\theta^2_{stick}(t_n) - \theta^2(t_{n-1})$")
    ax.set_ylabel(r"$\Delta\theta^2$ in sticking (°)", color="tab:red")
    ax.set_xlabel("t (s)")
    tw = _twin(ax, "tab:purple", r"$\dot X_g$ (cm/s)")
    tw.plot(t, 100 * ds["Xg_dot"].values, color="tab:purple", ls="--", lw=1.0, label=r"$\dot X_g$")
    _legend(ax, tw, loc="lower right", bbox_to_anchor=(1, 1), ncols=2, borderaxespad=0.2)
    ax.set_title(f"(e) sticking rotation of the pad (max |Δθ²| = {np.nanmax(np.abs(stick_rotation)):.2f}°) "
                 "and ground velocity", loc="left")
    return _finish(fig, spec.id, caption, spec.title)


def _two_phase(spec, datasets, caption):
    """Fig. 20: configurations at the start of the step ending nearest each panel's t, at the end of
    its sticking phase and at the end of its slipping phase; stick-slip panels side by side."""
    fig, axes = _figure((13, 5.9), 1, len(spec.panels))
    styles = (("0.45", "--"), ("tab:red", "-"), ("tab:blue", "-."))
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ax = axes[0, k]
        g = geometry_from_attrs(ds.attrs)
        shapes = _shapes(g)
        n = max(1, int(np.abs(ds["t"].values - panel.t).argmin()))
        now = ds.isel(t=n)
        configs = ((_q(ds.isel(t=n - 1)), "(1) start of step"), (_q(now, "_stick"), "(2) end of sticking"),
                   (_q(now), "(3) end of slipping"))
        points = []
        for (q, name), (colour, ls) in zip(configs, styles):
            label = f"{name}: $\\theta^2$ = {q['theta2']:.2f}°"
            points.append(_device(ax, g, q, shapes, fill=False, colour=colour, ls=ls, label=label, lw=1.1,
                                  corners=name.startswith("(2)")))
        _frame(ax, np.vstack(points))
        diagonal = ("$A^2D^2$", "$B^2C^2$")[int(now["sticking_diagonal"])]
        ax.set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}, step ending at t = {float(now['t']):.3f} s,\n"
                     f"$\\dot X_g$ = {100 * float(now['Xg_dot']):.2f} cm/s, sticking diagonal {diagonal}", loc="left")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), handlelength=3.5)
    return _finish(fig, spec.id, caption, spec.title)


# --- the registry of figure kinds -------------------------------------------------------------
MODELS = ("compliant", "stick_slip")


@dataclass(frozen=True)
class Kind:
    """How a kind of figure is drawn.

    Attributes
    ----------
    draw : (FigureSpec, one dataset per panel, caption line) -> Figure.
    data : the datasets it draws, "cases" (time histories) or "breakaway" (sweeps).
    panels : (fewest, most) panels it lays out.
    needs : panel keys it needs besides those naming the dataset ("t", "theta2_0").
    models : models whose time histories it can draw.
    """

    draw: Callable[[FigureSpec, Sequence, str], Figure]
    data: str
    panels: tuple[int, int]
    needs: tuple[str, ...] = ()
    models: tuple[str, ...] = MODELS


KINDS: dict[str, Kind] = {
    "breakaway": Kind(_breakaway, "breakaway", (1, 6)),
    "breakaway_configurations": Kind(_breakaway_configurations, "breakaway", (1, 3), ("theta2_0",)),
    "diagonals": Kind(_diagonals, "cases", (1, 4)),
    "differences": Kind(_differences, "cases", (1, 4)),
    "global_coordinates": Kind(_global_coordinates, "cases", (1, 1)),
    "interpenetration": Kind(_interpenetration, "cases", (1, 6)),
    "sticking": Kind(_sticking, "cases", (1, 1), ("t",), ("stick_slip",)),
    "two_phase": Kind(_two_phase, "cases", (1, 3), ("t",), ("stick_slip",)),
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


def render(spec: FigureSpec, datasets: Sequence, caption: str) -> Figure:
    """Draw one figure.

    Parameters
    ----------
    spec : the figure (see ``figure_spec``).
    datasets : one dataset per panel, in the order of ``spec.panels``: a time history, or a
        breakaway sweep (with or without a ``dXg`` dimension).
    caption : line printed at the bottom (e.g. the case set).

    Returns
    -------
    matplotlib.figure.Figure (no pyplot: freed when unreferenced).
    """
    if len(datasets) != len(spec.panels):
        raise ValueError(f"{spec.id} draws {len(spec.panels)} panel(s), got {len(datasets)} dataset(s)")
    return KINDS[spec.kind].draw(spec, list(datasets), caption)
