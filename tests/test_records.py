"""Recorded ground motions: PEER and text readers, units, integration with baseline correction, errors."""

import hashlib
import importlib.util
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import cumulative_trapezoid

from dccss import records
from dccss.case import case_from
from dccss.checks import CaseError
from dccss.excitation import Table
from dccss.records import (
    BASELINES,
    G,
    Record,
    RecordWarning,
    integrate,
    read_acceleration_csv,
    read_at2,
    read_peer,
    units_from,
    write_at2,
    write_peer,
)

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
    np.savetxt(path, np.column_stack([t, a]), delimiter=",", header="time (s),acceleration (m/s2)", comments="",
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


@pytest.mark.parametrize("baseline", ["none", "linear", "quadratic"])
def test_a_window_never_changes_the_motion_inside_it(sine_at2, baseline):
    """The window keeps the samples in [t0, t1] on the original time axis, of the whole record
    processed first: its acceleration, velocity and X_g are the whole record's there, bit for bit."""
    t, a = sine_record()
    record = Record.from_file(sine_at2, window=(0.5, 1.75), baseline=baseline)
    whole = Record.from_file(sine_at2, baseline=baseline)
    assert record.t_start == 0.5 and record.t_end == pytest.approx(1.75) and record.npts == 126
    assert np.array_equal(record.time, t[50:176])
    for name in ("acceleration", "velocity_samples", "displacement_samples"):
        assert np.array_equal(getattr(record, name), getattr(whole, name)[50:176]), name
    inside = np.linspace(0.5, 1.75, 77)
    assert np.array_equal(record.displacement(inside), whole.displacement(inside))
    if baseline == "none":  # the raw acceleration, as written (AT2 keeps 8 significant digits)
        assert np.allclose(record.acceleration, a[50:176], atol=1e-6)
    attrs = Record.from_file(sine_at2, window=(0.5, 1.75)).attrs()
    assert (attrs["record_window_start_s"], attrs["record_window_end_s"]) == (0.5, 1.75)
    assert attrs["record_npts"] == 126 and attrs["record_raw_npts"] == 301
    # a bound between samples keeps the samples inside
    assert Record.from_file(sine_at2, window=(0.505, 1.0)).t_start == pytest.approx(0.51)


def test_a_window_keeps_the_whole_records_peak_displacement():
    """A drifting accelerogram (a constant offset on a long swing) cut to its first half: the linear
    baseline fitted to the window alone moved X_g by centimetres (El Centro (270) [0, 10]: a peak
    θ² 25 % low); fitted to the whole record, the window's X_g is the whole record's."""
    t = np.arange(0, 20.0, 0.01)
    a = 2.0 * np.sin(2 * np.pi * t / 7.0) * np.exp(-((t - 6.0) / 4.0) ** 2) + 0.01
    whole = Record(t, a, baseline="linear")
    cut = Record(t, a, baseline="linear", window=(0.0, 10.0))
    inside = t <= 10.0
    assert np.array_equal(cut.displacement_samples, whole.displacement_samples[inside])
    assert cut.pgd == np.max(np.abs(whole.displacement_samples[inside]))
    windowed_raw = Record(t[inside], a[inside], baseline="linear")  # what a window of the raw samples gives
    assert np.max(np.abs(windowed_raw.displacement_samples - cut.displacement_samples)) > 0.01


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
    "wrong header": ("channel,acc (g),gain\n0,0,1\n1,1,1\n2,2,1\n",
                     "line 1: with 3 columns the header must name the time column"),
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
    expect_error(path, problem, units="m/s2")


@pytest.mark.parametrize("name, problem", [("nope.AT2", "does not exist"), ("nope.csv", "does not exist"),
                                           ("nope.DT2", "does not exist"),
                                           ("record.xlsx", "unknown record format '.xlsx'")])
def test_missing_file_and_unknown_format(tmp_path, name, problem):
    path = tmp_path / name
    if name.endswith(".xlsx"):
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
    from dccss.paper.prototypes import DFP1
    from dccss.simulation import simulate

    record = Record.from_file(SYNTHETIC, window=(4.0, 6.0))
    ds = simulate(DFP1, record, model="compliant", dt=0.01)
    assert ds.sizes["t"] == 201 and float(ds.t[0]) == 4.0
    assert np.array_equal(ds["Xg"].values, record.displacement(ds.t.values))
    assert np.array_equal(ds["Xg_dot"].values, record.velocity(ds.t.values))
    assert ds.attrs["excitation"] == "record" and ds.attrs["record_source"] == "synthetic.AT2"
    assert float(np.abs(ds["Xg"]).max()) > 0.01 and int(ds["capacity_exceeded"].sum()) == 0


# --- units and formats: the same motion, whatever the file -------------------------------------------
def reference():
    """The raw acceleration (m/s², with an offset for the baseline to remove) and its processed Record."""
    t, a = sine_record()
    a = a + 0.05
    return t, a, Record(t, a)


def write_peer_file(path, values_si, units, line3=None, line4=None):
    """A PEER file at full precision; line 3 or 4 optionally replaced (``{units}`` is filled in)."""
    write_peer(path, DT, values_si / units_from(units).to_si, units, decimals=16)
    lines = path.read_text().splitlines()
    if line3 is not None:
        lines[2] = line3.format(units=units)
    if line4 is not None:
        lines[3] = line4
    path.write_text("\n".join(lines) + "\n")


def write_text_file(path, t, values, header=None, separator=",", comments=(), extra=None):
    """A text record at full precision: comment lines, an optional header, then the columns."""
    rows = [separator.join(f"{v:.17g}" for v in row) for row in zip(t, values, *([extra] if extra is not None else []))]
    rows[3:3] = ["# a comment between the rows"]
    path.write_text("\n".join([*comments, *([header] if header else []), *rows]) + "\n")


def peer(suffix, units, line3=None, line4=None, given=None):
    quantity = {".AT2": "acceleration", ".VT2": "velocity", ".DT2": "displacement"}[suffix]
    return (f"r{suffix}", quantity, units, given,
            lambda path, t, motion: write_peer_file(path, motion[quantity], units, line3, line4))


def text(name, quantity, units, header, separator=",", given=None, comments=(), extra=None):
    def write(path, t, motion):
        values = motion[quantity] / units_from(units).to_si
        write_text_file(path, t, values, header, separator, comments, None if extra is None else motion[extra])
    return name, quantity, units, given, write


ACC_UNITS = ["G", "g", "CM/S/S", "CM/SEC/SEC", "CM/S^2", "CM/S2", "GAL", "gal", "cm/s²", "CM/S**2", "cm / sec / sec",
             "M/S2", "m/s/s", "m/sec^2", "MM/S2", "mm/s**2"]
FORMATS = [
    *[peer(".AT2", u) for u in ACC_UNITS],
    peer(".AT2", "G", line3="ACCELERATION TIME HISTORY IN UNITS OF {units}", line4="  301    0.0100    NPTS, DT"),
    peer(".AT2", "CM/S/S", line3="ACCELERATION IN {units}"),
    peer(".AT2", "G", line3="ACCELERATION TIME SERIES", given="g"),  # line 3 without units: the given ones
    peer(".AT2", "CM/S/S", given="gal"),  # the same units, spelled differently
    *[peer(".VT2", u) for u in ("CM/S", "CM/SEC", "cm/sec", "M/S", "MM/S")],
    peer(".VT2", "CM/SEC", line3="VELOCITY TIME HISTORY IN UNITS OF {units}", line4="301 .01 NPTS, DT"),
    *[peer(".DT2", u) for u in ("CM", "cm", "M", "MM")],
    peer(".DT2", "CM", line3="DISPLACEMENT TIME HISTORY IN UNITS OF {units}", given="cm"),
    text("r.csv", "acceleration", "g", "time (s), acc (g)"),
    text("r.csv", "acceleration", "cm/s2", "t [s]; acceleration (cm/s2)", separator=";"),
    text("r.csv", "acceleration", "m/s^2", "time,acceleration[m/s^2]"),
    text("r.csv", "acceleration", "gal", "time (s),acceleration (gal)", given="CM/S/S"),
    text("r.csv", "acceleration", "m/s2", "time,acceleration", given="m/s2"),
    text("r.csv", "acceleration", "cm/s2", None, given="cm/s2"),
    text("r.csv", "acceleration", "g", "time (s),acceleration (g),channel", extra="velocity"),
    text("r.csv", "acceleration", "g", "time (s),acc (g),disp (m)", extra="displacement", given="G"),
    text("r.csv", "displacement", "m", "time (s),disp (m),acc (g)", extra="acceleration", given="m"),
    text("r.txt", "displacement", "cm", "time (s)\tdisp (cm)", separator="\t"),
    text("r.txt", "acceleration", "g", None, separator=" ", given="g", comments=["# PGA about 0.4 g"]),
    text("r.txt", "velocity", "mm/s", "# time, velocity\n# t (s)\tv (mm/s)", separator="\t", given="mm/s"),
    text("r.dat", "velocity", "cm/sec", "time (s)    vel (cm/sec)", separator="    "),
    text("r.dat", "acceleration", "gal", "t[s] a[gal]", separator="\t", comments=["# recorded somewhere"]),
    text("r.dat", "displacement", "mm", "time  displacement", separator="  ", given="mm"),
]


@pytest.mark.parametrize("name, quantity, units, given, write", FORMATS,
                         ids=[f"{f[0]}-{f[2]}-{i}" for i, f in enumerate(FORMATS)])
def test_same_motion_same_displacement(tmp_path, name, quantity, units, given, write):
    """Every format and units spelling of one motion gives its displacement to 1e-9 relative."""
    t, a, ref = reference()
    motion = {"acceleration": a, "velocity": ref.velocity_samples, "displacement": ref.displacement_samples}
    path = tmp_path / name
    write(path, t, motion)
    record = Record.from_file(path, units=given)
    assert record.quantity == quantity and record.npts == t.size
    assert np.max(np.abs(record.time - t)) < 1e-12
    assert np.max(np.abs(record.displacement_samples - ref.displacement_samples)) < 1e-9 * ref.pgd
    assert record.pgd == pytest.approx(ref.pgd, rel=1e-9)
    attrs = record.attrs()
    assert attrs["record_quantity"] == quantity
    assert units_from(attrs["record_units"]).same_as(units_from(units))
    assert attrs["record_baseline"] == ("none" if quantity == "displacement" else "linear")
    assert "record_warning" not in attrs


def test_the_used_file_really_differs_by_units(tmp_path):
    """The comparison above can fail: the same numbers in other units are another motion."""
    t, a, ref = reference()
    write_peer_file(tmp_path / "r.AT2", a, "CM/S/S")
    lines = (tmp_path / "r.AT2").read_text().replace("UNITS OF CM/S/S", "UNITS OF G")
    (tmp_path / "r.AT2").write_text(lines)
    with pytest.warns(RecordWarning):
        wrong = Record.from_file(tmp_path / "r.AT2")
    assert wrong.pgd == pytest.approx(100 * G * ref.pgd, rel=1e-9)


def test_velocity_record_baseline_as_after_the_first_integration(tmp_path):
    """A raw velocity (the integral of a raw acceleration) is corrected exactly as the acceleration record is."""
    t, a = sine_record()
    a = a + 0.05 + 0.02 * t
    raw_velocity = cumulative_trapezoid(a, t, initial=0.0)
    for baseline in BASELINES:
        ref = Record(t, a, baseline=baseline)
        path = tmp_path / f"{baseline}.VT2"
        write_peer_file(path, raw_velocity, "M/S")
        record = Record.from_file(path, baseline=baseline)
        assert record.baseline == baseline
        assert np.max(np.abs(record.velocity_samples - ref.velocity_samples)) < 1e-12
        assert np.max(np.abs(record.displacement_samples - ref.displacement_samples)) < 1e-9 * ref.pgd


def test_displacement_record_is_used_as_recorded(tmp_path):
    """No integration: X_g is the samples, the velocity that of a Table, no baseline but "none"."""
    t, _, ref = reference()
    x = ref.displacement_samples + 0.01  # a permanent offset, which a baseline would remove
    path = tmp_path / "r.DT2"
    write_peer_file(path, x, "CM")
    record = Record.from_file(path)
    assert np.allclose(record.displacement_samples, x, rtol=1e-15, atol=1e-17)
    table = Table(t, x)
    tq = np.linspace(0.0, PERIODS, 777)
    assert np.allclose(record.velocity(tq), table.velocity(tq), rtol=0, atol=1e-12)
    assert Record.from_file(path, baseline="none").baseline == "none"
    windowed = Record.from_file(path, window=(0.5, 1.75))
    assert windowed.displacement(0.5) == pytest.approx(x[50], abs=1e-15)  # not restarted from 0
    for baseline in ("linear", "quadratic"):
        expect_error(path, f"baseline {baseline!r} removes a trend from an integrated velocity, but a displacement "
                           f"record is used as recorded", baseline=baseline)


def test_pga_of_velocity_and_displacement_records(tmp_path):
    """Estimated PGA: central differences, the same for both, (omega dt)²/4 below the sine's peak."""
    t, a, ref = reference()
    write_peer_file(tmp_path / "r.VT2", ref.velocity_samples, "CM/S")
    write_peer_file(tmp_path / "r.DT2", ref.displacement_samples, "CM")
    vt2, dt2 = Record.from_file(tmp_path / "r.VT2"), Record.from_file(tmp_path / "r.DT2")
    assert vt2.pga == pytest.approx(dt2.pga, rel=1e-9)
    assert vt2.pga == pytest.approx(ref.pga, rel=(OMEGA * DT) ** 2 / 4)
    assert np.max(np.abs(dt2.acceleration[1:-1] - vt2.acceleration[1:-1])) < 1e-9 * ref.pga


def test_write_peer_variants(tmp_path):
    acc = np.array([0.0, 1.234567e-3, -0.35, 2.5e-9, 0.1, -0.2, 0.3])
    path = tmp_path / "r.AT2"
    write_at2(path, 0.005, acc * G * 100, units="CM/S/S")
    assert path.read_text().splitlines()[2] == "ACCELERATION TIME SERIES IN UNITS OF CM/S/S"
    dt, back = read_at2(path)
    assert dt == 0.005 and np.allclose(back, acc, rtol=1e-7, atol=0)  # read_at2 converts to g
    write_peer(tmp_path / "r.VT2", 0.005, acc, "CM/SEC")
    assert (tmp_path / "r.VT2").read_text().splitlines()[2] == "VELOCITY TIME SERIES IN UNITS OF CM/SEC"
    dt, values, units = read_peer(tmp_path / "r.VT2")
    assert units == ("CM/SEC", "velocity", 0.01) and np.allclose(values, acc, rtol=1e-7, atol=0)


@pytest.mark.parametrize("text, quantity, to_si", [
    ("G", "acceleration", G), ("CM/S/S", "acceleration", 0.01), ("cm/sec/sec", "acceleration", 0.01),
    ("CM/S^2", "acceleration", 0.01), ("CM/S2", "acceleration", 0.01), ("Gal", "acceleration", 0.01),
    ("cm/s²", "acceleration", 0.01), ("m/s**2", "acceleration", 1.0), ("MM / S / S", "acceleration", 1e-3),
    ("CM/SEC", "velocity", 0.01), ("m/s", "velocity", 1.0), ("mm/s", "velocity", 1e-3),
    ("CM", "displacement", 0.01), ("m", "displacement", 1.0), ("MM", "displacement", 1e-3), ("sec", "time", 1.0)])
def test_units_table(text, quantity, to_si):
    assert units_from(text) == (text, quantity, to_si)


@pytest.mark.parametrize("text", ["FT/S2", "in", "km", "g/s", "ms", "CM/S3", "", "G G"])
def test_unknown_units(text):
    with pytest.raises(ValueError, match=re.escape(f"unknown units {text!r}; allowed: acceleration: g, m/s2")):
        units_from(text)


# --- refused: unknown, missing, conflicting units; the wrong quantity -----------------------------------
PEER_ERRORS = [
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF FT/S2", {},
     "line 3: unknown units 'FT/S2' in 'ACCELERATION TIME SERIES IN UNITS OF FT/S2'; allowed: acceleration: g, "
     "m/s2, cm/s2, gal, mm/s2"),
    ("r.AT2", "ACCELERATION TIME SERIES", {}, "line 3: no units in 'ACCELERATION TIME SERIES'"),
    ("r.AT2", "", {}, "line 3: no units in ''"),
    ("r.AT2", "VELOCITY TIME SERIES IN UNITS OF G", {}, "line 3: 'VELOCITY TIME SERIES IN UNITS OF G' says "
                                                        "velocity, but an AT2 file holds acceleration"),
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF CM/S", {},
     "line 3: 'CM/S' are units of velocity, but an AT2 file holds acceleration"),
    ("r.VT2", "VELOCITY TIME SERIES IN UNITS OF CM/S/S", {},
     "line 3: 'CM/S/S' are units of acceleration, but a VT2 file holds velocity"),
    ("r.DT2", "ACCELERATION TIME SERIES IN UNITS OF CM", {}, "says acceleration, but a DT2 file holds displacement"),
    ("r.DT2", "DISPLACEMENT TIME SERIES IN UNITS OF G", {}, "'G' are units of acceleration, but a DT2 file holds"),
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF G", {"units": "cm/s2"},
     "line 3 states units 'G', but units 'cm/s2' were given"),
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF G", {"units": "cm"},
     "units 'cm' are units of displacement, but an AT2 file holds acceleration"),
    ("r.AT2", "ACCELERATION TIME SERIES", {"units": "cm/s"}, "units 'cm/s' are units of velocity, but an AT2 file"),
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF G", {"units": "furlongs"}, "units: unknown units 'furlongs'"),
    ("r.AT2", "ACCELERATION TIME SERIES IN UNITS OF G", {"units": "s"}, "units 's' is a time unit"),
]


