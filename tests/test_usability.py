"""What a user meets first: the output's format follows its suffix, steps are counted one way, every
mistake of a file is reported at once, ``dccss run --help`` documents the case file, ``dccss check``
checks a file without running it, ``breakaway`` states its angles' unit, and the licence."""

import csv
import io
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from dccss import Geometry, breakaway, cli
from dccss.case import CaseError, case_from, load_case
from dccss.files import write_netcdf
from dccss.mechanics import backend
from dccss.paper.prototypes import TABLE1
from dccss.schema import schema
from dccss.studies import Study, StudyError

ROOT = Path(__file__).resolve().parents[1]
#: 100 steps of 2 ms
CASE = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.19, "omega": 30.0, "duration": 0.2},
        "dt": 0.002, "model": "stick_slip", "theta2_0": -2.0, "id": "usability"}
STUDY = {"study": {"name": "two", "description": "a small study"}, "prototype": "DFP1", "symmetric": True,
         "excitation": {"kind": "sine", "amplitude": 0.19, "omega": 30.0, "duration": 0.2}, "dt": 0.01,
         "models": ["compliant"], "sweep": {"alpha21": [8.0, 10.0], "h2": [0.12, 0.15]}}


def write(folder, mapping, name="case.yaml"):
    path = folder / name
    path.write_text(yaml.safe_dump(mapping, sort_keys=False))
    return path


def read_table(path):
    """(attributes, header, rows) of a CSV history: the '# key: value' lines, then the table."""
    attrs, lines = {}, path.read_text(encoding="utf-8").splitlines()
    while lines and lines[0].startswith("# "):
        key, _, value = lines.pop(0)[2:].partition(": ")
        attrs[key] = value
    header, *rows = list(csv.reader(io.StringIO("\n".join(lines))))
    return attrs, header, rows


# --- 1. the output's format follows its suffix ------------------------------------------------------
def test_run_writes_a_csv_table_of_the_history_when_the_output_ends_in_csv(tmp_path):
    case = write(tmp_path, CASE)
    assert cli.main(["run", str(case), "-o", str(tmp_path / "out.csv"), "-q"]) == 0
    ds = load_case(case).run()
    attrs, header, rows = read_table(tmp_path / "out.csv")
    assert attrs == {k: str(v) for k, v in ds.attrs.items()}  # self-describing: the dataset's attributes
    assert header[0] == "t [s]" and "theta2 [degree]" in header and "Xg_dot [m s-1]" in header
    names = ["t"] + [name for name in ds.data_vars if ds[name].dims == ("t",)]
    assert [h.split(" [")[0] for h in header] == names
    assert len(rows) == ds.sizes["t"] == 101  # one row per time step
    for j, name in enumerate(names):  # every number in full: the table equals the dataset
        np.testing.assert_array_equal(np.array([float(r[j]) for r in rows]), ds[name].values.astype(float))


def test_run_writes_netcdf_as_before_when_the_output_ends_in_nc(tmp_path):
    case = write(tmp_path, CASE)
    assert cli.main(["run", str(case), "-o", str(tmp_path / "out.nc"), "-q"]) == 0
    write_netcdf(load_case(case).run(), tmp_path / "direct.nc")
    assert (tmp_path / "out.nc").read_bytes() == (tmp_path / "direct.nc").read_bytes()


@pytest.mark.parametrize("output, named", [("out.txt", "'.txt'"), ("out.netcdf", "'.netcdf'"), ("out", "no suffix")])
def test_run_refuses_any_other_suffix_before_running(tmp_path, capsys, monkeypatch, output, named):
    def never(*args, **kwargs):
        raise AssertionError("the case was read although the output cannot be written")

    monkeypatch.setattr(cli, "load_case", never)
    assert cli.main(["run", str(write(tmp_path, CASE)), "-o", str(tmp_path / output)]) == 2
    err = capsys.readouterr().err
    assert named in err and ".nc" in err and ".csv" in err, err
    assert not (tmp_path / output).exists()


# --- 2. steps and states --------------------------------------------------------------------------
def test_run_counts_steps_and_the_states_they_join(tmp_path, capsys):
    """A history of N steps holds N + 1 states (t_0 and the end of each step): the summary says both."""
    out = tmp_path / "out.nc"
    assert cli.main(["run", str(write(tmp_path, CASE)), "-o", str(out)]) == 0
    line = capsys.readouterr().out
    assert xr.open_dataset(out).sizes["t"] == 101
    assert "stick_slip, 100 steps (101 states): max |theta2|" in line, line
    # dccss animate counts the same history the same way
    assert cli.main(["animate", str(out), "-o", str(tmp_path / "out.gif"), "--max-frames", "20"]) == 0
    assert ": 100 steps (101 states, t = " in capsys.readouterr().out


