#!/bin/sh
# eomc import's contacts (docs/import.md "Contacts") against MuJoCo:
#  - the pairs: tests/import/models/contacts.xml overlaps every geom with
#    every other at qpos0, so MuJoCo's own mj_forward there has a contact
#    of each pair its filters keep (mj_pairs.c); eomc's pairs are those of
#    them its contact can take (docs/spec.md's table: no cylinder, no box
#    against anything but a plane), the rest named in warnings;
#  - the law: k = m / (tc^2 dr^2), c = 2 m / tc from solref (tc, dr), m
#    the pair's effective mass along the normal at qpos0, here by hand: a
#    free ball with a child on a hinge through its centre moves as 2 kg
#    (5000, 200 at MuJoCo's default solref 0.02, 1), the free capsule
#    with its ghost sphere 1.1 kg (2750, 110; with the <pair>'s solref
#    0.04, 0.5: 2750, 55), the box 1 kg (2500, 100), and the ball against
#    the capsule 1 / (1/2 + 1/1.1) (1774.19..., 70.967...);
#  - a ball dropped on the floor (models/ball_drop.xml, 1 kg, radius 0.1,
#    0.4 m above): it touches at sqrt(2 0.4 / g) and comes to rest sunk
#    m g / k = 9.81 / 2500 (critically damped); MuJoCo's rests higher,
#    its impedance d letting only 1 - d of the weight press (what differs:
#    docs/import.md), and the test prints both;
#  - --strict refuses the pairs it would drop;
#  - friction (docs/import.md "Contacts"): a pair with a plane and condim
#    > 1 gets `friction: mu`, mu as MuJoCo mixes it (the larger of the
#    geoms', the geom of higher priority's, a <pair>'s own), each checked
#    by a box slid on the floor against Coulomb's stop; condim 1 none;
#    what eomc does not take (no plane, condim 4's and 6's spin and
#    rolling, an elliptic cone, a model with equality constraints) named
#    by exact warnings, and --strict refuses it.
# usage: test_import_contact.sh EOMC SOURCE_ROOT BUILD_ROOT MJ_PAIRS
set -u
eomc=$1 src=$2 build=$3 mj=$4
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
models=$src/tests/import/models

"$eomc" import "$models/contacts.xml" -o "$tmp/c.yaml" 2> "$tmp/err"; st=$?
sed -n 's/^    - {contact: \[\[\([A-Za-z_0-9]*\), \([A-Za-z_0-9]*\)\]\].*/\1 \2/p' "$tmp/c.yaml" |
  awk '{ print ($1 < $2) ? $1 " " $2 : $2 " " $1 }' | sort > "$tmp/ours"
"$mj" "$models/contacts.xml" | awk '$1 != "f_cyl" && $2 != "f_cyl" &&
  !(($1 == "e_box" && $2 != "floor") || ($2 == "e_box" && $1 != "floor"))' | sort > "$tmp/theirs"
[ $st -eq 0 ] && [ -s "$tmp/ours" ] && cmp -s "$tmp/ours" "$tmp/theirs"
ok $? "the pairs are MuJoCo's own that eomc's contact takes: $(wc -l < "$tmp/ours") ($(tr '\n' ',' < "$tmp/ours"))"
all=$("$mj" "$models/contacts.xml" | wc -l)
grep -q "warning: dropped: the contacts of 5 geom pairs: floor-f_cyl, a_ball-f_cyl, b_cap-f_cyl, c_cap-f_cyl, f_cyl-e_box (eomc's contact has no gap for a cylinder" "$tmp/err" &&
  grep -q "warning: dropped: the contacts of 3 geom pairs: a_ball-e_box, b_cap-e_box, c_cap-e_box (eomc's contact has no gap for a box or an ellipsoid against a shape other than a plane)" "$tmp/err" &&
  [ $((all - $(wc -l < "$tmp/ours"))) -eq 8 ]
ok $? "the $((all - $(wc -l < "$tmp/ours"))) of MuJoCo's $all pairs it cannot take are named, by reason"

