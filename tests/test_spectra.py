"""Response spectra (dccss.spectra) against closed forms, and records scaled to a spectral acceleration."""

from pathlib import Path

import numpy as np
import pytest

from dccss import spectra
from dccss.case import CaseError, case_from
from dccss.records import G, PairWarning, Record, RecordPair

RECORDS = Path(__file__).resolve().parents[1] / "config/studies/records"


@pytest.mark.parametrize("damping", [0.0, 0.02, 0.05, 0.2])
def test_a_step_of_ground_acceleration_gives_the_known_overshoot(damping):
    """a_g = a0 from rest: the peak |u| is (a0 / ω²)(1 + exp(-πζ / √(1 - ζ²))) at ω_d t = π (on the grid here)."""
    period, a0 = 0.8, 2.0
    omega_d = 2 * np.pi / period * np.sqrt(1 - damping**2)
    t = np.linspace(0.0, 3 * np.pi / omega_d, 3001)  # the peak, at π / ω_d, is sample 1000
    expected = a0 * (1 + np.exp(-np.pi * damping / np.sqrt(1 - damping**2)))
    assert spectra.psa(t, np.full(t.size, a0), period, damping) == pytest.approx(expected, rel=1e-12)


def test_a_resonant_sine_gives_the_steady_state_amplitude():
    """a_g = A sin(ω t) at the oscillator's own period, 100 cycles: PSA = A / 2ζ once the transient has
    gone (exp(-2πζ 100) = 2e-14), times sinc²(ω dt / 2), the straight lines' loss at ω (3.3e-6 here)."""
    period, damping, A = 1.3, 0.05, 1.7
    dt = period / 1000
    t = np.arange(0, 100 * 1000 + 1) * dt
    x = np.pi / 1000
    expected = A / (2 * damping) * (np.sin(x) / x) ** 2
    assert spectra.psa(t, A * np.sin(2 * np.pi * t / period), period, damping) == pytest.approx(expected, rel=1e-7)


def test_rotd_of_a_pair():
    x = Record.from_file(RECORDS / "synthetic.AT2")
    y = Record.from_file(RECORDS / "synthetic_y.AT2")
    t = x.time
    one = spectra.psa(t, x.acceleration, 1.0)
    # RotD100 of (x, 0) is x's PSA; RotD50 of (x, 0) is x's times the median of |cos θ| over 1° steps
    assert spectra.rotd(t, x.acceleration, 0 * x.acceleration, 1.0, percentile=100) == pytest.approx(one, rel=1e-14)
    median = np.median(np.abs(np.cos(np.radians(np.arange(180.0)))))
    assert spectra.rotd(t, x.acceleration, 0 * x.acceleration, 1.0) == pytest.approx(median * one, rel=1e-12)
    # turning the pair by 90° turns the orientations by 90°: RotD50 is the same
    assert spectra.rotd(t, y.acceleration, -x.acceleration, 1.0) == pytest.approx(
        spectra.rotd(t, x.acceleration, y.acceleration, 1.0), rel=1e-12)
    pair = RecordPair(x, y)
    assert spectra.spectral_acceleration(pair, 1.0, definition="geometric_mean") == pytest.approx(
        np.sqrt(one * spectra.psa(t, y.acceleration, 1.0)), rel=1e-14)
    # RotD100: the largest over orientations of the PSA of the rotated component, each computed alone
    rotated = [spectra.psa(t, np.cos(a) * x.acceleration + np.sin(a) * y.acceleration, 1.0)
               for a in np.radians(np.arange(0.0, 180.0, 1.0))]
    rotd100 = spectra.spectral_acceleration(pair, 1.0, definition="rotd100")
    assert rotd100 == pytest.approx(max(rotated), rel=1e-12)
    assert rotd100 > spectra.spectral_acceleration(pair, 1.0) > 0


CASE = {"prototype": "DFP1", "dt": 0.01, "model": "compliant"}


