"""Bad input, one row per mistake: the exit status, a message naming the key, value or file, and
nothing written. Case files go through ``dccss run``; configurations through the workflow."""

import re

import numpy as np
import pytest
import yaml
from conftest import copy_project, snakemake

from dccss.cli import main
from dccss.paper.prototypes import TABLE1
from dccss.records import write_at2

CASE = {
    "prototype": dict(TABLE1["DFP1"]),
    "excitation": {"kind": "sine", "amplitude": 0.19, "omega": 30.0, "duration": 0.2},
    "dt": 0.01,
    "model": "stick_slip",
}


SINE_AT2 = "\n".join(["PEER NGA", "test", "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS=    4, DT=   .0100 SEC",
                      "  .1E-01  .2E-01  .1E-01  .0E+00"])
# (id, changes to the case or raw YAML text, extra files, expected exit status, message)
CLI_ROWS = [
    ("missing key", {"model": None}, {}, 2, r"case: missing key\(s\) \['model'\]"),
    ("unknown key", {"colour": "red"}, {}, 2, r"case: unknown key\(s\) \['colour'\]"),
    ("wrong type", {"dt": [0.01]}, {}, 2, "dt: expected a number, got list"),
    ("YAML 1e-3 string", "dt: 1e-3", {}, 2, "dt: expected a number, got the string '1e-3'"),
    ("non-finite", "theta2_0: .nan", {}, 2, "theta2_0: expected a finite number"),
    ("start turned past 90 degrees", {"theta2_0": 400}, {}, 2,
     "theta2_0 400 is greater than or equal to the maximum of 90"),
    ("start turned by -90 degrees", {"theta2_0": -90}, {}, 2,
     "theta2_0 -90 is less than or equal to the minimum of -90"),
    ("infinite amplitude", {"excitation": {**CASE["excitation"], "amplitude": float("inf")}}, {}, 2,
     "excitation.amplitude: expected a finite number"),
    ("non-positive length", {"prototype": {**TABLE1["DFP1"], "R1": 0.0}}, {}, 2,
     "'R1' is a length and must be > 0"),
    ("non-positive dt", {"dt": 0.0}, {}, 2, "dt: must be > 0"),
    ("dt larger than duration", {"dt": 0.5}, {}, 2, "dt: 0.5 s is larger than the excitation's duration"),
    ("cap wider than lower plate", {"prototype": {**TABLE1["DFP1"], "alpha21": 21.0}}, {}, 2,
     "'alpha21' must lie in 0 < alpha21 < alpha1"),
    ("cap wider than upper plate", {"prototype": {**TABLE1["DFP1"], "alpha23": 30.0}}, {}, 2,
     "'alpha23' must lie in 0 < alpha23 < alpha3"),
    ("pad too tall", {"prototype": {**TABLE1["DFP1"], "h2": 2.5}}, {}, 2, "the pad is too tall"),
    ("unknown model", {"model": "pendulum"}, {}, 2, r"model: must be one of \['compliant', 'stick_slip'\]"),
    ("unknown normals", {"normals": "absolute"}, {}, 2, "normals: must be one of"),
    ("unknown prototype", {"prototype": "DFP3"}, {}, 2, "prototype: unknown prototype 'DFP3'"),
    ("unknown capacity policy", {"capacity": "ignore"}, {}, 2, r"capacity: must be one of \['continue'"),
    ("bad newton iterations", {"newton": {"max_iter": "many"}}, {}, 2, "newton.max_iter: expected an integer"),
    ("table file missing", {"excitation": {"kind": "table", "file": "nope.csv"}}, {}, 2, "nope.csv' does not exist"),
    ("table wrong header", {"excitation": {"kind": "table", "file": "t.csv"}}, {"t.csv": "t,x\n0,0\n1,0\n"}, 2,
     "t.csv' must have a header with columns 'time' and 'displacement'"),
    ("table non-monotonic time", {"excitation": {"kind": "table", "file": "t.csv"}},
     {"t.csv": "time,displacement\n0,0\n0.2,0.01\n0.1,0\n"}, 2, "time must increase strictly"),
    ("table NaN", {"excitation": {"kind": "table", "file": "t.csv"}},
     {"t.csv": "time,displacement\n0,0\n0.1,nan\n0.2,0\n"}, 2, "displacement sample 1 is not finite"),
    ("record file missing", {"excitation": {"kind": "record", "file": "nope.AT2"}}, {}, 2, "nope.AT2"),
    ("record empty", {"excitation": {"kind": "record", "file": "r.AT2"}}, {"r.AT2": ""}, 2, "r.AT2"),
    ("record without NPTS", {"excitation": {"kind": "record", "file": "r.AT2"}},
     {"r.AT2": SINE_AT2.replace("NPTS=    4, DT=   .0100 SEC", "no header here")}, 2, "r.AT2"),
    ("record non-numeric", {"excitation": {"kind": "record", "file": "r.AT2"}},
     {"r.AT2": SINE_AT2.replace(".2E-01", "abc")}, 2, "r.AT2"),
    ("record NaN", {"excitation": {"kind": "record", "file": "r.AT2"}}, {"r.AT2": SINE_AT2.replace(".2E-01", "nan")},
     2, "r.AT2"),
    ("capacity exceeded, policy error", {"excitation": {**CASE["excitation"], "amplitude": 0.45}, "capacity": "error"},
     {}, 4, r"ring of RB1 at t = 0.03 s \(step 3, RB1 moved by 35.25 cm; the ring is where the pad has turned by "
            r"alpha1 - alpha21, which compliant sliding reaches at L sin\(alpha1 - alpha21\) = 34.72 cm; one "
            r"surface's capacity R1 sin\(alpha1 - alpha21\) = 19.08 cm\)"),
    ("solver failure", {"newton": {"tol": 1.0e-30, "max_iter": 2}}, {}, 3,
     "did not converge in sticking .*step 1, time 0.01 s"),
    # every mistake of a sine and of a structure at once (before: the first of each)
    ("sine and structure keys", {"excitation": {**CASE["excitation"], "omega": float("inf"), "duration": -1.0},
                                 "structure": {"friction": 1.5, "damping": -0.1}}, {}, 2,
     r"4 errors:\n  - excitation.duration: must be > 0, got -1.0\n  - excitation.omega: expected a finite number, "
     r"got inf\n  - structure.friction: 1.5 is outside 0 <= μ < 1\n  - structure.damping: -0.1 is outside 0 <= ζ < 1"),
    ("amplitude word", {"excitation": {**CASE["excitation"], "amplitude": "Capacity"}}, {}, 2,
     r"excitation.amplitude: expected a number \(m\) or the word 'capacity' .*got the string 'Capacity'"),
]


