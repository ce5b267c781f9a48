"""Snakemake adapter: one case mapping -> one netCDF dataset."""

import contextlib

from dccss.case import case_from
from dccss.files import write_netcdf

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    ds = case_from(snakemake.params.case).run()
    write_netcdf(ds, snakemake.output[0])
    print(f"{snakemake.params.case['id']}: {ds.sizes['time']} steps")
