"""Snakemake adapter: a study's combined summaries and histories -> its standard plots."""

import csv
import io
from pathlib import Path

from _log import logged

from dccss.drawing import save
from dccss.files import write_text
from dccss.results import load
from dccss.studies import intensity_plots, plots

with logged(snakemake.log[0]):
    params = snakemake.params
    out = {Path(f).name: f for f in snakemake.output}
    combined = load(snakemake.input.combined)
    save(plots.maps(combined, params.marks, params.caption), out["maps.png"], out["maps.pdf"])
    if "spectra.png" in out:
        save(plots.spectra(combined, params.caption), out["spectra.png"], out["spectra.pdf"])
    if "ida.png" in out:
        save(intensity_plots.ida(combined, params.caption), out["ida.png"], out["ida.pdf"])
    if "fragility.png" in out:
        save(intensity_plots.fragility(combined, params.caption), out["fragility.png"], out["fragility.pdf"])
    if params.labels:
        runs = [{} for _ in params.labels]
        for path in snakemake.input.histories:
            model, i = Path(path).stem.rsplit("_", 1)
            runs[int(i)][model] = load(path)
        save(plots.histories(list(zip(params.labels, runs)), params.caption), out["histories.png"],
             out["histories.pdf"])
    if "convergence.png" in out:
        rows = plots.convergence_table(combined, list(zip(params.points, runs)))
        save(plots.convergence(rows, params.caption), out["convergence.png"], out["convergence.pdf"])
        table = io.StringIO()
        writer = csv.DictWriter(table, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows({k: f"{v:.6g}" if isinstance(v, float) else v for k, v in r.items()} for r in rows)
        write_text(table.getvalue(), out["convergence.csv"])
        for name, label, factor, _unit in plots.CONVERGENCE_PANELS:
            for group in dict.fromkeys(r["group"] for r in rows):
                mine = [r for r in rows if r["group"] == group]
                order = plots.fitted_order([r["dt"] for r in mine], [factor * r[name] for r in mine])
                print(f"{group}: {label}: fitted order {order:.3f}")
