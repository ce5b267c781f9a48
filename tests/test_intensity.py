"""Intensity levels, incremental dynamic analysis and fragility: each record scaled to its levels (the intensity
it reaches, and a case against dccss run of the record at its factor), the lognormal fitted by maximum likelihood
against an independent fit, the limit states and failed runs, the figures, and the mistakes a file can make."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import xarray as xr
from scipy.signal import lsim
from scipy.stats import norm
from suite_records import write_suite
from test_fragility_fit import independent

from dccss.case import case_from
from dccss.excitation import underlying
from dccss.studies import Study, StudyError, combine, history_case, run_chunk
from dccss.studies.fragility import fit

LEVELS = [0.05, 0.12, 0.2, 0.3, 0.45]


@pytest.fixture(scope="module")
def suite(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ida")
    write_suite(folder / "records", 8)
    write_suite(folder / "pairs", 3, pairs=True)
    return folder


def config(**changes):
    base = {"study": {"name": "ida"}, "prototype": "DFP1", "excitation": {"kind": "record", "baseline": "linear"},
            "dt": 0.02, "models": ["compliant"], "structure": {"friction": 0.05},
            "sweep": {"record": ["records/*.AT2"], "intensity": LEVELS}}
    return {**base, **changes}


def _combined(study):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # dt 0.02 s divides no record's length here
        return combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})


@pytest.fixture(scope="module")
def ida(suite):
    study = Study.from_config(config(fragility=["ring", {"name": "stroke_20cm", "variable": "stroke_max_abs",
                                                         "above": 0.2}]), suite)
    return study, _combined(study)


# --- the levels -------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("intensity", "pairs"), [
    ({}, False), ({"measure": "pga"}, False), ({"measure": "pgv"}, False), ({"period": 1.0, "damping": 0.02}, False),
    ({}, True), ({"definition": "rotd100"}, True), ({"definition": "geometric_mean", "measure": "pga"}, True),
    ({"measure": "pgv", "definition": "rotd50"}, True)])
def test_each_record_reaches_its_level_to_1e_9(suite, intensity, pairs):
    """The intensity measured on the record as it runs (read at its factor) equals the level, relative 1e-9; the
    default Sa is at the device's isolated period 2π sqrt(L/g), 5 %, RotD50."""
    records = ["pairs/RSN1001_SYN0*.AT2"] if False else (
        [[f"pairs/RSN{1001 + k}_SYN{k}000.AT2", f"pairs/RSN{1001 + k}_SYN{k}090.AT2"] for k in range(3)] if pairs
        else ["records/*.AT2"])
    study = Study.from_config(config(intensity=intensity, sweep={"record": records, "intensity": LEVELS},
                                     models=["compliant"]), suite)
    if not intensity:
        assert study.intensity.period == pytest.approx(2 * math.pi * math.sqrt(1.8196 / 9.80665), rel=1e-4)
    from dccss.studies.combine import intensity_levels

    levels = intensity_levels(study)
    achieved = levels["intensity_achieved"].values
    assert np.max(np.abs(achieved / np.asarray(LEVELS)[None, :] - 1.0)) < 1e-9
    # each record's own intensity, computed here another way: its factor times it is the level. Sa by scipy's
    # lsim, exact (matrix exponential) for the samples joined by straight lines as the library's closed form is:
    # the two differ by the rounding of N ~ 1400 steps of a damped recursion, at most about N eps = 3e-13
    i = study.intensity
    for r, name in enumerate(study.records):
        own = _own_intensity(underlying(study.records[name]), i.measure, i.period, i.damping, i.definition)
        assert levels["intensity_factor"].values[r] * own == pytest.approx(np.asarray(LEVELS) * i.to_si, rel=1e-11)


def _own_intensity(record, measure, period, damping, definition):
    """A record's (or a pair's) intensity, not by the library's spectra: its oscillator by scipy.signal.lsim
    (first-order hold), the orientations' peaks over every sample and every degree."""
    parts = [record] if record.components == 1 else [record.x, record.y]
    if measure == "sa":
        omega = 2 * math.pi / period
        system = ([[0.0, 1.0], [-omega**2, -2 * damping * omega]], [[0.0], [-1.0]], [[omega**2, 0.0]], [[0.0]])
        motions = [lsim(system, p.acceleration, p.time - p.time[0], interp=True)[1] for p in parts]
    else:
        motions = [p.acceleration if measure == "pga" else p.velocity_samples for p in parts]
    if len(motions) == 1:
        return float(np.max(np.abs(motions[0])))
    if definition == "geometric_mean":
        return math.sqrt(np.max(np.abs(motions[0])) * np.max(np.abs(motions[1])))
    angle = np.radians(np.arange(180))[:, None]
    peaks = np.max(np.abs(np.cos(angle) * motions[0] + np.sin(angle) * motions[1]), axis=1)
    return float(np.median(peaks) if definition == "rotd50" else np.max(peaks))


