"""Animations of a result history: the device drawn to scale (as in Figs. 8 and 20) moving in time.

``dccss animate RESULT.nc -o OUT.gif|OUT.html|OUT.mp4`` and :func:`animate` draw, for every
shown step, the plates RB1 and RB3 with their retaining rings and the pad RB2, to scale, with
fixed limits in the ground-fixed frame (RB1 moves with X_g), and

* four zoom windows on the pad corners A^2, B^2, C^2, D^2 at true scale, each with the
  interpenetration I (µm to mm) as a red radial segment and its value (in nm, µm or mm; "0 (contact)"
  within the solver's tolerance, where what is left is round-off); on the whole device
  the positive interpenetrations are red spikes into the plates, magnified by a labelled
  exaggeration factor;
* time traces of X_g, θ^2 and the rise of RB3 with a cursor at the shown step;
* for the Stick-Slip model, both phases of the step in one frame: the device filled at the
  end of slipping (the step's result, the plain variables), the end of sticking drawn over it
  as a red outline (the ``*_stick`` variables), and the jammed diagonal (A^2D^2 or B^2C^2,
  ``sticking_diagonal``) as a thick red line between its two corners; the traces show the
  path through the end of sticking (red) as in Figs. 18 and 19;
* a note for histories whose solver failed (the data end at the last converged step) or in
  which the pad reached a retaining ring.

Long histories are subsampled to a frame budget (``max_frames``): every k-th step and the last.
GIF and HTML bytes are reproducible: no dates, no random ids, no software stamps.
matplotlib is imported on first use, so that loading this module (the command line) stays fast.
"""

from __future__ import annotations

import argparse
import base64
import functools
import math
import shutil
import tempfile
from io import BytesIO
from pathlib import Path

import numpy as np

from .files import write_atomic
from .mechanics.kinematics import CORNERS, Q_NAMES, interpenetration
from .mechanics.models import REGISTRY
from .mechanics.newton import NewtonOptions
from .results import MODEL_TITLES, failure_of, geometry_from_attrs, has_structure
from .viewer import (
    DPI,
    FIGSIZE,
    AnimationError,
    case_text,
    events,
    is_real,
    open_result,
    run_command,
    run_notes,
)

FORMATS = (".gif", ".html", ".mp4")
MAX_FPS = 50  # GIF delays are whole hundredths of a second, and viewers slow down delays below 0.02 s
MAX_FRAMES = 200
STICK_COLOUR, SPIKE_COLOUR, CURSOR_COLOUR = "tab:red", "crimson", "tab:green"
DIAGONALS = ((0, 3), (1, 2))  # sticking_diagonal 0: A2D2, 1: B2C2 (indices in CORNERS)
DIAGONAL_NAMES = ("$A^2D^2$", "$B^2C^2$")
WINDOW_MIN, WINDOW_MAX = 2e-6, 0.05  # half sides of the corner zoom windows (m)
SPIKE_LENGTH = 0.03  # automatic exaggeration: the largest interpenetration drawn about this long (m)
# figure fractions: the device, the zoom windows beside it (each on its corner's side), the traces
_DEVICE = (0.225, 0.405, 0.55, 0.455)
_INSETS = {"C": (0.012, 0.655), "D": (0.853, 0.655), "A": (0.012, 0.405), "B": (0.853, 0.405)}
_INSET_SIZE = (0.135, 0.205)
_INSET_FIELD = {"C": 0.36, "D": 0.2, "A": 0.36, "B": 0.2}  # where a window's value starts (axes fraction)
_LABEL_STRIP = 13.0 / (72 * FIGSIZE[1] * _INSET_SIZE[1])  # a zoom window's label strip, 13 pt (axes fraction)
# the status lines above the device: (label, x of the value) at the end of the step and of sticking
_STATUS = ({"t": ("t =", 0.25), "step": ("step", 0.345), "Xg": ("$X_g$ =", 0.475),
            "theta2": (r"$\theta^2$ =", 0.6), "rise": ("rise =", 0.72)},
           {"diagonal_stick": ("jammed", 0.475), "theta2_stick": (r"$\theta^2$ =", 0.6),
            "rise_stick": ("rise =", 0.72)})
_STATUS_Y = (0.895, 0.87)
_TRACES = ((0.055, 0.1, 0.25, 0.175), (0.385, 0.1, 0.25, 0.175), (0.715, 0.1, 0.25, 0.175))
def check_options(output, *, start=None, end=None, fps=10, max_frames=MAX_FRAMES, exaggeration=None):
    """Check the options of ``animate`` before any work; returns the output format ('.gif', ...)."""
    suffix = Path(output).suffix.lower()
    if suffix not in FORMATS:
        raise AnimationError(f"output {str(output)!r}: unknown extension {Path(output).suffix or '(none)'!r}, "
                             f"expected one of {', '.join(FORMATS)}")
    if not is_real(fps) or not 0 < fps <= MAX_FPS:
        raise AnimationError(f"fps must be a number with 0 < fps <= {MAX_FPS}, got {fps!r}")
    if isinstance(max_frames, bool) or not isinstance(max_frames, int | np.integer) or max_frames < 2:
        raise AnimationError(f"max_frames must be an integer >= 2, got {max_frames!r}")
    if exaggeration is not None and (not is_real(exaggeration) or exaggeration < 0):
        raise AnimationError(f"exaggeration must be a number >= 0 (0: none) or None (automatic), got {exaggeration!r}")
    for name, value in (("start", start), ("end", end)):
        if value is not None and not is_real(value):
            raise AnimationError(f"{name} must be a finite time in seconds or None, got {value!r}")
    if start is not None and end is not None and start > end:
        raise AnimationError(f"start ({start:g} s) is after end ({end:g} s): the time range is empty")
    if suffix == ".mp4":
        _check_ffmpeg()
    return suffix


