"""dccss.paper.validation on small synthetic datasets: every quantity kind against a hand-computed value,
the statuses and readings, the load-time checks (each naming the entry), missing datasets, and the
reports (markdown, CSV, JSON) with values at round-off."""

import copy
import csv
import inspect
import io
import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
import yaml

from dccss.paper import validation as V

ROOT = Path(__file__).resolve().parents[1]
DT = 0.01
#: ground steps X_g(t_n) - X_g(t_{n-1}) of steps 1..12 (m): half cycles 1-4 (+), 5-8 (-), 9-11 (+), 12 (-);
#: the complete ones are 5-8 (largest step 6) and 9-11 (largest step 10)
STEPS = np.array([1, 1, 2, 1, -1, -3, -2, -1, 2, 3, 1, -1]) * 0.01
N = len(STEPS) + 1
A_DFP1, B_DFP1 = 0.17364817766693033, 0.075  # R sin(10 deg), h2 / 2 (m)
CATALOGUE = V.Catalogue(prototypes=("DFP1", "DFP2"), models=("compliant", "stick_slip"), dt=(0.01, 0.001),
                        case_variants=("as_printed", "as_reported"), breakaway_variants=("signed", "unsigned"),
                        dXg=(0.05, 0.10), duration=1.0,
                        case_prototypes=(("as_printed", ("DFP1",)), ("as_reported", ("DFP1", "DFP2"))))
CASE_VARIANTS, BREAKAWAY_VARIANTS = CATALOGUE.case_variants, CATALOGUE.breakaway_variants


def history(dt=DT, steps=STEPS, failed=0, **variables):
    """A time history as the workflow writes it (zeros unless given; theta2_stick nan at t_0)."""
    n = len(steps) + 1
    data = {"Xg": np.concatenate([[0.0], np.cumsum(steps)]), "Xg_dot": np.zeros(n), "theta2": np.zeros(n),
            "rise": np.zeros(n), "theta2_stick": np.concatenate([[np.nan], np.zeros(n - 1)]),
            "sticking_diagonal": np.zeros(n, dtype=np.int8), "det_Cq": np.zeros(n), "alpha_A": np.full(n, 10.0),
            **{f"I_{c}": np.zeros(n) for c in "ABCD"}}
    data.update({k: np.asarray(v) for k, v in variables.items()})
    return xr.Dataset({k: ("t", v) for k, v in data.items()}, coords={"t": np.arange(n) * dt},
                      attrs={"A1_m": A_DFP1, "B_m": B_DFP1, "failed": failed})


def stick_slip(rotation, theta2=None, **variables):
    """A stick-slip history with the given sticking rotation by step (deg): theta2 at the end of
    sticking is theta2 at the step's start plus the rotation."""
    theta2 = np.zeros(len(rotation)) if theta2 is None else np.asarray(theta2, dtype=float)
    stick = np.concatenate([[np.nan], theta2[:-1] + rotation[1:]])
    return history(theta2=theta2, theta2_stick=stick, **variables)


def sweep(I_A, I_B, I_C=None, I_D=None, det=None):
    """A breakaway sweep: dims (dXg, theta2_0) = (2, 3)."""
    data = {"I_A": I_A, "I_B": I_B, "I_C": I_B if I_C is None else I_C, "I_D": I_A if I_D is None else I_D,
            "det_Cq": np.full((2, 3), 0.2) if det is None else det}
    return xr.Dataset({k: (("dXg", "theta2_0"), np.asarray(v, dtype=float)) for k, v in data.items()},
                      coords={"dXg": [0.05, 0.10], "theta2_0": [-2.0, -1.0, 0.0]})


def results(cases=None, breakaway=None):
    return V.Results(cases=cases or {}, breakaway=breakaway or {})


def compute(kind, r, variant="as_printed", **params):
    return V.QUANTITIES[kind](r, variant, **params)


# --- quantity kinds against hand-computed values ----------------------------------------------------
THETA2 = [0, 1, 3, 2, 5, 4, 0, -1, -2, 0, 1, 2, 1.5]
RISE = [0, 1, 2, 4, 3, 2, 1, 0, 1, 2, 3, 3.5, 3]
#: I_B - I_A by step: 100 at the breakaway step 1, a cyclic peak of 5 (um)
D_BA = np.array([0, 100, 1, -2, 3, -4, 0.01, 5, -1, 2, -3, 4, -5]) * 1e-6
#: jammed diagonal by step (1: B2C2); opposite to the loaded one at steps 1-5, 7, 8, 12, not at 9-11
JAMMED = np.array([0, 0, 0, 1, 0, 1, 1, 0, 1, 1, 0, 1, 1], dtype=np.int8)
ROTATION = np.array([np.nan, 9, 1, 1, 1, 2, 5, 1, 1, 1, 4, 1, 1])  # largest in each half cycle at its peak


