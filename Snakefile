# dccss: reproduce Bianco, Monti & Belfiore (2021) with one command:
#     snakemake --profile profiles/default
# The workflow is workflow/Snakefile (the layout of the Snakemake workflow catalog); this file lets
# `snakemake` find it from the project's root as well.


include: "workflow/Snakefile"


workflow.default_target = "all"  # Snakemake keeps the includer's default target, which is none here
