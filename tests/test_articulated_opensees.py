"""The articulated slider (two pendulums in series, each surface sliding by its own friction) against
OpenSees: two singleFPBearing elements (SingleFPSimple2d, SingleFPSimple3d) in series, a small mass (the
slider) on the node between them.

Surface j is OpenSees' friction pendulum with R_eff = L_j and the Coulomb coefficient μ̄_j = μ_j R^j / L_j
(``series``: F = N u_j / L_j + μ̄_j N z_j on both surfaces). The models differ in three ways, each measured
or bounded here:

* **the elastic sticking branch** of each element (initial stiffness kInit_j = μ̄_j W / uy): OpenSees creeps
  where dccss sticks; its effect vanishes as kInit grows (uy -> 0), shown by a trend (uy = 1e-4, 1e-5, 1e-6 m);
* **OpenSees' normal force** N_j = W + F u_j / L_j (the shear force's share along the deformed normal) where
  dccss keeps N = W: the force on surface j grows by the factor 1 / (1 - r_j (r_j + μ̄_j z_j)),
  r_j = u_j / L_j, a second-order effect of relative size ε_j = (μ̄_j + r_j) r_j at a peak r_j;
* **the slider's mass** m (dccss's is massless; OpenSees needs one to solve the elements in series, the
  middle node being otherwise held only by the two elements' tangents). Where both surfaces start to slide
  together the massless slider's velocity jumps (from 0 to L_i/L of the stroke's, the series' kinematics);
  a slider of mass m instead oscillates between the two pendulum stiffnesses W / L_1 + W / L_3 at
  ω_m = sqrt(g (1/L_1 + 1/L_3) / (m/M)) with an amplitude up to δ_m = max|u̇| max(L_1, L_3) / L / ω_m
  (seen in the surfaces' displacements, the oscillation's period 2π/ω_m = 43 ms at m/M = 1e-3).

So the tests integrate the massless series under OpenSees' normal-force law event by event (``_oracle``,
scipy's DOP853 between stick/slip events; under N = W it is dccss's own law and equals dccss's exact
one-component solution to 1e-14 m), show OpenSees converging to it as uy shrinks to within δ_m, and show
that what is left between OpenSees and dccss is the normal-force law: of first order in ε (ε u_max).
The rigid slider of the same frictions (both surfaces sliding together, in proportion) is far outside
all of it: the articulated slider is what OpenSees' two bearings in series compute.
"""

import functools
import math

import numpy as np
import pytest

try:
    import openseespy.opensees as ops
except (ImportError, RuntimeError) as err:  # openseespy raises RuntimeError where BLAS/LAPACK are missing
    raise ImportError("openseespy is a test dependency (pip install -e '.[test]'); on Linux it needs the "
                      "libblas3 and liblapack3 packages (bash .ci/system-libraries.sh)") from err
from conftest import ROOT, scalar_at
from scipy.integrate import solve_ivp

from dccss.mechanics.structure import G, Ground, Structure, respond
from dccss.paper.prototypes import DFP1
from dccss.records import Record, RecordPair

# one worker runs them all: its OpenSees runs (functools.cache) serve each test that uses them
pytestmark = [pytest.mark.slow, pytest.mark.xdist_group("articulated_opensees")]

RECORDS = ROOT / "config/studies/records"
W = 1000.0  # N: drops out
M = W / G
FRICTION = [0.03, 0.06]  # μ_1 (RB1, the lower surface), μ_3 (RB3): unequal, so the surfaces slide alone and together
ARTICULATED, RIGID = "articulated", "rigid"
#: ζ = 0: OpenSees' model has no dashpot
STRUCTURES = {slider: Structure(FRICTION, 0.0, "surfaces", slider=slider) for slider in (ARTICULATED, RIGID)}
L1, L3 = STRUCTURES[ARTICULATED].pendulums(DFP1)
L = L1 + L3
MBAR = (FRICTION[0] * float(DFP1.R1) / L1, FRICTION[1] * float(DFP1.R3) / L3)  # μ̄_j: OpenSees' coefficients
#: the slider's mass over the superstructure's: small enough that its oscillation δ_m stays a few mm, large
#: enough that OpenSees' modified Newton converges (the slider's inertia 4 m / h² against kInit; at 1e-4 it
#: does not converge at uy = 1e-6 in 1000 iterations, at 1e-2 the oscillation is 10 mm)
RATIO = 1e-3
OMEGA_SLIDER = math.sqrt(G * (1 / L1 + 1 / L3) / RATIO)  # 147 rad/s
UY = (1e-4, 1e-5, 1e-6)  # m: the elastic branch's yield displacement μ̄_j W / kInit_j, the same on both elements


