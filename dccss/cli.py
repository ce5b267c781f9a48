"""Command line: ``dccss run CASE.yaml -o OUT.nc|OUT.csv``, ``dccss check CASE_OR_STUDY.yaml``,
``dccss animate RESULT.nc -o OUT.gif|html|mp4`` and ``dccss plot RESULT.nc -o OUT.png|pdf`` (also
``python -m dccss ...``).

Exit codes: 0 written (also a history marked failed with ``on_failure: mark``), 2 bad input,
3 solver failure, 4 the pad reached a ring with ``capacity: error``. Warnings (an implausible
record, a retaining ring reached, a history cut short or marked failed) are one line each on
stderr; on a terminal (not with --quiet) a line says when the compiled kernels are compiled, once
per machine and version of dccss (10-30 s).
``dccss run --help`` lists the case file's keys (from its schema), the exit codes and the
``DCCSS_BACKEND`` environment variable. ``dccss run`` and ``dccss check`` do not import the
drawing code (matplotlib).
"""

from __future__ import annotations

import argparse
import logging
import os
import re
import sys
import textwrap
import time
import warnings
from pathlib import Path

import numpy as np

from ._version import __version__
from .case import CaseError, case_from, load_case, read_yaml
from .excitation import step_times
from .files import write_csv, write_netcdf
from .mechanics import backend, registry
from .mechanics.capacity import CapacityError
from .mechanics.newton import ConvergenceError
from .mechanics.scalar import log as kernels_log
from .mechanics.structure import G
from .results import failure_of, friction_text
from .schema import schema

#: what ``dccss run -o OUT`` writes, by the suffix of OUT
OUTPUTS = {".nc": "the netCDF dataset", ".csv": "a CSV table of the history (the dataset's attributes as # lines)"}
#: the exit codes of ``dccss run`` (``dccss check``: 0 valid, 2 not)
EXIT_CODES = {0: "written (also a history marked failed with on_failure: mark)",
              2: "bad input: the case file, the output path or DCCSS_BACKEND; nothing is run or written (or the output "
                 "could not be written)",
              3: "solver failure (on_failure: error); nothing is written",
              4: "the pad reached a retaining ring, or the structure lifted off its device (capacity: error); "
                 "nothing is written"}
#: what each value of DCCSS_BACKEND runs (``dccss.mechanics.backend``)
BACKEND_CHOICES = {"auto": "the kernels, compiled where the run is large enough for them to pay, interpreted "
                           "otherwise (the default; the same results to the last bit)",
                   "numba": "always the compiled kernels (an error where numba is not installed)",
                   "python": "always the kernels interpreted, on Python numbers"}


def _summary(ds) -> str:
    return _kinematics(ds) + _record(ds.attrs) + (_structure(ds) if "structure_friction" in ds.attrs else "")


def _record(a) -> str:
    """The peaks of a record (each component of a pair) after processing, and the scale applied."""
    parts = [("", "record_")] if "record_pga_m_per_s2" in a else \
        [(f"{i} ({a[f'record_{i}_source']}): ", f"record_{i}_") for i in (1, 2) if f"record_{i}_pga_m_per_s2" in a]
    if not parts:
        return ""
    peaks = "; ".join(f"{label}PGA = {a[p + 'pga_m_per_s2'] / G:.3g} g, PGV = {100 * a[p + 'pgv_m_per_s']:.3g} cm/s, "
                      f"PGD = {100 * a[p + 'pgd_m']:.3g} cm" for label, p in parts)
    scaled = (f": Sa(T = {a['record_scaling_period_s']:g} s, {100 * a['record_scaling_damping']:g} %) = "
              f"{a['record_scaled_to_sa_g']:g} g" if "record_scaled_to_sa_g" in a else "")
    if a.get("record_scaled_to") == "spectrum":
        low, high = a["record_scaling_periods_s"]
        scaled = (f": its suite's mean spectrum at or above {a['record_scaling_fraction']:g} x target over "
                  f"{low:g}-{high:g} s ({100 * a['record_scaling_damping']:g} %; a record alone is its own suite), "
                  f"its fit {a['record_scaling_fit']:.4g} x the suite's factor {a['record_scaling_suite_factor']:.4g}")
    return f"; record {peaks} (scale {a[parts[0][1] + 'scale']:g}{scaled})"


