"""The spatial models (bidirectional ground motion): ``dccss run`` on the shipped synthetic record
pair, 10 s at dt = 0.005 s (2000 steps), as a whole process (start, imports, run, netCDF written),
for each model. Lines:

    run motion=bidirectional model=stick_slip steps=2000 seconds=... ms_per_step=...

Run: python benchmarks/bidirectional.py [--repeats 3]
"""

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT / "config/studies/records"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        for model in ("compliant", "stick_slip"):
            case = Path(tmp) / f"{model}.yaml"
            case.write_text(yaml.safe_dump({
                "prototype": "DFP1", "dt": 0.005, "model": model,
                "excitation": {"kind": "record",
                               "file": [str(RECORDS / "synthetic.AT2"), str(RECORDS / "synthetic_y.AT2")],
                               "window": [0.0, 10.0], "baseline": "linear"}}))
            best = float("inf")
            for _ in range(args.repeats):
                start = time.perf_counter()
                subprocess.run([sys.executable, "-m", "dccss", "run", str(case), "-o", str(Path(tmp) / "out.nc"), "-q"],
                               check=True)
                best = min(best, time.perf_counter() - start)
            print(f"run motion=bidirectional model={model} steps=2000 seconds={best:.2f} "
                  f"ms_per_step={1e3 * best / 2000:.2f}", flush=True)


if __name__ == "__main__":
    main()
