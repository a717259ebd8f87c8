#!/bin/sh
# Two seconds of MuJoCo's humanoid dropped onto its floor, eomc beside
# MuJoCo (issue 44's speed check).
#
# eomc: the model imported as `eomc import` writes it (contacts, limits,
# control clamps on): first with its contacts' friction at 1e-7 (its CPU
# seconds, steps and the ratio to MuJoCo's step, below), then without
# it; let go at qpos0 at rest, run to t = 2 at each tolerance with --error against its
# extended-precision reference: CPU seconds of the run alone
# (cpu_seconds), steps, flips, error_max (the largest error over
# coordinates and speeds at the 0.01 s rows), and the cheapest run with
# error_max <= 1e-6.
#
# MuJoCo: mj_step at the model's own step (0.005) and at half of it
# (bench/mj_contact.c fall), CPU seconds of the stepping; its error taken
# as the largest difference over qpos and qvel at the same 0.01 s rows
# between the two (its own law, soft contact with friction, differs from
# eomc's, so eomc's reference cannot measure it: docs/benchmarks.md).
# usage: drop_bench.sh EOMC MJ_CONTACT [MODEL]  ($BENCH_TOLS: the tolerances)
set -eu
eomc=$1 mjc=$2
model=${3:-${BENCH_HUMANOID:-/usr/share/mujoco/model/humanoid/humanoid.xml}}
[ -f "$model" ] || { echo "drop_bench: no $model (Debian: libmujoco-samples)"; exit 77; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export EOMC_CACHE_DIR="$dir/cache"

"$eomc" import "$model" -o "$dir/model.yaml" 2> /dev/null
"$eomc" run "$dir/model.yaml" --t-end 2 --rtol 1e-7 --atol 1e-7 --stats -o /dev/null 2> "$dir/err" &&
  fric=$(awk '$1 == "cpu_seconds" { c = $2 } $1 == "steps" { s = $2 } END { print c, s }' "$dir/err") &&
  echo "eomc with the contacts' friction, 1e-7: runs to t = 2, cpu_s ${fric% *}, steps ${fric#* }" ||
  { fric=; echo "eomc with the contacts' friction, 1e-7: stops ($(grep -m1 'error:' "$dir/err" | cut -c1-160)...)"; }
sed 's/, friction: [0-9.e+-]*}$/}/' "$dir/model.yaml" > "$dir/frictionless.yaml"
model_xml=$model model=$dir/frictionless.yaml
echo "eomc: $model_xml without its contacts' friction, t = 0 .. 2, --error against its reference"
printf '%-8s %10s %8s %8s %12s\n' tol cpu_s steps flips error_max
best=
for tol in ${BENCH_TOLS:-1e-5 1e-6 1e-7 1e-8}; do
  "$eomc" run "$model" --t-end 2 --rtol $tol --atol $tol --error --stats -o /dev/null \
    2> "$dir/err" || { echo "$tol: failed: $(grep -v warning "$dir/err" | head -c 300)"; continue; }
  set -- $(awk '$1 == "cpu_seconds" { c = $2 } $1 == "steps" { s = $2 } $1 == "switches" { f = $2 }
                $1 == "error_max" { e = $2 } END { print c, s, f, e }' "$dir/err")
  printf '%-8s %10s %8s %8s %12s\n' $tol "$1" "$2" "$3" "$4"
  if [ -z "$best" ] && awk -v e="$4" 'BEGIN { exit !(e <= 1e-6) }'; then
    best="$tol $1"
  fi
  grep "warning: the reference and the run switched differently" "$dir/err" | head -1 | cut -c1-200
done

echo "MuJoCo: mj_step from qpos0 at rest to t = 2"
"$mjc" "$model_xml" fall 2 0.005 0.01 > "$dir/h"
"$mjc" "$model_xml" fall 2 0.0025 0.01 > "$dir/h2"
cpu=$(awk 'NR == 1 { print $2 }' "$dir/h")
err=$(awk 'NR == FNR { if (FNR > 1) for (i = 2; i <= NF; i++) a[FNR, i] = $i; next }
  FNR > 1 { for (i = 2; i <= NF; i++) { d = $i - a[FNR, i]; d = d < 0 ? -d : d; if (d > m) m = d } }
  END { printf "%.3g", m }' "$dir/h" "$dir/h2")
echo "step 0.005: cpu_s $cpu, its error against its halved step $err"
[ -z "$fric" ] || echo "eomc with friction at 1e-7: ${fric% *} s of CPU; eomc/MuJoCo" \
  "$(awk -v a="${fric% *}" -v b="$cpu" 'BEGIN { printf "%.0f", a / b }')"
if [ -n "$best" ]; then
  set -- $best
  echo "eomc to 1e-6 (tol $1): $2 s of CPU; MuJoCo at its step: $cpu s with an error of $err:" \
    "eomc/MuJoCo $(awk -v a="$2" -v b="$cpu" 'BEGIN { printf "%.1f", a / b }')"
fi
