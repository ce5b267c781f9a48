# One job per group of figures that read the same datasets, and per variant ("" or "_<companion>").
for group, figs in FIGURE_GROUPS.items():

    rule:
        name:
            f"figures_{group}"
        input:
            lambda w, group=group: figure_inputs(group, w.variant),
        output:
            png=[
                report(f"figures/{fig}{{variant}}.png", caption="../report/figure.rst", category="Figures",
                       subcategory=fig, labels={"figure": f"{fig}{{variant}}", "shows": FIGURES[fig].title})
                for fig in figs
            ],
            pdf=[f"figures/{fig}{{variant}}.pdf" for fig in figs],
        params:
            script=script_hash("figures.py"),
            datasets=lambda w, group=group: figure_datasets(group, w.variant),
            figures={fig: config["figures"][fig] for fig in figs},
            titles={fig: FIGURES[fig].title for fig in figs},
            caption=lambda w, group=group: figure_caption(group, w.variant),
            library=FIGURES_SOURCE,
        wildcard_constraints:
            variant=one_of(group_variants(group)),
        log:
            f"logs/figures/{group}{{variant}}.log",
        conda:
            "../envs/dccss.yaml"
        script:
            "../scripts/figures.py"


rule animate:
    priority: 1  # the longest jobs first
    input:
        animation_input,
    output:
        "figures/animations/{name}.gif",  # in the report as results/report/animations/{name}.html
    params:
        script=script_hash("animate.py"),
        window=lambda w: {k: v for k, v in config["animations"][w.name].items() if k in ("start", "end")},
        library=ANIMATION_SOURCE,
    wildcard_constraints:
        name=one_of(config.get("animations") or {}),
    log:
        "logs/animations/{name}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/animate.py"
