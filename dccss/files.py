"""Writing result files safely: a temporary file in the target's folder, then an atomic rename.

Readers and interrupted runs never see a half-written file; a temporary file left by a writer
that was killed is removed by the next write of the same target.
"""

from __future__ import annotations

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


def write_text(text, path) -> None:
    """Write a text file atomically."""
    write_atomic(path, lambda tmp: Path(tmp).write_text(text))
