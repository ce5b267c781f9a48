"""Checks of user input (case files, study files, library arguments): each error names the key."""

from __future__ import annotations

import numpy as np


class CaseError(ValueError):
    """An input (a case or study file, a mapping, an argument) is invalid; the message names the key."""


def number(value, key, *, positive=False):
    """A finite real number from a YAML value; the error names the key."""
    if isinstance(value, str):
        hint = ""
        try:
            float(value)
            hint = (" (YAML reads a number with an exponent but no decimal point or no sign, e.g. 1e-3 or 1.0e5, "
                    "as a string: write 1.0e-3, 1.0e+5)")
        except ValueError:
            pass
        raise CaseError(f"{key}: expected a number, got the string {value!r}{hint}")
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise CaseError(f"{key}: expected a number, got {type(value).__name__} {value!r}")
    value = float(value)
    if not np.isfinite(value):
        raise CaseError(f"{key}: expected a finite number, got {value!r}")
    if positive and value <= 0:
        raise CaseError(f"{key}: must be > 0, got {value!r}")
    return value


def choice(value, key, allowed):
    """``value`` if it is one of ``allowed``; the error names the key and the allowed values."""
    if not isinstance(value, str) or value not in allowed:
        raise CaseError(f"{key}: must be one of {list(allowed)}, got {value!r}")
    return value


def check_keys(mapping, key, required, optional=()):
    """``mapping`` is a mapping with every required key and no key outside required + optional."""
    if not isinstance(mapping, dict):
        raise CaseError(f"{key}: expected a mapping, got {type(mapping).__name__} {mapping!r}")
    unknown = sorted(set(mapping) - set(required) - set(optional), key=str)
    if unknown:
        allowed = sorted(set(required) | set(optional))
        raise CaseError(f"{key}: unknown key(s) {unknown}; allowed: {allowed}")
    missing = [k for k in required if k not in mapping]
    if missing:
        raise CaseError(f"{key}: missing key(s) {missing}")
