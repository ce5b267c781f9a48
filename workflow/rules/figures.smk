rule figure:
    input:
        figure_inputs,
    output:
        png=report(
            "figures/{fig}{variant}.png",
            caption="../report/figure.rst",
            category="Figures",
            subcategory="{fig}",
        ),
        pdf="figures/{fig}{variant}.pdf",
    params:
        datasets=lambda w: [list(k) for k in FIGURES[w.fig].keys],
        title=lambda w: FIGURES[w.fig].title,
        caption=figure_caption,
    wildcard_constraints:
        fig="fig[0-9]{2}",
        variant="(_[A-Za-z0-9_]+)?",
    log:
        "logs/figures/{fig}{variant}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/figure.py"
