"""What a run gives: the structure's response (``Response``) and its summaries, and the driver
(``respond``, ``solve``) that picks the exact one-component solution or the two-component integrator."""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .circular import plane_history
from .exact import line_history
from .inputs import G, Ground, Structure
from .sliders import SLIDERS, SliderKind, pendulums, register, ring_strokes


class Response(NamedTuple):
    """The structure's response at the requested times: stroke u (m), its velocity (m/s), the
    friction state z and the force ratio F/W, each (T, c); ``sticking`` (T,) whether u̇ = 0 there;
    ``peaks``: the largest |u| (m) and |F/W| over the record's samples and the requested times, from
    the first of these to the record's end (a coarse step would miss the peaks between its times, and
    a step that does not divide the record the peaks after its last time); ``normal`` (T,) N/W = 1 +
    a_v/g (ones without a vertical) and ``uplift`` the intervals (start, end) (s) where N/W <= 0, from
    the first requested time on (None without a vertical)."""

    stroke: np.ndarray
    velocity: np.ndarray
    z: np.ndarray
    shear_ratio: np.ndarray
    sticking: np.ndarray
    peaks: tuple = (math.nan, math.nan)
    normal: np.ndarray | None = None
    uplift: list | None = None
    friction: np.ndarray | None = None  # (T,) μ(t) of a friction law (None: Coulomb's constant μ)
    temperature: np.ndarray | None = None  # (T, surfaces) the plates' temperatures (°C) of a temperature law
    surfaces: Surfaces | None = None  # each surface's own history (an articulated slider)


class Surfaces(NamedTuple):
    """Each sliding surface's history (j = 1, 3 in the last axis): the hinge's displacement u_j (m; u_1
    relative to C¹, u_3 of C³ relative to the hinge, u_1 + u_3 = u) and its velocity, (T, c, 2); the friction
    state z_j = (F/N - u_j / L_j) / μ̄_j (T, c, 2); whether each slides (T, 2); each surface's coefficient μ_j
    (λ included, at its own sliding speed) (T, 2); the hinge rotation (T,) (rad: θ_1 - θ_3, sin θ_j = u_j /
    L_j, in one component; the angle between the halves' axes in two); the pendulum lengths L_j and the
    strokes u_j at which each half reaches its ring (m); ``peaks`` the largest |u_j| over the record's
    samples and the requested times (as ``Response.peaks``) and ``hinge_peak`` the largest hinge rotation
    (rad); ``ring`` each surface's (time it first reaches its ring, s, or NaN; by how much at most, m)."""

    stroke: np.ndarray
    velocity: np.ndarray
    z: np.ndarray
    sliding: np.ndarray
    friction: np.ndarray
    hinge: np.ndarray
    pendulums: tuple
    rings: tuple
    peaks: tuple
    hinge_peak: float
    ring: tuple


#: a structure's summaries of one history: name -> (units, long_name)
SUMMARIES = {
    "stroke_max_abs": ("m", "largest |stroke| (the superstructure's displacement relative to the ground) over the "
                            "whole record, whatever became of the pad"),
    "stroke_end": ("m", "residual stroke u(t_end) (its size |u| for two components)"),
    "shear_ratio_max_abs": ("1", "largest |F/W| of the device"),
}
#: the summaries of a structure under a vertical component too
VERTICAL_SUMMARIES = {
    "normal_ratio_min": ("1", "smallest N/W = 1 + a_v/g over the whole record"),
    "uplift_duration": ("s", "how long the superstructure lifts off its device (N/W <= 0) in all"),
    "uplift_count": ("1", "how many times the superstructure lifts off its device (N/W <= 0)"),
}


#: each sliding surface's summaries, where a study compares slider kinds (``surface_summaries``)
SURFACE_SUMMARIES = {
    "stroke_1_max_abs": ("m", "largest |u_1|, the displacement on the lower surface (RB1): the hinge relative to C1 "
                              "(the rigid slider's L_1 / L of the stroke: its surfaces slide in proportion)"),
    "stroke_3_max_abs": ("m", "largest |u_3|, the displacement on the upper surface (RB3): C3 relative to the hinge "
                              "(the rigid slider's L_3 / L of the stroke)"),
    "ring_1_reached": ("1", "the half on the lower surface reaches the ring of RB1, |u_1| >= L_1 sin(alpha1 - "
                            "alpha21) (1), or not (0)"),
    "ring_3_reached": ("1", "the half on the upper surface reaches the ring of RB3, |u_3| >= L_3 sin(alpha3 - "
                            "alpha23) (1), or not (0)"),
    "hinge_rotation_max_abs": ("degree", "largest rotation of the hinge, the angle between the two halves (0 for "
                                         "the rigid slider)"),
}


