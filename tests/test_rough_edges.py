"""What a newcomer meets: inputs that cannot be built refused naming the key (a hinge outside the pad, a pair's
intensity definition on single records), a history cut at a ring that says only what it kept, the intensity
study shipped with its records, and the curves of a study with the friction's bounds drawing every bound."""

from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml

from dccss.case import CaseError, case_from
from dccss.mechanics.structure import Structure
from dccss.paper.prototypes import DFP1
from dccss.records import Record
from dccss.simulation import simulate
from dccss.studies import Study, StudyError, combine, run_chunk

ROOT = Path(__file__).resolve().parent.parent
STUDIES = ROOT / "config" / "studies"
CASE = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.27, "omega": 30.0, "duration": 0.2},
        "dt": 0.001, "model": "compliant", "slider": {"kind": "articulated"}, "friction": [0.03, 0.06]}
WITH_STRUCTURE = {**CASE, "friction": None, "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces"}}


# --- the hinge -------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("base", [CASE, WITH_STRUCTURE], ids=["imposed", "structure"])
@pytest.mark.parametrize("hinge", [-0.5, 0.9, 5.0, 0.075, -0.075])
def test_a_hinge_outside_the_pad_is_refused_naming_the_key(base, hinge):
    """DFP1's pad is 0.15 m high: the hinge joins its halves inside it, |hinge| < 0.075 m (at 0.075 m it would sit
    on a cap's apex, a half of no height); -0.5 and 0.9 m gave positive pendulum lengths and were run, 5.0 m passed
    the check of a case without a structure and failed in the run."""
    with pytest.raises(CaseError, match=r"slider.hinge: .* outside the pad: .*-h2/2 < hinge < h2/2 = 0.075 m") as err:
        case_from({**base, "slider": {"kind": "articulated", "hinge": hinge}})
    assert "friction" not in str(err.value)


@pytest.mark.parametrize("base", [CASE, WITH_STRUCTURE], ids=["imposed", "structure"])
def test_a_hinge_inside_the_pad_runs(base):
    ds = case_from({**base, "slider": {"kind": "articulated", "hinge": 0.07}}).run()
    assert ds.attrs["slider_hinge_m"] == 0.07


def test_a_hinge_that_is_not_a_number_gives_one_error_about_the_hinge():
    """It gave a second error, about friction, read as a rigid slider's."""
    with pytest.raises(CaseError) as err:
        case_from({**CASE, "slider": {"kind": "articulated", "hinge": float("nan")}})
    assert str(err.value).count("\n") == 0 and "slider.hinge" in str(err.value) and "friction" not in str(err.value)


def test_a_study_refuses_a_hinge_outside_a_swept_pad_naming_the_point():
    config = {"study": {"name": "hinge"}, "prototype": "DFP1", "slider": {"kind": "articulated", "hinge": 0.06},
              "excitation": {"kind": "sine", "amplitude": 0.27, "omega": 30.0, "duration": 0.2}, "dt": 0.01,
              "models": ["compliant"], "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces"},
              "sweep": {"h2": [0.15, 0.1]}}
    with pytest.raises(StudyError, match=r"sweep point h2=0.1: slider.hinge: 0.06 m .* outside the pad"):
        Study.from_config(config)
    Study.from_config({**config, "sweep": {"h2": [0.15, 0.13]}})


# --- intensity -------------------------------------------------------------------------------------------------
def _intensity_study(**changes):
    base = {"study": {"name": "ida"}, "prototype": "DFP1", "excitation": {"kind": "record", "baseline": "linear"},
            "dt": 0.02, "models": ["compliant"], "structure": {"friction": 0.05},
            "sweep": {"record": ["records/suite/RSN100[1-3]_*.AT2"], "intensity": [0.1, 0.3]}}
    return {**base, **changes}


def test_a_pairs_definition_on_single_records_is_refused():
    with pytest.raises(StudyError, match=r"intensity.definition: 'rotd50' combines the two horizontal components"):
        Study.from_config(_intensity_study(intensity={"definition": "rotd50"}), STUDIES)
    Study.from_config(_intensity_study(intensity={"measure": "pga"}), STUDIES)


def test_record_jobs_names_only_the_pattern_that_matches_nothing():
    with pytest.raises(StudyError) as err:
        Study.from_config(_intensity_study(sweep={"record": ["nowhere/*.AT2"], "intensity": [0.1]}, record_jobs=2),
                          STUDIES)
    assert "matches no file" in str(err.value) and "record_jobs" not in str(err.value)


def test_the_shipped_intensity_study_reads_the_shipped_records_as_their_writer_writes_them(tmp_path):
    """config/studies/ida.yaml runs on config/studies/records/suite, which make_suite.py writes byte for byte."""
    sys.path.insert(0, str(ROOT / "tests"))
    from suite_records import write_suite

    names = write_suite(tmp_path, 12)
    shipped = sorted((STUDIES / "records" / "suite").glob("*.AT2"))
    assert [p.stem for p in shipped] == sorted(names)
    assert all((tmp_path / p.name).read_bytes() == p.read_bytes() for p in shipped)
    study = Study.from_config(yaml.safe_load((STUDIES / "ida.yaml").read_text()), STUDIES)
    assert sorted(study.records) == sorted(names) and study.grid.n_cases == 12 * 8 * 3


