wildcard_constraints:
    study=STUDY.name,
    model="compliant|stick_slip",
    chunk="[0-9]+|[A-Za-z0-9_.+-]+[.][0-9]+|@[0-9]+",
    i="[0-9]+",


rule study_chunk:
    input:
        lambda w: study_files(chunk_records(w.chunk)),
    output:
        "results/studies/{study}/chunks/{model}_{chunk}.nc",
    params:
        script=script_hash("study_chunk.py"),
        study_dir=str(STUDY_FILE.parent),
        spec=chunk_spec,
        library=COMPUTE_SOURCE,
    log:
        "logs/studies/{study}/{model}_{chunk}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/study_chunk.py"


rule study_combine:
    input:
        chunk_files(),
    output:
        "results/studies/{study}/{study}.nc",
    params:
        script=script_hash("study_combine.py"),
        study_dir=str(STUDY_FILE.parent),
        spec=sweep_spec(config),
        library=COMPUTE_SOURCE,
    log:
        "logs/studies/{study}/combine.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/study_combine.py"


# every history of a model in one job: a history takes 0.1-0.5 s, a job's start and imports about 0.6 s
if STUDY.histories:

    rule study_history:
        input:
            lambda w: sorted({f for point in STUDY.histories for f in study_files(point.get("record"))}),
        output:
            [f"results/studies/{{study}}/histories/{{model}}_{i}.nc" for i in range(len(STUDY.histories))],
        params:
            script=script_hash("study_history.py"),
            study_dir=str(STUDY_FILE.parent),
            cases=lambda w: [history_mapping(STUDY, i, w.model) for i in range(len(STUDY.histories))],
            library=COMPUTE_SOURCE,
        log:
            "logs/studies/{study}/histories_{model}.log",
        conda:
            "../envs/dccss.yaml"
        script:
            "../scripts/study_history.py"


rule study_plots:
    input:
        combined=f"results/studies/{STUDY.name}/{STUDY.name}.nc",
        histories=history_files(),
    output:
        [
            report(f, caption="../report/study.rst", category="Study")
            for f in study_plots()
            if f.endswith(".png")
        ],
        [f for f in study_plots() if not f.endswith(".png")],
    params:
        script=script_hash("study_plots.py"),
        caption=f"study {STUDY.name}: {STUDY.description}".rstrip(": "),
        marks=STUDY.marks,
        labels=history_labels(),
        points=STUDY.histories,
        library=STUDY_PLOTS_SOURCE,
    log:
        f"logs/studies/{STUDY.name}/plots.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/study_plots.py"


rule study_animate:
    input:
        "results/studies/{study}/histories/{model}_{i}.nc",
    output:
        "figures/studies/{study}/animations/{model}_{i}.gif",  # in the report as an HTML page (report.smk)
    params:
        script=script_hash("animate.py"),
        window={},
        library=ANIMATION_SOURCE,
    log:
        "logs/studies/{study}/animate_{model}_{i}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/animate.py"
