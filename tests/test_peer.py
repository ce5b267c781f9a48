"""PEER NGA-West2 downloads (dccss.peer) and their AT2 files (dccss.records.read_peer, peer_azimuth),
on folders written with the layout and the quirks of real downloads (tests/peer_download.py)."""

import re
from pathlib import Path

import numpy as np
import pytest
from peer_download import (
    FULL_HEADER,
    LINE4,
    Component,
    PeerDownloadRecord,
    at2_text,
    example_records,
    fortran_e,
    write_download,
)

from dccss.peer import PeerRecord, read_search_results, suite_entries
from dccss.records import peer_azimuth, read_peer

# each example component's line-2 label and the direction peer_azimuth must read from it
DIRECTIONS = {"180": 180.0, "270": 270.0, "85": 85.0, "355": 355.0, "21": 21.0, "291": 291.0, "N17E": 17.0,
              "N73W": 287.0, "S26W": 206.0, "S64E": 116.0, "S14W": 194.0, "N76W": 284.0, "N": 0.0, "E": 90.0,
              "L": None, "T": None, "L1": None, "T1": None, "NS": 0.0, "EW": 90.0, "HNN": 0.0, "HNE": 90.0,
              "NA": None, "UP": "vertical", "DWN": "vertical", "V": "vertical", "VER": "vertical", "UD": "vertical",
              "V1": "vertical", "HNZ": "vertical"}


@pytest.fixture(scope="module")
def examples():
    return example_records()


@pytest.fixture(scope="module")
def download(tmp_path_factory, examples):
    """The fourteen example records as a download in <tmp>/peer/, the csv with CRLF and a final newline."""
    base = tmp_path_factory.mktemp("study")
    write_download(base / "peer", examples)
    return base


def expected(record: PeerDownloadRecord, line, frequency=True) -> PeerRecord:
    return PeerRecord(record.rsn, record.earthquake, record.year, record.station.strip(), record.scale_factor,
                      record.file(record.h1), record.file(record.h2), record.file(record.v) if record.v else None,
                      record.lowest_usable_frequency if frequency else None, line)


def test_the_fixture_writes_what_real_files_hold():
    # the forms of the notes (peer-and-friction.md) and of real files, character for character
    assert LINE4["comma"](8773, 0.005) == "NPTS=  8773, DT=   .0050 SEC,"
    assert LINE4["no comma"](8773, 0.005) == "NPTS=  8773, DT=   .0050 SEC"
    assert LINE4["spaced"](7500, 0.02) == "NPTS =   7500 , DT =   .020 SEC ,"
    assert LINE4["decimal"](1000, 0.01) == "NPTS=  1000, DT=  0.01000 SEC"
    assert LINE4["filter"](1999, 0.01) == ("NPTS=   1999, DT=   .0100 SEC,   0 POLE @    30.00000 HZ,   0 POLE @      "
                                          ".00000")  # RSN960_NORTHR_LOS270.AT2
    assert f"{fortran_e(-6.176621e-4):>15}" == "  -.6176621E-03" and fortran_e(0.1187e-1) == ".1187000E-01"
    assert fortran_e(0.0) == ".0000000E+00"
    assert ", ".join(FULL_HEADER) == (  # as a real download of 2025 writes it
        "Result ID, Spectral Ordinate, Record Sequence Number, Mean Squared Error, Scale Factor, Tp-Pulse Period "
        "(sec), 5-75% Duration (sec), 5-95% Duration (sec), Arias Intensity (m/sec), Earthquake Name, Year, Station "
        "Name, Magnitude, Mechanism, Rjb (km), Rrup (km), Vs30 (m/sec), Lowest Useable Frequency (Hz), Initial-search "
        "Scale Factor, Horizontal-1 Acc. Filename, Horizontal-2 Acc. Filename, Vertical Acc. Filename")


