"""The registry of kinematic models: a model is a ``Model`` entry, and nothing else names it.

An entry holds everything that differs between models: its name and title, its kernels (planar:
``PlanarKernels`` for ``compiled``; spatial: a history for ``spatial``), the diagnostics its
datasets carry, its summaries, its line style on plots and whether it has a sticking phase.
``models`` defines and registers the paper's two models (importing ``dccss.mechanics`` registers
them); a new model is one ``register`` call.
This module imports nothing of the package, so every module can look a model up by name.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple


class PlanarKernels(NamedTuple):
    """A model's planar kernels (``dccss.mechanics.compiled``: its docstring gives their arguments).

    Attributes
    ----------
    case : callable
        ``case(k, xg, q0, constants, flags, history_out, summary_out, status_out)``: all the steps
        of case k (a plain function: interpreted, or compiled inlined into ``batch``).
    batch : callable
        The same over all cases (``for k in scalar.prange(...)``), compiled with Numba.
    history : dict
        {key: (trailing shape, dtype)} of the history arrays ``case`` fills, in the order of
        ``history_out`` and of the histories it returns.
    summary_columns : dict
        {summary name: column of the accumulators} of the model's own summaries.
    rows : callable
        ``rows(phase, down)``: the ``newton.Rows`` of the failing phase (0 or 1) of a step, for an
        error's message (``down``: the jammed diagonal is B-C; None: a batch, both).
    """

    case: Callable
    batch: Callable
    history: dict
    summary_columns: dict
    rows: Callable


@dataclass(frozen=True)
class Model:
    """A kinematic model as data.

    Attributes
    ----------
    name, title : str
        Identifier (files, configs) and the paper's name.
    planar : PlanarKernels
        Its planar kernels.
    diagnostics : callable
        ``diagnostics(history, geometry) -> {name: (values, units, long_name[, attrs])}``: the
        variables only this model's datasets carry (besides the configuration at the end of each
        step, which every model has).
    stages : dict
        The configurations a step stores besides its end (suffix -> long-name phrase).
    summaries : dict
        {name: (units, long_name)} of the sweep summaries only this model has (its kernels reduce
        them: ``PlanarKernels.summary_columns``).
    line, marker : dict
        How plots draw it (matplotlib line and marker properties; empty: a spare style).
    spatial : callable or None
        Its spatial history (``spatial.history(step, ...)`` bound to its step; None: it does not
        run in space).
    """

    name: str
    title: str
    planar: PlanarKernels
    diagnostics: Callable
    stages: dict = field(default_factory=dict)
    summaries: dict = field(default_factory=dict)
    line: dict = field(default_factory=dict)
    marker: dict = field(default_factory=dict)
    spatial: Callable | None = None

    @property
    def sticking(self) -> bool:
        """Whether its steps have a sticking phase (and store its end, ``stages``)."""
        return bool(self.stages)


#: the registered models, by name, in the order of registration
REGISTRY: dict[str, Model] = {}


def register(entry: Model) -> Model:
    """Add ``entry`` to the registry (a ValueError if its name is taken)."""
    if entry.name in REGISTRY:
        raise ValueError(f"a model named {entry.name!r} is registered already")
    REGISTRY[entry.name] = entry
    return entry


def names(where=None) -> tuple:
    """The registered models' names; ``where(entry)`` filters them."""
    return tuple(name for name, entry in REGISTRY.items() if where is None or where(entry))


def model(name, where=None, context="") -> Model:
    """The registry entry of ``name``; a ValueError names the models allowed (``where`` filters them,
    ``context`` says where: e.g. " in space")."""
    allowed = names(where)
    if name not in allowed:
        raise ValueError(f"model must be one of {allowed}{context}, got {name!r}")
    return REGISTRY[name]
