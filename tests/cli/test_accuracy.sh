#!/bin/sh
# eomc accuracy and the simulator's accuracy options, as a user runs them
# (TAP):
#  - the CSV has the documented header, one row per run, numbers in every
#    measured cell; the plot is an SVG naming every method;
#  - --target names the cheapest run within the target, which this script
#    finds again from the CSV; the Pareto front has no run beaten by a
#    cheaper one;
#  - a run that fails (the step limit) is a row with empty error cells and
#    its reason in the table; when every run fails, exit status 3;
#  - --reference-out writes the reference with the simulator's columns,
#    and --reference FILE reads it back: the same errors; a file that does
#    not fit is a usage error naming FILE:LINE;
#  - --error measures one run; --summary says what is conserved, or why
#    nothing is; on a stiff spring the report, --stats and --error name the
#    linearly implicit reference;
#  - digits by component (a top whose big spin angle hid its nutation
#    rate's error): the table's digits and worst component, and --errors
#    FILE's rows, against errors computed here from the run's and the
#    reference's CSVs;
#  - robots at rest (MJCF, skipped without MuJoCo): a floating base with
#    mirrored legs and ball-jointed arms, whose reference is the closed
#    form of its rigid fall, in steps rounding does not hold; an arm with
#    fingers a joint equality couples, whose reference is rk8pd's at 1e-13;
#    the errors --error and eomc accuracy report against those;
#  - usage errors (exit 2, no file left): report options without
#    --work-precision, a plot that is neither .svg nor .png, an unknown
#    method with a suggestion.
# usage: test_accuracy.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
header="method,tolerance,fixed_step,cpu_seconds,steps,rejected,rhs_evals,jac_evals,error_end,error_max,invariant_drift,constraint_residual,order_mean"

"$eomc" build "$src/specs/pendulum.yaml" -o "$tmp/pend" 2> "$tmp/build.err" ||
  cat "$tmp/build.err"

# the CSV and the plot, through eomc accuracy
EOMC_CACHE_DIR="$tmp/cache" "$eomc" accuracy "$src/specs/pendulum.yaml" \
  --methods rk8pd,rkf45,rk4 --tolerances 1e-4,1e-7,1e-10 --csv "$tmp/wp.csv" \
  --plot "$tmp/wp.svg" --target 1e-8 > "$tmp/wp.txt" 2> "$tmp/wp.err"; st=$?
[ $st -eq 0 ] && [ "$(head -n 1 "$tmp/wp.csv")" = "$header" ]
ok $? "eomc accuracy --csv: exit $st, the header is $header"
rows=$(($(wc -l < "$tmp/wp.csv") - 1))
awk -F, 'NR > 1 { if (NF != 13) bad = 1
  for (i = 4; i <= 11; i++) if ($i !~ /^[0-9.e+-]+$/) bad = 1 }
  END { exit bad }' "$tmp/wp.csv" && [ "$rows" -eq 12 ]
ok $? "... 12 runs (3 methods x 3 tolerances, rk4 at 3 fixed steps), every measured cell a number"
awk -F, 'NR > 1 && ($2 == "") == ($3 == "") { bad = 1 } END { exit bad }' "$tmp/wp.csv"
ok $? "... each row has a tolerance or a fixed step, not both"
[ -s "$tmp/wp.svg" ] && grep -q "<svg" "$tmp/wp.svg" && grep -q ">rk8pd<" "$tmp/wp.svg" &&
  grep -q ">rkf45<" "$tmp/wp.svg" && grep -q ">rk4<" "$tmp/wp.svg" &&
  grep -q "rk4 (fixed steps)" "$tmp/wp.svg" && grep -q "CPU time" "$tmp/wp.svg"
ok $? "--plot: an SVG with a curve named for every method, and labelled axes"
! ls "$tmp"/wp.*.tmp* > /dev/null 2>&1
ok $? "... and no temporary file left"

# --target: the cheapest row of the CSV with error_max <= 1e-8
want=$(awk -F, 'NR > 1 && $10 != "" && $10 + 0 <= 1e-8 {
    if (best == "" || $4 + 0 < best + 0) { best = $4; m = $1; tol = $2; h = $3 } }
  END { if (tol != "") printf "%s at tolerance %.0e", m, tol; else printf "%s, fixed steps", m }' \
  "$tmp/wp.csv")