# (MuJoCo's default friction, 1, and condim 3: friction 1 on the pairs
# with the floor; a_ball-c_cap, two shapes, none, named)
law() { grep -q "^    - {contact: \[\[$1, $2\]\], stiffness: $3, damping: $4, friction: 1}$" "$tmp/c.yaml"; }
law floor a_ball 5000 200 && law floor b_cap 5000 200 && law floor c_cap 2750 110 &&
  law floor e_box 2500 100 && law floor c_ghost 2750 55 &&
  grep -q "^    - {contact: \[\[a_ball, c_cap\]\], stiffness: 1774.19354838709[0-9]*, damping: 70.96774193548[0-9]*}$" "$tmp/c.yaml" &&
  grep -q "warning: dropped: the friction of contact pair a_ball-c_cap (eomc's contact friction acts where a shape touches a plane: written without friction)$" "$tmp/err"
ok $? "each pair's k and c from its solref and effective mass (by hand: 5000/200, 2750/110, 2500/100, 2750/55, 1774.19/70.97), friction 1 with the floor, none between two shapes (named)"

grep -q "^  - {type: plane, name: floor, pos: \[0, 0, 0.05\]}$" "$tmp/c.yaml" && ! grep -q "view:" "$tmp/c.yaml"
ok $? "the floor is a plane of the ground at its height (the page's floor: no view: floor:)"

"$eomc" import "$models/contacts.xml" --strict > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "contacts of 5 geom pairs" "$tmp/err"
ok $? "--strict refuses the pairs it would drop (exit $st)"

"$eomc" import "$models/ball_drop.xml" -o "$tmp/b.yaml" 2> /dev/null &&
  "$eomc" run "$tmp/b.yaml" --t-end 3 --rtol 1e-12 --atol 1e-14 --events "$tmp/ev.csv" > "$tmp/b.csv"; st=$?
z=$(tail -1 "$tmp/b.csv" | cut -d, -f4) xy=$(tail -1 "$tmp/b.csv" | cut -d, -f2,3)
touch=$(grep "touch" "$tmp/ev.csv" | head -1 | cut -d, -f1)
theirs=$("$mj" "$models/ball_drop.xml" --rest 3 2)
want_t=$(awk 'BEGIN { printf "%.17g", sqrt(2 * 0.4 / 9.81) }')
# (with friction 1, it touches with no speed along the floor: it sticks
# there, the moment the friction of its slip switch's side moves it off 0,
# located a few units of rounding of t later: x and y 0 to 1e-15 of r)
[ $st -eq 0 ] && within "$z" 0.096076 1e-9 && within "$touch" "$want_t" 1e-12 &&
  awk -v a="$theirs" 'BEGIN { exit !(a > 0.096076 && a < 0.1) }' &&
  awk -v xy="$xy" 'BEGIN { split(xy, p, ","); for (i = 1; i <= 2; i++) { a = p[i] < 0 ? -p[i] : p[i]
      if (p[i] == "" || a > 1e-15 * 0.1) exit 1 } }' &&
  grep -q ',contacts\.floor\.ball_geom\.x\.stick,' "$tmp/ev.csv"
ok $? "a ball dropped: touches at $touch ($want_t), rests at $z (0.1 - 9.81/2500 = 0.096076), stuck where it touched (x, y = $xy); MuJoCo's rests at $theirs"

