"""Batched summaries: the capacity policies per case, equal to one-case histories."""

import numpy as np
import pytest

from dccss.excitation import Sine, step_times
from dccss.mechanics.capacity import CapacityError
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import NewtonOptions
from dccss.mechanics.summaries import summarize
from dccss.paper.prototypes import TABLE1
from dccss.simulation import simulate

#: DFP1, and DFP1 with plate 3 steeper (RB3's ring at 15.6 cm reached first)
DEVICES = [TABLE1["DFP1"], {**TABLE1["DFP1"], "alpha3": 19.0}]
BATCH = Geometry.from_degrees(**{k: np.array([d[k] for d in DEVICES]) for k in DEVICES[0]})
ONE = [Geometry.from_degrees(**d) for d in DEVICES]
MARK = NewtonOptions(on_failure="mark")


def run(model, excitation, dt=0.01, **kw):
    t = step_times(excitation, dt)
    return summarize(model, BATCH, excitation.displacement(t)[:, None], times=t, **kw)


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_capacity_stop_summarises_the_history_up_to_the_ring(model):
    excitation = Sine(0.40, 10.0, 1.0)
    out = run(model, excitation, capacity="stop")
    for i, geometry in enumerate(ONE):
        ds = simulate(geometry, excitation, model=model, dt=0.01, capacity="stop")
        assert bool(out["capacity_exceeded"][i]) and not out["failed"][i]
        assert out["capacity_time"][i] == pytest.approx(ds.attrs["capacity_exceeded_at_s"], abs=1e-12)
        theta2 = ds["theta2"].values
        assert out["theta2_max_abs"][i] == pytest.approx(np.abs(theta2).max(), abs=1e-10)
        assert out["theta2_end"][i] == pytest.approx(theta2[-1], abs=1e-10)
        assert out["rise_end"][i] == pytest.approx(float(ds["rise"][-1]), abs=1e-12)
        assert out["clearance_min"][i] == pytest.approx(-ds.attrs["capacity_exceeded_by_m"], abs=1e-12)
        if model == "stick_slip":
            turn = np.abs(ds["theta2_stick"].values[1:] - theta2[:-1]).max()
            assert out["sticking_rotation_max"][i] == pytest.approx(turn, abs=1e-10)


def test_capacity_stop_ignores_a_failure_after_the_ring():
    """Under this motion sticking fails at 0.15 s for DFP1, 0.11 s after it passed the ring."""
    excitation = Sine(0.9, 10.0, 1.0)
    going_on = run("stick_slip", excitation, options=MARK)
    assert going_on["failed"].tolist()[0] and going_on["failure_time"][0] == pytest.approx(0.15)
    stopped = run("stick_slip", excitation, options=MARK, capacity="stop")
    assert not stopped["failed"].any() and np.isfinite(stopped["theta2_end"]).all()
    assert stopped["capacity_time"][0] == pytest.approx(0.04)


def test_capacity_error_marks_the_case_failed_at_the_ring():
    out = run("compliant", Sine(0.40, 10.0, 1.0), options=MARK, capacity="error")
    assert out["failed"].all() and np.isnan(out["theta2_max_abs"]).all()
    assert np.array_equal(out["failure_time"], out["capacity_time"]) and out["capacity_exceeded"].all()
    assert out["capacity_time"][1] < out["capacity_time"][0]  # RB3's ring, nearer, first


def test_capacity_error_without_marking_names_the_case():
    with pytest.raises(CapacityError, match=r"batch index \(1,\)") as err:
        run("compliant", Sine(0.40, 10.0, 1.0), capacity="error")
    assert err.value.index == (1,)


def test_progress_is_reported_once_at_the_end():
    calls = []
    run("compliant", Sine(0.27, 30.0, 0.05), progress=lambda n, total: calls.append((n, total)))
    assert calls == [(5, 5)]


def test_unknown_capacity_policy_is_refused():
    with pytest.raises(ValueError, match="capacity must be one of"):
        run("compliant", Sine(0.27, 30.0, 0.05), capacity="ignore")


def test_a_spatial_sweep_reports_progress_once_at_the_end():
    """The spatial models run case after case: progress (steps) is reported once, when all are done
    (before, after each case, so a log said "100 %" while most cases were still to run)."""
    from dccss.mechanics import runs

    t = np.arange(6) * 0.01
    Xg = np.stack([np.stack([0.01 * np.sin(3 * t), 0.005 * np.sin(2 * t)], axis=-1)] * 3, axis=1)  # (T, 3, 2)
    calls = []
    runs.summaries("compliant", Geometry.from_degrees(**TABLE1["DFP1"]), Xg, times=t,
                   progress=lambda n, total: calls.append((n, total)))
    assert calls == [(5, 5)]
