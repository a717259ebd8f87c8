#!/bin/sh
# A scene's `assemble:` (docs/spec.md), as a user runs it (TAP).
# specs/bicycle_tree.yaml holds every coordinate and rate but the contact
# point's velocity (x', y'); started off its rolling constraints (heading
# psi = 0.3 with x' = 5 R, y' = 0 from the spec), every run moves x', y'
# alone onto them: x' = R rs' cos(psi), y' = R rs' sin(psi), the closed
# form of the rear wheel rolling, computed here; the held values,
# rs' = 5 (the speed) among them, stay exactly as given:
#  - a run's first row; --linearize (the state it is linearized at); each
#    run of a sweep (with its own R); --assemble alone (the scene's list);
#  - the command line overrides: --hold LIST replaces the scene's list,
#    --no-assemble starts as given (and the constraint warning says so);
#  - --equilibrium: the guess is assembled at rest keeping the held
#    positions (a rod's x; y moves onto x^2 + y^2 = l^2), then found.
# usage: test_assemble.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
# |got - want| <= 1e-15 max(1, |want|)
near() { awk -v g="$1" -v w="$2" 'BEGIN { d = g - w; if (d < 0) d = -d; s = w < 0 ? -w : w; if (s < 1) s = 1; exit !(g != "" && d <= 1e-15 * s) }'; }
# column NAME of CSV row ROW (1 = the first after the header)
cell() { awk -F, -v name="$1" -v row="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) k = i }
    NR == row + 1 { print $k }' "$3"; }

"$eomc" build "$src/specs/bicycle_tree.yaml" --jacobian auto -o "$tmp/bike" 2> "$tmp/err"
ok $? "bicycle_tree with a scene hold builds"
R=0.35
wx=$(awk -v R=$R 'BEGIN { printf "%.17g", R * 5 * cos(0.3) }')
wy=$(awk -v R=$R 'BEGIN { printf "%.17g", R * 5 * sin(0.3) }')
held="x y psi lean rs pitch steer fs psi' lean' rs' pitch' steer' fs'"

# a run
"$tmp/bike" --init psi=0.3 --t-end 0.01 -o "$tmp/run.csv" 2> "$tmp/run.err"; st=$?
"$tmp/bike" --init psi=0.3 --t-end 0.01 --no-assemble -o "$tmp/asis.csv" 2> "$tmp/asis.err"
same=1
for v in $held; do
  [ "$(cell "$v" 1 "$tmp/run.csv")" = "$(cell "$v" 1 "$tmp/asis.csv")" ] || same=0
done
[ $st -eq 0 ] && [ $same -eq 1 ] && [ "$(cell "rs'" 1 "$tmp/run.csv")" = 5 ] &&
  near "$(cell "x'" 1 "$tmp/run.csv")" "$wx" && near "$(cell "y'" 1 "$tmp/run.csv")" "$wy" &&
  [ "$(grep -c '^  ' "$tmp/run.err")" -eq 2 ] && grep -q "the scene's assembly moved" "$tmp/run.err"
ok $? "a run from psi = 0.3: the held values as given (rs' = $(cell "rs'" 1 "$tmp/run.csv")), x' = $(cell "x'" 1 "$tmp/run.csv") = R rs' cos(psi), y' = R rs' sin(psi)"
[ "$(cell "x'" 1 "$tmp/asis.csv")" = 1.75 ] && [ "$(cell "y'" 1 "$tmp/asis.csv")" = 0 ] &&
  grep -q "warning: the initial state is off 2 constraints, worst first: roll_y (velocities" "$tmp/asis.err"
ok $? "--no-assemble: the start as given (x' = 1.75, y' = 0), with the constraint warning"
"$tmp/bike" --init psi=0.3 --t-end 0.01 --assemble -o "$tmp/again.csv" 2> /dev/null
cmp -s "$tmp/run.csv" "$tmp/again.csv"
ok $? "--assemble alone assembles as the scene does (its hold list): the same rows"

# --linearize from the same start: assembled first, linearized there
"$tmp/bike" --init psi=0.3 --linearize > "$tmp/lin.out" 2> "$tmp/lin.err"; st=$?
gx=$(sed -n "s/^  x' [^ ]* -> \\([^ ]*\\) .*/\\1/p" "$tmp/lin.err")
gy=$(sed -n "s/^  y' [^ ]* -> \\([^ ]*\\) .*/\\1/p" "$tmp/lin.err")
at=$(awk -v x="$wx" -v y="$wy" 'BEGIN { printf "x'"'"' = %.6g, y'"'"' = %.6g, psi'"'"' = 0, lean'"'"' = 0, rs'"'"' = 5,", x, y }')
[ $st -eq 0 ] && [ "$(grep -c '^  ' "$tmp/lin.err")" -eq 2 ] && near "$gx" "$wx" && near "$gy" "$wy" &&
  grep -q "^bike: linearized at t = 0, .*$at" "$tmp/lin.out"
ok $? "--linearize assembles first: only x' -> $gx and y' -> $gy move; linearized at $at ..."

# the command line's --hold replaces the scene's list: rs' alone kept, the
# other rates move too (the least change in the mass matrix's metric)
"$tmp/bike" --init psi=0.3 --t-end 0.01 --hold "rs'" -o "$tmp/over.csv" 2> "$tmp/over.err"; st=$?
[ $st -eq 0 ] && [ "$(cell "rs'" 1 "$tmp/over.csv")" = 5 ] && [ "$(cell "psi'" 1 "$tmp/over.csv")" != 0 ] &&
  grep -q "^bike: --assemble moved" "$tmp/over.err" && grep -q "^  psi' 0 -> " "$tmp/over.err"
ok $? "--hold \"rs'\" overrides the scene's list: rs' kept, psi' -> $(cell "psi'" 1 "$tmp/over.csv") moves too"
"$tmp/bike" --no-assemble --hold x -o /dev/null 2> "$tmp/u.err"; st=$?
[ $st -eq 2 ] && grep -q -- "--no-assemble starts from the initial state as given" "$tmp/u.err"
ok $? "--no-assemble with --hold: a usage error (exit $st)"

# a sweep: each run assembled with its own R
"$tmp/bike" --init psi=0.3 --t-end 1e-9 --sweep R=0.3:0.4:2 -o "$tmp/sweep.csv" 2> /dev/null; st=$?
bad=0
for row in 1 2; do
  r=$(cell R $row "$tmp/sweep.csv")
  awk -v g="$(cell "x'" $row "$tmp/sweep.csv")" -v h="$(cell "y'" $row "$tmp/sweep.csv")" -v R="$r" \
    'BEGIN { exit !(g != "" && (g - R * 5 * cos(0.3))^2 < 1e-16 && (h - R * 5 * sin(0.3))^2 < 1e-16) }' ||
    bad=$((bad + 1))
done
[ $st -eq 0 ] && [ $bad -eq 0 ]
ok $? "a sweep over R: each run starts at x' = R rs' cos(psi), y' = R rs' sin(psi) with its own R"

# --equilibrium: the guess at rest, x held, y onto the rod; then the top
cat > "$tmp/rod.yaml" <<'YAML'
name: rod
parameters: {m: 1, l: 1, g: 9.81}
coordinates: [x, y]
particles: {bob: {mass: m, position: [x, y]}}
effects: {gravity: {gravity: [0, -g]}}
constraints: {rod: x^2 + y^2 - l^2}
initial: {x: 0.6, y: 0.3, "x'": 1}
scene: {assemble: {hold: [x, "x'"]}}
YAML
"$eomc" build "$tmp/rod.yaml" --jacobian auto -o "$tmp/rod" 2> "$tmp/err"
"$tmp/rod" --equilibrium > "$tmp/eq.out" 2> "$tmp/eq.err"; st=$?
gy=$(sed -n 's/^  y 0.2999[0-9]* -> \([^ ]*\) .*/\1/p' "$tmp/eq.err")
ex=$(sed -n 's/^  x = //p' "$tmp/eq.out")
ey=$(sed -n 's/^  y = //p' "$tmp/eq.out")
[ $st -eq 0 ] && [ "$(grep -c '^  ' "$tmp/eq.err")" -eq 1 ] && near "$gy" 0.8 &&
  awk -v x="$ex" -v y="$ey" 'BEGIN { exit !(x != "" && x * x < 1e-30 && (y - 1)^2 < 1e-30) }' &&
  grep -q '^unstable' "$tmp/eq.out"
ok $? "--equilibrium: the guess assembled at rest with x = 0.6 held (y -> $gy), then the top ($ex, $ey), unstable"
tap_end
