#!/bin/sh
# A scene's events against closed forms (TAP), computed here:
#  - a pendulum released from rest at theta0 reaches theta = 0 after a
#    quarter period K(sin(theta0/2)) / sqrt(g/l) (K by the arithmetic-
#    geometric mean): a stop event ends the run there, with a last row at
#    the event; recorded passes come every half period after it, and
#    recording changes nothing of the motion;
#  - a ball dropped from rest at height h with restitution e hits the
#    floor at t1 = sqrt(2h/g) and then at t1 + (2 v1/g) e (1 - e^k)/(1 - e),
#    v1 = g t1; where the bounces accumulate (t1 (1 + 2e/(1 - e))) the run
#    stops with exit status 3, the rows before kept, and never hangs;
#  - resets on a constrained model (the Cartesian pendulum turned back at
#    the bottom, or set off its rod), with the default method and with
#    Taylor's (the KKT system's series);
#  - an event the scene does not ask for leaves no trace in its C;
#  - a grazing event (tests/sim/specs/graze.yaml: x = cos t, the event
#    x = 0.999) crosses twice 0.089 apart around each maximum, inside one
#    step where the steps are long: every method finds all 7 crossings up
#    to t = 20 (3 of them upward), at 2 pi k -+ acos(0.999).
# usage: test_events.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
swing="$src/specs/swing.yaml" ball="$src/specs/bouncing_ball.yaml"

# the quarter period, K(k) = pi / (2 agm(1, sqrt(1 - k^2))), theta0 = 1, g = 9.81, l = 1
quarter=$(awk 'BEGIN { k = sin(0.5); a = 1; b = sqrt(1 - k * k)
    for (i = 0; i < 40; i++) { m = (a + b) / 2; b = sqrt(a * b); a = m }
    printf "%.17g", 3.14159265358979323846 / (2 * a) / sqrt(9.81) }')

"$eomc" run "$swing" --scene quarter > "$tmp/quarter.csv" 2> "$tmp/err"; st=$?
last=$(tail -1 "$tmp/quarter.csv" | cut -d, -f1)
[ $st -eq 0 ] && within "$last" "$quarter" 1e-10
ok $? "stop at theta = 0: the last row is at t = $last, the quarter period $quarter"
theta=$(tail -1 "$tmp/quarter.csv" | cut -d, -f2)
before=$(tail -2 "$tmp/quarter.csv" | head -1 | cut -d, -f1)
within "$theta" 0 1e-12 && awk -v a="$before" -v b="$last" 'BEGIN { exit !(a < b && b - a < 0.01) }'
ok $? "the last row is the event itself (theta = $theta), after the row at $before"

"$eomc" run "$swing" --scene passes --events "$tmp/passes.csv" > "$tmp/passes_rows.csv"; st1=$?
"$eomc" run "$swing" --scene free > "$tmp/free_rows.csv"; st2=$?
[ $st1 -eq 0 ] && [ $st2 -eq 0 ] && [ "$(wc -l < "$tmp/free_rows.csv")" -gt 100 ] &&
  cmp -s "$tmp/passes_rows.csv" "$tmp/free_rows.csv"
ok $? "recording events changes nothing of the motion (the same rows as scene free)"
head -1 "$tmp/passes.csv" | grep -qx "t,event,theta,theta'"
ok $? "--events writes the header t,event,theta,theta'"
worst=$(awk -F, -v q="$quarter" 'NR > 1 { want = q * (2 * (NR - 2) + 1); d = $1 - want
    if (d < 0) d = -d; if (d > w) w = d; rows++ }
    END { if (rows != 9) print "rows?"; else printf "%.3g", w }' "$tmp/passes.csv")
awk -v w="$worst" 'BEGIN { exit !(w != "" && w != "rows?" && w + 0 <= 1e-10) }'
ok $? "the 9 passes through the bottom come at (2k + 1) T/4, to $worst"

