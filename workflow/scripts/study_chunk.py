"""Snakemake adapter: one chunk of a study's sweep under one model -> its summaries."""

import contextlib
from pathlib import Path

from dccss.files import write_netcdf
from dccss.study import Study

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    study = Study.from_config(snakemake.config, Path(snakemake.params.study_dir))
    ds = study.run_chunk(snakemake.wildcards.model, int(snakemake.wildcards.chunk))
    write_netcdf(ds, snakemake.output[0])
    print(f"{ds.sizes['case']} cases, {int(ds['failed'].sum())} failed")
