"""The one driver of runs (dccss.mechanics.runs): planar or spatial by the ground motion's shape, the
capacity and failure policies as events with a status and a message, for histories and sweeps alike."""

import re

import numpy as np
import pytest

from dccss.excitation import Oriented, Sine, step_times
from dccss.mechanics import runs, spatial, summaries
from dccss.mechanics.capacity import CapacityError
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import ConvergenceError, NewtonOptions
from dccss.paper.prototypes import DFP1
from dccss.simulation import simulate

#: far beyond DFP1's capacity: the pad passes RB1's ring at 0.04 s, the solver fails at 0.15 s
BEYOND = Sine(0.9, 10.0, 1.0)
TIMES = step_times(BEYOND, 0.01)
X = BEYOND.displacement(TIMES)
MOTIONS = {"planar": X, "spatial": np.stack([X, np.zeros_like(X)], axis=-1)}


@pytest.mark.parametrize("motion", list(MOTIONS))
@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_the_ground_motion_picks_the_models(motion, model):
    small = MOTIONS[motion][:6] * 0.1
    run = runs.history(model, DFP1, small, times=TIMES[:6])
    assert run.motion == motion and run.status == "completed" and run.message == "" and run.steps == 6
    assert run.reached is None and run.failure is None
    expected = spatial.run(model, DFP1, small) if motion == "spatial" else None
    if expected is not None:
        assert all(np.array_equal(run.history[k], expected[k], equal_nan=True) for k in expected)


def test_a_ground_motion_of_another_shape_is_refused():
    with pytest.raises(ValueError, match=r"Xg must have shape \(T,\) or \(T, 2\), got \(3, 3\)"):
        runs.history("compliant", DFP1, np.zeros((3, 3)))


@pytest.mark.parametrize("motion", list(MOTIONS))
def test_capacity_stop_is_a_terminal_event(motion):
    run = runs.history("stick_slip", DFP1, MOTIONS[motion], capacity="stop", times=TIMES)
    assert run.status == "stopped" and run.failure is None
    # DFP1 is symmetric: both rings are passed at the same step, the deeper named
    assert run.reached["t"] == pytest.approx(0.04) and run.reached["plate"] in ("RB1", "RB3")
    assert run.steps == 5  # t_0 .. 0.04 s: the first step beyond the ring is the last one stored
    assert f"reached the retaining ring of {run.reached['plate']} at t = 0.04 s" in run.message
    assert "the run stopped there" in run.message


@pytest.mark.parametrize("motion", list(MOTIONS))
def test_capacity_error_and_a_failure_after_the_ring(motion):
    with pytest.raises(CapacityError, match="retaining ring of RB[13] at t = 0.04 s.*lower it, or set capacity"):
        runs.history("stick_slip", DFP1, MOTIONS[motion], capacity="error", times=TIMES)
    with pytest.raises(ConvergenceError, match="Before the solver failed, the pad reached the retaining ring"):
        runs.history("stick_slip", DFP1, MOTIONS[motion], times=TIMES)
    run = runs.history("stick_slip", DFP1, MOTIONS[motion], on_failure="mark", times=TIMES)
    assert run.status == "failed" and run.message == str(run.failure) and run.reached["t"] == pytest.approx(0.04)
    assert 5 <= run.steps < len(TIMES)  # it failed after the ring


@pytest.mark.parametrize("bad, message", [(dict(capacity="halt"), "capacity must be one of"),
                                          (dict(on_failure="raise"), r"on_failure must be one of \('error', 'mark'\)"),
                                          (dict(normals="unsigned"), "signed normals only")])
def test_bad_policies_are_named(bad, message):
    with pytest.raises(ValueError, match=message):
        runs.history("compliant", DFP1, MOTIONS["spatial"][:3], **bad)


def test_sweeps_go_to_the_planar_or_spatial_summaries():
    planar = np.stack([X[:9], 0.5 * X[:9]], axis=1)
    assert_same(runs.summaries("compliant", DFP1, planar, times=TIMES[:9]),
                summaries.summarize("compliant", DFP1, planar, times=TIMES[:9]))
    both = np.stack([MOTIONS["spatial"][:9], 0.5 * MOTIONS["spatial"][:9]], axis=1)
    out = runs.summaries("stick_slip", DFP1, both, times=TIMES[:9], capacity="stop")
    for k in range(2):  # each case: its history (stopped at the ring) reduced by spatial.summary
        run = runs.history("stick_slip", DFP1, both[:, k], capacity="stop", times=TIMES[:9])
        mine = spatial.summary(run.history, DFP1)
        assert all(np.array_equal(out[key][k], mine[key], equal_nan=True) for key in mine)
        assert out["capacity_exceeded"][k] == (run.reached is not None)
    assert list(out["capacity_exceeded"]) == [True, False] and out["capacity_time"][0] == pytest.approx(0.04)


