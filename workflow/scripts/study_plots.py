"""Snakemake adapter: a study's combined summaries and histories -> its standard plots."""

import contextlib
from pathlib import Path

from dccss import studyplots
from dccss.plotting import save
from dccss.results import load
from dccss.study import Study

with open(snakemake.log[0], "w") as log, contextlib.redirect_stdout(log), contextlib.redirect_stderr(log):
    study = Study.from_config(snakemake.config, Path(snakemake.params.study_dir))
    caption = f"study {study.name}: {study.description}"
    pngs = [f for f in snakemake.output if f.endswith(".png")]
    pdfs = [f for f in snakemake.output if f.endswith(".pdf")]
    save(studyplots.maps(load(snakemake.input.combined), study.marks, caption), pngs[0], pdfs[0])
    if study.histories:
        runs = []
        for path in snakemake.input.histories:
            model, i = Path(path).stem.rsplit("_", 1)
            point = ", ".join(f"{k} = {v}" for k, v in study.histories[int(i)].items())
            runs.append((f"{point} ({model})", load(path)))
        save(studyplots.histories(runs, caption), pngs[1], pdfs[1])