# --- a history cut at a ring -----------------------------------------------------------------------------------
def test_an_articulated_history_cut_at_a_ring_says_only_what_it_kept():
    """Under capacity: stop the history ends where the half on RB1 reaches its ring: its peaks and by how much the
    ring is passed are those of the samples kept (they were taken over the whole record, past the cut)."""
    rec = Record.from_file(STUDIES / "records" / "synthetic.AT2", scale=2.2)
    structure = Structure([0.03, 0.06], 0.02, "surfaces", slider="articulated")
    whole = simulate(DFP1, rec, dt=0.01, structure=structure)
    cut = simulate(DFP1, rec, dt=0.01, structure=structure, capacity="stop")
    assert cut.sizes["t"] < whole.sizes["t"]
    a = cut.attrs
    assert a["stroke_1_max_abs_m"] == float(np.abs(cut["stroke_1"]).max()) < whole.attrs["stroke_1_max_abs_m"]
    assert a["stroke_3_max_abs_m"] == float(np.abs(cut["stroke_3"]).max())
    assert a["structure_stroke_max_abs_m"] == float(np.abs(cut["stroke"]).max())
    assert a["ring_1_exceeded_by_m"] == pytest.approx(float(np.abs(cut["stroke_1"]).max()) - a["ring_stroke_1_m"],
                                                      abs=1e-15)
    assert 0.0 <= a["ring_1_exceeded_by_m"] < whole.attrs["ring_1_exceeded_by_m"]


def test_a_rigid_history_cut_at_the_ring_keeps_the_structures_peaks_of_what_it_kept():
    rec = Record.from_file(STUDIES / "records" / "synthetic.AT2", scale=2.2)
    structure = Structure(0.03, 0.02)
    whole = simulate(DFP1, rec, dt=0.01, structure=structure, model="compliant")
    cut = simulate(DFP1, rec, dt=0.01, structure=structure, model="compliant", capacity="stop")
    assert cut.sizes["t"] < whole.sizes["t"]
    assert cut.attrs["structure_stroke_max_abs_m"] == float(np.abs(cut["stroke"]).max()) \
        < whole.attrs["structure_stroke_max_abs_m"]


# --- curves over the friction's bounds -------------------------------------------------------------------------
def test_curves_over_an_intensity_axis_with_bounds_draw_every_bound():
    """An intensity axis crossed with the friction's bounds drew the first bound alone ("the others not drawn")."""
    from matplotlib.text import Text

    from dccss.studies import plots

    config = _intensity_study(structure={"friction": 0.05, "property": {"lower": 0.8, "upper": 1.3}},
                              sweep={"record": ["records/suite/RSN100[1-3]_*.AT2"], "intensity": [0.1, 0.3],
                                     "property": ["lower", "nominal", "upper"]})
    study = Study.from_config(config, STUDIES)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = combine(study, {m: [run_chunk(study, m, k) for k in range(study.grid.n_chunks)] for m in study.models})
    fig = plots.maps(ds, {}, "caption")
    texts = [t.get_text() for t in fig.findobj(Text)]
    assert not any("not drawn" in t for t in texts)
    assert {"property = lower", "property = nominal", "property = upper"} <= set(texts)  # the bounds' legend
    stroke = next(ax for ax in fig.axes if ax.get_title() == "max |stroke u| of the structure")
    drawn = {tuple(np.round(line.get_ydata(), 9)) for line in stroke.get_lines()}
    for bound in ("lower", "nominal", "upper"):  # each bound's record curves are there
        for record in study.records:
            values = 100 * ds["stroke_max_abs"].sel(model="compliant", property=bound, record=record).values
            assert tuple(np.round(values, 9)) in drawn, (bound, record)


# --- the README's command for the tests, and its pages -----------------------------------------------------------
def test_dccss_check_of_the_shipped_intensity_study_passes():
    run = subprocess.run([sys.executable, "-m", "dccss", "check", str(STUDIES / "ida.yaml")], capture_output=True,
                         text=True)
    assert run.returncode == 0, run.stderr
    assert "288 cases" in run.stdout


def test_a_threshold_on_a_pad_summary_is_refused_for_articulated_sliders_alone():
    """Their pad summaries are NaN: a threshold on one would count nothing (it counted them as not exceeded)."""
    config = _intensity_study(slider="articulated", structure={"friction": [0.03, 0.06], "friction_on": "surfaces"},
                              fragility=[{"name": "tilt", "variable": "theta2_max_abs", "above": 10.0}])
    with pytest.raises(StudyError, match=r"fragility\[0\].variable: 'theta2_max_abs' is not a summary of this study"):
        Study.from_config(config, STUDIES)
    Study.from_config({**config, "fragility": ["ring", {"name": "big", "variable": "stroke_1_max_abs",
                                                        "above": 0.1}]}, STUDIES)
