#!/bin/sh
# Dry friction (effect items `friction: q, force: F`) against closed forms
# (TAP):
#  - a block slid along the floor at v0 with friction mu m g
#    (tests/cli/friction_slope.yaml, th = 0) decelerates at mu g: it stops
#    at v0^2 / (2 mu g) at t = v0 / (mu g), by rk8pd, rkf45, msadams and
#    bsimp, and stays there: its position over the next 10 s moves by at
#    most 1e-9 of that distance (it is held exactly: its speed is set to 0
#    where it sticks, its acceleration is 0 while it is stuck);
#  - released at rest on a slope of 20 degrees with mu = 0.5 (tan 20 deg
#    = 0.364 < mu) it stays, within 1e-9 m over 10 s; with mu = 0.2 it
#    slides with a = g (sin th - mu cos th);
#  - Coulomb's oscillator (friction_spring.yaml: y'' = -k y / m -+ F / m,
#    w = sqrt(k / m)): each half-swing takes pi / w and ends at
#    y_(n+1) = -y_n + 2 F/k sign(y_n); it sticks for good at the first
#    turn where |k y| <= F;
#  - the same block pushed by c t from rest (effect ramp) is held until
#    c t = F, at t = F / c, then slides: y = c (t - F/c)^3 / (6 m);
#  - --error on the block and on the oscillator says the error the closed
#    form says (at loose tolerances, where it is large), and so does the
#    reference's own record of the flips (no warning of a parting);
#  - a double pendulum with friction on both joints comes to rest where
#    the torques that hold it are within both bounds, the reference's
#    flips the run's;
#  - Taylor's method and a model with constraints are refused by name; a
#    bound below 0 (a force that depends on the state) stops the run.
# usage: test_friction.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
slope="$src/tests/cli/friction_slope.yaml"
spring="$src/tests/cli/friction_spring.yaml"
tight="--rtol 1e-12 --atol 1e-12"
th20=$(awk 'BEGIN { printf "%.17g", 20 * 3.14159265358979323846 / 180 }')

# the block on the floor: the stop, and the 10 s after it
want=$(awk 'BEGIN { m = 2; g = 9.81; mu = 0.3; v0 = 3
    printf "%.17g %.17g", v0 * v0 / (2 * mu * g), v0 / (mu * g) }')
d=${want% *} ts=${want#* }
t_end=$(awk -v t="$ts" 'BEGIN { printf "%.17g", t + 10 }')
fine=0 got=
for m in rk8pd rkf45 msadams bsimp; do
  "$eomc" run "$slope" --method $m $tight --t-end "$t_end" --events "$tmp/ev.csv" \
    > "$tmp/rows.csv" 2> "$tmp/err" || continue
  stop=$(awk -F, '$2 == "floor.s.stick" { print $1 "," $3 }' "$tmp/ev.csv")
  last=$(tail -1 "$tmp/rows.csv" | cut -d, -f2,3)
  within "${stop#*,}" "$d" 1e-11 && within "${stop%,*}" "$ts" 1e-11 &&
    awk -F, -v s="${stop#*,}" -v d="$d" -v l="$last" 'BEGIN { split(l, x, ",")
        e = x[1] - s; if (e < 0) e = -e; exit !(e <= 1e-9 * d && x[2] == 0) }' &&
    fine=$((fine + 1)) got="$got $m: $stop;"
done
[ $fine -eq 4 ]
ok $? "a block slid along the floor stops at v0^2/(2 mu g) = $d at t = v0/(mu g) = $ts, and stays 10 s ($got)"

# the slope: held at mu = 0.5, sliding at mu = 0.2
"$eomc" run "$slope" --set th=$th20 --set mu=0.5 --set v0=0 --t-end 10 --events "$tmp/ev.csv" \
  > "$tmp/rows.csv"; st=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 1 ] &&
  awk -F, 'NR > 1 { if ($2 < 0) $2 = -$2; if ($2 > 1e-9 || $3 != 0) bad = 1 } END { exit bad || NR < 2 }' \
    "$tmp/rows.csv"
