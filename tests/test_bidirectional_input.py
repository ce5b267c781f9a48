"""Bidirectional ground motion input: oriented excitations, two-component tables, record pairs,
their case-file keys, and the refusal of bad input (the message names the key or the file)."""

import hashlib
import importlib.util
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from dccss.case import case_from
from dccss.checks import CaseError
from dccss.excitation import (
    Oriented,
    PlaneTable,
    Scaled,
    Sine,
    Table,
    check_step,
    direction,
    read_table,
    step_times,
)
from dccss.records import G, Record, RecordPair, RecordWarning, read_at2, write_at2, write_peer

RECORDS = Path(__file__).resolve().parents[1] / "config" / "studies" / "records"
SYNTHETIC, SYNTHETIC_Y = RECORDS / "synthetic.AT2", RECORDS / "synthetic_y.AT2"
SYNTHETIC_SHA256 = "8e7fc90b6f7e1d724ffc7f71aacecbccb01f2a0a88fb1a27a7a4cce249195078"
CASE = {"prototype": "DFP1", "dt": 0.01, "model": "compliant"}
SINE = {"kind": "sine", "amplitude": 0.1, "omega": 30.0, "duration": 1.0}
T = np.linspace(0.0, 1.0, 101)


def case(tmp_path, excitation, **extra):
    return case_from({**CASE, "excitation": excitation, **extra}, tmp_path)


def write_csv(path, header, *columns):
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=header, comments="", fmt="%.17g")
    return path


def write_accel(path, n=300, dt=0.01, seed=0, units="G"):
    """A smooth, plausible acceleration record (about 0.1 g) of n samples at dt."""
    t = dt * np.arange(n)
    rng = np.random.default_rng(seed)
    a = 0.1 * np.sin(2 * np.pi * 1.3 * t + rng.uniform(0, 2 * np.pi)) * np.sin(np.pi * t / t[-1])
    write_peer(path, dt, a if units == "G" else a * G * 100, units)
    return path


def plain(attrs):
    return all(isinstance(v, (str, int, float, np.integer, np.floating)) and not isinstance(v, bool)
               for v in attrs.values())


# --- the common interface ---------------------------------------------------------------------------------
def test_components_of_every_excitation(tmp_path):
    sine = Sine(0.1, 30.0, 1.0)
    table = Table([0.0, 1.0], [0.0, 0.1])
    plane = PlaneTable([0.0, 1.0], [0.0, 0.1], [0.0, -0.1])
    record = Record.from_file(SYNTHETIC)
    pair = RecordPair(record, record)
    assert [e.components for e in (sine, table, record, Scaled(sine, 2.0), Scaled(record, 2.0))] == [1] * 5
    assert Sine.components == Table.components == Record.components == 1
    two = [Oriented(sine, 30.0), Oriented(table, 30.0), Oriented(record, 30.0), plane, pair, Scaled(plane, 2.0),
           Scaled(pair, -1.0), Scaled(Oriented(sine, 30.0), 2.0), Oriented(Scaled(sine, 2.0), 30.0)]
    for e in two:
        assert e.components == 2
        assert e.displacement(T).shape == e.velocity(T).shape == (T.size, 2)
        assert e.displacement(0.5).shape == (2,)
        attrs = e.attrs()
        assert attrs["excitation_components"] == 2 and plain(attrs) and isinstance(e.azimuth, float)
        assert isinstance(e.t_start, float) and isinstance(e.t_end, float) and isinstance(e.parameters, tuple)
    assert plane.azimuth == pair.azimuth == Scaled(plane, 2.0).azimuth == 0.0
    assert Scaled(Oriented(sine, 30.0), 2.0).azimuth == Oriented(sine, 30.0).azimuth == np.radians(30.0)
    assert not hasattr(Scaled(sine, 2.0), "azimuth") and not hasattr(sine, "azimuth")
    # unidirectional attrs are as before: no excitation_components
    assert all("excitation_components" not in e.attrs() for e in (sine, table, record, Scaled(sine, 2.0)))


