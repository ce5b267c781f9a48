"""What the figures show agrees with what they say: marks where the legend puts them, every text inside
the figure, legends off the data, captions naming only what is drawn, coinciding curves told apart,
the paper's symbols printed alike in titles and on axes."""

import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from matplotlib.figure import Figure
from matplotlib.text import Text

from dccss import plan
from dccss.animation import draw_frame
from dccss.case import geometry_from
from dccss.drawing import freeze
from dccss.excitation import Oriented, Sine
from dccss.mechanics.structure import Structure
from dccss.paper.figures import figure_specs, render
from dccss.paper.prototypes import DFP1, DFP2
from dccss.simulation import breakaway, simulate
from dccss.studies import plots as studyplots

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[1] / "config/config.yaml").read_text())
SPECS = figure_specs(CONFIG["figures"])
SINE = Sine(0.27, 30.0, 0.2)


@pytest.fixture(scope="module")
def runs():
    """Short histories: planar compliant (DFP1) and stick-slip (DFP1 at 1 ms, DFP2 at 10 ms), and a
    bidirectional stick-slip one under a structure (two components: the structure's panels have legends)."""
    return {"compliant": simulate(DFP1, SINE, model="compliant", dt=0.01),
            "stick_slip": simulate(DFP2, SINE, model="stick_slip", dt=0.01),
            "stick_slip_fine": simulate(DFP1, SINE, model="stick_slip", dt=0.001),
            "structure": simulate(DFP2, Oriented(Sine(0.15, 2 * np.pi, 1.0), 137.0), model="stick_slip", dt=0.05,
                                  structure=Structure(0.02, 0.05))}


# --- helpers -----------------------------------------------------------------------------------------
def _tick_labels(fig):
    return {id(label) for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)
            for tick in axis.get_major_ticks() + axis.get_minor_ticks() for label in (tick.label1, tick.label2)}


