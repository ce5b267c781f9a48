"""A PEER NGA-West2 download, written from its documented layout (real records cannot be shipped).

:func:`write_download` writes a folder as ngawest2.berkeley.edu delivers it: one AT2 file per
component and ``_SearchResults.csv``, with the quirks of real downloads, each selectable per file
or per table (see /work/shared/notes/peer-and-friction.md and two real ``_SearchResults.csv``
found in public repositories: a download of 2025-12-30 and one of 2022-01-12 re-saved by a
spreadsheet).

AT2 files (:class:`Component`): four header lines, then the values in PEER's Fortran E15.7 form
(``  -.6176621E-03``, no zero before the point), 5 (or ``per_line``) to a line:

1. ``PEER NGA STRONG MOTION DATABASE RECORD``
2. ``<earthquake>, <date>, <station>, <component>``; the component as an azimuth without leading
   zeros (``52``), a bearing (``N76W``, ``S14W``), ``NS``/``EW``, ``N``/``E``, ``L``/``T``, ``NA``,
   a channel code (``HNE``); a vertical as ``UP``, ``DWN``, ``V``, ``VER``, ``UD``, ``HNZ``
3. ``ACCELERATION TIME SERIES IN UNITS OF G``
4. one of :data:`LINE4`: ``NPTS=  8773, DT=   .0050 SEC,`` with or without the trailing comma,
   ``NPTS =   7500 , DT =   .020 SEC ,``, ``NPTS=  1000, DT=  0.01000 SEC``, filter notes after DT,
   or the older ``4000  0.0100  NPTS, DT``

with CRLF or LF line ends; the components of one record may differ in length (Δt is shared).

``_SearchResults.csv``: the report title, then four tables, each after a title line starting
`` -- ``: the search criteria, the metadata of the selected records (the full 22-column header, or
the shorter header of an older download: :data:`OLD_HEADER`, a stand-in in another order, since
no older file was at hand), then PEER's note, the scaled spectra and the unscaled spectra (their
column headings approximate the real ones; nothing here reads them). Names are quoted (and may
hold commas or trailing spaces), file names have trailing spaces, a missing vertical is ``---``
(``missing="-----"`` as in the download of 2025), the file may lack its final newline, and
``spreadsheet=True`` writes it as a spreadsheet re-saves it (every line padded with commas, a name
written as a quoted field holding a space and the name in quotes, the inner quotes doubled).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

FULL_HEADER = ["Result ID", "Spectral Ordinate", "Record Sequence Number", "Mean Squared Error", "Scale Factor",
               "Tp-Pulse Period (sec)", "5-75% Duration (sec)", "5-95% Duration (sec)", "Arias Intensity (m/sec)",
               "Earthquake Name", "Year", "Station Name", "Magnitude", "Mechanism", "Rjb (km)", "Rrup (km)",
               "Vs30 (m/sec)", "Lowest Useable Frequency (Hz)", "Initial-search Scale Factor",
               "Horizontal-1 Acc. Filename", "Horizontal-2 Acc. Filename", "Vertical Acc. Filename"]
# a shorter header in another order, standing in for an older download's
OLD_HEADER = ["Result ID", "Record Sequence Number", "Scale Factor", "Mean Squared Error", "Earthquake Name", "Year",
              "Station Name", "Magnitude", "Mechanism", "Rjb (km)", "Rrup (km)", "Vs30 (m/sec)",
              "Horizontal-1 Acc. Filename", "Horizontal-2 Acc. Filename", "Vertical Acc. Filename"]
NAMES = {"Earthquake Name", "Station Name"}  # quoted
TEXTS = {"Spectral Ordinate", "Tp-Pulse Period (sec)", "Mechanism", "Horizontal-1 Acc. Filename",
         "Horizontal-2 Acc. Filename", "Vertical Acc. Filename"}  # kept with their leading space by a spreadsheet
PERIODS = [0.01, 0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.5, 10.0]
CRITERIA = [("Magnitude Min:", "0.0"), ("Magnitude Max:", "9.5"), ("Rrup Min (km):", "0.0"),
            ("Rrup Max (km):", "100.0"), ("Rjb Min (km):", "-1.0e-06"), ("Rjb Max (km):", "99999"),
            ("Vs30 Min (m/sec):", "0.0"), ("Vs30 Max (m/sec):", "550.0"), ("D9-95 Min (sec):", "-1.0e-06"),
            ("D9-95 Max (sec):", "99999"), ("Scale Factor Min:", "0.0"), ("Scale Factor Max:", "5.0"),
            ("Period Array:", ""), ("Weight Array:", ""), ("Record Sequence Number:", ""), ("Earthquake Name:", ""),
            ("Station Name:", ""), ("User-Defined Maximum Number of Records:", "30"), ("Pulse:", "1"),
            ("Damping Ratio:", "0.05"), ("Scaling Method:", "No Scaling"), ("Suite Average:", "Arithmetic"),
            ("Single-Period-Scaling Period (sec):", ""), ("Component:", "SRSS"), ("Fault Type:", "All Types")]
NOTE = [" These records were obtained from the NGA-West2 On-Line Ground-Motion Database Tool",
        " These records are UNSCALED, AS RECORDED", " Filename Extension: ", "   ,AT2 = Acceleration",
        "   ,VT2 = Velocity", "   ,DT2 = Displacement",
        " The users of the NGA-West2 databases, flatfiles, models and reports are requested to acknowledge the "
        "Pacific Earthquake Engineering Research Center (PEER) in their work and publications."]
SPREADSHEET_WIDTH = 31  # fields a spreadsheet pads each line to


def fortran_number(value, decimals) -> str:
    """``value`` with ``decimals`` digits after the point and no zero before it (``.0050``, ``-.5``)."""
    text = f"{value:.{decimals}f}"
    return text.replace("0.", ".", 1) if text.lstrip("-").startswith("0.") else text


def fortran_e(value, digits=7) -> str:
    """PEER's E15.7 form of a value: ``-.6176621E-03`` (mantissa in [0.1, 1), no leading zero)."""
    if value == 0:
        return "." + "0" * digits + "E+00"
    mantissa, exponent = f"{abs(value):.{digits - 1}e}".split("e")
    return f"{'-' if value < 0 else ''}.{mantissa.replace('.', '')}E{int(exponent) + 1:+03d}"


