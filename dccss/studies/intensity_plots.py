"""The figures of a study with intensity levels: the response against the intensity (incremental dynamic analysis,
stripes) and the fragility curves.

``ida`` draws, per response (rows: the structure's stroke, each surface's where there are two, the pad's tilt,
the smallest N/W) and per friction bound (columns), each record's response against the intensity (faint), and at
each level the median and the 16th and 84th percentiles over the records; the intensity on the vertical axis, as
IDA curves are drawn. ``fragility`` draws, per limit state, the fraction of the runs that exceed it at each level
and the fitted lognormal, per model and bound. A fractile or a fraction stands on the runs with a value (a run that
failed, or an articulated slider's pad summary, has none): where they are fewer than the records, their number is
written beside it. Paper units: cm, degrees.
"""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from scipy.special import ndtr

from ..drawing import new_figure
from .fragility import LIMITS
from .plots import complete, model_line, model_title, ordered_models

#: (variable, label, factor to plot units, unit, whether it is the pad's: one curve per model)
RESPONSES = [
    ("stroke_max_abs", "max |stroke u| of the structure", 100.0, "cm", False),
    ("stroke_1_max_abs", "max $|u_1|$ on the lower surface", 100.0, "cm", False),
    ("stroke_3_max_abs", "max $|u_3|$ on the upper surface", 100.0, "cm", False),
    ("theta2_max_abs", "max |θ²| of the pad", 1.0, "°", True),
    ("normal_ratio_min", "min N/W", 1.0, "-", False),
]
#: the fractiles drawn over the records at each level, and how
FRACTILES = {50: dict(lw=2.6), 16: dict(lw=1.3, ls=(0, (4, 2))), 84: dict(lw=1.3, ls=(0, (4, 2)))}
RECORD_LOOK = dict(lw=0.7, alpha=0.35)
PANEL_INCHES = (3.9, 3.1)
#: the limit states' colours in a fragility panel of several models or bounds: by bound, a marker each
BOUND_MARKERS = {"lower": "v", "nominal": "o", "upper": "^"}


def _intensity_label(ds) -> str:
    """'Sa(T = 2.71 s, 5 %) (g)'."""
    return ds["intensity"].attrs["label"]


def _bounds(ds) -> list:
    return [str(b) for b in ds["property"].values] if "property" in ds.dims else [None]


def _same_across_models(ds, name) -> bool:
    """Whether a variable is the same for every model (the structure's: it does not depend on the pad)."""
    values = ds[name].transpose("model", ...).values
    return bool(np.array_equal(values, np.broadcast_to(values[:1], values.shape), equal_nan=True))


def _runs_beside(ax, x, y, runs, records, color):
    """The number of runs a point stands on, written beside it where it is fewer than the ``records`` (and > 0)."""
    for xi, yi, k in zip(x, y, runs):
        if 0 < k < records:
            ax.annotate(f"{k}", (xi, yi), xytext=(3, -9), textcoords="offset points", fontsize=7, color=color,
                        gid="runs")


def ida(ds, caption: str) -> Figure:
    """Each record's response against the intensity, and the median and 16/84 % over the records at each level,
    per response and friction bound (the docstring of the module)."""
    responses = [r for r in RESPONSES if r[0] in ds and np.isfinite(ds[r[0]].values).any()]
    bounds = _bounds(ds)
    models = ordered_models([str(m) for m in ds["model"].values])
    fig, axs = new_figure((PANEL_INCHES[0] * len(bounds) + 0.4, PANEL_INCHES[1] * len(responses) + 1.4),
                          len(responses), len(bounds), sharey=True)
    levels = ds["intensity"].values.astype(float)
    for row, (name, label, factor, unit, _) in zip(axs, responses):
        drawn = models[:1] if _same_across_models(ds, name) else models
        for ax, bound in zip(row, bounds):
            for model in drawn:
                style = model_line(model, models) if len(drawn) > 1 else dict(color="0.15")
                sel = ds[name].sel(model=model, **({"property": bound} if bound else {}))
                values = factor * sel.transpose("record", "intensity").values
                for record in values:
                    ax.plot(record, levels, color=style["color"], **RECORD_LOOK)
                runs = np.isfinite(values).sum(axis=0)
                for q, look in FRACTILES.items():
                    stripe = np.full(levels.shape, np.nan)
                    stripe[runs > 0] = np.nanpercentile(values[:, runs > 0], q, axis=0)
                    ax.plot(stripe, levels, color=style["color"], **look, gid=f"p{q}")
                    if q == 50:
                        _runs_beside(ax, stripe, levels, runs, len(values), style["color"])
            ax.set_xlabel(f"{label} ({unit})")
            ax.grid(True, color="0.9", lw=0.6)
            if bound:
                ax.set_title(f"{label}\nproperty = {bound}", fontsize=10)
            else:
                ax.set_title(label, fontsize=10)
        row[0].set_ylabel(_intensity_label(ds))
    n = ds.sizes["record"]
    handles = [[Line2D([], [], color="0.3", **RECORD_LOOK, label=f"each of the {n} records"),
                Line2D([], [], color="0.3", **FRACTILES[50], label="median over the records (k: over k runs "
                                                                   "with a value)"),
                Line2D([], [], color="0.3", **FRACTILES[16], label="16th and 84th percentiles")]]
    if len(models) > 1:
        handles.append([Line2D([], [], **model_line(m, models), label=model_title(m)) for m in models]
                       + [Line2D([], [], color="0.15", label="the structure (the same under every model)")])
    title = f"Study {ds.attrs.get('study', '')}: response against the intensity ({n} records, {len(levels)} levels)"
    return complete(fig, title, caption, handles)