grep -q "the cheapest measured setting is $want" "$tmp/wp.txt"
ok $? "--target 1e-8 names the cheapest run within it, as the CSV has it: $want"
awk '/^Pareto front/ { on = 1; next } on && /^ *[0-9]/ { if (n++ && !($1 + 0 >= c && $2 + 0 < e)) bad = 1; c = $1 + 0; e = $2 + 0 }
  on && /^$/ { on = 0 } END { exit bad || n < 2 }' "$tmp/wp.txt"
ok $? "the Pareto front is in order of CPU time, each more accurate than the one before"

# a failed run is a row; all failed: exit 3
"$tmp/pend" --work-precision --methods rk4 --tolerances 1e-3,1e-12 --steps 0.1 \
  --max-steps 300 --csv "$tmp/fail.csv" > "$tmp/fail.txt" 2> "$tmp/fail.err"; st=$?
row=$(grep '^rk4,1e-12,' "$tmp/fail.csv")
[ $st -eq 0 ] && [ -n "$row" ] && [ "$(echo "$row" | cut -d, -f9-12)" = ",,," ] &&
  grep -q "failed: t = .*too many steps (the limit is 300)" "$tmp/fail.txt"
ok $? "a run stopped by --max-steps: a row with empty error cells, its reason in the table (exit $st)"
"$tmp/pend" --work-precision --methods rk4 --tolerances 1e-12 --steps 0.001 --max-steps 50 \
  > /dev/null 2> "$tmp/allfail.err"; st=$?
[ $st -eq 3 ] && grep -q "no run succeeded" "$tmp/allfail.err"
ok $? "every run failed: exit status 3 (got $st)"

# the reference, out and back in
"$tmp/pend" --reference-out "$tmp/ref.csv" --error -o /dev/null --t-end 2 --dt 0.1 \
  --method rkf45 --rtol 1e-6 --atol 1e-6 --stats 2> "$tmp/ref1.err"; st=$?
[ $st -eq 0 ] && [ "$(head -n 1 "$tmp/ref.csv")" = "t,theta,theta',T,V,E" ] &&
  [ "$(wc -l < "$tmp/ref.csv")" -eq 22 ]
ok $? "--reference-out: the simulator's columns, a row at each of the 21 output times"
"$tmp/pend" --reference "$tmp/ref.csv" -o /dev/null --t-end 2 --dt 0.1 --method rkf45 \
  --rtol 1e-6 --atol 1e-6 --stats 2> "$tmp/ref2.err"; st=$?
e1=$(sed -n 's/^error_max //p' "$tmp/ref1.err") e2=$(sed -n 's/^error_max //p' "$tmp/ref2.err")
[ $st -eq 0 ] && [ -n "$e1" ] && [ "$e1" = "$e2" ] && grep -q "^reference_error nan" "$tmp/ref2.err"
ok $? "--reference FILE: the same error_max ($e1, $e2); a file's own error is not known"
"$tmp/pend" --reference "$tmp/ref.csv" -o /dev/null --t-end 2 --dt 0.1 --method rkf45 \
  --rtol 1e-6 --atol 1e-6 2> "$tmp/ref5.err"; st=$?
[ $st -eq 0 ] && ! grep -qi "nan" "$tmp/ref5.err" &&
  grep -q "(the reference, read from $tmp/ref.csv, has no estimate of its own error)" "$tmp/ref5.err"
ok $? "--reference FILE: the line says the file's own error is not known, never 'good to nan'"
"$tmp/pend" --reference "$tmp/ref.csv" -o "$tmp/none.csv" --t-end 2 --dt 0.2 \
  2> "$tmp/ref3.err"; st=$?
[ $st -eq 2 ] && grep -q "ref.csv:3: a row at t = 0.10000000000000001 where the runs have one at t = 0.20000000000000001" "$tmp/ref3.err" &&
  [ ! -e "$tmp/none.csv" ]
