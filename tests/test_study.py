"""Studies from config: validation, chunking, batched = one-case results, failures, the workflow."""

import hashlib
import shutil
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import DELETE, changed, copy_project, snakemake

from dccss.case import CaseError
from dccss.excitation import Sine, step_times
from dccss.mechanics import models
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import NewtonOptions
from dccss.mechanics.summaries import summarize
from dccss.paper.prototypes import TABLE1
from dccss.studies import Study, combine, history_case, history_mapping, run_chunk

TINY = {
    "study": {"name": "tiny", "description": "test"},
    "prototype": "DFP1",
    "symmetric": True,
    "excitation": {"kind": "sine", "amplitude": 0.2, "omega": 30.0, "duration": 0.3},
    "dt": 0.01,
    "models": ["compliant", "stick_slip"],
    "sweep": {"alpha21": [8.0, 10.0], "h2": [0.12, 0.15, 0.18]},
    "chunk_size": 4,
    "histories": [{"alpha21": 10.0, "h2": 0.15}],
}


def tiny(**changes):
    return changed(TINY, **{k: DELETE if v is None else v for k, v in changes.items()})


def test_grid_and_chunks_cover_every_case_once():
    study = Study.from_config(tiny())
    assert study.grid.shape == (2, 3) and study.grid.n_cases == 6 and study.grid.n_chunks == 2
    cases = np.concatenate([study.grid.chunk(k) for k in range(study.grid.n_chunks)])
    assert np.array_equal(cases, np.arange(6))
    assert study.grid.point(4) == {"alpha21": 10.0, "h2": 0.15}
    g = study.grid.geometry(np.array([4]))
    assert g.alpha23[0] == pytest.approx(np.radians(10.0))  # symmetric: cap 23 follows cap 21


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_chunked_summaries_equal_one_case_runs(model):
    """The batched, chunked sweep gives the one-case path's results to 1e-12."""
    study = Study.from_config(tiny())
    combined = combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})
    for case in range(study.grid.n_cases):
        point = study.grid.point(case)
        g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": point["alpha21"], "alpha23": point["alpha21"],
                                     "h2": point["h2"]})
        t = step_times(Sine(0.2, 30.0, 0.3), 0.01)
        h = models.run(model, g, Sine(0.2, 30.0, 0.3).displacement(t))
        got = combined.sel(model=model, alpha21=point["alpha21"], h2=point["h2"])
        assert float(got["theta2_end"]) == pytest.approx(np.degrees(h["q"][-1, 5]), abs=1e-12)
        assert float(got["theta2_max_abs"]) == pytest.approx(np.degrees(np.abs(h["q"][:, 5]).max()), abs=1e-12)
        rise = h["q"][:, 7] - g.Ry3_compatible(0.0)
        assert float(got["rise_max"]) == pytest.approx(rise.max(), abs=1e-12)


def test_failed_case_is_marked_and_others_complete():
    """A pad shape with no stick-slip solution at this step size fails alone (NaN, flag, time)."""
    geometry = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.array([10.0, 12.0]),
                                        "alpha23": np.array([10.0, 12.0]), "h2": np.array([0.15, 0.10])})
    t = step_times(Sine(0.27, 30.0, 1.0), 0.01)
    Xg = Sine(0.27, 30.0, 1.0).displacement(t)
    out = summarize("stick_slip", geometry, Xg, options=NewtonOptions(on_failure="mark"), times=t)
    assert out["failed"].tolist() == [False, True]
    assert np.isnan(out["theta2_max_abs"][1]) and np.isfinite(out["theta2_max_abs"][0])
    assert out["failure_time"][1] == pytest.approx(0.16)
    with pytest.raises(Exception, match="did not converge in sticking"):
        summarize("stick_slip", geometry, Xg, times=t)  # the default policy stops


