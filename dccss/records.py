"""Recorded ground motions: an acceleration, velocity or displacement history turned into X_g(t).

A :class:`Record` reads a recorded (or synthetic) ground-motion history and turns it into a
ground displacement and velocity with the interface of ``dccss.excitation`` (``t_start``,
``t_end``, ``displacement(t)``, ``velocity(t)``, ``attrs()``), so that ``simulation.simulate``
accepts it like a ``Sine`` or a ``Table``. Inside, everything is SI: s, m/s², m/s, m.

Formats
-------
* PEER NGA files: ``.AT2`` (acceleration), ``.VT2`` (velocity), ``.DT2`` (displacement). Line 3
  states the units, e.g. ``ACCELERATION TIME SERIES IN UNITS OF G`` (NGA-West2), ``ACCELERATION
  TIME HISTORY IN UNITS OF G`` (older NGA), ``VELOCITY TIME SERIES IN UNITS OF CM/S``,
  ``DISPLACEMENT TIME SERIES IN UNITS OF CM``: the text after ``UNITS OF`` (or ``UNITS:``, or
  after ``IN``). A quantity word on that line (ACCELERATION, VELOCITY, DISPLACEMENT) must agree
  with the extension, and so must the units. Line 4 gives NPTS and DT (``NPTS=  4000, DT= .0100
  SEC`` or the older ``4000  0.0100  NPTS, DT``); NPTS values follow.
* Two-column text files: ``.csv``, ``.txt``, ``.dat``; separated by commas, semicolons, tabs or
  white space (the first of ``,``, ``;``, tab found on the first non-comment line, else white
  space); lines starting with ``#`` are comments and ignored. The first non-comment line is a
  header if none of its fields is a number. A header field is a name and optional units in
  brackets: ``time (s)``, ``acc [g]``, ``acceleration[m/s^2]``, ``disp (cm)``. A column is a time
  column or a motion column by its units or by a word of its name (``t``/``time``;
  ``a``/``acc``/``accel…``; ``v``/``vel``/``veloc…``; ``d``/``u``/``disp``/``displ…``); a
  name that says one quantity and units that say another are refused. With two columns, a
  column the header does not identify takes its place: time first, then the motion. With more
  columns the header must identify one time column and one motion column (others are ignored;
  several motion columns are told apart by ``units``). Without a header the file has exactly two
  columns. Time is in s (other time units are refused); it must increase strictly and need not
  be uniform.

Units
-----
One table, :data:`UNITS`: acceleration g, m/s2, cm/s2 (= gal), mm/s2; velocity m/s, cm/s, mm/s;
displacement m, cm, mm. Spelling is case-insensitive and tolerant: ``SEC`` for ``S``, ``S/S``,
``^2``, ``**2`` or ``²`` for ``S2``, spaces ignored (``CM/SEC/SEC``, ``cm/s^2``, ``CM/S2``,
``GAL`` are the same unit). The units say the quantity. They come from the file (PEER line 3, a
header) or from the ``units`` argument (the ``units`` key of a record excitation); when both are
given they must agree (a PEER file whose line 3 states no units is read with the given ones).
Units that cannot be told are refused, never guessed.

Why a baseline correction
-------------------------
A raw accelerogram integrated twice drifts: a constant offset c in the acceleration (instrument
zero, tilt, digitisation) becomes a velocity c t and a displacement c t²/2, growing without bound,
and low-frequency noise does the same more slowly. The standard minimal remedy, used here, is to
remove a least-squares polynomial trend from the velocity before the second integration.

Processing, in this order
-------------------------
1. Units: the samples are converted to SI (g = 9.80665 m/s²); ``scale`` then multiplies them
   (any finite non-zero number; a negative one flips the record).
2. Velocity: an acceleration record is integrated, v = ∫ a dt from v = 0 at the first sample
   (``cumulative_trapezoid``: scipy's, bit for bit); a velocity record is its samples.
3. Baseline: ``"linear"`` (default) subtracts from v its least-squares straight line p(t),
   ``"quadratic"`` its least-squares parabola, ``"none"`` nothing. Removing p from v is the same
   as removing p'(t) from the acceleration, i.e. a constant (linear) acceleration offset for the
   linear (quadratic) baseline; the corrected acceleration a - p' is what ``acceleration``
   holds and what the peak ground acceleration is measured on. The fit is weighted with the
   trapezoidal quadrature weights, so it is the discrete form of the continuous least-squares
   fit (minimising ∫ (v - p)² dt) and keeps the O(dt²) accuracy of step 3: an unweighted fit
   (``scipy.signal.detrend``) counts the two end samples fully and leaves an O(dt) offset in the
   velocity, i.e. a drift of the displacement. The corrected velocity need not be 0 at
   the first sample.
4. Displacement: X_g = ∫ v dt from X_g = 0 at the first sample (``cumulative_trapezoid``). The
   displacement is not detrended; but since the fitted trend has a constant term, the weighted
   residual v - p sums to zero, so with a baseline X_g also returns to 0 at the record's end (no
   permanent ground offset: the correction cannot represent one).
5. ``window=(t0, t1)`` then keeps the samples with t0 <= t <= t1 (a bound within 1e-9 dt of a
   sample counts as on it): the whole record is integrated and corrected first, so **a window
   never changes the motion inside it** (a window of the raw samples would fit the baseline to
   the window alone and move X_g by centimetres). The record keeps its own time axis:
   ``t_start`` is the first kept sample (= t0 on the sample grid), not 0, and X_g and its
   velocity there need not be 0 (the models start from the device's compatible configuration at
   X_g(t_start); a structure starts at rest relative to the ground there).

A displacement record is not integrated: X_g is its samples as recorded (after units and scale,
then the window; so X_g(t_start) is the first kept sample, not necessarily 0), and its velocity is their
second-order central difference (``numpy.gradient``, as ``dccss.excitation.Table``). Its baseline
is ``"none"``: ``"linear"`` and ``"quadratic"`` act on an integrated velocity and are refused.
Integrating each record only as far as needed keeps a processed velocity or displacement from
being processed again.

Peak ground acceleration and plausibility
-----------------------------------------
``acceleration`` (hence ``pga``) is the corrected acceleration of an acceleration record; for a
velocity record the central difference of the corrected velocity (``numpy.gradient``), for a
displacement record the three-point second difference of the displacement (the end samples
take their neighbour's value). On uniform steps both estimates equal (a[i-1] + 2 a[i] + a[i+1])/4
of a trapezoid-integrated acceleration, slightly below its peak for components near the Nyquist
frequency. A peak outside 0.001 g to 5 g (:data:`PGA_PLAUSIBLE_G`), usually wrong units or
scale, is reported: a :class:`RecordWarning` and the ``record_warning`` attribute.

Between samples, ``displacement(t)`` and ``velocity(t)`` interpolate the processed samples
linearly.

Two components
--------------
A :class:`RecordPair` is a bidirectional ground motion: two records, the x and y components,
each processed as above with the same scale, window and baseline (each file's units its own).
Components of the same step but different lengths are joined (:func:`read_components`): over the
time both cover (``pair_span="common"``, a window over it) or the shorter padded with zero
acceleration (``"longest"``); different steps are refused, naming both files with their dt and
npts: nothing is resampled. Components whose axes are not at right angles are resolved onto east
and north (:func:`_frame`). A record's vertical component is read with its horizontals by
:func:`read_components` (same processing and span; a ``DWN`` channel negated).

Errors are ``ValueError``s that name the file (or the ``source`` of arrays), the line where there
is one, and the problem.
"""

