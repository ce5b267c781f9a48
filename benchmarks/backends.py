"""The numpy and the compiled (numba) backends side by side: sweeps and one long history.

Each measurement runs in a fresh process (its own peak resident memory; the compiled one
loads its kernels from the on-disk cache, or compiles them if the cache is empty):

* ``compile``: the compiled kernels built from an empty cache (a temporary NUMBA_CACHE_DIR);
* ``sweep``: N cases of DFP1-type devices with pad angles alpha21 spread over 6..12 deg, 1000
  steps each (sine of 0.27 m at 30 rad/s over 1 s, dt = 0.001 s), reduced to per-case
  summaries (``dccss.studies.sweep.summarize`` / ``dccss.mechanics.compiled.summarize``), as benchmarks/sweep.py;
* ``history``: one stick-slip history of DFP1, the same sine over 30 s at dt = 0.001 s
  (30 000 steps; ``dccss.mechanics.models.stick_slip`` / ``dccss.mechanics.compiled.stick_slip``).

cold_s is the first call in the process (the compiled backend: loading or compiling its
kernels), warm_s the second; the numpy backend runs once (it has nothing to warm up). Lines:

    sweep backend=numba model=compliant N=10000 steps=1000 case_steps_per_s=... peak_mem_mb=... cold_s=... warm_s=...
    ratio sweep model=compliant N=10000 numba_over_numpy=...

Run: python benchmarks/backends.py [--sizes 10000] [--big 100000] [--steps 1000] [--history-steps 30000]
"""

import argparse
import multiprocessing as mp
import os
import resource
import tempfile
import time

MODELS = ("compliant", "stick_slip")


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


def sweep(backend, model, n, steps, queue):
    import numpy as np

    from dccss.excitation import Sine

    summarize = _summarize(backend)
    geometry = _geometry(n)
    Xg = Sine(0.27, 30.0, 1.0).displacement(np.arange(steps + 1) * (1.0 / steps))
    out, times = _timed(lambda: summarize(model, geometry, Xg), 1 if backend == "numpy" else 2)
    assert np.isfinite(out["theta2_max_abs"]).all()
    queue.put((times, _peak_mb()))


def _summarize(backend):
    if backend == "numpy":
        from dccss.studies.sweep import summarize
    else:
        from dccss.mechanics.compiled import summarize
    return summarize


def history(backend, steps, queue):
    import numpy as np

    from dccss.excitation import Sine, step_times
    from dccss.paper.prototypes import DFP1

    if backend == "numpy":
        from dccss.mechanics.models import stick_slip
    else:
        from dccss.mechanics.compiled import stick_slip
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
    args = parser.parse_args()
    if not args.no_compile:
        seconds, peak = _in_process(compile_cold)
        print(f"compile backend=numba models={','.join(MODELS)} seconds={seconds[0]:.1f} peak_mem_mb={peak:.0f}",
              flush=True)
    for model in MODELS:
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
    rates = {}
    for backend in ("numpy", "numba"):
        seconds, peak = _in_process(history, backend, args.history_steps)
        _, warm, text = _times(seconds)
        rates[backend] = args.history_steps / warm
        print(f"history backend={backend} model=stick_slip steps={args.history_steps} steps_per_s={rates[backend]:.0f} "
              f"peak_mem_mb={peak:.0f} {text}", flush=True)
    print(f"ratio history model=stick_slip steps={args.history_steps} "
          f"numba_over_numpy={rates['numba'] / rates['numpy']:.1f}", flush=True)


if __name__ == "__main__":
    main()
