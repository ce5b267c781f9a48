"""Snakemake adapter: the datasets of a group of figures -> their PNG and PDF files."""

from _log import logged

from dccss.drawing import save
from dccss.paper.figures import figure_spec, render
from dccss.results import load

with logged(snakemake.log[0]):
    files = {f: load(f) for f in snakemake.input}
    paths = snakemake.params.datasets
    for (fig, entry), png, pdf in zip(snakemake.params.figures.items(), snakemake.output.png, snakemake.output.pdf):
        save(render(figure_spec(fig, entry), [files[p] for p in paths[fig]], snakemake.params.caption), png, pdf)
        print(f"{fig}: {png}, {pdf}")
