rule validate:
    input:
        unpack(validation_inputs),
    output:
        md="figures/validation.md",
        csv=report("results/validation.csv", caption="../report/validation.rst", category="Validation"),
        json="results/validation.json",
    params:
        results=result_keys(),
        case_variants=list(config["case_sets"]),
        breakaway_variants=(config.get("breakaway") or {}).get("normals", []),
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
    log:
        "logs/check_validation.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/check_validation.py"