ok $? "a box released at rest on a 20 degree slope with mu = 0.5 stays put: s = $(tail -1 "$tmp/rows.csv" | cut -d, -f2) at t = 10"
want=$(awk 'BEGIN { g = 9.81; th = 20 * 3.14159265358979323846 / 180; a = g * (sin(th) - 0.2 * cos(th))
    printf "%.17g", -a * 50 }')
"$eomc" run "$slope" --set th=$th20 --set mu=0.2 --set v0=0 --t-end 10 $tight \
  --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
got=$(tail -1 "$tmp/rows.csv" | cut -d, -f2)
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 1 ] &&
  awk -v g="$got" -v w="$want" 'BEGIN { e = (g - w) / w; if (e < 0) e = -e; exit !(e <= 1e-12) }'
ok $? "with mu = 0.2 it slides down: s(10) = -a 10^2/2 = $want, a = g (sin th - mu cos th) ($got)"

# Coulomb's oscillator: every turn, and the stick
cat > "$tmp/osc.awk" <<'AWK'
BEGIN { k = 4; m = 1; F = 0.7; y = 3; w = sqrt(k / m); pi = 3.14159265358979323846
        n = 0; while (y > F / k || y < -F / k) { y = -y + (y > 0 ? 2 : -2) * F / k; n++
        printf "%.17g %.17g\n", n * pi / w, y } }
AWK
awk -f "$tmp/osc.awk" > "$tmp/turns"
"$eomc" run "$spring" $tight --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
awk -F, '$2 == "friction.y.slip" { print $1, $3 }' "$tmp/ev.csv" > "$tmp/got"
last=$(tail -1 "$tmp/turns")
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/got")" -eq "$(wc -l < "$tmp/turns")" ] &&
  paste -d' ' "$tmp/got" "$tmp/turns" | awk '{ for (i = 1; i <= 2; i++) { e = $i - $(i + 2)
      if (e < 0) e = -e; if (e > 1e-11) bad = 1 } } END { exit bad }' &&
  [ "$(awk -F, '$2 == "friction.y.stick"' "$tmp/ev.csv" | wc -l)" -eq 1 ] &&
  awk -F, '$2 == "friction.y.stick" { print $1, $3 }' "$tmp/ev.csv" |
    awk -v l="$last" '{ split(l, w, " "); if ((e = $1 - w[1]) < 0) e = -e; if ((f = $2 - w[2]) < 0) f = -f
                        exit !(e <= 1e-11 && f <= 1e-11) }' &&
  tail -1 "$tmp/rows.csv" | awk -F, -v l="$last" '{ split(l, w, " "); exit !($2 == w[2] + 0 || $3 == 0) }'
ok $? "Coulomb's oscillator: $(wc -l < "$tmp/turns") half-swings, each losing 2F/k, turning at n pi/w; it sticks for good at (t, y) = ($last) where |k y| <= F"

# the ramp: held until c t = F, then y = c (t - F/c)^3 / (6 m)
"$eomc" run "$spring" --effects ramp,friction --set c=3 --set F=4.5 --set m=2 --set y0=0 \
  --t-end 3 $tight --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
unstick=$(awk -F, '$2 == "friction.y.stick" { print $1 }' "$tmp/ev.csv")
got=$(tail -1 "$tmp/rows.csv" | cut -d, -f2,3)
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 2 ] && within "$unstick" 1.5 4e-16 &&
  within "${got%,*}" 0.84375 1e-13 && within "${got#*,}" 1.6875 1e-13
ok $? "a block pulled by c t from rest is held until c t = F, t = 1.5 ($unstick), then slides: y(3) = 0.84375, y'(3) = 1.6875 ($got)"

