"""One case in, one dataset out: failure marking, capacity policies and what the messages say."""

import numpy as np
import pytest

from dccss.excitation import Sine, Table, step_times
from dccss.mechanics import runs
from dccss.mechanics.capacity import CapacityError
from dccss.mechanics.geometry import Geometry
from dccss.mechanics.newton import ConvergenceError, NewtonOptions
from dccss.paper.prototypes import DFP1, TABLE1
from dccss.simulation import breakaway, simulate

#: far beyond DFP1's capacity: the pad passes RB1's ring at 0.04 s, sticking fails at 0.15 s
BEYOND = Sine(0.9, 10.0, 1.0)
#: a wide, flat pad whose sticking phase cannot follow an 8 cm ground step at dt = 0.01 s
WIDE_FLAT = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": 12.0, "alpha23": 12.0, "h2": 0.10})
#: plate 3 steeper than plate 1: RB3's ring (15.6 cm) is reached before RB1's (19.1 cm)
STEEP_TOP = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha3": 19.0})


def test_failure_after_the_ring_says_so_first_and_not_reduce_dt():
    with pytest.raises(ConvergenceError) as err:
        simulate(DFP1, BEYOND, model="stick_slip", dt=0.01)
    msg = str(err.value)
    assert msg.startswith("Before the solver failed, the pad reached the retaining ring of RB1 at t = 0.04 s")
    assert "capacity: stop" in msg and "reduce dt" not in msg
    assert "did not converge in sticking (step 15, time 0.15 s" in msg


def test_failure_without_a_ring_suggests_reducing_dt_and_that_helps():
    with pytest.raises(ConvergenceError, match="reduce dt") as err:
        simulate(WIDE_FLAT, Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.01)
    assert "retaining ring" not in str(err.value)
    ds = simulate(WIDE_FLAT, Sine(0.27, 30.0, 1.0), model="stick_slip", dt=0.005)
    assert ds.attrs["failed"] == 0 and np.isfinite(ds["theta2"]).all()


def test_marked_failure_keeps_the_history_up_to_the_failure():
    ds = simulate(DFP1, BEYOND, model="stick_slip", dt=0.01, on_failure="mark")
    assert ds.attrs["failed"] == 1 and ds.attrs["failure_time_s"] == pytest.approx(0.15)
    assert ds.sizes["t"] == 15 and float(ds["t"][-1]) == pytest.approx(0.14)  # steps 0..14 converged
    assert all(np.isfinite(ds[v]).all() for v in ("theta2", "Ry3", "I_A"))
    assert np.isfinite(ds["theta2_stick"][1:]).all()  # (no sticking phase ends at t0)
    assert "retaining ring of RB1" in ds.attrs["failure_message"]
    reference = simulate(DFP1, Sine(0.9, 10.0, 0.14), model="stick_slip", dt=0.01)
    assert np.array_equal(ds["theta2"].values, reference["theta2"].values)  # the same steps, bit for bit


def test_unmarked_run_records_no_failure():
    ds = simulate(DFP1, Sine(0.27, 30.0, 0.2), model="compliant", dt=0.01, on_failure="mark")
    assert ds.attrs["failed"] == 0 and "failure_time_s" not in ds.attrs and "capacity_exceeded_at_s" not in ds.attrs


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_capacity_error_names_the_plate_reached_and_its_own_capacity(model):
    with pytest.raises(CapacityError) as err:
        simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model=model, dt=0.01, capacity="error")
    msg = str(err.value)
    assert "retaining ring of RB3" in msg
    assert f"R3 sin(alpha3 - alpha23) = {100 * STEEP_TOP.capacity3:.4g} cm" in msg
    assert f"{100 * STEEP_TOP.capacity1:.4g} cm" not in msg
    device = STEEP_TOP.L * np.sin(STEEP_TOP.alpha3 - STEEP_TOP.alpha23)  # RB1's displacement at the ring
    assert f"compliant sliding reaches at L sin(alpha3 - alpha23) = {100 * device:.4g} cm" in msg


