# A study file (config/studies/*.yaml): loaded and checked once, before any job runs. Each job's
# params are the part of the study file that its output depends on, so that Snakemake reruns a
# job when, and only when, that part changes (editing the description reruns only the plots).
import os
from pathlib import Path

from snakemake.exceptions import WorkflowError

from dccss.case import CaseError
from dccss.mechanics.models import REGISTRY
from dccss.studies import Study, history_mapping, sweep_spec
from dccss.studies.spec import entry_files

STUDY_FILE = Path(workflow.overwrite_configfiles[-1]) if workflow.overwrite_configfiles else Path("study.yaml")
# relative to the working directory, as a job's parameter: a project moved or copied whole reruns nothing
STUDY_FILE = Path(os.path.relpath(STUDY_FILE))
try:
    STUDY = Study.from_config(config, STUDY_FILE.parent)
except CaseError as err:
    raise WorkflowError(f"study file {STUDY_FILE}: {err}") from None


def _paths(files):
    return [str(STUDY_FILE.parent / f) for f in ([files] if isinstance(files, str) else files)]


def study_files(records=None):
    """Files the study reads (a recorded or tabulated ground motion; with a record axis, those of
    ``records`` (a name or a list of names), or of every record; a target spectrum the records are scaled to): inputs
    of its jobs."""
    scale = STUDY.excitation_spec.get("scale")
    target = _paths(scale["target"]) if isinstance(scale, dict) and isinstance(scale.get("target"), str) else []
    if STUDY.records:
        names = [records] if isinstance(records, str) else records or list(STUDY.record_entries)
        return [p for name in names for p in _paths(entry_files(STUDY.record_entries[name]))] + target
    return _paths(STUDY.excitation_spec.get("file", [])) + target


def chunk_label(k):
    """A chunk's name in its file: its number, or with a record axis '<record>.<number within it>'
    (a record's jobs then do not change when other records are added or dropped), or with record_jobs
    '@<group>' (a group of records, by their names' hash: it changes only when one of its records does)."""
    cases = STUDY.grid.chunk(k)
    if STUDY.grid.groups is not None:
        return f"@{sorted(STUDY.grid.groups)[k]}"
    record = STUDY.grid.record_of(cases)
    if record is None:
        return str(k)
    first = next(j for j in range(STUDY.grid.n_chunks) if STUDY.grid.record_of(STUDY.grid.chunk(j)) == record)
    return f"{record}.{k - first}"


def chunk_records(label):
    """The records of a chunk label (None without a record axis)."""
    if label.startswith("@"):
        return STUDY.grid.groups[int(label[1:])]
    return [label.rsplit(".", 1)[0]] if "." in label else None


def chunk_spec(wildcards):
    """What a chunk's summaries depend on: its model's part of the study file, and only its records'
    (and, for a suite scaled over a period range, the suite's factor, which all its records set)."""
    records = chunk_records(wildcards.chunk)
    return sweep_spec(config, [wildcards.model],
                      None if records is None else [STUDY.record_entries[r] for r in records], STUDY.suite_factor)


def chunk_files():
    return [
        f"results/studies/{STUDY.name}/chunks/{model}_{chunk_label(k)}.nc"
        for model in STUDY.models
        for k in range(STUDY.grid.n_chunks)
    ]


def history_files():
    return [
        f"results/studies/{STUDY.name}/histories/{model}_{i}.nc"
        for i in range(len(STUDY.histories))
        for model in STUDY.models
    ]


def history_labels():
    return [", ".join(f"{k} = {v:g}" if isinstance(v, float) else f"{k} = {v}" for k, v in point.items())
            for point in STUDY.histories]


def convergence_plot():
    """A Δt study (a dt axis, a model with a sticking phase and one without, run in full at its points)
    also gets its convergence plot."""
    sticking = {REGISTRY[model].sticking for model in STUDY.models}
    return "dt" in STUDY.axes and sticking == {True, False} and any("dt" in point for point in STUDY.histories)


def study_plots():
    names = ["maps"] + (["histories"] if STUDY.histories else []) + (["convergence"] if convergence_plot() else [])
    names += ["spectra"] if STUDY.suite_factor is not None else []  # a suite scaled over a period range
    names += ["ida"] + (["fragility"] if STUDY.limits else []) if STUDY.intensity is not None else []
    files = [f"figures/studies/{STUDY.name}/{name}.{ext}" for name in names for ext in ("png", "pdf")]
    return files + ([f"figures/studies/{STUDY.name}/convergence.csv"] if convergence_plot() else [])


def animation_files():
    return [
        f"figures/studies/{STUDY.name}/animations/{model}_{i}.gif"
        for i in STUDY.animate
        for model in STUDY.models
    ]


def all_targets():
    targets = [f"results/studies/{STUDY.name}/{STUDY.name}.nc"] + study_plots() + animation_files()
    return targets + report_pages(targets)
