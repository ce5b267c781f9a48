"""Study plots from small synthetic datasets: what is drawn where, in which units, reproducibly."""

import numpy as np
import pytest
import xarray as xr
from matplotlib.collections import PatchCollection, QuadMesh
from matplotlib.image import AxesImage

from dccss.drawing import save
from dccss.studies import plots as studyplots

MODELS = ("compliant", "stick_slip")
AXIS_UNITS = {"alpha21": "degree", "h2": "m", "amplitude": "m", "omega": "rad s-1", "scale": "1",
              "theta2_0": "degree", "dt": "s", "friction": "1"}
CATEGORICAL = ("prototype", "record", "component")


# --- synthetic datasets ----------------------------------------------------------------------------
def history(model, t_end=1.0, dt=0.01, gain=1.0, **attrs):
    """A history dataset like ``dccss.simulate``'s (only what the plots read), t = 0 .. t_end."""
    t = np.round(np.arange(0.0, t_end + dt / 2, dt), 10)
    phase = 30.0 * t
    corners = {f"I_{c}": ("t", gain * 1e-3 * np.sin(phase + k) ** 2 * (-1) ** k) for k, c in enumerate("ABCD")}
    ds = xr.Dataset({"Xg": ("t", 0.27 * np.sin(phase)), "theta2": ("t", gain * 8.5 * np.sin(phase)),
                     "rise": ("t", gain * 0.02 * np.sin(phase) ** 2), **corners}, coords={"t": t})
    ds["Xg"].attrs["units"] = "m"
    ds.attrs = {"model": model, **attrs}
    return ds


def pair(**attrs):
    """Both models at one history point; the stick-slip values 5 % larger, to tell the lines apart."""
    return {"compliant": history("compliant", **attrs), "stick_slip": history("stick_slip", gain=1.05, **attrs)}


def study(axes, capacity=None, failed=None, models=MODELS, structure=False):
    """A combined study dataset over ``axes`` ({name: values}); capacity/failed: {model: bool grid}; with a
    ``structure``, its summaries, which have a value where the pad failed."""
    names = list(axes)
    shape = tuple(len(v) for v in axes.values())
    ramp = np.indices(shape).sum(axis=0) if shape else np.zeros(())
    data = {}
    for k, model in enumerate(models):
        base = 1.0 + 0.1 * ramp + 0.2 * k
        cap = np.zeros(shape, bool) if capacity is None else np.asarray(capacity.get(model, np.zeros(shape, bool)))
        bad = np.zeros(shape, bool) if failed is None else np.asarray(failed.get(model, np.zeros(shape, bool)))
        stick = model == "stick_slip"
        values = {"theta2_max_abs": 8.0 * base, "theta2_end": 7.0 * base, "rise_max": 0.02 * base,
                  "rise_end": 0.01 * base, "clearance_min": np.where(cap, -0.01, 0.05),
                  "capacity_time": np.where(cap, 0.3, np.nan), "newton_iterations_mean": 2.0 * base,
                  "newton_iterations_max": 3.0 + 0 * base, "failure_time": np.where(bad, 0.6, np.nan),
                  "sticking_rotation_max": 12.0 * base if stick else np.full(shape, np.nan),
                  "rise_stick_max": 0.05 * base if stick else np.full(shape, np.nan),
                  **{f"I_{c}_max": 1e-3 * base * (1 + 0.01 * j) for j, c in enumerate("ABCD")}}
        values = {name: np.where(bad, np.nan, v) for name, v in values.items()}
        if structure:
            values |= {"stroke_max_abs": 0.1 * base, "shear_ratio_max_abs": 0.05 * base, "stroke_end": 0.01 * base}
        values["capacity_exceeded"] = cap.astype(np.int8)
        values["failed"] = bad.astype(np.int8)
        data[model] = xr.Dataset({name: (names, v) for name, v in values.items()})
    coords = {name: xr.Variable((name,), np.asarray(v, dtype=object) if name in CATEGORICAL else np.asarray(v, float),
                                {} if name in CATEGORICAL else {"units": AXIS_UNITS[name]}) for name, v in axes.items()}
    ds = xr.concat([data[m] for m in models], dim="model").assign_coords(model=list(models), **coords)
    ds.attrs = {"study": "synthetic", "sweep_axes": " ".join(names)}
    return ds