def _check_ffmpeg():
    from matplotlib import animation

    if not animation.writers.is_available("ffmpeg"):
        raise AnimationError("MP4 output needs ffmpeg, which is not installed (or not found: see matplotlib's "
                             "rcParams['animation.ffmpeg_path']); install ffmpeg, or write .gif or .html")


def select(ds, start=None, end=None):
    """The steps with start <= t <= end (None: no bound), with their step numbers as coordinate ``step``."""
    t = ds["t"].values
    tol = 1e-9 * max(1.0, float(np.abs(t).max()))
    keep = np.ones(t.size, bool)
    if start is not None:
        keep &= t >= start - tol
    if end is not None:
        keep &= t <= end + tol
    if not keep.any():
        raise AnimationError(f"no stored step in the time range {_bound(start, '-inf')} .. {_bound(end, '+inf')} s: "
                             f"the history covers t = {t[0]:g} .. {t[-1]:g} s")
    return ds.assign_coords(step=("t", np.arange(t.size))).isel(t=np.flatnonzero(keep))


def _bound(value, default):
    return default if value is None else f"{value:g}"


def frame_steps(n_steps, max_frames=MAX_FRAMES):
    """Indices of the shown steps and the stride k: all steps, or every k-th step and the last,
    at most ``max_frames`` in all."""
    if n_steps <= max_frames:
        return np.arange(n_steps), 1
    k = math.ceil((n_steps - 1) / (max_frames - 1))
    idx = np.arange(0, n_steps, k)
    return (idx if idx[-1] == n_steps - 1 else np.append(idx, n_steps - 1)), k


def _number(x):
    """A length for a label: two significant digits, no exponent."""
    return f"{x:.2g}" if abs(x) < 100 else f"{x:.0f}"


def _ordinal(k):
    return f"{k}{'th' if 10 <= k % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(k % 10, 'th')}"


def summary(output, ds, idx, k, fps):
    """The one-line report: steps, frames, stride, duration."""
    t, n = ds["t"].values, ds.sizes["t"]
    how = "every step" if k == 1 else f"every {_ordinal(k)} step" + ("" if (n - 1) % k == 0 else " and the last")
    return (f"{output}: {_count(n - 1, 'step')} ({_count(n, 'state')}, t = {t[0]:g} .. {t[-1]:g} s) shown as "
            f"{_count(len(idx), 'frame')}, "
            f"{how}; {fps:g} fps, {len(idx) / fps:.1f} s")


def _count(n, noun):
    return f"{n} {noun}{'' if n == 1 else 's'}"


# --- the scene ----------------------------------------------------------------------------------------
def _config(ds, suffix=""):
    """Configuration arrays {name: (n,)} in m and degrees."""
    return {name: ds[name + suffix].values.astype(float) for name in Q_NAMES}


def _body(q, i, n):
    return q[f"Rx{i}"][n], q[f"Ry{i}"][n], q[f"theta{i}"][n]


def _interpenetration(ds, g, q):
    """I_A..I_D (n, 4) (m): the dataset's, or computed from the configurations."""
    if all(f"I_{c}" in ds for c in CORNERS):
        return np.stack([ds[f"I_{c}"].values for c in CORNERS], axis=-1).astype(float)
    qq = np.stack([np.radians(q[k]) if k.startswith("theta") else q[k] for k in Q_NAMES], axis=-1)
    return interpenetration(qq, g)


def _nice_factor(x):
    """The largest of 1, 2, 5 x 10^e not above x (at least 1)."""
    if not x > 1:
        return 1.0
    e = 10.0 ** math.floor(math.log10(x))
    return max(m * e for m in (1, 2, 5) if m * e <= x * (1 + 1e-12))


def _nice_ceil(x):
    """The smallest of 1, 2, 3, 5 x 10^e not below x > 0 (0 for x <= 0)."""
    if not x > 0:
        return 0.0
    e = 10.0 ** math.floor(math.log10(x))
    return min(m * e for m in (1, 2, 3, 5, 10) if m * e >= x * (1 - 1e-12))


def _spike_factor(I, exaggeration):
    """Magnification of the interpenetration spikes; None: draw none."""
    if exaggeration is not None:
        return float(exaggeration) or None
    peak = float(np.nanmax(I, initial=0.0))
    return _nice_factor(SPIKE_LENGTH / peak) if peak > 0 else None


def interpenetration_text(value, tol):
    """An interpenetration I (m) as a zoom window prints it: "0 (contact)" when |I| is within the
    solver's tolerance ``tol`` (the corner is on its surface: what is left is round-off), else three
    digits in nm, µm or mm, with "(gap)" when I < 0."""
    if not math.isfinite(value):
        return "\u2013"
    if abs(value) <= tol:
        return "0 (contact)"
    factor, unit = next((f, u) for f, u, least in ((1e3, "mm", 1e-3), (1e6, "µm", 1e-6), (1e9, "nm", 0.0))
                        if abs(value) >= least)
    return f"{factor * value:.3g} {unit}" + (" (gap)" if value < 0 else "")