# --error against the closed forms: the report within 10% of the truth,
# and 100 times smaller at 1e-9 than at 1e-6 (the block by msadams: its
# motion is quadratic in t, which a Runge-Kutta method of order 2 or more
# integrates exactly; the oscillator by rkf45)
for case in block oscillator; do
  for e in 6 9; do
    if [ $case = block ]; then
      "$eomc" run "$slope" --method msadams --rtol 1e-$e --atol 1e-$e --error --stats \
        > "$tmp/run$e.csv" 2> "$tmp/err$e"
      eval "true$e=$(tail -1 "$tmp/run$e.csv" | awk -F, -v d="$d" '{ e = $2 - d; print e < 0 ? -e : e }')"
    else
      "$eomc" run "$spring" --method rkf45 --rtol 1e-$e --atol 1e-$e --error --stats \
        > "$tmp/run$e.csv" 2> "$tmp/err$e"
      eval "true$e=$(tail -1 "$tmp/run$e.csv" | awk -F, -v y="${last#* }" '{ e = $2 - y; print e < 0 ? -e : e }')"
    fi
    eval "said$e=$(awk '$1 == "error_end" { print $2 }' "$tmp/err$e")"
    grep -q "warning" "$tmp/err$e" && eval "said$e=warned"
  done
  awk -v t6="$true6" -v s6="$said6" -v t9="$true9" -v s9="$said9" 'BEGIN {
        ok = t6 > 0 && t9 > 0 && s6 / t6 < 1.1 && t6 / s6 < 1.1 && s9 / t9 < 1.1 &&
             t9 / s9 < 1.1 && t9 < t6 / 100 && s9 < s6 / 100; exit !ok }'
  ok $? "$case: --error says $said6 and $said9 at rtol 1e-6 and 1e-9; the closed form, $true6 and $true9"
done

# two items coupled: a double pendulum with friction on both joints
# (torques of at most 2 and 1.5) comes to rest held by both, where the
# torques that hold it against gravity, (m1 + m2) g l1 sin th1 and
# m2 g l2 sin th2 (m = l = 1), are within the bounds; the reference
# flips the same switches at the same times (no warning)
sed -e 's/  gravity: {gravity: \[0, -g\]}/  gravity: {gravity: [0, -g]}\n  joints: [{friction: th1, force: 2}, {friction: th2, force: 1.5}]/' \
  -e 's/t_end: 10/t_end: 20/' "$src/specs/double_pendulum.yaml" > "$tmp/dpf.yaml"
"$eomc" run "$tmp/dpf.yaml" --error --stats > "$tmp/rows.csv" 2> "$tmp/err"; st=$?
end=$(tail -1 "$tmp/rows.csv" | cut -d, -f2-5)
[ $st -eq 0 ] && ! grep -q warning "$tmp/err" && grep -q "^reference_switches 22$" "$tmp/err" &&
  grep -q "^switches 22$" "$tmp/err" &&
  echo "$end" | awk -F, '{ t1 = 2 * 9.81 * sin($1); t2 = 9.81 * sin($2); if (t1 < 0) t1 = -t1
      if (t2 < 0) t2 = -t2; exit !($3 == 0 && $4 == 0 && t1 <= 2 && t2 <= 1.5 && $1 != 0) }'
ok $? "a double pendulum with friction on both joints comes to rest held by both (th1, th2 = $(echo "$end" | cut -d, -f1,2)); 22 flips, the reference's the same"

# refused by name, or stopped
"$eomc" run "$slope" --method taylor > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "taylor: friction_slope has dry friction (floor.s)" "$tmp/err"
ok $? "Taylor's method refused by name, exit 2"
cat > "$tmp/rod.yaml" <<'EOF'
name: rod
parameters: {m: 1}
coordinates: [x, y]
particles:
  bob: {mass: m, position: [x, y]}
effects:
  gravity: {gravity: [0, -9.81]}
  drag: {friction: x, force: 0.1}
constraints:
  rod: x^2 + y^2 - 1
initial: {x: 0.6, y: -0.8}
EOF
"$eomc" run "$tmp/rod.yaml" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "rod has dry friction (drag.x) and constraints" "$tmp/err"
ok $? "a model with constraints refused by name, exit 2"
"$eomc" run "$slope" --set mu=-0.1 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "dry friction on 's': its force cannot be negative" "$tmp/err"
ok $? "--set making the bound negative: refused, exit 2 ($(head -1 "$tmp/err"))"
sed 's/force: mu\*m\*g\*cos(th)/force: "mu*m*g*cos(th) - 10*s"/' "$slope" > "$tmp/neg.yaml"
"$eomc" run "$tmp/neg.yaml" > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 3 ] && grep -q "dry friction floor.s: its force is -[0-9.e+-]*, below 0" "$tmp/err"
ok $? "a bound of the state that falls below 0 stops the run, exit 3"
tap_end
