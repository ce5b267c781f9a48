"""Animations of result histories: frames, configurations drawn, subsampling, bad input, reproducible bytes."""

import argparse
import base64
import os
import re
import subprocess
import sys
from io import BytesIO

import numpy as np
import pytest
import xarray as xr
from matplotlib import animation as mpl_animation
from matplotlib.figure import Figure
from PIL import Image

from dccss import animation
from dccss.animation import AnimationError, add_parser, animate, draw_frame, frame_steps, select
from dccss.excitation import Sine
from dccss.files import write_netcdf
from dccss.paper.prototypes import DFP1, DFP2
from dccss.results import geometry_from_attrs
from dccss.simulation import simulate

N_STEPS = 21  # t = 0, 0.01, ..., 0.2 s


@pytest.fixture(scope="module")
def histories(tmp_path_factory):
    """Short histories on disk: stick-slip (DFP2), compliant (DFP1), and the stick-slip one marked
    as failed and as capacity-stopped."""
    folder = tmp_path_factory.mktemp("histories")
    stick = simulate(DFP2, Sine(0.27, 30.0, 0.2), model="stick_slip", dt=0.01)
    compliant = simulate(DFP1, Sine(0.27, 30.0, 0.2), model="compliant", dt=0.01)
    failed = stick.isel(t=slice(0, 12)).assign_attrs(failed=1, failure_time_s=0.12,
                                                      failure_message="Newton-Raphson did not converge")
    stopped = stick.isel(t=slice(0, 9)).assign_attrs(capacity_exceeded_at_s=0.08, capacity_exceeded_plate="RB3",
                                                      capacity_exceeded_by_m=0.004, stopped_at_s=0.08)
    paths = {}
    for name, ds in (("stick", stick), ("compliant", compliant), ("failed", failed), ("stopped", stopped)):
        paths[name] = folder / f"{name}.nc"
        write_netcdf(ds, paths[name])
    return paths


def _pad_corners(ds, n, suffix=""):
    """Pad corners (4, 2) in cm from R_x^2, R_y^2, theta^2 of the dataset: R + e^{i theta} u."""
    g = geometry_from_attrs(ds.attrs)
    u = g.pad_corners[:, 0] + 1j * g.pad_corners[:, 1]
    z = (float(ds[f"Rx2{suffix}"][n]) + 1j * float(ds[f"Ry2{suffix}"][n])
         + np.exp(1j * np.radians(float(ds[f"theta2{suffix}"][n]))) * u)
    return 100 * np.column_stack([z.real, z.imag])


def _drawn(fig, gid):
    (line,) = fig.findobj(lambda a: a.get_gid() == gid)
    return np.column_stack(line.get_data()), line.get_visible()


def _texts(fig):
    return {artist.get_text() for artist in fig.findobj(lambda a: hasattr(a, "get_text"))}


