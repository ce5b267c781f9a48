"""Recorded ground motions: AT2/CSV readers, integration with baseline correction, errors."""

import hashlib
import importlib.util
import re
from pathlib import Path

import numpy as np
import pytest

from dccss.records import G, Record, integrate, read_acceleration_csv, read_at2, write_at2

RECORDS = Path(__file__).resolve().parents[1] / "config" / "studies" / "records"
SYNTHETIC = RECORDS / "synthetic.AT2"

A, OMEGA, PERIODS, DT = 0.1, 2 * np.pi, 3, 0.01  # m, rad/s, -, s


def sine_record():
    """t, a(t) = -A omega² sin(omega t) over an integer number of periods, on the sample grid."""
    n = round(PERIODS * 2 * np.pi / OMEGA / DT)
    t = DT * np.arange(n + 1)
    return t, -A * OMEGA**2 * np.sin(OMEGA * t)


def trapezoid_tolerance(omega=OMEGA, dt=DT):
    """Each trapezoidal integration of a sine scales it by 1 + (omega dt)²/12 + O(dt⁴): the
    displacement, integrated twice, is within 2 A (omega dt)²/12; allow a factor 1.5 more."""
    return 3 * A * (omega * dt) ** 2 / 12


def write_csv(path, t, a):
    np.savetxt(path, np.column_stack([t, a]), delimiter=",", header="time,acceleration", comments="",
               fmt="%.17g")


@pytest.fixture
def sine_at2(tmp_path):
    t, a = sine_record()
    path = tmp_path / "sine.AT2"
    write_at2(path, DT, a / G, title="closed form: -A omega^2 sin(omega t)")
    return path


def test_at2_closed_form(sine_at2):
    """Double integration with the linear baseline recovers A sin(omega t) to O(dt²)."""
    record = Record.from_file(sine_at2)
    t = record.time
    assert record.t_start == 0.0 and record.t_end == pytest.approx(PERIODS)
    assert record.npts == t.size == 301 and record.dt == DT
    tol = trapezoid_tolerance()
    assert tol < 2e-4
    assert np.max(np.abs(record.displacement(t) - A * np.sin(OMEGA * t))) < tol
    assert np.max(np.abs(record.velocity(t) - A * OMEGA * np.cos(OMEGA * t))) < OMEGA * tol
    assert record.pgd == pytest.approx(A, abs=tol) and record.pgv == pytest.approx(A * OMEGA, abs=OMEGA * tol)
    assert record.pga == pytest.approx(A * OMEGA**2, rel=1e-6)


def test_at2_between_samples(sine_at2):
    """Arbitrary step times interpolate linearly: error <= A (omega dt)²/8 + the integration error."""
    record = Record.from_file(sine_at2)
    tq = np.linspace(0.0, PERIODS, 777)
    tol = trapezoid_tolerance() + A * (OMEGA * DT) ** 2 / 8
    assert np.max(np.abs(record.displacement(tq) - A * np.sin(OMEGA * tq))) < tol


def test_linear_baseline_removes_a_constant_offset(sine_at2):
    t, a = sine_record()
    clean = Record(t, a)
    offset = Record(t, a + 0.05)
    drift = 0.5 * 0.05 * t[-1] ** 2  # what the offset does uncorrected: 0.225 m
    change = np.max(np.abs(offset.displacement_samples - clean.displacement_samples))
    assert change < 1e-12 < 1e-6 * drift
    raw = Record(t, a + 0.05, baseline="none").displacement_samples - Record(t, a, baseline="none").displacement_samples
    assert raw[-1] == pytest.approx(drift, rel=1e-12)
    assert np.allclose(offset.acceleration, a, atol=1e-12)  # the corrected acceleration


def test_quadratic_baseline_removes_a_linear_offset():
    t, a = sine_record()
    clean = Record(t, a, baseline="quadratic")
    offset = Record(t, a + 0.05 + 0.02 * t, baseline="quadratic")
    assert np.max(np.abs(offset.displacement_samples - clean.displacement_samples)) < 1e-12
    linear = Record(t, a + 0.05 + 0.02 * t).displacement_samples - Record(t, a).displacement_samples
    assert np.max(np.abs(linear)) > 1e-3  # the linear baseline cannot remove a sloping offset


