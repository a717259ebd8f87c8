#!/bin/sh
# MuJoCo's joint limits and actuator ranges as eomc imports them, against
# closed forms (TAP; docs/import.md, "Joint limits and actuator ranges"):
#  - tests/import/models/stop_rotor.xml, a rotor of inertia I = 0.5 on a
#    hinge limited to [-1, 0.5], gravity off, at w0 = 1 into its upper
#    limit: MuJoCo's solref (timeconst, dampratio) is a stop of natural
#    frequency w = 1/(timeconst dampratio) and damping ratio dampratio.
#    At the default (0.02, 1), critically damped: the stop is reached at
#    0.5, the push ends 2 timeconst later, the rotor leaves at -w0 e^-2
#    and is out of the stop at 0.5 + 4 timeconst.  With solreflimit
#    (0.05, 0.3), and (-400, -4) (stiffness 400 I, damping 4 I: w = 20,
#    zeta = 0.1), the underdamped closed form of tests/cli/test_limits.sh;
#  - its motors: one with ctrlrange [-1, 1] and gear 2 at u = -5 turns it
#    from rest as -2 t^2/(2 I); one with forcerange [-0.5, 0.5] and gear 3
#    at u = 5 as 1.5 t^2/(2 I); with actuators_unclamped in place of
#    actuators, the command as given, -10 t^2/(2 I);
#  - a pendulum (mass 1 at 0.5 below the hinge, its own inertia 0.01)
#    limited to [0.3, 2], dropped from 1: it falls into its lower limit
#    and comes to rest against it where k (0.3 - theta) = m g l sin(theta),
#    k = I/timeconst^2 (I = 0.01 + 0.5^2: the law's k, from the model's
#    numbers, not the import's);
#  - a URDF's <limit>: a stop of the same law;
#  - MuJoCo's humanoid (where libmujoco-samples is installed), every motor
#    at its control range's end for 0.5 s: each knee stays within 1.5 rad
#    of its range (measured: 0.62 and 0.81; imported without its limits the
#    knees went 22 rad).
# usage: test_limits.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
rotor="$src/tests/import/models/stop_rotor.xml"
tight="--rtol 1e-12 --atol 1e-14"

# contact EVENTS RELEASE OUT: the upper limit's four flips: the push's
# switch outside, the limit reached at 0.5, the push's end at RELEASE, out
# of the stop at OUT
contact() {
  [ "$(wc -l < "$1")" -eq 5 ] &&
    [ "$(sed -n 2,5p "$1" | cut -d, -f2 | tr '\n' ' ')" = "limits.turn.hi.push limits.turn.hi limits.turn.hi.push limits.turn.hi " ] &&
    within "$(sed -n 3p "$1" | cut -d, -f1)" 0.5 1e-13 &&
    within "$(sed -n 4p "$1" | cut -d, -f1)" "$2" 1e-12 &&
    within "$(sed -n 5p "$1" | cut -d, -f1)" "$3" 1e-12
}
# underdamped W ZETA: the push's end, the speed the rotor leaves at, and
# when it is out of the stop, entering at 0.5 at w0 = 1
underdamped() {
  awk -v w="$1" -v z="$2" 'BEGIN { s = sqrt(1 - z * z); wd = w * s; a = z * w
    t1 = (3.14159265358979323846 - atan2(2 * z * s, 1 - 2 * z * z)) / wd
    e = exp(-a * t1); d1 = e * sin(wd * t1) / wd; v1 = e * (-a * sin(wd * t1) + wd * cos(wd * t1)) / wd
    printf "%.17g %.17g %.17g", 0.5 + t1, v1, 0.5 + t1 + d1 / -v1 }'
}

"$eomc" run "$rotor" --init "turn'=1" --events "$tmp/ev.csv" $tight > "$tmp/rows.csv"; st=$?
v1=$(awk 'BEGIN { printf "%.17g", -exp(-2) }')
[ $st -eq 0 ] && contact "$tmp/ev.csv" 0.54 0.58 &&
  within "$(tail -1 "$tmp/rows.csv" | cut -d, -f3)" "$v1" 1e-12
