# One job per group of figures that read the same datasets, drawing every variant of them ("" and each
# "_<companion>"): one process start and one set of imports (about 1.1 s with matplotlib) for all.
for group, figs in FIGURE_GROUPS.items():

    rule:
        name:
            f"figures_{group}"
        priority: 1  # the longest jobs (4-6 s) first, the animations (1.5-4 s) fill the end
        input:
            lambda w, group=group: sorted({p for v in group_variants(group) for p in figure_inputs(group, v)}),
        output:
            png=[
                report(f"figures/{fig}{variant}.png", caption="../report/figure.rst", category="Figures",
                       subcategory=fig, labels={"figure": f"{fig}{variant}", "shows": FIGURES[fig].title,
                                                "draws": figure_caption(group, variant)})
                for variant in group_variants(group)
                for fig in figs
            ],
            pdf=[f"figures/{fig}{variant}.pdf" for variant in group_variants(group) for fig in figs],
        params:
            script=script_hash("figures.py"),
            variants=lambda w, group=group: [{"datasets": figure_datasets(group, v), "caption": figure_caption(group, v)}
                                             for v in group_variants(group)],
            figures={fig: config["figures"][fig] for fig in figs},
            titles={fig: FIGURES[fig].title for fig in figs},
            library=FIGURES_SOURCE,
        log:
            f"logs/figures/{group}.log",
        conda:
            "../envs/dccss.yaml"
        script:
            "../scripts/figures.py"


rule animate:
    priority: 0
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