def _run(argv):
    parser = argparse.ArgumentParser(prog="dccss")
    add_parser(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(["animate", *map(str, argv)])
    return args.handler(args)


# --- frames -----------------------------------------------------------------------------------------
@pytest.mark.slow
def test_gif_has_one_frame_per_step_and_decodes(histories, tmp_path):
    out = tmp_path / "stick.gif"
    line = animate(histories["stick"], out, fps=20)
    assert f"{N_STEPS - 1} steps ({N_STEPS} states" in line and f"shown as {N_STEPS} frames, every step" in line
    with Image.open(out) as im:
        assert im.n_frames == N_STEPS and im.info["duration"] == 50 and im.size == (1100, 720)
        for k in range(im.n_frames):
            im.seek(k)
            im.load()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["stick.gif"]  # no temporary file left


@pytest.mark.slow
def test_html_is_one_page_holding_every_frame(histories, tmp_path):
    out = tmp_path / "compliant.html"
    animate(histories["compliant"], out, max_frames=8)
    page = out.read_text(encoding="utf-8")
    frames = re.findall(r'"data:image/png;base64,((?:[^"\\]|\\\n)*)"', page)
    assert len(frames) == 8  # 21 steps: every 3rd, 0, 3, ..., 18, and the last, 20
    assert "new Array(8)" in page and 'type="range"' in page and "pause_animation" in page
    assert "http" not in page  # self-contained: no web font, no script from elsewhere
    with Image.open(BytesIO(base64.b64decode(frames[3].replace("\\\n", "")))) as im:
        assert im.format == "PNG" and im.size == (1100, 720)


@pytest.mark.parametrize("n", [1, 7, 15])
def test_frame_draws_the_stick_slip_configurations_of_the_step(histories, n):
    ds = xr.load_dataset(histories["stick"])
    fig = Figure()
    draw_frame(fig, ds, n)
    corners, _ = _drawn(fig, "pad_corners")
    np.testing.assert_allclose(corners, _pad_corners(ds, n), atol=1e-9)
    stick, visible = _drawn(fig, "pad_corners_stick")
    assert visible
    np.testing.assert_allclose(stick, _pad_corners(ds, n, "_stick"), atol=1e-9)
    assert np.abs(stick - corners).max() > 0.1  # the two phases differ: the test can tell them apart
    diagonal, visible = _drawn(fig, "jammed_diagonal")
    ends = [(0, 3), (1, 2)][int(ds["sticking_diagonal"][n])]
    assert visible
    np.testing.assert_allclose(diagonal, stick[list(ends)], atol=1e-9)
    (rb1,) = fig.findobj(lambda a: a.get_gid() == "RB1")
    g = geometry_from_attrs(ds.attrs)
    np.testing.assert_allclose(rb1.get_xy()[:-1, 0].max(), 100 * (float(ds["Rx1"][n]) + g.R1 * np.sin(g.alpha1)
                                                                  + g.tr1), atol=1e-9)


def test_moving_the_scene_follows_the_dataset(histories):
    ds = xr.load_dataset(histories["compliant"])
    fig = Figure()
    scene = draw_frame(fig, ds, 0)
    assert not fig.findobj(lambda a: a.get_gid() == "pad_corners_stick")  # compliant: no sticking phase
    for n in (12, 4, -1):
        scene.show(range(N_STEPS)[n])
        np.testing.assert_allclose(_drawn(fig, "pad_corners")[0], _pad_corners(ds, n), atol=1e-9)


def test_first_stick_slip_step_has_no_sticking_phase(histories):
    fig = Figure()
    draw_frame(fig, xr.load_dataset(histories["stick"]), 0)
    assert not _drawn(fig, "pad_corners_stick")[1] and not _drawn(fig, "jammed_diagonal")[1]


@pytest.mark.parametrize("exaggeration, label", [(500.0, "interpenetration × 500"), (None, "interpenetration × 20"),
                                                  (0.0, None)])
def test_interpenetration_spikes_are_magnified_as_labelled(histories, exaggeration, label):
    ds = xr.load_dataset(histories["compliant"])
    fig = Figure()
    draw_frame(fig, ds, 9, exaggeration=exaggeration)
    assert {text for text in _texts(fig) if "interpenetration ×" in text} == ({label} if label else set())
    spikes, _ = _drawn(fig, "spikes")
    lengths = np.hypot(*np.diff(spikes, axis=0)[::3].T)  # segments foot-tip, separated by NaN
    I = np.array([float(ds[f"I_{c}"][9]) for c in "ABCD"])
    factor = float(label.split("× ")[1]) if label else 0.0
    np.testing.assert_allclose(sorted(lengths), sorted(100 * factor * I[I > 0]) if label else [], rtol=1e-9)


@pytest.mark.parametrize("name, words", [
    ("failed", ["solver failed at t = 0.12 s", "Newton-Raphson did not converge"]),
    ("stopped", ["retaining ring of RB3 at t = 0.08 s", "stopped there"]),
])
def test_frames_of_failed_and_stopped_runs_say_so(histories, name, words):
    fig = Figure()
    draw_frame(fig, xr.load_dataset(histories[name]), -1)
    text = " ".join(_texts(fig)).replace("\n", " ")
    assert all(word in text for word in words)


# --- titles ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("attrs, text", [
    ({"excitation": "sine", "amplitude_m": 0.1908, "omega_rad_per_s": 30.0, "dt_s": 0.001},
     "sine $X_{g,max}$ = 19.08 cm, ω = 30 rad/s; Δt = 0.001 s"),
    ({"excitation": "sine", "amplitude_m": 0.27, "omega_rad_per_s": 30.0, "excitation_scale": 0.5,
      "excitation_azimuth_deg": 45.0, "theta2_0_deg": 2.0},
     "sine $X_{g,max}$ = 27 cm, ω = 30 rad/s, scaled by 0.5, along 45°; $\\theta^2(t_0)$ = 2°"),
    ({"excitation": "record", "record_source": "RSN6_ELC180.AT2", "record_scale": 2.0, "dt_s": 0.005},
     "record RSN6_ELC180, scaled by 2; Δt = 0.005 s"),
    ({"excitation": "record", "record_1_source": "RSN6_ELC180.AT2", "record_2_source": "RSN6_ELC270.AT2",
      "record_1_scale": 1.5, "record_2_scale": 1.5, "record_rotation_deg": 30.0, "excitation_component": "both",
      "vertical_form": "record", "record_vertical_source": "RSN6_ELCUP.AT2", "structure_friction": 0.04,
      "structure_damping": 0.0, "structure_friction_on": "device", "dt_s": 0.01},
     "record pair RSN6_ELC180 + RSN6_ELC270, scaled by 1.5, turned by 30°, both components, vertical RSN6_ELCUP; "
     "structure μ = 0.04, ζ = 0; Δt = 0.01 s"),
    ({"excitation": "sine", "amplitude_m": 0.1, "omega_rad_per_s": 5.0, "vertical_form": "sine",
      "vertical_amplitude_m_per_s2": 2.5, "vertical_omega_rad_per_s": 10.0},
     "sine $X_{g,max}$ = 10 cm, ω = 5 rad/s, vertical sine 2.5 m/s², ω = 10 rad/s"),
    ({"excitation": "table", "table_source": "tables/motion.csv", "excitation_component": "y",
      "structure_friction": 0.05, "structure_friction_given": 0.03, "structure_friction_on": "surfaces",
      "structure_damping": 0.02}, "table motion.csv, its y component alone; structure $μ_s$ = 0.03 on each surface, "
                                  "ζ = 0.02"),
])
def test_a_history_is_said_by_its_motion_and_parameters(attrs, text):
    from dccss.viewer import case_text

    assert case_text(attrs) == text