def test_the_ring_is_reached_where_the_message_says():
    """Under compliant sliding the pad reaches the ring of RB3 where RB1 has moved L sin(alpha3 - alpha23)
    from RB3 (the pad on C^1C^3 turned by alpha3 - alpha23): the displacement the message quotes."""
    device = STEEP_TOP.L * np.sin(STEEP_TOP.alpha3 - STEEP_TOP.alpha23)
    ds = simulate(STEEP_TOP, Table(np.linspace(0.0, 1.0, 2001), np.linspace(0.0, 1.05 * device, 2001)),
                  model="compliant", dt=0.0005)
    assert ds.attrs["capacity_exceeded_plate"] == "RB3"
    reached = ds.attrs["capacity_exceeded_displacement_m"]
    assert device <= reached <= device + 1.05 * device / 2000  # the first step past it


def test_capacity_attributes_say_when_where_and_how_far():
    ds = simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model="compliant", dt=0.01)
    n = int(np.argmax(ds["capacity_exceeded"].values))
    assert ds.attrs["capacity_exceeded_plate"] == "RB3"
    assert ds.attrs["capacity_exceeded_at_s"] == pytest.approx(float(ds["t"][n]))
    assert float(ds["clearance_3"][n]) < 0 <= float(ds["clearance_3"][n - 1])
    deepest = -min(float(ds["clearance_1"].min()), float(ds["clearance_3"].min()))
    assert ds.attrs["capacity_exceeded_by_m"] == pytest.approx(deepest, rel=1e-12)
    assert ds.attrs["capacity_policy"] == "continue" and "stopped_at_s" not in ds.attrs


def test_capacity_stop_ends_the_history_at_the_ring():
    full = simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model="stick_slip", dt=0.01)
    stopped = simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model="stick_slip", dt=0.01, capacity="stop")
    n = int(np.argmax(full["capacity_exceeded"].values))
    assert stopped.sizes["t"] == n + 1 and stopped.attrs["stopped_at_s"] == pytest.approx(float(full["t"][n]))
    assert np.array_equal(stopped["theta2"].values, full["theta2"].values[:n + 1])
    assert stopped.attrs["capacity_exceeded_by_m"] == pytest.approx(-float(full["clearance_3"][n]), rel=1e-12)


def test_progress_is_reported_once_at_the_end(monkeypatch):
    """The kernels report once, at the end (they take well under a second where they run interpreted)."""
    assert len(step_times(Sine(0.27, 30.0, 0.1), 0.01)) == 11
    monkeypatch.setenv("DCCSS_BACKEND", "python")
    calls = []
    simulate(DFP1, Sine(0.27, 30.0, 0.1), model="compliant", dt=0.01,
             progress=lambda n, total: calls.append((n, total)))
    assert calls == [(10, 10)]


@pytest.mark.parametrize("theta2_0", [np.nan, np.pi / 2, -2.0, 10.0])
def test_a_start_that_is_not_an_angle_within_90_degrees_is_refused(theta2_0):
    """Before, NaN ran to an all-NaN history marked as not failed, and 10 rad (573 degrees) ran."""
    with pytest.raises(ValueError, match=r"theta2_0 must be a finite angle with \|theta2_0\| < pi/2 rad"):
        simulate(DFP1, Sine(0.1, 5.0, 1.0), dt=0.01, theta2_0=theta2_0)
    with pytest.raises(ValueError, match=r"theta2_0 must be a finite angle"):
        runs.summaries("stick_slip", DFP1, np.zeros((3, 2)), np.array([0.0, theta2_0]))
    with pytest.raises(ValueError, match=r"theta2_0 must be a finite angle"):
        breakaway(DFP1, np.array([0.0, theta2_0]), 0.001)