@pytest.mark.parametrize("name, line3, kw, problem", PEER_ERRORS, ids=[e[3][:40] for e in PEER_ERRORS])
def test_peer_units_errors(tmp_path, name, line3, kw, problem):
    path = tmp_path / name
    write_peer_file(path, sine_record()[1], "G" if name.endswith("AT2") else "CM", line3=line3)
    expect_error(path, problem, **kw)


TEXT_ERRORS = [
    ("time,acceleration\n0,0\n0.1,1\n0.2,0\n", {},
     "line 1: cannot tell the units of column 'acceleration': state them in the header, e.g. 'time (s), "
     "acceleration (g)', or give units"),
    ("# time (s), acc (g)\n0,0\n0.1,1\n0.2,0\n", {}, "has no header stating the units: add one"),
    ("0 0\n0.1 1\n0.2 0\n", {}, "has no header stating the units"),
    ("0,0,1\n0.1,1,1\n0.2,0,1\n", {"units": "g"}, "line 1: without a header a record has 2 columns"),
    ("time (s),acc (g)\n0,0\n0.1,1\n0.2,0\n", {"units": "cm/s2"},
     "line 1: the header states units 'g' for column 'acc (g)', but units 'cm/s2' were given"),
    ("time (s),acceleration\n0,0\n0.1,1\n0.2,0\n", {"units": "cm"},
     "line 1: column 'acceleration' holds acceleration, but units 'cm' are units of displacement"),
    ("time (s),acc (ft/s2)\n0,0\n0.1,1\n0.2,0\n", {}, "line 1: unknown units 'ft/s2' in column 'acc (ft/s2)'; allowed"),
    ("time (ms),acc (g)\n0,0\n100,1\n200,0\n", {}, "line 1: the time column 'time (ms)' must be in s, got 'ms'"),
    ("time (min);acc (g)\n0;0\n1;1\n2;0\n", {}, "line 1: the time column 'time (min)' must be in s, got 'min'"),
    ("time (s),acceleration (cm/s)\n0,0\n0.1,1\n0.2,0\n", {},
     "line 1: column 'acceleration (cm/s)' is named as acceleration but 'cm/s' are units of velocity"),
    ("time (s),acc (g),vel (cm/s)\n0,0,0\n0.1,1,0\n0.2,0,0\n", {},
     "line 1: more than one motion column in ['time (s)', 'acc (g)', 'vel (cm/s)']; keep one, or give units"),
    ("time (s),acc (g),disp (cm)\n0,0,0\n0.1,1,0\n0.2,0,0\n", {"units": "cm/s"},
     "line 1: with 3 columns the header must name the motion column"),
    ("t (s),time,acc (g)\n0,0,0\n0.1,0.1,1\n0.2,0.2,0\n", {}, "line 1: more than one time column"),
    ("\n# only a comment\n", {}, "has no data rows (only comments)"),
    ("time (s);acc (g)\n0;0\n0.1\n0.2;0\n", {}, "line 3: expected 2 semicolon-separated fields, got 1"),
    ("time (s)\tacc (g)\n0\t0\n0.1\t1\t2\n", {}, "line 3: expected 2 tab-separated fields, got 3"),
    ("time (s) acc (g)\n0 0\n0.1 x1\n0.2 0\n", {}, "line 3: acceleration 'x1' is not a number"),
]


