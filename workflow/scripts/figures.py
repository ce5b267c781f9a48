"""Snakemake adapter: the datasets of a group of figures -> their PNG and PDF files, in every variant."""

from _log import logged

from dccss.drawing import save
from dccss.paper.figures import figure_spec, render
from dccss.results import load

with logged(snakemake.log[0]):
    files = {f: load(f) for f in snakemake.input}
    figures = snakemake.params.figures
    drawn = [(variant, fig) for variant in snakemake.params.variants for fig in figures]
    for (variant, fig), png, pdf in zip(drawn, snakemake.output.png, snakemake.output.pdf, strict=True):
        save(render(figure_spec(fig, figures[fig]), [files[p] for p in variant["datasets"][fig]], variant["caption"]),
             png, pdf)
        print(f"{fig}: {png}, {pdf}")