# --- 3. every mistake at once -----------------------------------------------------------------------
def test_a_case_file_with_several_mistakes_reports_them_all(tmp_path, capsys):
    bad = {**CASE, "dt": 0.0, "model": "pendulum", "colour": "red", "newton": {"tol": 0.0, "max_iter": 0},
           "prototype": {**TABLE1["DFP1"], "R1": "one", "hr3": None}}
    with pytest.raises(CaseError) as err:
        case_from(bad, tmp_path)
    expected = [f"case: unknown key(s) ['colour']; allowed: {sorted(schema('case')['properties'])}",
                "prototype.R1: expected a number, got the string 'one'",
                "prototype.hr3: expected a number, got NoneType None",
                "dt: must be > 0, got 0.0",
                "model: must be one of ['compliant', 'stick_slip'], got 'pendulum'",
                "newton.tol: must be > 0, got 0.0",
                "newton.max_iter: expected an integer >= 1, got 0"]
    assert sorted(err.value.messages) == sorted(expected)
    assert str(err.value).startswith(f"{len(expected)} errors:\n")
    assert cli.main(["run", str(write(tmp_path, bad)), "-o", str(tmp_path / "out.nc")]) == 2
    printed = capsys.readouterr().err
    assert all(m in printed for m in expected), printed


def test_a_dependent_key_is_checked_once_what_it_depends_on_passed(tmp_path):
    """An unknown prototype leaves the excitation to the schema (its amplitude may depend on the device)."""
    bad = {**CASE, "prototype": "DFP9", "excitation": {"kind": "sine", "omgea": 30.0}, "normals": "absolute"}
    with pytest.raises(CaseError) as err:
        case_from(bad, tmp_path)
    assert err.value.messages == [
        "prototype: unknown prototype 'DFP9'; known: ['DFP1', 'DFP2']",
        "excitation: unknown key(s) ['omgea']; known: ['amplitude', 'azimuth', 'duration', 'kind', 'omega', 'scale', "
        "'vertical']",
        "excitation: missing key(s) ['amplitude', 'omega', 'duration']",
        "normals: must be one of ['signed', 'unsigned'], got 'absolute'"]


def test_one_mistake_reads_as_before(tmp_path):
    with pytest.raises(CaseError) as err:
        case_from({**CASE, "dt": -0.01}, tmp_path)
    assert str(err.value) == "dt: must be > 0, got -0.01" and err.value.messages == [str(err.value)]


def test_a_study_file_with_several_mistakes_reports_them_all(tmp_path):
    bad = {**STUDY, "models": ["compliant", "rolling"], "chunk_size": 0, "capacity": "ignore",
           "sweep": {"alpha21": [8.0], "h3": [1.0], "h2": {"start": 0.1, "stop": 0.2, "num": 0}}}
    with pytest.raises(StudyError) as err:
        Study.from_config(bad, tmp_path)
    assert err.value.messages == [
        "models[1]: must be one of ['compliant', 'stick_slip'], got 'rolling'",
        f"sweep: unknown axis 'h3'; allowed: {list(__import__('dccss.studies.spec').studies.spec.AXES)}",
        "sweep.h2.num: expected an integer >= 1, got 0",
        "chunk_size: expected an integer >= 1 or 'auto', got 0",
        "capacity: must be one of ['continue', 'stop', 'error'], got 'ignore'"]


# --- 4. dccss run --help ------------------------------------------------------------------------------
def test_run_help_lists_the_case_keys_the_exit_codes_and_the_backend(capsys):
    with pytest.raises(SystemExit) as done:
        cli.main(["run", "--help"])
    assert done.value.code == 0
    text = capsys.readouterr().out
    entries = dict(re.findall(r"^  (\S+) +(.+(?:\n {15,}\S.*)*)", text, re.MULTILINE))  # an entry and its wrapped lines
    entries = {label: " ".join(entry.split()) for label, entry in entries.items()}
    spec = schema("case")
    for key, prop in spec["properties"].items():  # every key, from the schema, with its description's start
        assert entries[key].startswith(" ".join(prop["description"].split())[:40]), (key, entries[key])
        assert entries[key].endswith("; required") == (key in spec["required"]), (key, entries[key])
    assert entries["theta2_0"].endswith("; default 0.0") and entries["capacity"].endswith("; default continue")
    assert "; one of compliant, stick_slip;" in entries["model"]
    assert "; kind: one of sine, table, record;" in entries["excitation"]
    documented = re.findall(r"\b(\d) [a-z]", cli.__doc__.split("Exit codes:")[1].split(".")[0])
    assert documented == ["0", "2", "3", "4"]
    for code in documented:
        assert code in entries, code
    for value in backend.BACKENDS:
        assert f"DCCSS_BACKEND={value}" in entries, value
    assert "(the default;" in entries["DCCSS_BACKEND=auto"]
    assert ".csv" in text and ".nc" in text


# --- 5. dccss check ---------------------------------------------------------------------------------
def test_check_says_a_case_file_is_valid_and_runs_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("dccss.case.Case.run", lambda *a, **k: pytest.fail("dccss check ran the case"))
    path = write(tmp_path, CASE)
    assert cli.main(["check", str(path)]) == 0
    assert capsys.readouterr().out == (
        f"{path}: a valid case file (model stick_slip, prototype DFP1, sine excitation, t = 0 .. 0.2 s by "
        f"dt = 0.002 s: 100 steps (101 states))\n")
    assert list(tmp_path.iterdir()) == [path]


