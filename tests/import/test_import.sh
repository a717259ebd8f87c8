#!/bin/sh
# eomc import against MuJoCo itself: each model (MJCF written for these
# tests: an arm, the same with damping and springs, a URDF arm, a floating
# base with a ball joint, armature and actuators, a closed loop, welds and
# fixed tendons (their constraints on independent trees: blocks that
# kkt.c solves apart), a four-bar linkage whose connect has a dependent
# row, a gripper whose connects have a row that constrains nothing; the
# benchmark's chain;
# MuJoCo's humanoid, 22 humanoids and humanoid100 (616 and 728
# coordinates) where libmujoco-samples is installed) imported, then
# q'' of `eomc run --accel` at 100 random states and controls against
# mj_forward's qacc at the same state (mj_accel.c: contact, limits and
# friction loss off, each limited joint inside its range; the controls and
# forces clamped as the model says: the servo arm's, a 6-joint arm of
# position servos, at every state), within 1e-10 of the largest |q''|; a
# URDF's joint inputs tau_J (and an MJCF's, --joint-inputs) against forces
# MuJoCo applies on the same dofs (qfrc_applied); --parameters set to other
# values against the file edited to them; and the import's refusals and
# warnings.
#
# usage: test_import.sh EOMC SOURCE_ROOT BUILD_ROOT MJ_ACCEL [PART]
# PART: small (the models written for these tests, the chain and the
# checks of refusals and warnings: the default), or one of MuJoCo's
# samples, humanoid, 22_humanoids or humanoid100, each a test of its own
# (meson's import-*), so that they run side by side and a configuration
# can leave the two large ones out (.ci/run says which and why).
# EOMC_TEST_STATES=N: at most N random states a model (the sanitizers'
# stage of .ci/run: it looks for memory errors and undefined behaviour,
# which every state's run meets in the same code; the numbers are checked
# at every state by the other configurations).
set -u
eomc=$1 src=$2 mj=$4 part=${5:-small}
. "$src/tests/cli/tap.sh"
STATES=100 TOL=1e-10
# eomc's double q'' against its own extended-precision solve (--accel-extended)
OWN=1e-12
# worse A B: the larger, or nan
worse() { awk -v a="$1" -v b="$2" 'BEGIN { print (b == "nan" || a == "nan") ? "nan" : (b > a ? b : a) }'; }

sh "$src/specs/gen_chain.sh" 5 --mjcf > "$tmp/chain5.xml"
# MuJoCo's <option><flag>s, each model loaded with some disabled: what they
# disable is left out of the spec as MuJoCo leaves it out (fluid.xml's
# gravity and passive forces, then its actuators; closed.xml's equality
# constraints, by the flag equality and by constraint)
models_dir=$src/tests/import/models
flagged() { # MODEL NAME FLAGS: MODEL with <flag FLAGS/> in its <option .../>
  sed "s|<option \(.*\)/>|<option \1><flag $3/></option>|" "$models_dir/$1" > "$tmp/$2.xml"
}
flagged fluid.xml fluid_unforced 'gravity="disable" passive="disable"'
flagged fluid.xml fluid_unactuated 'actuation="disable"'
flagged closed.xml closed_noequality 'equality="disable"'
flagged closed.xml closed_noconstraint 'constraint="disable"'
# legged.urdf is imported with --floating, its trunk free; MuJoCo's q'' is
# that of the same file with the trunk joined to the world by a joint of
# type floating, written here
sed 's|</robot>|<link name="world"/><joint name="trunk" type="floating"><parent link="world"/><child link="trunk"/></joint></robot>|' \
  "$models_dir/legged.urdf" > "$tmp/legged_floating.urdf"
# floating.xml imported with --joint-inputs --parameters, and run with
# parameters set to other values: MuJoCo's q'' is that of the file edited
# to those values (the base's mass, and so its inertia, 3 -> 3.5; the
# ball's damping and armature; a spring on the tip), with forces on the
# joints' dofs (qfrc_applied) where eomc has tau_J
cp "$models_dir/floating.xml" "$tmp/floating_inputs.xml"
sed -e 's/mass="3"/mass="3.5"/' -e 's/damping="0.3" armature="0.02"/damping="0.7" armature="0.05"/' \
  -e 's|<joint name="tip" axis="0 0 1"/>|<joint name="tip" axis="0 0 1" stiffness="2"/>|' \
  "$models_dir/floating.xml" > "$tmp/floating_edited.xml"
# MuJoCo's own humanoid where Debian's libmujoco-samples is installed
samples=/usr/share/mujoco/model
case $part in
small) models="$src/tests/import/models/arm.xml $src/tests/import/models/springs.xml
         $src/tests/import/models/planar_arm.urdf $src/tests/import/models/visual_arm.urdf
         $src/tests/import/models/floating.xml $tmp/floating_inputs.xml
         $src/tests/import/models/closed.xml $src/tests/import/models/welded.xml
         $src/tests/import/models/fluid.xml $tmp/fluid_unforced.xml $tmp/fluid_unactuated.xml
         $tmp/closed_noequality.xml $tmp/closed_noconstraint.xml
         $src/tests/import/models/legged.urdf
         $src/tests/import/models/fourbar.xml $src/tests/import/models/gripper.xml
         $src/specs/arm.urdf $src/specs/floating_base.xml $tmp/chain5.xml" ;;
robots) r=$src/tests/import/models/robots # written for the robots benchmark too
        models="$r/arm_gripper.xml $r/arm_gripper_unconstrained.xml $r/quadruped.xml
                $r/humanoid_free.xml $r/fourbar.xml
                $r/freebody.xml $r/biped_loops.xml $r/servo_arm.xml" ;;
humanoid | 22_humanoids) models=$samples/humanoid/$part.xml ;;
humanoid100) models=$samples/humanoid100/$part.xml ;;
*) echo "test_import.sh: no part '$part'" >&2; exit 2 ;;
esac
if [ "$part" != small ] && [ "$part" != robots ] && [ ! -e "$models" ]; then
  echo "1..0 # SKIP $models: libmujoco-samples is not installed"
  exit 0
