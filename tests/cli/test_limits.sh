#!/bin/sh
# Stops (`limit:` effect items) and saturation written in a spec, against
# closed forms (TAP), on tests/cli/stops.yaml: a pendulum of inertia
# I = m l^2 = 1, its stops at lo and hi each a spring-damper k d + c d' on
# the penetration d that only pushes.
#  - gravity off (a rotor) coming in at w0 = 1: the stop is reached at
#    t0 = hi/w0; inside, d = (w0/w_d) e^(-zeta w t) sin(w_d t) (w^2 = k/I,
#    zeta = c/(2 sqrt(k I)), w_d = w sqrt(1 - zeta^2)) until the push would
#    pull, k d + c d' = 0, at w_d t1 = pi - atan2(2 zeta sqrt(1 - zeta^2),
#    1 - 2 zeta^2); the rotor leaves at d'(t1) and coasts out of the stop
#    at t0 + t1 + d(t1)/|d'(t1)|.  The push's switch also flips once
#    outside, where k d + c d' = 0 on the way in (at (hi - c w0/k)/w0: the
#    force is 0 either way there);
#  - the same with an end left open (null, or .inf on its side), and at
#    the lower stop, mirrored;
#  - a motor's torque clamp(u, -tau_max, tau_max): a constant u beyond
#    tau_max turns the rotor from rest as tau_max t^2/(2 I), one within
#    it as u t^2/(2 I);
#  - --linearize inside a stop (with gravity) against central differences
#    of --accel; on a kink, the warning naming its switches;
#  - --equilibrium against a stop: k (lo - theta) = m g l sin(theta),
#    solved here by bisection; with lo = 0 the equilibrium is the stop's
#    edge, a kink, and says so;
#  - a negative stiffness or a reversed range by --set: refused.
# usage: test_limits.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
spec="$src/tests/cli/stops.yaml"

# the rotor's contact: t1, d'(t1) and d(t1) (k = 100, c = 4, I = 1, w0 = 1)
want=$(awk 'BEGIN { I = 1; k = 100; c = 4; w0 = 1
    w = sqrt(k / I); z = c / (2 * sqrt(k * I)); s = sqrt(1 - z * z); wd = w * s; a = z * w
    t1 = (3.14159265358979323846 - atan2(2 * z * s, 1 - 2 * z * z)) / wd
    e = exp(-a * t1); d1 = (w0 / wd) * e * sin(wd * t1)
    v1 = (w0 / wd) * e * (-a * sin(wd * t1) + wd * cos(wd * t1))
    printf "%.17g %.17g %.17g", 0.5 + t1, v1, 0.5 + t1 + d1 / -v1 }')
set -- $want
release=$1 v1=$2 out=$3
# contact CSV EVENTS END: the stop's four flips (named END) at the times above
contact() {
  [ "$(wc -l < "$2")" -eq 5 ] &&
    [ "$(sed -n 2,5p "$2" | cut -d, -f2 | tr '\n' ' ')" = "stops.theta.$3.push stops.theta.$3 stops.theta.$3.push stops.theta.$3 " ] &&
    within "$(sed -n 2p "$2" | cut -d, -f1)" 0.46 1e-13 &&
    within "$(sed -n 3p "$2" | cut -d, -f1)" 0.5 1e-13 &&
    within "$(sed -n 4p "$2" | cut -d, -f1)" "$release" 1e-12 &&
    within "$(sed -n 5p "$2" | cut -d, -f1)" "$out" 1e-12
}
"$eomc" run "$spec" --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
[ $st -eq 0 ] && contact "$tmp/rows.csv" "$tmp/ev.csv" hi
ok $? "rotor into its upper stop: reached at 0.5, the push ends at $release, out at $out ($(cut -d, -f1,2 "$tmp/ev.csv" | tail -n +2 | tr '\n' ' '))"
within "$(tail -1 "$tmp/rows.csv" | cut -d, -f3)" "$v1" 1e-12
ok $? "rotor: it leaves at d'(t1) = $v1 ($(tail -1 "$tmp/rows.csv" | cut -d, -f3))"

# one end open: the same motion at the end that is there
for range in '[~, hi]' '[-.inf, hi]' '[lo, null]' '[lo, .inf]'; do
  sed "s/range: \[lo, hi\]/range: $range/" "$spec" > "$tmp/open.yaml"
  case $range in *hi*) end=hi w=1 ;; *) end=lo w=-1 ;; esac
  "$eomc" run "$tmp/open.yaml" --set w0=$w --events "$tmp/ev1.csv" > "$tmp/rows1.csv"; st=$?
  [ $st -eq 0 ] && contact "$tmp/rows1.csv" "$tmp/ev1.csv" $end &&
    within "$(tail -1 "$tmp/rows1.csv" | cut -d, -f3)" "$(awk -v v="$v1" -v w=$w 'BEGIN { printf "%.17g", v * w }')" 1e-12
  ok $? "range $range, w0 = $w: the $end stop alone, the same contact ($(sed -n 5p "$tmp/ev1.csv" | cut -d, -f1))"
done

