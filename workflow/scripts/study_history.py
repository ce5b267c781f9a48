"""Snakemake adapter: one chosen case of a study, run in full -> its time-history dataset."""

import contextlib
from pathlib import Path

from dccss.files import write_netcdf
from dccss.study import Study

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    study = Study.from_config(snakemake.config, Path(snakemake.params.study_dir))
    case = study.history_case(int(snakemake.wildcards.i), snakemake.wildcards.model)
    write_netcdf(case.run(), snakemake.output[0])
