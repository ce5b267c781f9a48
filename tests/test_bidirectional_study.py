"""Studies with bidirectional input: azimuth and component sweep axes, record pairs, the shipped example."""


import numpy as np
import pytest
import xarray as xr
from conftest import ROOT, changed

from dccss.case import CaseError
from dccss.mechanics import runs
from dccss.studies import Study, combine, history_case, run_chunk

PAIR = {"kind": "record", "file": ["synthetic.AT2", "synthetic_y.AT2"], "window": [0.0, 3.0], "baseline": "linear"}
AZIMUTHS = {
    "study": {"name": "turn"},
    "prototype": "DFP2",
    "excitation": {"kind": "sine", "amplitude": 0.15, "omega": 6.0, "duration": 0.5},
    "dt": 0.01,
    "models": ["compliant", "stick_slip"],
    "sweep": {"azimuth": [0.0, 30.0, 137.0, 240.0], "amplitude": [0.1, 0.15]},
    "histories": [{"azimuth": 137.0, "amplitude": 0.15}],
}
RECORDS = ROOT / "config/studies/records"


def _combined(study):
    return combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})


def test_an_azimuth_sweep_gives_the_planar_summaries_at_every_azimuth():
    study = Study.from_config(AZIMUTHS)
    assert study.excitation.components == 2
    turned = _combined(study)
    planar = _combined(Study.from_config(changed(AZIMUTHS, sweep={"amplitude": [0.1, 0.15]}, histories=[])))
    assert turned["azimuth"].attrs["units"] == "degree"
    for name in ("theta2_max_abs", "rise_max", "rise_end", "clearance_min", "sticking_rotation_max",
                 "rise_stick_max"):
        expected = planar[name].values[:, None, :]
        assert np.nanmax(np.abs(turned[name].values - expected)) < 1e-9, name
    # under bidirectional input the residual rotation is the (unsigned) residual tilt
    assert np.nanmax(np.abs(turned["theta2_end"].values - np.abs(planar["theta2_end"].values)[:, None, :])) < 1e-9
    case = history_case(study, 0, "stick_slip")
    assert case.excitation.azimuth_deg == 137.0 and case.excitation.components == 2


def test_a_component_sweep_over_a_record_pair(tmp_path):
    for name in ("synthetic.AT2", "synthetic_y.AT2"):
        (tmp_path / name).write_bytes((RECORDS / name).read_bytes())
    config = {"study": {"name": "pair"}, "prototype": "DFP1", "excitation": PAIR, "dt": 0.01,
              "models": ["stick_slip"], "sweep": {"component": ["x", "y", "both"]},
              "histories": [{"component": "y"}]}
    study = Study.from_config(config, tmp_path)
    ds = _combined(study)
    assert list(ds["component"].values) == ["x", "y", "both"]
    t = study.grid.times(0.01)
    ground = study.grid.ground_motion(np.arange(3), t)
    assert ground.shape == (len(t), 3, 2)
    assert not ground[:, 0, 1].any() and not ground[:, 1, 0].any()
    assert np.array_equal(ground[:, 2], study.excitation.displacement(t))
    assert np.allclose(study.grid.azimuth_of(np.arange(3)), [0.0, np.pi / 2, 0.0])
    # the y component alone is the planar model along 90 degrees
    history = history_case(study, 0, "stick_slip").run()
    assert history.attrs["excitation_component"] == "y"
    assert float(ds.sel(model="stick_slip", component="y")["theta2_max_abs"]) == pytest.approx(
        float(history["tilt"].max()), abs=1e-12)
    x = study.grid.ground_motion(np.array([0]), t)[:, 0, 0]
    from dccss.mechanics import models

    planar = models.run("stick_slip", study.grid.geometry(np.array([0])), x[:, None])
    assert float(ds.sel(model="stick_slip", component="x")["theta2_max_abs"]) == pytest.approx(
        np.degrees(np.abs(planar["q"][:, 0, 5]).max()), abs=1e-9)


@pytest.mark.parametrize("changes, message", [
    (dict(sweep={"component": ["x", "y"]}), "sweep.component: selects the components of a two-component"),
    (dict(sweep={"azimuth": [0.0, 10.0]}, excitation=PAIR), "sweep.azimuth: orients a one-component excitation"),
    (dict(sweep={"component": ["x", "z"]}, excitation=PAIR), r"sweep.component\[1\]: must be one of"),
    (dict(sweep={"azimuth": [0.0, "north"]}), r"sweep.azimuth\[1\]"),
    (dict(normals="unsigned"), "normals: bidirectional ground motion runs the spatial models"),
    (dict(sweep={"component": ["x"]}, excitation={**PAIR, "component": "x"}), "sweep.component: selects"),
])
def test_bad_bidirectional_studies_are_refused(changes, message, tmp_path):
    for name in ("synthetic.AT2", "synthetic_y.AT2"):
        (tmp_path / name).write_bytes((RECORDS / name).read_bytes())
    with pytest.raises(CaseError, match=message):
        Study.from_config(changed(AZIMUTHS, **changes), tmp_path)


