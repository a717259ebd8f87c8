#!/bin/sh
# Constrained trees by unit loads (TAP): a tree with constraints affine in
# q'' solved by the articulated-body recursion without the constraints,
# then M^-1 B^T one row at a time (minv) and the nc x nc system B M^-1 B^T
# (runtime/model/kkt.c), M never formed.  Each check sets it against Lagrange's
# form eliminating the dependent coordinates (--eliminate), whose M is
# differentiated from the energies and whose system is solved densely: an
# independent derivation and solve (Lagrange's form with multipliers is
# solved by unit loads too, through its unrolled LDL^T).
#  - --accel (q'' and the multipliers) of the rolling disk, the bicycle of
#    specs/ and the Whipple bicycle, straight-line and as loops over the
#    tables: equal to 1e-12 of the largest entry;
#  - one row (kkt.c's 1 x 1 system, a division without the blocks of
#    several): --accel of the Chaplygin sleigh, the precessing top, the
#    Cartesian pendulum and the constant-speed particle (one constraint
#    each, their default forms by unit loads), equal to Lagrange's
#    elimination to 1e-12 of the largest entry;
#  - B's entries that can be nonzero listed (the model's c_nz) wherever B
#    has a zero, the rolling disk's 4 of 10: those its constraint function
#    stores other than 0.0;
#  - the banner says so, and the simulator has minv; Lagrange's form with
#    multipliers says it solves by the loads through its LDL^T, and with
#    --eliminate has no unit loads;
#  - a run of the bicycle to t = 1 (rk8pd at 1e-12) ends where Lagrange's
#    does (1e-9), and one with msbdf (its Jacobian forms M on demand) too;
#  - units: the rolling disk with the mass unit 1e-6 kg and the length
#    unit 1e4 m (m * 1e6, R and x, y * 1e-4, g * 1e-4): q'' the same (x'',
#    y'' * 1e-4) and the multipliers * 1e2, to 1e-12;
#  - a constraint written twice: its rows are dependent, the second is
#    left out of the solves with a note naming both, its multiplier 0, and
#    q'' and the other multipliers are the disk's own (1e-12); a run to
#    t = 0.1 goes through; by elimination it is refused, naming both (each
#    would determine a coordinate of its own);
#  - ball joints (a frame turned by a quaternion): the Chaplygin ball of
#    tests/sim/specs/rolling_ball.yaml and the floating body with an arm of
#    tests/sim/specs/floating_arm.yaml (three slides, a ball, a hinge): q''
#    and the multipliers of the articulated-body and Newton-Euler forms =
#    Lagrange's at the initial state (on |e| = 1, e.e' = 0) to 1e-12, but
#    for the unit constraint's, which the recursion leaves at 0 (to 1e-12 of
#    Lagrange's, which depends on how T is written off |e| = 1); a run of
#    the floating body to t = 2 ends where Lagrange's does (1e-9, every
#    column but that multiplier); the tables refuse ball joints, saying so.
# usage: test_loads.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"

below() { awk -v d="$1" -v t="$2" 'BEGIN { exit !(d == d + 0 && d < t) }'; }

disk="$src/specs/rolling_disk.yaml" bike="$src/specs/bicycle_tree.yaml"
whip="$src/tests/sim/specs/whipple.yaml"
for spec in "$disk" "$bike" "$whip"; do
  name=$(basename "$spec" .yaml)
  in=$(init "$spec")
  for code in straight tables; do
    # shellcheck disable=SC2086 # $in is a list of options
    "$eomc" run "$spec" --form articulated-body --code $code $in --accel > "$tmp/ab.acc" 2> /dev/null &&
      "$eomc" run "$spec" --form lagrange --eliminate $in --accel > "$tmp/lag.acc" 2> /dev/null
    st=$?
    d=$(accel_diff "$tmp/lag.acc" "$tmp/ab.acc" 1)
    [ $st -eq 0 ] && grep -q '^lambda' "$tmp/ab.acc" && below "$d" 1e-12
    ok $? "$name ($code): q'' and the multipliers by unit loads = lagrange's dense elimination to $d"
  done
