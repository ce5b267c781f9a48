"""Time of the articulated slider's response against the rigid slider's, in one run: a two-component record of
``--duration`` seconds at ``--dt`` (the shipped synthetic pair, 20 s at 0.01 s, repeated and resampled by
straight lines, times ``--scale``: deterministic; ``benchmarks/friction.py``'s), DFP1, through
``dccss.mechanics.structure.respond``, compiled (``DCCSS_BACKEND=numba`` unless set otherwise), each structure
warmed up first (compiling or loading its kernel), then the best of ``--repeat`` runs, the structures taken in
turn in each round. The structures, all on each surface (``friction_on: surfaces``), ζ = 0.02:

* rigid: μ = 0.03 / 0.06, the rigid slider (DOP853, the surfaces sliding in proportion);
* articulated: the same frictions on an articulated slider (one surface alone by DOP853, both by Radau IIA);
* rigid_velocity: speed laws 0.02-0.04 / 0.04-0.08, rate 20 s/m, the rigid slider;
* articulated_velocity: the same speed laws, articulated;
* articulated_together: μ̄_1 = μ̄_3 (the surfaces yield together: the rigid slider's answer).

Prints one line per structure and its ratio to the rigid slider's time under the same friction (the speed
laws' to ``rigid_velocity``'s, the others' to ``rigid``'s), e.g.

    articulated structure=articulated seconds=0.0874 ratio=2.82 stroke_max_m=0.3427 sticking=0.12 alone_1=0.48 ...

Run: python benchmarks/articulated.py [--duration 90] [--dt 0.005] [--scale 2.0] [--repeat 5]
"""

import argparse
import os
import sys
from pathlib import Path

os.environ.setdefault("DCCSS_BACKEND", "numba")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from friction import best_of, record  # noqa: E402  (the friction laws' benchmark's record and timing)

from dccss.mechanics import backend  # noqa: E402
from dccss.mechanics.structure import Ground, Structure  # noqa: E402
from dccss.mechanics.structure.sliders import pendulums  # noqa: E402
from dccss.paper.prototypes import DFP1  # noqa: E402

L1, L3 = pendulums(DFP1)
TOGETHER = 0.03 * float(DFP1.R1) / L1 * L3 / float(DFP1.R3)
VELOCITY = [{"law": "velocity", "slow": 0.02, "fast": 0.04, "rate": 20.0},
            {"law": "velocity", "slow": 0.04, "fast": 0.08, "rate": 20.0}]
STRUCTURES = {
    "rigid": Structure([0.03, 0.06], 0.02, "surfaces"),
    "articulated": Structure([0.03, 0.06], 0.02, "surfaces", slider="articulated"),
    "rigid_velocity": Structure(VELOCITY, 0.02, "surfaces"),
    "articulated_velocity": Structure(VELOCITY, 0.02, "surfaces", slider="articulated"),
    "articulated_together": Structure([0.03, TOGETHER], 0.02, "surfaces", slider="articulated"),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=90.0)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--scale", type=float, default=2.0)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    t, acc = record(args.duration, args.dt, args.scale)
    ground = Ground.from_samples(t, acc)
    responses, best = best_of(STRUCTURES, ground, t, args.repeat)
    print(f"articulated backend={os.environ[backend.ENV]} samples={t.size} duration_s={t[-1]:g} dt_s={args.dt:g} "
          f"scale={args.scale:g} repeat={args.repeat}")
    for name, seconds in best.items():
        r = responses[name]
        share = ""
        if r.surfaces is not None:
            sliding = r.surfaces.sliding
            share = (f" alone_1={np.mean(sliding[:, 0] & ~sliding[:, 1]):.2f} alone_3="
                     f"{np.mean(sliding[:, 1] & ~sliding[:, 0]):.2f} both={np.mean(sliding.all(axis=1)):.2f}")
        rigid = best["rigid_velocity" if name.endswith("velocity") else "rigid"]
        print(f"articulated structure={name} seconds={seconds:.4f} ratio={seconds / rigid:.2f} "
              f"stroke_max_m={r.peaks[0]:.4f} sticking={np.mean(r.sticking):.2f}{share}")


if __name__ == "__main__":
    main()
