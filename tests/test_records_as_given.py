"""Records as PEER gives them: pairs of different lengths, components not at right angles, the vertical
component (with uplift), per-record settings and PEER downloads as suites."""

import subprocess
import sys
import warnings

import numpy as np
import pytest
import yaml
from peer_download import example_records, write_download

from dccss import cli
from dccss.case import case_from, geometry_from
from dccss.checks import CaseError
from dccss.mechanics.structure import G
from dccss.records import PairWarning, Record, RecordPair, RecordWarning, read_at2, write_peer
from dccss.simulation import UpliftError
from dccss.studies import Study, combine, run_chunk

RECORDS = "config/studies/records"


def _accelerations():
    _, a = read_at2(f"{RECORDS}/synthetic.AT2")
    _, b = read_at2(f"{RECORDS}/synthetic_y.AT2")
    return a, b


def _write(folder, name, values, label, dt=0.01, newline="\n"):
    path = folder / name
    write_peer(path, dt, values, "G", title=f"SYN 2026, STATION, {label}")
    if newline != "\n":
        path.write_bytes(path.read_bytes().replace(b"\n", newline.encode()))
    return path


@pytest.fixture
def uneven(tmp_path):
    """A pair of 1990 and 2000 samples (azimuths 0 and 90) and a vertical of 1995, as PEER distributes them."""
    a, b = _accelerations()
    v = 0.4 * np.roll(a, 300)[:1995]
    return (_write(tmp_path, "H1.AT2", a[:1990], "0"), _write(tmp_path, "H2.AT2", b, "90"),
            _write(tmp_path, "V.AT2", v, "UP"))


def _case(tmp_path, excitation, **more):
    return case_from({"prototype": "DFP1", "excitation": excitation, "dt": 0.01, "model": "compliant",
                      "structure": {"friction": 0.04}, **more}, tmp_path)


# --- pairs of different lengths ------------------------------------------------------------------------------
def test_the_common_span_equals_a_manual_window_over_it_bit_for_bit(uneven):
    h1, h2, _ = uneven
    with pytest.warns(PairWarning, match=r"run over the 19.89 s all cover, 0 to 19.89 s \(pair_span: common\); "
                                         r"dropped 'H2.AT2': 0.1 s \(largest \|a\| 0.\d+ g\)"):
        pair = RecordPair.from_files([h1, h2], scale=1.5)
    manual = RecordPair(Record.from_file(h1, scale=1.5, window=(0.0, 19.89)),
                        Record.from_file(h2, scale=1.5, window=(0.0, 19.89)), (0.0, 90.0))
    for name in ("displacement_samples", "velocity_samples", "time"):
        assert np.array_equal(getattr(pair, name), getattr(manual, name))
    assert np.array_equal(pair.ground_acceleration().a0, manual.ground_acceleration().a0)
    attrs = pair.attrs()
    assert attrs["record_2_dropped_s"] == pytest.approx(0.1) and attrs["record_1_dropped_s"] == 0.0
    _, b = _accelerations()
    assert attrs["record_2_dropped_max_abs_acceleration_m_per_s2"] == pytest.approx(1.5 * G * np.max(np.abs(b[1990:])))
    assert attrs["record_2_pair_span"] == "common"


def test_longest_equals_the_shorter_file_padded_with_zeros_by_hand(uneven, tmp_path):
    h1, h2, _ = uneven
    a, _ = _accelerations()
    padded = _write(tmp_path / "..", "H1_padded.AT2", np.concatenate([a[:1990], np.zeros(10)]), "0")
    with pytest.warns(PairWarning, match=r"padded with zero acceleration to the longest, 0 to 19.99 s "
                                         r"\(pair_span: longest\): 'H1.AT2': 0.1 s"):
        pair = RecordPair.from_files([h1, h2], pair_span="longest")
    by_hand = RecordPair.from_files([padded, h2])
    for name in ("displacement_samples", "velocity_samples", "time"):
        assert np.array_equal(getattr(pair, name), getattr(by_hand, name))
    assert pair.attrs()["record_1_padded_s"] == pytest.approx(0.1)