ok $? "--reference FILE on another grid: usage error at FILE:LINE, no output (exit $st)"
printf 't,theta\n0,1\n' > "$tmp/bad.csv"
"$tmp/pend" --reference "$tmp/bad.csv" -o /dev/null 2> "$tmp/ref4.err"; st=$?
[ $st -eq 2 ] && grep -q "bad.csv:1: no column 'theta''" "$tmp/ref4.err"
ok $? "--reference FILE without a velocity column: usage error naming it (exit $st)"

# A motion every method integrates exactly (the falling particle: a
# parabola): the two refinements agree to every bit, and the reference is
# still good only to the rounding of its doubles, half a unit in the last
# place of its largest entry (|y'| = g t_end = 9.81): never "good to 0".
"$eomc" run "$src/specs/falling_particle.yaml" --error -o /dev/null 2> "$tmp/fall.err"
half_ulp=$(awk 'BEGIN { printf "%.2g", 0.5 * 2^-52 * 9.81 }')
grep -q "(the reference, by Gragg-Bulirsch-Stoer extrapolation, is good to $half_ulp)" "$tmp/fall.err"
ok $? "an exact motion: the reference is good to the rounding of doubles, $half_ulp, not 0"

# The stiff spring (roots -1 and -1e4): the reference is the linearly
# implicit one, and the report's header, --stats and --error's line say so
"$eomc" build "$src/tests/hard/specs/stiff_spring.yaml" -o "$tmp/stiff" 2> /dev/null
"$tmp/stiff" --work-precision --methods msbdf --tolerances 1e-8 > "$tmp/stiff.txt"; st1=$?
"$tmp/stiff" --error --stats -o /dev/null 2> "$tmp/stiff1.err"; st2=$?
"$tmp/stiff" --error -o /dev/null 2> "$tmp/stiff2.err"; st3=$?
[ $st1 -eq 0 ] && [ $st2 -eq 0 ] && [ $st3 -eq 0 ] &&
  grep -q "^reference: linearly implicit Euler extrapolation of order 8 .*; the problem is stiff: " "$tmp/stiff.txt" &&
  grep -q "^reference_method linearly implicit Euler extrapolation$" "$tmp/stiff1.err" &&
  grep -q "(the reference, by linearly implicit Euler extrapolation (the problem is stiff), is good to " "$tmp/stiff2.err"
ok $? "a stiff spring: the report's header, --stats and --error's line name the linearly implicit reference"

# Fixed steps estimate no error: rk4 in steps of 0.5 on the pendulum
# (period 2.1 s) keeps no digit of its energy, which the run says; in steps
# of 0.1 it keeps about three, and says nothing.  E = theta'^2/2 - g cos(theta)
# and T = theta'^2/2 computed here from the rows (m = l = 1).
for h in 0.5 0.1; do
  "$tmp/pend" --method rk4 --fixed-step $h --t-end 10 > "$tmp/fix$h.csv" 2> "$tmp/fix$h.err"
  echo $? >> "$tmp/fix$h.err"
done
set -- $(awk -F, 'NR > 1 { e = $3 * $3 / 2 - 9.81 * cos($2); t = $3 * $3 / 2
    if (NR == 2) e0 = e; d = e - e0; if (d < 0) d = -d; if (d > dh) dh = d; if (t > tm) tm = t }
    END { printf "%.3g %.3g %.2g", dh, tm, dh / tm }' "$tmp/fix0.5.csv")
grep -q "warning: fixed steps of 0.5: the conserved quantity E changed by $1, $3 of the largest kinetic energy ($2): fewer than two of its digits are right" "$tmp/fix0.5.err" &&
  [ "$(tail -1 "$tmp/fix0.5.err")" = 0 ] && [ "$(wc -l < "$tmp/fix0.1.err")" -eq 1 ] &&
  awk -F, 'NR > 1 { e = $3 * $3 / 2 - 9.81 * cos($2); t = $3 * $3 / 2
    if (NR == 2) e0 = e; d = e - e0; if (d < 0) d = -d; if (d > dh) dh = d; if (t > tm) tm = t }
    END { exit !(dh < 0.01 * tm) }' "$tmp/fix0.1.csv"