def test_a_download_of_fourteen_records_is_read(download, examples):
    path = download / "peer" / "_SearchResults.csv"
    records = read_search_results(path)
    lines = path.read_text().splitlines()
    header = lines.index(" -- Summary of Metadata of Selected Records --") + 2  # 1-based line of the header
    assert records == [expected(r, header + 1 + i) for i, r in enumerate(examples)]
    assert all(f", {r.rsn}, " in lines[r.line - 1] for r in records)
    # names with commas, a trailing space (dropped), file names without their trailing spaces
    by_rsn = {r.rsn: r for r in records}
    assert by_rsn[1614].earthquake == "Duzce, Turkey" and by_rsn[6915].station == "Heathcote Valley Primary School"
    assert by_rsn[6].h2 == "RSN6_IMPVALL.I_I-ELC270.AT2" and by_rsn[6].vertical == "RSN6_IMPVALL.I_I-ELC-UP.AT2"


@pytest.mark.parametrize("newline", ["\r\n", "\n"])
@pytest.mark.parametrize("final_newline", [True, False])
@pytest.mark.parametrize("spreadsheet", [False, True])
def test_line_ends_final_newline_and_a_spreadsheets_copy_read_alike(tmp_path, examples, newline, final_newline,
                                                                     spreadsheet):
    path = write_download(tmp_path, examples, newline=newline, final_newline=final_newline, spreadsheet=spreadsheet)
    raw = path.read_bytes()
    assert raw.endswith(newline.encode()) == final_newline and (b"\r\n" in raw) == (newline == "\r\n")
    if spreadsheet:
        assert b'" ""Duzce, Turkey"""' in raw and b",,,,\r\n" in raw.replace(newline.encode(), b"\r\n")
    records = read_search_results(path)
    assert [r._replace(line=0) for r in records] == [expected(r, 0) for r in examples]


def test_an_older_download_with_fewer_columns_in_another_order_is_read_by_name(tmp_path, examples):
    path = write_download(tmp_path, examples, header="old")
    records = read_search_results(path)
    assert [r._replace(line=0) for r in records] == [expected(r, 0, frequency=False) for r in examples]
    # without the optional columns: no station, earthquake, year, vertical
    columns = ["Record Sequence Number", "Horizontal-1 Acc. Filename", "Horizontal-2 Acc. Filename", "Scale Factor"]
    path = write_download(tmp_path / "bare", examples[:2], header=columns)
    bare = read_search_results(path)
    assert [(r.rsn, r.earthquake, r.station, r.year, r.vertical, r.scale_factor) for r in bare] == [
        (6, "", "", None, None, 1.0), (30, "", "", None, None, 1.5)]
    assert list(suite_entries(path, tmp_path)) == ["RSN6", "RSN30"]


def test_rows_as_real_downloads_write_them(tmp_path):
    """Rows of two real downloads, verbatim: one of 2025 (a missing vertical written '-----', no pulse '-')
    and one of 2022 re-saved by a spreadsheet (padding commas, quotes doubled, a station's trailing space)."""
    header = ", ".join(FULL_HEADER)
    real = (f"\n -- Summary of Metadata of Selected Records --\n{header}\n"
            '13, SRSS, 78, 2.5232, 1.0, -, 10.0, 18.9, 0.3, "San Fernando", 1971, "Palmdale Fire Station", 6.61, '
            "Reverse, 24.16, 28.99, 452.86, 0.1875, 1.0, RSN78_SFERN_PDL120.AT2, RSN78_SFERN_PDL210.AT2 ,  -----   \n"
            "\n These records were obtained from the NGA-West2 On-Line Ground-Motion Database Tool\n")
    (tmp_path / "a.csv").write_text(real)
    assert read_search_results(tmp_path / "a.csv") == [
        PeerRecord(78, "San Fernando", 1971, "Palmdale Fire Station", 1.0, "RSN78_SFERN_PDL120.AT2",
                   "RSN78_SFERN_PDL210.AT2", None, 0.1875, 4)]
    saved = (" -- Summary of Metadata of Selected Records --,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,\r\n"
             f"{header},,,,,,,,,\r\n"
             '9, SRSS,6915,0.4334,1.336, -,8.5,15.7,4.1," ""Darfield_ New Zealand""",2010," ""Heathcote Valley '
             'Primary School """,7, strike slip,24.36,24.47,422,0.075,1.4397, RSN6915_DARFIELD_HVSCS26W.AT2, '
             "RSN6915_DARFIELD_HVSCS64E.AT2 , RSN6915_DARFIELD_HVSCUP.AT2  ,,,,,,,,,\r\n"
             ",,,,,,,,,,,,,,,,,,,,,,,,,,,,,,\r\n These records were obtained from the NGA-West2 On-Line Ground-Motion "
             "Database Tool,,,,,,,,,,,,,,,,,,,,,,,,,,,,,,\r\n")
    (tmp_path / "b.csv").write_text(saved, newline="")
    assert read_search_results(tmp_path / "b.csv") == [
        PeerRecord(6915, "Darfield_ New Zealand", 2010, "Heathcote Valley Primary School", 1.336,
                   "RSN6915_DARFIELD_HVSCS26W.AT2", "RSN6915_DARFIELD_HVSCS64E.AT2", "RSN6915_DARFIELD_HVSCUP.AT2",
                   0.075, 3)]