from __future__ import annotations

import hashlib
import re
import warnings
from pathlib import Path
from typing import NamedTuple

import numpy as np
from numpy.polynomial import Polynomial

from .mechanics.structure import G, Ground  # G: standard gravity (m/s²)

BASELINES = {"none": None, "linear": 1, "quadratic": 2}  # degree of the velocity trend removed
MIN_SAMPLES = 3
PGA_PLAUSIBLE_G = (0.001, 5.0)  # a peak ground acceleration outside this range (g) is reported
QUANTITIES = ("acceleration", "velocity", "displacement")
PEER_QUANTITY = {".at2": "acceleration", ".vt2": "velocity", ".dt2": "displacement"}
TEXT_SUFFIXES = (".csv", ".txt", ".dat")
_SNAP = 1e-9  # relative (to dt) tolerance for window bounds on the sample grid

# Units, by their normalised spelling (see _unit_key): (quantity, factor to SI).
UNITS = {
    "G": ("acceleration", G), "M/S2": ("acceleration", 1.0), "CM/S2": ("acceleration", 1e-2),
    "GAL": ("acceleration", 1e-2), "MM/S2": ("acceleration", 1e-3),
    "M/S": ("velocity", 1.0), "CM/S": ("velocity", 1e-2), "MM/S": ("velocity", 1e-3),
    "M": ("displacement", 1.0), "CM": ("displacement", 1e-2), "MM": ("displacement", 1e-3),
    "S": ("time", 1.0),
}
SI_UNITS = {"time": "s", "acceleration": "m/s2", "velocity": "m/s", "displacement": "m"}
_SPELLINGS = [(r"\s+|\*\*|\^", ""), ("²", "2"), (r"SEC(OND)?S?", "S"), (r"/S/S$", "/S2")]

_NUMBER = r"([^\s,]+)"
_HEADER_NEW = re.compile(rf"^\s*NPTS\s*=\s*{_NUMBER}\s*,?\s*DT\s*=\s*{_NUMBER}", re.IGNORECASE)
_HEADER_OLD = re.compile(rf"^\s*{_NUMBER}\s+{_NUMBER}\s+NPTS\s*,\s*DT\b", re.IGNORECASE)
# PEER line 3: the units follow "IN UNITS OF", "UNITS OF", "UNITS:" or "IN"
_UNITS_LINE = re.compile(r"(?:\bIN\s+UNITS?\s+OF\b|\bUNITS?\s*(?:OF\b|:|=)|\bIN\b(?!\s+UNITS?\b))"
                         r"\s*(?P<units>\S.*?)\s*$", re.IGNORECASE)
_QUANTITY_WORD = {"acceleration": r"acc|accel\w*", "velocity": r"vel|veloc\w*", "displacement": r"disp|displ\w*"}
_COLUMN_WORD = {"time": r"t|time", "acceleration": r"a|acc|accel\w*", "velocity": r"v|vel|veloc\w*",
                "displacement": r"d|u|disp|displ\w*"}
_BRACKETS = re.compile(r"[(\[]\s*([^)\]]*?)\s*[)\]]")
_HEADER_TOKEN = re.compile(r"[^\s(\[]+(?:\s*[(\[][^)\]]*[)\]])?|[(\[][^)\]]*[)\]]")
_SEPARATORS = {",": "comma", ";": "semicolon", "\t": "tab"}


class WindowError(ValueError):
    """A record's window lies outside it (the file itself reads)."""


class RecordWarning(UserWarning):
    """A record that reads without error but looks wrong (an implausible peak ground acceleration)."""


class Units(NamedTuple):
    """Units of a record's samples."""

    text: str  # as written in the file or given
    quantity: str  # "time", "acceleration", "velocity" or "displacement"
    to_si: float  # factor to s, m/s², m/s or m

    def same_as(self, other: Units) -> bool:
        return (self.quantity, self.to_si) == (other.quantity, other.to_si)


def _unit_key(text) -> str:
    key = str(text).upper().strip(" .")
    for pattern, replacement in _SPELLINGS:
        key = re.sub(pattern, replacement, key)
    return key


def allowed_units(quantity=None) -> str:
    """The units of ``quantity`` (default: all motion quantities), for messages."""
    quantities = QUANTITIES if quantity is None else (quantity,)
    groups = [f"{q}: " + ", ".join(k.lower() for k, (kq, _) in UNITS.items() if kq == q) for q in quantities]
    return "; ".join(groups) + " (case-insensitive; SEC for S, S/S, ^2, **2 or ² for S2)"


def units_from(text) -> Units:
    """The :class:`Units` written ``text`` (e.g. ``"G"``, ``"CM/S/S"``, ``"cm/s^2"``, ``"gal"``, ``"cm"``).

    Raises
    ------
    ValueError
        Unknown units; the message lists the allowed ones.
    """
    key = _unit_key(text)
    if key not in UNITS:
        raise ValueError(f"unknown units {str(text)!r}; allowed: {allowed_units()}")
    return Units(str(text).strip(), *UNITS[key])


def _kind(path) -> str:
    """'an AT2 file', 'a VT2 file', ... for messages."""
    name = Path(path).suffix.upper().lstrip(".") or "PEER"
    return f"{'an' if name[0] in 'AEIOU' else 'a'} {name} file"


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


def _is_number(token) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def _check_finite(values, lines, path, what):
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        raise _fail(path, f"line {lines[i]}: {what} {float(values[i])!r} is not finite")


def _given_units(path, units) -> Units | None:
    """The ``units`` argument parsed, a motion unit; errors name the file."""
    if units is None:
        return None
    try:
        given = units_from(units)
    except ValueError as err:
        raise _fail(path, f"units: {err}") from None
    if given.quantity == "time":
        raise _fail(path, f"units {given.text!r} is a time unit; give the units of the motion: {allowed_units()}")
    return given


def _words_quantity(text, table) -> str | None:
    """The one quantity named by the words of ``text`` (see the tables above), else None."""
    words = re.findall(r"[a-z]+", text.lower())
    named = {q for word in words for q, pattern in table.items() if re.fullmatch(pattern, word)}
    return named.pop() if len(named) == 1 else None


# --- PEER NGA files --------------------------------------------------------------------------------
def _peer_units(path, line, quantity, given) -> Units:
    """Units from line 3 of a PEER file holding ``quantity`` (None: as the line says), checked against ``given``."""
    kind = _kind(path)
    said = _words_quantity(line, _QUANTITY_WORD)
    if quantity is not None and said is not None and said != quantity:
        raise _fail(path, f"line 3: {line.strip()!r} says {said}, but {kind} holds {quantity}")
    quantity = quantity or said
    allowed = allowed_units(quantity)
    match = _UNITS_LINE.search(line)
    stated = None
    if match is not None:
        try:
            stated = units_from(match["units"])
        except ValueError:
            raise _fail(path, f"line 3: unknown units {match['units']!r} in {line.strip()!r}; "
                              f"allowed: {allowed}") from None
        if stated.quantity != (quantity or stated.quantity) or stated.quantity not in QUANTITIES:
            raise _fail(path, f"line 3: {stated.text!r} are units of {stated.quantity}, but {kind} holds "
                              f"{quantity or 'a ground motion'}; allowed: {allowed}")
    elif given is None:
        raise _fail(path, f"line 3: no units in {line.strip()!r}; expected e.g. "
                          f"'{(quantity or 'acceleration').upper()} TIME SERIES IN UNITS OF ...' with one of "
                          f"{allowed}, or give units")
    if given is not None:
        if quantity is not None and given.quantity != quantity:
            raise _fail(path, f"units {given.text!r} are units of {given.quantity}, but {kind} holds {quantity}")
        if stated is not None and not stated.same_as(given):
            raise _fail(path, f"line 3 states units {stated.text!r}, but units {given.text!r} were given")
    return stated or given