ok $? "fixed steps of 0.5 lose E (by $1, $3 of T's largest, $2): a warning; of 0.1: none"

# --error alone, --summary
"$tmp/pend" --error -o /dev/null --method rkf45 --rtol 1e-8 --atol 1e-8 2> "$tmp/err.err"
grep -q "error against the reference solution: at most .* over the 1001 rows" "$tmp/err.err"
ok $? "--error: one line on stderr with the run's error"
"$eomc" build "$src/specs/arenstorf.yaml" -o "$tmp/aren" 2> /dev/null
"$tmp/aren" --summary -o /dev/null 2> "$tmp/aren.err"
tr '\n' ' ' < "$tmp/aren.err" | grep -q "The conserved quantity h started at -1.4282062"
ok $? "arenstorf --summary: the conserved quantity is h, Jacobi's, not T + V"
"$tmp/aren" -o "$tmp/aren.csv" --t-end 0.1
[ "$(head -n 1 "$tmp/aren.csv")" = "t,x,y,x',y',T,V,E,h" ]
ok $? "... and its CSV has a column h after E"
# released from the horizontal, E = 0 up to rounding: its change is said
# against the largest kinetic energy, m g l = 9.81 at the bottom (not
# against E's own value, which would make it 1e+4 "relative")
"$tmp/pend" --init theta=1.5707963267948966 --summary -o /dev/null 2> "$tmp/flat.err"
tr '\n' ' ' < "$tmp/flat.err" | grep -q "its largest change was [0-9.e-]* ([0-9.]*e-1[0-9] of the largest kinetic energy, 9.81)\."
ok $? "--summary: E's change against the largest kinetic energy (9.81), also where E = 0"
"$eomc" build "$src/tests/sim/specs/cart_pole.yaml" -o "$tmp/cp" 2> /dev/null
"$tmp/cp" --summary -o /dev/null 2> "$tmp/cp.err"
tr '\n' ' ' < "$tmp/cp.err" | grep -q "No drift is reported: nothing is conserved: the effect 'drive' is a force, not a potential"
ok $? "a driven, damped cart-pole: --summary says nothing is conserved, and why"

# Digits by component: a heavy top spinning to 700 rad (phi), whose
# nutation rate theta' (up to 0.89) rkf45 at 1e-3 gets wrong by 0.05.
# Against the whole state's largest entry that would read 3.9 digits; each
# component against its own largest |x_ref| (at least 1e-6 of its group's)
# gives theta' 1.3, which the table names.  Computed here from the run's
# CSV and the reference's, both written by the simulator.
cat > "$tmp/top.yaml" <<'YAML'
name: top
parameters: {m: 1.0, l: 0.2, g: 9.81, A: 0.05, C: 0.02}
coordinates: [psi, theta, phi]
frames:
  body_axes: {rotation: [{z: psi}, {x: theta}, {z: phi}]}
points:
  centre: {frame: body_axes, at: [0, 0, l]}
bodies:
  top: {mass: m, frame: body_axes, center: centre, inertia: [A, A, C]}
effects:
  gravity: {gravity: [0, 0, -g]}