fi
for model in $models; do
  base=$(basename "$model"); base=${base%.*}_${base##*.} # arm.xml and arm.urdf apart
  opts='' ref=$model sets='' joints=0
  case $base in
  *_urdf) joints=1 ;; # a URDF's joints have inputs tau_J (MuJoCo's qfrc_applied)
  esac
  [ "$base" = legged_urdf ] && opts=--floating ref=$tmp/legged_floating.urdf
  [ "$base" = floating_inputs_xml ] &&
    opts="--joint-inputs --parameters" ref=$tmp/floating_edited.xml joints=1
  # shellcheck disable=SC2086 # $opts: none, or options
  "$eomc" import "$model" $opts -o "$tmp/$base.yaml" 2> "$tmp/err"
  ok $? "$base: imports${opts:+ $opts} ($(head -c 200 "$tmp/err"))"
  # MuJoCo is run with its contacts off (mj_accel.c): the spec without its
  # effect contacts (the other tests of contacts: test_import_contact.sh),
  # which for 22 humanoids is 3 500 pairs the compiler would build
  sed -i -e '/^  contacts:$/,/^[^ ]/{/^  contacts:$/d;/^    - /d}' \
    -e 's/^\(scene: {effects: \[.*\), contacts\]/\1]/' "$tmp/$base.yaml"
  coords=$(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$tmp/$base.yaml" | tr -d ',')
  # mj_accel.c turns MuJoCo's contacts off: eomc's effect contacts too (the
  # scene's effects where it lists them, else every effect), and friction
  # loss, whose laws differ (import.md)
  effs=$(sed -n 's/^scene: {effects: \[\([^]]*\)\].*/\1/p' "$tmp/$base.yaml" | tr -d ' ' | tr ',' '\n')
  [ -n "$effs" ] || effs=$(sed -n '/^effects:/,/^[a-z]/s/^  \([A-Za-z_0-9]*\):.*/\1/p' "$tmp/$base.yaml")
  effs=$(echo "$effs" | grep -vx 'contacts\|friction_loss' | paste -sd, -)
  inputs=$(sed -n '/^inputs:/,/^[a-z]/s/^  \([A-Za-z_0-9]*\):.*/\1/p' "$tmp/$base.yaml")
  if [ "$base" = floating_inputs_xml ]; then # the edited file's values
    sets="--set mass_base=3.5 --set damping_shoulder=0.7 --set armature_shoulder=0.05 --set stiffness_tip=2"
    sets="$sets $(sed -n 's/^  \(inertia_base_[xyz]*\): \(.*\)/\1 \2/p' "$tmp/$base.yaml" |
      awk '{ printf " --set %s=%.17g", $1, $2 * 3.5 / 3 }')"
  fi
  worst=0 fails=0 own=0 mjx=0 ext=1
  k=0 states=$STATES
  # the two large samples (616 and 728 coordinates): 20 states, each run
  # loading a simulator of tens of megabytes, and without the extended-
  # precision twin (it would double their build)
  # the flagged variants, 20: a flag leaves terms out or keeps them, which
  # any state shows (their models' every term is checked at 100 above)
  case $base in
  22_humanoids_xml | humanoid100_xml) states=20 ext= ;;
  fluid_unforced_xml | fluid_unactuated_xml | closed_noequality_xml | closed_noconstraint_xml) states=20 ;;
  esac
  if [ -n "${EOMC_TEST_STATES:-}" ] && [ "$EOMC_TEST_STATES" -lt $states ]; then
    states=$EOMC_TEST_STATES
  fi
  # the random states and MuJoCo's q'' there, in eomc's coordinates
  # (mj_accel.c: one process for them all, a block of 3 + nq lines each),
  # and each state as eomc's options, a line each
  MJ_ACCEL_JOINT_INPUTS=$joints "$mj" "$ref" 1 "$states" > "$tmp/mj" 2> "$tmp/mjerr" ||
    fails=$((fails + 1))
  # where MuJoCo clamps a control or a force (the servo arm: at every state)
  clamps=$(sed -n 's/^mj_accel: a control or force clamped at \([0-9]*\) of.*/\1/p' "$tmp/mjerr")
  [ "$base" = servo_arm_xml ] && [ "${clamps:-0}" -lt $((states / 2)) ] && fails=$((fails + 1))
  # the speeds' names in order, from --accel's lines (x'' a coordinate's
  # rate's, wx' a rotation's speed's): MuJoCo's qvel
  speeds=$("$eomc" run "$tmp/$base.yaml" --accel 2> /dev/null |
    sed -n "s/^\([A-Za-z_0-9]*'*\)' .*/\1/p" | tr '\n' ' ')
  nq=$(echo $speeds | wc -w) # (the q'' compared: one per speed)
  awk -v names="$coords" -v speeds="$speeds" -v inputs="$inputs" -v nv="$nq" -v sets="$sets" '
    BEGIN { n = split(names, c, " "); split(speeds, v, " "); nu = split(inputs, u, " ") }
    { r = (NR - 1) % (nv + 3) }
    r == 0 { for (i = 1; i <= n; i++) printf " --init %s=%s", c[i], $i }
    r == 1 { for (i = 1; i <= nv; i++) printf " --init %s=%s", v[i], $i }
    r == 2 { if (NF < nu) printf " --set inputs_and_controls_differ_in_count=1"
             for (i = 1; i <= nu; i++) printf " --set %s=%s", u[i], $i; printf " %s\n", sets }' \
    "$tmp/mj" > "$tmp/args"
  [ "$(wc -l < "$tmp/args")" -eq "$states" ] || fails=$((fails + 1))
  : > "$tmp/eomc" && : > "$tmp/ext"
  while IFS= read -r args; do
    k=$((k + 1))
    # (the q'' and w' lines only, not a multiplier's)
    # shellcheck disable=SC2086 # $args is a list of options
    "$eomc" run "$tmp/$base.yaml" --effects "$effs" --accel $args < /dev/null > "$tmp/one" \
      2>> "$tmp/err" ||
      fails=$((fails + 1))
    sed -n "/^[A-Za-z_0-9]*' /s/^/$k /p; /'' /s/^/$k /p" "$tmp/one" >> "$tmp/eomc"
    if [ -n "$ext" ]; then # and the extended-precision solve of the same state
      # shellcheck disable=SC2086
      "$eomc" run "$tmp/$base.yaml" --effects "$effs" --accel-extended $args < /dev/null \
        > "$tmp/one" \
        2>> "$tmp/err" || fails=$((fails + 1))
      sed -n "/^[A-Za-z_0-9]*' /s/^/$k /p; /'' /s/^/$k /p" "$tmp/one" >> "$tmp/ext"
    fi
  done < "$tmp/args"
  # per state, the largest difference over the reference's largest |q''|
  # (tap.sh's accel_diff, to 3 digits; nan where the counts differ), and
  # the worst over the states: eomc's against MuJoCo's; with the twin,
  # eomc's doubles and MuJoCo's against eomc's extended-precision solve
  set -- $(awk -v nq="$nq" -v states="$states" -v ext="$ext" '
    function diff(ref, got, k,   i, d, dm, am) {
      if (cnt[ref, k] != nq || cnt[got, k] != nq) return "nan"
      for (i = 1; i <= nq; i++) {
        d = val[got, k, i] - val[ref, k, i]; if (d < 0) d = -d; if (d > dm) dm = d
        d = val[ref, k, i] < 0 ? -val[ref, k, i] : val[ref, k, i]; if (d > am) am = d
      }
      return am == 0 ? "nan" : sprintf("%.3g", dm / am)
    }
    function worse(a, b) { return (a == "nan" || b == "nan") ? "nan" : (b + 0 > a + 0 ? b : a) }
    FILENAME ~ /\/mj$/ { r = (FNR - 1) % (nq + 3); k = int((FNR - 1) / (nq + 3)) + 1
                         if (r >= 3) { cnt["mj", k]++; val["mj", k, r - 2] = $1 }; next }
    { src = FILENAME ~ /\/ext$/ ? "ext" : "eomc"; cnt[src, $1]++; val[src, $1, cnt[src, $1]] = $3 }
    END { w = o = x = 0
          for (k = 1; k <= states; k++) {
            w = worse(w, diff("mj", "eomc", k))
            if (ext != "") { o = worse(o, diff("ext", "eomc", k)); x = worse(x, diff("ext", "mj", k)) }
          }
          print w, o, x }' "$tmp/mj" "$tmp/eomc" "$tmp/ext")
  worst=$1 own=$2 mjx=$3
  [ "$k" -eq "$states" ] || fails=$((fails + 1))
  awk -v w="$worst" -v t="$TOL" -v o="$own" -v x="$ext" -v ot="$OWN" \
    'BEGIN { exit !(w != "nan" && w <= t && (x == "" || (o != "nan" && o <= ot))) }' &&
    [ $fails -eq 0 ]
  ok $? "$base: q'' equals MuJoCo's qacc at $states random states$([ "${clamps:-0}" -gt 0 ] && echo " (MuJoCo clamping a control or a force at $clamps)") within $worst of the largest (<= $TOL)${ext:+; against eomc's extended-precision solve: eomc's doubles $own (<= $OWN), MuJoCo's $mjx}"
done

# 22 humanoids, the first moving and the other 21 at rest: T of the
# run's first row (q'.M q'/2 by mass_times, which runs one humanoid's code
# per copy and stores zeros for a copy at rest: repeat.c) = MuJoCo's
# kinetic energy there (mj_energyVel, armature included)
if [ "$part" = 22_humanoids ]; then
  model=$samples/humanoid/22_humanoids.xml
  "$mj" "$model" 1 > "$tmp/mj"
  coords=$(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$tmp/22_humanoids_xml.yaml" | tr -d ',')
  speeds=$("$eomc" run "$tmp/22_humanoids_xml.yaml" --accel 2> /dev/null |
    sed -n "s/^\([A-Za-z_0-9]*'*\)' .*/\1/p" | tr '\n' ' ')
  nq=$(echo $coords | wc -w) nv=$(echo $speeds | wc -w)
  args=$(awk -v names="$coords" -v speeds="$speeds" -v one=$((nv / 22)) '
      BEGIN { n = split(names, c, " "); split(speeds, v, " ") }
      NR == 1 { for (i = 1; i <= n; i++) printf " --init %s=%s", c[i], $i }
      NR == 2 { for (i = 1; i <= one; i++) printf " --init %s=%s", v[i], $i }' "$tmp/mj")
  # shellcheck disable=SC2086 # $args is a list of options
  "$eomc" run "$tmp/22_humanoids_xml.yaml" $args --t-end 0.01 -o "$tmp/h22.csv" 2> "$tmp/err"
  st=$?
  row=$(awk -F, 'NR == 2 { for (i = 1; i <= NF; i++) printf "%s ", $i }' "$tmp/h22.csv")
  mine=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "T") k = i } NR == 2 { print $k }' "$tmp/h22.csv")
  theirs=$(echo "$row" | cut -d' ' -f1-$((1 + nq + nv)) | "$mj" "$model" kinetic | cut -d' ' -f2)
  d=$(awk -v a="$mine" -v b="$theirs" 'BEGIN { d = a - b; if (d < 0) d = -d; if (b <= 0) print "nan"; else printf "%.3g\n", d / b }')
  [ $st -eq 0 ] && awk -v d="$d" 'BEGIN { exit !(d != "nan" && d <= 1e-12) }'
  ok $? "22_humanoids: one moving, 21 at rest: T = $mine, MuJoCo's $theirs (relative $d <= 1e-12)"
fi

# MuJoCo's humanoid dropped on its floor (its contacts on): it falls as a
# stone until its feet, 0.215 above the floor at qpos0 (MuJoCo's
# kinematics), touch at sqrt(2 h / g), their four capsules' ends (8
# touches) at once to rounding; then on through the landing, where the
# two feet's nearly parallel capsules flip clamps that read each other's
# modes at one instant (the run stopped there at t = 0.2094, exit 3)
# Without its contacts' friction, then with it.
# A run's end at rest (CSV, its SPEC, its MJCF): nq, the coordinates'
# count; still, the speeds at the last row over their largest in the run;
# carried, "sum k d / (M g) - 1" and the points' count, each point's depth
# d below the floor by MuJoCo's kinematics at the last pose (mj_accel
# sinks), its k the spec's for the shape's pair with the floor (a geom
# whose name a body has is NAME_2 in the spec), M and g MuJoCo's.
at_rest() {
  nq=$(head -1 "$1" | awk -F, '{ for (i = 2; i <= NF; i++)
      if ($i ~ /\x27$/ || $i ~ /_w[xyz]$/) { print i - 2; exit } }')
  still=$(awk -F, 'NR == 1 { for (i = 2; i <= NF; i++) s[i] = $i ~ /\x27$/ || $i ~ /_w[xyz]$/; next }
      { m = 0; for (i in s) if (s[i]) { a = $i < 0 ? -$i : $i; if (a > m) m = a }
        if (m > top) top = m; last = m } END { printf "%.2g", last / top }' "$1")
  tail -1 "$1" | tr , ' ' | cut -d' ' -f1-$((nq + 1)) | "$mj" "$3" sinks > "$tmp/sinks"
  carried=$(awk 'FNR == NR { if ($0 ~ /^    - \{contact: \[\[floor, /) { n = $4; sub(/\]\],$/, "", n)
                               k[n] = $6 + 0 } next }
      FNR == 1 { w = $1 * $2; next } { n = $2 in k ? $2 : $2 "_2"; if (!(n in k)) bad = 1
                                      sum += k[n] * $3; pts++ }
      END { if (bad) print "unknown"; else printf "%.2g %d", sum / w - 1, pts }' \
    "$2" "$tmp/sinks")
}

if [ "$part" = humanoid ]; then
  set -- $("$mj" "$models" lowest)
  want=$(awk -v h="$1" -v g="$2" 'BEGIN { printf "%.17g", sqrt(2 * h / g) }')
  mjcf=$models
  "$eomc" import "$models" -o "$tmp/humanoid.yaml" 2> /dev/null
  sed 's/, friction: [0-9.e+-]*}$/}/' "$tmp/humanoid.yaml" > "$tmp/frictionless.yaml"
  grep -q 'friction: ' "$tmp/humanoid.yaml" && ! grep -q 'friction: ' "$tmp/frictionless.yaml" ||
    echo "# the import's contact friction not found, or not stripped"
  models="$tmp/frictionless.yaml"
  "$eomc" run "$models" --t-end 0.3 --rtol 1e-8 --atol 1e-8 --events "$tmp/hev.csv" \
    -o /dev/null 2> "$tmp/err"; st=$?
  got=$(awk -F, -v w="$want" '$2 ~ /^contacts\.floor\..*\.touch$/ { n++; e = $1 - w; if (e < 0) e = -e
      if (e > m) m = e; if (n == 8) exit } END { printf "%d %.2g", n, m }' "$tmp/hev.csv")
  [ $st -eq 0 ] && [ "${got% *}" = 8 ] && awk -v e="${got#* }" 'BEGIN { exit !(e <= 1e-12) }' &&
    [ "$(awk -F, '$1 > 0.2094' "$tmp/hev.csv" | wc -l)" -gt 0 ]
  ok $? "the humanoid dropped: its feet's 8 ends touch at sqrt(2 h/g) = $want (to ${got#* } s), and it runs on through the landing ($(grep -v 'dropped: the friction' "$tmp/err" | head -c 200))"
  # on to t = 2 at rtol 1e-7, where the feet's nearly parallel capsules
  # flipped their lines' clamps back and forth (exit 3 at t = 0.2094, the
  # events accumulating): their switches no longer swing with rounding
  "$eomc" run "$models" --t-end 2 --rtol 1e-7 --atol 1e-7 --events "$tmp/hev2.csv" \
    -o "$tmp/h2.csv" 2> "$tmp/err"; st=$?
  last=$(tail -1 "$tmp/h2.csv" | cut -d, -f1)
  feet=$(grep -c ',contacts\.left_right_foot\.left_left_foot\.' "$tmp/hev2.csv")
  [ $st -eq 0 ] && [ "$last" = 2 ] && [ -z "$(grep -v 'dropped: the friction' "$tmp/err")" ]
  ok $? "the humanoid dropped, on to t = 2 at rtol 1e-7: exit $st, last row t = $last, the feet's pair flipped $feet switches ($(grep -v 'dropped: the friction' "$tmp/err" | head -c 200))"
  # with friction (1 on each pair with the floor), on to t = 10 at rtol
  # 1e-7: it lands on its feet, crouches, falls onto its hands and its
  # back, and lies still, its feet's ends sticking and slipping on the
  # way.  The model is its own mirror image across the x-z plane, and
  # dropped straight it stays so: root_y and the quaternion's x and z stay
  # 0 to rounding.  At rest its contacts' springs carry its weight: sum k d
  # = M g, each depth d from MuJoCo's kinematics at eomc's last pose
  # (mj_accel sinks; a geom whose name a body has is NAME_2 in the spec), M
  # and g MuJoCo's.  (Before the touch points were put on the floor's
  # surface, a foot's four ends, at depths apart by a rounding-sized tilt,
  # gave rows independent by that margin: the run stopped at the landing,
  # t = 0.20939, exit 3.  Before the shares the switches read were the
  # lexicographic least, it stopped at t = 1.178, a switch chattering; and
  # before a switch could flip once within 1e-9 of the span, at 3.233,
  # where the arms' mirror images touch 2.6e-11 apart.)  MuJoCo's own run
  # falls the other way, forward (root_qy near 1): its torso's height at
  # t = 10 is printed beside eomc's.
  "$eomc" run "$tmp/humanoid.yaml" --t-end 10 --rtol 1e-7 --atol 1e-7 \
    --events "$tmp/hev3.csv" -o "$tmp/h3.csv" 2> "$tmp/err"; st=$?
  last=$(tail -1 "$tmp/h3.csv" | cut -d, -f1)
  sticks=$(grep -c ',contacts\.floor\..*_foot\..*\.stick,' "$tmp/hev3.csv")
  mirror=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      { for (k = 0; k < 3; k++) { a = $(c[k == 0 ? "root_y" : k == 1 ? "root_qx" : "root_qz"])
          a = a < 0 ? -a : a; if (a > m) m = a } }
      END { printf "%.2g", m }' "$tmp/h3.csv")
  at_rest "$tmp/h3.csv" "$tmp/humanoid.yaml" "$mjcf"
  ours=$(tail -1 "$tmp/h3.csv" | cut -d, -f4)
  theirs=$("$mj" "$mjcf" rest 10 2> /dev/null | cut -d' ' -f3)
  [ $st -eq 0 ] && [ "$last" = 10 ] && [ "$sticks" -ge 16 ] &&
    awk -v m="$mirror" -v s="$still" 'BEGIN { exit !(m <= 1e-8 && s <= 1e-9) }' &&
    awk -v c="$carried" 'BEGIN { split(c, x, " "); e = x[1] < 0 ? -x[1] : x[1]
      exit !(c != "unknown" && e <= 1e-9 && x[2] >= 3) }'
  ok $? "the humanoid dropped with friction, to t = 10 at rtol 1e-7: exit $st, last row t = $last, its feet's ends stuck or let go $sticks times, its mirror symmetry kept (|root_y|, |qx|, |qz| at most $mirror); it comes to rest (speeds at t = 10: $still of their largest), its points' springs carrying its weight (sum k d / M g - 1, points: $carried); its torso at $ours, MuJoCo's at $theirs ($(head -c 300 "$tmp/err"))"
