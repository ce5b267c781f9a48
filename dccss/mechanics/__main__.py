"""``python -m dccss.mechanics [--jobs N]``: compile (or load) every registered model's kernels, planar and
spatial, and the isolated structure's into the on-disk cache, in N processes (default: one per core), e.g.
once before parallel jobs that would each compile them."""

import argparse
import os
import time

from dccss.mechanics.warmup import warm

if __name__ == "__main__":  # not again in the processes that compile the parts
    parser = argparse.ArgumentParser(prog="python -m dccss.mechanics", description=__doc__.split(":", 1)[1].strip())
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="processes compiling in parallel (default: one per core, %(default)s here)")
    args = parser.parse_args()
    if args.jobs < 1:
        parser.error(f"--jobs: at least 1, got {args.jobs}")
    start = time.monotonic()
    done = warm(args.jobs)
    print(f"dccss: {len(done)} kernels compiled or loaded in {time.monotonic() - start:.1f} s: {', '.join(done)}")
