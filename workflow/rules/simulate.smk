# only the configured names: a result the config does not define has no rule (no KeyError in a job)
wildcard_constraints:
    case_set=one_of(config["case_sets"]),
    proto=one_of(config["prototypes"]),


# One job per prototype of a case set writes its cases under every model and dt (a simulation takes
# 0.1-0.3 s, a job's start and imports about 0.6 s): a prototype or case set added to the config runs
# alone. The simulations run first, so that the figures and animations (1-6 s) keep both cores busy
# to the end.
rule simulate:
    priority: 2
    output:
        [case_path("{case_set}", "{proto}", model, dt) for model in config["models"] for dt in config["dt"]],
    params:
        script=script_hash("simulate.py"),
        cases=case_mappings,
        library=COMPUTE_SOURCE,
    log:
        "logs/simulate/{case_set}/{proto}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/simulate.py"


# the Fig. 7 sweeps of a prototype (each about 0.15 s) in one job
if config.get("breakaway"):

    rule breakaway:
        priority: 2
        output:
            [breakaway_path("{proto}", normals) for normals in config["breakaway"]["normals"]],
        params:
            script=script_hash("breakaway.py"),
            sweeps=breakaway_params,
            library=COMPUTE_SOURCE,
        log:
            "logs/breakaway/{proto}.log",
        conda:
            "../envs/dccss.yaml"
        script:
            "../scripts/breakaway.py"
