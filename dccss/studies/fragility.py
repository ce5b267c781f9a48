"""Fragility: the probability that the device reaches a limit state given the intensity, P(exceed | x), fitted as
a lognormal by maximum likelihood on the stripes of a study with intensity levels (Baker 2015, Earthquake
Spectra 31(1), "Efficient analytical fragility function fitting using dynamic structural analysis data").

At each level x_j, z_j of the n_j records counted exceed the limit; the fit maximises the binomial likelihood
Π p_j^z_j (1 - p_j)^(n_j - z_j), p_j = Φ(ln(x_j / θ) / β): a probit model of ln x, solved by Fisher scoring
(iteratively reweighted least squares). θ is the median intensity, β the dispersion.

A limit state is one of the device's (``LIMITS``) or a threshold on a summary ({name, variable, above or below}).
A run that failed counts as what it is: a pad limit (its ring) that the run reached before it failed is exceeded;
a failed run that had not reached it is not counted (``*_failed`` says how many, per level); the structure's own
limits (its stroke, uplift, a surface's ring) do not depend on the pad and count every run.
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.special import log_ndtr, ndtri

from ..checks import CaseError, check_keys, number

#: the device's limit states: name -> (the summary that flags it, what it is, whether the pad's run decides it)
LIMITS = {
    "ring": ("capacity_exceeded", "the pad (an articulated slider: either half) reaches a retaining ring", True),
    "ring_1": ("ring_1_reached", "the half on the lower surface reaches the ring of RB1", False),
    "ring_3": ("ring_3_reached", "the half on the upper surface reaches the ring of RB3", False),
    "uplift": ("uplift_count", "the superstructure lifts off its device (N <= 0) at least once", False),
}
#: Fisher scoring: at most this many iterations; converged where the step in (a, b) is below TOL
ITERATIONS, TOL = 100, 1e-12


def limits_from(value, available) -> list:
    """The study's limit states (its ``fragility`` key: a list of LIMITS' names and thresholds {name, variable,
    above | below}, in the variable's SI units), checked against the summaries the study has (``available``:
    {name: whether the pad's run decides it}); None: every device limit it has. Returns [(name, variable, kind,
    threshold, decided by the pad)]."""
    if value is None:
        return [(name, var, "flag", 0.0, pad) for name, (var, _, pad) in LIMITS.items() if var in available]
    if not isinstance(value, list) or not value:
        raise CaseError(f"fragility: expected a list of limit states ({list(LIMITS)} or {{name, variable, above}}), "
                        f"got {value!r}")
    out = []
    for i, item in enumerate(value):
        key = f"fragility[{i}]"
        if isinstance(item, str):
            if item not in LIMITS:
                raise CaseError(f"{key}: unknown limit state {item!r}; the device's: {list(LIMITS)}, or a threshold "
                                f"{{name, variable, above}}")
            var, _, pad = LIMITS[item]
            if var not in available:
                raise CaseError(f"{key}: {item} needs the summary {var}, which this study does not have "
                                f"({_why(item)})")
            out.append((item, var, "flag", 0.0, pad))
            continue
        if not isinstance(item, dict):
            raise CaseError(f"{key}: expected a limit state's name or {{name, variable, above}}, got {item!r}")
        check_keys(item, key, ("name", "variable"), ("above", "below"))
        if ("above" in item) == ("below" in item):
            raise CaseError(f"{key}: give one of above (exceeded where the variable is above it) or below")
        name, variable = item["name"], item["variable"]
        if not isinstance(name, str) or not name.replace("_", "").isalnum():
            raise CaseError(f"{key}.name: expected a name of letters, digits and '_', got {name!r}")
        if variable not in available:
            raise CaseError(f"{key}.variable: {variable!r} is not a summary of this study; its summaries: "
                            f"{sorted(available)}")
        kind = "above" if "above" in item else "below"
        out.append((name, variable, kind, number(item[kind], f"{key}.{kind}"), available[variable]))
    names = [o[0] for o in out]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise CaseError(f"fragility: the limit state {twice[0]!r} is given twice")
    return out


def _why(name) -> str:
    return {"ring_1": "a study comparing sliders, or an articulated slider", "ring_3": "a study comparing sliders, "
            "or an articulated slider", "uplift": "a structure under a vertical component",
            "ring": "a pad model"}[name]


def exceeded(ds, limit) -> tuple[xr.DataArray, xr.DataArray]:
    """(exceeded, counted) booleans of every case for one limit state (``limits_from``'s tuple)."""
    name, variable, kind, threshold, pad = limit
    values = ds[variable]
    if kind == "flag":
        hit = values.fillna(0) > 0
    elif kind == "above":
        hit = values > threshold
    else:
        hit = values < threshold
    counted = xr.ones_like(hit, dtype=bool)
    if pad and "failed" in ds:  # a failed run counts where it reached the limit first, else not at all
        counted = ~(ds["failed"].astype(bool) & ~hit)
    return hit & counted, counted


def fit(levels, exceeded, counted) -> tuple[float, float, str]:
    """The lognormal P(exceed | x) = Φ(ln(x / θ) / β) of the largest binomial likelihood on stripes at ``levels``
    (> 0), ``exceeded`` of ``counted`` runs at each: (θ, β, status). status 'fitted', or NaN with 'none exceeded',
    'all exceeded', 'separated' (the fractions jump from 0 to 1 between two levels: β -> 0, no finite maximum) or
    'one level' (a curve needs two)."""
    x = np.log(np.asarray(levels, dtype=float))
    z, n = np.asarray(exceeded, dtype=float), np.asarray(counted, dtype=float)
    keep = n > 0
    x, z, n = x[keep], z[keep], n[keep]
    if z.sum() == 0:
        return math.nan, math.nan, "none exceeded"
    if z.sum() == n.sum():
        return math.nan, math.nan, "all exceeded"
    if np.unique(x).size < 2:
        return math.nan, math.nan, "one level"
    low = x[z > 0].min()
    high = x[z < n].max()
    if high < low or (high == low and np.all((z[x == low] == 0) | (z[x == low] == n[x == low]))):
        return math.nan, math.nan, "separated"
    # start: least squares on the probits of the fractions (clipped off 0 and 1)
    f = np.clip((z + 0.5) / (n + 1.0), 1e-3, 1 - 1e-3)
    b, a = np.polyfit(x, ndtri(f), 1, w=np.sqrt(n))
    b = max(b, 1e-3)
    X = np.column_stack([np.ones_like(x), x])
    best = _loglikelihood(a, b, x, z, n)
    for _ in range(ITERATIONS):
        eta = a + b * x
        up, down = log_ndtr(eta), log_ndtr(-eta)  # ln p, ln (1 - p), without cancellation in the tails
        log_phi = -0.5 * eta * eta - 0.5 * math.log(2.0 * math.pi)
        w = n * np.exp(2.0 * log_phi - up - down)  # Fisher's weights n φ² / (p (1 - p))
        score = X.T @ (z * np.exp(log_phi - up) - (n - z) * np.exp(log_phi - down))
        try:
            step = np.linalg.solve(X.T @ (w[:, None] * X), score)
        except np.linalg.LinAlgError:
            return math.nan, math.nan, "separated"
        if np.max(np.abs(step)) <= TOL * max(1.0, abs(a), abs(b)):  # converged: the maximum
            a, b = a + step[0], b + step[1]
            return math.exp(-a / b), 1.0 / b, "fitted"
        for _ in range(60):  # halved until the likelihood grows (Fisher scoring's steps are ascent directions)
            trial = _loglikelihood(a + step[0], b + step[1], x, z, n)
            if b + step[1] > 0.0 and trial >= best:
                break
            step = 0.5 * step
        else:
            return math.nan, math.nan, "separated"
        a, b, best = a + step[0], b + step[1], trial
    return math.nan, math.nan, "separated"


def _loglikelihood(a, b, x, z, n) -> float:
    """The binomial log-likelihood of Φ(a + b x) (its constant left out)."""
    eta = a + b * x
    return float(np.sum(z * log_ndtr(eta) + (n - z) * log_ndtr(-eta)))


def fragility(ds, limits, units) -> dict:
    """The fragility variables of a combined study dataset with ``record`` and ``intensity`` dimensions, for each
    limit state: ``fragility_<name>_exceeded`` and ``_counted`` (runs per level), ``_failed`` (runs left out: a
    failed run short of the limit), ``_median`` (θ, the levels' units), ``_dispersion`` (β) and ``_fit`` (its
    status); over the other dimensions (the model, a property bound, ...)."""
    out = {}
    levels = ds["intensity"].values.astype(float)
    for limit in limits:
        name, variable, kind, threshold, pad = limit
        hit, counted = exceeded(ds, limit)
        what = (LIMITS[name][1] if kind == "flag" else
                f"{variable} {'>' if kind == 'above' else '<'} {threshold:g} {ds[variable].attrs.get('units', '')}")
        prefix = f"fragility_{name}"
        z, n = hit.sum("record").astype(np.int32), counted.sum("record").astype(np.int32)
        out[f"{prefix}_exceeded"] = z.assign_attrs(units="1", long_name=f"runs in which {what}, per level")
        out[f"{prefix}_counted"] = n.assign_attrs(units="1", long_name=f"runs counted for '{name}', per level")
        out[f"{prefix}_failed"] = (ds.sizes["record"] - n).astype(np.int32).assign_attrs(
            units="1", long_name=f"runs left out of '{name}' per level: they failed short of the limit")
        others = [d for d in z.dims if d != "intensity"]
        stacked_z = z.transpose(*others, "intensity")
        stacked_n = n.transpose(*others, "intensity")
        shape = stacked_z.shape[:-1]
        theta, beta, status = np.full(shape, np.nan), np.full(shape, np.nan), np.empty(shape, dtype=object)
        for index in np.ndindex(shape):
            theta[index], beta[index], status[index] = fit(levels, stacked_z.values[index], stacked_n.values[index])
        coords = {d: stacked_z[d] for d in others}
        out[f"{prefix}_median"] = xr.DataArray(theta, coords=coords, dims=others, attrs={
            "units": units, "long_name": f"median intensity θ at which {what} (lognormal fit, maximum likelihood)"})
        out[f"{prefix}_dispersion"] = xr.DataArray(beta, coords=coords, dims=others, attrs={
            "units": "1", "long_name": f"dispersion β of the fragility of '{name}' (lognormal fit)"})
        out[f"{prefix}_fit"] = xr.DataArray(status.astype(str), coords=coords, dims=others, attrs={
            "long_name": f"the fit of '{name}': fitted, or why not (none exceeded, all exceeded, separated, one "
                         f"level)"})
    return out
