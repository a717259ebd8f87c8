#!/bin/sh
# eomc import against MuJoCo itself: each model (MJCF written for these
# tests: an arm, the same with damping and springs, a URDF arm; and the benchmark's
# chain) imported, then q'' of `eomc run --accel`
# at 100 random states against mj_forward's qacc at the same state
# (mj_accel.c: contact, limits, friction loss and equality off), within
# 1e-10 of the largest |q''|; and the import's refusals.
#
# usage: test_import.sh EOMC SOURCE_ROOT BUILD_ROOT MJ_ACCEL
set -u
eomc=$1 src=$2 mj=$4
. "$src/tests/cli/tap.sh"
STATES=100 TOL=1e-10

sh "$src/specs/gen_chain.sh" 5 --mjcf > "$tmp/chain5.xml"
for model in "$src/tests/import/models/arm.xml" "$src/tests/import/models/springs.xml" \
    "$src/tests/import/models/planar_arm.urdf" \
    "$tmp/chain5.xml"; do
  base=$(basename "$model"); base=${base%.*}
  "$eomc" import "$model" -o "$tmp/$base.yaml" 2> "$tmp/err"
  ok $? "$base: imports ($(head -c 200 "$tmp/err"))"
  coords=$(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$tmp/$base.yaml" | tr -d ',')
  worst=0 fails=0
  k=0
  while [ $k -lt $STATES ]; do
    k=$((k + 1))
    # a state: each q and q' uniform in [-1.5, 1.5], from awk's seeded rand
    set -- $(awk -v seed="$k" -v n="$(echo $coords | wc -w)" \
      'BEGIN { srand(seed); for (i = 0; i < 2 * n; i++) printf "%.17g ", 3 * rand() - 1.5 }')
    args= qv="$*" i=0
    for c in $coords; do
      i=$((i + 1))
      eval "q=\${$i}"
      args="$args --init $c=$q"
    done
    for c in $coords; do
      i=$((i + 1))
      eval "v=\${$i}"
      args="$args --init $c'=$v"
    done
    "$eomc" run "$tmp/$base.yaml" --accel $args > "$tmp/eomc" 2>> "$tmp/err" || fails=$((fails + 1))
    "$mj" "$model" $qv > "$tmp/mj" || fails=$((fails + 1))
    d=$(awk 'NR == FNR { w[NR] = $1; n = NR; next }
             { dd = $2 - w[FNR]; if (dd < 0) dd = -dd; if (dd > dm) dm = dd;
               a = w[FNR] < 0 ? -w[FNR] : w[FNR]; if (a > am) am = a; m++ }
             END { if (m != n || am == 0) print "nan"; else printf "%.3g\n", dm / am }' \
      "$tmp/mj" "$tmp/eomc")
    worst=$(awk -v a="$worst" -v b="$d" 'BEGIN { print (b == "nan" || a == "nan") ? "nan" : (b > a ? b : a) }')
  done
  awk -v w="$worst" -v t="$TOL" 'BEGIN { exit !(w != "nan" && w <= t) }' && [ $fails -eq 0 ]
  ok $? "$base: q'' equals MuJoCo's qacc at $STATES random states within $worst of the largest (<= $TOL)"
done

"$eomc" run "$src/tests/import/models/arm.xml" --accel > "$tmp/direct0" 2> /dev/null
# the model file itself where a spec goes: imported first, the same q''
"$eomc" run "$src/tests/import/models/springs.xml" --accel > "$tmp/direct" 2> "$tmp/err" &&
  "$eomc" run "$tmp/springs.yaml" --accel > "$tmp/spec" 2>> "$tmp/err" &&
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

# what the first slice refuses, by name, with exit 2
cat > "$tmp/ball.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" type="ball"/><geom size="0.1"/></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/ball.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "joint j: ball joints are not imported yet" "$tmp/err"
ok $? "a ball joint: refused by name, exit 2, nothing written ($(cat "$tmp/err"))"
cat > "$tmp/armature.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0" armature="0.1"/><geom size="0.1"/></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/armature.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "joint j: its armature is not imported yet" "$tmp/err"
ok $? "armature: refused by name until it is imported, exit 2 ($(cat "$tmp/err"))"
# what is dropped is named (limits, friction loss, contacts), and --strict refuses it
cat > "$tmp/dropped.xml" <<'XML'
<mujoco><worldbody><body name="b"><joint name="j" axis="0 1 0" limited="true" range="-1 1" frictionloss="0.2"/>
<geom size="0.1"/><body pos="0 0 -0.3"><joint name="k" axis="1 0 0"/><geom size="0.1"/></body></body></worldbody></mujoco>
XML
"$eomc" import "$tmp/dropped.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 0 ] && [ -s "$tmp/out" ] && grep -q "joint j: its limits are dropped" "$tmp/err" &&
  grep -q "joint j: its friction loss is dropped" "$tmp/err" &&
  grep -q "contacts between its 2 colliding geoms are dropped" "$tmp/err"
ok $? "limits, friction loss and contacts: each named as dropped, exit 0"
"$eomc" import "$tmp/dropped.xml" --strict -o "$tmp/strict.yaml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/strict.yaml" ] && grep -q "error: --strict" "$tmp/err"
ok $? "--strict: the same model refused, exit 2, no file written"
"$eomc" import "$tmp/nosuch.xml" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && grep -q "nosuch.xml: error: MuJoCo cannot load it" "$tmp/err"
ok $? "a missing file: MuJoCo's message, exit 2"
tap_end
