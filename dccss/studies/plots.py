"""Standard plots of a study: summaries over the sweep axes and time histories of chosen points.

``maps`` draws the combined study dataset (dimension ``model`` plus one per sweep axis):

* two or more numeric axes: maps over the first two, one row per model (and per category of a further
  categorical axis; a suite's mean and largest over its records in place of a row per record), the
  cells where the pad reached a retaining ring hatched, and those where the solver failed where the
  summary has no value; further numeric axes at their first value;
* one numeric axis: curves with markers, one per model (and per category of ``prototype``);
* a categorical axis only (``prototype``): one mark per model and category at integer positions.

Their panels, a map per model and summary or a panel of curves per summary, go on as many rows as keep
the figure at most MAX_INCHES wide.

``histories`` draws, for each history point, the ground displacement, θ², the rise of RB3 and
the largest corner interpenetration against time, one column per point, with the times at which
the pad reached a retaining ring or the solver failed; with a structure, the stroke beside the
ground displacement and a last row with the device's force-displacement loop (F/W against u).

The datasets are SI (angles in degrees); the plots are in paper units: degrees, cm, mm.
"""

from __future__ import annotations

import re
import textwrap

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.collections import LineCollection, PatchCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle
from matplotlib.ticker import NullLocator
from matplotlib.transforms import ScaledTranslation

from ..drawing import caption_line, friction_loop, new_figure
from ..mechanics.models import REGISTRY
from ..mechanics.structure import G
from ..mechanics.summaries import model_specific
from ..results import MODEL_TITLES, failure_of, friction_text, has_structure
from .spec import layout

#: how a model is drawn: its registry entry's ``line`` and ``marker``, else one of these
OTHER_LINES = (dict(color="tab:green", ls="-.", lw=1.8, zorder=4), dict(color="tab:purple", ls=":", lw=1.8, zorder=5))
#: one per group of a map (a record of a suite: codes ask for 7 to 11); the first six as before
GROUP_MARKERS = ("o", "s", "^", "v", "P", "*", "D", "<", ">", "h", "p", "d")  # no "X": a failure's mark
CAPACITY_COLOUR, FAILED_COLOUR = "crimson", "0.25"
EVENT_LINE = {"capacity": dict(ls=(0, (1, 1.5)), lw=1.6), "failure": dict(ls=(0, (6, 2, 1, 2)), lw=1.6)}
LOG_AXES = ("dt",)
MAX_VALUE_TICKS = 8  # a swept axis with at most this many values is ticked at its values
POINTS_PER_ROW = 3  # history points side by side; more go to a block below
COLUMN_INCHES = 3.9  # width of a history point's column
MAX_INCHES = 16.0  # a summaries figure's panels go on as many rows as keep it this wide at most
LINE_INCHES = (4.0, 3.4)  # width and height of a panel of curves
MAP_INCHES = (4.4, 3.2)  # width (with its colour bar: its title's first line fits) and height of a map
MAP_MARGIN = 0.6  # the maps figure's margin beside its maps (inches)
FAILURE_SPACING = 10.0  # points between the failure marks of different curves at one x
ROTATE_FROM, SMALL_FROM = 8, 16  # categories beyond which their tick labels stand upright, then get smaller
CATEGORY_INCHES = 0.2  # a panel's width per category beyond ROTATE_FROM of them (a suite's records)

#: (summary variable, label, factor to plot units, plot unit)
SUMMARY_VARIABLES = [
    ("theta2_max_abs", "max |θ²|", 1.0, "°"),
    ("sticking_rotation_max", "max sticking rotation", 1.0, "°"),
    ("rise_max", "max rise of RB3", 100.0, "cm"),
    ("interpenetration_max", "max interpenetration (corners)", 1e3, "mm"),
    ("stroke_max_abs", "max |stroke u| of the structure", 100.0, "cm"),
    ("shear_ratio_max_abs", "max |F/W| of the device", 1.0, "-"),
    ("stroke_1_max_abs", "max $|u_1|$ on the lower surface", 100.0, "cm"),
    ("stroke_3_max_abs", "max $|u_3|$ on the upper surface", 100.0, "cm"),
    ("hinge_rotation_max_abs", "max hinge rotation", 1.0, "°"),
]
STROKE_COLOUR = "tab:purple"
#: how the suite statistics over the records are drawn, and their legend
#: a suite's statistics over its record curves (which are drawn faded, SUITE_RECORDS): the mean in its model's
#: line made wider, the 84th percentile dotted
SUITE_LINES = {"mean": dict(lw=3.4, zorder=8), "p84_lognormal": dict(lw=1.6, ls=(0, (1, 1.2)), zorder=8)}
SUITE_RECORDS = dict(alpha=0.4)
SUITE_WIDER = 1.4  # points added to the model's line width for the mean
SUITE_LABELS = {"mean": "mean over the records", "p84_lognormal": "84th percentile over the records (lognormal)"}
#: (history variable, label, factor to plot units, plot unit)
HISTORY_ROWS = [
    ("Xg", "ground displacement $X_g$", 100.0, "cm"),
    ("theta2", "pad rotation θ²", 1.0, "°"),
    ("rise", "rise of RB3", 100.0, "cm"),
    ("interpenetration", "max $|I|$ of the corners", 1e3, "mm"),
]
AXIS_SYMBOLS = {"record": "record", "amplitude": "$X_{g,max}$", "omega": "ω", "scale": "scale of $X_g$",
                "theta2_0": "$θ^2(t_0)$", "dt": "Δt", "prototype": "prototype", "azimuth": "azimuth of $X_g$",
                "rotation": "rotation of the pair", "component": "component of $X_g$", "friction": "friction μ",
                "damping": "damping ζ", "slider": "slider", "intensity": "intensity"}
GEOMETRY_SYMBOLS = {"alpha": r"\alpha", "hmin": "h_{min}", "hr": "h_r", "tr": "t_r"}
UNIT_TEXT = {"degree": "°", "rad s-1": "rad/s", "1": "", "s": "s", "m": "m"}


# --- styles and labels -------------------------------------------------------------------------
def _styled(model):
    return model in REGISTRY and bool(REGISTRY[model].line)


def ordered_models(models):
    """Model names in a fixed order: the registry's, then any other by name."""
    known = [m for m in REGISTRY if m in models]
    return known + sorted(m for m in models if m not in REGISTRY)


def model_line(model, models):
    """Colour, line style and width of a model (the same in every panel and figure)."""
    if _styled(model):
        return REGISTRY[model].line
    others = [m for m in models if not _styled(m)]
    return OTHER_LINES[others.index(model) % len(OTHER_LINES)]


def _marker(model):
    entry = REGISTRY.get(model)
    return entry.marker if entry is not None and entry.marker else dict(marker="s", ms=5, mew=0.8)


def model_title(model):
    return MODEL_TITLES.get(model, model)


def _symbol(name):
    """The paper's symbol of a sweep axis (e.g. alpha21 -> α²¹); the name itself if it has none."""
    if name in AXIS_SYMBOLS:
        return AXIS_SYMBOLS[name]
    match = re.fullmatch(r"(alpha|hmin|hr|tr|h|R)(\d+)", name)
    if match:
        return f"${GEOMETRY_SYMBOLS.get(match[1], match[1])}^{{{match[2]}}}$"
    return name


def _axis_unit(ds, name):
    """(factor to plot units, unit) of a sweep axis: its units, a ground amplitude in cm."""
    units = ds[name].attrs.get("units")
    if name == "amplitude" and units == "m":
        return 100.0, "cm"
    return 1.0, UNIT_TEXT.get(units, units or "")