def _time_format(ds):
    dt = ds.attrs.get("dt_s")
    if not is_real(dt) or dt <= 0:
        steps = np.diff(ds["t"].values)
        dt = float(steps[steps > 0].min()) if (steps > 0).any() else 1.0
    return f".{max(0, math.ceil(-math.log10(dt) - 1e-9))}f"


class Scene:
    """A figure showing one step of a history at a time: ``show(n)`` moves it to step n.

    Parameters
    ----------
    fig : matplotlib Figure with a canvas (its size is set to FIGSIZE).
    ds : time-history dataset (the shown time range).
    frames : indices of the steps to be shown: they fix the drawing limits and zoom windows.
    exaggeration : magnification of the interpenetration spikes; None: automatic, 0: none.
    name : what the history is of, after the model and the device in the heading (``viewer.case_text``).

    Attributes
    ----------
    dynamic : the artists that change from step to step, in drawing order.
    """

    def __init__(self, fig, ds, frames, exaggeration=None, name=""):
        from .drawing import body_shapes

        self.fig, self.ds = fig, ds
        self.g = geometry_from_attrs(ds.attrs)
        self.shapes = body_shapes(self.g)
        self.t = ds["t"].values.astype(float)
        self.steps = ds["step"].values if "step" in ds.coords else np.arange(self.t.size)
        self.q = _config(ds)
        self.stick = REGISTRY[ds.attrs["model"]].sticking and all(f"{k}_stick" in ds for k in Q_NAMES)
        self.qs = _config(ds, "_stick") if self.stick else None
        self.diag = ds["sticking_diagonal"].values if self.stick and "sticking_diagonal" in ds else None
        self.I = _interpenetration(ds, self.g, self.q)
        self.tol = float(ds.attrs["newton_tol_m"]) if is_real(ds.attrs.get("newton_tol_m")) else NewtonOptions().tol
        self.tfmt = _time_format(ds)
        frames = np.asarray(frames, dtype=int)
        self.factor = _spike_factor(self.I[frames], exaggeration)
        self.dynamic = []
        fig.set_size_inches(*FIGSIZE)
        self._device(frames)
        self._insets(frames)
        self._traces()
        self._texts(name)

    def _add(self, artist):
        self.dynamic.append(artist)
        return artist

    # --- building ---------------------------------------------------------------------------
    def _device(self, frames):
        from matplotlib.lines import Line2D
        from matplotlib.patches import Patch

        from .drawing import PAD_COLOUR

        ax = self.ax = self.fig.add_axes(_DEVICE)
        self.bodies = self._bodies(ax, gid="RB{}")
        self.link = self._add(ax.plot([], [], color="0.35", ls=":", lw=0.9)[0])
        self.corners = self._add(ax.plot([], [], "o", color="k", ms=2.5, gid="pad_corners")[0])
        handles = [Patch(fc=PAD_COLOUR, ec="k", lw=0.8, label="end of step" + (" (slipping)" if self.stick else ""))]
        if self.stick:
            self.ghosts = {i: self._add(ax.fill([], [], fill=False, ec=STICK_COLOUR, lw=1.6 if i == 2 else 0.9,
                                                gid=f"RB{i}_stick")[0]) for i in (1, 3, 2)}
            self.ghost_corners = self._add(ax.plot([], [], "o", color=STICK_COLOUR, ms=2.5,
                                                   gid="pad_corners_stick")[0])
            self.diagonal = self._add(ax.plot([], [], color=STICK_COLOUR, lw=3.2, alpha=0.8, solid_capstyle="round",
                                              gid="jammed_diagonal")[0])
            handles += [Line2D([], [], color=STICK_COLOUR, lw=1.6, label="end of sticking"),
                        Line2D([], [], color=STICK_COLOUR, lw=3.2, alpha=0.8, label="jammed diagonal")]
        self.spikes = self._add(ax.plot([], [], color=SPIKE_COLOUR, lw=2.2, solid_capstyle="butt", gid="spikes")[0])
        self.labels = [self._add(ax.annotate(f"${c}^2$", (0, 0), xytext=(0, 0), textcoords="offset points",
                                             fontsize=9, ha="center", va="center", annotation_clip=False,
                                             bbox=dict(fc="white", ec="none", alpha=0.7, pad=0.5)))
                       for c in CORNERS]
        if self.factor:
            handles.append(Line2D([], [], color=SPIKE_COLOUR, lw=2.2, label=f"interpenetration × {self.factor:g}"))
        handles.append(Line2D([], [], color="0.35", ls=":", lw=0.9, label="$C^1C^3$"))
        _limits(ax, self._extent(frames))
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncols=len(handles),
                  fontsize=8, frameon=False, handlelength=2.2, columnspacing=1.4)

    def _bodies(self, ax, gid="", alpha=0.9):
        """Filled outlines of RB1, RB3, RB2 (drawn in that order) on ``ax``."""
        from .drawing import PAD_COLOUR, PLATE_COLOUR

        return {i: self._add(ax.fill([], [], ec="k", lw=0.8, fc=PAD_COLOUR if i == 2 else PLATE_COLOUR,
                                     alpha=alpha if i == 2 else 1.0, gid=gid.format(i) or None)[0])
                for i in (1, 3, 2)}

    def _extent(self, frames):
        """Points (cm) enclosing every shown configuration."""
        from .drawing import placed

        pts = []
        for q in (self.q, self.qs) if self.stick else (self.q,):
            for i in (1, 2, 3):
                lo, hi = self.shapes[i].min(axis=0), self.shapes[i].max(axis=0)
                box = np.array([[lo[0], lo[1]], [lo[0], hi[1]], [hi[0], lo[1]], [hi[0], hi[1]]])
                Rx, Ry, th = (v[:, None] for v in _body(q, i, frames))
                ok = np.isfinite(Rx + Ry + th)[:, 0]
                pts.append(100 * placed(box[None], Rx[ok], Ry[ok], th[ok]).reshape(-1, 2))
        return np.vstack(pts)

    def _insets(self, frames):
        from matplotlib.transforms import Bbox, TransformedBbox

        from .drawing import I_LABEL, length_unit

        self.zoom = {}
        for j, c in enumerate(CORNERS):
            ins = self.fig.add_axes([*_INSETS[c], *_INSET_SIZE])
            peak = float(np.nanmax(np.abs(self.I[frames, j]), initial=0.0))
            half = min(max(_nice_ceil(2 * peak), WINDOW_MIN), WINDOW_MAX)
            bodies = self._bodies(ins, alpha=0.75)
            segment = self._add(ins.plot([], [], color=SPIKE_COLOUR, lw=1.8, solid_capstyle="butt")[0])
            point = self._add(ins.plot([], [], "o", color=SPIKE_COLOUR, ms=3, gid=f"zoom_{c}")[0])
            # the moving parts stay above the strip of the window's label, which is then drawn once
            above = TransformedBbox(Bbox.from_extents(0, _LABEL_STRIP, 1, 1), ins.transAxes)
            for artist in (*bodies.values(), segment, point):
                artist.set_clip_box(above)
            self.dynamic += ins.spines.values()  # over the bodies
            ins.set_aspect("equal")
            ins.set_xticks([])
            ins.set_yticks([])
            factor, unit = length_unit(2 * half)
            ins.text(0.5, _LABEL_STRIP / 2, f"window {_number(factor * 2 * half)} {unit} wide", fontsize=7,
                     transform=ins.transAxes, ha="center", va="center")
            title = self._add(_field(self.fig, _INSET_FIELD[c], 1.04, f"{I_LABEL[c]} =", ins.transAxes, fontsize=8.5))
            self._add(self.ax.indicate_inset_zoom(ins, edgecolor="0.5", alpha=0.6, lw=0.6))
            self.zoom[c] = (ins, bodies, segment, point, title, half)

    def _traces(self):
        from matplotlib.lines import Line2D
        from matplotlib.ticker import MaxNLocator

        from .drawing import step_path

        t, ds = self.t, self.ds
        rise = ds["rise"].values if "rise" in ds else self.q["Ry3"] - self.q["Ry3"][0]
        rest = self.q["Ry3"] - rise
        structure = has_structure(ds)
        ground = ("$X_g$ (grey), stroke $u$ (cm)", 100 * ds["stroke"].values, None) if structure else \
            ("$X_g$ (cm)", 100 * (ds["Xg"].values if "Xg" in ds else self.q["Rx1"]), None)
        series = [ground,
                  (r"$\theta^2$ (°)", self.q["theta2"], self.qs["theta2"] if self.stick else None),
                  ("rise of RB3 (cm)", 100 * rise, 100 * (self.qs["Ry3"] - rest) if self.stick else None)]
        self.trace = []
        for box, (label, end, stick) in zip(_TRACES, series):
            ax = self.fig.add_axes(box)
            if stick is not None and t.size > 1:
                ax.plot(*step_path(t, end, stick), color=STICK_COLOUR, lw=0.6, alpha=0.6)
            if structure and not self.trace:  # the ground beside the stroke
                ax.plot(t, 100 * ds["Xg"].values, color="0.55", lw=1.0)
            ax.plot(t, end, color="tab:purple" if structure and not self.trace else "k", lw=1.3)
            ax.set_xlim(t[0], t[-1] if t[-1] > t[0] else t[0] + 1e-3)
            ax.set_xlabel("t (s)", labelpad=1)
            ax.set_ylabel(label, labelpad=2)
            ax.tick_params(labelsize=8)
            ax.xaxis.set_major_locator(MaxNLocator(5))
            events = self._events(ax)
            cursor = self._add(ax.axvline(t[0], color=CURSOR_COLOUR, lw=1.2))
            dot = self._add(ax.plot([], [], "o", color=CURSOR_COLOUR, ms=5)[0])
            sdot = self._add(ax.plot([], [], "o", color=STICK_COLOUR, ms=4)[0])
            self.trace.append((cursor, dot, sdot, end, stick))
        handles = [Line2D([], [], color="k", lw=1.3, label="end of step" if self.stick else "history"),
                   Line2D([], [], color=CURSOR_COLOUR, lw=1.2, marker="o", ms=5, label="shown step")]
        if self.stick:
            handles.insert(1, Line2D([], [], color=STICK_COLOUR, lw=0.8, marker="o", ms=4,
                                     label="through the end of sticking (at mid-step)"))
        handles += [Line2D([], [], color=colour, ls="--", lw=1.0, label=label) for label, colour in events]
        self.fig.legend(handles=handles, loc="lower center", bbox_to_anchor=(0.5, sum(_TRACES[0][1::2]) + 0.005),
                        ncols=len(handles), fontsize=8, frameon=False, handlelength=2.2, columnspacing=1.6)

    def _events(self, ax):
        """Dashed lines at the history's events (``viewer.events``) within the traces; their (label, colour)."""
        attrs, (lo, hi) = self.ds.attrs, ax.get_xlim()
        drawn = []
        for value, colour, label in events(attrs):
            if lo <= value <= hi + 2 * float(attrs.get("dt_s", 0.0)):
                ax.axvline(value, color=colour, ls="--", lw=1.0)
                if value >= hi:  # at or after the last step: off the right spine, where it would not show
                    hi = value + 0.01 * (hi - lo)
                    ax.set_xlim(lo, hi)
                drawn.append((label, colour))
        return drawn

    def _texts(self, name):
        from .drawing import fit_width

        attrs, g = self.ds.attrs, self.g
        head = (f"{MODEL_TITLES[attrs['model']]} model;  $R^1$ = {g.R1:g} m, $\\alpha^1$ = "
                f"{np.degrees(g.alpha1):.3g}°, $\\alpha^{{21}}$ = {np.degrees(g.alpha21):.3g}°, $h^2$ = "
                f"{100 * g.h2:.3g} cm  —  {name}")
        fit_width(self.fig.text(0.5, 0.985, head, ha="center", va="top", fontsize=11), self.fig)
        notes = run_notes(attrs)
        if notes:
            self.fig.text(0.5, 0.006, notes, ha="center", va="bottom", fontsize=8, color="tab:red", linespacing=1.1,
                          bbox=dict(fc="#fff4f0", ec="tab:red", lw=0.6, pad=1.5))
        self.status = {}
        for row, y in zip(_STATUS[:2 if self.stick else 1], _STATUS_Y):
            if has_structure(self.ds):  # the device's motion is the stroke: RB1 moves by -u
                row = {**row, "Xg": ("$u$ =", row["Xg"][1])} if "Xg" in row else row
            self.status |= {key: self._add(_field(self.fig, x, y, label, fontsize=9.5))
                            for key, (label, x) in row.items()}
        if self.stick:
            self.fig.text(_DEVICE[0], _STATUS_Y[1], "end of sticking (red):", fontsize=9.5, color=STICK_COLOUR)
        self.flag = self._add(self.ax.text(0.5, 0.97, "", transform=self.ax.transAxes, ha="center", va="top",
                                           fontsize=9, color="tab:red", fontweight="bold"))

    # --- one step ---------------------------------------------------------------------------
    def show(self, n):
        """Move every dynamic artist to step n (index in the dataset)."""
        from .drawing import placed

        xy = {i: 100 * placed(self.shapes[i], *_body(self.q, i, n)) for i in (1, 2, 3)}
        for i, patch in self.bodies.items():
            patch.set_xy(xy[i])
        pts = placed(self.g.pad_corners, *_body(self.q, 2, n))
        self.corners.set_data(100 * pts[:, 0], 100 * pts[:, 1])
        out = pts - [self.q["Rx2"][n], self.q["Ry2"][n]]
        for label, p, d in zip(self.labels, 100 * pts, out / np.hypot(*out.T)[:, None]):
            label.xy, label.xyann = tuple(p), tuple(11 * d)  # the label outside its corner
        centres = np.array([placed(self.g.circle_centres[0], *_body(self.q, 1, n)),
                            placed(self.g.circle_centres[1], *_body(self.q, 3, n))])
        self.link.set_data(100 * centres[:, 0], 100 * centres[:, 1])
        self._spikes(n, pts, centres)
        self._zooms(n, xy, pts, centres)
        sticking = self._ghost(n) if self.stick else None
        self._cursor(n)
        self._status(n, sticking)

    def _foot(self, j, point, centres):
        """Radial projection of corner j onto its plate's circle, and the unit radius through it."""
        centre, radius = (centres[0], self.g.R1) if j < 2 else (centres[1], self.g.R3)
        u = (point - centre) / np.hypot(*(point - centre))
        return centre + radius * u, u

    def _spikes(self, n, pts, centres):
        xs, ys = [], []
        for j in range(4) if self.factor else ():
            if self.I[n, j] > 0:
                foot, u = self._foot(j, pts[j], centres)
                tip = foot + self.factor * self.I[n, j] * u
                xs += [100 * foot[0], 100 * tip[0], np.nan]
                ys += [100 * foot[1], 100 * tip[1], np.nan]
        self.spikes.set_data(xs, ys)

    def _zooms(self, n, xy, pts, centres):
        for j, c in enumerate(CORNERS):
            ins, bodies, segment, point, title, half = self.zoom[c]
            for i, patch in bodies.items():
                patch.set_xy(xy[i])
            foot, _ = self._foot(j, pts[j], centres)
            p, foot = 100 * pts[j], 100 * foot
            segment.set_data([p[0], foot[0]], [p[1], foot[1]])
            point.set_data([p[0]], [p[1]])
            ins.set_xlim(p[0] - 100 * half, p[0] + 100 * half)
            ins.set_ylim(p[1] - 100 * half, p[1] + 100 * half)
            value = float(self.I[n, j])
            title.set_text(interpenetration_text(value, self.tol))
            title.set_color(SPIKE_COLOUR if value > self.tol else "0.25")

    def _ghost(self, n):
        """Draw the end of sticking of step n; returns (theta2, diagonal) or None (no sticking phase)."""
        from .drawing import placed

        valid = all(math.isfinite(v[n]) for v in self.qs.values())
        for artist in (*self.ghosts.values(), self.ghost_corners, self.diagonal):
            artist.set_visible(valid)
        if not valid:
            return None
        for i, patch in self.ghosts.items():
            pose = _body(self.qs, i, n)
            patch.set_xy(100 * placed(self.shapes[i], *pose))
            # RB1 follows the ground in both phases: outline it only where it differs
            patch.set_visible(i != 1 or not np.allclose(pose, _body(self.q, i, n), rtol=0, atol=1e-9))
        pts = 100 * placed(self.g.pad_corners, *_body(self.qs, 2, n))
        self.ghost_corners.set_data(pts[:, 0], pts[:, 1])
        d = int(self.diag[n]) if self.diag is not None else None
        self.diagonal.set_visible(d in (0, 1))
        if d in (0, 1):
            self.diagonal.set_data(pts[list(DIAGONALS[d]), 0], pts[list(DIAGONALS[d]), 1])
        return self.qs["theta2"][n], self.trace[2][4][n], d

    def _cursor(self, n):
        t = self.t[n]
        mid = 0.5 * (self.t[n - 1] + t) if n > 0 else None
        for cursor, dot, sdot, end, stick in self.trace:
            cursor.set_xdata([t, t])
            dot.set_data([t], [end[n]])
            if stick is not None and mid is not None and np.isfinite(stick[n]):
                sdot.set_data([mid], [stick[n]])
            else:
                sdot.set_data([], [])

    def _status(self, n, sticking):
        motion = -100 * self.q["Rx1"][n] if has_structure(self.ds) else 100 * self.q["Rx1"][n]  # u, or X_g
        values = {"t": f"{self.t[n]:{self.tfmt}} s", "step": f"{self.steps[n]}", "Xg": f"{motion:+.2f} cm",
                  "theta2": f"{self.q['theta2'][n]:+.2f}°", "rise": f"{self.trace[2][3][n]:+.2f} cm"}
        if self.stick:
            theta2, rise, d = sticking or (None, None, None)
            values |= {"diagonal_stick": DIAGONAL_NAMES[d] if d in (0, 1) else "\u2013",
                       "theta2_stick": "\u2013" if theta2 is None else f"{theta2:+.2f}°",
                       "rise_stick": "\u2013" if rise is None else f"{rise:+.2f} cm"}
        for key, text in self.status.items():
            text.set_text(values.get(key, ""))
        flags = []
        if "capacity_exceeded" in self.ds and int(self.ds["capacity_exceeded"].values[n]):
            flags.append("pad beyond a retaining ring")
        if int(self.ds.attrs.get("failed", 0)) and n == self.t.size - 1:
            flags.append("the ring ends the run (capacity: error)" if failure_of(self.ds.attrs) == "capacity"
                         else "last converged step: the solver failed on the next")
        if self.stick and sticking is None:
            flags.append("no sticking phase at the first step")
        self.flag.set_text("; ".join(flags))


