"""Standard plots of a study: summary maps over the sweep axes and time histories of chosen cases.

Maps use the first two sweep axes (one axis: curves); further axes are shown at their first
value, as the panel titles say. Paper units: degrees, cm, mm or µm.
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: (summary variable, label, scale to paper units, unit)
MAP_VARIABLES = [
    ("theta2_max_abs", "max |θ²|", 1.0, "°"),
    ("sticking_rotation_max", "max sticking rotation", 1.0, "°"),
    ("rise_max", "max rise of RB3", 100.0, "cm"),
    ("interpenetration_max", "max interpenetration", 1e3, "mm"),
]


def _label(name, ds):
    units = ds[name].attrs.get("units")
    unit = {"degree": "°", "m": "m", "1": "", "rad s-1": "rad/s"}.get(units, units or "")
    return f"{name} ({unit})" if unit else name


def _positions(ds, name):
    values = ds[name].values
    if values.dtype.kind in "OUS":  # a categorical axis (device names)
        return np.arange(len(values), dtype=float), [str(v) for v in values]
    return values.astype(float), None


def maps(ds, marks: dict, caption: str) -> Figure:
    """One row per model, one column per summary variable (max over corners for the interpenetration)."""
    axes_names = ds.attrs["sweep_axes"].split()
    ds = ds.assign(interpenetration_max=ds[["I_A_max", "I_B_max", "I_C_max", "I_D_max"]].to_array().max("variable"))
    fixed = {name: ds[name].values[0] for name in axes_names[2:]}
    ds = ds.isel({name: 0 for name in axes_names[2:]})
    variables = [v for v in MAP_VARIABLES if v[0] in ds and np.isfinite(ds[v[0]].values).any()]
    models = [str(m) for m in ds["model"].values]
    height = 3.6 * len(models) + 0.6
    fig = Figure(figsize=(4.2 * len(variables), height), dpi=150, layout="constrained")
    fig.get_layout_engine().set(rect=(0, 0.3 / height, 1, 1 - 0.3 / height))  # room for the caption
    FigureCanvasAgg(fig)
    axs = fig.subplots(len(models), len(variables), squeeze=False)
    x_name = axes_names[0]
    x, x_ticks = _positions(ds, x_name)
    for r, model in enumerate(models):
        for c, (name, label, scale, unit) in enumerate(variables):
            ax = axs[r, c]
            data = ds[name].sel(model=model)
            if not np.isfinite(data.values).any():  # e.g. the sticking rotation of compliant sliding
                ax.set_axis_off()
                ax.text(0.5, 0.5, f"{label}:\nnot defined for {model}", ha="center", va="center",
                        transform=ax.transAxes, color="0.4")
                continue
            exceeded = ds["capacity_exceeded"].sel(model=model).values.astype(bool)
            failed = ds["failed"].sel(model=model).values.astype(bool)
            if len(axes_names) == 1:
                ax.plot(x, scale * data.values, "o-", ms=3)
                ax.plot(x[exceeded], scale * data.values[exceeded], "rx", label="capacity exceeded")
                ax.set_ylabel(f"{label} ({unit})")
            else:
                y, y_ticks = _positions(ds, axes_names[1])
                mesh = ax.pcolormesh(x, y, scale * data.values.T, shading="nearest", cmap="viridis")
                fig.colorbar(mesh, ax=ax, label=f"{label} ({unit})")
                if exceeded.any():
                    ax.contour(x, y, exceeded.T.astype(float), levels=[0.5], colors="red", linewidths=1.2)
                if failed.any():
                    ax.contourf(x, y, failed.T.astype(float), levels=[0.5, 1.5], colors="none", hatches=["///"])
                    ax.contour(x, y, failed.T.astype(float), levels=[0.5], colors="0.3", linewidths=0.8)
                for mark, point in marks.items():
                    px = _mark_position(ds, x_name, point)
                    py = _mark_position(ds, axes_names[1], point)
                    if px is not None and py is not None:
                        ax.plot(px, py, "w*", ms=11, mec="k")
                        ax.annotate(mark, (px, py), xytext=(4, 4), textcoords="offset points", fontsize=8,
                                    color="w", path_effects=None, bbox={"fc": "k", "alpha": 0.4, "pad": 1})
                ax.set_ylabel(_label(axes_names[1], ds))
                if y_ticks:
                    ax.set_yticks(y, y_ticks)
            ax.set_xlabel(_label(x_name, ds))
            if x_ticks:
                ax.set_xticks(x, x_ticks)
            ax.set_title(f"{model}: {label}", fontsize=10)
    note = ", ".join(f"{k} = {v}" for k, v in fixed.items())
    fig.suptitle(f"Study {ds.attrs['study']}: summaries over the sweep" + (f" ({note})" if note else ""))
    fig.text(0.5, 0.002, caption + " — red line: pad reaches a retaining ring; hatched: no solution (failed)",
             ha="center", va="bottom", fontsize=8, style="italic")
    return fig


def _mark_position(ds, name, point):
    if name not in point:
        return None
    values = ds[name].values
    if values.dtype.kind in "OUS":
        hits = [i for i, v in enumerate(values) if str(v) == str(point[name])]
        return float(hits[0]) if hits else None
    return float(point[name])


def histories(datasets: list, caption: str) -> Figure:
    """theta2, rise and max |interpenetration| against time for (label, dataset) pairs."""
    fig = Figure(figsize=(13, 8), dpi=150, layout="constrained")
    fig.get_layout_engine().set(rect=(0, 0.3 / 8, 1, 1 - 0.3 / 8))
    FigureCanvasAgg(fig)
    axs = fig.subplots(3, 1, sharex=True)
    for label, ds in datasets:
        t = ds["t"].values
        interp = np.max([ds[f"I_{c}"].values for c in "ABCD"], axis=0)
        axs[0].plot(t, ds["theta2"].values, lw=1, label=label)
        axs[1].plot(t, 100 * ds["rise"].values, lw=1, label=label)
        axs[2].plot(t, 1e3 * interp, lw=1, label=label)
    axs[0].set_ylabel("θ² (°)")
    axs[1].set_ylabel("rise of RB3 (cm)")
    axs[2].set_ylabel("max interpenetration (mm)")
    axs[2].set_xlabel("t (s)")
    axs[0].legend(fontsize=8, ncols=2)
    fig.suptitle("Time histories of selected study cases")
    fig.text(0.5, 0.0, caption, ha="center", va="bottom", fontsize=8, style="italic")
    return fig