# --- Oriented ---------------------------------------------------------------------------------------------
def test_oriented_sine_at_30_degrees_is_exact():
    sine = Sine(0.1, 30.0, 1.0)
    ex = Oriented(sine, 30.0)
    c, s = np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    X, V = sine.displacement(T), sine.velocity(T)
    assert np.array_equal(ex.displacement(T), np.column_stack([c * X, s * X]))
    assert np.array_equal(ex.velocity(T), np.column_stack([c * V, s * V]))
    assert ex.azimuth == np.radians(30.0) and ex.azimuth_deg == 30.0
    assert np.array_equal(ex.direction, [c, s])
    assert (ex.kind, ex.t_start, ex.t_end, ex.parameters) == ("sine", 0.0, 1.0, ("amplitude", "omega", "azimuth"))
    assert ex.attrs() == {**sine.attrs(), "excitation_components": 2, "excitation_form": "oriented",
                          "excitation_azimuth_deg": 30.0}


@pytest.mark.parametrize("azimuth, unit", [(0.0, (1, 0)), (90.0, (0, 1)), (180.0, (-1, 0)), (270.0, (0, -1)),
                                           (-90.0, (0, -1)), (450.0, (0, 1)), (390.0, None)])
def test_oriented_quadrants_are_exact(azimuth, unit):
    sine = Sine(0.1, 30.0, 1.0)
    X = sine.displacement(T)
    got = Oriented(sine, azimuth).displacement(T)
    if unit is None:  # 390° = 30°
        assert np.array_equal(got, Oriented(sine, 30.0).displacement(T))
    else:
        assert np.array_equal(got, np.column_stack([unit[0] * X, unit[1] * X]))
    assert np.array_equal(direction(azimuth), Oriented(sine, azimuth).direction)


def test_oriented_sine_evaluates_a_batch():
    ex = Oriented(Sine(0.1, 30.0, 1.0), 30.0)
    a, w, az = np.array([0.05, 0.1, 0.2]), np.array([10.0, 30.0, 20.0]), np.array([0.0, 137.0, 240.0])
    got = ex.displacement(T[:, None], amplitude=a, omega=w, azimuth=az)
    vel = ex.velocity(T[:, None], amplitude=a, omega=w, azimuth=az)
    assert got.shape == vel.shape == (T.size, 3, 2)
    for i in range(3):
        one = Oriented(Sine(a[i], w[i], 1.0), az[i])
        assert np.array_equal(got[:, i], one.displacement(T)) and np.array_equal(vel[:, i], one.velocity(T))
    only_azimuth = ex.displacement(T[:, None], azimuth=az)
    assert only_azimuth.shape == (T.size, 3, 2)
    for i in range(3):
        assert np.array_equal(only_azimuth[:, i], Oriented(Sine(0.1, 30.0, 1.0), az[i]).displacement(T))
    # the inner parameters alone keep the excitation's own azimuth
    assert np.array_equal(ex.displacement(T[:, None], amplitude=a)[:, 1],
                          Oriented(Sine(0.1, 30.0, 1.0), 30.0).displacement(T))


def test_oriented_table_and_record_are_exact():
    table = Table(np.linspace(0, 1, 11), np.linspace(0, 1, 11) ** 2)
    record = Record.from_file(SYNTHETIC, window=(2.0, 4.0))
    for inner, t in ((table, T), (record, np.linspace(2.0, 4.0, 57))):
        ex = Oriented(inner, 137.0)
        c, s = np.cos(np.radians(137.0)), np.sin(np.radians(137.0))
        assert np.array_equal(ex.displacement(t), np.column_stack([c * inner.displacement(t),
                                                                  s * inner.displacement(t)]))
        assert np.array_equal(ex.velocity(t), np.column_stack([c * inner.velocity(t), s * inner.velocity(t)]))
        assert ex.parameters == ("azimuth",) and (ex.t_start, ex.t_end) == (inner.t_start, inner.t_end)
        batch = ex.displacement(t[:, None], azimuth=[0.0, 137.0])
        assert np.array_equal(batch[:, 1], ex.displacement(t))


