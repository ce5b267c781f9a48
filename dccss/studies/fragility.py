"""Fragility: the probability that the device reaches a limit state given the intensity, P(exceed | x), fitted as
a lognormal by maximum likelihood on the stripes of a study with intensity levels (Baker 2015, Earthquake
Spectra 31(1), "Efficient analytical fragility function fitting using dynamic structural analysis data").

At each level x_j, z_j of the n_j records counted exceed the limit; the fit maximises the binomial likelihood
Π p_j^z_j (1 - p_j)^(n_j - z_j), p_j = Φ(ln(x_j / θ) / β): a probit model of ln x, solved by Fisher scoring
(iteratively reweighted least squares). θ is the median intensity, β the dispersion.

A limit state is one of the device's (``LIMITS``) or a threshold on a summary ({name, variable, above or below}),
strict: ``above`` is exceeded where the summary is strictly above the threshold (a value equal to it is not),
``below`` strictly below. A run counts as what it is: a pad limit (its ring) that the run reached before it failed
is exceeded; a failed run that had not reached it is not counted; nor is a run whose summary is NaN (unknown: an
articulated slider's pad summaries, which its pad models do not give, or a failed run's), so a threshold on a
summary that no run of a slider kind has is fitted on no run ('none counted'). ``*_failed`` says how many runs
were left out, per level. The structure's own limits (its stroke, uplift, a surface's ring) do not depend on the
pad and count every run that has them.
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
#: Fisher scoring: at most this many iterations; converged where the Newton decrement λ² = score' I⁻¹ score (twice
#: the rise of ln L the step promises) is below ln L's own rounding, ROUNDING times max(1, |ln L|), and no longer
#: falls (at the floor rounding sets: the steps then are of the order of the last bits of a and b)
ITERATIONS, ROUNDING = 500, 4.0 * np.finfo(float).eps


def limits_from(value, available) -> list:
    """The study's limit states (its ``fragility`` key: a list of LIMITS' names and thresholds {name, variable,
    above | below}, in the variable's SI units: exceeded where the variable is strictly above, or strictly below,
    the threshold), checked against the summaries the study has (``available``: {name: whether the pad's run
    decides it}); None: every device limit it has. Returns [(name, variable, kind, threshold, decided by the
    pad)]."""
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
            raise CaseError(f"{key}: give one of above (exceeded where the variable is strictly above it: a value "
                            f"equal to it is not) or below (strictly below it)")
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
    """(exceeded, counted) booleans of every case for one limit state (``limits_from``'s tuple).

    A flag is exceeded where it is > 0 (NaN: not raised, e.g. ``uplift_count`` of a record without a vertical
    component); a threshold where the variable is strictly above it (``above``) or strictly below it (``below``),
    and a run whose variable is NaN is not counted (unknown). A failed run counts for a pad limit where it
    reached the limit before it failed, else not at all."""
    name, variable, kind, threshold, pad = limit
    values = ds[variable]
    if kind == "flag":
        hit, counted = values.fillna(0) > 0, xr.ones_like(values, dtype=bool)
    else:
        hit = values > threshold if kind == "above" else values < threshold
        counted = values.notnull()
    if pad and "failed" in ds:
        counted = counted & ~(ds["failed"].astype(bool) & ~hit)
    return hit & counted, counted


def fit(levels, exceeded, counted) -> tuple[float, float, str]:
    """The lognormal P(exceed | x) = Φ(ln(x / θ) / β) of the largest binomial likelihood on stripes at ``levels``
    (> 0), ``exceeded`` of ``counted`` runs at each: (θ, β, status).

    Returns
    -------
    theta, beta, status : float, float, str
        status 'fitted', or θ and β NaN and why there is no curve:

        - 'none counted': no run counted at any level;
        - 'none exceeded', 'all exceeded': the stripes have no run of the other kind;
        - 'one level': a curve needs runs at two levels;
        - 'falling': the fractions do not rise with the intensity: the runs exceeded are on average at no
          higher ln x than those not exceeded (e.g. 10, 6, 4, 0 of 10); the best b = 1/β > 0 is b -> 0;
        - 'separated': (quasi-)completely separated, every level with a run exceeded at or above every level
          with a run not exceeded (e.g. 0, 5, 10, 10 of 10): the likelihood grows as β -> 0;
        - 'flat': the maximum's θ is beyond the floating-point numbers (the fractions barely rise: β in the
          hundreds);
        - 'not converged': Fisher scoring did not settle within ``ITERATIONS``.

    Notes
    -----
    With η = a + b ln x, a finite maximum with b > 0 exists exactly where none of the statuses above but the last
    two holds. The log-likelihood is strictly concave in (a, b) on two levels or more; where the runs overlap (some
    run exceeded at a level below one not exceeded, and the other way round) it has a finite maximum (Silvapulle
    1981, JRSS B 43(3)), else it grows without bound along the separating direction. Its maximum over b >= 0 is
    at b = 0 iff its derivative in b there, at the pooled fraction p̄ = Z / N, is <= 0: Σ_j x_j (z_j - n_j p̄) =
    Z (N - Z) / N (the mean ln x of the Z runs exceeded - that of the N - Z not) <= 0 ('falling'; this holds
    where the overlap fails the other way round). Otherwise the maximum has b > 0: finite unless the runs are
    separated ('separated').
    """
    x = np.log(np.asarray(levels, dtype=float))
    z, n = np.asarray(exceeded, dtype=float), np.asarray(counted, dtype=float)
    keep = n > 0
    x, z, n = x[keep], z[keep], n[keep]
    if n.size == 0:
        return math.nan, math.nan, "none counted"
    if z.sum() == 0:
        return math.nan, math.nan, "none exceeded"
    if z.sum() == n.sum():
        return math.nan, math.nan, "all exceeded"
    if np.unique(x).size < 2:
        return math.nan, math.nan, "one level"
    if np.sum((z * n.sum() - n * z.sum()) * (x - x.mean())) <= 0.0:  # Z (N - Z) (mean x exceeded - mean x not)
        return math.nan, math.nan, "falling"
    if x[z < n].max() <= x[z > 0].min():
        return math.nan, math.nan, "separated"
    # start: least squares on the probits of the fractions (clipped off 0 and 1)
    f = np.clip((z + 0.5) / (n + 1.0), 1e-3, 1 - 1e-3)
    b, a = np.polyfit(x, ndtri(f), 1, w=np.sqrt(n))
    b = max(b, 1e-3)
    X = np.column_stack([np.ones_like(x), x])
    best, last = _loglikelihood(a, b, x, z, n), math.inf
    for _ in range(ITERATIONS):
        eta = a + b * x
        up, down = log_ndtr(eta), log_ndtr(-eta)  # ln p, ln (1 - p), without cancellation in the tails
        log_phi = -0.5 * eta * eta - 0.5 * math.log(2.0 * math.pi)
        w = n * np.exp(2.0 * log_phi - up - down)  # Fisher's weights n φ² / (p (1 - p))
        score = X.T @ (z * np.exp(log_phi - up) - (n - z) * np.exp(log_phi - down))
        try:
            step = np.linalg.solve(X.T @ (w[:, None] * X), score)
        except np.linalg.LinAlgError:
            return math.nan, math.nan, "not converged"
        decrement = float(score @ step)
        if decrement <= ROUNDING * max(1.0, abs(best)):  # ln L cannot tell the step's rise: taken as it is
            a, b = a + step[0], b + step[1]
            if decrement >= last:  # and the decrement no longer falls: at its rounding floor
                with np.errstate(over="ignore"):
                    theta = float(np.exp(-a / b))
                if not 0.0 < theta < math.inf:
                    return math.nan, math.nan, "flat"
                return theta, 1.0 / float(b), "fitted"
            last = decrement
            continue
        for _ in range(60):  # halved until the likelihood grows (Fisher scoring's steps are ascent directions)
            trial = _loglikelihood(a + step[0], b + step[1], x, z, n)
            if b + step[1] > 0.0 and trial >= best - ROUNDING * max(1.0, abs(best)):  # not lower beyond rounding
                break
            step = 0.5 * step
        else:
            return math.nan, math.nan, "not converged"
        a, b, best = a + step[0], b + step[1], trial
    return math.nan, math.nan, "not converged"


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
            units="1", long_name=f"runs left out of '{name}' per level: they failed short of the limit, or "
                                 f"have no value of {variable}")
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
            "long_name": f"the fit of '{name}': fitted, or why not (none counted, none exceeded, all exceeded, one "
                         f"level, falling, separated, flat, not converged: dccss.studies.fragility.fit)"})
    return out
