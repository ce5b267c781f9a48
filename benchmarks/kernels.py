"""The compiled planar kernels' sweep throughput, this checkout against another revision in one run.

N cases of DFP1-type devices (pad angles alpha21 = alpha23 spread over 6..12 deg), 1000 steps each
(sine of 0.27 m at 30 rad/s over 1 s, dt = 0.001 s), reduced to per-case summaries by the compiled
kernels (DCCSS_BACKEND=numba, ``dccss.mechanics.summaries.summarize``), both models, on both cores.
Each measurement is a fresh process that warms the kernels up (loads or compiles them) and takes the
best of --repeat calls; with --baseline REV the same runs on revision REV (a temporary git worktree),
alternating with this checkout's --rounds times, so both see the same machine load. Lines:

    kernels tree=checkout model=compliant N=10000 steps=1000 case_steps_per_s=...
    ratio model=compliant checkout_over_baseline=...   (the best rounds of each)

Run: python benchmarks/kernels.py [--baseline REV] [--n 10000] [--repeat 3] [--rounds 2]
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

from worktree import worktree

ROOT = Path(__file__).resolve().parents[1]
MODELS = ("compliant", "stick_slip")


def measure(n, repeat):
    """Case-steps per second of each model on this interpreter's dccss."""
    import numpy as np

    from dccss.excitation import Sine
    from dccss.mechanics.geometry import Geometry
    from dccss.mechanics.summaries import summarize
    from dccss.paper.prototypes import TABLE1

    steps = 1000
    geometry = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.linspace(6.0, 12.0, n),
                                        "alpha23": np.linspace(6.0, 12.0, n)})
    Xg = Sine(0.27, 30.0, 1.0).displacement(np.arange(steps + 1) * (1.0 / steps))
    out = {}
    for model in MODELS:
        summarize(model, geometry, Xg)  # warm-up: load or compile the kernels
        best = float("inf")
        for _ in range(repeat):
            start = time.perf_counter()
            summarize(model, geometry, Xg)
            best = min(best, time.perf_counter() - start)
        out[model] = n * steps / best
    return out


def run(tree, n, repeat):
    """``measure`` in a fresh process on the dccss of ``tree`` (None: this checkout)."""
    env = {**os.environ, "DCCSS_BACKEND": "numba"}
    if tree is not None:
        env["PYTHONPATH"] = str(tree)
    res = subprocess.run([sys.executable, __file__, "--inner", "--n", str(n), "--repeat", str(repeat)], env=env,
                         check=True, capture_output=True, text=True, cwd=tree or ROOT)
    return json.loads(res.stdout.splitlines()[-1])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", help="a git revision to time in the same run (e.g. HEAD~1)")
    parser.add_argument("--n", type=int, default=10000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--inner", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.inner:
        print(json.dumps(measure(args.n, args.repeat)))
        return
    best = {"checkout": dict.fromkeys(MODELS, 0.0), "baseline": dict.fromkeys(MODELS, 0.0)}
    with worktree(args.baseline) as tree:
        for _ in range(args.rounds):
            for name, where in (("checkout", None), ("baseline", tree)):
                if name == "baseline" and tree is None:
                    continue
                speeds = run(where, args.n, args.repeat)
                for model in MODELS:
                    print(f"kernels tree={name} model={model} N={args.n} steps=1000 "
                          f"case_steps_per_s={speeds[model]:.4g}", flush=True)
                    best[name][model] = max(best[name][model], speeds[model])
    if args.baseline:
        for model in MODELS:
            print(f"ratio model={model} checkout_over_baseline={best['checkout'][model] / best['baseline'][model]:.3f}")

if __name__ == "__main__":
    main()