initial: {theta: 0.5, phi': 60}
scene: {t_end: 12, dt: 0.01, method: rkf45, rtol: 1e-3, atol: 1e-3}
YAML
"$eomc" build "$tmp/top.yaml" -o "$tmp/top" 2> /dev/null
"$tmp/top" --work-precision --methods rkf45 --tolerances 1e-3 --errors "$tmp/errs.csv" \
  > "$tmp/top.txt"; st1=$?
"$tmp/top" --reference-out "$tmp/topref.csv" -o "$tmp/toprun.csv" --errors "$tmp/errs1.csv" \
  2> "$tmp/top.err"; st2=$?
# per component: largest |x - x_ref|, largest |x_ref|, the floor of its group
read -r errs worst digits whole <<EOF
$(awk -F, 'NR == FNR { if (FNR > 1) for (i = 2; i <= 7; i++) { r[FNR, i] = $i
      a = $i < 0 ? -$i : $i; if (a > s[i]) s[i] = a }; next }
    FNR == 1 { for (i = 2; i <= 7; i++) name[i] = $i; next }
    { for (i = 2; i <= 7; i++) { d = $i - r[FNR, i]; if (d < 0) d = -d; if (d > e[i]) e[i] = d } }
    END { for (i = 2; i <= 7; i++) { g = i <= 4 ? 2 : 5; m = 0
        for (j = g; j < g + 3; j++) if (s[j] > m) m = s[j]
        sc = s[i] > 1e-6 * m ? s[i] : 1e-6 * m; dg = -log(e[i] / sc) / log(10)
        if (i == 2 || dg < best) { best = dg; worst = name[i] }
        if (e[i] > emax) emax = e[i]; if (s[i] > smax) smax = s[i] }
      for (i = 2; i <= 7; i++) printf "%s=%.17g;", name[i], e[i]
      printf " %s %.1f %.1f\n", worst, best, -log(emax / smax) / log(10) }' \
  "$tmp/topref.csv" "$tmp/toprun.csv")
EOF
row=$(grep '^  1e-03 ' "$tmp/top.txt")
[ $st1 -eq 0 ] && [ $st2 -eq 0 ] && [ "$worst" = "theta'" ] &&
  awk -v d="$digits" -v w="$whole" 'BEGIN { exit !(d + 2 < w) }' &&
  [ "$(echo "$row" | awk '{ print $10, $11 }')" = "$digits $worst" ]
ok $? "the report's digits are the worst component's, named: $worst $digits (against the whole state $whole): $(echo "$row" | awk '{ print $10, $11 }')"
# --errors: a row per run and component, the same errors as computed here
check_errors() { awk -F, -v errs="$errs" 'BEGIN { n = split(errs, kv, ";")
    for (k = 1; k < n; k++) { split(kv[k], p, "="); want[p[1]] = p[2] } }
  NR == 1 { bad = $0 != "method,tolerance,fixed_step,component,scale,error_end,error_max,digits"; next }
  { rows++; d = $7 - want[$4]; if (d < 0) d = -d
    if ($1 != "rkf45" || $2 != "0.001" || $3 != "" || !($4 in want) || d > 1e-12 * want[$4]) bad = 1 }
  END { exit bad || rows != 6 }' "$1"; }
check_errors "$tmp/errs.csv" && check_errors "$tmp/errs1.csv"
ok $? "--errors: one row per component with the same error_max, from the report and from one run"
grep -q "; theta' keeps the fewest digits, $digits$" "$tmp/top.err"
ok $? "--error's line names the component with the fewest digits ($digits, theta')"

