"""Imposed ground displacement histories X_g(t) (m) and velocities (m/s).

Every excitation has ``components``: 1 for a ground motion along one horizontal line (the
planar models' X_g), 2 for a bidirectional one in the horizontal plane. Both kinds have
``t_start``, ``t_end`` (s), ``parameters`` (what a sweep may vary, per case), ``attrs()``
(global netCDF attributes: numbers and strings) and ``kind`` (the ``kind`` of its case file
entry). ``displacement(t)`` (m) and ``velocity(t)`` (m/s) return the shape of ``t`` for one
component, and that shape plus a last axis (x, y) of length 2 for two.

``ground_acceleration()`` is the ground's acceleration (m/s²) as a ``mechanics.structure.Ground``
(straight lines between interval ends, a column per component): what drives an isolated
structure. The structure starts at rest relative to the ground at ``t_start``, so only the
acceleration on (t_start, t_end) acts: a sine's is its second derivative (sampled at 4000 points a
period: 3.1e-7 of its peak at most off), a table's the derivative of its velocity (constant between
samples), a record's its processed acceleration samples joined by straight lines.

Two-component excitations also have ``azimuth`` (rad): the reference direction for a zero
increment, measured from +x towards +y (the azimuth of an :class:`Oriented` input, 0.0
otherwise); their ``attrs()`` include ``excitation_components = 2`` and
``excitation_form`` (``"oriented"``, ``"two-column table"``, ``"record pair"``). Azimuths are
given in degrees (case files, sweeps, ``Oriented``).

* :class:`Sine`, :class:`Table` (CSV ``time, displacement``): one component;
* :class:`Oriented`: a one-component excitation applied along an azimuth, X(t) (cos az, sin az);
* :class:`PlaneTable` (CSV ``time, x, y``): two sampled components; :func:`read_table` reads
  either CSV by its header;
* ``dccss.records.Record`` (one component) and ``dccss.records.RecordPair`` (two);
* :class:`Scaled`: any of them times a constant factor;
* :class:`Vertical`: any of them with a vertical ground acceleration (a record's vertical component or
  a :class:`VerticalSine`), which acts on an isolated structure's normal force only.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .checks import CaseError, number
from .mechanics.structure import Ground

#: the CSV headers a table excitation may have: one component, two components
TABLE_HEADERS = (("time", "displacement"), ("time", "x", "y"))
_ALLOWED_HEADERS = " or ".join(f"'{', '.join(h)}'" for h in TABLE_HEADERS)


def _number(name, value, *, positive=False):
    return number(value, f"excitation.{name}", positive=positive)


def direction(azimuth_deg):
    """(cos az, sin az) of an azimuth in degrees (scalars or arrays): the angle is reduced to
    [0, 360) first (exactly), and multiples of 90° give exact 0 and ±1."""
    deg = np.mod(np.asarray(azimuth_deg, dtype=float), 360.0)
    rad = np.radians(deg)
    c, s = np.cos(rad), np.sin(rad)
    right = deg % 90.0 == 0.0
    return np.where(right, np.round(c), c) + 0.0, np.where(right, np.round(s), s) + 0.0


@dataclass(frozen=True)
class Sine:
    """X_g(t) = X_g,max sin(omega t) on 0 <= t <= duration, with the analytic velocity."""

    amplitude: float  # X_g,max (m)
    omega: float  # omega_g (rad/s)
    duration: float  # t_g (s)
    kind = "sine"
    components = 1

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

    #: samples a period of the sine's acceleration is drawn with in ``ground_acceleration``
    SAMPLES_PER_PERIOD = 4000

    def ground_acceleration(self, amplitude=None, omega=None) -> Ground:
        """-X_g,max ω² sin(ω t), sampled at SAMPLES_PER_PERIOD points a period and joined by straight
        lines (``amplitude``, ``omega``: one case's, in place of the sine's own)."""
        amplitude, omega = (float(v) for v in self._batch(amplitude, omega))
        periods = abs(omega) * self.duration / (2 * np.pi)
        t = np.linspace(0.0, self.duration, max(2, int(np.ceil(periods * self.SAMPLES_PER_PERIOD)) + 1))
        return Ground.from_samples(t, -amplitude * omega**2 * np.sin(omega * t))

    def attrs(self) -> dict:
        return {"excitation": "sine", "amplitude_m": self.amplitude, "omega_rad_per_s": self.omega,
                "duration_s": self.duration}


def _check_samples(source, time, **columns):
    """(time, *columns) as float arrays, checked: 1-D of equal length, >= 2 samples, finite,
    time strictly increasing; errors name ``source`` and the column."""
    t = np.asarray(time, dtype=float)
    arrays = {name: np.asarray(a, dtype=float) for name, a in columns.items()}
    for name, a in arrays.items():
        if t.ndim != 1 or a.shape != t.shape:
            raise ValueError(f"table excitation ({source}): time and {name} must be "
                             f"1-D of equal length, got shapes {t.shape} and {a.shape}")
    if t.size < 2:
        raise ValueError(f"table excitation ({source}): needs at least 2 samples, got {t.size}")
    for name, a in (("time", t), *arrays.items()):
        bad = ~np.isfinite(a)
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"table excitation ({source}): {name} sample {i} is not "
                             f"finite ({float(a[i])})")
    steps = np.diff(t)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise ValueError(f"table excitation ({source}): time must increase strictly; "
                         f"sample {i + 1} ({float(t[i + 1]):.12g} s) follows {float(t[i]):.12g} s")
    return (t, *arrays.values())


def _read_csv(path):
    """(path, header, columns) of a table CSV: ``columns`` are the motion columns its header names,
    ("displacement",) or ("x", "y"); the header is checked against :data:`TABLE_HEADERS`."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"table excitation: file {str(path)!r} does not exist")
    lines = path.read_text().splitlines()
    header = [h.strip() for h in lines[0].split(",")] if lines else []
    name = repr(str(path))
    plane = [c for c in ("x", "y") if c in header]
    if "time" not in header or not ("displacement" in header or plane):
        raise ValueError(f"table excitation: {name} must have a header with columns 'time' and 'displacement' "
                         f"(one component, m) or 'time', 'x' and 'y' (two components, m), got {header}; "
                         f"allowed headers: {_ALLOWED_HEADERS}")
    if "displacement" in header and plane:
        raise ValueError(f"table excitation: {name} has both 'displacement' and {plane} columns in {header}: "
                         f"give one component ('time, displacement') or two ('time, x, y'); allowed headers: "
                         f"{_ALLOWED_HEADERS}")
    columns = ("displacement",) if not plane else ("x", "y")
    if plane and len(plane) != 2:
        missing = "y" if "x" in plane else "x"
        raise ValueError(f"table excitation: {name} has a column {plane[0]!r} but no {missing!r} (columns found: "
                         f"{header}): a two-component table needs both; allowed headers: {_ALLOWED_HEADERS}")
    if plane and len(header) != 3:
        raise ValueError(f"table excitation: {name}: a two-component table has exactly the columns 'time', 'x' "
                         f"and 'y', got {header}; allowed headers: {_ALLOWED_HEADERS}")
    repeated = [c for c in ("time", *columns) if header.count(c) > 1]
    if repeated:
        raise ValueError(f"table excitation: {name}: column(s) {repeated} appear more than once in {header}")
    rows = [line for line in lines[1:] if line.strip()]
    if not rows:
        raise ValueError(f"table excitation: {name} has no data rows")
    try:
        data = np.loadtxt(rows, delimiter=",", ndmin=2)
    except ValueError as err:
        raise ValueError(f"table excitation: {name} is not numeric CSV: {err}") from None
    return path, header, data, columns