def _excitation(components):
    if components == 1:
        return Record.from_file(RECORDS / "synthetic.AT2", scale=2.0)
    return RecordPair.from_files([RECORDS / "synthetic.AT2", RECORDS / "synthetic_y.AT2"], scale=2.0)


@functools.cache
def _ground(components):
    """(t, a_g (T, c)): the record's samples, what dccss joins by straight lines and OpenSees' Path series too."""
    excitation = _excitation(components)
    return excitation.time, excitation.ground_acceleration().at(excitation.time)


@functools.cache
def _ours(components, slider):
    t, a = _ground(components)
    return respond(Ground.from_samples(t, a), t, DFP1, STRUCTURES[slider])


def _substeps(uy, dt):
    """OpenSees' steps per sample interval: ten per radian of the fastest motion it must resolve, the stroke
    on the two elastic branches in series (kInit_1 kInit_3 / (kInit_1 + kInit_3) on M: 46 rad/s at uy = 1e-4,
    464 at 1e-6) or the slider's oscillation ω_m (147 rad/s). The slider on its elastic branches (3e4 rad/s
    at 1e-6) is left unresolved: TRBDF2 is L-stable and damps it out, as the massless slider has none."""
    stick = math.sqrt(G / uy * MBAR[0] * MBAR[1] / (MBAR[0] + MBAR[1]))
    return math.ceil(10 * dt * max(stick, OMEGA_SLIDER))


def _solver():
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("BandGeneral")


@functools.cache
def opensees(components, uy):
    """OpenSees' stroke u (T, c) and lower surface's displacement u_1 (T, c) at the samples: node 1 fixed,
    node 2 the slider (mass RATIO M), node 3 the superstructure (mass M, vertical load W), element 1
    (surface 1: R_eff = L_1, μ̄_1) from 1 to 2, element 2 (surface 3: L_3, μ̄_3) from 2 to 3, kInit_j =
    μ̄_j W / uy, stiff axial springs, rotations fixed; UniformExcitation with the record's samples; TRBDF2,
    modified Newton from the initial stiffness (full Newton cycles between the elements' branches and does
    not converge), the displacement increment to 1e-9 m (a thousandth of the smallest uy)."""
    t, a = _ground(components)
    dt = float(t[1] - t[0])
    ndm, ndf = (2, 3) if components == 1 else (3, 6)
    ops.wipe()
    ops.model("basic", "-ndm", ndm, "-ndf", ndf)
    for node in (1, 2, 3):
        ops.node(node, *[0.0] * ndm)
    ops.fix(1, *[1] * ndf)
    for node, mass in ((2, RATIO * M), (3, M)):
        ops.fix(node, *[0] * ndm, *[1] * (ndf - ndm))
        ops.mass(node, *[mass] * ndm, *[0.0] * (ndf - ndm))
    ops.uniaxialMaterial("Elastic", 1, 1e12)
    ops.uniaxialMaterial("Elastic", 2, 1.0)
    # 2D: local x (axial) along global Y (up), local y (shear) along global -X; 3D: local x along Z
    springs = (("-P", 1, "-Mz", 2, "-orient", 0.0, 1.0, 0.0, -1.0, 0.0, 0.0) if components == 1 else
               ("-P", 1, "-T", 2, "-My", 2, "-Mz", 2, "-orient", 0.0, 0.0, 1.0, 1.0, 0.0, 0.0))
    for tag, (i, j, Lj, mu) in enumerate(((1, 2, L1, MBAR[0]), (2, 3, L3, MBAR[1])), 1):
        ops.frictionModel("Coulomb", tag, mu)
        ops.element("singleFPBearing", tag, i, j, tag, Lj, mu * W / uy, *springs)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(3, *[0.0] * (ndm - 1), -W, *[0.0] * (ndf - ndm))
    _solver()
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 0.1)
    ops.analysis("Static")
    assert ops.analyze(10) == 0
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()
    for k in range(components):
        ops.timeSeries("Path", 2 + k, "-dt", dt, "-values", *a[:, k])
        ops.pattern("UniformExcitation", 2 + k, 1 + k, "-accel", 2 + k)
    _solver()
    ops.test("NormDispIncr", 1e-9, 1000)
    ops.algorithm("ModifiedNewton", "-initial")
    ops.integrator("TRBDF2")
    ops.analysis("Transient")
    sub = _substeps(uy, dt)
    out = [[0.0] * 2 * components]
    for _ in range(t.size - 1):
        assert ops.analyze(sub, dt / sub) == 0
        out.append([ops.nodeDisp(node, 1 + k) for node in (3, 2) for k in range(components)])
    out = np.array(out)
    return out[:, :components], out[:, components:]