def case_results():
    """DFP1 histories of as_printed and a DFP1 compliant history at dt 0.001 (for ratios over dt)."""
    peak_diff = np.zeros(N)
    peak_diff[6] = 1e-4  # |I_A - I_B| peaks at step 6, whose ground step is 0.03 m
    compliant = history(theta2=THETA2, rise=np.array(RISE) * 1e-3, I_A=np.zeros(N), I_B=peak_diff,
                        I_C=np.r_[0, 0, 0, 0, 0, 3e-4, 0, 0, 0, 0, 0, 0, 0],
                        I_D=np.r_[0, 0, 0, 0, 0, 0, 0, -5e-4, 0, 0, 0, 0, 0],
                        det_Cq=np.r_[-0.2129, np.zeros(N - 1)], Xg_dot=np.arange(N) * 0.5)
    fine = history(dt=0.001, I_C=np.r_[0, 2e-5, np.zeros(N - 2)])
    slip = stick_slip(ROTATION, theta2=THETA2)
    return results({("as_printed", "DFP1", "compliant", 0.01): compliant,
                    ("as_printed", "DFP1", "compliant", 0.001): fine,
                    ("as_printed", "DFP1", "stick_slip", 0.01): slip})


def breakaway_results():
    I_A = np.array([[1, 2, 3], [4, 8, 12]]) * 1e-6
    diff = np.array([[1e-7, 2e-7, -3e-8], [8e-7, 1.6e-6, 6e-7]])
    I_D = I_A.copy()
    I_D[0, 1] += 4e-9
    det = np.array([[-0.2, 0.1, 0.3], [0.25, -0.15, 0.2]])
    return results(breakaway={("signed", "DFP1"): sweep(I_A, I_A + diff, I_D=I_D, det=det)})


CASE_EXAMPLES = [
    ("theta2_max", dict(prototype="DFP1", model="compliant", dt=0.01), 5.0),
    ("theta2_end", dict(prototype="DFP1", model="compliant", dt=0.01), 1.5),
    ("rise_max", dict(prototype="DFP1", model="compliant", dt=0.01), 4e-3),
    ("rise_end", dict(prototype="DFP1", model="compliant", dt=0.01), 3e-3),
    ("interpenetration_difference", dict(prototype="DFP1", model="compliant", dt=0.01), 1e-4),
    ("interpenetration_peak", dict(prototype="DFP1", model="compliant", dt=0.01), 3e-4),  # I_D's -5e-4 is a gap
    ("difference_ground_step", dict(prototype="DFP1", model="compliant", dt=0.01), 0.03),
    ("cubic_coefficient", dict(prototype="DFP1", model="compliant", dt=0.01), 1e-4 / 0.03 ** 3),
    ("dt_ratio", dict(of="interpenetration_peak", prototype="DFP1", model="compliant", dt=0.01, other_dt=0.001),
     3e-4 / 2e-5),
    ("velocity", dict(prototype="DFP1", model="compliant", dt=0.01, time=0.05), 2.5),
    ("fig20_theta2", dict(prototype="DFP1", dt=0.01, time=0.05, phase="start"), 5.0),
    ("fig20_theta2", dict(prototype="DFP1", dt=0.01, time=0.05, phase="stick"), 7.0),  # 5 + rotation 2
    ("fig20_theta2", dict(prototype="DFP1", dt=0.01, time=0.05, phase="end"), 4.0),
    ("rest_determinant", dict(prototype="DFP1", dt=0.01), -0.2129),
    # Eq. 30 for DFP1 at rest (alpha = 10 deg, theta2 = 0): printed +0.24795 m, corrected -0.21286 m
    ("eq30_printed", dict(prototype="DFP1", dt=0.01), 0.247948),
    ("eq30_corrected", dict(prototype="DFP1", dt=0.01), -0.212855),
    ("eq30_alpha_reversed", dict(prototype="DFP1", dt=0.01), 0.247948),
    ("sticking_rotation_at_velocity_peak", dict(prototype="DFP1", dt=0.01), 1.0),
    ("diagonal_endpoint_mismatch", dict(prototype="DFP1", model="compliant", dt=0.01), 5e-4),  # |I_A - I_D|
]
BREAKAWAY_EXAMPLES = [
    ("breakaway_difference", dict(prototype="DFP1", dXg=0.05, statistic="mean"), 9e-8),
    ("breakaway_difference", dict(prototype="DFP1", dXg=0.05, statistic="max"), 2e-7),
    ("breakaway_difference", dict(prototype="DFP1", dXg=0.10, statistic="mean"), 1e-6),
    ("breakaway_cubic_coefficient", dict(prototype="DFP1", dXg=0.05, statistic="mean"), 9e-8 / 0.05 ** 3),
    ("breakaway_ground_step", dict(prototype="DFP1", dXg=0.10), 0.10),
    ("breakaway_endpoint_mismatch", dict(prototype="DFP1", dXg=0.05), 4e-9),
    ("breakaway_bc_larger", dict(prototype="DFP1", dXg=0.05), 2 / 3),
    ("breakaway_min_determinant", dict(prototype="DFP1", dXg=0.10), 0.15),
    ("breakaway_scaling", dict(prototype="DFP1", dXg=0.10, other_dXg=0.05, corner="A"), 4.0),
]
SPECIAL = {"sticking_rotation_ratio", "opposite_working_diagonal"}  # tested below with two histories