# line 4, by style: NPTS and DT as real files write them
LINE4 = {
    "comma": lambda n, dt: f"NPTS={n:6d}, DT={fortran_number(dt, 4):>8} SEC,",
    "no comma": lambda n, dt: f"NPTS={n:6d}, DT={fortran_number(dt, 4):>8} SEC",
    "spaced": lambda n, dt: f"NPTS = {n:6d} , DT = {fortran_number(dt, 3):>6} SEC ,",
    "decimal": lambda n, dt: f"NPTS={n:6d}, DT={dt:9.5f} SEC",
    "filter": lambda n, dt: (f"NPTS={n:7d}, DT={fortran_number(dt, 4):>8} SEC,   0 POLE @    30.00000 HZ,   "
                             f"0 POLE @      .00000"),
    "old": lambda n, dt: f"{n:7d}  {dt:.4f}  NPTS, DT",
}


@dataclass
class Component:
    """One AT2 file of a record: its samples (g), line 2's component field and how it is written."""

    acc: np.ndarray  # acceleration (g)
    label: str  # line 2's component field: "180", "52", "N76W", "NS", "L", "UP", "DWN", "HNZ", ...
    suffix: str  # the file name after RSN<n>_<code>: "180", "-UP", "N76W"
    line4: str = "comma"  # a key of LINE4
    newline: str = "\r\n"  # "\r\n" or "\n"
    per_line: int = 5  # values per line
    line2: str | None = None  # the whole of line 2, instead of "<earthquake>, <date>, <station>, <label>"

    @property
    def npts(self) -> int:
        return int(np.asarray(self.acc).size)


@dataclass
class PeerDownloadRecord:
    """A record of a download: its metadata row and its components (``v`` None: no vertical, ``---``)."""

    rsn: int
    earthquake: str
    station: str
    scale_factor: float
    dt: float  # s, shared by the components
    h1: Component
    h2: Component
    v: Component | None = None
    year: int = 1994
    date: str = "1/17/1994"
    code: str = "EVENT_STA"  # the file names' middle: RSN<rsn>_<code><suffix>.AT2
    lowest_usable_frequency: float = 0.125
    fields: dict = field(default_factory=dict)  # metadata fields written as given: {"Scale Factor": "1.2x"}

    def file(self, component: Component) -> str:
        return f"RSN{self.rsn}_{self.code}{component.suffix}.AT2"

    @property
    def components(self) -> dict[str, Component]:
        """The record's components present, by "h1", "h2", "vertical"."""
        return {k: c for k, c in (("h1", self.h1), ("h2", self.h2), ("vertical", self.v)) if c is not None}