done

one="chaplygin_sleigh precession cartesian_pendulum central_constant_speed"
for name in $one; do
  spec="$src/specs/$name.yaml" in=$(init "$src/specs/$name.yaml")
  # shellcheck disable=SC2086 # $in is a list of options
  "$eomc" compile "$spec" -o "$tmp/one.c" 2> /dev/null && grep -q '\.nc = 1,' "$tmp/one.c" &&
    grep -q '_minv, /\* the multipliers by unit loads \*/' "$tmp/one.c" &&
    "$eomc" run "$spec" $in --accel > "$tmp/one.acc" 2> /dev/null &&
    "$eomc" run "$spec" --form lagrange --eliminate $in --accel > "$tmp/lag.acc" 2> /dev/null
  st=$?
  d=$(accel_diff "$tmp/lag.acc" "$tmp/one.acc" 3)
  [ $st -eq 0 ] && grep -q '^lambda' "$tmp/one.acc" && below "$d" 1e-12
  ok $? "$name (one row by unit loads): q'' and the multiplier = lagrange's dense elimination to $d"
done

"$eomc" compile "$disk" -o "$tmp/disk.c" 2> /dev/null
nz=$(sed -n 's/^static const int c_nz\[4\] = {\(.*\)};$/\1/p' "$tmp/disk.c")
stored=$(awk '/^rolling_disk_constraint\(/ { on = 1 } on && /^}/ { exit }
              on && /^    B\[[0-9]+\] = / && $3 != "0.0;" { print substr($1, 3) + 0 }' "$tmp/disk.c" |
         sort -n | paste -sd, | sed 's/,/, /g')
[ -n "$nz" ] && [ "$nz" = "$stored" ] &&
  grep -q '\.c_nnz = 4, \.c_nz = c_nz,' "$tmp/disk.c"
ok $? "rolling_disk: B's nonzeros listed (c_nz = {$nz}), the entries its constraint stores other than 0.0 ($stored)"

"$eomc" compile "$bike" --form articulated-body -o "$tmp/bike.c" &&
  grep -q '^ \* The multipliers by unit loads' "$tmp/bike.c" &&
  grep -q '\.free_accel = bicycle_tree_accel, \.minv = bicycle_tree_minv, /\* the multipliers by unit loads \*/' "$tmp/bike.c" &&
  "$eomc" compile "$bike" --form lagrange -o "$tmp/lag.c" &&
  grep -q '^ \* The multipliers by unit loads: q.. without the constraints by the unrolled$' "$tmp/lag.c" &&
  grep -q '\.nshared = [0-9]*, \.free_accel_shared = bicycle_tree_accel_shared, \.minv_shared = bicycle_tree_minv_shared,' "$tmp/lag.c" &&
  "$eomc" compile "$bike" --form lagrange --eliminate -o "$tmp/elim.c" &&
  grep -q '\.free_accel = NULL, \.minv = NULL, /\* no unit-load passes \*/' "$tmp/elim.c"
ok $? "the banner says the multipliers are by unit loads, and the model has free_accel and minv (lagrange's through its LDL^T factors, shared with minv; eliminating, neither)"

for method in rk8pd msbdf; do
  "$eomc" run "$bike" --form articulated-body --t-end 1 --method $method --rtol 1e-12 \
    --atol 1e-12 -o "$tmp/ab.csv" 2> /dev/null &&
    "$eomc" run "$bike" --form lagrange --eliminate --t-end 1 --method $method --rtol 1e-12 --atol 1e-12 \
      -o "$tmp/lag.csv" 2> /dev/null
  st=$?
  tail -1 "$tmp/ab.csv" > "$tmp/ab.last"
  tail -1 "$tmp/lag.csv" > "$tmp/lag.last"
  d=$(row_diff "$tmp/lag.last" "$tmp/ab.last")
  [ $st -eq 0 ] && below "$d" 1e-9
  ok $? "bicycle_tree with $method to t = 1: by unit loads the last row is lagrange's to $d"
done