@pytest.mark.parametrize("kind, params, expected", CASE_EXAMPLES)
def test_case_kind(kind, params, expected):
    assert compute(kind, case_results(), **params) == pytest.approx(expected, rel=1e-5)


@pytest.mark.parametrize("kind, params, expected", BREAKAWAY_EXAMPLES)
def test_breakaway_kind(kind, params, expected):
    assert compute(kind, breakaway_results(), "signed", **params) == pytest.approx(expected, rel=1e-9)


def test_every_kind_has_a_hand_computed_test():
    tested = {k for k, _, _ in CASE_EXAMPLES + BREAKAWAY_EXAMPLES} | SPECIAL
    assert tested == set(V.QUANTITIES)


def test_eq30_printed_form_is_the_corrected_form_with_alpha_reversed():
    ds = history(alpha_A=np.full(N, 23.0), theta2=np.r_[5.0, np.zeros(N - 1)])
    r = results({("as_printed", "DFP2", "compliant", 0.01): ds})
    printed = compute("eq30_printed", r, prototype="DFP2", dt=0.01)
    assert compute("eq30_alpha_reversed", r, prototype="DFP2", dt=0.01) == pytest.approx(printed, rel=1e-12)
    assert compute("eq30_corrected", r, prototype="DFP2", dt=0.01) != pytest.approx(printed, rel=1e-3)


def test_sticking_rotation_peak_ignores_the_breakaway_step_and_finds_a_miss():
    # the step-1 rotation (9 deg at a 0.01 m step) is outside the complete half cycles
    assert compute("sticking_rotation_at_velocity_peak", case_results(), prototype="DFP1", dt=0.01) == 1.0
    late = ROTATION.copy()
    late[11] = 6.0  # half cycle 9-11 now peaks at step 11 (ground step 0.01 against its largest 0.03)
    r = results({("as_printed", "DFP1", "stick_slip", 0.01): stick_slip(late)})
    assert compute("sticking_rotation_at_velocity_peak", r, prototype="DFP1", dt=0.01) == pytest.approx(1 / 3)


def test_sticking_rotation_ratio_is_the_smallest_over_the_half_cycles():
    other = ROTATION.copy()
    other[6], other[10] = 2.0, 2.0  # half-cycle peaks 2 and 2 against 5 and 4: ratios 2.5 and 2 (maxima: 2.5)
    other[1] = 90.0  # the breakaway step does not enter
    r = results({("as_printed", "DFP2", "stick_slip", 0.01): stick_slip(ROTATION),
                 ("as_printed", "DFP1", "stick_slip", 0.01): stick_slip(other)})
    value = compute("sticking_rotation_ratio", r, prototype="DFP2", dt=0.01, other_prototype="DFP1", other_dt=0.01)
    assert value == pytest.approx(2.0)


def test_sticking_rotation_ratio_refuses_histories_that_do_not_pair():
    r = results({("as_printed", "DFP2", "stick_slip", 0.01): stick_slip(ROTATION),
                 ("as_printed", "DFP1", "stick_slip", 0.01): stick_slip(ROTATION[:10], steps=STEPS[:9])})
    with pytest.raises(ValueError, match="do not pair"):
        compute("sticking_rotation_ratio", r, prototype="DFP2", dt=0.01, other_prototype="DFP1", other_dt=0.01)


def diagonal_results():
    return results({("as_printed", "DFP1", "compliant", 0.01): history(I_B=D_BA),
                    ("as_printed", "DFP1", "stick_slip", 0.01): history(sticking_diagonal=JAMMED)})


def test_opposite_working_diagonal_over_the_cyclic_part():
    # steps 2-12, threshold 10 % of the cyclic peak 5 um: 10 working steps (not step 6), opposite at 7
    r = diagonal_results()
    assert compute("opposite_working_diagonal", r, prototype="DFP1", dt=0.01) == pytest.approx(0.7)
    # with the threshold at half the peak: steps 4, 5, 7, 10, 11, 12, opposite at 4, 5, 7, 12
    assert compute("opposite_working_diagonal", r, prototype="DFP1", dt=0.01, threshold=0.5) == pytest.approx(4 / 6)


# --- statuses -----------------------------------------------------------------------------------
def entry(id="x", value=8.0, unit="deg", tolerance=0.01, expect=("as_printed",), quantity=None, **extra):
    q = quantity or {"kind": "theta2_end", "prototype": "DFP1", "model": "compliant", "dt": 0.01}
    e = {"id": id, "description": f"what {id} is", "source": "Sec. 1", "value": value, "unit": unit,
         "tolerance": tolerance, "quantity": q, "expect": list(expect), **extra}
    if not expect and "reason" not in extra:
        e["reason"] = "a known miss"
    return e


