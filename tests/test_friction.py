"""Friction laws of the isolated structure (dccss.mechanics.friction): each law's μ, the limits that tie
them to Coulomb friction, two surfaces, the property factor and the plates' heating."""

import math
from pathlib import Path

import numpy as np
import pytest

from dccss.case import case_from
from dccss.checks import CaseError
from dccss.mechanics.friction import LAWS, TEMPERATURE, VELOCITY, VELOCITY_PRESSURE, row, surface_mu
from dccss.mechanics.structure import Structure, StructureError, respond, solve
from dccss.mechanics.structure.heat import plate_temperatures
from dccss.paper.prototypes import DFP1
from dccss.records import Record, RecordPair

RECORDS = "config/studies/records"
L = float(DFP1.L)


def _one(window=None):
    return Record.from_file(f"{RECORDS}/synthetic.AT2", scale=2.0, window=window)


def _pair(window=None):
    return RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=2.0,
                                 window=window)


def _run(record, friction, **more):
    return respond(record.ground_acceleration(), record.time, DFP1, Structure(friction, **more))


# --- each law's μ ---------------------------------------------------------------------------------------------
def test_each_law_gives_its_formula():
    v = np.array([0.0, 0.01, 0.1, 1.0])
    law = {"slow": 0.03, "fast": 0.09, "rate": 20.0}
    assert np.allclose(VELOCITY.mu(VELOCITY.values(law), v), 0.09 - 0.06 * np.exp(-20.0 * v), rtol=0, atol=1e-15)
    law = {"slow": 0.03, "fast0": 0.1, "delta": 0.04, "alpha": 5e-8, "rate": 20.0, "pressure": 2e7}
    values = VELOCITY_PRESSURE.values(law)
    for p in (0.0, 1e7, 4e7):
        fast = 0.1 - 0.04 * math.tanh(5e-8 * p) if p > 0 else 0.1
        assert np.allclose(VELOCITY_PRESSURE.mu(values, v, pressure=p), fast - (fast - 0.03) * np.exp(-20.0 * v),
                           rtol=0, atol=1e-15)
    values = TEMPERATURE.values({"mu_ref": 0.06, "contact_radius": 0.1, "pressure": 3e7, "p_ref": 2e7})
    for T in (20.0, 150.0):
        kp, kT = 0.7 ** (0.02 * 10.0), 0.789 * (0.7 ** (T / 50.0) + 0.4)
        assert np.allclose(TEMPERATURE.mu(values, v, temperature=T), 0.06 * kp * kT * (1 - 0.5 * np.exp(-100.0 * v)),
                           rtol=0, atol=1e-15)
    assert set(LAWS) == {"coulomb", "velocity", "velocity_pressure", "temperature"}


def test_a_laws_bad_parameters_are_named():
    with pytest.raises(CaseError) as err:
        case_from({"prototype": "DFP1", "dt": 0.01, "model": "compliant",
                   "excitation": {"kind": "sine", "amplitude": 0.1, "omega": 3.0, "duration": 1.0},
                   "structure": {"friction": {"law": "velocity", "slow": 0.03, "fast": 1.2, "speed": 3}}})
    messages = str(err.value)
    assert "structure.friction: unknown key(s) ['speed'] of the velocity law" in messages
    assert "structure.friction.rate: missing" in messages and "structure.friction.fast: 1.2 is outside" in messages
    with pytest.raises(StructureError, match=r"structure.friction.law: must be one of \['coulomb', 'velocity', "):
        Structure({"law": "stribeck"})
    with pytest.raises(StructureError, match="give the contact pressure at N = W as pressure, or as load and area"):
        Structure({"law": "velocity_pressure", "slow": 0.03, "fast0": 0.1, "delta": 0.02, "alpha": 1e-8, "rate": 9})


# --- the limits that tie the laws to Coulomb friction -----------------------------------------------------------
@pytest.mark.parametrize("components", [1, 2])
def test_a_coulomb_law_is_the_number_bit_for_bit(components):
    record = _one() if components == 1 else _pair()
    plain, law = _run(record, 0.05), _run(record, {"law": "coulomb", "mu": 0.05})
    for a, b in zip(plain[:5], law[:5]):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("components", [1, 2])
