"""Paper figures from small real datasets: panels, labels with units, captions, reproducible files.

The figures and their panels are those of ``config/config.yaml`` (the paper study)."""

import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from dccss.case import geometry_from
from dccss.drawing import save
from dccss.excitation import Sine
from dccss.paper.figures import DRAW, KINDS, Panel, figure_spec, figure_specs, render, title_text
from dccss.simulation import breakaway, simulate

CONFIG = yaml.safe_load((Path(__file__).resolve().parents[1] / "config/config.yaml").read_text())
SPECS = figure_specs(CONFIG["figures"])
PROTOTYPES = {name: geometry_from(params) for name, params in CONFIG["prototypes"].items()}
CAPTION = "case set: test (X_g,max = 27 cm, θ²(t₀) = 0)"
UNIT = re.compile(r"\((µm|mm|cm|cm/s|m|°|s)\)$")
# panel letters, number of axes (twins included), number of insets (None: depends on the data)
EXPECTED = {"fig07": ("abcd", 8, 0), "fig08": ("ab", 2, 8), "fig09": ("abcd", 8, 0), "fig10": ("ab", 4, None),
            "fig11": ("abcd", 6, 0), "fig12": ("abcd", 6, 0), "fig17": ("abcd", 4, 0), "fig18": ("abcde", 6, 0),
            "fig19": ("abcde", 6, 0), "fig20": ("ab", 2, 0)}
REQUIRED_UNITS = {"fig07": ["(°)", "(m)"], "fig08": ["(cm)"], "fig10": ["(µm)"], "fig11": ["(cm)", "(cm/s)", "(°)"],
                  "fig12": ["(cm)", "(cm/s)", "(°)"], "fig18": ["(°)", "(cm)", "(cm/s)"],
                  "fig19": ["(°)", "(cm)", "(cm/s)"], "fig20": ["(cm)"]}


@pytest.fixture(scope="module")
def datasets(tmp_path_factory):
    """{(prototype, model, dt) or prototype: dataset} for every panel of the paper's figures, from
    short runs, read back from netCDF like the workflow does (a sweep holds every ground step)."""
    folder = tmp_path_factory.mktemp("data")
    panels = [(spec.data, panel) for spec in SPECS.values() for panel in spec.panels]
    steps = {}
    for data, p in panels:
        if data == "breakaway":
            steps.setdefault(p.prototype, set()).add(p.dXg)
    theta = np.radians([-10.0, -8.8, -6.0, -3.0, 0.0])
    out = {}
    for data, p in panels:
        key = (p.prototype, p.model, p.dt) if data == "cases" else p.prototype
        if key in out:
            continue
        if data == "cases":
            ds = simulate(PROTOTYPES[p.prototype], Sine(0.27, 30.0, 0.2), model=p.model, dt=p.dt)
        else:
            ds = breakaway(PROTOTYPES[p.prototype], theta, sorted(steps[p.prototype]))
        path = folder / f"{'_'.join(map(str, np.atleast_1d(key)))}.nc"
        ds.to_netcdf(path)
        out[key] = xr.load_dataset(path)
    return out


def panel_datasets(spec, datasets):
    """One dataset per panel of ``spec``, in order."""
    if spec.data == "breakaway":
        return [datasets[p.prototype] for p in spec.panels]
    return [datasets[(p.prototype, p.model, p.dt)] for p in spec.panels]


def letters(fig):
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    return "".join(sorted(m[1] for t in titles if (m := re.match(r"\((\w)\) ", t))))


def test_registry():
    assert sorted(SPECS) == sorted(EXPECTED)
    assert sorted(DRAW) == sorted(KINDS)  # every kind a spec may name is drawn, and nothing else
    for name, kind in KINDS.items():
        assert kind.data in ("breakaway", "cases") and 1 <= kind.panels[0] <= kind.panels[1]
        assert DRAW[name].__doc__
    for spec in SPECS.values():
        assert spec.kind in KINDS and spec.title and "\n" not in spec.title
        assert KINDS[spec.kind].panels[0] <= len(spec.panels) <= KINDS[spec.kind].panels[1]


def test_render_needs_one_dataset_per_panel():
    with pytest.raises(ValueError, match=r"fig11 draws 1 panel\(s\), got 0 dataset"):
        render(SPECS["fig11"], [], CAPTION)


