# Paths and parameters derived from the configuration (no computation here).
import re

from snakemake.exceptions import WorkflowError

from dccss.case import CaseError, geometry_from
from dccss.mechanics.models import MODELS
from dccss.paper.specs import Runs, SpecError, figure_specs


def dt_label(dt):
    return f"{dt:g}"


def case_path(case_set, proto, model, dt):
    return f"results/cases/{case_set}/{proto}_{model}_dt{dt_label(dt)}.nc"


def breakaway_path(proto, normals):
    return f"results/breakaway/{proto}_{normals}.nc"


def check_config():
    """What the schema cannot say: names that refer to each other, each device's geometry, and that
    every figure panel asks for a dataset the study runs. Returns the figure specs.

    Every mistake is reported before any job runs, one "config: <key>: <problem>" line each; a
    figure asking for a time step, model, prototype, ground step or variant that is not run is
    such a mistake (figures are neither skipped nor adapted).
    """
    errors = [*model_errors(), *prototype_errors(), *case_set_errors(), *dt_errors(), *breakaway_errors(),
              *animation_errors()]
    specs = {}
    try:
        specs = figure_specs(config.get("figures") or {}, runs())
    except SpecError as err:
        errors += err.errors
    if errors:
        raise WorkflowError("\n".join(f"config: {e}" for e in errors))
    return specs


def model_errors():
    for i, model in enumerate(config["models"]):
        if model not in MODELS:
            yield f"models[{i}]: unknown model {model!r}; registered: {list(MODELS)}"


def prototype_errors():
    for name, params in config["prototypes"].items():
        try:
            geometry_from(params, f"prototypes.{name}")
        except CaseError as err:
            yield str(err)


def case_set_errors():
    for case_set, spec in config["case_sets"].items():
        for proto in spec["cases"]:
            if proto not in config["prototypes"]:
                yield (f"case_sets.{case_set}.cases: unknown prototype {proto!r}; "
                       f"defined: {sorted(config['prototypes'])}")


def dt_errors():
    if config["duration"] < max(config["dt"]):
        yield f"dt: {max(config['dt'])} s is larger than the duration {config['duration']} s"
    labels = [dt_label(dt) for dt in config["dt"]]
    for label in sorted({x for x in labels if labels.count(x) > 1}):
        yield f"dt: {[dt for dt in config['dt'] if dt_label(dt) == label]} share the file name label dt{label}"


def breakaway_errors():
    grid = (config.get("breakaway") or {}).get("theta2_0")
    if grid and not breakaway_theta2_0(grid):
        yield (f"breakaway.theta2_0: the grid from start {grid['start']} to stop {grid['stop']} by step "
               f"{grid['step']} is empty (stop < start)")


def animation_errors():
    """Each animation names a result the study runs and a time window inside the motion."""
    for name, spec in (config.get("animations") or {}).items():
        key = f"animations.{name}"
        case_set = spec["case_set"]
        if case_set not in config["case_sets"]:
            yield f"{key}.case_set: unknown case set {case_set!r}; defined: {sorted(config['case_sets'])}"
        elif spec["prototype"] not in config["case_sets"][case_set]["cases"]:
            yield (f"{key}.prototype: {spec['prototype']!r} is not a case of case set {case_set!r}; "
                   f"its cases: {sorted(config['case_sets'][case_set]['cases'])}")
        if spec["model"] not in config["models"]:
            yield f"{key}.model: {spec['model']!r} is not run; models: {config['models']}"
        if spec["dt"] not in config["dt"]:
            yield f"{key}.dt: {spec['dt']} s is not run; dt: {config['dt']}"
        start, end = spec.get("start", 0.0), spec.get("end", config["duration"])
        if not 0 <= start < end:
            yield f"{key}: the window start {start} s .. end {end} s must have 0 <= start < end"


def runs():
    """The datasets the workflow computes, which the figures may draw."""
    spec = config.get("breakaway") or {}
    grid = breakaway_theta2_0(spec["theta2_0"]) if spec else []
    return Runs(prototypes=list(config["prototypes"]),
                case_sets={name: list(s["cases"]) for name, s in config["case_sets"].items()},
                models=config["models"], dt=config["dt"], duration=config["duration"],
                dXg=spec.get("dXg", []), normals=spec.get("normals", []),
                theta2_0=(min(grid), max(grid)) if grid else None)


