"""The articulated slider (dccss.mechanics.structure: series, corner, articulated): two pendulums in
series, each surface sliding by its own friction; against the rigid slider where the surfaces yield
together, the exact one-component solution, finite differences of its equations, scipy's Radau, and an
independent implicit integration (tests/series_reference.py, the slow tests)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from dccss.mechanics.friction import COULOMB, LAWS, RATIO, WEIGHT, row, surface_mu, surface_mu_slopes
from dccss.mechanics.structure import G, Ground, Structure, StructureError, articulated, corner, respond
from dccss.mechanics.structure.articulated import RADAU_RTOL, articulated_history, surfaces_alike
from dccss.mechanics.structure.series import BOTH, SLIDE1, SLIDE3, STUCK, series_line_history
from dccss.mechanics.structure.sliders import pendulums, ring_strokes
from dccss.paper.prototypes import DFP1
from dccss.records import Record, RecordPair

RECORDS = "config/studies/records"
R1, R3 = float(DFP1.R1), float(DFP1.R3)
L1, L3 = pendulums(DFP1)
L = L1 + L3


def _record(scale=2.0):
    return Record.from_file(f"{RECORDS}/synthetic.AT2", scale=scale)


def _pair(scale=2.0):
    return RecordPair.from_files([f"{RECORDS}/synthetic.AT2", f"{RECORDS}/synthetic_y.AT2"], scale=scale)


def _articulated(friction, damping=0.02, **kw):
    return Structure(friction, damping, "surfaces", slider="articulated", **kw)


def _coulomb_rows(mu1, mu3):
    """The kernel's rows of Coulomb surfaces of weight 1 (μ̄_j = μ_j), and the same laws as the rigid slider's (weight
    and ratio L_j / L: both surfaces starting together from rest)."""
    rows = np.array([row(COULOMB, {"mu": mu1}), row(COULOMB, {"mu": mu3})])
    rigid = rows.copy()
    rigid[:, WEIGHT] *= [L1 / L, L3 / L]
    rigid[:, RATIO] *= [L1 / L, L3 / L]
    return rows, rigid


def _together(mu1):
    """μ3 with which both surfaces yield together: μ1 R1 / L1 = μ3 R3 / L3."""
    return mu1 * R1 / L1 * L3 / R3


# --- the device ------------------------------------------------------------------------------------

def test_the_hinge_at_the_pads_centre_splits_L():
    """L_1 + L_3 = L = |C1C3| wherever the hinge is; DFP1's halves are 0.910 m each (R^j - h_j)."""
    assert L1 + L3 == pytest.approx(float(DFP1.L), abs=1e-15)
    assert L1 == pytest.approx(0.9098, abs=1e-4) and L3 == pytest.approx(0.9098, abs=1e-4)
    up = pendulums(DFP1, hinge=0.05)
    assert up[0] == pytest.approx(L1 - 0.05) and up[1] == pytest.approx(L3 + 0.05)
    # a half reaches its ring when it has turned by α^j - α^2j about C^j
    assert ring_strokes(DFP1)[0] == pytest.approx(L1 * math.sin(DFP1.alpha1 - DFP1.alpha21))


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"slider": "hinged"}, r"structure.slider: must be one of \['rigid', 'articulated'\], got 'hinged'"),
    ({"slider": "articulated", "friction_on": "device"}, r"structure.friction_on: an articulated slider's surfaces"),
    ({"slider": "articulated", "friction": [0.0, 0.05]}, r"structure.friction\[0\]: an articulated slider's "
                                                         r"surfaces need friction at rest"),
    ({"slider": "articulated", "hinge": "high"}, r"structure.hinge: expected a finite number"),
])
def test_a_bad_slider_is_refused_naming_the_key(kwargs, message):
    given = {"friction": [0.03, 0.06], "friction_on": "surfaces", **kwargs}
    with pytest.raises(StructureError, match=message):
        Structure(**given)


def test_a_hinge_outside_the_pad_is_refused():
    s = _articulated([0.03, 0.06], hinge=1.0)
    with pytest.raises(StructureError, match=r"structure.hinge: 1.0 m above the pad's centre puts the hinge outside "
                                             r"the pad"):
        s.pendulums(DFP1)