def _field(fig, x, y, label, transform=None, **kwargs):
    """A static label ending at (x, y) and, returned, the Text of its value starting there."""
    from matplotlib.transforms import offset_copy

    transform = fig.transFigure if transform is None else transform
    fig.text(x, y, label, ha="right", va="baseline", transform=offset_copy(transform, fig, x=-2, units="points"),
             **kwargs)
    return fig.text(x, y, "", ha="left", va="baseline", transform=offset_copy(transform, fig, x=2, units="points"),
                    **kwargs)


def _limits(ax, points, margin=2.0):
    """Equal-aspect limits (cm) around ``points``, filling the axes box."""
    lo, hi = points.min(axis=0) - margin, points.max(axis=0) + margin
    width, height = ax.get_position().size * ax.get_figure().get_size_inches()
    span = np.maximum(hi - lo, (hi - lo)[::-1] * np.array([width / height, height / width]))
    mid = 0.5 * (lo + hi)
    ax.set_xlim(mid[0] - span[0] / 2, mid[0] + span[0] / 2)
    ax.set_ylim(mid[1] - span[1] / 2, mid[1] + span[1] / 2)
    ax.set_aspect("equal")
    ax.set_xlabel("X (cm)", labelpad=1)
    ax.set_ylabel("Y (cm)", labelpad=1)