def test_baseline_none_integrates_from_rest():
    t, a = sine_record()
    record = Record(t, a, baseline="none")
    # v = A omega (cos - 1), x = A sin - A omega t, to O(dt²); the velocity error integrates to a drift
    tol = trapezoid_tolerance()
    assert np.all(np.abs(record.velocity_samples - A * OMEGA * (np.cos(OMEGA * t) - 1)) < OMEGA * tol)
    assert np.all(np.abs(record.displacement_samples - A * (np.sin(OMEGA * t) - OMEGA * t)) < tol * (1 + OMEGA * t))


def test_csv_closed_form(tmp_path):
    t, a = sine_record()
    path = tmp_path / "sine.csv"
    write_csv(path, t, a)
    time, acc = read_acceleration_csv(path)
    assert np.array_equal(time, t) and np.array_equal(acc, a)
    record = Record.from_file(path)
    assert np.max(np.abs(record.displacement(t) - A * np.sin(OMEGA * t))) < trapezoid_tolerance()
    assert record.attrs()["record_source"] == "sine.csv"


def test_csv_non_uniform_time(tmp_path):
    """Non-uniform steps (dt/2 to 3dt/2) are integrated with the actual steps, still to O(dt²)."""
    s = np.linspace(0.0, 1.0, 301)
    t = PERIODS * (s + 0.04 * np.sin(4 * np.pi * s))
    assert np.ptp(np.diff(t)) > 0.5 * DT
    path = tmp_path / "uneven.csv"
    write_csv(path, t, -A * OMEGA**2 * np.sin(OMEGA * t))
    record = Record.from_file(path)
    assert np.max(np.abs(record.displacement(t) - A * np.sin(OMEGA * t))) < 3 * trapezoid_tolerance(dt=1.5 * DT)


@pytest.mark.parametrize("header", ["NPTS=    301, DT=   .0100 SEC", "NPTS= 301, DT= 0.01 SEC",
                                    "301    0.0100    NPTS, DT", "npts=301 dt=0.01"])
def test_at2_header_variants(sine_at2, header):
    lines = sine_at2.read_text().splitlines()
    lines[3] = header
    sine_at2.write_text("\n".join(lines) + "\n")
    dt, acc = read_at2(sine_at2)
    assert dt == 0.01 and acc.size == 301


def test_write_read_round_trip(tmp_path):
    acc = np.array([0.0, 1.234567e-3, -0.35, 2.5e-9, 0.1, -0.2, 0.3])
    path = tmp_path / "r.at2"
    write_at2(path, 0.005, acc, title="EVENT, STATION, COMPONENT")
    lines = path.read_text().splitlines()
    assert lines[2] == "ACCELERATION TIME SERIES IN UNITS OF G" and len(lines) == 6
    assert len(lines[4].split()) == 5 and len(lines[4]) == 5 * 15 + 4
    dt, back = read_at2(path)
    assert dt == 0.005 and np.allclose(back, acc, rtol=1e-7, atol=0)


def test_scale(sine_at2):
    base = Record.from_file(sine_at2)
    for scale in (2.5, -1.0):
        scaled = Record.from_file(sine_at2, scale=scale)
        assert np.allclose(scaled.displacement_samples, scale * base.displacement_samples, atol=1e-15)
        assert np.allclose(scaled.velocity_samples, scale * base.velocity_samples, atol=1e-14)
        assert scaled.pga == pytest.approx(abs(scale) * base.pga) and scaled.attrs()["record_scale"] == scale


def test_window(sine_at2):
    """The window keeps the samples in [t0, t1] on the original time axis and integrates them from 0."""
    t, a = sine_record()
    record = Record.from_file(sine_at2, window=(0.5, 1.75), baseline="none")
    assert record.t_start == 0.5 and record.t_end == pytest.approx(1.75) and record.npts == 126
    assert np.array_equal(record.time, t[50:176])
    assert np.allclose(record.acceleration, a[50:176], atol=1e-6)  # AT2 keeps 8 significant digits
    assert record.displacement(0.5) == 0.0 and record.velocity(0.5) == 0.0
    direct = Record(t[50:176], a[50:176], baseline="none")
    assert np.allclose(record.displacement_samples, direct.displacement_samples, atol=1e-8)
    attrs = Record.from_file(sine_at2, window=(0.5, 1.75)).attrs()
    assert (attrs["record_window_start_s"], attrs["record_window_end_s"]) == (0.5, 1.75)
    assert attrs["record_npts"] == 126 and attrs["record_raw_npts"] == 301
    # a bound between samples keeps the samples inside
    assert Record.from_file(sine_at2, window=(0.505, 1.0)).t_start == pytest.approx(0.51)


