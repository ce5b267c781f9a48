"""Snakemake adapter: the case mappings of one rule job -> one netCDF dataset each."""

import contextlib

from dccss.case import case_from
from dccss.files import write_netcdf

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    for case, path in zip(snakemake.params.cases, snakemake.output):
        ds = case_from(case).run()
        write_netcdf(ds, path)
        print(f"{case['id']}: {ds.sizes['t']} steps -> {path}")