STUCK, SLIDE1, SLIDE3, BOTH = 0, 1, 2, 3


@functools.cache
def _oracle(normal_force):
    """The massless series in one component, event by event, under OpenSees' normal force N_j = W + F u_j / L_j
    (``normal_force``) or dccss's N_j = W: (u, u_1) at the samples. Surface j carries F/M = f_j(u_j, z) =
    g c / (1 - r c), c = r + μ̄_j z, r = u_j / L_j (N = W: g c), so both hold while the demand -a_g lies within
    [max_j f_j(u_j, -1), min_j f_j(u_j, +1)]; one surface slides (ü = -a_g - f_j) while the other's force
    f_i(u_i, z) is not reached; both slide with f_1(u_1) = f_3(u_3), u̇_1 = u̇ f_3' / (f_1' + f_3'). DOP853 within
    each sample interval, in steps of at most a fifth of it (a stop that the velocity dips through and back
    within one step would hide), stops and yields located by its events; breakaways from rest exact (the
    demand is a straight line on an interval, the thresholds constant)."""
    t, acc = _ground(1)
    a_g = scalar_at(Ground.from_samples(t, acc))
    Ls = (L1, L3)

    def f(j, uj, z):
        r = uj / Ls[j]
        c = r + MBAR[j] * z
        return G * c / (1.0 - r * c) if normal_force else G * c

    def slope(j, uj, z):  # df/du_j
        if not normal_force:
            return G / Ls[j]
        r = uj / Ls[j]
        c = r + MBAR[j] * z
        d = 1.0 - r * c
        return G / Ls[j] * (d + c * (c + r)) / (d * d)

    def rest(s, y):  # the phase from rest at time s: (phase, direction)
        demand = -a_g(s)
        up, lo = [f(j, y[j], 1.0) for j in (0, 1)], [f(j, y[j], -1.0) for j in (0, 1)]
        if demand > min(up):
            return (SLIDE1 if up[0] < up[1] else SLIDE3), 1.0
        if demand < max(lo):
            return (SLIDE1 if lo[0] > lo[1] else SLIDE3), -1.0
        return STUCK, 0.0

    def events(sign, j=None, other=None):
        """The velocity (the state's last entry) falling to zero; with ``other``, surface j's force reaching it."""
        def stop(s, x):
            return sign * x[-1]

        def yields(s, x):
            return sign * (other - f(j, x[0], sign))

        stop.terminal, stop.direction, yields.terminal, yields.direction = True, -1, True, -1
        return (stop,) if other is None else (stop, yields)

    y, v, now = [0.0, 0.0], 0.0, float(t[0])
    phase, sign = rest(now, y)
    out = [(0.0, 0.0)]
    for k in range(1, t.size):
        end, step = float(t[k]), float(t[k] - t[k - 1]) / 5
        while now < end:
            if phase == STUCK:
                up, lo = min(f(j, y[j], 1.0) for j in (0, 1)), max(f(j, y[j], -1.0) for j in (0, 1))
                d0, d1 = -a_g(now), -a_g(end)
                if lo <= d1 <= up:
                    now = end
                    continue
                bound, sign = (up, 1.0) if d1 > up else (lo, -1.0)
                now = min(max(now + (end - now) * (bound - d0) / (d1 - d0), now), end)
                phase = SLIDE1 if f(0, y[0], sign) == bound else SLIDE3
                continue
            if phase != BOTH:  # surface j slides, the other holds below its threshold
                j = 0 if phase == SLIDE1 else 1

                def alone(s, x, j=j, sign=sign):
                    return [x[1], -a_g(s) - f(j, x[0], sign)]

                sol = solve_ivp(alone, (now, end), [y[j], v], method="DOP853", rtol=1e-11, atol=1e-13,
                                events=events(sign, j, f(1 - j, y[1 - j], sign)), first_step=1e-7, max_step=step)
                y[j], v, now = float(sol.y[0, -1]), float(sol.y[1, -1]), float(sol.t[-1])
                if sol.status == 1:
                    if sol.t_events[0].size:
                        v = 0.0
                        phase, sign = rest(now, y)
                    else:
                        phase = BOTH
                continue

            def both(s, x, sign=sign):
                a, b = slope(0, x[0], sign), slope(1, x[1], sign)
                return [x[2] * b / (a + b), x[2] * a / (a + b), -a_g(s) - f(0, x[0], sign)]

            sol = solve_ivp(both, (now, end), [y[0], y[1], v], method="DOP853", rtol=1e-11, atol=1e-13,
                            events=events(sign), first_step=1e-7, max_step=step)
            y[0], y[1], v, now = float(sol.y[0, -1]), float(sol.y[1, -1]), float(sol.y[2, -1]), float(sol.t[-1])
            if sol.status == 1:
                v = 0.0
                phase, sign = rest(now, y)
        out.append((y[0] + y[1], y[0]))
    out = np.array(out)
    return out[:, 0], out[:, 1]