def _structure(ds) -> str:
    """Peak and residual stroke and peak F/W of a structure-driven history."""
    two = "stroke_x" in ds
    if two:
        residual = f"{100 * float(np.hypot(ds['stroke_x'].values[-1], ds['stroke_y'].values[-1])):.3f} cm"
    else:
        residual = f"{100 * float(ds['stroke'].values[-1]):+.3f} cm"
    end = ("residual stroke" if "stopped_at_s" not in ds.attrs and not ds.attrs.get("failed") else
           f"stroke where the history ends (t = {float(ds['t'].values[-1]):.6g} s)")  # a cut history has no residual
    a = ds.attrs  # the peaks over the record's samples too (not only the steps), over the whole record
    return (f"; structure ({friction_text(a).replace('μ', 'mu').replace('λ', 'lambda')}, "
            f"zeta = {a['structure_damping']:g}, "
            f"T = {a['structure_period_s']:.3g} s): peak |u| = {100 * a['structure_stroke_max_abs_m']:.3f} cm, "
            f"{end} = {residual}, peak |F/W| = {a['structure_shear_ratio_max_abs']:.4f}{_vertical(a)}")


def _vertical(a) -> str:
    """The vertical component's peak and the smallest N/W (and the uplift, if any) of a structure's history."""
    if "vertical_pga_m_per_s2" not in a:
        return ""
    lifted = (f"; lifts off at t = {a['uplift_at_s']:.6g} s, {a['uplift_count']} time(s), "
              f"{a['uplift_duration_s']:.3g} s in all" if "uplift_at_s" in a else "")
    return (f"; vertical PGA = {a['vertical_pga_m_per_s2'] / G:.3g} g, smallest N/W = "
            f"{a['structure_normal_ratio_min']:.3g}{lifted}")


def _surfaces(ds) -> str:
    """An articulated slider's history: each surface's largest displacement and the hinge's largest rotation."""
    peaks = []
    for j in (1, 3):
        if f"stroke_{j}_x" in ds:
            peak = float(np.max(np.hypot(ds[f"stroke_{j}_x"].values, ds[f"stroke_{j}_y"].values)))
        else:
            peak = float(np.max(np.abs(ds[f"stroke_{j}"].values)))
        peaks.append(f"max |u_{j}| = {100 * peak:.3f} cm")
    hinge = float(np.max(np.abs(ds["hinge_rotation"].values)))
    return f"articulated slider, {_steps(ds.sizes['t'])}: {', '.join(peaks)}, max hinge rotation = {hinge:.3f} deg"


def _kinematics(ds) -> str:
    if ds.attrs.get("model") == "articulated":
        return _surfaces(ds)
    if ds.attrs.get("motion") == "bidirectional":
        interp = max(float(np.nanmax(np.abs(ds[name].values))) for name in ds if name.startswith("I_"))
        return (f"{ds.attrs['model']}, bidirectional, {_steps(ds.sizes['t'])}: max tilt = "
                f"{np.nanmax(ds['tilt'].values):.3f} deg, max rise = {100 * float(ds['rise'].max()):.3f} cm, "
                f"max |interpenetration| = {1e3 * interp:.4g} mm")
    theta2 = ds["theta2"].values
    interp = max(float(np.nanmax(np.abs(ds[f"I_{c}"].values))) for c in "ABCD")
    return (f"{ds.attrs['model']}, {_steps(ds.sizes['t'])}: max |theta2| = "
            f"{np.nanmax(np.abs(theta2)):.3f} deg, max rise = {100 * float(ds['rise'].max()):.3f} cm, "
            f"max |interpenetration| = {1e3 * interp:.4g} mm")


def _steps(states) -> str:
    """The steps of a history of ``states`` stored instants (t_0 and the end of each step)."""
    return f"{states - 1} step{'' if states == 2 else 's'} ({states} state{'' if states == 1 else 's'})"


