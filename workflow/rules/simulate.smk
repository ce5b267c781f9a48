wildcard_constraints:
    case_set="[A-Za-z][A-Za-z0-9_]*",
    proto="[A-Za-z][A-Za-z0-9-]*",
    model="compliant|stick_slip",
    normals="signed|unsigned",
    dt="[0-9.e-]+",


rule simulate:
    output:
        "results/cases/{case_set}/{proto}_{model}_dt{dt}.nc",
    params:
        case=case_mapping,
    log:
        "logs/simulate/{case_set}/{proto}_{model}_dt{dt}.log",
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
