"""The figures of docs/how-to/intensity-and-fragility.md: docs/img/ida.png and docs/img/fragility.png.

The how-to's study, the shipped config/studies/ida.yaml (DFP1 on its structure, 12 records at 8 levels of
Sa(T_isolated), the friction's three bounds, the compliant model, Δt = 0.02 s), run as a user runs it, by
``snakemake --profile profiles/default --configfile config/studies/ida.yaml`` in a temporary copy of the project
(Snakefile, config, workflow, profiles), on the 12 shipped synthetic records in PEER's format
(config/studies/records/suite, written by config/studies/records/make_suite.py: the shipped synthetic pair's
components mixed, shifted, some reversed in time, each at its own amplitude: real records cannot be
redistributed). The workflow's ``ida.png`` and ``fragility.png`` are
copied as drawn, and the fitted medians and dispersions printed (the how-to quotes them). About 30 s on two cores.

Run: python docs/intensity_fragility.py
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import xarray as xr

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "docs" / "img"


def main():
    with tempfile.TemporaryDirectory() as work:
        work = Path(work)
        for name in ("Snakefile", "config", "workflow", "profiles"):
            (shutil.copytree if (ROOT / name).is_dir() else shutil.copy)(ROOT / name, work / name)
        run = subprocess.run([str(Path(sys.executable).parent / "snakemake"), "--profile", "profiles/default",
                              "--configfile", "config/studies/ida.yaml"], cwd=work, capture_output=True, text=True)
        if run.returncode:
            print(run.stderr[-3000:])
            raise SystemExit(run.returncode)
        for name in ("ida", "fragility"):
            shutil.copy(work / f"figures/studies/ida/{name}.png", OUT / f"{name}.png")
            print(f"wrote {OUT / f'{name}.png'}")
        ds = xr.open_dataset(work / "results/studies/ida/ida.nc")
        for limit in ("ring", "stroke_15cm"):
            for bound in ds["property"].values:
                sel = {"model": "compliant", "property": bound}
                z = ds[f"fragility_{limit}_exceeded"].sel(sel).values.tolist()
                n = ds[f"fragility_{limit}_counted"].sel(sel).values.tolist()
                print(f"{limit} {bound}: {ds[f'fragility_{limit}_fit'].sel(sel).values}, "
                      f"θ = {float(ds[f'fragility_{limit}_median'].sel(sel)):.4f} g, "
                      f"β = {float(ds[f'fragility_{limit}_dispersion'].sel(sel)):.4f}, exceeded {z} of {n}")
        print("record_intensity (m s-2):", [round(v, 4) for v in ds["record_intensity"].values.tolist()])
        print("chunks:", sorted(p.name for p in (work / "results/studies/ida/chunks").iterdir()))


if __name__ == "__main__":
    main()
