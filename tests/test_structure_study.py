"""Studies of an isolated structure: friction and damping as sweep axes, the shipped example."""

import numpy as np
import pytest
import xarray as xr
from conftest import ROOT, changed

from dccss.case import CaseError
from dccss.mechanics.structure import Structure, respond
from dccss.studies import Study, combine, history_case, run_chunk
from dccss.studies.combine import study_attrs

RECORDS = ROOT / "config/studies/records"
SINE = {
    "study": {"name": "frictions"},
    "prototype": "DFP1",
    "excitation": {"kind": "sine", "amplitude": 0.08, "omega": 3.0, "duration": 4.0},
    "structure": {"friction": 0.05},
    "dt": 0.01,
    "models": ["compliant", "stick_slip"],
    "sweep": {"friction": [0.02, 0.05], "damping": [0.0, 0.1], "amplitude": [0.05, 0.08]},
    "histories": [{"friction": 0.02, "damping": 0.1, "amplitude": 0.08}],
}


def _combined(study):
    return combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})


def test_friction_and_damping_sweep_the_structure_of_each_case():
    study = Study.from_config(SINE)
    ds = _combined(study)
    assert ds["friction"].attrs["units"] == "1" and ds["damping"].attrs["units"] == "1"
    assert ds["stroke_max_abs"].attrs["units"] == "m"
    # friction and damping are axes: no single value of either is the study's (before: the file's 0.05)
    assert ds.attrs["structure_friction_on"] == "device"
    assert not {"structure_friction", "structure_friction_given", "structure_damping"} & set(ds.attrs)
    for mu in (0.02, 0.05):
        for zeta in (0.0, 0.1):
            for amplitude in (0.05, 0.08):
                from dccss.excitation import Sine

                sine = Sine(amplitude, 3.0, 4.0)
                r = respond(sine.ground_acceleration(), study.grid.times(0.01), study.grid.pendulums([0])[0],
                            Structure(mu, zeta))
                case = ds.sel(friction=mu, damping=zeta, amplitude=amplitude, model="stick_slip")
                # the peaks over the ground's samples too, not only the steps
                assert float(case["stroke_max_abs"]) == r.peaks[0] >= np.max(np.abs(r.stroke))
                assert float(case["stroke_end"]) == r.stroke[-1, 0]
                assert float(case["shear_ratio_max_abs"]) == r.peaks[1] >= np.max(np.abs(r.shear_ratio))
    # more friction, less stroke; the pad follows the stroke (θ² ≈ asin(u / L))
    s = ds.sel(model="compliant", damping=0.0, amplitude=0.08)
    assert float(s.sel(friction=0.02)["stroke_max_abs"]) > float(s.sel(friction=0.05)["stroke_max_abs"])
    L = float(study.grid.geometry([0]).L[0])
    # (θ² at the steps, the stroke's peak over the ground's samples too: between steps Δt apart the peak of a
    # motion of frequency ω = 3 rad/s is at most 1 - cos(ω Δt / 2) ≈ (ω Δt)² / 8 above the steps' largest)
    theta2 = np.radians(ds.sel(model="compliant")["theta2_max_abs"].values)
    follows = np.arcsin(ds.sel(model="compliant")["stroke_max_abs"].values / L)
    assert np.all(theta2 <= follows * (1 + 1e-5)) and np.all(theta2 >= follows * (1 - (3.0 * 0.01) ** 2 / 8 - 1e-5))
    # a history point carries its structure into its case, and equals the sweep
    case = history_case(study, 0, "stick_slip")
    assert case.structure == Structure(0.02, 0.1)
    history = case.run()
    assert float(ds.sel(model="stick_slip", friction=0.02, damping=0.1, amplitude=0.08)["stroke_max_abs"]) == \
        history.attrs["structure_stroke_max_abs_m"] >= np.max(np.abs(history["stroke"].values))


def test_a_study_without_a_structure_key_gets_one_from_its_friction_axis():
    config = changed(SINE, sweep={"friction": [0.03, 0.06]}, histories=[])
    del config["structure"]
    study = Study.from_config(config)
    assert study.structure == Structure(0.03, 0.0)
    assert [s.friction for s in study.grid.structures(np.arange(2))] == [0.03, 0.06]
    assert Study.from_config(changed(SINE, structure=None, sweep={"amplitude": [0.05]}, histories=[])).structure is None


@pytest.mark.parametrize("changes, message", [
    (dict(sweep={"friction": [0.02, 1.5]}), r"sweep\.friction\[1\]: 1\.5 is outside 0 <= μ < 1"),
    (dict(sweep={"friction": [-0.01]}), r"sweep\.friction\[0\]: -0\.01 is outside"),
    (dict(sweep={"damping": [0.1, -0.2]}), r"sweep\.damping\[1\]: -0\.2 is outside 0 <= ζ < 1"),
    (dict(structure={"damping": 0.1}, sweep={"amplitude": [0.05]}), r"structure\.friction: missing"),
    (dict(structure={"friction": 0.05, "mass": 2.0}), r"structure: unknown key\(s\) \['mass'\]"),
    (dict(structure={"friction": 2.0}), r"structure\.friction: 2\.0 is outside"),
    (dict(structure="stiff"), r"structure: expected a mapping"),
])
def test_bad_structures_in_a_study_are_refused_naming_the_key(changes, message):
    with pytest.raises(CaseError, match=message):
        Study.from_config(changed(SINE, histories=[], **changes))