def test_a_study_window_outside_the_common_span_and_longest_on_a_displacement_are_refused(uneven, tmp_path):
    h1, h2, _ = uneven
    with pytest.raises(CaseError, match=r"excitation.window: record pair: the window \(0.0, 19.95\) s lies outside "
                                        r"the time all components cover, 0.0 to 19.89 s"):
        _case(tmp_path, {"kind": "record", "file": ["H1.AT2", "H2.AT2"], "window": [0.0, 19.95]})
    with pytest.raises(CaseError,
                       match=r"excitation.pair_span: must be one of \['common', 'longest'\], got 'shortest'"):
        _case(tmp_path, {"kind": "record", "file": ["H1.AT2", "H2.AT2"], "pair_span": "shortest"})
    d = tmp_path / "d"
    d.mkdir()
    for name, n in (("x.DT2", 300), ("y.DT2", 290)):
        write_peer(d / name, 0.01, np.sin(np.arange(n) / 30), "CM")
    with pytest.raises(ValueError, match=r"pads with zero acceleration, but \['x.DT2', 'y.DT2'\] hold"):
        RecordPair.from_files([d / "x.DT2", d / "y.DT2"], pair_span="longest")


# --- components not at right angles ---------------------------------------------------------------------------
def test_components_85_degrees_apart_give_the_motion_back_and_the_tilt_of_the_orthogonal_pair():
    """Two sensors at azimuths 260 and 345 read the projections of one known motion (east, north) on their
    axes; resolved, they give that motion back to 1e-12, and the pad's tilt is the orthogonal pair's."""
    a, b = _accelerations()
    t = 0.01 * np.arange(a.size)
    east, north = G * a, G * b  # m/s²
    readings = []
    for az in (260.0, 345.0):
        r = np.radians(az)
        readings.append(Record(t, east * np.sin(r) + north * np.cos(r), source=f"az{az:g}"))
    with pytest.warns(PairWarning, match="azimuths 260 and 345 degrees are 85 degrees apart, not at right angles"):
        skew = RecordPair(*readings, azimuths=(260.0, 345.0))
    straight = RecordPair(Record(t, east, source="east"), Record(t, north, source="north"), azimuths=(90.0, 0.0))
    for name in ("displacement_samples", "velocity_samples"):
        got, want = getattr(skew, name), getattr(straight, name)
        assert np.max(np.abs(got - want)) <= 1e-12 * np.max(np.abs(want))
    assert "resolved from axes 85 degrees apart" in skew.orientation
    from dccss.simulation import simulate

    with pytest.warns(UserWarning, match=r"dt = 0.02 s does not divide the excitation's duration \(19.99 s\)"):
        tilt = [simulate(geometry_from("DFP1"), p, model="compliant", dt=0.02)["tilt"].values for p in (skew, straight)]
    assert np.max(np.abs(tilt[0] - tilt[1])) < 1e-9 and np.max(tilt[1]) > 1.0


# --- the vertical component -----------------------------------------------------------------------------------
def test_a_vertical_is_processed_with_its_horizontals_and_scaled_as_they_are(uneven, tmp_path):
    with pytest.warns(PairWarning, match="'V.AT2': 0.05 s"):
        case = _case(tmp_path, {"kind": "record", "file": ["H1.AT2", "H2.AT2"], "vertical": "V.AT2", "scale": 2.0})
    excitation = case.excitation
    a, _ = _accelerations()
    alone = Record.from_file(uneven[2], scale=2.0, window=(0.0, 19.89))
    assert np.array_equal(excitation.vertical.acceleration, alone.acceleration)
    assert np.array_equal(excitation.vertical.time, excitation.excitation.time)
    ground = excitation.ground_acceleration()
    assert np.array_equal(ground.v0, alone.acceleration[:-1])
    attrs = excitation.attrs()
    assert attrs["vertical_form"] == "record" and attrs["record_vertical_source"] == "V.AT2"
    assert attrs["vertical_pga_m_per_s2"] == pytest.approx(alone.pga)
    assert attrs["record_vertical_scale"] == 2.0


