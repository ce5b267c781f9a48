"""The paper is data: what each figure shows lives in ``config/config.yaml``.

A figure spec that asks for a dataset the study does not run is refused before any job, naming its
key (``dccss.paper.figures.figure_specs``, called by the workflow's ``check_config``); a config that
passes the checks runs to the end: another time step grid, a prototype renamed everywhere, a third
prototype.
"""

import copy
import hashlib
import shutil
from pathlib import Path

import pytest
import yaml
from conftest import ROOT, copy_project, snakemake

from dccss.paper.figures import Runs, SpecError, figure_spec, figure_specs
from dccss.paper.prototypes import TABLE1

CONFIG = yaml.safe_load((ROOT / "config/config.yaml").read_text())


def runs_of(config):
    """The datasets the workflow runs for ``config`` (the grid's ends taken as its start and stop)."""
    sweep = config.get("breakaway") or {}
    grid = sweep.get("theta2_0")
    return Runs(prototypes=list(config["prototypes"]),
                case_sets={name: list(s["cases"]) for name, s in config["case_sets"].items()},
                models=config["models"], dt=config["dt"], duration=config["duration"],
                dXg=sweep.get("dXg", []), normals=sweep.get("normals", []),
                theta2_0=(grid["start"], grid["stop"]) if grid else None)


def renamed(config, old, new):
    """``config`` with the prototype ``old`` renamed ``new`` everywhere (names, titles, comments); the
    device stays Table 1's ``old``."""
    out = yaml.safe_load(yaml.safe_dump(config, allow_unicode=True).replace(old, new))
    if config["prototypes"][old] == old:  # a Table 1 name: the device itself is not renamed
        out["prototypes"][new] = old
    return out


def with_third_prototype(config, name="DFP3"):
    """A copy of DFP1 with alpha21 = 8 deg, a case of every case set like DFP1."""
    config = copy.deepcopy(config)
    config["prototypes"][name] = {**TABLE1["DFP1"], "alpha21": 8.0}
    for spec in config["case_sets"].values():
        spec["cases"][name] = dict(spec["cases"]["DFP1"])
    return config


# --- the spec parser (fast) -------------------------------------------------------------------
def test_paper_figures_parse_and_match_what_is_run():
    specs = figure_specs(CONFIG["figures"], runs_of(CONFIG))
    assert list(specs) == [k for k in CONFIG["figures"] if k.startswith("fig")]
    for fig_id, spec in specs.items():
        entry = CONFIG["figures"][fig_id]
        assert spec.kind == entry["kind"] and spec.title == entry["title"]
        assert [p.prototype for p in spec.panels] == [p["prototype"] for p in entry["panels"]]
    # the numbers the figures once carried in code, now read from the config
    assert [p.theta2_0 for p in specs["fig08"].panels] == [p["theta2_0"] for p in CONFIG["figures"]["fig08"]["panels"]]
    assert [p.t for p in specs["fig20"].panels] == [specs["fig18"].panels[0].t, specs["fig19"].panels[0].t]


@pytest.mark.parametrize("config", [renamed(CONFIG, "DFP2", "SQUAT"), with_third_prototype(CONFIG),
                                    {**CONFIG, "dt": [0.01, 0.001, 0.002]}],
                         ids=["renamed everywhere", "third prototype", "another dt as well"])
def test_consistent_changes_pass(config):
    specs = figure_specs(config["figures"], runs_of(config))
    assert len(specs) == len(figure_specs(CONFIG["figures"]))


def _set(path, value):
    """A change of the figures section: ``path`` like "fig09.panels.1.dt" (value None: delete)."""
    def change(figures, runs):
        *parents, last = [int(p) if p.isdigit() else p for p in path.split(".")]
        target = figures
        for p in parents:
            target = target[p]
        if value is None:
            del target[last]
        else:
            target[last] = value
        return figures, runs
    return change


def _runs(**changes):
    def change(figures, runs):
        return figures, Runs(**{**runs.__dict__, **changes})
    return change


