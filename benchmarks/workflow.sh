#!/usr/bin/env bash
# Time the full reproduction from empty results/ and figures/ (dependencies installed), in a
# temporary copy of the project so the checkout is untouched. Usage: bash benchmarks/workflow.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp -r "$root/Snakefile" "$root/config" "$root/workflow" "$root/profiles" "$work/"
cd "$work"
start=$(date +%s.%N)
"$root/.venv/bin/snakemake" --profile profiles/default --quiet all > snakemake.out 2>&1 || { tail -20 snakemake.out; exit 1; }
end=$(date +%s.%N)
jobs=$(grep -c "^Finished job\|Finished jobid" .snakemake/log/*.log || true)
printf 'workflow full_reproduction seconds=%.1f files_nc=%d files_png=%d\n' "$(echo "$end - $start" | bc)" \
  "$(find results -name '*.nc' | wc -l)" "$(find figures -name '*.png' | wc -l)"