fi

# The quadruped dropped on its floor with friction (1 on each pair of a
# shape with the floor; the pairs between its own shapes have none):
# it lands, its legs fold, and it comes to rest by t = 10 (its speeds
# below 1e-9 of the largest it had).  At rest its weight is carried by
# the floor alone: the springs' k d, each point's depth d below the floor
# computed by MuJoCo's kinematics at eomc's last pose (mj_accel sinks) and
# its k read from the import, sum to M g (MuJoCo's mass and gravity) to
# 1e-9.  MuJoCo's own run from the same start (mj_accel rest) comes to rest
# elsewhere, its torso's height printed beside eomc's: its contacts are
# soft constraints with pyramidal cones, on all 67 pairs (eomc takes the
# friction of the 13 pairs with the floor, and no pair of a cylinder), and
# the fall that folds the legs is sensitive to all of it.
if [ "$part" = robots ]; then
  q=$src/tests/import/models/robots/quadruped.xml
  "$eomc" import "$q" -o "$tmp/quad.yaml" 2> /dev/null
  "$eomc" run "$tmp/quad.yaml" --t-end 10 --rtol 1e-9 --atol 1e-9 -o "$tmp/quad.csv" \
    2> "$tmp/err"; st=$?
  at_rest "$tmp/quad.csv" "$tmp/quad.yaml" "$q"
  ours=$(tail -1 "$tmp/quad.csv" | cut -d, -f4)
  theirs=$("$mj" "$q" rest 10 | cut -d' ' -f3)
  [ $st -eq 0 ] && [ "$nq" = 19 ] && awk -v s="$still" 'BEGIN { exit !(s <= 1e-9) }' &&
    awk -v c="$carried" 'BEGIN { split(c, x, " "); e = x[1] < 0 ? -x[1] : x[1]
      exit !(c != "unknown" && e <= 1e-9 && x[2] >= 3) }'
  ok $? "the quadruped dropped with friction comes to rest (speeds at t = 10: $still of their largest), its points' springs carrying its weight (sum k d / M g - 1, points: $carried); its torso at $ours, MuJoCo's at $theirs ($(head -c 200 "$tmp/err"))"
