"""The spatial models in process: one history of the shipped record pair (synthetic.AT2 along x,
synthetic_y.AT2 along y, 10 s, linear baseline) on DFP1 at dt = 0.001 s (10 000 steps), each model,
timed as the best of --repeat runs after one warm-up run (which loads or compiles the kernels).

With --baseline REV the same measurement runs, in the same invocation, on revision REV of this
repository (a temporary git worktree, in a subprocess), and the lines give the speed-up and the
largest differences of tilt, rise, pad centre and the end of sticking between the two:

    spatial model=compliant steps=10000 seconds=... steps_per_s=... [baseline_seconds=... speedup=...
            tilt_diff_rad=... rise_diff_m=... G_diff_m=... stick_G_diff_m=... stick_tilt_diff_rad=...]

Run: python benchmarks/spatial.py [--baseline REV] [--repeat 3] [--dt 0.001]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from worktree import worktree

ROOT = Path(__file__).resolve().parents[1]
RECORDS = ROOT / "config/studies/records"
MODELS = ("compliant", "stick_slip")


def measure(dt, repeat, save):
    """Time each model on this interpreter's dccss; save the compared quantities to ``save`` (.npz)."""
    from dccss.excitation import step_times
    from dccss.mechanics import spatial
    from dccss.paper.prototypes import DFP1
    from dccss.records import Record, RecordPair

    pair = RecordPair(*(Record.from_file(RECORDS / name, window=(0.0, 10.0), baseline="linear")
                        for name in ("synthetic.AT2", "synthetic_y.AT2")))
    times = step_times(pair, dt)
    Xg = pair.displacement(times)
    out, arrays = {}, {}
    for model in MODELS:
        spatial.run(model, DFP1, Xg[:50])  # warm-up: load or compile the kernels
        best = float("inf")
        for _ in range(repeat):
            start = time.perf_counter()
            h = spatial.run(model, DFP1, Xg)
            best = min(best, time.perf_counter() - start)
        d = spatial.diagnostics(h, DFP1)
        arrays.update({f"{model}_tilt": d["tilt"], f"{model}_rise": d["rise"], f"{model}_G": h["G"]})
        if "stick_G" in h:
            arrays[f"{model}_stick_G"] = h["stick_G"][1:]
            arrays[f"{model}_stick_tilt"] = spatial.tilt(h["stick_Q"][1:])[0]
        out[model] = {"steps": len(times) - 1, "seconds": best}
    np.savez(save, **arrays)
    return out


def baseline(rev, dt, repeat, save):
    """``measure`` on revision ``rev`` (a temporary worktree), in a subprocess."""
    with worktree(rev) as tree:
        env = {**os.environ, "PYTHONPATH": str(tree)}
        res = subprocess.run([sys.executable, __file__, "--inner", "--dt", str(dt), "--repeat", str(repeat),
                              "--save", str(save)], env=env, check=True, capture_output=True, text=True)
    return json.loads(res.stdout.splitlines()[-1])

def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", help="a git revision to time in the same run (e.g. HEAD~1)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--dt", type=float, default=0.001)
    parser.add_argument("--inner", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--save", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.inner:
        print(json.dumps(measure(args.dt, args.repeat, args.save)))
        return
    with tempfile.TemporaryDirectory() as tmp:
        ours = measure(args.dt, args.repeat, Path(tmp) / "ours.npz")
        base = baseline(args.baseline, args.dt, args.repeat, Path(tmp) / "base.npz") if args.baseline else None
        a = np.load(Path(tmp) / "ours.npz")
        b = np.load(Path(tmp) / "base.npz") if base else None
        for model in MODELS:
            r = ours[model]
            line = (f"spatial model={model} steps={r['steps']} seconds={r['seconds']:.4f} "
                    f"steps_per_s={r['steps'] / r['seconds']:.0f}")
            if base:
                s = base[model]["seconds"]
                line += f" baseline_seconds={s:.3f} speedup={s / r['seconds']:.1f}"
                for key in ("tilt", "rise", "G", "stick_G", "stick_tilt"):
                    name = f"{model}_{key}"
                    if name in a.files and name in b.files:
                        line += f" {key}_diff={np.max(np.abs(a[name] - b[name])):.2e}"
            print(line, flush=True)


if __name__ == "__main__":
    main()
