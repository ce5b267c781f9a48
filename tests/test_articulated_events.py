"""The articulated slider's events while both surfaces slide (``articulated._both``, ``corner.consistent``): a
surface stopping is found where it happens, inside a Radau step too, and where the step to it does not meet it
the search goes on until it does; a split of the sliding that no σ in [0, 1] balances says which surface holds.
Interpreted (the kernel's helpers are plain functions): no compiling."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dccss.mechanics.friction import COULOMB, RATIO, WEIGHT, row
from dccss.mechanics.structure import G, Ground, Structure, corner
from dccss.mechanics.structure import articulated as kernel
from dccss.mechanics.structure.articulated import RADAU_ATOL, RADAU_MIN, RADAU_RTOL, articulated_history
from dccss.mechanics.structure.integrator import YIELD
from dccss.paper.prototypes import DFP1
from dccss.records import RecordPair

COULOMB_ROWS = np.array([row(COULOMB, {"mu": 0.03}), row(COULOMB, {"mu": 0.06})])
L1 = L3 = 0.91


def _rates(t, y, p, rows):
    """ẏ of the corner equations, M(y) ẏ = F(y, t) solved for (δ̇, σ̇)."""
    F, M = np.zeros(6), np.zeros(4)
    corner.system(t, y, p, rows, F, M)
    return np.concatenate([F[:4], np.linalg.solve(M.reshape(2, 2), F[4:])])


def _both(y, p, rows, end):
    """``_both`` from y over [0, end], a new phase: (what ended it, when, the state there)."""
    y = np.array(y, dtype=float)
    ended, when, _ = kernel._both(y, np.zeros(corner.N), end, 0.0, np.asarray(p, dtype=float), rows,
                                  np.zeros(corner.N), corner.workspace(), np.zeros(corner.S * corner.N))
    return ended, when, y


@pytest.mark.parametrize("sigma", [0.0898329110034, 0.0899197511777])
def test_a_surface_stopping_inside_a_step_is_found_there(sigma):
    """Both sliding (δ = 0.6 rad, u̇ = 0.05 m/s nearest z_3); a ground acceleration across u̇ that turns about at
    5 ms (1 - 200 t m/s²) turns u̇ onto z_3 and back: σ dips below 0 (surface 1 stops) for 0.3 ms (dip of 1e-4)
    or 0.1 ms (1e-5) and is back above 0 by 10 ms, inside one of Radau's steps (σ only at the steps' ends
    missed it). Found at scipy's Radau's time (rtol 1e-12), to σ's tolerance over its rate there, the state to
    the step's tolerance."""
    y0 = [0.05, 0.0, 0.05, 0.0, 0.6, sigma]
    p = [L1, L3, G, 0.05, 0.0, 1.0, 0.0, -200.0, 1.0, 0.0, 20.0, 20.0]

    def stops(t, y, p, rows):
        return y[5]
    stops.terminal, stops.direction = True, -1
    whole = solve_ivp(_rates, (0.0, 0.01), y0, method="Radau", rtol=1e-12, atol=1e-14, args=(p, COULOMB_ROWS))
    assert whole.y[5, -1] > 0.0  # back by the end
    ref = solve_ivp(_rates, (0.0, 0.01), y0, method="Radau", rtol=1e-12, atol=1e-14, args=(p, COULOMB_ROWS),
                    events=stops)
    at, state = ref.t_events[0][0], ref.y_events[0][0]
    ended, when, y = _both(y0, p, COULOMB_ROWS, 0.01)
    assert ended == YIELD and y[5] == 0.0
    rate = abs(_rates(at, state, p, COULOMB_ROWS)[5])
    assert abs(when - at) <= (RADAU_ATOL + RADAU_RTOL) / rate
    assert np.all(np.abs(y - state) <= RADAU_ATOL + RADAU_RTOL * np.abs(state))


def _law(mu):
    """A temperature law on its pressure alone (its speed and temperature factors off): μ changes with N/W only."""
    return {"law": "temperature", "mu_ref": mu, "contact_radius": 0.2, "pressure": 3.0e7, "p_ref": 2.0e7,
            "speed_factor": False, "temperature_factor": False}


def _pressure_rows():
    return Structure([_law(0.03), _law(0.09)], 0.02, "surfaces", slider="articulated").rows(DFP1, proportional=False)