def _axis_label(ds, name):
    if "label" in ds[name].attrs:  # an intensity axis: its measure and unit
        return ds[name].attrs["label"]
    unit = _axis_unit(ds, name)[1]
    symbol = _symbol(name)
    if name == "friction" and ds.attrs.get("structure_friction_on") == "surfaces":
        symbol = "friction $μ_s$ of each surface"
    return f"{symbol} ({unit})" if unit else symbol


def _value_text(ds, name, value):
    """'α²¹ = 10°', 'h² = 0.15 m', 'prototype = DFP1'."""
    if _categorical(ds, name):
        return f"{_symbol(name)} = {value}"
    factor, unit = _axis_unit(ds, name)
    space = "" if unit in ("", "°") else " "
    return f"{_symbol(name)} = {factor * float(value):.4g}{space}{unit}"


def _legend_rows(groups, width):
    """Groups of legend handles as rows of a table (one line if they all fit in ``width`` inches): a group
    too long for one line goes on as many as it needs, rows of at most as many entries as let the table,
    whose columns are as wide as their widest entry, fit."""
    def size(h):
        return 0.6 + 0.065 * len(h.get_label())

    def fits(row):
        return sum(size(h) for h in row) < 0.95 * width

    handles = [h for group in groups for h in group]
    if fits(handles):
        return [handles]
    for most in range(max(len(group) for group in groups), 0, -1):
        rows = []
        for group in groups:
            line = []
            for h in group:
                if line and (len(line) == most or not fits(line + [h])):
                    rows.append(line)
                    line = []
                line.append(h)
            if line:
                rows.append(line)
        columns = max(len(row) for row in rows)
        if sum(max(size(row[c]) for row in rows if c < len(row)) for c in range(columns)) < 0.95 * width:
            break
    return rows


def complete(fig, title, caption, groups):
    """The title over a legend at the top (a row per group of handles if one line is too long), the
    caption line at the bottom (laid out once and frozen when saved: ``drawing.save``)."""
    rows = _legend_rows(groups, fig.get_figwidth())
    ncols = max(1, *(len(row) for row in rows))
    blank = Line2D([], [], ls="none", label=" ")
    table = [row + [blank] * (ncols - len(row)) for row in rows]
    by_columns = [row[c] for c in range(ncols) for row in table]  # the legend fills its columns first
    fig.legend(handles=by_columns, loc="outside upper center", ncols=ncols, fontsize=9, frameon=False, title=title,
               title_fontsize=12)
    caption_line(fig, caption)
    return fig