def draw_frame(fig, ds, n, *, exaggeration=None, frames=None, name=None):
    """Draw step n of the history ``ds`` on a figure (cleared first); returns the Scene.

    Parameters
    ----------
    fig : matplotlib Figure.
    ds : time-history dataset.
    n : step index in ``ds`` (0: the first stored step).
    exaggeration : magnification of the interpenetration spikes; None: automatic, 0: none.
    frames : steps that fix the drawing limits and zoom windows (default: up to MAX_FRAMES of all).
    name : what the history is of, in the heading; None: its case (``viewer.case_text``).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    n = range(ds.sizes["t"])[n]  # IndexError out of range; -1: the last step
    if frames is None:
        frames = frame_steps(ds.sizes["t"])[0]
    fig.clear()
    if fig.canvas is None or not hasattr(fig.canvas, "copy_from_bbox"):
        FigureCanvasAgg(fig)
    scene = _scene(fig, ds, np.union1d(frames, [n]), exaggeration, name)
    scene.show(n)
    return scene


class _Blitter:
    """Renders the steps of a Scene: the static parts are drawn once, the dynamic ones per step."""

    def __init__(self, scene, first):
        self.scene, self.canvas = scene, scene.fig.canvas
        scene.show(first)
        for artist in scene.dynamic:
            artist.set_animated(True)
        self.canvas.draw()
        self.background = self.canvas.copy_from_bbox(scene.fig.bbox)

    def __call__(self, n):
        """Draw step n; returns the image."""
        self.scene.show(n)
        self.canvas.restore_region(self.background)
        for artist in self.scene.dynamic:
            self.scene.fig.draw_artist(artist)
        return _rgb(self.scene.fig)


# --- writers ----------------------------------------------------------------------------------
def _rgb(fig):
    """The figure's canvas as drawn, as a Pillow RGB image."""
    from PIL import Image

    w, h = fig.canvas.get_width_height(physical=True)
    return Image.frombuffer("RGBA", (w, h), fig.canvas.buffer_rgba(), "raw", "RGBA", 0, 1).convert("RGB")


