"""Time one 1000-step history (DFP1, dt = 0.001 s, X_g,max = 0.27 m) per model, on the numpy
reference unless DCCSS_BACKEND says otherwise.

Prints the best of several repeats: seconds per history and steps per second.
Run: python benchmarks/solver.py [--repeats N]
"""

import argparse
import os
import time

os.environ.setdefault("DCCSS_BACKEND", "numpy")

from dccss.excitation import Sine, step_times
from dccss.mechanics import models
from dccss.paper.prototypes import DFP1


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    excitation = Sine(amplitude=0.27, omega=30.0, duration=1.0)
    times = step_times(excitation, 0.001)
    Xg = excitation.displacement(times)
    steps = len(times) - 1
    for model in models.MODELS:
        best = float("inf")
        for _ in range(args.repeats):
            start = time.perf_counter()
            models.run(model, DFP1, Xg, 0.0, times=times)
            best = min(best, time.perf_counter() - start)
        print(f"solver backend={os.environ['DCCSS_BACKEND']} "
              f"model={model} steps={steps} seconds={best:.4f} steps_per_s={steps / best:.0f}")


if __name__ == "__main__":
    main()