def test_a_speed_law_with_slow_equal_to_fast_is_coulomb(components):
    """In one component against the exact solution (another integrator: 1e-9 m), in two bit for bit (the same
    integrator serves both)."""
    record = _one() if components == 1 else _pair()
    coulomb = _run(record, 0.05)
    law = _run(record, {"law": "velocity", "slow": 0.05, "fast": 0.05, "rate": 30.0})
    assert np.max(np.abs(law.stroke - coulomb.stroke)) < 1e-9
    if components == 2:
        assert np.array_equal(law.stroke, coulomb.stroke) and np.array_equal(law.velocity, coulomb.velocity)
    assert np.max(np.abs(coulomb.stroke)) > 0.05
    assert np.all(law.friction == 0.05)


@pytest.mark.parametrize("components", [1, 2])
def test_a_large_rate_tends_to_coulomb_at_fast(components):
    """rate → ∞: μ = fast at any speed but zero; only the breakaway (at slow) differs, and it matters
    less the faster μ reaches fast."""
    record = _one() if components == 1 else _pair()
    fast = _run(record, 0.06)
    gaps = [np.max(np.abs(_run(record, {"law": "velocity", "slow": 0.03, "fast": 0.06, "rate": rate}).stroke
                          - fast.stroke)) for rate in (1e2, 1e3, 1e4)]
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 2e-3


def test_the_friction_falls_as_the_plate_heats_and_the_stroke_grows():
    record = _one()
    law = {"law": "temperature", "mu_ref": 0.06, "contact_radius": 0.15, "load": 1.5e6}
    hot = _run(record, law)
    cold = _run(record, {**law, "temperature_factor": False})
    assert hot.temperature.shape == (record.time.size, 1) and hot.temperature[0, 0] == 20.0
    # the surface heats while the slider rubs it, and cools as the heat spreads into the plate after
    assert hot.temperature.max() > 60.0 and 20.0 < hot.temperature[-1, 0] < hot.temperature.max()
    assert np.max(np.abs(hot.stroke)) > np.max(np.abs(cold.stroke))
    assert hot.friction.min() < cold.friction.min()


def test_the_plates_temperature_under_a_constant_flux_is_the_half_space_solution():
    """q constant from t = 0: ΔT(t) = (2 q / k) √(D t / π), to rounding (the sum over constant pieces is exact)."""
    n = 400
    time = np.linspace(0.0, 4.0, n + 1)
    law = np.array([row(TEMPERATURE, TEMPERATURE.values({"mu_ref": 0.05, "contact_radius": 0.2, "pressure": 2e7,
                                                         "speed_factor": False, "pressure_factor": False,
                                                         "temperature_factor": False}))])
    heat, temperature = np.zeros((n + 1, 4)), np.zeros((n + 1, 2))
    temperature[0] = 20.0
    for k in range(n):
        x = 1e-4 * (k + 1)  # a steady creep at 0.01 m/s, within the contact circle (0.04 m < 0.2 √π / 2)
        temperature[k + 1] = temperature[k]
        plate_temperatures(k, time[k], time[k + 1], x - 1e-4, 0.0, x, 0.0, 1.0, law.tolist(), heat, temperature,
                           k + 1)
    q = 0.05 * 2e7 * 0.01
    assert np.allclose(heat[:n, 2], q, rtol=1e-12) and np.array_equal(heat[:n, 1], time[1:])
    D, k = 4.44e-6, 18.0
    assert np.allclose(temperature[:, 0], 20.0 + 2 * q / k * np.sqrt(D * time / math.pi), rtol=1e-12, atol=1e-9)