@pytest.mark.slow
def test_an_animation_is_titled_by_its_motion_and_parameters_not_its_file(histories, tmp_path, monkeypatch):
    """The heading named the history's file ("compliant.nc", a study's "compliant_1.nc") where the history
    has no case id: it says the ground motion and the case's parameters, read from the dataset."""
    scenes, start = [], animation._Blitter.__init__

    def spy(blit, scene, first):
        scenes.append(scene)
        start(blit, scene, first)

    monkeypatch.setattr(animation._Blitter, "__init__", spy)
    animate(histories["compliant"], tmp_path / "compliant.gif", max_frames=2)
    (scene,) = scenes
    (head,) = [text for text in _texts(scene.fig) if text.startswith("Compliant Sliding model")]
    assert head.endswith("  —  sine $X_{g,max}$ = 27 cm, ω = 30 rad/s; Δt = 0.01 s") and ".nc" not in head


# --- subsampling and time range ------------------------------------------------------------------
@pytest.mark.parametrize("n, budget", [(1001, 200), (1000, 200), (21, 200), (21, 5), (21, 2), (200, 200), (201, 200),
                                       (10001, 37)])
def test_frame_budget(n, budget):
    idx, k = frame_steps(n, budget)
    assert idx[0] == 0 and idx[-1] == n - 1 and len(idx) <= budget
    assert set(np.diff(idx)[:-1]) <= {k} and 0 < idx[-1] - idx[-2] <= k
    assert k == 1 or len(idx) > budget // 2  # the budget is used, not wasted


@pytest.mark.slow
def test_long_history_is_subsampled_and_says_so(histories, tmp_path):
    out = tmp_path / "short.gif"
    line = animate(histories["stick"], out, max_frames=5)
    assert "20 steps (21 states, t = 0 .. 0.2 s) shown as 5 frames, every 5th step;" in line
    with Image.open(out) as im:
        assert im.n_frames == 5


@pytest.mark.slow
def test_start_end_select_steps(histories, tmp_path):
    out = tmp_path / "part.gif"
    line = animate(histories["stick"], out, start=0.05, end=0.1)
    assert "5 steps (6 states, t = 0.05 .. 0.1 s) shown as 6 frames" in line
    with Image.open(out) as im:
        assert im.n_frames == 6
    part = select(xr.load_dataset(histories["stick"]), 0.05, 0.1)
    assert list(part["step"].values) == [5, 6, 7, 8, 9, 10]


# --- bad input ------------------------------------------------------------------------------------
@pytest.fixture
def not_dccss(tmp_path_factory):
    folder = tmp_path_factory.mktemp("other")
    plain, grid = folder / "plain.nc", folder / "grid.nc"
    xr.Dataset({"x": ("t", np.arange(3.0))}, coords={"t": np.arange(3.0)}).to_netcdf(plain)
    xr.Dataset({"I_A": ("theta2_0", np.zeros(3))}, attrs={"model": "compliant"}).to_netcdf(grid)
    text = folder / "notes.nc"
    text.write_text("not a netCDF file")
    return {"plain": plain, "grid": grid, "text": text}


