"""PEER NGA-West2 downloads: the records a ``_SearchResults.csv`` lists, and a suite made of them.

A download from the PEER NGA-West2 database (ngawest2.berkeley.edu) is a folder holding the AT2
files of the selected records (the two horizontal components of each, usually its vertical too)
and ``_SearchResults.csv``. That file is not one table but several, each after a title line
starting with `` -- `` (a leading space, then two dashes)::

     PEER Ground Motion Database, Time Series Search Report -- NGA-West2 -- <date>
     -- Summary of PEER Ground Motion Database Search Criteria --
    Magnitude Min:, 0.0
    ...
     -- Summary of Metadata of Selected Records --
    Result ID, Spectral Ordinate, Record Sequence Number, Mean Squared Error, Scale Factor, ...
    1, SRSS, 6, 0.4768, 1.0, -, ..., "Imperial Valley-02", 1940, "El Centro Array #9", ..., RSN6_..180.AT2, ...
    <blank line>
     These records were obtained from the NGA-West2 On-Line Ground-Motion Database Tool
    ...
     -- Scaled Spectra used in Search & Scaling --
    ...
     -- Unscaled Horizontal & Vertical Spectra, as recorded --
    ...

What is read
------------
Only the metadata table (:func:`read_search_results`): the line after its title is its header,
and its rows run to the first blank line (a line of commas alone, as a spreadsheet saves it, is
blank too). Columns are found by **name**, not position (names compared without surrounding
spaces and case; the header keeps a leading space before each name), because older downloads
have fewer columns in another order. The full header of a current download has 22 columns:
Result ID, Spectral Ordinate, Record Sequence Number, Mean Squared Error, Scale Factor, Tp-Pulse
Period (sec), 5-75% Duration (sec), 5-95% Duration (sec), Arias Intensity (m/sec), Earthquake
Name, Year, Station Name, Magnitude, Mechanism, Rjb (km), Rrup (km), Vs30 (m/sec), Lowest Useable
Frequency (Hz), Initial-search Scale Factor, Horizontal-1 Acc. Filename, Horizontal-2 Acc.
Filename, Vertical Acc. Filename. Of these, **Record Sequence Number, Scale Factor,
Horizontal-1 Acc. Filename and Horizontal-2 Acc. Filename are required**; Earthquake Name, Year,
Station Name, Lowest Useable (or Usable) Frequency (Hz) and Vertical Acc. Filename are read
where present; the other columns are not read.

Fields are comma-separated with a space after each comma; names are quoted and may hold commas
(PEER usually writes a comma in a name as ``_``, e.g. ``"Tabas_ Iran"``) or trailing spaces, and a
spreadsheet that re-saved the file may have quoted the quoted name again (a field holding a space
and ``"Landers"``): a name is read without surrounding spaces and quotes. File names carry
trailing spaces, which are dropped; a missing file is written as dashes (``---``; a download of
2025 writes ``-----``), read as None. A year or lowest usable frequency written ``-`` (PEER's
"none") or left empty is None. The file may use CRLF or LF, lack a final newline, or start with
a byte-order mark.

What is refused
---------------
Every problem is a ``ValueError`` naming the file, the line and (for a field) the column: a file
that does not exist or has no metadata table, a table without a header or without rows, a
header missing a required column, a row too short to hold a column it needs, and a number that
does not read (Record Sequence Number must be a whole number, Scale Factor a finite number
> 0). :func:`suite_entries` also refuses, in one error naming each record and file, the files the
table lists but the folder lacks, a record without a horizontal file, and (asked for verticals)
a record without one; and two rows of the same record (the same entry name).
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path
from typing import NamedTuple

TITLE = "-- Summary of Metadata of Selected Records --"
SEARCH_RESULTS = "_SearchResults.csv"

# columns, by their normalised names (_key)
RSN = "record sequence number"
SCALE = "scale factor"
H1 = "horizontal-1 acc. filename"
H2 = "horizontal-2 acc. filename"
VERTICAL = "vertical acc. filename"
EARTHQUAKE = "earthquake name"
STATION = "station name"
YEAR = "year"
LOWEST_FREQUENCY = ("lowest useable frequency (hz)", "lowest usable frequency (hz)")
REQUIRED = (RSN, SCALE, H1, H2)
# how each column is named in messages
_SPELLING = {RSN: "Record Sequence Number", SCALE: "Scale Factor", H1: "Horizontal-1 Acc. Filename",
             H2: "Horizontal-2 Acc. Filename", VERTICAL: "Vertical Acc. Filename", EARTHQUAKE: "Earthquake Name",
             STATION: "Station Name", YEAR: "Year",
             LOWEST_FREQUENCY[0]: "Lowest Useable Frequency (Hz)", LOWEST_FREQUENCY[1]: "Lowest Usable Frequency (Hz)"}
_NONE = re.compile(r"^-+$")  # "-", "---", "-----": nothing
_NAME_CHARACTERS = re.compile(r"[^A-Za-z0-9_.+-]")
COMPONENTS = {"h1": "horizontal-1", "h2": "horizontal-2", "vertical": "vertical"}


class PeerRecord(NamedTuple):
    """One row of a download's metadata table."""

    rsn: int  # Record Sequence Number
    earthquake: str  # Earthquake Name ("" where the table has no such column)
    year: int | None  # Year
    station: str  # Station Name ("" where the table has no such column)
    scale_factor: float  # Scale Factor
    h1: str | None  # Horizontal-1 Acc. Filename (None for ---)
    h2: str | None  # Horizontal-2 Acc. Filename
    vertical: str | None  # Vertical Acc. Filename (None for --- or no such column)
    lowest_usable_frequency_hz: float | None  # Lowest Useable Frequency (Hz)
    line: int  # the row's line number in the csv (1-based)

    @property
    def label(self) -> str:
        """The record as messages name it: ``RSN1063_Rinaldi Receiving Sta``."""
        return f"RSN{self.rsn}_{self.station}" if self.station else f"RSN{self.rsn}"

    @property
    def name(self) -> str:
        """Its entry name in a suite: ``RSN<number>_<station>``, the station's characters other than
        ``A-Z a-z 0-9 _ . + -`` written ``_``."""
        return f"RSN{self.rsn}_{_NAME_CHARACTERS.sub('_', self.station)}" if self.station else f"RSN{self.rsn}"


