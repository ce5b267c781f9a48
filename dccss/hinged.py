"""An articulated slider's history drawn: the device to scale with its two halves turning about the hinge,
the summary figure (``figure``, ``dccss plot``) and the animation's scene (``Scene``, ``dccss animate``).

The pad's outline is cut at the hinge (``halves``): the lower half, seated on RB1, turns by θ_1 about the
sphere centre C¹ (above it); the upper half, seated on RB3, by θ_3 about C³ (below it); the hinge lies at
L_1 from C¹ and L_3 from C³ (``pose``). RB1 stays in place; RB3 sits where C³ is, L_1 (1 - cos θ_1) + L_3 (1 - cos θ_3)
higher than at rest. A rigid pad would have θ_1 = θ_3; the angle between the halves is the hinge
rotation θ_1 - θ_3. Lengths in cm, angles in degrees.
"""

from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.patches import Polygon

from . import drawing
from .results import geometry_from_attrs

#: a history of an articulated slider must hold these (one component; two: the _x, _y components)
NAMES = ("stroke_1", "stroke_3", "hinge_rotation")
SURFACE_COLOURS = {1: "tab:blue", 3: "tab:red"}


def is_articulated(ds) -> bool:
    """Whether a dccss dataset holds an articulated slider's history."""
    return ds.attrs.get("model") == "articulated"


def two_components(ds) -> bool:
    return "stroke_1_x" in ds


def _clip(points, level, below):
    """The part of the closed polygon ``points`` at or below (``below``) or above ``level`` in y
    (Sutherland-Hodgman against one line)."""
    out = []
    inside = (lambda p: p[1] <= level) if below else (lambda p: p[1] >= level)
    for a, b in zip(points, np.roll(points, -1, axis=0)):
        if inside(a):
            out.append(a)
        if inside(a) != inside(b):
            s = (level - a[1]) / (b[1] - a[1])
            out.append(a + s * (b - a))
    return np.array(out)


def halves(g, hinge=0.0):
    """(lower, upper) outlines of the pad (its frame, m) cut at the hinge ``hinge`` m above its centre."""
    outline = g.pad_outline(n_arc=121)[:-1]
    return _clip(outline, hinge, True), _clip(outline, hinge, False)


def pose(g, theta1, theta3, hinge=0.0):
    """Where things are for the halves' rotations θ_1, θ_3 (rad), RB1 at rest: {"C1", "H" (the hinge), "C3",
    "RB3" (its origin), "lower", "upper": (centre, angle) about which the half's pad-frame points turn
    (``placed_half``)}, m."""
    (c21, c23) = g.pad_cap_centres
    L1, L3 = float(c21[1]) - hinge, hinge - float(c23[1])
    C1 = np.array([0.0, float(g.hs1 + g.R1)])
    H = C1 + L1 * np.array([np.sin(theta1), -np.cos(theta1)])
    C3 = H + L3 * np.array([np.sin(theta3), -np.cos(theta3)])  # C3 lies below the hinge, C1 above it
    return {"C1": C1, "H": H, "C3": C3, "RB3": C3 + np.array([0.0, float(g.hs3 + g.R3)]),
            "lower": (C1, theta1, np.asarray(c21, float)), "upper": (C3, theta3, np.asarray(c23, float))}


def placed_half(points, about):
    """A half's pad-frame ``points`` placed: its cap centre on the sphere centre, turned by the angle."""
    centre, angle, cap = about
    c, s = np.cos(angle), np.sin(angle)
    d = points - cap
    return np.column_stack([centre[0] + c * d[:, 0] - s * d[:, 1], centre[1] + s * d[:, 0] + c * d[:, 1]])


def device_points(g, shapes, parts, theta1, theta3, hinge):
    """{part: (n, 2) points in cm} of RB1, RB3 and the two halves at θ_1, θ_3."""
    p = pose(g, theta1, theta3, hinge)
    return {"RB1": 100 * drawing.placed(shapes[1], 0.0, 0.0, 0.0),
            "RB3": 100 * drawing.placed(shapes[3], p["RB3"][0], p["RB3"][1], 0.0),
            "lower": 100 * placed_half(parts[0], p["lower"]), "upper": 100 * placed_half(parts[1], p["upper"]),
            "link": 100 * np.array([p["C1"], p["H"], p["C3"]])}


