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
#: modules that draw or check results: the simulations do not run them
DRAWING = ("plotting.py", "studyplots.py", "animation.py")
CHECKING = ("validation.py",)


def source_hash(include=None, exclude=()):
    """SHA-256 of the dccss sources: the modules or subpackages ``include`` (default: all) minus
    ``exclude`` (paths relative to the package)."""
    files = []
    for name in include or [p.name for p in LIBRARY.iterdir()]:
        path = LIBRARY / name
        files += sorted(path.rglob("*.py")) if path.is_dir() else [path] if path.suffix == ".py" else []
    digest = hashlib.sha256()
    for path in sorted(f for f in files if f.relative_to(LIBRARY).parts[0] not in exclude):
        digest.update(path.relative_to(LIBRARY).as_posix().encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()


COMPUTE_SOURCE = source_hash(exclude=DRAWING + CHECKING + ("cli.py",))
FIGURES_SOURCE = source_hash(include=("plotting.py",))
STUDY_PLOTS_SOURCE = source_hash(include=("plotting.py", "studyplots.py"))
ANIMATION_SOURCE = source_hash(include=("plotting.py", "animation.py"))
VALIDATION_SOURCE = source_hash(include=CHECKING)

# numpy and OpenBLAS pick kernels by CPU; AVX-512 kernels round some results differently from the
# AVX2 ones, and results at round-off then differ in their last digits. The jobs use the AVX2 kernels
# on every x86-64 machine that has them (set these variables yourself to choose otherwise).
os.environ.setdefault("NPY_DISABLE_CPU_FEATURES", "X86_V4 AVX512_ICL AVX512_SPR")
os.environ.setdefault("OPENBLAS_CORETYPE", "Haswell")
