"""What the drawing commands (``dccss animate``, ``dccss plot``) share: opening a result history, the
error that says why a file or an option cannot be drawn, their exit codes, and what a history is of (its
case, said from the dataset's attributes)."""

from __future__ import annotations

import math
import sys
import textwrap
from pathlib import Path

from .mechanics.kinematics import Q_NAMES
from .results import MODEL_TITLES, failure_of, friction_text, geometry_from_attrs, is_real

#: the size of an animation's frames (inches, dots per inch)
FIGSIZE, DPI = (11.0, 7.2), 100
#: what a bidirectional history must hold to be drawn
SPATIAL_NAMES = ("Xg_x", "Xg_y", *(f"{v}_{c}" for v in ("G2", "axis", "R3") for c in "xyz"), "tilt", "tilt_azimuth",
                 "rise")


class AnimationError(ValueError):
    """Bad input to ``animate``: the message names the value and what is allowed."""


def open_result(path):
    """Load a dccss time-history dataset, or raise AnimationError saying why it is not one."""
    import xarray as xr

    path = Path(path)
    if not path.is_file():
        raise AnimationError(f"result file {str(path)!r} {'is not a file' if path.exists() else 'does not exist'}")
    try:
        ds = xr.load_dataset(path)
    except Exception as err:  # each netCDF engine raises its own errors
        raise AnimationError(f"cannot read {str(path)!r} as a netCDF file: {err}") from None
    if ds.attrs.get("model") not in (*MODEL_TITLES, "articulated"):
        raise AnimationError(f"{str(path)!r} is not a dccss result: its global attribute 'model' is "
                             f"{ds.attrs.get('model', 'missing')!r}, expected one of {', '.join(MODEL_TITLES)} or "
                             f"articulated")
    if ds.attrs.get("model") == "articulated":  # an articulated slider's history (dccss.hinged)
        two = ds.attrs.get("motion") == "bidirectional"
        names = [f"{n}_{c}" for n in ("stroke_1", "stroke_3") for c in "xy"] + ["hinge_rotation"] if two else \
            ["stroke_1", "stroke_3", "hinge_rotation"]
    else:
        names = SPATIAL_NAMES if ds.attrs.get("motion") == "bidirectional" else Q_NAMES
    missing = ([] if "t" in ds.dims else ["the time coordinate t"]) + [name for name in names if name not in ds]
    if missing:
        raise AnimationError(f"{str(path)!r} is not a dccss time history (a breakaway sweep or a study grid?): it "
                             f"lacks {', '.join(missing)}")
    try:
        geometry_from_attrs(ds.attrs)
    except (KeyError, ValueError) as err:
        raise AnimationError(f"{str(path)!r}: the device geometry attributes are missing or invalid ({err})") from None
    if ds.sizes["t"] == 0:
        raise AnimationError(f"{str(path)!r} holds no step (the time coordinate t is empty)")
    return ds


def run_command(name, call, quiet) -> int:
    """A drawing sub-command: ``call()`` returns its summary line; an AnimationError is exit code 2."""
    try:
        line = call()
    except AnimationError as err:
        print(f"dccss {name}: error: {err}", file=sys.stderr)
        return 2
    if not quiet:
        print(f"dccss {name}: wrote {line}")
    return 0


#: how the component a history keeps of a two-component excitation is said
COMPONENT_TEXT = {"x": "its x component alone", "y": "its y component alone", "both": "both components"}


def case_text(attrs) -> str:
    """What a history is of, from its dataset's attributes, for the title of its frames: its ground motion and
    the case's parameters besides the device; e.g. "record pair synthetic + synthetic_y, scaled by 1.5, both
    components; structure μ = 0.04, ζ = 0; Δt = 0.01 s"."""
    return "; ".join([_motion_text(attrs), *_parameter_texts(attrs)])


