"""``python -m dccss.mechanics``: compile (or load) every registered model's kernels, planar and spatial,
and the isolated structure's into the on-disk cache, e.g. once before parallel jobs that would each compile them."""

from dccss.mechanics.warmup import warm

warm()
