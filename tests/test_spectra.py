"""Response spectra (dccss.spectra) against closed forms, and records scaled to a spectral acceleration."""

from pathlib import Path

import numpy as np
import pytest

from dccss import spectra
from dccss.case import CaseError, case_from
from dccss.records import G, Record, RecordPair

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
    ({"to": "pga", "period": 1.0, "target": 0.4}, r"excitation\.scale\.to: must be one of \['spectral_acceleration'\]"),
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