def two_variants(printed=8.0, reported=8.43, peak_printed=1e-4, peak_reported=1.6e-3):
    """theta2_end 8.0 (as printed) / 8.43 deg (as reported); |I_A - I_B| 2.2 mm at step 12 (a gap at A)
    and the peak interpenetration (at C) in both prototypes."""
    def case(end, peak):
        return history(theta2=np.r_[np.zeros(N - 1), end], I_A=np.r_[np.zeros(N - 1), -2.2e-3],
                       I_C=np.r_[np.zeros(N - 1), peak])
    values = (("as_printed", printed, peak_printed), ("as_reported", reported, peak_reported))
    return results({(v, p, "compliant", 0.01): case(end, peak) for v, end, peak in values for p in ("DFP1", "DFP2")})


def evaluate(entries, r=None, readings=()):
    return V.evaluate(V.PaperValues(tuple(entries), tuple(readings)), r or two_variants(),
                      CASE_VARIANTS, BREAKAWAY_VARIANTS)


@pytest.mark.parametrize("value, relation, status", [
    (8.0, "within", "reproduced"),
    (8.43, "within", "reproduced with reported inputs"),
    (9.0, "within", "not reproduced"),
    (8.2, "greater", "reproduced with reported inputs"),
    (8.2, "less", "reproduced"),
])
def test_status(value, relation, status):
    row, = evaluate([entry(value=value, relation=relation, expect=[], reason="r")])
    assert row["status"] == status and row["ok"]


def test_reproduced_by_both_is_reproduced():
    row, = evaluate([entry(value=8.2, tolerance=0.3)])
    assert row["status"] == "reproduced" and set(row["computed"]) == {"as_printed", "as_reported"}


def test_an_expected_variant_that_does_not_reproduce_fails():
    row, = evaluate([entry(value=8.43, expect=["as_printed", "as_reported"])])
    assert row["status"] == "reproduced with reported inputs" and not row["ok"]
    md = V.markdown([row], CASE_VARIANTS, BREAKAWAY_VARIANTS)
    assert "**FAIL** reproduced with reported inputs" in md
    assert "FAILED (expected to reproduce, did not): x" in md


def reading_entry(value=1.6, **extra):
    """The stated difference (2.2 mm) against 1.6 mm, read as the peak interpenetration."""
    q = {"kind": "interpenetration_difference", "prototype": "DFP2", "model": "compliant", "dt": 0.01}
    reading = {"label": "the peak interpenetration",
               "quantity": {**q, "kind": "interpenetration_peak"}, "expect": ["as_reported"]}
    return entry(id="dI", value=value, unit="mm", tolerance=0.1, quantity=q, expect=[],
                 reason="the difference is 2.2 mm", reading=reading, **extra)


def test_reproduced_only_under_a_reading_is_counted_apart():
    rows = evaluate([reading_entry(), entry(id="y")])
    assert rows[0]["status"] == "reproduced as the peak interpenetration with reported inputs"
    assert rows[0]["ok"] and rows[0]["under_reading"]
    assert rows[0]["reading"]["computed"] == pytest.approx({"as_printed": 0.1, "as_reported": 1.6})
    assert V.summary(rows) == ("2 of 2 stated numbers reproduced, 1 of them only under a reading; "
                               "every number expected to reproduce does.")
    note = V.markdown(rows, CASE_VARIANTS, BREAKAWAY_VARIANTS)
    assert "the difference is 2.2 mm; as the peak interpenetration: 0.1 (as_printed), 1.6 (as_reported) mm" in note


def test_a_reading_that_does_not_reproduce_fails_when_expected():
    row, = evaluate([reading_entry()], two_variants(peak_reported=1.2e-3))
    assert row["status"] == "not reproduced" and not row["ok"]


def test_a_stated_quantity_that_reproduces_keeps_its_status():
    row, = evaluate([reading_entry(value=2.2)])
    assert row["status"] == "reproduced" and not row["under_reading"]


# --- readings -----------------------------------------------------------------------------------
def reading(id="g", reads="x", law="value", unit="deg", quantity=None, expect="holds", **extra):
    q = quantity or {"kind": "theta2_end", "prototype": "DFP1", "model": "compliant", "dt": 0.01}
    return {"id": id, "description": f"how {reads} reads", "reads": reads, "law": law, "variant": "as_reported",
            "unit": unit, "quantity": q, "expect": expect, **extra}


def test_reading_value_law():
    row = evaluate([entry(value=8.43)], readings=[reading()])[-1]
    assert row["section"] == "reading" and row["status"] == "holds" and row["ok"]
    assert row["paper_value"] == 8.43 and row["range"] == pytest.approx([8.42, 8.44])
    assert row["computed"] == {"as_reported": pytest.approx(8.43)}


