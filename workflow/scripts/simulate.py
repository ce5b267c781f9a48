"""Snakemake adapter: the case mappings of one rule job -> one netCDF dataset each."""

from _log import logged

from dccss.case import case_from
from dccss.files import write_netcdf

with logged(snakemake.log[0]):
    for case, path in zip(snakemake.params.cases, snakemake.output):
        ds = case_from(case).run()
        write_netcdf(ds, path)
        print(f"{case['id']}: {ds.sizes['t']} steps -> {path}")