class _Sampled:
    """The time range of an excitation given as samples at ``time`` (s)."""

    @property
    def t_start(self):
        return float(self.time[0])

    @property
    def t_end(self):
        return float(self.time[-1])


@dataclass(frozen=True, eq=False)
class Table(_Sampled):
    """Sampled X_g: linear interpolation between samples; the velocity is the interpolated
    second-order central difference of the samples (numpy.gradient)."""

    time: np.ndarray  # (n,) s, strictly increasing
    displacement_samples: np.ndarray  # (n,) m
    source: str = "arrays"
    kind = "table"
    components = 1
    parameters = ()

    def __post_init__(self):
        t, x = _check_samples(self.source, self.time, displacement=self.displacement_samples)
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "displacement_samples", x)

    @classmethod
    def from_csv(cls, path) -> Table:
        """Read a CSV with a header naming the columns ``time`` (s) and ``displacement`` (m)
        (other columns are ignored; see :func:`read_table` for either kind of table)."""
        path, header, data, columns = _read_csv(path)
        if columns != ("displacement",):
            raise ValueError(f"table excitation: {str(path)!r} has two components (columns {header}): read it with "
                             f"PlaneTable.from_csv or read_table")
        return cls(data[:, header.index("time")], data[:, header.index("displacement")],
                   source=str(path))

    def displacement(self, t):
        return np.interp(t, self.time, self.displacement_samples)

    def velocity(self, t):
        return np.interp(t, self.time, np.gradient(self.displacement_samples, self.time))

    def ground_acceleration(self) -> Ground:
        """The derivative of ``velocity``: constant between samples."""
        return _steps(self.time, self.displacement_samples[:, None])

    def attrs(self) -> dict:
        return {"excitation": "table", "table_source": self.source,
                "table_samples": int(self.time.size)}