def at2_text(record: PeerDownloadRecord, component: Component) -> str:
    """An AT2 file's text, as PEER writes it (module docstring)."""
    values = np.asarray(component.acc, dtype=float).ravel()
    line2 = component.line2 or f"{record.earthquake}, {record.date}, {record.station.strip()}, {component.label}"
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD", line2, "ACCELERATION TIME SERIES IN UNITS OF G",
             LINE4[component.line4](values.size, record.dt)]
    k = component.per_line
    lines += ["".join(f"{fortran_e(v):>15}" for v in values[i:i + k]) for i in range(0, values.size, k)]
    nl = component.newline
    return nl.join(lines) + nl


def _metadata(i, record: PeerDownloadRecord, missing) -> dict[str, str]:
    files = {k: record.file(c) for k, c in record.components.items()}
    rsn = record.rsn
    values = {"Result ID": str(i + 1), "Spectral Ordinate": "SRSS", "Record Sequence Number": str(rsn),
              "Mean Squared Error": f"{0.1 + (rsn % 37) / 10:.4f}", "Scale Factor": repr(float(record.scale_factor)),
              "Tp-Pulse Period (sec)": "-", "5-75% Duration (sec)": "7.4", "5-95% Duration (sec)": "23.6",
              "Arias Intensity (m/sec)": "0.2", "Earthquake Name": record.earthquake, "Year": str(record.year),
              "Station Name": record.station, "Magnitude": "6.61", "Mechanism": "strike slip",
              "Rjb (km)": "24.69", "Rrup (km)": "24.87", "Vs30 (m/sec)": "389.0",
              "Lowest Useable Frequency (Hz)": repr(float(record.lowest_usable_frequency)),
              "Initial-search Scale Factor": repr(float(record.scale_factor)),
              # the file names' trailing spaces as in real downloads: none, one, two
              "Horizontal-1 Acc. Filename": files["h1"], "Horizontal-2 Acc. Filename": files["h2"] + " ",
              "Vertical Acc. Filename": files["vertical"] + "  " if "vertical" in files else f" {missing}   "}
    values.update(record.fields)
    return values


def _quoted(text, spreadsheet) -> str:
    text = text.replace('"', '""')
    return f'" ""{text}"""' if spreadsheet else f'"{text}"'


def _row(header, values, spreadsheet) -> str:
    fields = []
    for column in header:
        value = values.get(column, "")
        if column in NAMES:
            value = _quoted(value, spreadsheet)
        elif spreadsheet and column in TEXTS:
            value = " " + value.lstrip()
        fields.append(value)
    return ("," if spreadsheet else ", ").join(fields)


def _spectrum(record, component, period) -> float:
    """A stand-in ordinate (g): nothing reads the spectra tables."""
    peak = float(np.max(np.abs(component.acc)))
    return peak * (1.0 + 1.5 * math.exp(-((math.log(period / 0.3)) ** 2)))


