"""Record suites: a `record` sweep axis, the suite statistics, and jobs per record in the workflow."""

import re

import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import ROOT, copy_project, snakemake

from dccss.records import read_at2, write_at2
from dccss.studies import Study, StudyError, combine, history_case, run_chunk

NAMES = ("RSN11_NORTH", "RSN12_SOUTH", "RSN13_EAST")


@pytest.fixture
def suite(tmp_path):
    """Three short PEER-format records (shapes of the synthetic pair, of different lengths) in tmp_path/records."""
    folder = tmp_path / "records"
    folder.mkdir()
    dt, a = read_at2(ROOT / "config/studies/records/synthetic.AT2")
    _, b = read_at2(ROOT / "config/studies/records/synthetic_y.AT2")
    for name, acc in zip(NAMES, (a[:900], b[:1000], 0.7 * a[::-1][:800])):
        write_at2(folder / f"{name}.AT2", dt, acc)
    return tmp_path


CONFIG = {"study": {"name": "suite"}, "prototype": "DFP1", "excitation": {"kind": "record", "baseline": "linear"},
          "dt": 0.01, "models": ["compliant", "stick_slip"],
          "sweep": {"record": ["records/*.AT2"], "scale": [1.0, 2.5]},
          "histories": [{"record": "RSN12_SOUTH", "scale": 2.5}]}


def _combined(study):
    return combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})


def test_a_record_axis_names_each_record_and_processes_it_once(suite):
    study = Study.from_config(CONFIG, suite)
    assert list(study.axes) == ["record", "scale"] and list(study.axes["record"]) == list(NAMES)
    assert study.grid.n_chunks == 3 and all(study.grid.record_of(study.grid.chunk(k)) == NAMES[k] for k in range(3))
    ds = _combined(study)
    assert list(ds["record"].values) == list(NAMES) and ds.sizes["statistic"] == 5
    # each record's cases are those of a study of that record alone
    for name in NAMES:
        alone = Study.from_config({**CONFIG, "excitation": {**CONFIG["excitation"], "file": f"records/{name}.AT2"},
                                   "sweep": {"scale": [1.0, 2.5]}, "histories": [], "chunk_size": 2}, suite)
        one = _combined(alone)
        for var in ("theta2_max_abs", "rise_max", "clearance_min"):
            assert np.array_equal(ds[var].sel(record=name).values, one[var].values, equal_nan=True), (name, var)
    assert ds["record_pga"].attrs["units"] == "m s-2" and ds["record_pgd"].sel(record="RSN12_SOUTH") > 0
    case = history_case(study, 0, "stick_slip")
    assert case.excitation.source.endswith("RSN12_SOUTH.AT2") and case.excitation.scale == 2.5


def test_the_suite_statistics_equal_numpys_on_the_records_values(suite):
    study = Study.from_config({**CONFIG, "structure": {"friction": 0.04}}, suite)
    ds = _combined(study)
    for name in ("theta2_max_abs", "rise_max", "stroke_max_abs", "shear_ratio_max_abs"):
        for model in study.models:
            for scale in (1.0, 2.5):
                values = ds[name].sel(model=model, scale=scale).values
                stats = ds[f"{name}_suite"].sel(model=model, scale=scale)
                assert float(stats.sel(statistic="mean")) == pytest.approx(np.mean(values), rel=1e-14)
                assert float(stats.sel(statistic="median")) == pytest.approx(np.median(values), rel=1e-14)
                assert float(stats.sel(statistic="max")) == np.max(values)
                assert float(stats.sel(statistic="min")) == np.min(values)
                logs = np.log(values)
                assert float(stats.sel(statistic="p84_lognormal")) == pytest.approx(
                    np.exp(logs.mean() + logs.std(ddof=1)), rel=1e-13)
    # a minimum's design value is its smallest: the record nearest its ring
    clearance = ds["clearance_min"].sel(model="compliant", scale=2.5).values
    assert float(ds["clearance_min_suite"].sel(model="compliant", scale=2.5, statistic="min")) == np.min(clearance)
    counted = ds["records_capacity_exceeded"].sel(model="compliant", scale=2.5)
    assert int(counted) == int(ds["capacity_exceeded"].sel(model="compliant", scale=2.5).sum())
    assert float(ds["records_capacity_exceeded_fraction"].sel(model="compliant", scale=2.5)) == int(counted) / 3
    assert "capacity_time_suite" not in ds and "failure_time_suite" not in ds  # event times are no demand
    # an end value, signed for one component, by its size: records pushed to either side do not cancel
    for name in ("stroke_end", "theta2_end"):
        values = ds[name].sel(model="stick_slip", scale=2.5).values
        stats = ds[f"{name}_suite"].sel(model="stick_slip", scale=2.5)
        assert (values < 0).any() and (values > 0).any()
        assert float(stats.sel(statistic="mean")) == pytest.approx(np.mean(np.abs(values)), rel=1e-14)
        assert float(stats.sel(statistic="max")) == np.max(np.abs(values))
        assert np.isfinite(float(stats.sel(statistic="p84_lognormal")))


