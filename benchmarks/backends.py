"""The compiled kernels (numba) beside the numpy reference (the tests' ``tests/oracle.py``, "numpy") and
the interpreted kernels ("python"): sweeps and one long history.

Each measurement runs in a fresh process (its own peak resident memory; the compiled one
loads its kernels from the on-disk cache, or compiles them if the cache is empty):

* ``compile``: the compiled kernels built from an empty cache (a temporary NUMBA_CACHE_DIR);
* ``sweep``: N cases of DFP1-type devices with pad angles alpha21 spread over 6..12 deg, 1000
  steps each (sine of 0.27 m at 30 rad/s over 1 s, dt = 0.001 s), reduced to per-case
  summaries (``dccss.mechanics.summaries.summarize`` / ``dccss.mechanics.compiled.summarize``), as benchmarks/sweep.py;
* ``history``: one stick-slip history of DFP1, the same sine over 30 s at dt = 0.001 s
  (30 000 steps; ``dccss.mechanics.models.stick_slip``);
* ``run``: the same history through ``dccss run CASE.yaml -o OUT.nc`` as a whole process
  (interpreter start, imports, the run, the dataset written), timed from outside.

Each runs through the package's entry points with DCCSS_BACKEND set to the backend measured (the
numpy reference: through its own ``run`` and ``summarize``; ``dccss run`` is timed on the interpreted
kernels instead). cold_s is the first call in the process (the compiled backend: loading its
kernels from the cache), warm_s the second; the numpy reference runs once (it has nothing to warm
up). For ``run`` cold_s is a process with an empty kernel cache (a temporary NUMBA_CACHE_DIR: it
compiles), warm_s the best of ``--repeat`` processes that load them (python: the best of as many,
alternating with them). Lines:

    sweep backend=numba model=compliant N=10000 steps=1000 case_steps_per_s=... peak_mem_mb=... cold_s=... warm_s=...
    ratio sweep model=compliant N=10000 numba_over_numpy=...
    run backend=numba model=stick_slip steps=30000 cold_s=... warm_s=... processes=3 all_s=...
    ratio run model=stick_slip steps=30000 numba_over_python=...   (python's process time over numba's, warm)

Run: python benchmarks/backends.py [--sizes 10000] [--big 100000] [--steps 1000] [--history-steps 30000]
     [--repeat 3] [--parts compile sweep history run]
"""

import argparse
import multiprocessing as mp
import os
import resource
import subprocess
import sys
import tempfile
import time
from functools import partial
from pathlib import Path

MODELS = ("compliant", "stick_slip")
PARTS = ["compile", "sweep", "history", "run"]


def _geometry(n):
    import numpy as np

    from dccss.mechanics.geometry import Geometry
    from dccss.paper.prototypes import TABLE1

    return Geometry.from_degrees(**{**TABLE1["DFP1"], "alpha21": np.linspace(6.0, 12.0, n),
                                    "alpha23": np.linspace(6.0, 12.0, n)})


def _peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # kB on Linux


def _timed(call, repeats):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = call()
        times.append(time.perf_counter() - start)
    return out, times