def test_reading_ratio_law():
    q = {"kind": "dt_ratio", "of": "theta2_end", "prototype": "DFP1", "model": "compliant", "dt": 0.01,
         "other_dt": 0.001}
    r = two_variants()
    r.cases[("as_reported", "DFP1", "compliant", 0.001)] = history(dt=0.001, theta2=np.r_[np.zeros(N - 1), 4.0])
    stated = [entry(id="a", value=8.0, tolerance=0.5, expect=[]), entry(id="b", value=4.0, tolerance=0.5, expect=[])]
    row = evaluate(stated, r, readings=[reading(reads=["a", "b"], law="ratio", unit="1", quantity=q)])[-1]
    assert row["paper_value"] == 2.0 and row["range"] == pytest.approx([7.5 / 4.5, 8.5 / 3.5])
    assert row["computed"]["as_reported"] == pytest.approx(8.43 / 4.0) and row["status"] == "holds"


def test_reading_per_cubed_step_law_and_a_miss():
    # |I_A - I_B| peaks (2.2 mm) at step 12, whose ground step is 0.01 m: 2.2e-3 / 1e-6 = 2200 m^-2
    q = {"kind": "cubic_coefficient", "prototype": "DFP1", "model": "compliant", "dt": 0.01}
    step = {**q, "kind": "difference_ground_step"}
    stated = entry(id="d", value=1.6, unit="mm", tolerance=0.1, expect=[],
                   quantity={**q, "kind": "interpenetration_difference"})
    g = reading(reads="d", law="per_cubed_step", unit="1e-5 mm/cm3", quantity=q, ground_step=step,
                expect="does not hold", reason="off the law")
    row = evaluate([stated], readings=[g])[-1]
    # 1 m^-2 = 1e-3 mm/cm3 = 100 x 1e-5 mm/cm3
    assert row["computed"]["as_reported"] == pytest.approx(2200 * 100)
    assert row["paper_value"] == pytest.approx(1600 * 100) and row["ground_step_m"] == pytest.approx(0.01)
    assert row["status"] == "off by -27.3 %" and row["ok"] and row["reason"] == "off the law"
    row = evaluate([stated], readings=[{**g, "expect": "holds"}])[-1]
    assert not row["ok"]


def test_readings_are_not_counted_among_the_stated_numbers():
    rows = evaluate([entry(value=8.43)], readings=[reading(expect="does not hold", reason="r", unit="deg")])
    assert V.summary(rows).startswith("1 of 1 stated numbers reproduced;")
    md = V.markdown(rows, CASE_VARIANTS, BREAKAWAY_VARIANTS)
    assert "## Readings" in md and "| g | how x reads | x | 8.43 deg | 8.43 | 8.42 to 8.44 | 8.43 | deg |" in md


# --- missing datasets ---------------------------------------------------------------------------
def test_results_raise_missing_dataset_for_an_absent_key():
    with pytest.raises(V.MissingDataset):
        results().case("as_printed", "DFP1", "compliant", 0.01)
    with pytest.raises(V.MissingDataset):
        results().sweep("signed", "DFP1", 0.05)
    assert issubclass(V.MissingDataset, LookupError)


def test_a_variant_without_the_dataset_is_skipped():
    r = results({("as_reported", "DFP2", "compliant", 0.01): history(theta2=np.r_[np.zeros(N - 1), 8.43])})
    q = {"kind": "theta2_end", "prototype": "DFP2", "model": "compliant", "dt": 0.01}
    row, = evaluate([entry(value=8.43, quantity=q, expect=["as_reported"])], r)
    assert row["computed"] == {"as_reported": pytest.approx(8.43)} and row["ok"]


def test_an_error_inside_a_kind_is_not_read_as_a_missing_dataset():
    broken = history().drop_vars("theta2")
    r = results({(v, "DFP1", "compliant", 0.01): broken for v in CASE_VARIANTS})
    with pytest.raises(KeyError) as err:
        evaluate([entry()], r)
    assert "paper value 'x'" in "\n".join(err.value.__notes__)


def test_no_dataset_in_any_variant_raises():
    q = {"kind": "theta2_end", "prototype": "DFP1", "model": "stick_slip", "dt": 0.01}
    with pytest.raises(ValueError, match="paper value 'x': no dataset for theta2_end"):
        evaluate([entry(quantity=q)])


def test_an_expected_variant_without_the_dataset_raises():
    r = results({("as_reported", "DFP1", "compliant", 0.01): history()})
    with pytest.raises(ValueError, match=r"paper value 'x': expected variant\(s\) \['as_printed'\] have no dataset"):
        evaluate([entry(value=0.0)], r)


def test_a_failed_history_is_not_checked():
    r = results({(v, "DFP1", "compliant", 0.01): history(failed=1) for v in CASE_VARIANTS})
    with pytest.raises(ValueError, match="stopped early"):
        evaluate([entry()], r)


def test_a_time_without_a_step_raises():
    with pytest.raises(ValueError, match="no step ends at t = 0.055 s"):
        compute("velocity", case_results(), prototype="DFP1", model="compliant", dt=0.01, time=0.055)