def _largest(x):
    """The largest |x| over the history (T, c): the Euclidean norm across the components."""
    return float(np.max(np.linalg.norm(x, axis=1)))


def _epsilon(ours):
    """Each surface's ε_j = (μ̄_j + r_j) r_j at its peak r_j = u_j,max / L_j (dccss's), and the stroke's
    ε u_max = max_j ε_j u_max: OpenSees' normal force makes the forces larger by up to the factor 1 + ε_j."""
    r = np.array(ours.surfaces.peaks) / (L1, L3)
    eps = (np.array(MBAR) + r) * r
    return eps, float(eps.max()) * ours.peaks[0]


def _slider_oscillation(ours):
    """δ_m (m): the massive slider's oscillation about the massless one's motion, at most the velocity jump of
    both surfaces starting together (max|u̇| max(L_1, L_3) / L) over ω_m."""
    return _largest(ours.velocity) * max(L1, L3) / L / OMEGA_SLIDER


def test_the_event_driven_series_is_the_exact_solution():
    """Under dccss's N = W the independent integration equals dccss's exact one-component solution over the
    whole record (measured: 9e-15 m): the oracle's phases and events are the series' own."""
    ours = _ours(1, ARTICULATED)
    u, u1 = _oracle(normal_force=False)
    assert np.max(np.abs(u - ours.stroke[:, 0])) < 1e-9
    assert np.max(np.abs(u1 - ours.surfaces.stroke[:, 0, 0])) < 1e-9


def test_one_component_against_opensees():
    """μ = 0.03 / 0.06 on DFP1, the 20 s record at scale 2: OpenSees' stroke and each surface's displacement
    tend to the massless series under OpenSees' normal force as its elastic branch shrinks, to within the
    slider's oscillation δ_m; what is left to dccss is that law, of first order in ε."""
    ours = _ours(1, ARTICULATED)
    u = ours.stroke[:, 0]
    law, law1 = _oracle(normal_force=True)
    eps, eps_u = _epsilon(ours)
    slider = _slider_oscillation(ours)
    runs = {uy: opensees(1, uy) for uy in UY}
    to_law = {uy: np.max(np.abs(U[:, 0] - law)) for uy, (U, U1) in runs.items()}
    to_ours = {uy: np.max(np.abs(U[:, 0] - u)) for uy, (U, U1) in runs.items()}
    # the elastic branch: OpenSees tends to its own law as uy shrinks (measured: 3.9, 2.2 and 0.74 mm) ...
    assert to_law[UY[0]] > to_law[UY[1]] > to_law[UY[2]] and to_law[UY[0]] > 2 * to_law[UY[2]]
    # ... to within the slider's oscillation (δ_m = 3.6 mm), on the stroke and on each surface (measured at
    # uy = 1e-6: 2.1 mm on each surface, the oscillation's 43 ms period seen while both slide)
    U, U1 = (x[:, 0] for x in runs[UY[-1]])
    assert to_law[UY[-1]] < slider
    assert np.max(np.abs(U1 - law1)) < slider
    assert np.max(np.abs((U - U1) - (law - law1))) < slider
    # the difference to dccss shrinks with uy (measured: 16.1, 14.6, 13.4 mm) and is mostly the normal-force law:
    # matching it leaves a fraction
    assert to_ours[UY[-1]] < to_ours[UY[0]]
    assert to_law[UY[-1]] < 0.5 * to_ours[UY[-1]]
    # that law's own difference (measured 13.3 mm against ε u_max = 12.2 mm) is of first order in ε: the
    # forces differ by the factor 1 + O(ε), the histories by O(ε u_max) (not within it: the stick-slip
    # instants drift with the force, so a half to twice it)
    law_difference = np.max(np.abs(law - u))
    assert 0.5 * eps_u < law_difference < 2 * eps_u
    # the peaks move by less: within ε u_max on the stroke, ε_j u_j,max on each surface (plus what the elastic
    # branch and the slider's oscillation leave; measured: 1.6, 0.0 and 1.7 mm)
    assert abs(np.max(np.abs(U)) - ours.peaks[0]) <= eps_u + to_law[UY[-1]]
    for j, x in enumerate((U1, U - U1)):
        assert abs(np.max(np.abs(x)) - ours.surfaces.peaks[j]) <= eps[j] * ours.surfaces.peaks[j] + slider