def test_failed_records_are_counted_and_left_out_of_the_statistics(suite):
    study = Study.from_config({**CONFIG, "sweep": {"record": ["records/*.AT2"], "scale": [1.0, 9.0]}}, suite)
    ds = _combined(study)
    failed = ds["failed"].sel(model="stick_slip", scale=9.0).values.astype(bool)
    assert failed.any()
    kept = ds["theta2_max_abs"].sel(model="stick_slip", scale=9.0).values[~failed]
    stats = ds["theta2_max_abs_suite"].sel(model="stick_slip", scale=9.0)
    assert int(ds["records_failed"].sel(model="stick_slip", scale=9.0)) == failed.sum()
    assert int(ds["records_counted"].sel(model="stick_slip", scale=9.0)) == (~failed).sum()
    if kept.size:
        assert float(stats.sel(statistic="mean")) == pytest.approx(kept.mean(), rel=1e-14)


def test_the_structures_statistics_keep_the_records_whose_pad_fails(suite):
    """The structure's stroke does not depend on the pad: a record whose pad run fails keeps its stroke in
    the suite's statistics (before, it was NaN and left out: the records of largest stroke were dropped
    from the design values)."""
    study = Study.from_config({**CONFIG, "structure": {"friction": 0.01}, "capacity": "error",
                               "sweep": {"record": ["records/*.AT2"], "scale": [1.0, 6.0]}}, suite)
    ds = _combined(study)
    sel = {"model": "stick_slip", "scale": 6.0}
    failed = ds["failed"].sel(sel).values.astype(bool)
    assert failed.any() and not failed.all()
    stroke = ds["stroke_max_abs"].sel(sel).values
    assert np.isfinite(stroke).all() and stroke[failed].max() > stroke[~failed].max()
    stats = ds["stroke_max_abs_suite"].sel(sel)
    assert float(stats.sel(statistic="max")) == stroke.max()
    assert float(stats.sel(statistic="mean")) == pytest.approx(stroke.mean(), rel=1e-14)
    assert int(ds["records_counted"].sel(sel)) == (~failed).sum()  # the pad's


@pytest.mark.parametrize("sweep, message", [
    ({"record": []}, r"sweep\.record: expected a non-empty list"),
    ({"record": ["records/*.DT2"]}, r"sweep\.record\[0\]: the pattern 'records/\*\.DT2' matches no file"),
    ({"record": ["records/RSN11_NORTH.AT2", "records/*.AT2"]}, r"two records are named 'RSN11_NORTH'"),
    ({"record": [["records/RSN11_NORTH.AT2"]]}, r"sweep\.record\[0\]: a pair is a list of two files"),
    ({"record": [3]}, r"sweep\.record\[0\]: expected a file, a pair \[x, y\], a pattern, a mapping"),
])
def test_bad_record_axes_are_refused(suite, sweep, message):
    with pytest.raises(StudyError, match=message):
        Study.from_config({**CONFIG, "sweep": sweep, "histories": []}, suite)
    with pytest.raises(StudyError, match="excitation.file: the records are the sweep's"):
        Study.from_config({**CONFIG, "excitation": {"kind": "record", "file": "records/RSN11_NORTH.AT2"}}, suite)


