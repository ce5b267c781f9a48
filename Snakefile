# dccss: reproduce Bianco, Monti & Belfiore (2021) with one command:
#     snakemake --profile profiles/default
# or run a new study through the same library:
#     snakemake --profile profiles/default --configfile config/studies/<name>.yaml
from importlib.resources import files

from snakemake.utils import validate


if not config:  # no --configfile: the paper study

    configfile: "config/config.yaml"


include: "workflow/rules/library.smk"


if "study" in config:

    include: "workflow/rules/study_common.smk"  # checks every key and sweep point, with clear messages

    validate(config, str(files("dccss") / "schemas" / "study.schema.yaml"))  # the library's own schema

    include: "workflow/rules/study.smk"

else:

    validate(config, str(files("dccss") / "schemas" / "config.schema.yaml"))

    include: "workflow/rules/common.smk"
    include: "workflow/rules/simulate.smk"
    include: "workflow/rules/figures.smk"
    include: "workflow/rules/validate.smk"


rule all:
    default_target: True
    input:
        all_targets(),