# --- two surfaces and the property factor ------------------------------------------------------------------------
def test_two_surfaces_combine_by_the_work_argument_at_their_own_speeds():
    R1, R3 = float(DFP1.R1), float(DFP1.R3)
    laws = [{"law": "velocity", "slow": 0.02, "fast": 0.07, "rate": 25.0}, {"law": "velocity", "slow": 0.04,
                                                                            "fast": 0.05, "rate": 5.0}]
    s = Structure(laws, friction_on="surfaces")
    rows = s.rows(DFP1)
    for v in (0.0, 0.05, 0.3):
        mu1 = 0.07 - 0.05 * math.exp(-25.0 * R1 / L * v)
        mu3 = 0.05 - 0.01 * math.exp(-5.0 * R3 / L * v)
        device = sum(r[1] * r[3] * surface_mu(r, r[2] * v, 1.0, 20.0) for r in rows)
        assert device == pytest.approx((mu1 * R1 + mu3 * R3) / L, abs=1e-15)
    # two numbers are Coulomb friction of the device's (μ1 R1 + μ3 R3) / L
    assert Structure([0.03, 0.05], friction_on="surfaces").device_friction(DFP1) == pytest.approx(
        (0.03 * R1 + 0.05 * R3) / L, abs=1e-16)
    record = _one()
    two = _run(record, [0.03, 0.05], friction_on="surfaces")
    one = _run(record, (0.03 * R1 + 0.05 * R3) / L)
    assert np.max(np.abs(two.stroke - one.stroke)) < 1e-12


@pytest.mark.parametrize("components", [1, 2])
def test_the_property_factor_multiplies_every_coefficient(components):
    record = _one() if components == 1 else _pair()
    law = {"law": "velocity", "slow": 0.03, "fast": 0.06, "rate": 20.0}
    upper = _run(record, law, factor=1.3)
    scaled = _run(record, {"law": "velocity", "slow": 0.039, "fast": 0.078, "rate": 20.0})
    assert np.max(np.abs(upper.stroke - scaled.stroke)) < 1e-9
    assert _run(record, 0.05, factor=0.8).peaks == _run(record, 0.05 * 0.8).peaks
    with pytest.raises(StructureError, match=r"structure.property: -1.0 is outside λ > 0"):
        Structure(0.05, factor=-1.0)


def test_a_case_carries_the_laws_coefficient_speed_and_temperature():
    case = case_from({"prototype": "DFP1", "dt": 0.01, "model": "compliant",
                      "excitation": {"kind": "record", "file": f"{RECORDS}/synthetic.AT2", "scale": 2.0},
                      "structure": {"friction": {"law": "temperature", "mu_ref": 0.06, "contact_radius": 0.15,
                                                 "load": 1.5e+6}, "property": 0.9}}, Path("."))
    ds = case.run()
    assert ds["friction_coefficient"].attrs["units"] == "1" and ds["surface_temperature"].attrs["units"] == "degC"
    assert ds["sliding_speed"].attrs["units"] == "m s-1"
    assert np.allclose(ds["sliding_speed"].values, np.abs(ds["stroke_velocity"].values), rtol=0, atol=0)
    assert ds.attrs["structure_friction_law"] == "temperature" and ds.attrs["structure_property_factor"] == 0.9
    assert ds["surface_temperature"].values.max() > 40.0


# --- bounds in a study ------------------------------------------------------------------------------------------
def _bounds_study(tmp_path, **changes):
    import shutil

    from dccss.studies import Study, combine, run_chunk

    (tmp_path / "records").mkdir(exist_ok=True)
    for name in ("synthetic.AT2", "synthetic_y.AT2"):
        shutil.copy(f"{RECORDS}/{name}", tmp_path / "records" / name)
    config = {"study": {"name": "bounds"}, "prototype": "DFP1", "dt": 0.02, "models": ["compliant"],
              "excitation": {"kind": "record", "scale": 2.0},
              "structure": {"friction": {"law": "velocity", "slow": 0.03, "fast": 0.07, "rate": 20.0},
                            "property": {"lower": 0.8, "upper": 1.3}},
              "sweep": {"record": ["records/synthetic.AT2", "records/synthetic_y.AT2"],
                        "property": ["lower", "nominal", "upper"]}, **changes}
    study = Study.from_config(config, tmp_path)
    return study, combine(study, {"compliant": [run_chunk(study, "compliant", k) for k in range(study.grid.n_chunks)]})


