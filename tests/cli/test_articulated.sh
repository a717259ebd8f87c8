#!/bin/sh
# The articulated-body form (forms/articulated.c) as a user runs it (TAP),
# on a 5-body tree of 3-axis joints (specs/gen_tree.sh 5: 15 coordinates;
# Lagrange's form differentiates the energies and factors its M, the
# articulated-body one recurses over the tree: two independent solves):
#  - --accel at a state with every angle and rate set agrees with
#    Lagrange's to 1e-11 of the largest |q''|;
#  - a run to t = 1 at rtol 1e-12 ends where Lagrange's does, to 1e-8,
#    and its energy (T = q'.M q'/2 by the form's mass_times) starts at
#    Lagrange's, to the 10 digits the summary prints;
#  - at gimbal lock (the pelvis's x turn at pi/2 lines its z and y turns
#    up) M is singular: --accel stops with exit 3 and names the pivot;
#  - past 24 coordinates the factored forms still unroll their LDL^T where
#    M's branch-induced zeros make it no longer than a dense 24 (gen_tree
#    9, 27 coordinates): newton-euler's --accel from it equals the
#    articulated-body recursion's to 1e-11; a dense M of 30 (the particle
#    chain) is left to the runtime (accel member NULL);
#  - further on, a tree's M goes to the runtime with its tree of nonzeros
#    (gen_tree 20, 60 coordinates: mass_parent), which factors it by LTDL:
#    newton-euler's --accel equals the articulated-body recursion's (as
#    tables) to 1e-11, and at gimbal lock it stops with exit 3 and names
#    the pivot;
#  - sliding joints (tests/sim/specs/slide_tree.yaml: a cart on a rail, a
#    pole turning on it, a slider along the pole, an arm): --accel of the
#    articulated-body and newton-euler forms, and the articulated-body
#    tables (--code tables), equal Lagrange's to 1e-12;
#  - a free joint is one joint of six degrees of freedom in the recursion
#    (spatial.h's SvFree): tests/cli/free_tilted.yaml, a floating base
#    whose position is written along slanted directions in a tilted frame
#    (G^-1 not the identity) with an arm on a hinge and a spring, at a
#    state with every rate set: --accel equals the Gibbs-Appell form's in
#    extended precision (--accel-extended; Lagrange's form takes no
#    speeds) to 1e-13 of the largest |q''|; with a rotor's inertia on one
#    of its coordinates, which keeps it three slides and a ball, it equals
#    the Newton-Euler form's (M factored; Gibbs-Appell takes no rotors).
# usage: test_articulated.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"

sh "$src/specs/gen_tree.sh" 5 > "$tmp/tree5.yaml"
init=$(init "$tmp/tree5.yaml")
# shellcheck disable=SC2086 # $init is a list of options
"$eomc" run "$tmp/tree5.yaml" --form articulated-body $init --accel > "$tmp/ab.acc" &&
  "$eomc" run "$tmp/tree5.yaml" --form lagrange $init --accel > "$tmp/lag.acc"
st=$?
d=$(accel_diff "$tmp/ab.acc" "$tmp/lag.acc" 15)
[ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-11) }'
ok $? "--accel at a full state: articulated-body = lagrange to $d of max |q''|"

# shellcheck disable=SC2086
"$eomc" run "$tmp/tree5.yaml" --form articulated-body $init --t-end 1 --rtol 1e-12 \
    --atol 1e-12 --summary 2> "$tmp/ab.sum" | tail -n 1 > "$tmp/ab.row" &&
  "$eomc" run "$tmp/tree5.yaml" --form lagrange $init --t-end 1 --rtol 1e-12 --atol 1e-12 \
    --summary 2> "$tmp/lag.sum" | tail -n 1 > "$tmp/lag.row"
st=$?
d=$(row_diff "$tmp/ab.row" "$tmp/lag.row" 31)
[ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-8) }'
ok $? "a run to t = 1: articulated-body ends where lagrange does, to $d"
# its energy's T is q'.M q'/2 by mass_times; lagrange's is the spec's T
e1=$(tr '\n' ' ' < "$tmp/ab.sum" | sed -n 's/.*E started at \([-0-9.e+]*\);.*/\1/p')
e2=$(tr '\n' ' ' < "$tmp/lag.sum" | sed -n 's/.*E started at \([-0-9.e+]*\);.*/\1/p')
[ -n "$e1" ] && [ "$e1" = "$e2" ]
ok $? "E = T + V with T = q'.M q'/2: $e1, lagrange's $e2 (the 10 digits printed)"

"$eomc" run "$tmp/tree5.yaml" --form articulated-body --init pelvis_b=1.5707963267948966 \
    --accel > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 3 ] && grep -q 'mass matrix is singular or not positive definite' "$tmp/err" &&
  grep -q 'coordinate pelvis_' "$tmp/err"
ok $? "gimbal lock: exit $st, the singular pivot named"