def search_results_text(records, header="full", missing="---", final_newline=True, spreadsheet=False,
                        newline="\r\n", date="2025-12-30") -> str:
    """The text of a download's ``_SearchResults.csv`` listing ``records`` (module docstring).

    ``header``: "full" (22 columns), "old" (:data:`OLD_HEADER`) or a list of column names.
    """
    header = {"full": FULL_HEADER, "old": OLD_HEADER}.get(header, header) if isinstance(header, str) else header
    lines = ["", f" PEER Ground Motion Database, Time Series Search Report -- NGA-West2 -- {date}", "", "",
             " -- Summary of PEER Ground Motion Database Search Criteria --"]
    lines += [f"{name}, {value}" for name, value in CRITERIA]
    lines += ["", "", " -- Summary of Metadata of Selected Records --", ", ".join(header)]
    lines += [_row(header, _metadata(i, r, missing), spreadsheet) for i, r in enumerate(records)]
    lines += [""] + NOTE + ["", " -- Scaled Spectra used in Search & Scaling --"]
    lines.append(",".join(["Period (sec)", "Target pSa (g)", "Arithmetic Mean pSa (g)",
                           "Arithmetic Mean + Sigma pSa (g)", "Arithmetic Mean - Sigma pSa (g)"]
                          + [f"RSN-{r.rsn} SRSS pSa (g)" for r in records]))
    for period in PERIODS:
        srss = [r.scale_factor * math.hypot(_spectrum(r, r.h1, period), _spectrum(r, r.h2, period)) for r in records]
        mean, sigma = float(np.mean(srss)), float(np.std(srss))
        lines.append(",".join(f"{v:.8g}" for v in [period, mean, mean, mean + sigma, max(mean - sigma, 0.0), *srss]))
    lines += ["", " -- Unscaled Horizontal & Vertical Spectra, as recorded --"]
    lines.append(",".join(["Period (sec)"] + [f"RSN-{r.rsn} {name} pSa (g)" for r in records
                                              for name in ("Horizontal-1", "Horizontal-2", "Vertical")]))
    for period in PERIODS:
        ordinates = [f"{_spectrum(r, c, period):.7g}" if c is not None else ""
                     for r in records for c in (r.h1, r.h2, r.v)]
        lines.append(",".join([f"{period:g}", *ordinates]))
    if spreadsheet:
        lines = [line + "," * max(SPREADSHEET_WIDTH - 1 - line.count(","), 0) for line in lines]
    return newline.join(lines) + (newline if final_newline else "")