def _palette(images):
    """One 255-colour palette (a "P" image) for all frames, from a few of them: the frames keep the
    same colours, and the GIF encoder can leave the unchanged pixels out (transparent)."""
    from PIL import Image

    w, h = images[0].size
    sheet = Image.new("RGB", (w, h * len(images)))
    for k, image in enumerate(images):
        sheet.paste(image, (0, h * k))
    return sheet.quantize(255, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE)


@functools.cache
def _writer_classes():
    """matplotlib's writers, taking each frame from the canvas as drawn (see _Blitter)."""
    from matplotlib import animation
    from PIL import Image

    class Gif(animation.PillowWriter):
        def __init__(self, fps, palette):
            super().__init__(fps=fps)
            self.palette = palette

        def grab_frame(self, **savefig_kwargs):
            self._frames.append(_rgb(self.fig).quantize(palette=self.palette, dither=Image.Dither.NONE))

        def finish(self):
            self._frames[0].save(self.outfile, format="GIF", save_all=True, append_images=self._frames[1:],
                                 duration=round(1000 / self.fps), loop=0, optimize=True)

    class Html(animation.AbstractMovieWriter):
        def __init__(self, fps, palette):
            super().__init__(fps=fps)
            self.palette, self.frames = palette, []

        def setup(self, fig, outfile, dpi=None):
            super().setup(fig, outfile, dpi)

        def grab_frame(self, **savefig_kwargs):
            png = BytesIO()
            _rgb(self.fig).quantize(palette=self.palette, dither=Image.Dither.NONE).save(png, format="PNG")
            self.frames.append(base64.b64encode(png.getvalue()).decode("ascii"))

        def finish(self):
            Path(self.outfile).write_text(html_page(self.frames, 1000 / self.fps), encoding="utf-8")

    class Mp4(animation.FFMpegWriter):
        def __init__(self, fps, palette):
            super().__init__(fps=fps, codec="h264", extra_args=["-pix_fmt", "yuv420p"])

        def grab_frame(self, **savefig_kwargs):
            self._proc.stdin.write(bytes(self.fig.canvas.buffer_rgba()))

    return {".gif": Gif, ".html": Html, ".mp4": Mp4}