def test_oriented_refusals():
    plane = PlaneTable([0.0, 1.0], [0.0, 0.1], [0.0, 0.1])
    with pytest.raises(ValueError, match="excitation.azimuth: orients a one-component excitation, but this table "
                                         "excitation has 2 components"):
        Oriented(plane, 30.0)
    with pytest.raises(CaseError, match="excitation.azimuth: expected a number, got the string 'north'"):
        Oriented(Sine(0.1, 30.0, 1.0), "north")
    with pytest.raises(CaseError, match="excitation.azimuth: expected a finite number"):
        Oriented(Sine(0.1, 30.0, 1.0), float("nan"))


# --- PlaneTable -------------------------------------------------------------------------------------------
def test_plane_table_interpolates_each_component():
    t = np.array([0.0, 0.5, 1.5, 2.0])
    x, y = np.array([0.0, 0.1, -0.1, 0.2]), np.array([0.0, -0.05, 0.3, 0.1])
    plane = PlaneTable(t, x, y)
    assert np.array_equal(plane.displacement(t), np.column_stack([x, y]))
    assert np.array_equal(plane.displacement_samples, np.column_stack([x, y]))
    mid = plane.displacement(np.array([0.25, 1.0, 1.75]))
    assert np.allclose(mid, [[0.05, -0.025], [0.0, 0.125], [0.05, 0.2]], rtol=0, atol=1e-15)
    tq = np.linspace(0.0, 2.0, 37)
    assert np.array_equal(plane.displacement(tq)[:, 0], Table(t, x).displacement(tq))
    assert np.array_equal(plane.velocity(tq)[:, 0], Table(t, x).velocity(tq))
    assert np.array_equal(plane.velocity(tq)[:, 1], Table(t, y).velocity(tq))
    assert (plane.t_start, plane.t_end, plane.kind, plane.parameters) == (0.0, 2.0, "table", ())


def test_plane_table_from_csv(tmp_path):
    t = np.linspace(0.0, 2.0, 2001)
    x, y = 0.1 * np.sin(3 * t), 0.05 * np.cos(2 * t)
    path = write_csv(tmp_path / "motion.csv", "time, x, y", t, x, y)
    for plane in (PlaneTable.from_csv(path), read_table(path)):
        assert isinstance(plane, PlaneTable)
        assert np.array_equal(plane.displacement(t), np.column_stack([x, y]))
        tq = np.array([0.3333, 1.5])
        assert np.allclose(plane.velocity(tq), np.column_stack([0.3 * np.cos(3 * tq), -0.1 * np.sin(2 * tq)]),
                           atol=1e-5)
    attrs = PlaneTable.from_csv(path).attrs()
    assert attrs["table_source"] == str(path) and attrs["table_samples"] == 2001 and plain(attrs)
    # columns in another order
    other = write_csv(tmp_path / "yxt.csv", "y,time,x", y, t, x)
    assert np.array_equal(read_table(other).displacement(t), np.column_stack([x, y]))
    # a one-component CSV still gives a Table
    one = write_csv(tmp_path / "one.csv", "time,displacement", t, x)
    assert type(read_table(one)) is Table and np.array_equal(read_table(one).displacement(t), x)


ALLOWED = "allowed headers: 'time, displacement' or 'time, x, y'"


