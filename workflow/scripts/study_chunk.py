"""Snakemake adapter: one chunk of a study's sweep under one model -> its summaries."""

import time
from pathlib import Path

from _log import logged

from dccss.files import write_netcdf
from dccss.studies import Study, run_chunk

with logged(snakemake.log[0]) as log:
    study = Study.from_config(snakemake.params.spec, Path(snakemake.params.study_dir))
    model, label = snakemake.wildcards.model, snakemake.wildcards.chunk
    # '<record>.<k>': the spec holds that record alone; '@<group>': that group's records, its only chunk
    k = 0 if label.startswith("@") else int(label.rsplit(".", 1)[-1])
    cases = study.grid.chunk(k)
    print(f"{model}, chunk {label}: {len(cases)} cases")
    start, shown = time.monotonic(), [0.0]

    def progress(n, total, size, dt):
        now = time.monotonic() - start
        if n == total or now - shown[0] >= 5.0:
            shown[0] = now
            print(f"  dt = {dt:g} s: {size} case(s) at step {n}/{total} ({100 * n / total:.0f} %), {now:.1f} s")

    ds = run_chunk(study, model, k, progress)
    write_netcdf(ds, snakemake.output[0])
    print(f"{len(cases)} cases done in {time.monotonic() - start:.1f} s: {int(ds['failed'].sum())} failed, "
          f"{int(ds['capacity_exceeded'].sum())} reached a retaining ring")
