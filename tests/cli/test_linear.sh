#!/bin/sh
# --linearize and --equilibrium as a user runs them (TAP): the printed
# matrices and --csv FILE (header matrix,row,column,value, rows and
# columns by name) against the pendulum's closed form A = [0 1; -g/l cos
# theta 0]; the equilibrium and the stability verdict from the
# eigenvalues; and the usage errors.
# usage: test_linear.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
pend="$src/specs/pendulum.yaml"

"$eomc" run "$pend" --linearize --init theta=0.7 --csv "$tmp/lin.csv" > "$tmp/lin.out"; st=$?
head -1 "$tmp/lin.csv" | grep -qx 'matrix,row,column,value' &&
    grep -qx "A,theta,theta',1" "$tmp/lin.csv" && grep -qx 'A,theta,theta,0' "$tmp/lin.csv"
ok $? "--csv: the header matrix,row,column,value and rows by name (A,theta,theta',1)"
got=$(sed -n "s/^A,theta',theta,//p" "$tmp/lin.csv")
want=$(awk 'BEGIN { printf "%.17g", -9.81 * cos(0.7) }')
[ $st -eq 0 ] && within "$got" "$want" 1e-13
ok $? "A[theta', theta] = $got = -g/l cos(0.7)"
grep -q 'B = dz./du: the model has no inputs' "$tmp/lin.out" && grep -q '^eigenvalues of A:' "$tmp/lin.out"
ok $? "the printed report: A, B (none here), the eigenvalues"

# The Cartesian pendulum at rest at theta0 = 1, x independent: with
# x = l sin(theta), x'' = -g x sqrt(l^2 - x^2) / l^2 at rest, so
# A[x', x] = -g cos(2 theta0) / (l cos(theta0)); Baumgarte's terms vanish
# on the constraint and with them their derivative along it, so the
# reduced A is the same with them.
cart="$src/specs/cartesian_pendulum.yaml"
"$eomc" run "$cart" --linearize --csv "$tmp/cart.csv" > /dev/null; st=$?
"$eomc" run "$cart" --linearize --stabilize baumgarte --baumgarte 5,6 --csv "$tmp/cartb.csv" > /dev/null; stb=$?
got=$(sed -n "s/^A,x',x,//p" "$tmp/cart.csv") gotb=$(sed -n "s/^A,x',x,//p" "$tmp/cartb.csv")
want=$(awk 'BEGIN { printf "%.17g", -9.81 * cos(2) / cos(1) }')
[ $st -eq 0 ] && [ $stb -eq 0 ] && within "$got" "$want" 1e-12 && within "$gotb" "$want" 1e-12 &&
  [ "$(grep -c '^A,' "$tmp/cartb.csv")" -eq 4 ] &&
  awk -F, 'NR == FNR { a[$1 "," $2 "," $3] = $4; next } FNR > 1 { d = $4 - a[$1 "," $2 "," $3]
      if (d < 0) d = -d; if (!(($1 "," $2 "," $3) in a) || d > 1e-12) bad = 1 } END { exit bad }' \
    "$tmp/cart.csv" "$tmp/cartb.csv"
ok $? "constrained: A[x', x] = $got = -g cos(2)/cos(1); with Baumgarte's terms $gotb"

"$eomc" run "$pend" --equilibrium --init theta=2.5 > "$tmp/top.out"; st=$?
theta=$(sed -n 's/^  theta = //p' "$tmp/top.out")
[ $st -eq 0 ] && within "$theta" 3.14159265358979324 4e-16 && grep -q '^unstable: ' "$tmp/top.out"
ok $? "from theta = 2.5: the equilibrium theta = $theta (pi), unstable"
"$eomc" run "$pend" --equilibrium --init theta=0.5 > "$tmp/bottom.out"
grep -q '^  theta = 0$\|^  theta = -\?[0-9.]*e-[0-9]*$' "$tmp/bottom.out" &&
    grep -q '^stable to first order only' "$tmp/bottom.out"
ok $? "from theta = 0.5: the bottom, stable to first order only (a centre)"

"$eomc" run "$src/specs/rolling_disk.yaml" --equilibrium > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'not isolated' "$tmp/err"
ok $? "a nonholonomic model's equilibria are not isolated: exit $st, said so"
"$eomc" run "$pend" --csv "$tmp/x.csv" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q -- '--csv belongs to --work-precision, --linearize or --equilibrium' "$tmp/err" &&
    [ ! -e "$tmp/x.csv" ]
ok $? "--csv without --linearize: a usage error (exit $st), no file"
"$eomc" run "$pend" --linearize -o "$tmp/y.csv" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'does not integrate' "$tmp/err"
ok $? "--linearize -o: a usage error (exit $st)"

tap_end