# A box slid along the floor with friction: a 0.2 x 0.2 x 0.05 brick of
# 1 kg, its centre of mass in the floor's plane as it rests (d above its
# lower corners), where the friction acts (its touch points are on the
# floor's surface), so that the friction puts no torque on it: it does
# not pitch, and stopped, it stays where it stopped (one that pitches
# rocks back and forth on the floor's springs as it stops, and rolls a
# little on its stuck points as it does).  Started at its
# resting depth d = m g / (4 k) = 9.81e-4 (each lower corner's spring, k =
# 2500 at MuJoCo's default solref, carries m g / 4) and slid at v0 = 3
# along x.  Its height obeys m z'' = N - m g, so the friction's impulse is
# mu (m g t + m (z'(t) - z'(0))): from its resting depth, N = m g all
# along, and it stops at Coulomb's v0^2 / (2 mu g) at t = v0 / (mu g),
# checked to 1e-11 of each (rtol 1e-12), then stays.  Started touching
# instead, it would sink by d as it slid, and that impulse would move
# the stop by mu d (6.9e-4 m at mu 0.7, 1e-3 of the distance): the
# tolerance such a start needs, which the resting depth removes (z staying
# at -d to 1e-15 checks that N is m g).  What MuJoCo mixes: 0.7 on the
# floor and 0.4 on the brick give the larger, 0.7; the brick's priority 1
# its own, 0.4; a <pair>, its 0.3.
box() { # NAME BRICK_ATTRIBUTES [CONTACT_ELEMENT]
  printf '%s\n' "<mujoco model=\"$1\"><worldbody><geom name=\"floor\" type=\"plane\" size=\"5 5 0.1\" friction=\"0.7\"/>" \
    '<body name="block" pos="0 0 -0.000981"><freejoint name="box"/>' \
    '<inertial pos="0 0 0.000981" mass="1" diaginertia="0.0035 0.0035 0.0067"/>' \
    "<geom name=\"brick\" type=\"box\" pos=\"0 0 0.025\" size=\"0.1 0.1 0.025\" friction=\"0.4\" $2/></body>" \
    "</worldbody>${3:-}</mujoco>" > "$tmp/$1.xml"
}
slide() { # NAME MU: 0 where it stops at Coulomb's x and t, and stays; the figures in $got
  got="$1: import ($(head -c 300 "$tmp/$1.err" 2> /dev/null))"
  "$eomc" import "$tmp/$1.xml" -o "$tmp/$1.yaml" 2> "$tmp/$1.err" &&
    grep -q "^    - {contact: \[\[floor, brick\]\], stiffness: 2500, damping: 100, friction: $2}$" "$tmp/$1.yaml" &&
    [ ! -s "$tmp/$1.err" ] || return 1
  set -- "$1" "$2" $(awk -v mu="$2" 'BEGIN { g = 9.81; v0 = 3
    printf "%.17g %.17g", v0 * v0 / (2 * mu * g), v0 / (mu * g) }')
  "$eomc" run "$tmp/$1.yaml" --init "box_x'=3" --t-end "$(awk -v t="$4" 'BEGIN { print t + 0.5 }')" \
    --rtol 1e-12 --atol 1e-12 --events "$tmp/$1.ev" > "$tmp/$1.csv" 2> "$tmp/$1.err"; st=$?
  stop=$(awk -F, '$2 ~ /\.x\.stick$/ { print $1 "," $3; exit }' "$tmp/$1.ev")
  end=$(tail -1 "$tmp/$1.csv" | cut -d, -f2,4)
  got="mu $2: exit $st, stops at t, x = $stop (Coulomb: $4, $3), x, z at the end $end"
  [ $st -eq 0 ] && within "${stop#*,}" "$3" "$(awk -v x="$3" 'BEGIN { print 1e-11 * x }')" &&
    within "${stop%,*}" "$4" "$(awk -v x="$4" 'BEGIN { print 1e-11 * x }')" &&
    within "${end%,*}" "${stop#*,}" 1e-12 && within "${end#*,}" -0.000981 1e-15
}
box mixed ''
slide mixed 0.7
ok $? "friction: the larger of the geoms' (0.4, 0.7), $got"
box priority 'priority="1"'
slide priority 0.4
ok $? "friction: the geom of higher priority's (the brick's 0.4 over the floor's 0.7), $got"
box pair '' '<contact><pair geom1="floor" geom2="brick" friction="0.3 0.3 0.005 0.0001 0.0001"/></contact>'
slide pair 0.3
ok $? "friction: a <pair>'s own (0.3), $got"