#: both sliding at a sample interval's start under a vertical (N/W = 0.96 + 3.44 t) on the surfaces' pressure laws
#: (the synthetic record with its vertical at scale 2, t = 3.76 s): the split σ = 0.12 of the interval before
PRESSURE_STATE = [0.26958705549603046, 0.0, 0.04016361922992649, 0.0, 0.0, 0.12268758624556222]
PRESSURE_LOAD = [0.9098077530122081, 0.9098077530122081, G, 0.09286039241233125, 4.7324821477424575, 0.0,
                 11.404506324399758, 0.0, 0.9598309762515376, 3.4383007799999206, 57.384268741173734, 97.63102978593906]


def _first_equation(y, p, rows, sigma):
    """The first corner equation's F and M's σ column (M[1]) at σ."""
    y = np.array(y, dtype=float)
    y[5] = sigma
    F, M = np.zeros(6), np.zeros(4)
    corner.system(0.0, y, np.asarray(p, dtype=float), rows, F, M)
    return F[4], M[1]


def test_a_surface_stopping_at_once_is_found_at_once():
    """The surfaces' μ does not change with their speeds (M's σ column zero: σ algebraic) and the first equation
    is positive for every σ in [0, 1] (its root below 0: surface 1 would slide backwards): surface 1 stops as the
    interval starts. Radau's first step ends with σ = -0.016 for every length down to 1e-12 s; Newton on the
    length crept (its rate, of the polynomial, wrong for an algebraic σ) and after 40 iterations the event was
    taken as reached 2.5e-6 s on, σ = -0.017 there. Now found within the search's bracket, RADAU_MIN."""
    rows = _pressure_rows()
    for sigma in (0.0, 1.0):
        f, column = _first_equation(PRESSURE_STATE, PRESSURE_LOAD, rows, sigma)
        assert f > 0.0 and column == 0.0
    ended, when, y = _both(PRESSURE_STATE, PRESSURE_LOAD, rows, 0.01)
    assert ended == YIELD and y[5] == 0.0
    assert when <= 1e-15 * kernel.RADAU_FIRST + RADAU_MIN


def test_a_split_no_share_balances_says_which_surface_holds():
    """``corner.consistent`` where the first equation changes no sign over σ in [0, 1]: the side of its root
    (below 0: surface 1 holds), σ kept; it bisected anyway, and set σ to 1 (surface 3 holding) whichever side.
    Where it has a root (Coulomb at δ = 0: the proportional split L_1 / L), σ is that root."""
    rows = _pressure_rows()
    y, F, M = np.array(PRESSURE_STATE), np.zeros(6), np.zeros(4)
    assert corner.consistent(y, np.array(PRESSURE_LOAD), rows, 0.0, F, M) == -1
    assert y[5] == PRESSURE_STATE[5]
    y = np.array([0.05, 0.0, 0.1, 0.0, 0.0, 1.0])
    p = np.array([0.8, 1.0, G, 0.05, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 20.0, 20.0])
    assert corner.consistent(y, p, COULOMB_ROWS, 0.0, F, M) == 0
    assert y[5] == pytest.approx(0.8 / 1.8, rel=1e-12)


def test_a_yield_whose_own_surface_would_slide_backwards_is_refused_naming_the_time(monkeypatch):
    """Where surface 3 yields from surface 1 sliding alone but the split's root lies above 1 (surface 3 would
    slide backwards), no phase holds: the run is refused, naming the sample interval (``consistent`` made to
    say so: it cannot under these equations, where the yielding surface's share follows from the force's
    approach to its circle)."""
    pair = RecordPair.from_files(["config/studies/records/synthetic.AT2", "config/studies/records/synthetic_y.AT2"],
                                 scale=2.0)
    n = 301
    ground = Ground.from_samples(pair.time[:n], pair.ground_acceleration().at(pair.time[:n]))
    rigid = COULOMB_ROWS.copy()  # the rigid slider's rows: weight and ratio L_j / L
    rigid[:, [WEIGHT, RATIO]] *= L1 / (L1 + L3)
    monkeypatch.setattr(corner, "consistent", lambda y, p, rows, t, F, M: 1)
    with pytest.raises(RuntimeError, match=r"a surface of the articulated slider yields in the sample interval at "
                                           r"t = \d+(\.\d+)? s, but no split of the sliding balances the hinge"):
        articulated_history(ground, L1, L3, 0.02, COULOMB_ROWS, rigid, compiled=False)