@dataclass(frozen=True, eq=False)
class PlaneTable(_Sampled):
    """Sampled two-component ground displacement (x, y) (m): each component is interpolated
    linearly between samples; the velocity is the interpolated second-order central difference
    of each component's samples (numpy.gradient), as in :class:`Table`."""

    time: np.ndarray  # (n,) s, strictly increasing
    x: np.ndarray  # (n,) m
    y: np.ndarray  # (n,) m
    source: str = "arrays"
    kind = "table"
    components = 2
    parameters = ()
    azimuth = 0.0

    def __post_init__(self):
        t, x, y = _check_samples(self.source, self.time, x=self.x, y=self.y)
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)

    @classmethod
    def from_csv(cls, path) -> PlaneTable:
        """Read a CSV with a header naming exactly the columns ``time`` (s), ``x`` and ``y`` (m)."""
        path, header, data, columns = _read_csv(path)
        if columns != ("x", "y"):
            raise ValueError(f"table excitation: {str(path)!r} has one component (columns {header}), not the "
                             f"columns 'time, x, y' of a two-component table")
        return cls(*(data[:, header.index(c)] for c in ("time", "x", "y")), source=str(path))

    @property
    def displacement_samples(self) -> np.ndarray:
        """(n, 2) samples (m)."""
        return np.column_stack([self.x, self.y])

    def displacement(self, t):
        """(x, y) (m) at times t (s): shape t.shape + (2,)."""
        return np.stack([np.interp(t, self.time, self.x), np.interp(t, self.time, self.y)], axis=-1)

    def velocity(self, t):
        """(dx/dt, dy/dt) (m/s) at times t (s): shape t.shape + (2,)."""
        return np.stack([np.interp(t, self.time, np.gradient(c, self.time)) for c in (self.x, self.y)], axis=-1)

    def ground_acceleration(self) -> Ground:
        """The derivative of ``velocity``, per component: constant between samples."""
        return _steps(self.time, self.displacement_samples)

    def attrs(self) -> dict:
        return {"excitation": "table", "excitation_components": 2, "excitation_form": "two-column table",
                "table_source": self.source, "table_samples": int(self.time.size), "table_columns": "time, x, y"}


def _steps(time, displacement):
    """The acceleration of a table: the slope of its velocity (numpy.gradient of the samples) between samples."""
    slope = np.diff(np.gradient(displacement, time, axis=0), axis=0) / np.diff(time)[:, None]
    return Ground(time, slope, np.zeros_like(slope))


def read_table(path):
    """A :class:`Table` or a :class:`PlaneTable` from a CSV, by its header (:data:`TABLE_HEADERS`)."""
    path, header, data, columns = _read_csv(path)
    if columns == ("x", "y"):
        return PlaneTable(*(data[:, header.index(c)] for c in ("time", "x", "y")), source=str(path))
    return Table(data[:, header.index("time")], data[:, header.index("displacement")], source=str(path))


def _times(ground: Ground, factor) -> Ground:
    """``ground`` with its horizontal acceleration multiplied by ``factor`` (a number, or a row per
    component); its vertical as it is."""
    return ground.scaled(factor)


def underlying(excitation):
    """The excitation a wrapper (``Component``, ``Oriented``, ``Scaled``) is built on (itself if none)."""
    while isinstance(excitation, _Wrapper):
        excitation = excitation.excitation
    return excitation


def has_vertical(excitation) -> bool:
    """Whether an excitation (through its wrappers) carries a vertical ground acceleration (``Vertical``)."""
    while isinstance(excitation, _Wrapper):
        if isinstance(excitation, Vertical):
            return True
        excitation = excitation.excitation
    return False


class _Wrapper:
    """An excitation built on another (``self.excitation``): its kind and time span are the inner one's."""

    @property
    def kind(self):
        return self.excitation.kind

    @property
    def t_start(self):
        return self.excitation.t_start

    @property
    def t_end(self):
        return self.excitation.t_end