@pytest.mark.slow
@pytest.mark.parametrize("fig_id", sorted(EXPECTED))
def test_figure(fig_id, datasets, tmp_path):
    fig = render(SPECS[fig_id], panel_datasets(SPECS[fig_id], datasets), CAPTION)
    expected_letters, n_axes, n_insets = EXPECTED[fig_id]
    assert letters(fig) == expected_letters
    assert len(fig.axes) == n_axes
    assert n_insets is None or sum(len(ax.child_axes) for ax in fig.axes) == n_insets
    labels = [label for ax in fig.axes for label in (ax.get_xlabel(), ax.get_ylabel()) if label]
    assert labels and all(UNIT.search(label) for label in labels), labels
    for unit in REQUIRED_UNITS.get(fig_id, ["(s)"]):
        assert any(label.endswith(unit) for label in labels), (unit, labels)
    assert fig._suptitle.get_text() == f"Figure {int(fig_id[3:])}. {title_text(SPECS[fig_id].title)}"
    assert title_text(CAPTION) in [text.get_text() for text in fig.texts]
    assert 11 <= fig.get_figwidth() <= 14

    first, second = tmp_path / "first", tmp_path / "second"
    save(fig, first / f"{fig_id}.png", first / f"{fig_id}.pdf")
    save(fig, second / f"{fig_id}.png", second / f"{fig_id}.pdf")
    for suffix in (".png", ".pdf"):
        data = (first / f"{fig_id}{suffix}").read_bytes()
        assert data.startswith(b"\x89PNG" if suffix == ".png" else b"%PDF")
        assert data == (second / f"{fig_id}{suffix}").read_bytes()
    assert sorted(p.name for p in first.iterdir()) == [f"{fig_id}.pdf", f"{fig_id}.png"]  # no temporary left


# (figure whose panels are reused, panel indices, letters, axes: a grid cell without a panel is removed)
OTHER_LAYOUTS = [
    ("fig07", (0, 1, 2), "abc", 6),  # 2 x 2 grid filled by columns, the last cell empty
    ("fig17", (0, 1, 2), "abc", 3),  # 2 x 2 grid filled by rows, the last cell empty
    ("fig09", (3,), "a", 2),  # one column
    ("fig10", (0, 1, 0), "abc", 6),  # three columns
    ("fig20", (1,), "a", 1),
]


@pytest.mark.parametrize("fig_id, picks, expected_letters, n_axes", OTHER_LAYOUTS,
                         ids=[f"{r[0]}-{len(r[1])}" for r in OTHER_LAYOUTS])
def test_other_panel_counts(datasets, fig_id, picks, expected_letters, n_axes):
    """A kind lays out any number of panels within its bounds; the lowest panel of a column has the time axis."""
    spec = SPECS[fig_id]
    spec = replace(spec, id="fig99", panels=tuple(spec.panels[i] for i in picks))
    fig = render(spec, panel_datasets(spec, datasets), CAPTION)
    assert letters(fig) == expected_letters and len(fig.axes) == n_axes
    assert fig._suptitle.get_text().startswith("Figure 99. ")
    if spec.kind == "interpenetration":
        lowest = [ax for ax in fig.axes if ax.get_xlabel() == "t (s)"]
        assert len(lowest) == 2 and all(ax.xaxis.get_tick_params()["labelbottom"] for ax in lowest)


def test_a_panel_naming_its_variant_says_so(datasets):
    """A panel with its own case set or normals keeps it in every version of the figure: its title names it."""
    entry = {"kind": "sticking", "title": "one line",
             "panels": [{"prototype": "DFP1", "model": "stick_slip", "dt": 0.01, "t": 0.1, "case_set": "as_printed"}]}
    spec = figure_spec("fig18", entry)
    assert spec.panels[0] == Panel("DFP1", "stick_slip", 0.01, t=0.1, variant="as_printed")
    fig = render(spec, [datasets[("DFP1", "stick_slip", 0.01)]], CAPTION)
    assert fig.axes[0].get_title(loc="left") == "(a) pad rotation, DFP1, Δt = 0.01 s, as_printed"


def test_rendering_is_reproducible(datasets, tmp_path):
    """Two independent renders give the same bytes (no timestamps, no state carried over)."""
    for name in ("a", "b"):
        save(render(SPECS["fig20"], panel_datasets(SPECS["fig20"], datasets), CAPTION),
             tmp_path / f"{name}.png", tmp_path / f"{name}.pdf")
    for suffix in (".png", ".pdf"):
        assert (tmp_path / f"a{suffix}").read_bytes() == (tmp_path / f"b{suffix}").read_bytes()


def test_figure_specs_parse_without_matplotlib():
    """The workflow checks its figures: section when it builds the DAG; that must not import matplotlib
    (it would cost every snakemake start, dry runs included, about 0.4 s)."""
    import subprocess
    import sys

    code = ("import sys; import dccss.case, dccss.paper.specs, dccss.paper.validation; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_save_lays_the_figure_out_once_and_saving_it_again_writes_the_same_bytes(tmp_path):
    """A figure is laid out when saved (``save`` freezes it), not when drawn up: a figure frozen already
    (saved once) is written with the same bytes."""
    from dccss.drawing import new_figure

    fig, axs = new_figure((4.0, 3.0), 1, 2)
    axs[0, 0].plot([0.0, 1.0], [0.0, 1.234567890123])
    axs[0, 1].set_ylabel("a long label " * 3)
    assert fig.get_layout_engine() is not None
    save(fig, tmp_path / "a.png", tmp_path / "a.pdf")
    assert fig.get_layout_engine() is None
    save(fig, tmp_path / "b.png", tmp_path / "b.pdf")
    for ext in ("png", "pdf"):
        assert (tmp_path / f"a.{ext}").read_bytes() == (tmp_path / f"b.{ext}").read_bytes()