def test_a_down_positive_vertical_is_negated(tmp_path):
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "UP.AT2", 0.3 * a, "UP")
    _write(tmp_path, "DWN.AT2", -0.3 * a, "DWN")
    up = _case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "UP.AT2"}).excitation
    down = _case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "DWN.AT2"}).excitation
    assert np.array_equal(up.vertical.acceleration, down.vertical.acceleration)
    assert "down-positive" in down.attrs()["record_vertical_sign"]


@pytest.mark.slow  # dccss run in a process: 2 s
def test_a_down_positive_vertical_is_said_in_the_log_and_the_run_summary(tmp_path):
    """Negating a DWN vertical is said: a RecordWarning, which dccss run prints (it was done without a word)."""
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "DWN.AT2", -0.3 * a, "DWN")
    with pytest.warns(RecordWarning, match=r"record 'DWN.AT2': the vertical component's channel is down-positive "
                                           r"\(DWN on line 2\): negated, so that up is positive"):
        _case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "DWN.AT2"})
    (tmp_path / "case.yaml").write_text(yaml.safe_dump({
        "prototype": "DFP1", "excitation": {"kind": "record", "file": "H.AT2", "vertical": "DWN.AT2"}, "dt": 0.01,
        "model": "compliant", "structure": {"friction": 0.04}}))
    run = subprocess.run([sys.executable, "-m", "dccss", "run", str(tmp_path / "case.yaml"), "-o",
                          str(tmp_path / "out.nc"), "-q"], capture_output=True, text=True, cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    assert "dccss: warning: record 'DWN.AT2': the vertical component's channel is down-positive" in run.stderr


def test_a_suites_combined_results_carry_each_records_vertical_sign(tmp_path):
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "UP.AT2", 0.3 * a, "UP")
    _write(tmp_path, "DWN.AT2", -0.3 * a, "DWN")
    config = {"study": {"name": "signs"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record", "window": [0.0, 4.0]}, "structure": {"friction": 0.04},
              "sweep": {"record": [{"file": "H.AT2", "vertical": "UP.AT2", "name": "up"},
                                   {"file": "H.AT2", "vertical": "DWN.AT2", "name": "down"}]}}
    with pytest.warns(RecordWarning, match="down-positive"):
        study = Study.from_config(config, tmp_path)
    ds = combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})
    assert ds["record_vertical_sign"].sel(record="up") == 1 and ds["record_vertical_sign"].sel(record="down") == -1
    assert "DWN" in ds["record_vertical_sign"].attrs["long_name"]
    # the same motion either way
    assert ds["stroke_max_abs"].sel(record="up").item() == ds["stroke_max_abs"].sel(record="down").item()


def test_a_vertical_without_a_structure_is_refused(tmp_path):
    """Under an imposed ground displacement the vertical acts on nothing: refused, not ignored and recorded."""
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "UP.AT2", 0.3 * a, "UP")
    message = r"excitation.vertical: a vertical ground acceleration acts on an isolated structure's normal force"
    with pytest.raises(CaseError, match=message):
        case_from({"prototype": "DFP1", "excitation": {"kind": "record", "file": "H.AT2", "vertical": "UP.AT2"},
                   "dt": 0.01, "model": "compliant"}, tmp_path)
    with pytest.raises(CaseError, match=message):
        case_from({"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.1, "omega": 3.0, "duration": 4.0,
                                                       "vertical": {"kind": "sine", "amplitude": 2.0, "omega": 9.0}},
                   "dt": 0.01, "model": "compliant"}, tmp_path)
    config = {"study": {"name": "v"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record"}, "sweep": {"record": [{"file": "H.AT2", "vertical": "UP.AT2"}]}}
    with pytest.raises(CaseError, match=r"sweep.record: the records' vertical components act on an isolated "
                                        r"structure's normal force \(structure\)"):
        Study.from_config(config, tmp_path)


def test_a_bad_vertical_is_named_as_the_vertical(tmp_path):
    """A vertical that is missing or does not join its horizontal: excitation.vertical, 'its vertical component'
    (they said excitation.file and 'record pair')."""
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "V2.AT2", 0.3 * a[::2], "UP", dt=0.02)
    _write(tmp_path, "V.AT2", 0.3 * a, "UP")
    with pytest.raises(CaseError, match=r"^excitation.vertical: the vertical component: record file '.*nothere.AT2': "
                                        r"does not exist"):
        _case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "nothere.AT2"})
    with pytest.raises(CaseError, match=r"^excitation.vertical: record and its vertical component: the components "
                                        r"must share their step"):
        _case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "V2.AT2"})
    with pytest.raises(CaseError, match=r"^excitation.vertical: record '.*H.AT2': line 2 names a horizontal"):
        _case(tmp_path, {"kind": "record", "file": "V.AT2", "vertical": "H.AT2"})


