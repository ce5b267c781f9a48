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
                       subcategory=fig)
                for fig in figs
            ],
            pdf=[f"figures/{fig}{{variant}}.pdf" for fig in figs],
        params:
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