def test_a_case_equals_dccss_run_of_its_record_at_its_factor_bit_for_bit(suite, ida):
    """The case of record r at level x is the record read with scale = its factor, as a case file gives it: the
    structure's peak and residual stroke and peak force, and the pad's peak tilt, to the last bit."""
    study, ds = ida
    name, level = "RSN1003_SYN2", 0.3
    factor = float(ds["intensity_factor"].sel(record=name, intensity=level))
    case = case_from({"prototype": "DFP1", "excitation": {"kind": "record", "file": f"records/{name}.AT2",
                                                          "baseline": "linear", "scale": factor},
                      "dt": 0.02, "model": "compliant", "structure": {"friction": 0.05}}, suite)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = case.run()
    cell = ds.sel(model="compliant", record=name, intensity=level)
    assert float(cell["stroke_max_abs"]) == run.attrs["structure_stroke_max_abs_m"]  # over the whole response
    assert float(cell["shear_ratio_max_abs"]) == run.attrs["structure_shear_ratio_max_abs"]
    assert float(cell["stroke_end"]) == float(run["stroke"].values[-1])
    assert float(cell["theta2_max_abs"]) == float(np.max(np.abs(run["theta2"].values)))
    assert float(cell["rise_max"]) == float(np.max(run["rise"].values))
    # a history point at that level is that case file
    point = Study.from_config(config(histories=[{"record": name, "intensity": level}]), suite)
    assert history_case(point, 0, "compliant").excitation.attrs()["record_scale"] == factor


# --- the fit ----------------------------------------------------------------------------------------------
def test_the_fitted_median_and_dispersion_equal_an_independent_maximum_likelihood_fit(ida):
    """θ and β of the study's own stripes against scipy's maximisation of the likelihood, relative 1e-6, wherever
    that finds a finite maximum (test_fragility_fit.independent decides on its own); else the same reason."""
    _, ds = ida
    fitted = 0
    for name in ("ring", "stroke_20cm"):
        sel = {"model": "compliant"}
        z, n = (ds[f"fragility_{name}_{k}"].sel(sel).values for k in ("exceeded", "counted"))
        expected = independent(LEVELS, z, n)
        status = str(ds[f"fragility_{name}_fit"].sel(sel).values)
        if isinstance(expected, str):
            assert status == expected, (name, z, n)
            continue
        assert status == "fitted", (name, z, n)
        assert float(ds[f"fragility_{name}_median"].sel(sel)) == pytest.approx(expected[0], rel=1e-6)
        assert float(ds[f"fragility_{name}_dispersion"].sel(sel)) == pytest.approx(expected[1], rel=1e-6)
        fitted += 1
    assert fitted >= 1, "no stripe data to fit: the levels miss the limits"


def test_the_fit_on_drawn_stripes_recovers_the_curve_and_says_when_there_is_none():
    rng = np.random.default_rng(7)
    levels = np.linspace(0.05, 1.5, 20)
    n = np.full(20, 40)
    z = rng.binomial(n, norm.cdf(np.log(levels / 0.6) / 0.35))
    theta, beta, status = fit(levels, z, n)
    assert status == "fitted" and np.allclose([theta, beta], independent(levels, z, n), rtol=1e-6)
    assert abs(theta / 0.6 - 1) < 0.1 and abs(beta / 0.35 - 1) < 0.25
    assert fit(levels, 0 * n, n)[2] == "none exceeded" and fit(levels, n, n)[2] == "all exceeded"
    assert fit(levels, np.where(levels > 0.6, n, 0), n)[2] == "separated"
    assert math.isnan(fit(levels, np.where(levels > 0.6, n, 0), n)[0])
    assert fit([0.3], [2], [5])[2] == "one level"


