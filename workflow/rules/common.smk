# Paths and parameters derived from the configuration (no computation here).
from snakemake.exceptions import WorkflowError

from dccss.case import CaseError, geometry_from
from dccss.plotting import FIGURES


def check_config():
    """What the schema cannot say: names that refer to each other, and each device's geometry."""
    for name, params in config["prototypes"].items():
        try:
            geometry_from(params, f"prototypes.{name}")
        except CaseError as err:
            raise WorkflowError(f"config: {err}") from None
    for case_set, spec in config["case_sets"].items():
        for proto in spec["cases"]:
            if proto not in config["prototypes"]:
                raise WorkflowError(f"config: case_sets.{case_set}.cases: unknown prototype {proto!r}; "
                                    f"defined: {sorted(config['prototypes'])}")
    figures = config.get("figures", {})
    if "case_set" in figures and figures["case_set"] not in config["case_sets"]:
        raise WorkflowError(f"config: figures.case_set: unknown case set {figures['case_set']!r}; "
                            f"defined: {sorted(config['case_sets'])}")
    normals = (config.get("breakaway") or {}).get("normals", [])
    if "breakaway_normals" in figures and figures["breakaway_normals"] not in normals:
        raise WorkflowError(f"config: figures.breakaway_normals: {figures['breakaway_normals']!r} is not among "
                            f"breakaway.normals {normals}")
    if config["duration"] < max(config["dt"]):
        raise WorkflowError(f"config: dt: {max(config['dt'])} s is larger than the duration {config['duration']} s")


check_config()


def dt_label(dt):
    return f"{dt:g}"


def case_path(case_set, proto, model, dt):
    return f"results/cases/{case_set}/{proto}_{model}_dt{dt_label(dt)}.nc"


def breakaway_path(proto, normals):
    return f"results/breakaway/{proto}_{normals}.nc"


def all_cases():
    return [
        case_path(case_set, proto, model, dt)
        for case_set, spec in config["case_sets"].items()
        for proto in spec["cases"]
        for model in config["models"]
        for dt in config["dt"]
    ]


def all_breakaway():
    spec = config.get("breakaway")
    if not spec:
        return []
    return [breakaway_path(proto, normals) for proto in config["prototypes"] for normals in spec["normals"]]


def case_mappings(wildcards):
    """The dccss case mappings (see dccss.case) of a case set, prototype and model, one per dt."""
    return [case_mapping(wildcards, dt) for dt in config["dt"]]


def case_mapping(wildcards, dt):
    """The dccss case mapping of one simulation."""
    spec = config["case_sets"][wildcards.case_set]["cases"][wildcards.proto]
    case = {
        "id": f"{wildcards.case_set}/{wildcards.proto}_{wildcards.model}_dt{dt_label(dt)}",
        "prototype": config["prototypes"][wildcards.proto],
        "excitation": {"kind": "sine", "amplitude": spec["amplitude"], "omega": config["omega"],
                       "duration": config["duration"]},
        "theta2_0": spec["theta2_0"],
        "dt": dt,
        "model": wildcards.model,
        "normals": spec["normals"],
    }
    if "newton" in config:
        case["newton"] = config["newton"]
    return case


def breakaway_params(wildcards):
    spec = config["breakaway"]
    grid = spec["theta2_0"]
    n = int(round((grid["stop"] - grid["start"]) / grid["step"]))
    return {
        "prototype": config["prototypes"][wildcards.proto],
        "theta2_0": [round(grid["start"] + k * grid["step"], 10) for k in range(n + 1)],
        "dXg": spec["dXg"],
        "normals": wildcards.normals,
        "newton": config.get("newton", {}),
    }


def all_targets():
    """Every result; for the paper study (a `figures:` section) also its figures and checks."""
    paper = ["figures/validation.md", "results/validation.ok"] if "figures" in config else []
    return all_cases() + all_breakaway() + paper + figure_targets()


# --- figures ---
def figure_group(fig):
    """Figures are drawn in groups that read the same datasets: breakaway, compliant, stick_slip."""
    spec = FIGURES[fig]
    return "breakaway" if spec.kind == "breakaway" else spec.keys[0][1]


FIGURE_GROUPS = {}
for _fig in FIGURES:
    FIGURE_GROUPS.setdefault(figure_group(_fig), []).append(_fig)


def group_kind(group):
    return "breakaway" if group == "breakaway" else "cases"


def group_variant(group, variant):
    """The case set (time-history figures) or normal convention (breakaway figures) drawn."""
    if variant:
        return variant.lstrip("_")
    return config["figures"]["case_set" if group_kind(group) == "cases" else "breakaway_normals"]


def group_variants(group):
    """'' for the variant that reproduces the paper, '_<other>' for each companion."""
    main = group_variant(group, "")
    others = config["case_sets"] if group_kind(group) == "cases" else config["breakaway"]["normals"]
    return [""] + [f"_{o}" for o in others if o != main]


def figure_datasets(group, variant):
    """{figure: [(key, file)]} of the datasets each figure of a group draws (keys as in dccss.plotting)."""
    v = group_variant(group, variant)
    path = (lambda key: case_path(v, *key)) if group_kind(group) == "cases" else (
        lambda key: breakaway_path(key[0], v))
    return {fig: [(list(key), path(key)) for key in FIGURES[fig].keys] for fig in FIGURE_GROUPS[group]}


def figure_inputs(group, variant):
    return sorted({p for pairs in figure_datasets(group, variant).values() for _, p in pairs})


def figure_caption(group, variant):
    v = group_variant(group, variant)
    if group_kind(group) == "cases":
        return f"case set: {v} ({config['case_sets'][v].get('description', '')})"
    return f"breakaway sweep, {v} normals"


def figure_targets():
    if "figures" not in config:
        return []
    return [
        f"figures/{fig}{variant}.{ext}"
        for group, figs in FIGURE_GROUPS.items()
        for variant in group_variants(group)
        for fig in figs
        for ext in ("png", "pdf")
    ]


# --- validation ---
def validation_inputs(wildcards=None):
    return {"cases": all_cases(), "breakaway": all_breakaway(), "values": "config/paper_values.yaml"}


def result_keys():
    """(variant, prototype, model, dt) of every case file and (normals, prototype) of every sweep,
    in the order of validation_inputs."""
    cases = [
        [case_set, proto, model, dt]
        for case_set, spec in config["case_sets"].items()
        for proto in spec["cases"]
        for model in config["models"]
        for dt in config["dt"]
    ]
    spec = config.get("breakaway") or {"normals": []}
    sweeps = [[normals, proto] for proto in config["prototypes"] for normals in spec["normals"]]
    return {"cases": cases, "breakaway": sweeps}