def test_suite_entries_name_each_record_and_give_its_files_relative_to_the_study(download, examples):
    entries = suite_entries("peer/_SearchResults.csv", download, vertical=True)
    assert list(entries) == ["RSN6_El_Centro_Array__9", "RSN30_Cholame_-_Shandon_Array__5",
                             "RSN57_Castaic_-_Old_Ridge_Route", "RSN6971_SPFS",
                             "RSN6915_Heathcote_Valley_Primary_School", "RSN1063_Rinaldi_Receiving_Sta",
                             "RSN1614_Lamont_1061", "RSN1616_Lamont_362", "RSN1633_Abbar", "RSN138_Boshrooyeh",
                             "RSN4845_NIG018", "RSN5827_Calexico_Fire_Station", "RSN1489_TCU049", "RSN1158_Duzce"]
    for (name, entry), record in zip(entries.items(), examples, strict=True):
        folder = Path("peer")
        assert entry == {"file": [str(folder / record.file(record.h1)), str(folder / record.file(record.h2))],
                         "peer_scale": record.scale_factor, "peer_rsn": record.rsn,
                         "vertical": str(folder / record.file(record.v))}, name
        assert all((download / f).is_file() for f in [*entry["file"], entry["vertical"]])
    plain = suite_entries(Path("peer/_SearchResults.csv"), download)
    assert all("vertical" not in e for e in plain.values())
    assert {k: {**v, "vertical": entries[k]["vertical"]} for k, v in plain.items()} == entries
    # an absolute csv gives absolute files
    absolute = suite_entries(download / "peer" / "_SearchResults.csv", "/elsewhere")
    assert absolute["RSN1158_Duzce"]["file"][0] == str(download / "peer" / "RSN1158_KOCAELI_DZC180.AT2")


def test_files_the_folder_lacks_are_named_together(tmp_path, examples):
    write_download(tmp_path / "peer", examples)
    (tmp_path / "peer" / "RSN1063_NORTHR_RRS-UP.AT2").unlink()
    (tmp_path / "peer" / "RSN6_IMPVALL.I_I-ELC270.AT2").unlink()
    (tmp_path / "peer" / "RSN1158_KOCAELI_DZC180.AT2").unlink()
    with pytest.raises(ValueError) as error:
        suite_entries("peer/_SearchResults.csv", tmp_path, vertical=True)
    message = str(error.value)
    assert "_SearchResults.csv" in message and "3 file(s)" in message
    for item in ("RSN6_El Centro Array #9: RSN6_IMPVALL.I_I-ELC270.AT2 (horizontal-2)",
                 "RSN1063_Rinaldi Receiving Sta: RSN1063_NORTHR_RRS-UP.AT2 (vertical)",
                 "RSN1158_Duzce: RSN1158_KOCAELI_DZC180.AT2 (horizontal-1)"):
        assert item in message
    # without verticals the missing vertical is no error; the horizontals still are
    with pytest.raises(ValueError, match=r"2 file\(s\)") as error:
        suite_entries("peer/_SearchResults.csv", tmp_path)
    assert "RRS-UP" not in str(error.value)