PAPER = runs_of(CONFIG)
# (id, change of (figures section, runs), message lines expected, each naming its key)
BAD = [
    ("dt not run", _runs(dt=[0.01, 0.002]),
     ["figures.fig09.panels[1].dt: 0.001 s is not run; dt: [0.01, 0.002]", "figures.fig09.panels[3].dt",
      "figures.fig10.panels[1].dt", "figures.fig12.panels[0].dt", "figures.fig17.panels[1].dt",
      "figures.fig18.panels[0].dt", "figures.fig20.panels[0].dt"]),
    ("prototype renamed outside the figures",
     _runs(prototypes=["DFP1", "SQUAT"], case_sets={k: ["DFP1", "SQUAT"] for k in PAPER.case_sets}),
     ["figures.fig07.panels[2].prototype: unknown prototype 'DFP2'; defined: ['DFP1', 'SQUAT']",
      "figures.fig20.panels[1].prototype: unknown prototype 'DFP2'"]),
    ("prototype missing from a case set", _runs(case_sets={"as_printed": ["DFP1"], "as_reported": ["DFP1", "DFP2"]}),
     ["figures.fig09.panels[2].prototype: 'DFP2' is not a case of case set(s) ['as_printed'] (the figure is drawn "
      "for every case set"]),
    ("model not run", _runs(models=["compliant"]),
     ["figures.fig17.panels[0].model: 'stick_slip' is not run; models: ['compliant']"]),
    ("ground step not run", _runs(dXg=[0.05]),
     ["figures.fig07.panels[1].dXg: 0.1 m is not a step of the breakaway sweeps; breakaway.dXg: [0.05]",
      "figures.fig08.panels[0].dXg"]),
    ("no breakaway sweep", _runs(dXg=[], normals=[], theta2_0=None),
     ["figures.fig07.kind: 'breakaway' draws breakaway sweeps, and none is run",
      "figures.breakaway_normals: 'unsigned' is not among breakaway.normals []"]),
    ("angle outside the grid", _set("fig08.panels.0.theta2_0", -12.0),
     ["figures.fig08.panels[0].theta2_0: -12° is outside the breakaway grid, -10.5° to 0°"]),
    ("instant outside the excitation", _set("fig20.panels.1.t", 1.5),
     ["figures.fig20.panels[1].t: 1.5 s is outside the excitation, 0 < t <= duration = 1 s"]),
    ("unknown kind", _set("fig09.kind", "spaghetti"), ["figures.fig09.kind: unknown kind 'spaghetti'; known: ["]),
    ("too many panels", _set("fig11.panels", [{"prototype": "DFP1", "model": "compliant", "dt": 0.01}] * 2),
     ["figures.fig11.panels: kind 'global_coordinates' draws 1 panel(s), got 2"]),
    ("missing instant", _set("fig18.panels.0.t", None),
     ["figures.fig18.panels[0]: missing key(s) ['t'] of kind 'sticking'"]),
    ("key of another kind", _set("fig09.panels.0.theta2_0", -6.0),
     ["figures.fig09.panels[0]: unknown key(s) ['theta2_0'] of kind 'diagonals'; allowed: "]),
    ("model the kind cannot draw", _set("fig19.panels.0.model", "compliant"),
     ["figures.fig19.panels[0].model: kind 'sticking' draws the stick_slip model, got 'compliant'"]),
    ("value of the wrong type", _set("fig10.panels.0.dt", "0.01"),
     ["figures.fig10.panels[0].dt: expected a number > 0, got '0.01'"]),
    ("unknown panel case set", _set("fig09.panels.0.case_set", "as_imagined"),
     ["figures.fig09.panels[0].case_set: unknown case set 'as_imagined'; defined: ['as_printed', 'as_reported']"]),
    ("panel normals not run", _set("fig07.panels.0.normals", "signed"), []),  # both conventions are run
    ("figure id", _set("figure7", {"kind": "breakaway", "title": "t", "panels": [{"prototype": "DFP1", "dXg": 0.05}]}),
     ["figures.figure7: a figure is named 'fig' and its number, e.g. fig07"]),
    ("two-line title", _set("fig12.title", "a\nb"), ["figures.fig12.title: expected one line of text"]),
    ("unknown figures.case_set", _set("case_set", "as_imagined"),
     ["figures.case_set: unknown case set 'as_imagined'; defined: ['as_printed', 'as_reported']"]),
    ("figures.case_set missing", _set("case_set", None),
     ["figures.case_set: required: the case set the time-history figures show"]),
    ("figures.breakaway_normals not run", _set("breakaway_normals", "absolute"),
     ["figures.breakaway_normals: 'absolute' is not among breakaway.normals ['signed', 'unsigned']"]),
]


