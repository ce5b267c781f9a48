"""Snakemake adapter: compute every stated number from the results and write the reports."""

from _log import logged

from dccss import validation
from dccss.files import write_text
from dccss.results import load

keys = snakemake.params.results
with logged(snakemake.log[0]):
    cases = zip(keys["cases"], snakemake.input.cases)
    sweeps = zip(keys["breakaway"], snakemake.input.breakaway)
    results = validation.Results(
        cases={(v, p, m, float(dt)): load(f) for (v, p, m, dt), f in cases},
        breakaway={(v, p): load(f) for (v, p), f in sweeps},
    )
    rows = validation.evaluate(validation.load_values(snakemake.input["values"]), results,
                               snakemake.params.case_variants, snakemake.params.breakaway_variants)
    write_text(validation.to_json(rows), snakemake.output.json)
    write_text(validation.to_csv(rows, snakemake.params.case_variants, snakemake.params.breakaway_variants),
               snakemake.output.csv)
    write_text(validation.markdown(rows, snakemake.params.case_variants, snakemake.params.breakaway_variants),
               snakemake.output.md)
