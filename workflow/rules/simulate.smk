wildcard_constraints:
    case_set="[A-Za-z][A-Za-z0-9_]*",
    proto="[A-Za-z][A-Za-z0-9-]*",
    model="compliant|stick_slip",
    normals="signed|unsigned",


# one job per (case set, prototype, model) writes one file per time step: every figure and check
# reads both, so this costs no extra reruns and saves a process start per case
rule simulate:
    output:
        [f"results/cases/{{case_set}}/{{proto}}_{{model}}_dt{dt_label(dt)}.nc" for dt in config["dt"]],
    params:
        cases=case_mappings,
    log:
        "logs/simulate/{case_set}/{proto}_{model}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/simulate.py"


rule breakaway:
    output:
        "results/breakaway/{proto}_{normals}.nc",
    params:
        sweep=breakaway_params,
    log:
        "logs/breakaway/{proto}_{normals}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/breakaway.py"