def assert_same(a, b):
    assert a.keys() == b.keys() and all(np.array_equal(a[k], b[k], equal_nan=True) for k in a)


# --- no compatible configuration: never a result ----------------------------------------------------
#: RB1 driven 2 m from its start: past DFP1's pendulum length L = 1.82 m at t = 0.73 s
FAR_TIMES = np.arange(0, 2.01, 0.01)
FAR = 2.0 * np.sin(np.pi * FAR_TIMES / 2)


@pytest.mark.parametrize("motion", ["planar", "spatial"])
@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_a_step_beyond_the_pendulum_length_is_an_error_whatever_the_capacity_policy(motion, model):
    from dccss.mechanics.capacity import IncompatibleMotion

    X = FAR if motion == "planar" else np.stack([FAR * 0.6, -FAR * 0.8], axis=-1)
    marked = runs.history(model, DFP1, X, times=FAR_TIMES, capacity="continue", on_failure="mark")
    assert marked.status == "failed" and marked.steps <= 73
    assert marked.steps == 73 or model == "stick_slip"  # compliant sliding follows the motion to the end of reach
    if marked.steps < 73:  # the solver gave up first, past the ring (stick-slip), and says so
        assert not isinstance(marked.failure, IncompatibleMotion)
        assert "Before the solver failed, the pad reached the retaining ring" in marked.message
        assert "RB1 moved by" in marked.message
        return
    assert "no compatible configuration" in marked.message and isinstance(marked.failure, IncompatibleMotion)
    with pytest.raises(IncompatibleMotion, match=r"at t = 0\.73 s \(step 73\) RB1 is displaced by 182\.3 cm .*"
                                                 r"L = \|C1C3\| = 182 cm or more from RB3: no compatible"):
        runs.history(model, DFP1, X, times=FAR_TIMES, capacity="continue")
    # the pad passes the ring long before: "stop" ends the history there, and that is a result
    stopped = runs.history(model, DFP1, X, times=FAR_TIMES, capacity="stop")
    assert stopped.status == "stopped" and stopped.steps < 20 and stopped.failure is None


def test_the_ring_message_says_how_far_rb1_had_moved():
    with pytest.raises(CapacityError, match=r"retaining ring of RB3 at t = 0\.12 s \(step 12, RB1 moved by 37\.48 cm; "
                                            r"the ring is where the pad has turned by alpha3 - alpha23, which "
                                            r"compliant sliding reaches at L sin\(alpha3 - alpha23\) = 34\.72 cm; "
                                            r"one surface's capacity R3 sin\(alpha3 - alpha23\) = 19\.08 cm\)"):
        runs.history("compliant", DFP1, FAR, times=FAR_TIMES, capacity="error")


def test_a_sweep_marks_or_names_the_case_beyond_reach():
    from dccss.mechanics.capacity import IncompatibleMotion
    from dccss.mechanics.newton import NewtonOptions

    X = np.sin(np.pi * FAR_TIMES / 2)[:, None] * np.array([0.1, 2.0, 0.2])
    with pytest.raises(IncompatibleMotion, match=r"in the case at batch index \(1,\): at t = 0\.73 s") as caught:
        runs.summaries("compliant", DFP1, X, times=FAR_TIMES)
    assert caught.value.index == (1,)
    out = runs.summaries("compliant", DFP1, X, times=FAR_TIMES, options=NewtonOptions(on_failure="mark"))
    assert list(out["failed"]) == [False, True, False] and np.isnan(out["theta2_max_abs"][1])
    assert out["failure_time"][1] <= 0.73 and np.isfinite(out["theta2_max_abs"][[0, 2]]).all()
    spatial_X = np.stack([X, np.zeros_like(X)], axis=-1)
    out = runs.summaries("compliant", DFP1, spatial_X, times=FAR_TIMES, options=NewtonOptions(on_failure="mark"))
    assert list(out["failed"]) == [False, True, False] and out["failure_time"][1] == 0.73


def test_oscillation_finds_a_growing_step_to_step_oscillation_only():
    t = np.linspace(0.0, 1.0, 40)
    smooth = np.column_stack([np.sin(3 * t), t ** 2])
    assert runs.oscillation(smooth) == 0.0
    wobble = smooth.copy()
    wobble[-6:, 1] += 1e-5 * (-1.8) ** np.arange(6)  # period 2, growing 1.8 times a step
    assert runs.oscillation(wobble) == pytest.approx(1.8, rel=0.05)
    assert runs.oscillation(smooth[:10]) == 0.0  # too short to tell