@pytest.mark.parametrize("change, messages", [r[1:] for r in BAD], ids=[r[0] for r in BAD])
def test_spec_errors_name_the_key(change, messages):
    figures, runs = change(copy.deepcopy(CONFIG["figures"]), PAPER)
    if not messages:
        figure_specs(figures, runs)
        return
    with pytest.raises(SpecError) as err:
        figure_specs(figures, runs)
    lines = err.value.errors
    assert all(line.startswith("figures.") for line in lines), lines
    for message in messages:
        assert any(line.startswith(message) for line in lines), (message, lines)


def test_pinned_normals_must_be_run():
    runs = Runs(**{**PAPER.__dict__, "normals": ["unsigned"]})
    entry = {"kind": "breakaway", "title": "t", "panels": [{"prototype": "DFP1", "dXg": 0.05, "normals": "signed"}]}
    with pytest.raises(SpecError, match=r"^figures.fig07.panels\[0\].normals: 'signed' is not run"):
        figure_spec("fig07", entry, runs)
    assert figure_spec("fig07", entry).panels[0].variant == "signed"  # without runs: the structure only


# --- the workflow (Snakemake) ------------------------------------------------------------------
def write_config(work, config):
    (work / "scenario.yaml").write_text(yaml.safe_dump(config, allow_unicode=True, sort_keys=False))


def assert_fails_before_any_job(work, run, *messages):
    out = run.stdout + run.stderr
    assert run.returncode != 0
    for message in messages:
        assert message in out, out[-3000:]
    for word in ("Traceback", "MissingInputException", "KeyError"):
        assert word not in out, out[-3000:]
    assert not any((work / d).exists() for d in ("results", "figures", "logs"))


@pytest.mark.slow
def test_dt_grid_without_a_figure_dt_fails_naming_the_panels(tmp_path):
    """dt: [0.01, 0.002] while the figures ask for 0.001 s: refused before any job (figures are
    not adapted); every panel asking for 0.001 s is named."""
    work = copy_project(tmp_path)
    write_config(work, {**CONFIG, "dt": [0.01, 0.002]})
    run = snakemake(work, "--configfile", "scenario.yaml")
    assert_fails_before_any_job(work, run, "config: figures.fig09.panels[1].dt: 0.001 s is not run; dt: [0.01, 0.002]",
                                "config: figures.fig10.panels[1].dt", "config: figures.fig20.panels[0].dt")


def _empty_grid(config):
    config["breakaway"]["theta2_0"] = {"start": -10.5, "stop": -11.0, "step": 0.1}


def _partial_rename(config):
    config["prototypes"]["SQUAT"] = config["prototypes"].pop("DFP2")
    for spec in config["case_sets"].values():
        spec["cases"]["SQUAT"] = spec["cases"].pop("DFP2")


def _no_sweep(config):
    del config["breakaway"]


def _dt_labels(config):
    config["dt"] = [0.01, 0.001, 0.0010000001]


def _animation_dt(config):
    config["animations"]["fig20a_steps"]["dt"] = 0.002


WORKFLOW_BAD = [
    ("animation of a result not run", _animation_dt,
     "config: animations.fig20a_steps.dt: 0.002 s is not run; dt: [0.01, 0.001]"),
    ("empty breakaway grid", _empty_grid,
     "config: breakaway.theta2_0: the grid from start -10.5 to stop -11.0 by step 0.1 is empty"),
    ("prototype renamed outside the figures", _partial_rename,
     "config: figures.fig07.panels[2].prototype: unknown prototype 'DFP2'; defined: ['DFP1', 'SQUAT']"),
    ("no breakaway section", _no_sweep, "config: figures.fig07.kind: 'breakaway' draws breakaway sweeps"),
    ("two dt with one file name", _dt_labels, "config: dt: [0.001, 0.0010000001] share the file name label dt0.001"),
]