def test_the_surfaces_laws_are_force_level_coefficients_mu_Rj_over_Lj():
    """Each surface's row: weight and speed ratio R^j / L_j (μ̄_j = μ_j R^j / L_j, Fenz and Constantinou's μ);
    the rigid slider's R^j / L."""
    s = _articulated([0.03, 0.06], factor=1.2)
    rows = s.rows(DFP1, proportional=False)
    assert rows[:, 1] == pytest.approx([R1 / L1, R3 / L3]) and rows[:, 2] == pytest.approx([R1 / L1, R3 / L3])
    assert rows[:, 3] == pytest.approx([1.2, 1.2])
    assert s.rows(DFP1)[:, 1] == pytest.approx([R1 / L, R3 / L])


# --- the friction laws' slopes -----------------------------------------------------------------------

@pytest.mark.parametrize("law", [
    {"law": "velocity", "slow": 0.03, "fast": 0.08, "rate": 20.0},
    {"law": "velocity_pressure", "slow": 0.03, "fast0": 0.09, "delta": 0.03, "alpha": 5e-8, "rate": 25.0,
     "pressure": 3.0e7},
    {"law": "temperature", "mu_ref": 0.08, "contact_radius": 0.2, "pressure": 3.0e7, "p_ref": 2.0e7},
])
def test_the_laws_slopes_equal_finite_differences(law):
    """dμ/dv and dμ/d(N/W) (``surface_mu_slopes``) against central differences of ``surface_mu``."""
    r = row(LAWS[law["law"]], LAWS[law["law"]].values(law))
    for speed, normal, temperature in ((0.0, 1.0, 20.0), (0.05, 0.7, 80.0), (0.4, 1.3, 150.0)):
        dv, dn = surface_mu_slopes(r, speed, normal, temperature)
        e = 1e-6

        def mu(v, normal=normal, temperature=temperature):
            return surface_mu(r, v, normal, temperature)
        # central differences, one-sided of second order at zero speed (μ is defined for v >= 0)
        fv = (mu(speed + e) - mu(speed - e)) / (2 * e) if speed > 0 else \
            (-3 * mu(0.0) + 4 * mu(e) - mu(2 * e)) / (2 * e)
        fn = (surface_mu(r, speed, normal + e, temperature) - surface_mu(r, speed, normal - e, temperature)) / (2 * e)
        assert dv == pytest.approx(fv, rel=1e-6, abs=1e-9)
        assert dn == pytest.approx(fn, rel=1e-6, abs=1e-12)


# --- both surfaces sliding: the equations -----------------------------------------------------------

ROWS = {"coulomb": np.array([row(COULOMB, {"mu": 0.03}), row(COULOMB, {"mu": 0.06})]),
        "velocity": np.array([row(LAWS["velocity"], {"slow": 0.02, "fast": 0.04, "rate": 20.0}),
                              row(LAWS["velocity"], {"slow": 0.04, "fast": 0.07, "rate": 20.0})])}
PARAMS = np.array([0.91, 0.91, G, 0.05, 1.0, -2.0, 3.0, 0.5, 1.0, 0.4, 20.0, 20.0])


def _rates(y, t, rows):
    F, M = np.zeros(6), np.zeros(4)
    corner.system(t, y, PARAMS, rows, F, M)
    return np.concatenate([F[:4], np.linalg.solve(M.reshape(2, 2), F[4:])])


@pytest.mark.parametrize("law", list(ROWS))
@pytest.mark.parametrize("state", [[0.1, 0.05, 0.15, -0.05, -0.1, 0.6], [0.1, 0.05, 0.15, -0.05, 0.3, 0.3],
                                   [0.0, 0.02, 0.05, 0.01, -0.02, 0.8]])
