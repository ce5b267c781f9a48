"""Snakemake adapter: one result history -> its animation (dccss animate)."""

from _log import logged

from dccss.animation import animate

with logged(snakemake.log[0]):
    print(animate(snakemake.input[0], snakemake.output[0], **snakemake.params.window))
