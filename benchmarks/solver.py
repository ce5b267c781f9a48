"""Time one 1000-step history (DFP1, dt = 0.001 s, X_g,max = 0.27 m) per model, on the interpreted
kernels (DCCSS_BACKEND=python, what a paper history runs on) and on the tests' numpy reference
(``tests/oracle.py``, "numpy"), alternating in one process; or on the one backend DCCSS_BACKEND names.

Prints the best of several repeats: seconds per history and steps per second.
Run: python benchmarks/solver.py [--repeats N]
"""

import argparse
import os
import sys
import time
from pathlib import Path

from dccss.excitation import Sine, step_times
from dccss.mechanics import models
from dccss.paper.prototypes import DFP1

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import oracle  # noqa: E402  (the numpy reference)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args()
    excitation = Sine(amplitude=0.27, omega=30.0, duration=1.0)
    times = step_times(excitation, 0.001)
    Xg = excitation.displacement(times)
    steps = len(times) - 1
    backends = [os.environ["DCCSS_BACKEND"]] if os.environ.get("DCCSS_BACKEND") else ["python", "numpy"]
    for model in models.MODELS:
        best = dict.fromkeys(backends, float("inf"))
        for _ in range(args.repeats):
            for backend in backends:
                os.environ["DCCSS_BACKEND"] = backend
                run = oracle.run if backend == "numpy" else models.run
                start = time.perf_counter()
                run(model, DFP1, Xg, 0.0, times=times)
                best[backend] = min(best[backend], time.perf_counter() - start)
        for backend, seconds in best.items():
            print(f"solver backend={backend} model={model} steps={steps} seconds={seconds:.4f} "
                  f"steps_per_s={steps / seconds:.0f}")


if __name__ == "__main__":
    main()
