"""The constraint sets of the two models, each with its analytic Jacobian, in numpy over a batch: the
tests' independent statement of the paper's equations (the library's kernels write the same rows on
scalars, ``dccss.mechanics.compiled``; ``oracle`` runs these).

A constraint set C(q) = 0 splits into

* prescribed rows, unit rows q_k - value = 0 (the imposed ground motion and the plates'
  guides, e.g. Eq. 5 rows 1-3, 8, 9), and
* contact rows g(q) = 0 with their Jacobian dg/dq (..., m, 9).

``residual``/``jacobian`` assemble C and C_q in the paper's row and column order (9 x 9 for
compliant sliding and sticking, 6 x 6 for slipping, Eq. 37). The Newton solver eliminates the
prescribed rows exactly and iterates on the contact rows over the ``free`` coordinates.

Sets:

* ``Compliant`` - Eqs. 5-11, Jacobian Eqs. 16-28: the four corners slide along the tangents
  at their previous contact points.
* ``Sticking`` - Eqs. 31-36 (diagonal A-D) and the mirrored set (B-C): the diagonal's
  corners are pinned to their plates; R_x^3 is held at its initial (absolute) value.
* ``Slipping`` - Eqs. 37-48, corrected: the diagonal's corners slide along their tangents
  (row 2 uses n_D^3, not n_C^3), G^2 and RB3 translate along C^1C^3 (k_1, k_3 from the end
  of sticking), R_y^3 restores compatibility (Eq. 41), RB1 is frozen.
"""

from __future__ import annotations

import numpy as np

from dccss.mechanics.kinematics import NORMALS, Corner, dot, frames, local, turn
from dccss.mechanics.linear import det


