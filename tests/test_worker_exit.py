"""The test workers end without the interpreter's teardown (``tests/worker_exit.py``): their results must still
reach the controller, or a failure would pass unseen."""

import subprocess
import sys
from pathlib import Path

import pytest

TESTS = Path(__file__).resolve().parent
PROBE = '''import atexit
from pathlib import Path


def test_passes():
    atexit.register(Path("torn_down").touch)  # an interpreter's teardown would leave this file


def test_fails():
    assert 1 == 2
'''


@pytest.mark.slow  # starts pytest with two workers
@pytest.mark.parametrize("stop", [False, True])
def test_a_worker_ending_at_once_still_reports_its_failures(tmp_path, stop):
    (tmp_path / "conftest.py").write_text(f"import sys\nsys.path.insert(0, {str(TESTS)!r})\n"
                                          "from worker_exit import pytest_unconfigure  # noqa: F401\n")
    (tmp_path / "test_probe.py").write_text(PROBE)
    run = subprocess.run([sys.executable, "-m", "pytest", "-n", "2", "-p", "no:cacheprovider",
                          *(["-x"] if stop else []), "test_probe.py"], cwd=tmp_path, capture_output=True, text=True)
    assert "FAILED test_probe.py::test_fails" in run.stdout, run.stdout[-2000:]
    assert run.returncode == (2 if stop else 1), run.stdout[-2000:]  # -x ends the session as interrupted
    if not stop:
        assert "1 failed, 1 passed" in run.stdout
        assert not (tmp_path / "torn_down").exists()  # the worker that passed ended before its teardown