def outside_texts(fig):
    """The texts drawn (partly) outside the figure: every visible text but the tick labels by its extent,
    the tick labels (only those of the ticks a draw shows) by the figure's tight box."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box, ticks = fig.bbox, _tick_labels(fig)
    out = []
    for text in fig.findobj(Text):
        if text.get_visible() and text.get_text().strip() and id(text) not in ticks:
            e = text.get_window_extent(renderer)
            if e.x0 < box.x0 - 0.5 or e.y0 < box.y0 - 0.5 or e.x1 > box.x1 + 0.5 or e.y1 > box.y1 + 0.5:
                out.append(text.get_text())
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    if tight.x0 < -0.01 or tight.y0 < -0.01 or tight.x1 > box.width + 0.01 or tight.y1 > box.height + 0.01:
        out.append(f"tight box {tight.extents.round(1)} of a figure {box.width:g} x {box.height:g}")
    return out


def texts(fig):
    return [t.get_text() for t in fig.findobj(Text) if t.get_visible()]


# --- 1. study summaries: the failed points on the bottom edge, as the legend says ----------------------------
def study(failed):
    """A combined study over Δt and the prototype, both models, the points ``failed`` ({model: (Δt, prototype)})
    without a result."""
    dts, names = [0.001, 0.005, 0.01, 0.02], ["DFP1", "DFP2"]
    base = 1.0 + 0.1 * np.arange(len(dts))[:, None] + 0.05 * np.arange(len(names))[None, :]
    data = []
    for k, model in enumerate(("compliant", "stick_slip")):
        bad = np.zeros(base.shape, bool)
        for dt, name in failed.get(model, ()):
            bad[dts.index(dt), names.index(name)] = True
        values = {"theta2_max_abs": 8.0 * base + k, "rise_max": 0.02 * base, "theta2_end": 7.0 * base,
                  "sticking_rotation_max": 12.0 * base if model == "stick_slip" else np.full(base.shape, np.nan),
                  **{f"I_{c}_max": 1e-3 * base * (1 + 0.01 * j) for j, c in enumerate("ABCD")}}
        values = {name: np.where(bad, np.nan, v) for name, v in values.items()}
        values |= {"capacity_exceeded": np.zeros(base.shape, np.int8), "failed": bad.astype(np.int8)}
        data.append(xr.Dataset({name: (("dt", "prototype"), v) for name, v in values.items()}))
    ds = xr.concat(data, dim="model").assign_coords(
        model=["compliant", "stick_slip"], dt=xr.Variable("dt", dts, {"units": "s"}),
        prototype=np.asarray(names, dtype=object))
    ds.attrs = {"study": "synthetic", "sweep_axes": "dt prototype"}
    return ds


def test_failed_points_are_marked_on_the_bottom_edge_as_the_legend_says():
    ds = study({"stick_slip": [(0.02, "DFP1")], "compliant": [(0.02, "DFP2"), (0.01, "DFP2")]})
    fig = freeze(studyplots.maps(ds, {}, "caption"))  # laid out as saved
    legend = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert any("solver failed" in label and "marked on the bottom edge" in label for label in legend)
    panels = [ax for ax in fig.axes if any(ln.get_gid() == "failed" for ln in ax.get_lines())]
    assert len(panels) == 4  # every summary panel: θ², sticking rotation, rise, interpenetration
    for ax in panels:
        marks = [ln for ln in ax.get_lines() if ln.get_gid() == "failed"]
        where = {}
        for ln in marks:
            shown = ln.get_transform().transform(np.column_stack(ln.get_data()))
            np.testing.assert_allclose(shown[:, 1], ax.bbox.y0, atol=0.01)  # on the bottom edge, not among the data
            for x, (sx, _) in zip(ln.get_xdata(), shown):
                where.setdefault(float(x), []).append(sx)
        expected = {0.02: 2, 0.01: 1} if "sticking" not in ax.get_title() else {0.02: 1}
        assert {x: len(v) for x, v in where.items()} == expected
        for x, shown in where.items():  # side by side, centred on their x
            centre = ax.transData.transform([(x, 1.0)])[0, 0]
            assert abs(np.mean(shown) - centre) < 0.01
            assert len(shown) == 1 or np.min(np.diff(sorted(shown))) >= 9 * fig.dpi / 72


# --- 2. animations: the corner values, every text inside the frame ----------------------------------------------
def test_round_off_prints_as_contact_and_every_text_stays_inside_the_frame(runs):
    ds = runs["compliant"].copy(deep=True)
    n = 9
    values = {"A": 0.0499, "B": -1.11e-16, "C": -9.99e-7, "D": -1.01e-12}  # m: 5 cm, round-off, µm, 1 pm
    for c, value in values.items():
        ds[f"I_{c}"][n] = value
    ds.attrs["case_id"] = "a_study_with_a_rather_long_name/history12_stick_slip_at_the_finest_step_of_all"
    fig = Figure()
    draw_frame(fig, ds, n)
    shown = texts(fig)
    assert "0 (contact)" in shown  # |I_B| is round-off, below the solver's tolerance
    assert "-1.01e-12" not in " ".join(shown) and not any("e-" in t for t in shown if "(gap)" in t)
    assert {"49.9 mm", "-999 nm (gap)", "-0.00101 nm (gap)"} <= set(shown)
    assert outside_texts(fig) == []


@pytest.mark.parametrize("name", ["stick_slip", "structure"])
def test_every_text_of_a_frame_stays_inside(runs, name):
    """A failed run (its note at the foot) of a case with a long id and title (the heading), planar and in
    space."""
    ds = runs[name].assign_attrs(failed=1, failure_time_s=0.2, failure_message="Newton-Raphson did not converge "
                                 "within 25 iterations at the step ending at t = 0.2 s: the residual is 1e-3 m.",
                                 case_id="a_study_with_a_rather_long_name/history12_stick_slip_at_the_finest_step",
                                 title="DCCSS kinematics under bidirectional ground motion of a structure on the "
                                       "device, Stick-Slip model, in a study with a rather long name")
    fig = Figure()
    draw_frame(fig, ds, -1, name="a_study_with_a_rather_long_name_history12.nc")
    assert outside_texts(fig) == []


def test_a_spatial_frame_draws_its_events_and_says_them_below_its_labels():
    """A bidirectional history's frame draws the ring on its traces and says it at the foot, below the axes'
    labels (the foot overprinted the x labels, and the traces had no event line)."""
    ds = simulate(DFP1, Oriented(Sine(0.6, 10.0, 0.6), 30.0), model="stick_slip", dt=0.01, capacity="error",
                  on_failure="mark")
    assert ds.attrs["failure_kind"] == "capacity"
    fig = Figure()
    draw_frame(fig, ds, -1)
    labels = [ln.get_label() for ax in fig.axes for ln in ax.get_lines()]
    assert "pad reaches a ring" in labels and "solver failure" not in labels
    renderer = fig.canvas.get_renderer() if hasattr(fig.canvas, "get_renderer") else None
    (foot,) = [t for t in fig.texts if t.get_text().startswith("capacity: error ended the run")]
    box = foot.get_window_extent(renderer)
    assert all(not box.overlaps(ax.get_tightbbox(renderer)) for ax in fig.axes)
    assert outside_texts(fig) == []


def test_a_spatial_frame_is_titled_by_its_ground_motion_and_parameters(runs):
    """A bidirectional history's frame says its ground motion and the case's parameters in its title (an
    animation said its file's name)."""
    fig = Figure()
    draw_frame(fig, runs["structure"], -1)
    assert fig.get_suptitle().endswith(" - sine $X_{g,max}$ = 15 cm, ω = 6.283 rad/s, along 137°; structure "
                                       "μ = 0.02, ζ = 0.05; Δt = 0.05 s")


def test_the_plan_views_legend_lies_above_the_rings_at_every_step(runs):
    """In the upper right corner of the plan view, the legend covered the top of the rings."""
    ds = runs["structure"]
    fig = Figure()
    scene = draw_frame(fig, ds, -1)
    fig.canvas.draw()
    legend = scene.plan.get_legend().get_window_extent(fig.canvas.get_renderer())
    assert scene.plan.bbox.y0 < legend.y0 and legend.y1 <= scene.plan.bbox.y1
    for n in range(ds.sizes["t"]):
        scene.show(n)
        tops = [scene.plan.transData.transform((ring.center[0], ring.center[1] + ring.radius))[1]
                for ring in scene.rings]
        assert max(tops) < legend.y0, n
    assert outside_texts(fig) == []


# --- 3. dccss plot: legends off the data, the caption naming what is drawn -----------------------------------
def _caption(fig):
    (caption,) = [t for t in fig.texts if t.get_style() == "italic"]
    return caption.get_text()


@pytest.mark.parametrize("name, sticking", [("compliant", False), ("stick_slip", True), ("structure", True)])
def test_plot_legends_lie_outside_the_data_and_the_caption_names_what_is_drawn(runs, name, sticking):
    fig = freeze(plan.figure(runs[name]))  # laid out as ``dccss plot`` writes it
    caption = _caption(fig)
    assert ("end of sticking in red" in caption) == sticking
    assert "sticking" in caption or not sticking
    assert caption.count("ground motion") == 1
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend()] + list(fig.legends)
    assert len(legends) == (5 if name == "structure" else 3)
    renderer = fig.canvas.get_renderer()
    for legend in legends:
        box = legend.get_window_extent(renderer)
        covered = [ax.get_title() or ax.get_ylabel() for ax in fig.axes if box.overlaps(ax.bbox)]
        assert covered == [], f"legend {[t.get_text() for t in legend.get_texts()]} covers {covered}"
    assert outside_texts(fig) == []


