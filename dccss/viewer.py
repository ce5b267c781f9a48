"""What the drawing commands (``dccss animate``, ``dccss plot``) share: opening a result history, the
error that says why a file or an option cannot be drawn, and their exit codes."""

from __future__ import annotations

import math
import sys
import textwrap
from pathlib import Path

import numpy as np

from .mechanics.kinematics import Q_NAMES
from .results import MODEL_TITLES, failure_of, geometry_from_attrs

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
    if ds.attrs.get("model") not in MODEL_TITLES:
        raise AnimationError(f"{str(path)!r} is not a dccss result: its global attribute 'model' is "
                             f"{ds.attrs.get('model', 'missing')!r}, expected one of {', '.join(MODEL_TITLES)}")
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


def is_real(value) -> bool:
    """A finite int or float (not a bool)."""
    return (isinstance(value, int | float | np.integer | np.floating) and not isinstance(value, bool)
            and math.isfinite(value))


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