def test_the_shipped_bidirectional_study(shipped_study):
    work = shipped_study("bidirectional")
    ds = xr.open_dataset(work / "results/studies/bidirectional/bidirectional.nc")
    assert dict(ds.sizes) == {"model": 2, "scale": 4, "component": 3}
    for name in ("maps.png", "histories.png", "animations/stick_slip_2.gif"):
        fresh = (work / "figures/studies/bidirectional" / name).read_bytes()
        assert fresh == (ROOT / "figures/studies/bidirectional" / name).read_bytes(), name
    # its x component at scale 1 is the planar ground-motion study's DFP1 at scale 1 (same record,
    # window, baseline and dt)
    planar = xr.open_dataset(shipped_study("ground_motion") / "results/studies/ground_motion/ground_motion.nc")
    for model in ("compliant", "stick_slip"):
        mine = ds.sel(model=model, component="x", scale=1.0)
        theirs = planar.sel(model=model, prototype="DFP1", scale=1.0)
        for name in ("theta2_max_abs", "rise_max", "rise_end"):
            assert abs(float(mine[name]) - float(theirs[name])) < 1e-9, (model, name)
    history = xr.open_dataset(work / "results/studies/bidirectional/histories/stick_slip_2.nc")
    assert history.attrs["motion"] == "bidirectional" and history.attrs["excitation_component"] == "both"


def _ring_batch():
    """Two cases along 45 deg: one within the capacity, one past the rings of RB1 and RB3."""
    from dccss.mechanics.geometry import Geometry
    from dccss.paper.prototypes import DFP1

    t = np.arange(101) * 0.01
    x = np.sin(2 * np.pi * t)[:, None] * np.array([0.1, 2.3 * float(DFP1.capacity1)])
    X = np.stack([x, x], axis=-1) / np.sqrt(2.0)
    return Geometry(**{k: np.full(2, getattr(DFP1, k)) for k in DFP1.__dataclass_fields__}), X, t


@pytest.mark.parametrize("capacity", ["continue", "stop", "error"])
def test_spatial_sweep_capacity_policies_match_the_planar_sweep(capacity):
    from dccss.mechanics.capacity import CapacityError
    from dccss.mechanics.newton import NewtonOptions
    from dccss.mechanics.summaries import summarize

    g, X, t = _ring_batch()
    planar_x = np.hypot(X[..., 0], X[..., 1])
    mark = NewtonOptions(on_failure="mark")
    ours = runs.summaries("compliant", g, X, azimuth=np.radians(45.0), capacity=capacity, options=mark, times=t)
    theirs = summarize("compliant", g, planar_x, capacity=capacity, options=mark, times=t)
    for name in ("capacity_exceeded", "failed"):
        assert np.array_equal(ours[name], theirs[name]), name
    for name in ("capacity_time", "failure_time", "theta2_max_abs", "rise_max", "clearance_min"):
        assert np.allclose(ours[name], theirs[name], rtol=0, atol=1e-9, equal_nan=True), name
    assert bool(ours["capacity_exceeded"][1] or ours["failed"][1]) and not ours["capacity_exceeded"][0]
    if capacity == "error":
        with pytest.raises(CapacityError, match=r"batch index \(1,\)"):
            runs.summaries("compliant", g, X, capacity=capacity, times=t)


def test_spatial_sweep_marks_a_failed_case_and_goes_on():
    from dccss.mechanics.newton import ConvergenceError, NewtonOptions

    g, X, t = _ring_batch()
    X = X.copy()
    X[50:, 1] += 0.8  # a jump no step can follow
    out = runs.summaries("stick_slip", g, X, options=NewtonOptions(on_failure="mark", max_iter=5), times=t)
    assert list(out["failed"]) == [False, True] and out["failure_time"][1] == pytest.approx(0.5)
    assert np.isfinite(out["theta2_max_abs"][0]) and np.isnan(out["theta2_max_abs"][1])
    with pytest.raises(ConvergenceError) as err:
        runs.summaries("stick_slip", g, X, options=NewtonOptions(max_iter=5), times=t)
    assert err.value.index == (1,)


def test_a_bidirectional_studys_corners_are_named_as_its_rim_points():
    """A bidirectional study's I_A_max .. I_D_max are the section's rim points, as its histories name them
    (their long names said "corner A2", whose history values they are not)."""
    study = Study.from_config(changed(AZIMUTHS, sweep={"azimuth": [30.0]}, histories=[], models=["compliant"]))
    part = run_chunk(study, "compliant", 0)
    assert part["I_A_max"].attrs["long_name"].startswith("largest interpenetration at the lower trailing rim point")
    assert part["I_D_max"].attrs["long_name"].startswith("largest interpenetration at the upper leading rim point")
