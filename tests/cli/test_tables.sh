#!/bin/sh
# The articulated-body form as loops over the model's tables (--code
# tables, runtime/include/eomc_tree.h) as a user runs it (TAP).  Each check sets
# it against Lagrange's form, derived by differentiating the energies and
# solved by factoring M: an independent derivation and solve.
#  - --accel at a state with every angle and rate set, on a 5-body tree of
#    3-axis joints (specs/gen_tree.sh 5) and on tests/sim/specs/
#    branched_tree.yaml (a fixed unit axis, fixed turns, a particle, forces
#    besides gravity): equal to 1e-11 of the largest |q''|;
#  - a run to t = 1 at rtol 1e-12 ends where Lagrange's does (1e-8), and
#    its energy E = T + V (T = q'.M q'/2 by the recursion) starts where
#    Lagrange's does, to the 10 digits the summary prints;
#  - --linearize (mass_bias by the recursion's columns) gives the A of the
#    straight-line articulated-body code to 1e-11 of max |A|;
#  - units: with the mass unit made 1e-6 kg, the length unit 1e4 m and the
#    time unit 1e3 s (m * 1e6, l * 1e-4, g * 1e-4 / 1e6, rates / 1e3),
#    q'' * 1e6 is the same to 1e-11 (no threshold of the loops is absolute);
#  - the banner says the code is tables, and the default picks tables past
#    the size of straight-line solve that compiles quickly (gen_tree 40),
#    not below it (gen_tree 5).
# usage: test_tables.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"

sh "$src/specs/gen_tree.sh" 5 > "$tmp/tree5.yaml"
cp "$src/tests/sim/specs/branched_tree.yaml" "$tmp/branched.yaml"
for spec in tree5 branched; do
  in=$(init "$tmp/$spec.yaml")
  nq=$(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$tmp/$spec.yaml" | tr ',' '\n' | wc -l)
  # shellcheck disable=SC2086 # $in is a list of options
  "$eomc" run "$tmp/$spec.yaml" --code tables $in --accel > "$tmp/tab.acc" &&
    "$eomc" run "$tmp/$spec.yaml" --form lagrange $in --accel > "$tmp/lag.acc"
  st=$?
  d=$(accel_diff "$tmp/tab.acc" "$tmp/lag.acc" "$nq")
  [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-11) }'
  ok $? "$spec: --accel by the tables = lagrange's to $d of max |q''|"
done

in=$(init "$tmp/tree5.yaml")
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree5.yaml" --code tables $in --t-end 1 --rtol 1e-12 --atol 1e-12 \
    --summary > "$tmp/tab.csv" 2> "$tmp/tab.sum" &&
  "$eomc" run "$tmp/tree5.yaml" --form lagrange $in --t-end 1 --rtol 1e-12 --atol 1e-12 \
    --summary > "$tmp/lag.csv" 2> "$tmp/lag.sum"
st=$?
tail -n 1 "$tmp/tab.csv" > "$tmp/tab.row"
tail -n 1 "$tmp/lag.csv" > "$tmp/lag.row"
d=$(row_diff "$tmp/tab.row" "$tmp/lag.row" 31)
[ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-8) }'
ok $? "a run to t = 1: the tables end where lagrange does, to $d"
e1=$(tr '\n' ' ' < "$tmp/tab.sum" | sed -n 's/.*E started at \([-0-9.e+]*\);.*/\1/p')
e2=$(tr '\n' ' ' < "$tmp/lag.sum" | sed -n 's/.*E started at \([-0-9.e+]*\);.*/\1/p')
[ -n "$e1" ] && [ -n "$e2" ] &&
  [ "$e1" = "$e2" ]
ok $? "E = T + V with T by the recursion: $e1, lagrange's $e2"

# units: every velocity / tau, m * 1e6, l * 1e-4, g * 1e-4 / tau^2, tau = 1e3
tau=1000
slow=$(init "$tmp/tree5.yaml" | awk -v tau=$tau '{ for (i = 1; i <= NF; i++) { if ($i ~ /'"'"'=/) {
  split($i, kv, "="); $i = sprintf("%s=%.17g", kv[1], kv[2] / tau) } } print }')
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree5.yaml" --code tables $(init "$tmp/tree5.yaml") --accel > "$tmp/si.acc" &&
  "$eomc" run "$tmp/tree5.yaml" --code tables $slow --set m=1e6 --set l=0.3e-4 \
    --set g=9.81e-10 --accel > "$tmp/scaled.acc"
st=$?
awk -v tau=$tau '{ printf "%s %.17g\n", $1, $2 * tau * tau }' "$tmp/scaled.acc" > "$tmp/back.acc"
d=$(accel_diff "$tmp/back.acc" "$tmp/si.acc" 15)
[ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d < 1e-11) }'
ok $? "units of mass, length and time rescaled: q'' the same to $d"

lin="--init pelvis_a'=0.3 --init spine2_c'=-0.7 --init spine3_b'=0.4"
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree5.yaml" --code tables --linearize $lin --csv "$tmp/a.csv" > /dev/null &&
  "$eomc" run "$tmp/tree5.yaml" --form articulated-body --code straight --linearize $lin \
    --csv "$tmp/b.csv" > /dev/null
st=$?
paste -d, "$tmp/a.csv" "$tmp/b.csv" | awk -F, -v st="$st" '
  NR > 1 && $1 == "A" { d = $4 - $8; if (d < 0) d = -d; if (d > m) m = d
                        a = $4 < 0 ? -$4 : $4; if (a > s) s = a; rows++ }
  END { printf "# %d entries, max |A| %g, max difference %g\n", rows, s, m
        exit !(st == 0 && rows == 900 && s > 0 && m <= 1e-11 * s) }'
ok $? "--linearize with M by the tables' recursion = the straight-line code's A"

sh "$src/specs/gen_tree.sh" 40 > "$tmp/tree40.yaml"
"$eomc" compile "$tmp/tree40.yaml" -o "$tmp/t40.c" --explain > "$tmp/x40" &&
  "$eomc" compile "$tmp/tree5.yaml" -o "$tmp/t5.c" --explain > "$tmp/x5" &&
  grep -q '^#include "eomc_tree.h"' "$tmp/t40.c" &&
  grep -q '^ \* The accelerations and the mass matrix are loops over' "$tmp/t40.c" &&
  grep -q "^  code: loops over the model's tables (120 turns" "$tmp/x40" &&
  ! grep -q 'eomc_tree' "$tmp/t5.c" && ! grep -q '^  code:' "$tmp/x5"
ok $? "the default: tables for gen_tree 40 (the banner and --explain say so), straight-line for gen_tree 5"
tap_end
