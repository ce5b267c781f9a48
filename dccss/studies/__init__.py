"""New studies from a YAML file: a base case, the models, and sweep axes (cartesian product).

In four parts, in the order a workflow uses them:

1. ``spec``: the study file, validated key by key before anything runs (``Study.from_config``);
   ``sweep_spec`` is the part of it that the sweep's results depend on.
2. ``grid``: the cases of the sweep (``Grid``): their axis values, devices, ground motions and
   step sizes, and the chunks a workflow runs as jobs.
3. ``run``: one chunk under one model, solved in batches and reduced to summaries
   (``run_chunk``), and the chosen cases run in full (``history_mapping``, ``history_case``).
4. ``combine``: the chunks of every model in one dataset with a dimension per sweep axis.

A study file (schema: ``dccss/schemas/study.schema.yaml``, which the workflow applies too)::

    study: {name: pad_shape, description: "..."}
    prototypes: {MyBearing: {R1: ..., ...}}   # optional: devices of your own (13 parameters each)
    prototype: DFP1              # the base device: a name (Table 1 or prototypes) or the 13 parameters
    symmetric: true              # plate 3 and cap 23 follow plate 1 and cap 21
    excitation: {kind: sine, amplitude: 0.27, omega: 30.0, duration: 1.0}   # or table / record
    structure: {friction: 0.05, damping: 0.0}   # optional: a superstructure whose stroke drives the device
    theta2_0: 0.0                # degrees
    dt: 0.01                     # s (or a sweep axis; then this is the histories' default)
    models: [compliant, stick_slip]
    normals: signed
    sweep:                       # each axis a list or {start, stop, num} (linspace)
      alpha21: {start: 4.0, stop: 14.0, num: 21}
      h2: [0.08, 0.10, 0.12]
    chunk_size: auto             # cases per job: auto (default) splits each model's sweep in 4 jobs of 16 cases or more
    on_failure: mark             # a case the solver fails on: mark it (NaN, flag) or error (stop the study)
    capacity: continue           # the pad reaches a ring: continue (flag), stop (end there) or error
    marks: {DFP1: {alpha21: 10.0, h2: 0.15}}        # points drawn on the maps
    histories: [{alpha21: 10.0, h2: 0.15}]          # cases also run in full (or: all)
    animate: [{alpha21: 10.0, h2: 0.15}]            # histories also animated (GIF), or: all

Sweep axes: ``record`` (a suite: files, pairs [x, y] or patterns, each named by its stem, a
pair by its station; the excitation then gives no file; the cases of a record are chunked on
their own, and the combined dataset adds each record's peaks and the suite statistics,
``combine.statistics``), ``prototype`` (a list of device names), any geometry parameter
(overriding the device's), the excitation's own parameters (``amplitude`` and ``omega`` of a
sine, ``rotation`` of a record pair), ``scale`` (multiplies X_g(t) of any excitation; recorded
motions are processed linearly, so this equals scaling the record), ``azimuth`` and
``component`` (bidirectional motion), ``friction`` and ``damping`` (the structure's, with
``structure:``), ``theta2_0`` and ``dt`` (the chunks take the cases by step size first and solve
each step size as one batch).
"""

from .combine import combine
from .grid import Grid
from .run import history_case, history_mapping, run_chunk
from .spec import AXES, Study, StudyError, sweep_spec

__all__ = ["AXES", "Grid", "Study", "StudyError", "combine", "history_case", "history_mapping", "run_chunk",
           "sweep_spec"]
