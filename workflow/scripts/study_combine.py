"""Snakemake adapter: the chunks of a study -> one dataset with a dimension per sweep axis."""

import contextlib
from pathlib import Path

from dccss.files import write_netcdf
from dccss.results import load
from dccss.study import Study

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    study = Study.from_config(snakemake.config, Path(snakemake.params.study_dir))
    chunks = {model: [] for model in study.models}
    for path in snakemake.input:
        ds = load(path)
        chunks[ds.attrs["model"]].append(ds)
    write_netcdf(study.combine(chunks), snakemake.output[0])