def test_a_record_pair_study_drives_each_component_through_the_structure(tmp_path):
    for name in ("synthetic.AT2", "synthetic_y.AT2"):
        (tmp_path / name).write_bytes((RECORDS / name).read_bytes())
    pair = {"kind": "record", "file": ["synthetic.AT2", "synthetic_y.AT2"], "window": [0.0, 4.0], "scale": 1.5}
    config = {"study": {"name": "pair"}, "prototype": "DFP1", "excitation": pair, "dt": 0.01, "models": ["compliant"],
              "structure": {"friction": 0.04}, "sweep": {"component": ["x", "both"], "scale": [1.0, 2.0]}}
    study = Study.from_config(config, tmp_path)
    t = study.grid.times(0.01)
    imposed, responses = study.grid.imposed(np.arange(4), t)
    assert imposed.shape == (len(t), 4, 2)
    assert not imposed[:, 0, 1].any()  # x alone: no y stroke
    # scale 2 of the x component (of the pair read at scale 1.5): the response to twice its acceleration
    from dccss.mechanics.structure import Ground

    g = study.excitation.excitation.x.ground_acceleration()
    r = respond(Ground(g.time, 2.0 * g.a0, 2.0 * g.a1), t, study.grid.pendulums([0])[0], Structure(0.04))
    # (the component runs as two-component motion with y = 0: the circular interaction's integrator,
    # equal to the exact one-component solution to 1e-9 m)
    assert np.allclose(imposed[:, 1, 0], 0.0 - r.stroke[:, 0], rtol=0, atol=1e-9)
    assert np.max(np.abs(responses[1].stroke)) == pytest.approx(np.max(np.abs(r.stroke)), rel=0, abs=1e-9)


def test_the_shipped_isolated_structure_study(shipped_study):
    work = shipped_study("isolated_structure")
    ds = xr.open_dataset(work / "results/studies/isolated_structure/isolated_structure.nc")
    assert dict(ds.sizes) == {"model": 2, "friction": 5, "component": 2}
    for name in ("maps.png", "maps.pdf", "histories.png", "histories.pdf", "animations/stick_slip_1.gif"):
        fresh = (work / "figures/studies/isolated_structure" / name).read_bytes()
        assert fresh == (ROOT / "figures/studies/isolated_structure" / name).read_bytes(), name
    stroke = ds["stroke_max_abs"].sel(model="stick_slip", component="both").values
    assert np.all(np.diff(stroke) < 0)  # more friction, less stroke
    history = xr.open_dataset(work / "results/studies/isolated_structure/histories/stick_slip_1.nc")
    assert history.attrs["structure_friction"] == 0.04 and "stroke_x" in history


@pytest.mark.parametrize("capacity", ["stop", "error"])
def test_the_structures_summaries_are_its_response_to_the_whole_record(capacity):
    """The structure's summaries are the demand on the device: its response to the whole record, which does
    not depend on the pad. A case that capacity "stop" ends at the ring, or that fails (capacity "error",
    marked), keeps them (before, they ended at the ring, or were NaN, and a suite's statistics left out
    the records of largest stroke); its history ends at the ring."""
    study = Study.from_config(changed(SINE, capacity=capacity, on_failure="mark", chunk_size=2,
                                      sweep={"friction": [0.02], "amplitude": [0.08, 0.4]},
                                      histories=[{"friction": 0.02, "amplitude": a} for a in (0.08, 0.4)]))
    part = run_chunk(study, "compliant", 0)
    assert list(part["capacity_exceeded"].values) == [0, 1]
    assert list(part["failed"].values) == [0, int(capacity == "error")]
    for i in range(2):
        history = history_case(study, i, "compliant").run()
        whole = study.grid.imposed(np.arange(i, i + 1), study.grid.times(0.01))[1][0]
        assert part["stroke_max_abs"].values[i] == whole.peaks[0]
        assert part["stroke_end"].values[i] == whole.stroke[-1, 0]
        ended = np.abs(history["stroke"].values).max()
        assert ended == pytest.approx(whole.peaks[0], rel=1e-3) if i == 0 else ended < 0.9 * whole.peaks[0]


def test_a_study_names_its_structure_as_its_histories_do():
    """``structure_friction`` is the device's μ, as in a history; a surfaces' μs is ``structure_friction_given``
    (before, a study's ``structure_friction`` was the file's value, μs under friction_on: surfaces)."""
    config = changed(SINE, structure={"friction": 0.04, "friction_on": "surfaces", "damping": 0.1},
                     sweep={"amplitude": [0.05, 0.08]}, histories=[{"amplitude": 0.08}])
    study = Study.from_config(config)
    attrs = study_attrs(study, "compliant")
    assert attrs["structure_friction_given"] == 0.04 and attrs["structure_damping"] == 0.1
    assert attrs["structure_friction_on"] == "surfaces" and "structure_friction" not in attrs
    history = history_case(study, 0, "compliant").run()
    assert history.attrs["structure_friction_given"] == 0.04 and history.attrs["structure_friction"] > 0.04
    device = Study.from_config(changed(config, structure={"friction": 0.04}))
    assert study_attrs(device, "compliant")["structure_friction"] == 0.04
