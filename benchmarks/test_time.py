"""Where the test suite's time goes, grouped by what a test starts.

Runs the README's test command with a JUnit report (or reads one, ``--xml``) and adds up each test's
time (setup, call and teardown, as pytest reports it) by what the test starts, the first that applies:

- Snakemake: it uses the ``reproduction`` or ``shipped_study`` fixture, or calls ``snakemake(`` (the
  time of a session-wide run is counted in the first test that uses it);
- the site build: ``mkdocs``;
- OpenSees: a ``*_opensees.py`` module;
- kernel compilation: a test that points Numba at an empty cache (``CACHE_DIR``);
- another process: ``subprocess`` or ``run_command(`` (the command line, a checker);
- figure rendering: ``maps(``, ``histories(``, ``render(``, ``animate(``, ``draw_frame(``, ``save(``,
  ``figure(`` or ``plot`` in its body;
- the rest (the library's own computation).

The sum over the tests is the CPU-bound work the workers share: on n workers the wall time is at least
that sum / n, plus each worker's start and collection.

Usage: python benchmarks/test_time.py [--xml report.xml | --save report.xml] [--top N] [-- pytest arguments]
"""

from __future__ import annotations

import argparse
import collections
import re
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RULES = [
    ("Snakemake", re.compile(r"\breproduction\b|\bshipped_study\b|\bsnakemake\(")),
    ("site build", re.compile(r"mkdocs")),
    ("kernel compilation", re.compile(r"CACHE_DIR")),
    ("another process", re.compile(r"subprocess|run_command\(")),
    ("figure rendering",
     re.compile(r"\b(maps|histories|render|animate|draw_frame|save|figure|spectra|convergence)\(|plot")),
]
GROUPS = [name for name, _ in RULES[:2]] + ["OpenSees"] + [name for name, _ in RULES[2:]] + ["the rest"]


def bodies(path: Path) -> dict[str, str]:
    """{test function name: its source} of a test module (a top-level function runs to the next one)."""
    text = path.read_text(encoding="utf-8")
    starts = [(m.start(), m.group(1)) for m in re.finditer(r"^def (test_\w+)\(", text, re.M)]
    tops = [m.start() for m in re.finditer(r"^\S", text, re.M)]
    out = {}
    for start, name in starts:
        end = next((t for t in tops if t > start), len(text))
        out[name] = text[start:end]
    return out


def group_of(module: str, name: str, sources: dict) -> str:
    if "@reproduction" in name or "@study_" in name:  # pytest-xdist's group of a session-wide run
        return "Snakemake"
    if module.endswith("_opensees"):
        return "OpenSees"
    body = sources.setdefault(module, bodies(ROOT / "tests" / f"{module}.py")).get(name.split("[")[0], "")
    return next((group for group, pattern in RULES if pattern.search(name + body)), "the rest")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--xml", type=Path, help="a JUnit report to read instead of running the tests")
    parser.add_argument("--top", type=int, default=15, help="also list the N slowest tests")
    parser.add_argument("--save", type=Path, help="keep the JUnit report of the run there")
    parser.add_argument("pytest_args", nargs="*", default=["-n", "auto", "--dist", "loadgroup"])
    args = parser.parse_args(argv)
    wall = None
    with tempfile.TemporaryDirectory() as tmp:
        xml = args.xml
        if xml is None:
            xml = args.save or Path(tmp) / "report.xml"
            start = time.perf_counter()
            subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", f"--junitxml={xml}",
                            *args.pytest_args], cwd=ROOT, check=False)
            wall = time.perf_counter() - start
        tests = [(tc.get("classname").removeprefix("tests."), tc.get("name"), float(tc.get("time")))
                 for tc in ET.parse(xml).iter("testcase")]
    sources, seconds, counts = {}, collections.Counter(), collections.Counter()
    for module, name, t in tests:
        group = group_of(module, name, sources)
        seconds[group] += t
        counts[group] += 1
    total = sum(seconds.values())
    print("| what the tests start | tests | seconds | share |\n|---|---|---|---|")
    for group in GROUPS:
        print(f"| {group} | {counts[group]} | {seconds[group]:.0f} | {100 * seconds[group] / total:.0f} % |")
    print(f"| all | {len(tests)} | {total:.0f} | 100 % |")
    if wall is not None:
        print(f"\nwall time {wall:.0f} s")
    for module, name, t in sorted(tests, key=lambda r: -r[2])[:args.top]:
        print(f"{t:7.1f} s  {group_of(module, name, sources):18s} {module}::{name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
