"""Write ``suite/RSN1001_SYN0.AT2`` ... ``RSN1012_SYN11.AT2``: a SYNTHETIC suite of 12 distinct records for the
intensity study (``config/studies/ida.yaml``) and the documentation's IDA and fragility figures.

These are not recorded earthquakes: real records may not be redistributed. Each record mixes the shipped synthetic
pair's two components (``synthetic.AT2``, ``synthetic_y.AT2``, written by ``make_synthetic.py``) at an angle,
shifts it in time (circularly), reverses every second one in time, and scales it by its own factor (0.5-1.5) and
length (9-14 s), all drawn from ``numpy.random.default_rng(2026)``: deterministic, byte for byte.

Usage: ``python config/studies/records/make_suite.py`` (rewrites the 12 files in ``suite/`` next to it). The tests
and benchmarks write other suites with ``write_suite`` (more records, pairs, other lengths).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from dccss.records import read_at2, write_peer

HERE = Path(__file__).resolve().parent
OUT = HERE / "suite"
RECORDS, SEED = 12, 2026


def write_suite(folder, n, seed=SEED, samples=(900, 1400), pairs=False) -> list[str]:
    """Write ``n`` records (pairs: two components each, azimuths 0 and 90) named RSN<1001..>_SYN<k> into
    ``folder``; returns their names (a pair's stem without its azimuth code)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    dt, a = read_at2(HERE / "synthetic.AT2")
    _, b = read_at2(HERE / "synthetic_y.AT2")
    rng = np.random.default_rng(seed)
    names = []
    for k in range(n):
        angle, shift = rng.uniform(0.0, np.pi), int(rng.integers(0, 800))
        size, length = rng.uniform(0.5, 1.5), int(rng.integers(*samples))
        x = np.roll(np.cos(angle) * a + np.sin(angle) * b, shift)
        y = np.roll(-np.sin(angle) * a + np.cos(angle) * b, shift)
        if k % 2:
            x, y = x[::-1], y[::-1]
        name = f"RSN{1001 + k}_SYN{k}"
        if pairs:
            write_peer(folder / f"{name}000.AT2", dt, size * x[:length], "G", title=f"SYN 2026, SYN{k}, 0")
            write_peer(folder / f"{name}090.AT2", dt, size * y[:length], "G", title=f"SYN 2026, SYN{k}, 90")
        else:
            write_peer(folder / f"{name}.AT2", dt, size * x[:length], "G", title=f"SYN 2026, SYN{k}, 0")
        names.append(name)
    return names


def main():
    names = write_suite(OUT, RECORDS)
    print(f"wrote {len(names)} records in {OUT}: {names[0]} ... {names[-1]}")


if __name__ == "__main__":
    main()
