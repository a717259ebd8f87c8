#!/bin/sh
# Switched expressions (max, min, clamp, step) against closed forms (TAP), on
# tests/cli/spring_floor.yaml: a mass at speed v0 meets a floor whose
# force is max(0, -k y - c y'), w = sqrt(k/m), zeta = c / (2 m w),
# w_d = w sqrt(1 - zeta^2):
#  - undamped (c = 0), coming from y0 = 0.1: the kinks at y = 0 are
#    located at t = y0/v0 and y0/v0 + pi/w (the contact lasts half a
#    period), and the mass leaves at exactly v0;
#  - damped (zeta = 0.1), from y = 0: the force is the linear
#    spring-damper's, y = -(v0/w_d) e^(-zeta w t) sin(w_d t), until it
#    would pull, k y + c y' = 0, at w_d t1 = pi - atan2(2 zeta
#    sqrt(1 - zeta^2), 1 - 2 zeta^2); the mass then coasts at y'(t1);
#  - starting on a kink (tests/cli/switch_start.yaml: y = 0 where
#    min(y, 2 y) switches), the mode is the side the motion leaves to:
#    y'' = -(k - 2) y / m, so -k y reaches c at
#    t = asin(c w / (k v0)) / w, w = sqrt((k - 2)/m) (with min's other
#    branch, y, it would be sqrt(k - 1): 6e-7 later);
#  - two kinks at the same instant (--effects pair: max(0, -k y) +
#    max(0, -2 k y)) both flip there: the contact lasts pi/sqrt(3k/m)
#    and the mass leaves at v0;
#  - step(0.3 - t) pushes with a unit force until t = 0.3: from rest,
#    y(1) = 0.3^2/2 + 0.3 (1 - 0.3) = 0.255, y'(1) = 0.3;
#  - an effect that is off (spring_floor.yaml's edge) brings no switch;
#  - the modes are no inputs: not in the CSV, not settable; what cannot
#    follow a switch yet (Taylor's series, the reference)
#    says so; --accel at a state takes that state's modes.
# usage: test_switch.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
spec="$src/tests/cli/spring_floor.yaml"

"$eomc" run "$spec" --set c=0 --set y0=0.1 --events "$tmp/ev0.csv" > "$tmp/rows0.csv"; st=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev0.csv")" -eq 3 ] &&
  within "$(sed -n 2p "$tmp/ev0.csv" | cut -d, -f1)" 0.1 1e-13 &&
  within "$(sed -n 3p "$tmp/ev0.csv" | cut -d, -f1)" 0.41415926535897932 1e-13
ok $? "undamped: the two kinks located, at y0/v0 = 0.1 and 0.1 + pi/w ($(tail -1 "$tmp/ev0.csv" | cut -d, -f1))"
[ "$(sed -n 2,3p "$tmp/ev0.csv" | cut -d, -f2 | sort -u)" = floor.max ]
ok $? "--events names them by their effect and function: floor.max"
within "$(tail -1 "$tmp/rows0.csv" | cut -d, -f3)" 1 1e-12
ok $? "undamped: it leaves at v0 ($(tail -1 "$tmp/rows0.csv" | cut -d, -f3))"

"$eomc" run "$spec" --effects pair --set y0=0.1 --events "$tmp/evp.csv" > "$tmp/rowsp.csv"; st=$?
want=$(awk 'BEGIN { printf "%.17g", 0.1 + 3.14159265358979323846 / sqrt(300) }')
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/evp.csv")" -eq 5 ] &&
  [ "$(cut -d, -f2 "$tmp/evp.csv" | sort | uniq -c | awk '{ print $1 $2 }' | tr '\n' ' ')" = "1event 2pair.max 2pair.max.2 " ] &&
  within "$(sed -n 2p "$tmp/evp.csv" | cut -d, -f1)" 0.1 1e-13 &&
  within "$(sed -n 3p "$tmp/evp.csv" | cut -d, -f1)" 0.1 1e-13 &&
  within "$(sed -n 4p "$tmp/evp.csv" | cut -d, -f1)" "$want" 1e-13 &&
  within "$(tail -1 "$tmp/rowsp.csv" | cut -d, -f3)" 1 1e-12
ok $? "two kinks at once (pair.max and pair.max.2) both flip: contact to $want, leaving at v0 ($(tail -1 "$tmp/rowsp.csv" | cut -d, -f3))"

