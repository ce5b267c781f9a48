"""Drawing results: figures of fixed size with reproducible bytes, and the device to scale.

Shared by the paper's figures (``dccss.paper.figures``), the study plots (``dccss.studies.plots``)
and the animations (``dccss.animation``): figures without pyplot (freed when unreferenced), laid
out once and frozen when saved (``freeze``; a figure that is only inspected is not laid out),
saved as PNG and PDF without varying metadata (``save``); the
plates, pad and rings drawn to scale from a configuration (``draw_device``) with zooms on the pad's
corners (``corner_inset``). Lengths are plotted in cm, mm or µm (``length_unit``), angles in
degrees.
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Polygon

from .files import write_atomic
from .mechanics.kinematics import CORNERS, Q_NAMES

CORNER_STYLE = {  # A/D and B/C superimpose: solid wide under dashed narrow
    "A": dict(color="tab:blue", ls="-", lw=2.6, zorder=2),
    "B": dict(color="tab:orange", ls="-", lw=2.6, zorder=2),
    "C": dict(color="tab:green", ls=(0, (4, 2)), lw=1.3, zorder=3),
    "D": dict(color="tab:red", ls=(0, (4, 2)), lw=1.3, zorder=3),
}
I_LABEL = {"A": r"$I_A^1$", "B": r"$I_B^1$", "C": r"$I_C^3$", "D": r"$I_D^3$"}
PLATE_COLOUR, PAD_COLOUR = "0.82", "#f2b35e"
CAPTION_INCHES = 0.35  # strip kept free at the bottom for the caption line
LINE_INCHES = 0.17  # and for each further line of it
DPI = 150
PNG_METADATA = {"Software": None}
PDF_METADATA = {"CreationDate": None, "ModDate": None, "Producer": None, "Creator": None}


def new_figure(size, nrows=1, ncols=1, caption_lines=1, **kwargs):
    """A constrained-layout figure of fixed size with a bottom strip for the caption (of ``caption_lines``
    lines: the figure grows by the lines beyond the first)."""
    strip = CAPTION_INCHES + LINE_INCHES * (caption_lines - 1)
    size = (size[0], size[1] + strip - CAPTION_INCHES)
    fig = Figure(figsize=size, dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)  # one Agg renderer for the layout pass and the PNG: text metrics computed once
    fig.get_layout_engine().set(rect=(0, strip / size[1], 1, 1 - strip / size[1]), w_pad=0.08)
    if nrows is None:
        return fig
    return fig, fig.subplots(nrows, ncols, squeeze=False, **kwargs)


def caption_line(fig, caption):
    """The caption, in italics, in the strip kept free at the bottom."""
    fig.text(0.5, 0.1 * CAPTION_INCHES / fig.get_figheight(), caption, ha="center", va="bottom",
             fontsize=9, style="italic", color="0.25")


def fit_width(text, fig, least=6.0):
    """Shrink the font of a figure-wide line (a heading naming a long case id) until it lies inside the
    figure, by half points down to ``least``."""
    renderer = fig.canvas.get_renderer()
    while text.get_fontsize() > least and text.get_window_extent(renderer).width > 0.98 * fig.bbox.width:
        text.set_fontsize(text.get_fontsize() - 0.5)
    return text


#: significant digits kept of the axis limits (see ``freeze``)
LIMIT_DIGITS = 9


def freeze(fig):
    """Lay the figure out once and freeze it, with reproducible bytes.

    Axis limits are rounded to ``LIMIT_DIGITS`` significant digits: autoscaled limits follow the
    data to its last bit, results at round-off differ in their last bits between machines, and the
    PDF prints tick positions to 1e-10 pt. The layout solver's last digits vary between processes:
    the frozen axes positions are rounded so that the PDF coordinates (1e-6 pt) are the same in
    every run. Each save then draws only once, and the layout costs no draw of its own: the
    layout engine runs by itself (what a draw would do first), on the renderer of the PNG.
    ``save`` calls it; a figure frozen already is left as it is (its limits and positions are
    rounded already)."""
    for ax in fig.axes:
        for get, set_ in ((ax.get_xlim, ax.set_xlim), (ax.get_ylim, ax.set_ylim)):
            set_(*(float(f"{v:.{LIMIT_DIGITS}g}") for v in get()))
    engine = fig.get_layout_engine()
    if engine is not None:
        engine.execute(fig)
    fig.set_layout_engine(None)
    for ax in fig.axes:
        ax.set_position([round(v, 6) for v in ax.get_position(original=False).bounds], which="both")
    return fig


def length_unit(*values):
    """(factor, unit) making lengths in m readable: µm below 1 mm, else mm."""
    peak = max((float(np.nanmax(np.abs(v))) for v in values if np.size(v)), default=0.0)
    return (1e6, "µm") if peak < 1e-3 else (1e3, "mm")


def headroom(*axes, frac=0.3):
    """Extend the y range upwards to leave room for a legend inside the axes."""
    for ax in axes:
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi + frac * (hi - lo))


def legend_on(ax, *axes, **kwargs):
    """One legend for an axes and its twins."""
    handles = [h for a in (ax, *axes) for h in a.get_legend_handles_labels()[0]]
    ax.legend(handles, [h.get_label() for h in handles], **{"fontsize": 8, **kwargs})


def twin_axis(ax, colour, label):
    tw = ax.twinx()
    tw.set_ylabel(label, color=colour)
    tw.tick_params(axis="y", colors=colour)
    return tw


def friction_loop(ax, x, y, mu, ls="-", lw=0.9):
    """The loop (x, y) as a line coloured by the friction coefficient ``mu`` at its points (viridis over
    the loop's range of μ); the LineCollection, for a colour bar."""
    from matplotlib.collections import LineCollection

    points = np.column_stack([x, y])
    segments = np.stack([points[:-1], points[1:]], axis=1)
    low, high = float(np.nanmin(mu)), float(np.nanmax(mu))
    lines = LineCollection(segments, cmap="viridis", linestyles=ls, linewidths=lw)
    lines.set_array(0.5 * (np.asarray(mu)[:-1] + np.asarray(mu)[1:]))
    lines.set_clim(low, high if high > low else low + 1e-12)
    ax.add_collection(lines)
    ax.autoscale_view()
    return lines


def plot_corners(ax, t, ds, which, factor, unit, what="interpenetration, < 0: gap"):
    for c in which:
        ax.plot(t, factor * ds[f"I_{c}"].values, label=I_LABEL[c], **CORNER_STYLE[c])
    ax.axhline(0, color="0.6", lw=0.6)
    ax.set_ylabel(f"{what} ({unit})")
    headroom(ax)
    ax.legend(fontsize=8, ncols=len(which), loc="upper right")


def grid_shape(n, rows=None, cols=None):
    """(rows, columns) of a grid of n panels with at most ``rows`` rows or ``cols`` columns."""
    if rows:
        rows = min(rows, n)
        return rows, -(-n // rows)
    cols = min(cols, n)
    return -(-n // cols), cols


def drop_unused(axes, n, by_columns=False):
    """Remove the grid cells after the n-th panel (filled row by row, or column by column)."""
    for ax in (axes.T if by_columns else axes).ravel()[n:]:
        ax.remove()


# --- drawing the device to scale --------------------------------------------------------------
def placed(u, Rx, Ry, theta_deg):
    """Global coordinates R + A(theta) u of local points u (..., 2)."""
    c, s = np.cos(np.radians(theta_deg)), np.sin(np.radians(theta_deg))
    u = np.asarray(u, dtype=float)
    return np.stack([Rx + c * u[..., 0] - s * u[..., 1], Ry + s * u[..., 0] + c * u[..., 1]], axis=-1)


def configuration_of(ds, suffix=""):
    """Generalised coordinates {name: value} of a 0-d dataset (m, degrees)."""
    return {name: float(ds[name + suffix]) for name in Q_NAMES}


def body_pose(q, i):
    return q[f"Rx{i}"], q[f"Ry{i}"], q[f"theta{i}"]


def body_shapes(g):
    """Local outlines of RB1, RB2, RB3 with fine arcs (interpenetrations are µm to mm)."""
    return {1: g.plate_outline(1, n_arc=1441), 2: g.pad_outline(n_arc=241), 3: g.plate_outline(3, n_arc=1441)}


def draw_device(ax, g, q, shapes, *, colour=None, ls="-", label=None, fill=True, corners=False, lw=0.8):
    """Draw RB1, RB2, RB3 at q (filled, or outlined in ``colour``) in cm; return their points."""
    drawn = []
    for i in (1, 3, 2):
        xy = 100 * placed(shapes[i], *body_pose(q, i))
        if fill:
            ax.add_artist(Polygon(xy, closed=True, fc=PAD_COLOUR if i == 2 else PLATE_COLOUR, ec="k", lw=lw,
                                 alpha=0.85 if i == 2 else 1.0, label=label if i == 2 else None))
        else:
            ax.add_artist(Polygon(xy, closed=True, fill=False, ec=colour, ls=ls, lw=lw * (1.8 if i == 2 else 1),
                                 label=label if i == 2 else None))
        drawn.append(xy)
    if corners:
        pts = 100 * placed(g.pad_corners, *body_pose(q, 2))
        for (x, y), c, dx, dy in zip(pts, CORNERS, (-1, 1, -1, 1), (-1, -1, 1, 1)):
            ax.annotate(f"${c}^2$", (x, y), xytext=(9 * dx, 7 * dy), textcoords="offset points", fontsize=9,
                        ha="center", va="center", bbox=dict(fc="white", ec="none", alpha=0.7, pad=0.5))
    c1 = 100 * placed(g.circle_centres[0], *body_pose(q, 1))
    c3 = 100 * placed(g.circle_centres[1], *body_pose(q, 3))
    ax.plot([c1[0], c3[0]], [c1[1], c3[1]], color=colour or "0.3", ls=":", lw=0.9)
    return np.vstack(drawn)


def frame_points(ax, points, margin=3.0, extra_y=(0.0, 0.0)):
    """Equal-aspect limits around the drawn points (cm), with room below/above for insets."""
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1] - extra_y[0], hi[1] + extra_y[1])
    ax.set_aspect("equal")
    ax.set_xlabel("X (cm)")
    ax.set_ylabel("Y (cm)")


def corner_inset(ax, g, q, shapes, corner, value, bounds, loaded):
    """Zoom on one pad corner, with the radial interpenetration segment and its value."""
    i = CORNERS.index(corner)
    plate, radius = (1, g.R1) if corner in "AB" else (3, g.R3)
    point = placed(g.pad_corners[i], *body_pose(q, 2))
    centre = placed(g.circle_centres[0 if plate == 1 else 1], *body_pose(q, plate))
    foot = centre + radius * (point - centre) / np.hypot(*(point - centre))
    half = max(2.5 * abs(value), 0.5e-3)
    ins = ax.inset_axes(bounds)
    for j in (1, 3, 2):
        ins.add_artist(Polygon(100 * placed(shapes[j], *body_pose(q, j)), closed=True, ec="k", lw=0.8,
                              fc=PAD_COLOUR if j == 2 else PLATE_COLOUR, alpha=0.7 if j == 2 else 1.0))
    ins.plot(100 * np.array([point[0], foot[0]]), 100 * np.array([point[1], foot[1]]), color="crimson", lw=1.5)
    ins.plot(*(100 * point), "o", color="crimson", ms=3)
    ins.set_xlim(100 * (point[0] - half), 100 * (point[0] + half))
    ins.set_ylim(100 * (point[1] - half), 100 * (point[1] + half))
    ins.set_aspect("equal")
    ins.set_xticks([])
    ins.set_yticks([])
    factor, unit = length_unit(value)
    ins.set_title(f"{I_LABEL[corner]} = {factor * value:.3g} {unit}  (window {2e3 * half:.2g} mm)", fontsize=8,
                  color="crimson" if loaded else "k", pad=2)
    for side in ins.spines.values():
        side.set(color="crimson" if loaded else "0.3", lw=1.6 if loaded else 0.8)
    ax.indicate_inset_zoom(ins, edgecolor="0.5", alpha=0.5, lw=0.6)


def step_path(t, end, stick):
    """Polyline start -> end of sticking (at mid-step) -> end of slipping, for every step."""
    tt = np.empty(2 * t.size - 1)
    vv = np.empty_like(tt)
    tt[0::2], vv[0::2] = t, end
    tt[1::2], vv[1::2] = 0.5 * (t[1:] + t[:-1]), stick[1:]
    return tt, vv



def save(fig: Figure, png_path, pdf_path) -> None:
    """Lay ``fig`` out once (``freeze``) and write it as PNG (150 dpi) and PDF, atomically and with
    reproducible bytes."""
    freeze(fig)
    write_atomic(png_path, lambda f: fig.savefig(f, format="png", dpi=DPI, metadata=PNG_METADATA))
    write_atomic(pdf_path, lambda f: fig.savefig(f, format="pdf", metadata=PDF_METADATA))