BAD = [
    (dict(colour="red"), r"unknown key\(s\) \['colour'\]"),
    (dict(dt=None), r"dt: missing: give the time step \(s\), or sweep it"),
    (dict(sweep__dt=[0.01, 0.5]), r"sweep.dt\[1\]: 0.5 s is larger than the excitation's duration"),
    (dict(sweep__dt=[0.01, -0.01]), r"sweep.dt\[1\]: must be > 0"),
    (dict(dt=None, sweep__dt=[0.01, 0.005]), r"histories\[0\]: no dt"),
    (dict(capacity="ignore"), r"capacity: must be one of \['continue', 'stop', 'error'\]"),
    (dict(chunk_size="many"), "chunk_size: expected an integer >= 1 or 'auto'"),
    (dict(dt=-0.01), "dt: must be > 0"),
    (dict(dt="1e-3"), "dt: expected a number, got the string '1e-3'"),
    (dict(sweep__h2=[]), "sweep.h2: the sweep axis is empty"),
    (dict(sweep__h3=[1.0]), "sweep: unknown axis 'h3'"),
    (dict(sweep__alpha23=[5.0]), "with symmetric: true, alpha23 follows alpha21"),
    (dict(sweep__alpha21=[8.0, 25.0]), "sweep point alpha21=25.0, h2=0.12: geometry parameter 'alpha21'"),
    (dict(sweep__alpha21={"start": 1, "stop": 2}), r"sweep.alpha21: missing key\(s\) \['num'\]"),
    (dict(models=["pendulum"]), "models\\[0\\]: must be one of"),
    (dict(chunk_size=0), "chunk_size: expected an integer >= 1"),
    (dict(prototype="DFP9"), "prototype: unknown prototype 'DFP9'"),
    (dict(histories=[{"alpha21": 10.0, "h9": 1}]), r"histories\[0\]: unknown key\(s\) \['h9'\]"),
    (dict(excitation={"kind": "record", "file": "missing.AT2"}), "excitation.file: record file .*missing.AT2"),
    (dict(on_failure="ignore"), "on_failure: must be one of"),
]


@pytest.mark.parametrize("changes, message", BAD, ids=[m[:40] for _, m in BAD])
def test_invalid_study_names_key(changes, message, tmp_path):
    with pytest.raises(CaseError, match=message):
        Study.from_config(tiny(**changes), tmp_path)


# --- the workflow -------------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["pad_shape", "ground_motion"])
def test_shipped_study_runs(name, shipped_study):
    work = shipped_study(name)
    ds = xr.open_dataset(work / f"results/studies/{name}/{name}.nc")
    for var in ("theta2_max_abs", "sticking_rotation_max", "rise_max", "rise_end", "theta2_end", "I_A_max",
                "capacity_exceeded", "newton_iterations_max", "failed"):
        assert var in ds and "units" in ds[var].attrs
    assert (work / f"figures/studies/{name}/maps.png").stat().st_size > 20_000
    assert (work / f"figures/studies/{name}/histories.png").exists()
    if name == "pad_shape":
        assert dict(ds.sizes) == {"model": 2, "alpha21": 25, "h2": 21}
        dfp1 = ds.sel(model="stick_slip").sel(alpha21=10.0, h2=0.15, method="nearest")
        assert int(dfp1["failed"]) == 0 and 5 < float(dfp1["sticking_rotation_max"]) < 40
    else:
        assert dict(ds.sizes) == {"model": 2, "prototype": 2, "scale": 3}
        assert int(ds["failed"].sum()) == 0
        assert (ds["theta2_max_abs"].diff("scale") > 0).all()  # a stronger record turns the pad more


@pytest.mark.slow
@pytest.mark.parametrize("change, message", [
    ({"sweep": {"h2": []}}, "sweep.h2"),
    ({"dt": -0.01}, "dt"),
    ({"colour": "red"}, "colour"),
    ({"excitation": {"kind": "record", "file": "nope.AT2"}}, "nope.AT2"),
    ({"excitation": {"kind": "record", "file": "bad.AT2"}}, "bad.AT2"),
    ({"sweep": {"alpha21": [8.0, 30.0]}}, "alpha21"),
])
def test_bad_study_fails_before_any_job(tmp_path, change, message):
    work = copy_project(tmp_path)
    (work / "bad.AT2").write_text("PEER\nx\nACCELERATION IN G\nNPTS=   3, DT=  .0100 SEC\n .1E-01 nan .1E-01\n")
    (work / "bad.yaml").write_text(yaml.safe_dump({**TINY, **change}))
    run = snakemake(work, "--configfile", "bad.yaml")
    assert run.returncode != 0
    assert message in run.stdout + run.stderr
    assert not (work / "results").exists() and not (work / "logs").exists()


def digest(root: Path):
    return {str(p.relative_to(root)): hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(root.rglob("*.nc"))}


