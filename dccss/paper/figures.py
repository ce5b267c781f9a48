"""Figures 7-12 and 17-20 of Bianco, Monti & Belfiore (2021), drawn from result datasets only.

What each figure shows is data: a ``FigureSpec`` (parsed from the ``figures:`` section of a study
configuration by ``figure_spec``, in ``dccss.paper.specs``) names its kind, title and panels, and
``DRAW`` maps each kind to the function that draws it. Each figure is a plain
``matplotlib.figure.Figure`` (no pyplot, no global state; freed when unreferenced). Datasets are
those of ``dccss.simulate`` ("cases") and ``dccss.breakaway`` ("breakaway"); their values are SI
(angles in degrees) and are converted to cm, mm or µm only for plotting.

Typical use::

    spec = figure_spec("fig09", config["figures"]["fig09"])   # kind, title and panels
    fig = render(spec, datasets, "case set: as_reported")      # one dataset per panel, in order
    save(fig, "fig09.png", "fig09.pdf")
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from string import ascii_lowercase

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from ..drawing import (
    CORNER_STYLE,
    I_LABEL,
    body_shapes,
    caption_line,
    configuration_of,
    corner_inset,
    draw_device,
    drop_unused,
    frame_points,
    grid_shape,
    headroom,
    legend_on,
    length_unit,
    new_figure,
    plot_corners,
    step_path,
    twin_axis,
)
from ..mechanics.kinematics import CORNERS
from ..results import geometry_from_attrs
from .specs import KINDS, FigureSpec, Panel, Runs, SpecError, figure_spec, figure_specs  # noqa: F401 (the API)

#: the paper's symbols as the titles of the configuration write them (plain text, one line) and as the
#: axes print them (mathtext)
TITLE_SYMBOLS = {r"\|C_q\|": r"$|\mathbf{C_q}|$", r"R_y(?:³|\^3)": r"$R_y^3$",
                 **{rf"\bI_{c}\b": I_LABEL[c] for c in CORNERS},
                 # the case sets' descriptions (config/config.yaml), printed in the caption line
                 r"\bX_g,max\b": r"$X_{g,\max}$", r"\btheta2\(t0\)": r"$\theta^2(t_0)$",
                 r"\bsin\(alpha1 - alpha21\)": r"$\sin(\alpha^1 - \alpha^{21})$"}


def title_text(title):
    r"""A title or caption with the paper's symbols as the axes print them: "|C_q|" -> $|\mathbf{C_q}|$,
    "R_y³" -> $R_y^3$, "I_A" -> $I_A^1$ (the corners' labels), "X_g,max" -> $X_{g,\max}$, "theta2(t0)" ->
    $\theta^2(t_0)$."""
    for pattern, symbol in TITLE_SYMBOLS.items():
        title = re.sub(pattern, lambda _, symbol=symbol: symbol, title)
    return title


def _finish(fig, fig_id, caption, title=None):
    """Heading "Figure N. <title>" (N from ``fig_id`` "figNN"; the title's symbols in mathtext, see
    ``title_text``), caption line (laid out when saved: ``drawing.save``)."""
    number = re.fullmatch(r"fig([0-9]+)", fig_id)
    heading = f"Figure {int(number[1])}." if number else fig_id
    fig.suptitle(f"{heading} {title_text(title)}" if title else heading, fontsize=12)
    caption_line(fig, title_text(caption))
    return fig


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
    nrows, ncols = grid_shape(len(spec.panels), rows=2)
    fig, axes = new_figure((13, 4.5 * nrows), nrows, ncols)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ds, ax = _sweep(ds, panel), axes[k % nrows, k // nrows]
        th = ds["theta2_0"].values
        factor, unit = length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for c in CORNERS:
            ax.plot(th, factor * ds[f"I_{c}"].values, label=I_LABEL[c], **CORNER_STYLE[c])
        ax.set_ylabel(f"interpenetration ({unit})")
        ax.set_xlabel(r"$\theta^2(t_0)$ (°)")
        tw = twin_axis(ax, "0.3", r"$|\mathbf{C_q}|$ (m)")
        tw.plot(th, ds["det_Cq"].values, color="0.3", ls=":", lw=1.4, marker=".", ms=4, label=r"$|\mathbf{C_q}|$")
        ax.set_title(f"({ascii_lowercase[k]}) {_sweep_label(panel)}, ΔX$_g(t_1)$ = {100 * panel.dXg:g} cm", loc="left")
        ax.margins(y=0.15)
        headroom(ax, tw)  # keep the legend clear of both curves
        legend_on(ax, tw, ncols=5, loc="upper center")
    drop_unused(axes, len(spec.panels), by_columns=True)
    return _finish(fig, spec.id, caption, spec.title)


def _breakaway_configurations(spec, datasets, caption):
    """Fig. 8: initial and displaced configurations at the sweep point nearest each panel's θ²(t₀),
    with the four corners zoomed; panels side by side."""
    fig, axes = new_figure((13, 7.6), 1, len(spec.panels))
    places = {"A": [0.01, 0.01, 0.40, 0.27], "B": [0.59, 0.01, 0.40, 0.27],
              "C": [0.01, 0.70, 0.40, 0.27], "D": [0.59, 0.70, 0.40, 0.27]}
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ds, ax = _sweep(ds, panel).sel(theta2_0=panel.theta2_0, method="nearest"), axes[0, k]
        g = geometry_from_attrs(ds.attrs)
        shapes = body_shapes(g)
        q0, q1 = configuration_of(ds, "_t0"), configuration_of(ds)
        points = draw_device(ax, g, q1, shapes, corners=True, label="displaced, $t_1$")
        points = np.vstack([points, draw_device(ax, g, q0, shapes, fill=False, colour="0.35", ls="--",
                                            label="initial, $t_0$")])
        frame_points(ax, points, extra_y=(30, 30))
        values = {c: float(ds[f"I_{c}"]) for c in CORNERS}
        loaded = "BC" if values["B"] + values["C"] > values["A"] + values["D"] else "AD"
        for c in CORNERS:
            corner_inset(ax, g, q1, shapes, c, values[c], places[c], c in loaded)
        ax.set_title(f"({ascii_lowercase[k]}) {_sweep_label(panel)}, $\\theta^2(t_0)$ = "
                     f"{float(ds['theta2_0']):.1f}°, ΔX$_g(t_1)$ = {100 * panel.dXg:g} cm, "
                     f"$\\theta^2(t_1)$ = {q1['theta2']:.2f}°", loc="left")
        ax.legend(fontsize=8, loc="upper center")
    return _finish(fig, spec.id, caption, spec.title)


def _diagonals(spec, datasets, caption):
    """Fig. 9: interpenetration histories on diagonal A²D² (top) and B²C² (bottom), a column per panel."""
    fig, axes = new_figure((14, 7.5), 2, len(spec.panels), sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        t = ds["t"].values
        factor, unit = length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for row, pair in enumerate(("AD", "BC")):
            plot_corners(axes[row, k], t, ds, pair, factor, unit,
                     f"diagonal ${pair[0]}^2{pair[1]}^2$\ninterpenetration, < 0: gap")
        axes[0, k].set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}", loc="left")
        axes[1, k].set_xlabel("t (s)")
    return _finish(fig, spec.id, caption, spec.title)


def _differences(spec, datasets, caption):
    """Fig. 10: I_A − I_B (top) and I_D − I_C (bottom), corners sliding on the same surface; a column
    per panel."""
    fig, axes = new_figure((12, 7), 2, len(spec.panels), sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        t = ds["t"].values
        for row, (a, b) in enumerate((("A", "B"), ("D", "C"))):
            ax, diff = axes[row, k], 1e6 * (ds[f"I_{a}"] - ds[f"I_{b}"]).values
            ax.plot(t, diff, color=CORNER_STYLE[a]["color"], lw=1.4, label=f"{I_LABEL[a]} − {I_LABEL[b]}")
            ax.axhline(0, color="0.6", lw=0.6)
            ax.set_ylabel(f"{I_LABEL[a]} − {I_LABEL[b]} (µm)")
            ax.ticklabel_format(axis="y", style="plain", useOffset=False)
            headroom(ax)
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
    shapes = body_shapes(g)
    t = ds["t"].values
    fig, axes = new_figure((13, 8.6), 2, 2, height_ratios=(1, 0.95))
    ax = axes[0, 0]
    ax.plot(t, 100 * ds["Xg"].values, color="k", lw=1.6, label="$X_g$")
    ax.set_ylabel("$X_g$ (cm)")
    tw = twin_axis(ax, "tab:purple", r"$\dot X_g$ (cm/s)")
    tw.plot(t, 100 * ds["Xg_dot"].values, color="tab:purple", ls="--", lw=1.2, label=r"$\dot X_g$")
    headroom(ax, tw)
    legend_on(ax, tw, loc="upper center", ncols=2)
    ax.set_title(f"(a) imposed ground motion, {_case_label(panel)}", loc="left")
    ax = axes[0, 1]
    ax.plot(t, ds["theta2"].values, color="tab:blue", lw=1.6, label=r"$\theta^2$")
    ax.set_ylabel(r"$\theta^2$ (°)", color="tab:blue")
    tw = twin_axis(ax, "tab:brown", r"$R_y^3$ rise above rest (cm)")
    tw.plot(t, 100 * ds["rise"].values, color="tab:brown", ls="--", lw=1.4, label=r"$R_y^3$ rise")
    headroom(ax, tw)
    legend_on(ax, tw, loc="upper center", ncols=2)
    ax.set_title("(b) pad rotation and upper-plate rise", loc="left")
    for ax in axes[0]:
        ax.set_xlabel("t (s)")
    points = []
    for k, (n, name) in enumerate(((0, "initial"), (-1, "final"))):
        ax, q = axes[1, k], configuration_of(ds.isel(t=n))
        points.append(draw_device(ax, g, q, shapes, corners=True))
        ax.set_title(f"({'cd'[k]}) {name} configuration, t = {t[n]:.2f} s: $X_g$ = {100 * q['Rx1']:.1f} cm, "
                     f"$\\theta^2$ = {q['theta2']:.2f}°, rise = {100 * float(ds['rise'][n]):.2f} cm",
                     loc="left", fontsize=10)
    for ax in axes[1]:  # same limits: both drawings at the same scale
        frame_points(ax, np.vstack(points))
    return _finish(fig, spec.id, caption, spec.title)


def _interpenetration(spec, datasets, caption):
    """Fig. 17: interpenetration histories at the four corners; panels fill the rows of a
    two-column grid."""
    n = len(spec.panels)
    nrows, ncols = grid_shape(n, cols=2)
    fig, axes = new_figure((13, 4.25 * nrows), nrows, ncols, sharex=True)
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ax = axes[k // ncols, k % ncols]
        factor, unit = length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        plot_corners(ax, ds["t"].values, ds, CORNERS, factor, unit)
        ax.set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}", loc="left")
    for k in range(max(0, n - ncols), n):  # the lowest panel of each column
        axes[k // ncols, k % ncols].set_xlabel("t (s)")
        if k // ncols < nrows - 1:
            axes[k // ncols, k % ncols].xaxis.set_tick_params(labelbottom=True)
    drop_unused(axes, n)
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
    fig = new_figure((13, 10), None)
    axd = fig.subplot_mosaic([["a", "b"], ["c", "d"], ["e", "e"]], width_ratios=(2.6, 1))
    for (main, zoom), (end, stick, label) in zip((("a", "b"), ("c", "d")), series.values()):
        tt, vv = step_path(t, end, stick)
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
    velocity = 100 * ds["Xg_dot"].values
    ax.plot(mid, stick_rotation, color="tab:red", lw=1.0, label=r"$\theta^2_{stick}(t_n) - \theta^2(t_{n-1})$")
    ax.set_ylabel(r"$\Delta\theta^2$ in sticking (°)", color="tab:red")
    ax.set_xlabel("t (s)")
    tw = twin_axis(ax, "tab:purple", r"$\dot X_g$ (cm/s)")
    tw.plot(t, velocity, color="tab:purple", lw=5.0, alpha=0.4, solid_capstyle="butt", label=r"$\dot X_g$")
    ax.set_zorder(tw.get_zorder() + 1)  # the sticking rotation over the wide band of the velocity
    ax.patch.set_visible(False)
    k, apart = proportional(stick_rotation, np.interp(mid, t, velocity))
    if np.isfinite(k) and k != 0:  # the velocity axis at the scale where k Xg_dot falls on the rotation
        lo, hi = ax.get_ylim()
        tw.set_ylim(*sorted((lo / k, hi / k)))
        tw.get_lines()[0].set_label(rf"$\dot X_g$, scaled by {k:.3g} °/(cm/s): they coincide within {apart:.2g}°")
    legend_on(ax, tw, loc="lower right", bbox_to_anchor=(1, 1), ncols=1, borderaxespad=0.2)
    ax.set_title(f"(e) sticking rotation of the pad (max |Δθ²| = {np.nanmax(np.abs(stick_rotation)):.2f}°) "
                 "and ground velocity", loc="left")
    return _finish(fig, spec.id, caption, spec.title)


def proportional(y, x):
    """(k, max |y - k x|): the least-squares factor of y = k x (through 0) over the finite pairs, and the
    largest distance of y from k x. The sticking rotation of a step is such a multiple of the ground
    velocity: the jammed pad turns with RB1 by the step's ground displacement, about X_g_dot dt."""
    ok = np.isfinite(y) & np.isfinite(x)
    if not ok.any() or not np.any(x[ok]):
        return float("nan"), float("nan")
    k = float(x[ok] @ y[ok] / (x[ok] @ x[ok]))
    return k, float(np.max(np.abs(y[ok] - k * x[ok])))


def _two_phase(spec, datasets, caption):
    """Fig. 20: configurations at the start of the step ending nearest each panel's t, at the end of
    its sticking phase and at the end of its slipping phase; stick-slip panels side by side."""
    fig, axes = new_figure((13, 5.9), 1, len(spec.panels))
    styles = (("0.45", "--"), ("tab:red", "-"), ("tab:blue", "-."))
    for k, (panel, ds) in enumerate(zip(spec.panels, datasets)):
        ax = axes[0, k]
        g = geometry_from_attrs(ds.attrs)
        shapes = body_shapes(g)
        n = max(1, int(np.abs(ds["t"].values - panel.t).argmin()))
        now = ds.isel(t=n)
        configs = ((configuration_of(ds.isel(t=n - 1)), "(1) start of step"),
                   (configuration_of(now, "_stick"), "(2) end of sticking"),
                   (configuration_of(now), "(3) end of slipping"))
        points = []
        for (q, name), (colour, ls) in zip(configs, styles):
            label = f"{name}: $\\theta^2$ = {q['theta2']:.2f}°"
            points.append(draw_device(ax, g, q, shapes, fill=False, colour=colour, ls=ls, label=label, lw=1.1,
                                  corners=name.startswith("(2)")))
        frame_points(ax, np.vstack(points))
        diagonal = ("$A^2D^2$", "$B^2C^2$")[int(now["sticking_diagonal"])]
        ax.set_title(f"({ascii_lowercase[k]}) {_case_label(panel)}, step ending at t = {float(now['t']):.3f} s,\n"
                     f"$\\dot X_g$ = {100 * float(now['Xg_dot']):.2f} cm/s, sticking diagonal {diagonal}", loc="left")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), handlelength=3.5)
    return _finish(fig, spec.id, caption, spec.title)


# --- the drawing function of each kind of figure (``specs.KINDS``: what each draws) ---------
DRAW: dict[str, Callable[[FigureSpec, Sequence, str], Figure]] = {
    "breakaway": _breakaway,
    "breakaway_configurations": _breakaway_configurations,
    "diagonals": _diagonals,
    "differences": _differences,
    "global_coordinates": _global_coordinates,
    "interpenetration": _interpenetration,
    "sticking": _sticking,
    "two_phase": _two_phase,
}

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
    matplotlib.figure.Figure (no pyplot: freed when unreferenced), laid out when saved
    (``dccss.drawing.save``) or drawn.
    """
    if len(datasets) != len(spec.panels):
        raise ValueError(f"{spec.id} draws {len(spec.panels)} panel(s), got {len(datasets)} dataset(s)")
    return DRAW[spec.kind](spec, list(datasets), caption)