def _key(name) -> str:
    return " ".join(str(name).split()).casefold()


def _text(field) -> str:
    """A field without surrounding spaces and quotes (also a spreadsheet's doubled ones)."""
    text = field.strip()
    while len(text) >= 2 and text[0] == text[-1] == '"':
        text = text[1:-1].strip()
    return text


def _blank(line) -> bool:
    return not line.strip().strip(",").strip()


class _Table:
    """The metadata table: its header's columns and where it is."""

    def __init__(self, path, lines):
        self.path = path
        title = next((i for i, line in enumerate(lines) if line.strip().startswith(TITLE)), None)
        if title is None:
            raise ValueError(f"{path}: no {TITLE!r} table (the title line of the records' metadata in a PEER "
                             f"NGA-West2 {SEARCH_RESULTS}); is this a PEER download's search results?")
        self.header_line = title + 2  # 1-based
        if title + 1 >= len(lines) or _blank(lines[title + 1]):
            raise ValueError(f"{path}: line {self.header_line}: the {TITLE!r} table has no header line (expected "
                             f"'Result ID, Spectral Ordinate, Record Sequence Number, ...')")
        names = next(csv.reader([lines[title + 1]], skipinitialspace=True))
        self.columns = {}
        for j, name in enumerate(names):
            self.columns.setdefault(_key(_text(name)), j)
        self.columns.pop("", None)
        missing = [_SPELLING[c] for c in REQUIRED if c not in self.columns]
        if missing:
            raise ValueError(f"{path}: line {self.header_line}: the {TITLE!r} table has no column "
                             f"{' and no column '.join(repr(m) for m in missing)}; its columns are "
                             f"{[_text(n) for n in names if _text(n)]}")
        self.rows = []
        for n in range(title + 2, len(lines)):
            if _blank(lines[n]) or lines[n].lstrip().startswith("-- "):
                break
            self.rows.append((n + 1, next(csv.reader([lines[n]], skipinitialspace=True))))
        if not self.rows:
            raise ValueError(f"{path}: line {self.header_line + 1}: the {TITLE!r} table has no rows")

    def field(self, line, row, column, required):
        """The text of ``column`` in ``row`` ("" where the table has no such column and it is optional)."""
        j = self.columns.get(column)
        if j is None:
            return ""
        if j >= len(row):
            if not required:
                return ""
            raise ValueError(f"{self.path}: line {line}: column {_SPELLING[column]!r}: the row has {len(row)} "
                             f"field(s), the header {len(self.columns)}: a row cut short or a comma missing")
        return _text(row[j])

    def fail(self, line, column, value, what):
        return ValueError(f"{self.path}: line {line}: column {_SPELLING[column]!r}: {value!r} is not {what}")


