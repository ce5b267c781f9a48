# Paths and parameters derived from the configuration (no computation here).
from dccss.plotting import FIGURES


def dt_label(dt):
    return f"{dt:g}"


def dx_label(dXg):
    return f"{100 * dXg:g}cm"


def case_path(case_set, proto, model, dt):
    return f"results/cases/{case_set}/{proto}_{model}_dt{dt_label(dt)}.nc"


def breakaway_path(proto, normals, dXg):
    return f"results/breakaway/{proto}_{normals}_dX{dx_label(dXg)}.nc"


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
    return [
        breakaway_path(proto, normals, dXg)
        for proto in config["prototypes"]
        for normals in spec["normals"]
        for dXg in spec["dXg"]
    ]


def case_mapping(wildcards):
    """The dccss case mapping of one simulation (see dccss.case)."""
    spec = config["case_sets"][wildcards.case_set]["cases"][wildcards.proto]
    dt = next(d for d in config["dt"] if dt_label(d) == wildcards.dt)
    case = {
        "id": f"{wildcards.case_set}/{wildcards.proto}_{wildcards.model}_dt{wildcards.dt}",
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
        "dXg": next(d for d in spec["dXg"] if dx_label(d) == wildcards.dx),
        "normals": wildcards.normals,
        "newton": config.get("newton", {}),
    }


def all_targets():
    """Every result; for the paper study (a `figures:` section) also its figures and checks."""
    paper = ["figures/validation.md", "results/validation.ok"] if "figures" in config else []
    return all_cases() + all_breakaway() + paper + figure_targets()


# --- figures ---
def figure_variant(fig, variant):
    """The case set (time-history figures) or normal convention (breakaway figures) a figure file shows."""
    if variant:
        return variant.lstrip("_")
    key = "case_set" if FIGURES[fig].kind == "cases" else "breakaway_normals"
    return config["figures"][key]


def figure_inputs(wildcards):
    spec, variant = FIGURES[wildcards.fig], figure_variant(wildcards.fig, wildcards.variant)
    if spec.kind == "cases":
        return [case_path(variant, proto, model, dt) for proto, model, dt in spec.keys]
    return [breakaway_path(proto, variant, dXg) for proto, dXg in spec.keys]


def figure_caption(wildcards):
    variant = figure_variant(wildcards.fig, wildcards.variant)
    if FIGURES[wildcards.fig].kind == "cases":
        spec = config["case_sets"][variant]
        return f"case set: {variant} ({spec.get('description', '')})"
    return f"breakaway sweep, {variant} normals"


def figure_targets():
    if "figures" not in config:
        return []
    out = []
    for fig, spec in FIGURES.items():
        main = figure_variant(fig, "")
        others = config["case_sets"] if spec.kind == "cases" else config["breakaway"]["normals"]
        for variant in [""] + [f"_{o}" for o in others if o != main]:
            out += [f"figures/{fig}{variant}.png", f"figures/{fig}{variant}.pdf"]
    return out


# --- validation ---
def validation_inputs(wildcards=None):
    return {"cases": all_cases(), "breakaway": all_breakaway(), "values": "config/paper_values.yaml"}


def result_keys():
    """(variant, prototype, model, dt) of every case file and (normals, prototype, dXg) of every sweep,
    in the order of validation_inputs."""
    cases = [
        [case_set, proto, model, dt]
        for case_set, spec in config["case_sets"].items()
        for proto in spec["cases"]
        for model in config["models"]
        for dt in config["dt"]
    ]
    spec = config.get("breakaway") or {"normals": [], "dXg": []}
    sweeps = [[normals, proto, dXg] for proto in config["prototypes"] for normals in spec["normals"] for dXg in spec["dXg"]]
    return {"cases": cases, "breakaway": sweeps}