def test_an_excitation_error_of_a_suite_names_the_key_and_the_record(suite):
    """An error in the study's excitation keys names the key the file has and the record (before: a
    window beyond a record was reported as ``sweep.record[NAME].window``); one in a file names sweep.record."""
    window = {**CONFIG, "excitation": {**CONFIG["excitation"], "window": [0.0, 8.5]}}
    with pytest.raises(StudyError, match=r"^excitation\.window: .* \(record 'RSN13_EAST'\)$"):
        Study.from_config(window, suite)
    (suite / "records" / "RSN14_WEST.AT2").write_text("not a record\n")
    with pytest.raises(StudyError, match=r"^sweep\.record: .*RSN14_WEST\.AT2.* \(record 'RSN14_WEST'\)$"):
        Study.from_config(CONFIG, suite)


def test_a_pair_is_named_by_its_station(suite):
    from dccss.studies.spec import record_entries

    pairs = record_entries([["RSN6_IMPVALL.I_I-ELC180.AT2", "RSN6_IMPVALL.I_I-ELC270.AT2"], ["a_x.AT2", "b_y.AT2"],
                            ["S01_STA01000.AT2", "S01_STA01090.AT2"], ["A000.AT2", "B090.AT2"]], suite)
    # the digit 000 and 090 share is not the station's (it was named S01_STA010)
    assert list(pairs) == ["RSN6_IMPVALL.I_I-ELC", "a_x+b_y", "S01_STA01", "A000+B090"]


def test_a_suite_history_names_its_record_and_a_swept_friction_its_key(suite):
    """Before, a history without a record passed the check and its workflow job failed ("excitation:
    missing key(s) ['file']"); a bad first sweep.friction was reported as structure.friction."""
    with pytest.raises(StudyError, match=r"histories\[0\]: no record: a suite's history names one of its records "
                                         r"\['RSN11_NORTH', 'RSN12_SOUTH', 'RSN13_EAST'\]"):
        Study.from_config({**CONFIG, "histories": [{"scale": 2.5}]}, suite)
    with pytest.raises(StudyError, match=r"sweep\.friction\[0\]: -0\.01 is outside"):
        Study.from_config({**CONFIG, "sweep": {**CONFIG["sweep"], "friction": [-0.01, 0.05]}}, suite)


def test_a_suite_of_pairs_is_a_study_and_runs_on_a_structure(suite):
    """Pairs [x, y] on the record axis (the study file's schema took single files only): each pair is
    one record, named by its station, and runs in two components."""
    for name in NAMES[:2]:
        dt, a = read_at2(suite / "records" / f"{name}.AT2")
        write_at2(suite / "records" / f"{name}_X.AT2", dt, a)
        write_at2(suite / "records" / f"{name}_Y.AT2", dt, 0.5 * a)
    config = {**CONFIG, "structure": {"friction": 0.04},
              "sweep": {"record": [[f"records/{n}_X.AT2", f"records/{n}_Y.AT2"] for n in NAMES[:2]], "scale": [1.0]},
              "histories": [{"record": "RSN12", "scale": 1.0}]}
    with pytest.raises(StudyError, match=r"histories\[0\]\.record: 'RSN12' is not on the sweep axis "
                                         r"\['RSN11_NORTH', 'RSN12_SOUTH'\]"):
        Study.from_config(config, suite)
    study = Study.from_config({**config, "histories": [{"record": "RSN12_SOUTH", "scale": 1.0}]}, str(suite))  # a str
    assert list(study.axes["record"]) == ["RSN11_NORTH", "RSN12_SOUTH"]
    ds = _combined(study)
    # (a, a / 2) moves along one line with c = √1.25 times a's acceleration: the stroke of a alone
    # under the friction μ / c, times c
    c = np.sqrt(1.25)
    alone = _combined(Study.from_config({**CONFIG, "structure": {"friction": 0.04 / c},
                                         "sweep": {"record": [f"records/{n}.AT2" for n in NAMES[:2]], "scale": [1.0]},
                                         "histories": []}, suite))
    assert np.all(ds["stroke_max_abs"].values > 0.01)
    assert np.allclose(ds["stroke_max_abs"].values, c * alone["stroke_max_abs"].values, rtol=1e-9)
    # the suite says it is bidirectional (its maps then name the pad's tilt, not θ², as a single pair's
    # do; before, a suite's dataset had no excitation_components) and names its one device's pendulum
    assert ds.attrs["excitation_components"] == 2 and alone.attrs["excitation_components"] == 1
    from dccss.mechanics.geometry import Geometry
    from dccss.mechanics.structure import period
    from dccss.paper.prototypes import TABLE1
    from dccss.studies import plots

    L = float(Geometry.from_degrees(**TABLE1["DFP1"]).L)
    assert ds.attrs["structure_pendulum_length_m"] == L and ds.attrs["structure_period_s"] == period(L)
    title = [t.get_text() for t in plots.maps(ds, {}, "suite").findobj(lambda a: hasattr(a, "get_text"))]
    assert any("tilt" in t for t in title) and not any("θ²" in t for t in title)