def test_a_ground_step_the_sweep_lacks_raises():
    with pytest.raises(ValueError, match="has no dXg = 0.07"):
        compute("breakaway_bc_larger", breakaway_results(), "signed", prototype="DFP1", dXg=0.07)


# --- load-time checks ---------------------------------------------------------------------------
def write_values(tmp_path, entries, readings=None):
    path = tmp_path / "paper_values.yaml"
    path.write_text(yaml.safe_dump({"values": entries, **({"readings": readings} if readings else {})}))
    return path


def load(tmp_path, entries, readings=None):
    return V.load_values(write_values(tmp_path, entries, readings), CATALOGUE)


def test_a_valid_file_loads(tmp_path):
    values = load(tmp_path, [entry(), reading_entry()], [reading()])
    assert [e["id"] for e in values.entries] == ["x", "dI"] and values.readings[0]["id"] == "g"


def test_the_corner_message(tmp_path):
    q = {"kind": "breakaway_scaling", "prototype": "DFP1", "dXg": 0.10, "other_dXg": 0.05, "corner": "Z"}
    bad = entry(id="fig20a_theta2_stick", unit="1", quantity=q, expect=["signed"])
    with pytest.raises(ValueError) as err:
        load(tmp_path, [bad])
    assert str(err.value) == "paper value 'fig20a_theta2_stick': quantity.corner 'Z' is not one of ['A', 'B', 'C', 'D']"


def fig20(**changes):
    q = {"kind": "fig20_theta2", "prototype": "DFP1", "dt": 0.001, "time": 0.73, "phase": "stick", **changes}
    return {k: v for k, v in q.items() if v is not None}


BREAKAWAY_Q = {"kind": "breakaway_difference", "prototype": "DFP1", "dXg": 0.05, "statistic": "mean"}
LOAD_ERRORS = [
    (dict(quantity={"kind": "theta2_maximum", "prototype": "DFP1"}),
     "quantity.kind 'theta2_maximum' is not a known kind"),
    (dict(quantity=fig20(phase=None)), r"quantity is missing parameter\(s\) \['phase'\] of kind 'fig20_theta2'"),
    (dict(quantity=fig20(model="compliant")), r"quantity has unknown parameter\(s\) \['model'\] for kind"),
    (dict(quantity=fig20(prototype="DFP3")), r"quantity.prototype 'DFP3' is not one of \['DFP1', 'DFP2'\]"),
    (dict(quantity=fig20(dt=0.005)), r"quantity.dt 0.005 is not one of \[0.01, 0.001\]"),
    (dict(quantity=fig20(dt="1e-3")), r"quantity.dt '1e-3' is not one of"),
    (dict(quantity=fig20(phase="middle")), r"quantity.phase 'middle' is not one of \['start', 'stick', 'end'\]"),
    (dict(quantity=fig20(time=1.5)), r"quantity.time 1.5 is not inside the motion \(0, 1.0\] s"),
    (dict(quantity=fig20(time=0.7305)), "quantity.time 0.7305 is not the end of a step of 0.001 s"),
    (dict(quantity={"kind": "theta2_end", "prototype": "DFP1", "model": "sliding", "dt": 0.01}),
     "quantity.model 'sliding' is not one of"),
    (dict(quantity={"kind": "sticking_rotation_ratio", "prototype": "DFP2", "dt": 0.01, "other_prototype": "DFP9",
                    "other_dt": 0.01}, unit="1"), "quantity.other_prototype 'DFP9'"),
    (dict(quantity={"kind": "sticking_rotation_ratio", "prototype": "DFP2", "dt": 0.01, "other_prototype": "DFP1",
                    "other_dt": 0.1}, unit="1"), "quantity.other_dt 0.1 is not one of"),
    (dict(quantity={**BREAKAWAY_Q, "dXg": 0.07}, unit="m", expect=["signed"]), "quantity.dXg 0.07 is not one of"),
    (dict(quantity={**BREAKAWAY_Q, "statistic": "median"}, unit="m", expect=["signed"]),
     r"quantity.statistic 'median' is not one of \['mean', 'max'\]"),
    (dict(quantity={"kind": "breakaway_scaling", "prototype": "DFP1", "dXg": 0.1, "other_dXg": 0.2, "corner": "A"},
          unit="1", expect=["signed"]), "quantity.other_dXg 0.2 is not one of"),
    (dict(quantity={"kind": "opposite_working_diagonal", "prototype": "DFP1", "dt": 0.01, "threshold": 1.5},
          unit="1"), "quantity.threshold 1.5 is not a number between 0 and 1"),
    (dict(quantity={"kind": "dt_ratio", "of": "velocity", "prototype": "DFP1", "model": "compliant", "dt": 0.01,
                    "other_dt": 0.001}, unit="1"), "quantity.of 'velocity' is not one of"),
    (dict(expect=["as_printd"]), r"expect 'as_printd' is not one of \['as_printed', 'as_reported'\]"),
    (dict(expect=["signed"]), r"expect 'signed' is not one of \['as_printed', 'as_reported'\]"),
    (dict(quantity={"kind": "theta2_end", "prototype": "DFP2", "model": "compliant", "dt": 0.01}),
     "expect 'as_printed' does not run prototype 'DFP2'"),
    (dict(unit="degrees"), "unit 'degrees' is not one of"),
    (dict(unit="mm"), "unit 'mm' measures length; quantity.kind 'theta2_end' gives angle"),
    (dict(relation="about"), r"relation 'about' is not one of \['within', 'greater', 'less'\]"),
    (dict(expect=[], reason=""), "a value expected not to reproduce needs a 'reason'"),
    (dict(value="8.5"), "value '8.5' is not a number"),
    (dict(tolerance=-0.1), "tolerance -0.1 is negative"),
    (dict(reasn="typo"), r"unknown key\(s\) \['reasn'\]"),
    (dict(source=None), r"missing key\(s\) \['source'\]"),
    (dict(reading={"label": "l", "quantity": {"kind": "theta2_max", "prototype": "DFP1", "model": "compliant",
                                              "dt": 0.01}, "expect": ["unsigned"]}),
     r"reading.expect 'unsigned' is not one of"),
    (dict(reading={"label": "l", "quantity": {"kind": "rise_max", "prototype": "DFP1", "model": "compliant",
                                              "dt": 0.01}, "expect": []}),
     "unit 'deg' measures angle; reading.quantity.kind 'rise_max' gives length"),
]