@pytest.mark.parametrize("file", ["synthetic.AT2", ["synthetic.AT2", "synthetic_y.AT2"]])
@pytest.mark.parametrize("definition", [None, "geometric_mean", "rotd100"])
def test_a_record_scaled_to_a_spectral_acceleration_has_it(file, definition):
    if definition and not isinstance(file, list):
        return
    spec = {"to": "spectral_acceleration", "period": 1.5, "damping": 0.05, "target": 0.42}
    if definition:
        spec["definition"] = definition
    case = case_from({**CASE, "excitation": {"kind": "record", "file": file, "scale": spec}}, RECORDS)
    sa = spectra.spectral_acceleration(case.excitation, 1.5, 0.05, definition or "rotd50")
    assert sa / G == pytest.approx(0.42, rel=1e-9)
    attrs = case.excitation.attrs()
    assert attrs["record_scaled_to_sa_g"] == 0.42 and attrs["record_scaling_period_s"] == 1.5
    unscaled = case_from({**CASE, "excitation": {"kind": "record", "file": file}}, RECORDS).excitation
    factor = 0.42 * G / spectra.spectral_acceleration(unscaled, 1.5, 0.05, definition or "rotd50")
    scale = attrs["record_scale"] if not isinstance(file, list) else attrs["record_1_scale"]
    assert scale == pytest.approx(factor, rel=1e-12)