def warnings_of(ds) -> list[str]:
    """One line for each thing about a written history that its reader must know."""
    a, out = ds.attrs, []
    if "capacity_exceeded_at_s" in a:
        moved = (f", RB1 {100 * a['capacity_exceeded_displacement_m']:.4g} cm from its start"
                 if "capacity_exceeded_displacement_m" in a else "")
        out.append(f"the pad reaches the retaining ring of {a['capacity_exceeded_plate']} at "
                   f"t = {a['capacity_exceeded_at_s']:.6g} s{moved} and passes it by up to "
                   f"{1e3 * a['capacity_exceeded_by_m']:.3g} mm (capacity: {a['capacity_policy']})")
    for j, plate in ((1, "RB1"), (3, "RB3")):  # an articulated slider's halves, each at its own ring
        if f"ring_{j}_reached_at_s" in a:
            policy = a.get("capacity_policy", "continue")
            out.append(f"the half on surface {j} reaches the retaining ring of {plate} at t = "
                       f"{a[f'ring_{j}_reached_at_s']:.6g} s and passes it by up to "
                       f"{1e3 * a[f'ring_{j}_exceeded_by_m']:.3g} mm (capacity: {policy})")
    if "stopped_at_s" in a:
        out.append(f"capacity: stop cut the history short at t = {a['stopped_at_s']:.6g} s "
                   f"({ds.sizes['t'] - 1} steps written)")
    if failure_of(a) == "capacity":
        out.append(f"capacity: error ended the history at the ring, t = {a['failure_time_s']:.6g} s, marked failed "
                   f"(on_failure: mark): {a['failure_message']}")
    elif failure_of(a) == "solver":
        out.append(f"the solver failed at t = {a['failure_time_s']:.6g} s; the history is written up to the "
                   f"last converged step (on_failure: mark): {a['failure_message']}")
    return out


def _show_compiling(stream):
    """Say on ``stream`` when a kernel compiles (the first run of a version of dccss on a machine), which
    takes 10-30 s where a run otherwise takes well under a second: a terminal would seem to hang."""
    if any(getattr(h, "stream", None) is stream for h in kernels_log.handlers):
        return  # main() called again in one process
    handler = logging.StreamHandler(stream)
    handler.setFormatter(logging.Formatter("dccss: %(message)s"))
    kernels_log.addHandler(handler)
    kernels_log.setLevel(logging.INFO)


def _failed(args, kind, err, code) -> int:
    """Say why the case failed, remove an older file at the output path (it is not this case's result)
    and return the exit code."""
    path, note = Path(args.output), ""
    if path.is_file():
        path.unlink()
        note = f" ({args.output}, an older result there, was removed: it is not this case's)"
    print(f"dccss: {kind} in {args.case}: {err}{note}", file=sys.stderr)
    return code


def _warn_line(message, category, *args, **kwargs):
    return f"dccss: warning: {message}\n"


def _wrap(label, text, indent=15, width=100) -> str:
    """One entry of the help's lists: ``label`` in a column, ``text`` wrapped beside it."""
    return textwrap.fill(text, width, initial_indent=f"  {label:<{indent - 2}}", subsequent_indent=" " * indent)


def _case_keys() -> list[str]:
    """The case file's top-level keys, each with the first sentence of its description, its allowed values
    and its default, from dccss/schemas/case.schema.yaml."""
    spec, out = schema("case"), []
    for key, prop in spec["properties"].items():
        text = re.split(r"(?<=\.)\s+(?=[A-Z])", " ".join(prop.get("description", "").split()))[0].rstrip(".")
        allowed = prop.get("enum") or prop.get("properties", {}).get("kind", {}).get("enum") or \
            (registry.names() if key == "model" else ())
        if allowed and not all(re.search(rf"\b{re.escape(str(v))}\b", text) for v in allowed):
            text += f"; {'kind: ' if 'enum' not in prop and key != 'model' else ''}one of {', '.join(allowed)}"
        if key in spec["required"]:
            text += "; required"
        elif prop.get("default") is not None:
            text += f"; default {prop['default']}"
        out.append(_wrap(key, text))
    return out