def test_a_negative_scale_mirrors_the_horizontal_motion_not_the_vertical(tmp_path):
    """scale -1.5: the horizontal accelerations negated, the vertical that of +1.5 (gravity keeps its direction:
    it flipped the vertical too, unsaid), the structure's stroke mirrored; in a study's scale axis the same."""
    a, _ = _accelerations()
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "UP.AT2", 0.6 * np.roll(a, 200), "UP")
    plus, minus = (_case(tmp_path, {"kind": "record", "file": "H.AT2", "vertical": "UP.AT2", "scale": f})
                   for f in (1.5, -1.5))
    g_plus, g_minus = plus.excitation.ground_acceleration(), minus.excitation.ground_acceleration()
    assert np.array_equal(g_minus.a0, -g_plus.a0) and np.array_equal(g_minus.v0, g_plus.v0)
    assert minus.excitation.attrs()["record_vertical_scale"] == 1.5
    up, down = plus.run(), minus.run()
    assert np.array_equal(down["stroke"].values, -up["stroke"].values)
    config = {"study": {"name": "mirror"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record", "file": "H.AT2", "vertical": "UP.AT2"}, "structure": {"friction": 0.04},
              "sweep": {"scale": [-1.5, 1.5]}}
    study = Study.from_config(config, tmp_path)
    ds = combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})
    peaks = ds["stroke_max_abs"].sel(model="compliant").values
    assert peaks[0] == peaks[1] and ds["normal_ratio_min"].sel(model="compliant").values[0] == \
        ds["normal_ratio_min"].sel(model="compliant").values[1]


def test_a_vertical_of_zeros_gives_todays_results_bit_for_bit(tmp_path):
    a, b = _accelerations()
    _write(tmp_path, "X.AT2", a, "90")
    _write(tmp_path, "Y.AT2", b, "0")
    _write(tmp_path, "Z.AT2", 0 * a, "UP")
    for file in ("X.AT2", ["X.AT2", "Y.AT2"]):
        plain = _case(tmp_path, {"kind": "record", "file": file, "scale": 2.0}).run()
        with pytest.warns(RecordWarning, match=r"record 'Z.AT2': the peak ground acceleration is 0 g"):
            zero = _case(tmp_path, {"kind": "record", "file": file, "scale": 2.0, "vertical": "Z.AT2"}).run()
        for name in plain.data_vars:
            assert np.array_equal(plain[name].values, zero[name].values, equal_nan=True), name
        assert np.all(zero["normal_ratio"].values == 1.0) and "uplift_at_s" not in zero.attrs


def _lifting(tmp_path):
    """A horizontal record and a vertical that passes -g once, around t = 6 s (0.95 s)."""
    a, _ = _accelerations()
    t = np.linspace(0.0, 20.0, 2000)
    v = 1.3 * np.sin(2 * t) * np.exp(-((t - 6) / 2) ** 2)
    _write(tmp_path, "H.AT2", a, "0")
    _write(tmp_path, "V.AT2", v, "UP")
    return {"kind": "record", "file": "H.AT2", "vertical": "V.AT2", "scale": 1.5}


