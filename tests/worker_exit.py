"""A pytest-xdist worker ends as soon as its session is over (``tests/conftest.py`` imports this hook;
``tests/test_worker_exit.py`` checks that failures still reach the controller)."""

import os
import sys

import pytest


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    """End a pytest-xdist worker without the interpreter's teardown (about 1 s with matplotlib, xarray,
    Numba and OpenSees loaded, which the controller waited for at the end of every run). Its results went
    to the controller at the end of its session (pytest-xdist's ``workerfinished``), before this hook, and
    its exit status is not read; only its output is flushed."""
    if hasattr(config, "workerinput"):
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(0)
