"""Shared fixtures: a full reproduction of the paper in a temporary copy of the project."""

import bisect
import copy
import inspect
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
from worker_exit import pytest_unconfigure  # noqa: F401  (a hook: each test worker ends at once)

#: a value for ``changed`` that removes the key
DELETE = object()


def changed(mapping, **changes):
    """A deep copy of ``mapping`` with ``a__b=value`` setting mapping["a"]["b"] (DELETE removes it)."""
    out = copy.deepcopy(mapping)
    for key, value in changes.items():
        *path, last = key.split("__")
        target = out
        for part in path:
            target = target[part]
        if value is DELETE:
            del target[last]
        else:
            target[last] = value
    return out

def scalar_at(ground, component=0):
    """``s -> ground.at([s])[0, component]`` in plain floats, bit for bit, and about 20 times faster: for the
    independent integrations, which call it at every right-hand side."""
    times = ground.time.tolist()
    a0, a1 = ground.a0[:, component].tolist(), ground.a1[:, component].tolist()
    first, last, top = times[0], times[-1], len(a0) - 1

    def at(s):
        k = min(max(bisect.bisect_right(times, s) - 1, 0), top)
        return a0[k] + a1[k] * (min(max(s, first), last) - times[k])

    return at


@pytest.hookimpl(tryfirst=True)
def pytest_collection(session):
    """Compile the kernels the cache lacks (a fresh clone, a change to the mechanics) once, one process per
    core, before any test runs: else each worker, and each of a workflow's parallel jobs, compiles the
    same kernel at the same time (in a fresh clone, about 90 s of the tests' time against 30 s). Nothing
    where the cache holds them all; in a worker (pytest-xdist), nothing: the controller does it while the
    workers start and collect, and sends them tests after it."""
    if hasattr(session.config, "workerinput"):
        return
    from dccss.mechanics import warmup

    todo = warmup.cold()
    if todo:
        start = time.monotonic()
        try:
            warmup.warm(os.cpu_count() or 1, only=todo)
            said = f"compiled the kernels ({', '.join(todo)}) in {time.monotonic() - start:.1f} s"
        except Exception as err:  # a broken model: the tests that run it say so, by name
            said = f"the kernels' warm-up failed ({type(err).__name__}: {err}); the tests compile them as they run"
        reporter = session.config.pluginmanager.get_plugin("terminalreporter")
        if reporter is not None:
            reporter.write_line(said)


ROOT = Path(__file__).resolve().parents[1]
PROJECT = ["Snakefile", "config", "workflow", "profiles"]


def copy_project(dest: Path) -> Path:
    for name in PROJECT:
        src = ROOT / name
        (shutil.copytree if src.is_dir() else shutil.copy)(src, dest / name)
    return dest


#: Snakemake's command line (what ``python -m snakemake`` runs), the process ended as soon as it returns: after
#: running jobs, Snakemake leaves a timer thread of its job-rate limit (up to 1 s, which no setting removes)
#: that the interpreter waits for at exit, an idle second of a worker per run. Output and logs are flushed first.
SNAKEMAKE = """
import logging, os, sys
from snakemake.cli import main
try:
    main()
    code = 0
except SystemExit as end:
    code = end.code if isinstance(end.code, int) else 0 if end.code is None else 1
    if not isinstance(end.code, (int, type(None))):
        print(end.code, file=sys.stderr)
sys.stdout.flush()
sys.stderr.flush()
logging.shutdown()
os._exit(code)
"""


def snakemake(cwd, *args, profile="profiles/default"):
    """Run the project's workflow in ``cwd`` (Snakemake's command line, ``SNAKEMAKE``); the completed process
    (stdout, stderr, returncode)."""
    return subprocess.run([sys.executable, "-c", SNAKEMAKE, "--profile", profile, *args],
                          cwd=cwd, capture_output=True, text=True)


