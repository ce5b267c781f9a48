"""Recorded ground motions: an acceleration history integrated to an imposed X_g(t).

A :class:`Record` reads a recorded (or synthetic) ground ACCELERATION history, from a PEER NGA
``.AT2`` file (in g) or a two-column CSV (``time`` in s, ``acceleration`` in m/s²), and turns it
into a ground displacement and velocity with the interface of ``dccss.excitation`` (``t_start``,
``t_end``, ``displacement(t)``, ``velocity(t)``, ``attrs()``), so that ``simulation.simulate``
accepts it like a ``Sine`` or a ``Table``.

Why a baseline correction
-------------------------
A raw accelerogram integrated twice drifts: a constant offset c in the acceleration (instrument
zero, tilt, digitisation) becomes a velocity c t and a displacement c t²/2, growing without bound,
and low-frequency noise does the same more slowly. The standard minimal remedy, used here, is to
remove a least-squares polynomial trend from the velocity before the second integration.

Processing, in this order
-------------------------
1. ``scale`` multiplies the acceleration (any finite non-zero number; a negative one flips the
   record); AT2 values are converted from g with g = 9.80665 m/s².
2. ``window=(t0, t1)`` keeps the samples with t0 <= t <= t1 (a bound within 1e-9 dt of a sample
   counts as on it). The record keeps its own time axis: ``t_start`` is the first kept sample (= t0 on
   the sample grid), not 0.
3. Velocity: v = ∫ a dt from v = 0 at ``t_start`` (``scipy.integrate.cumulative_trapezoid``).
4. Baseline: ``"linear"`` (default) subtracts from v its least-squares straight line p(t),
   ``"quadratic"`` its least-squares parabola, ``"none"`` nothing. Removing p from v is the same
   as removing p'(t) from the acceleration, i.e. a constant (linear) acceleration offset for the
   linear (quadratic) baseline; the corrected acceleration a - p' is what ``acceleration``
   holds and what the peak ground acceleration is measured on. The fit is weighted with the
   trapezoidal quadrature weights, so it is the discrete form of the continuous least-squares
   fit (minimising ∫ (v - p)² dt) and keeps the O(dt²) accuracy of step 3: an unweighted fit
   (``scipy.signal.detrend``) counts the two end samples fully and leaves an O(dt) offset in the
   velocity, i.e. a drift of the displacement. The corrected velocity need not be 0 at
   ``t_start``.
5. Displacement: X_g = ∫ v dt from X_g = 0 at ``t_start`` (``cumulative_trapezoid``). The
   displacement is not detrended; but since the fitted trend has a constant term, the weighted
   residual v - p sums to zero, so with a baseline X_g also returns to 0 at ``t_end`` (no
   permanent ground offset: the correction cannot represent one).

Between samples, ``displacement(t)`` and ``velocity(t)`` interpolate the processed samples
linearly. CSV time need not be uniform (the trapezoidal rule and its weights take the actual
steps); it must increase strictly.

Errors are ``ValueError``s that name the file (or the ``source`` of arrays) and the problem.
"""

from __future__ import annotations

import hashlib
import re
from pathlib import Path

import numpy as np
from numpy.polynomial import Polynomial
from scipy.integrate import cumulative_trapezoid

G = 9.80665  # standard gravity (m/s²), the unit of AT2 files
BASELINES = {"none": None, "linear": 1, "quadratic": 2}  # degree of the velocity trend removed
MIN_SAMPLES = 3
_SNAP = 1e-9  # relative (to dt) tolerance for window bounds on the sample grid

_NUMBER = r"([^\s,]+)"
_HEADER_NEW = re.compile(rf"^\s*NPTS\s*=\s*{_NUMBER}\s*,?\s*DT\s*=\s*{_NUMBER}", re.IGNORECASE)
_HEADER_OLD = re.compile(rf"^\s*{_NUMBER}\s+{_NUMBER}\s+NPTS\s*,\s*DT\b", re.IGNORECASE)


def _fail(path, problem):
    return ValueError(f"record file {str(path)!r}: {problem}")


def _read_lines(path) -> list[str]:
    path = Path(path)
    if not path.is_file():
        raise _fail(path, "does not exist")
    text = path.read_text(errors="replace")
    if not text.strip():
        raise _fail(path, "is empty")
    return text.splitlines()


