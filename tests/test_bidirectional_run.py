"""Bidirectional cases end to end: simulate, the datasets, `dccss run`, `dccss plot`, `dccss animate`."""

import math
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from dccss import cli, simulation
from dccss.excitation import Oriented, PlaneTable, Sine
from dccss.files import write_netcdf
from dccss.mechanics.capacity import CapacityError
from dccss.mechanics.newton import ConvergenceError, NewtonOptions
from dccss.paper.prototypes import DFP1, DFP2

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT / "config/studies/records"


def orbit_table(path, dt=0.01, radius=0.095, period=2.0):
    t = np.arange(int(round(period / dt)) + 1) * dt
    phase = 2 * np.pi * t / period
    lines = ["time,x,y"] + [f"{float(a)!r},{float(b)!r},{float(c)!r}" for a, b, c in
                            zip(t, radius * (1 - np.cos(phase)), radius * np.sin(phase))]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_an_oriented_sine_gives_the_planar_history(model):
    sine = Sine(0.15, 2 * math.pi, 1.0)
    ds = simulation.simulate(DFP2, Oriented(sine, 137.0), model=model, dt=0.01)
    planar = simulation.simulate(DFP2, sine, model=model, dt=0.01)
    assert ds.attrs["motion"] == "bidirectional" and "motion" not in planar.attrs
    assert np.max(np.abs(ds["tilt"].values - np.abs(planar["theta2"].values))) < 1e-9 * 180 / math.pi
    assert np.max(np.abs(ds["rise"].values - planar["rise"].values)) < 1e-9
    x = planar["Xg"].values
    assert np.allclose(ds["Xg_x"].values, x * math.cos(math.radians(137.0)), rtol=0, atol=1e-15)
    assert np.allclose(ds["Xg_y"].values, x * math.sin(math.radians(137.0)), rtol=0, atol=1e-15)
    if model == "stick_slip":
        assert np.nanmax(np.abs(ds["tilt_stick"].values[1:] - np.abs(planar["theta2_stick"].values[1:]))) < 1e-7


def test_dataset_variables_units_and_attributes(tmp_path):
    table = PlaneTable.from_csv(orbit_table(tmp_path / "orbit.csv"))
    ds = simulation.simulate(DFP1, table, model="stick_slip", dt=0.01)
    for name, units in {"Xg_x": "m", "Xg_y": "m", "tilt": "degree", "tilt_azimuth": "degree", "rise": "m",
                        "G2_x": "m", "G2_z": "m", "axis_x": "1", "axis_z": "1", "R3_z": "m", "tilt_stick": "degree",
                        "clearance_1": "m", "I_lower_trailing": "m", "sticking_rotation": "degree"}.items():
        assert ds[name].attrs["units"] == units, name
        assert ds[name].attrs["long_name"]
    axis = np.stack([ds[f"axis_{c}"].values for c in "xyz"], axis=-1)
    assert np.allclose(np.linalg.norm(axis, axis=-1), 1.0, atol=1e-14)
    assert np.allclose(np.degrees(np.arccos(axis[:, 2])), ds["tilt"].values, atol=1e-6)
    assert ds.attrs["excitation_components"] == 2 and ds.attrs["failed"] == 0
    assert ds.attrs["capacity_policy"] == "continue" and "capacity_exceeded_at_s" not in ds.attrs
    assert ds["tilt"].max() > 5.0


@pytest.mark.slow  # the CF checker
def test_bidirectional_dataset_passes_the_cf_checker(tmp_path):
    from test_conformance import check, high_and_medium

    ds = simulation.simulate(DFP1, Oriented(Sine(0.1, 6.0, 0.5), 30.0), model="stick_slip", dt=0.01)
    path = tmp_path / "bi.nc"
    write_netcdf(ds, path)
    assert high_and_medium(check([path], tmp_path / "report.json")) == {}


@pytest.mark.parametrize("policy", ["continue", "stop", "error"])
def test_capacity_policies_on_a_large_orbit(policy):
    excitation = Oriented(Sine(2.3 * float(DFP1.capacity1), 2 * math.pi, 1.0), 45.0)
    if policy == "error":
        with pytest.raises(CapacityError, match="retaining ring of RB"):
            simulation.simulate(DFP1, excitation, model="compliant", dt=0.01, capacity=policy)
        return
    ds = simulation.simulate(DFP1, excitation, model="compliant", dt=0.01, capacity=policy)
    planar = simulation.simulate(DFP1, excitation.excitation, model="compliant", dt=0.01, capacity=policy)
    assert ds.attrs["capacity_exceeded_at_s"] == planar.attrs["capacity_exceeded_at_s"]
    assert ds.attrs["capacity_exceeded_plate"] == planar.attrs["capacity_exceeded_plate"]
    assert ds.sizes["t"] == planar.sizes["t"]
    if policy == "stop":
        assert ds.attrs["stopped_at_s"] == planar.attrs["stopped_at_s"]


def test_a_solver_failure_is_raised_or_marked():
    excitation = Oriented(Sine(0.25, 60.0, 0.3), 10.0)
    options = NewtonOptions(max_iter=2)
    with pytest.raises(ConvergenceError, match="did not converge"):
        simulation.simulate(DFP1, excitation, model="stick_slip", dt=0.01, options=options)
    ds = simulation.simulate(DFP1, excitation, model="stick_slip", dt=0.01, options=options, on_failure="mark")
    assert ds.attrs["failed"] == 1 and "did not converge" in ds.attrs["failure_message"]
    assert ds["t"].values[-1] < ds.attrs["failure_time_s"]