# condim 1 on both geoms: no friction written; it slides on at v0, x'
# unchanged to rounding
box frictionless 'condim="1"'
sed -i 's/<geom name="floor" type="plane"/<geom name="floor" condim="1" type="plane"/' "$tmp/frictionless.xml"
"$eomc" import "$tmp/frictionless.xml" -o "$tmp/f.yaml" 2> "$tmp/err" &&
  "$eomc" run "$tmp/f.yaml" --init "box_x'=3" --t-end 2 --rtol 1e-12 --atol 1e-12 > "$tmp/f.csv"; st=$?
v=$(tail -1 "$tmp/f.csv" | cut -d, -f9)
[ $st -eq 0 ] && [ ! -s "$tmp/err" ] &&
  grep -q '^    - {contact: \[\[floor, brick\]\], stiffness: 2500, damping: 100}$' "$tmp/f.yaml" &&
  within "$v" 3 "$(awk 'BEGIN { print 4 * 3 * 2^-52 }')"
ok $? "condim 1: no friction written, x'(2) = $v (3, to 4 rounding units)"

# what eomc's friction does not take, each named: a sphere on a sphere
# (no plane), condim 4 (spin) and 6 (spin and rolling) with the floor, a
# <pair> whose two sliding coefficients differ; the sliding part kept;
# an elliptic cone, taken as eomc's square, named too; --strict
# refuses each
printf '%s\n' '<mujoco model="lost"><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>' \
  '<body pos="0 0 0.1"><freejoint/><geom name="ball" size="0.1" condim="4" mass="1"/></body>' \
  '<body pos="0.5 0 0.1"><freejoint/><geom name="rock" size="0.1" condim="6" mass="1"/></body>' \
  '<body pos="1 0 0.1"><freejoint/><geom name="pebble" size="0.1" mass="1" contype="0" conaffinity="0"/></body>' \
  '</worldbody><contact><pair geom1="floor" geom2="pebble" friction="0.3 0.5 0.005 0.0001 0.0001"/></contact></mujoco>' \
  > "$tmp/lost.xml"
"$eomc" import "$tmp/lost.xml" -o "$tmp/lost.yaml" 2> "$tmp/err"; st=$?
"$eomc" import "$tmp/lost.xml" --strict -o "$tmp/strict.yaml" > "$tmp/out" 2> "$tmp/err2"; st2=$?
w="$tmp/lost.xml: warning: dropped:"
printf '%s\n' \
  "$w the friction of contact pair ball-rock (eomc's contact friction acts where a shape touches a plane: written without friction)" \
  "$w the torsional friction of contact pair floor-ball (condim 4: eomc's contact friction is sliding only, friction[0]; its spin about the normal, friction[1], is free)" \
  "$w the torsional and rolling friction of contact pair floor-rock (condim 6: eomc's contact friction is sliding only, friction[0]; its spin and rolling, friction[1] and friction[2], are free)" \
  "$w the second sliding friction of contact pair floor-pebble (the <pair>'s friction[1] differs from its friction[0]: eomc's contact friction has one coefficient, friction[0], along both of the plane's axes)" \
  > "$tmp/want"
[ $st -eq 0 ] && cmp -s "$tmp/err" "$tmp/want" &&
  grep -q '^    - {contact: \[\[floor, ball\]\], stiffness: 2500, damping: 100, friction: 1}$' "$tmp/lost.yaml" &&
  grep -q '^    - {contact: \[\[floor, rock\]\], stiffness: 2500, damping: 100, friction: 1}$' "$tmp/lost.yaml" &&
  grep -q '^    - {contact: \[\[floor, pebble\]\], stiffness: 2500, damping: 100, friction: 0.3}$' "$tmp/lost.yaml" &&
  grep -q '^    - {contact: \[\[ball, rock\]\], stiffness: 1250, damping: 50}$' "$tmp/lost.yaml" &&
  [ $st2 -eq 2 ] && [ ! -e "$tmp/strict.yaml" ] && [ ! -s "$tmp/out" ] &&
  [ "$(tail -1 "$tmp/err2")" = "$tmp/lost.xml: error: --strict: the elements named above would be dropped or changed" ]
