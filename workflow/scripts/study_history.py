"""Snakemake adapter: the chosen cases of a study under one model, each run in full -> its time-history dataset."""

from pathlib import Path

from _log import logged

from dccss.case import case_from
from dccss.cli import warnings_of
from dccss.files import write_netcdf

with logged(snakemake.log[0]):
    for mapping, path in zip(snakemake.params.cases, snakemake.output, strict=True):
        case = case_from(mapping, Path(snakemake.params.study_dir))
        ds = case.run()
        write_netcdf(ds, path)
        for line in warnings_of(ds):
            print(f"warning: {line}")
        print(f"{case.id}: {ds.sizes['t'] - 1} steps -> {path}")
