"""The mechanics of the three-body model (numpy only; nothing here reads files or draws).

``geometry`` (the Table 1 parameters and what follows from them), ``kinematics`` (bodies, corners
and contact points), ``constraints`` (the constraint sets with their analytic Jacobians), ``newton``
(one Newton-Raphson solver for every set), ``models`` (the time steppers, and the registry of
models), ``capacity`` (the retaining rings), ``compiled`` (the same steppers compiled with Numba,
where it is installed) and ``backend`` (which of the two runs: DCCSS_BACKEND, and the size of the
run).
"""
