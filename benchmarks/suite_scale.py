"""Time and memory of a research-scale suite study run by the workflow: 22 records x 20 intensity levels x 3
friction bounds = 1 320 cases per model, one component, the isolated structure and the pad, both models, the
fragility of the ring fitted and the figures drawn.

Writes 22 distinct synthetic PEER records (``tests/suite_records.py``: 16-20 s at dt = 0.01 s, the shipped
shape mixed, shifted and reversed), a study of them on DFP1 (μ = 0.05, bounds 0.8 / 1.3, Sa(T_isolated) levels
0.03-0.6 g) in a temporary copy of the project, compiles the kernels into a kernel cache first (``python -m
dccss.mechanics``: the warm cache the target is stated for), then runs ``snakemake --profile profiles/default``
(two cores) on it, with ``record_jobs`` jobs per model (``--record-jobs``, 0: a job per record), and prints its
wall time, the number of jobs, and the largest resident memory of any of its processes (getrusage of the
children: the largest job), e.g.

    suite_scale records=22 levels=20 bounds=3 cases_per_model=1320 record_jobs=8 jobs=21 seconds=95.1 peak_job_mb=412

Run: python benchmarks/suite_scale.py [--record-jobs 8] [--records 22] [--levels 20] [--repeat 1]
"""

import argparse
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from suite_records import write_suite  # noqa: E402


def study(records, levels, jobs) -> dict:
    config = {"study": {"name": "suite_scale", "description": "22 records x 20 levels x 3 bounds"},
              "prototype": "DFP1", "excitation": {"kind": "record", "baseline": "linear"}, "dt": 0.01,
              "models": ["compliant", "stick_slip"], "on_failure": "mark",
              "structure": {"friction": 0.05, "property": {"lower": 0.8, "upper": 1.3}},
              "intensity": {"measure": "sa"},
              "sweep": {"record": ["records_suite/*.AT2"], "intensity": {"start": 0.03, "stop": 0.6, "num": levels},
                        "property": ["lower", "nominal", "upper"]},
              "fragility": ["ring", {"name": "stroke_30cm", "variable": "stroke_max_abs", "above": 0.3}]}
    if jobs:
        config["record_jobs"] = jobs
    return config


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--record-jobs", type=int, default=8)
    parser.add_argument("--records", type=int, default=22)
    parser.add_argument("--levels", type=int, default=20)
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    env = {**os.environ, "NUMBA_CACHE_DIR": os.environ.get("NUMBA_CACHE_DIR", str(Path(tempfile.gettempdir())
                                                                                   / "dccss-suite-scale-cache"))}
    subprocess.run([sys.executable, "-m", "dccss.mechanics"], env=env, check=True, capture_output=True)  # warm
    for _ in range(args.repeat):
        with tempfile.TemporaryDirectory() as work:
            work = Path(work)
            for name in ("Snakefile", "config", "workflow", "profiles"):
                (shutil.copytree if (ROOT / name).is_dir() else shutil.copy)(ROOT / name, work / name)
            write_suite(work / "config/studies/records_suite", args.records, samples=(1600, 2000))
            (work / "config/studies/suite_scale.yaml").write_text(
                yaml.safe_dump(study(args.records, args.levels, args.record_jobs), sort_keys=False))
            before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
            start = time.perf_counter()
            run = subprocess.run([str(Path(sys.executable).parent / "snakemake"), "--profile", "profiles/default",
                                  "--configfile", "config/studies/suite_scale.yaml", "--quiet", "all"], cwd=work,
                                 env=env, capture_output=True, text=True)
            seconds = time.perf_counter() - start
            peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
            if run.returncode:
                print(run.stderr[-3000:])
                raise SystemExit(run.returncode)
            logs = list((work / "logs/studies/suite_scale").glob("*.log"))
            print(f"suite_scale records={args.records} levels={args.levels} bounds=3 "
                  f"cases_per_model={args.records * args.levels * 3} record_jobs={args.record_jobs} jobs={len(logs)} "
                  f"seconds={seconds:.1f} peak_job_mb={max(peak, before) / 1024:.0f}")
            for name in ("ida", "fragility", "maps"):
                figure = work / f"figures/studies/suite_scale/{name}.png"
                if figure.is_file():
                    shutil.copy(figure, Path(tempfile.gettempdir()) / f"suite_scale_{name}.png")


if __name__ == "__main__":
    main()