@pytest.mark.parametrize("header, message", [
    ("time,x", r"has a column 'x' but no 'y' \(columns found: \['time', 'x'\]\)"),
    ("time,y", r"has a column 'y' but no 'x' \(columns found: \['time', 'y'\]\)"),
    ("time,displacement,y", r"has both 'displacement' and \['y'\] columns in \['time', 'displacement', 'y'\]"),
    ("time,x,y,z", r"a two-component table has exactly the columns 'time', 'x' and 'y', got \['time', 'x', 'y', 'z'\]"),
    ("t,x,y", r"must have a header with columns 'time' and 'displacement' \(one component, m\) or 'time', 'x' "
              r"and 'y' \(two components, m\), got \['t', 'x', 'y'\]"),
])
def test_csv_headers_refused(tmp_path, header, message):
    n = len(header.split(","))
    path = write_csv(tmp_path / "bad.csv", header, *([np.arange(3.0)] * n))
    for read in (read_table, PlaneTable.from_csv, Table.from_csv):
        with pytest.raises(ValueError, match=message) as err:
            read(path)
        assert str(path) in str(err.value) and ALLOWED in str(err.value)
    with pytest.raises(CaseError, match=f"excitation.file: table excitation: {re.escape(repr(str(path)))}.*{message}"):
        case(tmp_path, {"kind": "table", "file": "bad.csv"})


def test_csv_of_the_other_kind_refused(tmp_path):
    plane = write_csv(tmp_path / "p.csv", "time,x,y", *([np.arange(3.0)] * 3))
    one = write_csv(tmp_path / "o.csv", "time,displacement", *([np.arange(3.0)] * 2))
    with pytest.raises(ValueError, match=r"'.*p.csv' has two components .*read it with PlaneTable.from_csv"):
        Table.from_csv(plane)
    with pytest.raises(ValueError, match=r"'.*o.csv' has one component .*not the columns 'time, x, y'"):
        PlaneTable.from_csv(one)


@pytest.mark.parametrize("content, message", [
    ("time,x,y\n", "no data rows"),
    ("time,x,y\n0,0,0\n1,0.1,abc\n", "not numeric"),
    ("time,x,y\n0,0,0\n1,0.1,nan\n", "y sample 1 is not finite"),
    ("time,x,y\n0,0,0\n1,inf,0\n", "x sample 1 is not finite"),
    ("time,x,y\n0,0,0\n1,0.1,0\n0.5,0.2,0\n", "time must increase strictly"),
    ("time,x,y\n0,0,0\n", "at least 2 samples"),
    ("time,x,y,x\n0,0,0,0\n1,0,0,0\n", "exactly the columns"),
])
def test_plane_table_errors_name_the_problem(tmp_path, content, message):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        PlaneTable.from_csv(path)


def test_plane_table_arrays_refused():
    with pytest.raises(ValueError, match=r"time and y must be 1-D of equal length, got shapes \(3,\) and \(2,\)"):
        PlaneTable([0.0, 1.0, 2.0], [0.0, 0.0, 0.0], [0.0, 0.0])


# --- Scaled, check_step, step_times -----------------------------------------------------------------------
def test_scaled_and_steps_for_two_components():
    plane = PlaneTable([0.0, 0.5, 1.0], [0.0, 0.1, 0.0], [0.0, -0.2, 0.3])
    oriented = Oriented(Sine(0.1, 30.0, 1.0), 240.0)
    pair = RecordPair.from_files([SYNTHETIC, SYNTHETIC_Y], window=(1.0, 3.0))
    for ex in (plane, oriented, pair):
        t = np.linspace(ex.t_start, ex.t_end, 41)
        scaled = Scaled(ex, -2.5)
        assert np.array_equal(scaled.displacement(t), -2.5 * ex.displacement(t))
        assert np.array_equal(scaled.velocity(t), -2.5 * ex.velocity(t))
        assert scaled.attrs() == {**ex.attrs(), "excitation_scale": -2.5} and scaled.components == 2
        assert (scaled.t_start, scaled.t_end, scaled.kind) == (ex.t_start, ex.t_end, ex.kind)
        assert check_step(0.01, ex) == 0.01
        one = Table([ex.t_start, ex.t_end], [0.0, 0.0])
        assert np.array_equal(step_times(ex, 0.01), step_times(one, 0.01))
        assert np.array_equal(step_times(scaled, 0.03), step_times(one, 0.03))
        with pytest.raises(CaseError, match="dt: .* is larger than the excitation's duration"):
            check_step(10.0, ex)
    assert step_times(pair, 0.01)[0] == 1.0 and step_times(pair, 0.01).size == 201