@pytest.mark.parametrize("missing", ["---", "-----"])
def test_a_missing_vertical_is_none_and_an_error_only_when_verticals_are_asked_for(tmp_path, examples, missing):
    records = [examples[0], PeerDownloadRecord(**{**examples[5].__dict__, "v": None})]
    path = write_download(tmp_path / "peer", records, missing=missing)
    assert f" {missing}   " in path.read_text()
    assert [r.vertical for r in read_search_results(path)] == ["RSN6_IMPVALL.I_I-ELC-UP.AT2", None]
    assert list(suite_entries("peer/_SearchResults.csv", tmp_path)) == ["RSN6_El_Centro_Array__9",
                                                                         "RSN1063_Rinaldi_Receiving_Sta"]
    with pytest.raises(ValueError, match=r"RSN1063_Rinaldi Receiving Sta: no vertical file \('---' in line \d+\)"):
        suite_entries("peer/_SearchResults.csv", tmp_path, vertical=True)


def test_a_record_without_a_horizontal_file_is_refused(tmp_path, examples):
    record = PeerDownloadRecord(**{**examples[1].__dict__, "fields": {"Horizontal-1 Acc. Filename": "---"}})
    write_download(tmp_path / "peer", [record])
    with pytest.raises(ValueError, match=r"RSN30_Cholame - Shandon Array #5: no horizontal-1 file"):
        suite_entries("peer/_SearchResults.csv", tmp_path)


def test_two_rows_of_one_record_are_refused_naming_both(tmp_path, examples):
    path = write_download(tmp_path / "peer", [examples[0], examples[1], examples[0]])
    assert len(read_search_results(path)) == 3
    with pytest.raises(ValueError, match=r"lines 35 and 37 are the same record 'RSN6_El Centro Array #9'"):
        suite_entries("peer/_SearchResults.csv", tmp_path)


@pytest.mark.parametrize("drop", ["Scale Factor", "Record Sequence Number", "Horizontal-2 Acc. Filename"])
def test_a_missing_column_is_named_with_the_file_and_line(tmp_path, examples, drop):
    path = write_download(tmp_path, examples[:3], header=[c for c in FULL_HEADER if c != drop])
    with pytest.raises(ValueError, match=rf"_SearchResults.csv: line 34: .* has no column '{drop}'; its columns"):
        read_search_results(path)


@pytest.mark.parametrize("column, value, what", [("Scale Factor", "1.2x", "a number"),
                                                 ("Scale Factor", "0", "a finite number > 0"),
                                                 ("Scale Factor", "-", "a number"),
                                                 ("Record Sequence Number", "RSN6", "a whole number"),
                                                 ("Record Sequence Number", "6.5", "a whole number"),
                                                 ("Year", "19x4", "a whole number"),
                                                 ("Lowest Useable Frequency (Hz)", "low", "a number")])
def test_a_bad_number_is_named_with_the_file_line_and_column(tmp_path, examples, column, value, what):
    record = PeerDownloadRecord(**{**examples[2].__dict__, "fields": {column: value}})
    path = write_download(tmp_path, [examples[0], record])
    message = rf"_SearchResults.csv: line 36: column '{re.escape(column)}': '{value}' is not {what}$"
    with pytest.raises(ValueError, match=message):
        read_search_results(path)


def test_optional_numbers_written_as_a_dash_are_none(tmp_path, examples):
    record = PeerDownloadRecord(**{**examples[2].__dict__,
                                   "fields": {"Year": "-", "Lowest Useable Frequency (Hz)": "-"}})
    (read,) = read_search_results(write_download(tmp_path, [record]))
    assert read.year is None and read.lowest_usable_frequency_hz is None