def _motion_text(attrs) -> str:
    """A history's ground motion: its record or excitation (``_excitation_text``), the factor it is scaled by,
    the azimuth it is applied along or the angle it is turned by, the component kept and a vertical component."""
    parts = [_excitation_text(attrs)]
    scale = math.prod(float(attrs[key]) for key in ("record_scale", "record_1_scale", "excitation_scale")
                      if key in attrs)
    if scale != 1.0:
        parts.append(f"scaled by {scale:.4g}")
    if is_real(attrs.get("excitation_azimuth_deg")):
        parts.append(f"along {attrs['excitation_azimuth_deg']:g}°")
    if attrs.get("record_rotation_deg"):
        parts.append(f"turned by {attrs['record_rotation_deg']:g}°")
    if attrs.get("excitation_component") in COMPONENT_TEXT:
        parts.append(COMPONENT_TEXT[attrs["excitation_component"]])
    if attrs.get("vertical_form") == "record":
        parts.append(f"vertical {Path(attrs['record_vertical_source']).stem}")
    elif attrs.get("vertical_form") == "sine":
        parts.append(f"vertical sine {attrs['vertical_amplitude_m_per_s2']:.3g} m/s², "
                     f"ω = {attrs['vertical_omega_rad_per_s']:.4g} rad/s")
    return ", ".join(parts)


def _excitation_text(attrs) -> str:
    """'sine X_g,max = 27 cm, ω = 30 rad/s', 'record RSN6_ELC180', 'record pair RSN6_ELC180 + RSN6_ELC270' (the
    files' stems), 'table motion.csv'."""
    kind = attrs.get("excitation")
    if kind == "sine":
        return f"sine $X_{{g,max}}$ = {100 * attrs['amplitude_m']:.4g} cm, ω = {attrs['omega_rad_per_s']:.4g} rad/s"
    if kind == "record":
        stems = [Path(attrs[key]).stem for key in ("record_source", "record_1_source", "record_2_source")
                 if key in attrs]
        return f"record{' pair' if len(stems) == 2 else ''} {' + '.join(stems)}"
    return f"{kind or 'ground motion'} {Path(str(attrs.get('table_source', ''))).name}".strip()


def _parameter_texts(attrs) -> list:
    """The case's parameters besides its device and ground motion: a structure's friction (on the device, or on
    each surface as given) and damping, a start angle other than 0, the time step."""
    texts = []
    if "structure_friction" in attrs:
        texts.append(f"structure {friction_text(attrs, surfaces_given=True)}, ζ = {attrs['structure_damping']:g}")
    if attrs.get("theta2_0_deg"):
        texts.append(f"$\\theta^2(t_0)$ = {attrs['theta2_0_deg']:g}°")
    if is_real(attrs.get("dt_s")):
        texts.append(f"Δt = {attrs['dt_s']:g} s")
    return texts


#: the events of a history drawn on its time traces: (attribute, colour, label)
EVENTS = (("capacity_exceeded_at_s", "tab:orange", "pad reaches a ring"),
          ("failure_time_s", "tab:red", "solver failure"))


def events(attrs) -> list:
    """(time, colour, label) of a history's events: the ring it reached and the solver's failure (not the
    failure that capacity 'error' marks at the ring, whose line is the ring's)."""
    return [(float(attrs[key]), colour, label) for key, colour, label in EVENTS
            if is_real(attrs.get(key)) and (key != "failure_time_s" or failure_of(attrs) == "solver")]


def run_notes(attrs):
    """The events of the run, for the foot of every frame: solver failure, capacity exceedance, stop."""
    notes = []
    if failure_of(attrs) == "capacity":
        notes.append("capacity: error ended the run at the ring, marked failed (on_failure: mark).")
    elif failure_of(attrs) == "solver":
        when = attrs.get("failure_time_s")
        note = "The solver failed" + (f" at t = {when:g} s" if is_real(when) else "")
        note += ": the data end at the last converged step."
        if attrs.get("failure_message"):
            note += " " + textwrap.shorten(str(attrs["failure_message"]), 100, placeholder=" ...")
        notes.append(note)
    if is_real(attrs.get("capacity_exceeded_at_s")):
        note = (f"The pad reaches the retaining ring of {attrs.get('capacity_exceeded_plate', 'a plate')} "
                f"at t = {attrs['capacity_exceeded_at_s']:g} s")
        if is_real(attrs.get("capacity_exceeded_by_m")):
            note += f" and passes it by up to {100 * attrs['capacity_exceeded_by_m']:.3g} cm"
        note += ": the excitation exceeds the device capacity."
        if is_real(attrs.get("stopped_at_s")):
            note += f" The run was stopped there (t = {attrs['stopped_at_s']:g} s)."
        notes.append(note)
    return "\n".join(textwrap.fill(note, 175) for note in notes)
