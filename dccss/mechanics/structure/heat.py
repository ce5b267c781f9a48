"""The sliding plates' heating under a temperature law: the half-space's surface temperature at the
centre of each plate for the frictional heat flux it receives (the module docstring of ``friction``)."""

from __future__ import annotations

import math

from .. import scalar
from ..friction import surface_mu


@scalar.jit
def plate_temperature(m, start, end, ux, uy, x0, x1, normal, r, s, heat, temperature, k):
    """Surface s's plate temperature at ``end`` (time[k]) after heat interval m from ``start`` (its law's row
    r, a temperature law), the slider going from (ux, uy) to (x0, x1) (its displacement; on the plate
    ``r[2]`` times that): the heat flux q = λ μ p v (its mean sliding speed v, N/W ``normal``, the plate's
    temperature held over it, temperature[k, s]) while the slider covers the plate's centre, into
    heat[m, 2 + s]; the half-space's surface temperature for a flux constant over each heat interval (the
    module docstring of ``friction``)."""
    h = end - start
    d0, d1 = x0 - ux, x1 - uy
    c0, c1 = 0.5 * (x0 + ux), 0.5 * (x1 + uy)
    moved, middle = math.sqrt(d0 * d0 + d1 * d1), math.sqrt(c0 * c0 + c1 * c1)
    heat[m, 0], heat[m, 1] = start, end
    speed = r[2] * moved / h
    covered = r[2] * middle < r[16] * 0.8862269254527580  # √π / 2: the contact circle's equal square
    heat[m, 2 + s] = r[3] * surface_mu(r, speed, normal, temperature[k, s]) * r[7] * normal * speed \
        if covered else 0.0
    rise = 0.0
    for j in range(m + 1):
        rise += heat[j, 2 + s] * (math.sqrt(end - heat[j, 0]) - math.sqrt(end - heat[j, 1]))
    temperature[k, s] = r[17] + 2.0 * math.sqrt(r[14] / math.pi) / r[15] * rise
    return temperature[k, s]


@scalar.jit
def plate_temperatures(m, start, end, ux, uy, x0, x1, normal, law, heat, temperature, k):
    """The plates' temperatures at ``end`` (time[k]) after heat interval m from ``start``, the stroke going
    from (ux, uy) to (x0, x1), each surface of a temperature law heated by its flux (``plate_temperature``;
    the rigid slider: every surface slides with the stroke)."""
    heat[m, 0], heat[m, 1] = start, end
    for s in range(len(law)):
        if law[s][0] == 3.0:
            plate_temperature(m, start, end, ux, uy, x0, x1, normal, law[s], s, heat, temperature, k)
    return temperature[k, 0], temperature[k, 1]
