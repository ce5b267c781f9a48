# The report's pages of a workflow's outputs (the rules that write them are in report.smk).

def report_pages(files):
    """The report's page of each animation (GIF) and of the validation report among ``files``."""
    pages = []
    for f in files:
        if f.endswith(".gif") and f.startswith("figures/"):
            pages.append(f"results/report/{f.removeprefix('figures/').removesuffix('.gif')}.html")
        elif f == "figures/validation.md":
            pages.append("results/report/validation.html")
    return pages