@pytest.mark.parametrize("content, kw, problem", TEXT_ERRORS, ids=[e[2][:40] for e in TEXT_ERRORS])
def test_text_units_errors(tmp_path, content, kw, problem):
    path = tmp_path / "bad.txt"
    path.write_text(content)
    expect_error(path, problem, **kw)


def test_arrays_with_units():
    t, a = sine_record()
    in_g = Record(t, a / G, units="g")
    assert np.allclose(in_g.displacement_samples, Record(t, a).displacement_samples, rtol=0, atol=1e-15)
    assert in_g.attrs()["record_units"] == "g" and Record(t, a).attrs()["record_units"] == "m/s2"
    with pytest.raises(ValueError, match="record 'arrays': units 'cm' are units of displacement, not acceleration"):
        Record(t, a, units="cm")
    with pytest.raises(ValueError, match="record 'arrays': unknown units 'furlongs'"):
        Record(t, a, units="furlongs")
    with pytest.raises(ValueError, match=re.escape("give exactly one of acceleration, velocity, displacement; "
                                                   "got ['acceleration', 'velocity']")):
        Record(t, a, velocity=a)


# --- implausible peak ground acceleration ----------------------------------------------------------------
@pytest.mark.parametrize("factor, units, side", [(100, "G", "above 5 g"), (1 / G, "CM/S/S", "below 0.001 g")])
def test_implausible_pga_is_reported(tmp_path, factor, units, side):
    """A record in cm/s² labelled g (981 times too large), one in g labelled cm/s² (981 times too small)."""
    t, a = sine_record()  # PGA 3.95 m/s² = 0.403 g
    path = tmp_path / "r.AT2"
    write_peer(path, DT, a * factor, units, decimals=16)
    with pytest.warns(RecordWarning, match=f"peak ground acceleration is .* g, {side}: implausible") as caught:
        record = Record.from_file(path)
    assert len(caught) == 1
    warning = record.attrs()["record_warning"]
    assert warning == record.warning == str(caught[0].message)
    assert "'r.AT2'" in warning and f"check the units ({units!r})" in warning


