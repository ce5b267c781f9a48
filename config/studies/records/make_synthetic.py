"""Write ``synthetic.AT2`` and ``synthetic_y.AT2``: SYNTHETIC accelerograms for the recorded-motion studies.

This is not a recorded earthquake. Real records (e.g. from the PEER NGA-West2 database) may not be
redistributed, so the repository ships this deterministic stand-in with realistic amplitudes:

* 20 s at dt = 0.01 s (2000 samples), in the PEER ``.AT2`` format (units of g);
* stationary noise: a sum of 200 sines at evenly spaced frequencies from 0.3 to 5 Hz with random
  phases (``numpy.random.default_rng(2021)``), amplitudes (f/fc)² / (1 + (f/fc)²) with
  fc = 0.3 Hz, a gentle high-pass that limits the low-frequency content and thus the drift;
* a Jennings envelope: quadratic rise over 0-2 s, strong motion 2-8 s, exponential decay to
  exp(-3) ≈ 5 % at 20 s;
* scaled to a peak ground acceleration of 0.35 g.

``synthetic_v.AT2`` is its vertical component (line 2 ends ``UP``): the same recipe in a higher band,
1-10 Hz (vertical motions carry higher frequencies), seed 2023, a peak of 0.25 g.

``synthetic_y.AT2`` is a second horizontal component for bidirectional studies (a record pair,
``file: [records/synthetic.AT2, records/synthetic_y.AT2]``, x then y): the same recipe, dt and
NPTS with other random phases (seed 2022) and a peak of 0.30 g, so the pair shakes in both
directions with different histories. ``synthetic.AT2`` is the x component, byte for byte as
before.

After the default processing of ``dccss.records.Record`` (linear velocity baseline) the peak
ground displacement is about 15 cm (PGV about 0.38 m/s), below the ~19-22 cm capacity of the Table 1 prototypes;
for ``synthetic_y.AT2`` PGD is about 9.4 cm (PGV about 0.31 m/s), and the pair's peak horizontal
ground displacement max |(x, y)| is about 15 cm, reached at t = 2.1 s, within the 0-12 s window of the studies.

To run a study on a real record instead, download it as a PEER ``.AT2`` file (or ``.VT2``/``.DT2``,
or write a two-column text file whose header states the units, e.g. ``time (s), acceleration (g)``)
and point the case at it, e.g. in Python ``Record.from_file("RSN1234_NORTHR_XYZ090.AT2", scale=1.0,
window=(0.0, 20.0))``, or in a case file an excitation of kind ``record`` whose ``file`` is that
path (relative to the case file); ``units`` states the units of a file that does not. For a real
two-component pair give both horizontal components of the same station and event, e.g.
``file: [RSN1234_NORTHR_XYZ090.AT2, RSN1234_NORTHR_XYZ360.AT2]`` (x, then y: here x along the
090 component, y along 360); the two components of one recording
have the same dt; where their NPTS differ, a ``window`` both cover gives them the same samples.

Usage: ``python config/studies/records/make_synthetic.py`` (rewrites both files next to it).
"""

from pathlib import Path

import numpy as np

from dccss.records import Record, RecordPair, write_at2

DT = 0.01  # s
NPTS = 2000
PGA_G = 0.35
SEED = 2021
SEED_Y, PGA_G_Y = 2022, 0.30  # the y component
SEED_V, PGA_G_V, F_V = 2023, 0.25, (1.0, 10.0)  # the vertical component: its seed, peak (g) and band (Hz)
F_LO, F_HI, N_FREQ, F_CORNER = 0.3, 5.0, 200, 0.3  # Hz, Hz, -, Hz
RISE, STRONG_END, DECAY = 2.0, 8.0, 3.0  # s, s, e-folds from STRONG_END to the end
OUT = Path(__file__).with_name("synthetic.AT2")
OUT_Y = Path(__file__).with_name("synthetic_y.AT2")
OUT_V = Path(__file__).with_name("synthetic_v.AT2")


def envelope(t):
    """Jennings envelope: (t/RISE)² up to RISE, 1 up to STRONG_END, then exponential decay."""
    decay = np.exp(-DECAY * (t - STRONG_END) / (t[-1] - STRONG_END))
    return np.where(t < RISE, (t / RISE) ** 2, np.where(t > STRONG_END, decay, 1.0))


def synthetic_acceleration(seed=SEED, pga_g=PGA_G, band=(F_LO, F_HI)):
    """(t, acceleration in g) of the synthetic record (default: ``synthetic.AT2``; ``seed=SEED_Y,
    pga_g=PGA_G_Y``: ``synthetic_y.AT2``; ``SEED_V, PGA_G_V, F_V``: ``synthetic_v.AT2``)."""
    rng = np.random.default_rng(seed)
    t = DT * np.arange(NPTS)
    f = np.linspace(*band, N_FREQ)
    amplitude = (f / F_CORNER) ** 2 / (1 + (f / F_CORNER) ** 2)
    phase = rng.uniform(0.0, 2 * np.pi, N_FREQ)
    noise = (amplitude[:, None] * np.sin(2 * np.pi * f[:, None] * t + phase[:, None])).sum(axis=0)
    acc = noise * envelope(t)
    return t, pga_g * acc / np.max(np.abs(acc))


def main():
    for out, seed, pga_g, component in ((OUT, SEED, PGA_G, ""), (OUT_Y, SEED_Y, PGA_G_Y, ", y component")):
        _, acc = synthetic_acceleration(seed, pga_g)
        write_at2(out, DT, acc, title=f"SYNTHETIC ACCELEROGRAM, NOT A RECORDED MOTION: dccss make_synthetic.py, "
                                      f"seed {seed}, {F_LO}-{F_HI} Hz, PGA {pga_g} g{component}",
                  database="dccss synthetic record (config/studies/records/make_synthetic.py)")
        record = Record.from_file(out)
        print(f"wrote {out}: {record.npts} samples, dt = {record.dt} s, PGA = {record.pga / 9.80665:.3f} g, "
              f"PGV = {record.pgv:.3f} m/s, PGD = {record.pgd:.3f} m")
    pair = RecordPair.from_files([OUT, OUT_Y])
    print(f"pair: peak horizontal ground displacement |(x, y)| = {pair.pgd:.3f} m")
    _, acc = synthetic_acceleration(SEED_V, PGA_G_V, F_V)
    write_at2(OUT_V, DT, acc, title=f"SYNTHETIC ACCELEROGRAM, NOT A RECORDED MOTION: dccss make_synthetic.py, seed "
                                    f"{SEED_V}, {F_V[0]}-{F_V[1]} Hz, PGA {PGA_G_V} g, UP",
              database="dccss synthetic record (config/studies/records/make_synthetic.py)")
    print(f"wrote {OUT_V}: the vertical component (UP), PGA = {np.max(np.abs(acc)):.3f} g")


if __name__ == "__main__":
    main()