def suite(records, failed=None, **axes):
    """A suite's combined dataset: ``records`` records on a structure over ``axes``, with the suite's statistics."""
    from dccss.studies.combine import statistics

    ds = study({"record": [f"RSN{100 + k}_SUITE" for k in range(records)], **axes}, failed=failed, structure=True)
    return ds.merge(statistics(ds))


# --- helpers reading the figures --------------------------------------------------------------------
def panel(fig, text):
    """The axes whose y label contains ``text``."""
    found = [ax for ax in fig.axes if text in ax.get_ylabel()]
    assert found, f"no panel labelled {text!r}: {[ax.get_ylabel() for ax in fig.axes]}"
    return found


def line_with(ax, y):
    """The one line of an axes whose y values are ``y`` (NaN where ``y`` is NaN)."""
    hits = [ln for ln in ax.get_lines()
            if len(ln.get_ydata()) == len(y) and np.allclose(ln.get_ydata(), y, equal_nan=True)]
    assert len(hits) == 1, f"{len(hits)} lines carry these values"
    return hits[0]


def vertical_lines(ax):
    """x of the vertical lines (axvline) of an axes."""
    return sorted(float(ln.get_xdata()[0]) for ln in ax.get_lines()
                  if len(ln.get_xdata()) == 2 and ln.get_xdata()[0] == ln.get_xdata()[1]
                  and list(ln.get_ydata()) == [0, 1])


def legend_labels(fig):
    return [t.get_text() for legend in fig.legends for t in legend.get_texts()]


def figure_title(fig):
    return " ".join(legend.get_title().get_text() for legend in fig.legends)


def meshes(fig):
    return [a for ax in fig.axes for a in ax.get_children() if isinstance(a, QuadMesh | AxesImage)]


def hatched_cells(ax, gid, xs, ys):
    """(i, j) indices of the cells covered by the patch collection ``gid`` of an axes."""
    found = [c for c in ax.collections if isinstance(c, PatchCollection) and c.get_gid() == gid]
    if not found:
        return set()
    assert len(found) == 1
    cells = set()
    for path in found[0].get_paths():
        lo, hi = path.vertices.min(axis=0), path.vertices.max(axis=0)
        i = [k for k, x in enumerate(xs) if lo[0] < x < hi[0]]
        j = [k for k, y in enumerate(ys) if lo[1] < y < hi[1]]
        assert len(i) == 1 and len(j) == 1, "a hatched rectangle covers exactly one cell"
        cells.add((i[0], j[0]))
    return cells


# --- histories ------------------------------------------------------------------------------------------
def test_ground_displacement_panel_in_cm():
    runs = pair()
    fig = studyplots.histories([("alpha21 = 10", runs)], "caption")
    (ax,) = panel(fig, "$X_g$")
    assert "(cm)" in ax.get_ylabel()
    line_with(ax, 100.0 * runs["compliant"]["Xg"].values)
    assert np.allclose(line_with(ax, 100.0 * runs["compliant"]["Xg"].values).get_xdata(), runs["compliant"]["t"])


def test_models_differ_in_colour_and_line_style_and_compliant_stays_visible():
    runs = pair()
    fig = studyplots.histories([("p", runs)], "caption")
    styles = {}
    for text, name, factor in (("θ²", "theta2", 1.0), ("rise", "rise", 100.0)):
        (ax,) = panel(fig, text)
        for model, ds in runs.items():
            ln = line_with(ax, factor * ds[name].values)
            styles.setdefault(model, set()).add((ln.get_color(), str(ln.get_linestyle()), ln.get_linewidth()))
    assert all(len(s) == 1 for s in styles.values()), "one style per model in every panel"
    (c_colour, c_ls, c_lw), (s_colour, s_ls, s_lw) = (styles[m].pop() for m in MODELS)
    assert c_colour != s_colour and c_ls != s_ls
    assert c_lw > s_lw, "the compliant line is wider than the stick-slip line drawn over it"
    (ax,) = panel(fig, "θ²")
    under, over = (line_with(ax, runs[m]["theta2"].values) for m in MODELS)
    assert under.get_zorder() < over.get_zorder()
    assert {"Compliant Sliding", "Stick-Slip"} <= set(legend_labels(fig))


def test_largest_interpenetration_in_mm():
    runs = pair()
    fig = studyplots.histories([("p", runs)], "caption")
    (ax,) = panel(fig, "$|I|$")
    assert "(mm)" in ax.get_ylabel()
    ds = runs["stick_slip"]
    line_with(ax, 1e3 * np.max(np.abs([ds[f"I_{c}"].values for c in "ABCD"]), axis=0))