def _project(suite):
    """A copy of the project with the suite's records in config/studies/records_suite."""
    (suite / "work").mkdir()
    work = copy_project(suite / "work")
    (work / "config/studies/records_suite").mkdir(parents=True)
    for name in NAMES:
        source = suite / "records" / f"{name}.AT2"
        (work / "config/studies/records_suite" / f"{name}.AT2").write_bytes(source.read_bytes())
    return work


@pytest.mark.slow
def test_a_suite_study_runs_through_snakemake_with_jobs_per_record(suite):
    work = _project(suite)
    study_file = work / "config/studies/suite.yaml"
    # the suite drives a structure, its damping swept: both axes through the workflow
    config = {**CONFIG, "structure": {"friction": 0.05},
              "sweep": {"record": ["records_suite/RSN11_NORTH.AT2", "records_suite/RSN12_SOUTH.AT2"],
                        "damping": [0.0, 0.1]}, "histories": [{"record": "RSN12_SOUTH", "damping": 0.1}]}
    study_file.write_text(yaml.safe_dump(config))
    run = snakemake(work, "--configfile", "config/studies/suite.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    ds = xr.open_dataset(work / "results/studies/suite/suite.nc")
    assert list(ds["record"].values) == ["RSN11_NORTH", "RSN12_SOUTH"] and list(ds["damping"].values) == [0.0, 0.1]
    stroke = ds["stroke_max_abs"].sel(model="compliant").values
    assert np.all(stroke[:, 1] < stroke[:, 0])  # damping lowers the peak stroke
    history = xr.open_dataset(work / "results/studies/suite/histories/compliant_0.nc")
    assert history.attrs["structure_damping"] == 0.1 and history.attrs["record_source"] == "RSN12_SOUTH.AT2"
    chunks = sorted(p.name for p in (work / "results/studies/suite/chunks").iterdir())
    assert chunks == [f"{m}_{r}.0.nc" for m in ("compliant", "stick_slip") for r in ("RSN11_NORTH", "RSN12_SOUTH")]
    assert (work / "figures/studies/suite/maps.png").is_file()
    # adding a record runs its jobs and the combination, not the other records' chunks again
    config["sweep"]["record"].append("records_suite/RSN13_EAST.AT2")
    study_file.write_text(yaml.safe_dump(config))
    dry = snakemake(work, "--configfile", "config/studies/suite.yaml", "--dry-run", "--quiet", "rules")
    assert dry.returncode == 0, dry.stderr[-2000:]
    plan = dry.stdout + dry.stderr
    assert "study_chunk" in plan
    run = snakemake(work, "results/studies/suite/suite.nc", "--configfile", "config/studies/suite.yaml")  # not redrawn
    assert run.returncode == 0, run.stderr[-3000:]
    rerun = re.findall(r"^\s*output: results/studies/suite/chunks/(\S+)\.nc$", run.stdout + run.stderr, re.MULTILINE)
    assert sorted(rerun) == ["compliant_RSN13_EAST.0", "stick_slip_RSN13_EAST.0"], rerun
    ds = xr.open_dataset(work / "results/studies/suite/suite.nc")
    assert list(ds["record"].values) == ["RSN11_NORTH", "RSN12_SOUTH", "RSN13_EAST"]
    assert np.allclose(ds["theta2_max_abs_suite"].sel(statistic="mean").values,
                       ds["theta2_max_abs"].mean("record").values, rtol=1e-14)


def test_a_suite_scaled_to_a_spectrum_has_the_target_at_its_period(suite):
    from dccss import spectra
    from dccss.records import G

    target = {"to": "spectral_acceleration", "period": 2.0, "damping": 0.05, "target": 0.25}
    study = Study.from_config({**CONFIG, "excitation": {**CONFIG["excitation"], "scale": target},
                               "sweep": {"record": ["records/*.AT2"], "friction": [0.03, 0.06]},
                               "histories": []}, suite)
    for name, excitation in study.records.items():
        sa = spectra.spectral_acceleration(excitation, 2.0, 0.05)
        assert abs(sa / G / 0.25 - 1) < 1e-6, name
    ds = _combined(study)
    assert ds["stroke_max_abs_suite"].sizes == {"statistic": 5, "model": 2, "friction": 2}
    for scale in (target, RANGE):  # a scale axis would multiply the scaling to a target again
        with pytest.raises(StudyError, match=r"sweep.scale: the records are scaled to a target spectrum or spectral "
                                             r"acceleration \(excitation.scale\)"):
            Study.from_config({**CONFIG, "excitation": {**CONFIG["excitation"], "scale": scale}}, suite)


def test_a_suite_of_tables(tmp_path):
    """The record axis takes displacement tables too, named by their stems."""
    t = np.linspace(0.0, 4.0, 401)
    for k, name in enumerate(("T1", "T2")):
        np.savetxt(tmp_path / f"{name}.csv", np.column_stack([t, (0.05 + 0.03 * k) * np.sin(2.5 * t)]),
                   delimiter=",", header="time,displacement", comments="")
    config = {"study": {"name": "tables"}, "prototype": "DFP1", "excitation": {"kind": "table"}, "dt": 0.01,
              "models": ["compliant"], "sweep": {"record": ["T*.csv"], "scale": [1.0, 2.0]}}
    study = Study.from_config(config, tmp_path)
    ds = _combined(study)
    assert list(ds["record"].values) == ["T1", "T2"]
    assert np.allclose(ds["record_pgd"].values, [0.05, 0.08], rtol=1e-3) and np.isnan(ds["record_pga"].values).all()
    theta = ds["theta2_max_abs"].sel(model="compliant", scale=1.0).values
    L = float(study.grid.geometry([0]).L[0])
    assert np.allclose(np.radians(theta), np.arcsin(np.array([0.05, 0.08]) / L), rtol=1e-4)


def test_a_suite_scaled_to_a_spectrum_keeps_each_records_factor(suite):
    """Each record's own scale factor and unscaled spectral acceleration are in the combined dataset (they were
    only in the chunks' attributes)."""
    spec = {"to": "spectral_acceleration", "period": 1.0, "target": 0.2}
    study = Study.from_config({**CONFIG, "excitation": {**CONFIG["excitation"], "scale": spec},
                               "sweep": {"record": ["records/*.AT2"]}, "models": ["compliant"], "histories": []},
                              suite)
    ds = _combined(study)
    from dccss.records import G

    # in m s-2: to a CF reader "g" is the gram
    sa = ds["record_sa_unscaled"]
    assert sa.attrs["units"] == "m s-2" and sa.attrs["scaled_to_sa_g"] == 0.2
    for name in NAMES:
        a = study.records[name].attrs()
        assert float(ds["record_scale"].sel(record=name)) == a["record_scale"]
        assert float(ds["record_sa_unscaled"].sel(record=name)) == a["record_sa_unscaled_g"] * G
        assert a["record_scale"] * a["record_sa_unscaled_g"] == pytest.approx(0.2, rel=1e-12)
    assert len(set(ds["record_scale"].values)) == 3  # a factor of each record's own


def test_a_rotation_given_twice_is_refused(suite):
    """Before, the sweep silently overrode excitation.rotation (and the chunks' attributes kept the latter)."""
    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "file": ["records/RSN11_NORTH.AT2",
                                                                        "records/RSN12_SOUTH.AT2"], "rotation": 30.0,
                                                 "window": [0.0, 8.0]},
              "sweep": {"rotation": [0.0, 30.0]}, "histories": []}
    with pytest.raises(StudyError, match=r"sweep\.rotation: the excitation gives a rotation itself"):
        Study.from_config(config, suite)