@pytest.fixture(scope="module")
def tiny_run(tmp_path_factory):
    """The TINY study run in full with the default profile, once for the tests that read it (one worker:
    conftest groups the tests using this fixture)."""
    work = copy_project(tmp_path_factory.mktemp("tiny"))
    (work / "tiny.yaml").write_text(yaml.safe_dump(TINY))
    run = snakemake(work, "--configfile", "tiny.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    return work


@pytest.mark.slow
def test_cluster_generic_profile_matches_local_run(tiny_run, tmp_path):
    """Every job through a scheduler-style submit script: same files as a local run (the results: the
    plots, drawn from them by the same rule, are left out)."""
    targets = ["results/studies/tiny/tiny.nc", *(f"results/studies/tiny/histories/{m}_0.nc" for m in TINY["models"])]
    work = copy_project(tmp_path)
    (work / "tiny.yaml").write_text(yaml.safe_dump(TINY))
    run = snakemake(work, *targets, "--configfile", "tiny.yaml", profile="profiles/cluster-local")
    assert run.returncode == 0, run.stderr[-3000:]
    local = digest(tiny_run / "results/studies/tiny")
    assert len(local) == 7  # 2 models x 2 chunks, the combined file, 2 histories
    assert digest(work / "results/studies/tiny") == local


def test_dt_axis_runs_each_step_size_as_its_own_batch():
    study = Study.from_config(tiny(dt=None, sweep={"dt": [0.01, 0.005], "alpha21": [8.0, 10.0]}, histories=[
        {"dt": 0.005, "alpha21": 10.0}], chunk_size=3))
    assert study.grid.shape == (2, 2) and study.grid.n_chunks == 2
    assert [sorted(study.grid.dt_of(study.grid.chunk(k))) for k in (0, 1)] == [[0.005, 0.005, 0.01], [0.01]]
    combined = combine(study, {m: [run_chunk(study, m, k) for k in range(2)] for m in study.models})
    assert combined["dt"].attrs["units"] == "s" and dict(combined.sizes) == {"model": 2, "dt": 2, "alpha21": 2}
    for dt in (0.01, 0.005):
        for alpha21 in (8.0, 10.0):
            g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": alpha21, "alpha23": alpha21})
            t = step_times(Sine(0.2, 30.0, 0.3), dt)
            h = models.run("stick_slip", g, Sine(0.2, 30.0, 0.3).displacement(t))
            got = combined.sel(model="stick_slip", dt=dt, alpha21=alpha21)
            assert float(got["theta2_end"]) == pytest.approx(np.degrees(h["q"][-1, 5]), abs=1e-12)
    mapping = history_mapping(study, 0, "compliant")
    assert mapping["dt"] == 0.005 and mapping["on_failure"] == "mark" and mapping["capacity"] == "continue"


@pytest.mark.parametrize(("cases", "chunks"), [(15, [15]), (16, [16]), (40, [16, 16, 8]), (64, [16] * 4),
                                               (100, [25] * 4), (101, [26, 26, 26, 23])])
def test_auto_chunks_are_a_quarter_of_the_sweep_of_at_least_sixteen_cases(cases, chunks):
    """Four jobs keep both cores busy; a job of fewer than 16 small cases costs more to start than to run."""
    study = Study.from_config(tiny(chunk_size=None, sweep__h2=[0.15], sweep__alpha21={"start": 8.0, "stop": 10.0,
                                                                                      "num": cases}))
    assert study.grid.n_cases == cases and [len(study.grid.chunk(k)) for k in range(study.grid.n_chunks)] == chunks


def test_history_mapping_is_a_case_with_the_points_scale():
    study = Study.from_config(tiny(sweep={"scale": [0.5, 1.0]}, histories=[{"scale": 0.5}], capacity="stop"))
    mapping = history_mapping(study, 0, "stick_slip")
    assert mapping["excitation"] == {**TINY["excitation"], "scale": 0.5} and mapping["capacity"] == "stop"
    ds = history_case(study, 0, "stick_slip").run()
    full = history_case(Study.from_config(tiny(sweep={"scale": [1.0]}, histories=[{"scale": 1.0}])), 0, "stick_slip")
    assert np.allclose(ds["Xg"].values, 0.5 * full.run()["Xg"].values, rtol=1e-15, atol=0)


def planned(work, configfile):
    """{rule: count} of the jobs `snakemake -n` would run."""
    run = snakemake(work, "--configfile", configfile, "-n")
    assert run.returncode == 0, run.stderr[-2000:]
    lines = (run.stdout + run.stderr).splitlines()
    if "Job stats:" not in lines:
        return {}
    table = lines[lines.index("Job stats:") + 3:]
    jobs = {}
    for line in table:
        parts = line.split()
        if len(parts) != 2 or parts[0] == "total":
            break
        jobs[parts[0]] = int(parts[1])
    jobs.pop("all", None)
    return jobs


@pytest.mark.slow
def test_a_job_reruns_only_when_its_part_of_the_study_changes(tiny_run, tmp_path):
    work = shutil.copytree(tiny_run, tmp_path / "work", symlinks=True)  # dry runs below: the shared run untouched
    assert planned(work, "tiny.yaml") == {}
    moved = shutil.copytree(work, tmp_path / "moved", symlinks=True)  # times kept
    assert planned(moved, "tiny.yaml") == {}  # a project moved whole reruns nothing (the folder was a parameter)
    edits = {
        "description": (dict(study={"name": "tiny", "description": "another text"}), {"study_plots": 1}),
        "marks": (dict(marks={"here": {"alpha21": 8.0, "h2": 0.12}}), {"study_plots": 1}),
        "histories": (dict(histories=TINY["histories"] + [{"alpha21": 8.0, "h2": 0.12}]),
                      {"study_history": 2, "study_plots": 1}),
        "sweep": (dict(sweep={"alpha21": [8.0, 10.0], "h2": [0.12, 0.15, 0.2]}),
                  {"study_chunk": 4, "study_combine": 1, "study_plots": 1}),
        "dt": (dict(dt=0.005), {"study_chunk": 4, "study_combine": 1, "study_history": 2, "study_plots": 1}),
        "models": (dict(models=["compliant"]), {"study_combine": 1, "study_plots": 1}),
    }
    for name, (change, expected) in edits.items():
        (work / "edited.yaml").write_text(yaml.safe_dump({**TINY, **change}))
        assert planned(work, "edited.yaml") == expected, name


FAILING = {**TINY, "excitation": {"kind": "sine", "amplitude": 0.27, "omega": 30.0, "duration": 0.3},
           "sweep": {"alpha21": [10.0, 12.0], "h2": [0.10, 0.15]}, "histories": [{"alpha21": 12.0, "h2": 0.10}],
           "chunk_size": 2}


@pytest.mark.slow
def test_a_case_without_solution_is_marked_and_the_study_completes(tmp_path):
    work = copy_project(tmp_path)
    (work / "failing.yaml").write_text(yaml.safe_dump({**FAILING, "on_failure": "mark"}))
    run = snakemake(work, "--configfile", "failing.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    combined = xr.open_dataset(work / "results/studies/tiny/tiny.nc")
    assert int(combined["failed"].sel(model="stick_slip", alpha21=12.0, h2=0.10)) == 1
    history = xr.open_dataset(work / "results/studies/tiny/histories/stick_slip_0.nc")
    assert history.attrs["failed"] == 1 and history.attrs["failure_time_s"] == pytest.approx(0.16)
    assert float(history["t"][-1]) == pytest.approx(0.15) and "reduce dt" in history.attrs["failure_message"]
    assert "did not converge in sticking" in (work / "logs/studies/tiny/histories_stick_slip.log").read_text()
    assert "1 failed" in (work / "logs/studies/tiny/stick_slip_1.log").read_text()
    assert (work / "figures/studies/tiny/histories.png").exists()


@pytest.mark.slow
def test_a_failing_job_leaves_the_full_message_in_its_log(tmp_path):
    work = copy_project(tmp_path)
    (work / "failing.yaml").write_text(yaml.safe_dump({**FAILING, "on_failure": "error", "histories": []}))
    # both stick-slip chunks hold a case without solution: on one core they run one after the other,
    # and the first to fail stops the workflow (on two, both may already be running)
    run = snakemake(work, "--configfile", "failing.yaml", "--cores", "1")
    assert run.returncode != 0
    assert "did not converge in sticking" in run.stderr
    logs = [p.read_text() for p in (work / "logs/studies/tiny").glob("stick_slip_*.log")]
    failed = [log for log in logs if "Traceback" in log]
    assert len(failed) == 1, "the first failing job stops the workflow"
    assert "sweep point {'alpha21': " in failed[0] and "'h2': 0.1} (stick_slip)" in failed[0]
    assert "did not converge in sticking" in failed[0] and "batch index (0,)" in failed[0]


def test_histories_all_runs_every_point_in_full():
    study = Study.from_config(tiny(histories="all", sweep={"alpha21": [8.0, 10.0], "dt": [0.01, 0.005]}))
    assert study.histories == [study.grid.point(i) for i in range(4)]
    assert [history_mapping(study, i, "compliant")["dt"] for i in range(4)] == [0.01, 0.005, 0.01, 0.005]
    with pytest.raises(CaseError, match="histories: expected a list of sweep points or 'all'"):
        Study.from_config(tiny(histories="some"))


def test_animations_are_histories():
    study = Study.from_config(tiny(animate=[{"alpha21": 10.0, "h2": 0.15}]))
    assert study.animate == [0]
    assert Study.from_config(tiny(animate="all")).animate == [0]
    with pytest.raises(CaseError, match=r"animate\[0\]: \{'alpha21': 8.0, 'h2': 0.15\} is not one of the histories"):
        Study.from_config(tiny(animate=[{"alpha21": 8.0, "h2": 0.15}]))


@pytest.mark.parametrize("sweep, mark, drawn", [
    ({"alpha21": [8.0, 10.0], "h2": [0.12, 0.15]}, {"alpha21": 10.0},
     r"\['alpha21', 'h2'\]; give a value for \['h2'\]"),
    ({"alpha21": [8.0, 10.0], "prototype": ["DFP1", "DFP2"]}, {"prototype": "DFP1"}, r"\['alpha21'\]"),
])
def test_a_mark_that_cannot_be_placed_is_refused(sweep, mark, drawn):
    """Before, a mark not naming every drawn axis was silently not drawn."""
    from dccss.studies import StudyError

    config = {"study": {"name": "m"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "sine", "amplitude": 0.1, "omega": 6.0, "duration": 0.2},
              "sweep": sweep, "marks": {"here": mark}}
    with pytest.raises(StudyError, match=rf"marks\.here: gives .* but the plots draw the summaries over {drawn}"):
        Study.from_config(config)


@pytest.mark.parametrize("changes, message", [
    ({"theta2_0": 95.0}, r"theta2_0 95.0 is greater than or equal to the maximum of 90"),
    ({"sweep": {"theta2_0": [-10.0, 90.0]}}, r"sweep\.theta2_0\[1\]: a compatible start needs \|theta2_0\| < 90 "
                                             r"degrees, got 90"),
])
def test_a_start_turned_by_90_degrees_or_more_is_refused(changes, message):
    """Before, such a start ran (400 degrees turned to about 40 after one step) or failed with advice on the
    excitation."""
    with pytest.raises(CaseError, match=message):
        Study.from_config(tiny(**changes))


def test_a_capacity_amplitude_is_each_swept_devices_own():
    """amplitude: capacity is R1 sin(alpha1 - alpha21) of each case's device, as the history of that point
    takes it (before, the sweep took the base device's for every case)."""
    from dccss.studies import run_chunk

    study = Study.from_config(tiny(excitation={"kind": "sine", "amplitude": "capacity", "omega": 30.0,
                                               "duration": 0.3}, chunk_size=6))
    part = run_chunk(study, "compliant", 0)
    for i, point in enumerate(study.grid.point(k) for k in range(study.grid.n_cases)):
        device = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha23": point["alpha21"], **point})
        t = step_times(Sine(device.capacity1, 30.0, 0.3), 0.01)
        alone = summarize("compliant", device, Sine(device.capacity1, 30.0, 0.3).displacement(t)[:, None], times=t)
        assert float(part["theta2_max_abs"].values.ravel()[i]) == pytest.approx(float(alone["theta2_max_abs"][0]),
                                                                                 rel=1e-12), point
    history = history_case(study, 0, "compliant")
    assert history.excitation.amplitude == Geometry.from_degrees(
        **{**TABLE1["DFP1"], "alpha21": 10.0, "alpha23": 10.0, "h2": 0.15}).capacity1


@pytest.mark.parametrize("sweep, message", [
    ({"h2": [0.12, 0.15, 0.12]}, r"sweep\.h2: 0\.12 is given twice"),
    ({"prototype": ["DFP1", "DFP1"]}, r"sweep\.prototype: 'DFP1' is given twice"),
])
def test_a_sweep_value_given_twice_is_refused(sweep, message):
    """Before, a numeric one computed its cases twice and a prototype one failed in the plots' job."""
    with pytest.raises(CaseError, match=message):
        Study.from_config(tiny(sweep=sweep, histories=[]))