#: the HTML player: frames in a JavaScript array, a slider, step and play buttons; no script or font
#: from elsewhere
_HTML_PAGE = """<!DOCTYPE html>
<html>
<head>
<meta charset="utf-8">
<title>dccss animation</title>
<style>
body {{ font-family: sans-serif; }}
#controls {{ display: flex; gap: 0.4em; align-items: center; margin-top: 0.4em; }}
#controls input[type=range] {{ flex: 1; }}
</style>
</head>
<body>
<img id="frame" alt="dccss animation frame" src="">
<div id="controls">
<button onclick="step(-{count})" title="first">|&#9664;&#9664;</button>
<button onclick="step(-1)" title="previous">|&#9664;</button>
<button id="play" onclick="toggle()" title="play / pause">&#9654;</button>
<button onclick="step(1)" title="next">&#9654;|</button>
<button onclick="step({count})" title="last">&#9654;&#9654;|</button>
<input id="slider" type="range" min="0" max="{last}" value="0" oninput="show(+this.value)">
<span id="label"></span>
</div>
<script>
var frames = new Array({count});
{frames}
var current = 0, timer = null;
function show(k) {{
  current = Math.max(0, Math.min({last}, k));
  document.getElementById("frame").src = frames[current];
  document.getElementById("slider").value = current;
  document.getElementById("label").textContent = "frame " + (current + 1) + " of {count}";
}}
function step(d) {{ pause_animation(); show(current + d); }}
function pause_animation() {{
  if (timer !== null) {{ clearInterval(timer); timer = null; }}
  document.getElementById("play").innerHTML = "&#9654;";
}}
function toggle() {{
  if (timer !== null) {{ pause_animation(); return; }}
  document.getElementById("play").innerHTML = "&#9646;&#9646;";
  timer = setInterval(function () {{ show((current + 1) % {count}); }}, {interval});
}}
show(0);
</script>
</body>
</html>
"""


def html_page(frames, interval_ms):
    """One self-contained HTML document playing ``frames`` (base64 PNG) every ``interval_ms``."""
    data = "\n".join(f'frames[{k}] = "data:image/png;base64,{frame}";' for k, frame in enumerate(frames))
    return _HTML_PAGE.format(count=len(frames), last=len(frames) - 1, frames=data, interval=max(1, round(interval_ms)))


