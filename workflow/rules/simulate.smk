# only the configured names: a result the config does not define has no rule (no KeyError in a job)
wildcard_constraints:
    model=one_of(config["models"]),


# One job per model writes every case of it (each case set, prototype and dt): a simulation takes
# 0.1-0.3 s, a job's start and imports about 0.6 s. The simulations run first, so that the figures
# and animations (1-6 s) keep both cores busy to the end.
rule simulate:
    priority: 2
    output:
        [case_path(case_set, proto, "{model}", dt) for case_set, proto, dt in model_cases()],
    params:
        script=script_hash("simulate.py"),
        cases=case_mappings,
        library=COMPUTE_SOURCE,
    log:
        "logs/simulate/{model}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/simulate.py"


# every Fig. 7 sweep in one job (each about 0.15 s)
rule breakaway:
    priority: 2
    output:
        all_breakaway(),
    params:
        script=script_hash("breakaway.py"),
        sweeps=breakaway_params(),
        library=COMPUTE_SOURCE,
    log:
        "logs/breakaway.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/breakaway.py"
