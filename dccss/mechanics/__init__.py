"""The mechanics of the three-body model (nothing here reads files or draws, or imports what does).

``geometry`` (the Table 1 parameters and what follows from them), ``kinematics`` (bodies, corners
and contact points), ``constraints`` (the constraint sets with their analytic Jacobians), ``newton``
(one Newton-Raphson solver for every set), ``linear`` (its 4 x 4 solve, written out), ``models``
(the time steppers, and the registry of models), ``capacity`` (the retaining rings and their
errors), ``summaries`` (the per-case reductions of a sweep), ``compiled`` (the planar models'
kernels, compiled with Numba or interpreted), ``backend`` (which runs: DCCSS_BACKEND and the run's size),
``spatial`` (both models in space, compiled) and ``runs`` (the one driver of histories and sweeps:
planar or spatial, the backend, the capacity and failure policies as events).
"""