fi

# the rest checks the import's own messages, once
if [ "$part" != small ]; then
  tap_end
  exit
fi

# the spatial tendon that nothing uses is dropped by name
"$eomc" import "$src/tests/import/models/welded.xml" 2>&1 > /dev/null |
  grep -q "warning: dropped: spatial tendon cable (nothing acts along it"
ok $? "welded.xml: its unused spatial tendon dropped by name"

# the closed loop's spec assembles its start (MuJoCo's qpos0: every hinge
# at 0, where only the magnitude of the constraints' terms measures their
# residuals) and runs on its constraints
"$eomc" run "$src/tests/import/models/closed.xml" -o "$tmp/closed.csv" --summary \
  > /dev/null 2> "$tmp/err"
st=$?
res=$(tr '\n' ' ' < "$tmp/err" | sed -n 's/.*largest constraint *residual was \([0-9.e+-]*[0-9]\).*/\1/p')
[ $st -eq 0 ] && grep -q "assemble: true" "$tmp/closed_xml.yaml" &&
  awk -v r="$res" 'BEGIN { exit !(r != "" && r + 0 <= 1e-10) }'
ok $? "closed.xml runs: assembled from qpos0, its constraints held to $res (<= 1e-10)"

# the gripper: each connect's row across the fingers' plane is 0 at every
# pose, dropped at import with a note (as eomc would refuse it), the two
# that move kept, the joint equality as it was
"$eomc" import "$src/tests/import/models/gripper.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] &&
  grep -q "gripper.xml: note: dropped: 2 constraint rows: left_loop_x, right_loop_x (0 at every pose" "$tmp/err" &&
  [ "$(sed -n '/^constraints:/,/^[a-z]/s/^  \([a-z_]*\):.*/\1/p' "$tmp/out" | tr '\n' ' ')" = \
    "left_loop_y left_loop_z right_loop_y right_loop_z mirror " ]
ok $? "gripper.xml: the connects' rows across the plane dropped with a note, exit $st ($(grep note "$tmp/err"))"

# the four-bar: the connect's three rows (in the coupler's axes, none of
# them constant: the hinges turn about (1 1 1)) have rank 2, found at the
# start, the dependent one left out with a note.  Over 5 s, the crank
# driven round 15 times and the base turning, the row left out stays as
# well met as the two kept (its largest residual in the CSV at most twice
# theirs, all below 1e-9 of the coupler's 0.4: no stabilization), and
# --error measures the run against the reference, which leaves the same
# row out, within 1e-9 of the largest coordinate (the crank's, 92 rad)
# (its links' contacts off: the loop's constraints are what is checked)
fb_effs=$("$eomc" import "$src/tests/import/models/fourbar.xml" 2> /dev/null |
  sed -n '/^effects:/,/^[a-z]/s/^  \([A-Za-z_0-9]*\):.*/\1/p' | grep -vx contacts | paste -sd, -)
"$eomc" run "$src/tests/import/models/fourbar.xml" --effects "$fb_effs" --set u_drive=1 \
  --init "turn'=1" --t-end 5 --error -o "$tmp/fourbar.csv" --summary > /dev/null 2> "$tmp/err"