def test_attrs_are_netcdf_safe(sine_at2):
    record = Record.from_file(sine_at2)
    attrs = record.attrs()
    assert Record.kind == "record" and attrs["excitation"] == "record"
    assert all(type(v) in (str, int, float) for v in attrs.values()), attrs
    assert attrs["record_source"] == "sine.AT2" and attrs["record_baseline"] == "linear"
    assert attrs["record_sha256"] == hashlib.sha256(sine_at2.read_bytes()).hexdigest()
    assert attrs["record_npts"] == 301 and attrs["record_dt_s"] == DT
    assert attrs["record_pgd_m"] == record.pgd and attrs["record_pga_m_per_s2"] == record.pga
    assert "sine.AT2" in repr(record)


HEADER = "DB\nEVENT STATION COMP\nACCELERATION TIME SERIES IN UNITS OF G\n"

AT2_ERRORS = {
    "empty": ("", "is empty"),
    "short header": ("DB\nEVENT\n", "has 2 line(s); an AT2 file has 4 header lines"),
    "no NPTS": (HEADER + "DT= 0.01 SEC\n0.1 0.2 0.3\n", "line 4: expected the NPTS/DT header"),
    "NPTS not integer": (HEADER + "NPTS= 3.5, DT= 0.01 SEC\n0.1 0.2 0.3\n", "line 4: NPTS '3.5' is not an integer"),
    "DT not a number": (HEADER + "NPTS= 3, DT= abc SEC\n0.1 0.2 0.3\n", "line 4: DT 'abc' is not a number"),
    "DT zero": (HEADER + "NPTS= 3, DT= 0.0 SEC\n0.1 0.2 0.3\n", "line 4: DT must be a finite number > 0"),
    "DT negative": (HEADER + "NPTS= 3, DT= -.01 SEC\n0.1 0.2 0.3\n", "line 4: DT must be a finite number > 0"),
    "NPTS mismatch": (HEADER + "NPTS= 5, DT= .01 SEC\n0.1 0.2 0.3\n0.4\n",
                      "the header says NPTS=5 but the file has 4 value(s)"),
    "non-numeric": (HEADER + "NPTS= 4, DT= .01 SEC\n0.1 0.2\n0.3 x0.4\n", "line 6: value 'x0.4' is not a number"),
    "nan": (HEADER + "NPTS= 4, DT= .01 SEC\n0.1 nan\n0.3 0.4\n", "line 5: value nan is not finite"),
    "inf": (HEADER + "NPTS= 4, DT= .01 SEC\n0.1 0.2\n0.3 -inf\n", "line 6: value -inf is not finite"),
    "too few samples": (HEADER + "NPTS= 2, DT= .01 SEC\n0.1 0.2\n", "has 2 sample(s); at least 3 are needed"),
}

CSV_ERRORS = {
    "empty": ("\n\n", "is empty"),
    "wrong header": ("t,a\n0,0\n1,1\n2,2\n", "line 1: expected a header naming the columns 'time' and 'acceleration'"),
    "no rows": ("time,acceleration\n", "has a header but no data rows"),
    "non-numeric": ("time,acceleration\n0,0\n0.1,abc\n0.2,0\n", "line 3: acceleration 'abc' is not a number"),
    "field count": ("time,acceleration\n0,0\n0.1\n0.2,0\n", "line 3: expected 2 comma-separated fields, got 1"),
    "nan time": ("time,acceleration\n0,0\nnan,1\n0.2,0\n", "line 3: time nan is not finite"),
    "inf acceleration": ("time,acceleration\n0,0\n0.1,inf\n0.2,0\n", "line 3: acceleration inf is not finite"),
    "non-monotonic": ("time,acceleration\n0,0\n0.1,1\n0.1,2\n0.3,0\n",
                      "line 4: time must increase strictly; 0.1 s follows 0.1 s"),
    "decreasing": ("time,acceleration\n0,0\n0.2,1\n0.1,2\n", "line 4: time must increase strictly"),
    "too few samples": ("time,acceleration\n0,0\n0.1,1\n", "has 2 sample(s); at least 3 are needed"),
}