ok $? "stop_rotor.xml, solref (0.02, 1): into its limit at 0.5, the push ends at 0.54, out at 0.58, leaving at -e^-2 = $v1 ($(sed -n 4,5p "$tmp/ev.csv" | cut -d, -f1 | tr '\n' ' ')$(tail -1 "$tmp/rows.csv" | cut -d, -f3))"
for ref in "0.05 0.3" "-400 -4"; do
  sed "s|range=\"-1 0.5\"|range=\"-1 0.5\" solreflimit=\"$ref\"|" "$rotor" > "$tmp/ref.xml"
  case $ref in -*) w=20 z=0.1 ;; *) w=$(awk 'BEGIN { printf "%.17g", 1 / (0.05 * 0.3) }') z=0.3 ;; esac
  set -- $(underdamped $w $z)
  "$eomc" run "$tmp/ref.xml" --init "turn'=1" --events "$tmp/ev.csv" $tight > "$tmp/rows.csv"; st=$?
  [ $st -eq 0 ] && contact "$tmp/ev.csv" "$1" "$3" &&
    within "$(tail -1 "$tmp/rows.csv" | cut -d, -f3)" "$2" 1e-12
  ok $? "solreflimit ($ref): w = $w, zeta = $z: the push ends at $1, out at $3, leaving at $2 ($(sed -n 4,5p "$tmp/ev.csv" | cut -d, -f1 | tr '\n' ' ')$(tail -1 "$tmp/rows.csv" | cut -d, -f3))"
done

# the motors from rest, to t = 0.5: q = tau t^2 / (2 I), inside the range
motor() { # EXPECTED_TAU ARGS...: the last row's q and q' against tau
  tau=$1
  shift
  last=$("$eomc" run "$rotor" --t-end 0.5 $tight "$@" 2> /dev/null | tail -1)
  within "$(echo "$last" | cut -d, -f2)" "$(awk -v t="$tau" 'BEGIN { printf "%.17g", t * 0.25 }')" 1e-13 &&
    within "$(echo "$last" | cut -d, -f3)" "$(awk -v t="$tau" 'BEGIN { printf "%.17g", t }')" 1e-13
}
motor -2 --set u_ranged=-5
ok $? "ctrlrange [-1, 1], gear 2, u = -5: torque -2, turn(0.5) = -0.5 ($last)"
motor 1.5 --set u_forced=5
ok $? "forcerange [-0.5, 0.5], gear 3, u = 5: torque 1.5, turn(0.5) = 0.375 ($last)"
"$eomc" import "$rotor" 2> /dev/null | grep -q '^scene: {effects: \[limits, actuators\], '
ok $? "the scene turns on limits and actuators, not actuators_unclamped"
motor -3.5 --set u_ranged=-5 --set u_forced=-5 --effects limits,actuators
ok $? "both at u = -5 (--effects limits,actuators): torque -2 - 1.5, turn(0.5) = -0.875 ($last)"
last=$("$eomc" run "$rotor" --t-end 0.2 $tight --set u_ranged=-5 --effects limits,actuators_unclamped | tail -1)
within "$(echo "$last" | cut -d, -f2)" -0.4 1e-13 && within "$(echo "$last" | cut -d, -f3)" -4 1e-13
ok $? "--effects limits,actuators_unclamped: the command as given, torque -10, turn(0.2) = -0.4 ($last)"

# the pendulum falls into its lower limit and rests against it
cat > "$tmp/pend.xml" <<'XML'
<mujoco model="stop_pendulum">
  <compiler angle="radian"/>
  <option gravity="0 0 -9.81"/>
  <worldbody>
    <body name="rod">
      <joint name="swing" axis="0 1 0" limited="true" range="0.3 2"/>
      <inertial pos="0 0 -0.5" mass="1" diaginertia="0.01 0.01 0.01"/>
    </body>
  </worldbody>