@pytest.mark.parametrize("capacity, on_failure, lines, note", [
    ("stop", "error", ["pad reaches a ring"], "The run was stopped there"),
    ("error", "mark", ["pad reaches a ring"], "capacity: error ended the run at the ring"),
    ("continue", "mark", ["pad reaches a ring", "solver failure"], "The solver failed at t = "),
])
def test_plot_draws_the_events_of_a_history_and_says_them(capacity, on_failure, lines, note):
    """A ring, a stop and a solver failure are drawn on the traces and said under the caption, as the
    animation does, without overlapping the panels (before, ``dccss plot`` showed none: a failed run looked
    like a short history)."""
    ds = simulate(DFP1, Sine(0.9, 10.0, 0.6), model="stick_slip", dt=0.01, capacity=capacity, on_failure=on_failure)
    fig = freeze(plan.figure(ds))
    (traces,) = [ax for ax in fig.axes if ax.get_title(loc="left").startswith("(c)")]
    assert [ln.get_label() for ln in traces.get_lines() if not ln.get_label().startswith("_")
            and ln.get_linestyle() == "--" and ln.get_label() in ("pad reaches a ring", "solver failure")] == lines
    caption = " ".join(_caption(fig).split())
    assert note in caption and ("solver failed" in caption.lower()) == ("solver failure" in lines)
    assert outside_texts(fig) == []
    renderer = fig.canvas.get_renderer()
    (text,) = [t for t in fig.texts if t.get_style() == "italic"]
    assert all(not text.get_window_extent(renderer).overlaps(ax.get_tightbbox(renderer)) for ax in fig.axes)


# --- 4. Fig. 18 (e): the sticking rotation and the ground velocity, which coincide ----------------------------
def test_fig18e_tells_the_coinciding_sticking_rotation_and_ground_velocity_apart(runs):
    ds = runs["stick_slip_fine"]
    fig = render(SPECS["fig18"], [ds], "caption")
    (ax,) = [a for a in fig.axes if a.get_title(loc="left").startswith("(e)")]
    (tw,) = [a for a in fig.axes if a is not ax and a.bbox.bounds == ax.bbox.bounds]
    (rotation,) = ax.get_lines()
    (velocity,) = tw.get_lines()
    t = ds["t"].values
    y = ds["theta2_stick"].values[1:] - ds["theta2"].values[:-1]
    x = np.interp(0.5 * (t[1:] + t[:-1]), t, 100 * ds["Xg_dot"].values)
    np.testing.assert_allclose(rotation.get_ydata(), y)
    k = x @ y / (x @ x)
    apart = np.max(np.abs(y - k * x))
    assert apart < 0.05 * np.max(np.abs(y))  # they do coincide: Δθ² is k times the ground velocity
    np.testing.assert_allclose(np.array(tw.get_ylim()) * k, ax.get_ylim(), rtol=1e-6)  # drawn at that scale
    label = velocity.get_label()
    assert f"{k:.3g}" in label and f"coincide within {apart:.2g}°" in label
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert label in legend and len(legend) == 2
    # both visible: the rotation a thin line over the wide band of the velocity
    assert velocity.get_linewidth() >= 4 * rotation.get_linewidth() and velocity.get_alpha() < 1
    assert ax.get_zorder() > tw.get_zorder() and not ax.patch.get_visible()