# the bouncing ball: h = 1, g = 9.81, e = 0.5
"$eomc" run "$ball" --events "$tmp/impacts.csv" > "$tmp/ball.csv"; st=$?
worst=$(awk -F, 'NR > 1 { g = 9.81; h = 1; e = 0.5; t1 = sqrt(2 * h / g); v1 = g * t1
    k = NR - 2; want = t1 + 2 * v1 / g * e * (1 - e ^ k) / (1 - e)
    d = $1 - want; if (d < 0) d = -d; if (d > w) w = d
    y = $3 < 0 ? -$3 : $3; if (y > wy) wy = y; rows++ }
    END { if (rows != 3) print "rows?"; else printf "%.3g %.3g", w, wy }' "$tmp/impacts.csv")
set -- $worst
[ $st -eq 0 ] && awk -v w="$1" -v y="${2:-1}" 'BEGIN { exit !(w != "rows?" && w <= 1e-10 && y <= 1e-12) }'
ok $? "the three impacts up to t = 1.2 at their closed-form times, to $1 (y there within ${2:-?} of 0)"
lowest=$(awk -F, 'NR > 1 && (m == "" || $2 < m) { m = $2 } END { print m }' "$tmp/ball.csv")
awk -v y="$lowest" 'BEGIN { exit !(y >= -1e-12) }'
ok $? "the ball never goes through the floor: its lowest row is y = $lowest"

rest=$(awk 'BEGIN { t1 = sqrt(2 / 9.81); printf "%.17g", t1 * (1 + 2 * 0.5 / 0.5) }')
timeout 60 "$eomc" run "$ball" --t-end 3 > "$tmp/zeno.csv" 2> "$tmp/zeno.err"; st=$?
at=$(sed -n 's/.*error: t = \([0-9.e+-]*\): the events accumulate.*/\1/p' "$tmp/zeno.err")
lastrow=$(tail -1 "$tmp/zeno.csv" | cut -d, -f1)
[ $st -eq 3 ] && within "$at" "$rest" 1e-6 &&
    awk -v t="$lastrow" -v r="$rest" 'BEGIN { exit !(t <= r && t > r - 0.02) }' &&
    grep -q "rows computed up to then, to t = $lastrow, are kept" "$tmp/zeno.err"
ok $? "bounces accumulating at t = $rest: exit $st at t = $at, rows kept up to $lastrow"
timeout 60 "$eomc" run "$ball" --set e=0 > /dev/null 2> "$tmp/rest.err"; st=$?
[ $st -eq 3 ] && grep -q 'floor holds again at the end of the first step after its reset' "$tmp/rest.err"
ok $? "restitution 0 (the ball stays on the floor): exit $st, the cause named"

"$eomc" compile "$swing" --scene free -o "$tmp/free.c"
"$eomc" compile "$swing" --scene quarter -o "$tmp/quarter.c"
! grep -q '_events\|ev_names' "$tmp/free.c" && grep -q 'swing_events,' "$tmp/quarter.c" &&
    ! grep -q '_event_set' "$tmp/quarter.c"
ok $? "events leave no code in a scene without them, and no reset without a set event"

"$eomc" run "$ball" --error > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'reference solution does not follow' "$tmp/err"
ok $? "--error with events that reset the motion is a usage error (exit $st)"
"$eomc" run "$swing" --scene free --events "$tmp/none.csv" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/none.csv" ]
ok $? "--events for a scene without events: exit $st, no file"

# A `set` that does not turn the motion back passes through its event: a
# particle falling from y = 1 gets x' = 1 as it crosses y = 0.5, at
# t_h = sqrt(2 * 0.5 / g), and falls on; x(1) = 1 - t_h.
cat > "$tmp/kick.yaml" <<'YAML'
name: kick
parameters: {g: 9.81}
coordinates: [x, y]
particles:
  p: {mass: 1, position: [x, y]}
effects:
  gravity: {gravity: [0, -g]}
initial: {y: 1}
scene:
  t_end: 1
  rtol: 1e-12
  atol: 1e-12
  events:
    half: {when: y - 0.5, direction: down, action: {set: {"x'": 1}}}
