"""A suite of distinct PEER-format records for tests and benchmarks: the shipped synthetic pair's two components
mixed at an angle, shifted, some reversed in time, each at its own amplitude and length (deterministic). The writer
is the one that writes the shipped suite, ``config/studies/records/make_suite.py``."""

from __future__ import annotations

import importlib.util
from pathlib import Path

RECORDS = Path(__file__).resolve().parent.parent / "config/studies/records"
_spec = importlib.util.spec_from_file_location("dccss_make_suite", RECORDS / "make_suite.py")
_module = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_module)
write_suite = _module.write_suite
