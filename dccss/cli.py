"""Command line: ``dccss run CASE.yaml -o OUT.nc``, ``dccss animate RESULT.nc -o OUT.gif|html|mp4`` and
``dccss plot RESULT.nc -o OUT.png|pdf`` (also ``python -m dccss ...``).

Exit codes: 0 written (also a history marked failed with ``on_failure: mark``), 2 bad input,
3 solver failure, 4 the pad reached a ring with ``capacity: error``. Warnings (an implausible
record, a retaining ring reached, a history cut short or marked failed) are one line each on
stderr; a progress line is shown while stepping when stderr is a terminal (not with --quiet).
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings

import numpy as np

from ._version import __version__
from .case import CaseError, load_case
from .files import write_netcdf
from .mechanics import backend
from .mechanics.capacity import CapacityError
from .mechanics.newton import ConvergenceError
from .mechanics.structure import G


def _summary(ds) -> str:
    return _kinematics(ds) + _record(ds.attrs) + (_structure(ds) if "structure_friction" in ds.attrs else "")


def _record(a) -> str:
    """The peaks of a record (each component of a pair) after processing, and the scale applied."""
    parts = [("", "record_")] if "record_pga_m_per_s2" in a else \
        [(f"{c}: ", f"record_{c}_") for c in "xy" if f"record_{c}_pga_m_per_s2" in a]
    if not parts:
        return ""
    peaks = "; ".join(f"{label}PGA = {a[p + 'pga_m_per_s2'] / G:.3g} g, PGV = {100 * a[p + 'pgv_m_per_s']:.3g} cm/s, "
                      f"PGD = {100 * a[p + 'pgd_m']:.3g} cm" for label, p in parts)
    scaled = (f": Sa(T = {a['record_scaling_period_s']:g} s, {100 * a['record_scaling_damping']:g} %) = "
              f"{a['record_scaled_to_sa_g']:g} g" if "record_scaled_to_sa_g" in a else "")
    return f"; record {peaks} (scale {a[parts[0][1] + 'scale']:g}{scaled})"


def _structure(ds) -> str:
    """Peak and residual stroke and peak F/W of a structure-driven history."""
    two = "stroke_x" in ds
    if two:
        stroke = np.hypot(ds["stroke_x"].values, ds["stroke_y"].values)
        force = np.hypot(ds["shear_ratio_x"].values, ds["shear_ratio_y"].values)
        residual = f"{100 * stroke[-1]:.3f} cm"
    else:
        stroke, force = np.abs(ds["stroke"].values), np.abs(ds["shear_ratio"].values)
        residual = f"{100 * float(ds['stroke'].values[-1]):+.3f} cm"
    return (f"; structure (mu = {ds.attrs['structure_friction']:g}, zeta = {ds.attrs['structure_damping']:g}, "
            f"T = {ds.attrs['structure_period_s']:.3g} s): peak |u| = {100 * np.max(stroke):.3f} cm, "
            f"residual stroke = {residual}, peak |F/W| = {np.max(force):.4f}")


def _kinematics(ds) -> str:
    if ds.attrs.get("motion") == "bidirectional":
        interp = max(float(np.nanmax(np.abs(ds[name].values))) for name in ds if name.startswith("I_"))
        return (f"{ds.attrs['model']}, bidirectional, {ds.sizes['t'] - 1} steps: max tilt = "
                f"{np.nanmax(ds['tilt'].values):.3f} deg, max rise = {100 * float(ds['rise'].max()):.3f} cm, "
                f"max |interpenetration| = {1e3 * interp:.4g} mm")
    theta2 = ds["theta2"].values
    interp = max(float(np.nanmax(np.abs(ds[f"I_{c}"].values))) for c in "ABCD")
    return (f"{ds.attrs['model']}, {ds.sizes['t'] - 1} steps: max |theta2| = "
            f"{np.nanmax(np.abs(theta2)):.3f} deg, max rise = {100 * float(ds['rise'].max()):.3f} cm, "
            f"max |interpenetration| = {1e3 * interp:.4g} mm")


def warnings_of(ds) -> list[str]:
    """One line for each thing about a written history that its reader must know."""
    a, out = ds.attrs, []
    if "capacity_exceeded_at_s" in a:
        moved = (f", RB1 {100 * a['capacity_exceeded_displacement_m']:.4g} cm from its start"
                 if "capacity_exceeded_displacement_m" in a else "")
        out.append(f"the pad reaches the retaining ring of {a['capacity_exceeded_plate']} at "
                   f"t = {a['capacity_exceeded_at_s']:.6g} s{moved} and passes it by up to "
                   f"{1e3 * a['capacity_exceeded_by_m']:.3g} mm (capacity: {a['capacity_policy']})")
    if "stopped_at_s" in a:
        out.append(f"capacity: stop cut the history short at t = {a['stopped_at_s']:.6g} s "
                   f"({ds.sizes['t'] - 1} steps written)")
    if a.get("failed"):
        out.append(f"the solver failed at t = {a['failure_time_s']:.6g} s; the history is written up to the "
                   f"last converged step (on_failure: mark): {a['failure_message']}")
    return out


class _Progress:
    """A one-line progress display on a terminal, updated at most 10 times a second."""

    def __init__(self, stream):
        self.stream, self.last, self.shown = stream, 0.0, False

    def __call__(self, n, total):
        now = time.monotonic()
        if n < total and now - self.last < 0.1:
            return
        self.last, self.shown = now, True
        self.stream.write(f"\rdccss: step {n}/{total} ({100 * n / max(total, 1):.0f} %)")
        self.stream.flush()

    def close(self):
        if self.shown:
            self.stream.write("\r\033[K")
            self.stream.flush()


def _failed(args, kind, err, code) -> int:
    """Say why the case failed, remove an older file at the output path (it is not this case's result)
    and return the exit code."""
    from pathlib import Path

    path, note = Path(args.output), ""
    if path.is_file():
        path.unlink()
        note = f" ({args.output}, an older result there, was removed: it is not this case's)"
    print(f"dccss: {kind} in {args.case}: {err}{note}", file=sys.stderr)
    return code


def _warn_line(message, category, *args, **kwargs):
    return f"dccss: warning: {message}\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="dccss", description="Kinematics of DCCSS isolators.")
    parser.add_argument("--version", action="version", version=f"dccss {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run one case file and write its netCDF dataset")
    run.add_argument("case", help="YAML case file")
    run.add_argument("-o", "--output", required=True, help="netCDF file to write")
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing on success (warnings still)")
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] != ["run"]:  # `dccss run` draws nothing: it does not import the drawing code (matplotlib)
        from . import animation, plan

        animation.add_parser(sub)
        plan.add_parser(sub)
    args = parser.parse_args(argv)
    if hasattr(args, "handler"):
        return args.handler(args)
    warnings.formatwarning = _warn_line
    start = time.perf_counter()
    try:
        backend.check()
    except (ValueError, backend.BackendError) as err:
        print(f"dccss: error: {err}", file=sys.stderr)
        return 2
    progress = _Progress(sys.stderr) if sys.stderr.isatty() and not args.quiet else None
    try:
        ds = load_case(args.case).run(progress=progress)
    except CaseError as err:
        return _failed(args, "error", err, 2)
    except ConvergenceError as err:
        return _failed(args, "solver failure", err, 3)
    except CapacityError as err:
        return _failed(args, "capacity exceeded", err, 4)
    finally:
        if progress is not None:
            progress.close()
    write_netcdf(ds, args.output)
    for line in warnings_of(ds):
        print(f"dccss: warning: {line}", file=sys.stderr)
    if not args.quiet:
        used = "numba: the spatial models are compiled" if ds.attrs.get("motion") == "bidirectional" \
            else backend.last
        print(f"dccss: wrote {args.output} ({_summary(ds)}) in {time.perf_counter() - start:.2f} s (backend {used})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