def read_peer(path, units=None, quantity=None) -> tuple[float, np.ndarray, Units]:
    """Read a PEER NGA ``.AT2`` (acceleration), ``.VT2`` (velocity) or ``.DT2`` (displacement) file.

    Four header lines (database, event/station/component, units, then ``NPTS=  4000, DT= .0100
    SEC`` or the older ``4000  0.0100  NPTS, DT``) followed by NPTS whitespace-separated values.

    Parameters
    ----------
    path : the file.
    units : optional units of the values (text); they must agree with line 3. Only needed when
        line 3 states none.
    quantity : what the file must hold; default from the extension (none for others: line 3 says).

    Returns
    -------
    dt : float
        Sampling interval (s), > 0.
    values : ndarray, shape (NPTS,)
        The samples as written (not converted).
    units : Units
        Their units, as line 3 (or ``units``) states them.
    """
    path = Path(path)
    quantity = quantity or PEER_QUANTITY.get(path.suffix.lower())
    given = _given_units(path, units)
    lines = _read_lines(path)
    if len(lines) < 4:
        raise _fail(path, f"has {len(lines)} line(s); {_kind(path)} has 4 header lines, the 4th with NPTS and DT")
    stated = _peer_units(path, lines[2], quantity, given)
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
    values = np.array(values, dtype=float)
    _check_finite(values, where, path, "value")
    return dt, values, stated


_AZIMUTH_WORDS = {"N": 0.0, "E": 90.0, "S": 180.0, "W": 270.0, "NS": 0.0, "EW": 90.0}
_VERTICAL = re.compile(r"^(UP|UD|DWN|DOWN|V\d?|Z|VER|VERT|[A-Z]{2}Z)\b", re.IGNORECASE)
# a quadrant bearing: N76W is 76 degrees west of north (284), S14W 14 west of south (194)
_BEARING = re.compile(r"^([NS])\s*(\d{1,2}(?:\.\d+)?)\s*([EW])\b", re.IGNORECASE)


def peer_azimuth(path):
    """A PEER file's component direction from its line 2 (event, station, component), whose last
    comma-separated field names it: the azimuth in degrees clockwise from north ('180', '270',
    '000', '52', also 'N', 'E', 'S', 'W', channel codes ending in them, 'HNE', the K-NET/KiK-net 'NS'
    (north) and 'EW' (east), and quadrant bearings: 'N76W' is 284, 'S14W' 194, 'S64E' 116);
    "vertical" for a vertical component ('UP', 'UD', 'DWN', 'V', 'V1', 'VER', 'Z', 'HNZ'; it does not
    say which way the component's positive is: 'UP' and 'DWN' alike give "vertical"); None where it
    says neither ('L'/'T', longitudinal and transverse, and 'NA' name no direction; a file of
    another kind)."""
    path = Path(path)
    if path.suffix.lower() not in PEER_QUANTITY:
        return None
    lines = _read_lines(path)
    if len(lines) < 2:
        return None
    field = lines[1].rsplit(",", 1)[-1].strip()
    number = re.match(r"^(\d{1,3}(?:\.\d+)?)(?:\s|$|\()", field)
    if number and 0.0 <= float(number.group(1)) <= 360.0:
        return float(number.group(1)) % 360.0
    bearing = _BEARING.match(field)
    if bearing and float(bearing.group(2)) <= 90.0:
        ref, angle, side = bearing.group(1).upper(), float(bearing.group(2)), bearing.group(3).upper()
        turn = angle if side == "E" else -angle  # clockwise from north (N) or anticlockwise from south (S)
        return (turn if ref == "N" else 180.0 - turn) % 360.0
    if _VERTICAL.match(field):
        return "vertical"
    word = re.match(r"^(NS|EW)\b", field, re.IGNORECASE) or re.match(r"^(?:[A-Z]{2})?([NESW])\b", field,
                                                                     re.IGNORECASE)
    return _AZIMUTH_WORDS[word.group(1).upper()] if word else None


def read_at2(path) -> tuple[float, np.ndarray]:
    """Read a PEER NGA ``.AT2`` acceleration file (see :func:`read_peer`).

    Returns
    -------
    dt : float
        Sampling interval (s), > 0.
    acc_g : ndarray, shape (NPTS,)
        Acceleration in g (converted from the units of line 3; as written if they are g).
    """
    dt, values, units = read_peer(path, quantity="acceleration")
    return dt, values * (units.to_si / G)


def write_peer(path, dt, values, units, title="dccss record", database="dccss", decimals=7) -> None:
    """Write a history in the PEER NGA format (``.AT2``/``.VT2``/``.DT2``), 5 values per line.

    Parameters
    ----------
    path : output file.
    dt : sampling interval (s).
    values : 1-D samples, in ``units``.
    units : their units as written on line 3 (e.g. ``"G"``, ``"CM/S/S"``, ``"CM/S"``, ``"CM"``),
        which also give the quantity word of line 3.
    title : line 2 (event, station, component).
    database : line 1.
    decimals : digits after the point of the E format (7, PEER's, keeps 8 significant digits).
    """
    quantity = units_from(units).quantity
    values = np.asarray(values, dtype=float).ravel()
    width = decimals + 8
    rows = [" ".join(f"{v:{width}.{decimals}E}" for v in values[i:i + 5]) for i in range(0, values.size, 5)]
    header = [database, title, f"{quantity.upper()} TIME SERIES IN UNITS OF {units}",
              f"NPTS= {values.size:7d}, DT= {float(dt):.10g} SEC"]
    Path(path).write_text("\n".join(header + rows) + "\n")


def write_at2(path, dt, acc_g, title="dccss acceleration record", database="dccss", units="G", decimals=7) -> None:
    """Write an acceleration history (in ``units``, default g) in the PEER NGA ``.AT2`` format
    (see :func:`write_peer`)."""
    write_peer(path, dt, acc_g, units, title=title, database=database, decimals=decimals)


# --- text files --------------------------------------------------------------------------------------
class _Column(NamedTuple):
    label: str  # the header field
    named: str | None  # the quantity its name says
    units_text: str | None  # the units in brackets, as written
    units: Units | None  # those units, if known

    @property
    def quantity(self):
        return self.units.quantity if self.units is not None else self.named


def _column(label) -> _Column:
    match = _BRACKETS.search(label)
    units_text = match[1] if match else None
    name = label[:match.start()] + label[match.end():] if match else label
    try:
        units = units_from(units_text) if units_text else None
    except ValueError:
        units = None
    return _Column(label, _words_quantity(name, _COLUMN_WORD), units_text, units)


def _split(line, separator) -> list[str]:
    return [f.strip() for f in line.split(separator)] if separator else line.split()