@dataclass(frozen=True)
class Oriented(_Wrapper):
    """A one-component excitation X(t) applied along the azimuth ``azimuth_deg`` (degrees, from
    +x towards +y): displacement X(t) (cos az, sin az), velocity likewise (see :func:`direction`).

    ``parameters`` are the inner excitation's and ``"azimuth"``; ``displacement(t,
    azimuth=..., **inner)`` evaluates a batch: the azimuth per case in degrees (as in case files
    and sweeps), the inner parameters (e.g. a Sine's amplitude and omega) passed on, all
    broadcast against t as ``Sine.displacement`` does (pass t[:, None] for (T, n)); the result
    has a last axis (x, y): (T, n, 2).
    """

    excitation: object
    azimuth_deg: float
    components = 2

    def __post_init__(self):
        if getattr(self.excitation, "components", 1) != 1:
            raise ValueError(f"excitation.azimuth: orients a one-component excitation, but this "
                             f"{self.excitation.kind} excitation has {self.excitation.components} components already")
        object.__setattr__(self, "azimuth_deg", _number("azimuth", self.azimuth_deg))

    @property
    def parameters(self):
        return (*self.excitation.parameters, "azimuth")

    @property
    def azimuth(self) -> float:
        """The azimuth (rad)."""
        return float(np.radians(self.azimuth_deg))

    @property
    def direction(self) -> np.ndarray:
        """The unit vector (cos az, sin az) the displacement is along."""
        return np.array(direction(self.azimuth_deg))

    def _along(self, X, azimuth):
        c, s = direction(self.azimuth_deg if azimuth is None else azimuth)
        return np.stack(np.broadcast_arrays(X * c, X * s), axis=-1)

    def displacement(self, t, azimuth=None, **parameters):
        """(x, y) (m) at times t (s): shape of the inner result + (2,); see the class docstring."""
        return self._along(self.excitation.displacement(t, **parameters), azimuth)

    def velocity(self, t, azimuth=None, **parameters):
        """(dx/dt, dy/dt) (m/s), as ``displacement``."""
        return self._along(self.excitation.velocity(t, **parameters), azimuth)

    def ground_acceleration(self, azimuth=None, **parameters) -> Ground:
        """The inner excitation's along the azimuth (one case's ``azimuth`` in degrees and inner parameters)."""
        along = np.array(direction(self.azimuth_deg if azimuth is None else azimuth))
        return _times(self.excitation.ground_acceleration(**parameters), along)

    def attrs(self) -> dict:
        return {**self.excitation.attrs(), "excitation_components": 2, "excitation_form": "oriented",
                "excitation_azimuth_deg": self.azimuth_deg}


#: the components of a two-component excitation a case may keep (``Component``)
COMPONENTS = ("x", "y", "both")


@dataclass(frozen=True)
class Component(_Wrapper):
    """One component of a two-component excitation, the other held at zero (``which``: "x" or
    "y"), or both ("both"): the same record pair or table run unidirectionally and
    bidirectionally, with the same spatial model and outputs. Along y the reference azimuth (the
    direction of a zero increment) is 90 degrees, along x 0."""

    excitation: object
    which: str
    components = 2

    def __post_init__(self):
        if getattr(self.excitation, "components", 1) != 2:
            raise ValueError("excitation.component: keeps a component of a two-component excitation (a record pair "
                             "or a time, x, y table); this one has one component")
        if self.which not in COMPONENTS:
            raise ValueError(f"excitation.component: expected one of {list(COMPONENTS)}, got {self.which!r}")

    @property
    def parameters(self):
        return self.excitation.parameters

    @property
    def azimuth(self) -> float:
        return {"x": 0.0, "y": float(np.pi / 2), "both": float(self.excitation.azimuth)}[self.which]

    @property
    def mask(self) -> np.ndarray:
        return np.array([self.which != "y", self.which != "x"], dtype=float)

    def displacement(self, t, **parameters):
        return self.excitation.displacement(t, **parameters) * self.mask

    def velocity(self, t, **parameters):
        return self.excitation.velocity(t, **parameters) * self.mask

    def ground_acceleration(self, **parameters) -> Ground:
        return _times(self.excitation.ground_acceleration(**parameters), self.mask)

    def attrs(self) -> dict:
        return {**self.excitation.attrs(), "excitation_component": self.which}


@dataclass(frozen=True)
class Scaled(_Wrapper):
    """An excitation multiplied by a constant ``factor`` (X_g and its velocity; both components
    of a two-component one)."""

    excitation: object
    factor: float
    parameters = ()

    def __post_init__(self):
        object.__setattr__(self, "factor", _number("scale", self.factor))

    @property
    def components(self):
        return getattr(self.excitation, "components", 1)

    @property
    def azimuth(self):
        """The inner excitation's azimuth (rad); only two-component excitations have one."""
        return self.excitation.azimuth

    def displacement(self, t):
        return self.factor * self.excitation.displacement(t)

    def velocity(self, t):
        return self.factor * self.excitation.velocity(t)

    def ground_acceleration(self) -> Ground:
        """The inner excitation's times the factor, its vertical times its size (a record's scale is its
        vertical's; a negative one mirrors the horizontal motion, and gravity keeps its direction)."""
        return self.excitation.ground_acceleration().scaled(self.factor, vertical=abs(self.factor))

    def attrs(self):
        return {**self.excitation.attrs(), "excitation_scale": self.factor}