def test_unsigned_normals_and_unknown_models_are_refused():
    excitation = Oriented(Sine(0.1, 6.0, 0.5), 30.0)
    with pytest.raises(ValueError, match="signed normals only"):
        simulation.simulate(DFP1, excitation, model="compliant", dt=0.01, normals="unsigned")
    with pytest.raises(ValueError, match="model must be one of"):
        simulation.simulate(DFP1, excitation, model="rolling", dt=0.01)


def test_progress_is_reported_when_the_compiled_history_is_done():
    calls = []
    simulation.simulate(DFP1, Oriented(Sine(0.1, 6.0, 0.2), 30.0), model="compliant", dt=0.01,
                        progress=lambda n, total: calls.append((n, total)))
    assert calls == [(20, 20)]


# --- the command line --------------------------------------------------------------------------
def _case(tmp_path, excitation, model="stick_slip", dt=0.005, **extra):
    path = tmp_path / "case.yaml"
    path.write_text(yaml.safe_dump({"prototype": "DFP1", "excitation": excitation, "dt": dt, "model": model, **extra}))
    return path


def test_dccss_run_on_a_record_pair(tmp_path, capsys):
    pair = [str(RECORDS / "synthetic.AT2"), str(RECORDS / "synthetic_y.AT2")]
    case = _case(tmp_path, {"kind": "record", "file": pair, "window": [0.0, 10.0], "baseline": "linear"})
    out = tmp_path / "pair.nc"
    assert cli.main(["run", str(case), "-o", str(out)]) == 0
    line = capsys.readouterr().out
    assert "bidirectional, 2000 steps (2001 states): max tilt" in line
    ds = xr.load_dataset(out)
    assert ds.sizes["t"] == 2001 and ds.attrs["motion"] == "bidirectional"
    assert ds.attrs["record_1_source"].endswith("synthetic.AT2")
    assert np.abs(ds["Xg_y"].values).max() > 0.01  # both components move the ground
    # the y component alone, along 90 deg, is a planar run of that record
    from dccss.records import Record

    y = Record.from_file(RECORDS / "synthetic_y.AT2", window=(0.0, 10.0), baseline="linear")
    assert np.allclose(ds["Xg_y"].values, y.displacement(ds["t"].values), rtol=0, atol=1e-15)


def test_components_of_different_steps_are_refused_and_nothing_is_written(tmp_path, capsys):
    coarse = tmp_path / "coarse.AT2"
    lines = (RECORDS / "synthetic_y.AT2").read_text().splitlines()
    shutil.copy(RECORDS / "synthetic.AT2", tmp_path / "x.AT2")
    header, values = lines[:4], " ".join(lines[4:]).split()[:1500]
    header[3] = header[3].replace("2000", "1500").replace(".01", ".02")
    coarse.write_text("\n".join(header + [" ".join(values[i:i + 5]) for i in range(0, 1500, 5)]) + "\n")
    case = _case(tmp_path, {"kind": "record", "file": ["x.AT2", "coarse.AT2"]})
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(case), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "excitation.file" in err and "coarse.AT2" in err and "must share their step" in err
    assert not out.exists()


def test_a_csv_without_y_is_refused(tmp_path, capsys):
    (tmp_path / "m.csv").write_text("time,x\n0,0\n1,0.1\n")
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(_case(tmp_path, {"kind": "table", "file": "m.csv"})), "-o", str(out)]) == 2
    assert "time, x, y" in capsys.readouterr().err
    assert not out.exists()


def test_dccss_plot_and_animate_a_bidirectional_result(tmp_path, capsys):
    orbit_table(tmp_path / "orbit.csv", dt=0.05)
    case = _case(tmp_path, {"kind": "table", "file": "orbit.csv"}, dt=0.05)
    result = tmp_path / "orbit.nc"
    assert cli.main(["run", str(case), "-o", str(result), "-q"]) == 0
    png, gif = tmp_path / "orbit.png", tmp_path / "orbit.gif"
    assert cli.main(["plot", str(result), "-o", str(png), "--at", "0.5", "1.0"]) == 0
    assert "sections at 0.5 s, 1 s" in capsys.readouterr().out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert cli.main(["plot", str(result), "-o", str(tmp_path / "bad.png"), "--at", "9"]) == 2
    assert "outside the history" in capsys.readouterr().err and not (tmp_path / "bad.png").exists()
    assert cli.main(["animate", str(result), "-o", str(gif), "-q"]) == 0
    from PIL import Image

    with Image.open(gif) as im:
        assert im.n_frames == 41
    first = png.read_bytes()
    assert cli.main(["plot", str(result), "-o", str(png), "--at", "0.5", "1.0", "-q"]) == 0
    assert png.read_bytes() == first  # reproducible bytes


def test_dccss_plot_draws_a_planar_result_too(tmp_path):
    case = _case(tmp_path, {"kind": "sine", "amplitude": 0.2, "omega": 6.283185307179586, "duration": 1.0},
                 dt=0.01)
    result = tmp_path / "planar.nc"
    assert cli.main(["run", str(case), "-o", str(result), "-q"]) == 0
    assert cli.main(["plot", str(result), "-o", str(tmp_path / "planar.pdf"), "-q"]) == 0
    assert (tmp_path / "planar.pdf").read_bytes()[:5] == b"%PDF-"