def test_implausible_pga_after_scale_and_estimated(tmp_path):
    t, a, ref = reference()
    with pytest.warns(RecordWarning, match="above 5 g"):
        Record(t, a, scale=13.0)
    write_peer_file(tmp_path / "r.DT2", ref.displacement_samples * 1e-3, "CM")
    with pytest.warns(RecordWarning, match="the peak ground acceleration, estimated from the displacement, is "
                                           r"0\.000\d+ g, below 0\.001 g") as caught:
        record = Record.from_file(tmp_path / "r.DT2")
    assert record.attrs()["record_warning"] == str(caught[0].message)


def test_plausible_record_is_not_reported(sine_at2):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RecordWarning)
        records = [Record.from_file(sine_at2), Record.from_file(SYNTHETIC), Record.from_file(sine_at2, scale=12),
                   Record(*sine_record(), scale=0.003)]
    assert all(r.warning == "" and "record_warning" not in r.attrs() for r in records)


# --- the units key of a case file -----------------------------------------------------------------------
CASE = {"prototype": "DFP1", "dt": 0.01, "model": "compliant"}


def test_case_units_key(tmp_path):
    t, a = sine_record()
    path = tmp_path / "r.csv"
    write_text_file(path, t, a / G, header="time,acceleration")
    case = case_from({**CASE, "excitation": {"kind": "record", "file": "r.csv", "units": "g"}}, tmp_path)
    assert case.excitation.pgd == pytest.approx(Record(t, a).pgd, rel=1e-9)
    assert case.excitation.attrs()["record_units"] == "g"
    for units, problem in [(None, "excitation.file: record file .*r.csv.*cannot tell the units"),
                           ("furlongs", "excitation.units: unknown units 'furlongs'"),
                           (9.81, "excitation.units: expected units such as g"),
                           ("cm", "excitation.file: record file .*column 'acceleration' holds acceleration")]:
        excitation = {"kind": "record", "file": "r.csv", **({} if units is None else {"units": units})}
        with pytest.raises(CaseError, match=problem):
            case_from({**CASE, "excitation": excitation}, tmp_path)


def test_case_baseline_defaults_by_quantity(tmp_path):
    t, _, ref = reference()
    write_peer_file(tmp_path / "r.DT2", ref.displacement_samples, "CM")
    case = case_from({**CASE, "excitation": {"kind": "record", "file": "r.DT2"}}, tmp_path)
    assert case.excitation.baseline == "none"
    with pytest.raises(CaseError, match="excitation.file: .*baseline 'linear' removes a trend"):
        case_from({**CASE, "excitation": {"kind": "record", "file": "r.DT2", "baseline": "linear"}}, tmp_path)


@pytest.mark.parametrize("n", [2, 3, 17, 4001])
def test_the_trapezoid_integral_is_scipys_bit_for_bit(n):
    """``records.cumulative_trapezoid`` (no scipy.integrate import in a workflow job) gives scipy's bits, on
    uneven steps too."""
    rng = np.random.default_rng(n)
    x = np.cumsum(rng.uniform(0.001, 0.02, n))
    y = rng.standard_normal(n) * 10.0 ** rng.uniform(-3, 3, n)
    assert np.array_equal(records.cumulative_trapezoid(y, x), cumulative_trapezoid(y, x, initial=0.0))