def test_the_corner_equations_keep_the_surfaces_on_their_friction_and_sliding_along_it(law, state):
    """Along (δ̇, σ̇) = M⁻¹ F, the derived p_1 - p_3 = μ̄_3 z_3 - μ̄_1 z_1 changes (central differences) as
    the surfaces' flow u̇_j / L_j says (s_1 z_1 / L_1 - s_3 z_3 / L_3), and u̇ = s_1 z_1 + s_3 z_3: the
    force balance and the kinematics both hold."""
    rows = ROWS[law]
    y, t = np.array(state), 0.1
    rates = _rates(y, t, rows)

    def derived(y, t):
        n, z1x, z1y, z3x, z3y, s1, s3, m1, m3, fx, fy = corner.shape(y, PARAMS, rows, t)
        return (np.array([m3 * z3x - m1 * z1x, m3 * z3y - m1 * z1y]),
                np.array([s1 * z1x / 0.91 - s3 * z3x / 0.91, s1 * z1y / 0.91 - s3 * z3y / 0.91]),
                np.array([s1 * z1x + s3 * z3x, s1 * z1y + s3 * z3y]))

    e = 1e-6
    after, before = derived(y + e * rates, t + e)[0], derived(y - e * rates, t - e)[0]
    _, flow, velocity = derived(y, t)
    assert (after - before) / (2 * e) == pytest.approx(flow, rel=1e-6, abs=1e-10)
    assert velocity == pytest.approx(y[2:4], abs=1e-14)


@pytest.mark.slow  # scipy's Radau at 1e-12: 2 s
def test_the_radau_step_equals_scipys_radau_on_a_turning_slide():
    """dccss's Radau IIA (transformed Newton systems, RADAU5's error estimate) against scipy's Radau on the
    same equations written as an ODE, over 0.3 s of both surfaces sliding while the velocity turns."""
    from scipy.integrate import solve_ivp

    for law in ROWS:
        rows = ROWS[law]
        y0 = np.array([0.1, 0.02, 0.3, 0.1, 0.3, 0.5])
        reference = solve_ivp(lambda t, y, rows=rows: _rates(y, t, rows), (0.0, 0.3), y0, method="Radau",
                              rtol=1e-11, atol=1e-13)
        work, Z = corner.workspace(), np.zeros(18)
        t, y, h, k0, first = 0.0, y0.copy(), 1e-3, _rates(y0, 0.0, rows), True
        while t < 0.3 - 1e-15:
            h = min(h, 0.3 - t)
            p = PARAMS.copy()
            p[4:6] += p[6:8] * t
            p[8] += p[9] * t
            status, error, _, _ = corner.radau_step(0.0, y, h, p, rows, k0, 1e-10, 1e-12, first, 2, Z, work)
            if status or error > 1.0:
                h *= 0.5
                continue
            first = False
            k0 = (corner.W[2, 0] * Z[:6] + corner.W[2, 1] * Z[6:12] + corner.W[2, 2] * Z[12:]) / h
            y, t = y + Z[12:], t + h
            h *= min(5.0, max(0.2, 0.9 * error ** -0.25))
        assert np.max(np.abs(y - reference.y[:, -1])) < 1e-11
        assert abs(math.degrees(math.atan2(y[3], y[2]) - math.atan2(0.1, 0.3))) > 30.0  # it turned


# --- the rigid slider where the surfaces yield together --------------------------------------------

def test_one_component_surfaces_yielding_together_is_the_rigid_slider():
    """μ1 R1 / L1 = μ3 R3 / L3: both surfaces yield and slide together, in proportion; the exact solution
    equals the rigid slider's over the whole 20 s record to rounding."""
    rec = _record()
    ground = rec.ground_acceleration()
    mu3 = _together(0.045)
    a = respond(ground, rec.time, DFP1, _articulated([0.045, mu3]))
    b = respond(ground, rec.time, DFP1, Structure([0.045, mu3], 0.02, "surfaces"))
    assert np.max(np.abs(a.stroke - b.stroke)) < 1e-12
    assert np.max(np.abs(a.surfaces.stroke[..., 0] - L1 / L * a.stroke)) < 1e-12
    assert np.array_equal(a.surfaces.sliding[:, 0], a.surfaces.sliding[:, 1])  # never one alone
    assert a.sticking.any() and not a.sticking.all()


@pytest.mark.parametrize("law", [pytest.param(0.045, marks=pytest.mark.slow),  # 1-3 s
                                 {"law": "velocity", "slow": 0.03, "fast": 0.06, "rate": 20.0}])
