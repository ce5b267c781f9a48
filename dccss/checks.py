"""Checks of user input (case files, study files, library arguments): each error names the key."""

from __future__ import annotations

import numpy as np


class CaseError(ValueError):
    """An input (a case or study file, a mapping, an argument) is invalid; the message names the key.

    One or more messages: ``messages`` lists them; the text is the message itself when there is one,
    else their number and one message a line (``Problems`` gathers them)."""

    def __init__(self, *messages):
        self.messages = [str(m) for m in messages] or [""]
        if len(self.messages) == 1:
            super().__init__(self.messages[0])
        else:
            super().__init__(f"{len(self.messages)} errors:\n" + "\n".join(f"  - {m}" for m in self.messages))


class Problems:
    """The errors of a file's checks, gathered so that every mistake is reported at once.

    Each check is made on its own (``check``) and its errors are noted under the top-level key it
    checks ("" for the file itself); a check that depends on another is made when that one passed
    (``failed`` says whether it did). ``raise_if_any`` raises them all in one error, in the order of
    the keys in the file, with those of the file's schema about the keys whose checks passed: the
    checks word an error best, the schema has the last word.

    Parameters
    ----------
    mapping : the file's mapping (its keys give the order of the errors).
    error : the exception class raised (CaseError or a subclass).
    """

    def __init__(self, mapping, error=None):
        self.order = list(mapping) if isinstance(mapping, dict) else []
        self.error = error or CaseError
        self.found = []  # (key, message)

    def check(self, key, function, *args, **kwargs):
        """``function(*args, **kwargs)``, or None after noting its CaseError under ``key``."""
        try:
            return function(*args, **kwargs)
        except CaseError as err:
            self.found += [(key, m) for m in err.messages]
            return None

    def add(self, key, message):
        """Note an error about ``key``."""
        self.found.append((key, message))

    def failed(self, *keys) -> bool:
        """Whether a check of any of ``keys`` failed."""
        return any(k in keys for k, _ in self.found)

    def raise_if_any(self, schema_problems=()):
        """Raise every error noted, and the schema's errors (``dccss.schema.errors``) about keys whose
        checks passed; nothing if there is none."""
        noted = {k for k, _ in self.found}
        found = self.found + [(str(p.path[0]) if p.path else "", p.message) for p in schema_problems
                              if (str(p.path[0]) if p.path else "") not in noted]
        if found:
            rank = {k: i for i, k in enumerate(["", *self.order])}
            raise self.error(*(m for _, m in sorted(found, key=lambda f: rank.get(f[0], len(rank)))))


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
    """``mapping`` is a mapping with every required key and no key outside required + optional (both
    mistakes are reported at once)."""
    if not isinstance(mapping, dict):
        raise CaseError(f"{key}: expected a mapping, got {type(mapping).__name__} {mapping!r}")
    problems = []
    unknown = sorted(set(mapping) - set(required) - set(optional), key=str)
    if unknown:
        allowed = sorted(set(required) | set(optional))
        problems.append(f"{key}: unknown key(s) {unknown}; allowed: {allowed}")
    missing = [k for k in required if k not in mapping]
    if missing:
        problems.append(f"{key}: missing key(s) {missing}")
    if problems:
        raise CaseError(*problems)
