"""Snakemake adapter: the chunks of a study -> one dataset with a dimension per sweep axis."""

from pathlib import Path

from _log import logged

from dccss.files import write_netcdf
from dccss.results import load
from dccss.studies import Study, combine

with logged(snakemake.log[0]):
    study = Study.from_config(snakemake.params.spec, Path(snakemake.params.study_dir))
    chunks = {model: [] for model in study.models}
    for path in snakemake.input:
        ds = load(path)
        chunks[ds.attrs["model"]].append(ds)
    write_netcdf(combine(study, chunks), snakemake.output[0])
