#!/usr/bin/env bash
# Time the full reproduction from empty results/ and figures/ (dependencies installed), in a
# temporary copy of the project so the checkout is untouched, with the compiled backend's kernel
# cache cold (an empty NUMBA_CACHE_DIR, as on a fresh clone) and warm (the same cache after
# `python -m dccss.mechanics.compiled` compiled both kernels into it). DCCSS_BACKEND is passed on
# (default auto). Usage: bash benchmarks/workflow.sh [cold] [warm]   (default: both)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cache="$(mktemp -d)"
trap 'rm -rf "$cache"' EXIT
export NUMBA_CACHE_DIR="$cache"

reproduce() {
  local work
  work="$(mktemp -d)"
  cp -r "$root/Snakefile" "$root/config" "$root/workflow" "$root/profiles" "$work/"
  (
    cd "$work"
    start=$(date +%s.%N)
    "$root/.venv/bin/snakemake" --profile profiles/default --quiet all > snakemake.out 2>&1 || { tail -20 snakemake.out; exit 1; }
    end=$(date +%s.%N)
    numba=$({ grep -rl "backend numba" logs 2>/dev/null || true; } | wc -l)
    printf 'workflow full_reproduction backend=%s cache=%s seconds=%.1f files_nc=%d files_png=%d jobs_on_numba=%d\n' \
      "${DCCSS_BACKEND:-auto}" "$1" "$(echo "$end - $start" | bc)" "$(find results -name '*.nc' | wc -l)" \
      "$(find figures -name '*.png' | wc -l)" "$numba"
  )
  rm -rf "$work"
}

for mode in "${@:-cold warm}"; do
  for m in $mode; do
    if [ "$m" = cold ]; then
      rm -rf "${cache:?}"/*
    else
      "$root/.venv/bin/python" -m dccss.mechanics.compiled
    fi
    reproduce "$m"
  done
done