@pytest.mark.parametrize("model", ["compliant", "stick_slip"])
def test_capacity_error_under_mark_ends_the_history_at_the_ring_marked_failed(model):
    """As a study marks such a case (before, the history raised CapacityError and stopped the study)."""
    ds = simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model=model, dt=0.01, capacity="error", on_failure="mark")
    stopped = simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model=model, dt=0.01, capacity="stop")
    assert ds.attrs["failed"] == 1 and "retaining ring of RB3" in ds.attrs["failure_message"]
    assert ds.attrs["failure_time_s"] == ds.attrs["capacity_exceeded_at_s"] == float(ds["t"][-1])
    assert np.array_equal(ds["theta2"].values, stopped["theta2"].values)
    with pytest.raises(CapacityError):
        simulate(STEEP_TOP, Sine(0.40, 10.0, 1.0), model=model, dt=0.01, capacity="error")


def test_a_sweeps_failure_policy_in_a_historys_options_hides_no_failure():
    """``NewtonOptions.on_failure`` is a sweep's: a history applies ``on_failure`` (before, options with
    "mark" gave a planar history of NaN steps marked as not failed)."""
    options = NewtonOptions(max_iter=1, on_failure="mark")
    with pytest.raises(ConvergenceError):
        simulate(DFP1, Sine(0.1, 6.0, 1.0), dt=0.01, options=options)
    ds = simulate(DFP1, Sine(0.1, 6.0, 1.0), dt=0.01, options=options, on_failure="mark")
    assert ds.attrs["failed"] == 1 and ds.attrs["failure_kind"] == "solver" and not np.isnan(ds["theta2"]).any()


@pytest.mark.parametrize("kw, message", [
    (dict(geometry={"R1": 1.0}), "geometry must be a Geometry"),
    (dict(excitation=1.0), "excitation must be a Sine, Table"),
    (dict(theta2_0="0"), "theta2_0 must be a number"),
    (dict(theta2_0=np.zeros(2)), "theta2_0 must be a number"),
    (dict(structure={"friction": 0.05}), "structure must be a Structure"),
    (dict(options={"tol": 1e-9}), "options must be a NewtonOptions"),
])
def test_simulate_names_a_wrong_argument(kw, message):
    """Before: AttributeErrors ('dict' object has no attribute 'L'), or numpy's after the whole run."""
    args = {"geometry": DFP1, "excitation": Sine(0.1, 6.0, 1.0), **kw}
    with pytest.raises(TypeError, match=message):
        simulate(args.pop("geometry"), args.pop("excitation"), dt=0.01, **args)


def test_a_step_that_does_not_divide_the_duration_is_warned_about():
    """Before, the motion's end was dropped silently (a 1 s sine at dt = 0.3 s ended at 0.9 s)."""
    with pytest.warns(UserWarning, match=r"dt = 0.3 s does not divide the excitation's duration \(1 s\): the "
                                         r"history ends at t = 0.9 s, 0.1 s before the motion does"):
        ds = simulate(DFP1, Sine(0.1, 6.0, 1.0), dt=0.3)
    assert ds["t"].values[-1] == pytest.approx(0.9)


@pytest.mark.parametrize("kw, message", [
    (dict(theta2_0_deg=95.0, dXg=0.01), r"theta2_0_deg must be finite angles within \(-90, 90\) degrees, got 95.0"),
    (dict(theta2_0_deg=[1.0, 2.0], dXg="x"), "theta2_0_deg and dXg must be numbers"),
    (dict(theta2_0_deg=[1.0, 2.0], dXg=2.0), r"dXg: a step of 2 m moves RB1 from RB3 by the pendulum length L"),
])
def test_breakaway_names_its_arguments(kw, message):
    """Before: theta2_0_deg = 95 was reported as theta2_0 in radians, a string dXg as numpy's conversion
    error, and a step beyond L as a Newton failure advising to reduce dt (breakaway has none)."""
    with pytest.raises(ValueError, match=message):
        breakaway(DFP1, **kw)
    with pytest.raises(TypeError, match="geometry must be a Geometry"):
        breakaway({"R1": 1.0}, theta2_0_deg=[1.0], dXg=0.01)