# --- RecordPair -------------------------------------------------------------------------------------------
def test_pair_of_the_same_file_equals_the_record():
    record = Record.from_file(SYNTHETIC, window=(1.0, 9.0), baseline="quadratic", scale=0.7)
    # (files refuse a pair of one file twice; the records themselves may be paired, for this check)
    pair = RecordPair(record, Record.from_file(SYNTHETIC, window=(1.0, 9.0), baseline="quadratic", scale=0.7))
    t = np.concatenate([record.time, np.linspace(1.0, 9.0, 777)])
    for k in (0, 1):
        assert np.array_equal(pair.displacement(t)[:, k], record.displacement(t))
        assert np.array_equal(pair.velocity(t)[:, k], record.velocity(t))
        assert np.array_equal(pair.displacement_samples[:, k], record.displacement_samples)
        assert np.array_equal(pair.velocity_samples[:, k], record.velocity_samples)
    assert (pair.t_start, pair.t_end, pair.npts, pair.dt) == (record.t_start, record.t_end, record.npts, record.dt)
    assert np.array_equal(pair.time, record.time) and pair.kind == "record" and pair.parameters == ("rotation",)
    assert pair.pgd == pytest.approx(np.sqrt(2) * record.pgd, rel=1e-15)


def test_pair_attrs_name_both_files():
    pair = RecordPair.from_files([SYNTHETIC, SYNTHETIC_Y])
    attrs = pair.attrs()
    assert plain(attrs)
    assert attrs["excitation"] == "record" and attrs["excitation_components"] == 2
    assert attrs["excitation_form"] == "record pair"
    assert attrs["record_1_source"] == "synthetic.AT2" and attrs["record_2_source"] == "synthetic_y.AT2"
    assert attrs["record_1_sha256"] == SYNTHETIC_SHA256
    assert attrs["record_2_sha256"] == hashlib.sha256(SYNTHETIC_Y.read_bytes()).hexdigest()
    assert attrs["record_1_units"] == attrs["record_2_units"] == "G"
    assert attrs["record_npts"] == 2000 and attrs["record_dt_s"] == 0.01
    for name, path in (("1", SYNTHETIC), ("2", SYNTHETIC_Y)):
        own = Record.from_file(path).attrs()
        assert all(attrs[f"record_{name}_{k.removeprefix('record_')}"] == v for k, v in own.items()
                   if k != "excitation")
    assert not any("warning" in k for k in attrs) and pair.warning == ""


def test_pair_honours_each_files_units_and_reports_warnings(tmp_path):
    x = write_accel(tmp_path / "x.AT2", units="G")
    y = write_accel(tmp_path / "y.AT2", units="CM/S/S")  # the same motion, written in cm/s²
    pair = RecordPair.from_files([x, y])
    assert np.allclose(pair.displacement_samples[:, 0], pair.displacement_samples[:, 1], rtol=1e-6, atol=1e-12)
    assert (pair.attrs()["record_1_units"], pair.attrs()["record_2_units"]) == ("G", "CM/S/S")
    with pytest.warns(RecordWarning) as caught:
        loud = RecordPair.from_files([x, y], scale=100.0)  # 10 g: implausible, both components
    assert len(caught) == 2
    attrs = loud.attrs()
    assert attrs["record_1_warning"] == str(caught[0].message) and "'x.AT2'" in attrs["record_1_warning"]
    assert attrs["record_2_warning"] == str(caught[1].message) and "'y.AT2'" in attrs["record_2_warning"]
    assert loud.warning == f"{attrs['record_1_warning']}; {attrs['record_2_warning']}"
    with pytest.raises(ValueError, match=r"record file '.*x.AT2': line 3 states units 'G', but units 'cm/s2'"):
        RecordPair.from_files([x, y], units="cm/s2")