def _float(token, path, line_no, what="value"):
    try:
        return float(token)
    except ValueError:
        raise _fail(path, f"line {line_no}: {what} {token!r} is not a number") from None


def _check_finite(values, lines, path, what):
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        raise _fail(path, f"line {lines[i]}: {what} {float(values[i])!r} is not finite")


def read_at2(path) -> tuple[float, np.ndarray]:
    """Read a PEER NGA ``.AT2`` acceleration file.

    Four header lines (database, event/station/component, units, then ``NPTS=  4000, DT= .0100
    SEC`` or the older ``4000  0.0100  NPTS, DT``) followed by NPTS whitespace-separated values.

    Returns
    -------
    dt : float
        Sampling interval (s), > 0.
    acc_g : ndarray, shape (NPTS,)
        Acceleration in g (not converted).
    """
    lines = _read_lines(path)
    if len(lines) < 4:
        raise _fail(path, f"has {len(lines)} line(s); an AT2 file has 4 header lines, the 4th with NPTS and DT")
    header = lines[3]
    match = _HEADER_NEW.match(header) or _HEADER_OLD.match(header)
    if match is None:
        raise _fail(path, f"line 4: expected the NPTS/DT header ('NPTS= 4000, DT= .0100 SEC' or "
                          f"'4000  0.0100  NPTS, DT'), got {header.strip()!r}")
    try:
        npts = int(match.group(1))
    except ValueError:
        raise _fail(path, f"line 4: NPTS {match.group(1)!r} is not an integer") from None
    dt = _float(match.group(2).rstrip(","), path, 4, "DT")
    if not np.isfinite(dt) or dt <= 0:
        raise _fail(path, f"line 4: DT must be a finite number > 0, got {match.group(2)!r}")
    values, where = [], []
    for line_no, line in enumerate(lines[4:], start=5):
        for token in line.split():
            values.append(_float(token, path, line_no))
            where.append(line_no)
    if len(values) != npts:
        raise _fail(path, f"the header says NPTS={npts} but the file has {len(values)} value(s)")
    acc = np.array(values, dtype=float)
    _check_finite(acc, where, path, "value")
    return dt, acc


def write_at2(path, dt, acc_g, title="dccss acceleration record", database="dccss") -> None:
    """Write an acceleration history (in g) in the PEER NGA ``.AT2`` format, 5 values per line.

    Parameters
    ----------
    path : output file.
    dt : sampling interval (s).
    acc_g : 1-D acceleration samples in g.
    title : line 2 (event, station, component).
    database : line 1.
    """
    acc = np.asarray(acc_g, dtype=float).ravel()
    rows = [" ".join(f"{v:15.7E}" for v in acc[i:i + 5]) for i in range(0, acc.size, 5)]
    header = [database, title, "ACCELERATION TIME SERIES IN UNITS OF G",
              f"NPTS= {acc.size:7d}, DT= {float(dt):.10g} SEC"]
    Path(path).write_text("\n".join(header + rows) + "\n")


