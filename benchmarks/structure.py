"""Time of the isolated structure's response (dccss.mechanics.structure): one component (exact,
closed form) and two (DOP853 with stick events), on the shipped synthetic pair repeated to
``--duration`` seconds and resampled to ``--dt`` by straight lines (El Centro 1940 is 53.7 s at
0.01 s; NGA-West2 records are often at 0.005 s), DFP1 (L = 1.82 m), mu = 0.05. In-process, best of
``--repeat`` after a warm-up; prints e.g.

    structure components=1 duration_s=53.7 samples=10741 seconds=0.11 steps_per_s=97000

Run: python benchmarks/structure.py [--duration 53.7] [--dt 0.005] [--repeat 3]
"""

import argparse
import time
from pathlib import Path

import numpy as np

from dccss.mechanics.geometry import Geometry
from dccss.mechanics.structure import Ground, solve
from dccss.paper.prototypes import TABLE1
from dccss.records import G, read_at2


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=53.7)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    folder = Path(__file__).resolve().parents[1] / "config/studies/records"
    dt, ax = read_at2(folder / "synthetic.AT2")
    _, ay = read_at2(folder / "synthetic_y.AT2")
    t0 = dt * np.arange(ax.size)
    t = np.arange(0.0, args.duration + args.dt / 2, args.dt)
    acc = np.column_stack([np.interp(t % t0[-1], t0, a) for a in (ax, ay)]) * G
    L = Geometry.from_degrees(**TABLE1["DFP1"]).L
    for components, samples in ((1, acc[:, 0]), (2, acc)):
        ground = Ground.from_samples(t, samples)
        solve(ground, t[:200], L, 0.05, 0.0)  # warm-up (imports)
        best = np.inf
        for _ in range(args.repeat):
            start = time.perf_counter()
            solve(ground, t, L, 0.05, 0.0)
            best = min(best, time.perf_counter() - start)
        print(f"structure components={components} duration_s={args.duration:g} samples={t.size} seconds={best:.3g} "
              f"steps_per_s={t.size / best:.0f}")


if __name__ == "__main__":
    main()