@pytest.mark.parametrize("changes, message", LOAD_ERRORS)
def test_load_errors_name_the_entry(tmp_path, changes, message):
    bad = {k: v for k, v in {**entry(id="bad"), **changes}.items() if v is not None}
    with pytest.raises(ValueError, match="paper value 'bad': " + message):
        load(tmp_path, [entry(id="good"), bad])


def test_every_kind_parameter_is_checked(tmp_path):
    for kind, fn in V.QUANTITIES.items():
        for name in list(inspect.signature(fn).parameters)[2:]:
            q = {"kind": kind, name: "bogus!"}
            with pytest.raises(ValueError, match=f"quantity.{name} 'bogus!' is not"):
                load(tmp_path, [entry(quantity=q, unit={"1/area": "1e-5 mm/cm3", "length": "m", "angle": "deg",
                                                        "velocity": "cm/s", "1": "1"}[V.KIND_DIMENSIONS[kind]])])


def test_duplicate_ids_and_every_error_are_reported(tmp_path):
    with pytest.raises(ValueError) as err:
        load(tmp_path, [entry(), entry(), entry(id="y", unit="m")])
    lines = str(err.value).splitlines()
    assert lines[0] == "paper value 'x' is listed 2 times"
    assert any(line.startswith("paper value 'y': unit 'm' measures length") for line in lines)


READING_ERRORS = [
    (dict(reads="nope"), r"reads unknown paper value\(s\) \['nope'\]"),
    (dict(law="cube"), r"law 'cube' is not one of \['value', 'ratio', 'per_cubed_step'\]"),
    (dict(law="ratio", unit="1"), r"law 'ratio' reads 2 paper value\(s\), not 1"),
    (dict(unit="1"), "unit '1' measures 1; quantity.kind 'theta2_end' gives angle"),
    (dict(variant="signed"), r"variant 'signed' is not one of \['as_printed', 'as_reported'\]"),
    (dict(expect="off"), r"expect 'off' is not one of \['holds', 'does not hold'\]"),
    (dict(expect="does not hold"), "a reading expected not to hold needs a 'reason'"),
    (dict(law="per_cubed_step", unit="1e-5 mm/cm3",
          quantity={"kind": "cubic_coefficient", "prototype": "DFP1", "model": "compliant", "dt": 0.01}),
     "law 'per_cubed_step' reads a length, not a angle"),
    (dict(ground_step={"kind": "difference_ground_step"}), "ground_step is used only by law 'per_cubed_step'"),
]


@pytest.mark.parametrize("changes, message", READING_ERRORS)
def test_reading_load_errors_name_the_reading(tmp_path, changes, message):
    with pytest.raises(ValueError, match="reading 'g': " + message):
        load(tmp_path, [entry()], [reading(**changes)])


def test_a_per_cubed_step_reading_needs_its_ground_step(tmp_path):
    stated = entry(id="d", value=1.6, unit="mm", expect=[],
                   quantity={"kind": "interpenetration_difference", "prototype": "DFP1", "model": "compliant",
                             "dt": 0.01})
    q = {"kind": "cubic_coefficient", "prototype": "DFP1", "model": "compliant", "dt": 0.01}
    with pytest.raises(ValueError, match="reading 'g': law 'per_cubed_step' needs a ground_step quantity"):
        load(tmp_path, [stated], [reading(reads="d", law="per_cubed_step", unit="1e-5 mm/cm3", quantity=q)])