YAML
th=$(awk 'BEGIN { printf "%.17g", sqrt(1 / 9.81) }')
"$eomc" run "$tmp/kick.yaml" --events "$tmp/kick_ev.csv" > "$tmp/kick.csv" 2> "$tmp/kick.err"; st=$?
xend=$(tail -1 "$tmp/kick.csv" | cut -d, -f2) tev=$(sed -n 2p "$tmp/kick_ev.csv" | cut -d, -f1)
[ $st -eq 0 ] && [ ! -s "$tmp/kick.err" ] && [ "$(wc -l < "$tmp/kick_ev.csv")" -eq 2 ] &&
  within "$tev" "$th" 1e-12 && within "$xend" "$(awk -v t="$th" 'BEGIN { printf "%.17g", 1 - t }')" 1e-12
ok $? "a kick passes through its event: once at t = $tev ($th), then x(1) = $xend = 1 - t_h"

# A reset that keeps the motion crossing, but slowly: y' = s y' at the
# event y = 1/2 (g = y - 1/2, so g's rate after is exactly s of the one
# it arrived with).  Over a millionth it passes through; below, the event
# is held, and the motion going on below it stops the run (exit 3, the
# rows kept) with a message that names that share, 1e-08 for s = 1e-8,
# not a return.  The share is of the rate at the event, not at the start
# of the step that found it (that was -1.35, not -3.13: 2.3e-08 printed,
# and s = 0.999e-6 passed).
slow() {
    sed -e "s/x'\": 1/y'\": \"$1*y'\"/" -e 's/name: kick/name: slow/' "$tmp/kick.yaml" > "$tmp/slow.yaml"
    "$eomc" run "$tmp/slow.yaml" > "$tmp/slow.csv" 2> "$tmp/slow.err"
}
slow 1e-8; st=$?
[ $st -eq 3 ] && grep -q 'event half holds still .* crossing it at 1e-08 of the rate it arrived with' "$tmp/slow.err" &&
  [ "$(wc -l < "$tmp/slow.csv")" -gt 1 ] &&
  grep -q "rows computed up to then, to t = $(tail -1 "$tmp/slow.csv" | cut -d, -f1), are kept" "$tmp/slow.err"
ok $? "a reset leaving the crossing at 1e-8 of its rate stops with exit 3 naming that share"
slow 0.999e-6; st1=$?; slow 1.001e-6; st2=$?
[ $st1 -eq 3 ] && [ $st2 -eq 0 ] && [ ! -s "$tmp/slow.err" ]
ok $? "the pass threshold is a millionth of the rate at the event: 0.999e-6 held ($st1), 1.001e-6 passes ($st2)"

# Resets on a constrained model: the pendulum of cartesian_pendulum.yaml
# (theta0 = 1), an event at the bottom (x = 0, falling).  Turning the bob
# back (x' = -x') keeps it on the rod: no warning, and it is back at the
# bottom after another half period, at 3T/4.  Setting y' = 0.001 breaks
# the velocity constraint g' = 2 (x x' + y y') = 0: the warning's share
# is the velocity's part along the rod, 0.001 / |v| (|v| at the bottom
# sqrt(2 g (1 - cos 1))), and without projection g' stays at
# 2 y y' = -0.002 (the equations hold g'' = 0), so g(2) = -0.002 (2 - T/4).
cat > "$tmp/rod.yaml" <<'YAML'
name: rod
parameters: {m: 1.0, l: 1.0, g: 9.81}
coordinates: [x, y]
particles:
  bob: {mass: m, position: [x, y]}
effects:
  gravity: {gravity: [0, -g]}
constraints:
  rod: x^2 + y^2 - l^2
initial: {x: l*sin(1), y: -l*cos(1)}
scenes:
  back:
    t_end: 2
    rtol: 1e-12
    atol: 1e-12
    events:
      bottom: {when: x, direction: down, action: {set: {"x'": "-x'"}}}
  off:
    t_end: 2
    rtol: 1e-12
    atol: 1e-12
    events:
      bottom: {when: x, direction: down, action: {set: {"y'": 0.001}}}