ok $? "friction eomc does not take, one warning a reason (no plane, condim 4, condim 6, a <pair>'s second coefficient), the sliding part kept; --strict: exit $st2, $(tail -1 "$tmp/err2" | sed 's/.*error: //')"
sed 's/<mujoco model="lost">/<mujoco model="lost"><option cone="elliptic"\/>/' "$tmp/lost.xml" > "$tmp/cone.xml"
"$eomc" import "$tmp/cone.xml" -o "$tmp/cone.yaml" 2> "$tmp/err"; st=$?
"$eomc" import "$tmp/cone.xml" --strict > "$tmp/out" 2> "$tmp/err2"; st2=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/err")" -eq 5 ] &&
  grep -qxF "$tmp/cone.xml: warning: changed: the friction cone of 3 contact pairs: floor-ball, floor-rock, floor-pebble (MuJoCo's cone=\"elliptic\" is Coulomb's circle |f| <= mu N; eomc's two items per touch point bound the square |f_x|, |f_y| <= mu N along the plane's axes: the same along an axis, up to sqrt(2) mu N on a diagonal)" "$tmp/err" &&
  [ "$(grep -c 'friction: ' "$tmp/cone.yaml")" -eq 3 ] &&
  [ $st2 -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "error: --strict" "$tmp/err2"
ok $? "an elliptic cone: the same mu, and one warning naming the pairs and the difference; --strict: exit $st2"

# a model with an equality constraint: no friction written (a run refuses
# contact friction with constraints), named; it runs, its wheel sliding
# on at sx' = 1 (sx(1) = 1); its contact given friction, a run refuses it
printf '%s\n' '<mujoco model="eq"><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>' \
  '<body pos="0 0 0.096076"><joint name="sx" type="slide" axis="1 0 0"/><joint name="sz" type="slide" axis="0 0 1"/>' \
  '<geom name="wheel" size="0.1" mass="1"/></body>' \
  '<body pos="0 1 0.5"><joint name="h1" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0 0 -0.2" size="0.02" mass="1" contype="0" conaffinity="0"/>' \
  '<body pos="0 0 -0.2"><joint name="h2" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0 0 -0.2" size="0.02" mass="1" contype="0" conaffinity="0"/></body></body>' \
  '</worldbody><equality><joint joint1="h1" joint2="h2"/></equality></mujoco>' > "$tmp/eq.xml"
"$eomc" import "$tmp/eq.xml" -o "$tmp/eq.yaml" 2> "$tmp/err" &&
  "$eomc" run "$tmp/eq.yaml" --init "sx'=1" --t-end 1 --rtol 1e-10 --atol 1e-10 > "$tmp/eq.csv" 2>> "$tmp/err"; st=$?
x=$(tail -1 "$tmp/eq.csv" | cut -d, -f2)
sed 's/damping: 100}/damping: 100, friction: 1}/' "$tmp/eq.yaml" > "$tmp/eqf.yaml"
"$eomc" run "$tmp/eqf.yaml" --t-end 1 > /dev/null 2> "$tmp/err2"; st2=$?
[ $st -eq 0 ] && within "$x" 1 1e-9 && [ "$(wc -l < "$tmp/err")" -eq 1 ] &&
  [ "$(cat "$tmp/err")" = "$tmp/eq.xml: warning: dropped: the friction of contact pair floor-wheel (the model has equality constraints, with which a run refuses contact friction: written without friction, so that the model runs)" ] &&
  [ $st2 -eq 2 ] && grep -q "dry friction (.*) and constraints" "$tmp/err2"
ok $? "equality constraints: the contact written without friction, named; the model runs (exit $st, sx(1) = $x); given friction, a run refuses it (exit $st2)"
tap_end
