"""Imposed ground displacement histories X_g(t) (m) and velocities (m/s)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .checks import CaseError, number


def _number(name, value, *, positive=False):
    return number(value, f"excitation.{name}", positive=positive)


@dataclass(frozen=True)
class Sine:
    """X_g(t) = X_g,max sin(omega t) on 0 <= t <= duration, with the analytic velocity."""

    amplitude: float  # X_g,max (m)
    omega: float  # omega_g (rad/s)
    duration: float  # t_g (s)
    kind = "sine"

    def __post_init__(self):
        object.__setattr__(self, "amplitude", _number("amplitude", self.amplitude))
        object.__setattr__(self, "omega", _number("omega", self.omega))
        object.__setattr__(self, "duration", _number("duration", self.duration, positive=True))

    t_start = 0.0
    #: what a sweep may vary, per case: displacement(t, amplitude=..., omega=...)
    parameters = ("amplitude", "omega")

    @property
    def t_end(self):
        return self.duration

    def displacement(self, t, amplitude=None, omega=None):
        """X_g (m) at times t (s); ``amplitude``/``omega`` (arrays) evaluate a batch of sines at once
        (broadcast against t: pass t[:, None] for (T, n))."""
        amplitude, omega = self._batch(amplitude, omega)
        return amplitude * np.sin(omega * np.asarray(t, dtype=float))

    def velocity(self, t, amplitude=None, omega=None):
        """dX_g/dt (m/s), as ``displacement``."""
        amplitude, omega = self._batch(amplitude, omega)
        return amplitude * omega * np.cos(omega * np.asarray(t, dtype=float))

    def _batch(self, amplitude, omega):
        return (self.amplitude if amplitude is None else amplitude, self.omega if omega is None else omega)

    def attrs(self) -> dict:
        return {"excitation": "sine", "amplitude_m": self.amplitude, "omega_rad_per_s": self.omega,
                "duration_s": self.duration}


@dataclass(frozen=True, eq=False)
class Table:
    """Sampled X_g: linear interpolation between samples; the velocity is the interpolated
    second-order central difference of the samples (numpy.gradient)."""

    time: np.ndarray  # (n,) s, strictly increasing
    displacement_samples: np.ndarray  # (n,) m
    source: str = "arrays"
    kind = "table"
    parameters = ()

    def __post_init__(self):
        t = np.asarray(self.time, dtype=float)
        x = np.asarray(self.displacement_samples, dtype=float)
        if t.ndim != 1 or x.shape != t.shape:
            raise ValueError(f"table excitation ({self.source}): time and displacement must be "
                             f"1-D of equal length, got shapes {t.shape} and {x.shape}")
        if t.size < 2:
            raise ValueError(f"table excitation ({self.source}): needs at least 2 samples, got {t.size}")
        for name, a in (("time", t), ("displacement", x)):
            bad = ~np.isfinite(a)
            if bad.any():
                i = int(np.argmax(bad))
                raise ValueError(f"table excitation ({self.source}): {name} sample {i} is not "
                                 f"finite ({a[i]!r})")
        steps = np.diff(t)
        if (steps <= 0).any():
            i = int(np.argmax(steps <= 0))
            raise ValueError(f"table excitation ({self.source}): time must increase strictly; "
                             f"sample {i + 1} ({t[i + 1]!r} s) follows {t[i]!r} s")
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "displacement_samples", x)

    @classmethod
    def from_csv(cls, path) -> Table:
        """Read a CSV with a header naming the columns ``time`` (s) and ``displacement`` (m)."""
        path = Path(path)
        if not path.is_file():
            raise ValueError(f"table excitation: file {str(path)!r} does not exist")
        lines = path.read_text().splitlines()
        header = [h.strip() for h in lines[0].split(",")] if lines else []
        if "time" not in header or "displacement" not in header:
            raise ValueError(f"table excitation: {str(path)!r} must have a header with columns "
                             f"'time' and 'displacement', got {header}")
        rows = [line for line in lines[1:] if line.strip()]
        if not rows:
            raise ValueError(f"table excitation: {str(path)!r} has no data rows")
        try:
            data = np.loadtxt(rows, delimiter=",", ndmin=2)
        except ValueError as err:
            raise ValueError(f"table excitation: {str(path)!r} is not numeric CSV: {err}") from None
        return cls(data[:, header.index("time")], data[:, header.index("displacement")],
                   source=str(path))

    @property
    def t_start(self):
        return float(self.time[0])

    @property
    def t_end(self):
        return float(self.time[-1])

    def displacement(self, t):
        return np.interp(t, self.time, self.displacement_samples)

    def velocity(self, t):
        return np.interp(t, self.time, np.gradient(self.displacement_samples, self.time))

    def attrs(self) -> dict:
        return {"excitation": "table", "table_source": self.source,
                "table_samples": int(self.time.size)}


@dataclass(frozen=True)
class Scaled:
    """An excitation multiplied by a constant ``factor`` (X_g and its velocity)."""

    excitation: object
    factor: float
    parameters = ()

    @property
    def kind(self):
        return self.excitation.kind

    @property
    def t_start(self):
        return self.excitation.t_start

    @property
    def t_end(self):
        return self.excitation.t_end

    def displacement(self, t):
        return self.factor * self.excitation.displacement(t)

    def velocity(self, t):
        return self.factor * self.excitation.velocity(t)

    def attrs(self):
        return {**self.excitation.attrs(), "excitation_scale": self.factor}


def check_step(dt, excitation, key="dt") -> float:
    """The time step dt (s) as a float: a number > 0 no larger than the excitation's duration;
    a CaseError names ``key`` otherwise."""
    dt = number(dt, key, positive=True)
    span = excitation.t_end - excitation.t_start
    if dt > span * (1 + 1e-12):
        raise CaseError(f"{key}: {dt!r} s is larger than the excitation's duration {span!r} s")
    return dt


def step_times(excitation, dt) -> np.ndarray:
    """t_n = t_start + n dt, n = 0..N, the last step ending at or before t_end."""
    dt = check_step(dt, excitation)
    span = excitation.t_end - excitation.t_start
    ratio = span / dt
    n = round(ratio) if abs(ratio - round(ratio)) < 1e-9 * max(1.0, ratio) else int(np.floor(ratio))
    return excitation.t_start + dt * np.arange(n + 1)