def draw_device(ax, g, theta1, theta3, hinge=0.0, shapes=None, parts=None):
    """Draw RB1, RB3 and the two halves at θ_1, θ_3 (rad) in cm; returns every point drawn."""
    shapes = shapes or drawing.body_shapes(g)
    parts = parts or halves(g, hinge)
    pts = device_points(g, shapes, parts, theta1, theta3, hinge)
    for name in ("RB1", "RB3"):
        ax.add_artist(Polygon(pts[name], closed=True, fc=drawing.PLATE_COLOUR, ec="k", lw=0.8))
    for name, plate in (("lower", 1), ("upper", 3)):
        ax.add_artist(Polygon(pts[name], closed=True, fc=drawing.PAD_COLOUR, ec=SURFACE_COLOURS[plate], lw=1.2,
                              alpha=0.9))
    ax.plot(*pts["link"].T, color="0.3", ls=":", lw=0.9)
    ax.plot(*pts["link"][1], "o", color="k", ms=3.5, zorder=5)
    return np.vstack([pts[k] for k in ("RB1", "RB3", "lower", "upper")])


def history(ds):
    """(t, u, u_1, u_3, F/W, hinge rotation (deg), sliding (T, 2)) of a one-component history (x components of
    a two-component one)."""
    x = "_x" if two_components(ds) else ""
    t = ds["t"].values.astype(float)
    u1, u3 = ds[f"stroke_1{x}"].values, ds[f"stroke_3{x}"].values
    sliding = np.stack([ds["sliding_1"].values, ds["sliding_3"].values], axis=-1).astype(bool)
    return t, u1 + u3, u1, u3, ds[f"shear_ratio{x}"].values, ds["hinge_rotation"].values, sliding


def instants(ds, at=None):
    """The steps drawn as sections: those nearest the times ``at``, or where the stroke is largest, where the
    hinge turns most, and the last."""
    t, u, *_, hinge, _ = history(ds)
    if at:
        if not 1 <= len(at) <= 3:
            raise ValueError(f"give 1 to 3 instants, got {len(at)}")
        for when in at:
            if not (np.isfinite(when) and t[0] - 1e-12 <= when <= t[-1] + 1e-12):
                raise ValueError(f"instant {float(when):g} s is outside the history ({t[0]:g} .. {t[-1]:g} s)")
        return [int(np.argmin(np.abs(t - when))) for when in at]
    chosen = []
    for n in (int(np.argmax(np.abs(u))), int(np.argmax(np.abs(hinge))), t.size - 1):
        if all(abs(t[n] - t[m]) > 0.05 * (t[-1] - t[0]) for m in chosen):  # not the same moment twice
            chosen.append(n)
    return sorted(chosen)


