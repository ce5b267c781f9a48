"""Response spectra of recorded ground motions, and scaling a record to a spectral acceleration.

The pseudo-spectral acceleration of a record at period T and damping ratio ζ is PSA = ω² max |u|,
ω = 2π / T, u the displacement of a linear oscillator ü + 2ζω u̇ + ω² u = -a_g(t) at rest at the
record's start. It is solved exactly for the record's samples joined by straight lines (the
Nigam-Jennings idea): by the same closed form that solves the isolated structure with no
friction (``mechanics.structure.solve`` with μ = 0 and a pendulum of length L = g / ω²), so the
records that drive the structure and their spectra are one reading of the samples. No library
does this exactly for non-uniform sample times with the windowed, baseline-corrected
acceleration dccss uses; ``pyrotd`` and ``eqsig`` (frequency-domain and Newmark-based
respectively, uniform steps) would add a dependency for a few lines.

Two components: ``rotd(... , percentile=50)`` is RotD50, the median over the horizontal
orientations 0-179° of the peak response to the rotated component (Boore 2010; what NGA-West2
reports), ``percentile=100`` RotD100, the largest (the maximum-direction spectrum of ASCE 7-22
§16.2.3.2, which Ch. 17 scales isolated structures' records to); since the oscillator is linear,
the response to a component rotated by θ is cos θ u_x + sin θ u_y, so the two responses are
computed once. ``geometric_mean`` is the geometric mean of the two as-recorded components' PSA
(older practice).

Codes scale a suite over a period range rather than at one period: ``suite_factors`` fits each record
to the target spectrum over the range, then scales the whole suite by the least factor that keeps
its mean spectrum at or above a fraction of the target at every period of the range
(``range_periods``).
"""

from __future__ import annotations

import functools
import hashlib
import json
import os
import tempfile
from pathlib import Path

import numpy as np

from .mechanics import backend
from .mechanics.structure import LINE_WORK, G, Ground, solve

#: the definitions of a pair's spectral acceleration that ``scale_factor`` knows
PAIR_DEFINITIONS = ("rotd50", "rotd100", "geometric_mean")
ORIENTATIONS = np.radians(np.arange(180.0))  # 1° steps, as NGA-West2
#: log-spaced periods a scaling over a period range checks, per decade of the range and at least (with
#: the target's own periods in it; NGA-West2's standard periods are about 25 per decade)
PER_DECADE, LEAST_POINTS = 100, 20


def _check(period, damping):
    """A ValueError names a period (s) that is not a finite number > 0 or a damping ratio not in [0, 1)."""
    if isinstance(period, bool) or not isinstance(period, (int, float, np.integer, np.floating)) or \
            not np.isfinite(period) or not period > 0:
        raise ValueError(f"period must be a finite number > 0 (s), got {period!r}")
    if isinstance(damping, bool) or not isinstance(damping, (int, float, np.integer, np.floating)) or \
            not 0 <= damping < 1:
        raise ValueError(f"damping must be a ratio 0 <= damping < 1, got {damping!r}")


def response(time, acceleration, period, damping=0.05, compiled=None) -> np.ndarray:
    """The oscillator's displacement u (m) at the sample times: (n,) for (n,) acceleration (m/s²),
    (n, 2) for two components (``compiled``: as ``mechanics.structure.solve``)."""
    _check(period, damping)
    omega = 2 * np.pi / period
    ground = Ground.from_samples(time, acceleration)
    u = solve(ground, np.asarray(time, dtype=float), G / omega**2, 0.0, damping, compiled).stroke
    return u[:, 0] if np.ndim(acceleration) == 1 else u


def psa(time, acceleration, period, damping=0.05, compiled=None) -> float:
    """Pseudo-spectral acceleration (m/s²) of one component at ``period`` (s) and ``damping``."""
    _check(period, damping)
    return float((2 * np.pi / period) ** 2 * np.max(np.abs(response(time, acceleration, period, damping, compiled))))


def rotd(time, ax, ay, period, damping=0.05, percentile=50.0, compiled=None) -> float:
    """RotD<percentile> (m/s²) of a pair: the percentile over orientations 0-179° of the PSA of the
    component rotated by each."""
    u = response(time, np.column_stack([ax, ay]), period, damping, compiled)
    return float((2 * np.pi / period) ** 2 * np.percentile(orientation_peaks(u), percentile))