</mujoco>
XML
want=$(awk 'BEGIN { k = (0.01 + 0.25) / 0.02^2; a = 0; b = 0.3
    for (i = 0; i < 200; i++) { m = (a + b) / 2; if (k * (0.3 - m) - 9.81 * 0.5 * sin(m) > 0) a = m; else b = m }
    printf "%.17g", (a + b) / 2 }')
"$eomc" run "$tmp/pend.xml" --init swing=1 --t-end 3 --events "$tmp/ev.csv" $tight > "$tmp/rows.csv"; st=$?
last=$(tail -1 "$tmp/rows.csv")
[ $st -eq 0 ] && within "$(echo "$last" | cut -d, -f2)" "$want" 1e-12 &&
  within "$(echo "$last" | cut -d, -f3)" 0 1e-12 && grep -q "limits.swing.lo$\|limits.swing.lo," "$tmp/ev.csv"
ok $? "a pendulum dropped into its lower limit: at rest against it at $want, k (0.3 - theta) = m g l sin(theta) ($(echo "$last" | cut -d, -f2,3))"

# a URDF's <limit>: MuJoCo's reader makes it a limit, and the import a stop
"$eomc" import "$src/tests/import/models/planar_arm.urdf" > "$tmp/urdf.yaml" 2> "$tmp/err"; st=$?
[ $st -eq 0 ] && grep -q "^  limits: \[{limit: [a-z_0-9]*, range: \[-2, 2\], stiffness: [0-9.e+-]*, damping: [0-9.e+-]*}, {limit: [a-z_0-9]*, range: \[0, 0.1\], " "$tmp/urdf.yaml" &&
  ! grep -q "limits of" "$tmp/err"
ok $? "planar_arm.urdf: its <limit>s, [-2, 2] and [0, 0.1], imported as stops ($(grep "^  limits:" "$tmp/urdf.yaml" | head -c 160))"

humanoid=/usr/share/mujoco/model/humanoid/humanoid.xml
if [ -e "$humanoid" ]; then
  "$eomc" import "$humanoid" -o "$tmp/humanoid.yaml" 2> /dev/null
  sets=$(sed -n '/^inputs:/,/^[a-z]/s/^  \(u_[a-z_0-9]*\):.*/--set \1=1/p' "$tmp/humanoid.yaml")
  # shellcheck disable=SC2086 # $sets is a list of options
  # (in the air: its contacts with the floor off, the scene's other effects on)
  effs=$(sed -n 's/^scene: {effects: \[\([^]]*\)\].*/\1/p' "$tmp/humanoid.yaml" | tr -d ' ' |
    tr ',' '\n' | grep -vx contacts | paste -sd, -)
  "$eomc" run "$tmp/humanoid.yaml" --effects "$effs" --t-end 0.5 $sets --set u_left_knee=-1 \
    -o "$tmp/h.csv" 2> "$tmp/err"; st=$?
  past=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "right_knee") r = i; else if ($i == "left_knee") l = i; next }
    { a = $r - 0.03490658503988659; if (a > mr) mr = a                # right: pushed past 2 degrees
      b = -2.792526803190927 - $l; if (b > ml) ml = b }               # left: past -160 degrees
    END { printf "%.3g %.3g", mr, ml }' "$tmp/h.csv")
  set -- $past
  [ $st -eq 0 ] && awk -v a="$1" -v b="$2" 'BEGIN { exit !(a > 0 && b > 0 && a < 1.5 && b < 1.5) }'
  ok $? "MuJoCo's humanoid, its knees driven into their limits for 0.5 s: past them by $1 and $2 rad at most (< 1.5)"
else
  echo "ok $((n + 1)) # SKIP $humanoid: libmujoco-samples is not installed"
  n=$((n + 1))
fi
tap_end