def test_no_table_no_rows_no_file_and_a_short_row_are_refused(tmp_path, examples):
    path = write_download(tmp_path, examples[:2])
    text = path.read_text()
    (tmp_path / "none.csv").write_text(text.replace("Metadata of Selected Records", "Metadata"))
    with pytest.raises(ValueError, match=r"none.csv: no '-- Summary of Metadata of Selected Records --' table"):
        read_search_results(tmp_path / "none.csv")
    lines = text.splitlines()
    title = lines.index(" -- Summary of Metadata of Selected Records --")
    (tmp_path / "empty.csv").write_text("\n".join(lines[:title + 2] + [""] + lines[title + 4:]))
    with pytest.raises(ValueError, match=r"empty.csv: line 35: .* table has no rows"):
        read_search_results(tmp_path / "empty.csv")
    (tmp_path / "short.csv").write_text("\n".join(lines[:title + 2] + [lines[title + 2].rsplit(",", 4)[0]]))
    with pytest.raises(ValueError, match=r"short.csv: line 35: column 'Horizontal-1 Acc. Filename': the row has "
                                         r"18 field\(s\), the header 22"):
        read_search_results(tmp_path / "short.csv")
    with pytest.raises(ValueError, match=r"nowhere.csv: no such file"):
        read_search_results(tmp_path / "nowhere.csv")
    with pytest.raises(ValueError, match=r"nowhere/_SearchResults.csv: no such file"):
        suite_entries("nowhere/_SearchResults.csv", tmp_path)


def test_every_at2_file_of_the_download_is_read_with_its_dt_npts_values_and_direction(download, examples):
    seen_line4, seen_newline, seen_labels = set(), set(), set()
    for record in examples:
        lengths = set()
        for component in record.components.values():
            path = download / "peer" / record.file(component)
            dt, values, units = read_peer(path)
            assert (dt, values.size, units.text, units.quantity) == (record.dt, component.npts, "G", "acceleration")
            assert np.allclose(values, component.acc, rtol=5e-7, atol=1e-15), path.name
            assert peer_azimuth(path) == DIRECTIONS[component.label], path.name
            seen_line4.add(component.line4)
            seen_newline.add(component.newline)
            seen_labels.add(component.label)
            lengths.add(component.npts)
        assert len(lengths) == 1 or record.rsn in (6, 1158)  # one sample apart, and hundreds apart
    assert seen_line4 == set(LINE4) and seen_newline == {"\r\n", "\n"} and seen_labels == set(DIRECTIONS)
    # H1 north in one record, east in the next
    assert [peer_azimuth(download / "peer" / r.file(r.h1)) for r in examples[6:8]] == [0.0, 90.0]


@pytest.mark.parametrize("label, direction", [("N76W", 284.0), ("S14W", 194.0), ("N17E", 17.0), ("S64E", 116.0),
                                              ("N0E", 0.0), ("S90W", 270.0), ("n45e", 45.0), ("N 30 W", 330.0),
                                              ("52", 52.0), ("NA", None), ("L", None), ("T", None),
                                              ("DWN", "vertical"), ("V1", "vertical"), ("N95W", None)])
def test_bearings_and_labels_give_the_direction(tmp_path, label, direction):
    record = example_records()[0]
    component = Component(np.zeros(7), label, "X", newline="\n")
    path = tmp_path / "r.AT2"
    path.write_text(at2_text(record, component))
    assert peer_azimuth(path) == direction


def test_a_dwn_vertical_is_read_as_written(download, examples):
    """read_peer does not turn a 'DWN' vertical: its samples come as the file holds them (PEER states no
    polarity for 'DWN' that this project could confirm; a vertical's user decides, see the report)."""
    record = examples[1]
    dt, values, _ = read_peer(download / "peer" / record.file(record.v))
    assert record.v.label == "DWN" and np.allclose(values, record.v.acc, rtol=5e-7, atol=1e-15)