# units: mass 1e-6 kg, length 1e4 m; the disk's state in both
st0="--init theta=1.2 --init psi=0.3 --init phi=0.4 --init theta'=0.5 --init psi'=1.5 --init phi'=6"
# shellcheck disable=SC2086 # $st0 is a list of options
"$eomc" run "$disk" --form articulated-body $st0 --init x=0.2 --init y=-0.1 --init "x'=0.7" \
  --init "y'=-0.4" --accel > "$tmp/si.acc" 2> /dev/null &&
  "$eomc" run "$disk" --form articulated-body --set m=1e6 --set R=0.5e-4 --set g=9.81e-4 $st0 \
    --init x=0.2e-4 --init y=-0.1e-4 --init "x'=0.7e-4" --init "y'=-0.4e-4" --accel \
    > "$tmp/scaled.acc" 2> /dev/null
st=$?
d=$(accel_diff "$tmp/si.acc" "$tmp/scaled.acc" 1 "x'' 1e4 y'' 1e4 lambda[roll_x] 1e-2 lambda[roll_y] 1e-2")
[ $st -eq 0 ] && below "$d" 1e-12
ok $? "rolling_disk in kg 1e-6 and m 1e4: q'' and the multipliers rescale exactly (to $d)"

# a constraint written twice: dependent rows, the second left out
sed 's/^  roll_y: \(.*\)$/  roll_y: \1\n  roll_y2: {expr: "\1", dependent: phi}/' "$disk" > "$tmp/twice.yaml"
"$eomc" run "$tmp/twice.yaml" --form articulated-body --t-end 0.1 -o "$tmp/twice.csv" \
  > /dev/null 2> "$tmp/twice.err"
st=$?
"$eomc" compile "$tmp/twice.yaml" --form articulated-body -o "$tmp/twice.c" 2> /dev/null &&
  grep -q '_minv, /\* the multipliers by unit loads' "$tmp/twice.c"
loads=$?
"$eomc" run "$tmp/twice.yaml" --form articulated-body --accel > "$tmp/twice.acc" 2> /dev/null &&
  "$eomc" run "$disk" --form articulated-body --accel > "$tmp/once.acc" 2> /dev/null
acc=$?
grep -v 'roll_y2' "$tmp/twice.acc" > "$tmp/twice.rest"
d=$(accel_diff "$tmp/once.acc" "$tmp/twice.rest" 7)
[ $st -eq 0 ] && [ $loads -eq 0 ] && [ $acc -eq 0 ] && below "$d" 1e-12 &&
  grep -q '^lambda\[roll_y2\] 0$' "$tmp/twice.acc" &&
  grep -q 'note: constraints dependent at the start: roll_y2, dependent on roll_y; the solves leave the dependent rows out' "$tmp/twice.err" &&
  [ "$(wc -l < "$tmp/twice.csv")" -eq 12 ]
ok $? "roll_y written twice: roll_y2 left out (its multiplier 0), q'' and the rest the disk's to $d, the run goes on ($(head -c 160 "$tmp/twice.err"))"
"$eomc" run "$tmp/twice.yaml" --form lagrange --eliminate --accel > /dev/null 2> "$tmp/elim.err"
st=$?
[ $st -eq 3 ] && grep -q 'error: t = 0: the constraints are dependent here (roll_y2, dependent on roll_y), and elimination needs independent ones' "$tmp/elim.err"
ok $? "roll_y written twice, eliminated: refused, naming the two, exit $st ($(head -c 200 "$tmp/elim.err"))"

