"""Snakemake adapter: the datasets of a group of figures -> their PNG and PDF files."""

from _log import logged

from dccss import plotting
from dccss.results import load

with logged(snakemake.log[0]):
    files = {f: load(f) for f in snakemake.input}
    figures = snakemake.params.datasets
    for (fig, pairs), png, pdf in zip(figures.items(), snakemake.output.png, snakemake.output.pdf):
        datasets = {}
        for key, path in pairs:
            ds = files[path]
            if "dXg" in ds.dims:  # key (prototype, dXg): one step size of a breakaway sweep
                ds = ds.sel(dXg=key[1]).assign_attrs(dXg_m=key[1])
            datasets[tuple(key)] = ds
        plotting.save(plotting.render(fig, datasets, snakemake.params.caption), png, pdf)
        print(f"{fig}: {png}, {pdf}")
