# dccss: reproduce Bianco, Monti & Belfiore (2021) with one command:
#     snakemake --profile profiles/default
# or run a new study: snakemake --profile profiles/default --configfile config/studies/<name>.yaml
from snakemake.utils import validate


configfile: "config/config.yaml"


validate(config, "workflow/schemas/config.schema.yaml")


include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/validate.smk"


rule all:
    default_target: True
    input:
        all_targets(),
