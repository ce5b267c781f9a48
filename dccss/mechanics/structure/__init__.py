"""The isolated structure: a rigid superstructure on the device, driven by the ground's acceleration.

The superstructure (mass m, weight W = m g) rests on the device. Its displacement relative to the
ground, the device's **stroke** u (m; one component, or two: x, y), obeys

    m ü + c u̇ + F = -m a_g(t),      F = (W / L) u + μ W z,      c = 2 ζ m ω,   ω² = g / L,

the friction pendulum of Zayas, Low and Mahin, and of Fenz and Constantinou's double friction
pendulum with equal friction on both sliding surfaces (OpenSees' ``singleFPBearing``). L = |C¹C³|
(``Geometry.L``): under compliant sliding the pad lies on C¹C³, RB3 moves sideways by L sin θ² and
rises by L (1 - cos θ²) (Eq. 41, ``Geometry.compatible``), so the superstructure's weight does
work W L (1 - cos θ²) ≈ W u² / (2 L): a pendulum of length L, whose restoring force is W u / L to
first order in u / L. μ is the device's friction coefficient as OpenSees and the Fenz-Constantinou
model use it: the force at zero stroke while sliding is μ W. The friction state z (|z| <= 1) is
u̇ / |u̇| while the structure slides, and sticking (u̇ = 0) holds while the force the friction must
supply, |-m a_g - W u / L|, is at most μ W; then z is that force over μ W. Dividing by m, W drops
out: only μ, ζ, L and g = 9.80665 m/s² remain.

**The vertical component.** A vertical ground acceleration a_v (up positive) changes the normal force
on the device to N = W (1 + a_v / g): the superstructure, rigid and rigidly carried vertically by the
device, is accelerated upwards with the ground. Both the pendulum's restoring force N u / L and the
friction μ N scale with N, so

    ü + 2ζω u̇ + (1 + a_v/g) (ω² u + μ g z) = -a_g,

with c = 2ζmω from the nominal period (the damping does not follow N), and sticking holds while
|-a_g - (1 + a_v/g) ω² u| <= μ g (1 + a_v/g). A constant a_v is the horizontal problem with g replaced
by g + a_v. Where N <= 0 the superstructure lifts off: the device holds it neither way (no restoring
force, no friction) and u follows ü = -a_g - 2ζω u̇ until it lands; the intervals are found exactly on
the straight lines joining the samples (``Ground.uplift``) and what follows them describes no real
structure (the landing's impact is not modelled). Neglected: the vertical inertia of the pad and of a
flexible superstructure beyond the rigid-body term (the normal force is W (1 + a_v/g) exactly only for
a rigid mass on a rigid device), rocking, and the second-order N = W + F u / R of OpenSees'
``singleFPBearing``. With a vertical, one component is solved by the two-component integrator (below),
its second component without load.

The ground acceleration is given as ``Ground``: on each interval [t_k, t_k+1] a straight line
a0_k + a1_k (t - t_k) (one column per component), as a record's samples are joined (and a
displacement table's piecewise-constant acceleration).

* One component (``respond``, ``exact.line``): solved exactly. On each interval the sliding
  equation is linear with a linear right-hand side, solved in closed form (a damped oscillator
  with a linear load); the ends of sliding (u̇ = 0) are roots of that closed form, found by
  bisection to the last bit; sticking ends where a straight line reaches ±μ g (exact). The
  solution is exact to rounding: no time step, no elastic branch.
* Two components (the circular interaction, z a vector): the sliding equation is nonlinear
  (ü = -a_g - ω² u - 2 ζ ω u̇ - μ g u̇ / |u̇|), integrated by DOP853 (the Runge-Kutta pair of order 8
  of Hairer, Nørsett and Wanner, with scipy's tableau and step-size control; relative tolerance
  ``RTOL``, absolute ``ATOL`` in m and m/s), with sticking as an event: a phase of sliding ends
  where |u̇| falls to 1e-9 m/s (the rest of the way to rest takes at most 1e-9 / (μ g - |f|) s,
  and moves the structure less than 1e-17 m), and sticking ends where |f|, a quadratic in t on an
  interval, reaches μ g (exact; in two components sticking holds while |f| <= μ g (1 + ``RTOL``),
  so that a stop where the force equals the friction to within the integration's accuracy is
  not decided by rounding). The integrator (``circular.plane``) is written for Numba like the device's
  kernels: compiled for a long record, interpreted for a short one, with the same bits, and no
  BLAS (whose kernels OpenBLAS chooses by processor).

The package, one concern a module: ``inputs`` (``Structure``, ``Ground``: what a run is given),
``sliders`` (the slider kinds' registry and the hinge's geometry), ``exact`` (one component, exact),
``integrator`` (DOP853 and its events), ``circular`` (two components, the circular interaction),
``heat`` (the plates' heating), ``response`` (``Response``, its summaries, ``respond``, and the rigid
slider: ``solve``), and the articulated slider: ``series`` (one component, exact), ``corner`` (both
surfaces sliding) and ``articulated`` (its history in general, and its ``respond``). A third kind (a
triple pendulum) is a module of its own registering itself, imported here.
"""

from __future__ import annotations

from . import articulated  # noqa: F401  (registers the articulated slider)
from .circular import INTERVAL_WORK, plane_history
from .exact import LINE_WORK, line_history
from .inputs import FRICTION_ON, G, Ground, Structure, StructureError, period
from .response import (
    SUMMARIES,
    SURFACE_SUMMARIES,
    VERTICAL_SUMMARIES,
    Response,
    Surfaces,
    respond,
    solve,
    summarize,
    surface_summaries,
)
from .sliders import SLIDERS

__all__ = ["FRICTION_ON", "G", "Ground", "INTERVAL_WORK", "LINE_WORK", "Response", "SLIDERS", "SUMMARIES", "Structure",
           "StructureError", "SURFACE_SUMMARIES", "Surfaces", "VERTICAL_SUMMARIES", "period", "respond", "solve",
           "summarize", "surface_summaries", "warm"]


def warm(kernels=("plane", "line", "articulated", "series")):
    """Compile (or load) the structure's kernels into the on-disk cache: the rigid slider's two-component
    (``plane``) and one-component (``line``) ones, the articulated slider's general (``articulated``) and
    one-component (``series``) ones."""
    import numpy as np

    from ..friction import COULOMB, row
    from . import series

    ground = Ground.from_samples([0.0, 0.01, 0.02], [[0.0, 0.0], [1.0, 0.5], [0.0, 0.0]])
    if "plane" in kernels:
        plane_history(ground, 2.0, 0.0, 0.05 * G, compiled=True)
    if "line" in kernels:
        line_history(ground.time, ground.a0[:, 0], ground.a1[:, 0], 2.0, 0.0, 0.05 * G, compiled=True)
    if "articulated" in kernels:
        rows = np.array([row(COULOMB, {"mu": 0.03}), row(COULOMB, {"mu": 0.06})])
        articulated.articulated_history(ground, 0.9, 0.9, 0.0, rows, rows, compiled=True)
    if "series" in kernels:
        series.series_line_history(ground.time, ground.a0[:, 0], ground.a1[:, 0], G / 0.9, G / 0.9, 3.3, 0.0, 0.3, 0.6,
                                   compiled=True)
