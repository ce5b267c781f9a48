"""A model is a registry entry: one registered alone runs through ``simulate``, a sweep and the
study plots, with its title and style from the entry, and nothing else to edit."""

import numpy as np
import pytest

from dccss.excitation import Sine
from dccss.mechanics import models, summaries
from dccss.mechanics.models import Model, Step
from dccss.paper.prototypes import DFP1
from dccss.simulation import simulate
from dccss.studies import plots


def rigid_steps(geometry, Xg, theta2_0=0.0, *, normals="signed", options=None, times=None):
    """The pad held at theta^2 = 0, carried with RB1: no solve."""
    Xg = np.asarray(Xg, dtype=float)
    for n in range(len(Xg)):
        yield Step(n, geometry.compatible(0.0, Xg[n]), 0, 0.0)


RIGID = Model("rigid", "Rigid Pad", rigid_steps, Step, lambda history, geometry: {}, {}, {}, None,
              ("newton_iterations",), line=dict(color="tab:green", ls="-.", lw=1.5), marker=dict(marker="x"))


@pytest.fixture
def rigid(monkeypatch):
    monkeypatch.setitem(models.REGISTRY, "rigid", RIGID)
    return RIGID


def test_a_registered_model_runs_through_simulate(rigid):
    ds = simulate(DFP1, Sine(0.1, 6.0, 0.5), model="rigid", dt=0.01)
    assert ds.attrs["model"] == "rigid" and "Rigid Pad" in ds.attrs["title"]
    assert np.array_equal(ds["theta2"].values, np.zeros(51))
    assert np.allclose(ds["Rx2"].values, ds["Xg"].values, atol=1e-15)  # the pad moves with RB1
    assert np.max(np.abs(ds["rise"].values)) < 1e-15
    assert "theta2_stick" not in ds  # no sticking phase


def test_a_registered_model_runs_through_a_sweep_and_the_plots(rigid):
    Xg = np.stack([np.linspace(0.0, a, 11) for a in (0.05, 0.1, 0.25)], axis=-1)
    out = summaries.summarize("rigid", DFP1, Xg, capacity="continue")
    assert np.array_equal(out["theta2_max_abs"], np.zeros(3))
    # RB3 moves with RB1: the pad stays centred on both plates, at the clearance of the rest position
    rest = min(DFP1.ring_inner_x[0] - DFP1.A1, DFP1.ring_inner_x[1] - DFP1.A3)
    assert np.allclose(out["clearance_min"], rest, rtol=0, atol=1e-15) and not out["capacity_exceeded"].any()
    assert "sticking_rotation_max" not in out
    assert plots._line("rigid", ["compliant", "rigid"]) == RIGID.line
    assert plots._ordered(["rigid", "stick_slip", "compliant"]) == ["compliant", "stick_slip", "rigid"]


def test_unregistered_models_are_refused_with_the_registered_ones():
    with pytest.raises(ValueError, match=r"model must be one of \('compliant', 'stick_slip'\), got 'rigid'"):
        simulate(DFP1, Sine(0.1, 6.0, 0.5), model="rigid", dt=0.01)
