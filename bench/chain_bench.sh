#!/bin/sh
# Benchmark of the N-link chain (specs/gen_chain.sh), N = 2 5 10 20 50:
#   compile_s  time of `eomc compile`
#   ops        operation count of the generated mass_bias (adds+muls+divs+calls)
#   ops_all    of all emitted functions
#   lines      lines of generated C
#   cc_s       time of `cc -O1 -c` on the generated C (as `eomc build` compiles it)
#   ns_rhs     ns per right-hand side: generated M and h + the runtime solve
#   allocs     allocations in 1000 right-hand sides (must be 0)
#   ns_jac     ns per full Jacobian (the model's jacobian member; the
#              default compile leaves it out, the scene's rk8pd needing
#              none, so of a second compile with --jacobian auto: unrolled
#              when small, seeded when large; M and h are the same)
# and checks the targets: N = 50 compiles in < 1 s and its C in < 10 s,
# N = 5 right-hand side <= 130 ns, no allocation.
#
#   mj_ns      ns per mj_forward of the same chain in MuJoCo (its
#              contact and limits off; bench/mj_bench.c, when meson found
#              libmujoco), measured in the same run
#   fr_form, fr_ns  the same chain written with frames (gen_chain.sh N
#              --frames, a tree the recursive forms apply to): the form
#              eomc picks for it and ns per right-hand side
#   ratio      mj_ns over the faster of ns_rhs and fr_ns: how many times
#              faster eomc's is
#
# usage: chain_bench.sh EOMC SOURCE_ROOT RUNTIME_INCLUDE RUNTIME_LIB [MJ_BENCH]
# $EOMC_FLAGS: more options for `eomc compile`, e.g. "--jacobian unrolled";
# $BENCH_N: the N to run (default "2 5 10 20 50").
set -eu
eomc=$1 src=$2 inc=$3 lib=$4 mj=${5:-}
cc=${CC:-cc}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
gsl_libs=$(pkg-config --libs gsl)
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", b - a }'; }

printf '%4s %10s %8s %8s %8s %8s %8s %7s %9s %17s %9s %9s %6s\n' N compile_s ops ops_all lines \
  cc_s ns_rhs allocs ns_jac fr_form fr_ns mj_ns ratio
fail=0
for n in ${BENCH_N:-2 5 10 20 50}; do
  "$src/specs/gen_chain.sh" "$n" > "$dir/chain$n.yaml"
  t0=$(now)
  "$eomc" compile "$dir/chain$n.yaml" -o "$dir/chain$n.c" --stats ${EOMC_FLAGS:-} 2> "$dir/stats$n"
  t1=$(now)
  ops=$(awk '$1 == "mass_bias" { print $6 }' "$dir/stats$n")
  all=$(awk 'NR > 1 { s += $6 } END { print s }' "$dir/stats$n")
  lines=$(wc -l < "$dir/chain$n.c")
  t2=$(now)
  $cc -std=c11 -O1 -I"$inc" -c "$dir/chain$n.c" -o "$dir/chain$n.o"
  t3=$(now)
  if grep -q '^ \* No Jacobian of E' "$dir/chain$n.c"; then
    "$eomc" compile "$dir/chain$n.yaml" -o "$dir/chain$n.c" --jacobian auto ${EOMC_FLAGS:-}
    $cc -std=c11 -O1 -I"$inc" -c "$dir/chain$n.c" -o "$dir/chain$n.o"
  fi
  $cc -std=c11 -O1 -I"$inc" -DMODEL="chain${n}_model" "$src/bench/rhs_bench.c" \
    "$dir/chain$n.o" "$lib" $gsl_libs -lm \
    -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc -o "$dir/bench$n"
  set -- $("$dir/bench$n" 2>/dev/null)
  ns=$1 allocs=$2 nsjac=$3
  ct=$(elapsed "$t0" "$t1") cct=$(elapsed "$t2" "$t3")
  sh "$src/specs/gen_chain.sh" "$n" --frames > "$dir/frames$n.yaml"
  "$eomc" compile "$dir/frames$n.yaml" -o "$dir/frames$n.c"
  frform=$(sed -n 's/^ \* form: *\([a-z-]*\),.*/\1/p' "$dir/frames$n.c")
  $cc -std=c11 -O1 -I"$inc" -c "$dir/frames$n.c" -o "$dir/frames$n.o"
  $cc -std=c11 -O1 -I"$inc" -DMODEL="chain${n}_model" "$src/bench/rhs_bench.c" \
    "$dir/frames$n.o" "$lib" $gsl_libs -lm \
    -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc -o "$dir/fbench$n"
  set -- $("$dir/fbench$n" 2>/dev/null)
  frns=$1
  mjns=- ratio=-
  if [ -n "$mj" ]; then
    sh "$src/specs/gen_chain.sh" "$n" --mjcf > "$dir/chain$n.xml"
    mjns=$("$mj" "$dir/chain$n.xml")
    ratio=$(awk -v a="$mjns" -v b="$ns" -v c="$frns" \
      'BEGIN { f = c + 0 < b + 0 ? c : b; printf "%.1f", a / f }')
  fi
  printf '%4d %10s %8d %8d %8d %8s %8s %7d %9s %17s %9s %9s %6s\n' "$n" "$ct" "$ops" "$all" "$lines" \
    "$cct" "$ns" "$allocs" "$nsjac" "$frform" "$frns" "$mjns" "$ratio"
  [ "$allocs" -eq 0 ] || { echo "FAIL: N = $n allocates in the right-hand side"; fail=1; }
  if [ "$n" -eq 50 ]; then
    awk -v t="$ct" 'BEGIN { exit !(t < 1) }' || { echo "FAIL: N = 50 compile $ct s >= 1 s"; fail=1; }
    awk -v t="$cct" 'BEGIN { exit !(t < 10) }' || { echo "FAIL: N = 50 cc $cct s >= 10 s"; fail=1; }
  fi
  [ "$n" -eq 20 ] && ops20=$ops
  if [ "$n" -eq 50 ] && [ -n "${ops20:-}" ]; then
    # polynomial growth: the mass matrix and bias (the Jacobian changes
    # method with size, so its total says less) ~ N^p, p well below 4
    p=$(awk -v a="$ops20" -v b="$ops" 'BEGIN { printf "%.2f", log(b / a) / log(2.5) }')
    echo "mass_bias code grows as N^$p between N = 20 and 50"
    awk -v p="$p" 'BEGIN { exit !(p < 4) }' || { echo "FAIL: growth exponent $p >= 4"; fail=1; }
  fi
  if [ "$n" -eq 5 ]; then
    awk -v t="$ns" 'BEGIN { exit !(t <= 130) }' || { echo "FAIL: N = 5 right-hand side $ns ns > 130 ns"; fail=1; }
  fi
done
exit $fail
