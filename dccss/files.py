"""Writing result files safely: a temporary file in the target's folder, then an atomic rename.

Readers and interrupted runs never see a half-written file; a temporary file left by a writer
that was killed is removed by the next write of the same target.
"""

from __future__ import annotations

import csv
import io
import os
import secrets
from pathlib import Path


def write_atomic(path, write) -> None:
    """Call ``write(temporary_path)``, then rename the temporary file onto ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    for stale in path.parent.glob(f".{path.name}.*.tmp"):
        stale.unlink(missing_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.{secrets.token_hex(4)}.tmp")
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise


def write_netcdf(ds, path) -> None:
    """Write a dataset atomically (netCDF4 format); coordinate variables carry no _FillValue
    (CF 2.5.1)."""
    encoding = {name: {"_FillValue": None} for name in ds.coords}
    write_atomic(path, lambda tmp: ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding))


def write_csv(ds, path, dim="t") -> None:
    """Write the history of a dataset atomically as a CSV table, one row per value of ``dim``.

    The columns are ``dim`` and every data variable along it alone, each headed ``name [units]``
    (its ``units`` attribute; ``name`` without one); above the header, the dataset's attributes as
    comment lines ``# key: value``, so that the file describes itself (pandas reads the table with
    ``read_csv(path, comment="#")``). Numbers are written in full (Python's shortest round-trip
    form; ``nan`` where a value is missing).
    """
    names = [dim] + [name for name in ds.data_vars if ds[name].dims == (dim,)]
    out = io.StringIO()
    for key, value in ds.attrs.items():
        value = value.tolist() if hasattr(value, "tolist") else value
        out.write(f"# {key}: {' '.join(str(value).splitlines())}\n")
    rows = csv.writer(out, lineterminator="\n")
    rows.writerow([f"{name} [{ds[name].attrs['units']}]" if "units" in ds[name].attrs else name for name in names])
    rows.writerows(zip(*(ds[name].values.tolist() for name in names)))
    write_atomic(path, lambda tmp: Path(tmp).write_text(out.getvalue(), encoding="utf-8"))


def write_text(text, path) -> None:
    """Write a text file atomically."""
    write_atomic(path, lambda tmp: Path(tmp).write_text(text))
