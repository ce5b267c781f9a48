"""Snakemake adapter: compute every stated number from the results and write the reports."""

from _log import logged

from dccss.files import write_text
from dccss.paper import validation
from dccss.results import load

keys = snakemake.params.results
with logged(snakemake.log[0]):
    catalogue = validation.catalogue_from_config(snakemake.config)
    values = validation.load_values(snakemake.input["values"], catalogue)
    results = validation.Results(
        cases={(v, p, m, float(dt)): load(f) for (v, p, m, dt), f in zip(keys["cases"], snakemake.input.cases)},
        breakaway={(v, p): load(f) for (v, p), f in zip(keys["breakaway"], snakemake.input.breakaway)},
    )
    variants = (catalogue.case_variants, catalogue.breakaway_variants)
    rows = validation.evaluate(values, results, *variants)
    write_text(validation.to_json(rows), snakemake.output.json)
    write_text(validation.to_csv(rows, *variants), snakemake.output.csv)
    write_text(validation.markdown(rows, *variants), snakemake.output.md)