def write_download(folder, records, header="full", missing="---", final_newline=True, spreadsheet=False,
                   newline="\r\n") -> Path:
    """Write the download of ``records`` (:class:`PeerDownloadRecord`) into ``folder``: each
    component's AT2 file and ``_SearchResults.csv`` (:func:`search_results_text`); returns the csv's path."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for record in records:
        for component in record.components.values():
            (folder / record.file(component)).write_bytes(at2_text(record, component).encode())
    path = folder / "_SearchResults.csv"
    text = search_results_text(records, header=header, missing=missing, final_newline=final_newline,
                               spreadsheet=spreadsheet, newline=newline)
    path.write_bytes(text.encode())
    return path


def _motion(rng, npts, dt, peak):
    """A ground acceleration (g) of ``npts`` samples: filtered noise under a rise-and-decay envelope."""
    t = dt * np.arange(npts)
    duration = t[-1] if npts > 1 else 1.0
    envelope = (t / (0.2 * duration)) ** 2 * np.exp(2 * (1 - t / (0.2 * duration)))
    noise = np.convolve(rng.standard_normal(npts + 20), np.hanning(21), mode="valid")[:npts]
    acc = envelope * noise
    return peak * acc / np.max(np.abs(acc))


# (rsn, earthquake, year, date, station, code, scale, dt, [(label, suffix, npts, line4, newline), x3 H1 H2 V])
EXAMPLES = [
    (6, "Imperial Valley-02", 1940, "5/19/1940", "El Centro Array #9", "IMPVALL.I_I-ELC", 1.0, 0.01,
     [("180", "180", 800, "comma", "\r\n"), ("270", "270", 801, "no comma", "\n"),
      ("UP", "-UP", 799, "filter", "\r\n")]),
    (30, "Parkfield", 1966, "6/28/1966", "Cholame - Shandon Array #5", "PARKF_C05", 1.5, 0.01,
     [("85", "085", 600, "no comma", "\n"), ("355", "355", 600, "no comma", "\n"),
      ("DWN", "DWN", 600, "comma", "\n")]),
    (57, "San Fernando", 1971, "2/9/1971", "Castaic - Old Ridge Route", "SFERN_ORR", 2.0149, 0.02,
     [("21", "021", 500, "spaced", "\r\n"), ("291", "291", 500, "spaced", "\r\n"),
      ("DWN", "DWN", 500, "spaced", "\r\n")]),
    (6971, "Darfield, New Zealand", 2010, "9/3/2010", "SPFS", "DARFIELD_SPFS", 2.1737, 0.005,
     [("N17E", "N17E", 900, "decimal", "\n"), ("N73W", "N73W", 900, "decimal", "\n"),
      ("UP", "UP", 900, "decimal", "\n")]),
    (6915, "Darfield, New Zealand", 2010, "9/3/2010", "Heathcote Valley Primary School ", "DARFIELD_HVSC", 1.336, 0.005,
     [("S26W", "S26W", 900, "filter", "\r\n"), ("S64E", "S64E", 900, "filter", "\r\n"),
      ("UP", "UP", 900, "filter", "\r\n")]),
    (1063, "Northridge-01", 1994, "1/17/1994", "Rinaldi Receiving Sta", "NORTHR_RRS", 1.2, 0.005,
     [("S14W", "S14W", 1000, "comma", "\r\n"), ("N76W", "N76W", 1000, "comma", "\n"),
      ("V", "-UP", 1000, "comma", "\n")]),
    (1614, "Duzce, Turkey", 1999, "11/12/1999", "Lamont 1061", "DUZCE_1061", 4.0546, 0.01,
     [("N", "-N", 700, "comma", "\r\n"), ("E", "-E", 700, "comma", "\r\n"),
      ("V", "-V", 700, "comma", "\r\n")]),
    (1616, "Duzce, Turkey", 1999, "11/12/1999", "Lamont 362", "DUZCE_362", 3.8094, 0.01,
     [("E", "-E", 650, "no comma", "\n"), ("N", "-N", 650, "no comma", "\n"),
      ("VER", "-VER", 650, "no comma", "\n")]),
    (1633, "Manjil, Iran", 1990, "6/20/1990", "Abbar", "MANJIL_ABBAR--", 0.8316, 0.02,
     [("L", "L", 450, "spaced", "\n"), ("T", "T", 450, "spaced", "\n"),
      ("UD", "V", 450, "spaced", "\n")]),
    (138, "Tabas, Iran", 1978, "9/16/1978", "Boshrooyeh", "TABAS_BOS-", 1.0, 0.02,
     [("L1", "L1", 400, "old", "\r\n"), ("T1", "T1", 400, "old", "\r\n"),
      ("V1", "V1", 400, "old", "\r\n")]),
    (4845, "Chuetsu-oki, Japan", 2007, "7/16/2007", "NIG018", "CHUETSU_NIG018", 1.3, 0.01,
     [("NS", "NS", 600, "decimal", "\r\n"), ("EW", "EW", 600, "decimal", "\r\n"),
      ("UD", "UD", 600, "decimal", "\r\n")]),
    (5827, "El Mayor-Cucapah, Mexico", 2010, "4/4/2010", "Calexico Fire Station", "SIERRA.MEX_CXO", 1.1, 0.005,
     [("HNN", "HNN", 800, "filter", "\n"), ("HNE", "HNE", 800, "filter", "\n"),
      ("HNZ", "HNZ", 800, "filter", "\n")]),
    (1489, "Chi-Chi, Taiwan", 1999, "9/20/1999", "TCU049", "CHICHI_TCU049", 1.0, 0.005,
     [("E", "-E", 700, "comma", "\n"), ("NA", "-NA", 700, "comma", "\n"),
      ("UP", "-V", 700, "comma", "\n")]),
    (1158, "Kocaeli, Turkey", 1999, "8/17/1999", "Duzce", "KOCAELI_DZC", 1.5, 0.005,
     [("180", "180", 1200, "comma", "\r\n"), ("270", "270", 1450, "comma", "\r\n"),
      ("UP", "-UP", 900, "comma", "\r\n")]),
]


def example_records(seed=0) -> list[PeerDownloadRecord]:
    """Fourteen records with H1, H2 and V that between them hold every AT2 quirk above: bearings,
    azimuths without leading zeros, NS/EW, N/E (H1 north in one record, east in the next), L/T, NA,
    channel codes; every vertical label; every line-4 form; CRLF and LF; components one sample
    apart and hundreds apart; quoted names with commas and a trailing space; 8 values per line in
    one record."""
    rng = np.random.default_rng(seed)
    out = []
    for i, (rsn, quake, year, date, station, code, scale, dt, parts) in enumerate(EXAMPLES):
        comps = [Component(_motion(rng, npts, dt, 0.05 + 0.03 * ((i + j) % 7)), label, suffix, line4, nl,
                           per_line=8 if rsn == 1158 else 5)
                 for j, (label, suffix, npts, line4, nl) in enumerate(parts)]
        out.append(PeerDownloadRecord(rsn, quake, station, scale, dt, *comps, year=year, date=date, code=code,
                                      lowest_usable_frequency=round(0.05 + 0.0125 * i, 4)))
    return out
