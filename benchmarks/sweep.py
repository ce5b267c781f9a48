"""Batched sweep throughput: case-steps per second and peak memory, per model and batch size.

Each measurement runs in a fresh process (so the peak resident memory is its own): N cases of
DFP1-type devices with pad angles alpha21 spread over 6..12 deg, 1000 steps each (sine of
0.27 m at 30 rad/s over 1 s, dt = 0.001 s), reduced to per-case summaries on the fly
(``dccss.mechanics.summaries.summarize``) on the backend DCCSS_BACKEND names, or ("numpy", the
default here) on the tests' numpy reference (``tests/oracle.py``; benchmarks/backends.py compares
them). Prints one line per measurement, e.g.

    sweep backend=numpy model=compliant N=10000 steps=1000 case_steps_per_s=1234567 peak_mem_mb=850

Run: python benchmarks/sweep.py [--sizes 1 100 10000] [--steps 1000]
"""

import argparse
import multiprocessing as mp
import os
import resource
import sys
import time
from pathlib import Path

os.environ.setdefault("DCCSS_BACKEND", "numpy")  # inherited by the measuring processes


def measure(model, n, steps, queue):
    import numpy as np

    from dccss.excitation import Sine
    from dccss.mechanics.geometry import Geometry
    from dccss.mechanics.summaries import summarize
    from dccss.paper.prototypes import TABLE1

    if os.environ["DCCSS_BACKEND"] == "numpy":
        sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
        from oracle import summarize

    geometry = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.linspace(6.0, 12.0, n),
                                        "alpha23": np.linspace(6.0, 12.0, n)})
    excitation = Sine(0.27, 30.0, 1.0)
    Xg = excitation.displacement(np.arange(steps + 1) * (1.0 / steps))
    start = time.perf_counter()
    out = summarize(model, geometry, Xg)
    seconds = time.perf_counter() - start
    assert np.isfinite(out["theta2_max_abs"]).all()
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # kB on Linux
    queue.put((n * steps / seconds, peak_mb))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1, 100, 10000])
    parser.add_argument("--steps", type=int, default=1000)
    args = parser.parse_args()
    ctx = mp.get_context("spawn")
    for model in ("compliant", "stick_slip"):
        for n in args.sizes:
            queue = ctx.Queue()
            proc = ctx.Process(target=measure, args=(model, n, args.steps, queue))
            proc.start()
            rate, peak = queue.get()
            proc.join()
            print(f"sweep backend={os.environ['DCCSS_BACKEND']} "
                  f"model={model} N={n} steps={args.steps} case_steps_per_s={rate:.0f} peak_mem_mb={peak:.0f}",
                  flush=True)


if __name__ == "__main__":
    main()