def test_a_failed_run_counts_as_what_it_is():
    """A pad's run that reached the ring and then failed is exceeded; one that failed short of it is left out and
    counted as such; the structure's own limits count every run."""
    from dccss.studies.fragility import fragility

    shape = (1, 3, 2)  # model, record, intensity
    capacity = np.array([[[0, 1], [0, 0], [1, 1]]])
    failed = np.array([[[0, 1], [0, 1], [0, 0]]])
    stroke = np.array([[[0.1, 0.3], [0.1, 0.4], [0.2, 0.5]]])
    ds = xr.Dataset({"capacity_exceeded": (("model", "record", "intensity"), capacity),
                     "failed": (("model", "record", "intensity"), failed),
                     "stroke_max_abs": (("model", "record", "intensity"), stroke, {"units": "m"})},
                    coords={"model": ["compliant"], "intensity": [0.1, 0.2]})
    assert ds["failed"].shape == shape
    out = fragility(ds, [("ring", "capacity_exceeded", "flag", 0.0, True),
                         ("big", "stroke_max_abs", "above", 0.25, False)], "1")
    assert list(out["fragility_ring_exceeded"].values[0]) == [1, 2]
    assert list(out["fragility_ring_counted"].values[0]) == [3, 2]  # record 1's failure short of the ring left out
    assert list(out["fragility_ring_failed"].values[0]) == [0, 1]
    assert list(out["fragility_big_exceeded"].values[0]) == [0, 3] and list(out["fragility_big_counted"].values[0]) \
        == [3, 3]


def _stripes(**variables):
    """A combined dataset of one model, records A-D at levels 0.1-0.3 g, of the given (record, intensity)
    variables and (slider, record, intensity) ones."""
    data = {name: (("slider", "record", "intensity") if np.ndim(v) == 3 else ("record", "intensity"), np.asarray(v))
            for name, v in variables.items()}
    ds = xr.Dataset(data, coords={"record": list("ABCD"), "intensity": [0.1, 0.2, 0.3]})
    if "slider" in ds.dims:
        ds = ds.assign_coords(slider=["rigid", "articulated"])
    return ds.expand_dims(model=["compliant"])


def test_a_run_without_a_value_is_unknown_not_unexceeded():
    """A pad summary that a run does not have (NaN, not failed: an articulated slider's) is not counted for a
    threshold on it; a slider kind with no value at all has no curve, and says so ('none counted')."""
    from dccss.studies.fragility import fragility

    nan = math.nan
    tilt = [[0.5, 1.5, 2.5], [nan, 1.6, 2.6], [0.4, nan, 2.4], [0.3, 0.6, nan]]  # degrees
    ds = _stripes(theta2_max_abs=[tilt, np.full((4, 3), nan)], failed=np.zeros((2, 4, 3), dtype=np.int8))
    out = fragility(ds, [("tilt", "theta2_max_abs", "above", 1.0, True)], "1")
    rigid, articulated = ({k: out[f"fragility_tilt_{k}"].sel(model="compliant", slider=s).values
                           for k in ("exceeded", "counted", "failed", "fit")} for s in ("rigid", "articulated"))
    assert list(rigid["exceeded"]) == [0, 2, 3] and list(rigid["counted"]) == [3, 3, 3]
    assert list(rigid["failed"]) == [1, 1, 1]  # left out: no value
    assert list(articulated["counted"]) == [0, 0, 0] and str(articulated["fit"]) == "none counted"
    assert "no value of theta2_max_abs" in out["fragility_tilt_failed"].attrs["long_name"]


@pytest.mark.parametrize("kind", ["above", "below"])
def test_a_threshold_is_strict_a_value_equal_to_it_is_not_exceeded(kind):
    """above: exceeded where the variable is > the threshold, below: where it is <; a value equal to the
    threshold is neither (the file's 0.2 is the very double the summary holds)."""
    from dccss.studies.fragility import exceeded, limits_from

    (limit,) = limits_from([{"name": "edge", "variable": "stroke_max_abs", kind: 0.2}], {"stroke_max_abs": False})
    stroke = [[0.2 - 1e-12, 0.2, 0.2 + 1e-12]] * 4
    hit, counted = exceeded(_stripes(stroke_max_abs=stroke), limit)
    expected = [False, False, True] if kind == "above" else [True, False, False]
    assert hit.sel(model="compliant", record="A").values.tolist() == expected and bool(counted.all())


