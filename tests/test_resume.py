"""A reproduction killed with SIGKILL in the middle and started again completes, with outputs
byte-identical to an uninterrupted run and no temporary file left behind (this is also the check
that two runs of the reproduction give byte-identical results; that they give byte-identical figures
and animations, the check that a fresh run draws the committed ones)."""

import hashlib
import os
import signal
import subprocess
import sys
import time

from conftest import copy_project, snakemake

#: the results and their validation (the figures and animations read them: test_workflow.py checks those)
TARGETS = ("results/validation.ok", "figures/validation.md")


def digests(root):
    files = [*root.glob("results/**/*.nc"), root / "results/validation.json", root / "figures/validation.md"]
    return {str(f.relative_to(root)): hashlib.sha256(f.read_bytes()).hexdigest() for f in sorted(files)}


def test_killed_run_resumes_to_identical_outputs(reproduction, tmp_path):
    work = copy_project(tmp_path)
    proc = subprocess.Popen([sys.executable, "-m", "snakemake", "--profile", "profiles/default", *TARGETS], cwd=work,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 120
    while len(list(work.glob("results/**/*.nc"))) < 6 and time.monotonic() < deadline:
        time.sleep(0.05)
    assert proc.poll() is None, "the run ended before it could be interrupted"
    os.killpg(proc.pid, signal.SIGKILL)  # the scheduler and every running job, mid-write
    proc.wait()
    done = len(list(work.glob("results/**/*.nc")))
    assert 6 <= done < 20  # interrupted in the middle

    assert snakemake(work, "--unlock").returncode == 0  # SIGKILL leaves Snakemake's lock behind
    resumed = snakemake(work, *TARGETS)
    assert resumed.returncode == 0, resumed.stderr[-3000:]
    assert digests(work) == digests(reproduction)
    assert list(work.rglob("*.tmp")) == []
