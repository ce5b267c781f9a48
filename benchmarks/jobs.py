"""Where the reproduction's time goes, job by job.

Runs the workflow in a temporary copy of the project (its Snakefile, config, workflow and profiles; the
checkout's ``dccss`` first on PYTHONPATH, as ``benchmarks/workflow.sh`` does) from empty results, one
job at a time (``--cores 1``: a job's wall time is then its CPU time), under ``strace -f`` following
only process starts and ends, and lists each job's time (from its script's start to its exit, imports
and interpreter teardown included), by rule, with the totals. Snakemake's own process is listed apart.
Needs ``strace`` (with ``--seccomp-bpf``, so that the traced processes run at full speed).

Usage: python benchmarks/jobs.py [snakemake arguments...]
       e.g. python benchmarks/jobs.py --configfile config/studies/bidirectional.yaml
"""

from __future__ import annotations

import collections
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: a traced line: pid, time, then the call (or "+++ exited")
LINE = re.compile(r"^(\d+)\s+([\d.]+)\s+(.*)$")
#: a Snakemake job's script, as Snakemake writes it: .snakemake/scripts/tmpXXXX.<script>.py
SCRIPT = re.compile(r"\.snakemake/scripts/tmp\w+\.(\w+)\.py")


def main(args: list[str]) -> int:
    if shutil.which("strace") is None:
        sys.exit("benchmarks/jobs.py needs strace")
    with tempfile.TemporaryDirectory(prefix="dccss-jobs-") as tmp:
        work = Path(tmp)
        for name in ("Snakefile", "config", "workflow", "profiles"):
            (shutil.copytree if (ROOT / name).is_dir() else shutil.copy)(ROOT / name, work / name)
        trace = work / "trace.log"
        command = ["strace", "--seccomp-bpf", "-f", "-ttt", "-s", "300", "-e", "trace=execve,exit_group",
                   "-o", str(trace), str(ROOT / ".venv/bin/snakemake"), "--profile", "profiles/default", "--quiet",
                   "--cores", "1", *args]
        env = {**__import__("os").environ, "PYTHONPATH": str(ROOT)}
        run = subprocess.run(command, cwd=work, env=env, capture_output=True, text=True)
        if run.returncode:
            sys.exit(f"the workflow failed:\n{run.stderr[-3000:]}")
        jobs, main_process = _jobs(trace.read_text().splitlines())
    by_rule = collections.defaultdict(list)
    for script, seconds in jobs:
        by_rule[script].append(seconds)
    print("| job script | jobs | seconds each | seconds |")
    print("|---|---|---|---|")
    for script, times in sorted(by_rule.items(), key=lambda item: -sum(item[1])):
        print(f"| {script} | {len(times)} | {', '.join(f'{t:.2f}' for t in times)} | {sum(times):.1f} |")
    print(f"| all jobs | {len(jobs)} | | {sum(t for _, t in jobs):.1f} |")
    print(f"\nSnakemake's process: {main_process:.1f} s from start to end (the jobs run one at a time within it)")
    return 0


def _jobs(lines: list[str]) -> tuple[list[tuple[str, float]], float]:
    """(script, seconds) of each traced process that ran a job's script, in start order, and the first
    process's lifetime."""
    start, script, end = {}, {}, {}
    for line in lines:
        match = LINE.match(line)
        if not match:
            continue
        pid, when, call = int(match[1]), float(match[2]), match[3]
        if call.startswith("execve(") and pid not in start:
            start[pid] = when
        if call.startswith("execve(") and (found := SCRIPT.search(call)):
            script[pid] = found[1]
        if call.startswith("exit_group(") or call.startswith("+++ exited"):
            end[pid] = when
    first = min(start, key=start.get)
    jobs = [(script[pid], end[pid] - start[pid]) for pid in sorted(script, key=start.get) if pid in end]
    return jobs, end.get(first, max(end.values())) - start[first]


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