def _first_beyond(x, level, t):
    """The first time |x| exceeds ``level`` (inf if never)."""
    beyond = np.nonzero(np.abs(x) > level)[0]
    return float(t[beyond[0]]) if beyond.size else math.inf


def test_opensees_slides_the_low_friction_surface_first_and_farther_as_the_articulated_slider():
    """OpenSees, like dccss's articulated slider, moves the lower-friction surface (μ̄_1 = 0.033 against 0.066)
    first and farther; the rigid slider, whose surfaces slide together in proportion (here equally: L_1 = L_3),
    is far outside what the elastic branch, the slider's mass and the normal-force law explain."""
    t = _ground(1)[0]
    ours, rigid = _ours(1, ARTICULATED), _ours(1, RIGID)
    u, u1 = ours.stroke[:, 0], ours.surfaces.stroke[:, 0, 0]
    U, U1 = (x[:, 0] for x in opensees(1, UY[-1]))
    slider = _slider_oscillation(ours)
    # first: beyond anything the elastic branches (uy) and the slider's oscillation (δ_m) move, surface 1
    # before surface 3 in OpenSees (measured: at 1.01 and 2.18 s, as dccss); dccss's first phase is surface 1
    # sliding alone (from 0.68 s), and OpenSees' surface 1 cannot have gone δ_m before it (its elastic
    # branch creeps by uy, and at u = 0 the normal-force laws agree)
    level = slider + UY[-1]
    first, later = _first_beyond(U1, level, t), _first_beyond(U - U1, level, t)
    assert first < later < math.inf
    starts = np.nonzero(ours.surfaces.sliding.any(axis=1))[0][0]
    assert ours.surfaces.sliding[starts].tolist() == [True, False] and t[starts] <= first
    # farther: the larger peak and the longer travel (measured: 0.168 and 0.139 m; 2.12 and 1.30 m in
    # OpenSees, 2.14 and 1.31 m in dccss), where the rigid slider's equal halves share both equally
    for lower, upper in ((U1, U - U1), (u1, u - u1)):
        assert np.max(np.abs(lower)) > np.max(np.abs(upper))
        assert np.sum(np.abs(np.diff(lower))) > np.sum(np.abs(np.diff(upper)))
    # the rigid slider is beyond what separates OpenSees from the articulated slider: the normal-force law
    # (13.3 mm on the stroke, 6.9 mm on surface 1) and what the elastic branch and the slider's oscillation leave
    # (0.74 mm; on a surface within δ_m = 3.6 mm). Measured: 53.7 mm against 14.1, and on surface 1 (the rigid
    # slider's proportional split L_1 / L of its stroke) 42.2 mm against 10.5
    law, law1 = _oracle(normal_force=True)
    explained = np.max(np.abs(law - u)) + np.max(np.abs(U - law))
    assert np.max(np.abs(U - rigid.stroke[:, 0])) > explained
    assert np.max(np.abs(U1 - L1 / L * rigid.stroke[:, 0])) > np.max(np.abs(law1 - u1)) + slider


def test_two_components_against_opensees():
    """The pair at scale 2 (SingleFPSimple3d: the circular interaction on each surface) at uy = 1e-4: the
    difference to dccss is the one-component difference at the same uy scaled by the normal-force law's
    estimate ε u_max from the x component's peaks to the pair's (measured: 21.4 mm against 16.1 mm x 20.5 /
    12.2 = 26.9 mm); the rigid slider is outside it, and the lower-friction surface goes farther."""
    uy = UY[0]
    ours, rigid = _ours(2, ARTICULATED), _ours(2, RIGID)
    U, U1 = opensees(2, uy)
    x = _ours(1, ARTICULATED)
    x_difference = np.max(np.abs(opensees(1, uy)[0][:, 0] - x.stroke[:, 0]))
    bound = x_difference * _epsilon(ours)[1] / _epsilon(x)[1]
    assert _largest(U - ours.stroke) <= bound
    assert _largest(U - rigid.stroke) > bound  # measured: 57.5 mm
    surfaces = ours.surfaces.stroke
    assert _largest(U1) > _largest(U - U1) and _largest(surfaces[..., 0]) > _largest(surfaces[..., 1])
    eps = _epsilon(ours)[0]
    slider = _slider_oscillation(ours)
    for j, X in enumerate((U1, U - U1)):  # measured: 0.4 and 4.0 mm
        assert abs(_largest(X) - ours.surfaces.peaks[j]) <= eps[j] * ours.surfaces.peaks[j] + slider
