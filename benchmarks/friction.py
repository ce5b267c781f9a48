"""Time of the isolated structure's response under the friction laws (dccss.mechanics.friction) against
Coulomb friction, in one run: a two-component record of ``--duration`` seconds at ``--dt`` (the shipped
synthetic pair, 20 s at 0.01 s, repeated and resampled by straight lines, times ``--scale``: deterministic),
DFP1 (L = 1.82 m), through ``dccss.mechanics.structure.respond``, compiled (``DCCSS_BACKEND=numba`` unless
set otherwise), each structure warmed up first (compiling or loading the kernel), then the best of
``--repeat`` runs, the structures taken in turn in each round. The structures:

* coulomb: μ = 0.06;
* velocity: slow 0.03, fast 0.08, rate 20 s/m (a PTFE-type liner, Constantinou, Mokha and Reinhorn 1990);
* velocity_flat: slow = fast = 0.06, the Coulomb friction above through the law's path (the cost of
  evaluating a law, the response the same to the integrator's accuracy);
* temperature: mu_ref 0.08, contact radius 0.2 m, pressure 30 MPa at N = W and p_ref 30 MPa, steel's
  diffusivity and conductivity (the defaults), T0 = 20 °C: the plate's temperature by the half-space sum,
  whose cost grows with the square of the samples.

Prints one line per structure and the ratios, e.g.

    friction law=velocity samples=18001 seconds=0.031 ratio=1.4 stroke_max_m=0.21 mu=0.030-0.080

Run: python benchmarks/friction.py [--duration 90] [--dt 0.005] [--scale 2.0] [--repeat 5]
"""

import argparse
import os
import time
from pathlib import Path

os.environ.setdefault("DCCSS_BACKEND", "numba")

import numpy as np  # noqa: E402

from dccss.mechanics import backend  # noqa: E402
from dccss.mechanics.structure import Ground, Structure, respond  # noqa: E402
from dccss.paper.prototypes import DFP1  # noqa: E402
from dccss.records import G, read_at2  # noqa: E402

STRUCTURES = {
    "coulomb": 0.06,
    "velocity": {"law": "velocity", "slow": 0.03, "fast": 0.08, "rate": 20.0},
    "velocity_flat": {"law": "velocity", "slow": 0.06, "fast": 0.06, "rate": 20.0},
    "temperature": {"law": "temperature", "mu_ref": 0.08, "contact_radius": 0.2, "pressure": 3.0e7,
                    "p_ref": 3.0e7},
}


def record(duration, dt, scale):
    """(t, a): the synthetic pair repeated to ``duration`` at ``dt`` (m/s², two columns), times ``scale``."""
    folder = Path(__file__).resolve().parents[1] / "config/studies/records"
    step, ax = read_at2(folder / "synthetic.AT2")
    _, ay = read_at2(folder / "synthetic_y.AT2")
    t0 = step * np.arange(ax.size)
    t = dt * np.arange(int(round(duration / dt)) + 1)
    return t, np.column_stack([np.interp(t % t0[-1], t0, a) for a in (ax, ay)]) * G * scale



def best_of(structures, ground, t, repeat):
    """Each structure's response to ``ground`` on DFP1 (after a warm-up run that compiles or loads its kernel, on
    the whole record) and its best time of ``repeat`` runs, the structures taken in turn in each round; every
    run must give the same bits."""
    responses = {name: respond(ground, t, DFP1, structure) for name, structure in structures.items()}
    best = dict.fromkeys(structures, np.inf)
    for _ in range(repeat):
        for name, structure in structures.items():
            start = time.perf_counter()
            response = respond(ground, t, DFP1, structure)
            best[name] = min(best[name], time.perf_counter() - start)
            assert np.array_equal(response.stroke, responses[name].stroke), f"{name}: not the same bits"
    return responses, best

def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=90.0)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--scale", type=float, default=2.0)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    t, acc = record(args.duration, args.dt, args.scale)
    ground = Ground.from_samples(t, acc)
    structures = {name: Structure(friction) for name, friction in STRUCTURES.items()}
    responses, best = best_of(structures, ground, t, args.repeat)
    print(f"friction backend={os.environ[backend.ENV]} samples={t.size} duration_s={t[-1]:g} dt_s={args.dt:g} "
          f"scale={args.scale:g} repeat={args.repeat}")
    for name, seconds in best.items():
        r = responses[name]
        mu = "0.060" if r.friction is None else f"{r.friction.min():.3f}-{r.friction.max():.3f}"
        hot = "" if r.temperature is None else f" temperature_max_C={r.temperature.max():.1f}"
        print(f"friction law={name} seconds={seconds:.4g} samples_per_s={t.size / seconds:.0f} "
              f"ratio={seconds / best['coulomb']:.2f} stroke_max_m={r.peaks[0]:.4f} "
              f"sticking={r.sticking.mean():.2f} mu={mu}{hot}")


if __name__ == "__main__":
    main()