@pytest.mark.parametrize("scale, message", [
    ({"to": "spectral_acceleration", "period": 0.0, "target": 0.4}, r"excitation\.scale\.period: must be > 0"),
    ({"to": "spectral_acceleration", "period": 1.0, "target": -0.4}, r"excitation\.scale\.target: must be > 0"),
    ({"to": "spectral_acceleration", "period": 100.0, "target": 0.4},
     r"excitation\.scale\.period: 100 s is longer than the record \(19\.99 s\)"),
    ({"to": "pga", "period": 1.0, "target": 0.4},
     r"excitation\.scale\.to: must be one of \['spectral_acceleration', 'spectrum'\]"),
    ({"to": "spectral_acceleration", "period": 1.0}, r"excitation\.scale: missing key\(s\) \['target'\]"),
    ({"to": "spectral_acceleration", "period": 1.0, "target": 0.4, "damping": 1.0},
     r"excitation\.scale\.damping: 1\.0 is outside"),
    ({"to": "spectral_acceleration", "period": 1.0, "target": 0.4, "definition": "rotd50"},
     r"excitation\.scale\.definition: says how a pair's"),
])
def test_bad_spectral_scales_are_refused(scale, message):
    with pytest.raises(CaseError, match=message):
        case_from({**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": scale}}, RECORDS)


@pytest.mark.parametrize("file", ["synthetic.AT2", ["synthetic.AT2", "synthetic_y.AT2"]])
def test_a_window_does_not_change_the_scale_to_a_spectrum(file):
    """The scale factor comes from the whole record's spectrum (it came from the window's), so the motion inside a
    window is the whole scaled record's there."""
    spec = {"to": "spectral_acceleration", "period": 2.5, "target": 0.3}
    whole = case_from({**CASE, "excitation": {"kind": "record", "file": file, "scale": spec}}, RECORDS).excitation
    cut = case_from({**CASE, "excitation": {"kind": "record", "file": file, "scale": spec, "window": [2.0, 6.0]}},
                    RECORDS).excitation
    assert cut.scaling["record_sa_unscaled_g"] == whole.scaling["record_sa_unscaled_g"]
    t = cut.time
    np.testing.assert_allclose(cut.displacement(t), whole.displacement(t), rtol=0, atol=1e-15)
    # and the window's own spectrum differs: the factor would have
    assert spectra.spectral_acceleration(cut, 2.5) != pytest.approx(0.3 * G, rel=1e-6)


@pytest.mark.parametrize("call, message", [
    (lambda t, a: spectra.psa(t, a, 0.0), r"period must be a finite number > 0 \(s\), got 0.0"),
    (lambda t, a: spectra.psa(t, a, 1.0, -0.1), r"damping must be a ratio 0 <= damping < 1, got -0.1"),
    (lambda t, a: spectra.psa(t, a, 1.0, 1.0), r"damping must be a ratio 0 <= damping < 1, got 1.0"),
    (lambda t, a: spectra.rotd(t, a, a, float("nan")), r"period must be a finite number > 0"),
])
def test_spectra_name_a_bad_period_or_damping(call, message):
    """Before: a ZeroDivisionError, a silent 181976 m/s² for a negative damping, NaN or a math domain error."""
    x = Record.from_file(RECORDS / "synthetic.AT2")
    with pytest.raises(ValueError, match=message):
        call(x.time, x.acceleration)


def test_spectral_acceleration_names_a_bad_definition_or_excitation():
    from dccss.excitation import Sine

    x = Record.from_file(RECORDS / "synthetic.AT2")
    with pytest.raises(ValueError, match=r"definition must be one of \['rotd50', 'rotd100', 'geometric_mean'\]"):
        spectra.spectral_acceleration(x, 1.0, definition="bogus")  # ignored for one component before
    with pytest.raises(TypeError, match="excitation must be a Record or a RecordPair"):
        spectra.spectral_acceleration(Sine(0.1, 6.0, 1.0), 1.0)


# --- scaling over a period range -----------------------------------------------------------------
def test_suite_factors_keep_the_mean_at_the_target_where_it_is_closest():
    rng = np.random.default_rng(3)
    target = np.linspace(0.6, 0.2, 15)
    records = target * rng.uniform(0.2, 3.0, size=(7, 15))
    for fraction, individual in ((1.0, True), (0.9, True), (1.0, False)):
        factors, fitted, suite = spectra.suite_factors(records, target, fraction, individual)
        mean = (factors[:, None] * records).mean(axis=0)
        assert mean.min() / fraction == pytest.approx(target[np.argmin(mean / target)], rel=1e-12)
        assert np.all(mean >= fraction * target * (1 - 1e-12))
        # the least such factor: a smaller suite factor leaves the mean below somewhere
        assert np.any(((1 - 1e-9) * factors[:, None] * records).mean(axis=0) < fraction * target)
        if individual:  # each record's own fit: the geometric mean of target / Sa
            assert fitted == pytest.approx([np.prod(target / r) ** (1 / 15) for r in records], rel=1e-12)
        else:  # one factor for all: the records keep their relative intensities
            assert np.all(factors == suite) and np.all(fitted == 1.0)


def test_range_periods_take_the_targets_bends_and_enough_points():
    grid = spectra.range_periods(1.0, 3.0, [0.5, 1.0, 2.0, 4.0])
    assert grid[0] == 1.0 and grid[-1] == pytest.approx(3.0, rel=1e-15) and 2.0 in grid
    assert np.all(np.diff(grid) > 0) and len(grid) >= spectra.PER_DECADE * np.log10(3.0)
    assert len(spectra.range_periods(1.0, 1.1)) >= spectra.LEAST_POINTS


TARGET = {"period": [0.1, 1.0, 2.0, 4.0], "sa": [0.5, 0.5, 0.25, 0.125]}


@pytest.mark.parametrize("file", ["synthetic.AT2", ["synthetic.AT2", "synthetic_y.AT2"]])
def test_a_record_scaled_over_a_range_is_nowhere_below_the_target(file):
    """A record alone is a suite of one: its spectrum, computed again from the scaled record at each period,
    is at or above fraction x target over the range and touches it at one period."""
    spec = {"to": "spectrum", "target": TARGET, "periods": [1.0, 3.0], "fraction": 0.9}
    if isinstance(file, list):
        spec["definition"] = "rotd100"
    case = case_from({**CASE, "excitation": {"kind": "record", "file": file, "scale": spec}}, RECORDS)
    grid = spectra.range_periods(1.0, 3.0, TARGET["period"])
    sa = np.array([spectra.spectral_acceleration(case.excitation, T, 0.05, spec.get("definition", "rotd50"))
                   for T in grid]) / G
    ratio = sa / (0.9 * np.interp(grid, TARGET["period"], TARGET["sa"]))
    assert ratio.min() == pytest.approx(1.0, rel=1e-9) and np.all(ratio > 1 - 1e-9)
    attrs = case.excitation.attrs()
    scale = attrs["record_scale"] if not isinstance(file, list) else attrs["record_1_scale"]
    assert attrs["record_scaled_to"] == "spectrum" and list(attrs["record_scaling_periods_s"]) == [1.0, 3.0]
    assert scale == attrs["record_scaling_fit"] * attrs["record_scaling_suite_factor"]
    # a given suite factor is applied to the record's own fit
    given = case_from({**CASE, "excitation": {"kind": "record", "file": file,
                                              "scale": {**spec, "suite_factor": 2.0}}}, RECORDS).excitation.attrs()
    assert given["record_scaling_suite_factor"] == 2.0 and given["record_scaling_fit"] == attrs["record_scaling_fit"]


def test_a_target_spectrum_file_is_read(tmp_path):
    (tmp_path / "target.csv").write_text("# design spectrum\nperiod, sa\n0.1, 0.5\n1.0, 0.5\n2.0, 0.25 # bend\n"
                                         "4.0, 0.125\n")
    (tmp_path / "synthetic.AT2").write_bytes((RECORDS / "synthetic.AT2").read_bytes())
    scale = {"to": "spectrum", "periods": [1.0, 3.0]}
    from_file = case_from({**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2",
                                                  "scale": {**scale, "target": "target.csv"}}}, tmp_path)
    inline = case_from({**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2",
                                               "scale": {**scale, "target": TARGET}}}, tmp_path)
    assert from_file.excitation.scale == inline.excitation.scale


