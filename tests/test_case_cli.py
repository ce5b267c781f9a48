"""Case files and the ``dccss run`` command: valid runs, and errors that name the key."""

import os
import pty
import re
import subprocess
import sys
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import DELETE, changed

from dccss.case import CaseError, case_from, load_case
from dccss.cli import main
from dccss.paper.prototypes import TABLE1

CASE = {
    "prototype": dict(TABLE1["DFP1"]),
    "excitation": {"kind": "sine", "amplitude": 0.1908, "omega": 30.0, "duration": 0.2},
    "theta2_0": 0.0,
    "dt": 0.01,
    "model": "compliant",
    "normals": "signed",
}


def write(tmp_path, mapping, name="case.yaml"):
    path = tmp_path / name
    path.write_text(yaml.safe_dump(mapping))
    return path


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_cli_run_writes_dataset(tmp_path, model, capsys):
    path = write(tmp_path, {**CASE, "model": model, "id": "dfp1-test"})
    out = tmp_path / "sub" / "out.nc"
    assert main(["run", str(path), "-o", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    ds = xr.open_dataset(out)
    assert ds.sizes["t"] == 21 and ds.attrs["model"] == model and ds.attrs["case_id"] == "dfp1-test"
    for name in ["Xg", "Xg_dot", "Rx1", "Ry1", "theta1", "Rx2", "Ry2", "theta2", "Rx3", "Ry3",
                 "theta3", "I_A", "I_B", "I_C", "I_D", "newton_iterations"]:
        assert "units" in ds[name].attrs and "long_name" in ds[name].attrs, name
    assert ds["theta2"].attrs["units"] == "degree" and ds["Ry3"].attrs["units"] == "m"
    if model == "compliant":
        assert "det_Cq" in ds
    else:
        assert np.isnan(ds["theta2_stick"][0]) and np.isfinite(ds["Ry3_stick"][1:]).all()
    for key in ("R1_m", "alpha21_deg", "amplitude_m", "omega_rad_per_s", "dccss_version", "normals"):
        assert key in ds.attrs
    with netCDF4.Dataset(out) as nc:  # plain netCDF4 reads names and units
        assert nc.variables["I_A"].units == "m"


def test_python_m_entry_point(tmp_path):
    path = write(tmp_path, CASE)
    out = tmp_path / "out.nc"
    r = subprocess.run([sys.executable, "-m", "dccss", "run", str(path), "-o", str(out), "-q"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert out.exists() and r.stdout == ""


def test_prototype_by_name_and_table_excitation(tmp_path):
    t = np.linspace(0, 0.2, 201)
    np.savetxt(tmp_path / "rec.csv", np.column_stack([t, 0.05 * np.sin(30 * t)]), delimiter=",",
               header="time,displacement", comments="")
    sub = tmp_path / "cases"
    sub.mkdir()
    path = write(sub, {**CASE, "prototype": "DFP2", "excitation": {"kind": "table", "file": "../rec.csv"}})
    case = load_case(path)
    ds = case.run()
    assert ds.attrs["alpha21_deg"] == pytest.approx(5.0)
    assert ds["Xg"].values[10] == pytest.approx(0.05 * np.sin(3.0), abs=1e-9)


def mutate(**changes):
    return changed(CASE, **changes)
BAD = [
    (dict(colour="red"), r"case: unknown key\(s\) \['colour'\]"),
    (dict(model=DELETE), r"case: missing key\(s\) \['model'\]"),
    (dict(dt="1e-3"), "dt: expected a number, got the string '1e-3'.*write 1.0e-3"),
    (dict(dt=-0.01), "dt: must be > 0"),
    (dict(dt=5.0), "dt: 5.0 s is larger than the excitation's duration"),
    (dict(model="pendulum"), r"model: must be one of \['compliant', 'stick_slip'\]"),
    (dict(normals="absolute"), r"normals: must be one of \['signed', 'unsigned'\]"),
    (dict(theta2_0=[1, 2]), "theta2_0: expected a number, got list"),
    (dict(theta2_0=float("nan")), "theta2_0: expected a finite number"),
    (dict(prototype="DFP9"), r"prototype: unknown prototype 'DFP9'; known: \['DFP1', 'DFP2'\]"),
    (dict(prototype__R1="one"), "prototype.R1: expected a number, got the string 'one'"),
    (dict(prototype__hr1=DELETE), r"prototype: missing key\(s\) \['hr1'\]"),
    (dict(prototype__alpha21=25.0), "prototype: geometry parameter 'alpha21' must lie in 0 < alpha21 < alpha1"),
    (dict(prototype__h2=0.0), "prototype: geometry parameter 'h2' is a length and must be > 0"),
    (dict(excitation__kind="ramp"), r"excitation.kind: must be one of \['sine', 'table', 'record'\]"),
    (dict(excitation__omega=True), "excitation.omega: expected a number, got bool"),
    (dict(excitation__phase=0.0), r"excitation: unknown key\(s\) \['phase'\]"),
    (dict(excitation={"kind": "table", "file": "missing.csv"}),
     "excitation.file: table excitation: file .*missing.csv' does not exist"),
    (dict(newton={"tol": 0.0}), "newton.tol: must be > 0"),
    (dict(newton={"max_iter": 2.5}), "newton.max_iter: expected an integer >= 1"),
    (dict(id=3), "id: expected a string"),
]


@pytest.mark.parametrize("changes, message", BAD, ids=[m[:40] for _, m in BAD])
def test_invalid_case_names_key(tmp_path, changes, message):
    with pytest.raises(CaseError, match=message):
        case_from(mutate(**changes), tmp_path)


def test_cli_error_exit_code_and_no_output(tmp_path, capsys):
    path = write(tmp_path, mutate(dt="1e-3"))
    out = tmp_path / "out.nc"
    assert main(["run", str(path), "-o", str(out)]) == 2
    assert "dt: expected a number" in capsys.readouterr().err
    assert not out.exists() and list(tmp_path.iterdir()) == [path]


def test_cli_solver_failure_exit_code(tmp_path, capsys):
    path = write(tmp_path, mutate(newton={"tol": 1e-30, "max_iter": 2}))
    out = tmp_path / "out.nc"
    assert main(["run", str(path), "-o", str(out)]) == 3
    err = capsys.readouterr().err
    assert "did not converge" in err and "step 1" in err
    assert not out.exists()


def test_missing_and_malformed_case_file(tmp_path):
    with pytest.raises(CaseError, match="does not exist"):
        load_case(tmp_path / "none.yaml")
    bad = tmp_path / "bad.yaml"
    bad.write_text("prototype: [unclosed\n")
    with pytest.raises(CaseError, match="not valid YAML"):
        load_case(bad)
    bad.write_text("- a list\n")
    with pytest.raises(CaseError, match="case: expected a mapping"):
        load_case(bad)


BEYOND = {**CASE, "excitation": {"kind": "sine", "amplitude": 0.40, "omega": 10.0, "duration": 1.0}}


@pytest.mark.parametrize("policy", ["continue", "stop"])
def test_cli_warns_once_when_a_ring_is_reached(tmp_path, policy, capsys):
    out = tmp_path / "out.nc"
    assert main(["run", str(write(tmp_path, {**BEYOND, "capacity": policy})), "-o", str(out)]) == 0
    err = capsys.readouterr().err.splitlines()
    ring = [line for line in err if "retaining ring" in line]
    ds = xr.open_dataset(out)
    plate, when = ds.attrs["capacity_exceeded_plate"], ds.attrs["capacity_exceeded_at_s"]
    moved = ds.attrs["capacity_exceeded_displacement_m"]
    assert moved == pytest.approx(abs(ds["Xg"].values[int(round(when / 0.01))]), rel=1e-12)
    assert len(ring) == 1 and ring[0].startswith(f"dccss: warning: the pad reaches the retaining ring of {plate} "
                                                 f"at t = {when:.6g} s, RB1 {100 * moved:.4g} cm from its start "
                                                 "and passes it by up to")
    assert f"(capacity: {policy})" in ring[0]
    cut = [line for line in err if "cut the history short" in line]
    if policy == "stop":
        assert len(cut) == 1 and f"({ds.sizes['t'] - 1} steps written)" in cut[0]
    else:
        assert cut == [] and ds.sizes["t"] == 101


def test_cli_writes_a_marked_failure_and_says_so(tmp_path, capsys):
    case = {**CASE, "model": "stick_slip", "on_failure": "mark",
            "excitation": {"kind": "sine", "amplitude": 0.9, "omega": 10.0, "duration": 1.0}}
    out = tmp_path / "out.nc"
    assert main(["run", str(write(tmp_path, case)), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "dccss: warning: the solver failed at t = 0.15 s; the history is written up to the last converged" in err
    assert xr.open_dataset(out).attrs["failed"] == 1 and xr.open_dataset(out).attrs["failure_kind"] == "solver"
    # a ring under capacity "error", marked: the ring ended it, not the solver (before: "the solver failed")
    assert main(["run", str(write(tmp_path, {**case, "capacity": "error"})), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "solver failed" not in err and "dccss: warning: capacity: error ended the history at the ring" in err
    assert xr.open_dataset(out).attrs["failure_kind"] == "capacity"
    assert main(["run", str(write(tmp_path, {**case, "on_failure": "error"})), "-o", str(tmp_path / "no.nc")]) == 3
    assert "Before the solver failed, the pad reached the retaining ring of RB1" in capsys.readouterr().err
    assert not (tmp_path / "no.nc").exists()


def _on_a_terminal(args, env):
    """Run ``python -m dccss`` with stderr on a pseudo-terminal: (return code, what the terminal showed)."""
    leader, follower = pty.openpty()
    run = subprocess.run([sys.executable, "-m", "dccss", *args], stdout=subprocess.PIPE, stderr=follower, text=True,
                         env=env)
    os.close(follower)
    try:
        screen = os.read(leader, 65536).decode()
    except OSError:  # EIO: nothing was written to the terminal
        screen = ""
    os.close(leader)
    return run.returncode, screen


@pytest.mark.slow
def test_a_terminal_is_told_when_the_kernels_compile(tmp_path):
    """The first compiled run of a version on a machine compiles for 10-30 s: a terminal is told so (a
    run with --quiet, or into a pipe, is not); a second run loads the kernels and says nothing. Before,
    the terminal showed nothing while compiling and a "step N/N" line, erased at once, after it.

    The run told is compiled for real. The runs not told (quiet, piped) run with a cold cache of their own
    and numba's JIT disabled: the kernel is announced before it compiles, on the same test of the cache,
    so they show the same; they skip the 8 s compilation that follows."""
    case = str(write(tmp_path, {**CASE, "model": "compliant", "dt": 0.001,
                                "excitation": {**CASE["excitation"], "duration": 30.0}}))
    out = str(tmp_path / "out.nc")
    env = {**os.environ, "DCCSS_BACKEND": "numba", "NUMBA_CACHE_DIR": str(tmp_path / "shown")}
    code, screen = _on_a_terminal(["run", case, "-o", out], env)
    assert code == 0 and "dccss: compiling compliant_batch: once for this machine and version" in screen, screen
    code, screen = _on_a_terminal(["run", case, "-o", out], env)
    assert code == 0 and "compiling" not in screen and "dccss: wrote" not in screen, screen  # wrote: on stdout
    short = str(write(tmp_path, {**CASE, "model": "compliant", "dt": 0.001}, name="short.yaml"))
    for name in ("told", "quiet", "piped"):  # told: the JIT disabled, the terminal is told as when it compiles
        env = {**env, "NUMBA_CACHE_DIR": str(tmp_path / name), "NUMBA_DISABLE_JIT": "1"}
        if name == "piped":
            run = subprocess.run([sys.executable, "-m", "dccss", "run", short, "-o", out], capture_output=True,
                                 text=True, env=env)
            code, screen = run.returncode, run.stderr
        else:
            code, screen = _on_a_terminal(["run", short, "-o", out] + (["--quiet"] if name == "quiet" else []), env)
        assert code == 0 and ("dccss: compiling compliant_batch" in screen) == (name == "told"), (name, screen)


def test_kernel_says_when_it_compiles(tmp_path, monkeypatch, caplog):
    """``scalar.kernel`` logs "compiling" where the cache holds no index of the function, not where it does."""
    numba = pytest.importorskip("numba")
    from dccss.mechanics import scalar

    monkeypatch.setattr(numba.config, "CACHE_DIR", str(tmp_path))
    monkeypatch.setattr(scalar, "_KERNELS", {})
    with caplog.at_level("INFO", logger="dccss.kernels"):
        assert scalar.kernel(_twice)(2.0) == 4.0
    assert [r.getMessage().split(":")[0] for r in caplog.records] == ["compiling _twice"]
    caplog.clear()
    monkeypatch.setattr(scalar, "_KERNELS", {})
    with caplog.at_level("INFO", logger="dccss.kernels"):
        assert scalar.kernel(_twice)(3.0) == 6.0
    assert not caplog.records


def _twice(x):
    return 2.0 * x


@pytest.mark.parametrize("policy", ["continue", "stop"])
def test_cli_refuses_to_write_motion_beyond_the_pendulum_length(tmp_path, policy, capsys):
    """|X_g| beyond L = 1.82 m: no compatible configuration; before, `continue` wrote θ² = 97.6° and exit 0."""
    far = {**CASE, "model": "compliant", "capacity": policy,
           "excitation": {"kind": "sine", "amplitude": 2.0, "omega": 1.0, "duration": 2.0}}
    out = tmp_path / "out.nc"
    code = main(["run", str(write(tmp_path, far)), "-o", str(out)])
    err = capsys.readouterr().err
    if policy == "stop":  # the ring comes first: the history ends there, a result
        assert code == 0 and xr.open_dataset(out).attrs["stopped_at_s"] < 0.5
        return
    assert code == 3 and not out.exists()
    assert "no compatible configuration exists" in err and "pendulum length L = |C1C3| = 182 cm" in err
    assert main(["run", str(write(tmp_path, {**far, "on_failure": "mark"})), "-o", str(out)]) == 0
    ds = xr.open_dataset(out)
    assert ds.attrs["failed"] == 1 and "no compatible configuration" in ds.attrs["failure_message"]
    assert np.abs(ds["theta2"].values).max() < 90


RECORDS = Path(__file__).resolve().parents[1] / "config/studies/records"


def _records(tmp_path):
    for name in ("synthetic.AT2", "synthetic_y.AT2"):
        (tmp_path / name).write_bytes((RECORDS / name).read_bytes())


def test_the_summary_line_states_the_records_peaks_and_scale(tmp_path, capsys):
    _records(tmp_path)
    one = {**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": 2.0}}
    assert main(["run", str(write(tmp_path, one)), "-o", str(tmp_path / "a.nc")]) == 0
    line = capsys.readouterr().out
    assert "; record PGA = 0.699 g, PGV = 76.4 cm/s, PGD = 30 cm (scale 2)" in line
    pair = {**one, "excitation": {**one["excitation"], "file": ["synthetic.AT2", "synthetic_y.AT2"]}}
    assert main(["run", str(write(tmp_path, pair)), "-o", str(tmp_path / "b.nc")]) == 0
    assert ("; record 1 (synthetic.AT2): PGA = 0.699 g, PGV = 76.4 cm/s, PGD = 30 cm; 2 (synthetic_y.AT2): PGA = 0.6 g"
            in capsys.readouterr().out)
    # scaled over a period range: what is held at the target is the suite's mean (a record alone: its own)
    scale = {"to": "spectrum", "target": {"period": [0.1, 4.0], "sa": [0.3, 0.3]}, "periods": [1.0, 3.0],
             "fraction": 0.9, "suite_factor": 1.5}
    ranged = {**one, "excitation": {**one["excitation"], "scale": scale}}
    assert main(["run", str(write(tmp_path, ranged)), "-o", str(tmp_path / "c.nc")]) == 0
    attrs = xr.open_dataset(tmp_path / "c.nc").attrs
    assert (f"(scale {attrs['record_scale']:g}: its suite's mean spectrum at or above 0.9 x target over 1-3 s (5 %; a "
            f"record alone is its own suite), its fit {attrs['record_scaling_fit']:.4g} x the suite's factor 1.5)"
            in capsys.readouterr().out)


@pytest.mark.parametrize("changes, message", [
    # before: a Python traceback and exit 1
    ({"normals": "unsigned", "excitation": {"kind": "sine", "amplitude": 0.1, "omega": 6.0, "duration": 0.2,
                                            "azimuth": 30.0}},
     "normals: two-component ground motion runs the spatial models, which use signed normals only"),
    # before: accepted
    ({"excitation": {"kind": "record", "file": ["synthetic.AT2", "synthetic.AT2"]}},
     "record pair: .* are the same file: a pair is two different horizontal components"),
    # before: "PGA is nan g"
    ({"excitation": {"kind": "record", "file": "synthetic.AT2", "scale": 1.0e+308}},
     "scale 1e\\+308 makes the acceleration overflow"),
])
def test_defects_found_with_real_records_are_refused_with_exit_2(tmp_path, changes, message, capsys):
    _records(tmp_path)
    out = tmp_path / "out.nc"
    out.write_text("an older result")
    assert main(["run", str(write(tmp_path, {**CASE, **changes})), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert re.search(message, err), err
    # before: the older file stayed, as if it were this case's result
    assert not out.exists() and f"({out}, an older result there, was removed: it is not this case's)" in err


def test_two_identical_files_are_not_a_pair(tmp_path):
    _records(tmp_path)
    (tmp_path / "copy.AT2").write_bytes((tmp_path / "synthetic.AT2").read_bytes())
    with pytest.raises(CaseError, match="are two identical files"):
        case_from({**CASE, "excitation": {"kind": "record", "file": ["synthetic.AT2", "copy.AT2"]}}, tmp_path)


@pytest.mark.parametrize("capacity, scale, words", [("continue", 1.0, "residual stroke = "),
                                                    ("stop", 6.0, "stroke where the history ends (t = ")])
def test_a_cut_history_states_no_residual_stroke(tmp_path, capsys, capacity, scale, words):
    """Before, the stroke where capacity: stop cut the history was printed as its residual stroke."""
    _records(tmp_path)
    case = {**CASE, "model": "compliant", "structure": {"friction": 0.02}, "capacity": capacity,
            "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": scale}}
    assert main(["run", str(write(tmp_path, case)), "-o", str(tmp_path / "a.nc")]) == 0
    out = capsys.readouterr().out
    assert words in out and ("stopped_at_s" in xr.open_dataset(tmp_path / "a.nc").attrs) == (capacity == "stop")
