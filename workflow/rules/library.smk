# The library as an input of the rules, and the same arithmetic on every machine.
#
# Snakemake reruns a job when its rule's script or parameters change, not when the code that the
# script imports does. Each rule therefore takes, as a parameter, the SHA-256 of the dccss sources
# it runs: editing the solver reruns the simulations (and what reads them), editing the plotting
# code reruns only the figures.
import hashlib
import os
from pathlib import Path

import dccss

LIBRARY = Path(dccss.__file__).parent
#: modules that draw or check results (and the command line): the simulations do not run them
DRAWING = ("drawing.py", "viewer.py", "animation.py", "plan.py", "paper/figures.py", "paper/specs.py",
           "studies/plots.py")
NOT_COMPUTING = DRAWING + ("paper/validation.py", "cli.py")


def source_hash(include=None, exclude=()):
    """SHA-256 of the dccss sources (paths relative to the package): the files ``include`` (default:
    all) minus ``exclude``."""
    files = sorted(LIBRARY.rglob("*.py")) if include is None else [LIBRARY / name for name in include]
    digest = hashlib.sha256()
    for path in files:
        name = path.relative_to(LIBRARY).as_posix()
        if name not in exclude:
            for part in (name.encode(), b"\0", path.read_bytes()):
                digest.update(part)
    return digest.hexdigest()


SCRIPTS = Path(workflow.current_basedir).parent / "scripts"  # beside rules/, this file's folder


def script_hash(name):
    """SHA-256 of a rule's script and of the log helper it imports: a rule takes it as a parameter, so
    that editing the script reruns the rule (the 'params' trigger; the 'code' trigger compares the
    script's modification time with the outputs', which means nothing in a fresh clone)."""
    digest = hashlib.sha256()
    for path in (SCRIPTS / name, SCRIPTS / "_log.py"):
        digest.update(path.read_bytes())
    return digest.hexdigest()


COMPUTE_SOURCE = source_hash(exclude=NOT_COMPUTING)
FIGURES_SOURCE = source_hash(include=("drawing.py", "paper/figures.py", "paper/specs.py"))
STUDY_PLOTS_SOURCE = source_hash(include=("drawing.py", "studies/plots.py", "studies/intensity_plots.py"))
ANIMATION_SOURCE = source_hash(include=("drawing.py", "viewer.py", "animation.py", "plan.py"))
VALIDATION_SOURCE = source_hash(include=("paper/validation.py",))

# numpy and OpenBLAS pick kernels by CPU; AVX-512 kernels round some results differently from the
# AVX2 ones, and results at round-off then differ in their last digits. The jobs use the AVX2 kernels
# on every x86-64 machine that has them (set these variables yourself to choose otherwise).
os.environ.setdefault("NPY_DISABLE_CPU_FEATURES", "X86_V4 AVX512_ICL AVX512_SPR")
os.environ.setdefault("OPENBLAS_CORETYPE", "Haswell")