"$eomc" run "$spec" --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
want=$(awk 'BEGIN { m = 1; k = 100; c = 2; v0 = 1; w = sqrt(k / m); z = c / (2 * m * w)
    wd = w * sqrt(1 - z * z); a = z * w; s = sqrt(1 - z * z)
    t1 = (3.14159265358979323846 - atan2(2 * z * s, 1 - 2 * z * z)) / wd
    e = exp(-a * t1); v1 = -(v0 / wd) * e * (-a * sin(wd * t1) + wd * cos(wd * t1))
    y1 = -(v0 / wd) * e * sin(wd * t1)
    printf "%.17g %.17g %.17g", t1, v1, y1 + v1 * (1 - t1) }')
t1=${want%% *} rest=${want#* } v1=${want#* }; v1=${v1%% *}; y_end=${rest#* }
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 2 ] &&
  within "$(sed -n 2p "$tmp/ev.csv" | cut -d, -f1)" "$t1" 1e-12
ok $? "damped: the push ends at t1 = $t1 ($(sed -n 2p "$tmp/ev.csv" | cut -d, -f1))"
last=$(tail -1 "$tmp/rows.csv")
within "$(echo "$last" | cut -d, -f3)" "$v1" 1e-11 && within "$(echo "$last" | cut -d, -f2)" "$y_end" 1e-11
ok $? "damped: it leaves at y'(t1) = $v1 and coasts to y(1) = $y_end ($(echo "$last" | cut -d, -f2,3))"

"$eomc" run "$src/tests/cli/switch_start.yaml" --events "$tmp/ev2.csv" > /dev/null; st=$?
want=$(awk 'BEGIN { w = sqrt(98); printf "%.17g", atan2(2 * w / 100, sqrt(1 - (2 * w / 100)^2)) / w }')
got=$(sed -n 2p "$tmp/ev2.csv" | cut -d, -f1)
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev2.csv")" -eq 2 ] && within "$got" "$want" 1e-12 &&
  [ "$(sed -n 2p "$tmp/ev2.csv" | cut -d, -f2)" = edge.clamp.hi ]
ok $? "a start on a kink takes the side the motion leaves to: the clamp saturates (edge.clamp.hi) at $want ($got)"

"$eomc" run "$spec" --effects pulse --set v0=0 --events "$tmp/evs.csv" > "$tmp/rowss.csv"; st=$?
last=$(tail -1 "$tmp/rowss.csv")
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/evs.csv")" -eq 2 ] &&
  within "$(sed -n 2p "$tmp/evs.csv" | cut -d, -f1)" 0.3 1e-14 &&
  within "$(echo "$last" | cut -d, -f2)" 0.255 1e-13 && within "$(echo "$last" | cut -d, -f3)" 0.3 1e-13
ok $? "step(0.3 - t): the push ends at 0.3, y(1) = 0.255, y'(1) = 0.3 ($(echo "$last" | cut -d, -f2,3))"

head -1 "$tmp/rows.csv" | grep -qx "t,y,y',T,V,E"
ok $? "the modes are not columns of the CSV"
"$eomc" run "$spec" --set "floor.max=1" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "'floor.max' is not a parameter or input" "$tmp/err"
ok $? "the modes are not inputs: --set refuses them"
"$eomc" run "$spec" --method taylor > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "switched expressions (max, min, clamp, step)" "$tmp/err"
ok $? "--method taylor is refused, naming the switched expressions"
for opt in --error; do
  "$eomc" run "$spec" $opt > "$tmp/out" 2> "$tmp/err"; st=$?
  [ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "^spring_floor: $opt: .*switched expressions" "$tmp/err"
  ok $? "$opt is refused, naming the switched expressions"
done
# outside a run, each mode is its state's: y = -0.01 at rest, the floor
# pushes k 0.01 = 1; y = 0.01, nothing
"$eomc" run "$spec" --accel --init y=-0.01 --init "y'=0" > "$tmp/a1" 2>&1 &&
  "$eomc" run "$spec" --accel --init y=0.01 --init "y'=0" > "$tmp/a2" 2>&1 &&
  within "$(awk '$1 == "y'"''"'" { print $2 }' "$tmp/a1")" 1 1e-15 &&
  within "$(awk '$1 == "y'"''"'" { print $2 }' "$tmp/a2")" 0 0
ok $? "--accel takes the modes of its state: y'' = $(cat "$tmp/a1" | tr '\n' ' ')and $(cat "$tmp/a2" | tr '\n' ' ')"
tap_end