def surface_summaries(response: Response, geometry, hinge=0.0) -> dict:
    """The :data:`SURFACE_SUMMARIES` of a response on ``geometry``: an articulated slider's from its own surfaces,
    the rigid slider's from its stroke, the surfaces sliding in proportion (u_j = L_j u / L, no hinge rotation)."""
    L1, L3 = pendulums(geometry, hinge)
    rings = ring_strokes(geometry, hinge)
    if response.surfaces is None:
        peaks, turn = (L1 / (L1 + L3) * response.peaks[0], L3 / (L1 + L3) * response.peaks[0]), 0.0
    else:
        peaks, turn = response.surfaces.peaks, float(np.degrees(response.surfaces.hinge_peak))
    return {"stroke_1_max_abs": float(peaks[0]), "stroke_3_max_abs": float(peaks[1]),
            "ring_1_reached": float(peaks[0] >= rings[0]), "ring_3_reached": float(peaks[1] >= rings[1]),
            "hinge_rotation_max_abs": turn}


def summarize(response: Response) -> dict:
    """The :data:`SUMMARIES` of a response: vector sizes for two components, u(t_end) signed for one; the
    peaks over the record's samples too (``Response.peaks``); with a vertical, :data:`VERTICAL_SUMMARIES`."""
    stroke = np.linalg.norm(response.stroke, axis=1)
    end = response.stroke[-1, 0] if response.stroke.shape[1] == 1 else stroke[-1]
    out = {"stroke_max_abs": response.peaks[0], "stroke_end": float(end), "shear_ratio_max_abs": response.peaks[1]}
    if response.uplift is not None:
        out.update(normal_ratio_min=response.peaks[2], uplift_duration=float(sum(b - a for a, b in response.uplift)),
                   uplift_count=len(response.uplift))
    return out


def respond(ground: Ground, times, geometry, structure: Structure) -> Response:
    """The structure's response to ``ground`` at ``times`` (s, within the ground's span), on the device
    ``geometry`` (its pendulum length L, and R1, R3 for a surfaces' friction); at rest (u = u̇ = 0) at
    ``ground.time[0]``; by its slider's kind (``sliders.SLIDERS``)."""
    return SLIDERS[structure.slider].respond(ground, times, geometry, structure)


def _rigid(ground: Ground, times, geometry, structure: Structure) -> Response:
    """The rigid slider's response: one pendulum of length L (``solve``)."""
    if structure.coulomb:
        return solve(ground, times, float(geometry.L), structure.device_friction(geometry), structure.damping)
    return solve(ground, times, float(geometry.L), math.nan, structure.damping, law=structure.rows(geometry))


def solve(ground: Ground, times, L, mu, zeta, compiled=None, law=None) -> Response:
    """:func:`respond` for any μ >= 0 (μ = 0: free sliding, the pendulum alone) and 0 <= ζ < 1, or a
    friction ``law`` (its kernel rows, ``friction.row``: then ``mu`` is not used); ``compiled`` None: the
    kernels compiled for a long record, interpreted for a short one.

    With a vertical acceleration a_v (``ground.v0``), the normal force is N = W (1 + a_v/g) and both the
    restoring force and the friction scale with it (N/W <= 0: the superstructure lifts off, and the
    device holds it neither way: u follows ü = -a_g - 2ζω u̇ until it lands); solved in one component
    as in two, by the two-component integrator, as is a friction law."""
    refined, index = ground.refined(times)
    omega = math.sqrt(G / L)
    components = refined.a0.shape[1]
    vertical = refined.has_vertical
    temperature = None
    if components == 1 and not vertical and law is None:
        u, v, z, stick = line_history(refined.time, refined.a0[:, 0], refined.a1[:, 0], omega, zeta, mu * G, compiled)
        u, v, z = u[:, None], v[:, None], z[:, None]
        coefficient = np.full(u.shape[0], float(mu))
    elif law is None:
        u, v, z, stick, _, _ = plane_history(refined, omega, zeta, mu * G, compiled)
        u, v, z = u[:, :components], v[:, :components], z[:, :components]
        coefficient = np.full(u.shape[0], float(mu))
    else:
        u, v, z, stick, temperature, coefficient = plane_history(refined, omega, zeta, G, compiled, law,
                                                          np.isin(refined.time, ground.time))
        u, v, z = u[:, :components], v[:, :components], z[:, :components]
        temperature = temperature[:, :len(law)] if np.any(np.asarray(law)[:, 0] == 3.0) else None
    normal = refined.normal()
    if law is None:
        force = (u / L + mu * z) * np.maximum(normal, 0.0)[:, None] if vertical else u / L + mu * z
    else:
        force = (u / L + coefficient[:, None] * z) * np.maximum(normal, 0.0)[:, None]
    span = slice(index[0], None)  # to the record's end, past the last requested time
    peaks = tuple(float(np.max(np.linalg.norm(x[span], axis=1))) for x in (u, force))
    uplift = None
    if refined.v0 is not None:
        peaks += (float(np.min(normal[span])),)
        uplift = [(max(a, float(times[0])), b) for a, b in refined.uplift() if b > times[0]]
    u, v, z, stick = u[index], v[index], z[index], stick[index]
    return Response(u, v, z, force[index], stick, peaks, None if uplift is None else normal[index], uplift,
                    None if law is None else coefficient[index],
                    None if temperature is None else temperature[index])



RIGID = register(SliderKind("rigid", "one body with two convex caps: both surfaces slide in proportion, the device "
                            "a pendulum of length L", _rigid, proportional=True))
