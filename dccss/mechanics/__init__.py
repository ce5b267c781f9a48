"""The mechanics of the three-body model (nothing here reads files or draws, or imports what does).

``geometry`` (the Table 1 parameters and what follows from them), ``kinematics`` (bodies, corners
and contact points), ``newton`` (Newton-Raphson's options and errors), ``linear`` (the 4 x 4
solve, written out), ``registry`` (a model is an entry), ``models`` (the paper's two models: their
kernels, written once on scalars, and registry entries),
``capacity`` (the retaining rings and their errors), ``summaries`` (the per-case reductions of a
sweep), ``scalar`` (how the kernels compile), ``compiled`` (the planar kernels' helpers and
driver, compiled with Numba or interpreted), ``backend`` (which runs: DCCSS_BACKEND and the run's
size), ``spatial`` (the phases and driver of the models in space, compiled), ``structure`` (the
isolated building) and ``runs`` (the one driver of histories and sweeps: planar or spatial, the
backend, the capacity and failure policies as events).
"""

from . import models  # noqa: F401  (registers the paper's models)
