"""The two-component slides' integrator, written in the scalar subset Numba compiles (``scalar.jit``):
the same functions run interpreted for a short record and compiled for a long one (``backend``), with
the same result to the last bit: plain IEEE arithmetic in a fixed order, no BLAS (whose kernels the
processor chooses) and no libm but ``pow``.

The integrator is DOP853 (Hairer, Nørsett and Wanner: 12 stages
of order 8, with error estimators of orders 5 and 3; scipy's tableau and step-size control), its
step carried from one sample interval to the next while the structure slides; an event (rest, or
the end of a start from rest) is located by bisecting the step's length to 4 ε s, each trial a
DOP853 step from the step's start.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .. import scalar
from ..friction import device_mu

#: a start from rest whose friction is at most the force (``_rhs``)
CAPPED = 2
#: a stop in two components: |u̇| (m/s) below which the structure is at rest
REST_SPEED = 1e-9
#: a start from rest in two components: the friction is along the force until |u̇| (m/s) reaches this
START_SPEED = 1e-7
#: the two-component integrator's tolerances (relative; absolute, in m and m/s)
RTOL, ATOL = 1e-12, 1e-14

#: DOP853's stages, and the size of the state y = (u, u̇) in two components
STAGES, SIZE = 12, 4
#: what ends a slide: none (the interval's end), |u̇| falling to REST_SPEED (stop), or for a start from
#: rest |u̇| reaching START_SPEED (moving) or the force falling back to μ g (held); a step too short; the
#: force reaching the other surface's friction (yield: an articulated slider's surface sliding alone)
NONE, STOP, MOVING, HELD, TOO_SHORT, YIELD = 0, 1, 2, 3, 4, 5
#: the step-size control (scipy's): safety factor, the bounds of a step's change, the error's exponent
SAFETY, MIN_FACTOR, MAX_FACTOR, EXPONENT = 0.9, 0.2, 10.0, -1.0 / 8.0
#: a step shorter than this (s) is a failure; an event is located to within BRACKET (s)
MIN_STEP, BRACKET = 1e-14, 4 * 2.220446049250313e-16
#: the entries of a slide's ``load``: the ground's acceleration b0 + b1 t (from the slide's start), ω² (g / L_j for
#: an articulated slider's surface), 2ζω, the friction's scale (μ g, or g under a law), N/W = n0 + n1 t, the
#: surfaces' temperatures; an articulated slider's surface sliding alone: the other's p_i = u_i / L_i and temperature
GROUND_X, GROUND_Y, JERK_X, JERK_Y, STIFFNESS, DAMPING, FRICTION, NORMAL, NORMAL_RATE, TEMPERATURE0, TEMPERATURE1, \
    OTHER_X, OTHER_Y, OTHER_TEMPERATURE = range(14)


def dop853_coefficients():
    """scipy's DOP853 coefficients (A, B, C, E3, E5 as ``scipy.integrate.DOP853`` takes them): read from
    their module's file, which imports numpy alone; importing it, or the class, imports all of
    ``scipy.integrate`` (0.3-0.5 s, in every workflow job with a two-component structure). The class's
    attributes where the file is not found."""
    import importlib.util
    from pathlib import Path

    scipy_spec = importlib.util.find_spec("scipy")
    path = Path(scipy_spec.origin).parent / "integrate" / "_ivp" / "dop853_coefficients.py"
    if path.is_file():
        spec = importlib.util.spec_from_file_location("_dccss_dop853_coefficients", path)
        table = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(table)
        n = table.N_STAGES
        return table.A[:n, :n], table.B, table.C[:n], table.E3, table.E5
    from scipy.integrate import DOP853

    return DOP853.A, DOP853.B, DOP853.C, DOP853.E3, DOP853.E5


@functools.cache
def tableau(compiled):
    """DOP853's A (row-major), B, C, E3 and E5 (scipy.integrate.DOP853's: ``dop853_coefficients``): numpy arrays for the
    compiled kernel, lists (faster to index) interpreted."""
    arrays = [np.ascontiguousarray(c, dtype=float).ravel() for c in dop853_coefficients()]
    if [a.size for a in arrays] != [STAGES * STAGES, STAGES, STAGES, STAGES + 1, STAGES + 1]:
        raise RuntimeError(f"scipy.integrate.DOP853's tableau is not of {STAGES} stages: scipy changed it")
    return tuple(arrays) if compiled else tuple(a.tolist() for a in arrays)


def scratch(compiled):
    """DOP853's scratch for ``integrate``: its stages' derivatives K, a state y, a step's end and a stage's state;
    lists (faster to index) interpreted."""
    arrays = (np.zeros((STAGES + 1) * SIZE), np.zeros(SIZE), np.zeros(SIZE), np.zeros(SIZE))
    return arrays if compiled else tuple(a.tolist() for a in arrays)


@scalar.jit
def normal_ratio(t, load):
    """N/W at t (from the slide's start): n0 + n1 t, 0 where the superstructure lifts off."""
    return max(load[NORMAL] + load[NORMAL_RATE] * t, 0.0)


@scalar.jit
def law_coefficient(t, y, load, law):
    """The friction law's coefficient at t (from the slide's start) and y: exactly 1 for Coulomb friction
    (whose μ g is load[FRICTION]); a law's μ at the speed |u̇|, N/W and the surfaces' temperatures."""
    speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
    return device_mu(law, speed, normal_ratio(t, load), load[TEMPERATURE0], load[TEMPERATURE1])


@scalar.jit
def demand(t, y, load):
    """f = -a_g - ω² (N/W) u at t (from the slide's start) and y, the ground's acceleration from there
    b0 + b1 t (``load``)."""
    n = normal_ratio(t, load)
    return (-(load[GROUND_X] + load[JERK_X] * t) - load[STIFFNESS] * n * y[0],
            -(load[GROUND_Y] + load[JERK_Y] * t) - load[STIFFNESS] * n * y[1])


@scalar.jit
def _rhs(t, y, row, K, load, law, start):
    """K[row] = dy/dt: u̇ and ü = f - 2ζω u̇ - μ g (N/W) z, z the direction of u̇ (of f for a ``start`` from
    rest; a ``start`` of CAPPED takes the friction at most |f|: a slide from rest never starts against the
    force, where its state puts the force a rounding short of the friction)."""
    f0, f1 = demand(t, y, load)
    friction = load[FRICTION] * law_coefficient(t, y, load, law) * normal_ratio(t, load)
    d0, d1 = (f0, f1) if start else (y[2], y[3])
    size = math.sqrt(d0 * d0 + d1 * d1)
    if start == CAPPED and friction > size:
        friction = size
    if size > 0.0:
        d0, d1 = d0 / size, d1 / size
    at = row * SIZE
    K[at] = y[2]
    K[at + 1] = y[3]
    K[at + 2] = f0 - load[DAMPING] * y[2] - friction * d0
    K[at + 3] = f1 - load[DAMPING] * y[3] - friction * d1


@scalar.jit
def _step(t, y, h, K, out, trial, load, law, start, A, B, C):
    """One DOP853 step of length h from (t, y), K[0] the derivative there: out = y(t + h), the stages in
    K, K[STAGES] the derivative at t + h."""
    for s in range(1, STAGES):
        for c in range(SIZE):
            acc = 0.0
            for j in range(s):
                acc += K[j * SIZE + c] * A[s * STAGES + j]
            trial[c] = y[c] + acc * h
        _rhs(t + C[s] * h, trial, s, K, load, law, start)
    for c in range(SIZE):
        acc = 0.0
        for j in range(STAGES):
            acc += K[j * SIZE + c] * B[j]
        out[c] = y[c] + h * acc
    _rhs(t + h, out, STAGES, K, load, law, start)


@scalar.jit
def _error(y, out, h, K, rtol, atol, E3, E5):
    """The step's error norm (scipy's DOP853: the order-5 estimate, damped by the order-3 one)."""
    e5, e3 = 0.0, 0.0
    for c in range(SIZE):
        scale = atol + max(abs(y[c]), abs(out[c])) * rtol
        s5, s3 = 0.0, 0.0
        for j in range(STAGES + 1):
            s5 += K[j * SIZE + c] * E5[j]
            s3 += K[j * SIZE + c] * E3[j]
        s5, s3 = s5 / scale, s3 / scale
        e5 += s5 * s5
        e3 += s3 * s3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return h * e5 / math.sqrt((e5 + 0.01 * e3) * SIZE)


@scalar.jit
def _first_step(y, end, K, trial, load, law, start, rtol, atol):
    """Hairer's first step for order 8 (scipy's ``select_initial_step``); K[0] the derivative at y."""
    d0, d1 = 0.0, 0.0
    for c in range(SIZE):
        scale = atol + abs(y[c]) * rtol
        d0 += (y[c] / scale) * (y[c] / scale)
        d1 += (K[c] / scale) * (K[c] / scale)
    d0, d1 = math.sqrt(d0 / SIZE), math.sqrt(d1 / SIZE)
    h0 = min(1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1, end)
    for c in range(SIZE):
        trial[c] = y[c] + h0 * K[c]
    _rhs(h0, trial, STAGES, K, load, law, start)  # K[STAGES] is scratch here
    d2 = 0.0
    for c in range(SIZE):
        g = (K[STAGES * SIZE + c] - K[c]) / (atol + abs(y[c]) * rtol)
        d2 += g * g
    d2 = math.sqrt(d2 / SIZE) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** (1.0 / 9.0)
    return min(100.0 * h0, h1, end)


@scalar.jit
def _g(event, t, y, load, law, start, other):
    """The event's function: |u̇| - REST_SPEED (STOP), |u̇| - START_SPEED (MOVING), |f| - μ g N/W (HELD),
    |F/N - p_i| - μ̄_i (YIELD: one surface of an articulated slider slides, y its own displacement u_j,
    ``load``'s STIFFNESS g / L_j, the other's p_i = u_i / L_i and temperature in it, its law
    ``other``, at zero speed)."""
    if event == YIELD:
        if start:
            d0, d1 = demand(t, y, load)
        else:
            d0, d1 = y[2], y[3]
        size = math.sqrt(d0 * d0 + d1 * d1)
        if size > 0.0:
            d0, d1 = d0 / size, d1 / size
        coef = law_coefficient(t, y, load, law)
        f0 = y[0] * load[STIFFNESS] / load[FRICTION] + coef * d0 - load[OTHER_X]
        f1 = y[1] * load[STIFFNESS] / load[FRICTION] + coef * d1 - load[OTHER_Y]
        n = normal_ratio(t, load)
        ti = load[OTHER_TEMPERATURE]
        return math.sqrt(f0 * f0 + f1 * f1) - device_mu(other, 0.0, n, ti, ti)
    if event == HELD:
        f0, f1 = demand(t, y, load)
        return (math.sqrt(f0 * f0 + f1 * f1)
                - load[FRICTION] * law_coefficient(t, y, load, law) * normal_ratio(t, load))
    speed = math.sqrt(y[2] * y[2] + y[3] * y[3])
    return speed - (REST_SPEED if event == STOP else START_SPEED)


@scalar.jit
def _beyond(event, g):
    """Whether g is past the event: STOP and HELD fall through zero, MOVING and YIELD rise through it."""
    return g >= 0.0 if event == MOVING or event == YIELD else g <= 0.0


@scalar.jit
def _crosses(event, g_old, g_new):
    """Whether a step crosses the event (scipy's test: from the event's near side or zero to its far
    side or zero)."""
    return _beyond(event, g_new) and (g_old == 0.0 or not _beyond(event, g_old))


@scalar.jit
def _locate(event, t, y, h, K, out, trial, load, law, start, A, B, C, other):
    """The length s in (0, h] of the step from (t, y) that reaches the event (bisection to BRACKET), the
    event being past at h and not at 0; ``out`` is scratch."""
    lo, hi = 0.0, h
    while hi - lo > BRACKET:
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        _step(t, y, mid, K, out, trial, load, law, start, A, B, C)
        if _beyond(event, _g(event, t + mid, out, load, law, start, other)):
            hi = mid
        else:
            lo = mid
    return hi


@scalar.jit(inline=False)
def integrate(y, end, h, load, law, start, stop, rtol, atol, A, B, C, E3, E5, K, out, trial, other):
    """DOP853 over [0, end] from y (overwritten with the state reached): (what ended it, when, the next
    step). Events: STOP if ``stop``; MOVING and HELD for a ``start``; YIELD where ``other`` (the other
    surface's law, one row; none for the rigid slider) has a row; the earliest ends the slide. ``load`` is
    (b0x, b0y, b1x, b1y, ω², 2ζω, friction, n0, n1, t0, t1, p_ix, p_iy, t_i)."""
    t = 0.0
    _rhs(t, y, 0, K, load, law, start)
    if h <= 0.0:
        h = _first_step(y, end, K, trial, load, law, start, rtol, atol)
    carry = h
    while t < end:
        rejected = False
        while True:
            if h < MIN_STEP:
                return TOO_SHORT, t, h
            t_new = min(t + h, end)
            taken = t_new - t
            _step(t, y, taken, K, out, trial, load, law, start, A, B, C)
            error = _error(y, out, taken, K, rtol, atol, E3, E5)
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error ** EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                carry = max(taken * factor, h) if t_new == end and taken < h else taken * factor
                h = taken * factor
                break
            h = taken * max(MIN_FACTOR, SAFETY * error ** EXPONENT)
            rejected = True
        crossed = (stop and _crosses(STOP, _g(STOP, t, y, load, law, start, other),
                                     _g(STOP, t_new, out, load, law, start, other)),
                   start != 0 and _crosses(MOVING, _g(MOVING, t, y, load, law, start, other),
                                           _g(MOVING, t_new, out, load, law, start, other)),
                   start != 0 and _crosses(HELD, _g(HELD, t, y, load, law, start, other),
                                           _g(HELD, t_new, out, load, law, start, other)),
                   False, len(other) > 0 and _crosses(YIELD, _g(YIELD, t, y, load, law, start, other),
                                                      _g(YIELD, t_new, out, load, law, start, other)))
        first, length = NONE, taken
        for event in (STOP, MOVING, HELD, YIELD):
            if crossed[event - 1]:
                s = _locate(event, t, y, taken, K, out, trial, load, law, start, A, B, C, other)
                if first == NONE or s < length:
                    first, length = event, s
        if first != NONE:
            _step(t, y, length, K, out, trial, load, law, start, A, B, C)
            for c in range(SIZE):
                y[c] = out[c]
            return first, t + length, carry
        for c in range(SIZE):
            y[c] = out[c]
            K[c] = K[STAGES * SIZE + c]
        t = t_new
    return NONE, end, carry