def _text_columns(path, line_no, columns, given) -> tuple[int, int, Units]:
    """Indices of the time and motion columns of a header, and the motion's units."""
    where = f"line {line_no}"
    for c in columns:
        if c.named and c.units and c.named != c.units.quantity:
            raise _fail(path, f"{where}: column {c.label!r} is named as {c.named} but {c.units.text!r} are units of "
                              f"{c.units.quantity}")
    times = [j for j, c in enumerate(columns) if c.quantity == "time"]
    motions = [j for j, c in enumerate(columns) if c.quantity in QUANTITIES]
    if given is not None and len(motions) > 1:
        motions = [j for j in motions if columns[j].quantity == given.quantity]
    labels = [c.label for c in columns]
    if len(times) > 1:
        raise _fail(path, f"{where}: more than one time column in {labels}")
    if len(motions) > 1:
        raise _fail(path, f"{where}: more than one motion column in {labels}; keep one, or give units to choose "
                          f"by quantity")
    if len(columns) == 2:  # time first, then the motion, unless the header says otherwise
        time = times[0] if times else (1 - motions[0] if motions else 0)
        motion = motions[0] if motions else 1 - time
    elif not (times and motions):
        missing = "time" if not times else "motion"
        raise _fail(path, f"{where}: with {len(columns)} columns the header must name the {missing} column, e.g. "
                          f"'time (s), acceleration (g)'; got {labels}")
    else:
        time, motion = times[0], motions[0]
    t, m = columns[time], columns[motion]
    if t.units_text is not None and (t.units is None or t.units.quantity != "time"):
        raise _fail(path, f"{where}: the time column {t.label!r} must be in s, got {t.units_text!r}")
    if m.units_text is not None and m.units is None:
        raise _fail(path, f"{where}: unknown units {m.units_text!r} in column {m.label!r}; allowed: "
                          f"{allowed_units(m.named)}")
    if given is not None:
        if m.quantity is not None and m.quantity != given.quantity:
            raise _fail(path, f"{where}: column {m.label!r} holds {m.quantity}, but units {given.text!r} are units of "
                              f"{given.quantity}")
        if m.units is not None and not m.units.same_as(given):
            raise _fail(path, f"{where}: the header states units {m.units.text!r} for column {m.label!r}, but units "
                              f"{given.text!r} were given")
    units = m.units or given
    if units is None:
        raise _fail(path, f"{where}: cannot tell the units of column {m.label!r}: state them in the header, e.g. "
                          f"'time (s), acceleration (g)', or give units (the 'units' key of a record excitation, e.g. "
                          f"units: cm/s2); allowed: {allowed_units()}")
    return time, motion, units


def read_text(path, units=None) -> tuple[np.ndarray, np.ndarray, Units]:
    """Read a two-column (time, motion) text file: ``.csv``, ``.txt`` or ``.dat`` (module docstring).

    Parameters
    ----------
    path : the file.
    units : units of the motion column (text), needed when the header does not state them; they
        must agree with the header.

    Returns
    -------
    time : ndarray
        Sample times (s), finite and strictly increasing.
    values : ndarray
        The motion samples as written (not converted).
    units : Units
        Their units (from the header, else ``units``).
    """
    path = Path(path)
    given = _given_units(path, units)
    rows = [(n, line) for n, line in enumerate(_read_lines(path), start=1)
            if line.strip() and not line.lstrip().startswith("#")]
    if not rows:
        raise _fail(path, "has no data rows (only comments)")
    first_no, first = rows[0]
    separator = next((s for s in _SEPARATORS if s in first), None)
    if not any(_is_number(f) for f in _split(first, separator)):  # a header
        labels = _split(first, separator) if separator else _HEADER_TOKEN.findall(first)
        rows = rows[1:]
        if not rows:
            raise _fail(path, "has a header but no data rows")
        width = len(labels)
        time_col, motion_col, units = _text_columns(path, first_no, [_column(label) for label in labels], given)
    else:
        width = len(_split(first, separator))
        if width != 2:
            raise _fail(path, f"line {first_no}: without a header a record has 2 columns (time in s, then the motion), "
                              f"got {width}; add a header naming them, e.g. 'time (s), acceleration (g)'")
        if given is None:
            raise _fail(path, "has no header stating the units: add one, e.g. 'time (s), acceleration (g)', or give "
                              "units (the 'units' key of a record excitation, e.g. units: cm/s2); allowed: "
                              f"{allowed_units()}")
        time_col, motion_col, units = 0, 1, given
    kind = _SEPARATORS.get(separator, "whitespace")
    time, values, where = [], [], []
    for line_no, line in rows:
        fields = _split(line, separator)
        if len(fields) != width:
            raise _fail(path, f"line {line_no}: expected {width} {kind}-separated fields, got {len(fields)}")
        time.append(_float(fields[time_col], path, line_no, "time"))
        values.append(_float(fields[motion_col], path, line_no, units.quantity))
        where.append(line_no)
    time, values = np.array(time), np.array(values)
    _check_finite(time, where, path, "time")
    _check_finite(values, where, path, units.quantity)
    steps = np.diff(time)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise _fail(path, f"line {where[i + 1]}: time must increase strictly; {float(time[i + 1])!r} s "
                          f"follows {float(time[i])!r} s")
    return time, values, units


def read_acceleration_csv(path, units=None) -> tuple[np.ndarray, np.ndarray]:
    """Read an acceleration text file (see :func:`read_text`).

    Returns
    -------
    time, acc : ndarray
        Sample times (s) and acceleration (m/s²).
    """
    time, values, stated = read_text(path, units)
    if stated.quantity != "acceleration":
        raise _fail(path, f"holds {stated.quantity} ({stated.text}), not acceleration")
    return time, values * stated.to_si


class Raw(NamedTuple):
    """A record file's samples as read, before any processing."""

    path: Path
    time: np.ndarray  # (s)
    values: np.ndarray  # in ``units``
    units: Units
    sha256: str
    span: dict | None = None  # how it was joined to other components (``read_components``)

    def record(self, **processing) -> Record:
        """The :class:`Record` of these samples (``processing``: scale, window, baseline)."""
        record = Record(self.time, **{self.units.quantity: self.values}, units=self.units.text,
                        source=str(self.path), sha256=self.sha256, **processing)
        if self.span:
            record.span = self.span
        return record