@pytest.fixture(scope="session")
def reproduction(tmp_path_factory):
    """The paper's reproduction, run once per session in a copy of the project."""
    work = copy_project(tmp_path_factory.mktemp("reproduction"))
    run = snakemake(work)
    assert run.returncode == 0, run.stderr[-3000:]
    return work


@pytest.fixture(scope="session")
def shipped_study(tmp_path_factory):
    """``shipped_study(name)``: the folder of a run of config/studies/<name>.yaml (once per session)."""
    runs = {}

    def run(name):
        if name not in runs:
            work = copy_project(tmp_path_factory.mktemp(name))
            result = snakemake(work, "--configfile", f"config/studies/{name}.yaml")
            assert result.returncode == 0, result.stderr[-3000:]
            runs[name] = work
        return runs[name]

    return run


#: fixtures that run a workflow once for the tests that use them (``shipped_study``: one run per study)
SHARED_RUNS = {"reproduction", "tiny_run"}


def _shared_runs(item):
    """The shared runs a test uses: those of SHARED_RUNS it names, and "study:<name>" for each shipped study it
    runs (its ``name`` parameter, or the names in its ``shipped_study("...")`` calls; "study:?" if neither
    says)."""
    names = set(getattr(item, "fixturenames", ()))
    runs = SHARED_RUNS & names
    if "shipped_study" in names:
        callspec = getattr(item, "callspec", None)
        studies = {callspec.params["name"]} if callspec and "name" in callspec.params else set(
            re.findall(r"shipped_study\(\s*[\"']([\w-]+)[\"']", inspect.getsource(item.function)))
        runs |= {f"study:{name}" for name in studies} or {"study:?"}
    return runs


@pytest.hookimpl(tryfirst=True)  # before pytest-xdist's own hook, which reads the groups
def pytest_collection_modifyitems(items):
    """Tests that need a workflow run are slow (``pytest -m "not slow"`` is the quick loop). On several
    workers (pytest-xdist, ``--dist loadgroup``) the tests of one session-wide run (the reproduction, or
    one shipped study) go to one worker, which runs it once; tests using several runs join their groups.
    The long tests go first (the shared runs' groups, then the other slow tests, each in the order
    collected), so that the many short ones fill both workers at the end: collected by module, the
    workflow tests came last, and one worker ran them while the other waited."""
    used = {item: _shared_runs(item) for item in items}
    group = {}  # run -> a representative run (union-find over the runs tests use together)

    def find(run):
        while group.setdefault(run, run) != run:
            run = group[run]
        return run

    for runs in used.values():
        for run in runs:
            group[find(run)] = find(min(runs))
    for item, runs in used.items():
        if runs:
            item.add_marker(pytest.mark.slow)
            item.add_marker(pytest.mark.xdist_group(find(min(runs)).replace(":", "_").replace("?", "any")))
    groups = list(dict.fromkeys(find(min(runs)) for runs in used.values() if runs))
    items.sort(key=lambda item: (groups.index(find(min(used[item]))) if used[item]
                                 else len(groups) + (0 if item.get_closest_marker("slow") else 1)))


@pytest.hookimpl(trylast=True)
def pytest_collection_finish(session):
    """On a pytest-xdist worker under ``--dist loadgroup``, each grouped test's id must carry its group
    (``...@reproduction``): otherwise every worker would run the same workflow (pytest 9.2 with
    pytest-xdist 3.8 silently drops the groups; workflow/envs/constraints.txt pins a pair that works)."""
    if getattr(session.config.option, "loadgroup", False) and hasattr(session.config, "workerinput"):
        lost = [item.nodeid for item in session.items
                if any(item.iter_markers("xdist_group")) and "@" not in item.nodeid]
        if lost:
            raise pytest.UsageError(f"pytest-xdist dropped the xdist_group of {len(lost)} tests (e.g. {lost[0]}); "
                                    "install the versions in workflow/envs/constraints.txt")
