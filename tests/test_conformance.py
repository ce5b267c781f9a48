"""Every netCDF file the workflow writes passes the IOOS compliance checker (CF-1.11) with no
error, and reads back in plain netCDF4 and in xarray with its names and units."""

import json
import subprocess
import sys
from pathlib import Path

import netCDF4
import numpy as np
import pytest
import xarray as xr

from dccss.results import TIME, TIME_UNITS, load

CHECKER = Path(sys.executable).with_name("cchecker.py")


def check(paths: list[Path], out: Path) -> dict:
    """The checker's findings for each file, by priority: {path: {priority: [message, ...]}} (one
    checker process for all the files)."""
    run = subprocess.run([sys.executable, str(CHECKER), "-t", "cf:1.11", "-f", "json_new", "-o", str(out),
                          *map(str, paths)], capture_output=True, text=True, timeout=600)
    reports = json.loads(out.read_text())
    assert sorted(reports) == sorted(map(str, paths)), run.stderr[-2000:]
    return {loc: {level: [f"{item['name']}: {m}" for item in report["cf:1.11"].get(level, [])
                          for m in item.get("msgs") or []]
                  for level in ("high_priorities", "medium_priorities", "low_priorities")}
            for loc, report in reports.items()}


def high_and_medium(findings: dict) -> dict:
    """The files with high- or medium-priority findings, and those findings."""
    return {name: {level: found[level] for level in ("high_priorities", "medium_priorities") if found[level]}
            for name, found in findings.items() if found["high_priorities"] or found["medium_priorities"]}


def test_every_file_passes_the_cf_checker(reproduction, tmp_path):
    files = sorted((reproduction / "results").rglob("*.nc"))
    assert len(files) == 20
    assert high_and_medium(check(files, tmp_path / "report.json")) == {}


def test_study_files_pass_the_cf_checker(shipped_study, tmp_path):
    work = shipped_study("ground_motion")
    files = sorted((work / "results/studies").rglob("*.nc"))
    assert len(files) == 2 * 1 + 1 + 4  # chunks (one of 6 cases per model), the combined file, the histories
    findings = check(files, tmp_path / "report.json")
    assert {name: found["high_priorities"] for name, found in findings.items() if found["high_priorities"]} == {}


@pytest.mark.parametrize("name", ["cases/as_reported/DFP2_stick_slip_dt0.01.nc", "breakaway/DFP1_unsigned.nc"])
def test_files_read_back_with_names_and_units(reproduction, name):
    path = reproduction / "results" / name
    with netCDF4.Dataset(path) as nc:
        assert nc.Conventions == "CF-1.11"
        for var in nc.variables.values():
            if var.dtype != str:
                assert hasattr(var, "units") and hasattr(var, "long_name"), var.name
    ds = load(path)
    for var in ds.variables.values():
        if var.dtype.kind in "fi":
            assert "units" in var.attrs and "long_name" in var.attrs
    if TIME in ds.dims:
        assert ds[TIME].attrs["units"] == TIME_UNITS and ds[TIME].dtype.kind == "f"  # seconds, not dates
        assert ds[TIME].values[0] == 0.0


def test_plain_xarray_reads_time_as_float_seconds(reproduction):
    """No decode_times=False needed: t is float seconds, and every other variable keeps its dtype."""
    with xr.open_dataset(reproduction / "results/cases/as_reported/DFP1_stick_slip_dt0.001.nc") as ds:
        assert ds["t"].dtype == np.float64 and ds["t"].attrs["units"] == "s"
        assert float(ds["t"][0]) == 0.0 and float(ds["t"][-1]) == pytest.approx(1.0)
        assert np.allclose(np.diff(ds["t"].values), 0.001)
        assert not any(v.dtype.kind in "mM" for v in ds.variables.values())  # no datetimes or timedeltas


def test_the_isolated_structure_study_files_pass_the_cf_checker(shipped_study, tmp_path):
    work = shipped_study("isolated_structure")
    files = sorted((work / "results/studies").rglob("*.nc"))
    assert len(files) == 2 * 1 + 1 + 4  # chunks (one of 10 cases per model), the combined file, the histories
    assert high_and_medium(check(files, tmp_path / "report.json")) == {}
