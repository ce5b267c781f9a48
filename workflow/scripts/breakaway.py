"""Snakemake adapter: the Fig. 7 breakaway sweeps -> one netCDF dataset each."""

import numpy as np
from _log import logged

from dccss import NewtonOptions, breakaway
from dccss.case import geometry_from, parameters_hash
from dccss.files import write_netcdf

with logged(snakemake.log[0]):
    for sweep, path in zip(snakemake.params.sweeps, snakemake.output):
        ds = breakaway(geometry_from(sweep["prototype"]), np.radians(sweep["theta2_0"]), sweep["dXg"],
                       normals=sweep["normals"], options=NewtonOptions(**sweep["newton"]),
                       attrs={"case_id": path, "case_parameters_sha256": parameters_hash(sweep)})
        write_netcdf(ds, path)
        print(f"{path}: {ds.sizes}")