@pytest.mark.parametrize("name", sorted(p.name for p in (ROOT / "config/studies").glob("*.yaml")))
def test_check_says_a_shipped_study_file_is_valid(name, capsys):
    path = ROOT / "config/studies" / name
    assert cli.main(["check", str(path)]) == 0
    study = yaml.safe_load(path.read_text())["study"]["name"]
    assert re.fullmatch(rf"{re.escape(str(path))}: a valid study file \(study {study}: \d+ cases? \(.+\) under .+\)\n",
                        capsys.readouterr().out)


@pytest.mark.parametrize("mapping, messages", [
    ({**CASE, "dt": 0.0, "model": "pendulum"},
     ["not a valid case file: 2 errors:", "  - dt: must be > 0", "  - model: must be one of"]),
    ({**STUDY, "chunk_size": 0, "models": ["rolling"]},
     ["not a valid study file: 2 errors:", "  - models[0]: must be one of", "  - chunk_size: expected an integer"]),
    ({"prototype": "DFP1", "colour": "red"}, ["not a valid case file: 2 errors:", "unknown key(s) ['colour']",
                                              "missing key(s) ['excitation', 'dt', 'model']"]),
    ({"model": "compliant", "sweep": {"h2": [0.1]}},
     ["neither a case file nor a study file: it has keys of both, ['model'] of a case file and ['sweep'] of a study"]),
    ({"colour": "red"}, ["neither a case file nor a study file: none of its keys ['colour'] is one of either"]),
    ([1, 2], ["neither a case file nor a study file: expected a mapping of keys, got list [1, 2]"]),
])
def test_check_reports_every_error_with_exit_code_2(tmp_path, capsys, mapping, messages):
    path = write(tmp_path, mapping, "file.yaml")
    assert cli.main(["check", str(path)]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.startswith(f"dccss: {path}: ")
    assert all(m in captured.err for m in messages), captured.err


def test_check_of_a_missing_file(tmp_path, capsys):
    assert cli.main(["check", str(tmp_path / "none.yaml")]) == 2
    assert "none.yaml' does not exist" in capsys.readouterr().err


@pytest.mark.parametrize("command", ["run", "check"])
def test_run_and_check_do_not_import_matplotlib(tmp_path, command):
    path = write(tmp_path, CASE)
    args = ["run", str(path), "-o", str(tmp_path / "out.nc"), "-q"] if command == "run" else ["check", str(path)]
    code = (f"import sys\nfrom dccss.cli import main\ncode = main({args!r})\n"
            "print(code, sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines()[-1] == "0 []"


# --- 6. breakaway's angles --------------------------------------------------------------------------
DFP1 = Geometry.from_degrees(**TABLE1["DFP1"])


def test_breakaway_takes_the_grid_in_degrees_by_name():
    degrees = np.array([-9.2, -7.7, -6.0, 0.0])  # -9.2 and -7.7 do not survive a round trip through radians
    by_degrees = breakaway(DFP1, theta2_0_deg=degrees, dXg=[0.05, 0.10])
    by_radians = breakaway(DFP1, np.radians(degrees), [0.05, 0.10])
    np.testing.assert_array_equal(by_degrees["theta2_0"].values, degrees)  # the coordinate holds the values given
    assert by_degrees["theta2_0"].attrs == by_radians["theta2_0"].attrs and by_degrees["theta2_0"].attrs[
        "units"] == "degree"
    xr.testing.assert_identical(by_degrees.drop_vars("theta2_0"), by_radians.drop_vars("theta2_0"))
    np.testing.assert_allclose(by_radians["theta2_0"].values, degrees, rtol=0, atol=1e-12)
    scalar = breakaway(DFP1, dXg=0.05, theta2_0_deg=-6.0)
    assert scalar["theta2_0"].values.tolist() == [-6.0] and scalar.attrs["dXg_m"] == 0.05


@pytest.mark.parametrize("kwargs, message", [
    (dict(theta2_0=0.0, theta2_0_deg=0.0, dXg=0.05), "theta2_0 \\(radians\\) or theta2_0_deg \\(degrees\\), got both"),
    (dict(dXg=0.05), "got neither"),
    (dict(theta2_0_deg=0.0), "needs the ground step dXg"),
])
def test_breakaway_takes_the_grid_once(kwargs, message):
    with pytest.raises(TypeError, match=message):
        breakaway(DFP1, **kwargs)


def test_breakaway_documents_the_units_of_its_angles():
    doc = breakaway.__doc__
    assert re.search(r"theta2_0 : .*in radians", doc) and re.search(r"theta2_0_deg : .*in degrees", doc)
    assert 'coordinate in degrees (``units`` "degree")' in " ".join(doc.split())


# --- 7. the licence ---------------------------------------------------------------------------------
def test_the_licence_is_mit_as_the_package_says():
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License\n") and "Copyright (c) 2021–2026 the dccss authors" in text
    assert 'THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND' in text
    assert 'license = { text = "MIT" }' in (ROOT / "pyproject.toml").read_text(encoding="utf-8")