def test_uplift_is_flagged_under_continue_and_never_an_ordinary_result_otherwise(tmp_path):
    excitation = _lifting(tmp_path)
    with pytest.warns(UserWarning, match=r"lifts off its device at t = 5\.\d+ s .*capacity: continue"):
        flagged = _case(tmp_path, excitation).run()
    start, duration = flagged.attrs["uplift_at_s"], flagged.attrs["uplift_duration_s"]
    n = flagged["normal_ratio"].values
    t = flagged["t"].values
    assert flagged.attrs["uplift_count"] == 1 and 0.5 < duration < 1.5
    assert np.array_equal(flagged["uplift"].values == 1, n <= 0.0)
    assert t[n <= 0].min() >= start and t[n <= 0].max() <= start + duration
    assert np.allclose(flagged["vertical_acceleration"].values, (n - 1) * G, rtol=0, atol=1e-12)
    stopped = _case(tmp_path, excitation, capacity="stop").run()
    assert stopped.attrs["stopped_by"] == "uplift" and stopped["t"].values[-1] < start
    assert stopped["t"].values[-1] >= start - 0.01
    marked = _case(tmp_path, excitation, capacity="error", on_failure="mark").run()
    assert marked.attrs["failed"] == 1 and marked.attrs["failure_kind"] == "uplift"
    assert marked.attrs["failure_time_s"] == start and marked["t"].values[-1] < start
    with pytest.raises(UpliftError, match=r"lifts off its device at t = 5\.\d+ s"):
        _case(tmp_path, excitation, capacity="error").run()


def test_dccss_run_prints_the_vertical_peak_and_the_smallest_normal_force(tmp_path, capsys):
    excitation = _lifting(tmp_path)
    case = tmp_path / "case.yaml"
    case.write_text(yaml.safe_dump({"prototype": "DFP1", "excitation": excitation, "dt": 0.01, "model": "compliant",
                                    "structure": {"friction": 0.04}, "capacity": "error"}))
    assert cli.main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 4
    assert "lifts off its device" in capsys.readouterr().err
    case.write_text(case.read_text().replace("capacity: error", "capacity: continue"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert cli.main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 0
    out = capsys.readouterr().out
    assert "vertical PGA = 1.84 g, smallest N/W = -0.841; lifts off at t = 5.0" in out


def test_a_vertical_sine_and_its_errors(tmp_path):
    sine = {"kind": "sine", "amplitude": 0.1, "omega": 20.0, "duration": 1.0, "vertical": {"kind": "sine",
                                                                                          "amplitude": 3.0,
                                                                                          "omega": 12.0}}
    ds = _case(tmp_path, sine).run()
    t = ds["t"].values
    # the sine as the structure sees it: sampled at the horizontal sine's 4000 points a period (every 79 µs) and
    # joined by straight lines, (79 µs)² / 8 x 3 x 12² = 3e-7 m/s² off at most
    assert np.allclose(ds["vertical_acceleration"].values, 3.0 * np.sin(12.0 * t), rtol=0, atol=5e-7)
    assert np.allclose(ds["normal_ratio"].values, 1 + 3.0 * np.sin(12.0 * t) / G, rtol=0, atol=1e-7)
    with pytest.raises(CaseError, match=r"excitation.vertical: a vertical file is a record's component"):
        _case(tmp_path, {**sine, "vertical": "V.AT2"})
    with pytest.raises(CaseError, match=r"excitation.vertical: unknown key\(s\) \['phase'\]"):
        _case(tmp_path, {**sine, "vertical": {"kind": "sine", "amplitude": 1.0, "omega": 2.0, "phase": 1.0}})


# --- suites: per-record settings and PEER downloads -----------------------------------------------------------
def test_a_suites_record_may_carry_its_own_window_and_scale(uneven, tmp_path):
    a, b = _accelerations()
    _write(tmp_path, "P1.AT2", a, "0")
    _write(tmp_path, "P2.AT2", b, "90")
    config = {"study": {"name": "own"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record", "scale": 1.5}, "structure": {"friction": 0.04},
              "sweep": {"record": [{"file": ["P1.AT2", "P2.AT2"], "name": "cut", "window": [2.0, 12.0], "scale": 2.0},
                                   ["H1.AT2", "H2.AT2"]], "friction": [0.03, 0.05]}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PairWarning)
        study = Study.from_config(config, tmp_path)
        ds = combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})
    assert list(ds["record"].values) == ["cut", "H"]
    assert list(ds["record_scale"].values) == [2.0, 1.5]
    cut = study.records["cut"]
    assert cut.t_start == 2.0 and cut.t_end == pytest.approx(12.0)
    # each record's values equal a case of that record alone
    for friction in (0.03, 0.05):
        alone = case_from({"prototype": "DFP1", "dt": 0.01, "model": "compliant",
                           "excitation": {"kind": "record", "file": ["P1.AT2", "P2.AT2"], "window": [2.0, 12.0],
                                          "scale": 2.0}, "structure": {"friction": friction}}, tmp_path).run()
        value = ds["stroke_max_abs"].sel(model="compliant", record="cut", friction=friction).values
        assert float(value) == alone.attrs["structure_stroke_max_abs_m"]


@pytest.fixture
def download(tmp_path):
    return write_download(tmp_path / "downloads", example_records())


def test_a_peer_download_is_a_suite_scaled_by_peers_factors(download, tmp_path):
    config = {"study": {"name": "peer"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record", "scale": "peer"}, "structure": {"friction": 0.05},
              "sweep": {"record": [{"peer": "downloads/_SearchResults.csv", "vertical": True}]}}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        study = Study.from_config(config, tmp_path)
        ds = combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})
    records = example_records()
    assert ds.sizes["record"] == 14
    names = [f"RSN{r.rsn}_{r.station.strip()}".replace(" ", "_").replace("#", "_") for r in records]
    assert [n.replace("-", "_") for n in ds["record"].values] == [n.replace("-", "_") for n in names]
    assert np.array_equal(ds["record_scale"].values, [r.scale_factor for r in records])
    assert np.all(np.isfinite(ds["normal_ratio_min"].sel(model="compliant").values))
    # every record carries its vertical, scaled by PEER's factor as its horizontals are
    for record, name in zip(records, ds["record"].values):
        excitation = study.records[str(name)]
        assert excitation.attrs()["record_vertical_scale"] == record.scale_factor


