"""A model is a registry entry: one registered alone, kernels and all, runs through ``simulate``, a
sweep and the study plots, interpreted and compiled, with its title and style from the entry, and
nothing else to edit."""

import dataclasses

import numpy as np
import pytest

from dccss.case import CaseError, case_from
from dccss.excitation import Sine
from dccss.mechanics import backend, compiled, models, registry, scalar, spatial, summaries
from dccss.mechanics.registry import Model, PlanarKernels
from dccss.paper.prototypes import DFP1
from dccss.simulation import simulate
from dccss.studies import plots


@scalar.jit
def rigid_case(k, xg, q0, constants, flags, history_out, summary_out, status_out):
    """A rigid pad as a planar kernel (``registry.PlanarKernels``): RB1, the pad and RB3 carried by X_g
    from the compatible start at theta^2 = 0, no solve."""
    pad, centre, radius, dims = constants
    fail, fail_g, fail_J, done = status_out
    hq, hits, hres = history_out
    now, acc_all, count_all, capacity = summary_out
    record = hq.shape[0] > 0
    acc, count, summarise = compiled.case_summaries(k, acc_all, count_all)
    for n in range(len(xg)):
        q = (xg[n], q0[1], q0[2], xg[n] + (q0[3] - q0[0]), q0[4], q0[5], xg[n] + (q0[6] - q0[0]), q0[7], q0[8])
        if record:
            for i in range(9):
                hq[n, k, i] = q[i]
            hits[n, k], hres[n, k] = 0, 0.0
        if summarise:
            u = compiled.plate_positions(compiled.frames(q), pad)
            acc, count = compiled.summarise_step(acc, count, n, now[n], q, u, compiled.distances(u, centre), radius,
                                                 dims, 0, capacity)
        done[k] = n + 1
    compiled.keep_summaries(k, acc_all, count_all, acc, count)


def rigid_batch(Xg, q0, pad, centre, radius, dims, flags, history_out, summary_out, status_out):
    for k in scalar.prange(q0.shape[0]):
        xg = Xg[:, k] if Xg.shape[1] > 1 else Xg[:, 0]
        rigid_case(k, xg, q0[k], compiled.case_constants(k, pad, centre, radius, dims), flags, history_out,
                   summary_out, status_out)


RIGID = Model("rigid", "Rigid Pad",
              PlanarKernels(rigid_case, rigid_batch,
                            {"q": ((9,), float), "newton_iterations": ((), np.int64), "residual": ((), float)}, {},
                            None),
              lambda history, geometry: {}, line=dict(color="tab:green", ls="-.", lw=1.5), marker=dict(marker="x"))


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
    assert plots.model_line("rigid", ["compliant", "rigid"]) == RIGID.line
    assert plots.ordered_models(["rigid", "stick_slip", "compliant"]) == ["compliant", "stick_slip", "rigid"]


def test_unregistered_models_are_refused_with_the_registered_ones():
    with pytest.raises(ValueError, match=r"model must be one of \('compliant', 'stick_slip'\), got 'rigid'"):
        simulate(DFP1, Sine(0.1, 6.0, 0.5), model="rigid", dt=0.01)


def _on(monkeypatch, name, call):
    monkeypatch.setenv(backend.ENV, name)
    out = call()
    assert backend.last == name
    return out


@pytest.mark.slow
def test_a_registered_model_runs_compiled_as_interpreted(rigid, monkeypatch):
    """Its batch kernel compiles (the slow part: a cold cache compiles it) and gives the same bytes."""
    run = lambda: simulate(DFP1, Sine(0.1, 6.0, 0.5), model="rigid", dt=0.01)  # noqa: E731
    assert _on(monkeypatch, "numba", run).identical(_on(monkeypatch, "python", run))
    Xg = np.stack([np.linspace(0.0, a, 11) for a in (0.05, 0.1, 0.25)], axis=-1)
    sweep = lambda: summaries.summarize("rigid", DFP1, Xg, capacity="continue")  # noqa: E731
    ours, interpreted = _on(monkeypatch, "numba", sweep), _on(monkeypatch, "python", sweep)
    assert ours.keys() == interpreted.keys()
    assert all(np.array_equal(ours[k], interpreted[k], equal_nan=True) for k in ours)


def test_a_name_is_registered_once_and_lookups_name_the_allowed_models(rigid):
    with pytest.raises(ValueError, match="a model named 'rigid' is registered already"):
        registry.register(RIGID)
    assert registry.names() == ("compliant", "stick_slip", "rigid")
    with pytest.raises(ValueError, match=r"model must be one of \('compliant', 'stick_slip'\) in space, got 'rigid'"):
        registry.model("rigid", spatial.in_space, " in space")


def test_case_files_and_summaries_know_a_model_registered_after_import(rigid, monkeypatch):
    """The names and summaries of the registry are read when used, not when the package is imported."""
    mapping = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.1, "omega": 6.0, "duration": 0.5},
               "dt": 0.01, "model": "rigid"}
    assert case_from(mapping).model == "rigid"
    own = dataclasses.replace(RIGID, summaries={"carried_max": ("m", "largest carried displacement")})
    monkeypatch.setitem(models.REGISTRY, "rigid", own)
    assert summaries.specs()["carried_max"] == ("m", "largest carried displacement")
    assert "carried_max" in summaries.model_specific() and "theta2_max_abs" not in summaries.model_specific()
    monkeypatch.delitem(models.REGISTRY, "rigid")
    with pytest.raises(CaseError, match="model"):
        case_from(mapping)