YAML
"$eomc" run "$tmp/rod.yaml" --scene back --events "$tmp/back_ev.csv" > /dev/null 2> "$tmp/back.err"; st=$?
t1=$(sed -n 2p "$tmp/back_ev.csv" | cut -d, -f1) t2=$(sed -n 3p "$tmp/back_ev.csv" | cut -d, -f1)
[ $st -eq 0 ] && [ ! -s "$tmp/back.err" ] && within "$t1" "$quarter" 1e-9 &&
  within "$t2" "$(awk -v q="$quarter" 'BEGIN { printf "%.17g", 3 * q }')" 1e-9
ok $? "a reset that keeps the constraints: no warning; at the bottom at T/4 = $t1 and 3T/4 = $t2"
# the same under Taylor's method (the KKT system's series, the step's
# polynomial between events): to 1e-14
"$eomc" run "$tmp/rod.yaml" --scene back --method taylor --events "$tmp/back_ev.csv" > /dev/null \
    2> "$tmp/back.err"; st=$?
t1=$(sed -n 2p "$tmp/back_ev.csv" | cut -d, -f1) t2=$(sed -n 3p "$tmp/back_ev.csv" | cut -d, -f1)
[ $st -eq 0 ] && [ ! -s "$tmp/back.err" ] && within "$t1" "$quarter" 1e-14 &&
  within "$t2" "$(awk -v q="$quarter" 'BEGIN { printf "%.17g", 3 * q }')" 1e-14
ok $? "the same under taylor: at the bottom at T/4 = $t1 and 3T/4 = $t2 (to 1e-14)"
"$eomc" run "$tmp/rod.yaml" --scene off > "$tmp/off.csv" 2> "$tmp/off.err"; st=$?
share=$(awk 'BEGIN { v = sqrt(2 * 9.81 * (1 - cos(1))); printf "%.2g", 0.001 / sqrt(v * v + 1e-6) }')
res=$(tail -1 "$tmp/off.csv" | awk -F, '{ print $NF }')
[ $st -eq 0 ] && grep -q "warning: t = 0.534784: event bottom set velocities that violate the constraint rod: its residual is $share of the size of its terms; the motion from there drifts off the constraints (column res\[rod\] shows how far" "$tmp/off.err" &&
  within "$res" "$(awk -v q="$quarter" 'BEGIN { printf "%.17g", -0.002 * (2 - q) }')" 1e-9
ok $? "a reset off the constraints: a warning naming event and constraint (share $share), and g(2) = $res = -0.002 (2 - T/4)"
"$eomc" run "$tmp/rod.yaml" --scene off --method taylor > "$tmp/off.csv" 2> "$tmp/off.err"; st=$?
res=$(tail -1 "$tmp/off.csv" | awk -F, '{ print $NF }')
[ $st -eq 0 ] && grep -q "warning: t = 0.534784: event bottom set velocities that violate the constraint rod" "$tmp/off.err" &&
  within "$res" "$(awk -v q="$quarter" 'BEGIN { printf "%.17g", -0.002 * (2 - q) }')" 1e-13
ok $? "the same under taylor: the warning, and g(2) = $res = -0.002 (2 - T/4) (to 1e-13)"
"$eomc" run "$tmp/rod.yaml" --scene off --stats -o /dev/null 2> "$tmp/offs.err"
grep -qx "reset_event bottom" "$tmp/offs.err" && grep -qx "reset_constraint rod" "$tmp/offs.err" &&
  [ "$(awk '/^reset_inconsistency / { printf "%.3g", $2 }' "$tmp/offs.err")" = \
    "$(awk 'BEGIN { v = sqrt(2 * 9.81 * (1 - cos(1))); printf "%.3g", 0.001 / sqrt(v * v + 1e-6) }')" ] &&
  within "$(sed -n 's/^t_reset //p' "$tmp/offs.err")" "$quarter" 1e-9