@pytest.mark.parametrize("changes, files, status, message", [r[1:] for r in CLI_ROWS], ids=[r[0] for r in CLI_ROWS])
def test_case_file_errors(tmp_path, capsys, changes, files, status, message):
    case = dict(CASE)
    if isinstance(changes, str):
        text = yaml.safe_dump(case) + changes + "\n"
    else:
        for key, value in changes.items():
            if value is None:
                case.pop(key)
            else:
                case[key] = value
        text = yaml.safe_dump(case)
    for name, body in files.items():
        (tmp_path / name).write_text(body)
    (tmp_path / "case.yaml").write_text(text)
    before = set(tmp_path.iterdir())
    out = tmp_path / "out" / "result.nc"
    assert main(["run", str(tmp_path / "case.yaml"), "-o", str(out)]) == status
    err = capsys.readouterr().err
    assert re.search(message, err), err
    assert not out.exists()
    leftovers = [p for p in tmp_path.rglob("*") if p not in before and p.is_file()]
    assert leftovers == []


def test_an_output_path_that_cannot_be_written_is_refused_before_the_run(tmp_path, capsys):
    """A folder, or a path under a file, is refused at once with exit code 2 (before: the case ran, then a
    traceback and exit code 1); a missing folder is made."""
    case = tmp_path / "case.yaml"
    case.write_text(yaml.safe_dump(CASE))
    (tmp_path / "folder.nc").mkdir()
    assert main(["run", str(case), "-o", str(tmp_path / "folder.nc")]) == 2
    assert "folder.nc: is a folder" in capsys.readouterr().err
    assert main(["run", str(case), "-o", str(case / "out.nc")]) == 2
    assert "case.yaml' is a file, not a folder" in capsys.readouterr().err
    assert main(["run", str(case), "-o", str(tmp_path / "made" / "out.nc"), "-q"]) == 0


