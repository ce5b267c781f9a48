"""Imposed ground motion: sine with analytic velocity, sampled tables, step times."""

import numpy as np
import pytest

from dccss.excitation import Sine, Table, step_times
from dccss.paper.prototypes import DFP1, DFP2


@pytest.mark.parametrize("geometry, t, velocity", [(DFP1, 0.73, -570.05), (DFP2, 0.94, -672.99)])
def test_fig20_velocities_with_table1_amplitude(geometry, t, velocity):
    """Fig. 20: X_g,max omega cos(omega t) with the unrounded X_g,max = R sin(alpha1 - alpha21),
    in cm/s (the caption's '-672.99 s' is cm/s)."""
    ex = Sine(geometry.capacity1, 30.0, 1.0)
    assert 100 * ex.velocity(t) == pytest.approx(velocity, abs=0.005)


def test_sine_velocity_is_derivative():
    ex = Sine(0.2, 30.0, 1.0)
    t = np.linspace(0, 1, 101)
    h = 1e-6
    fd = (ex.displacement(t + h) - ex.displacement(t - h)) / (2 * h)
    assert np.allclose(ex.velocity(t), fd, atol=1e-6)


def test_step_times_cover_duration_exactly():
    t = step_times(Sine(0.1, 30.0, 1.0), 0.001)
    assert len(t) == 1001 and t[-1] == pytest.approx(1.0) and t[730] == pytest.approx(0.73)
    assert len(step_times(Sine(0.1, 30.0, 1.0), 0.3)) == 4  # 0, 0.3, 0.6, 0.9


def test_step_times_reject_bad_dt():
    with pytest.raises(ValueError, match="larger than the excitation's duration"):
        step_times(Sine(0.1, 30.0, 1.0), 2.0)
    with pytest.raises(ValueError, match="dt: must be > 0"):
        step_times(Sine(0.1, 30.0, 1.0), 0.0)


def test_table_interpolates_and_differentiates(tmp_path):
    t = np.linspace(0.0, 2.0, 2001)
    x = 0.1 * np.sin(3 * t)
    path = tmp_path / "record.csv"
    np.savetxt(path, np.column_stack([t, x]), delimiter=",", header="time,displacement", comments="")
    table = Table.from_csv(path)
    tq = np.array([0.0, 0.3333, 1.5, 2.0])
    assert np.allclose(table.displacement(tq), 0.1 * np.sin(3 * tq), atol=2e-7)
    assert np.allclose(table.velocity(tq[1:3]), 0.3 * np.cos(3 * tq[1:3]), atol=1e-5)
    assert table.t_start == 0.0 and table.t_end == 2.0


@pytest.mark.parametrize("content, message", [
    ("time,displacement\n", "no data rows"),
    ("t,x\n0,0\n1,1\n", "header with columns 'time' and 'displacement'"),
    ("time,displacement\n0,0\n1,abc\n", "not numeric"),
    ("time,displacement\n0,0\n1,nan\n", "displacement sample 1 is not finite"),
    ("time,displacement\n0,0\n1,0.1\n0.5,0.2\n", "time must increase strictly"),
    ("time,displacement\n0,0\n", "at least 2 samples"),
])
def test_table_errors_name_the_problem(tmp_path, content, message):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=message):
        Table.from_csv(path)


def test_missing_table_file(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        Table.from_csv(tmp_path / "nope.csv")


def test_sine_rejects_bad_values():
    with pytest.raises(ValueError, match="excitation.duration: must be > 0"):
        Sine(0.1, 30.0, -1.0)
    with pytest.raises(ValueError, match="excitation.amplitude: expected a number"):
        Sine("0.1", 30.0, 1.0)