RANGE = {"to": "spectrum", "target": {"period": [0.1, 1.0, 2.0, 4.0], "sa": [0.5, 0.5, 0.25, 0.125]},
         "periods": [0.8, 2.5], "fraction": 0.9}


def test_a_suite_scaled_over_a_period_range_has_its_mean_at_the_target(suite):
    """Codes' scaling: the suite's mean spectrum (each record's computed again from its scaled record) is at
    or above fraction x target over the range and touches it; a chunk's and a history's record (their
    spec holds that record alone, with the suite's factor) has the factor the whole suite gives it."""
    from dccss import spectra
    from dccss.records import G
    from dccss.studies import sweep_spec

    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "scale": RANGE}, "sweep": {"record": ["records/*.AT2"]},
              "models": ["compliant"], "histories": [{"record": "RSN13_EAST"}]}
    study = Study.from_config(config, suite)
    grid = spectra.range_periods(0.8, 2.5, RANGE["target"]["period"])
    sa = np.array([spectra.spectrum(e, grid) for e in study.records.values()]) / G
    ratio = sa.mean(axis=0) / (0.9 * np.interp(grid, RANGE["target"]["period"], RANGE["target"]["sa"]))
    assert ratio.min() == pytest.approx(1.0, rel=1e-9) and np.all(ratio > 1 - 1e-9)
    factors = {name: e.attrs()["record_scale"] for name, e in study.records.items()}
    assert len(set(factors.values())) == 3 and study.suite_factor != 1.0
    for name, entry in study.record_entries.items():
        alone = Study.from_config(sweep_spec(config, ["compliant"], entry, study.suite_factor), suite)
        assert alone.records[name].attrs()["record_scale"] == factors[name]
    assert history_case(study, 0, "compliant").excitation.scale == factors["RSN13_EAST"]
    ds = _combined(study)
    assert np.array_equal(ds["record_scale"].values, list(factors.values()))
    mean = ds["record_sa"].mean("record") / (0.9 * ds["target_sa"])
    assert float(mean.min()) == pytest.approx(1.0, rel=1e-12)
    assert ds["record_sa"].attrs["scaling_suite_factor"] == study.suite_factor
    assert np.allclose(ds["record_sa"].values / G, sa, rtol=1e-9)  # the factor times the spectrum: the scaled one's
    assert np.array_equal(ds["record_scale"].values, ds["record_scale_fit"].values * study.suite_factor)