def orientation_peaks(u, first=64) -> np.ndarray:
    """max over the samples of |u_x cos θ + u_y sin θ| at each of ORIENTATIONS, u (n, 2).

    Only a sample whose |u| reaches the smallest of these peaks can give one (|u_x cos θ + u_y sin θ|
    <= |u|): the peaks over the ``first`` largest samples bound that from below, and the peaks are then
    taken over the samples at or above the bound (with a margin for rounding), the same values as over
    all samples at a fraction of the cost."""
    c, s = np.cos(ORIENTATIONS)[None, :], np.sin(ORIENTATIONS)[None, :]
    size = np.sqrt(u[:, 0] ** 2 + u[:, 1] ** 2)
    if len(u) > first:
        top = np.argpartition(size, len(u) - first)[len(u) - first:]
        bound = np.min(np.max(np.abs(c * u[top, :1] + s * u[top, 1:]), axis=0))
        u = u[size >= bound * (1 - 1e-9)]
    return np.max(np.abs(c * u[:, :1] + s * u[:, 1:]), axis=0)


def spectral_acceleration(excitation, period, damping=0.05, definition="rotd50", compiled=None) -> float:
    """The spectral acceleration (m/s²) of a ``records.Record`` or of a ``records.RecordPair``
    (``definition``: rotd50, rotd100 or geometric_mean; ``compiled``: as ``mechanics.structure.solve``)."""
    if definition not in PAIR_DEFINITIONS:
        raise ValueError(f"definition must be one of {list(PAIR_DEFINITIONS)}, got {definition!r}")
    if not hasattr(excitation, "acceleration") and not hasattr(excitation, "x"):
        raise TypeError(f"excitation must be a Record or a RecordPair (its samples' accelerations), got "
                        f"{type(excitation).__name__}")
    if excitation.components == 1:
        return psa(excitation.time, excitation.acceleration, period, damping, compiled)
    x, y = excitation.x, excitation.y
    if definition in ("rotd50", "rotd100"):
        return rotd(excitation.time, x.acceleration, y.acceleration, period, damping, float(definition[4:]), compiled)
    if definition == "geometric_mean":
        return float(np.sqrt(psa(x.time, x.acceleration, period, damping, compiled)
                             * psa(y.time, y.acceleration, period, damping, compiled)))
    raise ValueError(f"definition must be one of {list(PAIR_DEFINITIONS)}, got {definition!r}")


#: the intensity measures a record is scaled to (``intensity_measure``): its spectral acceleration at a period,
#: its peak ground acceleration or velocity (a pair's by the definition, as its spectral acceleration)
MEASURES = ("sa", "pga", "pgv")


def intensity_measure(excitation, measure="sa", period=None, damping=0.05, definition="rotd50") -> float:
    """A record's (or a pair's) intensity in SI units: ``sa`` its spectral acceleration at ``period`` (m/s²,
    ``spectral_acceleration``), ``pga`` its peak ground acceleration (m/s²), ``pgv`` its peak ground velocity
    (m/s), over its samples; a pair's by ``definition``: the 50th or 100th percentile over the orientations
    0-179° of the peak of its components turned by each (RotD50, RotD100, as NGA-West2 takes a pair's PGA and
    PGV too) or the geometric mean of its components' peaks."""
    if measure not in MEASURES:
        raise ValueError(f"measure must be one of {list(MEASURES)}, got {measure!r}")
    if measure == "sa":
        return spectral_acceleration(excitation, period, damping, definition)
    if definition not in PAIR_DEFINITIONS:
        raise ValueError(f"definition must be one of {list(PAIR_DEFINITIONS)}, got {definition!r}")
    samples = "acceleration" if measure == "pga" else "velocity_samples"
    if excitation.components == 1:
        return float(np.max(np.abs(getattr(excitation, samples))))
    x, y = (getattr(c, samples) for c in (excitation.x, excitation.y))
    if definition == "geometric_mean":
        return float(np.sqrt(np.max(np.abs(x)) * np.max(np.abs(y))))
    return float(np.percentile(orientation_peaks(np.column_stack([x, y])), float(definition[4:])))


