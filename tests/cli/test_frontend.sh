#!/bin/sh
# Specs as a user writes them, built and run (TAP):
#  - a coordinate named `delta` builds and runs, its q'' the closed form of
#    tests/sim/specs/steer_delta.yaml at random states and parameters, with
#    delta(...) virtual work and a parameter named `exp` beside exp(...);
#  - a uniform ball on a frame turned by a quaternion
#    (tests/sim/specs/rolling_ball.yaml, A = B = C) rolls straight on at a
#    constant angular velocity w: x'' = y'' = 0, e'' = -|w|^2 e / 4, at
#    random consistent states made here;
#  - a heavy top on a quaternion frame (tests/sim/specs/top_frame.yaml) has
#    the q'' of the same top with the body's own quaternion
#    (tests/hard/specs/sleeping_top.yaml) at random consistent states;
#  - the simulator's "did you mean" names every name as near: `--method
#    rk45` is one edit from both rk4 and rkf45.
# usage: test_frontend.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
spec="$src/tests/sim/specs/steer_delta.yaml"

# |got - want| <= 1e-13 max(1, |want|)
near() { awk -v g="$1" -v w="$2" 'BEGIN { d = g - w; if (d < 0) d = -d; s = w < 0 ? -w : w; if (s < 1) s = 1; exit !(g != "" && d <= 1e-13 * s) }'; }

"$eomc" build "$spec" -o "$tmp/steer" 2> "$tmp/err"
ok $? "a spec with the coordinate delta builds"
bad=0 k=0
while [ $k -lt 8 ]; do
  # m l g c exp delta delta': seeded, different each k
  set -- $(awk -v k=$k 'BEGIN { srand(21 + k); printf "%.17g %.17g %.17g %.17g %.17g %.17g %.17g",
    0.5 + 2 * rand(), 0.2 + rand(), 1 + 15 * rand(), rand(), -3 + 6 * rand(),
    -3 + 6 * rand(), -4 + 8 * rand() }')
  got=$("$tmp/steer" --accel --set m=$1 --set l=$2 --set g=$3 --set c=$4 --set exp=$5 \
        --init delta=$6 --init "delta'=$7" | sed -n "s/^delta'' //p")
  want=$(awk -v m=$1 -v l=$2 -v g=$3 -v c=$4 -v F=$5 -v d=$6 -v dd=$7 'BEGIN {
    printf "%.17g", (-m * g * l * sin(d) - c * dd + F * exp(-d * d) * l * cos(d)) / (m * l * l) }')
  near "$got" "$want" || { echo "# k=$k: delta'' = $got, closed form $want"; bad=$((bad + 1)); }
  k=$((k + 1))
done
[ $bad -eq 0 ]; ok $? "delta'' is the closed form at 8 random states (delta(delta) damper, exp*exp(...) drive)"
"$eomc" run "$spec" -o "$tmp/steer.csv" 2> "$tmp/err"; st=$?
rows=$(tail -n +2 "$tmp/steer.csv" | wc -l)
head -n 1 "$tmp/steer.csv" | grep -q "^t,delta,delta'," && [ $st -eq 0 ] && [ "$rows" -eq 21 ]
ok $? "eomc run of it: exit $st, the column delta, $rows rows to t_end = 2"

