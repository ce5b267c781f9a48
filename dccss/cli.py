"""Command line: ``dccss run CASE.yaml -o OUT.nc`` (also ``python -m dccss run ...``)."""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from ._version import __version__
from .case import CaseError, load_case
from .files import write_netcdf
from .newton import ConvergenceError
from .simulation import CapacityError


def _summary(ds) -> str:
    theta2 = ds["theta2"].values
    interp = max(float(np.nanmax(np.abs(ds[f"I_{c}"].values))) for c in "ABCD")
    return (f"{ds.attrs['model']}, {ds.sizes['t'] - 1} steps: max |theta2| = "
            f"{np.nanmax(np.abs(theta2)):.3f} deg, max rise = {100 * float(ds['rise'].max()):.3f} cm, "
            f"max |interpenetration| = {1e3 * interp:.4g} mm")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="dccss", description="Kinematics of DCCSS isolators.")
    parser.add_argument("--version", action="version", version=f"dccss {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run one case file and write its netCDF dataset")
    run.add_argument("case", help="YAML case file")
    run.add_argument("-o", "--output", required=True, help="netCDF file to write")
    run.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    try:
        ds = load_case(args.case).run()
    except CaseError as err:
        print(f"dccss: error in {args.case}: {err}", file=sys.stderr)
        return 2
    except ConvergenceError as err:
        print(f"dccss: solver failure in {args.case}: {err}", file=sys.stderr)
        return 3
    except CapacityError as err:
        print(f"dccss: capacity exceeded in {args.case}: {err}", file=sys.stderr)
        return 4
    write_netcdf(ds, args.output)
    if not args.quiet:
        print(f"dccss: wrote {args.output} ({_summary(ds)}) in {time.perf_counter() - start:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
