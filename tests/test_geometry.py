"""Geometry derived from Table 1: values, compatible configurations, validation, outlines."""

import numpy as np
import pytest
from constraint_sets import circle_centre

from dccss.mechanics.geometry import Geometry, _section_centroid
from dccss.mechanics.kinematics import all_corners, frames, interpenetration, position
from dccss.paper.prototypes import DFP1, DFP2, TABLE1


def test_pad_dimensions_from_table1():
    assert DFP1.A1 == pytest.approx(0.17365, abs=5e-6)  # 17.365 cm
    assert DFP2.A1 == pytest.approx(0.08716, abs=5e-6)  # 8.716 cm
    assert DFP1.B == DFP2.B == pytest.approx(0.075)


@pytest.mark.parametrize("geometry, L", [(DFP1, 1.819616), (DFP2, 1.842389)])
def test_centre_distance_is_eq41_bracket(geometry, L):
    bracket = geometry.h2 + geometry.R1 * (1 - np.cos(geometry.alpha21)) + geometry.R3 * (1 - np.cos(geometry.alpha23))
    assert geometry.L == pytest.approx(geometry.R1 + geometry.R3 - bracket, abs=1e-15)
    assert geometry.L == pytest.approx(L, abs=5e-7)


@pytest.mark.parametrize("geometry, capacity", [(DFP1, 0.190809), (DFP2, 0.224951)])
def test_capacity_is_table1_amplitude(geometry, capacity):
    assert geometry.capacity1 == pytest.approx(capacity, abs=5e-7)


UNEQUAL = Geometry.from_degrees(**{**TABLE1["DFP1"], "R3": 1.4, "alpha3": 17.0, "alpha23": 7.0,
                                   "hmin3": 0.08})


@pytest.mark.parametrize("geometry", [DFP1, DFP2, UNEQUAL], ids=["DFP1", "DFP2", "unequal"])
@pytest.mark.parametrize("theta2", np.radians([-10.0, -3.3, 0.0, 2.0, 8.0]))
def test_compatible_configuration(geometry, theta2):
    """Eq. 41 holds, C^1C^3 has length L and all four corners lie on their circles (1e-12 m)."""
    Xg = 0.0123
    q = geometry.compatible(theta2, Xg)
    assert q[0] == Xg and q[1] == 0 and q[2] == 0 and q[8] == 0
    assert q[7] == pytest.approx(geometry.Ry3_compatible(theta2), abs=1e-12)
    eq41 = (geometry.hs1 + geometry.R1 * (1 - np.cos(theta2)) + geometry.hs3 + geometry.R3 * (1 - np.cos(theta2))
            + np.cos(theta2) * (geometry.h2 + geometry.R1 * (1 - np.cos(geometry.alpha21))
                                + geometry.R3 * (1 - np.cos(geometry.alpha23))))
    assert q[7] == pytest.approx(eq41, abs=1e-12)
    assert np.abs(interpenetration(q, geometry)).max() < 1e-12
    F = frames(q)
    A, B, C, D = all_corners(geometry)
    assert abs(abs(circle_centre(F, D) - circle_centre(F, A)) - geometry.L) < 1e-12
    assert q[6] - q[0] == pytest.approx(geometry.L * np.sin(theta2), abs=1e-12)
    # the corners sit at the cap angles alpha21 -/+ theta2 from the plate axis
    d = position(F, A) - circle_centre(F, A)
    assert np.angle(1j * d) == pytest.approx(-(geometry.alpha21 - theta2), abs=1e-12)


def test_batch_geometry_broadcasts():
    g = Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.array([5.0, 10.0])})
    assert g.L.shape == (2,)
    assert g.A1[1] == pytest.approx(DFP1.A1)
    q = g.compatible(np.radians([1.0, -2.0]))
    assert q.shape == (2, 9)
    assert np.abs(interpenetration(q, g)).max() < 1e-12