@pytest.mark.parametrize("scale, message", [
    ({"target": {"period": [1.0, 0.5], "sa": [0.1, 0.2]}}, "target: the periods must be at least two, > 0 and incr"),
    ({"target": {"period": [1.0, 2.0], "sa": [0.1]}}, "target: expected lists period (s) and sa (g) of the same"),
    ({"target": {"period": [1.0, 2.0], "sa": [0.1, 0.0]}}, "target: every Sa must be a number > 0"),
    ({"target": "missing.csv"}, "target: cannot read the target spectrum 'missing.csv'"),
    ({"periods": [3.0, 1.0]}, "periods: expected T_low < T_high, got [3.0, 1.0]"),
    ({"periods": [0.05, 3.0]}, "periods: the range [0.05, 3.0] s is not within the target's periods 0.1 to 4 s"),
    ({"fraction": 0.0}, "fraction: must be > 0"),
    ({"individual": "yes"}, "individual: expected true (each record fitted to the target first) or false"),
    ({"definition": "rotd100"}, "definition: says how a pair's spectral acceleration is taken"),
    ({"to": "spectra"}, "to: must be one of ['spectral_acceleration', 'spectrum'], got 'spectra'"),
    ({"period": 1.0}, "unknown key"),
])
def test_bad_range_scaling_is_refused_naming_the_key(scale, message):
    spec = {"to": "spectrum", "target": TARGET, "periods": [1.0, 3.0], **scale}
    with pytest.raises(CaseError) as err:
        case_from({**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": spec}}, RECORDS)
    assert f"excitation.scale.{message}" in str(err.value) or message in str(err.value)


def test_periods_beyond_the_record_are_refused():
    spec = {"to": "spectrum", "target": {"period": [0.1, 100.0], "sa": [0.3, 0.1]}, "periods": [1.0, 50.0]}
    with pytest.raises(CaseError, match=r"excitation.scale.periods: 50 s is longer than the record"):
        case_from({**CASE, "excitation": {"kind": "record", "file": "synthetic.AT2", "scale": spec}}, RECORDS)


def test_a_pair_of_unequal_components_cut_by_a_window_is_scaled_on_what_both_cover(tmp_path):
    """Components of 1200 and 1400 samples, a window both cover: accepted with a factor, and (before,
    refused) scaled to a spectral acceleration from the part both components cover."""
    from dccss.records import read_at2, write_at2

    dt, a = read_at2(RECORDS / "synthetic.AT2")
    _, b = read_at2(RECORDS / "synthetic_y.AT2")
    write_at2(tmp_path / "Q_000.AT2", dt, a[:1200])
    write_at2(tmp_path / "Q_090.AT2", dt, b[:1400])
    spec = {"to": "spectral_acceleration", "period": 1.0, "target": 0.3}
    excitation = {"kind": "record", "file": ["Q_000.AT2", "Q_090.AT2"], "window": [0.0, 10.0]}
    # the spectrum is the whole record's: of the time both cover (the run is the window's, which drops nothing)
    with pytest.warns(PairWarning, match=r"run over the 11.99 s all cover, 0 to 11.99 s \(pair_span: common\); "
                                         r"dropped 'Q_090.AT2': 2 s"):
        case = case_from({**CASE, "excitation": {**excitation, "scale": spec}}, tmp_path)
    both = RecordPair.from_files([tmp_path / "Q_000.AT2", tmp_path / "Q_090.AT2"], window=(0.0, 1199 * dt))
    expected = 0.3 * G / spectra.spectral_acceleration(both, 1.0)
    assert case.excitation.attrs()["record_1_scale"] == pytest.approx(expected, rel=1e-12)


def test_the_orientation_peaks_are_those_over_every_sample():
    """``orientation_peaks`` skips the samples that cannot give a peak: the same values, bit for bit, as the
    largest |u_x cos θ + u_y sin θ| over all samples, whatever the motion's shape."""
    rng = np.random.default_rng(7)
    c, s = np.cos(spectra.ORIENTATIONS), np.sin(spectra.ORIENTATIONS)
    for n in (2, 50, 3000):
        for shape in ((1.0, 1.0), (1.0, 1e-6), (0.0, 0.0), (3.0, 0.5)):
            u = rng.normal(size=(n, 2)) * shape
            every = np.max(np.abs(c[None, :] * u[:, :1] + s[None, :] * u[:, 1:]), axis=0)
            assert np.array_equal(spectra.orientation_peaks(u), every)


def test_a_spectrum_is_computed_once_and_then_read_from_the_cache(tmp_path, monkeypatch):
    """Snakemake reads a study at each start (and in each cluster job): a suite's spectra are kept on disk by
    the record's attributes, periods, damping, definition and code; read back bit for bit."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    record = Record.from_file(RECORDS / "synthetic.AT2")
    periods = spectra.range_periods(1.0, 2.0)
    first = spectra.cached_spectrum(record, periods)
    assert np.array_equal(first, spectra.spectrum(record, periods))
    assert len(list((tmp_path / "dccss/spectra").glob("*.npy"))) == 1

    def computed(*args, **kwargs):
        raise AssertionError("computed again")

    monkeypatch.setattr(spectra, "spectrum", computed)
    assert np.array_equal(spectra.cached_spectrum(record, periods), first)
    with pytest.raises(AssertionError, match="computed again"):  # another damping, another record: computed
        spectra.cached_spectrum(record, periods, damping=0.02)
    with pytest.raises(AssertionError, match="computed again"):
        spectra.cached_spectrum(Record.from_file(RECORDS / "synthetic.AT2", scale=2.0), periods)
    # a damaged entry (empty, cut short, not a spectrum) is computed again and replaced
    entry = next((tmp_path / "dccss/spectra").glob("*.npy"))
    monkeypatch.setattr(spectra, "spectrum", lambda *a, **k: first)
    for damage in (b"", entry.read_bytes()[:100]):
        entry.write_bytes(damage)
        assert np.array_equal(spectra.cached_spectrum(record, periods), first)
    for wrong in (np.full(periods.shape, np.nan), first.astype(np.int64), -first):
        np.save(entry, wrong)
        assert np.array_equal(spectra.cached_spectrum(record, periods), first)
    assert np.array_equal(np.load(entry), first)
    # a cache that cannot be written is skipped
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "file"))
    (tmp_path / "file").write_text("not a folder")
    monkeypatch.setattr(spectra, "spectrum", lambda *a, **k: first)
    assert np.array_equal(spectra.cached_spectrum(record, periods), first)