def run_epilog() -> str:
    """The epilog of ``dccss run --help``: the case file's keys, the exit codes and DCCSS_BACKEND."""
    return "\n".join([
        "case file (YAML; lengths in m, angles in degrees, times in s; schema dccss/schemas/case.schema.yaml):",
        *_case_keys(), "", "output (-o), by its suffix:", *(_wrap(k, v) for k, v in OUTPUTS.items()), "",
        "exit codes:", *(_wrap(str(k), v) for k, v in EXIT_CODES.items()), "",
        textwrap.fill(f"environment: {backend.ENV}, which implementation runs the planar models (the spatial ones, "
                      "for two-component motion, always run compiled):", 100),
        *(_wrap(f"{backend.ENV}={k}", BACKEND_CHOICES[k], indent=23) for k in backend.BACKENDS),
    ])


def _output_error(output) -> str | None:
    """Why ``dccss run`` cannot write ``output`` (its suffix is not one of OUTPUTS, it is a folder, or its
    folder, made if missing, cannot be), or None: checked before the case runs."""
    path = Path(output)
    suffix = path.suffix.lower()
    if suffix not in OUTPUTS:
        what = f"unknown output suffix {suffix!r}" if suffix else "no suffix"
        allowed = ", ".join(f"{k} ({v.split(' (')[0]})" for k, v in OUTPUTS.items())
        return f"-o {output}: {what}; allowed: {allowed}"
    if path.is_dir():
        return f"-o {output}: is a folder; give a file name ending in {suffix}"
    folder = path.parent.absolute()  # made if missing: its nearest existing parent must be a writable folder
    while not folder.exists():
        folder = folder.parent
    if not folder.is_dir():
        return f"-o {output}: {str(folder)!r} is a file, not a folder"
    if not os.access(folder, os.W_OK):
        return f"-o {output}: the folder {str(folder)!r} is not writable"
    return None


def file_kind(mapping) -> str:
    """'case' or 'study': the kind of file whose keys ``mapping`` has. A key only a study file has (study,
    models, sweep, ...) makes a study file, else a key a case file has (a misspelt key aside) a case
    file; a CaseError says why it is neither (no key of either, or keys only a case file has beside
    keys only a study file has)."""
    if not isinstance(mapping, dict):
        raise CaseError(f"neither a case file nor a study file: expected a mapping of keys, got "
                        f"{type(mapping).__name__} {mapping!r}")
    case, study = set(schema("case")["properties"]), set(schema("study")["properties"])
    own_case, own_study = sorted(set(mapping) & (case - study)), sorted(set(mapping) & (study - case))
    if own_case and own_study:
        raise CaseError(f"neither a case file nor a study file: it has keys of both, {own_case} of a case file "
                        f"and {own_study} of a study file")
    if own_study:
        return "study"
    if set(mapping) & case:
        return "case"
    raise CaseError(f"neither a case file nor a study file: none of its keys {sorted(map(str, mapping))} is one "
                    f"of either; a case file has the keys {schema('case')['required']}, a study file "
                    f"{schema('study')['required']}")


def _validated(kind, mapping, base) -> str:
    """The summary of a case or study file's mapping (files relative to ``base``), checked."""
    if kind == "case":
        return _case_summary(case_from(mapping, base), mapping)
    from .studies import Study

    return _study_summary(Study.from_config(mapping, base))


def _case_summary(case, mapping) -> str:
    """One line on a valid case: model, device, ground motion, time span and steps."""
    proto = mapping["prototype"] if isinstance(mapping["prototype"], str) else "a device of its own"
    excitation, times = case.excitation, step_times(case.excitation, case.dt)
    two = " (two components)" if excitation.components == 2 else ""
    structure = "" if case.structure is None else (
        f", a structure (friction {case.structure.friction:g})" if isinstance(case.structure.friction, float) else
        f", a structure (friction: the {' + '.join(law.name for law, _ in case.structure.laws)} law)")
    return (f"model {case.model}, prototype {proto}, {mapping['excitation']['kind']} excitation{two}{structure}, "
            f"t = {times[0]:g} .. {times[-1]:g} s by dt = {case.dt:g} s: {_steps(times.size)}")


