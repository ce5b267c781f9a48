"""Record pairs read as seismologists mean them: each component's azimuth from its PEER header, one
right-handed frame (x east, y north) whatever the order of the files, and a rotation."""

import numpy as np
import pytest
from conftest import ROOT

from dccss.case import CaseError, case_from
from dccss.records import RecordPair, peer_azimuth, read_at2
from dccss.studies import Study, combine, run_chunk

SOURCE = ROOT / "config/studies/records"


def _peer(path, azimuth_field, values, dt=0.01):
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD",
             f"Imperial Valley-02, 5/19/1940, El Centro Array #9, {azimuth_field}",
             "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS= {len(values)}, DT= {dt:.4f} SEC"]
    lines += ["  ".join(f"{v:.7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def station(tmp_path):
    _, a = read_at2(SOURCE / "synthetic.AT2")
    _, b = read_at2(SOURCE / "synthetic_y.AT2")
    return (_peer(tmp_path / "ELC180.AT2", "180", a[:600]), _peer(tmp_path / "ELC270.AT2", "270", b[:600]))


@pytest.mark.parametrize("field, azimuth", [("180", 180.0), ("000", 0.0), ("090", 90.0),
                                            ("270 (USGS STATION 117)", 270.0), ("E", 90.0), ("HNN", 0.0),
                                            ("UP", "vertical"), ("HNZ", "vertical"), ("UD", "vertical"),
                                            ("NS", 0.0), ("EW", 90.0),
                                            ("PGA 0.35 g", None)])
def test_the_component_azimuth_is_read_from_line_2(tmp_path, field, azimuth):
    assert peer_azimuth(_peer(tmp_path / "r.AT2", field, np.zeros(10))) == azimuth


def test_a_pair_in_either_order_gives_the_same_motion_east_and_north(station):
    south, west = station
    one = RecordPair.from_files([south, west])
    other = RecordPair.from_files([west, south])
    assert np.array_equal(one.displacement_samples, other.displacement_samples)
    # 180 points south, 270 west: east is minus the 270 component, north minus the 180 one
    assert np.allclose(one.displacement_samples[:, 0], -one.y.displacement_samples, rtol=0, atol=1e-15)
    assert np.allclose(one.displacement_samples[:, 1], -one.x.displacement_samples, rtol=0, atol=1e-15)
    assert "x east, y north" in one.attrs()["record_orientation"]
    # without azimuths the files' order stands, and the attribute says so
    plain = RecordPair.from_files([SOURCE / "synthetic.AT2", SOURCE / "synthetic_y.AT2"])
    assert np.array_equal(plain.displacement_samples[:, 0], plain.x.displacement_samples)
    assert plain.attrs()["record_orientation"].startswith("file order")


def test_rotation_turns_the_pair(station):
    pair = RecordPair.from_files(station)
    turned = RecordPair.from_files(station, rotation=90.0)
    x, y = pair.displacement_samples.T
    assert np.allclose(turned.displacement_samples, np.column_stack([-y, x]), rtol=0, atol=1e-15)
    t = pair.time[:, None]
    batch = pair.displacement(t, rotation=np.array([0.0, 90.0, 30.0]))
    assert batch.shape == (pair.npts, 3, 2)
    assert np.allclose(batch[:, 1], turned.displacement(pair.time), atol=1e-15)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    assert np.allclose(batch[:, 2], np.column_stack([c * x - s * y, s * x + c * y]), atol=1e-15)
    # the structure's ground acceleration turns with it
    g, base = turned.ground_acceleration(), pair.ground_acceleration()
    assert np.allclose(g.a0, np.column_stack([-base.a0[:, 1], base.a0[:, 0]]), atol=1e-15)


def test_nearly_parallel_or_vertical_components_are_refused(tmp_path, station):
    _, a = read_at2(SOURCE / "synthetic.AT2")
    odd = _peer(tmp_path / "ELC200.AT2", "200", a[:600] * 0.5)
    with pytest.raises(ValueError, match="azimuths 180 and 200 degrees put their axes 20 degrees apart, closer to "
                                         "parallel than 30 degrees"):
        RecordPair.from_files([station[0], odd])
    up = _peer(tmp_path / "ELCUP.AT2", "UP", a[:600] * 0.3)
    with pytest.raises(ValueError, match="is a vertical component"):
        RecordPair.from_files([station[0], up])


def test_rotation_in_a_case_and_as_a_sweep_axis(tmp_path, station):
    case = {"prototype": "DFP1", "dt": 0.01, "model": "compliant",
            "excitation": {"kind": "record", "file": ["ELC180.AT2", "ELC270.AT2"], "rotation": 45.0}}
    assert case_from(case, tmp_path).excitation.rotation == 45.0
    with pytest.raises(CaseError, match="excitation.rotation: turns a record pair"):
        case_from({**case, "excitation": {"kind": "record", "file": "ELC180.AT2", "rotation": 45.0}}, tmp_path)
    study = Study.from_config({"study": {"name": "turn"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
                               "excitation": {"kind": "record", "file": ["ELC180.AT2", "ELC270.AT2"]},
                               "sweep": {"rotation": [0.0, 90.0, 180.0]}}, tmp_path)
    ds = combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})
    assert ds["rotation"].attrs["units"] == "degree"
    tilt = ds["theta2_max_abs"].sel(model="compliant").values  # the tilt does not care which way the pair faces
    assert np.allclose(tilt, tilt[0], rtol=1e-9)
    t = study.grid.times(0.01)
    ground = study.grid.ground_motion(np.arange(3), t)
    assert np.allclose(ground[:, 2], -ground[:, 0], atol=1e-15)


def test_a_placed_pairs_attributes_name_each_file_by_its_place_not_x_and_y(station):
    """Before, the first file's attributes were called record_x_* although, placed by the azimuths, x (east)
    is minus the 270 file (the second): its peaks were printed as x's."""
    south, west = station
    attrs = RecordPair.from_files([south, west]).attrs()
    assert attrs["record_1_source"] == "ELC180.AT2" and attrs["record_1_azimuth_deg"] == 180.0
    assert attrs["record_2_source"] == "ELC270.AT2" and attrs["record_2_azimuth_deg"] == 270.0
    assert not any(k.startswith(("record_x_", "record_y_")) for k in attrs)