# --- mistakes ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("changes", "message"), [
    ({"intensity": {"measure": "sa"}, "sweep": {"record": ["records/*.AT2"]}},
     r"intensity: names the measure of the intensity levels, but the study has none"),
    ({"sweep": {"record": ["records/*.AT2"], "intensity": [0.1, 0.0]}}, r"sweep.intensity\[1\]: a level is an "
                                                                        r"intensity > 0, got 0.0"),
    ({"sweep": {"record": ["records/*.AT2"], "intensity": [0.1], "scale": [1.0, 2.0]}},
     r"sweep.scale: the intensity levels set each record's factor"),
    ({"excitation": {"kind": "record", "scale": 2.0}}, r"excitation.scale: the intensity levels set each record's "
                                                       r"factor"),
    ({"sweep": {"record": [{"file": "records/RSN1001_SYN0.AT2", "scale": 2.0}], "intensity": [0.1]}},
     r"sweep.record\[0\].scale: the intensity levels set each record's factor"),
    ({"sweep": {"record": ["records/*.AT2"], "intensity": [0.1], "prototype": ["DFP1", "DFP2"]}},
     r"intensity.period: the isolated period differs between the devices the study sweeps"),
    ({"intensity": {"measure": "pgv", "period": 1.0}}, r"intensity.period: a spectral acceleration's \(measure: "
                                                       r"sa\); pgv has none"),
    ({"intensity": {"measure": "sv"}}, r"intensity.measure: must be one of \['sa', 'pga', 'pgv'\], got 'sv'"),
    ({"fragility": ["ring_1"]}, r"fragility\[0\]: ring_1 needs the summary ring_1_reached, which this study does "
                                r"not have"),
    ({"fragility": ["collapse"]}, r"fragility\[0\]: unknown limit state 'collapse'"),
    ({"fragility": [{"name": "big", "variable": "stroke_max", "above": 0.2}]},
     r"fragility\[0\].variable: 'stroke_max' is not a summary of this study"),
    ({"fragility": [{"name": "big", "variable": "stroke_max_abs"}]},
     r"fragility\[0\]: give one of above \(exceeded where the variable is strictly above it: a value equal to it is "
     r"not\) or below \(strictly below it\)"),
    ({"fragility": ["ring"], "sweep": {"record": ["records/*.AT2"], "scale": [1.0]}},
     r"fragility: is fitted on the stripes of intensity levels"),
])
def test_mistakes_are_named(suite, changes, message):
    with pytest.raises(StudyError, match=message):
        Study.from_config(config(**changes), suite)


def test_a_sine_has_no_intensity_levels(suite):
    with pytest.raises(StudyError, match=r"sweep.intensity: scales recorded ground motions"):
        Study.from_config(config(excitation={"kind": "sine", "amplitude": 0.1, "omega": 3.0, "duration": 4.0},
                                 sweep={"intensity": [0.1]}), suite)


# --- the figures ------------------------------------------------------------------------------------------
def test_the_ida_figure_draws_each_record_and_the_stripes_fractiles(ida):
    from dccss.studies import intensity_plots

    _, ds = ida
    fig = intensity_plots.ida(ds, "caption")
    ax = next(a for a in fig.axes if a.get_title().startswith("max |stroke u|"))
    values = 100 * ds["stroke_max_abs"].sel(model="compliant").transpose("record", "intensity").values
    lines = ax.get_lines()
    for record in values:
        assert any(np.array_equal(ln.get_xdata(), record) for ln in lines)
    (median,) = [ln for ln in lines if ln.get_gid() == "p50"]
    assert np.allclose(median.get_xdata(), np.percentile(values, 50, axis=0)) and list(median.get_ydata()) == LEVELS
    assert ax.get_ylabel() == "Sa(T = 2.71 s, 5 %) (g)"


def test_the_fragility_figure_draws_the_observed_fractions_and_the_fitted_curve(ida):
    from dccss.studies import intensity_plots

    _, ds = ida
    fig = intensity_plots.fragility(ds, "caption")
    for name in ("ring", "stroke_20cm"):
        ax = next(a for a in fig.axes if a.get_title().startswith(f"{name}:"))
        (observed,) = [ln for ln in ax.get_lines() if ln.get_gid() == "observed"]
        z, n = (ds[f"fragility_{name}_{k}"].sel(model="compliant").values for k in ("exceeded", "counted"))
        assert np.allclose(observed.get_ydata(), z / n)
        fitted = [ln for ln in ax.get_lines() if ln.get_gid() == "fitted"]
        theta = float(ds[f"fragility_{name}_median"].sel(model="compliant"))
        if isinstance(independent(LEVELS, z, n), str):
            assert fitted == [] and math.isnan(theta)
        else:  # a finite maximum: drawn, its median at one half
            (curve,) = fitted
            assert np.interp(theta, curve.get_xdata(), curve.get_ydata()) == pytest.approx(0.5, abs=5e-3)