def test_the_envelope_over_the_bounds_is_the_largest_of_the_bound_runs(tmp_path):
    study, ds = _bounds_study(tmp_path)
    for name in ("stroke_max_abs", "shear_ratio_max_abs", "stroke_max_abs_suite", "shear_ratio_max_abs_suite"):
        assert np.array_equal(ds[f"{name}_envelope"].values, np.max(ds[name].values, axis=ds[name].dims.index(
            "property")), equal_nan=True)
    # each bound is the law with every coefficient times its factor
    upper = ds["stroke_max_abs"].sel(model="compliant", property="upper", record="synthetic").values
    alone = respond(_one().ground_acceleration(), study.grid.times(0.02), DFP1,
                    Structure({"law": "velocity", "slow": 0.03, "fast": 0.07, "rate": 20.0}, factor=1.3))
    assert float(upper) == alone.peaks[0]
    lower, nominal = (ds["stroke_max_abs"].sel(model="compliant", property=p).values for p in ("lower", "nominal"))
    assert np.all(lower > nominal)  # less friction, more displacement on this record


def _panel(fig, title):
    return next(ax for ax in fig.axes if ax.get_title().startswith(title))


def test_a_suite_crossed_with_bounds_draws_each_bound_and_each_records_envelope(tmp_path):
    """Records x bounds: a mark per record and bound (a marker per bound), each record's largest over the
    bounds as a bar at it, the suite's mean of the bounds' largest as a line across (its plots failed with
    'only 0-dimensional arrays can be converted to Python scalars')."""
    from matplotlib.collections import LineCollection

    from dccss.studies import plots

    study, ds = _bounds_study(tmp_path)
    fig = plots.maps(ds, {}, "caption")
    ax = _panel(fig, "max |stroke u|")
    (bars,) = [c for c in ax.collections if isinstance(c, LineCollection) and c.get_gid() == "envelope"]
    heights = [segment[0][1] for segment in bars.get_segments()]
    assert np.allclose(heights, 100.0 * ds["stroke_max_abs_envelope"].sel(model="compliant").values, rtol=1e-12)
    marks = {tuple(np.round(ln.get_ydata(), 12)) for ln in ax.get_lines()}
    for bound in ("lower", "nominal", "upper"):
        assert tuple(np.round(100.0 * ds["stroke_max_abs"].sel(model="compliant", property=bound).values, 12)) in marks
    mean = 100.0 * float(ds["stroke_max_abs_suite_envelope"].sel(model="compliant", statistic="mean"))
    assert any(np.allclose(ln.get_ydata(), mean) for ln in ax.get_lines())
    labels = [t.get_text() for legend in fig.legends for t in legend.get_texts()]
    assert {"property = lower", "property = nominal", "property = upper"} <= set(labels)


def test_bounds_crossed_with_a_scale_draw_their_envelope(tmp_path):
    """Scale x bounds: a curve per bound, and the largest over the bounds drawn over them (it was computed, not
    drawn)."""
    from dccss.studies import plots

    study, ds = _bounds_study(tmp_path, excitation={"kind": "record", "file": "records/synthetic.AT2"},
                              sweep={"scale": [1.0, 2.0], "property": ["lower", "nominal", "upper"]})
    fig = plots.maps(ds, {}, "caption")
    for title, name, factor in (("max |stroke u|", "stroke_max_abs", 100.0), ("max |F/W|", "shear_ratio_max_abs", 1.0)):
        (line,) = [ln for ln in _panel(fig, title).get_lines() if ln.get_gid() == "envelope"]
        assert np.allclose(line.get_ydata(), factor * ds[f"{name}_envelope"].sel(model="compliant").values, rtol=1e-12)