def figure(ds, at=None, title=None):
    """The summary figure of an articulated slider's history: the device at up to three instants, each
    surface's share of the stroke, the loops F/W against u and against each u_j, and the hinge rotation with
    which surfaces slide. Returns the Figure."""
    g = geometry_from_attrs(ds.attrs)
    a = ds.attrs
    hinge = float(a.get("slider_hinge_m", 0.0))
    t, u, u1, u3, force, rotation, sliding = history(ds)
    steps = instants(ds, at)
    fig = drawing.new_figure((11.0, 9.6), nrows=None, caption_lines=2)
    grid = fig.add_gridspec(3, 2, height_ratios=(1.15, 1.0, 0.9))
    sections = grid[0, :].subgridspec(1, len(steps))
    shapes, parts = drawing.body_shapes(g), halves(g, hinge)
    L1, L3 = a["pendulum_length_1_m"], a["pendulum_length_3_m"]
    drawn = []
    for k, n in enumerate(steps):
        ax = fig.add_subplot(sections[0, k])
        drawn.append((ax, draw_device(ax, g, np.arcsin(np.clip(u1[n] / L1, -1, 1)),
                                      np.arcsin(np.clip(u3[n] / L3, -1, 1)), hinge, shapes, parts)))
        ax.set_title(f"({chr(97 + k)}) t = {t[n]:.3g} s: hinge {rotation[n]:+.2f} deg", fontsize=9)
    every = np.concatenate([points for _, points in drawn])
    for ax, _ in drawn:  # one frame for all: the sections the same size, at the same scale
        drawing.frame_points(ax, every, margin=2.0)
    split = fig.add_subplot(grid[1, 0])
    split.plot(t, 100 * u, color="k", lw=1.1, label="stroke $u = u_1 + u_3$")
    for j, uj in ((1, u1), (3, u3)):
        split.plot(t, 100 * uj, color=SURFACE_COLOURS[j], lw=1.0, label=f"$u_{j}$ (surface {j})")
        ring = a.get(f"ring_stroke_{j}_m")
        if ring is not None:
            for sign in (1, -1):
                split.axhline(100 * sign * ring, color=SURFACE_COLOURS[j], ls="--", lw=0.7)
    split.set_title(f"({chr(97 + len(steps))}) each surface's share of the stroke (dashed: its ring)", fontsize=9)
    split.set_xlabel("t (s)")
    split.set_ylabel("displacement (cm)")
    split.legend(fontsize=8, loc="best")
    loop = fig.add_subplot(grid[1, 1])
    loop.plot(100 * u, force, color="k", lw=1.0, label="$F/W$ against $u$")
    for j, uj in ((1, u1), (3, u3)):
        loop.plot(100 * uj, force, color=SURFACE_COLOURS[j], lw=0.8, alpha=0.8, label=f"against $u_{j}$")
    loop.set_title(f"({chr(98 + len(steps))}) force-displacement loops", fontsize=9)
    loop.set_xlabel("displacement (cm)")
    loop.set_ylabel("F/W (-)")
    loop.legend(fontsize=8, loc="best")
    hinge_ax = fig.add_subplot(grid[2, :])
    hinge_ax.plot(t, rotation, color="tab:purple", lw=1.0, label="hinge rotation")
    low, high = hinge_ax.get_ylim()
    for j in (1, 3):
        hinge_ax.fill_between(t, 0, 1, where=sliding[:, 0 if j == 1 else 1], step="mid", color=SURFACE_COLOURS[j],
                              alpha=0.12, lw=0, transform=hinge_ax.get_xaxis_transform(), label=f"surface {j} slides")
    hinge_ax.set_ylim(low, high)
    hinge_ax.set_title(f"({chr(99 + len(steps))}) the angle between the halves, and which surfaces slide", fontsize=9,
                       loc="left")
    hinge_ax.set_xlabel("t (s)")
    hinge_ax.set_ylabel("hinge rotation (deg)")
    hinge_ax.legend(fontsize=8, ncols=3, loc="upper right")
    for ax in (split, loop, hinge_ax):
        ax.grid(True, color="0.9", lw=0.6)
    drawing.caption_line(fig, title or caption(ds))
    return fig


def caption(ds) -> str:
    """What the figure shows: the device, its friction and what drives it."""
    a = ds.attrs
    if "friction_surfaces" in a:
        mu = np.atleast_1d(a["friction_surfaces"])
        drive = f"under the imposed displacement, quasi-statically; μ1 = {mu[0]:g}, μ3 = {mu[1]:g}"
    else:
        drive = (f"driven by its structure ({a.get('structure_friction_given', '')}, "
                 f"ζ = {a.get('structure_damping', 0):g})")
    text = (f"Articulated slider (two halves on a hinge, L1 = {100 * a['pendulum_length_1_m']:.1f} cm, "
            f"L3 = {100 * a['pendulum_length_3_m']:.1f} cm) {drive}")
    reached = [f"surface {j} reaches its ring at t = {a[f'ring_{j}_reached_at_s']:.3g} s" for j in (1, 3)
               if f"ring_{j}_reached_at_s" in a]
    return textwrap.fill(text + ("; " + ", ".join(reached) if reached else ""), 150)