# --- a suite scaled to a spectrum ---------------------------------------------------------------
def spectra(ds, caption: str) -> Figure:
    """A suite scaled over a period range: each record's spectrum as scaled, their mean and the target
    (and the fraction of it the mean must reach), in g, over the range's periods."""
    how = ds["record_sa"].attrs
    period, fraction = ds["spectrum_period"].values, float(how["scaling_fraction"])
    fig, axs = new_figure((9.6, 4.8))
    ax = axs[0, 0]
    records = [str(r) for r in ds["record"].values]
    colours = colormaps["tab10" if len(records) <= 10 else "tab20"].colors
    for i, (name, label) in enumerate(zip(records, _shortened(records))):
        ax.plot(period, ds["record_sa"].sel(record=name).values / G, lw=1.0, color=colours[i % len(colours)],
                marker=GROUP_MARKERS[i % len(GROUP_MARKERS)], ms=4, markevery=max(1, len(period) // 8), label=label)
    mean = ds["record_sa"].mean("record").values / G
    target = ds["target_sa"].values / G
    ax.plot(period, mean, color="black", lw=2.6, label="mean over the records", zorder=5)
    ax.plot(period, target, color="tab:red", lw=1.8, label="target", zorder=6)
    if fraction != 1.0:
        ax.plot(period, fraction * target, color="tab:red", lw=1.4, ls=(0, (4, 2)), label=f"{fraction:g} × target",
                zorder=6)
    worst = int(np.argmin(mean / (fraction * target)))
    ax.plot(period[worst], mean[worst], ls="none", marker="o", ms=9, mfc="none", mec="black", mew=1.4, zorder=7,
            clip_on=False, label=f"closest to {'the target' if fraction == 1.0 else f'{fraction:g} × target'}: "
                  f"T = {period[worst]:.3g} s")
    ax.set_xlim(period[0], period[-1])
    ax.set_ylim(0, None)
    ax.set_xlabel("period T (s)")
    names = {"rotd50": "RotD50", "rotd100": "RotD100", "geometric_mean": "geometric mean"}
    definition = f", {names[how['scaling_definition']]}" if "scaling_definition" in how else ""
    ax.set_ylabel(f"spectral acceleration Sa (g; {100 * float(how['scaling_damping']):g} % damping{definition})")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncols=2 if len(records) > 12 else 1, loc="upper left", bbox_to_anchor=(1.01, 1.0),
              borderaxespad=0.0)
    low, high = (float(v) for v in how["scaling_periods_s"])
    what = "record pairs" if ds.attrs.get("excitation_components") == 2 else "records"
    title = (f"{len(records)} {what} scaled over {low:g}–{high:g} s: their mean at or above "
             f"{'the target' if fraction == 1.0 else f'{fraction:g} × target'} (suite factor "
             f"{float(how['scaling_suite_factor']):.3g})")
    fig.suptitle(title, fontsize=11)
    caption_line(fig, caption)
    return fig


# --- time histories ------------------------------------------------------------------------------
def histories(points: list, caption: str) -> Figure:
    """Time histories of the history points of a study, one column per point.

    Parameters
    ----------
    points : list of (label, {model: dataset}); each dataset a history of ``dccss.simulate``
        (time coordinate ``t`` in s), possibly cut short by the capacity policy or a solver failure.
    caption : line printed at the bottom of the figure.

    Returns
    -------
    matplotlib.figure.Figure
        Per point a column of four panels sharing the time axis: ground displacement X_g (cm),
        θ² (°), rise of RB3 (cm), largest |I| of the corners (mm); up to three columns side by
        side, further points in a second block below. The models are told apart by colour and
        line style; dotted and dash-dotted vertical lines mark where the pad reached a retaining
        ring and where the solver failed, and the column title says so (and whether the capacity
        policy cut the history).
    """
    if not points:
        raise ValueError("histories: no history points to draw")
    models = ordered_models({m for _, runs in points for m in runs})
    structure = any(has_structure(ds) for _, runs in points for ds in runs.values())
    rows, ncols = len(HISTORY_ROWS) + structure, min(len(points), POINTS_PER_ROW)
    blocks = -(-len(points) // POINTS_PER_ROW)
    fig, axs = new_figure((max(7.5, 1.2 + COLUMN_INCHES * ncols), 1.4 + 8.6 * blocks * rows / len(HISTORY_ROWS)),
                          rows * blocks, ncols)
    events = set()
    for k, ((label, runs), col) in enumerate(zip(points, _panels(axs, len(points), rows))):
        _share_time(col, ylabels=k % POINTS_PER_ROW == 0, spatial=any(_bidirectional(ds) for ds in runs.values()))
        events |= _history_column(col, f"({_letter(k)}) {label}", runs, models)
    two = any(_bidirectional(ds) for _, runs in points for ds in runs.values())
    lines = [Line2D([], [], color="k", lw=1.2, label="$X_g$, imposed ground motion")]
    if two:
        lines = [Line2D([], [], color="k", lw=1.2, label="$X_{g,x}$"),
                 Line2D([], [], color="k", lw=1.2, ls="--", label="$X_{g,y}$")]
    if structure:
        lines[0].set_label(lines[0].get_label().replace(", imposed ground motion", ", ground"))
        lines += [Line2D([], [], color=STROKE_COLOUR, lw=1.2, label="$u_x$, stroke" if two else "$u$, stroke")]
        if two:
            lines.append(Line2D([], [], color=STROKE_COLOUR, lw=1.2, ls="--", label="$u_y$"))
    lines += [Line2D([], [], **model_line(m, models), label=model_title(m)) for m in models]
    return complete(fig, "Time histories at the study's history points", caption, [lines, _event_handles(events)])


def _share_time(col, ylabels, spatial=False):
    """One time axis for the panels of a point, labelled at the bottom; quantities on the left (the
    tilt for θ² under bidirectional motion). A structure's loop, below them, has axes of its own."""
    timed = col[:len(HISTORY_ROWS)]
    for ax in timed[1:]:
        ax.sharex(timed[0])
    for ax in timed[:-1]:
        ax.tick_params(labelbottom=False)
    timed[-1].set_xlabel("t (s)")
    if ylabels:
        for ax, (key, name, _, unit) in zip(timed, HISTORY_ROWS):
            ax.set_ylabel(f"{'tilt of the pad' if spatial and key == 'theta2' else name} ({unit})")
        if len(col) > len(HISTORY_ROWS):
            col[-1].set_ylabel("device force F/W (-)")


def _panels(axs, n, rows):
    """The columns of ``rows`` axes of ``n`` panels laid out in blocks of ``rows`` rows of ``axs``, one block
    below the other; the places the last block leaves empty are hidden."""
    ncols = axs.shape[1]
    columns = [axs[rows * (k // ncols):rows * (k // ncols + 1), k % ncols] for k in range(axs.shape[0] // rows * ncols)]
    for ax in (ax for column in columns[n:] for ax in column):
        ax.set_visible(False)
    return columns[:n]


def _grid_shape(n, width, margin=0.0):
    """(blocks, columns) of ``n`` panels ``width`` inches wide beside ``margin`` inches: as few blocks, one
    below the other, as keep the figure at most MAX_INCHES wide, the panels shared evenly between them."""
    blocks = -(-n // max(1, int((MAX_INCHES - margin) // width)))
    return blocks, -(-n // blocks)


def _grid(n, inches, rows=1, margin=0.0):
    """A figure of ``n`` panels, each a column of ``rows`` axes of ``inches`` (width, height), beside ``margin``
    inches, in blocks (``_grid_shape``), with room for a title and legend above; the figure and the
    panels' columns."""
    blocks, ncols = _grid_shape(n, inches[0], margin)
    fig, axs = new_figure((inches[0] * ncols + margin, inches[1] * rows * blocks + 1.6), rows * blocks, ncols)
    return fig, _panels(axs, n, rows)


def _letter(k):
    return "abcdefghijklmnopqrstuvwxyz"[k % 26]


def _history_column(col, label, runs, models):
    """Draw one history point in a column of axes; return the kinds of events drawn."""
    ground = max(runs.values(), key=lambda ds: ds.sizes["t"])
    if _bidirectional(ground):  # x solid, y dashed
        for name, ls in (("Xg_x", "-"), ("Xg_y", "--")):
            col[0].plot(ground["t"].values, HISTORY_ROWS[0][2] * ground[name].values, color="k", lw=1.2, ls=ls)
    else:
        col[0].plot(ground["t"].values, HISTORY_ROWS[0][2] * ground["Xg"].values, color="k", lw=1.2)
    if has_structure(ground):
        _structure(col, ground)
    events, notes = set(), []
    # the ring tags of two models: the earlier one left of its line, the later one right of it (tags on
    # the sides facing each other covered one another); a failure's tag left of its line
    rings = sorted((time, slot) for slot, model in enumerate(m for m in models if m in runs)
                   for kind, time, _ in _events(runs[model]) if kind == "capacity")
    right = {slot for _, slot in rings[1::2]}
    for slot, model in enumerate(m for m in models if m in runs):
        ds, style = runs[model], model_line(model, models)
        t = ds["t"].values
        for ax, (name, _, factor, _) in zip(col[1:], HISTORY_ROWS[1:]):
            ax.plot(t, factor * _history_values(ds, name), **style)
        for kind, time, tag in _events(ds):
            events.add(kind)
            for ax in col[:len(HISTORY_ROWS)]:  # as wide as the model's curve: coinciding lines stay visible
                ax.axvline(time, color=style["color"], zorder=style["zorder"] + 3,
                           **{**EVENT_LINE[kind], "lw": 0.8 * style["lw"]})
            side = 1 if slot in right and kind == "capacity" else -1
            col[0].annotate(tag, (time, 0.97), xycoords=("data", "axes fraction"), rotation=90,
                            ha="left" if side > 0 else "right", va="top", fontsize=7, color=style["color"],
                            xytext=(2 * side, 0), textcoords="offset points",
                            bbox=dict(fc="w", ec="none", alpha=0.8, pad=0.5))
        notes += _notes(ds, model)
    for ax in col:
        ax.grid(True, color="0.9", lw=0.6)
        ax.axhline(0, color="0.6", lw=0.6, zorder=1)
    for ax in col[len(HISTORY_ROWS):]:
        ax.axvline(0, color="0.6", lw=0.6, zorder=1)
    wrapped = [textwrap.fill(note, width=int(15 * COLUMN_INCHES), subsequent_indent="  ") for note in notes]
    label = textwrap.fill(label, width=int(11 * COLUMN_INCHES), subsequent_indent="  ", break_on_hyphens=False)
    col[0].set_title("\n".join([label, *wrapped]), loc="left", fontsize=9)
    return events


def _bidirectional(ds):
    return ds.attrs.get("motion") == "bidirectional"


def _structure(col, ds):
    """The stroke beside the ground displacement (top panel) and the loop F/W against u (last panel):
    x solid, y dashed. The structure is the models' common input: drawn once."""
    t, factor = ds["t"].values, HISTORY_ROWS[0][2]
    if col[0].get_ylabel():
        col[0].set_ylabel(f"ground $X_g$, stroke $u$ ({HISTORY_ROWS[0][3]})")
    parts = (("_x", "-"), ("_y", "--")) if _bidirectional(ds) else (("", "-"),)
    for suffix, ls in parts:
        col[0].plot(t, factor * ds[f"stroke{suffix}"].values, color=STROKE_COLOUR, lw=1.2, ls=ls)
        if "friction_coefficient" in ds:  # a friction law: the loop coloured by μ (its range in the title)
            friction_loop(col[-1], factor * ds[f"stroke{suffix}"].values, ds[f"shear_ratio{suffix}"].values,
                          ds["friction_coefficient"].values, ls)
        else:
            col[-1].plot(factor * ds[f"stroke{suffix}"].values, ds[f"shear_ratio{suffix}"].values,
                         color=STROKE_COLOUR, lw=0.9, ls=ls)
    col[-1].set_xlabel("stroke u (cm)")
    mu = ds["friction_coefficient"].values if "friction_coefficient" in ds else None
    coloured = "" if mu is None else f"\nloop coloured by μ, {np.min(mu):.3g} (violet) to {np.max(mu):.3g} (yellow)"
    col[-1].set_title(f"{friction_text(ds.attrs)}, ζ = {ds.attrs['structure_damping']:g}, "
                      f"T = {ds.attrs['structure_period_s']:.3g} s{coloured}", fontsize=8, loc="left")


def _history_values(ds, name):
    """A history row's values in SI units; "interpenetration" is the largest |I| of the corners A..D
    (of the rim points of each step's section, bidirectional); θ² of a bidirectional history is its
    tilt."""
    if ds.attrs.get("model") == "articulated":  # its halves: the lower one's rotation, RB3's rise, no interpenetration
        two = _bidirectional(ds)
        theta = [np.radians(ds[f"tilt_{j}" if two else f"theta_{j}"].values) for j in (1, 3)]
        lengths = (ds.attrs["pendulum_length_1_m"], ds.attrs["pendulum_length_3_m"])
        return {"theta2": np.degrees(theta[0]), "Xg": ds[name].values if name in ds else np.nan,
                "rise": sum(L * (1.0 - np.cos(th)) for L, th in zip(lengths, theta)),
                "interpenetration": np.full(ds.sizes["t"], np.nan)}[name]
    if name == "interpenetration":
        names = [v for v in ds.data_vars if v.startswith("I_") and not v.endswith("_stick")]
        return np.max(np.abs([ds[v].values for v in names]), axis=0)
    if name == "theta2" and _bidirectional(ds):
        return ds["tilt"].values
    return ds[name].values


def _failed(ds):
    if "failed" in ds.attrs:
        return bool(int(ds.attrs["failed"]))
    return "failed" in ds and bool(np.any(ds["failed"].values))


def _stop_time(ds):
    """Time at which the capacity policy 'stop' cut the history (None if it was not cut)."""
    if "stopped_at_s" in ds.attrs:
        return float(ds.attrs["stopped_at_s"])
    if str(ds.attrs.get("capacity_policy", "")).startswith("stopped"):
        return float(ds["t"].values[-1])
    return None


def _events(ds):
    """(kind, time, short text) of the capacity exceedance and of the solver failure of a history."""
    out = []
    if "capacity_exceeded_at_s" in ds.attrs:
        out.append(("capacity", float(ds.attrs["capacity_exceeded_at_s"]),
                    f"{ds.attrs.get('capacity_exceeded_plate', '')} ring".strip()))
    if _failed(ds) and failure_of(ds.attrs) != "capacity":  # capacity "error": the ring's event ended it
        out.append(("failure", float(ds.attrs.get("failure_time_s", ds["t"].values[-1])), "failed"))
    return out


def _notes(ds, model):
    """The events of a history in one line (empty if none), for the column title."""
    parts = []
    if ds.attrs.get("model") == "articulated":
        parts.append(f"articulated: θ² is the lower half's, hinge up to "
                     f"{float(np.max(np.abs(ds['hinge_rotation'].values))):.2f}°")
        for j in (1, 3):
            if f"ring_{j}_reached_at_s" in ds.attrs:
                parts.append(f"surface {j}'s ring reached at {float(ds.attrs[f'ring_{j}_reached_at_s']):.4g} s")
    if "capacity_exceeded_at_s" in ds.attrs:
        reached = float(ds.attrs["capacity_exceeded_at_s"])
        text = f"{ds.attrs.get('capacity_exceeded_plate', 'a')} ring reached at {reached:.4g} s"
        if "capacity_exceeded_by_m" in ds.attrs:
            text += f" (up to {100.0 * float(ds.attrs['capacity_exceeded_by_m']):.2g} cm beyond)"
        parts.append(text)
    stop = _stop_time(ds)
    if stop is not None:
        parts.append(f"history cut at {stop:.4g} s (capacity policy 'stop')")
    if _failed(ds) and failure_of(ds.attrs) == "capacity":
        parts.append("history ended there, marked failed (capacity policy 'error')")
    elif _failed(ds):
        time = float(ds.attrs.get("failure_time_s", ds["t"].values[-1]))
        message = _failure_reason(str(ds.attrs.get("failure_message", "")))
        parts.append(f"solver failed at {time:.4g} s" + (f": {message}" if message else ""))
    return [f"{model_title(model)}: " + "; ".join(parts)] if parts else []


def _failure_reason(message):
    """The sentence of a solver message that says what did not converge, shortened to 90 characters."""
    sentences = re.split(r"(?<=\.)\s+", " ".join(message.split()))
    reason = next((s for s in sentences if "converge" in s), sentences[0])
    return textwrap.shorten(reason, 90, placeholder=" …") if reason else ""


def _event_handles(kinds):
    labels = {"capacity": "pad reaches a retaining ring", "failure": "solver failed (history ends)"}
    return [Line2D([], [], color="0.3", **EVENT_LINE[kind], label=labels[kind]) for kind in EVENT_LINE if kind in kinds]


# --- summaries over the sweep ---------------------------------------------------------------------
def maps(ds, marks: dict, caption: str) -> Figure:
    """Summaries of a study over its sweep axes.

    Parameters
    ----------
    ds : the combined study dataset: dimension ``model`` and one per sweep axis (attribute
        ``sweep_axes``, in order); summaries as written by ``Study.combine``.
    marks : {label: {axis: value}}, points to draw (values in the study file's units).
    caption : line printed at the bottom of the figure.

    Returns
    -------
    matplotlib.figure.Figure
        Two or more numeric axes of more than one value: maps over the first two (one row per
        model), with the cells where the pad reached a retaining ring hatched in red and the
        failed cells without a value hatched in grey; one numeric axis: curves with markers (one
        per model, and per category of a categorical axis), capacity points boxed in red, failed
        points marked ✕ on the bottom edge; a categorical axis only: marks per category at integer
        positions. Maps give a further categorical axis (a prototype) rows of its own; any other
        further axis is shown at its first value, as the title says. The panels go on as many rows
        as keep the figure at most MAX_INCHES wide.
    """
    ds = ds.assign(interpenetration_max=ds[[f"I_{c}_max" for c in "ABCD"]].to_array().max("variable"))
    kind, drawn, fixed = _plan(ds)
    records = ds.sizes.get("record", 0)
    if kind == "map" and fixed.get("record", 0) > 1 and "statistic" in ds.coords:  # a suite: its statistics
        ds = _suite_maps(ds)
        fixed = {"statistic": ds.sizes["statistic"], **{n: size for n, size in fixed.items() if n != "record"}}
    # maps: a further categorical axis (a prototype) gets rows of its own, one per category and model
    group = next((n for n, size in fixed.items() if kind == "map" and size > 1 and _categorical(ds, n)), None)
    if kind == "lines" and fixed.get("property", 0) > 1:  # curves: each friction bound drawn, by its marker
        group = "property"
    fixed = {n: size for n, size in fixed.items() if n != group}
    ds = ds.isel({name: 0 for name in fixed})
    ds = ds.sortby([name for name in drawn if not _categorical(ds, name)])
    models = ordered_models([str(m) for m in ds["model"].values])
    tilt = ds.attrs.get("excitation_components") == 2  # bidirectional: |θ²| is the pad axis's tilt
    variables = [(name, "max tilt of the pad" if tilt and name == "theta2_max_abs" else label, factor, unit)
                 for name, label, factor, unit in SUMMARY_VARIABLES
                 if name in ds and any(_defined(ds, name, m) for m in models)]
    if kind == "map":
        rows = [(m, {group: str(v)} if group else {}) for m in models for v in (ds[group].values if group else [0])]
        fig, columns = _grid(len(variables), MAP_INCHES, len(rows), MAP_MARGIN)
        legend = _draw_maps(fig, columns, ds, drawn, marks, variables, rows, models, group)
        what = f"maps over {_symbol(drawn[0])} and {_symbol(drawn[1])}" + (
            f": statistics over its {records} records" if group == "statistic" else
            f" per {_symbol(group)}" if group else "")
    else:
        inches = LINE_INCHES
        if kind == "categories" and ds.sizes[drawn[0]] > ROTATE_FROM:  # room for each category's label and marks
            inches = (max(LINE_INCHES[0], CATEGORY_INCHES * ds.sizes[drawn[0]] + 1.0), LINE_INCHES[1] + 0.6)
        fig, columns = _grid(len(variables), inches)
        if kind == "lines":
            legend = _draw_lines([column[0] for column in columns], ds, drawn, marks, variables, models,
                                 bounds=group == "property")
        else:
            legend = _draw_categories([column[0] for column in columns], ds, drawn, marks, variables, models)
        what = f"summaries against {_symbol(drawn[0])}" + (f" per {_symbol(drawn[1])}" if len(drawn) > 1 else "")
    title = f"Study {ds.attrs.get('study', '')}: {what}"
    if fixed:
        title += "\n" + _fixed_note(ds, fixed)
    return complete(fig, title, caption, legend)


#: how a summary's envelope over the friction's bounds is drawn (``combine.envelope``), and its legend
ENVELOPE_LOOK = {"ls": (0, (4, 2)), "lw": 0.9}
ENVELOPE_OVER = {"ls": (0, (3, 2)), "lw": 1.3, "color": "0.1"}  # over the bounds' curves, which it follows
ENVELOPE_LABEL = "largest over the friction's bounds: the design displacement and force (ASCE 7-22 17.2.8.4, EN 15129)"
#: the statistics a suite's maps draw, in place of its records (``_suite_maps``): the design values of
#: EN 1998-1 §4.3.3.4.3 from seven records on and from fewer (both defined wherever a record has a value)
SUITE_MAPS = {"mean": "mean of the records", "max": "largest of the records"}


def _suite_maps(ds):
    """A suite's maps: rows of its statistics over the records (SUITE_MAPS) in place of a row per record
    (seven to eleven records would make a figure twenty rows tall that shows no design value); a
    cell flagged where a record's pad reaches a ring, failed where every record's run fails."""
    from .combine import statistics

    stats = statistics(ds).sel(statistic=list(SUITE_MAPS))
    out = {name: stats[f"{name}_suite"] for name, *_ in SUMMARY_VARIABLES if f"{name}_suite" in stats}
    shape = next(iter(out.values()))
    out["capacity_exceeded"] = (stats["records_capacity_exceeded"] > 0).broadcast_like(shape)
    out["failed"] = (stats["records_failed"] == ds.sizes["record"]).broadcast_like(shape)
    labels = np.array([SUITE_MAPS[str(s)] for s in stats["statistic"].values])
    suite = xr.Dataset(out).assign_coords(statistic=("statistic", labels))
    axes = ["statistic" if name == "record" else name for name in ds.attrs["sweep_axes"].split()]
    suite.attrs = {**ds.attrs, "sweep_axes": " ".join(axes)}
    return suite


def _defined(ds, name, model):
    """Whether a summary exists for a model: not a stick-slip quantity of another model, and a value
    somewhere or no point the solver completed (then every point is marked failed)."""
    if name in model_specific() and name not in REGISTRY[model].summaries:
        return False
    sel = ds.sel(model=model)
    return bool(np.isfinite(sel[name].values).any() or sel["failed"].values.all())


def _categorical(ds, name):
    return ds[name].values.dtype.kind in "OUS"


def _plan(ds):
    """(kind, drawn axes, {further axis: its number of values}) for the sweep axes of ``ds``.

    Axes of one value are never drawn; two numeric axes make maps, one numeric axis curves (a
    categorical axis then gives one curve per category), a categorical axis alone marks per category.
    """
    names = ds.attrs["sweep_axes"].split()
    kind, drawn = layout({n: ds.sizes[n] for n in names}, {n for n in names if _categorical(ds, n)})
    return kind, drawn, {n: ds.sizes[n] for n in names if n not in drawn}


def _fixed_note(ds, fixed):
    """'h² = 0.15 m; prototype = DFP1 (first of 2 values, the others not drawn)'."""
    parts = [_value_text(ds, name, ds[name].values[()]) + (f" (first of {size} values, the others not drawn)"
                                                           if size > 1 else "") for name, size in fixed.items()]
    return "at " + "; ".join(parts)


def _plot_values(ds, name):
    factor = _axis_unit(ds, name)[0]
    return factor * ds[name].values.astype(float)


def _edges(centres, log):
    """Cell edges around sorted cell centres: midpoints (geometric on a log axis), ends mirrored."""
    c = np.log(centres) if log else np.asarray(centres, dtype=float)
    mid = 0.5 * (c[1:] + c[:-1])
    edges = np.concatenate([[2 * c[0] - mid[0]], mid, [2 * c[-1] - mid[-1]]])
    return np.exp(edges) if log else edges


def _flags(ds, model, *dims, where=None):
    """(capacity exceeded, failed) boolean arrays of a model (at ``where``: {axis: value}), dimensions
    ordered as ``dims`` (``_case_flags``)."""
    flags = [n for n in ("capacity_exceeded", "failed", "capacity_time", "failure_time") if n in ds]
    return _case_flags(ds[flags].sel(model=model, **(where or {})).transpose(*dims))


def _case_flags(sel):
    """(capacity exceeded, the solver failed) of the cases of ``sel``: a case that capacity "error" marked
    failed where it reached the ring is one that reached it, not a solver failure."""
    capacity, failed = (sel[f].values.astype(bool) for f in ("capacity_exceeded", "failed"))
    if "capacity_time" in sel and "failure_time" in sel:
        failed = failed & ~(capacity & (sel["failure_time"].values == sel["capacity_time"].values))
    return capacity, failed


def _flag_labels(ds, models, dims):
    """Legend labels of the capacity and failure marks with their counts per model."""
    suite = "statistic" in dims  # a suite's maps: cells, whichever statistic
    dims = [d for d in dims if d != "statistic"]
    total = int(np.prod([ds.sizes[d] for d in dims]))
    counts = [_flags(ds.isel(statistic=0) if suite else ds, m, *dims) for m in models]
    cap = ", ".join(f"{model_title(m)} {int(c.sum())}" for m, (c, _) in zip(models, counts))
    fail = ", ".join(f"{model_title(m)} {int(f.sum())}" for m, (_, f) in zip(models, counts))
    ended = " (on the bottom edge where capacity: error ended the case there)" \
        if str(ds.attrs.get("capacity_policy")) == "error" else ""
    if suite:
        return (f"a record's pad reaches a retaining ring ({cap} of {total} cells)",
                f"every record's run failed, no result ({fail} of {total} cells)")
    return (f"pad reaches a retaining ring ({cap} of {total}){ended}", f"solver failed, no result ({fail} of {total})")


def _undefined(ax, label, model):
    ax.set_axis_off()
    ax.text(0.5, 0.5, f"{label}:\nnot defined for {model_title(model)}", ha="center", va="center",
            transform=ax.transAxes, color="0.4")


def _draw_maps(fig, columns, ds, drawn, marks, variables, rows, models, group=None):
    """A column of axes per variable (``columns``), with its colour bar: a map per model (and category of
    ``group``: ``rows`` of (model, {group: category})); the legend's groups of handles."""
    x, y = drawn
    logs = [name in LOG_AXES for name in drawn]
    xe, ye = (_edges(_plot_values(ds, n), log) for n, log in zip(drawn, logs))
    for column, (name, label, factor, unit) in zip(columns, variables):
        values = factor * ds[name].values
        finite = values[np.isfinite(values)]
        vmin, vmax = (finite.min(), finite.max()) if finite.size else (0.0, 1.0)
        mesh = None
        for ax, (model, where) in zip(column, rows):
            data = factor * ds[name].sel(model=model, **where).transpose(x, y).values
            if not _defined(ds, name, model):
                _undefined(ax, label, model)
                continue
            mesh = ax.pcolormesh(xe, ye, data.T, cmap="viridis", vmin=vmin, vmax=vmax)
            capacity, failed = _flags(ds, model, x, y, where=where)
            _hatch(ax, capacity, xe, ye, "capacity_exceeded", CAPACITY_COLOUR, "///", "none")
            missing = failed & ~np.isfinite(data)  # a structure's summaries have a value where the pad failed
            _hatch(ax, missing, xe, ye, "failed", FAILED_COLOUR, "xx", "0.85")
            _map_marks(ax, ds, drawn, marks)
            _scale(ax, "x", x, _plot_values(ds, x))
            _scale(ax, "y", y, _plot_values(ds, y))
            ax.set_xlim(xe[0], xe[-1])
            ax.set_ylim(ye[0], ye[-1])
            ax.set_xlabel(_axis_label(ds, x))
            ax.set_ylabel(_axis_label(ds, y))
            # the model and the row's category, then the summary: the title stays within its map
            ax.set_title(f"{', '.join([model_title(model), *where.values()])}:\n{label}", fontsize=10)
        if mesh is not None:
            fig.colorbar(mesh, ax=list(column), label=f"{label} ({unit})", shrink=0.9)
    cap_label, fail_label = _flag_labels(ds, models, [*drawn, group] if group else drawn)
    flags = [Patch(fc="none", ec=CAPACITY_COLOUR, hatch="///", label=cap_label),
             Patch(fc="0.85", ec=FAILED_COLOUR, hatch="xx", label=fail_label)]
    if any(_mark_point(ds, drawn, p) for p in marks.values()):
        return [flags, [Line2D([], [], ls="none", marker="*", ms=11, mfc="w", mec="k", label="marked points")]]
    return [flags]


def _hatch(ax, mask, xe, ye, gid, colour, hatch, face):
    """Hatch exactly the cells of ``mask`` (x, y) and outline them along the cell edges."""
    cells = [Rectangle((xe[i], ye[j]), xe[i + 1] - xe[i], ye[j + 1] - ye[j]) for i, j in zip(*np.nonzero(mask))]
    if not cells:
        return
    patches = PatchCollection(cells, fc=face, ec=colour, lw=0.0, hatch=hatch, zorder=2)
    patches.set_gid(gid)
    ax.add_collection(patches)
    outline = LineCollection(_outline(mask, xe, ye), colors=colour, linewidths=1.2, zorder=3)
    outline.set_gid(gid + "_outline")
    ax.add_collection(outline)


def _outline(mask, xe, ye):
    """Segments of the cell edges that separate flagged from unflagged cells (or the grid's border)."""
    padded = np.pad(mask, 1)
    across_x = padded[1:, 1:-1] != padded[:-1, 1:-1]  # edge at xe[i] from ye[j] to ye[j + 1]
    across_y = padded[1:-1, 1:] != padded[1:-1, :-1]  # edge at ye[j] from xe[i] to xe[i + 1]
    return ([[(xe[i], ye[j]), (xe[i], ye[j + 1])] for i, j in zip(*np.nonzero(across_x))]
            + [[(xe[i], ye[j]), (xe[i + 1], ye[j])] for i, j in zip(*np.nonzero(across_y))])


def _mark_position(ds, name, point):
    """Plot coordinate of a marked point on an axis (category index, or value in plot units)."""
    if name not in point:
        return None
    if _categorical(ds, name):
        hits = [i for i, v in enumerate(ds[name].values) if str(v) == str(point[name])]
        return float(hits[0]) if hits else None
    return _axis_unit(ds, name)[0] * float(point[name])


def _mark_point(ds, drawn, point):
    """Coordinates of a marked point on the drawn axes (None when it does not name them all)."""
    where = [_mark_position(ds, name, point) for name in drawn]
    return None if any(v is None for v in where) else where


def _map_marks(ax, ds, drawn, marks):
    for label, point in marks.items():
        where = _mark_point(ds, drawn, point)
        if where:
            ax.plot(*where, ls="none", marker="*", ms=12, mfc="w", mec="k", zorder=6)
            ax.annotate(label, where, xytext=(5, 5), textcoords="offset points", fontsize=8, color="w", zorder=6,
                        bbox={"fc": "k", "alpha": 0.5, "pad": 1, "lw": 0})


def _line_marks(ax, ds, name, marks):
    """A dotted vertical line and its label at each marked value of the x axis."""
    for label, point in marks.items():
        x = _mark_position(ds, name, point)
        if x is not None:
            ax.axvline(x, color="0.45", ls=":", lw=1.0, zorder=1)
            ax.annotate(label, (x, 0.99), xycoords=("data", "axes fraction"), rotation=90, ha="right", va="top",
                        fontsize=7, color="0.35", xytext=(-2, 0), textcoords="offset points")


def _flag_marks(ax, x, values, capacity, failed, colour, failures):
    """Red boxes around the points beyond capacity; the points where the solver failed and that have no
    value (a structure's summaries have one: they do not depend on the pad) are added to ``failures``
    (x, colour), drawn by ``_failure_marks``."""
    if capacity.any():
        ax.plot(x[capacity], values[capacity], ls="none", marker="s", ms=14, mfc="none", mec=CAPACITY_COLOUR,
                mew=1.4, zorder=6, gid="capacity_exceeded")
    ended = capacity & ~np.isfinite(values)  # no value: capacity "error" ended the case at the ring
    if ended.any():
        ax.plot(x[ended], np.zeros(int(ended.sum())), ls="none", marker="s", ms=11, mfc="none", mec=CAPACITY_COLOUR,
                mew=1.4, transform=ax.get_xaxis_transform(), clip_on=False, zorder=6, gid="capacity_ended")
    failed = failed & ~np.isfinite(values)
    if failed.any():
        failures.append((x[failed], colour))


def _failure_marks(ax, failures):
    """✕ on the bottom edge of the axes (no value: the solver failed) at each failed point, in the colour
    of its curve; the marks of the curves failing at the same x side by side, FAILURE_SPACING points
    apart, centred on it."""
    curves_at = {}
    for k, (x, _) in enumerate(failures):
        for value in x:
            curves_at.setdefault(float(value), []).append(k)
    for k, (x, colour) in enumerate(failures):
        by_offset = {}
        for value in x:
            curves = curves_at[float(value)]
            by_offset.setdefault(curves.index(k) - (len(curves) - 1) / 2, []).append(value)
        for offset, xs in by_offset.items():
            transform = ax.get_xaxis_transform()
            if offset:
                transform += ScaledTranslation(FAILURE_SPACING * offset / 72, 0, ax.figure.dpi_scale_trans)
            ax.plot(xs, np.zeros(len(xs)), ls="none", marker="X", ms=9, color=colour, mec="k", mew=0.6,
                    transform=transform, clip_on=False, zorder=6, gid="failed")


def _flag_handles(ds, models, dims):
    cap_label, fail_label = _flag_labels(ds, models, dims)
    return [Line2D([], [], ls="none", marker="s", ms=11, mfc="none", mec=CAPACITY_COLOUR, mew=1.4, label=cap_label),
            Line2D([], [], ls="none", marker="X", ms=9, color="0.6", mec="k", mew=0.6,
                   label=fail_label + ", marked on the bottom edge")]


def _draw_lines(axs, ds, drawn, marks, variables, models, bounds=False):
    """One panel per variable: the summary against the numeric axis, a curve per model (and category); with
    ``bounds`` (a further axis of the friction's bounds) a curve per bound too, each bound's by its marker."""
    x_name = drawn[0]
    x = _plot_values(ds, x_name)
    groups = list(ds[drawn[1]].values) if len(drawn) > 1 else [None]
    crowd = len(drawn) > 1 and drawn[1] == "record" and len(groups) > ROTATE_FROM  # a suite's many records
    labels = list(ds["property"].values) if bounds else [None]
    for ax, (name, label, factor, unit) in zip(axs, variables):
        failures = []
        for model, (b, bound) in ((m, b) for m in models if _defined(ds, name, m) for b in enumerate(labels)):
            style = model_line(model, models)
            own = ds.sel(model=model) if bound is None else ds.sel(model=model, property=bound)
            for g, group in enumerate(groups):
                sel = own if group is None else own.sel({drawn[1]: group})
                values = factor * sel[name].values
                if crowd:  # each record a faint line, its flags counted in the legend, not marked point by point
                    ax.plot(x, values, color=style["color"], lw=0.8, **SUITE_RECORDS, gid="record")
                    continue
                shape = ({} if group is None and bound is None else
                         {"marker": GROUP_MARKERS[(b if bound is not None else g) % len(GROUP_MARKERS)]})
                marker = dict(_marker(model), **shape)
                ax.plot(x, values, **style, **marker, **(SUITE_RECORDS if f"{name}_suite" in ds else {}))
                capacity, failed = _case_flags(sel)
                _flag_marks(ax, x, values, capacity, failed, style["color"], failures)
            suite = _suite_lines(own, name)
            if suite is not None:  # the suite's mean and 84th percentile over the records
                shape = {} if bound is None else {"marker": GROUP_MARKERS[b % len(GROUP_MARKERS)], "ms": 5}
                for statistic, look in _suite_looks(style).items():
                    ax.plot(x, factor * own[suite].sel(statistic=statistic).transpose(x_name).values,
                            **look, **shape)
            if bound is None and f"{name}_envelope" in ds and "record" not in ds[f"{name}_envelope"].dims:
                ax.plot(x, factor * ds[f"{name}_envelope"].sel(model=model).transpose(x_name).values,
                        **ENVELOPE_OVER, zorder=style["zorder"] + 1, gid="envelope")  # the bounds' largest
        _failure_marks(ax, failures)
        _line_marks(ax, ds, x_name, marks)
        _scale(ax, "x", x_name, x)
        ax.set_xlabel(_axis_label(ds, x_name))
        _summary_axes(ax, ds, name, label, unit, models)
    legend = [[Line2D([], [], **model_line(m, models), **_marker(m), label=model_title(m)) for m in models]]
    if bounds:
        legend.append([Line2D([], [], ls="none", marker=GROUP_MARKERS[b % len(GROUP_MARKERS)], color="0.4",
                              label=_value_text(ds, "property", bound)) for b, bound in
                       enumerate(labels)])
    if crowd:
        label = f"each of the {len(groups)} records" + ", at each bound" * bounds
        legend.append([Line2D([], [], color="0.4", lw=0.8, **SUITE_RECORDS, label=label)])
        cap_label, fail_label = _flag_labels(ds, models, drawn + ["property"] * bounds)
        return legend + ([_suite_handles(bounds="property" in ds.dims and not bounds)] if "statistic" in ds.coords
                         else []) + [
            [Line2D([], [], ls="none", label=f"{cap_label}; {fail_label}: counted, not marked point by point")]]
    if len(drawn) > 1:
        legend.append([Line2D([], [], ls="none", marker=GROUP_MARKERS[g % len(GROUP_MARKERS)], color="0.4",
                              label=_value_text(ds, drawn[1], group)) for g, group in enumerate(groups)])
    if "statistic" in ds.coords:
        legend.append(_suite_handles(bounds="property" in ds.dims and not bounds))
    if not bounds and any(f"{name}_envelope" in ds and "record" not in ds[f"{name}_envelope"].dims
                          for name, *_ in variables):
        legend.append([Line2D([], [], **ENVELOPE_OVER, label=ENVELOPE_LABEL)])
    return legend + [_flag_handles(ds, models, drawn + ["property"] * bounds)]


def _suite_looks(style):
    """How a model (its line ``style``) draws the suite's statistics: the mean in its own line, wider, over
    the faded record curves; the 84th percentile dotted."""
    mean = dict(style, lw=style.get("lw", 1.5) + SUITE_WIDER, zorder=SUITE_LINES["mean"]["zorder"])
    return {"mean": mean, "p84_lognormal": dict(SUITE_LINES["p84_lognormal"], color=style["color"])}


def _suite_handles(bounds=False):
    """The legend of a suite's statistics (``bounds``: of the largest over the friction's bounds)."""
    return [Line2D([], [], color="0.3", **look, label=SUITE_LABELS[statistic] + (
        ", largest over the friction's bounds" if bounds else "")) for statistic, look in SUITE_LINES.items()]


def _rsn(names):
    """PEER's record sequence numbers of records named RSN<number>_<station> (a download's: ``dccss.peer``), where
    each has one and they tell the records apart; else None."""
    found = [re.match(r"RSN\d+", n) for n in names]
    short = [m.group(0) for m in found if m]
    return short if len(short) == len(names) and len(set(short)) == len(names) else None


def _shortened(names, most=24):
    """Tick labels of at most ``most`` characters: a longer name keeps its start and end around "…" (as
    many characters as keep the names told apart)."""
    for keep in range(most, max(map(len, names)) + 1):
        half = (keep - 1) // 2
        short = [n if len(n) <= keep else f"{n[:half]}…{n[len(n) - half:]}" for n in names]
        if len(set(short)) == len(names):
            return short
    return list(names)


def _draw_categories(axs, ds, drawn, marks, variables, models):
    """One panel per variable: a mark per model at each category's integer position (and, with a second
    categorical axis, a mark per its category side by side around it, a marker each); a suite's statistics
    as lines across; the largest over the friction's bounds (``combine.envelope``) as a line across where
    it is one value, as a bar at each category where it is one per category."""
    name_axis = drawn[0]
    names = [str(v) for v in ds[name_axis].values]
    x = np.arange(len(names), dtype=float)
    groups = [str(v) for v in ds[drawn[1]].values] if len(drawn) > 1 else [None]
    width = min(0.7, 0.25 * len(groups))  # the side-by-side marks' spread around a category
    offsets = np.linspace(-width / 2, width / 2, len(groups)) if len(groups) > 1 else [0.0]
    for ax, (name, label, factor, unit) in zip(axs, variables):
        failures = []
        for model in (m for m in models if _defined(ds, name, m)):
            style = model_line(model, models)
            for g, (group, offset) in enumerate(zip(groups, offsets)):
                sel = ds.sel(model=model) if group is None else ds.sel({"model": model, drawn[1]: group})
                values = factor * sel[name].values
                marker = _marker(model) if group is None else dict(_marker(model), marker=GROUP_MARKERS[g % len(
                    GROUP_MARKERS)])
                ax.plot(x + offset, values, ls="none", color=style["color"], zorder=style["zorder"], **marker)
                capacity, failed = _case_flags(sel)
                _flag_marks(ax, x + offset, values, capacity, failed, style["color"], failures)
            suite = _suite_lines(ds, name)
            if suite is not None:  # the suite's mean and 84th percentile over the records
                for statistic, look in _suite_looks(style).items():
                    ax.axhline(factor * float(ds[suite].sel(model=model, statistic=statistic)), **look)
            if f"{name}_envelope" in ds:  # the design demand: the largest over the friction's bounds
                envelope = factor * ds[f"{name}_envelope"].sel(model=model)
                if envelope.ndim == 0:
                    ax.axhline(float(envelope), **ENVELOPE_LOOK, color=style["color"], zorder=style["zorder"] - 1)
                else:  # one per category: a bar across its marks
                    bars = [[(xi - width / 2 - 0.1, v), (xi + width / 2 + 0.1, v)]
                            for xi, v in zip(x, envelope.transpose(name_axis).values)]
                    ax.add_collection(LineCollection(bars, colors=style["color"], linestyles=ENVELOPE_LOOK["ls"],
                                                     linewidths=1.6, zorder=style["zorder"] - 1, gid="envelope"))
        _failure_marks(ax, failures)
        _line_marks(ax, ds, name_axis, marks)
        _category_ticks(ax, x, names, name_axis)
        ax.set_xlim(-0.6, len(names) - 0.4)
        ax.set_xlabel(_axis_label(ds, name_axis))
        _summary_axes(ax, ds, name, label, unit, models)
    envelope = [[Line2D([], [], color="0.3", **ENVELOPE_LOOK, label=ENVELOPE_LABEL)]] \
        if any(f"{name}_envelope" in ds for name, *_ in variables) else []
    legend = [[Line2D([], [], ls="none", color=model_line(m, models)["color"], **_marker(m), label=model_title(m))
               for m in models]]
    if len(drawn) > 1:
        legend.append([Line2D([], [], ls="none", marker=GROUP_MARKERS[g % len(GROUP_MARKERS)], color="0.4",
                              label=_value_text(ds, drawn[1], group)) for g, group in enumerate(groups)])
    suite = [_suite_handles(bounds="property" in ds.dims)] if "statistic" in ds.coords else []
    return legend + suite + envelope + [_flag_handles(ds, models, drawn)]


def _suite_lines(ds, name):
    """The variable of a summary's suite statistics drawn as lines across: ``<name>_suite``, or over the
    friction's bounds their largest (``<name>_suite_envelope``); None where there is neither."""
    if f"{name}_suite" not in ds:
        return None
    if "property" in ds[f"{name}_suite"].dims:
        return f"{name}_suite_envelope" if f"{name}_suite_envelope" in ds else None
    return f"{name}_suite"


def _category_ticks(ax, x, names, name_axis):
    """Tick labels of the categories: a suite's records turned to fit (upright beyond ROTATE_FROM records,
    smaller beyond SMALL_FROM), names shortened to keep them apart."""
    many = len(names) > ROTATE_FROM
    rotation = 90 if many else (30 if name_axis == "record" else 0)
    small = {"fontsize": 7} if len(names) > SMALL_FROM else {}
    labels = _rsn(names) if many and name_axis == "record" else None
    ax.set_xticks(x, labels or _shortened(names, 16 if many else 24), rotation=rotation,
                  ha="center" if many else ("right" if name_axis == "record" else "center"), **small)


def _scale(ax, which, name, values):
    """Log scale for a time-step axis; ticks at the swept values when there are few of them."""
    getattr(ax, f"set_{which}scale")("log" if name in LOG_AXES else "linear")
    axis = ax.xaxis if which == "x" else ax.yaxis
    if len(values) <= MAX_VALUE_TICKS:
        axis.set_ticks(values, [f"{v:.4g}" for v in values])
        axis.set_minor_locator(NullLocator())


def _summary_axes(ax, ds, name, label, unit, models):
    """Labels, title (saying for which models a variable is not defined), margins and grid."""
    missing = [model_title(m) for m in models if not _defined(ds, name, m)]
    ax.set_ylabel(f"{label} ({unit})")
    ax.set_title(label + (f"\n(not defined for {', '.join(missing)})" if missing else ""), fontsize=10)
    ax.margins(y=0.18)
    ax.grid(True, color="0.9", lw=0.6)


# --- convergence in the step size -------------------------------------------------------------------
#: the steps used to fit the order: the smallest ones (where the asymptotic order shows)
FIT_POINTS = 4


def convergence_table(ds, points) -> list[dict]:
    """What a Δt study measures, per device (the point's other coordinates) and step size: the
    largest sticking rotation (deg, from the summaries ``ds``) and the largest differences between
    the first model with a sticking phase (stick-slip; end of step) and the first without one
    (compliant sliding) of θ² (deg) and of the rise of RB3 (m), from the histories.

    ``points`` is a list of ({axis: value}, {model: history dataset}), one per history point with a
    ``dt``; a failed or cut history contributes up to its last step in common with the other model.
    """
    rows = []
    for point, runs in points:
        sticking = [m for m in ordered_models(runs) if m in REGISTRY and REGISTRY[m].sticking]
        plain = [m for m in ordered_models(runs) if m in REGISTRY and not REGISTRY[m].sticking]
        if "dt" not in point or not sticking or not plain:
            continue
        comp, stick = runs[plain[0]], runs[sticking[0]]
        n = min(comp.sizes["t"], stick.sizes["t"])
        others = {k: v for k, v in point.items() if k != "dt"}
        turn = ds["sticking_rotation_max"].sel(model=sticking[0], dt=point["dt"],
                                               **{k: v for k, v in others.items() if k in ds.dims})
        rows.append({"group": ", ".join(f"{k} = {v}" for k, v in others.items()) or "the case",
                     "dt": float(point["dt"]), "sticking_rotation_max": float(turn),
                     "theta2_difference_max": float(np.abs(stick["theta2"][:n] - comp["theta2"][:n]).max()),
                     "rise_difference_max": float(np.abs(stick["rise"][:n] - comp["rise"][:n]).max()),
                     "failed": bool(stick.attrs.get("failed", 0) or comp.attrs.get("failed", 0))})
    return sorted(rows, key=lambda r: (r["group"], r["dt"]))


def fitted_order(dt, values, n=FIT_POINTS) -> float:
    """Slope of log(values) against log(dt) over the ``n`` smallest step sizes (least squares)."""
    dt, values = np.asarray(dt, float), np.asarray(values, float)
    keep = np.argsort(dt)[:n]
    keep = keep[np.isfinite(values[keep]) & (values[keep] > 0)]
    if keep.size < 2:
        return float("nan")
    return float(np.polyfit(np.log(dt[keep]), np.log(values[keep]), 1)[0])


CONVERGENCE_PANELS = [
    ("sticking_rotation_max", "largest sticking rotation", 1.0, "°"),
    ("theta2_difference_max", "max |θ² stick-slip − θ² compliant|", 1.0, "°"),
    ("rise_difference_max", "max |rise stick-slip − rise compliant|", 1e3, "mm"),
]


def convergence(rows, caption: str) -> Figure:
    """Log-log panels of ``convergence_table`` rows against Δt, one line per device, with the order
    fitted over the ``FIT_POINTS`` smallest steps in the legend; failed runs drawn hollow."""
    fig, axs = new_figure((13, 4.6), 1, len(CONVERGENCE_PANELS))
    groups = list(dict.fromkeys(r["group"] for r in rows))
    for ax, (name, label, factor, unit) in zip(axs[0], CONVERGENCE_PANELS):
        for k, group in enumerate(groups):
            mine = [r for r in rows if r["group"] == group]
            dt = np.array([r["dt"] for r in mine])
            y = factor * np.array([r[name] for r in mine])
            order = fitted_order(dt, y)
            colour = f"C{k}"
            ax.loglog(dt, y, "-", color=colour, marker=GROUP_MARKERS[k % len(GROUP_MARKERS)], ms=5,
                      label=f"{group}: order {order:.2f}")
            failed = np.array([r["failed"] for r in mine])
            if failed.any():
                ax.loglog(dt[failed], y[failed], "o", ms=11, mfc="none", mec=FAILED_COLOUR, mew=1.2,
                          label="solver failed (up to the failure)" if k == 0 else None)
        ax.set_xlabel("Δt (s)")
        ax.set_ylabel(f"{label} ({unit})")
        ax.grid(True, which="both", alpha=0.3)
        steps = len({r["dt"] for r in rows})
        fitted = f"the {FIT_POINTS} smallest Δt" if steps > FIT_POINTS else f"all {steps} Δt"
        ax.legend(fontsize=8, title=f"order fitted on {fitted}", title_fontsize=8)
    fig.suptitle("Stick-slip against Δt: the sticking rotation and the distance to compliant sliding", fontsize=12)
    caption_line(fig, caption)
    return fig
