# only the configured names: a result the config does not define has no rule (no KeyError in a job)
wildcard_constraints:
    case_set=one_of(config["case_sets"]),
    proto=one_of(config["prototypes"]),
    model=one_of(config["models"]),
    normals=one_of((config.get("breakaway") or {}).get("normals", ["signed", "unsigned"])),


# one job per (case set, prototype, model) writes one file per time step: every figure and check
# reads both, so this costs no extra reruns and saves a process start per case. The simulations
# (about 1 s each) run first, so that the figures and animations (3-6 s) keep both cores busy to the end.
rule simulate:
    priority: 2
    output:
        [f"results/cases/{{case_set}}/{{proto}}_{{model}}_dt{dt_label(dt)}.nc" for dt in config["dt"]],
    params:
        script=script_hash("simulate.py"),
        cases=case_mappings,
        library=COMPUTE_SOURCE,
    log:
        "logs/simulate/{case_set}/{proto}_{model}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/simulate.py"


rule breakaway:
    priority: 2
    output:
        "results/breakaway/{proto}_{normals}.nc",
    params:
        script=script_hash("breakaway.py"),
        sweep=breakaway_params,
        library=COMPUTE_SOURCE,
    log:
        "logs/breakaway/{proto}_{normals}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/breakaway.py"
