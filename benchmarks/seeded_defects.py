"""Seeded defects: does the quick loop (``pytest -m "not slow"``) still catch them?

Each defect of :data:`DEFECTS` is a small, realistic mutation of one file (an exact snippet of the
source and its replacement, which must occur exactly once: the script stops with an error if the
code has moved). The script clones the repository's committed revision (``--rev``, default HEAD)
into a scratch folder, runs the quick loop there once unmutated (it must pass), then for each defect
applies the mutation, runs the quick loop again and restores the file (its bytes and its time stamp,
so that Python's and Numba's caches of the unmutated sources stay valid):

    <python> -m pytest -m "not slow" -x -q -p no:cacheprovider -n <workers> --dist worksteal

in the scratch folder, with the scratch folder first on PYTHONPATH (the development install of
dccss points at the main checkout; the script checks that ``dccss`` imports from the scratch copy).
A defect is caught when pytest names a failed test or error: exit code 1, or 2 (with pytest-xdist
``-x`` ends the session as interrupted at the first failure; also a collection error); missed when
the loop passes (exit code 0). It prints a table (defect, caught, the first failing test, seconds)
and exits 1 if any defect was missed (2 for any other problem).

    python benchmarks/seeded_defects.py                  # the baseline, then every defect
    python benchmarks/seeded_defects.py --list           # the defects
    python benchmarks/seeded_defects.py --defect NAME    # the baseline, then one (repeatable)

Options: ``--workers`` (pytest-xdist workers, default 2; 0 runs without xdist), ``--repo`` (the
repository to clone, default this one), ``--rev``, ``--keep`` (keep the scratch folder),
``--timeout`` (seconds per quick loop, default 1800), ``--logs DIR`` (write each quick loop's output
to DIR/<defect>.log).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Defect:
    name: str
    path: str  # relative to the repository's root
    old: str  # exact snippet, found exactly once
    new: str
    what: str


DEFECTS = (
    Defect("constraint_row_sign", "dccss/mechanics/compiled.py",
           "(nC.real, nC.imag, tC, -nC.imag)",
           "(nC.real, nC.imag, tC, nC.imag)",
           "compliant sliding's tangency row of corner C: the sign of dg/dR_y^3 (= -n_y) in the Jacobian"),
    Defect("slip_row_sign", "dccss/mechanics/compiled.py",
           "_dot(R2, n12) - k1, _dot(R3, n12) - k3)",
           "_dot(R2, n12) - k1, _dot(R3, n12) + k3)",
           "slipping (Eq. 37): the sign of k_3 in the row keeping RB3 on C^1C^3"),
    Defect("baseline_skipped", "dccss/records.py",
           "vel, slope = _remove_trend(time, cumulative_trapezoid(acc, time), baseline)",
           "vel, slope = cumulative_trapezoid(acc, time), 0.0",
           "integrate: the baseline correction of the velocity skipped (whatever the baseline asked)"),
    Defect("ring_stop_one_step_early", "dccss/mechanics/models.py",
           "radius, dims, its, capacity)\n"
           "        done[k] = n + 1\n"
           "        if stop_at_ring and compiled.beyond_ring(u, dims):\n"
           "            break\n",
           "radius, dims, its, capacity)\n"
           "        if stop_at_ring and compiled.beyond_ring(u, dims):\n"
           "            break\n"
           "        done[k] = n + 1\n",
           "compliant kernel, capacity stop: the ring test before the step is counted, the history ends one "
           "step early"),
    Defect("ring_reached_off_by_one", "dccss/mechanics/capacity.py",
           "n = int(np.argmax(beyond))",
           "n = int(np.argmax(beyond[1:]))",
           "ring_reached: the first step beyond a ring searched from step 1 without adding 1 back"),
    Defect("at2_units_cm_s2", "dccss/records.py",
           '"CM/S2": ("acceleration", 1e-2)',
           '"CM/S2": ("acceleration", 1e-3)',
           "UNITS: an AT2 header's CM/S/S (CM/S2) read as mm/s2"),
    Defect("suite_lognormal_sign", "dccss/studies/combine.py",
           'np.exp(logs.mean("record") + logs.std("record", ddof=1))',
           'np.exp(logs.mean("record") - logs.std("record", ddof=1))',
           "suite statistics: the lognormal 84th percentile computed as the 16th"),
    Defect("suite_median_is_mean", "dccss/studies/combine.py",
           'stack = [values.mean("record"), values.median("record"),',
           'stack = [values.mean("record"), values.mean("record"),',
           "suite statistics: the median replaced by the mean"),
    Defect("schema_key_dropped", "dccss/schemas/case.schema.yaml",
           "  capacity:\n"
           "    description: >-\n"
           "      what happens when the pad reaches a retaining ring: continue (flag the steps and go on), stop (the "
           "history\n"
           "      ends there) or error (the case fails, exit code 4)\n"
           "    enum: [continue, stop, error]\n"
           "    default: continue\n",
           "",
           "case schema: the key capacity dropped"),
    Defect("study_plot_time_shifted", "dccss/studies/plots.py",
           'col[0].plot(ground["t"].values, HISTORY_ROWS[0][2] * ground["Xg"].values, color="k", lw=1.2)',
           'col[0].plot(ground["t"].values[1:], HISTORY_ROWS[0][2] * ground["Xg"].values[:-1], color="k", lw=1.2)',
           "study histories: the ground displacement drawn one sample late"),
    Defect("paper_figure_time_shifted", "dccss/paper/figures.py",
           'ax.plot(t, 100 * ds["Xg"].values, color="k", lw=1.6, label="$X_g$")',
           'ax.plot(t[1:], 100 * ds["Xg"].values[:-1], color="k", lw=1.6, label="$X_g$")',
           "Figs. 11, 12 (a): the ground displacement drawn one sample late"),
    Defect("stick_loosened_1d", "dccss/mechanics/structure.py",
           "            if abs(demand) <= friction:\n",
           "            if abs(demand) <= 1.05 * friction:\n",
           "structure, one component: at a stop it sticks while |demand| <= 1.05 mu g (not mu g)"),
    Defect("stick_loosened_2d", "dccss/mechanics/structure.py",
           "hold = 1.0 + rtol",
           "hold = 1.0 + 0.05",
           "structure, two components: sticking holds while |f| <= 1.05 mu g (N/W) (not (1 + rtol))"),
    Defect("vertical_sign", "dccss/mechanics/structure.py",
           "n0, n1 = 1.0 + ground.v0 / G, ground.v1 / G",
           "n0, n1 = 1.0 - ground.v0 / G, -ground.v1 / G",
           "structure: N/W = 1 - a_v/g in the kernel (a_v taken positive down)"),
    Defect("friction_velocity_law", "dccss/mechanics/friction.py",
           "return r[5] - (r[5] - r[4]) * math.exp(-r[6] * speed)",
           "return r[4] - (r[4] - r[5]) * math.exp(-r[6] * speed)",
           "velocity law: slow and fast swapped (mu = slow - (slow - fast) exp(-rate v))"),
    Defect("peer_scale_column", "dccss/peer.py",
           'SCALE = "scale factor"',
           'SCALE = "initial-search scale factor"',
           "PEER _SearchResults.csv: the Initial-search Scale Factor column read as the Scale Factor"),
)

BY_NAME = {d.name: d for d in DEFECTS}
assert len(BY_NAME) == len(DEFECTS), "defect names are unique"
_FAILED = re.compile(r"^(?:FAILED|ERROR) (.+?)(?: - .*)?$", re.MULTILINE)
_HEADER = re.compile(r"^_{3,} (?:ERROR collecting )?(\S.*?) _{3,}$", re.MULTILINE)


def git(*args, cwd=None) -> str:
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True).stdout.strip()


def scratch_clone(repo: Path, rev: str) -> Path:
    """A clone of ``repo`` at ``rev`` (resolved in ``repo``) in a new temporary folder."""
    commit = git("rev-parse", "--verify", f"{rev}^{{commit}}", cwd=repo)
    tree = Path(tempfile.mkdtemp(prefix="dccss-seeded-")) / "repo"
    git("clone", "-q", "--no-checkout", str(repo), str(tree))
    git("checkout", "-q", "--detach", commit, cwd=tree)
    return tree


def environment(tree: Path) -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(tree), *filter(None, [env.get("PYTHONPATH")])])
    return env


def check_import(tree: Path, python: str):
    """dccss must import from the scratch copy, not from the development install."""
    out = subprocess.run([python, "-c", "import dccss; print(dccss.__file__)"], cwd=tree, env=environment(tree),
                         check=True, capture_output=True, text=True).stdout.strip()
    if not Path(out).resolve().is_relative_to(tree.resolve()):
        raise SystemExit(f"dccss imports from {out}, not from the scratch copy {tree}")
    print(f"dccss imports from {out}", flush=True)


def _drop_bytecode(path: Path):
    for pyc in (path.parent / "__pycache__").glob(f"{path.stem}.*.pyc"):
        pyc.unlink()


class Mutation:
    """``defect`` applied to the file in ``tree`` for the ``with`` block, then the file restored
    (bytes and time stamps)."""

    def __init__(self, tree: Path, defect: Defect):
        self.path, self.defect = tree / defect.path, defect

    def __enter__(self):
        self.stat = self.path.stat()
        self.original = self.path.read_bytes()
        text = self.original.decode("utf-8")
        count = text.count(self.defect.old)
        if count != 1:
            raise SystemExit(f"defect {self.defect.name}: its snippet occurs {count} times in {self.defect.path} "
                             f"(must be once; has the code moved?):\n{self.defect.old}")
        self.path.write_bytes(text.replace(self.defect.old, self.defect.new).encode("utf-8"))
        _drop_bytecode(self.path)
        return self

    def __exit__(self, *exc):
        self.path.write_bytes(self.original)
        os.utime(self.path, ns=(self.stat.st_atime_ns, self.stat.st_mtime_ns))
        _drop_bytecode(self.path)
        return False


@dataclass
class Outcome:
    returncode: int
    seconds: float
    first: str
    output: str


def quick_loop(tree: Path, python: str, workers: int, timeout: float) -> Outcome:
    """The quick loop in ``tree``: pytest's exit code, the time, the first failing test and the output."""
    command = [python, "-m", "pytest", "-m", "not slow", "-x", "-q", "-p", "no:cacheprovider"]
    if workers:
        command += ["-n", str(workers), "--dist", "worksteal"]
    start = time.perf_counter()
    process = subprocess.Popen(command, cwd=tree, env=environment(tree), stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, start_new_session=True)
    try:
        output, _ = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)  # the session this script started: pytest and its workers
        output, _ = process.communicate()
        return Outcome(-1, time.perf_counter() - start, f"(timed out after {timeout:g} s)", output)
    seconds = time.perf_counter() - start
    found = _FAILED.search(output) or _HEADER.search(output)
    return Outcome(process.returncode, seconds, found.group(1) if found else "", output)