def test_centroid_matches_polygon_area_centroid():
    """The analytic section centroid (h_s) equals the shoelace centroid of the drawn outline."""
    for g in (DFP1, DFP2, UNEQUAL):
        for plate in (1, 3):
            pts = g.plate_outline(plate, n_arc=4001)
            x, y = pts[:, 0], pts[:, 1]
            cross = x[:-1] * y[1:] - x[1:] * y[:-1]
            area = cross.sum() / 2
            cy = ((y[:-1] + y[1:]) * cross).sum() / (6 * area)
            assert abs(cy) < 1e-6  # the outline is drawn about the centroid
    assert _section_centroid(1.0, np.radians(21), 0.1, 0.02, 0.0258) == pytest.approx(-DFP1.hs1)


def test_outlines_are_closed_and_to_scale():
    pad = DFP1.pad_outline()
    assert np.allclose(pad[0], pad[-1])
    assert pad[:, 0].max() == pytest.approx(DFP1.A1)
    plate = DFP1.plate_outline(1)
    assert np.allclose(plate[0], plate[-1])
    assert plate[:, 0].max() == pytest.approx(DFP1.R1 * np.sin(DFP1.alpha1) + DFP1.tr1)
    top = DFP1.plate_outline(3)
    assert np.allclose(top, plate * [1, -1])  # RB3 is RB1 mirrored for equal plates


BAD = [
    ({"R1": 0.0}, "'R1' is a length and must be > 0"),
    ({"h2": -0.1}, "'h2' is a length and must be > 0"),
    ({"tr3": 0.0}, "'tr3' is a length"),
    ({"R3": np.nan}, "'R3' must be finite"),
    ({"hmin1": np.inf}, "'hmin1' must be finite"),
    ({"alpha21": 21.0}, "'alpha21' must lie in 0 < alpha21 < alpha1"),
    ({"alpha23": 25.0}, "'alpha23' must lie in 0 < alpha23 < alpha3"),
    ({"alpha21": 0.0}, "'alpha21' must lie in 0 < alpha21"),
    ({"alpha1": 90.0}, "'alpha1' must lie in 0 < alpha1 < 90 deg"),
    ({"alpha3": -5.0}, "'alpha3' must lie in 0 < alpha3 < 90 deg"),
    ({"h2": 2.5}, "the pad is too tall"),
    ({"R1": "1 m"}, "'R1' must be a number"),
]


@pytest.mark.parametrize("change, message", BAD, ids=[m for _, m in BAD])
def test_invalid_geometry_names_parameter(change, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Geometry.from_degrees(**{**TABLE1["DFP1"], **change})


def test_invalid_batch_element_reports_index():
    with pytest.raises(ValueError, match=r"batch index \(1,\)"):
        Geometry.from_degrees(**{**TABLE1["DFP1"], "R1": np.array([1.0, -1.0])})


def test_unknown_and_missing_parameters():
    with pytest.raises(ValueError, match="unknown geometry parameter"):
        Geometry.from_degrees(**TABLE1["DFP1"], R2=1.0)
    params = dict(TABLE1["DFP1"])
    del params["hr1"]
    with pytest.raises(ValueError, match=r"missing geometry parameter\(s\) \['hr1'\]"):
        Geometry.from_degrees(**params)


def test_every_bad_parameter_is_named_at_once():
    """Before, only the first was (R1 here), and an angle showed its round trip through radians."""
    params = {**TABLE1["DFP1"], "R1": -3.0, "h2": -0.1, "alpha1": 100.0, "alpha23": -12.0}
    with pytest.raises(ValueError) as err:
        Geometry.from_degrees(**params)
    msg = str(err.value)
    for part in ("'R1' is a length and must be > 0 m, got -3", "'h2' is a length and must be > 0 m, got -0.1",
                 "'alpha1' must lie in 0 < alpha1 < 90 deg, got 100 deg", "got -12 deg"):
        assert part in msg


@pytest.mark.parametrize("key, value", [("R1", None), ("R1", "1.0"), ("R1", True), ("alpha1", "21"),
                                        ("alpha21", None)])
def test_a_parameter_that_is_not_a_number_is_named(key, value):
    """None read as "must be finite, got nan", and "1.0" or True were taken as numbers, unlike a sine's or a
    structure's numbers."""
    from dccss.paper.prototypes import TABLE1

    with pytest.raises(ValueError, match=f"geometry parameter '{key}' must be a number, got {value!r}"):
        Geometry.from_degrees(**{**TABLE1["DFP1"], key: value})