def test_a_non_finite_ground_motion_is_refused():
    """A NaN or infinite scale (the Python API) and a non-finite X_g are refused, naming the value (before: a
    NaN history marked as not failed)."""
    from dccss import Scaled, Sine
    from dccss.mechanics import runs
    from dccss.paper.prototypes import DFP1

    for factor in (float("nan"), float("inf")):
        with pytest.raises(ValueError, match=f"excitation.scale: expected a finite number, got {factor}"):
            Scaled(Sine(0.1, 3.0, 1.0), factor)
    with pytest.raises(ValueError, match=r"Xg must be finite: step 2 \(t = 0.02 s\) is nan"):
        runs.history("compliant", DFP1, np.array([0.0, 0.01, np.nan]), times=np.array([0.0, 0.01, 0.02]))
    with pytest.raises(ValueError, match="Xg must be finite: step 1 is inf"):
        runs.summaries("stick_slip", DFP1, np.array([[0.0, 0.0], [np.inf, 0.0]]))


def test_case_file_missing_and_not_yaml(tmp_path, capsys):
    assert main(["run", str(tmp_path / "none.yaml"), "-o", str(tmp_path / "o.nc")]) == 2
    assert "none.yaml' does not exist" in capsys.readouterr().err
    (tmp_path / "bad.yaml").write_text("dt: [unclosed\n")
    assert main(["run", str(tmp_path / "bad.yaml"), "-o", str(tmp_path / "o.nc")]) == 2
    assert "is not valid YAML" in capsys.readouterr().err
    assert not (tmp_path / "o.nc").exists()


def test_record_helper_round_trip(tmp_path):
    """The AT2 rows above use the format the reader accepts when intact."""
    write_at2(tmp_path / "ok.AT2", 0.01, np.array([0.01, 0.02, 0.01, 0.0]))
    case = {**CASE, "excitation": {"kind": "record", "file": "ok.AT2"}, "dt": 0.01}
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(case))
    assert main(["run", str(tmp_path / "case.yaml"), "-o", str(tmp_path / "ok.nc"), "-q"]) == 0


def _paper(config):
    config["colour"] = "red"


def _unknown_case_set(config):
    config["figures"]["case_set"] = "as_imagined"


def _unknown_prototype(config):
    config["case_sets"]["as_printed"]["cases"]["DFP9"] = {"amplitude": 0.2, "theta2_0": 0.0, "normals": "signed"}


def _negative_dt(config):
    config["dt"] = [-0.01]


def _bad_geometry(config):
    config["prototypes"]["DFP1"] = {**TABLE1["DFP1"], "alpha21": 25.0}


def _unknown_model(config):
    config["models"] = ["compliant", "rolling"]


WORKFLOW_ROWS = [
    ("paper config unknown key", _paper, "colour"),
    ("paper config unknown case set", _unknown_case_set, "figures.case_set: unknown case set 'as_imagined'"),
    ("paper config unknown prototype", _unknown_prototype, "unknown prototype 'DFP9'"),
    ("paper config unknown model", _unknown_model, "models[1]: unknown model 'rolling'; registered:"),
    ("paper config negative dt", _negative_dt, "-0.01"),
    ("paper config impossible geometry", _bad_geometry, "prototypes.DFP1: geometry parameter 'alpha21'"),
]


@pytest.mark.slow
@pytest.mark.parametrize("mutate, message", [r[1:] for r in WORKFLOW_ROWS], ids=[r[0] for r in WORKFLOW_ROWS])
def test_workflow_config_errors(tmp_path, mutate, message):
    work = copy_project(tmp_path)
    config = yaml.safe_load((work / "config/config.yaml").read_text())
    mutate(config)
    (work / "bad.yaml").write_text(yaml.safe_dump(config))
    run = snakemake(work, "--configfile", "bad.yaml")
    assert run.returncode != 0
    assert message in run.stdout + run.stderr, (run.stdout + run.stderr)[-2000:]
    assert not (work / "results").exists() and not (work / "figures").exists()


def test_a_device_in_other_units_is_warned_about(tmp_path):
    """A device given in mm, or with its angles in radians, is valid but warned about, naming the keys (it ran
    silently)."""
    from dccss.case import DeviceWarning, geometry_from

    mm = {**TABLE1["DFP1"], "R1": 2000.0, "R3": 2000.0, "h2": 150.0}
    with pytest.warns(DeviceWarning, match=r"prototype: R1 = 2000, R3 = 2000, h2 = 150 m: lengths are in metres"):
        geometry_from(mm)
    radians = {**TABLE1["DFP1"], **{k: np.radians(TABLE1["DFP1"][k]) for k in ("alpha1", "alpha3", "alpha21",
                                                                                  "alpha23")}}
    with pytest.warns(DeviceWarning, match="every angle is under 1 degree .* are they in radians"):
        geometry_from(radians)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        geometry_from("DFP1")  # Table 1 and the shipped studies' devices raise no warning