def test_catalogue_from_config():
    catalogue = V.catalogue_from_config(yaml.safe_load((ROOT / "config/config.yaml").read_text()))
    assert catalogue.prototypes == ("DFP1", "DFP2") and catalogue.models == ("compliant", "stick_slip")
    assert catalogue.dt == (0.01, 0.001) and catalogue.dXg == (0.05, 0.10) and catalogue.duration == 1.0
    assert catalogue.case_variants == ("as_printed", "as_reported")
    assert catalogue.breakaway_variants == ("signed", "unsigned")
    assert catalogue.runs("as_printed", "DFP2") and not CATALOGUE.runs("as_printed", "DFP2")


def test_the_project_values_load():
    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    values = V.load_values(ROOT / "config/paper_values.yaml", V.catalogue_from_config(config))
    assert len(values.entries) == 55 and len(values.readings) >= 7


def test_a_config_that_drops_a_prototype_is_refused():
    config = yaml.safe_load((ROOT / "config/config.yaml").read_text())
    smaller = copy.deepcopy(config)
    del smaller["prototypes"]["DFP2"]
    with pytest.raises(ValueError, match="quantity.prototype 'DFP2' is not one of \\['DFP1'\\]"):
        V.load_values(ROOT / "config/paper_values.yaml", V.catalogue_from_config(smaller))


# --- reports and round-off ----------------------------------------------------------------------
def mismatch_results(mismatch):
    """Endpoint mismatch |I_A - I_D| = ``mismatch`` (m) in both case sets."""
    return results({(v, "DFP1", "stick_slip", 0.01): history(I_D=np.r_[0.0, mismatch, np.zeros(N - 2)])
                    for v in CASE_VARIANTS})


def mismatch_entry():
    q = {"kind": "diagonal_endpoint_mismatch", "prototype": "DFP1", "model": "stick_slip", "dt": 0.01}
    return entry(id="ends", value=0, unit="um", tolerance=1e-6, quantity=q, expect=list(CASE_VARIANTS))


def reports(rows):
    return (V.markdown(rows, CASE_VARIANTS, BREAKAWAY_VARIANTS), V.to_csv(rows, CASE_VARIANTS, BREAKAWAY_VARIANTS),
            V.to_json(rows))


def test_round_off_prints_the_floor_in_every_output():
    rows = evaluate([mismatch_entry()], mismatch_results(4.4e-16))
    assert rows[0]["status"] == "reproduced" and rows[0]["computed"]["as_printed"] == pytest.approx(4.4e-10)
    md, table, js = reports(rows)
    assert "| 0 | um | ± 1e-06 | < 1e-8 | < 1e-8 |" in md and "(< 1e-8 um)" in md
    assert next(csv.reader(io.StringIO(table.splitlines()[1])))[6:8] == ["< 1e-8", "< 1e-8"]
    row = json.loads(js)[0]
    assert row["computed"] == {"as_printed": "< 1e-8", "as_reported": "< 1e-8"} and row["round_off"] == "< 1e-8"


def test_round_off_values_print_byte_identically():
    assert reports(evaluate([mismatch_entry()], mismatch_results(2.2e-16))) == \
        reports(evaluate([mismatch_entry()], mismatch_results(4.4e-16)))


def test_a_real_mismatch_is_printed_and_fails():
    rows = evaluate([mismatch_entry()], mismatch_results(5e-12))
    assert rows[0]["status"] == "not reproduced" and not rows[0]["ok"]
    md, table, js = reports(rows)
    assert "| 5e-06 | 5e-06 |" in md and json.loads(js)[0]["computed"]["as_printed"] == pytest.approx(5e-6)


def test_reports_hold_every_row():
    rows = evaluate([entry(value=8.43, expect=["as_reported"]), reading_entry()], readings=[reading(reads="x")])
    md, table, js = reports(rows)
    assert md.startswith("# Validation against the paper\n\n2 of 2 stated numbers reproduced, 1 of them only under")
    assert "| x | what x is | Sec. 1 | 8.43 | deg | ± 0.01 | 8 | 8.43 |  |  | reproduced with reported inputs |  |" \
        in md
    parsed = list(csv.reader(io.StringIO(table)))
    assert parsed[0] == ["id", "what", "source", "paper", "unit", "check", "as_printed", "as_reported", "signed",
                         "unsigned", "status", "note"]
    assert [line[0] for line in parsed[1:]] == ["x", "dI", "g"]
    assert parsed[3][4:8] == ["deg", "8.42 to 8.44", "", "8.43"] and parsed[3][-2] == "holds"
    loaded = json.loads(js)
    assert [r["section"] for r in loaded] == ["paper value", "paper value", "reading"]
    assert loaded[1]["status"] == "reproduced as the peak interpenetration with reported inputs"


def test_cells_escape_the_table_separator():
    md = V.markdown(evaluate([entry(description="max |I_A - I_B|")]), CASE_VARIANTS, BREAKAWAY_VARIANTS)
    assert "max \\|I_A - I_B\\|" in md
