"""Snakemake adapter: one Fig. 7 breakaway sweep -> one netCDF dataset."""

import numpy as np
from _log import logged

from dccss import NewtonOptions, breakaway
from dccss.case import geometry_from, parameters_hash
from dccss.files import write_netcdf

sweep = snakemake.params.sweep
with logged(snakemake.log[0]):
    ds = breakaway(geometry_from(sweep["prototype"]), np.radians(sweep["theta2_0"]), sweep["dXg"],
                   normals=sweep["normals"], options=NewtonOptions(**sweep["newton"]),
                   attrs={"case_id": snakemake.output[0], "case_parameters_sha256": parameters_hash(sweep)})
    write_netcdf(ds, snakemake.output[0])
