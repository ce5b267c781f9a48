"""A suite of distinct PEER-format records for tests and benchmarks: the shipped synthetic pair's two components
mixed at an angle, shifted, some reversed in time, each at its own amplitude and length (deterministic)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from dccss.records import read_at2, write_peer

RECORDS = Path(__file__).resolve().parent.parent / "config/studies/records"


def write_suite(folder, n, seed=2026, samples=(900, 1400), pairs=False) -> list[str]:
    """Write ``n`` records (pairs: two components each, azimuths 0 and 90) named RSN<1001..>_SYN<k> into
    ``folder``; returns their names (a pair's stem without its azimuth code)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    dt, a = read_at2(RECORDS / "synthetic.AT2")
    _, b = read_at2(RECORDS / "synthetic_y.AT2")
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