def expect_error(path, problem, **kw):
    with pytest.raises(ValueError) as err:
        Record.from_file(path, **kw)
    message = str(err.value)
    assert str(path) in message, message
    assert problem in message, message


@pytest.mark.parametrize("case", AT2_ERRORS)
def test_at2_errors_name_file_and_problem(tmp_path, case):
    content, problem = AT2_ERRORS[case]
    path = tmp_path / "bad.AT2"
    path.write_text(content)
    expect_error(path, problem)


@pytest.mark.parametrize("case", CSV_ERRORS)
def test_csv_errors_name_file_and_problem(tmp_path, case):
    content, problem = CSV_ERRORS[case]
    path = tmp_path / "bad.csv"
    path.write_text(content)
    expect_error(path, problem)


@pytest.mark.parametrize("name, problem", [("nope.AT2", "does not exist"), ("nope.csv", "does not exist"),
                                           ("record.txt", "unknown record format '.txt'")])
def test_missing_file_and_unknown_format(tmp_path, name, problem):
    path = tmp_path / name
    if name.endswith(".txt"):
        path.write_text("0 0\n")
    expect_error(path, problem)


@pytest.mark.parametrize("kw, problem", [
    (dict(window=(-1.0, 1.0)), "window (-1.0, 1.0) s lies outside the record, which spans 0.0 to"),
    (dict(window=(1.0, 3.5)), "window (1.0, 3.5) s lies outside the record"),
    (dict(window=(1.0, 1.0)), "window (1.0, 1.0) s must be finite with t0 < t1"),
    (dict(window=(2.0, 1.0)), "window (2.0, 1.0) s must be finite with t0 < t1"),
    (dict(window=(1.0, 1.015)), "holds 2 sample(s); at least 3 are needed"),
    (dict(window=1.0), "window must be a pair (t0, t1)"),
    (dict(scale=0.0), "scale must be finite and non-zero, got 0.0"),
    (dict(scale=float("nan")), "scale must be finite and non-zero"),
    (dict(scale="2"), "scale must be a number, got '2'"),
    (dict(baseline="cubic"), "baseline must be one of ['none', 'linear', 'quadratic'], got 'cubic'"),
])
def test_processing_errors_name_file_and_problem(sine_at2, kw, problem):
    expect_error(sine_at2, problem, **kw)


def test_integrate_rejects_unknown_baseline():
    with pytest.raises(ValueError, match=re.escape("baseline must be one of")):
        integrate(np.arange(3.0), np.zeros(3), "cubic")


def test_shipped_synthetic_record():
    record = Record.from_file(SYNTHETIC)
    assert record.npts == 2000 and record.dt == 0.01 and record.t_end == pytest.approx(19.99)
    assert 0.34 * G < record.pga < 0.36 * G
    assert 0.10 < record.pgd < 0.19  # below the ~19-22 cm capacity of DFP1/DFP2
    assert 0.2 < record.pgv < 0.6
    assert abs(record.displacement_samples[-1]) < 1e-12  # the linear baseline leaves no permanent offset
    raw = Record.from_file(SYNTHETIC, baseline="none")
    assert raw.pgd > 5 * record.pgd  # why the baseline correction is needed


def test_synthetic_script_reproduces_the_file():
    spec = importlib.util.spec_from_file_location("make_synthetic", RECORDS / "make_synthetic.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    _, acc = module.synthetic_acceleration()
    dt, stored = read_at2(SYNTHETIC)
    assert dt == module.DT and np.allclose(stored, acc, rtol=1e-7, atol=1e-12)


def test_simulate_accepts_a_record():
    from dccss.prototypes import DFP1
    from dccss.simulation import simulate

    record = Record.from_file(SYNTHETIC, window=(4.0, 6.0))
    ds = simulate(DFP1, record, model="compliant", dt=0.01)
    assert ds.sizes["time"] == 201 and float(ds.time[0]) == 4.0
    assert np.array_equal(ds["Xg"].values, record.displacement(ds.time.values))
    assert np.array_equal(ds["Xg_dot"].values, record.velocity(ds.time.values))
    assert ds.attrs["excitation"] == "record" and ds.attrs["record_source"] == "synthetic.AT2"
    assert float(np.abs(ds["Xg"]).max()) > 0.01 and int(ds["capacity_exceeded"].sum()) == 0
