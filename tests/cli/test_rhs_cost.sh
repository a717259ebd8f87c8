#!/bin/sh
# What one joint equality costs an arm's right-hand side (TAP), counted in
# instructions: valgrind's callgrind, inside eomc_sim_accel and what it
# calls (--toggle-collect), a count the machine's load does not move, where
# the robots benchmark's nanoseconds vary by a tenth from run to run.  The
# arms are tests/import/models/robots/arm_gripper.xml (8 coordinates, a
# joint equality coupling the fingers: one row by unit loads, kkt.c) and
# arm_gripper_unconstrained.xml (the same arm, the equality off), each
# compiled as eomc build compiles it (-O1) and called by rhs_calls.c at the
# benchmark's state:
#  - the instructions per call, the difference of 3 000 calls and 1 000
#    over 2 000 (so that the first call's choice of rows is not counted);
#    every call EOMC_OK;
#  - the constrained arm at most 1.2 times the unconstrained (issue 43
#    asks 1.3; 1.28 before kkt.c's bookkeeping of a single row was
#    trimmed, 1.15 after, at gcc -O2 and -O3).
# Only on an optimized runtime: at -O0 the library's own loops cost what
# no user runs (1.20 there).
# usage: test_rhs_cost.sh VALGRIND EOMC SOURCE_ROOT BUILD_ROOT OPTIMIZATION
set -u
valgrind=$1 eomc=$2 src=$3 build=$4 opt=$5
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
case $opt in
  plain | 0 | g)
    echo "1..0 # SKIP the runtime is not optimized (-Doptimization=$opt): the counts are an optimized library's"
    exit 0 ;;
esac
cc=${CC:-cc}
inc="$src/runtime/include" lib="$build/runtime/libeomcrt.a" gsl=$(pkg-config --libs gsl)
robots="$src/tests/import/models/robots"

# count NAME CALLS: eomc_sim_accel's instructions over CALLS calls
count() {
  "$valgrind" --tool=callgrind --toggle-collect=eomc_sim_accel \
    --callgrind-out-file="$tmp/$1.$2.cg" "$tmp/$1" "$2" > "$tmp/$1.$2.out" 2> "$tmp/$1.$2.err" &&
    grep -q '^0 ' "$tmp/$1.$2.out" && sed -n 's/.*Collected : *\([0-9]*\)$/\1/p' "$tmp/$1.$2.err"
}

for arm in arm_gripper arm_gripper_unconstrained; do
  if ! "$eomc" compile "$robots/$arm.xml" -o "$tmp/$arm.c" 2> "$tmp/$arm.err"; then
    if grep -q 'MuJoCo' "$tmp/$arm.err"; then
      echo "1..0 # SKIP eomc import needs MuJoCo: $(head -1 "$tmp/$arm.err")"
      exit 0
    fi
    sed 's/^/# /' "$tmp/$arm.err"
  fi
  name=$(sed -n 's/^const eomc_model \([A-Za-z0-9_]*\)_model = {$/\1/p' "$tmp/$arm.c")
  # shellcheck disable=SC2086 # $cc and $gsl are lists
  $cc -std=c11 -O1 -I"$inc" -c "$tmp/$arm.c" -o "$tmp/$arm.o" &&
    $cc -std=c11 -O1 -I"$inc" -DMODEL="${name}_model" "$src/tests/cli/rhs_calls.c" \
      "$tmp/$arm.o" "$lib" $gsl -lm -pthread -o "$tmp/$arm"
  ok $? "$arm: compiled, and linked with rhs_calls.c"
  c1=$(count "$arm" 1000) && c3=$(count "$arm" 3000)
  st=$?
  per=$(awk -v a="${c1:-}" -v b="${c3:-}" 'BEGIN { if (a == "" || b == "") print "nan"; else printf "%.1f\n", (b - a) / 2000 }')
  [ $st -eq 0 ] && [ "$per" != nan ]
  ok $? "$arm: $per instructions per eomc_sim_accel, every call EOMC_OK"
  eval "per_$arm=\$per"
done

# shellcheck disable=SC2154 # set by the eval above
ratio=$(awk -v a="$per_arm_gripper" -v b="$per_arm_gripper_unconstrained" \
  'BEGIN { if (a == "nan" || b == "nan" || b <= 0) print "nan"; else printf "%.3f\n", a / b }')
awk -v r="$ratio" 'BEGIN { exit !(r == r + 0 && r <= 1.2) }'
ok $? "the arm's one joint equality costs $ratio times its unconstrained right-hand side (<= 1.2)"

tap_end
