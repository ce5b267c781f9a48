"""Snakemake adapter: a study's combined summaries and histories -> its standard plots."""

from pathlib import Path

from _log import logged

from dccss import studyplots
from dccss.plotting import save
from dccss.results import load

with logged(snakemake.log[0]):
    params = snakemake.params
    pngs = [f for f in snakemake.output if f.endswith(".png")]
    pdfs = [f for f in snakemake.output if f.endswith(".pdf")]
    save(studyplots.maps(load(snakemake.input.combined), params.marks, params.caption), pngs[0], pdfs[0])
    if params.labels:
        points = [(label, {}) for label in params.labels]
        for path in snakemake.input.histories:
            model, i = Path(path).stem.rsplit("_", 1)
            points[int(i)][1][model] = load(path)
        save(studyplots.histories(points, params.caption), pngs[1], pdfs[1])
