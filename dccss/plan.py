"""Drawing a history in space: plan view, the pad axis's trace, tilt and rise, and sections.

Works on any dccss time history: a bidirectional one (``results.spatial_dataset``) and a planar
one, read as motion along x (``view``). The section at an instant is the device cut by the
vertical plane through its pad axis (the plane it leans in), drawn to scale by the planar
drawing (``drawing.draw_device``): in that plane the pad is tilted by the tilt, and what lies off
it (a few mm of RB3 after a slip) is projected onto it.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass

import numpy as np
from matplotlib.patches import Circle, Polygon

from . import drawing
from .results import friction_text, geometry_from_attrs, has_structure, imposed, is_bidirectional

MAX_INSTANTS = 4
#: legends outside the data: beside the axes (right), or above them on the right (the title on the left)
BESIDE = dict(fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
ABOVE = dict(fontsize=8, loc="lower right", bbox_to_anchor=(1.0, 1.0), borderaxespad=0.2)


@dataclass
class View:
    """A history in space (SI units, time first): ground (T, 2) (RB1 relative to RB3: the ground
    displacement, or minus a structure's stroke), pad centre G (T, 3), pad axis (T, 3),
    RB3 position R3 (T, 3), tilt and its azimuth (T,) (degrees), rise (T,) (m), and the same at the
    end of sticking (None for compliant sliding)."""

    t: np.ndarray
    ground: np.ndarray
    G: np.ndarray
    axis: np.ndarray
    R3: np.ndarray
    tilt: np.ndarray
    tilt_azimuth: np.ndarray
    rise: np.ndarray
    stick: dict | None


def _xyz(ds, name, suffix=""):
    return np.stack([ds[f"{name}_{c}{suffix}"].values for c in "xyz"], axis=-1).astype(float)


def view(ds) -> View:
    """The spatial view of a dataset (a planar one moves along x, its pad tilting in the x-z plane)."""
    t = ds["t"].values.astype(float)
    if is_bidirectional(ds):
        stick = None
        if "tilt_stick" in ds:
            stick = {"tilt": ds["tilt_stick"].values, "tilt_azimuth": ds["tilt_azimuth_stick"].values,
                     "axis": _xyz(ds, "axis", "_stick"), "G": _xyz(ds, "G2", "_stick")}
        return View(t, imposed(ds), _xyz(ds, "G2"), _xyz(ds, "axis"),
                    _xyz(ds, "R3"), ds["tilt"].values, ds["tilt_azimuth"].values, ds["rise"].values, stick)
    zero = np.zeros_like(t)

    def planar(suffix=""):
        theta = np.radians(ds["theta2" + suffix].values)
        axis = np.stack([-np.sin(theta), zero, np.cos(theta)], axis=-1)
        tilt = np.degrees(np.abs(theta))
        azimuth = np.where(theta > 0, 180.0, np.where(theta < 0, 0.0, np.nan))
        G = np.stack([ds["Rx2" + suffix].values, zero, ds["Ry2" + suffix].values], axis=-1)
        return axis, tilt, azimuth, G

    axis, tilt, azimuth, G = planar()
    stick = None
    if "theta2_stick" in ds:
        a, ti, az, Gs = planar("_stick")
        stick = {"tilt": ti, "tilt_azimuth": az, "axis": a, "G": Gs}
    R3 = np.stack([ds["Rx3"].values, zero, ds["Ry3"].values], axis=-1)
    return View(t, np.stack([imposed(ds), zero], axis=-1), G, axis, R3, tilt, azimuth, ds["rise"].values, stick)


def section_q(v: View, n, g, stick=False) -> dict:
    """Planar coordinates (m, degrees) of the device at step n in the vertical plane of its pad axis:
    RB1, the pad and RB3 projected on that plane, the pad turned by -tilt (it leans along +h). With
    ``stick``, the end of sticking projected on the same plane (the step's), its pad turned by its axis's
    tilt within that plane: RB1 does not move between the phases, and is drawn where it is."""
    lean = np.hypot(v.axis[n, 0], v.axis[n, 1])
    h = v.axis[n, :2] / lean if lean > 0 else np.array([1.0, 0.0])
    axis = v.stick["axis"][n] if stick else v.axis[n]
    G = v.stick["G"][n] if stick else v.G[n]
    tilt = np.degrees(np.arctan2(axis[:2] @ h, axis[2]))
    return {"Rx1": float(v.ground[n] @ h), "Ry1": 0.0, "theta1": 0.0, "Rx2": float(G[:2] @ h), "Ry2": float(G[2]),
            "theta2": -float(tilt), "Rx3": float(v.R3[n, :2] @ h), "Ry3": float(v.R3[n, 2]), "theta3": 0.0}


def rim(centre, axis, radius, k=73):
    """Plan view (k, 2) of a rim circle (centre (3,), normal ``axis``) of the pad."""
    helper = np.array([0.0, 0.0, 1.0]) if abs(axis[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    beta = np.linspace(0.0, 2 * np.pi, k)
    return (centre[None, :] + radius * (np.cos(beta)[:, None] * u + np.sin(beta)[:, None] * w))[:, :2]


def ground_label(ds) -> str:
    """The label of RB1's path in the plan: the ground, or minus the stroke of a structure."""
    return "RB1 relative to RB3: $-u$" if has_structure(ds) else "ground $X_g$"


def draw_plan(ax, v: View, g, n, *, history=True, colour="tab:orange", ground_label="ground $X_g$"):
    """Plan view at step n (cm): the rings of RB1 (moving with the ground) and RB3, the pad's two rims
    and, with ``history``, the path of RB1 (labelled ``ground_label``) and the pad centre's path up to n."""
    if history:
        ax.plot(100 * v.ground[: n + 1, 0], 100 * v.ground[: n + 1, 1], color="0.55", lw=0.9, label=ground_label)
        ax.plot(100 * v.G[: n + 1, 0], 100 * v.G[: n + 1, 1], color=colour, lw=1.1, label="pad centre $G^2$")
    ring1, ring3 = (float(r) for r in g.ring_inner_x)
    ax.add_patch(Circle(100 * v.ground[n], 100 * ring1, fill=False, ec="0.35", lw=1.0))
    ax.add_patch(Circle(100 * v.R3[n, :2], 100 * ring3, fill=False, ec="0.35", ls="--", lw=1.0))
    a = v.axis[n]
    for sign, radius in ((-1.0, float(g.A1)), (1.0, float(g.A3))):
        ax.add_patch(Polygon(100 * rim(v.G[n] + sign * float(g.B) * a, a, radius), closed=True, fc=drawing.PAD_COLOUR,
                             ec="k", lw=0.6, alpha=0.5))
    ax.plot(*(100 * v.ground[n]), "+", color="0.35", ms=7)
    ax.plot(*(100 * v.R3[n, :2]), "x", color="0.35", ms=6)
    ax.set_aspect("equal")
    ax.set_xlabel("x (cm)")
    ax.set_ylabel("y (cm)")


def draw_axis_trace(ax, v: View, n=None):
    """The pad axis's trace: the tilt vector (tilt cos azimuth, tilt sin azimuth) in degrees, up to n."""
    end = len(v.t) if n is None else n + 1

    def vec(tilt, azimuth):
        az = np.radians(np.nan_to_num(azimuth))
        return tilt * np.cos(az), tilt * np.sin(az)

    if v.stick is not None:
        ax.plot(*vec(v.stick["tilt"][1:end], v.stick["tilt_azimuth"][1:end]), color="crimson", lw=0.5, alpha=0.7,
                label="end of sticking")
    x, y = vec(v.tilt[:end], v.tilt_azimuth[:end])
    ax.plot(x, y, color="tab:blue", lw=1.2, label="end of step")
    ax.plot(0, 0, "+", color="k", ms=6)
    # square limits around the whole trace and the origin (a planar trace has no y extent)
    whole = [vec(v.tilt, v.tilt_azimuth)]
    if v.stick is not None:
        whole.append(vec(v.stick["tilt"][1:], v.stick["tilt_azimuth"][1:]))
    xs = np.concatenate([[0.0]] + [tx for tx, _ in whole])
    ys = np.concatenate([[0.0]] + [ty for _, ty in whole])
    lo, hi = np.array([np.nanmin(xs), np.nanmin(ys)]), np.array([np.nanmax(xs), np.nanmax(ys)])
    _square(ax, 0.5 * (lo + hi), 0.55 * max(float((hi - lo).max()), 0.02))
    ax.set_xlabel("tilt towards x (deg)")
    ax.set_ylabel("tilt towards y (deg)")


def _square(ax, mid, half):
    """Equal-aspect limits: a square of half side ``half`` centred on ``mid``."""
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_aspect("equal")


def draw_traces(ax, v: View):
    """Tilt (deg, left axis) and rise of RB3 (cm, right axis) against time."""
    ax.plot(v.t, v.tilt, color="tab:blue", lw=1.2, label="tilt")
    if v.stick is not None:
        ax.plot(v.t[1:], v.stick["tilt"][1:], color="crimson", lw=0.5, alpha=0.7, label="tilt, end of sticking")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("tilt (deg)", color="tab:blue")
    right = ax.twinx()
    right.plot(v.t, 100 * v.rise, color="tab:green", lw=1.0, ls="--", label="rise of RB3")
    right.set_ylabel("rise (cm)", color="tab:green")
    return right


def draw_section(ax, v: View, g, n, shapes=None):
    """The device to scale in the vertical plane of its pad axis at step n (cm); returns its points."""
    shapes = shapes or drawing.body_shapes(g)
    q = section_q(v, n, g)
    points = drawing.draw_device(ax, g, q, shapes)
    if v.stick is not None and n > 0:
        drawing.draw_device(ax, g, section_q(v, n, g, stick=True), shapes, colour="crimson", fill=False, lw=0.6)
    ax.set_aspect("equal")
    return points


def instants(v: View, at=None) -> list[int]:
    """Step indices of the instants to draw: the steps nearest to the times ``at`` (s), or by default
    the largest tilt and the last step."""
    if at is None:
        return sorted({int(np.nanargmax(v.tilt)), len(v.t) - 1})
    at = list(np.atleast_1d(np.asarray(at, dtype=float)))
    if not 1 <= len(at) <= MAX_INSTANTS:
        raise ValueError(f"give 1 to {MAX_INSTANTS} instants, got {len(at)}")
    for when in at:
        if not (np.isfinite(when) and v.t[0] - 1e-12 <= when <= v.t[-1] + 1e-12):
            raise ValueError(f"instant {float(when):g} s is outside the history ({v.t[0]:g} .. {v.t[-1]:g} s)")
    return [int(np.argmin(np.abs(v.t - when))) for when in at]


def figure(ds, at=None, title=None):
    """The summary figure of a history: plan view, the pad axis's trace, tilt and rise against time,
    and the section at each instant (``instants``). Returns the Figure (``plot`` lays it out once and
    freezes it before writing it: ``drawing.freeze``)."""
    g = geometry_from_attrs(ds.attrs)
    v = view(ds)
    steps = instants(v, at)
    structure = has_structure(ds)
    from .viewer import run_notes

    notes = run_notes(ds.attrs)  # a ring, a stop, a failure: what the reader must know, as the animation says
    notes = textwrap.fill(notes.replace("\n", " "), 150) if notes else ""
    fig = drawing.new_figure((11.0, 11.4 if structure else 8.6), nrows=None,
                             caption_lines=1 + (notes.count("\n") + 1 if notes else 0))
    # two columns above and below the sections, which have their own row of as many columns as instants
    grid = fig.add_gridspec(3 + structure, 2, height_ratios=(1.25, 0.8, 1.0) + (0.95,) * structure)
    plan = fig.add_subplot(grid[0, 0])
    trace = fig.add_subplot(grid[0, 1])
    draw_plan(plan, v, g, steps[-1], ground_label=ground_label(ds))
    plan.set_title(f"(a) plan at t = {v.t[steps[-1]]:.3g} s: rings of RB1 (solid), RB3 (dashed), pad rims", fontsize=9)
    drawing.legend_on(plan, **BESIDE)
    draw_axis_trace(trace, v)
    trace.set_title("(b) trace of the pad axis", fontsize=9)
    trace.legend(**BESIDE)
    traces = fig.add_subplot(grid[1, :])
    right = draw_traces(traces, v)
    for n in steps:
        traces.axvline(v.t[n], color="0.5", lw=0.7, ls=":")
    draw_events(traces, ds.attrs)
    traces.set_title("(c) tilt of the pad and rise of RB3", fontsize=9, loc="left")
    drawing.legend_on(traces, right, **ABOVE, ncols=3)
    shapes = drawing.body_shapes(g)
    sections = grid[2, :].subgridspec(1, max(2, len(steps)))
    for k, n in enumerate(steps):
        ax = fig.add_subplot(sections[0, k])
        points = draw_section(ax, v, g, n, shapes)
        drawing.frame_points(ax, points, margin=2.0)
        azimuth = v.tilt_azimuth[n]
        if len(steps) < 3:
            plane = f", leaning towards {azimuth:.0f} deg" if np.isfinite(azimuth) else ""
            heading = f"({chr(100 + k)}) t = {v.t[n]:.3g} s: tilt {v.tilt[n]:.2f} deg{plane}"
        else:  # three or four sections side by side: a shorter title on two lines
            plane = f", towards {azimuth:.0f}°" if np.isfinite(azimuth) else ""
            heading = f"({chr(100 + k)}) t = {v.t[n]:.3g} s\ntilt {v.tilt[n]:.2f}°{plane}"
        ax.set_title(heading, fontsize=9)
        ax.set_xlabel("along the lean (cm)")
        ax.set_ylabel("z (cm)")
    if structure:
        draw_structure(fig.add_subplot(grid[3, 0]), fig.add_subplot(grid[3, 1]), ds, steps,
                       letters=(chr(100 + len(steps)), chr(101 + len(steps))))
    drawing.caption_line(fig, (title or caption(ds, v)) + ("\n" + notes if notes else ""))
    return fig


def draw_events(ax, attrs):
    """Dashed lines at the history's events (``viewer.events``: the ring, a solver failure; a stop is at
    the ring), the time axis extended to them."""
    from .viewer import events

    lo, hi = ax.get_xlim()
    found = events(attrs)
    for value, colour, label in found:
        ax.axvline(value, color=colour, ls="--", lw=1.0, label=label)
    if found:
        ax.set_xlim(lo, max(hi, *(value for value, _, _ in found)))


def caption(ds, v: View) -> str:
    """The caption line of ``figure``: the history's title, its ground motion (unless the title says it)
    and what the sections show; the end of sticking only where there is one (not in compliant sliding)."""
    text = ds.attrs.get("title", "dccss history")
    if "ground motion" not in text:
        text += f": {'bidirectional' if is_bidirectional(ds) else 'unidirectional (x)'} ground motion"
    text += "; sections in the vertical plane of the pad axis"
    return text + (", end of sticking in red" if v.stick is not None else "")


def draw_structure(history, loop, ds, steps=(), letters=("e", "f")):
    """A structure-driven history: the stroke u beside the ground displacement X_g against time, and the
    device's loop F/W against u (x solid, y dashed for two components; cm)."""
    t = ds["t"].values
    parts = (("_x", "-", " x"), ("_y", "--", " y")) if is_bidirectional(ds) else (("", "-", ""),)
    for suffix, ls, name in parts:
        history.plot(t, 100 * ds[f"Xg{suffix}"].values, color="k", lw=1.0, ls=ls, label=f"ground $X_g${name}")
        history.plot(t, 100 * ds[f"stroke{suffix}"].values, color="tab:purple", lw=1.2, ls=ls,
                     label=f"stroke $u${name}")
        if "friction_coefficient" in ds:  # a friction law: the loop coloured by μ
            coloured = drawing.friction_loop(loop, 100 * ds[f"stroke{suffix}"].values,
                                             ds[f"shear_ratio{suffix}"].values, ds["friction_coefficient"].values, ls)
        else:
            loop.plot(100 * ds[f"stroke{suffix}"].values, ds[f"shear_ratio{suffix}"].values, color="tab:purple",
                      lw=0.9, ls=ls, label=f"$u${name}" if suffix else None)
    twins = []
    if "friction_coefficient" in ds:
        loop.figure.colorbar(coloured, ax=loop, label="friction μ", pad=0.02)
        twins = [drawing.twin_axis(history, "tab:green", "friction μ")]
        twins[0].plot(t, ds["friction_coefficient"].values, color="tab:green", lw=0.7, label="friction μ")
    for n in steps:
        history.axvline(t[n], color="0.5", lw=0.7, ls=":")
    a = ds.attrs
    title = (f"({letters[0]}) the structure on the device ({friction_text(a)}, ζ = {a['structure_damping']:g}, "
             f"T = {a['structure_period_s']:.3g} s)")
    history.set_title(textwrap.fill(title, 64) if twins else title, fontsize=9)  # a law's text is longer
    history.set_xlabel("t (s)")
    history.set_ylabel("displacement (cm)")
    drawing.legend_on(history, *twins, **(BESIDE if not twins else {**BESIDE, "bbox_to_anchor": (1.2, 1.0)}))
    loop.set_title(f"({letters[1]}) force-displacement loop of the device", fontsize=9)
    loop.set_xlabel("stroke u (cm)")
    loop.set_ylabel("F/W (-)")
    if len(parts) > 1 and not twins:
        loop.legend(**BESIDE)
    for ax in (history, loop):
        ax.grid(True, color="0.9", lw=0.6)
        ax.axhline(0, color="0.6", lw=0.6, zorder=1)


# --- command line ------------------------------------------------------------------------------
def plot(path, output, at=None) -> str:
    """Write the summary figure of a result history to ``output`` (.png or .pdf); returns a one-line
    summary. Errors (``viewer.AnimationError``) name the file or value; nothing is written then."""
    from pathlib import Path

    from .files import write_atomic
    from .viewer import AnimationError, open_result

    suffix = Path(output).suffix.lower()
    if suffix not in (".png", ".pdf"):
        raise AnimationError(f"output {str(output)!r}: unknown extension {Path(output).suffix or '(none)'!r}, "
                             "expected .png or .pdf")
    ds = open_result(path)
    articulated = ds.attrs.get("model") == "articulated"
    try:
        if articulated:
            from . import hinged

            fig, steps = hinged.figure(ds, at), hinged.instants(ds, at)
        else:
            fig, steps = figure(ds, at), instants(view(ds), at)
    except ValueError as err:
        raise AnimationError(f"--at: {err}") from None
    metadata = drawing.PNG_METADATA if suffix == ".png" else drawing.PDF_METADATA
    drawing.freeze(fig)
    write_atomic(output, lambda f: fig.savefig(f, format=suffix[1:], dpi=drawing.DPI, metadata=metadata))
    steps = ", ".join(f"{ds['t'].values[n]:g} s" for n in steps)
    return f"{output}: {ds.sizes['t'] - 1} steps, sections at {steps}"


def add_parser(subparsers):
    """The ``plot`` sub-command."""
    p = subparsers.add_parser("plot", help="draw a result history: plan, pad axis trace, tilt, rise and sections",
                              description="Draw a dccss result history (bidirectional or planar): the plan view "
                                          "with the ground path, the pad axis's trace, tilt and rise against time, "
                                          "and the device cut by the vertical plane of its pad axis at chosen "
                                          "instants.")
    p.add_argument("result", help="dccss result netCDF file (a time history)")
    p.add_argument("-o", "--output", required=True, help="OUT.png or OUT.pdf")
    p.add_argument("--at", type=float, nargs="+", metavar="T",
                   help=f"instants of the sections (s), 1 to {MAX_INSTANTS} (default: the largest tilt and the end)")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    p.set_defaults(handler=_command)
    return p


def _command(args) -> int:
    from .viewer import run_command

    return run_command("plot", lambda: plot(args.result, args.output, args.at), args.quiet)


# --- animation -----------------------------------------------------------------------------------
class Scene:
    """One step of a history at a time, in space (``dccss animate`` on a bidirectional history): the
    plan view (left), the section in the vertical plane of the pad axis (right, the end of sticking in
    red), the pad axis's trace and tilt and rise against time with a cursor (below). The interface of
    ``animation.Scene``: ``show(n)`` and ``dynamic``; ``frames`` fix the limits."""

    def __init__(self, fig, ds, frames, exaggeration=None, name=""):
        from .viewer import FIGSIZE, run_notes

        self.fig, self.ds = fig, ds
        self.g = g = geometry_from_attrs(ds.attrs)
        self.v = v = view(ds)
        self.shapes = drawing.body_shapes(g)
        self.dynamic = []
        frames = np.asarray(frames, dtype=int)
        fig.set_size_inches(*FIGSIZE)
        notes = run_notes(ds.attrs)  # the run's events, at the foot: room for their lines below the x labels
        grid = fig.add_gridspec(2, 3, height_ratios=(1.6, 1.0), left=0.06, right=0.94, top=0.9,
                                bottom=0.1 + (0.025 * (notes.count("\n") + 1) if notes else 0.0), wspace=0.3,
                                hspace=0.3)
        plan = self.plan = fig.add_subplot(grid[0, 0])
        section = self.section = fig.add_subplot(grid[0, 1:])
        trace = fig.add_subplot(grid[1, 0])
        traces = self.traces = fig.add_subplot(grid[1, 1:])
        # plan: fixed limits around every ring and path of the shown steps
        ring1, ring3 = (float(r) for r in g.ring_inner_x)
        lo = np.minimum((v.ground[frames] - ring1).min(axis=0), (v.R3[frames, :2] - ring3).min(axis=0))
        hi = np.maximum((v.ground[frames] + ring1).max(axis=0), (v.R3[frames, :2] + ring3).max(axis=0))
        _square(plan, 50 * (hi + lo), 100 * (hi - lo).max() / 2 + 2.0)
        plan.set_xlabel("x (cm)")
        plan.set_ylabel("y (cm)")
        plan.set_title("plan: rings of RB1 (solid), RB3 (dashed)", fontsize=9)
        self.ground_path = self._add(plan.plot([], [], color="0.55", lw=0.9, label=ground_label(ds))[0])
        self.pad_path = self._add(plan.plot([], [], color="tab:orange", lw=1.1, label="pad centre")[0])
        self.rings = [self._add(plan.add_patch(Circle((0, 0), 100 * r, fill=False, ec="0.35", lw=1.0, ls=ls)))
                      for r, ls in ((ring1, "-"), (ring3, "--"))]
        self.rims = [self._add(plan.add_patch(Polygon(np.zeros((2, 2)), closed=True, fc=drawing.PAD_COLOUR, ec="k",
                                                      lw=0.6, alpha=0.5))) for _ in range(2)]
        plan.legend(fontsize=7, loc="upper right")
        # section: the device in the plane of its pad axis, limits over the shown steps
        points = []
        for n in frames:
            q = section_q(v, int(n), g)
            points.append(np.vstack([100 * drawing.placed(self.shapes[i], *drawing.body_pose(q, i))
                                     for i in (1, 2, 3)]))
        points = np.vstack(points)
        drawing.frame_points(section, points, margin=2.0)
        section.set_xlabel("along the lean of the pad axis (cm)")
        section.set_ylabel("z (cm)")
        self.bodies = {i: self._add(section.add_patch(Polygon(np.zeros((2, 2)), closed=True, ec="k", lw=0.8,
                                                              fc=drawing.PAD_COLOUR if i == 2 else drawing.PLATE_COLOUR,
                                                              alpha=0.85 if i == 2 else 1.0)))
                       for i in (1, 3, 2)}
        self.sticks = {}
        if v.stick is not None:
            self.sticks = {i: self._add(section.add_patch(Polygon(np.zeros((2, 2)), closed=True, fill=False,
                                                                  ec="crimson", lw=0.9 if i == 2 else 0.5)))
                           for i in (1, 3, 2)}
        self.line = self._add(section.plot([], [], color="0.3", ls=":", lw=0.9)[0])
        # the axis trace and the time traces, with cursors
        draw_axis_trace(trace, v)
        trace.set_title("trace of the pad axis", fontsize=9)
        self.tip = self._add(trace.plot([], [], "o", color="tab:blue", ms=5)[0])
        right = draw_traces(traces, v)
        draw_events(traces, ds.attrs)
        drawing.legend_on(traces, right, fontsize=7, loc="upper right")
        self.cursor = self._add(traces.axvline(v.t[0], color="crimson", lw=1.0))
        title = ds.attrs.get("title", "dccss history")
        drawing.fit_width(fig.suptitle(f"{title}{' - ' + name if name else ''}", fontsize=10), fig)
        self.status = self._add(fig.text(0.5, 0.935, "", ha="center", fontsize=9))
        if notes:
            fig.text(0.5, 0.01, notes, ha="center", va="bottom", fontsize=7, color="crimson")

    def _add(self, artist):
        self.dynamic.append(artist)
        return artist

    def show(self, n):
        v, g = self.v, self.g
        self.ground_path.set_data(100 * v.ground[: n + 1, 0], 100 * v.ground[: n + 1, 1])
        self.pad_path.set_data(100 * v.G[: n + 1, 0], 100 * v.G[: n + 1, 1])
        self.rings[0].set_center(100 * v.ground[n])
        self.rings[1].set_center(100 * v.R3[n, :2])
        a = v.axis[n]
        for rim_patch, (sign, radius) in zip(self.rims, ((-1.0, float(g.A1)), (1.0, float(g.A3)))):
            rim_patch.set_xy(100 * rim(v.G[n] + sign * float(g.B) * a, a, radius))
        q = section_q(v, n, g)
        for i, patch in self.bodies.items():
            patch.set_xy(100 * drawing.placed(self.shapes[i], *drawing.body_pose(q, i)))
        for i, patch in self.sticks.items():
            visible = n > 0 and np.isfinite(v.stick["tilt"][n])
            patch.set_visible(bool(visible))
            if visible:
                stuck = section_q(v, n, g, stick=True)
                patch.set_xy(100 * drawing.placed(self.shapes[i], *drawing.body_pose(stuck, i)))
        c1 = 100 * drawing.placed(g.circle_centres[0], *drawing.body_pose(q, 1))
        c3 = 100 * drawing.placed(g.circle_centres[1], *drawing.body_pose(q, 3))
        self.line.set_data([c1[0], c3[0]], [c1[1], c3[1]])
        az = np.radians(np.nan_to_num(v.tilt_azimuth[n]))
        self.tip.set_data([v.tilt[n] * np.cos(az)], [v.tilt[n] * np.sin(az)])
        self.cursor.set_xdata([v.t[n], v.t[n]])
        lean = f", leaning towards {v.tilt_azimuth[n]:.0f} deg" if np.isfinite(v.tilt_azimuth[n]) else ""
        self.status.set_text(f"t = {v.t[n]:.3f} s   tilt {v.tilt[n]:.3f} deg{lean}   rise {100 * v.rise[n]:.3f} cm")