# ball joints: the unit constraint's multiplier apart
ball="$src/tests/sim/specs/rolling_ball.yaml" float="$src/tests/sim/specs/floating_arm.yaml"
for spec in "$ball" "$float"; do
 for form in articulated-body newton-euler; do
  name=$(basename "$spec" .yaml)
  "$eomc" run "$spec" --form $form --accel > "$tmp/ab.acc" 2> "$tmp/said" &&
    "$eomc" run "$spec" --form lagrange --accel > "$tmp/lag.acc" 2> "$tmp/said"
  st=$?
  grep -v '_unit\]' "$tmp/ab.acc" > "$tmp/ab.rest"
  grep -v '_unit\]' "$tmp/lag.acc" > "$tmp/lag.rest"
  d=$(accel_diff "$tmp/lag.rest" "$tmp/ab.rest" 6)
  unit=$(awk 'NR == FNR && /_unit\]/ { u = $2 < 0 ? -$2 : $2 } NR != FNR && /_unit\]/ { l = $2 < 0 ? -$2 : $2 }
              END { if (l > 0) printf "%.3g\n", u / l; else print "nan" }' "$tmp/ab.acc" "$tmp/lag.acc")
  [ $st -eq 0 ] && below "$d" 1e-12 && below "$unit" 1e-12
  ok $? "$name (a ball joint), $form: q'' and the other multipliers = lagrange's to $d; the unit constraint's $unit of lagrange's$(why $st "$tmp/said")"
 done
done
# the unit quaternion's row is held by the recursion itself (c_held), and
# it is not where a rotor's inertia on the ball (MuJoCo's armature: its
# Lagrange terms have -2 a |w|^2 along e) acts on the parameters: then its
# row is solved, and q'' is still Lagrange's (the unit multiplier differs
# between the forms, docs/spec.md)
"$eomc" compile "$float" --form articulated-body -o "$tmp/held.c" 2> /dev/null
sed 's/^  gravity: {gravity: \[0, 0, -g\]}$/&\n  rotor: {kinetic: "0.02*(2*(e0*e1'"'"' - e1*e0'"'"' + e3*e2'"'"' - e2*e3'"'"'))^2"}/' "$float" \
  > "$tmp/rotor.yaml"
"$eomc" compile "$tmp/rotor.yaml" --form articulated-body -o "$tmp/rotor.c" 2> /dev/null &&
  "$eomc" run "$tmp/rotor.yaml" --form articulated-body --accel > "$tmp/ab.acc" 2> /dev/null &&
  "$eomc" run "$tmp/rotor.yaml" --form lagrange --accel > "$tmp/lag.acc" 2> /dev/null
st=$?
grep -v '_unit\]' "$tmp/ab.acc" > "$tmp/ab.rest"
grep -v '_unit\]' "$tmp/lag.acc" > "$tmp/lag.rest"
d=$(accel_diff "$tmp/lag.rest" "$tmp/ab.rest" 8)
[ $st -eq 0 ] && grep -q "c_held\[1\] = {1};" "$tmp/held.c" && grep -q "rotor" "$tmp/rotor.yaml" &&
  grep -q "\.c_held = NULL" "$tmp/rotor.c" && below "$d" 1e-12
ok $? "floating_arm: its unit row held by the recursion; with a rotor on the ball it is solved, and q'' is lagrange's to $d"
"$eomc" run "$float" --form articulated-body -o "$tmp/ab.csv" 2> "$tmp/said" &&
  "$eomc" run "$float" --form lagrange -o "$tmp/lag.csv" 2> "$tmp/said"
st=$?
# every column but the unit constraint's multiplier
col=$(head -1 "$tmp/ab.csv" | tr ',' '\n' | grep -n '^lambda\[body_axes_unit\]$' | cut -d: -f1)
tail -1 "$tmp/ab.csv" | cut -d, -f"$col" --complement > "$tmp/ab.last"
tail -1 "$tmp/lag.csv" | cut -d, -f"$col" --complement > "$tmp/lag.last"
d=$(row_diff "$tmp/lag.last" "$tmp/ab.last" 20)
[ $st -eq 0 ] && [ -n "$col" ] && below "$d" 1e-9
ok $? "floating_arm to t = 2 by the articulated-body form: lagrange's last row to $d$(why $st "$tmp/said")"
"$eomc" compile "$float" --code tables -o "$tmp/fa.c" 2> "$tmp/fa.err"
st=$?
[ $st -eq 0 ] && grep -q 'note: --code tables: not here (the tables have no ball joints' "$tmp/fa.err" &&
  ! grep -q eomc_tree "$tmp/fa.c"
ok $? "--code tables on a ball joint: straight-line code, and a note that says why"

tap_end
