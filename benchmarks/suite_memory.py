"""Peak memory of a record-suite study: 10 records x 10 scales x 1000 devices = 10^5 cases, 4000 steps.

Writes ten 40 s synthetic PEER records (dt = 0.01 s: 4000 steps; the shipped synthetic shape, each
turned and cut differently) and a study over ``record`` (10), ``scale`` (10) and a 40 x 25 grid of
alpha21 x h2 on DFP1 (1000 devices), compliant sliding. Each workflow job is one record's chunk
(10^4 cases): this runs ``--chunks`` of them, each in a fresh process as the workflow does, and
prints the peak resident memory (ru_maxrss) and the time of each, e.g.

    suite_memory chunk=0 cases=10000 steps=4000 seconds=14.2 peak_mem_mb=612

Run: python benchmarks/suite_memory.py [--chunks 1] [--model compliant]
"""

import argparse
import multiprocessing as mp
import resource
import tempfile
import time
from pathlib import Path


def write_records(folder: Path):
    import numpy as np

    from dccss.records import read_at2, write_at2

    dt, a = read_at2(Path(__file__).resolve().parents[1] / "config/studies/records/synthetic.AT2")
    _, b = read_at2(Path(__file__).resolve().parents[1] / "config/studies/records/synthetic_y.AT2")
    for k in range(10):
        base = np.concatenate([a, b])  # 40 s
        write_at2(folder / f"R{k:02d}.AT2", dt, np.roll(base, 97 * k) * (0.6 + 0.05 * k))


def study_config():
    return {"study": {"name": "suite_memory"}, "prototype": "DFP1", "excitation": {"kind": "record"},
            "dt": 0.01, "models": ["compliant"], "on_failure": "mark",
            "sweep": {"record": ["R*.AT2"], "scale": {"start": 0.2, "stop": 1.0, "num": 10},
                      "alpha21": {"start": 6.0, "stop": 12.0, "num": 40},
                      "h2": {"start": 0.10, "stop": 0.20, "num": 25}}}


def measure(folder, model, k, queue):
    from dccss.studies import Study, run_chunk

    study = Study.from_config({**study_config(), "models": [model]}, Path(folder))
    cases = study.grid.chunk(k)
    start = time.perf_counter()
    ds = run_chunk(study, model, k)
    seconds = time.perf_counter() - start
    assert ds.sizes["case"] == len(cases)
    queue.put((len(cases), seconds, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chunks", type=int, default=1, help="how many of the 10 record chunks to run")
    parser.add_argument("--model", default="compliant")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        write_records(Path(folder))
        ctx = mp.get_context("spawn")
        for k in range(args.chunks):
            queue = ctx.Queue()
            process = ctx.Process(target=measure, args=(folder, args.model, k, queue))
            process.start()
            cases, seconds, peak = queue.get()
            process.join()
            print(f"suite_memory chunk={k} model={args.model} cases={cases} steps=4000 seconds={seconds:.1f} "
                  f"peak_mem_mb={peak:.0f}")


if __name__ == "__main__":
    main()
