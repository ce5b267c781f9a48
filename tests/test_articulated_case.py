"""The articulated slider in use: under the paper's imposed displacement (Fenz and Constantinou's closed
forms), in a case file, its dataset, a study comparing slider kinds, and its drawings."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import changed

from dccss.case import case_from
from dccss.checks import CaseError
from dccss.excitation import Sine
from dccss.mechanics.structure import Structure
from dccss.mechanics.structure.series import BOTH, SLIDE1, SLIDE3, STUCK, quasi_static
from dccss.mechanics.structure.sliders import pendulums, ring_strokes
from dccss.paper.prototypes import DFP1
from dccss.simulation import simulate
from dccss.studies.spec import Study, StudyError

L1, L3 = pendulums(DFP1)
R1, R3 = float(DFP1.R1), float(DFP1.R3)
CASE = {"prototype": "DFP1", "excitation": {"kind": "sine", "amplitude": 0.27, "omega": 30.0, "duration": 1.0},
        "dt": 0.001, "model": "compliant", "slider": "articulated", "friction": [0.03, 0.06]}


# --- Fenz and Constantinou's regimes under an imposed displacement ------------------------------------------

@pytest.mark.parametrize(("m1", "m3", "La", "Lb"), [(0.03, 0.06, 0.9, 0.9), (0.05, 0.02, 0.7, 1.1),
                                                    (0.033, 0.066, L1, L3)])
def test_the_loop_under_a_sine_is_fenz_and_constantinous(m1, m3, La, Lb):
    """From rest, the surface of the lower force-level friction slides alone (regime I, slope W/L_j from
    F/W = μ̄_j) up to u* = (μ̄_high - μ̄_low) L_low; then both (regime II, slope W/(L_1 + L_3), F/W = (u + μ̄_1 L_1
    + μ̄_3 L_3)/L); on a reversal F/W falls at a fixed stroke by 2 μ̄_low (the low-friction surface slides back
    first), the loop's corners are regime-I segments; in regime II the hinge rotation u_1/L_1 - u_3/L_3 =
    ±(μ̄_3 - μ̄_1). To 1e-9 W and 1e-12 m at every sample."""
    t = np.linspace(0.0, 2.0, 4001)
    u = 0.3 * np.sin(2 * math.pi * t)
    u1, f, phase = quasi_static(u, La, Lb, m1, m3)
    low, L_low, high = (m1, La, m3) if m1 < m3 else (m3, Lb, m1)
    first = SLIDE1 if m1 < m3 else SLIDE3
    star = (high - low) * L_low
    rising = (t <= 0.25) & (t > 0)
    alone = rising & (u < star - 1e-12)
    assert np.all(phase[alone] == first)
    assert np.max(np.abs(f[alone] - (low + u[alone] / L_low))) < 1e-9
    both = rising & (u > star + 1e-12)
    assert both.sum() > 100 and np.all(phase[both] == BOTH)
    assert np.max(np.abs(f[both] - (u[both] + m1 * La + m3 * Lb) / (La + Lb))) < 1e-9
    # the reversal at the top: F/W falls by 2 μ̄_low at the same stroke before anything moves
    top = np.argmax(u[:1001])
    after = top + 1 + np.argmax(phase[top + 1:1001] != STUCK)
    assert np.all(phase[top + 1:after] == STUCK)
    assert f[after] == pytest.approx(f[top] - 2 * low, abs=1e-9 + abs(u[after] - u[top]) / L_low)
    # regime II on the way down too, and the hinge keeps its rotation while both slide
    w = u1 / La - (u - u1) / Lb
    sliding_both = phase == BOTH
    assert np.allclose(np.abs(w[sliding_both]), abs(m3 - m1), rtol=0, atol=1e-12)
    down = (t > 0.25) & (t < 0.75) & sliding_both
    assert down.any() and np.max(np.abs(f[down] - (u[down] - m1 * La - m3 * Lb) / (La + Lb))) < 1e-9


def test_equal_force_level_frictions_slide_together_from_the_start():
    t = np.linspace(0.0, 1.0, 1001)
    u = 0.2 * np.sin(2 * math.pi * t)
    u1, f, phase = quasi_static(u, 0.8, 1.0, 0.05, 0.05)
    moving = np.diff(u, prepend=0.0) != 0.0
    assert set(np.unique(phase[moving])) <= {BOTH, STUCK}
    assert np.max(np.abs(u1 - 0.8 / 1.8 * u)) < 1e-12  # in proportion, as the rigid slider


# --- the case file, and its dataset --------------------------------------------------------------------------

def test_an_articulated_case_runs_quasi_statically_and_its_dataset_says_what_it_is():
    ds = case_from(CASE).run()
    assert ds.attrs["model"] == "articulated" and ds.attrs["slider"] == "articulated"
    assert ds.attrs["pendulum_length_1_m"] == pytest.approx(L1)
    assert np.allclose(ds["stroke_1"] + ds["stroke_3"], -ds["Xg"], atol=1e-15)
    assert np.allclose(ds["theta_1"], np.degrees(np.arcsin(ds["stroke_1"] / L1)))
    assert np.allclose(ds["hinge_rotation"], ds["theta_1"] - ds["theta_3"])
    # regime II: the hinge at μ̄_3 - μ̄_1 (rad, to first order; the dataset's in degrees of the exact angles)
    both = (ds["sliding_1"] == 1) & (ds["sliding_3"] == 1)
    w = ds["stroke_1"].values / L1 - ds["stroke_3"].values / L3
    assert np.allclose(np.abs(w[both.values]), 0.06 * R3 / L3 - 0.03 * R1 / L1, atol=1e-12)
    assert set(np.unique(ds["sliding_1"])) == {0, 1}


@pytest.mark.parametrize(("changes", "message"), [
    ({"friction": None}, r"friction: an articulated slider without a structure needs its surfaces' Coulomb"),
    ({"slider": "rigid"}, r"friction: only an articulated slider under the imposed displacement takes it"),
    ({"model": "stick_slip"}, r"model: an articulated slider's halves stay seated"),
    ({"slider": "hinged"}, r"slider: must be one of \['rigid', 'articulated'\], got 'hinged'"),
    ({"slider": {"kind": "articulated", "hinge": "top"}}, r"slider.hinge: expected a number"),
    ({"friction": [0.03, 1.2]}, r"friction: expected \[mu1, mu3\], two numbers each in 0 < mu < 1"),
    ({"friction": None, "structure": {"friction": 0.05}}, r"structure.friction_on: an articulated slider's"),
    ({"friction": None, "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces"},
      "slider": {"kind": "articulated", "hinge": 2.0}}, r"slider.hinge: 2.0 m above the pad's centre"),
])
def test_a_bad_articulated_case_is_refused_naming_the_key(changes, message):
    with pytest.raises(CaseError, match=message):
        case_from(changed(CASE, **changes))


def test_two_components_without_a_structure_are_refused():
    with pytest.raises(ValueError, match=r"an articulated slider under an imposed displacement is modelled in one "):
        from dccss.excitation import Oriented
        simulate(DFP1, Oriented(Sine(amplitude=0.1, omega=10.0, duration=0.5), 30.0), dt=0.01, slider="articulated",
                 friction=[0.03, 0.06])


def test_a_structure_on_an_articulated_slider_gives_each_surfaces_history():
    from dccss.records import Record

    rec = Record.from_file("config/studies/records/synthetic.AT2", scale=2.2)
    ds = simulate(DFP1, rec, dt=0.01, structure=Structure([0.03, 0.06], 0.02, "surfaces", slider="articulated"))
    assert {"stroke", "stroke_1", "stroke_3", "z_1", "z_3", "friction_coefficient_1", "hinge_rotation",
            "structure_sticking"} <= set(ds.data_vars)
    assert "z" not in ds  # the device has no one friction state
    assert np.allclose(ds["stroke_1"] + ds["stroke_3"], ds["stroke"], atol=1e-15)
    assert ds.attrs["ring_1_reached_at_s"] == pytest.approx(3.71, abs=0.01)  # the lower surface alone
    assert "ring_3_reached_at_s" not in ds.attrs
    assert ds.attrs["stroke_1_max_abs_m"] > ring_strokes(DFP1)[0] > ds.attrs["stroke_3_max_abs_m"]


@pytest.mark.parametrize(("capacity", "on_failure"), [("stop", "error"), ("error", "mark")])
def test_a_ring_reached_ends_the_history_by_the_capacity_policy(capacity, on_failure):
    from dccss.records import Record

    rec = Record.from_file("config/studies/records/synthetic.AT2", scale=2.2)
    ds = simulate(DFP1, rec, dt=0.01, capacity=capacity, on_failure=on_failure,
                  structure=Structure([0.03, 0.06], 0.02, "surfaces", slider="articulated"))
    assert ds["t"].values[-1] == pytest.approx(ds.attrs["ring_1_reached_at_s"])
    assert ds.attrs["failed"] == (capacity == "error")


def test_a_ring_reached_under_capacity_error_is_an_error():
    from dccss.mechanics.capacity import CapacityError
    from dccss.records import Record

    rec = Record.from_file("config/studies/records/synthetic.AT2", scale=2.2)
    with pytest.raises(CapacityError, match=r"the half on surface 1 reaches the ring of RB1 at t = 3.71 s"):
        simulate(DFP1, rec, dt=0.01, capacity="error",
                 structure=Structure([0.03, 0.06], 0.02, "surfaces", slider="articulated"))


# --- a study comparing slider kinds -------------------------------------------------------------------------

STUDY = {"study": {"name": "sliders", "description": "rigid against articulated"}, "prototype": "DFP1",
         "excitation": {"kind": "record", "file": "config/studies/records/synthetic.AT2"}, "dt": 0.01,
         "models": ["compliant"], "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces",
                                                "damping": 0.02},
         "sweep": {"slider": ["rigid", "articulated"], "scale": [1.0, 2.2]}}


def test_a_study_compares_slider_kinds_surface_by_surface():
    """The rigid slider's surfaces slide in proportion (L_j / L of its stroke, no hinge rotation); the
    articulated slider's lower surface takes more, and reaches its ring at a scale where the rigid's does not;
    the pad's models are the rigid slider's (NaN for the articulated cases)."""
    from dccss.studies.run import run_chunk

    study = Study.from_config(STUDY)
    ds = run_chunk(study, "compliant", 0)
    rigid = ds["slider"].values == "rigid"
    assert np.allclose(ds["stroke_1_max_abs"].values[rigid], L1 / (L1 + L3) * ds["stroke_max_abs"].values[rigid])
    assert np.all(ds["hinge_rotation_max_abs"].values[rigid] == 0.0)
    assert np.all(ds["stroke_1_max_abs"].values[~rigid] > ds["stroke_1_max_abs"].values[rigid])
    assert list(ds["ring_1_reached"].values[ds["scale"].values == 2.2]) == [0.0, 1.0]
    assert np.all(np.isnan(ds["theta2_max_abs"].values[~rigid])) and np.all(np.isfinite(ds["theta2_max_abs"][rigid]))
    assert list(ds["capacity_exceeded"].values[~rigid]) == [0, 1]  # the articulated's ring: its capacity


@pytest.mark.parametrize(("changes", "message"), [
    ({"structure": None}, r"sweep.slider: an articulated slider in a study is driven by its structure"),
    ({"structure": {"friction": 0.05}}, r"sweep.slider\[1\] \(articulated\) on structure.friction_on"),
    ({"sweep": {"slider": ["rigid", "hinged"]}}, r"sweep.slider\[1\]: must be one of \['rigid', 'articulated'\]"),
])
def test_a_bad_slider_axis_is_refused_naming_the_key(changes, message):
    with pytest.raises(StudyError, match=message):
        Study.from_config(changed(STUDY, **changes))


# --- the drawings -------------------------------------------------------------------------------------------

def test_the_device_is_drawn_with_its_halves_turned_about_the_hinge():
    """The halves' outlines: the lower one's cap on RB1's sphere about C1, the upper one's on C3; the hinge
    where both halves meet, L_1 from C1 and L_3 from C3."""
    from dccss.hinged import halves, placed_half, pose

    for theta1, theta3 in ((0.0, 0.0), (0.15, 0.12), (-0.1, 0.05)):
        p = pose(DFP1, theta1, theta3)
        assert np.linalg.norm(p["H"] - p["C1"]) == pytest.approx(L1)
        assert np.linalg.norm(p["C3"] - p["H"]) == pytest.approx(L3)
        assert p["H"][0] - p["C1"][0] == pytest.approx(L1 * math.sin(theta1))
        assert p["C3"][0] - p["H"][0] == pytest.approx(L3 * math.sin(theta3))
        lower, upper = halves(DFP1)
        # the cut edges of both halves meet at the hinge
        cut_low = placed_half(lower[np.isclose(lower[:, 1], 0.0)], p["lower"])
        cut_up = placed_half(upper[np.isclose(upper[:, 1], 0.0)], p["upper"])
        hinge = placed_half(np.array([[0.0, 0.0]]), p["lower"])[0]
        assert hinge == pytest.approx(p["H"]) and placed_half(np.array([[0.0, 0.0]]), p["upper"])[0] == \
            pytest.approx(p["H"])
        assert cut_low.shape == cut_up.shape == (2, 2)
        # the lower cap stays on RB1's sphere: its points at R1 from C1
        cap = placed_half(lower[lower[:, 1] < -0.5 * float(DFP1.h2) - 1e-9], p["lower"])
        assert np.allclose(np.linalg.norm(cap - p["C1"], axis=1), R1)


@pytest.mark.slow  # a figure and an animation: 1.6 s
def test_plot_and_animate_an_articulated_history(tmp_path):
    from dccss.animation import animate
    from dccss.plan import plot

    path = tmp_path / "a.nc"
    case_from(CASE).run().to_netcdf(path)
    line = plot(path, tmp_path / "a.png")
    assert "sections at" in line and (tmp_path / "a.png").stat().st_size > 10_000
    line = animate(path, tmp_path / "a.gif", max_frames=4)
    assert "shown as 4 frames" in line and (tmp_path / "a.gif").is_file()


def test_the_sections_are_drawn_at_one_scale():
    """The device's sections share their limits (one drawn near the centre had a narrower frame, so a taller
    equal-aspect box, and its title ran off the figure)."""
    from dccss.hinged import figure, instants

    ds = case_from({"prototype": "DFP1", "dt": 0.01, "model": "compliant", "slider": "articulated",
                    "excitation": {"kind": "record", "file": "config/studies/records/synthetic.AT2", "scale": 2.2},
                    "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces"}}).run()
    n = len(instants(ds))
    sections = figure(ds).axes[:n]
    assert n >= 2 and len({(ax.get_xlim(), ax.get_ylim()) for ax in sections}) == 1


@pytest.mark.parametrize("structure", [False, True])
def test_dccss_run_of_an_articulated_case_says_each_surface_and_its_ring(tmp_path, capsys, structure):
    """dccss run writes and sums up an articulated history (each surface's peak, the hinge; it failed with
    KeyError 'theta2' after writing), and warns of a half at its ring."""
    import shutil

    import yaml

    from dccss import cli

    shutil.copy("config/studies/records/synthetic.AT2", tmp_path / "r.AT2")
    case = ({"prototype": "DFP1", "excitation": {"kind": "record", "file": "r.AT2", "scale": 2.2}, "dt": 0.01,
             "model": "compliant", "slider": "articulated",
             "structure": {"friction": [0.03, 0.06], "friction_on": "surfaces"}} if structure else
            {**CASE, "slider": "articulated", "friction": [0.03, 0.06]})
    (tmp_path / "case.yaml").write_text(yaml.safe_dump(case))
    assert cli.main(["run", str(tmp_path / "case.yaml"), "-o", str(tmp_path / "out.nc")]) == 0
    out = capsys.readouterr()
    assert "articulated slider" in out.out and "max |u_1| = " in out.out and "max hinge rotation = " in out.out
    assert "backend" not in out.out and "theta2" not in out.out
    if structure:  # the lower surface passes its ring (see test_a_ring_reached_by_one_surface_alone...)
        assert "dccss: warning: the half on surface 1 reaches the retaining ring of RB1 at t = 3.68 s" in out.err
