#!/usr/bin/env bash
# Time the full reproduction from empty results/ and figures/ (dependencies installed), in a
# temporary copy of the project so the checkout is untouched, with the compiled backend's kernel
# cache cold (an empty NUMBA_CACHE_DIR, as on a fresh clone) and warm (the same cache after
# `python -m dccss.mechanics` compiled the kernels into it). DCCSS_BACKEND is passed on
# (default auto).
#
# Usage: bash benchmarks/workflow.sh [cold] [warm]   (default: both)
#   BASELINE=<git revision>  also time that revision's reproduction (its Snakefile, config, workflow
#                            and dccss, from `git archive`) in the same run, alternating with this
#                            checkout's, so that the two are compared under the same machine load
#   REPEAT=<n>               run each timing n times (default 1)
#   ARGS="..."               more snakemake arguments for every run, e.g. "--configfile
#                            config/studies/bidirectional.yaml" to time a study instead
#   CHECKOUT_ARGS="..."      more snakemake arguments for this checkout's runs, e.g. "--configfile
#                            my.yaml" with a config that draws what BASELINE drew (a revision without
#                            the animations: config/config.yaml without its animations section)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cache="$(mktemp -d)"
base=""
trap 'rm -rf "$cache" ${base:+"$base"}' EXIT
export NUMBA_CACHE_DIR="$cache"

sources=("$root")
labels=("checkout")
if [ -n "${BASELINE:-}" ]; then
  base="$(mktemp -d)"
  git -C "$root" archive "$BASELINE" Snakefile config workflow profiles dccss | tar -x -C "$base"
  sources+=("$base")
  labels+=("$(git -C "$root" rev-parse --short "$BASELINE")")
fi

reproduce() {  # reproduce SOURCE LABEL CACHE [SNAKEMAKE ARGUMENTS...]
  local work
  work="$(mktemp -d)"
  cp -r "$1/Snakefile" "$1/config" "$1/workflow" "$1/profiles" "$work/"
  (
    cd "$work"
    export PYTHONPATH="$1"  # that source's dccss, before the installed one
    start=$(date +%s.%N)
    "$root/.venv/bin/snakemake" --profile profiles/default --quiet all "${@:4}" > snakemake.out 2>&1 ||
      { tail -20 snakemake.out; exit 1; }
    end=$(date +%s.%N)
    numba=$({ grep -rl "backend numba" logs 2>/dev/null || true; } | wc -l)
    printf 'workflow full_reproduction source=%s backend=%s cache=%s seconds=%.1f files_nc=%d files_png=%d jobs_on_numba=%d\n' \
      "$2" "${DCCSS_BACKEND:-auto}" "$3" "$(echo "$end - $start" | bc)" "$(find results -name '*.nc' | wc -l)" \
      "$(find figures -name '*.png' | wc -l)" "$numba"
  )
  rm -rf "$work"
}

for ((r = 0; r < ${REPEAT:-1}; r++)); do
  for mode in ${@:-cold warm}; do
    for k in "${!sources[@]}"; do
      if [ "$mode" = cold ]; then
        rm -rf "${cache:?}"/*
      else
        PYTHONPATH="${sources[$k]}" "$root/.venv/bin/python" -m dccss.mechanics 2>/dev/null ||
            PYTHONPATH="${sources[$k]}" "$root/.venv/bin/python" -m dccss.mechanics.compiled  # older revisions
      fi
      if [ "$k" = 0 ]; then
        # shellcheck disable=SC2086  # CHECKOUT_ARGS is split into words on purpose
        reproduce "${sources[$k]}" "${labels[$k]}" "$mode" ${ARGS:-} ${CHECKOUT_ARGS:-}
      else
        # shellcheck disable=SC2086
        reproduce "${sources[$k]}" "${labels[$k]}" "$mode" ${ARGS:-}
      fi
    done
  done
done
