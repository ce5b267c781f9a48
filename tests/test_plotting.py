"""Paper figures from small real datasets: panels, labels with units, captions, reproducible files."""

import re

import numpy as np
import pytest
import xarray as xr

from dccss.excitation import Sine
from dccss.plotting import FIGURES, render, save
from dccss.prototypes import DFP1, DFP2
from dccss.simulation import breakaway, simulate

PROTOTYPES = {"DFP1": DFP1, "DFP2": DFP2}
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
    """Every dataset the figures need, from short runs, read back from netCDF like the workflow does."""
    folder = tmp_path_factory.mktemp("data")
    keys = {key for spec in FIGURES.values() for key in spec.keys}
    theta = np.radians([-10.0, -8.8, -6.0, -3.0, 0.0])
    out = {}
    for key in sorted(keys, key=str):
        if len(key) == 3:
            proto, model, dt = key
            ds = simulate(PROTOTYPES[proto], Sine(0.27, 30.0, 0.2), model=model, dt=dt)
        else:
            proto, dXg = key
            ds = breakaway(PROTOTYPES[proto], theta, dXg)
        path = folder / f"{'_'.join(map(str, key))}.nc"
        ds.to_netcdf(path)
        out[key] = xr.load_dataset(path)
    return out


def test_registry():
    assert sorted(FIGURES) == sorted(EXPECTED)
    for spec in FIGURES.values():
        assert spec.kind in ("breakaway", "cases")
        assert all(len(key) == (2 if spec.kind == "breakaway" else 3) for key in spec.keys)
        assert spec.title and "\n" not in spec.title


def test_render_names_missing_datasets():
    with pytest.raises(KeyError, match="fig11 needs"):
        render("fig11", {}, CAPTION)


@pytest.mark.parametrize("fig_id", sorted(EXPECTED))
def test_figure(fig_id, datasets, tmp_path):
    fig = render(fig_id, datasets, CAPTION)
    letters, n_axes, n_insets = EXPECTED[fig_id]
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert sorted(m[1] for t in titles if (m := re.match(r"\((\w)\) ", t))) == list(letters)
    assert len(fig.axes) == n_axes
    assert n_insets is None or sum(len(ax.child_axes) for ax in fig.axes) == n_insets
    labels = [label for ax in fig.axes for label in (ax.get_xlabel(), ax.get_ylabel()) if label]
    assert labels and all(UNIT.search(label) for label in labels), labels
    for unit in REQUIRED_UNITS.get(fig_id, ["(s)"]):
        assert any(label.endswith(unit) for label in labels), (unit, labels)
    assert fig._suptitle.get_text().startswith(f"Figure {int(fig_id[3:])}. ")
    assert CAPTION in [text.get_text() for text in fig.texts]
    assert 11 <= fig.get_figwidth() <= 14

    first, second = tmp_path / "first", tmp_path / "second"
    save(fig, first / f"{fig_id}.png", first / f"{fig_id}.pdf")
    save(fig, second / f"{fig_id}.png", second / f"{fig_id}.pdf")
    for suffix in (".png", ".pdf"):
        data = (first / f"{fig_id}{suffix}").read_bytes()
        assert data.startswith(b"\x89PNG" if suffix == ".png" else b"%PDF")
        assert data == (second / f"{fig_id}{suffix}").read_bytes()
    assert sorted(p.name for p in first.iterdir()) == [f"{fig_id}.pdf", f"{fig_id}.png"]  # no temporary left


def test_rendering_is_reproducible(datasets, tmp_path):
    """Two independent renders give the same bytes (no timestamps, no state carried over)."""
    for name in ("a", "b"):
        save(render("fig20", datasets, CAPTION), tmp_path / f"{name}.png", tmp_path / f"{name}.pdf")
    for suffix in (".png", ".pdf"):
        assert (tmp_path / f"a{suffix}").read_bytes() == (tmp_path / f"b{suffix}").read_bytes()