st=$?
drop=$(sed -n 's/.*note: constraints dependent at the start: \(loop_[xyz]\), dependent on loop_[xyz], loop_[xyz]; the solves leave the dependent rows out.*/\1/p' "$tmp/err")
fb=$(awk -F, -v drop="res[$drop]" 'NR == 1 { for (i = 1; i <= NF; i++) { if ($i ~ /^res\[loop_/) c[i] = 1; if ($i == drop) d = i; if ($i == "a") a = i } }
  NR > 1 { for (i in c) { r = $i < 0 ? -$i : $i; if (i == d && r > md) md = r; if (i != d && r > mk) mk = r }
           r = $a < 0 ? -$a : $a; if (r > big) big = r; n++ }
  END { printf "%.3g %.3g %.3g %d", md, mk, big, (d && n == 501) }' "$tmp/fourbar.csv")
err=$(tr '\n' ' ' < "$tmp/err" | sed -n 's/.*the error was at *most \([0-9.e+-]*[0-9]\) over the rows.*/\1/p')
set -- $fb nan nan nan 0 # (a run that wrote no CSV: the defaults)
[ $st -eq 0 ] && [ "$4" -eq 1 ] &&
  awk -v d="$1" -v k="$2" -v big="$3" -v e="$err" \
    'BEGIN { exit !(d <= 2 * k && k <= 0.4e-9 && e != "" && e + 0 <= 1e-9 * big) }'
ok $? "fourbar.xml over 5 s: $drop left out, held to $1 (the others to $2) of 0.4; the error against the reference $err, the crank at $3 rad ($(grep note "$tmp/err" | head -c 120))"
# the same by Taylor's method (its series' KKT solves leave the row out
# too) and against Taylor's reference in extended precision: at t = 2 the
# state of the run above, within 1e-9 of the crank's angle
"$eomc" run "$src/tests/import/models/fourbar.xml" --effects "$fb_effs" --set u_drive=1 \
  --init "turn'=1" --t-end 2 --method taylor --error --reference-method taylor -o "$tmp/fourbar_taylor.csv" --summary \
  > /dev/null 2> "$tmp/err"
st=$?
err=$(tr '\n' ' ' < "$tmp/err" | sed -n 's/.*the error was at *most \([0-9.e+-]*[0-9]\) over the rows.*/\1/p')
d=$(awk -F, 'NR == FNR && $1 == 2 { for (i = 2; i <= 9; i++) x[i] = $i }
  NR != FNR && FNR > 1 && $1 == 2 { for (i = 2; i <= 9; i++) { e = $i - x[i]; e = e < 0 ? -e : e; if (e > m) m = e
                                                              a = $i < 0 ? -$i : $i; if (a > big) big = a }; n++ }
  END { if (n != 1 || big == 0) print "nan"; else printf "%.3g\n", m / big }' "$tmp/fourbar.csv" "$tmp/fourbar_taylor.csv")
[ $st -eq 0 ] && awk -v d="$d" -v e="$err" 'BEGIN { exit !(d != "nan" && d + 0 <= 1e-9 && e != "" && e + 0 <= 1e-7) }'
ok $? "fourbar.xml by Taylor's method to t = 2: rk8pd's state to $d, the error against Taylor's reference $err"

# the shipped floating base, its motors driving the legs: no force but
# gravity acts on the whole, so its centre of mass falls as a stone
# dropped at rest, z(t) = z(0) - g t^2/2, x and y still, whatever the legs
# do (the centre from the run's rows by MuJoCo's kinematics)
"$eomc" run "$src/specs/floating_base.xml" --set u_left_hip=0.5 --set u_right_knee=-0.8 \
  --rtol 1e-12 --atol 1e-12 -o "$tmp/fb.csv" 2> "$tmp/err"
st=$?
# (the coordinates: the columns before the first speed, a free joint's x')
nq=$(head -1 "$tmp/fb.csv" | tr ',' '\n' | awk "/'/ { print NR - 2; exit }")
cut -d, -f1-$((nq + 1)) "$tmp/fb.csv" | tail -n +2 | tr ',' ' ' | "$mj" "$src/specs/floating_base.xml" com \
  > "$tmp/com"
com=$(awk 'NR == 1 { x0 = $2; y0 = $3; z0 = $4 }
  { d = $4 - (z0 - 9.81 * $1 * $1 / 2); e = $2 - x0; f = $3 - y0
    d = d < 0 ? -d : d; e = e < 0 ? -e : e; f = f < 0 ? -f : f
    m = d > m ? d : m; m = e > m ? e : m; m = f > m ? f : m; n++ }
  END { if (n < 101) print "nan"; else printf "%.3g\n", m }' "$tmp/com")
swing=$(awk -F, 'NR == 2 { a = $9 } END { d = $9 - a; print (d < 0 ? -d : d) }' "$tmp/fb.csv")
[ $st -eq 0 ] && [ ! -s "$tmp/err" ] && awk -v c="$com" -v s="$swing" \
  'BEGIN { exit !(c != "nan" && c <= 1e-11 && s > 0.1) }'
ok $? "floating_base.xml, legs driven (left hip turned $swing rad): its centre of mass falls as g t^2/2 to $com m (<= 1e-11)"

"$eomc" run "$src/tests/import/models/arm.xml" --accel > "$tmp/direct0" 2> /dev/null
# the model file itself where a spec goes: imported first, the same q''
# (against a fresh import: the one above lost its contacts for MuJoCo)
"$eomc" import "$src/tests/import/models/springs.xml" -o "$tmp/springs_full.yaml" 2> "$tmp/err" &&
  "$eomc" run "$src/tests/import/models/springs.xml" --accel > "$tmp/direct" 2>> "$tmp/err" &&
  "$eomc" run "$tmp/springs_full.yaml" --accel > "$tmp/spec" 2>> "$tmp/err" &&
  [ -s "$tmp/direct" ] && cmp -s "$tmp/direct" "$tmp/spec" &&
  "$eomc" compile "$src/tests/import/models/springs.xml" 2> "$tmp/err" |
    grep -q "from springs.xml (as imported)"
ok $? "eomc run MODEL.xml: the q'' of its imported spec, to the bit; compile names it"

# a model's name that is no identifier is made one (it names the C)
sed 's/<mujoco model="arm">/<mujoco model="9b my-arm">/' "$src/tests/import/models/arm.xml" \
  > "$tmp/named.xml"
"$eomc" import "$tmp/named.xml" 2> /dev/null | grep -q '^name: _9b_my_arm$' &&
  "$eomc" run "$tmp/named.xml" --accel > "$tmp/named" 2> /dev/null && cmp -s "$tmp/named" "$tmp/direct0"
ok $? "model '9b my-arm': the spec's name _9b_my_arm, and the arm's q''"
abs=$eomc # run in $tmp, where a file "-" would be made
case $abs in /*) ;; *) abs=$(pwd)/$abs ;; esac
(cd "$tmp" && "$abs" import named.xml -o - > dash.yaml 2> /dev/null &&
  "$abs" import named.xml > plain.yaml 2> /dev/null)
[ -s "$tmp/dash.yaml" ] && cmp -s "$tmp/dash.yaml" "$tmp/plain.yaml" && [ ! -e "$tmp/-" ]
ok $? "import -o -: the spec on stdout, as without -o, and no file '-'"

# names that collide once made identifiers: the later one takes _2 and
# the import says so; bodies have their own namespace and keep theirs
cat > "$tmp/clash.xml" <<'XML'
<mujoco><worldbody><body name="a-b"><joint name="a-b" axis="0 1 0"/><geom size="0.1"/>
<body name="x" pos="0 0 -0.3"><joint name="a_b" axis="1 0 0"/><geom size="0.1"/></body></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/clash.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q '^coordinates: \[a_b, a_b_2\]$' "$tmp/out" && grep -q '^  a_b: {mass:' "$tmp/out" &&
  grep -q "warning: renamed: joint 'a_b' is 'a_b_2' in the spec ('a_b' is another's name)" "$tmp/err" &&
  [ $(grep -c renamed "$tmp/err") -eq 1 ]
ok $? "joints 'a-b' and 'a_b': coordinates a_b and a_b_2, the rename told; body 'a-b' keeps a_b"

# what the import cannot write is refused by name, with exit 2 and nothing written
cat > "$tmp/ballspring.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" type="ball" stiffness="2"/><geom size="0.1"/></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/ballspring.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "joint j: the stiffness of a ball joint is not imported" "$tmp/err"
ok $? "a ball joint's spring: refused by name, exit 2, nothing written ($(cat "$tmp/err"))"
cat > "$tmp/cable.xml" <<'XML'
<mujoco><worldbody><site name="top" pos="0 0 1"/><body name="b"><joint name="j" axis="0 1 0"/><geom size="0.1"/>
<site name="tip" pos="0 0 -0.5"/></body></worldbody>
<tendon><spatial name="cable" stiffness="3"><site site="top"/><site site="tip"/></spatial></tendon></mujoco>
XML
"$eomc" import "$tmp/cable.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] &&
  grep -q "cable.xml:3:24: error: tendon cable: the stiffness or damping of a spatial tendon" "$tmp/err" &&
  grep -q '^ *| *\^$' "$tmp/err"
ok $? "a spatial tendon's spring: refused by name at the element's name (file:line:column, caret), exit 2 ($(cat "$tmp/err"))"
# MuJoCo's own loader error, at the line it names
printf '<mujoco>\n  <worldbody>\n    <body>\n      <joint type="bogus"/>\n    </body>\n  </worldbody>\n</mujoco>\n' > "$tmp/bogus.xml"
"$eomc" import "$tmp/bogus.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "bogus.xml:4:7: error: MuJoCo cannot load it: .*'bogus'" "$tmp/err"
ok $? "MuJoCo's loader error: at the line it names, first character, exit 2 ($(head -1 "$tmp/err"))"
sed 's|stiffness="3"||; s|</tendon>|<fixed name="f"><joint joint="j" coef="1"/></fixed></tendon><equality><tendon name="tie" tendon1="f" tendon2="cable"/></equality>|' \
  "$tmp/cable.xml" > "$tmp/tie.xml"
"$eomc" import "$tmp/tie.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "equality constraint tie: couples a spatial tendon" "$tmp/err"
ok $? "a tendon equality on a spatial tendon: refused by name, exit 2 ($(cat "$tmp/err"))"
cat > "$tmp/filter.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0"/><geom size="0.1"/></body></worldbody>
<actuator><general name="slow" joint="j" dyntype="filter" dynprm="0.1"/></actuator></mujoco>
XML
"$eomc" import "$tmp/filter.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "actuator slow: its activation dynamics (dyntype) is not imported" "$tmp/err"
ok $? "an actuator with activation dynamics: refused by name, exit 2 ($(cat "$tmp/err"))"
# what is dropped is named (a ball joint's limits, tendon limits, a
# tendon's friction loss, contacts), and --strict refuses it; a hinge's
# limits and the actuators' ranges are kept (the stops of effect limits,
# the clamps of defines ctrl_NAME and force_NAME), and so is a joint's
# friction loss, as dry friction (the range "-1 1" is in degrees, MJCF's
# default)
cat > "$tmp/dropped.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0" limited="true" range="-1 1" frictionloss="0.2"/>
<geom size="0.1"/><body pos="0 0 -0.3"><joint name="k" axis="1 0 0" limited="true" range="-1 1"/><geom size="0.1"/>
<body pos="0 0 -0.3"><joint axis="1 0 0" limited="true" range="-1 1"/><geom size="0.1"/>
<body pos="0 0 -0.3"><joint name="ball" type="ball" limited="true" range="0 1"/><geom size="0.1"/></body></body></body></body></worldbody>
<tendon><fixed name="tf" limited="true" range="-1 1" frictionloss="0.1"><joint joint="j" coef="1"/></fixed></tendon>
<actuator><motor joint="j" ctrllimited="true" ctrlrange="-1 1"/><motor name="m2" joint="k" forcelimited="true" forcerange="-2 2"/></actuator></mujoco>
XML
"$eomc" import "$tmp/dropped.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && [ -s "$tmp/out" ] &&
  grep -q "warning: dropped: the limits of ball joint ball (MuJoCo's limit on a ball joint's angle of rotation is not imported" "$tmp/err" &&
  ! grep -q "friction loss of joint j" "$tmp/err" &&
  grep -q "^  friction_loss: \[{friction: j, force: 0.2}\]$" "$tmp/out" &&
  grep -q "warning: dropped: the friction of 3 contact pairs: #0-#2, #0-#3, #1-#3 (eomc's contact friction acts where a shape touches a plane: written without friction)$" "$tmp/err" &&
  grep -q "warning: dropped: the limits of tendon tf (tendon limits are not imported" "$tmp/err" &&
  grep -q "warning: dropped: the friction loss of tendon tf (eomc's dry friction acts on a coordinate" "$tmp/err" &&
  [ $(wc -l < "$tmp/err") -eq 4 ] &&
  grep -q "^  limits: \[{limit: j, range: \[-0.0174532925199[0-9]*, 0.0174532925199[0-9]*\], stiffness: [0-9.e+-]*, damping: [0-9.e+-]*}, {limit: k, " "$tmp/out" &&
  grep -q '^  ctrl_j: "clamp(u_j, -1, 1)"$' "$tmp/out" && grep -q '^  force_m2: "clamp(u_m2, -2, 2)"$' "$tmp/out" &&
  grep -q '^  actuators: \[{work: "ctrl_j\*delta(j)"}, {work: "force_m2\*delta(k)"}\]$' "$tmp/out" &&
  grep -q '^  actuators_unclamped: \[{work: "u_j\*delta(j)"}, {work: "u_m2\*delta(k)"}\]$' "$tmp/out" &&
  grep -q '^scene: {effects: \[gravity, friction_loss, limits, actuators, contacts\], ' "$tmp/out"
ok $? "a ball joint's and a tendon's limits, a tendon's friction loss, the friction of contacts without a plane: one warning each, naming what is dropped, exit 0; hinge limits, actuator ranges and a joint's friction loss kept, the unclamped actuators off in the scene ($(tr '\n' ' ' < "$tmp/err" | head -c 300))"
"$eomc" import "$tmp/dropped.xml" --strict -o "$tmp/strict.yaml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/strict.yaml" ] && grep -q "error: --strict" "$tmp/err"
ok $? "--strict: the same model refused, exit 2, no file written"
# a hinge's friction loss is dry friction of at most frictionloss on its
# coordinate: an arm of mass m whose centre is l from a horizontal hinge
# feels gravity's torque m g l cos(swing), and started at rest it stays
# put where that is within the loss, swing >= acos(F / (m g l)) = th; a
# little below th it moves, and so it does a little above th without the
# effect (its scene can turn it off)
cat > "$tmp/fricloss.xml" <<'XML'
<mujoco><worldbody><body name="arm" pos="0 0 1"><joint name="swing" axis="0 1 0" frictionloss="0.5"/>
<geom type="sphere" pos="0.2 0 0" size="0.02" mass="0.3"/></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/fricloss.xml" -o "$tmp/fricloss.yaml" 2> /dev/null
th=$(awk 'BEGIN { printf "%.17g", atan2(sqrt(0.5886^2 - 0.25), 0.5) }')
fric_run() { # START [ARGS]: swing and swing' at t = 1 from rest at START
  sed "s/^scene:/initial: {swing: $1}\nscene:/" "$tmp/fricloss.yaml" > "$tmp/fricloss_at.yaml"
  shift
  "$eomc" run "$tmp/fricloss_at.yaml" "$@" | tail -1 | cut -d, -f2,3
}
above=$(awk -v t="$th" 'BEGIN { printf "%.17g", t + 0.01 }')
below=$(awk -v t="$th" 'BEGIN { printf "%.17g", t - 0.01 }')
[ "$(grep -c 'friction_loss: \[{friction: swing, force: 0.5}\]' "$tmp/fricloss.yaml")" -eq 1 ] &&
  fric_run "$above" | awk -F, -v a="$above" '{ exit !($1 == a && $2 == 0) }' &&
  fric_run "$below" | awk -F, -v a="$below" '{ exit !($1 > a + 0.01) }' &&
  fric_run "$above" --effects gravity | awk -F, -v a="$above" '{ exit !($1 > a + 0.01) }'
ok $? "a hinge's friction loss (effect friction_loss): at rest it stays put where gravity's torque is below the loss, past acos(F/(m g l)) = $th, and moves 0.01 short of it, or without the effect"
# where it cannot be kept, it is dropped by name: a ball's turn has no
# coordinate, and the stuck solve does not take equality constraints
cat > "$tmp/fricball.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="ball" type="ball" frictionloss="0.1"/><geom size="0.1"/>
<body pos="0 0 -0.3"><joint name="h" axis="0 1 0" frictionloss="0.1"/><geom size="0.1"/></body></body>
<body name="c" pos="1 0 0"><joint name="h2" axis="0 1 0"/><geom size="0.1"/></body></worldbody>
<equality><joint joint1="h" joint2="h2"/></equality></mujoco>
XML
"$eomc" import "$tmp/fricball.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && ! grep -q friction_loss "$tmp/out" &&
  grep -q "warning: dropped: the friction loss of the turn of joint ball (eomc's dry friction acts on a coordinate" "$tmp/err" &&
  grep -q "warning: dropped: the friction loss of joint h (eomc's dry friction does not take equality constraints yet)" "$tmp/err"
ok $? "a ball's friction loss, and one in a model with equality constraints: dropped by name ($(grep friction "$tmp/err" | tr '\n' ' '))"
# MuJoCo's flags that turn off what eomc drops or keeps (limits, friction
# loss, contacts, the clamping of controls; constraint: all but the
# clamping): nothing is dropped there, and what they turn off is not
# written, as MuJoCo computes none of it either (the force range stays:
# no flag turns it off)
sed 's|<mujoco>|<mujoco><option><flag limit="disable" frictionloss="disable" contact="disable" clampctrl="disable"/></option>|' \
  "$tmp/dropped.xml" > "$tmp/dropped_off.xml"
sed 's|<mujoco>|<mujoco><option><flag constraint="disable"/></option>|' "$tmp/dropped.xml" > "$tmp/dropped_nocon.xml"
"$eomc" import "$tmp/dropped_off.xml" > "$tmp/off.yaml" 2> "$tmp/err"
st=$?
"$eomc" import "$tmp/dropped_nocon.xml" > "$tmp/nocon.yaml" 2> "$tmp/err2"
st2=$?
[ $st -eq 0 ] && [ $st2 -eq 0 ] && [ ! -s "$tmp/err" ] && [ ! -s "$tmp/err2" ] &&
  ! grep -q "limits:\|ctrl_j" "$tmp/off.yaml" && grep -q "force_m2:" "$tmp/off.yaml" &&
  ! grep -q "limits:" "$tmp/nocon.yaml" && grep -q "ctrl_j:" "$tmp/nocon.yaml" &&
  grep -q "force_m2:" "$tmp/nocon.yaml"
ok $? "flags limit, frictionloss, contact, clampctrl disabled: nothing dropped, no stops and no control clamp written (the force range's kept); constraint disabled: no stops, both clamps ($(cat "$tmp/err" "$tmp/err2" | tr '\n' ' '))"
# a flag that leaves something out says so, in a note and in the spec
"$eomc" import "$tmp/fluid_unforced.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q "note: left out, as the model's <option><flag> disables them in MuJoCo too: gravity (flag gravity), springs, damping and fluid forces (flag passive)$" "$tmp/err" &&
  grep -q "^# Left out, as the model's <option><flag> disables them: gravity (flag gravity), springs" "$tmp/out" &&
  grep -q "^  actuators:" "$tmp/out" && ! grep -q "^  gravity:\|^  damping:\|^  stiffness:\|^  fluid:" "$tmp/out"
ok $? "flags gravity and passive disabled: no gravity, damping, stiffness, fluid in the spec, the actuators kept, a note says why"
"$eomc" import "$tmp/closed_noconstraint.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && ! grep -q "^constraints:\|assemble" "$tmp/out" &&
  grep -q "note: left out, .*: equality constraints (flag constraint)$" "$tmp/err" && [ $(wc -l < "$tmp/err") -eq 1 ]
ok $? "flag constraint disabled: no constraints, nothing dropped (contacts off too), a note ($(cat "$tmp/err"))"
# what a flag disables is not refused: a ball joint's spring with passive
# forces off, an actuator with activation dynamics with actuation off
cat > "$tmp/offrefused.xml" <<'XML'
<mujoco><option><flag passive="disable" actuation="disable"/></option><worldbody><body name="b"><joint name="j" type="ball" stiffness="2"/><geom size="0.1"/>
<body pos="0 0 -0.3"><joint name="k" axis="0 1 0"/><geom size="0.1"/></body></body></worldbody>
<actuator><general name="slow" joint="k" dyntype="filter" dynprm="0.1"/></actuator></mujoco>
XML
"$eomc" import "$tmp/offrefused.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && ! grep -q "^inputs:\|^  stiffness:\|^  actuators:" "$tmp/out" &&
  grep -q "springs, damping and fluid forces (flag passive), actuators (flag actuation)$" "$tmp/err"
ok $? "a ball's spring with passive forces disabled, a filtered actuator with actuation disabled: left out, not refused ($(cat "$tmp/err"))"
# <contact><pair>: a contact whatever the geoms' contype, kept with its
# friction (MuJoCo's default, 1; k = m/0.02^2, c = 2 m/0.02, m = 4/3 pi
# 0.1^3 1000);
# MuJoCo's ellipsoid fluid model (a geom's fluidshape): its body's fluid
# forces dropped by name, the other bodies' imported; --strict refuses both
cat > "$tmp/pairs.xml" <<'XML'
<mujoco><option density="1000"/><worldbody><geom name="floor" type="plane" size="1 1 0.1" contype="0" conaffinity="0"/>
<body name="ball" pos="0 0 1"><freejoint/><geom name="g" size="0.1" contype="0" conaffinity="0" fluidshape="ellipsoid"/></body>
<body name="box" pos="1 0 1"><freejoint/><geom size="0.1 0.2 0.3" type="box" contype="0" conaffinity="0"/></body></worldbody>
<contact><pair name="bounce" geom1="floor" geom2="g"/></contact></mujoco>
XML
"$eomc" import "$tmp/pairs.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
"$eomc" import "$tmp/pairs.xml" --strict > "$tmp/out2" 2> "$tmp/err2"
st2=$?
[ $st -eq 0 ] &&
  grep -q '^    - {contact: \[\[floor, g\]\], stiffness: 10471.97551196597[0-9]*, damping: 418.879020478639[0-9]*, friction: 1}$' "$tmp/out" &&
  grep -q "warning: dropped: the fluid forces on body ball (MuJoCo's ellipsoid model" "$tmp/err" &&
  [ $(wc -l < "$tmp/err") -eq 1 ] && grep -q '^  fluid: \[{force: ".*", on: box}, {torque: ".*", on: box}\]$' "$tmp/out" &&
  [ $st2 -eq 2 ] && [ ! -s "$tmp/out2" ] && grep -q "error: --strict" "$tmp/err2"
ok $? "a contact pair kept with its friction, an ellipsoid fluid model dropped by name (--strict: exit 2), the box's fluid imported ($(cat "$tmp/err" | tr '\n' ' '))"

# --floating: the URDF's root link free.  The spec has the trunk's free
# joint first; without it, the trunk is the world's (no body).  Run so
# (eomc run ROBOT.urdf --floating), legs swinging from their initial
# rates, nothing but gravity acts on the whole: its centre of mass (by
# MuJoCo's kinematics of the floating URDF) moves on a parabola, its second
# differences over the rows' step h are (0, 0, -g h^2)
"$eomc" import "$models_dir/legged.urdf" > "$tmp/fixed.yaml" 2> /dev/null
grep -q '^coordinates: \[trunk_x, trunk_y, trunk_z, trunk_qw, trunk_qx, trunk_qy, trunk_qz, left_hip, left_knee, right_hip, right_knee\]$' "$tmp/legged_urdf.yaml" &&
  grep -q '^  trunk: {mass: 4, frame: trunk_axes, center: trunk_com' "$tmp/legged_urdf.yaml" &&
  grep -q '^coordinates: \[left_hip, left_knee, right_hip, right_knee\]$' "$tmp/fixed.yaml" &&
  ! grep -q '^  trunk:' "$tmp/fixed.yaml"
ok $? "legged.urdf --floating: the trunk a free body (trunk_x .. trunk_qz); without it, fixed to the world"
"$eomc" run "$models_dir/legged.urdf" --floating --init "left_hip'=3" --init "right_knee'=-2" \
  --init "trunk_x'=0.4" --rtol 1e-12 --atol 1e-12 -o "$tmp/legged.csv" 2> "$tmp/err"
st=$?
cut -d, -f1-12 "$tmp/legged.csv" | tail -n +2 | tr ',' ' ' | "$mj" "$tmp/legged_floating.urdf" com > "$tmp/com"
par=$(awk '{ t[NR] = $1; x[NR] = $2; y[NR] = $3; z[NR] = $4 }
  END { if (NR < 101) { print "nan"; exit }
        for (i = 2; i < NR; i++) {
          h = t[i + 1] - t[i]
          d = z[i + 1] - 2 * z[i] + z[i - 1] + 9.81 * h * h; e = x[i + 1] - 2 * x[i] + x[i - 1]
          f = y[i + 1] - 2 * y[i] + y[i - 1]
          d = d < 0 ? -d : d; e = e < 0 ? -e : e; f = f < 0 ? -f : f
          m = d > m ? d : m; m = e > m ? e : m; m = f > m ? f : m; s = x[NR] - x[1] }
        printf "%.3g %.3g\n", m, s }' "$tmp/com")
swing=$(awk -F, 'NR == 2 { a = $9 } END { d = $9 - a; print (d < 0 ? -d : d) }' "$tmp/legged.csv")
set -- $par
[ $st -eq 0 ] && grep -q "^t,trunk_x,trunk_y,trunk_z,trunk_qw,trunk_qx,trunk_qy,trunk_qz,left_hip,left_knee,right_hip,right_knee," "$tmp/legged.csv" &&
  awk -v c="$1" -v s="$swing" -v x="${2:-0}" 'BEGIN { exit !(c != "nan" && c <= 1e-11 && s > 0.2 && x > 0.2) }'
ok $? "eomc run legged.urdf --floating, the legs swinging ($swing rad): its centre of mass on a parabola, second differences within $1 m of (0, 0, -g h^2) (<= 1e-11)"
# a URDF joint's <mimic> (a coupling MuJoCo's reader ignores): dropped by
# name, --strict refuses it; one in a comment is no mimic
sed 's|<joint name="right_knee" type="revolute">|&<mimic joint="left_knee" multiplier="1"/>|
     s|<joint name="right_hip" type="continuous">|&<!-- <mimic joint="left_hip"/> -->|' \
  "$models_dir/legged.urdf" > "$tmp/mimic.urdf"
"$eomc" import "$tmp/mimic.urdf" --floating > "$tmp/out" 2> "$tmp/err"
st=$?
"$eomc" import "$tmp/mimic.urdf" --strict > "$tmp/out2" 2> "$tmp/err2"
st2=$?
[ $st -eq 0 ] && [ $(grep -c "<mimic>" "$tmp/err") -eq 1 ] &&
  grep -q "warning: dropped: the <mimic> of joint right_knee (MuJoCo's URDF reader ignores it: the joint moves on its own)" "$tmp/err" &&
  [ $st2 -eq 2 ] && [ ! -s "$tmp/out2" ] && grep -q "error: --strict" "$tmp/err2"
ok $? "a URDF joint's <mimic>: dropped by name (--strict: exit 2) ($(grep "<mimic>" "$tmp/err"))"
# --floating on an MJCF, on a URDF whose root is the link world (MuJoCo's
# world itself), and on a spec: refused, exit 2, nothing written
"$eomc" import "$models_dir/arm.xml" --floating -o "$tmp/f.yaml" > /dev/null 2> "$tmp/err"
st=$?
sed 's|<robot name="legged">|<robot name="legged"><link name="world"/><joint name="w" type="fixed"><parent link="world"/><child link="trunk"/></joint>|' \
  "$models_dir/legged.urdf" > "$tmp/world.urdf"
"$eomc" import "$tmp/world.urdf" --floating > "$tmp/out" 2> "$tmp/err2"
st2=$?
"$eomc" run "$tmp/fixed.yaml" --floating > /dev/null 2> "$tmp/err3"
st3=$?
[ $st -eq 2 ] && [ ! -e "$tmp/f.yaml" ] &&
  grep -q "arm.xml: error: --floating frees the root link of a URDF, which MuJoCo welds to the world; an MJCF says itself how its bodies move: give its root body a <freejoint/>" "$tmp/err" &&
  [ $st2 -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "world.urdf: error: --floating: the URDF's root link is 'world'" "$tmp/err2" &&
  [ $st3 -eq 2 ] && grep -q "eomc: --floating is for an MJCF or URDF model given where the spec goes" "$tmp/err3"
ok $? "--floating on an MJCF, on a URDF rooted at the link world, on a spec: refused by name, exit 2 ($(cat "$tmp/err" "$tmp/err2" "$tmp/err3" | tr '\n' ' '))"

# docs/import.md lists what eomc does with every flag, option and model
# field of the MuJoCo it is built with (its mjmodel.h): a MuJoCo that adds
# one is noticed here
header=$(printf '#include <mujoco/mjmodel.h>\n' | cc -E -x c - 2> /dev/null |
  sed -n 's|^# [0-9]* "\(.*/mjmodel\.h\)".*|\1|p' | head -1)
names=$(awk '/^typedef enum mjtDisableBit_/, /} mjtDisableBit;/ { if (match($0, /mjDSBL_[A-Z]+/)) print "flag " tolower(substr($0, RSTART + 7, RLENGTH - 7)) }
  /^typedef enum mjtEnableBit_/, /} mjtEnableBit;/ { if (match($0, /mjENBL_[A-Z]+/)) print "flag " tolower(substr($0, RSTART + 7, RLENGTH - 7)) }
  /^struct mjOption_/, /^};/ { if (match($0, /[a-z_0-9]+(\[[A-Za-z0-9]+\])?;/)) { f = substr($0, RSTART, RLENGTH); sub(/[[;].*/, "", f); print "option " f } }
  /^struct mjModel_/, /^};/ { if ($0 ~ /\*/ && match($0, /[a-z_A-Z0-9]+;/)) print "field " substr($0, RSTART, RLENGTH - 1)
                            else if ($0 ~ /^  mj[A-Z][a-z]+ +[a-z]+;/ && match($0, /[a-z]+;/)) print "field " substr($0, RSTART, RLENGTH - 1) }' "$header")
# a flag as a row of the flags' table, in its MJCF spelling (| `gravity="disable"` |),
# an option in the first cell of a row, a field anywhere
missing=$(echo "$names" | while read -r kind name; do
  case $kind in
  flag) pat="^| \`$name=\"\(disable\|enable\)\"\` |" ;;
  option) pat="^| [^|]*\`$name\`" ;;
  *) pat="\`$name\`" ;;
  esac
  grep -q "$pat" "$src/docs/import.md" || printf '%s %s, ' "$kind" "$name"; done)