def test_the_figures_say_how_many_runs_a_fractile_or_a_fraction_stands_on():
    """Where runs have no value, the IDA's median at a level is over those that do and their number is written
    beside it; so is the number of runs an observed fraction stands on; nothing where all records count."""
    from dccss.studies import intensity_plots
    from dccss.studies.fragility import fragility

    nan = math.nan
    stroke = [[0.05, 0.12, 0.20], [0.06, nan, 0.25], [0.04, 0.10, nan], [0.07, 0.15, nan]]  # m
    ds = _stripes(stroke_max_abs=stroke)
    ds["stroke_max_abs"].attrs["units"] = "m"
    ds["intensity"].attrs["label"] = "Sa(T = 2.71 s, 5 %) (g)"
    ds = ds.assign(fragility(ds, [("stroke_11cm", "stroke_max_abs", "above", 0.11, False)], "1"))
    fig = intensity_plots.ida(ds, "caption")
    ax = next(a for a in fig.axes if a.get_title().startswith("max |stroke u|"))
    (median,) = [ln for ln in ax.get_lines() if ln.get_gid() == "p50"]
    assert np.allclose(median.get_xdata(), [5.5, 12.0, 22.5])  # over 4, 3 and 2 runs
    written = {t.xy[1]: t.get_text() for t in ax.texts if t.get_gid() == "runs"}
    assert written == {0.2: "3", 0.3: "2"}
    fig = intensity_plots.fragility(ds, "caption")
    ax = next(a for a in fig.axes if a.get_title().startswith("stroke_11cm:"))
    written = {t.xy[0]: (t.xy[1], t.get_text()) for t in ax.texts if t.get_gid() == "runs"}
    assert written == {0.2: (2 / 3, "3"), 0.3: (1.0, "2")}


# --- jobs of several records ------------------------------------------------------------------------------
@pytest.mark.slow  # a suite run three ways: 4 s
def test_records_spread_over_jobs_give_the_same_results_to_the_last_bit(suite):
    """record_jobs 3 (a job per group of records, by their names' hash) against a job per record: the combined
    dataset identical, its netCDF the same bytes."""
    plain = _combined(Study.from_config(config(), suite))
    study = Study.from_config(config(record_jobs=3), suite)
    assert study.grid.n_chunks <= 3 and sum(len(g) for g in study.grid.groups.values()) == 8
    grouped = _combined(study)
    xr.testing.assert_identical(plain, grouped)


def test_a_records_job_does_not_depend_on_the_others():
    """A record's group is its name's hash modulo the number of jobs: the same whatever else is in the suite."""
    from dccss.studies.grid import record_group

    groups = [record_group(f"RSN{k}_X", 8) for k in range(200)]
    assert set(groups) == set(range(8)) and record_group("RSN12_X", 8) == groups[12]


@pytest.mark.slow
def test_an_intensity_study_runs_through_snakemake_in_record_jobs_and_draws_its_figures(tmp_path):
    """A suite at levels of PGA with bounds through the workflow: ida and fragility drawn, records in 3 jobs per
    model; adding a record reruns its own job and the combination only. (The workflow wrote the schema's
    defaults into the study its jobs read: a PGA study's filled-in Sa period was refused there.)"""
    import re

    import yaml
    from conftest import copy_project, snakemake

    work = copy_project(tmp_path)
    names = write_suite(work / "config/studies/ida_records", 7)
    study = work / "config/studies/ida.yaml"
    spec = config(models=["compliant"], record_jobs=3, fragility=["ring"], intensity={"measure": "pga"},
                  structure={"friction": 0.05, "property": {"lower": 0.8, "upper": 1.3}},
                  sweep={"record": [f"ida_records/{n}.AT2" for n in names[:6]], "intensity": LEVELS,
                         "property": ["lower", "upper"]})
    study.write_text(yaml.safe_dump(spec))
    run = snakemake(work, "--configfile", "config/studies/ida.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    for name in ("ida", "fragility", "maps"):
        assert (work / f"figures/studies/ida/{name}.png").is_file()
    chunks = sorted(p.name for p in (work / "results/studies/ida/chunks").iterdir())
    assert all(re.fullmatch(r"compliant_@[0-2]\.nc", c) for c in chunks) and len(chunks) <= 3
    ds = xr.open_dataset(work / "results/studies/ida/ida.nc")
    assert ds.sizes["record"] == 6 and "fragility_ring_median" in ds and ds.attrs["intensity_measure"] == "pga"
    # the seventh record: only its group's job runs again
    from dccss.studies.grid import record_group

    spec["sweep"]["record"].append(f"ida_records/{names[6]}.AT2")
    study.write_text(yaml.safe_dump(spec))
    run = snakemake(work, "results/studies/ida/ida.nc", "--configfile", "config/studies/ida.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    rerun = re.findall(r"^\s*output: results/studies/ida/chunks/(\S+)\.nc$", run.stdout + run.stderr, re.MULTILINE)
    assert rerun == [f"compliant_@{record_group(names[6], 3)}"], rerun
    assert xr.open_dataset(work / "results/studies/ida/ida.nc").sizes["record"] == 7