def verdict(outcome: Outcome) -> str:
    if outcome.returncode == 0:
        return "missed"
    if outcome.returncode in (1, 2) and outcome.first:
        return "caught"
    return "error"


def table(baseline: Outcome, rows) -> str:
    lines = ["| defect | caught? | first failing test | seconds |", "|---|---|---|---|",
             f"| (baseline, no mutation) | passes | — | {baseline.seconds:.0f} |"]
    for name, outcome in rows:
        shown = {"caught": "yes", "missed": "**no**", "error": f"error (exit {outcome.returncode})"}[verdict(outcome)]
        first = f"`{outcome.first}`" if outcome.first else "—"
        lines.append(f"| {name} | {shown} | {first} | {outcome.seconds:.0f} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--list", action="store_true", help="list the defects and exit")
    parser.add_argument("--defect", action="append", choices=list(BY_NAME), metavar="NAME",
                        help="run this defect only (repeatable)")
    parser.add_argument("--workers", type=int, default=2, help="pytest-xdist workers (0: no xdist)")
    parser.add_argument("--repo", type=Path, default=ROOT, help="the repository to clone")
    parser.add_argument("--rev", default="HEAD", help="the revision to clone")
    parser.add_argument("--keep", action="store_true", help="keep the scratch folder")
    parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per quick loop")
    parser.add_argument("--logs", type=Path, help="write each quick loop's output to LOGS/<defect>.log")
    args = parser.parse_args(argv)
    if args.list:
        for d in DEFECTS:
            print(f"{d.name:28s} {d.path}: {d.what}")
        return 0
    chosen = [BY_NAME[n] for n in args.defect] if args.defect else list(DEFECTS)
    python = sys.executable
    if args.logs:
        args.logs.mkdir(parents=True, exist_ok=True)

    def log(name, outcome):
        if args.logs:
            (args.logs / f"{name}.log").write_text(outcome.output)

    began = time.perf_counter()
    tree = scratch_clone(args.repo.resolve(), args.rev)
    print(f"scratch clone of {args.repo} at {git('rev-parse', '--short', 'HEAD', cwd=tree)}: {tree}", flush=True)
    try:
        # every snippet must apply exactly once before anything runs
        for defect in chosen:
            with Mutation(tree, defect):
                pass
        check_import(tree, python)
        print("baseline (no mutation) ...", flush=True)
        base = quick_loop(tree, python, args.workers, args.timeout)
        log("baseline", base)
        if base.returncode != 0:
            print(base.output[-5000:])
            print(f"the baseline fails (exit {base.returncode}, first failure {base.first or '?'}): stopping")
            return 2
        print(f"baseline passes: {base.seconds:.0f} s ({base.output.strip().splitlines()[-1]})", flush=True)
        rows = []
        for defect in chosen:
            print(f"{defect.name}: {defect.what} ...", flush=True)
            with Mutation(tree, defect):
                outcome = quick_loop(tree, python, args.workers, args.timeout)
            rows.append((defect.name, outcome))
            log(defect.name, outcome)
            print(f"  {verdict(outcome)} (exit {outcome.returncode}) in {outcome.seconds:.0f} s: "
                  f"{outcome.first or outcome.output.strip().splitlines()[-1]}", flush=True)
            if verdict(outcome) == "error":
                print(outcome.output[-3000:])
    finally:
        if args.keep:
            print(f"kept {tree}")
        else:
            shutil.rmtree(tree.parent, ignore_errors=True)
    print()
    print(table(base, rows))
    print(f"\ntotal {time.perf_counter() - began:.0f} s, {len(rows)} defects, quick loop: pytest -m 'not slow' -x -q "
          f"-p no:cacheprovider{f' -n {args.workers} --dist worksteal' if args.workers else ''}")
    verdicts = [verdict(o) for _, o in rows]
    if "error" in verdicts:
        return 2
    if "missed" in verdicts:
        print("missed: " + ", ".join(n for (n, o), v in zip(rows, verdicts) if v == "missed"))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