def spectrum(excitation, periods, damping=0.05, definition="rotd50") -> np.ndarray:
    """``spectral_acceleration`` (m/s²) of ``excitation`` at each of ``periods`` (s): compiled (the same
    values) when the periods' work together is large, as a run's steps (``mechanics.backend``)."""
    n = len(getattr(excitation, "time", ()))
    compiled = backend.choose(len(periods) * max(n - 1, 1), LINE_WORK) == "numba"
    return np.array([spectral_acceleration(excitation, float(T), damping, definition, compiled) for T in periods])


def cached_spectrum(excitation, periods, damping=0.05, definition="rotd50") -> np.ndarray:
    """``spectrum``, kept on disk: a study reads its records, and a suite scaled over a period range
    computes their spectra, each time Snakemake starts (and in each job on a cluster). The key is the
    record's attributes (its files' SHA-256 and processing), the periods, damping and definition, and a
    digest of the code that computes it; a cache that cannot be written is skipped."""
    folder = _cache_folder()
    periods = np.asarray(periods, dtype=float)
    key = hashlib.sha256(json.dumps([excitation.attrs(), damping, definition, _code_digest()], sort_keys=True,
                                    default=str).encode() + periods.tobytes()).hexdigest()
    path = None if folder is None else folder / f"{key}.npy"
    if path is not None and path.is_file():
        try:
            values = np.load(path)
            if values.shape == periods.shape and values.dtype == np.float64 and (values > 0).all():
                return values  # a spectrum: positive accelerations (also never NaN)
        except (OSError, ValueError, EOFError):
            pass  # a damaged entry (cut short, empty, not a spectrum): computed again
    values = spectrum(excitation, periods, damping, definition)
    if path is not None:
        try:
            with tempfile.NamedTemporaryFile(dir=folder, suffix=".npy", delete=False) as out:
                np.save(out, values)
            os.replace(out.name, path)  # whole or not at all, whatever other processes do
        except OSError:
            pass
    return values


def _cache_folder():
    """``$XDG_CACHE_HOME/dccss/spectra`` (or ``~/.cache/...``), None where it cannot be made."""
    folder = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "dccss" / "spectra"
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return folder if os.access(folder, os.W_OK) else None


@functools.cache
def _code_digest() -> str:
    """A digest of the sources a spectrum depends on: this module, the records' processing and the
    mechanics (the oscillator's solution)."""
    from .mechanics.scalar import source_digest

    here = Path(__file__).parent
    mine = hashlib.sha256(b"".join((here / f).read_bytes() for f in ("spectra.py", "records.py"))).hexdigest()
    return mine[:16] + source_digest(here / "mechanics")


def range_periods(low, high, table=()) -> np.ndarray:
    """The periods (s) a scaling over [low, high] checks: log-spaced from low to high (PER_DECADE, at least
    LEAST_POINTS) and the target's own periods ``table`` inside the range (where its straight pieces bend)."""
    table = np.asarray(table, dtype=float)
    num = max(LEAST_POINTS, int(np.ceil(PER_DECADE * np.log10(high / low))) + 1)
    return np.unique(np.concatenate([np.geomspace(low, high, num), table[(table > low) & (table < high)]]))


def suite_factors(spectra, target, fraction=1.0, individual=True):
    """Amplitude scale factors of a suite of records over a period range, as codes scale them.

    ``spectra`` (R, P): each record's spectral acceleration at the range's P periods; ``target`` (P,):
    the target spectrum there (the same units). With ``individual``, each record is first fitted to
    the target on its own: its factor is the geometric mean of target / Sa over the periods (the
    least-squares fit of log Sa); then one factor for the whole suite, the smallest that keeps the
    suite's mean spectrum at or above ``fraction`` × target at every period (where it is closest it
    touches it). Returns (the records' factors (R,), their own fits (R,), the suite's factor)."""
    spectra, target = np.asarray(spectra, dtype=float), np.asarray(target, dtype=float)
    fitted = np.exp(np.mean(np.log(target / spectra), axis=1)) if individual else np.ones(len(spectra))
    mean = np.mean(fitted[:, None] * spectra, axis=0)
    suite = float(np.max(fraction * target / mean))
    return suite * fitted, fitted, suite