# --- 4b. Figs. 11 and 12 (a): the ground motion drawn is the dataset's, sample for sample -------------------
@pytest.mark.parametrize("figure", ["fig11", "fig12"])
def test_figs_11_and_12_draw_the_datasets_ground_motion_at_its_times(runs, figure):
    ds = runs["compliant"]
    fig = render(SPECS[figure], [ds], "caption")
    (ax,) = [a for a in fig.axes if a.get_title(loc="left").startswith("(a)")]
    (tw,) = [a for a in fig.axes if a is not ax and a.bbox.bounds == ax.bbox.bounds]
    (ground,), (velocity,) = ax.get_lines(), tw.get_lines()
    t = ds["t"].values
    for line, values in ((ground, ds["Xg"].values), (velocity, ds["Xg_dot"].values)):
        np.testing.assert_array_equal(line.get_xdata(), t)
        np.testing.assert_allclose(line.get_ydata(), 100 * values, rtol=1e-15, atol=0)


# --- 5. the paper's symbols in titles as on the axes ------------------------------------------------------
def _outside_math(text):
    return re.sub(r"\$[^$]*\$", "", text)


def test_titles_print_the_symbols_as_the_axes_do(runs):
    sweep = breakaway(geometry_from(CONFIG["prototypes"]["DFP1"]), np.radians([-6.0, -3.0, 0.0]), [0.05, 0.10])
    figures = {"fig07": render(SPECS["fig07"], [sweep] * len(SPECS["fig07"].panels), "caption"),
               "fig10": render(SPECS["fig10"], [runs["compliant"]] * len(SPECS["fig10"].panels), "caption"),
               "fig11": render(SPECS["fig11"], [runs["compliant"]], "caption"),
               "fig18": render(SPECS["fig18"], [runs["stick_slip_fine"]], "caption")}
    symbols = {"fig07": r"$|\mathbf{C_q}|$", "fig10": "$I_A^1$", "fig11": "$R_y^3$", "fig18": "$R_y^3$"}
    for fig_id, fig in figures.items():
        title = fig.get_suptitle()
        assert "_" not in _outside_math(title), title
        assert symbols[fig_id] in title
        labels = [a.get_ylabel() for a in fig.axes] + [t.get_text() for a in fig.axes if a.get_legend()
                                                       for t in a.get_legend().get_texts()]
        assert any(symbols[fig_id] in label for label in labels)  # the same symbol as on the axes


def test_every_configured_title_prints_its_symbols_in_mathtext():
    from dccss.paper.figures import title_text

    for spec in SPECS.values():
        assert "_" not in _outside_math(title_text(spec.title)), spec.title


def test_every_case_set_caption_prints_its_symbols_in_mathtext():
    """The caption line of a paper figure is its case set's description: 'X_g,max' and 'theta2(t0)' are
    printed as the axes print them, not raw."""
    from dccss.paper.figures import title_text

    for name, case_set in CONFIG["case_sets"].items():
        caption = _outside_math(title_text(case_set["description"]))
        assert "_" not in caption and "theta2" not in caption and "alpha" not in caption, (name, caption)


def test_the_end_of_sticking_is_drawn_in_the_plane_of_the_step(runs):
    """A section's end-of-sticking outline is the same plane's: RB1, which does not move between the phases,
    is drawn where the step's is (before, each configuration was projected on its own lean, and a sticking
    phase leaning the other way drew RB1 mirrored)."""
    ds = simulate(DFP1, Oriented(Sine(0.15, 2 * np.pi, 1.0), 137.0), model="stick_slip", dt=0.01)
    v, g = plan.view(ds), geometry_from("DFP1")
    flipped = 0
    for n in range(1, ds.sizes["t"]):
        step, stuck = plan.section_q(v, n, g), plan.section_q(v, n, g, stick=True)
        assert stuck["Rx1"] == step["Rx1"]
        flipped += np.sign(stuck["theta2"]) == -np.sign(step["theta2"]) != 0
    assert flipped > 0  # the sticking phase leans the other way at some steps: the case the fix is about