def read_raw(path, units=None) -> Raw:
    """Read a record file (``.AT2``/``.VT2``/``.DT2``: :func:`read_peer`; ``.csv``/``.txt``/``.dat``:
    :func:`read_text`) without processing it; errors name the file."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix in PEER_QUANTITY:
        dt, values, stated = read_peer(path, units)
        time = dt * np.arange(values.size)
    elif suffix in TEXT_SUFFIXES:
        time, values, stated = read_text(path, units)
    else:
        raise _fail(path, f"unknown record format {path.suffix!r}; expected .AT2, .VT2, .DT2 (PEER NGA) or "
                          f".csv, .txt, .dat (time and motion columns)")
    return Raw(path, time, values, stated, hashlib.sha256(path.read_bytes()).hexdigest())


# --- processing --------------------------------------------------------------------------------------
def _trapezoid_weights(t):
    w = np.zeros_like(t)
    h = np.diff(t) / 2
    w[:-1] += h
    w[1:] += h
    return w


def _remove_trend(time, vel, baseline):
    """(v - p, p') for the weighted least-squares polynomial p of the baseline's degree (p' = 0 for "none")."""
    degree = BASELINES[baseline]
    if degree is None:
        return vel, 0.0
    trend = Polynomial.fit(time, vel, degree, w=np.sqrt(_trapezoid_weights(time)))
    return vel - trend(time), trend.deriv()(time)


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
    vel, slope = _remove_trend(time, cumulative_trapezoid(acc, time), baseline)
    return acc - slope, vel, cumulative_trapezoid(vel, time)


def cumulative_trapezoid(y, x):
    """∫ y dx from 0 at the first sample, by the trapezoid rule, at every sample of (n,) arrays: the
    operations of ``scipy.integrate.cumulative_trapezoid(y, x, initial=0)`` in their order, so the same
    bits, without importing ``scipy.integrate`` (0.3 s, in every workflow job that reads a record)."""
    y, x = np.asarray(y, dtype=float), np.asarray(x, dtype=float)
    return np.concatenate(([0.0], np.cumsum(np.diff(x) * (y[1:] + y[:-1]) / 2.0)))


def _second_difference(time, x):
    """d²x/dt² by the three-point formula (exact for parabolas); the ends take their neighbour's value."""
    h = np.diff(time)
    acc = np.empty_like(x)
    acc[1:-1] = 2 * np.diff(np.diff(x) / h) / (h[:-1] + h[1:])
    acc[0], acc[-1] = acc[1], acc[-2]
    return acc


def _motion(time, samples, quantity, baseline):
    """(acceleration, velocity, displacement) samples (SI) of a record of ``quantity``, integrated as far as needed."""
    if quantity == "acceleration":
        return integrate(time, samples, baseline)
    if quantity == "velocity":
        vel, _ = _remove_trend(time, samples, baseline)
        return np.gradient(vel, time), vel, cumulative_trapezoid(vel, time)
    return _second_difference(time, samples), np.gradient(samples, time), samples


def _scale(value, source):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"record {source!r}: scale must be a number, got {value!r}")
    value = float(value)
    if not np.isfinite(value) or value == 0:
        raise ValueError(f"record {source!r}: scale must be finite and non-zero, got {value!r}")
    return value


def _baseline(baseline, quantity, source):
    """The baseline (default "linear"; "none" for a displacement record, which refuses the others)."""
    if baseline is None:
        return "none" if quantity == "displacement" else "linear"
    if baseline not in BASELINES:
        raise ValueError(f"record {source!r}: baseline must be one of {list(BASELINES)}, got {baseline!r}")
    if quantity == "displacement" and baseline != "none":
        raise ValueError(f"record {source!r}: baseline {baseline!r} removes a trend from an integrated velocity, but "
                         f"a displacement record is used as recorded, not integrated; leave baseline out or set it "
                         f"to 'none'")
    return baseline


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
        raise WindowError(f"record {source!r}: window ({t0!r}, {t1!r}) s lies outside the record, "
                         f"which spans {float(time[0])!r} to {float(time[-1])!r} s")
    return slice(int(np.searchsorted(time, t0 - tol, side="left")),
                 int(np.searchsorted(time, t1 + tol, side="right")))


class Record:
    """Imposed ground motion from a recorded history (see the module docstring).

    Give exactly one of ``acceleration``, ``velocity``, ``displacement``.

    Parameters
    ----------
    time : (n,) strictly increasing sample times (s).
    acceleration, velocity, displacement : (n,) raw ground motion in ``units``, before scale and
        baseline correction.
    units : units of those samples (text, see :data:`UNITS`); default SI (m/s2, m/s, m).
    source : what the record is (a file name); named in errors and in ``attrs()``.
    sha256 : SHA-256 of the source file's bytes, recorded in ``attrs()`` (``from_file`` sets it).
    scale : finite non-zero factor on the samples.
    window : optional (t0, t1) (s): keep only the samples in that interval (after processing the whole record).
    baseline : "linear", "quadratic" or "none"; default "linear", and "none" (the only one
        allowed) for a displacement record.

    Attributes
    ----------
    time, acceleration, velocity_samples, displacement_samples : ndarray
        The processed samples: windowed times (s), scaled and corrected (or, for velocity and
        displacement records, estimated) acceleration (m/s²), velocity (m/s) and displacement (m).
    quantity, units : str
        What the raw samples are and their units as written.
    warning : str
        Why the record looks wrong ("" if it does not): a peak ground acceleration outside
        :data:`PGA_PLAUSIBLE_G`.
    """

    kind = "record"
    components = 1
    parameters = ()

    def __init__(self, time, acceleration=None, *, velocity=None, displacement=None, units=None, source="arrays",
                 scale=1.0, window=None, baseline=None, sha256=""):
        given = {q: v for q, v in zip(QUANTITIES, (acceleration, velocity, displacement), strict=True) if v is not None}
        if len(given) != 1:
            raise ValueError(f"record {source!r}: give exactly one of acceleration, velocity, displacement; "
                             f"got {list(given) or 'none'}")
        ((quantity, samples),) = given.items()
        try:
            units = units_from(SI_UNITS[quantity] if units is None else units)
        except ValueError as err:
            raise ValueError(f"record {source!r}: {err}") from None
        if units.quantity != quantity:
            raise ValueError(f"record {source!r}: units {units.text!r} are units of {units.quantity}, not {quantity}")
        time = np.asarray(time, dtype=float)
        samples = np.asarray(samples, dtype=float)
        if time.ndim != 1 or samples.shape != time.shape:
            raise ValueError(f"record {source!r}: time and {quantity} must be 1-D of equal length, "
                             f"got shapes {time.shape} and {samples.shape}")
        if not (np.isfinite(time).all() and np.isfinite(samples).all()):
            raise ValueError(f"record {source!r}: time and {quantity} must be finite")
        if time.size >= 2 and (np.diff(time) <= 0).any():
            raise ValueError(f"record {source!r}: time must increase strictly")
        self.source = str(source)
        self.sha256 = str(sha256)
        self.quantity = quantity
        self.units = units.text
        self.baseline = _baseline(baseline, quantity, source)
        self.scale = _scale(scale, source)
        self.raw_npts = int(time.size)
        if time.size < MIN_SAMPLES:
            raise ValueError(f"record {source!r}: has {time.size} sample(s); at least {MIN_SAMPLES} are needed")
        cut = _window(time, window, source)
        self.window = (float(window[0]), float(window[1])) if window is not None else None
        if time[cut].size < MIN_SAMPLES:
            raise ValueError(f"record {source!r}: the window {window!r} s holds {time[cut].size} sample(s); "
                             f"at least {MIN_SAMPLES} are needed")
        # the whole record is processed, then cut: a window never changes the motion inside it
        with np.errstate(over="ignore", invalid="ignore"):
            motion = _motion(time, self.scale * (units.to_si * samples), quantity, self.baseline)
        if not all(np.isfinite(m).all() for m in motion):
            raise ValueError(f"record {source!r}: scale {self.scale:g} makes the {quantity} overflow (its processed "
                             f"samples are not finite); give a scale that keeps the motion physical")
        self.time = time[cut]
        self.acceleration, self.velocity_samples, self.displacement_samples = (m[cut] for m in motion)
        self.warning = self._plausibility()
        if self.warning:
            warnings.warn(self.warning, RecordWarning, stacklevel=2)

    @classmethod
    def from_file(cls, path, scale=1.0, window=None, baseline=None, units=None) -> Record:
        """Read ``path`` and process it; errors name the file.

        ``.AT2``/``.VT2``/``.DT2``: PEER NGA acceleration, velocity, displacement (:func:`read_peer`);
        ``.csv``/``.txt``/``.dat``: two columns, time and motion (:func:`read_text`). ``units``
        states the units of the motion when the file does not (and must agree when it does).
        """
        return read_raw(path, units).record(scale=scale, window=window, baseline=baseline)

    def _plausibility(self) -> str:
        low, high = PGA_PLAUSIBLE_G
        pga_g = self.pga / G
        if low <= pga_g <= high:
            return ""
        side = f"above {high:g} g" if pga_g > high else f"below {low:g} g"
        how = "" if self.quantity == "acceleration" else f", estimated from the {self.quantity},"
        return (f"record {Path(self.source).name!r}: the peak ground acceleration{how} is {pga_g:.3g} g, {side}: "
                f"implausible for a ground motion; check the units ({self.units!r}) and the scale ({self.scale:g})")

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
        """Peak ground acceleration after processing (m/s²); estimated for velocity and displacement records."""
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

    def ground_acceleration(self) -> Ground:
        """The processed acceleration samples joined by straight lines (what drives a structure)."""
        return Ground.from_samples(self.time, self.acceleration)

    def attrs(self) -> dict:
        """netCDF global attributes (str, int, float) describing the record and its processing;
        ``record_warning`` only when there is a warning."""
        start, end = self.window if self.window is not None else (self.t_start, self.t_end)
        attrs = {"excitation": "record", "record_source": Path(self.source).name, "record_sha256": self.sha256,
                 "record_quantity": self.quantity, "record_units": self.units,
                 "record_npts": self.npts, "record_raw_npts": self.raw_npts, "record_dt_s": self.dt,
                 "record_scale": self.scale, "record_window_start_s": float(start),
                 "record_window_end_s": float(end), "record_baseline": self.baseline,
                 "record_pga_m_per_s2": self.pga, "record_pgv_m_per_s": self.pgv, "record_pgd_m": self.pgd}
        if self.warning:
            attrs["record_warning"] = self.warning
        return {**attrs, **getattr(self, "span", {}), **getattr(self, "scaling", {})}

    def __repr__(self):
        return (f"Record({Path(self.source).name!r}, {self.quantity} in {self.units}, {self.npts} samples, "
                f"t = {self.t_start:g}..{self.t_end:g} s, scale={self.scale:g}, baseline={self.baseline!r}, "
                f"PGA={self.pga / G:.3f} g, PGD={self.pgd:.3f} m)")


#: the least angle (degrees) between two components' axes that are resolved onto east and north: at
#: 30 degrees an error e in each sensor's reading becomes at most e / sqrt(1 - cos 30°) = 2.7 e in the
#: resolved motion (the inverse of the smallest singular value of the sensors' directions); closer to
#: parallel the two readings barely tell the directions apart, and their noise swamps the motion
MIN_AXES_ANGLE = 30.0
#: how two components of different lengths (the same step) are joined: over the time both cover, or
#: the shorter padded with zero acceleration to the longer
PAIR_SPANS = ("common", "longest")


class PairWarning(RecordWarning):
    """Components that a pair joins by a rule: different lengths, or axes not at right angles."""


class VerticalError(ValueError):
    """A record's vertical component cannot be read or joined with its horizontal component(s)."""


def _frame(az1, az2) -> tuple[np.ndarray, float]:
    """The matrix that turns the two sensors' readings into (east, north), and how far (degrees) their
    axes are from right angles (0: orthogonal). Sensor i reads the projection of the ground's motion on
    its axis e_i = (sin az_i, cos az_i): the readings are E^T m, so m = (E^T)^-1 readings (for axes at
    right angles, E itself)."""
    a = np.radians([az1, az2])
    E = np.array([[np.sin(a[0]), np.sin(a[1])], [np.cos(a[0]), np.cos(a[1])]])  # columns: the axes (east, north)
    gap = (az2 - az1) % 180.0
    angle = min(gap, 180.0 - gap)  # between the axes as lines
    if abs(gap - 90.0) <= 1e-6:
        return E, 0.0
    if angle < MIN_AXES_ANGLE:
        raise ValueError(f"record pair: the components' azimuths {az1:g} and {az2:g} degrees put their axes "
                         f"{angle:g} degrees apart, closer to parallel than {MIN_AXES_ANGLE:g} degrees: two such "
                         f"readings cannot be resolved onto east and north (an error in either would grow more "
                         f"than {1 / np.sqrt(1 - np.cos(np.radians(MIN_AXES_ANGLE))):.1f} times); a pair is two "
                         f"horizontal components at (or near) right angles")
    warnings.warn(f"record pair: the components' azimuths {az1:g} and {az2:g} degrees are {angle:g} degrees apart, "
                  f"not at right angles: the motion is resolved exactly onto east and north from both readings",
                  PairWarning, stacklevel=3)
    return np.linalg.inv(E.T), float(90.0 - angle)


def _uniform_step(raw) -> float | None:
    """The step of ``raw``'s sample times if they are uniform (to 1e-9 of it), else None."""
    steps = np.diff(raw.time)
    mean = float(raw.time[-1] - raw.time[0]) / steps.size
    return mean if np.ptp(steps) <= 1e-9 * mean else None


def _describe(raw) -> str:
    return (f"{raw.path.name!r}: {raw.time.size} samples, t = {float(raw.time[0]):.6g} to {float(raw.time[-1]):.6g} s, "
            f"dt = {float(np.max(np.diff(raw.time))):.12g} s")


def read_components(paths, vertical=None, *, scale=1.0, window=None, baseline=None, units=None,
                    pair_span="common") -> tuple[list[Record], Record | None]:
    """Read the horizontal component(s) ``paths`` (one or two files) and an optional ``vertical`` file
    of one recording, each processed as :meth:`Record.from_file` does with the same ``scale``,
    ``window``, ``baseline`` and ``units``, on the same sample times.

    Files of the same step but different lengths (PEER distributes such pairs) are joined by
    ``pair_span``: ``"common"`` (default) runs over the time all of them cover (each file processed
    whole, then cut there: the same as a ``window`` over that time); ``"longest"`` pads the shorter
    files with zero acceleration samples up to the longest (then processed with the record, as if the
    file held them). Both say so: a :class:`PairWarning`, and each record's ``span`` (its attributes)
    says what was dropped or padded, in s, and the largest |a| dropped. With ``"common"``, a ``window``
    (which must lie within the common time) drops nothing the run would keep: then no warning, and
    0 s dropped. Different steps are refused: nothing is resampled.

    Returns
    -------
    horizontals : list of Record
        One per file of ``paths``.
    vertical : Record or None
        The vertical component, up positive (a file labelled ``DWN`` or ``DOWN`` on its line 2 is
        negated: PEER's down-positive channel, with a :class:`RecordWarning` saying so), scaled by
        |scale|: a negative scale mirrors the horizontal motion, and gravity keeps its direction.

    Raises
    ------
    VerticalError
        Where the vertical file cannot be read, names a horizontal direction, or cannot be joined with
        horizontal components that join among themselves.
    """
    if pair_span not in PAIR_SPANS:
        raise ValueError(f"pair_span must be one of {list(PAIR_SPANS)}, got {pair_span!r}")
    raws = [read_raw(p, units) for p in paths]
    if vertical is not None:
        try:
            raws.append(read_raw(vertical, units))
        except ValueError as err:
            raise VerticalError(f"the vertical component: {err}") from None
        direction = peer_azimuth(vertical)
        if direction not in (None, "vertical"):
            raise VerticalError(f"record {str(vertical)!r}: line 2 names a horizontal direction ({direction:g} "
                                f"degrees); the vertical component is the file labelled UP, DWN, V, UD or Z")
    windows = [window] * len(raws)
    if len(raws) > 1 and not all(np.array_equal(r.time, raws[0].time) for r in raws):
        try:
            raws, windows = _joined(raws, window, pair_span, scale, vertical is not None)
        except ValueError as err:
            horizontal = raws[:len(paths)]
            if vertical is not None and all(np.array_equal(r.time, horizontal[0].time) for r in horizontal):
                raise VerticalError(str(err)) from None  # the horizontals alone join: the vertical does not
            raise
    if vertical is not None and _down_positive(vertical):
        raws[-1] = raws[-1]._replace(values=-raws[-1].values,
                                     span={**(raws[-1].span or {}), "record_sign": "negated: the file's channel "
                                                                                   "is down-positive (DWN)"})
        warnings.warn(f"record {Path(vertical).name!r}: the vertical component's channel is down-positive (DWN on "
                      f"line 2): negated, so that up is positive", RecordWarning, stacklevel=2)
    factors = [scale] * len(paths) + ([abs(scale)] if vertical is not None else [])
    records = [r.record(scale=f, window=w, baseline=baseline) for r, w, f in zip(raws, windows, factors)]
    return (records, None) if vertical is None else (records[:-1], records[-1])


def _down_positive(path) -> bool:
    """Whether a PEER file's line 2 labels its channel down-positive (``DWN``, ``DOWN``)."""
    if Path(path).suffix.lower() not in PEER_QUANTITY:
        return False
    lines = _read_lines(path)
    return len(lines) > 1 and re.match(r"^(DWN|DOWN)\b", lines[1].rsplit(",", 1)[-1].strip(), re.IGNORECASE) is not None


def _what(raws, vertical=False) -> str:
    """'record pair' or 'record', and its vertical component where the last of ``raws`` is one, for messages."""
    horizontal = len(raws) - (1 if vertical else 0)
    return ("record pair" if horizontal == 2 else "record") + (" and its vertical component" if vertical else "")


def _joined(raws, window, pair_span, scale, vertical=False):
    """The raws (padded, for "longest") and the window of each that put them on the same sample times."""
    steps = [_uniform_step(r) for r in raws]
    if None in steps or max(steps) - min(steps) > 1e-9 * min(steps):
        raise ValueError(f"{_what(raws, vertical)}: the components must share their step to be joined, but "
                         + " and ".join(_describe(r) for r in raws)
                         + "; dccss does not resample: give components recorded together (the same dt)")
    dt = steps[0]
    starts = np.array([float(r.time[0]) for r in raws])
    ends = np.array([float(r.time[-1]) for r in raws])
    offsets = (starts - starts.min()) / dt
    if np.max(np.abs(offsets - np.round(offsets))) > 1e-9:
        raise ValueError(f"{_what(raws, vertical)}: the components' samples are not at the same times (their starts "
                         f"are not a whole number of steps apart): " + " and ".join(_describe(r) for r in raws))
    names = ", ".join(_describe(r) for r in raws)
    if pair_span == "common":
        low, high = float(starts.max()), float(ends.min())
        if high - low < 2 * dt:
            raise ValueError(f"{_what(raws, vertical)}: the components share no time ({names}): nothing to run")
        if window is not None and (window[0] < low - _SNAP * dt or window[1] > high + _SNAP * dt):
            raise WindowError(f"{_what(raws, vertical)}: the window ({window[0]!r}, {window[1]!r}) s lies outside "
                              f"the time all components cover, {low!r} to {high!r} s ({names}); pair_span: longest "
                              f"pads the shorter ones instead")
        told, joined = [], []
        for r in raws:
            # a window (within the common span) keeps nothing the join drops: the run loses nothing to it
            out = ((r.time < low - _SNAP * dt) | (r.time > high + _SNAP * dt)) & (window is None)
            peak = float(np.max(np.abs(r.values[out]))) * r.units.to_si * abs(scale) if out.any() else 0.0
            span = {"record_pair_span": "common", "record_dropped_s": float(np.count_nonzero(out) * dt)}
            if r.units.quantity == "acceleration":
                span["record_dropped_max_abs_acceleration_m_per_s2"] = peak
            joined.append(r._replace(span=span))
            if out.any():
                told.append(f"{r.path.name!r}: {np.count_nonzero(out) * dt:.4g} s"
                            + (f" (largest |a| {peak / G:.3g} g)" if r.units.quantity == "acceleration" else ""))
        if told:
            warnings.warn(f"{_what(raws, vertical)}: components of different lengths ({names}) run over the "
                          f"{high - low:.6g} s all cover, {low:g} to {high:g} s (pair_span: common); dropped "
                          + "; ".join(told),
                          PairWarning, stacklevel=3)
        return joined, [window if window is not None else (low, high)] * len(raws)
    not_acc = [r.path.name for r in raws if r.units.quantity != "acceleration"]
    if not_acc:
        raise ValueError(f"{_what(raws, vertical)}: pair_span: longest pads with zero acceleration, but {not_acc} "
                         f"hold(s) velocity or displacement; use pair_span: common")
    n = int(round((ends.max() - starts.min()) / dt)) + 1
    cover = next((r.time for r in raws if r.time.size == n and r.time[0] == starts.min()), None)
    time = cover if cover is not None else starts.min() + dt * np.arange(n)
    padded, told = [], []
    for r, offset in zip(raws, np.round(offsets).astype(int)):
        values = np.zeros(n)
        values[offset:offset + r.values.size] = r.values
        extra = (n - r.values.size) * dt
        padded.append(r._replace(time=time, values=values, span={"record_pair_span": "longest",
                                                                  "record_padded_s": float(extra)}))
        if extra:
            told.append(f"{r.path.name!r}: {extra:.4g} s")
    warnings.warn(f"{_what(raws, vertical)}: components of different lengths ({names}) padded with zero "
                  f"acceleration to the longest, {float(time[0]):g} to {float(time[-1]):g} s (pair_span: longest): "
                  + "; ".join(told),
                  PairWarning, stacklevel=3)
    return padded, [window] * len(raws)


class RecordPair:
    """Bidirectional ground motion from two records: ``x`` and ``y``, the two horizontal
    components as given (the first and the second file), each a :class:`Record` processed on its
    own (its file's units, the same ``scale``, ``window`` and ``baseline``).

    **Orientation.** ``azimuths`` are the components' directions in degrees clockwise from north
    (a PEER file's line 2, :func:`peer_azimuth`): given both, the pair's motion is placed in one
    right-handed frame, **x east and y north** (z up), whatever the order of the files, by
    x = Σ c_i sin az_i, y = Σ c_i cos az_i for orthogonal axes, and in general the 2 x 2 solve of
    each sensor reading the projection of the motion on its axis (axes at least
    :data:`MIN_AXES_ANGLE` apart).
    Without them (text files, a header that names no direction) x is the first component and y the
    second (``orientation`` says which). ``rotation`` (degrees, from x towards y) then turns the
    motion; it is also a parameter per case (``displacement(t, rotation=...)``, a sweep axis).

    Both must have the same sample times (equal npts, and times equal within 1e-9 of the step):
    :meth:`from_files` joins files of different lengths first (``pair_span``); different steps are
    refused, never resampled. ``displacement(t)`` and ``velocity(t)`` interpolate each component linearly and
    return shape t.shape + (2,) (x, y in m, m/s).

    Attributes
    ----------
    x, y : Record
        The components.
    time : ndarray
        The x component's sample times (s).
    displacement_samples, velocity_samples : ndarray, shape (npts, 2)
        The processed samples of both components.
    warning : str
        The components' warnings (RecordWarning texts), "; "-joined ("" if none).
    """

    kind = "record"
    components = 2
    parameters = ("rotation",)
    azimuth = 0.0  # rad: the reference direction (+x)

    def __init__(self, x: Record, y: Record, azimuths=None, rotation=0.0):
        for name, record in (("x", x), ("y", y)):
            if not isinstance(record, Record) or record.components != 1:
                raise ValueError(f"record pair: the {name} component must be a one-component Record, got {record!r}")
        tol = _SNAP * float(min(np.min(np.diff(x.time)), np.min(np.diff(y.time))))
        if x.npts != y.npts or np.max(np.abs(x.time - y.time)) > tol:
            def where(r):
                return (f"{r.source!r}: npts={r.npts}, dt={r.dt!r} s, t = {r.t_start!r} to {r.t_end!r} s "
                        f"(raw npts={r.raw_npts})")
            cut = " after the window" if x.window is not None else ""
            raise ValueError(f"record pair: the two components must have the same sample times{cut}, but "
                             f"x {where(x)} and y {where(y)}; dccss does not resample: give two components recorded "
                             f"together (same dt and npts), or a window both cover")
        self.x, self.y = x, y
        self.azimuths = None if azimuths is None or None in azimuths else tuple(float(a) for a in azimuths)
        self.rotation = float(rotation)
        self.frame, self.skew = np.eye(2), 0.0
        if self.azimuths is not None:
            self.frame, self.skew = _frame(*self.azimuths)

    @property
    def orientation(self) -> str:
        """How x and y are placed: by the components' azimuths, or in file order."""
        if self.azimuths is None:
            return "file order: x the first component, y the second (the files name no directions)"
        how = "" if not self.skew else f", resolved from axes {90.0 - abs(self.skew):g} degrees apart"
        return (f"x east, y north, from the components' azimuths {self.azimuths[0]:g} and {self.azimuths[1]:g} "
                f"degrees (clockwise from north){how}")

    def matrix(self, rotation=None) -> np.ndarray:
        """(..., 2, 2): the components (first, second) to (x, y), turned by ``rotation`` (degrees)."""
        angle = np.radians(self.rotation if rotation is None else np.asarray(rotation, dtype=float))
        c, s = np.cos(angle), np.sin(angle)
        turn = np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)
        return turn @ self.frame

    def _placed(self, components, rotation=None):
        """Samples (..., 2) of the components as given, in the pair's frame (turned per case)."""
        return np.einsum("...ij,...j->...i", self.matrix(rotation), components)

    @classmethod
    def from_files(cls, paths, scale=1.0, window=None, baseline=None, units=None, rotation=0.0,
                   pair_span="common") -> RecordPair:
        """Read and process the two files ``paths = (x, y)`` as :meth:`Record.from_file` does,
        with the same ``scale``, ``window``, ``baseline`` and ``units`` (each file's own units
        header is honoured; ``units`` must agree with it where it states units); files of different
        lengths are joined by ``pair_span`` (:func:`read_components`)."""
        if isinstance(paths, (str, Path)) or len(paths) != 2:
            raise ValueError(f"record pair: expected two files [x, y], got {paths!r}")
        for i, p in enumerate(paths):
            if not isinstance(p, (str, Path)):
                raise ValueError(f"record pair: file {i} must be a path, got {p!r}")
        (x, y), _ = read_components(paths, scale=scale, window=window, baseline=baseline, units=units,
                                    pair_span=pair_span)
        return cls.of(x, y, paths, rotation)

    @classmethod
    def of(cls, x: Record, y: Record, paths, rotation=0.0) -> RecordPair:
        """The pair of the processed components ``x``, ``y`` read from the files ``paths``, placed by the
        azimuths the files name (refused: the same file twice, a vertical component)."""
        if x.sha256 == y.sha256:
            same = "the same file" if Path(paths[0]).resolve() == Path(paths[1]).resolve() else "two identical files"
            raise ValueError(f"record pair: {str(paths[0])!r} and {str(paths[1])!r} are {same}: a pair is two "
                             f"different horizontal components of one station")
        azimuths = [peer_azimuth(p) for p in paths]
        for p, a in zip(paths, azimuths):
            if a == "vertical":
                raise ValueError(f"record pair: {str(p)!r} is a vertical component (line 2 of the file); a pair is "
                                 f"two horizontal components")
        return cls(x, y, azimuths, rotation)

    @property
    def records(self) -> tuple[Record, Record]:
        return self.x, self.y

    @property
    def time(self) -> np.ndarray:
        return self.x.time

    @property
    def t_start(self) -> float:
        return self.x.t_start

    @property
    def t_end(self) -> float:
        return self.x.t_end

    @property
    def npts(self) -> int:
        return self.x.npts

    @property
    def dt(self) -> float:
        return self.x.dt

    @property
    def displacement_samples(self) -> np.ndarray:
        """(npts, 2): x and y in the pair's frame (m)."""
        return self._placed(np.column_stack([self.x.displacement_samples, self.y.displacement_samples]))

    @property
    def velocity_samples(self) -> np.ndarray:
        return self._placed(np.column_stack([self.x.velocity_samples, self.y.velocity_samples]))

    @property
    def pgd(self) -> float:
        """Peak horizontal ground displacement: max |(x, y)| over the samples (m)."""
        return float(np.max(np.hypot(self.x.displacement_samples, self.y.displacement_samples)))

    @property
    def warning(self) -> str:
        return "; ".join(w for w in (self.x.warning, self.y.warning) if w)

    def displacement(self, t, rotation=None):
        """(x, y) ground displacement (m) at times t (s): shape t.shape + (2,); ``rotation`` (degrees,
        per case) broadcast against t as ``Oriented.displacement`` does (pass t[:, None] for (T, n))."""
        return self._placed(np.stack([self.x.displacement(t), self.y.displacement(t)], axis=-1), rotation)

    def velocity(self, t, rotation=None):
        """(x, y) ground velocity (m/s) at times t (s), as ``displacement``."""
        return self._placed(np.stack([self.x.velocity(t), self.y.velocity(t)], axis=-1), rotation)

    def ground_acceleration(self, rotation=None) -> Ground:
        """Both components' processed acceleration samples joined by straight lines, in the pair's frame."""
        return Ground.from_samples(self.time, self._placed(np.column_stack([self.x.acceleration,
                                                                            self.y.acceleration]), rotation))

    def attrs(self) -> dict:
        """netCDF global attributes: the pair, and each component's :meth:`Record.attrs` with its
        keys prefixed ``record_1_`` and ``record_2_`` by its file's place in the pair (source, sha256,
        units, processing, peaks, warning; ``azimuth_deg`` where the file names its direction). The
        components are numbered, not called x and y: placed by their azimuths, the first file's need
        not be x (``record_orientation`` says how they are placed)."""
        attrs = {"excitation": "record", "excitation_components": 2, "excitation_form": "record pair",
                 "record_npts": self.npts, "record_dt_s": self.dt, "record_peak_horizontal_displacement_m": self.pgd,
                 "record_orientation": self.orientation, "record_rotation_deg": self.rotation}
        for i, record in enumerate((self.x, self.y)):
            attrs.update({f"record_{i + 1}_{k.removeprefix('record_')}": v for k, v in record.attrs().items()
                          if k != "excitation"})
            if self.azimuths is not None:
                attrs[f"record_{i + 1}_azimuth_deg"] = self.azimuths[i]
        return {**attrs, **getattr(self, "scaling", {})}

    def __repr__(self):
        return f"RecordPair(x={self.x!r}, y={self.y!r})"
