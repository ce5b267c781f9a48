"""Snakemake adapter: the datasets of one figure -> its PNG and PDF."""

import contextlib

import xarray as xr

from dccss import plotting

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    datasets = {tuple(k): xr.load_dataset(f) for k, f in zip(snakemake.params.datasets, snakemake.input)}
    fig = plotting.render(snakemake.wildcards.fig, datasets, snakemake.params.caption)
    plotting.save(fig, snakemake.output.png, snakemake.output.pdf)