def test_a_suite_scaled_by_one_factor_keeps_the_records_relative_intensities(suite):
    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "scale": {**RANGE, "individual": False}},
              "sweep": {"record": ["records/*.AT2"]}, "models": ["compliant"], "histories": []}
    study = Study.from_config(config, suite)
    assert {e.attrs()["record_scale"] for e in study.records.values()} == {study.suite_factor}


@pytest.mark.slow
def test_a_suite_scaled_over_a_range_runs_through_snakemake_and_draws_its_spectra(suite):
    work = _project(suite)
    study_file = work / "config/studies/suite.yaml"
    target = work / "config/studies/records_suite/target.csv"
    target.write_text("period, sa\n" + "".join(f"{t}, {a}\n" for t, a in zip(*RANGE["target"].values())))
    scale = {**RANGE, "target": "records_suite/target.csv"}
    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "scale": scale}, "models": ["compliant"],
              "sweep": {"record": ["records_suite/RSN11_NORTH.AT2", "records_suite/RSN12_SOUTH.AT2"]},
              "histories": [{"record": "RSN12_SOUTH"}]}
    study_file.write_text(yaml.safe_dump(config))
    run = snakemake(work, "--configfile", "config/studies/suite.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    ds = xr.open_dataset(work / "results/studies/suite/suite.nc")
    assert float((ds["record_sa"].mean("record") / (0.9 * ds["target_sa"])).min()) == pytest.approx(1.0, rel=1e-12)
    history = xr.open_dataset(work / "results/studies/suite/histories/compliant_0.nc")
    assert history.attrs["record_scale"] == float(ds["record_scale"].sel(record="RSN12_SOUTH"))
    assert (work / "figures/studies/suite/spectra.png").is_file()
    # a third record changes the suite's factor: every record's jobs run again (the results: not redrawn)
    config["sweep"]["record"].append("records_suite/RSN13_EAST.AT2")
    study_file.write_text(yaml.safe_dump(config))
    run = snakemake(work, "results/studies/suite/suite.nc", "--configfile", "config/studies/suite.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    rerun = re.findall(r"^\s*output: results/studies/suite/chunks/(\S+)\.nc$", run.stdout + run.stderr, re.MULTILINE)
    assert sorted(rerun) == [f"compliant_{n}.0" for n in NAMES], rerun
    # a target twice as high: each record's fit doubles, the suite's factor does not change; the target is
    # an input of every record's jobs, so all of them run again (before, none did)
    before = xr.open_dataset(work / "results/studies/suite/suite.nc")["record_scale"].values
    target.write_text("period, sa\n" + "".join(f"{t}, {2 * a}\n" for t, a in zip(*RANGE["target"].values())))
    run = snakemake(work, "results/studies/suite/suite.nc", "--configfile", "config/studies/suite.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    rerun = re.findall(r"^\s*output: results/studies/suite/chunks/(\S+)\.nc$", run.stdout + run.stderr, re.MULTILINE)
    assert sorted(rerun) == [f"compliant_{n}.0" for n in NAMES], rerun
    after = xr.open_dataset(work / "results/studies/suite/suite.nc")["record_scale"].values
    assert np.allclose(after, 2 * before, rtol=1e-12)


def test_a_suites_maps_draw_its_mean_and_largest_not_a_row_per_record(suite):
    """Two numeric axes: a row per statistic and model (before, a row per record and model: 18 rows for
    nine records and two models, and no design value drawn)."""
    from dccss.studies import plots

    study = Study.from_config({**CONFIG, "models": ["compliant"], "histories": [],
                               "sweep": {"record": ["records/*.AT2"], "scale": [1.0, 2.5], "theta2_0": [0.0, 0.5]}},
                              suite)
    ds = _combined(study)
    fig = plots.maps(ds, {}, "suite")
    titles = [ax.get_title() for ax in fig.axes if ax.get_title()]
    assert len(titles) == 2 * 3  # mean and largest of compliant sliding's max |θ²|, rise and interpenetration
    assert sum("mean of the records" in t for t in titles) == 3 and not any("RSN" in t for t in titles)
    panel = next(ax for ax in fig.axes if ax.get_title() == "Compliant Sliding, mean of the records:\nmax |θ²|")
    drawn = panel.collections[0].get_array().reshape(2, 2)  # (theta2_0, scale) cells
    expected = ds["theta2_max_abs"].sel(model="compliant").mean("record").transpose("theta2_0", "scale").values
    assert np.allclose(drawn, expected, rtol=1e-12)
    assert "statistics over its 3 records" in fig.legends[0].get_title().get_text()


def test_a_suite_warns_of_the_scales_it_runs_not_of_each_records_scale_alone(tmp_path):
    """Records scaled to a strong target reach an implausible PGA: each is warned about once, with the factor
    the suite runs it at (before, also with the factor it would have alone, the study's first pass, which
    is never run)."""
    import warnings

    dt, a = read_at2(ROOT / "config/studies/records/synthetic.AT2")
    _, b = read_at2(ROOT / "config/studies/records/synthetic_y.AT2")
    write_at2(tmp_path / "ONE.AT2", dt, a)
    write_at2(tmp_path / "TWO.AT2", dt, 0.02 * b)
    scale = {**RANGE, "fraction": 1.0, "target": {"period": [0.5, 3.0], "sa": [3.0, 3.0]}}
    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "scale": scale},
              "sweep": {"record": ["ONE.AT2", "TWO.AT2"]}, "models": ["compliant"], "histories": []}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        study = Study.from_config(config, tmp_path)
    said = [str(w.message) for w in caught if "peak ground acceleration" in str(w.message)]
    scales = {name: e.attrs()["record_scale"] for name, e in study.records.items()}
    assert len(said) == 2 and all(any(f"scale ({f:g})" in m for m in said) for f in scales.values()), said


def test_a_suites_range_scaling_errors_are_the_studys_not_a_records(suite):
    """A mistake in the suite's scaling is reported once, as the study file's (before: once per record,
    each ending "(record 'NAME')"); a record's own problem still names the record."""
    bad = {**RANGE, "periods": [3.0, 1.0], "fraction": 0}
    config = {**CONFIG, "excitation": {**CONFIG["excitation"], "scale": bad}, "sweep": {"record": ["records/*.AT2"]}}
    with pytest.raises(StudyError) as err:
        Study.from_config(config, suite)
    assert err.value.messages == ["excitation.scale.periods: expected T_low < T_high, got [3.0, 1.0]",
                                  "excitation.scale.fraction: must be > 0, got 0.0"]
    long = {**RANGE, "target": {"period": [0.1, 100.0], "sa": [0.3, 0.1]}, "periods": [1.0, 50.0]}
    config["excitation"]["scale"] = long
    with pytest.raises(StudyError, match=r"excitation.scale.periods: 50 s is longer than the record .* \(record "
                                         r"'RSN11_NORTH'\)"):
        Study.from_config(config, suite)


@pytest.mark.parametrize(("scale", "message"), [
    ({"to": "spectral_acceleration", "period": 2.0, "target": 0.2, "damping": 1.5},
     r"^excitation\.scale\.damping: 1\.5 is outside 0 <= damping < 1$"),
    ({"to": "spectral_acceleration", "period": 2.0, "target": -0.2},
     r"^excitation\.scale\.target: must be > 0, got -0\.2$"),
    ({"to": "spectrum", "target": {"period": [0.1, 1.0, 3.0], "sa": [0.5, 0.5, 0.2]}, "periods": [0.2, 5.0]},
     r"^excitation\.scale\.periods: the range \[0\.2, 5\.0\] s is not within the target's periods 0\.1 to 3 s$"),
])
def test_a_suites_scaling_mistakes_name_no_record(suite, scale, message):
    """A target or period range is the suite's: its mistakes named no record (before, the first record's
    name ended the message of a spectral-acceleration scaling's, "(record 'RSN11_NORTH')")."""
    with pytest.raises(StudyError, match=message):
        Study.from_config({**CONFIG, "excitation": {"kind": "record", "scale": scale}, "sweep": {"record":
                                                                                                ["records/*.AT2"]}},
                          suite)
    # a record's own problem still names it
    with pytest.raises(StudyError, match=r"longer than the record .*\(record 'RSN11_NORTH'\)"):
        Study.from_config({**CONFIG, "excitation": {"kind": "record", "scale": {"to": "spectral_acceleration",
                                                                                  "period": 9.5, "target": 0.2}},
                           "sweep": {"record": ["records/*.AT2"]}}, suite)


# --- mistakes a suite's file makes ----------------------------------------------------------------------------
def test_a_record_mappings_peer_scale_must_be_a_factor_above_zero(suite):
    """peer_scale: -1.0 ran with a negative factor (a download's CSV refuses one)."""
    config = {**CONFIG, "excitation": {"kind": "record", "scale": "peer"},
              "sweep": {"record": [{"file": "records/RSN11_NORTH.AT2", "peer_scale": -1.0}]}, "histories": []}
    with pytest.raises(StudyError, match=r"sweep.record\[0\].peer_scale: must be > 0, got -1.0"):
        Study.from_config(config, suite)


@pytest.mark.parametrize(("bounds", "message"), [
    ({"lower": 1.3, "upper": 0.8}, r"structure.property.lower: 1.3 is above the nominal 1"),
    ({"lower": 0.8, "upper": 0.9}, r"structure.property.upper: 0.9 is below the nominal 1"),
])
def test_bounds_on_the_wrong_side_of_nominal_are_refused(suite, bounds, message):
    """property: {lower: 1.3, upper: 0.8} was accepted silently."""
    config = {**CONFIG, "structure": {"friction": 0.05, "property": bounds},
              "sweep": {"record": ["records/*.AT2"], "property": ["lower", "nominal", "upper"]}, "histories": []}
    with pytest.raises(StudyError, match=message):
        Study.from_config(config, suite)


def test_a_step_that_does_not_divide_a_record_is_said_by_the_study(suite):
    """The warning dccss run gives reached no study's log: a chunk now says it, naming the record."""
    config = {**CONFIG, "dt": 0.03, "sweep": {"record": ["records/RSN11_NORTH.AT2"], "scale": [1.0]}, "histories": []}
    study = Study.from_config(config, suite)
    with pytest.warns(UserWarning, match=r"record 'RSN11_NORTH': dt = 0.03 s does not divide the excitation's "
                                         r"duration \(8.99 s\)"):
        run_chunk(study, "compliant", 0)
