"""Figures 7-12 and 17-20 of Bianco, Monti & Belfiore (2021), drawn from result datasets only.

Each figure is a plain ``matplotlib.figure.Figure`` (no pyplot, no global state; freed when
unreferenced). Datasets are those of ``dccss.simulate`` ("cases") and ``dccss.breakaway``;
their values are SI (angles in degrees) and are converted to cm, mm or µm only for plotting.

Typical use::

    fig = render("fig09", datasets, "case set: as_reported")   # datasets keyed like FIGURES[...].keys
    save(fig, "fig09.png", "fig09.pdf")
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import partial

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from matplotlib.ticker import MaxNLocator

from .constraints import Q_NAMES
from .files import write_atomic
from .kinematics import CORNERS
from .results import geometry_from_attrs

CORNER_STYLE = {  # A/D and B/C superimpose: solid wide under dashed narrow
    "A": dict(color="tab:blue", ls="-", lw=2.6, zorder=2),
    "B": dict(color="tab:orange", ls="-", lw=2.6, zorder=2),
    "C": dict(color="tab:green", ls=(0, (4, 2)), lw=1.3, zorder=3),
    "D": dict(color="tab:red", ls=(0, (4, 2)), lw=1.3, zorder=3),
}
I_LABEL = {"A": r"$I_A^1$", "B": r"$I_B^1$", "C": r"$I_C^3$", "D": r"$I_D^3$"}
PLATE_COLOUR, PAD_COLOUR = "0.82", "#f2b35e"
CAPTION_INCHES = 0.35  # strip kept free at the bottom for the caption line
DPI = 150
PNG_METADATA = {"Software": None}
PDF_METADATA = {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": None}


@dataclass(frozen=True)
class FigureSpec:
    """A paper figure: which datasets it needs and how to draw it.

    Attributes
    ----------
    kind : "breakaway" or "cases".
    keys : datasets needed, (prototype, model, dt) for "cases", (prototype, dXg_m) for "breakaway".
    draw : (datasets keyed like ``keys``, caption line) -> Figure.
    title : one-line description (report caption).
    """

    kind: str
    keys: tuple
    draw: Callable[[dict, str], Figure]
    title: str


# --- helpers --------------------------------------------------------------------------------
def _figure(size, nrows=1, ncols=1, **kwargs):
    """A constrained-layout figure of fixed size with a bottom strip for the caption."""
    fig = Figure(figsize=size, dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)  # one Agg renderer for the layout pass and the PNG: text metrics computed once
    fig.get_layout_engine().set(rect=(0, CAPTION_INCHES / size[1], 1, 1 - CAPTION_INCHES / size[1]), w_pad=0.08)
    if nrows is None:
        return fig
    return fig, fig.subplots(nrows, ncols, squeeze=False, **kwargs)


def _finish(fig, fig_id, caption):
    fig.suptitle(f"Figure {int(fig_id[3:])}. {FIGURES[fig_id].title}", fontsize=12)
    fig.text(0.5, 0.1 * CAPTION_INCHES / fig.get_figheight(), caption, ha="center", va="bottom",
             fontsize=9, style="italic", color="0.25")
    fig.draw_without_rendering()  # constrained layout once, then frozen: each save draws only once
    fig.set_layout_engine(None)
    # the layout solver's last digits vary between processes: round the frozen axes positions so the
    # PDF coordinates (printed to 1e-6 pt) are the same in every run
    for ax in fig.axes:
        ax.set_position([round(v, 6) for v in ax.get_position(original=False).bounds], which="both")
    return fig


def _length_unit(*values):
    """(factor, unit) making lengths in m readable: µm below 1 mm, else mm."""
    peak = max((float(np.nanmax(np.abs(v))) for v in values if np.size(v)), default=0.0)
    return (1e6, "µm") if peak < 1e-3 else (1e3, "mm")


def _headroom(*axes, frac=0.3):
    """Extend the y range upwards to leave room for a legend inside the axes."""
    for ax in axes:
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + frac * (hi - lo))


def _legend(ax, *axes, **kwargs):
    """One legend for an axes and its twins."""
    handles = [h for a in (ax, *axes) for h in a.get_legend_handles_labels()[0]]
    ax.legend(handles, [h.get_label() for h in handles], **{"fontsize": 8, **kwargs})


def _twin(ax, colour, label):
    tw = ax.twinx()
    tw.set_ylabel(label, color=colour)
    tw.tick_params(axis="y", colors=colour)
    return tw


def _corners(ax, t, ds, which, factor, unit, what="interpenetration, < 0: gap"):
    for c in which:
        ax.plot(t, factor * ds[f"I_{c}"].values, label=I_LABEL[c], **CORNER_STYLE[c])
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_ylabel(f"{what} ({unit})")
    _headroom(ax)
    ax.legend(fontsize=8, ncols=len(which), loc="upper right")


def _case_label(key):
    proto, _, dt = key
    return f"{proto}, Δt = {dt:g} s"


# --- drawing the device to scale --------------------------------------------------------------
def _pose(u, Rx, Ry, theta_deg):
    """Global coordinates R + A(theta) u of local points u (..., 2)."""
    c, s = np.cos(np.radians(theta_deg)), np.sin(np.radians(theta_deg))
    u = np.asarray(u, dtype=float)
    return np.stack([Rx + c * u[..., 0] - s * u[..., 1], Ry + s * u[..., 0] + c * u[..., 1]], axis=-1)


def _q(ds, suffix=""):
    """Generalised coordinates {name: value} of a 0-d dataset (m, degrees)."""
    return {name: float(ds[name + suffix]) for name in Q_NAMES}


def _body(q, i):
    return q[f"Rx{i}"], q[f"Ry{i}"], q[f"theta{i}"]


def _shapes(g):
    """Local outlines of RB1, RB2, RB3 with fine arcs (interpenetrations are µm to mm)."""
    return {1: g.plate_outline(1, n_arc=1441), 2: g.pad_outline(n_arc=241), 3: g.plate_outline(3, n_arc=1441)}


def _device(ax, g, q, shapes, *, colour=None, ls="-", label=None, fill=True, corners=False, lw=0.8):
    """Draw RB1, RB2, RB3 at q (filled, or outlined in ``colour``) in cm; return their points."""
    drawn = []
    for i in (1, 3, 2):
        xy = 100 * _pose(shapes[i], *_body(q, i))
        if fill:
            ax.add_artist(Polygon(xy, closed=True, fc=PAD_COLOUR if i == 2 else PLATE_COLOUR, ec="k", lw=lw,
                                 alpha=0.85 if i == 2 else 1.0, label=label if i == 2 else None))
        else:
            ax.add_artist(Polygon(xy, closed=True, fill=False, ec=colour, ls=ls, lw=lw * (1.8 if i == 2 else 1),
                                 label=label if i == 2 else None))
        drawn.append(xy)
    if corners:
        pts = 100 * _pose(g.pad_corners, *_body(q, 2))
        for (x, y), c, dx, dy in zip(pts, CORNERS, (-1, 1, -1, 1), (-1, -1, 1, 1)):
            ax.annotate(f"${c}^2$", (x, y), xytext=(9 * dx, 7 * dy), textcoords="offset points", fontsize=9,
                        ha="center", va="center", bbox=dict(fc="white", ec="none", alpha=0.7, pad=0.5))
    c1 = 100 * _pose(g.circle_centres[0], *_body(q, 1))
    c3 = 100 * _pose(g.circle_centres[1], *_body(q, 3))
    ax.plot([c1[0], c3[0]], [c1[1], c3[1]], color=colour or "0.3", ls=":", lw=0.9)
    return np.vstack(drawn)


def _frame(ax, points, margin=3.0, extra_y=(0.0, 0.0)):
    """Equal-aspect limits around the drawn points (cm), with room below/above for insets."""
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1] - extra_y[0], hi[1] + extra_y[1])
    ax.set_aspect("equal")
    ax.set_xlabel("X (cm)")
    ax.set_ylabel("Y (cm)")


def _corner_inset(ax, g, q, shapes, corner, value, bounds, loaded):
    """Zoom on one pad corner, with the radial interpenetration segment and its value."""
    i = CORNERS.index(corner)
    plate, radius = (1, g.R1) if corner in "AB" else (3, g.R3)
    point = _pose(g.pad_corners[i], *_body(q, 2))
    centre = _pose(g.circle_centres[0 if plate == 1 else 1], *_body(q, plate))
    foot = centre + radius * (point - centre) / np.hypot(*(point - centre))
    half = max(2.5 * abs(value), 0.5e-3)
    ins = ax.inset_axes(bounds)
    for j in (1, 3, 2):
        ins.add_artist(Polygon(100 * _pose(shapes[j], *_body(q, j)), closed=True, ec="k", lw=0.8,
                              fc=PAD_COLOUR if j == 2 else PLATE_COLOUR, alpha=0.7 if j == 2 else 1.0))
    ins.plot(100 * np.array([point[0], foot[0]]), 100 * np.array([point[1], foot[1]]), color="crimson", lw=1.5)
    ins.plot(*(100 * point), "o", color="crimson", ms=3)
    ins.set_xlim(100 * (point[0] - half), 100 * (point[0] + half))
    ins.set_ylim(100 * (point[1] - half), 100 * (point[1] + half))
    ins.set_aspect("equal")
    ins.set_xticks([])
    ins.set_yticks([])
    factor, unit = _length_unit(value)
    ins.set_title(f"{I_LABEL[corner]} = {factor * value:.3g} {unit}  (window {2e3 * half:.2g} mm)", fontsize=8,
                  color="crimson" if loaded else "k", pad=2)
    for side in ins.spines.values():
        side.set(color="crimson" if loaded else "0.3", lw=1.6 if loaded else 0.8)
    ax.indicate_inset_zoom(ins, edgecolor="0.5", alpha=0.5, lw=0.6)


# --- figures -------------------------------------------------------------------------------------
def _fig07(datasets, caption):
    fig, axes = _figure((13, 9), 2, 2)
    for k, (proto, dX) in enumerate(FIGURES["fig07"].keys):
        ds, ax = datasets[(proto, dX)], axes[k % 2, k // 2]
        th = ds["theta2_0"].values
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for c in CORNERS:
            ax.plot(th, factor * ds[f"I_{c}"].values, label=I_LABEL[c], **CORNER_STYLE[c])
        ax.set_ylabel(f"interpenetration ({unit})")
        ax.set_xlabel(r"$\theta^2(t_0)$ (°)")
        tw = _twin(ax, "0.3", r"$|\mathbf{C_q}|$ (m)")
        tw.plot(th, ds["det_Cq"].values, color="0.3", ls=":", lw=1.4, marker=".", ms=4, label=r"$|\mathbf{C_q}|$")
        ax.set_title(f"({'abcd'[k]}) {proto}, ΔX$_g(t_1)$ = {100 * dX:g} cm", loc="left")
        ax.margins(y=0.15)
        _headroom(ax, tw)  # keep the legend clear of both curves
        _legend(ax, tw, ncols=5, loc="upper center")
    return _finish(fig, "fig07", caption)


def _fig08(datasets, caption):
    fig, axes = _figure((13, 7.6), 1, 2)
    places = {"A": [0.01, 0.01, 0.40, 0.27], "B": [0.59, 0.01, 0.40, 0.27],
              "C": [0.01, 0.70, 0.40, 0.27], "D": [0.59, 0.70, 0.40, 0.27]}
    for k, ((proto, dX), th0) in enumerate(zip(FIGURES["fig08"].keys, (-6.0, -8.8))):
        ds, ax = datasets[(proto, dX)].sel(theta2_0=th0, method="nearest"), axes[0, k]
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
        ax.set_title(f"({'ab'[k]}) {proto}, $\\theta^2(t_0)$ = {float(ds['theta2_0']):.1f}°, "
                     f"ΔX$_g(t_1)$ = {100 * dX:g} cm, $\\theta^2(t_1)$ = {q1['theta2']:.2f}°", loc="left")
        ax.legend(fontsize=8, loc="upper center")
    return _finish(fig, "fig08", caption)


def _fig09(datasets, caption):
    fig, axes = _figure((14, 7.5), 2, 4, sharex=True)
    for k, key in enumerate(FIGURES["fig09"].keys):
        ds = datasets[key]
        t = ds["t"].values
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        for row, pair in enumerate(("AD", "BC")):
            _corners(axes[row, k], t, ds, pair, factor, unit,
                     f"diagonal ${pair[0]}^2{pair[1]}^2$\ninterpenetration, < 0: gap")
        axes[0, k].set_title(f"({'abcd'[k]}) {_case_label(key)}", loc="left")
        axes[1, k].set_xlabel("t (s)")
    return _finish(fig, "fig09", caption)


def _fig10(datasets, caption):
    fig, axes = _figure((12, 7), 2, 2, sharex=True)
    for k, key in enumerate(FIGURES["fig10"].keys):
        ds = datasets[key]
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
        axes[0, k].set_title(f"({'ab'[k]}) {_case_label(key)}", loc="left")
        axes[1, k].set_xlabel("t (s)")
    return _finish(fig, "fig10", caption)


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


def _overview(fig_id, datasets, caption):
    """Figs. 11, 12: X_g, dX_g/dt; theta2, rise; initial and final configurations."""
    key = FIGURES[fig_id].keys[0]
    ds = datasets[key]
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
    ax.set_title(f"(a) imposed ground motion, {_case_label(key)}", loc="left")
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
    return _finish(fig, fig_id, caption)


def _fig17(datasets, caption):
    fig, axes = _figure((13, 8.5), 2, 2, sharex=True)
    for k, key in enumerate(FIGURES["fig17"].keys):
        ds, ax = datasets[key], axes[k // 2, k % 2]
        factor, unit = _length_unit(*(ds[f"I_{c}"].values for c in CORNERS))
        _corners(ax, ds["t"].values, ds, CORNERS, factor, unit)
        ax.set_title(f"({'abcd'[k]}) {_case_label(key)}", loc="left")
    for ax in axes[1]:
        ax.set_xlabel("t (s)")
    return _finish(fig, "fig17", caption)


def _step_path(t, end, stick):
    """Polyline start -> end of sticking (at mid-step) -> end of slipping, for every step."""
    tt = np.empty(2 * t.size - 1)
    vv = np.empty_like(tt)
    tt[0::2], vv[0::2] = t, end
    tt[1::2], vv[1::2] = 0.5 * (t[1:] + t[:-1]), stick[1:]
    return tt, vv


def _sticking(fig_id, t_zoom, datasets, caption):
    """Figs. 18, 19: theta2 and R_y^3 at the end of each step and of each sticking phase."""
    key = FIGURES[fig_id].keys[0]
    ds = datasets[key]
    t = ds["t"].values
    mid = 0.5 * (t[1:] + t[:-1])
    rest = ds["Ry3"].values - ds["rise"].values
    series = {"theta2": (ds["theta2"].values, ds["theta2_stick"].values, r"$\theta^2$ (°)"),
              "rise": (100 * ds["rise"].values, 100 * (ds["Ry3_stick"].values - rest), r"$R_y^3$ rise (cm)")}
    n = max(1, int(np.abs(t - t_zoom).argmin()))
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
    axd["a"].set_title(f"(a) pad rotation, {_case_label(key)}", loc="left")
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
    return _finish(fig, fig_id, caption)


def _fig20(datasets, caption):
    fig, axes = _figure((13, 5.9), 1, 2)
    styles = (("0.45", "--"), ("tab:red", "-"), ("tab:blue", "-."))
    for k, (key, t_target) in enumerate(zip(FIGURES["fig20"].keys, (0.73, 0.94))):
        ds, ax = datasets[key], axes[0, k]
        g = geometry_from_attrs(ds.attrs)
        shapes = _shapes(g)
        n = max(1, int(np.abs(ds["t"].values - t_target).argmin()))
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
        ax.set_title(f"({'ab'[k]}) {_case_label(key)}, step ending at t = {float(now['t']):.3f} s,\n"
                     f"$\\dot X_g$ = {100 * float(now['Xg_dot']):.2f} cm/s, sticking diagonal {diagonal}", loc="left")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), handlelength=3.5)
    return _finish(fig, "fig20", caption)


def _four(model):
    """(a, b) DFP1 with dt 0.01, 0.001 s; (c, d) the same for DFP2."""
    return tuple((proto, model, dt) for proto in ("DFP1", "DFP2") for dt in (0.01, 0.001))


FIGURES: dict[str, FigureSpec] = {
    "fig07": FigureSpec("breakaway", tuple((p, dX) for p in ("DFP1", "DFP2") for dX in (0.05, 0.10)), _fig07,
                        "Breakaway (compliant sliding): corner interpenetration after the first step and |C_q| "
                        "vs θ²(t₀)"),
    "fig08": FigureSpec("breakaway", (("DFP1", 0.10), ("DFP2", 0.05)), _fig08,
                        "Breakaway (compliant sliding): initial and displaced configurations, corner zooms"),
    "fig09": FigureSpec("cases", _four("compliant"), _fig09,
                        "Compliant sliding: interpenetration time histories at the corners of RB2"),
    "fig10": FigureSpec("cases", (("DFP1", "compliant", 0.01), ("DFP1", "compliant", 0.001)), _fig10,
                        "Compliant sliding, DFP1: difference of interpenetration I_A − I_B and I_D − I_C"),
    "fig11": FigureSpec("cases", (("DFP1", "compliant", 0.01),), partial(_overview, "fig11"),
                        "Compliant sliding, DFP1, Δt = 0.01 s: ground motion, θ², R_y³ and configurations"),
    "fig12": FigureSpec("cases", (("DFP2", "compliant", 0.001),), partial(_overview, "fig12"),
                        "Compliant sliding, DFP2, Δt = 0.001 s: ground motion, θ², R_y³ and configurations"),
    "fig17": FigureSpec("cases", _four("stick_slip"), _fig17,
                        "Stick-slip: interpenetration time histories at the corners of RB2"),
    "fig18": FigureSpec("cases", (("DFP1", "stick_slip", 0.001),), partial(_sticking, "fig18", 0.73),
                        "Stick-slip, DFP1, Δt = 0.001 s: θ² and R_y³ time histories with the sticking oscillation"),
    "fig19": FigureSpec("cases", (("DFP2", "stick_slip", 0.01),), partial(_sticking, "fig19", 0.94),
                        "Stick-slip, DFP2, Δt = 0.01 s: θ² and R_y³ time histories with the sticking oscillation"),
    "fig20": FigureSpec("cases", (("DFP1", "stick_slip", 0.001), ("DFP2", "stick_slip", 0.01)), _fig20,
                        "Stick-slip: configurations at the start of a step, end of sticking and end of slipping"),
}


def render(fig_id: str, datasets: dict, caption: str) -> Figure:
    """Draw one paper figure.

    Parameters
    ----------
    fig_id : key of ``FIGURES`` ("fig07" ... "fig20").
    datasets : mapping holding at least the datasets ``FIGURES[fig_id].keys``.
    caption : line printed at the bottom (e.g. the case set).

    Returns
    -------
    matplotlib.figure.Figure (no pyplot: freed when unreferenced).
    """
    spec = FIGURES[fig_id]
    missing = [key for key in spec.keys if key not in datasets]
    if missing:
        raise KeyError(f"{fig_id} needs the datasets {missing}")
    return spec.draw({key: datasets[key] for key in spec.keys}, caption)


def save(fig: Figure, png_path, pdf_path) -> None:
    """Write ``fig`` as PNG (150 dpi) and PDF, atomically and with reproducible bytes."""
    write_atomic(png_path, lambda f: fig.savefig(f, format="png", dpi=DPI, metadata=PNG_METADATA))
    write_atomic(pdf_path, lambda f: fig.savefig(f, format="pdf", metadata=PDF_METADATA))