def test_pair_refuses_unequal_steps_and_joins_unequal_lengths(tmp_path):
    x = write_accel(tmp_path / "x.AT2", n=300, dt=0.01)
    coarse = write_accel(tmp_path / "coarse.AT2", n=150, dt=0.02)
    short = write_accel(tmp_path / "short.AT2", n=250, dt=0.01, seed=1)
    with pytest.raises(ValueError, match=r"record pair: the components must share their step to be joined, but "
                                         r"'x.AT2': 300 samples, t = 0 to 2.99 s, dt = 0.01 s and 'coarse.AT2': "
                                         r"150 samples, t = 0 to 2.98 s, dt = 0.02 s; dccss does not resample"):
        RecordPair.from_files([x, coarse])
    with pytest.warns(RecordWarning, match=r"run over the 2.49 s all cover, 0 to 2.49 s \(pair_span: common\); "
                                           r"dropped 'x.AT2': 0.5 s"):
        pair = RecordPair.from_files([x, short])
    assert pair.npts == 250
    # a window both cover gives them the same samples, as before: each file's own over it, so nothing of the run
    # is dropped, and the pair says no such thing (it said "dropped 'x.AT2': 0.5 s", which the window drops anyway)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pair = RecordPair.from_files([x, short], window=(0.5, 2.0))
    assert pair.npts == 151 and np.array_equal(pair.x.time, pair.y.time)
    for record, path in ((pair.x, x), (pair.y, short)):
        alone = Record.from_file(path, window=(0.5, 2.0))
        assert np.array_equal(record.displacement_samples, alone.displacement_samples)
    attrs = pair.attrs()
    assert attrs["record_1_dropped_s"] == attrs["record_2_dropped_s"] == 0.0
    assert attrs["record_1_pair_span"] == "common"
    with pytest.raises(ValueError, match=r"must share their step"):
        RecordPair.from_files([x, coarse], window=(0.5, 2.0))


def test_pair_refuses_other_than_two_files():
    for paths in ([SYNTHETIC], [SYNTHETIC] * 3, str(SYNTHETIC), []):
        with pytest.raises(ValueError, match="record pair: expected two files"):
            RecordPair.from_files(paths)
    with pytest.raises(ValueError, match="record pair: file 1 must be a path, got 3"):
        RecordPair.from_files([SYNTHETIC, 3])
    with pytest.raises(ValueError, match="the y component must be a one-component Record"):
        RecordPair(Record.from_file(SYNTHETIC), Oriented(Record.from_file(SYNTHETIC), 0.0))


# --- case files -------------------------------------------------------------------------------------------
def test_without_azimuth_nothing_changes(tmp_path):
    write_csv(tmp_path / "one.csv", "time,displacement", T, 0.01 * T)
    assert type(case(tmp_path, SINE).excitation) is Sine
    assert type(case(tmp_path, {**SINE, "scale": 2.0}).excitation) is Scaled
    assert type(case(tmp_path, {"kind": "table", "file": "one.csv"}).excitation) is Table
    assert type(case(tmp_path, {"kind": "record", "file": str(SYNTHETIC)}).excitation) is Record