count=$(echo "$names" | grep -c .)
[ -n "$header" ] && [ "$count" -gt 300 ] && [ -z "$missing" ]
ok $? "docs/import.md names each of the $count flags, options and model fields of $header${missing:+; not: $missing}"
"$eomc" import "$tmp/nosuch.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && grep -q "nosuch.xml: error: MuJoCo cannot load it" "$tmp/err"
ok $? "a missing file: MuJoCo's message, exit 2"
# geoms become the body's shapes, in its axes at its centre of mass
# (geom_pos - body_ipos), in MuJoCo's sizes; a mesh is drawn as the box
# that bounds it, with a warning naming it; the world's geoms, and those of
# a body welded to it without mass, are the spec's ground, in the world's
# axes (the body's placed by its pos and euler turn); a plane of the world
# across z is the page's floor (view: floor: its height), another plane is
# not drawn, with a note naming it
cat > "$tmp/shapes.xml" <<'XML'
<mujoco><asset><mesh name="tet" vertex="0 0 0  1 0 0  0 1 0  0 0 1"/></asset>
<worldbody><geom name="floor" type="plane" size="1 1 0.1" pos="0 0 -0.5" euler="0 0 30" contype="0" conaffinity="0"/>
<geom name="wall" type="plane" size="1 1 0.1" pos="2 0 0" euler="0 90 0" contype="0" conaffinity="0"/>
<geom name="post" type="cylinder" size="0.05 0.5" pos="0 0 0.5" contype="0" conaffinity="0"/>
<body name="stand" pos="1 0 0" euler="0 0 90"><geom type="box" size="0.2 0.1 0.01" pos="0.1 0 0" mass="0" contype="0" conaffinity="0"/></body>
<body name="b"><joint name="j" axis="0 1 0"/>
<inertial pos="0 0 -0.1" mass="1" diaginertia="0.1 0.1 0.1"/>
<geom type="box" size="0.1 0.2 0.3" pos="0.5 0 0" rgba="1 0 0 0.5" contype="0" conaffinity="0"/>
<geom type="ellipsoid" size="0.1 0.2 0.3" quat="0 0 0 1" contype="0" conaffinity="0"/>
<geom type="mesh" mesh="tet" contype="0" conaffinity="0"/>
</body></worldbody></mujoco>
XML
"$eomc" import "$tmp/shapes.xml" -o "$tmp/shapes.yaml" 2> "$tmp/err"
st=$?
# the mesh's box, from the spec: every corner of the tetrahedron (in b's
# axes from its centre of mass, so + [0, 0, 0.1]) inside it, and touching
# each of its faces (to 1e-6: MuJoCo keeps a mesh in floats)
box=$(sed -n '/^  b: /s/.*{type: box, size: \[\([^]]*\)\], pos: \[\([^]]*\)\], quat: \[\([^]]*\)\].*/\1, \2, \3/p' "$tmp/shapes.yaml")
bounds=$(echo "$box" | awk -F', ' '{
    w = $7; x = $8; y = $9; z = $10
    R[1,1] = 1-2*(y*y+z*z); R[1,2] = 2*(x*y-w*z); R[1,3] = 2*(x*z+w*y)
    R[2,1] = 2*(x*y+w*z); R[2,2] = 1-2*(x*x+z*z); R[2,3] = 2*(y*z-w*x)
    R[3,1] = 2*(x*z-w*y); R[3,2] = 2*(y*z+w*x); R[3,3] = 1-2*(x*x+y*y)
    split("0 0 0.1 1 0 0.1 0 1 0.1 0 0 1.1", v, " ")
    bad = NF != 10
    for (c = 0; c < 4; c++)
      for (i = 1; i <= 3; i++) {
        b = 0 # the corner in the box axes: R^T (v - pos)
        for (j = 1; j <= 3; j++) b += R[j,i] * (v[3*c+j] - $(3+j))
        b = b < 0 ? -b : b
        if (b > $i + 1e-6) bad = 1
        if (b > top[i]) top[i] = b
      }
    for (i = 1; i <= 3; i++) if (top[i] < $i - 1e-6) bad = 1
    print bad ? "no" : "yes" }')
