"""The written-out 4 x 4 solve (mechanics.linear): it solves, it finds the singular systems LAPACK
finds, and the batched and compiled forms round as the scalar one, bit for bit."""

import os
import shutil
from pathlib import Path

import numpy as np
import oracle
import pytest

from dccss.mechanics import linear


def systems(n=400, seed=3):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(n, 4, 4)) * rng.uniform(1e-3, 1e3, size=(n, 1, 4))  # badly scaled columns
    A[::7, 1, 0] = A[::7, 2, 0] = A[::7, 0, 0]  # ties in the first pivot search
    A[::11, 3, :] = 0.0  # singular: the last pivot is exactly 0
    return A, rng.normal(size=(n, 4))


def scalar(A, b):
    return linear.solve4(tuple(tuple(r) for r in A.tolist()), tuple(b.tolist()))


def test_solves_as_lapack_to_round_off():
    A, b = systems()
    regular = np.abs(np.linalg.det(A)) > 1e-9 * np.prod(np.abs(A).max(axis=-1), axis=-1)
    for Ai, bi in zip(A[regular], b[regular]):
        ok, x = scalar(Ai, bi)
        assert ok
        cond = np.linalg.cond(Ai)
        assert np.allclose(x, np.linalg.solve(Ai, bi), rtol=0, atol=1e-13 * cond * np.abs(x).max())


def test_singular_where_lapack_says_singular():
    A = np.array([[1.0, 2.0, 0.0, 0.0], [2.0, 4.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.solve(A, np.ones(4))
    assert scalar(A, np.ones(4))[0] is False
    assert not oracle.solve4_batch(A[None], np.ones((1, 4)))[0][0]
    assert scalar(np.eye(4), np.ones(4)) == (True, (1.0, 1.0, 1.0, 1.0))


def test_batch_rounds_as_the_scalar_solve():
    A, b = systems()
    A[5, 2, 1] = np.nan  # a NaN entry: NaN out, as the scalar solve
    ok, x = oracle.solve4_batch(A, b)
    for k in range(len(A)):
        ok_k, x_k = scalar(A[k], b[k])
        assert ok[k] == ok_k, k
        if ok_k:
            assert np.array_equal(x[k], np.array(x_k), equal_nan=True), k
    assert np.array_equal(~ok, np.arange(len(A)) % 11 == 0)


def test_compiled_rounds_as_the_interpreted_solve():
    from numba import njit

    from dccss.mechanics.scalar import compilable, compile_helpers

    compilable(*linear.SCALAR)
    compile_helpers()  # registered with Numba, whatever ran before
    compiled = njit(lambda A, b: linear.solve4(A, b))
    A, b = systems(50)
    for Ai, bi in zip(A, b):
        args = (tuple(tuple(r) for r in Ai.tolist()), tuple(bi.tolist()))
        assert compiled(*args) == linear.solve4(*args)


def test_the_kernel_cache_is_named_by_every_mechanics_source(tmp_path):
    """Numba would keep a kernel compiled from an old helper (it watches the kernel's own file only):
    the cache folder's name changes with any module of the mechanics."""
    from dccss.mechanics import scalar

    copy = tmp_path / "mechanics"
    shutil.copytree(Path(scalar.__file__).parent, copy, ignore=shutil.ignore_patterns("__pycache__"))
    before = scalar.source_digest(copy)
    assert before == scalar.source_digest() and scalar.cache_folder("/cache").name == f"kernels-{before}"
    with open(copy / "linear.py", "a") as f:
        f.write("\n# a changed helper\n")
    assert scalar.source_digest(copy) != before


def test_a_read_only_installation_caches_its_kernels_in_the_users_cache(tmp_path, monkeypatch):
    from dccss.mechanics import scalar

    package = Path(scalar.__file__).parent / "__pycache__"
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    monkeypatch.setattr(scalar.os, "access", lambda path, mode: Path(path) != package)
    (tmp_path / "dccss" / "kernels-0123456789abcdef").mkdir(parents=True)  # an older version's kernels
    folder = scalar.cache_folder()
    assert folder == tmp_path / "dccss" / f"kernels-{scalar.source_digest()}"
    assert [p.name for p in (tmp_path / "dccss").iterdir()] == []  # the older digest removed
    assert scalar.cache_folder("/elsewhere") == Path("/elsewhere") / folder.name  # NUMBA_CACHE_DIR first


def test_the_determinant_is_lapacks_to_round_off_and_rounds_alike_on_every_processor():
    """|C_q| in the datasets (Fig. 7 plots it) comes from ``linear.det``, not LAPACK's getrf, whose
    OpenBLAS kernels round by CPU: a process told to use another core's kernels gives the same bits."""
    import subprocess
    import sys

    rng = np.random.default_rng(7)
    A = rng.normal(size=(200, 9, 9))
    ours = linear.det(A)
    hadamard = np.prod(np.linalg.norm(A, axis=-2), axis=-1)  # |det| <= the product of the column norms
    assert np.all(np.abs(ours - np.linalg.det(A)) <= 1e-13 * hadamard)
    swap = np.eye(9)[[1, 0, 2, 3, 4, 5, 6, 7, 8]]
    assert linear.det(swap) == -1.0 and linear.det(np.eye(9)) == 1.0
    singular = A[0].copy()
    singular[:, 4] = 0.0
    assert linear.det(singular) == 0.0
    code = ("import numpy as np; from dccss.mechanics import linear; "
            "print(linear.det(np.random.default_rng(7).normal(size=(200, 9, 9))).tobytes().hex())")
    env = {**os.environ, "OPENBLAS_CORETYPE": "Katmai"}
    other = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    assert other.stdout.strip() == ours.tobytes().hex()