def read_acceleration_csv(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a CSV whose header names the columns ``time`` (s) and ``acceleration`` (m/s²).

    Other columns are ignored. Time must be finite and increase strictly; it need not be uniform.

    Returns
    -------
    time, acc : ndarray
        Sample times (s) and acceleration (m/s²).
    """
    lines = _read_lines(path)
    header = [h.strip() for h in lines[0].split(",")]
    if "time" not in header or "acceleration" not in header:
        raise _fail(path, f"line 1: expected a header naming the columns 'time' and 'acceleration', got {header}")
    columns = {name: header.index(name) for name in ("time", "acceleration")}
    data = {name: [] for name in columns}
    where = []
    for line_no, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        fields = line.split(",")
        if len(fields) != len(header):
            raise _fail(path, f"line {line_no}: expected {len(header)} comma-separated fields, got {len(fields)}")
        for name, j in columns.items():
            data[name].append(_float(fields[j].strip(), path, line_no, name))
        where.append(line_no)
    if not where:
        raise _fail(path, "has a header but no data rows")
    time = np.array(data["time"])
    acc = np.array(data["acceleration"])
    _check_finite(time, where, path, "time")
    _check_finite(acc, where, path, "acceleration")
    steps = np.diff(time)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise _fail(path, f"line {where[i + 1]}: time must increase strictly; {float(time[i + 1])!r} s "
                          f"follows {float(time[i])!r} s")
    return time, acc


def _trapezoid_weights(t):
    w = np.zeros_like(t)
    h = np.diff(t) / 2
    w[:-1] += h
    w[1:] += h
    return w


def integrate(time, acc, baseline="linear"):
    """Integrate an acceleration history to velocity and displacement (steps 3-5 above).

    Parameters
    ----------
    time : (n,) strictly increasing sample times (s), n >= 3.
    acc : (n,) acceleration (m/s²).
    baseline : "none", "linear" or "quadratic": degree of the least-squares trend removed from
        the velocity.

    Returns
    -------
    acc, vel, disp : ndarray
        Corrected acceleration a - p'(t) (m/s²), corrected velocity v - p(t) (m/s) and the
        displacement integrated from 0 (m).
    """
    if baseline not in BASELINES:
        raise ValueError(f"baseline must be one of {list(BASELINES)}, got {baseline!r}")
    vel = cumulative_trapezoid(acc, time, initial=0.0)
    degree = BASELINES[baseline]
    if degree is not None:
        trend = Polynomial.fit(time, vel, degree, w=np.sqrt(_trapezoid_weights(time)))
        vel = vel - trend(time)
        acc = acc - trend.deriv()(time)
    return acc, vel, cumulative_trapezoid(vel, time, initial=0.0)


def _scale(value, source):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"record {source!r}: scale must be a number, got {value!r}")
    value = float(value)
    if not np.isfinite(value) or value == 0:
        raise ValueError(f"record {source!r}: scale must be finite and non-zero, got {value!r}")
    return value


def _window(time, window, source):
    """Index slice of the samples inside window=(t0, t1); bounds snap to samples within 1e-9 dt."""
    if window is None:
        return slice(None)
    try:
        t0, t1 = (float(b) for b in window)
    except (TypeError, ValueError):
        raise ValueError(f"record {source!r}: window must be a pair (t0, t1) of times in s, got {window!r}") from None
    if not (np.isfinite(t0) and np.isfinite(t1)) or t0 >= t1:
        raise ValueError(f"record {source!r}: window ({t0!r}, {t1!r}) s must be finite with t0 < t1")
    tol = _SNAP * float(np.min(np.diff(time)))
    if t0 < time[0] - tol or t1 > time[-1] + tol:
        raise ValueError(f"record {source!r}: window ({t0!r}, {t1!r}) s lies outside the record, "
                         f"which spans {float(time[0])!r} to {float(time[-1])!r} s")
    return slice(int(np.searchsorted(time, t0 - tol, side="left")),
                 int(np.searchsorted(time, t1 + tol, side="right")))


class Record:
    """Imposed ground motion from a recorded acceleration history (see the module docstring).

    Parameters
    ----------
    time : (n,) strictly increasing sample times (s).
    acceleration : (n,) raw ground acceleration (m/s²), before scale and baseline correction.
    source : what the record is (a file name); named in errors and in ``attrs()``.
    sha256 : SHA-256 of the source file's bytes, recorded in ``attrs()`` (``from_file`` sets it).
    scale : finite non-zero factor on the acceleration.
    window : optional (t0, t1) (s): keep only the samples in that interval.
    baseline : "linear" (default), "quadratic" or "none".

    Attributes
    ----------
    time, acceleration, velocity_samples, displacement_samples : ndarray
        The processed samples: windowed times (s), scaled and corrected acceleration (m/s²),
        velocity (m/s) and displacement (m).
    """

    kind = "record"

    def __init__(self, time, acceleration, *, source="arrays", scale=1.0, window=None, baseline="linear",
                 sha256=""):
        time = np.asarray(time, dtype=float)
        acc = np.asarray(acceleration, dtype=float)
        if time.ndim != 1 or acc.shape != time.shape:
            raise ValueError(f"record {source!r}: time and acceleration must be 1-D of equal length, "
                             f"got shapes {time.shape} and {acc.shape}")
        if not (np.isfinite(time).all() and np.isfinite(acc).all()):
            raise ValueError(f"record {source!r}: time and acceleration must be finite")
        if time.size >= 2 and (np.diff(time) <= 0).any():
            raise ValueError(f"record {source!r}: time must increase strictly")
        if baseline not in BASELINES:
            raise ValueError(f"record {source!r}: baseline must be one of {list(BASELINES)}, got {baseline!r}")
        self.source = str(source)
        self.sha256 = str(sha256)
        self.scale = _scale(scale, source)
        self.baseline = baseline
        self.raw_npts = int(time.size)
        if time.size < MIN_SAMPLES:
            raise ValueError(f"record {source!r}: has {time.size} sample(s); at least {MIN_SAMPLES} are needed")
        cut = _window(time, window, source)
        self.window = (float(window[0]), float(window[1])) if window is not None else None
        time, acc = time[cut], acc[cut]
        if time.size < MIN_SAMPLES:
            raise ValueError(f"record {source!r}: the window {window!r} s holds {time.size} sample(s); "
                             f"at least {MIN_SAMPLES} are needed")
        self.time = time
        self.acceleration, self.velocity_samples, self.displacement_samples = integrate(
            time, self.scale * acc, baseline)

    @classmethod
    def from_file(cls, path, scale=1.0, window=None, baseline="linear") -> Record:
        """Read ``path`` (``.AT2``/``.at2``: PEER NGA, in g; ``.csv``: time, acceleration in m/s²)
        and process it; errors name the file."""
        path = Path(path)
        suffix = path.suffix.lower()
        if suffix == ".at2":
            dt, acc_g = read_at2(path)
            time, acc = dt * np.arange(acc_g.size), G * acc_g
        elif suffix == ".csv":
            time, acc = read_acceleration_csv(path)
        else:
            raise _fail(path, f"unknown record format {path.suffix!r}; expected .AT2 (PEER NGA) or .csv")
        return cls(time, acc, source=str(path), scale=scale, window=window, baseline=baseline,
                   sha256=hashlib.sha256(path.read_bytes()).hexdigest())

    @property
    def t_start(self) -> float:
        return float(self.time[0])

    @property
    def t_end(self) -> float:
        return float(self.time[-1])

    @property
    def npts(self) -> int:
        """Number of samples used (after the window)."""
        return int(self.time.size)

    @property
    def dt(self) -> float:
        """Sampling interval (s, to 12 significant digits); the largest step if the time is not uniform."""
        steps = np.diff(self.time)
        mean = (self.t_end - self.t_start) / steps.size
        dt = mean if np.ptp(steps) <= 1e-9 * mean else float(np.max(steps))
        return float(f"{dt:.12g}")

    @property
    def pga(self) -> float:
        """Peak ground acceleration after processing (m/s²)."""
        return float(np.max(np.abs(self.acceleration)))

    @property
    def pgv(self) -> float:
        """Peak ground velocity after processing (m/s)."""
        return float(np.max(np.abs(self.velocity_samples)))

    @property
    def pgd(self) -> float:
        """Peak ground displacement after processing (m)."""
        return float(np.max(np.abs(self.displacement_samples)))

    def displacement(self, t):
        """X_g (m) at times t (s), linearly interpolated."""
        return np.interp(t, self.time, self.displacement_samples)

    def velocity(self, t):
        """dX_g/dt (m/s) at times t (s), linearly interpolated."""
        return np.interp(t, self.time, self.velocity_samples)

    def attrs(self) -> dict:
        """netCDF global attributes (str, int, float) describing the record and its processing."""
        start, end = self.window if self.window is not None else (self.t_start, self.t_end)
        return {"excitation": "record", "record_source": Path(self.source).name, "record_sha256": self.sha256,
                "record_npts": self.npts, "record_raw_npts": self.raw_npts, "record_dt_s": self.dt,
                "record_scale": self.scale, "record_window_start_s": float(start),
                "record_window_end_s": float(end), "record_baseline": self.baseline,
                "record_pga_m_per_s2": self.pga, "record_pgv_m_per_s": self.pgv, "record_pgd_m": self.pgd}

    def __repr__(self):
        return (f"Record({Path(self.source).name!r}, {self.npts} samples, t = {self.t_start:g}..{self.t_end:g} s, "
                f"scale={self.scale:g}, baseline={self.baseline!r}, PGA={self.pga / G:.3f} g, PGD={self.pgd:.3f} m)")
