"""The 4 x 4 solve of every Newton step, written out: Gaussian elimination with partial pivoting.

One algorithm, the same operations in the same order wherever a Newton step is taken: ``solve4``
runs interpreted and compiled into the kernels (``compiled`` registers these functions with Numba:
``scalar.compilable``), and the tests' numpy reference repeats it elementwise over a stack of
systems. So the interpreted and compiled solvers round alike, on every machine. LAPACK's ``gesv``
(``numpy.linalg.solve``) would not: OpenBLAS picks its kernels by CPU, and their fused
multiply-adds round differently on another processor.

A pivot exactly 0 is singular (``ok`` False), as LAPACK's: numpy's LinAlgError('Singular matrix').
"""

from __future__ import annotations

import numpy as np


def pivot(column):
    """Partial pivoting: the index of the largest |entry| of a column (the first on ties, as
    LAPACK's idamax; a NaN is never chosen after the first entry)."""
    p, best = 0, abs(column[0])
    for r in range(1, len(column)):
        if abs(column[r]) > best:
            p, best = r, abs(column[r])
    return p


def eliminate(pivot_row, inverse, row, c):
    """row - (row[c] / pivot[c]) pivot on the entries right of column c of a row [A | b] (the
    multiplier from the pivot's reciprocal, as LAPACK getf2)."""
    f = row[c] * inverse
    return (row[0], row[1] - f * pivot_row[1] if c < 1 else row[1], row[2] - f * pivot_row[2] if c < 2 else row[2],
            row[3] - f * pivot_row[3], row[4] - f * pivot_row[4])


def solve4(A, b):
    """Solve A x = b (4 x 4; A a tuple of rows, b a tuple): (ok, x); ok is False when a pivot is
    exactly zero (x is then b)."""
    unsolved = (b[0], b[1], b[2], b[3])  # returned with ok False
    r0 = (A[0][0], A[0][1], A[0][2], A[0][3], b[0])
    r1 = (A[1][0], A[1][1], A[1][2], A[1][3], b[1])
    r2 = (A[2][0], A[2][1], A[2][2], A[2][3], b[2])
    r3 = (A[3][0], A[3][1], A[3][2], A[3][3], b[3])
    p = pivot((r0[0], r1[0], r2[0], r3[0]))
    if p == 1:
        r0, r1 = r1, r0
    elif p == 2:
        r0, r2 = r2, r0
    elif p == 3:
        r0, r3 = r3, r0
    if r0[0] == 0.0:
        return False, unsolved
    inverse = 1.0 / r0[0]
    r1, r2, r3 = eliminate(r0, inverse, r1, 0), eliminate(r0, inverse, r2, 0), eliminate(r0, inverse, r3, 0)
    p = pivot((r1[1], r2[1], r3[1]))
    if p == 1:
        r1, r2 = r2, r1
    elif p == 2:
        r1, r3 = r3, r1
    if r1[1] == 0.0:
        return False, unsolved
    inverse = 1.0 / r1[1]
    r2, r3 = eliminate(r1, inverse, r2, 1), eliminate(r1, inverse, r3, 1)
    if pivot((r2[2], r3[2])) == 1:
        r2, r3 = r3, r2
    if r2[2] == 0.0:
        return False, unsolved
    r3 = eliminate(r2, 1.0 / r2[2], r3, 2)
    if r3[3] == 0.0:
        return False, unsolved
    x3 = r3[4] / r3[3]
    x2 = (r2[4] - r2[3] * x3) / r2[2]
    x1 = (r1[4] - r1[2] * x2 - r1[3] * x3) / r1[1]
    x0 = (r0[4] - r0[1] * x1 - r0[2] * x2 - r0[3] * x3) / r0[0]
    return True, (x0, x1, x2, x3)


#: what the kernels compile (``scalar.compilable``)
SCALAR = (pivot, eliminate, solve4)


def det(A):
    """Determinant of a stack of square matrices (..., n, n): Gaussian elimination with partial
    pivoting (the first largest |entry|), the product of the pivots signed by the row swaps, in
    elementwise numpy arithmetic, which rounds alike on every processor (LAPACK's ``getrf`` behind
    ``numpy.linalg.det`` runs OpenBLAS kernels chosen by CPU). 0 where a pivot is exactly 0."""
    A = np.asarray(A, dtype=float)
    shape, n = A.shape[:-2], A.shape[-1]
    M = A.reshape(-1, n, n).copy()
    cases = np.arange(len(M))
    out = np.ones(len(M))
    for c in range(n):
        p = c + np.argmax(np.abs(M[:, c:, c]), axis=-1)
        swapped = p != c
        if swapped.any():
            row = M[cases, c].copy()
            M[cases, c] = M[cases, p]
            M[cases, p] = row
            out = np.where(swapped, -out, out)
        pivot = M[:, c, c]
        singular = pivot == 0.0
        out = np.where(singular, 0.0, out * pivot)
        if c + 1 < n:
            f = M[:, c + 1:, c] / np.where(singular, 1.0, pivot)[:, None]
            M[:, c + 1:, c + 1:] = M[:, c + 1:, c + 1:] - f[:, :, None] * M[:, None, c, c + 1:]
    return out.reshape(shape)
