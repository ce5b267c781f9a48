"""Snakemake adapter: one chosen case of a study, run in full -> its time-history dataset."""

from pathlib import Path

from _log import logged

from dccss.case import case_from
from dccss.cli import warnings_of
from dccss.files import write_netcdf

with logged(snakemake.log[0]):
    case = case_from(snakemake.params.case, Path(snakemake.params.study_dir))
    ds = case.run()
    write_netcdf(ds, snakemake.output[0])
    for line in warnings_of(ds):
        print(f"warning: {line}")
    print(f"{case.id}: {ds.sizes['t'] - 1} steps -> {snakemake.output[0]}")
