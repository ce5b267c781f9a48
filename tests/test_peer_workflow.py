"""PEER downloads through the workflow: a suite of twelve pairs built like real NGA-West2 ones, and a
fourteen-record download with its verticals scaled by PEER's factors (slow: each starts Snakemake)."""

import warnings

import numpy as np
import pytest
import xarray as xr
import yaml
from conftest import copy_project, snakemake
from peer_download import Component, PeerDownloadRecord, example_records, write_download

from dccss import cli

pytestmark = pytest.mark.slow


def twelve_pairs():
    """Eleven records of the example download (bearings, N/E with H1 north then east, L/T, NA, CRLF and LF,
    every line-4 form, components one sample and hundreds apart) without their verticals, and a pair
    recorded 85 degrees apart (azimuths 260 and 345) whose components differ by 76 samples."""
    records = [PeerDownloadRecord(**{**vars(r), "v": None}) for r in example_records()[:11]]
    rng = np.random.default_rng(7)
    t = 0.01 * np.arange(600)
    base = np.sin(2 * np.pi * t / 1.7) * np.exp(-((t - 2.5) / 1.5) ** 2)
    h1 = Component(0.3 * base + 0.01 * rng.standard_normal(600), "260", "260", "spaced", "\r\n")
    h2 = Component((0.2 * np.roll(base, 40) + 0.01 * rng.standard_normal(600))[:524], "345", "345", "no comma", "\n")
    records.append(PeerDownloadRecord(848, "Landers", "Coolwater", 1.7, 0.01, h1, h2, year=1992, date="6/28/1992",
                                      code="LANDERS_CLW"))
    return records


STUDY = {"study": {"name": "peer"}, "prototype": "DFP1", "dt": 0.02, "models": ["compliant"],
         "excitation": {"kind": "record", "scale": "peer"}, "structure": {"friction": 0.05}, "chunk_size": "auto",
         "sweep": {"record": [{"peer": "downloads/_SearchResults.csv"}]}}


def _run(tmp_path, records, study, *targets):
    work = copy_project(tmp_path)
    csv = write_download(work / "config/studies/downloads", records)
    (work / "config/studies/peer.yaml").write_text(yaml.safe_dump(study))
    run = snakemake(work, *targets, "--configfile", "config/studies/peer.yaml")
    return work, csv, run


def test_twelve_pairs_as_peer_gives_them_run_and_each_equals_its_record_alone(tmp_path):
    records = twelve_pairs()
    work, csv, run = _run(tmp_path, records, STUDY, "results/studies/peer/peer.nc")  # drawn: the fourteen records
    assert run.returncode == 0, run.stderr[-3000:]
    log = run.stderr + "".join(p.read_text() for p in (work / "logs").rglob("*.log"))
    assert "85 degrees apart" in log and "run over the" in log  # the skewed and the uneven pairs say so
    ds = xr.open_dataset(work / "results/studies/peer/peer.nc")
    assert ds.sizes["record"] == 12
    assert np.array_equal(ds["record_scale"].values, [r.scale_factor for r in records])
    for record, name in zip(records, ds["record"].values):
        case = {"prototype": "DFP1", "dt": 0.02, "model": "compliant", "structure": {"friction": 0.05},
                "excitation": {"kind": "record", "scale": record.scale_factor,
                               "file": [f"downloads/{record.file(record.h1)}", f"downloads/{record.file(record.h2)}"]}}
        path = work / "config/studies" / f"{name}.yaml"
        path.write_text(yaml.safe_dump(case))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert cli.main(["run", str(path), "-o", str(tmp_path / f"{name}.nc")]) == 0
        alone = xr.open_dataset(tmp_path / f"{name}.nc")
        mine = ds.sel(record=name, model="compliant")
        assert float(mine["stroke_max_abs"]) == alone.attrs["structure_stroke_max_abs_m"], name
        assert float(mine["theta2_max_abs"]) == pytest.approx(float(np.nanmax(alone["tilt"].values)), abs=1e-12)


def test_a_fourteen_record_download_with_verticals_runs_scaled_by_peers_factors(tmp_path):
    """Crossed as a design study crosses them: the download's pairs with their verticals, the friction's bounds,
    both models, the records in a few jobs; the results combined and every figure drawn."""
    records = example_records()
    study = {**STUDY, "models": ["compliant", "stick_slip"], "record_jobs": 4,
             "structure": {"friction": 0.05, "property": {"lower": 0.8, "upper": 1.3}},
             "sweep": {"record": [{"peer": "downloads/_SearchResults.csv", "vertical": True}],
                       "property": ["lower", "nominal", "upper"]},
             "histories": [{"record": "RSN6_El_Centro_Array__9", "property": "upper"}]}
    work, csv, run = _run(tmp_path, records, study)
    assert run.returncode == 0, run.stderr[-3000:]
    ds = xr.open_dataset(work / "results/studies/peer/peer.nc")
    assert ds.sizes["record"] == 14 and ds.sizes["property"] == 3 and ds.sizes["model"] == 2
    assert np.array_equal(ds["record_scale"].values, [r.scale_factor for r in records])
    assert np.all(ds["normal_ratio_min"].sel(model="compliant").values < 1.0)
    assert "records_uplift" in ds and "normal_ratio_min_suite" in ds
    assert np.array_equal(ds["stroke_max_abs_envelope"].values, ds["stroke_max_abs"].max("property").values)
    # the structure's summaries do not depend on the pad's model
    assert np.array_equal(ds["stroke_max_abs"].sel(model="compliant").values,
                          ds["stroke_max_abs"].sel(model="stick_slip").values, equal_nan=True)
    history = xr.open_dataset(work / "results/studies/peer/histories/stick_slip_0.nc")
    assert "vertical_acceleration" in history and history.attrs["structure_property_factor"] == 1.3
    for name in ("maps.png", "histories.png"):
        assert (work / "figures/studies/peer" / name).is_file(), name
    # a file the table lists but the folder lacks: named with its record, nothing run
    (csv.parent / records[5].file(records[5].v)).unlink()
    (work / "results").rename(work / "old_results")
    run = snakemake(work, "--configfile", "config/studies/peer.yaml")
    assert run.returncode != 0
    assert f"RSN1063_Rinaldi Receiving Sta: {records[5].file(records[5].v)} (vertical)" in run.stderr
    assert not (work / "results/studies/peer/peer.nc").exists()