def circle_centre(F, corner: Corner):
    """Global position of the concave circle centre of the corner's plate (complex)."""
    R, e = F[corner.body // 3]
    return R + turn(e, corner.centre)


def contact_point(F, corner: Corner, normals="signed", u=None):
    """Previous contact point: radial projection of the corner onto its concave circle.

    Returns the plate-frame point and unit normal (complex), the normal pointing from the point
    to the circle centre (Eq. 7). With ``normals="unsigned"`` the normal is built from |alpha|
    instead of the signed contact angle alpha (the authors' evident computation): it is
    mirrored when the point lies across the plate axis from its corner. ``u``: the corner's
    plate-frame position, if already known.
    """
    d = (local(F, corner) if u is None else u) - corner.centre
    n = -d / abs(d)
    point = corner.centre - corner.radius * n
    if normals == "unsigned":
        n = -corner.side * abs(n.real) + 1j * n.imag
    elif normals != "signed":
        raise ValueError(f"normals must be one of {NORMALS}, got {normals!r}")
    return point, n


def tangent_row(F, corner: Corner, point, normal, rotations=True):
    """Tangency row (r_P^2 - r_P^j)^T n_P^j (Eqs. 6-11) and its Jacobian entries (Eqs. 17-28).

    point, normal : the previous contact point and unit normal in the plate frame (complex),
    held fixed during the iterations; F = frames(q). Returns g and {column: dg/dq_column};
    ``rotations=False`` leaves out the plate-rotation column (prescribed in every set).
    """
    R2, e2 = F[1]
    Rj, ej = F[corner.body // 3]
    arm = e2 * corner.u2
    n = turn(ej, normal)
    lever = R2 + arm - Rj
    b = corner.body
    entries = {3: n.real, 4: n.imag, 5: dot(1j * arm, n), b: -n.real, b + 1: -n.imag}
    if rotations:
        # the x-bar, y-bar terms cancel (point and normal rotate together): Eqs. 18, 21, 25, 28
        entries[b + 2] = dot(lever, 1j * n)
    return dot(lever - turn(ej, point), n), entries


def pin_rows(F, corner: Corner, point):
    """Pin rows r_P^2 - r_P^j (Eq. 32), x and y, and their Jacobian entries (Eqs. 33-36);
    point is the pinned point in the plate frame (complex); F = frames(q)."""
    R2, e2 = F[1]
    Rj, ej = F[corner.body // 3]
    arm = 1j * e2 * corner.u2
    pin = 1j * turn(ej, point)
    h = R2 - 1j * arm - Rj + 1j * pin
    b = corner.body
    return [(h.real, {3: 1.0, 5: arm.real, b: -1.0, b + 2: -pin.real}),
            (h.imag, {4: 1.0, 5: arm.imag, b + 1: -1.0, b + 2: -pin.imag})]


def stack_residual(rows, shape):
    """The contact residual (..., m) from ``rows`` (one case: ``shape`` is ())."""
    if not shape:
        return np.array([gi for gi, _ in rows])
    g = np.empty((len(rows),) + shape)
    for i, (gi, _) in enumerate(rows):
        g[i] = gi
    return np.moveaxis(g, 0, -1)


def stack_jacobian(rows, columns, shape):
    """The Jacobian (..., m, len(columns)) from ``rows``; rows and columns first, then a view with
    the batch first (contiguous writes)."""
    if not shape:
        return np.array([[entries.get(c, 0.0) for c in columns] for _, entries in rows])
    where = {c: j for j, c in enumerate(columns)}
    J = np.zeros((len(rows), len(columns)) + shape)
    for i, (_, entries) in enumerate(rows):
        for col, value in entries.items():
            if col in where:
                J[i, where[col]] = value
    return np.moveaxis(J, (0, 1), (-2, -1))


class ConstraintSet:
    """Prescribed unit rows plus contact rows. Subclasses set the class attributes and
    ``values`` (..., len(prescribed)) and implement ``rows`` and ``row_labels``."""

    phase: str
    prescribed: tuple[int, ...]
    free: tuple[int, ...]
    #: the paper's row order: ('q', k) for a prescribed row on q_k, ('g', i) for contact row i
    paper_rows: tuple[tuple[str, int], ...]
    paper_columns: tuple[int, ...]
    values: np.ndarray

    def rows(self, F, rotations=True) -> list:
        """Contact rows as [(g_i, {column: dg_i/dq_column}), ...]; F = frames(q); without the
        plate-rotation columns if ``rotations`` is False."""
        raise NotImplementedError

    def row_labels(self) -> list[str]:
        raise NotImplementedError

    @property
    def labels(self) -> tuple[str, ...]:
        """The contact rows' labels (as ``dccss.mechanics.newton.Rows``, which names a failure)."""
        return tuple(self.row_labels())

    def contact(self, q, columns=tuple(range(9))):
        """Contact rows g (..., m) and their Jacobian dg/dq (..., m, len(columns)), by default
        on all nine coordinates."""
        rows = self.rows(frames(q), rotations=bool({2, 8} & set(columns)))
        return stack_residual(rows, q.shape[:-1]), stack_jacobian(rows, columns, q.shape[:-1])

    def prescribe(self, q):
        """Copy of q with the prescribed coordinates set: the exact solution of the unit rows."""
        q = np.array(q, dtype=float, copy=True)
        q[..., list(self.prescribed)] = self.values
        return q

    def residual(self, q):
        """C(q) in the paper's row order."""
        g, _ = self.contact(q)
        pres = q[..., list(self.prescribed)] - self.values
        col = {k: i for i, k in enumerate(self.prescribed)}
        return np.stack([pres[..., col[i]] if kind == "q" else g[..., i]
                         for kind, i in self.paper_rows], axis=-1)

    def jacobian(self, q):
        """C_q(q) in the paper's row and column order."""
        _, J = self.contact(q)
        unit = np.eye(9)
        rows = [np.broadcast_to(unit[i], J.shape[:-2] + (9,)) if kind == "q" else J[..., i, :]
                for kind, i in self.paper_rows]
        return np.stack(rows, axis=-2)[..., list(self.paper_columns)]

    def determinant(self, q):
        """|C_q| in the paper's row and column order."""
        return det(self.jacobian(q))


_NINE_ROWS = (("q", 0), ("q", 1), ("q", 2), ("g", 0), ("g", 1), ("g", 2), ("g", 3), ("q", 6), ("q", 8))


def _stack_values(*columns):
    if all(np.ndim(c) == 0 for c in columns):
        return np.array(columns, dtype=float)
    return np.stack(np.broadcast_arrays(*[np.asarray(c, dtype=float) for c in columns]), axis=-1)


class Compliant(ConstraintSet):
    """Eq. 5: compliant sliding of the four corners, RB1 driven by X_g, RB3 guided vertically.

    Parameters
    ----------
    corners : the four Corner objects A, B, C, D (``kinematics.all_corners``).
    Xg : imposed R_x^1 at this step (m).
    Rx3 : guided abscissa of RB3 (m); Eq. 5 has 0, a start at theta^2(t_0) != 0 needs
        L sin theta^2(t_0).
    points, normals : previous contact points and normals of A, B, C, D (complex, plate frames).
    """

    phase = "compliant sliding"
    prescribed = (0, 1, 2, 6, 8)
    free = (3, 4, 5, 7)
    paper_rows = _NINE_ROWS
    paper_columns = tuple(range(9))

    def __init__(self, corners, Xg, Rx3, points, normals):
        self.corners, self.points, self.normals = corners, points, normals
        self.values = _stack_values(Xg, 0.0, 0.0, Rx3, 0.0)

    def rows(self, F, rotations=True):
        return [tangent_row(F, c, p, n, rotations) for c, p, n in zip(self.corners, self.points, self.normals)]

    def row_labels(self):
        return [f"row {4 + i} (Eq. {8 + i}: {c.name}^2 sliding on the tangent to C_nf^{1 if i < 2 else 3})"
                for i, c in enumerate(self.corners)]


def diagonal(geometry, bc) -> tuple[Corner, Corner]:
    """The (RB1, RB3) corners of the jammed diagonal: A-D, or B-C where ``bc`` is True
    (a bool, or a boolean array for a batch)."""
    A, B, C, D = (Corner.of(geometry, name) for name in "ABCD")
    return A.where(bc, B), D.where(bc, C)


class Sticking(ConstraintSet):
    """Eq. 31 (diagonal A-D) or its mirror (B-C): the diagonal's corners pinned to their plates.

    Parameters
    ----------
    corners : the diagonal's (RB1, RB3) corners (``diagonal``).
    Xg, Rx3 : as for Compliant; R_x^3 is absolute (its initial value), so a sideways move of
        RB3 in the previous slip is undone here.
    points : the pinned points of the two corners in the RB1 and RB3 frames (complex).
    """

    phase = "sticking"
    prescribed = (0, 1, 2, 6, 8)
    free = (3, 4, 5, 7)
    paper_rows = _NINE_ROWS
    paper_columns = tuple(range(9))

    def __init__(self, corners, Xg, Rx3, points):
        self.corners, self.points = corners, points
        self.values = _stack_values(Xg, 0.0, 0.0, Rx3, 0.0)

    def rows(self, F, rotations=True):
        return [row for c, p in zip(self.corners, self.points) for row in pin_rows(F, c, p)]

    def row_labels(self):
        p1, p3 = (c.name for c in self.corners)
        return [f"row 4 (Eq. 32: x of {p1}^2 pinned to RB1)", f"row 5 (Eq. 32: y of {p1}^2 pinned to RB1)",
                f"row 6 (Eq. 32: x of {p3}^2 pinned to RB3)", f"row 7 (Eq. 32: y of {p3}^2 pinned to RB3)"]


class Slipping(ConstraintSet):
    """Eq. 37, corrected: roto-translation of the pad restoring compatibility.

    Parameters
    ----------
    corners : the diagonal's (RB1, RB3) corners.
    q_stick : (..., 9) configuration at the end of sticking (RB1 stays frozen there).
    points, normals : contact points and normals (RB1, RB3 frames, complex) of the diagonal's
        corners, projected at the end of sticking.
    n12 : unit normal to C^1C^3 at the end of sticking (complex).
    k1, k3 : G^2 . n12 and R^3 . n12 at the end of sticking (Eqs. 38, 39; Eq. 37 projects F^3,
        a point of RB3 on C^1C^3, which differs from R^3 by a constant along n12).
    Ry3_rc : Eq. 41 ordinate of RB3 restoring compatibility.
    """

    phase = "slipping"
    prescribed = (0, 1, 2, 7, 8)
    free = (3, 4, 5, 6)
    paper_rows = (("g", 0), ("g", 1), ("g", 2), ("g", 3), ("q", 7), ("q", 8))
    paper_columns = (3, 4, 5, 6, 7, 8)

    def __init__(self, corners, q_stick, points, normals, n12, k1, k3, Ry3_rc):
        self.corners, self.points, self.normals = corners, points, normals
        self.n12, self.k1, self.k3 = n12, k1, k3
        self.values = _stack_values(q_stick[..., 0], q_stick[..., 1], q_stick[..., 2], Ry3_rc, 0.0)

    def rows(self, F, rotations=True):
        nx, ny = self.n12.real, self.n12.imag
        return [tangent_row(F, c, p, n, rotations) for c, p, n in zip(self.corners, self.points, self.normals)] + [
            (dot(F[1][0], self.n12) - self.k1, {3: nx, 4: ny}),
            (dot(F[2][0], self.n12) - self.k3, {6: nx, 7: ny}),
        ]

    def row_labels(self):
        p1, p3 = (c.name for c in self.corners)
        return [f"row 1 (Eq. 37: {p1}^2 sliding on the tangent to C_nf^1)",
                f"row 2 (Eq. 37: {p3}^2 sliding on the tangent to C_nf^3)",
                "row 3 (Eq. 38: G^2 on the line C^1C^3)",
                "row 4 (Eq. 39: RB3 translating along C^1C^3)"]