def _study_summary(study) -> str:
    """One line on a valid study: its cases and axes, models, chunks and histories."""
    grid, models = study.grid, study.models
    return (f"study {study.name}: {grid.n_cases} case{'' if grid.n_cases == 1 else 's'} "
            f"({' x '.join(f'{name} {len(values)}' for name, values in study.axes.items())}) under "
            f"{len(models)} model{'' if len(models) == 1 else 's'} ({', '.join(models)}), {grid.n_chunks} "
            f"chunk{'' if grid.n_chunks == 1 else 's'} per model, {len(study.histories)} "
            f"histor{'y' if len(study.histories) == 1 else 'ies'}")


def _check(args) -> int:
    """``dccss check FILE``: 0 and a summary if FILE is a valid case or study file, 2 and every error if not."""
    try:
        mapping = read_yaml(args.file)
        kind = file_kind(mapping)
    except CaseError as err:
        print(f"dccss: {args.file}: {err}", file=sys.stderr)
        return 2
    try:
        summary = _validated(kind, mapping, Path(args.file).parent)
    except CaseError as err:
        print(f"dccss: {args.file}: not a valid {kind} file: {err}", file=sys.stderr)
        return 2
    print(f"{args.file}: a valid {kind} file ({summary})")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="dccss", description="Kinematics of DCCSS isolators.")
    parser.add_argument("--version", action="version", version=f"dccss {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run one case file and write its dataset (netCDF) or history (CSV)",
                         description="Run one case file: its history, written as a netCDF dataset or a CSV table.",
                         epilog=run_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    run.add_argument("case", help="YAML case file")
    run.add_argument("-o", "--output", required=True,
                     help="file to write: OUT.nc (the netCDF dataset) or OUT.csv (a table of the history)")
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing on success (warnings still)")
    check = sub.add_parser("check", help="check a case file or a study file without running it",
                           description="Check a case file or a study file (told apart by their keys) without "
                                       "running anything: exit code 0 and a one-line summary if it is valid, 2 and "
                                       "every error otherwise.")
    check.add_argument("file", help="YAML case file or study file")
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] not in (["run"], ["check"]):  # these draw nothing: they do not import the drawing code (matplotlib)
        from . import animation, plan

        animation.add_parser(sub)
        plan.add_parser(sub)
    args = parser.parse_args(argv)
    warnings.formatwarning = _warn_line  # "dccss: warning: ...", not the library's file and line
    if hasattr(args, "handler"):
        return args.handler(args)
    if args.command == "check":
        return _check(args)
    start = time.perf_counter()
    problem = _output_error(args.output)
    if problem is not None:
        print(f"dccss: error: {problem}", file=sys.stderr)
        return 2
    try:
        backend.check()
    except (ValueError, backend.BackendError) as err:
        print(f"dccss: error: {err}", file=sys.stderr)
        return 2
    if sys.stderr.isatty() and not args.quiet:
        _show_compiling(sys.stderr)
    try:
        ds = load_case(args.case).run()
    except CaseError as err:
        return _failed(args, "error", err, 2)
    except ConvergenceError as err:
        return _failed(args, "solver failure", err, 3)
    except CapacityError as err:
        return _failed(args, "capacity exceeded", err, 4)
    try:
        (write_csv if Path(args.output).suffix.lower() == ".csv" else write_netcdf)(ds, args.output)
    except OSError as err:
        print(f"dccss: error: cannot write {args.output}: {err.strerror or err}", file=sys.stderr)
        return 2
    for line in warnings_of(ds):
        print(f"dccss: warning: {line}", file=sys.stderr)
    if not args.quiet:
        used = "numba: the spatial models are compiled" if ds.attrs.get("motion") == "bidirectional" \
            else backend.last
        how = "" if ds.attrs.get("model") == "articulated" else f" (backend {used})"  # no pad model ran
        print(f"dccss: wrote {args.output} ({_summary(ds)}) in {time.perf_counter() - start:.2f} s{how}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
