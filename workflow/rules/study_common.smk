# A study file (config/studies/*.yaml): loaded and checked once, before any job runs.
from pathlib import Path

from snakemake.exceptions import WorkflowError

from dccss.case import CaseError, parameters_hash
from dccss.study import Study

STUDY_FILE = Path(workflow.overwrite_configfiles[-1]) if workflow.overwrite_configfiles else Path("study.yaml")
try:
    STUDY = Study.from_config(config, STUDY_FILE.parent)
except CaseError as err:
    raise WorkflowError(f"study file {STUDY_FILE}: {err}") from None
STUDY_HASH = parameters_hash(config)


def study_files():
    """Files the study reads (a recorded or tabulated ground motion): inputs of its jobs."""
    spec = STUDY.excitation_spec
    return [str(STUDY_FILE.parent / spec["file"])] if "file" in spec else []


def chunk_files():
    return [
        f"results/studies/{STUDY.name}/chunks/{model}_{k}.nc"
        for model in STUDY.models
        for k in range(STUDY.n_chunks)
    ]


def history_files():
    return [
        f"results/studies/{STUDY.name}/histories/{model}_{i}.nc"
        for i in range(len(STUDY.histories))
        for model in STUDY.models
    ]


def study_plots():
    names = ["maps"] + (["histories"] if STUDY.histories else [])
    return [f"figures/studies/{STUDY.name}/{name}.{ext}" for name in names for ext in ("png", "pdf")]


def all_targets():
    return [f"results/studies/{STUDY.name}/{STUDY.name}.nc"] + study_plots()