def test_a_peer_download_missing_files_are_named_together_with_their_records(download, tmp_path):
    folder = download.parent
    gone = sorted(folder.glob("RSN1063_*"))[:1] + sorted(folder.glob("RSN6_*UP.AT2"))
    for path in gone:
        path.unlink()
    config = {"study": {"name": "peer"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": {"kind": "record", "scale": "peer"}, "structure": {"friction": 0.05},
              "sweep": {"record": [{"peer": "downloads/_SearchResults.csv", "vertical": True}]}}
    with pytest.raises(CaseError) as err:
        Study.from_config(config, tmp_path)
    for path in gone:
        assert path.name in str(err.value)
    assert "RSN1063_Rinaldi Receiving Sta" in str(err.value) and "sweep.record[0].peer" in str(err.value)
    with pytest.raises(CaseError, match=r"excitation.scale: 'peer' takes each record's factor from the PEER search "
                                        r"results"):
        Study.from_config({**config, "sweep": {"record": ["downloads/RSN6_IMPVALL.I_I-ELC180.AT2"]}}, tmp_path)


def test_a_study_counts_uplift_and_never_keeps_a_lifted_run_as_an_ordinary_result(tmp_path):
    excitation = _lifting(tmp_path)
    config = {"study": {"name": "lift"}, "prototype": "DFP1", "dt": 0.01, "models": ["compliant"],
              "excitation": excitation, "structure": {"friction": 0.04}, "sweep": {"scale": [0.5, 1.0]}}

    def summaries(**more):
        study = Study.from_config({**config, **more}, tmp_path)
        return combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})

    flagged = summaries()
    counts = flagged["uplift_count"].sel(model="compliant").values
    assert list(counts) == [0, 1]  # 1.5 x 0.5 of the vertical stays above -g, the full one passes it once
    assert list(flagged["failed"].sel(model="compliant").values) == [0, 0]
    assert flagged["normal_ratio_min"].sel(model="compliant").values[1] < 0
    for capacity in ("stop", "error"):
        marked = summaries(capacity=capacity)
        assert list(marked["failed"].sel(model="compliant").values) == [0, 1]
        lifted = marked.sel(model="compliant", scale=1.0)
        assert np.isnan(lifted["theta2_max_abs"]) and float(lifted["failure_time"]) > 5.0
        assert float(lifted["stroke_max_abs"]) == float(flagged.sel(model="compliant", scale=1.0)["stroke_max_abs"])
    with pytest.raises(UpliftError, match=r"sweep point scale=1.0 \(compliant\): the superstructure lifts off"):
        summaries(capacity="error", on_failure="error")