def test_two_components_surfaces_yielding_together_is_the_rigid_slider(law, monkeypatch):
    """The same in two components, Coulomb and a speed law (DFP1's halves are alike: both surfaces slide at the
    same speed). Surfaces alike slide as the rigid slider (``surfaces_alike``: its path, the same stroke to 1e-9
    m). Made to take the corner equations instead (Radau on (u, u̇, δ, σ)), they meet the rigid slider's DOP853 (at
    1e-12) within Radau's tolerance, RADAU_RTOL of the largest stroke (measured: 1e-8 m Coulomb, 5e-9 m the law),
    and the hinge does not turn: δ stays 0 but for rounding."""
    pair = _pair()
    ground = pair.ground_acceleration()
    a = respond(ground, pair.time, DFP1, _articulated([law, law]))
    b = respond(ground, pair.time, DFP1, Structure([law, law], 0.02, "surfaces"))
    assert np.max(np.abs(a.stroke - b.stroke)) < 1e-9
    assert a.surfaces.hinge_peak < 1e-8
    monkeypatch.setattr(articulated, "surfaces_alike", lambda rows, L1, L3: False)
    c = respond(ground, pair.time, DFP1, _articulated([law, law]))
    assert not np.array_equal(c.stroke, a.stroke)  # another path
    assert c.surfaces.sliding.all(axis=1).mean() > 0.5
    assert np.max(np.abs(c.stroke - b.stroke)) < RADAU_RTOL * b.peaks[0]
    assert c.surfaces.hinge_peak < 1e-12


def test_surfaces_nearly_alike_take_the_corner_equations_and_meet_the_rigid_slider():
    """μ_3 = μ_1 (1 + 1e-7): not alike, so both sliding goes through the corner equations (Radau); the hinge
    turns, by little, and the stroke stays within 1e-8 m of the rigid slider's (Radau's tolerance, relative
    1e-6 of a 0.16 m stroke, leaves a few nanometres; the hinge's turn, about 1e-8 m more)."""
    pair = _pair()
    ground = pair.ground_acceleration()
    friction = [0.045, 0.045 * (1.0 + 1e-7)]
    assert not surfaces_alike(Structure(friction, 0.02, "surfaces").rows(DFP1, proportional=False), L1, L3)
    a = respond(ground, pair.time, DFP1, _articulated(friction))
    b = respond(ground, pair.time, DFP1, Structure(friction, 0.02, "surfaces"))
    assert np.max(np.abs(a.stroke - b.stroke)) < 1e-8
    assert 1e-10 < a.surfaces.hinge_peak < 1e-6


def test_which_surfaces_are_alike():
    """Alike: equal μ̄ under Coulomb (μ_3 = μ_1 R^1 L_3 / (L_1 R^3), to 1e-12), or the same law, values and
    halves; not: unequal frictions, another law, another rate, or a hinge off the pad's centre under a law."""
    law = {"law": "velocity", "slow": 0.03, "fast": 0.06, "rate": 20.0}

    def alike(friction, hinge=0.0):
        s = _articulated(friction, hinge=hinge)
        return surfaces_alike(s.rows(DFP1, proportional=False), *s.pendulums(DFP1))
    assert alike([0.045, _together(0.045)]) and alike([law, law]) and alike([0.03, 0.03], hinge=0.0)
    assert not alike([0.03, 0.06]) and not alike([law, 0.045]) and not alike([law, {**law, "rate": 21.0}])
    assert not alike([law, law], hinge=0.05) and not alike([0.03, 0.03], hinge=0.05)


def test_the_general_history_equals_the_exact_one_in_one_component():
    """Coulomb, unequal frictions, one component: the general kernel (DOP853 for one surface, Radau for both)
    equals the exact closed-form solution over the whole record, phase for phase."""
    rec = _record()
    ground = Ground.from_samples(rec.time, rec.acceleration)
    rows, rigid = _coulomb_rows(0.03, 0.06)
    u, v, u1, phase, force = series_line_history(ground.time, ground.a0[:, 0], ground.a1[:, 0], G / L1, G / L3,
                                                 math.sqrt(G / L), 0.02, 0.03 * G, 0.06 * G)
    U, V, U1, _, PHASE, F, _, _ = articulated_history(ground, L1, L3, 0.02, rows, rigid)
    assert np.array_equal(phase, PHASE)
    assert np.max(np.abs(U[:, 0] - u)) < 1e-8 and np.max(np.abs(U1[:, 0] - u1)) < 1e-8
    assert np.all(U[:, 1] == 0.0)
    assert set(np.unique(phase)) == {STUCK, SLIDE1, BOTH}  # the low-friction surface first, then both


