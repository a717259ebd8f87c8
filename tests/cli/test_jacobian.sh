#!/bin/sh
# The Jacobian of a large model is printed only when something needs it
# (TAP), on a 4-body tree of 3-axis joints (specs/gen_tree.sh 4: 12
# coordinates), and a 6-body one (18 coordinates, whose unrolled Jacobian
# is above the size eomc prints unasked):
#  - its scene runs rk8pd, so `eomc compile` leaves the Jacobian out and
#    the banner says why; --jacobian seeded and a scene with an implicit
#    method put it in;
#  - the simulator built without it refuses the implicit methods and
#    --linearize with exit 2 and the rebuild to do; --work-precision leaves
#    those methods out and says so;
#  - `eomc run ... --linearize` builds with it: the seeded Jacobian's A
#    equals the unrolled one's to rounding (two derivations, two codes),
#    and its rows of q'' equal central differences of --accel;
#  - an imported arm with seven actuators (robots/arm_gripper_unconstrained.xml),
#    whose seeded dE/du is 56 entries set to 0 by a loop before its
#    nonzeros: --linearize's B (dq''/du) equals central differences of
#    --accel over the inputs (--set).
# usage: test_jacobian.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
jac_ops() { awk '$1 == "jacobian" { print $6 }' "$1"; }

sh "$src/specs/gen_tree.sh" 4 > "$tmp/tree4.yaml"
"$eomc" compile "$tmp/tree4.yaml" -o "$tmp/auto.c" --stats 2> "$tmp/auto.stats"
[ "$(jac_ops "$tmp/auto.stats")" = 0 ] && grep -q '^ \* No Jacobian of E: the scene'"'"'s method' "$tmp/auto.c" &&
    grep -q 'rk8pd, needs none' "$tmp/auto.c" && grep -q '^    \.jacobian = NULL, /\* no Jacobian' "$tmp/auto.c"
ok $? "auto, scene rk8pd: no Jacobian printed, the banner says why, the member is NULL"

"$eomc" compile "$tmp/tree4.yaml" -o "$tmp/seeded.c" --stats --jacobian seeded 2> "$tmp/seeded.stats"
[ "$(jac_ops "$tmp/seeded.stats")" -gt 0 ] && grep -q '_jacobian_dq(' "$tmp/seeded.c"
ok $? "--jacobian seeded: printed ($(jac_ops "$tmp/seeded.stats") operations)"

sh "$src/specs/gen_tree.sh" 6 | sed 's/^scene: {/scene: {method: bsimp, /' > "$tmp/stiff.yaml"
grep -q '^scene: {method: bsimp, ' "$tmp/stiff.yaml" &&
    "$eomc" compile "$tmp/stiff.yaml" -o "$tmp/stiff.c" --stats 2> "$tmp/stiff.stats" &&
    [ "$(jac_ops "$tmp/stiff.stats")" -gt 0 ] && grep -q '_jacobian_dq(' "$tmp/stiff.c"
ok $? "auto, scene bsimp, 18 coordinates: the seeded Jacobian printed"

"$eomc" build "$tmp/tree4.yaml" -o "$tmp/tree4"
for what in "--method msbdf" "--method rk4imp" "--linearize" "--equilibrium"; do
  "$tmp/tree4" $what --t-end 0.1 > "$tmp/out" 2> "$tmp/err"; st=$?
  [ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q 'needs the Jacobian of the equations' "$tmp/err" &&
      grep -q "eomc build tree4.yaml --jacobian auto" "$tmp/err"
  ok $? "built without it, $what: exit $st, no output, the rebuild said"
done
"$tmp/tree4" --method rk8pd --t-end 0.1 > /dev/null
ok $? "built without it, an explicit method runs"
"$tmp/tree4" --work-precision --t-end 0.01 --tolerances 1e-6 --steps 0.005 \
    > "$tmp/wp.out" 2> "$tmp/wp.err"; st=$?
[ $st -eq 0 ] && grep -q 'note: rk1imp, rk2imp, rk4imp, bsimp, msbdf left out' "$tmp/wp.err" &&
    grep -q '^rk8pd, adaptive' "$tmp/wp.out" && ! grep -q '^bsimp\|^msbdf' "$tmp/wp.out"
ok $? "--work-precision without it: the explicit methods reported, the others named as left out"

# eomc run builds with the Jacobian when the task needs it
init="--init pelvis_a'=0.3 --init spine2_c'=-0.7 --init spine3_b'=0.4"
"$eomc" run "$tmp/tree4.yaml" --jacobian seeded --linearize $init --csv "$tmp/a.csv" \
    > /dev/null; st1=$?
"$eomc" run "$tmp/tree4.yaml" --jacobian unrolled --linearize $init --csv "$tmp/b.csv" \
    > /dev/null; st2=$?
# max |a - b| <= 1e-12 max |A|, row by row (the same rows in the same order)
paste -d, "$tmp/a.csv" "$tmp/b.csv" | awk -F, -v st="$st1$st2" '
  NR > 1 && $1 == "A" { d = $4 - $8; if (d < 0) d = -d; if (d > m) m = d
                        a = $4 < 0 ? -$4 : $4; if (a > s) s = a; rows++ }
  END { printf "# %d entries, max |A| %g, max difference %g\n", rows, s, m
        exit !(st == "00" && rows == 576 && s > 0 && m <= 1e-12 * s) }'
ok $? "eomc run --linearize builds with the Jacobian: seeded A = unrolled A to 1e-12"
# ... and both are the motion's: the q'' rows of A at a state set in full
# against central differences of --accel (step 1e-5: truncation about
# 1e-10 of |A|), the check independent of either derivation
states=$(awk -F, 'NR > 1 && $1 == "A" && !seen[$3]++ { print $3 }' "$tmp/a.csv")
echo "$states" | awk '{ v = index($1, "\047") ? 0.5 * cos(2 * NR + 1) : 0.3 * sin(NR + 1)
                       printf "%s %.17g\n", $1, v }' > "$tmp/base.txt"