def _oracle():
    """The numpy reference of the tests."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    import oracle

    return oracle


def sweep(backend, model, n, steps, queue):
    os.environ["DCCSS_BACKEND"] = backend
    import numpy as np

    from dccss.excitation import Sine
    from dccss.mechanics.summaries import summarize

    if backend == "numpy":
        summarize = _oracle().summarize

    geometry = _geometry(n)
    Xg = Sine(0.27, 30.0, 1.0).displacement(np.arange(steps + 1) * (1.0 / steps))
    out, times = _timed(lambda: summarize(model, geometry, Xg), 1 if backend == "numpy" else 2)
    assert np.isfinite(out["theta2_max_abs"]).all()
    queue.put((times, _peak_mb()))


def history(backend, steps, queue):
    os.environ["DCCSS_BACKEND"] = backend
    import numpy as np

    from dccss.excitation import Sine, step_times
    from dccss.mechanics.models import stick_slip
    from dccss.paper.prototypes import DFP1

    if backend == "numpy":
        stick_slip = partial(_oracle().run, "stick_slip")

    dt = 0.001
    excitation = Sine(0.27, 30.0, steps * dt)
    times = step_times(excitation, dt)
    out, seconds = _timed(lambda: stick_slip(DFP1, excitation.displacement(times), times=times),
                          1 if backend == "numpy" else 2)
    assert np.isfinite(out["q"]).all()
    queue.put((seconds, _peak_mb()))


def compile_cold(queue):
    with tempfile.TemporaryDirectory() as cache:
        os.environ["NUMBA_CACHE_DIR"] = cache  # before numba is imported: an empty cache
        import numpy as np

        from dccss.mechanics import compiled
        from dccss.paper.prototypes import DFP1

        start = time.perf_counter()
        for model in MODELS:
            compiled.run(model, DFP1, np.array([0.0, 1e-3]))
        queue.put(([time.perf_counter() - start], _peak_mb()))


def cli_run(backend, steps, cache=None):
    """Seconds of one ``dccss run`` process of the stick-slip history (``cache``: NUMBA_CACHE_DIR)."""
    with tempfile.TemporaryDirectory() as work:
        case = Path(work) / "case.yaml"
        case.write_text("prototype: DFP1\n"
                        f"excitation: {{kind: sine, amplitude: 0.27, omega: 30.0, duration: {steps * 0.001!r}}}\n"
                        "dt: 0.001\nmodel: stick_slip\n")
        env = {**os.environ, "DCCSS_BACKEND": backend}
        if cache is not None:
            env["NUMBA_CACHE_DIR"] = cache
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "dccss", "run", str(case), "-o", str(Path(work) / "out.nc"), "-q"],
                       env=env, check=True)
        return time.perf_counter() - start


def _in_process(target, *args):
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    proc = ctx.Process(target=target, args=(*args, queue))
    proc.start()
    result = queue.get()
    proc.join()
    return result


def _times(seconds):
    cold = seconds[0]
    warm = seconds[1] if len(seconds) > 1 else seconds[0]
    return cold, warm, f"cold_s={cold:.3f} warm_s={warm:.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[10000], help="sweep sizes run on both backends")
    parser.add_argument("--big", type=int, nargs="*", default=[100000], help="sweep sizes run compiled only")
    parser.add_argument("--steps", type=int, default=1000)
    parser.add_argument("--history-steps", type=int, default=30000)
    parser.add_argument("--no-compile", action="store_true", help="skip the empty-cache compile measurement")
    parser.add_argument("--repeat", type=int, default=3, help="processes per backend for `run` (the best counts)")
    parser.add_argument("--parts", nargs="+", default=PARTS, choices=PARTS, help="what to measure (default: all)")
    args = parser.parse_args()
    if args.no_compile:
        args.parts = [p for p in args.parts if p != "compile"]
    if "compile" in args.parts:
        seconds, peak = _in_process(compile_cold)
        print(f"compile backend=numba models={','.join(MODELS)} seconds={seconds[0]:.1f} peak_mem_mb={peak:.0f}",
              flush=True)
    for model in MODELS if "sweep" in args.parts else ():
        for n in args.sizes + args.big:
            rates = {}
            for backend in ("numpy", "numba") if n in args.sizes else ("numba",):
                seconds, peak = _in_process(sweep, backend, model, n, args.steps)
                _, warm, text = _times(seconds)
                rates[backend] = n * args.steps / warm
                print(f"sweep backend={backend} model={model} N={n} steps={args.steps} "
                      f"case_steps_per_s={rates[backend]:.0f} peak_mem_mb={peak:.0f} {text}", flush=True)
            if len(rates) == 2:
                print(f"ratio sweep model={model} N={n} numba_over_numpy={rates['numba'] / rates['numpy']:.1f}",
                      flush=True)
    if "history" in args.parts:
        _history(args)
    if "run" in args.parts:
        _run(args)


def _history(args):
    rates = {}
    for backend in ("numpy", "numba"):
        seconds, peak = _in_process(history, backend, args.history_steps)
        _, warm, text = _times(seconds)
        rates[backend] = args.history_steps / warm
        print(f"history backend={backend} model=stick_slip steps={args.history_steps} steps_per_s={rates[backend]:.0f} "
              f"peak_mem_mb={peak:.0f} {text}", flush=True)
    print(f"ratio history model=stick_slip steps={args.history_steps} "
          f"numba_over_numpy={rates['numba'] / rates['numpy']:.1f}", flush=True)


def _run(args):
    """python and numba processes alternate (the same machine load for both); each backend's time is
    the best of ``--repeat`` processes, as timeit reports (the machine's noise only ever adds)."""
    seconds = {"python": [], "numba": []}
    with tempfile.TemporaryDirectory() as cache:  # an empty kernel cache: the first process compiles
        cold = cli_run("numba", args.history_steps, cache)
        for _ in range(args.repeat):
            seconds["python"].append(cli_run("python", args.history_steps))
            seconds["numba"].append(cli_run("numba", args.history_steps, cache))
    best = {backend: min(times) for backend, times in seconds.items()}
    for backend, times in seconds.items():
        cold_s = f"cold_s={cold:.3f} " if backend == "numba" else ""
        print(f"run backend={backend} model=stick_slip steps={args.history_steps} {cold_s}warm_s={best[backend]:.3f} "
              f"processes={len(times)} all_s={','.join(f'{t:.2f}' for t in times)}", flush=True)
    print(f"ratio run model=stick_slip steps={args.history_steps} "
          f"numba_over_python={best['python'] / best['numba']:.1f}", flush=True)


if __name__ == "__main__":
    main()