def fragility(ds, caption: str) -> Figure:
    """The observed fraction of the runs exceeding each limit state at each level (markers; the runs counted
    beside them where some are left out) and the fitted lognormal P(exceed | x) = Φ(ln(x / θ) / β), per model and
    friction bound."""
    names = [v.removeprefix("fragility_").removesuffix("_median") for v in ds.data_vars
             if v.startswith("fragility_") and v.endswith("_median")]
    models = ordered_models([str(m) for m in ds["model"].values])
    bounds = _bounds(ds)
    columns = min(3, len(names))
    rows = -(-len(names) // columns)
    fig, axs = new_figure((4.4 * columns + 0.4, 3.4 * rows + 1.2), rows, columns)
    levels = ds["intensity"].values.astype(float)
    grid = np.linspace(0.0, levels.max() * 1.05, 200)[1:]
    notes, per_model = [], False
    for ax, name in zip(axs.ravel(), names):
        prefix = f"fragility_{name}"
        drawn = models[:1] if _same_across_models(ds, f"{prefix}_exceeded") else models
        per_model = per_model or len(drawn) > 1
        for model in drawn:
            style = model_line(model, models) if len(drawn) > 1 else dict(color="0.15")
            for bound in bounds:
                where = {"model": model, **({"property": bound} if bound else {})}
                z = ds[f"{prefix}_exceeded"].sel(where).values
                n = ds[f"{prefix}_counted"].sel(where).values
                with np.errstate(all="ignore"):
                    fraction = np.where(n > 0, z / n, np.nan)
                marker = BOUND_MARKERS.get(bound, "o")
                ax.plot(levels, fraction, ls="none", marker=marker, ms=5, mfc="none", mec=style["color"],
                        gid="observed")
                theta = float(ds[f"{prefix}_median"].sel(where))
                beta = float(ds[f"{prefix}_dispersion"].sel(where))
                who = ", ".join(([model_title(model)] if len(drawn) > 1 else []) + ([bound] if bound else []))
                if np.isfinite(theta):
                    ls = {"lower": ":", "upper": "--"}.get(bound, "-")
                    ax.plot(grid, ndtr(np.log(grid / theta) / beta), color=style["color"], ls=ls, lw=1.6,
                            label=f"{who + ': ' if who else ''}θ = {theta:.3g}, β = {beta:.2f}", gid="fitted")
                else:
                    status = str(ds[f"{prefix}_fit"].sel(where).values)
                    notes.append(f"{name}{' (' + who + ')' if who else ''}: no fit, {status}")
                _runs_beside(ax, levels, fraction, n, ds.sizes["record"], style["color"])
        title = LIMITS[name][1] if name in LIMITS else ds[f"{prefix}_exceeded"].attrs["long_name"].removeprefix(
            "runs in which ").removesuffix(", per level")
        ax.set_title(f"{name}: " + title, fontsize=9, wrap=True)
        ax.set_xlabel(_intensity_label(ds))
        ax.set_ylabel("P(exceeded | intensity)")
        ax.set_ylim(-0.03, 1.03)
        ax.set_xlim(0.0, grid[-1])
        ax.grid(True, color="0.9", lw=0.6)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="lower right")
    for ax in axs.ravel()[len(names):]:
        ax.set_axis_off()
    handles = [[Line2D([], [], ls="none", marker="o", mfc="none", mec="0.3",
                       label="fraction exceeding it (k: of k runs; the others failed or have no value)"),
                Line2D([], [], color="0.3", lw=1.6, label="lognormal fitted by maximum likelihood")]]
    if len(bounds) > 1:
        handles.append([Line2D([], [], ls={"lower": ":", "upper": "--"}.get(b, "-"), marker=BOUND_MARKERS.get(b, "o"),
                               mfc="none", color="0.3", label=f"property = {b}") for b in bounds])
    if per_model:
        handles.append([Line2D([], [], **model_line(m, models), label=model_title(m)) for m in models])
    elif len(models) > 1:
        handles.append([Line2D([], [], color="0.15", lw=1.6, label="the same under every model")])
    title = f"Study {ds.attrs.get('study', '')}: fragility over {ds.sizes['record']} records"
    if notes:
        title += "\n" + "; ".join(notes)
    return complete(fig, title, caption, handles)
