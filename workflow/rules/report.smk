# Pages the report shows inline. `snakemake --report` shows PNG, SVG, JPEG, HTML and PDF files and
# offers anything else only for download: a GIF or a Markdown table becomes a small HTML page here.


rule report_animation:
    input:
        "figures/{path}.gif",
    output:
        report("results/report/{path}.html", caption="../report/animation.rst", category="Animations",
               labels={"animation": "{path}"}),
    wildcard_constraints:
        path=r"(studies/[^/]+/)?animations/[^/]+",
    params:
        script=script_hash("report_page.py"),
    log:
        "logs/report/{path}.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/report_page.py"


rule report_validation:
    input:
        "figures/validation.md",
    output:
        report("results/report/validation.html", caption="../report/validation.rst", category="Validation"),
    params:
        script=script_hash("report_page.py"),
    log:
        "logs/report/validation.log",
    conda:
        "../envs/dccss.yaml"
    script:
        "../scripts/report_page.py"