# a deep device with a flat pad, found losing stick-slip's stability well before its rings
DEEP = Geometry.from_degrees(R1=0.5, R3=0.8, alpha1=60.0, alpha3=50.0, h2=0.1, alpha21=10.0, alpha23=8.0, hr1=0.01,
                             hr3=0.2, hmin1=0.05, hmin3=0.05, tr1=0.02, tr3=0.02)


@pytest.mark.parametrize("azimuth", [None, 90.0])
def test_a_stick_slip_oscillation_is_explained_and_a_smaller_dt_fails_earlier(azimuth):
    """Stick-slip on DEEP oscillates from step to step, growing, from about 16-20 degrees (its rings are at
    42 degrees): the failure says so instead of advising a smaller dt, which fails earlier."""
    sine = Sine(0.6 * DEEP.L * np.sin(DEEP.alpha3 - DEEP.alpha23), 5.0, 0.5)
    failed = []
    for dt in (0.002, 0.0005):
        with pytest.raises(ConvergenceError) as err:
            simulate(DEEP, sine if azimuth is None else Oriented(sine, azimuth), model="stick_slip", dt=dt)
        assert "oscillate from step to step" in str(err.value) and "reduce dt" not in str(err.value)
        failed.append(float(re.search(r"time ([0-9.]+) s", str(err.value)).group(1)))
    assert failed[1] < failed[0]
    ds = simulate(DEEP, sine, model="compliant", dt=0.0005)  # compliant sliding is stable there
    assert ds.attrs["failed"] == 0 and np.abs(ds["theta2"]).max() > 20.0


def test_a_sweep_case_that_passes_a_ring_then_fails_keeps_the_ring():
    """As its history does (before, the sweep reported a failed case as never reaching the ring)."""
    model = "stick_slip"  # its solver gives up past the ring (compliant sliding goes on to L)
    run = runs.history(model, DFP1, X, times=TIMES, on_failure="mark")
    assert run.status == "failed" and run.reached["t"] < TIMES[run.steps]
    out = runs.summaries(model, DFP1, np.stack([X, 0.1 * X], axis=1), times=TIMES,
                         options=NewtonOptions(on_failure="mark"))
    assert out["failed"][0] and out["failure_time"][0] == TIMES[run.steps]
    assert out["capacity_exceeded"][0] and out["capacity_time"][0] == run.reached["t"]
    assert not out["failed"][1] and not out["capacity_exceeded"][1] and np.isnan(out["capacity_time"][1])


def test_an_oscillation_caught_three_steps_before_the_failure_is_explained():
    """At a coarser step the oscillation grows faster (8 times a step here): three steps of it are enough."""
    with pytest.raises(ConvergenceError, match="oscillate from step to step"):
        simulate(DEEP, Sine(0.6, 4.0, 1.6), model="stick_slip", dt=0.004)


@pytest.mark.parametrize("kernels", ["python", "numba"])
@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_a_sweep_case_stopped_at_its_ring_is_not_stepped_on_to_a_failure(monkeypatch, kernels, model):
    """capacity "stop" with on_failure "error": case 0 reaches its ring at 0.04 s and (stick-slip) would fail the
    solver at 0.15 s; stopped there, it is neither stepped nor judged any more, and the sweep completes with its
    summaries ending at the ring, as with on_failure "mark"; case 1 stays inside."""
    from dccss.mechanics import backend

    monkeypatch.setenv(backend.ENV, kernels)
    both = np.stack([X, 0.1 * X], axis=1)
    out = runs.summaries(model, DFP1, both, times=TIMES, capacity="stop")
    assert backend.last == kernels
    assert_same(out, runs.summaries(model, DFP1, both, times=TIMES, capacity="stop",
                                    options=NewtonOptions(on_failure="mark")))
    assert list(out["failed"]) == [False, False] and np.isnan(out["failure_time"]).all()
    assert list(out["capacity_exceeded"]) == [True, False] and out["capacity_time"][0] == pytest.approx(0.04)
    inside = runs.summaries(model, DFP1, both[:, 1:], times=TIMES, capacity="stop")
    assert all(np.array_equal(out[k][1:], inside[k], equal_nan=True) for k in out)
    # the other policies as before: the failure beyond the ring counts under "continue", the ring under "error"
    if model == "stick_slip":
        with pytest.raises(ConvergenceError, match=r"batch index \(0,\), step 15"):
            runs.summaries(model, DFP1, both, times=TIMES)
    with pytest.raises(CapacityError, match=r"t = 0\.04 s in the case at batch index \(0,\)"):
        runs.summaries(model, DFP1, both, times=TIMES, capacity="error")