def breakaway_theta2_0(grid):
    """The theta2(t0) values (deg) of the breakaway grid {start, stop, step}; empty if stop < start."""
    n = int(round((grid["stop"] - grid["start"]) / grid["step"]))
    return [round(grid["start"] + k * grid["step"], 10) for k in range(n + 1)]


def one_of(names):
    """A wildcard constraint matching exactly these names."""
    return "|".join(re.escape(name) for name in names)


FIGURES = check_config()  # {figure: dccss.paper.specs.FigureSpec}


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
    """The dccss case mappings (see dccss.case) of one prototype in one case set: each model, each dt."""
    if wildcards.proto not in config["case_sets"][wildcards.case_set]["cases"]:
        raise WorkflowError(f"config: case_sets.{wildcards.case_set}.cases: no prototype {wildcards.proto!r}")
    return [case_mapping(wildcards.case_set, wildcards.proto, model, dt) for model in config["models"]
            for dt in config["dt"]]


def case_mapping(case_set, proto, model, dt):
    """The dccss case mapping of one simulation."""
    spec = config["case_sets"][case_set]["cases"][proto]
    case = {
        "id": f"{case_set}/{proto}_{model}_dt{dt_label(dt)}",
        "prototype": config["prototypes"][proto],
        "excitation": {"kind": "sine", "amplitude": spec["amplitude"], "omega": config["omega"],
                       "duration": config["duration"]},
        "theta2_0": spec["theta2_0"],
        "dt": dt,
        "model": model,
        "normals": spec["normals"],
    }
    if "newton" in config:
        case["newton"] = config["newton"]
    return case


def breakaway_params(wildcards):
    """The Fig. 7 sweeps of one prototype, one per normal convention."""
    spec = config["breakaway"]
    return [{"prototype": config["prototypes"][wildcards.proto], "theta2_0": breakaway_theta2_0(spec["theta2_0"]),
             "dXg": spec["dXg"], "normals": normals, "newton": config.get("newton", {})}
            for normals in spec["normals"]]


def all_targets():
    """Every result; for the paper study (a `figures:` section) also its figures and checks; the
    animations."""
    paper = ["figures/validation.md", "results/validation.ok"] if "figures" in config else []
    targets = all_cases() + all_breakaway() + paper + figure_targets() + animation_targets()
    return targets + report_pages(targets)


# --- animations ---
def animation_targets():
    return [f"figures/animations/{name}.gif" for name in config.get("animations") or {}]


def animation_input(wildcards):
    spec = config["animations"][wildcards.name]
    return case_path(spec["case_set"], spec["prototype"], spec["model"], spec["dt"])


# --- figures ---

def figure_group(spec):
    """Figures are drawn in groups that read the same datasets: breakaway, or the models drawn
    (compliant, stick_slip, compliant_stick_slip)."""
    if spec.data == "breakaway":
        return "breakaway"
    return "_".join(sorted({panel.model for panel in spec.panels}))


FIGURE_GROUPS = {}
for _fig, _spec in FIGURES.items():
    FIGURE_GROUPS.setdefault(figure_group(_spec), []).append(_fig)


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


def panel_path(panel, kind, variant):
    """The result file a panel draws; a panel naming its own variant keeps it in every version."""
    v = panel.variant or variant
    if kind == "cases":
        return case_path(v, panel.prototype, panel.model, panel.dt)
    return breakaway_path(panel.prototype, v)


def figure_datasets(group, variant):
    """{figure: [file of each panel]} of the figures of a group."""
    v, kind = group_variant(group, variant), group_kind(group)
    return {fig: [panel_path(panel, kind, v) for panel in FIGURES[fig].panels] for fig in FIGURE_GROUPS[group]}


def figure_inputs(group, variant):
    return sorted({p for paths in figure_datasets(group, variant).values() for p in paths})


def figure_caption(group, variant):
    v = group_variant(group, variant)
    if group_kind(group) == "cases":
        return f"case set: {v} ({config['case_sets'][v].get('description', '')})"
    return f"breakaway sweep, {v} normals"


def figure_targets():
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
