#!/bin/sh
# Names as a user writes them (TAP):
#  - a coordinate named `delta` builds and runs, its q'' the closed form of
#    tests/sim/specs/steer_delta.yaml at random states and parameters, with
#    delta(...) virtual work and a parameter named `exp` beside exp(...);
#  - the simulator's "did you mean" names every name as near: `--method
#    rk45` is one edit from both rk4 and rkf45.
# usage: test_names.sh EOMC SOURCE_ROOT BUILD_ROOT
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

# the simulator's suggestion lists every tie
"$tmp/steer" --method rk45 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "unknown method 'rk45' (did you mean 'rk4' or 'rkf45'?)" "$tmp/err"
ok $? "--method rk45: exit $st, did you mean 'rk4' or 'rkf45'? ($(head -c 120 "$tmp/err"))"
tap_end