def test_capacity_and_failure_times_draw_vertical_lines():
    cut = history("compliant", t_end=0.3, capacity_exceeded_at_s=0.3, capacity_exceeded_plate="RB1",
                  capacity_exceeded_by_m=0.004, capacity_policy="stop", stopped_at_s=0.3)
    failed = history("stick_slip", t_end=0.61, failed=1, failure_time_s=0.62,
                     failure_message="Newton-Raphson did not converge in 25 iterations at step 62")
    fig = studyplots.histories([("quiet", pair()), ("events", {"compliant": cut, "stick_slip": failed})], "c")
    quiet, events = ([ax for ax in fig.axes if ax.get_subplotspec().colspan.start == k] for k in (0, 1))
    assert len(events) == 4 and all(vertical_lines(ax) == [0.3, 0.62] for ax in events)
    assert all(vertical_lines(ax) == [] for ax in quiet)
    title = " ".join(events[0].get_title(loc="left").split())  # wrapped to the column width
    assert "RB1 ring reached at 0.3 s" in title and "cut at 0.3 s" in title and "'stop'" in title
    assert "solver failed at 0.62 s" in title and "did not converge" in title
    assert "pad reaches a retaining ring" in legend_labels(fig)
    assert "solver failed (history ends)" in legend_labels(fig)