@pytest.mark.slow
@pytest.mark.parametrize("mutate, message", [r[1:] for r in WORKFLOW_BAD], ids=[r[0] for r in WORKFLOW_BAD])
def test_workflow_config_errors(tmp_path, mutate, message):
    work = copy_project(tmp_path)
    config = copy.deepcopy(CONFIG)
    mutate(config)
    write_config(work, config)
    assert_fails_before_any_job(work, snakemake(work, "--configfile", "scenario.yaml"), message)


def planned_outputs(run):
    """The files a dry run (-n) would write."""
    lines = (run.stdout + run.stderr).splitlines()
    return {w for line in lines if line.strip().startswith("output:")
            for w in line.split(":", 1)[1].replace(",", " ").split()}


@pytest.mark.slow
def test_prototype_renamed_in_the_study_only_fails_naming_the_paper_values(tmp_path):
    """The paper's values name DFP2: renaming it in config.yaml alone stops the workflow before any
    job, naming each entry that asks for the old name."""
    work = copy_project(tmp_path)
    write_config(work, renamed(CONFIG, "DFP2", "SQUAT"))
    assert_fails_before_any_job(work, snakemake(work, "--configfile", "scenario.yaml"),
                                "paper value 'fig20b_velocity': quantity.prototype 'DFP2' is not one of "
                                "['DFP1', 'SQUAT']")


@pytest.mark.slow
def test_prototype_renamed_everywhere_runs(tmp_path):
    """DFP2 -> SQUAT in the prototypes, case sets, figures and the paper's values: every job is
    planned under the new name."""
    work = copy_project(tmp_path)
    write_config(work, renamed(CONFIG, "DFP2", "SQUAT"))
    values = work / "config/paper_values.yaml"
    values.write_text(values.read_text().replace("DFP2", "SQUAT"))
    run = snakemake(work, "--configfile", "scenario.yaml", "-n")
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    outputs = planned_outputs(run)
    assert "results/breakaway/SQUAT_unsigned.nc" in outputs and "figures/fig19.png" in outputs
    assert "results/cases/as_reported/SQUAT_stick_slip_dt0.01.nc" in outputs
    assert not [o for o in outputs if "DFP2" in o]


@pytest.mark.slow
def test_third_prototype_dry_run(tmp_path):
    work = copy_project(tmp_path)
    write_config(work, with_third_prototype(CONFIG))
    run = snakemake(work, "--configfile", "scenario.yaml", "-n")
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    outputs = planned_outputs(run)
    assert {"results/breakaway/DFP3_signed.nc", "results/cases/as_printed/DFP3_compliant_dt0.001.nc"} <= outputs


def figure_digests(root: Path):
    return {f.name: hashlib.sha256(f.read_bytes()).hexdigest() for f in sorted(root.glob("figures/fig*"))}


@pytest.mark.slow
def test_third_prototype_runs_to_the_end(reproduction, tmp_path):
    """A third prototype added to the reproduced study: its cases and sweeps run, the validation
    passes, and the figures (which do not ask for it) are unchanged."""
    work = tmp_path / "work"
    shutil.copytree(reproduction, work, symlinks=True)
    write_config(work, with_third_prototype(CONFIG))
    run = snakemake(work, "--configfile", "scenario.yaml")
    assert run.returncode == 0, (run.stdout + run.stderr)[-3000:]
    assert len(list((work / "results/cases").rglob("DFP3_*.nc"))) == 2 * 2 * 2  # case sets x models x dt
    assert len(list((work / "results/breakaway").glob("DFP3_*.nc"))) == 2
    assert (work / "results/validation.ok").exists()
    assert figure_digests(work) == figure_digests(reproduction)