[ $st -eq 0 ] && grep -q 'shapes: \[{type: box, size: \[0.1, 0.2, 0.3\], pos: \[0.5, 0, 0.1\], rgba: \[1, 0, 0, 0.5\]}, {type: ellipsoid, size: \[0.1, 0.2, 0.3\], pos: \[0, 0, 0.1\], quat: \[0, 0, 0, 1\], rgba: \[0.5, 0.5, 0.5, 1\]}, {type: box, ' "$tmp/shapes.yaml" &&
  [ "$bounds" = yes ] &&
  grep -q '^  - {type: cylinder, size: \[0.05, 0.5\], pos: \[0, 0, 0.5\], rgba: \[0.5, 0.5, 0.5, 1\]}$' "$tmp/shapes.yaml" &&
  grep -q '^  - {type: box, size: \[0.2, 0.1, 0.01\], pos: \[1, 0.1, 0\], quat: \[0.707106781186547[0-9]*, 0, 0, 0.707106781186547[0-9]*\]' "$tmp/shapes.yaml" &&
  grep -q "shapes.xml: warning: drawn as boxes: mesh geom #6 of b (mesh tet) (--animate draws no meshes" "$tmp/err" &&
  grep -q "shapes.xml: note: not drawn: geom wall of the world (a plane)" "$tmp/err" &&
  grep -q '^scene: {t_end: 1, dt: 0.01, view: {floor: -0.5}}$' "$tmp/shapes.yaml" &&
  [ $(wc -l < "$tmp/err") -eq 2 ] &&
  "$eomc" compile "$tmp/shapes.yaml" -o "$tmp/shapes.c" 2> /dev/null &&
  grep -q '^    {0, EOMC_SHAPE_BOX, {0.1, 0.2, 0.3}, {0.5, 0.0, 0.1}, {1.0, 0.0, 0.0, 0.0}, {1.0, 0.0, 0.0, 0.5}},$' "$tmp/shapes.c" &&
  grep -q '^    {"ground", EOMC_DRAW_BODY, 3, 0},$' "$tmp/shapes.c" &&
  grep -q '^    {1, EOMC_SHAPE_CYLINDER, {0.05, 0.5, 0.0}, {0.0, 0.0, 0.5}, ' "$tmp/shapes.c" &&
  grep -q '^    .nshape = 5, .shapes = shapes,$' "$tmp/shapes.c"
