# The paper's numbers are checked when the workflow is parsed: an entry naming an unknown kind,
# prototype, corner, model, dt or variant stops it before any job, naming the entry.
from dccss.paper import validation

try:
    validation.load_values("config/paper_values.yaml", validation.catalogue_from_config(config))
except ValueError as err:
    raise WorkflowError(f"config/paper_values.yaml:\n{err}") from None


rule validate:
    input:
        unpack(validation_inputs),
    output:
        md="figures/validation.md",
        csv="results/validation.csv",
        json="results/validation.json",
    params:
        script=script_hash("validate.py"),
        results=result_keys(),
        case_variants=list(config["case_sets"]),
        breakaway_variants=(config.get("breakaway") or {}).get("normals", []),
        library=VALIDATION_SOURCE,
    log:
        "logs/validate.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/validate.py"


rule check_validation:
    input:
        "results/validation.json",
    output:
        "results/validation.ok",
    params:
        script=script_hash("check_validation.py"),
    log:
        "logs/check_validation.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/check_validation.py"