@pytest.mark.parametrize("case, options, message", [
    ("missing", {}, "does not exist"),
    ("plain", {}, "not a dccss result: its global attribute 'model' is 'missing'"),
    ("grid", {}, "not a dccss time history (a breakaway sweep or a study grid?): it lacks the time coordinate t, Rx1"),
    ("text", {}, "cannot read"),
    ("stick", {"suffix": ".avi"}, "unknown extension '.avi', expected one of .gif, .html, .mp4"),
    ("stick", {"suffix": ""}, "unknown extension '(none)'"),
    ("stick", {"start": 0.15, "end": 0.05}, "start (0.15 s) is after end (0.05 s)"),
    ("stick", {"start": 5.0}, "no stored step in the time range 5 .. +inf s: the history covers t = 0 .. 0.2 s"),
    ("stick", {"fps": 0}, "fps must be a number with 0 < fps <= 50, got 0"),
    ("stick", {"fps": -2.5}, "got -2.5"),
    ("stick", {"max_frames": 1}, "max_frames must be an integer >= 2, got 1"),
])
def test_bad_input_is_named_and_leaves_nothing(histories, not_dccss, tmp_path, capsys, case, options, message):
    path = {**histories, **not_dccss}.get(case, tmp_path / "nowhere.nc")
    options = dict(options)
    out = tmp_path / "out" / f"movie{options.pop('suffix', '.gif')}"
    with pytest.raises(AnimationError, match=re.escape(message)):
        animate(path, out, **options)
    argv = [path, "-o", out] + [f"--{k.replace('_', '-')}={v}" for k, v in options.items()]
    assert _run(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("dccss animate: error: ") and message in err
    assert list(tmp_path.iterdir()) == []  # not even the output folder


def test_error_keeps_an_existing_output(histories, tmp_path):
    out = tmp_path / "movie.gif"
    out.write_bytes(b"previous")
    with pytest.raises(AnimationError):
        animate(histories["stick"], out, start=1.0)
    assert out.read_bytes() == b"previous" and list(tmp_path.iterdir()) == [out]


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".gif", ".html"])
def test_interrupted_rendering_leaves_the_previous_output(histories, tmp_path, monkeypatch, suffix):
    out = tmp_path / f"movie{suffix}"
    out.write_bytes(b"previous")
    show, calls = animation.Scene.show, []

    def failing(scene, n):
        calls.append(n)
        if len(calls) == 9:
            raise KeyboardInterrupt
        show(scene, n)

    monkeypatch.setattr(animation.Scene, "show", failing)
    with pytest.raises(KeyboardInterrupt):
        animate(histories["stick"], out)
    assert out.read_bytes() == b"previous" and list(tmp_path.iterdir()) == [out]


@pytest.mark.slow
def test_command_line_prints_the_summary(histories, tmp_path, capsys):
    out = tmp_path / "cli.gif"
    assert _run([histories["stick"], "-o", out, "--max-frames", "3", "--fps", "5"]) == 0
    assert capsys.readouterr().out == (f"dccss animate: wrote {out}: 20 steps (21 states, t = 0 .. 0.2 s) "
                                       "shown as 3 frames, every 10th step; 5 fps, 0.6 s\n")


# --- reproducible bytes, mp4 -----------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".gif", ".html"])
def test_two_runs_give_the_same_bytes(histories, tmp_path, suffix):
    """Once here, once in another process with another hash seed."""
    first, second = tmp_path / f"a{suffix}", tmp_path / f"b{suffix}"
    animate(histories["stick"], first, max_frames=4)
    code = f"from dccss.animation import animate; animate({str(histories['stick'])!r}, {str(second)!r}, max_frames=4)"
    subprocess.run([sys.executable, "-c", code], check=True, env={**os.environ, "PYTHONHASHSEED": "12345"})
    assert first.read_bytes() == second.read_bytes()


def test_mp4_without_ffmpeg_names_it(histories, tmp_path, monkeypatch):
    available = mpl_animation.writers.is_available
    monkeypatch.setattr(mpl_animation.writers, "is_available", lambda name: name != "ffmpeg" and available(name))
    out = tmp_path / "movie.mp4"
    with pytest.raises(AnimationError, match="MP4 output needs ffmpeg, which is not installed"):
        animate(histories["stick"], out)
    assert not out.exists()


@pytest.mark.skipif(not mpl_animation.writers.is_available("ffmpeg"), reason="ffmpeg is not installed")
@pytest.mark.slow
def test_mp4_where_ffmpeg_is_installed(histories, tmp_path):
    out = tmp_path / "movie.mp4"
    assert "shown as 4 frames" in animate(histories["compliant"], out, max_frames=4)
    assert out.read_bytes()[4:8] == b"ftyp"