def test_a_nominal_property_axis_is_the_study_without_it(tmp_path):
    _, plain = _bounds_study(tmp_path, sweep={"record": ["records/synthetic.AT2", "records/synthetic_y.AT2"]})
    _, nominal = _bounds_study(tmp_path, sweep={"record": ["records/synthetic.AT2", "records/synthetic_y.AT2"],
                                                "property": ["nominal"]})
    for name in ("stroke_max_abs", "theta2_max_abs", "shear_ratio_max_abs"):
        assert np.array_equal(plain[name].values, nominal[name].sel(property="nominal").values)


def test_a_bound_without_its_factor_is_named(tmp_path):
    from dccss.studies import StudyError

    with pytest.raises(StudyError, match=r"sweep.property\[2\]: 'upper' needs its factor, structure.property.upper"):
        _bounds_study(tmp_path, structure={"friction": 0.05, "property": {"lower": 0.8}})
    with pytest.raises(StudyError, match=r"sweep.property\[0\]: must be one of \['lower', 'nominal', 'upper'\]"):
        _bounds_study(tmp_path, sweep={"record": ["records/synthetic.AT2"], "property": ["low"]})


def test_dccss_check_and_run_name_the_law(tmp_path, capsys):
    from dccss import cli

    case = tmp_path / "case.yaml"
    case.write_text(f"""prototype: DFP1
excitation: {{kind: record, file: {Path(RECORDS).resolve()}/synthetic.AT2, scale: 2.0}}
dt: 0.01
model: compliant
structure: {{friction: {{law: velocity, slow: 0.03, fast: 0.07, rate: 20.0}}, property: 1.3}}
""")
    assert cli.main(["check", str(case)]) == 0
    assert "a structure (friction: the velocity law)" in capsys.readouterr().out
    assert cli.main(["run", str(case), "-o", str(tmp_path / "out.nc")]) == 0
    assert "structure (velocity law, mu = 0.039 at rest, lambda = 1.3" in capsys.readouterr().out


@pytest.mark.parametrize("components", [1, 2])
@pytest.mark.parametrize("law", [{"law": "velocity", "slow": 0.03, "fast": 0.07, "rate": 20.0},
                                 {"law": "velocity_pressure", "slow": 0.03, "fast0": 0.09, "delta": 0.03,
                                  "alpha": 3e-8, "rate": 15.0, "pressure": 3e7},
                                 {"law": "temperature", "mu_ref": 0.06, "contact_radius": 0.15, "load": 1.5e6}])
def test_every_law_gives_the_same_bits_compiled_and_interpreted(law, components):
    """The record's first 4 s: the largest strokes, and sticking and sliding phases in turn."""
    record = _one((0.0, 4.0)) if components == 1 else _pair((0.0, 4.0))
    ground, t = record.ground_acceleration(), record.time
    rows = Structure(law).rows(DFP1)
    runs = [solve(ground, t, L, math.nan, 0.02, compiled=compiled, law=rows) for compiled in (True, False)]
    assert 0 < np.count_nonzero(runs[0].sticking) < t.size and np.count_nonzero(np.diff(runs[0].sticking))
    for a, b in zip(runs[0][:5], runs[1][:5]):
        assert np.array_equal(a, b)
    assert np.array_equal(runs[0].friction, runs[1].friction)


def test_the_plates_heat_does_not_depend_on_the_times_asked_for():
    """The heat is kept over the record's sample intervals: asking for the response at half the sample
    interval moves neither the temperature nor the stroke at the samples beyond the integration's
    accuracy (before, the heat was per interval of the integration: 6 °C and 0.5 mm)."""
    record = _one()
    law = Structure({"law": "temperature", "mu_ref": 0.06, "contact_radius": 0.15, "load": 1.5e6})
    coarse = respond(record.ground_acceleration(), record.time, DFP1, law)
    half = np.union1d(record.time, 0.5 * (record.time[:-1] + record.time[1:]))
    fine = respond(record.ground_acceleration(), half, DFP1, law)
    at = np.isin(half, record.time)
    assert np.max(np.abs(fine.temperature[at] - coarse.temperature)) < 1e-8
    assert np.max(np.abs(fine.stroke[at] - coarse.stroke)) < 1e-10
    assert coarse.temperature.max() > 60.0