class Scene:
    """The animation of an articulated slider's history: the device with its halves, and the traces of each
    surface's displacement and the hinge rotation with a time cursor; ``show(n)`` moves it to step n,
    ``dynamic`` the artists that change."""

    def __init__(self, fig, ds, frames, name=""):
        from .viewer import FIGSIZE

        self.fig, self.ds = fig, ds
        a = ds.attrs
        self.g = geometry_from_attrs(a)
        self.hinge = float(a.get("slider_hinge_m", 0.0))
        self.L = (a["pendulum_length_1_m"], a["pendulum_length_3_m"])
        self.t, self.u, self.u1, self.u3, self.force, self.rotation, self.sliding = history(ds)
        self.shapes, self.parts = drawing.body_shapes(self.g), halves(self.g, self.hinge)
        fig.set_size_inches(*FIGSIZE)
        self.dynamic = []
        ax = self.ax = fig.add_axes([0.06, 0.33, 0.88, 0.54])
        frames = np.asarray(frames, dtype=int)
        points = []
        for n in frames[np.linspace(0, frames.size - 1, min(frames.size, 40)).astype(int)]:
            drawn = self._points(n)
            points.append(np.vstack([drawn[k] for k in ("RB1", "RB3", "lower", "upper")]))
        drawing.frame_points(ax, np.vstack(points), margin=2.0)
        self.bodies = {}
        for part in ("RB1", "RB3"):
            self.bodies[part] = self._add(ax.fill([], [], fc=drawing.PLATE_COLOUR, ec="k", lw=0.8)[0])
        for part, plate in (("lower", 1), ("upper", 3)):
            self.bodies[part] = self._add(ax.fill([], [], fc=drawing.PAD_COLOUR, ec=SURFACE_COLOURS[plate], lw=1.4,
                                                  alpha=0.9, label=f"half on surface {plate}")[0])
        self.link = self._add(ax.plot([], [], color="0.3", ls=":", lw=0.9, label="$C^1$ - hinge - $C^3$")[0])
        self.joint = self._add(ax.plot([], [], "o", color="k", ms=4, label="hinge")[0])
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncols=4, fontsize=8, frameon=False)
        self.text = self._add(fig.text(0.06, 0.925, "", va="top", fontsize=9, family="monospace"))
        traces = self.traces = fig.add_axes([0.06, 0.06, 0.88, 0.17])
        traces.plot(self.t, 100 * self.u, color="k", lw=1.0, label="u")
        for j, uj in ((1, self.u1), (3, self.u3)):
            traces.plot(self.t, 100 * uj, color=SURFACE_COLOURS[j], lw=0.9, label=f"$u_{j}$")
        traces.set_xlim(self.t[frames[0]], self.t[frames[-1]] if frames[-1] > frames[0] else self.t[frames[0]] + 1)
        traces.set_xlabel("t (s)")
        traces.set_ylabel("cm")
        traces.legend(fontsize=7, loc="upper right", ncols=3)
        traces.grid(True, color="0.9", lw=0.6)
        self.cursor = self._add(traces.axvline(self.t[frames[0]], color="0.4", lw=0.8))
        fig.text(0.06, 0.955, f"Articulated slider: {name}" if name else "Articulated slider", fontsize=10)

    def _add(self, artist):
        self.dynamic.append(artist)
        return artist

    def _points(self, n):
        L1, L3 = self.L
        return device_points(self.g, self.shapes, self.parts, np.arcsin(np.clip(self.u1[n] / L1, -1, 1)),
                             np.arcsin(np.clip(self.u3[n] / L3, -1, 1)), self.hinge)

    def show(self, n):
        pts = self._points(n)
        for part, artist in self.bodies.items():
            artist.set_xy(pts[part])
        self.link.set_data(*pts["link"].T)
        self.joint.set_data([pts["link"][1, 0]], [pts["link"][1, 1]])
        state = {(True, True): "both slide", (True, False): "surface 1 slides", (False, True): "surface 3 slides",
                 (False, False): "both hold"}[tuple(bool(x) for x in self.sliding[n])]
        self.text.set_text(f"t = {self.t[n]:8.4f} s   u = {100 * self.u[n]:+7.2f} cm   u1 = {100 * self.u1[n]:+7.2f} cm"
                           f"   u3 = {100 * self.u3[n]:+7.2f} cm\nhinge {self.rotation[n]:+6.2f} deg   F/W = "
                           f"{self.force[n]:+.3f}   {state}")
        self.cursor.set_xdata([self.t[n], self.t[n]])