ok $? "--stats: reset_event, t_reset (T/4), reset_constraint, reset_inconsistency ($share)"
"$eomc" run "$tmp/rod.yaml" --scene off --stabilize project > "$tmp/offp.csv" 2> "$tmp/offp.err"; st=$?
res=$(tail -1 "$tmp/offp.csv" | awk -F, '{ print $NF }')
[ $st -eq 0 ] && grep -q "the projection after the next step moved the state back onto the constraints" "$tmp/offp.err" &&
  within "$res" 0 1e-12
ok $? "the same with --stabilize project: the warning says the projection undid it; g(2) = $res"
# The bob in space, on the rod and in the plane z = 0: a reset of y' and
# z' at the bottom (0, -l, 0) leaves both velocity constraints, the rod's
# g' = 2 y y' (share 0.001 / |v|, as above) and the plane's z' (0.002 /
# |v|, B = (0, 0, 1) against m |v|): the warning names both, worst first.
cat > "$tmp/rod3.yaml" <<'YAML'
name: rod3
parameters: {m: 1.0, l: 1.0, g: 9.81}
coordinates: [x, y, z]
particles:
  bob: {mass: m, position: [x, y, z]}
effects:
  gravity: {gravity: [0, -g, 0]}
constraints:
  rod: x^2 + y^2 + z^2 - l^2
  plane: z
initial: {x: l*sin(1), y: -l*cos(1)}
scene:
  t_end: 1
  rtol: 1e-12
  atol: 1e-12
  events:
    bottom: {when: x, direction: down, action: {set: {"y'": 0.001, "z'": 0.002}}}
YAML
"$eomc" run "$tmp/rod3.yaml" -o /dev/null 2> "$tmp/rod3.err"; st=$?
shares=$(awk 'BEGIN { v = sqrt(2 * 9.81 * (1 - cos(1)) + 5e-6); printf "plane (velocities: %.2g), rod (velocities: %.2g)", 0.002 / v, 0.001 / v }')
[ $st -eq 0 ] && grep -qF "event bottom set a state off the constraints, worst first: $shares (each residual" "$tmp/rod3.err"
ok $? "a reset off two constraints: the warning names both, worst first: $shares"

# the grazing pairs, each method at rtol 1e-12 and 1e-8 (longer steps);
# the error in a crossing's time is g's over its rate there,
# sin(acos(0.999)) = 0.0447, and each bound about 5 times what the method
# measured
for mb in rk8pd:1e-12:5e-11 rkf45:1e-12:2e-9 msadams:1e-12:1e-8 msbdf:1e-12:5e-7 \
          bsimp:1e-12:5e-11 rk4imp:1e-12:2e-9 taylor:1e-12:5e-12 rk8pd:1e-8:1e-6 \
          rkf45:1e-8:1.5e-5 msadams:1e-8:3e-5 msbdf:1e-8:2e-4 bsimp:1e-8:5e-6 rk4imp:1e-8:2e-6 \
          taylor:1e-8:2e-8; do
  m=${mb%%:*} rest=${mb#*:}
  tol=${rest%%:*} bound=${rest#*:}
  "$eomc" run "$src/tests/sim/specs/graze.yaml" --method "$m" --rtol "$tol" --atol "$tol" \
      --events "$tmp/graze.csv" -o /dev/null 2> "$tmp/graze.err"
  st=$?
  set -- $(awk -F, 'NR > 1 { a = atan2(sqrt(1 - 0.999^2), 0.999)
      if ($2 == "top") { n++; k = int(n / 2); want = 2 * 3.14159265358979323846 * k + (n % 2 ? a : -a) }
      else { u++; want = 2 * 3.14159265358979323846 * u - a }
      d = $1 - want; d = d < 0 ? -d : d; if (d > m) m = d } END { printf "%d %d %.2g", n, u, m }' \
      "$tmp/graze.csv")
  [ $st = 0 ] && [ "$1" = 7 ] && [ "$2" = 3 ] && awk -v d="$3" -v b="$bound" 'BEGIN { exit !(d <= b) }'
  ok $? "graze, $m at $tol: $1 crossings of x = 0.999 (7), $2 upward (3), within $3 of 2 pi k -+ acos(0.999) (<= $bound)"
done

tap_end