def test_one_model_and_several_points_share_time_within_a_point():
    points = [(f"scale = {k}", pair() if k != 2 else {"stick_slip": history("stick_slip")}) for k in range(5)]
    fig = studyplots.histories(points, "caption")
    columns = {}
    for ax in fig.axes:
        if ax.get_visible():
            spec = ax.get_subplotspec()
            columns.setdefault((spec.rowspan.start // 4, spec.colspan.start), []).append(ax)
    assert len(columns) == 5 and all(len(col) == 4 for col in columns.values())
    for col in columns.values():
        assert all(col[0].get_shared_x_axes().joined(col[0], ax) for ax in col)
    first, second = columns[(0, 0)], columns[(0, 1)]
    assert not first[0].get_shared_x_axes().joined(first[0], second[0])
    titles = [col[0].get_title(loc="left") for col in columns.values()]
    assert titles == [f"({'abcde'[k]}) scale = {k}" for k in range(5)]


def test_histories_need_a_point():
    with pytest.raises(ValueError, match="no history points"):
        studyplots.histories([], "caption")


# --- summaries over the sweep ----------------------------------------------------------------------------
def test_one_dimensional_sweep_draws_lines_with_marked_points():
    x = [4.0, 6.0, 8.0, 10.0, 12.0]
    cap = {"stick_slip": np.array([0, 0, 0, 1, 1], bool)}
    bad = {"compliant": np.array([0, 0, 0, 0, 1], bool)}
    ds = study({"alpha21": x}, capacity=cap, failed=bad)
    fig = studyplots.maps(ds, {"DFP1": {"alpha21": 10.0}}, "caption")
    assert meshes(fig) == []
    (ax,) = panel(fig, "max |θ²|")
    for model in MODELS:
        expected = ds["theta2_max_abs"].sel(model=model).values
        ln = line_with(ax, expected)
        assert np.allclose(ln.get_xdata(), x) and ln.get_linestyle() != "None" and ln.get_marker() != "None"
    flagged = {ln.get_gid(): list(ln.get_xdata()) for ln in ax.get_lines() if ln.get_gid()}
    assert flagged == {"capacity_exceeded": [10.0, 12.0], "failed": [12.0]}
    assert 10.0 in vertical_lines(ax), "the marked point"
    assert ax.get_xlabel() == r"$\alpha^{21}$ (°)"
    assert ax.get_xscale() == "linear"


def test_a_model_failing_everywhere_is_marked_failed_not_undefined():
    ds = study({"omega": [20.0, 30.0, 40.0]}, failed={"compliant": np.ones(3, bool)})
    fig = studyplots.maps(ds, {}, "caption")
    (ax,) = panel(fig, "max rise")
    assert [list(ln.get_xdata()) for ln in ax.get_lines() if ln.get_gid() == "failed"] == [[20.0, 30.0, 40.0]]
    assert "not defined" not in ax.get_title()
    (ax,) = panel(fig, "sticking rotation")
    assert [ln.get_gid() for ln in ax.get_lines() if ln.get_gid()] == []
    assert ax.get_title() == "max sticking rotation\n(not defined for Compliant Sliding)"
    ds = study({"omega": [20.0, 30.0], "scale": [1.0, 2.0]}, failed={m: np.ones((2, 2), bool) for m in MODELS})
    fig = studyplots.maps(ds, {}, "caption")
    assert len([ax for ax in fig.axes if ax.get_title()]) == 7  # all but the sticking rotation of compliant
    assert all(hatched_cells(ax, "failed", [20.0, 30.0], [1.0, 2.0]) == {(0, 0), (0, 1), (1, 0), (1, 1)}
               for ax in fig.axes if ax.get_title())


def test_amplitude_axis_and_summaries_in_paper_units():
    ds = study({"amplitude": [0.1, 0.2, 0.3]})
    fig = studyplots.maps(ds, {}, "caption")
    (ax,) = panel(fig, "max rise of RB3")
    assert ax.get_xlabel() == "$X_{g,max}$ (cm)" and "(cm)" in ax.get_ylabel()
    ln = line_with(ax, 100.0 * ds["rise_max"].sel(model="compliant").values)
    assert np.allclose(ln.get_xdata(), [10.0, 20.0, 30.0])
    (ax,) = panel(fig, "interpenetration")
    assert "(mm)" in ax.get_ylabel()
    line_with(ax, 1e3 * ds[[f"I_{c}_max" for c in "ABCD"]].to_array().max("variable").sel(model="compliant").values)


def test_categorical_axis_marks_each_category_at_an_integer():
    names = ["DFP1", "DFP2", "Mine"]
    ds = study({"prototype": names}, failed={"stick_slip": np.array([0, 1, 0], bool)})
    fig = studyplots.maps(ds, {}, "caption")
    assert meshes(fig) == []
    for ax in panel(fig, "("):
        assert list(ax.get_xticks()) == [0, 1, 2]
        assert [t.get_text() for t in ax.get_xticklabels()] == names
    (ax,) = panel(fig, "max |θ²|")
    for model in MODELS:
        values = ds["theta2_max_abs"].sel(model=model).values
        ln = line_with(ax, values)
        assert list(ln.get_xdata()) == [0.0, 1.0, 2.0] and ln.get_linestyle() == "None"
    assert [list(ln.get_xdata()) for ln in ax.get_lines() if ln.get_gid() == "failed"] == [[1.0]]


def test_categorical_and_numeric_axes_give_a_curve_per_category():
    ds = study({"prototype": ["DFP1", "DFP2"], "scale": [0.5, 1.0, 1.5]})
    fig = studyplots.maps(ds, {}, "caption")
    assert meshes(fig) == []
    (ax,) = panel(fig, "max |θ²|")
    for model in MODELS:
        for proto in ("DFP1", "DFP2"):
            ln = line_with(ax, ds["theta2_max_abs"].sel(model=model, prototype=proto).values)
            assert np.allclose(ln.get_xdata(), [0.5, 1.0, 1.5])
    assert {"prototype = DFP1", "prototype = DFP2"} <= set(legend_labels(fig))


def test_two_dimensional_grid_hatches_exactly_the_flagged_cells():
    xs, ys = [4.0, 6.0, 9.0, 12.0], [0.10, 0.15, 0.20]
    cap = {"compliant": np.array([[0, 0, 0], [0, 0, 1], [0, 1, 1], [1, 1, 1]], bool),
           "stick_slip": np.array([[0, 0, 0], [0, 0, 0], [0, 0, 1], [0, 0, 1]], bool)}
    bad = {"stick_slip": np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 0]], bool)}
    ds = study({"alpha21": xs, "h2": ys}, capacity=cap, failed=bad)
    fig = studyplots.maps(ds, {"DFP1": {"alpha21": 9.0, "h2": 0.15}}, "caption")
    rows = {model: [ax for ax in fig.axes if ax.get_title().startswith(studyplots.MODEL_TITLES[model] + ":")]
            for model in MODELS}
    assert len(rows["compliant"]) == 3 and len(rows["stick_slip"]) == 4  # no sticking rotation for compliant
    for model, axes in rows.items():
        expected_cap = set(zip(*np.nonzero(cap[model])))
        expected_bad = set(zip(*np.nonzero(bad.get(model, np.zeros((4, 3), bool)))))
        for ax in axes:
            assert hatched_cells(ax, "capacity_exceeded", xs, ys) == expected_cap
            assert hatched_cells(ax, "failed", xs, ys) == expected_bad
            (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
            shown = np.ma.masked_invalid(mesh.get_array()).mask.reshape(len(ys), len(xs)).T
            assert np.array_equal(shown, bad.get(model, np.zeros((4, 3), bool)))
            stars = [ln for ln in ax.get_lines() if ln.get_marker() == "*"]
            assert [(list(s.get_xdata()), list(s.get_ydata())) for s in stars] == [([9.0], [0.15])]
            assert ax.get_xlabel() == r"$\alpha^{21}$ (°)" and ax.get_ylabel() == "$h^{2}$ (m)"
    labels = legend_labels(fig)
    assert "pad reaches a retaining ring (Compliant Sliding 6, Stick-Slip 2 of 12)" in labels
    assert "solver failed, no result (Compliant Sliding 0, Stick-Slip 5 of 12)" in labels


def test_time_step_axis_on_a_log_scale():
    ds = study({"dt": [0.001, 0.003, 0.01, 0.03]})
    fig = studyplots.maps(ds, {}, "caption")
    assert all(ax.get_xscale() == "log" for ax in panel(fig, "("))
    fig = studyplots.maps(study({"dt": [0.001, 0.01, 0.1], "omega": [20.0, 30.0]}), {}, "caption")
    for ax in [ax for ax in fig.axes if ax.get_title()]:
        assert ax.get_xscale() == "log" and ax.get_yscale() == "linear"
        lo, hi = ax.get_xlim()
        assert lo == pytest.approx(0.001 / np.sqrt(10)) and hi == pytest.approx(0.1 * np.sqrt(10))


def test_more_than_two_axes_map_the_first_two_numeric_with_a_row_per_prototype():
    """A further categorical axis gets rows of its own (before: only its first category was drawn)."""
    ds = study({"prototype": ["DFP1", "DFP2"], "alpha21": [5.0, 10.0], "h2": [0.1, 0.15, 0.2]})
    fig = studyplots.maps(ds, {}, "caption")
    title = figure_title(fig)
    assert r"maps over $\alpha^{21}$ and $h^{2}$ per prototype" in title and "not drawn" not in title
    for proto in ("DFP1", "DFP2"):
        ax = next(ax for ax in fig.axes if ax.get_title() == f"Stick-Slip, {proto}:\nmax |θ²|")
        (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
        expected = ds["theta2_max_abs"].sel(model="stick_slip", prototype=proto).values.T
        assert np.allclose(mesh.get_array().reshape(expected.shape), expected)
    # a further numeric axis is still shown at its first value, and the title says so
    ds = study({"alpha21": [5.0, 10.0], "h2": [0.1, 0.15, 0.2], "theta2_0": [0.0, 1.0]})
    assert "(first of 2 values, the others not drawn)" in figure_title(studyplots.maps(ds, {}, "caption"))


def test_a_bidirectional_study_labels_the_rotation_as_the_tilt():
    ds = study({"alpha21": [5.0, 10.0], "h2": [0.1, 0.15]})
    ds.attrs["excitation_components"] = 2
    titles = [ax.get_title() for ax in studyplots.maps(ds, {}, "caption").axes]
    assert "Stick-Slip:\nmax tilt of the pad" in titles and not any("θ²" in t for t in titles)


def test_an_axis_of_one_value_is_a_note():
    ds = study({"alpha21": [5.0, 10.0, 15.0], "h2": [0.15]})
    fig = studyplots.maps(ds, {}, "caption")
    assert meshes(fig) == []
    assert "$h^{2}$ = 0.15 m" in figure_title(fig) and "first of" not in figure_title(fig)


@pytest.mark.parametrize("axes", [{"scale": [0.5, 1.0]}, {"scale": [0.5, 1.0], "friction": [0.02, 0.04]}],
                         ids=["curves", "maps"])
def test_a_suites_undrawn_component_axis_is_said_at_the_value_drawn(axes):
    """A suite of pairs swept over their components draws one of them, the first: the title says which."""
    title = figure_title(studyplots.maps(suite(3, **axes, component=["x", "y", "both"]), {}, "caption"))
    assert "component of $X_g$ = x (first of 3 values, the others not drawn)" in title


STRUCTURE_LABELS = ("max |stroke u| of the structure", "max |F/W| of the device")
SUMMARY_LABELS = ("max |θ²|", "max sticking rotation", "max rise of RB3", "max interpenetration (corners)",
                  *STRUCTURE_LABELS)


@pytest.mark.parametrize("records", [6, 12])
@pytest.mark.parametrize("axes", [{"scale": [0.5, 1.0, 2.0]}, {"scale": [0.5, 1.0, 2.0], "friction": [0.02, 0.04]}],
                         ids=["curves", "maps"])
def test_a_suites_panels_go_on_rows_of_a_figure_at_most_16_inches_wide(records, axes):
    """A suite's six summaries (the pad's and its structure's) were drawn in one row of panels, 24.6 inches of
    curves and 25.8 of maps (3690 pixels for six records), too wide to read: they go on rows, at most 16
    inches wide, every summary drawn."""
    fig = studyplots.maps(suite(records, **axes), {}, "caption")
    panels = [ax for ax in fig.axes if ax.get_visible() and ax.get_title()]
    assert fig.get_figwidth() <= 16.0
    assert all(any(label in ax.get_title() for ax in panels) for label in SUMMARY_LABELS)
    assert len(panels) == (6 if "friction" not in axes else 4 * 6 - 2)  # maps: no sticking rotation of compliant
    assert len({round(ax.get_position().y0, 3) for ax in panels}) > (1 if "friction" not in axes else 4)


GRIDS = ((studyplots.LINE_INCHES, 1, 0.0), (studyplots.MAP_INCHES, 4, studyplots.MAP_MARGIN))


@pytest.mark.parametrize("inches, rows, margin", GRIDS, ids=["lines", "maps"])
def test_any_number_of_panels_goes_on_as_few_blocks_as_keep_the_figure_at_most_16_inches_wide(inches, rows, margin):
    for n in range(1, 61):
        blocks, ncols = studyplots._grid_shape(n, inches[0], margin)
        assert (blocks - 1) * ncols < n <= blocks * ncols  # every panel has a place, the last block is not empty
        assert ncols * inches[0] + margin <= 16.0 or ncols == 1
        assert blocks == 1 or -(-n // (blocks - 1)) * inches[0] + margin > 16.0  # one block fewer: too wide
        assert blocks * ncols - n < blocks  # shared evenly: no block more than one panel short


@pytest.mark.parametrize("n", [1, 5, 7, 12])
def test_the_panels_of_a_grid_are_its_columns_of_axes_the_places_left_hidden(n):
    for inches, rows, margin in GRIDS:
        fig, columns = studyplots._grid(n, inches, rows, margin)
        assert len(columns) == n and all(len(column) == rows for column in columns)
        assert len([ax for ax in fig.axes if ax.get_visible()]) == n * rows
        assert fig.get_figwidth() <= 16.0
        blocks = len({ax.get_subplotspec().rowspan.start // rows for column in columns for ax in column})
        assert blocks == 1 or -(-n // (blocks - 1)) * inches[0] + margin > 16.0  # one block fewer: too wide


@pytest.mark.parametrize("records", [0, 6], ids=["one record", "a suite"])
def test_where_the_pad_failed_the_structures_summaries_are_drawn_not_hatched(records):
    """Where every record's run failed, the grey hatch hid the structure's stroke and F/W too, which do not
    depend on the pad and have a value: only the summaries without one are hatched."""
    xs, ys = [0.5, 1.0, 2.0], [0.02, 0.04]
    bad = np.zeros((3, 2), bool)
    bad[2, 1] = True
    if records:
        ds = suite(records, failed={"stick_slip": np.broadcast_to(bad, (records, 3, 2))}, scale=xs, friction=ys)
    else:
        ds = study({"scale": xs, "friction": ys}, failed={"stick_slip": bad}, structure=True)
    fig = studyplots.maps(ds, {}, "caption")
    maps = [ax for ax in fig.axes if ax.get_title().startswith("Stick-Slip")]
    assert len(maps) == 6 * (2 if records else 1)
    for ax in maps:
        (mesh,) = [c for c in ax.collections if isinstance(c, QuadMesh)]
        shown = ~np.ma.masked_invalid(mesh.get_array()).mask.reshape(len(ys), len(xs)).T
        structure = ax.get_title().split("\n")[-1] in STRUCTURE_LABELS
        assert hatched_cells(ax, "failed", xs, ys) == (set() if structure else {(2, 1)})
        assert shown[2, 1] == structure and shown.sum() == 5 + structure


# --- files -----------------------------------------------------------------------------------------------
KINDS = {
    "map": lambda: studyplots.maps(study({"alpha21": np.linspace(4, 14, 6), "h2": [0.1, 0.15, 0.2, 0.25]},
                                         capacity={"compliant": np.eye(6, 4, dtype=bool)},
                                         failed={"stick_slip": np.eye(6, 4, k=1, dtype=bool)}),
                                   {"DFP1": {"alpha21": 10.0, "h2": 0.15}}, "study synthetic: a map"),
    "lines": lambda: studyplots.maps(study({"dt": [0.001, 0.003, 0.01, 0.03]},
                                           capacity={"stick_slip": np.array([0, 0, 1, 1], bool)},
                                           failed={"compliant": np.array([0, 0, 0, 1], bool)}),
                                     {"chosen": {"dt": 0.003}}, "study synthetic: lines"),
    "categories": lambda: studyplots.maps(study({"prototype": ["DFP1", "DFP2", "Mine"]},
                                                failed={"stick_slip": np.array([0, 1, 0], bool)}),
                                          {}, "study synthetic: categories"),
    "histories": lambda: studyplots.histories(
        [("prototype = DFP1", pair()),
         ("prototype = DFP2", {"compliant": history("compliant", t_end=0.3, capacity_exceeded_at_s=0.3,
                                                    capacity_exceeded_plate="RB3", stopped_at_s=0.3),
                               "stick_slip": history("stick_slip", t_end=0.61, failed=1, failure_time_s=0.62,
                                                     failure_message="Newton-Raphson did not converge")})],
        "study synthetic: histories"),
}


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(KINDS))
def test_files_are_written_and_reproducible(kind, tmp_path):
    for k in range(2):
        save(KINDS[kind](), tmp_path / f"{kind}{k}.png", tmp_path / f"{kind}{k}.pdf")
    for ext in ("png", "pdf"):
        first, second = ((tmp_path / f"{kind}{k}.{ext}").read_bytes() for k in range(2))
        assert len(first) > 10_000 and first == second


# --- convergence in the step size ------------------------------------------------------------------
def test_fitted_order_recovers_a_power_law_on_the_smallest_steps():
    dt = np.array([0.02, 0.01, 0.005, 0.002, 0.001, 0.0005])
    values = 3.0 * dt**1.5 + np.where(dt > 0.006, 1.0, 0.0)  # a power law on the 4 smallest, spoilt above
    assert studyplots.fitted_order(dt, values) == pytest.approx(1.5, abs=1e-12)
    assert studyplots.fitted_order(dt, values, n=6) != pytest.approx(1.5, abs=0.05)
    assert np.isnan(studyplots.fitted_order(dt[:1], values[:1]))


def _history(theta2, rise, dt, failed=0):
    t = dt * np.arange(len(theta2))
    return xr.Dataset({"theta2": ("t", np.asarray(theta2, float)), "rise": ("t", np.asarray(rise, float))},
                      coords={"t": t}, attrs={"dt_s": dt, "failed": failed})


def test_convergence_table_measures_the_distance_between_the_models():
    summaries = xr.Dataset({"sticking_rotation_max": (("model", "prototype", "dt"), [[[np.nan] * 2] * 2,
                                                                                     [[2.0, 1.0], [4.0, 3.0]]])},
                           coords={"model": ["compliant", "stick_slip"], "prototype": ["DFP1", "DFP2"],
                                   "dt": [0.01, 0.005]})
    points = [({"prototype": "DFP2", "dt": 0.005},
               {"compliant": _history([0, 1, 2, 3], [0, 0.1, 0.2, 0.3], 0.005),
                "stick_slip": _history([0, 1.5, 1.0], [0, 0.1, 0.25], 0.005, failed=1)})]
    (row,) = studyplots.convergence_table(summaries, points)
    assert row == {"group": "prototype = DFP2", "dt": 0.005, "sticking_rotation_max": 3.0,
                   "theta2_difference_max": pytest.approx(1.0), "rise_difference_max": pytest.approx(0.05),
                   "failed": True}  # compared up to the failed run's last step
    fig = studyplots.convergence([row, {**row, "dt": 0.01, "failed": False}], "caption")
    assert all(ax.get_xscale() == "log" and ax.get_yscale() == "log" for ax in fig.axes)
    # two steps: the legend says the order is fitted on both, not on "the 4 smallest"
    assert all(ax.get_legend().get_title().get_text() == "order fitted on all 2 Δt" for ax in fig.axes)


def test_a_legend_group_too_long_for_the_figure_goes_on_more_lines():
    """A one-column histories figure clipped its six-entry legend line at both sides."""
    from matplotlib.lines import Line2D

    group = [Line2D([], [], label=label) for label in ("X_g,x", "X_g,y", "u_x, stroke", "u_y", "Compliant Sliding",
                                                       "Stick-Slip")]
    ring = Line2D([], [], label="pad reaches a retaining ring")
    assert studyplots._legend_rows([group, [ring]], 12.0) == [group + [ring]]  # all on one line where they fit
    rows = studyplots._legend_rows([group, [ring]], 5.0)
    assert [h for r in rows for h in r] == group + [ring] and len(rows) > 2

    def size(h):
        return 0.6 + 0.065 * len(h.get_label())

    # the table's columns are as wide as their widest entry: the table fits, not only each row
    columns = max(len(r) for r in rows)
    assert sum(max(size(r[c]) for r in rows if c < len(r)) for c in range(columns)) < 0.95 * 5.0


def test_a_suite_of_eleven_records_gets_eleven_markers():
    """Design codes average 7 to 11 records; a map tells each record by its marker (six markers made the
    seventh record the first's)."""
    from dccss.studies.plots import GROUP_MARKERS

    assert len(set(GROUP_MARKERS[:11])) == 11


def test_a_ring_that_capacity_error_marks_is_no_solver_failure_on_the_study_figures():
    """A history and a sweep case that ``capacity: error`` ended at the ring are drawn as reaching the ring,
    not as solver failures (before: "solver failed (history ends)" and ✕ marks, and no ring box at all)."""
    from dccss.excitation import Sine
    from dccss.paper.prototypes import DFP1
    from dccss.simulation import simulate
    from dccss.studies.plots import _case_flags, _events

    ds = simulate(DFP1, Sine(0.9, 10.0, 0.6), model="compliant", dt=0.01, capacity="error", on_failure="mark")
    assert ds.attrs["failure_kind"] == "capacity" and [kind for kind, _, _ in _events(ds)] == ["capacity"]
    cases = xr.Dataset({"capacity_exceeded": ("case", [1, 1, 0]), "failed": ("case", [1, 1, 1]),
                        "capacity_time": ("case", [0.05, 0.05, np.nan]), "failure_time": ("case", [0.05, 0.3, 0.2])})
    capacity, failed = _case_flags(cases)
    assert list(capacity) == [True, True, False] and list(failed) == [False, True, True]


def test_a_legend_table_of_ten_records_fits_its_figure():
    """The legend is a table whose columns are as wide as their widest entry: rows are cut so that the
    table fits (before, each row was checked alone, and a ten-record suite's legend ran off both edges)."""
    from matplotlib.lines import Line2D

    from dccss.studies.plots import _legend_rows

    def size(h):  # the estimate _legend_rows makes (inches)
        return 0.6 + 0.065 * len(h.get_label())

    groups = [[Line2D([], [], label=m) for m in ("Compliant Sliding", "Stick-Slip")],
              [Line2D([], [], label=f"record = RSN1{i:02d}_SUITE") for i in range(10)],
              [Line2D([], [], label=s) for s in ("mean over the records", "84th percentile over the records")],
              [Line2D([], [], label="pad reaches a retaining ring (Compliant Sliding 5, Stick-Slip 5 of 20)"),
               Line2D([], [], label="solver failed, no result (Compliant Sliding 0, Stick-Slip 2 of 20)")]]
    rows = _legend_rows(groups, 16.4)
    columns = max(len(row) for row in rows)
    assert sum(max(size(row[c]) for row in rows if c < len(row)) for c in range(columns)) < 0.95 * 16.4
    assert [h for row in rows for h in row] == [h for group in groups for h in group]  # all, in order


def test_long_record_names_are_shortened_on_the_ticks_and_still_told_apart():
    """Record names of 70 characters broke the maps' layout (the axes collapsed): the ticks keep their
    start and end around "…", with as many characters as tell them apart."""
    from dccss.studies.plots import _shortened

    names = ["RSN1234_IMPERIAL_VALLEY_06_EL_CENTRO_ARRAY_NUMBER_7_COMPONENT_140_FILTERED",
             "RSN1234_IMPERIAL_VALLEY_06_EL_CENTRO_ARRAY_NUMBER_7_COMPONENT_230_FILTERED", "RSN6_ELC"]
    short = _shortened(names)
    assert short[2] == "RSN6_ELC" and len(set(short)) == 3 and all(len(s) < 50 for s in short)
    assert all(s.startswith(n[:10]) and "…" in s for s, n in zip(short[:2], names))