ok $? "geoms: shapes at geom_pos - body_ipos, the mesh as a box bounding it ($bounds), the world's and a welded body's as the ground, the floor plane as view: floor, the wall noted; in the C ($(cat "$tmp/err"))"

# a robot on one free joint: its page's camera follows the base from
# the start (view: follow:), the item the page names so; two free bodies
# (contacts.xml): none is chosen for the user
check="python3 $src/tests/cli/page_check.py"
"$eomc" import "$src/specs/floating_base.xml" -o "$tmp/fbv.yaml" 2> /dev/null &&
  "$eomc" run "$tmp/fbv.yaml" --t-end 0.05 -o /dev/null --animate "$tmp/fbv.html" 2> /dev/null
st=$?
i=$($check json "$tmp/fbv.html" follow 2> /dev/null)
[ $st -eq 0 ] && grep -q '^scene: {.*view: {follow: base}}$' "$tmp/fbv.yaml" &&
  [ "$($check json "$tmp/fbv.html" "items.$i.name" 2> /dev/null)" = '"base"' ] &&
  "$eomc" import "$src/tests/import/models/contacts.xml" 2> /dev/null | grep '^scene: ' | grep -vq follow
ok $? "a floating base's page follows it (item $i, base); with four free bodies (contacts.xml), none"

# a URDF's visuals drawn (MuJoCo discards them unless told): the fixed
# root link's as the ground, at its <origin>; a link's box at half its
# URDF size; on a link with both, the visual, not the collision box; the
# mesh as a box, named; the dynamics are MuJoCo's without the visuals
# (q'' against mj_forward above: visual_arm_urdf)
va=$tmp/visual_arm_urdf.yaml
"$eomc" import "$src/tests/import/models/visual_arm.urdf" 2> "$tmp/err" > /dev/null
grep -q '^  - {type: cylinder, size: \[0.1, 0.05\], pos: \[0, 0, 0.05\], rgba: \[0.8, 0.1, 0.1, 1\]}$' "$va" &&
  grep -q '^  upper: .*shapes: \[{type: box, size: \[0.15, 0.025, 0.025\], rgba: \[0.6, 0.6, 0.65, 1\]}, {type: sphere, size: \[0.04\], pos: \[-0.15, 0, 0\]' "$va" &&
  grep -q '^  fore: {mass: 0.32, .*shapes: \[{type: cylinder, size: \[0.02, 0.12\], [^]]*\], quat: \[[^]]*\], rgba: \[0.5, 0.5, 0.5, 1\]}\]}$' "$va" &&
  grep -q '^  tip: {mass: 0.4, .*shapes: \[{type: box, size: \[0.0199999[0-9]*, 0.0299999[0-9]*, 0.0399999[0-9]*\], .*{type: sphere, size: \[0.015\]' "$va" &&
  grep -q "visual_arm.urdf: warning: drawn as boxes: mesh geom #5 of tip (mesh visual_arm_tip)" "$tmp/err"
ok $? "visual_arm.urdf: its visuals drawn, the root link's as the ground, a mesh as a box, named ($(grep boxes "$tmp/err"))"
# where MuJoCo cannot load the visuals (a mesh file missing), the URDF as
# MuJoCo loads it by default, with a warning saying why
sed 's|package://visual_arm/meshes/visual_arm_tip.obj|missing.obj|' \
  "$src/tests/import/models/visual_arm.urdf" > "$tmp/nomesh.urdf"
"$eomc" import "$tmp/nomesh.urdf" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && grep -q "nomesh.urdf: warning: the URDF's visuals are not drawn: MuJoCo cannot load them (.*missing" "$tmp/err" &&
  ! grep -q "^ground:" "$tmp/out" && ! grep -q "shapes:.*cylinder" "$tmp/out" &&
  grep -q '^  fore: {mass: 0.32, .*shapes: \[{type: box, size: \[0.1, 0.02, 0.02\]' "$tmp/out"
ok $? "a URDF whose visual mesh is missing: imported without its visuals, saying why ($(head -c 300 "$tmp/err"))"
# a URDF's own <mujoco><compiler>: discardvisual="false" joins its
# attributes (MuJoCo reads the first <mujoco> only); its own discardvisual
# stands
cp "$src/tests/import/models/visual_arm_tip.obj" "$tmp/"
sed 's|<robot name="visual_arm">|<robot name="visual_arm"><mujoco><compiler balanceinertia="true"/></mujoco>|' \
  "$src/tests/import/models/visual_arm.urdf" > "$tmp/own.urdf"
sed 's|balanceinertia="true"|discardvisual="true"|' "$tmp/own.urdf" > "$tmp/discard.urdf"
"$eomc" import "$tmp/own.urdf" 2> /dev/null | grep -q '^  - {type: cylinder, size: \[0.1, 0.05\]' &&
  "$eomc" import "$tmp/discard.urdf" > "$tmp/out" 2> "$tmp/err" && ! grep -q "^ground:" "$tmp/out" &&
  ! grep -q "visuals\|boxes" "$tmp/err"
ok $? "a URDF's own <mujoco><compiler ...>: its visuals kept; with discardvisual=\"true\", not"
tap_end