# Robots at rest (MJCF through MuJoCo's loader; skipped without it).  A
# velocity group that is 0 at the start, and q'' that is 0 in exact
# arithmetic there but rounding in extended precision, once stopped the
# reference at t = 0; components near 0 beside large ones, judged finer
# than long double resolves, held its steps to rounding.
# state_diff A B [CF]: the largest |difference| of the state columns (those
# before T) of two CSVs of the same header, row by row; with CF = freefall,
# B is ignored and A is against the rigid fall from rest of
# tests/cli/rest_biped.xml: root_z = 1.3 - g t^2 / 2, root_z' = -g t, the
# quaternions (1, 0, 0, 0), all else 0
state_diff() {
  awk -F, -v cf="${3:-}" -v zv="root_z'" 'FNR == 1 { for (i = 2; i <= NF && $i != "T"; i++) name[i] = $i; last = i - 1; next }
    NR == FNR { for (i = 2; i <= last; i++) a[FNR, i] = $i; if (cf == "") next }
    { for (i = 2; i <= last; i++) {
        if (cf == "") w = a[FNR, i]
        else w = name[i] == "root_z" ? 1.3 - 9.81 * $1 * $1 / 2 : name[i] == zv ? -9.81 * $1 : name[i] ~ /_qw$/ ? 1 : 0
        d = $i - w; if (d < 0) d = -d; if (d > dm) dm = d } }
    END { printf "%.17g\n", dm }' "$1" "${2:-$1}"
}
"$eomc" import "$src/tests/cli/rest_biped.xml" > /dev/null 2> "$tmp/imp.err"; st=$?
if [ $st = 0 ] || ! grep -q 'libmujoco-dev' "$tmp/imp.err"; then
  export EOMC_CACHE_DIR="$tmp/cache"
  # a floating base with mirrored, damped legs and arms falls as one
  # rigid body (over 0.5, for the time the tests take)
  biped="$src/tests/cli/rest_biped.xml" span="--t-end 0.5 --dt 0.05"
  "$eomc" build "$biped" --extended -o "$tmp/biped" 2> /dev/null
  "$tmp/biped" $span --error --stats --reference-out "$tmp/bref.csv" -o "$tmp/brun.csv" \
    2> "$tmp/biped.err"; st=$?
  refe=$(stat_of reference_error "$tmp/biped.err") emax=$(stat_of error_max "$tmp/biped.err")
  steps=$(stat_of reference_steps "$tmp/biped.err")
  # the reference's rows and the closed form are each rounded to doubles
  bound=$(awk -v e="$refe" 'BEGIN { printf "%.3g", e + 2^-52 * 9.81 }')
  dref=$(state_diff "$tmp/bref.csv" "" freefall) drun=$(state_diff "$tmp/brun.csv" "" freefall)
  [ $st -eq 0 ] && [ -n "$refe" ] && within "$dref" 0 "$bound"
  ok $? "a floating base at rest, --error (exit $st): the reference is the rigid fall to $dref, within its own estimate $refe and rounding ($bound)"
  within "$emax" "$drun" "$bound"
  ok $? "... and the run's error it reports, $emax, is the run's against the fall, $drun"
  # GBS integrates a parabola exactly at any step: what holds its steps
  # is rounding (2890 steps when it was asked for digits below it)
  [ -n "$steps" ] && [ "$steps" -le 300 ]
  ok $? "... its steps are not held by rounding: $steps"
  "$eomc" accuracy "$biped" $span --methods rk8pd,rkf45 --tolerances 1e-6,1e-10 \
    --csv "$tmp/bwp.csv" > /dev/null 2>&1; st1=$?
  "$tmp/biped" $span --method rkf45 --rtol 1e-6 --atol 1e-6 -o "$tmp/brkf.csv" 2> /dev/null
  want=$(state_diff "$tmp/brkf.csv" "" freefall)
  got=$(awk -F, '$1 == "rkf45" && $2 == "1e-06" { print $10 }' "$tmp/bwp.csv")
  [ $st1 -eq 0 ] && [ "$(wc -l < "$tmp/bwp.csv")" -eq 5 ] && within "$got" "$want" "$bound"
  ok $? "... eomc accuracy (exit $st1): rkf45 at 1e-6 is off by $got, against the fall $want"
  # the doubles' q'' there is the closed form's to the bit (18 speeds: its two balls' and the
  # free joint's rotation are 3 each); the twin's is
  # it to long double's rounding, what the doubles print as 0 included
  "$tmp/biped" --accel-extended > "$tmp/bacc.txt" 2> /dev/null
  dacc=$(awk -v zv="root_z''" '/^lambda/ { next } { w = $1 == zv ? -9.81 : 0; d = $2 - w
      if (d < 0) d = -d; if (d > dm) dm = d; k++ } END { printf "%.3g", k == 18 ? dm : 1 }' "$tmp/bacc.txt")
  awk -v d="$dacc" 'BEGIN { exit !(d <= 2^-52 * 9.81) }'
  ok $? "... --accel-extended: q'' = (0, 0, -g, 0, ...) to $dacc, within a double's rounding of g"

  # an arm whose gripper's fingers a joint equality couples, at its default
  # pose: against rk8pd at 1e-13, in doubles, an independent solution
  grip="$src/tests/cli/rest_gripper.xml"
  "$eomc" build "$grip" --extended -o "$tmp/grip" 2> /dev/null
  "$tmp/grip" --error --stats --reference-out "$tmp/gref.csv" -o "$tmp/grun.csv" \
    2> "$tmp/grip.err"; st=$?
  "$tmp/grip" --method rk8pd --rtol 1e-13 --atol 1e-13 -o "$tmp/gtight.csv" 2> /dev/null
  dref=$(state_diff "$tmp/gtight.csv" "$tmp/gref.csv") drun=$(state_diff "$tmp/gtight.csv" "$tmp/grun.csv")
  emax=$(stat_of error_max "$tmp/grip.err")
  fingers=$(awk -F, 'NR > 1 { d = $5 - $6; if (d < 0) d = -d; if (d > dm) dm = d; if ($5 > f) f = $5 }
    END { printf "%.3g %.3g", dm, f }' "$tmp/gref.csv")
  [ $st -eq 0 ] && within "$dref" 0 1e-12 && [ "$(sed -n '1s/^t,j1,j2,j3,f1,f2,.*/ok/p' "$tmp/gref.csv")" = ok ] &&
    awk -v d="${fingers% *}" -v f="${fingers#* }" 'BEGIN { exit !(d <= 1e-17 && f > 1e-4) }'
  ok $? "an arm with coupled fingers at rest, --error (exit $st): the reference is rk8pd's at 1e-13 to $dref, its fingers equal to ${fingers% *} (open to ${fingers#* })"
  within "$emax" "$drun" 1e-12
  ok $? "... the run's error it reports, $emax, is the run's against rk8pd's, $drun"
  "$eomc" accuracy "$grip" --methods rk8pd,rkf45 --tolerances 1e-6,1e-10 \
    --csv "$tmp/gwp.csv" > /dev/null 2>&1; st1=$?
  "$tmp/grip" --method rkf45 --rtol 1e-10 --atol 1e-10 -o "$tmp/grkf.csv" 2> /dev/null
  want=$(state_diff "$tmp/gtight.csv" "$tmp/grkf.csv")
  got=$(awk -F, '$1 == "rkf45" && $2 == "1e-10" { print $10 }' "$tmp/gwp.csv")
  [ $st1 -eq 0 ] && [ "$(wc -l < "$tmp/gwp.csv")" -eq 5 ] && within "$got" "$want" 1e-12
  ok $? "... eomc accuracy (exit $st1): rkf45 at 1e-10 is off by $got, against rk8pd's $want"
  unset EOMC_CACHE_DIR
else
  for k in 1 2 3 4 5 6 7 8; do
    echo "ok $((n + 1)) # SKIP eomc import needs MuJoCo: $(head -1 "$tmp/imp.err")"
    n=$((n + 1))
  done
fi

# usage errors
"$tmp/pend" --csv "$tmp/x.csv" > /dev/null 2> "$tmp/u1.err"; st=$?
[ $st -eq 2 ] && grep -q -- "--csv belongs to --work-precision" "$tmp/u1.err" && [ ! -e "$tmp/x.csv" ]
ok $? "--csv without --work-precision: usage error (exit $st)"
"$tmp/pend" --work-precision --plot "$tmp/x.pdf" > /dev/null 2> "$tmp/u2.err"; st=$?
[ $st -eq 2 ] && grep -q "neither .svg nor .png" "$tmp/u2.err"
ok $? "--plot x.pdf: usage error (exit $st)"
"$tmp/pend" --work-precision --methods rk8pd,rk8pf > /dev/null 2> "$tmp/u3.err"; st=$?
[ $st -eq 2 ] && grep -q "unknown method 'rk8pf' (did you mean 'rk8pd'?)" "$tmp/u3.err"
ok $? "--methods with a typo: usage error with a suggestion (exit $st)"
"$tmp/pend" --work-precision --method rk8pd > /dev/null 2> "$tmp/u4.err"; st=$?
[ $st -eq 2 ] && grep -q -- "--methods chooses the report's" "$tmp/u4.err"
ok $? "--work-precision --method: usage error pointing to --methods (exit $st)"
"$tmp/pend" --work-precision --tolerances 1e-3,0 > /dev/null 2> "$tmp/u5.err"; st=$?
[ $st -eq 2 ] && grep -q -- "--tolerances: 0 is out of range" "$tmp/u5.err"
ok $? "--tolerances with a zero: usage error (exit $st)"

tap_end