def test_case_azimuth_on_each_kind(tmp_path):
    write_csv(tmp_path / "one.csv", "time,displacement", T, 0.01 * T)
    sine = case(tmp_path, {**SINE, "azimuth": 30}).excitation
    assert isinstance(sine, Oriented) and sine.azimuth_deg == 30.0 and sine.excitation == Sine(0.1, 30.0, 1.0)
    assert sine.parameters == ("amplitude", "omega", "azimuth")
    capacity = case(tmp_path, {**SINE, "amplitude": "capacity", "azimuth": 240.0}).excitation
    assert capacity.excitation.amplitude == case(tmp_path, {**SINE, "amplitude": "capacity"}).excitation.amplitude
    scaled = case(tmp_path, {**SINE, "azimuth": 30.0, "scale": 2.0}).excitation
    assert isinstance(scaled, Oriented) and isinstance(scaled.excitation, Scaled)
    assert np.array_equal(scaled.displacement(T), 2.0 * sine.displacement(T))
    assert scaled.attrs()["excitation_scale"] == 2.0 and scaled.attrs()["excitation_azimuth_deg"] == 30.0
    table = case(tmp_path, {"kind": "table", "file": "one.csv", "azimuth": -45.0}).excitation
    assert isinstance(table, Oriented) and isinstance(table.excitation, Table) and table.azimuth == np.radians(-45.0)
    record = case(tmp_path, {"kind": "record", "file": str(SYNTHETIC), "window": [0.0, 5.0], "azimuth": 137}).excitation
    assert isinstance(record, Oriented) and isinstance(record.excitation, Record) and record.t_end == 5.0


def test_case_plane_table_and_pair(tmp_path):
    write_csv(tmp_path / "motion.csv", "time,x,y", T, 0.01 * T, -0.02 * T)
    plane = case(tmp_path, {"kind": "table", "file": "motion.csv", "scale": 0.5}).excitation
    assert isinstance(plane, Scaled) and isinstance(plane.excitation, PlaneTable) and plane.components == 2
    assert np.allclose(plane.displacement(T), np.column_stack([0.005 * T, -0.01 * T]), rtol=0, atol=1e-17)
    spec = {"kind": "record", "file": [str(SYNTHETIC), str(SYNTHETIC_Y)], "scale": 0.8, "window": [0.0, 12.0],
            "baseline": "linear", "units": "g"}
    c = case(tmp_path, spec, dt=0.005)
    assert isinstance(c.excitation, RecordPair) and c.dt == 0.005
    ref = RecordPair.from_files([SYNTHETIC, SYNTHETIC_Y], scale=0.8, window=(0.0, 12.0))
    assert np.array_equal(c.excitation.displacement_samples, ref.displacement_samples)
    assert (c.excitation.t_start, c.excitation.t_end) == (0.0, 12.0)
    # the shipped study's record, relative to the case file's folder
    shipped = case_from({**CASE, "excitation": {"kind": "record", "file": ["records/synthetic.AT2",
                                                                            "records/synthetic_y.AT2"]}},
                        RECORDS.parent)
    assert shipped.excitation.attrs()["record_2_source"] == "synthetic_y.AT2"


@pytest.mark.parametrize("excitation, message", [
    ({"kind": "record", "file": ["x.AT2"]},
     r"excitation.file: a record pair is a list of two files \[x, y\], got 1 \(\['x.AT2'\]\): one component is "
     r"missing"),
    ({"kind": "record", "file": ["x.AT2", "y.AT2", "z.AT2"]},
     r"excitation.file: a record pair is a list of two files \[x, y\], got 3 .*at most two horizontal components"),
    ({"kind": "record", "file": []}, r"excitation.file: a record pair is a list of two files \[x, y\], got 0"),
    ({"kind": "record", "file": ["x.AT2", 7]}, r"excitation.file\[1\]: expected a path string, got int 7"),
    ({"kind": "record", "file": 7}, r"excitation.file: expected a path string or a list of two \[x, y\], got int 7"),
    ({"kind": "record", "file": ["x.AT2", "y.AT2"], "azimuth": 30.0},
     r"excitation.azimuth: a record pair \(file: \[x, y\]\) has two components already"),
    ({"kind": "table", "file": "motion.csv", "azimuth": 30.0},
     r"excitation.azimuth: the table 'motion.csv' has two components \(columns time, x, y\) already"),
    ({**SINE, "azimuth": "north"}, "excitation.azimuth: expected a number, got the string 'north'"),
    ({**SINE, "azimuth": [30.0]}, r"excitation.azimuth: expected a number, got list \[30.0\]"),
    ({**SINE, "azimuth": True}, "excitation.azimuth: expected a number, got bool True"),
    ({"kind": "record", "file": "x.AT2", "azimuth": "1e1"}, "excitation.azimuth: expected a number, got the string"),
    ({**SINE, "azimuth": 30.0, "direction": 1}, r"excitation: unknown key\(s\) \['direction'\]"),
])
def test_case_refusals_name_the_key(tmp_path, excitation, message):
    write_csv(tmp_path / "motion.csv", "time,x,y", T, 0.01 * T, -0.02 * T)
    with pytest.raises(CaseError, match=message):
        case(tmp_path, excitation)