# --- entry points --------------------------------------------------------------------------------
def animate(path, output, *, start=None, end=None, fps=10, max_frames=MAX_FRAMES, exaggeration=None) -> str:
    """Animate a result history to OUT.gif, OUT.html (one self-contained page) or OUT.mp4 (needs ffmpeg).

    One frame per shown step. For the Stick-Slip model each frame shows both phases of its step
    (one frame per step keeps the motion smooth and puts the sticking excursion beside the
    step's result): the device filled at the end of slipping and, in red outline, at the end of
    sticking, with the jammed diagonal as a thick red line between its two corners.

    Parameters
    ----------
    path : dccss result netCDF file holding a time history (any model; failed or capacity-stopped too).
    output : file to write; its extension chooses the format (.gif, .html, .mp4).
    start, end : shown time range (s), bounds included; None: from the first / to the last step.
    fps : frames per second, 0 < fps <= 50.
    max_frames : frame budget (>= 2): longer histories show every k-th step and the last.
    exaggeration : magnification of the interpenetration spikes on the device; None: automatic,
        0: none (the corner zoom windows are at true scale in any case).

    Returns
    -------
    str : one-line summary, e.g. "out.gif: 1000 steps (1001 states, t = 0 .. 1 s) shown as 168 frames, every 6th
        step and the last; 10 fps, 16.8 s".

    Raises
    ------
    AnimationError
        Missing or unreadable file, not a dccss time history, unknown extension, empty time range,
        bad fps, max_frames or exaggeration, MP4 without ffmpeg. Nothing is written then.
    """
    suffix = check_options(output, start=start, end=end, fps=fps, max_frames=max_frames, exaggeration=exaggeration)
    ds = select(open_result(path), start, end)
    idx, k = frame_steps(ds.sizes["t"], max_frames)
    _render(ds, idx, output, suffix, fps, exaggeration)
    return summary(output, ds, idx, k, fps)


def _scene(fig, ds, frames, exaggeration=None, name=None):
    """The scene of a history: the planar device, or the spatial view of a bidirectional one (``plan.Scene``);
    its heading says ``name``, by default its case (``viewer.case_text``)."""
    name = case_text(ds.attrs) if name is None else name
    if ds.attrs.get("model") == "articulated":
        from .hinged import Scene as ArticulatedScene

        return ArticulatedScene(fig, ds, frames, name)
    if ds.attrs.get("motion") != "bidirectional":
        return Scene(fig, ds, frames, exaggeration, name)
    from .plan import Scene as SpatialScene

    scene = SpatialScene(fig, ds, frames, exaggeration, name)
    _legend_above_the_rings(scene.plan)
    return scene


def _legend_above_the_rings(ax):
    """The plan view's legend in one row, in a strip added above the rings (in the upper right corner it covered
    their top), as high as the legend: the plan, of equal aspect, grows into the room its place leaves above and
    below it, or shrinks where there is too little."""
    from .drawing import headroom

    handles, labels = ax.get_legend_handles_labels()
    legend = ax.legend(handles, labels, loc="upper center", ncols=len(handles), fontsize=7, frameon=False)
    ax.apply_aspect()
    strip = ax.bbox.y1 - legend.get_window_extent(ax.figure.canvas.get_renderer()).y0  # pixels
    room = ax.get_position(original=True).height * ax.figure.bbox.height
    headroom(ax, frac=strip / min(ax.bbox.height, room - strip))


def _render(ds, idx, output, suffix, fps, exaggeration):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=FIGSIZE, dpi=DPI)
    FigureCanvasAgg(fig)
    blit = _Blitter(_scene(fig, ds, idx, exaggeration), int(idx[0]))
    palette = _palette([blit(int(n)) for n in idx[np.linspace(0, idx.size - 1, min(idx.size, 6)).astype(int)]])
    writer = _writer_classes()[suffix](fps=fps, palette=palette)
    with tempfile.TemporaryDirectory(prefix="dccss-animate-") as tmp:
        movie = Path(tmp) / f"animation{suffix}"
        with writer.saving(fig, movie, DPI):
            for n in idx:
                blit(int(n))
                writer.grab_frame()
        write_atomic(output, lambda target: shutil.copyfile(movie, target))


def add_parser(subparsers):
    """Add the ``animate`` sub-command to an argparse subparsers object; its handler returns the exit code."""
    p = subparsers.add_parser("animate", help="animate a result history to GIF, HTML or MP4",
                              description="Animate a dccss result history: the device to scale with zooms on the "
                                          "pad corners, and time traces of X_g, theta2 and the rise of RB3.")
    p.add_argument("result", help="dccss result netCDF file (a time history)")
    p.add_argument("-o", "--output", required=True, help="OUT.gif, OUT.html (self-contained) or OUT.mp4 (ffmpeg)")
    p.add_argument("--start", type=float, help="first time shown (s; default: the first step)")
    p.add_argument("--end", type=float, help="last time shown (s; default: the last step)")
    p.add_argument("--fps", type=float, default=10.0, help=f"frames per second, 0 < fps <= {MAX_FPS} (default 10)")
    p.add_argument("--max-frames", type=int, default=MAX_FRAMES,
                   help=f"frame budget: longer histories show every k-th step and the last (default {MAX_FRAMES})")
    p.add_argument("--exaggeration", type=float,
                   help="magnification of the interpenetration spikes (default: automatic; 0: none)")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    p.set_defaults(handler=_command)
    return p


def _command(args: argparse.Namespace) -> int:
    return run_command("animate", lambda: animate(args.result, args.output, start=args.start, end=args.end,
                                                  fps=args.fps, max_frames=args.max_frames,
                                                  exaggeration=args.exaggeration), args.quiet)