sh "$src/specs/gen_tree.sh" 9 > "$tmp/tree9.yaml"
init=$(init "$tmp/tree9.yaml")
"$eomc" compile "$tmp/tree9.yaml" --form newton-euler -o "$tmp/ne9.c" &&
  grep -q '^    \.accel = tree9_accel,$' "$tmp/ne9.c"
st1=$?
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree9.yaml" --form newton-euler $init --accel > "$tmp/ne.acc" &&
  "$eomc" run "$tmp/tree9.yaml" --form articulated-body $init --accel > "$tmp/ab.acc"
st=$?
d=$(accel_diff "$tmp/ab.acc" "$tmp/ne.acc" 27)
[ $st1 -eq 0 ] && [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-11) }'
ok $? "27 coordinates: newton-euler's unrolled sparse LDL^T = the recursion, to $d"
sh "$src/specs/gen_chain.sh" 30 > "$tmp/chain30.yaml"
"$eomc" compile "$tmp/chain30.yaml" --form lagrange -o "$tmp/c30.c" &&
  grep -q '^    \.accel = NULL, /\* more than 24 coordinates' "$tmp/c30.c"
ok $? "a dense M of 30 coordinates: no unrolled solve, the runtime's"

sh "$src/specs/gen_tree.sh" 20 > "$tmp/tree20.yaml"
init=$(init "$tmp/tree20.yaml")
"$eomc" compile "$tmp/tree20.yaml" --form newton-euler -o "$tmp/ne20.c" &&
  grep -q '^    \.mass_parent = mass_parent, /\* M.s factorizations by LTDL' "$tmp/ne20.c" &&
  grep -q '^    \.accel = NULL, /\* .*the runtime solves, by LTDL' "$tmp/ne20.c"
st1=$?
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree20.yaml" --form newton-euler $init --accel > "$tmp/ne.acc" &&
  "$eomc" run "$tmp/tree20.yaml" --code tables $init --accel > "$tmp/ab.acc"
st=$?
d=$(accel_diff "$tmp/ab.acc" "$tmp/ne.acc" 60)
[ $st1 -eq 0 ] && [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-11) }'
ok $? "60 coordinates: newton-euler's M factored by LTDL in the runtime = the recursion, to $d"
"$eomc" run "$tmp/tree20.yaml" --form newton-euler --init pelvis_b=1.5707963267948966 \
    --accel > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 3 ] && grep -q 'mass matrix is singular or not positive definite' "$tmp/err" &&
  grep -q 'coordinate pelvis_' "$tmp/err"
ok $? "LTDL at gimbal lock: exit $st, the singular pivot named"

sl="$src/tests/sim/specs/slide_tree.yaml"
in="--init x=0.3 --init th=0.4 --init y=0.2 --init ph=-0.5 --init x'=0.7 --init th'=-1.1"
in="$in --init y'=0.3 --init ph'=0.9"
# shellcheck disable=SC2086
"$eomc" run "$sl" --form lagrange $in --accel > "$tmp/sl.lag" &&
  "$eomc" run "$sl" --form articulated-body $in --accel > "$tmp/sl.ab" &&
  "$eomc" run "$sl" --form newton-euler $in --accel > "$tmp/sl.ne"
st=$?
d=$(accel_diff "$tmp/sl.lag" "$tmp/sl.ab" 4) d2=$(accel_diff "$tmp/sl.lag" "$tmp/sl.ne" 4)
[ $st -eq 0 ] && awk -v d="$d2" 'BEGIN { exit !(d < 1e-12) }' &&
  [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-12) }'
ok $? "sliding joints: articulated-body and newton-euler --accel = lagrange's, to $d and $d2"
# shellcheck disable=SC2086
"$eomc" compile "$sl" --code tables -o "$tmp/sl.c" && grep -q '^#include "eomc_tree.h"' "$tmp/sl.c" &&
  "$eomc" run "$sl" --code tables $in --accel > "$tmp/sl.tab"
st=$?
d=$(accel_diff "$tmp/sl.lag" "$tmp/sl.tab" 4)
[ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-12) }'
ok $? "sliding joints in the tables: --accel = lagrange's, to $d"

ft="$src/tests/cli/free_tilted.yaml"
sed 's/^effects:$/effects:\n  rotor: {kinetic: "0.02\/2*y'"'"'^2"}/' "$ft" > "$tmp/ft_rotor.yaml"
for f in "$ft:gibbs-appell --accel-extended" "$tmp/ft_rotor.yaml:newton-euler --accel"; do
  # shellcheck disable=SC2086 # the form and its option
  "$eomc" run "${f%%:*}" --form articulated-body --accel > "$tmp/ft.ab" 2> /dev/null &&
    "$eomc" run "${f%%:*}" --form ${f#*:} > "$tmp/ft.ref" 2> /dev/null
  st=$?
  d=$(accel_diff "$tmp/ft.ref" "$tmp/ft.ab" 7)
  [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-13) }'
  ok $? "a free joint ($(basename "${f%%:*}")): articulated-body = ${f#*:}, to $d"
done
tap_end