@dataclass(frozen=True)
class VerticalSine:
    """A vertical ground acceleration a_v(t) = amplitude sin(omega (t - t_start)) (m/s², up positive; rad/s)."""

    amplitude: float
    omega: float
    t_start: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "amplitude", number(self.amplitude, "excitation.vertical.amplitude"))
        object.__setattr__(self, "omega", number(self.omega, "excitation.vertical.omega"))

    def at(self, t):
        return self.amplitude * np.sin(self.omega * (np.asarray(t, dtype=float) - self.t_start))

    def attrs(self) -> dict:
        return {"vertical_form": "sine", "vertical_amplitude_m_per_s2": self.amplitude,
                "vertical_omega_rad_per_s": self.omega}


@dataclass(frozen=True)
class Vertical(_Wrapper):
    """An excitation with a vertical ground acceleration a_v(t) (m/s², up positive): ``vertical`` a
    processed ``dccss.records.Record`` on the excitation's samples (a record's vertical component) or a
    :class:`VerticalSine`. It changes nothing of the horizontal motion; it acts on an isolated
    structure's normal force N = W (1 + a_v/g) (``ground_acceleration`` carries it, sampled at the
    horizontal's interval ends)."""

    excitation: object
    vertical: object

    @property
    def components(self):
        return self.excitation.components

    @property
    def parameters(self):
        return self.excitation.parameters

    @property
    def azimuth(self):
        return self.excitation.azimuth

    def displacement(self, t, **parameters):
        return self.excitation.displacement(t, **parameters)

    def velocity(self, t, **parameters):
        return self.excitation.velocity(t, **parameters)

    def vertical_acceleration(self, t):
        """a_v (m/s², up positive) at times t (s): a record's samples joined by straight lines."""
        if isinstance(self.vertical, VerticalSine):
            return self.vertical.at(t)
        return np.interp(t, self.vertical.time, self.vertical.acceleration)

    @property
    def vertical_pga(self) -> float:
        """The largest |a_v| (m/s²) over the excitation's span."""
        if isinstance(self.vertical, VerticalSine):
            return abs(self.vertical.amplitude)
        return float(np.max(np.abs(self.vertical.acceleration)))

    def ground_acceleration(self, **parameters) -> Ground:
        ground = self.excitation.ground_acceleration(**parameters)
        a_v = self.vertical_acceleration(ground.time)
        return ground._replace(v0=a_v[:-1], v1=np.diff(a_v) / np.diff(ground.time))

    def attrs(self) -> dict:
        own = self.vertical.attrs()
        if not isinstance(self.vertical, VerticalSine):
            own = {"vertical_form": "record", **{f"record_vertical_{k.removeprefix('record_')}": v
                                                 for k, v in own.items() if k != "excitation"}}
        return {**self.excitation.attrs(), **own, "vertical_pga_m_per_s2": self.vertical_pga}


def check_step(dt, excitation, key="dt") -> float:
    """The time step dt (s) as a float: a number > 0 no larger than the excitation's duration;
    a CaseError names ``key`` otherwise."""
    dt = number(dt, key, positive=True)
    span = excitation.t_end - excitation.t_start
    if dt > span * (1 + 1e-12):
        raise CaseError(f"{key}: {dt!r} s is larger than the excitation's duration {span!r} s")
    return dt


def uncovered(excitation, times, dt) -> str | None:
    """What a run at step ``dt`` (its step ``times``) leaves of the excitation's duration, said; None where
    dt divides it."""
    left = excitation.t_end - times[-1]
    if left > 1e-9 * float(dt):
        span = excitation.t_end - excitation.t_start
        return (f"dt = {float(dt):g} s does not divide the excitation's duration ({span:g} s): the history ends at "
                f"t = {times[-1]:.6g} s, {left:.3g} s before the motion does")
    return None


def step_times(excitation, dt) -> np.ndarray:
    """t_n = t_start + n dt, n = 0..N, the last step ending at or before t_end."""
    dt = check_step(dt, excitation)
    span = excitation.t_end - excitation.t_start
    ratio = span / dt
    n = round(ratio) if abs(ratio - round(ratio)) < 1e-9 * max(1.0, ratio) else int(np.floor(ratio))
    return excitation.t_start + dt * np.arange(n + 1)