# --- the regimes -------------------------------------------------------------------------------------

def test_while_both_slide_the_hinge_keeps_its_rotation_and_alone_the_other_holds():
    """One component, Coulomb: both sliding, u_1 / L_1 - u_3 / L_3 = ±(μ̄_3 - μ̄_1) (the hinge's rotation,
    Fenz and Constantinou); surface 1 alone, surface 3 does not move; u_1 + u_3 = u; |z_j| <= 1."""
    rec = _record()
    r = respond(rec.ground_acceleration(), rec.time, DFP1, _articulated([0.03, 0.06]))
    s = r.surfaces
    m1, m3 = 0.03 * R1 / L1, 0.06 * R3 / L3
    both = s.sliding.all(axis=1)
    w = s.stroke[:, 0, 0] / L1 - s.stroke[:, 0, 1] / L3
    assert both.sum() > 100
    assert np.allclose(np.abs(w[both]), m3 - m1, rtol=0, atol=1e-12)
    alone = s.sliding[:, 0] & ~s.sliding[:, 1]
    assert alone.sum() > 100 and np.all(s.velocity[alone, 0, 1] == 0.0)
    assert np.max(np.abs(s.stroke.sum(axis=-1) - r.stroke)) < 1e-16
    assert np.max(np.abs(s.z)) <= 1.0 + 1e-9
    assert np.allclose(np.abs(s.z[both]), 1.0, atol=1e-9)
    assert s.hinge == pytest.approx(np.arcsin(s.stroke[:, 0, 0] / L1) - np.arcsin(s.stroke[:, 0, 1] / L3))


def test_the_low_friction_surface_reaches_its_ring_where_the_proportional_split_would_not():
    """μ = 0.03 / 0.06 on DFP1: the lower surface slides alone first and takes more than its share. At a scale
    where the rigid slider's surfaces, sliding in proportion, stay inside their rings, the articulated
    slider's lower surface passes its ring (and the upper does not): the result says when and by how much."""
    rec = _record(scale=2.2)
    r = respond(rec.ground_acceleration(), rec.time, DFP1, _articulated([0.03, 0.06]))
    rigid = respond(rec.ground_acceleration(), rec.time, DFP1, Structure([0.03, 0.06], 0.02, "surfaces"))
    ring1, ring3 = ring_strokes(DFP1)
    assert rigid.peaks[0] * L1 / L < ring1 and rigid.peaks[0] * L3 / L < ring3  # proportionally: inside
    (when, by), (when3, by3) = r.surfaces.ring
    assert math.isfinite(when) and by > 0.0 and by == pytest.approx(r.surfaces.peaks[0] - ring1)
    assert math.isnan(when3) and by3 == 0.0
    first = np.argmax(np.abs(r.surfaces.stroke[:, 0, 0]) >= ring1)
    assert rec.time[first] == pytest.approx(when, abs=1e-12)


# --- the compiled and interpreted kernels ------------------------------------------------------------

@pytest.mark.slow
def test_the_articulated_kernel_compiled_equals_interpreted():
    """The same bits compiled and interpreted, in two components with unequal frictions (one surface alone,
    both, stops and starts)."""
    pair = _pair()
    n = 301
    ground = Ground.from_samples(pair.time[:n], pair.ground_acceleration().at(pair.time[:n]))
    rows, rigid = _coulomb_rows(0.03, 0.06)
    compiled = articulated_history(ground, L1, L3, 0.02, rows, rigid, compiled=True)
    interpreted = articulated_history(ground, L1, L3, 0.02, rows, rigid, compiled=False)
    for a, b in zip(compiled, interpreted, strict=True):
        assert np.array_equal(a, b)
    assert set(np.unique(compiled[4])) == {STUCK, SLIDE1, BOTH} | ({SLIDE3} & set(np.unique(compiled[4])))