# the motor from rest: theta(1) = tau/2, theta'(1) = tau, tau the clamped u
for u in 5 -5 0.5; do
  tau=$(awk -v u=$u 'BEGIN { print (u > 1 ? 1 : u < -1 ? -1 : u) }')
  last=$("$eomc" run "$spec" --effects motor --set u=$u --init "theta'=0" --t-end 1 | tail -1)
  within "$(echo "$last" | cut -d, -f2)" "$(awk -v t=$tau 'BEGIN { print t / 2 }')" 1e-13 &&
    within "$(echo "$last" | cut -d, -f3)" "$tau" 1e-13
  ok $? "motor at u = $u: torque clamp(u, -1, 1) = $tau, theta(1) = tau/2 ($(echo "$last" | cut -d, -f2,3))"
done

# --linearize inside the upper stop, with gravity: A's row of theta''
# against central differences of --accel (h = 1e-5: the error h^2 q''' is
# 1e-10 of A, the rounding 1e-16/h of it 1e-11)
accel() {
  "$eomc" run "$spec" --effects gravity,stops --accel --init theta=$1 --init "theta'=$2" |
    awk '{ printf "%.17g", $2 }'
}
"$eomc" run "$spec" --effects gravity,stops --linearize --init theta=0.6 --init "theta'=0.1" \
  --csv "$tmp/lin.csv" > /dev/null 2> "$tmp/err"; st=$?
fd=$(awk -v a="$(accel 0.60001 0.1)" -v b="$(accel 0.59999 0.1)" -v c="$(accel 0.6 0.10001)" \
  -v d="$(accel 0.6 0.09999)" 'BEGIN { printf "%.17g %.17g", (a - b) / 2e-5, (c - d) / 2e-5 }')
got=$(awk -F, '$1 == "A" && $2 == "theta'"'"'" { printf "%s ", $4 }' "$tmp/lin.csv")
set -- $fd $got
[ $st -eq 0 ] && [ $# -eq 4 ] && within "$3" "$1" 1e-7 && within "$4" "$2" 1e-8 &&
  ! grep -q kink "$tmp/err"
ok $? "--linearize in the stop: d theta''/d(theta, theta') = $3 $4, central differences of --accel $1 $2"
# (the closed form: -g cos(theta) - k, -c)
within "$3" "$(awk 'BEGIN { printf "%.17g", -9.81 * cos(0.6) - 100 }')" 1e-12 && within "$4" -4 1e-13
ok $? "--linearize in the stop: -g cos(theta) - k/I and -c/I"
"$eomc" run "$spec" --effects gravity,stops --linearize --init theta=0.5 --init "theta'=0" \
  > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 0 ] && grep -q "^A = " "$tmp/out" &&
  grep -q "warning: t = 0: the state is on the kinks of stops.theta.hi.push and stops.theta.hi (their switch functions are 0 to rounding here)" "$tmp/err"
ok $? "--linearize on the stop's edge: A given, and a warning naming the kinks ($(head -c 150 "$tmp/err"))"
"$eomc" run "$spec" --effects gravity,stops --linearize --init theta=0.5000001 --init "theta'=0" \
  > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 0 ] && ! grep -q kink "$tmp/err"
ok $? "--linearize 1e-7 inside the stop: no kink"

# an equilibrium against the lower stop at lo = 0.2, from outside it
want=$(awk 'BEGIN { a = 0; b = 0.2
    for (i = 0; i < 200; i++) { m = (a + b) / 2; if (100 * (0.2 - m) - 9.81 * sin(m) > 0) a = m; else b = m }
    printf "%.17g", (a + b) / 2 }')
"$eomc" run "$spec" --effects gravity,stops --set lo=0.2 --equilibrium --init theta=0.5 \
  > "$tmp/out" 2> "$tmp/err"; st=$?
got=$(sed -n 's/^  theta = //p' "$tmp/out")
[ $st -eq 0 ] && within "$got" "$want" 1e-14 && ! grep -q kink "$tmp/err"
ok $? "--equilibrium against the stop from outside it: theta = $got, k (lo - theta) = m g l sin(theta) at $want"
for start in 0.5 -0.3; do
  "$eomc" run "$spec" --effects gravity,stops --set lo=0 --equilibrium --init theta=$start \
    > "$tmp/out" 2> "$tmp/err"; st=$?
  got=$(sed -n 's/^  theta = //p' "$tmp/out")
  [ $st -eq 0 ] && within "$got" 0 1e-15 && grep -q "warning: t = 0: the state is on the kinks of stops.theta.lo.push and stops.theta.lo" "$tmp/err"
  ok $? "--equilibrium on the stop's edge (lo = 0) from $start: theta = $got, and the kink said"
done
# a stop's constants of parameters, checked again for the values --set gives
"$eomc" run "$spec" --set k=-1 > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] &&
  grep -q "limit on 'theta': its stiffness cannot be negative (k = -1)" "$tmp/err"
ok $? "--set k=-1: refused, exit 2 ($(head -1 "$tmp/err"))"
"$eomc" run "$spec" --set lo=1 > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "limit on 'theta': its range is reversed" "$tmp/err"
ok $? "--set lo=1 above hi: refused, exit 2"
tap_end