# |got - want| <= 1e-12 scale
close() { awk -v g="$1" -v w="$2" -v s="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= 1e-12 * s) }'; }
value() { sed -n "s/^$1'' //p" "$2"; }

# a uniform rolling ball: e random and unit, w random in space, e' = E^T w / 2
# (tangent to |e| = 1), the centre's velocity rolling: x' = R w_y, y' = -R w_x
"$eomc" build "$src/tests/sim/specs/rolling_ball.yaml" -o "$tmp/ball" 2> "$tmp/err"
bad=0 k=0
while [ $k -lt 6 ]; do
  set -- $(awk -v k=$k 'BEGIN { srand(121 + k); R = 0.2 + rand();
    for (i = 0; i < 4; i++) { e[i] = rand() - 0.5; n += e[i] * e[i] }
    for (i = 0; i < 4; i++) e[i] /= sqrt(n);
    for (i = 0; i < 3; i++) w[i] = 6 * rand() - 3;
    # E = [-e1 e0 -e3 e2; -e2 e3 e0 -e1; -e3 -e2 e1 e0]
    E[0,0] = -e[1]; E[0,1] = e[0]; E[0,2] = -e[3]; E[0,3] = e[2];
    E[1,0] = -e[2]; E[1,1] = e[3]; E[1,2] = e[0]; E[1,3] = -e[1];
    E[2,0] = -e[3]; E[2,1] = -e[2]; E[2,2] = e[1]; E[2,3] = e[0];
    for (j = 0; j < 4; j++) { d[j] = 0; for (r = 0; r < 3; r++) d[j] += E[r,j] * w[r] / 2 }
    printf "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g",
      R, e[0], e[1], e[2], e[3], d[0], d[1], d[2], d[3], R * w[1], -R * w[0],
      w[0] * w[0] + w[1] * w[1] + w[2] * w[2] }')
  "$tmp/ball" --accel --set A=0.7 --set B=0.7 --set C=0.7 --set R=$1 --init x=0.4 --init y=-1 \
    --init e0=$2 --init e1=$3 --init e2=$4 --init e3=$5 --init "e0'=$6" --init "e1'=$7" \
    --init "e2'=$8" --init "e3'=$9" --init "x'=${10}" --init "y'=${11}" > "$tmp/acc" 2>&1
  w2=${12}
  ok_k=1
  close "$(value x "$tmp/acc")" 0 "$w2" && close "$(value y "$tmp/acc")" 0 "$w2" || ok_k=0
  i=0
  for e in $2 $3 $4 $5; do
    close "$(value e$i "$tmp/acc")" "$(awk -v e=$e -v w2=$w2 'BEGIN { printf "%.17g", -w2 * e / 4 }')" "$w2" || ok_k=0
    i=$((i + 1))
  done
  [ $ok_k -eq 1 ] || { echo "# state $k:"; sed 's/^/#   /' "$tmp/acc"; bad=$((bad + 1)); }
  k=$((k + 1))
done
[ $bad -eq 0 ]; ok $? "a uniform ball on a quaternion frame: x'' = y'' = 0, e'' = -|w|^2 e/4 at 6 random rolling states"

# the heavy top: e random and unit, body rates w random, e' = L^T w / 2
"$eomc" build "$src/tests/sim/specs/top_frame.yaml" -o "$tmp/topf" 2> "$tmp/err"
"$eomc" build "$src/tests/hard/specs/sleeping_top.yaml" -o "$tmp/topb" 2> "$tmp/err"
bad=0 k=0
while [ $k -lt 6 ]; do
  args=$(awk -v k=$k 'BEGIN { srand(221 + k);
    for (i = 0; i < 4; i++) { e[i] = rand() - 0.5; n += e[i] * e[i] }
    for (i = 0; i < 4; i++) e[i] /= sqrt(n);
    for (i = 0; i < 3; i++) w[i] = 20 * rand() - 10;
    # L = [-e1 e0 e3 -e2; -e2 -e3 e0 e1; -e3 e2 -e1 e0]
    L[0,0] = -e[1]; L[0,1] = e[0]; L[0,2] = e[3]; L[0,3] = -e[2];
    L[1,0] = -e[2]; L[1,1] = -e[3]; L[1,2] = e[0]; L[1,3] = e[1];
    L[2,0] = -e[3]; L[2,1] = e[2]; L[2,2] = -e[1]; L[2,3] = e[0];
    for (j = 0; j < 4; j++) { d = 0; for (r = 0; r < 3; r++) d += L[r,j] * w[r] / 2;
      printf " --init=e%d=%.17g --init=e%d\047=%.17g", j, e[j], j, d } }')
  # shellcheck disable=SC2086 # the words of $args, each an option
  "$tmp/topf" --accel $args > "$tmp/af" 2>&1
  # shellcheck disable=SC2086
  "$tmp/topb" --accel $args > "$tmp/ab" 2>&1
  scale=$(awk '/^e[0-3]\047\047/ { v = $2 < 0 ? -$2 : $2; if (v > s) s = v } END { printf "%.17g", s }' "$tmp/ab")
  ok_k=1
  for i in 0 1 2 3; do
    close "$(value e$i "$tmp/af")" "$(value e$i "$tmp/ab")" "$scale" || ok_k=0
  done
  [ $ok_k -eq 1 ] || { echo "# state $k:"; paste "$tmp/af" "$tmp/ab" | sed 's/^/#   /'; bad=$((bad + 1)); }
  k=$((k + 1))
done
[ $bad -eq 0 ]; ok $? "a heavy top on a quaternion frame: the q'' of the body's own quaternion at 6 random states"

# the simulator's suggestion lists every tie
"$tmp/steer" --method rk45 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "unknown method 'rk45' (did you mean 'rk4' or 'rkf45'?)" "$tmp/err"
ok $? "--method rk45: exit $st, did you mean 'rk4' or 'rkf45'? ($(head -c 120 "$tmp/err"))"
tap_end