def test_case_pair_refusals_name_both_files(tmp_path):
    write_accel(tmp_path / "x.AT2", n=300, dt=0.01)
    write_accel(tmp_path / "y.AT2", n=150, dt=0.02)
    write_accel(tmp_path / "short.AT2", n=200, dt=0.01)
    with pytest.raises(CaseError, match=r"excitation.file: record pair: .* 'x.AT2': 300 samples, .*dt = 0.01 s and "
                                        r"'y.AT2': 150 samples, .*dt = 0.02 s"):
        case(tmp_path, {"kind": "record", "file": ["x.AT2", "y.AT2"]})
    with pytest.raises(CaseError, match=r"excitation.window: record pair: the window \(0.0, 2.5\) s lies outside "
                                        r"the time all components cover, 0.0 to 1.99 s"):
        case(tmp_path, {"kind": "record", "file": ["x.AT2", "short.AT2"], "window": [0.0, 2.5]})
    with pytest.raises(CaseError, match=r"excitation.file: record file '.*/missing.AT2': does not exist"):
        case(tmp_path, {"kind": "record", "file": ["x.AT2", "missing.AT2"]})
    with pytest.raises(CaseError, match=r"excitation.window: expected \[t_start, t_end\]"):
        case(tmp_path, {"kind": "record", "file": ["x.AT2", "short.AT2"], "window": 1.0})


# --- the shipped synthetic pair ---------------------------------------------------------------------------
def test_shipped_synthetic_pair():
    assert hashlib.sha256(SYNTHETIC.read_bytes()).hexdigest() == SYNTHETIC_SHA256  # x component unchanged
    with warnings.catch_warnings():
        warnings.simplefilter("error", RecordWarning)
        pair = RecordPair.from_files([SYNTHETIC, SYNTHETIC_Y])
    y = pair.y
    assert y.npts == 2000 and y.dt == 0.01 and 0.29 * G < y.pga < 0.31 * G
    assert 0.05 < y.pgd < 0.15 and abs(y.displacement_samples[-1]) < 1e-12
    assert np.corrcoef(pair.x.acceleration, y.acceleration)[0, 1] < 0.5  # a different history
    assert pair.pgd < 0.19  # below the capacity of DFP1/DFP2
    spec = importlib.util.spec_from_file_location("make_synthetic", RECORDS / "make_synthetic.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    _, acc = module.synthetic_acceleration(module.SEED_Y, module.PGA_G_Y)
    dt, stored = read_at2(SYNTHETIC_Y)
    assert dt == module.DT and np.allclose(stored, acc, rtol=1e-7, atol=1e-12)


def test_writer_round_trip_of_a_pair(tmp_path):
    """Two components written with the same writer read back as a pair on the same samples."""
    t = 0.01 * np.arange(400)
    ax = 0.2 * np.sin(2 * np.pi * t) * np.sin(np.pi * t / t[-1])
    ay = 0.1 * np.cos(3 * t) * np.sin(np.pi * t / t[-1])
    write_at2(tmp_path / "a.AT2", 0.01, ax)
    write_at2(tmp_path / "b.AT2", 0.01, ay)
    pair = RecordPair.from_files([tmp_path / "a.AT2", tmp_path / "b.AT2"])
    assert np.array_equal(pair.x.displacement_samples, Record.from_file(tmp_path / "a.AT2").displacement_samples)
    assert np.array_equal(pair.y.displacement_samples, Record.from_file(tmp_path / "b.AT2").displacement_samples)