base=$(awk '{ printf "--init %s=%s ", $1, $2 }' "$tmp/base.txt")
"$eomc" run "$tmp/tree4.yaml" --linearize $base --csv "$tmp/c.csv" > /dev/null; st=$?
: > "$tmp/fd.txt"
while read -r s v; do
  for sg in 1 -1; do
    x=$(awk -v v="$v" -v s=$sg 'BEGIN { printf "%.17g", v + s * 1e-5 }')
    "$eomc" run "$tmp/tree4.yaml" --accel $base --init "$s=$x" 2> /dev/null |
      awk -v s="$s" -v sg=$sg '{ print sg, s, $1, $2 }' >> "$tmp/fd.txt"
  done
done < "$tmp/base.txt"
# against MATRIX N FD CSV ST: the rows of q'' of --linearize's MATRIX (A or
# B) in CSV against the central differences in FD (lines "SIGN VARIABLE
# NAME'' VALUE", step 1e-5), N entries, the run's status ST; the figures,
# and its status 0 when they agree to 1e-7 of the largest entry
against() {
  awk -F'[ ,]' -v mat="$1" -v want="$2" -v st="$5" '
    FNR == NR { if ($1 == 1) up[$2 "|" $3] = $4; else dn[$2 "|" $3] = $4; next }
    FNR > 1 && $1 == mat && $2 ~ /\047$/ { k = $3 "|" $2 "\047"
      if (!(k in up) || !(k in dn)) miss++
      d = (up[k] - dn[k]) / 2e-5 - $4; if (d < 0) d = -d; if (d > m) m = d
      a = $4 < 0 ? -$4 : $4; if (a > s) s = a; n++ }
    END { printf "%d entries, max |%s| %g, max |%s - differences| %.2g", n, mat, s, mat, m
          exit !(st == 0 && n == want && !miss && s > 0 && m <= 1e-7 * s) }' "$3" "$4"
}
got=$(against A 288 "$tmp/fd.txt" "$tmp/c.csv" $st)
ok $? "--linearize's A against central differences of --accel: $got"

arm="$src/tests/import/models/robots/arm_gripper_unconstrained.xml"
"$eomc" compile "$arm" --jacobian seeded -o "$tmp/arm.c" 2> /dev/null
inputs=$(sed -n 's/^static const char \*const u_names\[[0-9]*\] = {\(.*\)};$/\1/p' "$tmp/arm.c" |
  tr -d '",')
uset=$(echo $inputs | awk '{ for (k = 1; k <= NF; k++) printf "--set %s=%.17g ", $k, 0.3 * sin(k) }')
# shellcheck disable=SC2086 # $uset is a list of options
"$eomc" run "$arm" --jacobian seeded --linearize $uset --csv "$tmp/arm.csv" > /dev/null 2>&1; st=$?
: > "$tmp/fdu.txt"
k=0
for u in $inputs; do
  k=$((k + 1))
  for sg in 1 -1; do
    x=$(awk -v k=$k -v s=$sg 'BEGIN { printf "%.17g", 0.3 * sin(k) + s * 1e-5 }')
    # shellcheck disable=SC2086
    "$eomc" run "$arm" --accel $uset --set "$u=$x" 2> /dev/null |
      awk -v u="$u" -v sg=$sg '{ print sg, u, $1, $2 }' >> "$tmp/fdu.txt"
  done
done
got=$(against B 56 "$tmp/fdu.txt" "$tmp/arm.csv" $st) &&
  grep -q 'for (int i = 0; i < 56; i++) /\* the nonzeros follow \*/' "$tmp/arm.c" &&
  grep -A1 'i < 56; i++) /\* the nonzeros follow' "$tmp/arm.c" | grep -q 'dEdu\[i\] = 0.0'
ok $? "a seeded dE/du filled by a loop: --linearize's B against central differences of --accel over the inputs: $got"

tap_end
