"""The shipped ground-motion study through ``profiles/slurm`` on a running Slurm: the same result files,
byte for byte, as a local run (``profiles/default``).

Skipped where Slurm is not running (no ``sinfo``, ``sinfo`` failing, or no node able to take a job) and
where ``snakemake-executor-plugin-slurm`` is not installed. On one machine:

    sudo bash profiles/slurm/start-local.sh
    python -m pytest -m slurm tests/test_slurm.py
    sudo bash profiles/slurm/stop-local.sh

On a cluster, the jobs must see the test's folders: put them on a shared file system with
``--basetemp=<shared folder>``; an account can be given with ``SBATCH_ACCOUNT``.
"""

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import copy_project

STUDY = "ground_motion"
#: seconds a Slurm run may take before it counts as hung (e.g. job status that is never seen)
TIMEOUT = 1200


def slurm_problem():
    """Why the workflow cannot run on Slurm here (None if it can)."""
    if importlib.util.find_spec("snakemake_executor_plugin_slurm") is None:
        return "snakemake-executor-plugin-slurm is not installed"
    if shutil.which("sinfo") is None or shutil.which("sbatch") is None:
        return "Slurm is not installed (no sinfo/sbatch)"
    try:
        run = subprocess.run(["sinfo", "--noheader", "--format=%T"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired) as err:
        return f"Slurm is not running (sinfo: {err})"
    if run.returncode != 0:
        return f"Slurm is not running (sinfo: {(run.stderr or run.stdout).strip()[:200]})"
    states = {s.strip().rstrip("*~#!%$@^-") for s in run.stdout.split()}
    if not states & {"idle", "mixed", "allocated", "completing"}:
        return f"no Slurm node can take a job (node states: {', '.join(sorted(states)) or 'none'})"
    return None


pytestmark = [pytest.mark.slurm, pytest.mark.slow]


@pytest.fixture
def slurm():
    """Skips the test where the workflow cannot run on Slurm (checked when the test runs, not when
    tests are collected: `sinfo` can take seconds to find that no controller answers)."""
    problem = slurm_problem()
    if problem:
        pytest.skip(problem)


def status_args():
    """Executor options for this cluster: job status from squeue where there is no accounting database
    (sacct then knows no job, and Snakemake would wait for ever), and a short first status check."""
    args = ["--slurm-init-seconds-before-status-checks", "5"]
    try:
        config = subprocess.run(["scontrol", "show", "config"], capture_output=True, text=True, timeout=30).stdout
    except (OSError, subprocess.TimeoutExpired):
        config = ""
    storage = re.search(r"^AccountingStorageType\s*=\s*(\S+)", config, re.MULTILINE)
    if storage is None or storage.group(1) == "accounting_storage/none":
        args += ["--slurm-status-command", "squeue"]
    return args


def snakemake_slurm(cwd, *args):
    """Run the workflow in ``cwd`` with ``profiles/slurm``; its jobs are cancelled if it hangs."""
    command = [sys.executable, "-m", "snakemake", "--profile", "profiles/slurm", *status_args(), *args]
    try:
        return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=TIMEOUT)
    except subprocess.TimeoutExpired as err:
        log = err.stderr.decode(errors="replace") if isinstance(err.stderr, bytes) else (err.stderr or "")
        run_id = re.search(r"SLURM run ID: (\S+)", log)
        if run_id:  # the executor names every job of a run after the run's id
            subprocess.run(["scancel", "--name", run_id.group(1)], capture_output=True)
        pytest.fail(f"the Slurm run took over {TIMEOUT} s:\n{log[-3000:]}")


def result_files(work):
    root = Path(work)
    return {p.relative_to(root): p.read_bytes() for p in sorted(root.glob(f"results/studies/{STUDY}/**/*.nc"))}


def test_ground_motion_study_on_slurm_equals_local_run(slurm, tmp_path, shipped_study):
    # shipped_study(...) runs the local study only when called, after the skip check
    work = copy_project(tmp_path)
    run = snakemake_slurm(work, "--configfile", f"config/studies/{STUDY}.yaml")
    assert run.returncode == 0, run.stderr[-3000:]
    assert "has been submitted with SLURM jobid" in run.stderr + run.stdout  # the jobs did go through Slurm

    on_slurm, local = result_files(work), result_files(shipped_study(STUDY))
    assert Path(f"results/studies/{STUDY}/{STUDY}.nc") in local
    assert sorted(on_slurm) == sorted(local)
    differ = [str(path) for path in local if on_slurm[path] != local[path]]
    assert not differ, f"differ from the local run: {differ}"