def _lines(path) -> list[str]:
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such file (a PEER download's {SEARCH_RESULTS})")
    return path.read_text(encoding="utf-8-sig", errors="replace").splitlines()


def _int(table, line, column, text, required):
    if not required and (not text or _NONE.match(text)):
        return None
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or value != int(value) or value < 0:
        raise table.fail(line, column, text, "a whole number")
    return int(value)


def _float(table, line, column, text, required):
    if not required and (not text or _NONE.match(text)):
        return None
    try:
        value = float(text)
    except ValueError:
        raise table.fail(line, column, text, "a number") from None
    if not math.isfinite(value) or (required and value <= 0):
        raise table.fail(line, column, text, "a finite number > 0" if required else "a finite number")
    return value


def _file(text):
    return None if not text or _NONE.match(text) else text


def read_search_results(path) -> list[PeerRecord]:
    """The records of a PEER NGA-West2 ``_SearchResults.csv``'s metadata table, in its order
    (module docstring: the layout, what is read and what is refused).

    Raises
    ------
    ValueError
        Naming the file, the line and the column: no such file or table, a required column
        missing, a field that is not a number.
    """
    path = Path(path)
    table = _Table(path, _lines(path))
    records = []
    for line, row in table.rows:
        def text(column, required=False, line=line, row=row):
            return table.field(line, row, column, required)

        frequency = next((c for c in LOWEST_FREQUENCY if c in table.columns), LOWEST_FREQUENCY[0])
        records.append(PeerRecord(
            rsn=_int(table, line, RSN, text(RSN, True), True),
            earthquake=text(EARTHQUAKE), year=_int(table, line, YEAR, text(YEAR), False), station=text(STATION),
            scale_factor=_float(table, line, SCALE, text(SCALE, True), True),
            h1=_file(text(H1, True)), h2=_file(text(H2, True)), vertical=_file(text(VERTICAL)),
            lowest_usable_frequency_hz=_float(table, line, frequency, text(frequency), False), line=line))
    return records


def suite_entries(csv, base, vertical=False) -> dict[str, dict]:
    """The records of a PEER download as a suite's entries, by name.

    Parameters
    ----------
    csv : the download's ``_SearchResults.csv`` as written in a study file: relative to ``base``
        (the study file's folder), or absolute.
    base : the folder relative paths start from.
    vertical : also give each record's vertical component (and refuse a record without one).

    Returns
    -------
    dict
        ``{"RSN<number>_<station>": {"file": [h1, h2], "peer_scale": scale_factor, "peer_rsn": rsn}}``
        in the table's order (plus ``"vertical": v`` with ``vertical=True``); the files are paths
        as strings next to ``csv`` as it was given (``str(Path(csv).parent / name)``: relative to
        ``base`` for a relative ``csv``).

    Raises
    ------
    ValueError
        :func:`read_search_results`'s errors; and, in one error naming each record and file, every
        file the table lists but the folder lacks, a record without H1 or H2 (or, with
        ``vertical``, without a vertical), and two rows that make the same entry name.
    """
    given = Path(csv)
    path = given if given.is_absolute() else Path(base) / given
    folder = path.parent
    components = ("h1", "h2", "vertical") if vertical else ("h1", "h2")
    entries, rows, problems = {}, {}, []
    for record in read_search_results(path):
        if record.name in rows:
            other = rows[record.name]
            raise ValueError(f"{path}: lines {other.line} and {record.line} are the same record {record.label!r} "
                             f"(entry {record.name!r}): a suite names each record once; remove one of the rows")
        rows[record.name] = record
        files = {}
        for component in components:
            name = getattr(record, component)
            if name is None:
                problems.append(f"{record.label}: no {COMPONENTS[component]} file ('---' in line {record.line})")
            elif not (folder / name).is_file():
                problems.append(f"{record.label}: {name} ({COMPONENTS[component]})")
            files[component] = None if name is None else str(given.parent / name)
        entry = {"file": [files["h1"], files["h2"]], "peer_scale": record.scale_factor, "peer_rsn": record.rsn}
        if vertical:
            entry["vertical"] = files["vertical"]
        entries[record.name] = entry
    if problems:
        raise ValueError(f"{path}: {len(problems)} file(s) of the records it lists missing from "
                         f"{str(folder)!r}: " + "; ".join(problems))
    return entries
