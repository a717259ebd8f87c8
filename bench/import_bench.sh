#!/bin/sh
# MuJoCo's own sample models (Debian's libmujoco-samples) imported and
# built by eomc, timed beside MuJoCo's mj_forward on the same model
# (issue 23's figures).  One row per model found:
#   model      the file under /usr/share/mujoco/model
#   coords     eomc's coordinates (MuJoCo's nq: a free joint has 7)
#   build_s    wall time of `eomc build MODEL.xml`: import, derive, cc,
#              with an empty object cache (its own $EOMC_CACHE_DIR)
#   lib_s      then `eomc build MODEL.xml --shared` (Python's library: the
#              Jacobian and the Taylor series added, so other C)
#   form       the form eomc chose, and its code (straight or tables)
#   ns_rhs     ns per right-hand side (bench/rhs_bench.c: eomc_sim_accel,
#              the constraints' multipliers included) at q_i = 0.3/(i+1),
#              linked with the objects eomc build compiled (its cache's)
#   mj_ns      ns per mj_forward (bench/mj_bench.c: contact, limits and
#              friction loss off), at MuJoCo's same-rule state
#   ratio      mj_ns / ns_rhs (above 1: eomc is the faster)
#
# usage: import_bench.sh EOMC SOURCE_ROOT RUNTIME_INCLUDE RUNTIME_LIB [MJ_BENCH]
# $BENCH_MODELS: the models to run (default: the three below), each under
# /usr/share/mujoco/model or a path of its own (the robots benchmark's).
# $BENCH_BUILD: options for eomc build (--portable: the model's code for
# any CPU of its kind, as MuJoCo's Debian package is built, not for this
# one; docs/benchmarks.md gives both).
# A model eomc cannot build or run gets a row that says so, and the rest
# still run.
set -eu
eomc=$1 src=$2 inc=$3 lib=$4 mj=${5:-}
samples=/usr/share/mujoco/model
gsl_libs=$(pkg-config --libs gsl)
cc=${CC:-cc}
cc=${cc#ccache } # build times are the compiler's, not a compiler cache's
export CC="$cc"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

printf '%-28s %6s %8s %6s %-24s %10s %10s %7s\n' model coords build_s lib_s form ns_rhs mj_ns \
  ratio
for rel in ${BENCH_MODELS:-humanoid/humanoid.xml humanoid/22_humanoids.xml \
    humanoid100/humanoid100.xml}; do
  case $rel in /*) model=$rel rel=$(basename "$rel") ;; *) model=$samples/$rel ;; esac
  if [ ! -e "$model" ]; then
    echo "$rel: not installed (apt-get install libmujoco-samples)"
    continue
  fi
  cache="$dir/cache-$(basename "$rel" .xml)"
  rm -rf "$cache"
  # MuJoCo is timed with contacts off (mj_bench.c): eomc's effect contacts off too
  effs=$("$eomc" import "$model" 2> /dev/null |
    sed -n '/^effects:/,/^[a-z]/s/^  \([A-Za-z_0-9]*\):.*/\1/p' | grep -vx contacts | paste -sd, -)
  t0=$(now)
  # shellcheck disable=SC2086 # $BENCH_BUILD is a list of options
  if ! EOMC_CACHE_DIR="$cache" "$eomc" build "$model" --effects "$effs" ${BENCH_BUILD:-} -o "$dir/sim" \
      2> "$dir/build.err"; then
    printf '%-28s fails to build: %s\n' "$rel" "$(grep -v 'warning: dropped' "$dir/build.err" | head -1)"
    continue
  fi
  t1=$(now)
  # the right-hand side as eomc build compiled it: its objects, but the main
  objs=
  for o in "$cache"/objects/*.o; do
    nm --defined-only "$o" | grep -q ' T main$' || objs="$objs $o"
  done
  "$eomc" compile "$model" --effects "$effs" -o "$dir/m.c" 2> /dev/null
  name=$(sed -n 's/^const eomc_model \([A-Za-z0-9_]*\)_model = {$/\1/p' "$dir/m.c")
  form=$(sed -n 's/^ \* form: *\([a-z-]*\).*/\1/p' "$dir/m.c" | head -1)
  code=straight
  grep -q '#include "eomc_tree.h"' "$dir/m.c" && code=tables
  coords=$(sed -n 's/^ *\.nq = \([0-9]*\),.*/\1/p' "$dir/m.c" | head -1)
  # shellcheck disable=SC2086 # $objs and $gsl_libs are lists
  $cc -std=c11 -O1 -I"$inc" -DMODEL="${name}_model" "$src/bench/rhs_bench.c" $objs \
    "$lib" $gsl_libs -lm -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc -o "$dir/rhs"
  t2=$(now)
  libs=-
  # shellcheck disable=SC2086
  EOMC_CACHE_DIR="$cache" "$eomc" build "$model" --effects "$effs" ${BENCH_BUILD:-} --shared -o "$dir/lib.so" \
      2> /dev/null &&
    libs=$(elapsed "$t2" "$(now)")
  ns=$("$dir/rhs" 2> /dev/null | awk '{ print $1 }')
  mjns=- ratio=-
  if [ -n "$mj" ]; then
    mjns=$("$mj" "$model")
    ratio=$(awk -v a="$mjns" -v b="$ns" 'BEGIN { printf "%.2f", a / b }')
  fi
  printf '%-28s %6s %8s %6s %-24s %10s %10s %7s\n' "$rel" "$coords" \
    "$(elapsed "$t0" "$t1")" "$libs" "$form/$code" "$ns" "$mjns" "$ratio"
  rm -rf "$cache"
done
