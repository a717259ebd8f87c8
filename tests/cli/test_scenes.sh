#!/bin/sh
# Named scenes and fixed parameters (specs/swing.yaml), as a user runs
# them (TAP):
#  - --explain lists the scenes, the banner and the simulator's --help
#    name the one compiled, and each scene's initial state is its own;
#  - what a scene leaves out leaves no trace in its C: the free scene
#    never reads c, A or w;
#  - fixing parameters folds them: fewer operations, and the same motion
#    as the unfixed code run with --set (fixed steps, so that both runs
#    take the same steps: only rounding may differ);
#  - --set of a fixed parameter is a usage error that names the scene;
#  - outputs (specs/cartesian_pendulum.yaml, scene tension) are columns
#    after the standard ones, equal to their closed forms computed here
#    from the state columns, and a scene without outputs has no code for
#    them.
# usage: test_scenes.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
spec="$src/specs/swing.yaml"
total() { awk -v f="$1" '$1 == f { print $6 }'; }

"$eomc" compile "$spec" --explain > "$tmp/explain"
grep -q '^  \* free ' "$tmp/explain" && grep -q '^    damped ' "$tmp/explain" &&
    grep -q '^    shaken  *effects: gravity damping; initial: theta' "$tmp/explain"
ok $? "--explain lists the scenes, the default marked"

"$eomc" compile "$spec" --scene damped -o "$tmp/damped.c"
grep -q '^ \* scene:   damped; fixed: A = 0.0$' "$tmp/damped.c"
ok $? "the banner names the scene and what it fixes"

"$eomc" build "$spec" --scene shaken -o "$tmp/shaken" 2> /dev/null
"$tmp/shaken" --help | grep -q '^Simulate swing (swing.yaml, [a-z-]* form, scene shaken)'
ok $? "the simulator's --help names the scene"
first=$("$tmp/shaken" --t-end 0.01 | sed -n 2p | cut -d, -f2)
[ "$first" = "0.1" ]
ok $? "scene shaken starts from its own initial theta = 0.1, written shortest ($first)"

"$eomc" compile "$spec" --scene free -o "$tmp/free.c"
"$eomc" compile "$spec" --scene shaken -o "$tmp/shaken.c"
! grep -q 'p_c =\|p_A =\|p_w =\|cos(t\|sin(t' "$tmp/free.c" &&
    grep -q 'p_c = p\[3\]' "$tmp/damped.c" && grep -q 'p_w = p\[5\]' "$tmp/shaken.c"
ok $? "scene free reads no damping c and no drive A, w; damped reads c, shaken w"

# folding: the shaken scene with A, w, g and l fixed, against the same
# scene unfixed and run with --set
fix="A=0.03,w=5.5,g=9.7,l=0.8"
"$eomc" compile "$spec" --scene shaken --jacobian auto --stats -o /dev/null 2> "$tmp/st0"
"$eomc" compile "$spec" --scene shaken --fix "$fix" --jacobian auto --stats -o /dev/null 2> "$tmp/st1"
# (M = m l^2 (sin^2 + cos^2) folds by structure with the parameters free
# too, so M and accel may cost the same either way; the Jacobian folds more)
for f in mass_bias jacobian accel; do
    a=$(total $f < "$tmp/st0") b=$(total $f < "$tmp/st1")
    if [ $f = jacobian ]; then [ "$b" -lt "$a" ]; else [ "$b" -le "$a" ]; fi
    ok $? "--fix $fix: $f takes $b operations, unfixed $a"
done
"$eomc" compile "$spec" --scene shaken --fix "$fix" -o "$tmp/fixed.c"
! grep -q 'p_A\b\|p_w\b\|p_g\b\|p_l\b' "$tmp/fixed.c" && grep -q 'p_m = p\[0\]' "$tmp/fixed.c"
ok $? "--fix $fix: the code reads none of A, w, g, l (it still reads m)"
"$eomc" build "$spec" --scene shaken --fix "$fix" -o "$tmp/fixed" 2> /dev/null
run="--method rk4 --fixed-step 0.001 --t-end 5 --dt 0.1"
"$tmp/shaken" $run --set A=0.03 --set w=5.5 --set g=9.7 --set l=0.8 > "$tmp/set.csv"
"$tmp/fixed" $run > "$tmp/fixed.csv"
# every column but T, V, E; relative to the column's own scale
worst=$(paste -d, "$tmp/set.csv" "$tmp/fixed.csv" | awk -F, 'NR > 1 {
    h = NF / 2
    for (k = 1; k <= 3; k++) {
        d = $k - $(k + h); if (d < 0) d = -d
        s = $k < 0 ? -$k : $k; if (s > scale[k]) scale[k] = s
        if (d > diff[k]) diff[k] = d
    } }
    END { if (NR != 52) { print "rows?"; exit } w = 0
          for (k = 1; k <= 3; k++) if (diff[k] / scale[k] > w) w = diff[k] / scale[k]; printf "%.3g", w }')
awk -v w="$worst" 'BEGIN { exit !(w != "rows?" && w <= 1e-12) }'
ok $? "fixed and folded = unfixed with --set, to $worst of each column's scale over 5 s"

"$tmp/fixed" --set g=1 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "parameter 'g' is fixed at 9.7 in scene 'shaken'" "$tmp/err"
ok $? "--set of a fixed parameter: exit $st, naming the scene"
"$eomc" compile "$spec" --scene free --fix A=0.02 --explain | grep -q 'fixed (folded into the code): A = 0.02$'
ok $? "--fix overrides the scene's fix"

# outputs: the rod's tension 2 l lambda = m (|v|^2 - g y) / l on the
# circle, the angle, and y'' = -tension y / (m l) - g
cp="$src/specs/cartesian_pendulum.yaml"
"$eomc" compile "$cp" -o "$tmp/swing.c"
"$eomc" compile "$cp" --scene tension -o "$tmp/tension.c"
! grep -q '_outputs\|lam_' "$tmp/swing.c" && grep -q 'cartesian_pendulum_outputs,' "$tmp/tension.c"
ok $? "only the scene that asks for outputs has code for them"
"$eomc" run "$cp" --scene tension --t-end 3 --dt 0.05 > "$tmp/tension.csv"
head -1 "$tmp/tension.csv" | grep -q ',lambda\[rod\],res\[rod\],tension,theta,ay$'
ok $? "the outputs are columns after the standard ones: $(head -1 "$tmp/tension.csv")"
worst=$(awk -F, 'NR > 1 { m = 1; l = 1; g = 9.81
    x = $2; y = $3; vx = $4; vy = $5
    T = m * (vx * vx + vy * vy - g * y) / l
    want[1] = T; want[2] = atan2(x, -y); want[3] = -T * y / (m * l) - g
    for (k = 1; k <= 3; k++) {
        d = $(10 + k) - want[k]; if (d < 0) d = -d
        s = want[k] < 0 ? -want[k] : want[k]; if (s < 1) s = 1
        if (d / s > w) w = d / s
    } rows++ }
    END { if (rows != 61) print "rows?"; else printf "%.3g", w }' "$tmp/tension.csv")
awk -v w="$worst" 'BEGIN { exit !(w != "rows?" && w <= 1e-9) }'
ok $? "tension, theta and y'' equal their closed forms from the state, to $worst"

tap_end
