#!/bin/sh
# Benchmark of the full default accuracy report of chain5: `eomc accuracy
# specs/chain5.yaml` (11 methods, tolerances 1e-3 .. 1e-13, the fixed-step
# methods at three steps; the reference solution first), from a warm
# build cache.  Prints the wall-clock seconds of the whole report, the
# number of runs it made and its Pareto front, and checks the target:
# under a minute on a 2-core machine.
#
# usage: accuracy_bench.sh EOMC SOURCE_ROOT
set -eu
eomc=$1 src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export EOMC_CACHE_DIR="$dir/cache"
# build once, so that the timing is the report's alone
"$eomc" accuracy "$src/specs/chain5.yaml" --methods rk8pd --tolerances 1e-3 > /dev/null
t0=$(date +%s.%N)
"$eomc" accuracy "$src/specs/chain5.yaml" --csv "$dir/runs.csv" > "$dir/report.txt"
t1=$(date +%s.%N)
wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
runs=$(($(wc -l < "$dir/runs.csv") - 1))
ref=$(sed -n 's/.*computed in \([0-9.e-]*\) s.*/\1/p' "$dir/report.txt")
printf 'eomc accuracy specs/chain5.yaml: %s s, %d runs (the reference: %s s)\n' \
  "$wall" "$runs" "$ref"
grep -A 20 '^Pareto front' "$dir/report.txt"
awk -v t="$wall" 'BEGIN { exit !(t < 60) }' || { echo "FAIL: the report took $wall s >= 60 s"; exit 1; }
