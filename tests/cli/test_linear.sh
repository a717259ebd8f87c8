#!/bin/sh
# --linearize and --equilibrium as a user runs them (TAP): the printed
# matrices and --csv FILE (header matrix,row,column,value, rows and
# columns by name, the eigenvalues as eig rows) against the pendulum's
# closed form A = [0 1; -g/l cos theta 0]; the equilibrium and the
# stability verdict from the eigenvalues; and the usage errors.
# The Whipple bicycle (tests/sim/specs/whipple.yaml) against the
# eigenvalues of Meijaard et al. (2007): their Table 2, and their
# published lean-and-steer matrices (whipple_benchmark.awk); a state off
# its constraints, which --linearize refuses and --accel warns of; and
# sweeps of linearizations, the pendulum's against +-i sqrt(g/l).
# --linearize away from rest warns; an equilibrium search that runs away
# (tests/sim/specs/arm4.yaml), in any units, or stops where q'' is not 0
# (slide_tree.yaml, pushed), ends in exit 3; the arm's equilibrium against
# its closed form.
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
grep -q 'B = dz./du: the model has no inputs' "$tmp/lin.out" &&
    grep -q '^eigenvalues of A (the largest real part first):' "$tmp/lin.out"
ok $? "the printed report: A, B (none here), the eigenvalues"
# the eigenvalues +-i sqrt(g cos(0.7)) as eig rows, in the printed order:
# the positive imaginary part first
w=$(awk 'BEGIN { printf "%.17g", sqrt(9.81 * cos(0.7)) }')
[ "$(grep -c '^eig,' "$tmp/lin.csv")" -eq 4 ] && grep -qx 'eig,1,re,0' "$tmp/lin.csv" &&
    grep -qx 'eig,2,re,0' "$tmp/lin.csv" &&
    within "$(sed -n 's/^eig,1,im,//p' "$tmp/lin.csv")" "$w" 1e-14 &&
    within "$(sed -n 's/^eig,2,im,//p' "$tmp/lin.csv")" "-$w" 1e-14
ok $? "--csv: eig,K,re and eig,K,im rows, +-i sqrt(g cos 0.7) = +-${w}i"

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
w=$(awk 'BEGIN { printf "%.6g", sqrt(9.81) }')
grep -q '^  theta = 0$\|^  theta = -\?[0-9.]*e-[0-9]*$' "$tmp/bottom.out" &&
    grep -q "^stable to first order only: the largest real part, 0, is within 1e-09 of the largest modulus ($w) of 0, which this verdict counts as 0" "$tmp/bottom.out"
ok $? "from theta = 0.5: the bottom, stable to first order only (a centre), saying how the verdict rounds (modulus sqrt(g/l) = $w)"

# --linearize away from rest says so: at theta = 0.7, q'' = -g/l sin(0.7)
# is named; at the bottom and the top (-g/l sin(pi) is rounding) nothing
# is said, nor below in the Whipple bicycle's steady run at 5 m/s
"$eomc" run "$pend" --linearize --init theta=0.7 > /dev/null 2> "$tmp/off.err"; st=$?
got=$(sed -n "s/.*warning: t = 0: q'' is not 0 here (theta'' = \([^)]*\)).*/\1/p" "$tmp/off.err")
want=$(awk 'BEGIN { printf "%.17g", -9.81 * sin(0.7) }')
[ $st -eq 0 ] && within "$got" "$want" 1e-14 && grep -q "so A and B describe the motion through it only near it" "$tmp/off.err"
ok $? "--linearize at theta = 0.7 warns that q'' is not 0 (theta'' = $got = -g/l sin 0.7), and what A then is"
"$eomc" run "$pend" --linearize --init theta=0 > /dev/null 2> "$tmp/at0.err"; st=$?
"$eomc" run "$pend" --linearize --init theta=3.141592653589793 > /dev/null 2> "$tmp/atpi.err"; st2=$?
[ $st -eq 0 ] && [ $st2 -eq 0 ] && [ ! -s "$tmp/at0.err" ] && [ ! -s "$tmp/atpi.err" ]
ok $? "--linearize at rest, theta = 0 and pi: no warning"

# ---- equilibria that are not there: tests/sim/specs/arm4.yaml ----
# A yaw, a shoulder, an elbow and a slide along the forearm.  From
# shoulder = 1.5 (the rest 0), Newton's method follows q'' towards
# extend = infinity, where the elbow's q'' (m g times a growing lever over
# an inertia growing as its square) falls as 1/extend without reaching 0:
# it must stop (exit 3) saying it runs away, and print no equilibrium.  The
# same in millimetres (every length and g times 1000): the same path, each
# length 1000 times as long, since the search is free of the units.
arm="$src/tests/sim/specs/arm4.yaml"
mm="--set h=200 --set l1=400 --set l2=300 --set d=100 --set r=30 --set g=9810"
"$eomc" run "$arm" --equilibrium > "$tmp/arm.out" 2> "$tmp/arm.err"; st=$?
"$eomc" run "$arm" --equilibrium $mm > "$tmp/armmm.out" 2> "$tmp/armmm.err"; st2=$?
far=$(sed -n "s/.*error: t = 0: Newton's method runs away: .*(extend from 0 to \([^)]*\)).*/\1/p" "$tmp/arm.err")
farmm=$(sed -n "s/.*error: t = 0: Newton's method runs away: .*(extend from 0 to \([^)]*\)).*/\1/p" "$tmp/armmm.err")
[ $st -eq 3 ] && [ $st2 -eq 3 ] && [ ! -s "$tmp/arm.out" ] && [ ! -s "$tmp/armmm.out" ] &&
    awk -v a="$far" -v b="$farmm" 'BEGIN { d = b / 1000 - a; if (d < 0) d = -d; exit !(a > 100 && d <= 1e-9 * a) }'
ok $? "arm4 from shoulder = 1.5: exit $st, runs away (extend from 0 to $far; in mm, to $farmm), no equilibrium printed"
# Its equilibria have the forearm level, the slide's and the payload's
# centre of mass with the forearm's right over the elbow, the upper arm
# hanging: shoulder = elbow = pi/2, extend = -(m2 l2/2 + m3 l2 + mt (l2 + d))
# / (m3 + mt) = -0.4875 (in mm -487.5); q'' there by --accel is rounding.
"$eomc" run "$arm" --equilibrium --init shoulder=1.6 --init elbow=1.5 --init extend=-0.45 > "$tmp/eq.out"; st=$?
"$eomc" run "$arm" --equilibrium --init shoulder=1.6 --init elbow=1.5 --init extend=-450 $mm > "$tmp/eqmm.out"; st2=$?
v() { sed -n "s/^  $1 = //p" "$2"; }
want=$(awk 'BEGIN { printf "%.17g", -(0.8 * 0.3 / 2 + 0.5 * 0.3 + 0.3 * (0.3 + 0.1)) / (0.5 + 0.3) }')
"$eomc" run "$arm" --accel --init shoulder="$(v shoulder "$tmp/eq.out")" \
    --init elbow="$(v elbow "$tmp/eq.out")" --init extend="$(v extend "$tmp/eq.out")" > "$tmp/acc.out"
worst=$(awk '{ a = $2 < 0 ? -$2 : $2; if (a > m) m = a } END { print m + 0 }' "$tmp/acc.out")
[ $st -eq 0 ] && [ $st2 -eq 0 ] && within "$(v shoulder "$tmp/eq.out")" 1.5707963267948966 4e-16 &&
    within "$(v elbow "$tmp/eq.out")" 1.5707963267948966 4e-16 &&
    within "$(v extend "$tmp/eq.out")" "$want" 1e-15 &&
    within "$(v extend "$tmp/eqmm.out")" "$(awk -v w="$want" 'BEGIN { printf "%.17g", 1000 * w }')" 1e-12 &&
    [ "$(wc -l < "$tmp/acc.out")" -eq 4 ] && awk -v w="$worst" 'BEGIN { exit !(w < 1e-14) }'
ok $? "arm4 from (1.6, 1.5, -0.45): shoulder = elbow = pi/2, extend = $want (and in mm, x 1000); --accel there at most $worst"
# Nor does Newton's method stop at a minimum of |q''| that is not 0 and
# call it one: the cart of tests/sim/specs/slide_tree.yaml is pushed along
# its rail by a constant 0.3 (a generalized force on x at every state), so
# nothing rests; the search must end in exit 3 naming x''.
"$eomc" run "$src/tests/sim/specs/slide_tree.yaml" --equilibrium --init x=-3 --init th=3.07 \
    --init y=0.94 --init ph=2.11 > "$tmp/sl.out" 2> "$tmp/sl.err"; st=$?
[ $st -eq 3 ] && [ ! -s "$tmp/sl.out" ] &&
    grep -q "error: t = 0: Newton's method stopped making progress after [0-9]* steps where q'' is not 0 (x'' = " "$tmp/sl.err"
ok $? "slide_tree, pushed along its rail: no equilibrium, exit $st naming x''"
# Coordinates are left as found, and those beyond (-pi, pi] are said as
# angles would read them: from shoulder = 7.9, the same equilibrium, a
# turn on
"$eomc" run "$arm" --equilibrium --init shoulder=7.9 --init elbow=1.5 --init extend=-0.45 > "$tmp/turn.out"; st=$?
[ $st -eq 0 ] && within "$(v shoulder "$tmp/turn.out")" 7.8539816339744831 1e-15 &&
    grep -q "^arm4: the coordinates are as Newton's method left them, not wrapped (eomc cannot tell an angle from a length); as angles, shoulder = 1.570796326794896[0-9]* + 2 pi$" "$tmp/turn.out"
ok $? "arm4 from shoulder = 7.9: shoulder = $(v shoulder "$tmp/turn.out"), said as 1.5707963267948966 + 2 pi"

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

# ---- the Whipple bicycle ----
whip="$src/tests/sim/specs/whipple.yaml" bench="$src/tests/cli/whipple_benchmark.awk"
"$eomc" build "$whip" --jacobian auto -o "$tmp/whipple" 2> "$tmp/build.err" || cat "$tmp/build.err"
# eig K's re and im from a --csv file
eig() { sed -n "s/^eig,$2,$3,//p" "$1"; }

# v = 5 (the spec's): Table 2's lean and steer eigenvalues, and six exact
# zeros (position, heading, wheel angles, speed), the largest real part
# first: the zeros, capsize, weave (its positive imaginary part first),
# castor; a steady motion, so no warning that q'' is not 0
"$tmp/whipple" --linearize --csv "$tmp/w5.csv" > /dev/null 2> "$tmp/w5.err"; st=$?
zeros=0
for k in 1 2 3 4 5 6; do [ "$(eig "$tmp/w5.csv" $k re)" = 0 ] && [ "$(eig "$tmp/w5.csv" $k im)" = 0 ] && zeros=$((zeros + 1)); done
[ $st -eq 0 ] && [ $zeros -eq 6 ] && [ ! -s "$tmp/w5.err" ] &&
    within "$(eig "$tmp/w5.csv" 7 re)" -0.32286642900409 2e-13 &&
    within "$(eig "$tmp/w5.csv" 8 re)" -0.77534188219585 2e-13 &&
    within "$(eig "$tmp/w5.csv" 8 im)" 4.46486771378823 2e-13 &&
    within "$(eig "$tmp/w5.csv" 9 im)" -4.46486771378823 2e-13 &&
    within "$(eig "$tmp/w5.csv" 10 re)" -14.07838969279822 2e-13
ok $? "Whipple bicycle at 5 m/s: capsize, weave and castor as Meijaard et al.'s Table 2 (2e-13), six eigenvalues exactly 0, no warning"

# v = 4.292382527, just below the weave speed 4.29238253634111: the weave
# grows at +1.25e-8, which the eigenvalues printed to 1e-9 of the largest
# modulus used to hide as 0; against the root of the published matrices'
# quartic (A's entries reach 221: rounding moves its eigenvalues by a few
# 1e-14, the matrices carry 15 digits)
"$tmp/whipple" --linearize --set v=4.292382527 > "$tmp/weave.out"; st=$?
first=$(sed -n '/^eigenvalues of A/{n;p;q}' "$tmp/weave.out")
re=$(echo "$first" | awk '{ print $1 }') im=$(echo "$first" | awk '{ print $3 }')
set -- $(awk -v v=4.292382527 -v sr=0 -v si=3.4 -f "$bench")
[ $st -eq 0 ] && awk -v r="$re" 'BEGIN { exit !(r > 0) }' && within "$re" "$1" 5e-13 &&
    within "${im%i}" "$2" 1e-12
ok $? "v = 4.292382527: the weave's real part printed as computed, $re (+$1 from the published matrices)"

# --linearize off the constraints: the rear wheel not turning (thetaR' = 0
# at 5 m/s) breaks rear_x; the issue's unstable weave 0.038 +- 3.70i came
# from this state.  Exit 3, no eigenvalues, the constraint named, and
# assemblies that keep what --init set (the bicycle stops) or the
# linearization's coordinates and velocities (the wheel turns again)
"$tmp/whipple" --linearize --init "thetaR'=0" > "$tmp/r.out" 2> "$tmp/r.err"; st=$?
[ $st -eq 3 ] && ! grep -q eigenvalues "$tmp/r.out" &&
    grep -q "error: t = 0: the linearization: the state is off the constraint rear_x (velocities: its residual is" "$tmp/r.err" &&
    grep -q "to linearize on them, --assemble --hold \"thetaR'\" keeps what --init set and moves the rest onto the constraints: x' 5 -> 0" "$tmp/r.err" &&
    grep -q "or --assemble --hold \"x,y,psi,phi,thetaR,steer,thetaF,x',psi',phi'\" keeps the linearization's coordinates and velocities and moves only those the constraints determine: thetaR' 0 -> 16.6667" "$tmp/r.err"
ok $? "--linearize with thetaR' = 0: exit 3 naming rear_x, suggesting two holds and what each moves"
# the first suggestion stops the bicycle: Table 2's eigenvalues at v = 0
"$tmp/whipple" --linearize --init "thetaR'=0" --assemble --hold "thetaR'" --csv "$tmp/w0.csv" > /dev/null 2>&1; st=$?
[ $st -eq 0 ] && within "$(eig "$tmp/w0.csv" 1 re)" 5.53094371765393 2e-13 &&
    within "$(eig "$tmp/w0.csv" 2 re)" 3.13164324790656 2e-13 &&
    within "$(eig "$tmp/w0.csv" 9 re)" -3.13164324790656 2e-13 &&
    within "$(eig "$tmp/w0.csv" 10 re)" -5.53094371765393 2e-13
ok $? "--assemble --hold \"thetaR'\" as suggested: the bicycle at rest, +-5.5309 and +-3.1316 as Table 2's v = 0"

# the pitch lifting the front wheel off the ground (thetaB = 0.1) breaks
# front_z; holding the linearization's coordinates and velocities puts it
# back, and then the eigenvalues are those at 5 m/s
"$tmp/whipple" --linearize --init thetaB=0.1 > "$tmp/p.out" 2> "$tmp/p.err"; st=$?
hold=$(sed -n 's/.*--assemble --hold "\([^"]*\)" keeps the linearization.*/\1/p' "$tmp/p.err")
"$tmp/whipple" --linearize --init thetaB=0.1 --assemble --hold "$hold" --csv "$tmp/wb.csv" > /dev/null 2>&1; sta=$?
[ $st -eq 3 ] && ! grep -q eigenvalues "$tmp/p.out" &&
    grep -q "the state is off the constraint front_z (positions: its residual is" "$tmp/p.err" &&
    [ "$hold" = "x,y,psi,phi,thetaR,steer,thetaF,x',psi',phi'" ] && [ $sta -eq 0 ] &&
    within "$(eig "$tmp/wb.csv" 8 re)" -0.77534188219585 2e-13 &&
    within "$(eig "$tmp/wb.csv" 8 im)" 4.46486771378823 2e-13
ok $? "--linearize with thetaB = 0.1: exit 3 naming front_z; the suggested hold gives the weave of 5 m/s again"

# --accel warns, and so does a run, naming every constraint off, worst
# first (rear_x's velocity 0.12 of the size of its terms, front_z's
# position 0.048 of the size of its own: c_scale's sum of |terms|)
"$tmp/whipple" --accel --init thetaB=0.1 --init "thetaR'=0" > "$tmp/a.out" 2> "$tmp/a.err"; st=$?
"$tmp/whipple" --t-end 0.01 --init thetaB=0.1 --init "thetaR'=0" > /dev/null 2> "$tmp/run.err"; str=$?
shares=$(sed -n 's/.*rear_x (velocities: its residual is \([0-9.e-]*\) of the size of its terms), front_z (positions: \([0-9.e-]*\)).*/\1 \2/p' "$tmp/a.err")
[ $st -eq 0 ] && grep -q "^x'' " "$tmp/a.out" &&
    grep -q "warning: the initial state is off 2 constraints, worst first: rear_x (velocities: its residual is" "$tmp/a.err" &&
    echo "$shares" | awk '{ exit !(NF == 2 && $1 >= $2 && $2 > 1e-8) }' &&
    [ $str -eq 0 ] && grep -q "off 2 constraints, worst first: rear_x (velocities:.*), front_z (positions:" "$tmp/run.err"
ok $? "--accel and a run off two constraints: exit 0, a warning naming rear_x and front_z, worst first ($shares)"

# ---- sweeps of linearizations ----
# the weave speed 4.29238253634111 (Meijaard et al.) between two rows:
# re1, the largest real part, the weave's below it and 0 above (the six
# zeros), each against the published matrices' quartic
"$tmp/whipple" --linearize --sweep v=4.2923825:4.2923826:2 -o "$tmp/ws.csv" 2> "$tmp/ws.err"; st=$?
cols=v
for k in 1 2 3 4 5 6 7 8 9 10; do cols="$cols,re$k,im$k"; done
r1=$(awk -F, 'NR == 2 { print $2 }' "$tmp/ws.csv") r2=$(awk -F, 'NR == 3 { print $2 }' "$tmp/ws.csv")
i1=$(awk -F, 'NR == 2 { print $3 }' "$tmp/ws.csv")
set -- $(awk -v v=4.2923825 -v sr=0 -v si=3.4 -f "$bench")
[ $st -eq 0 ] && [ "$(head -1 "$tmp/ws.csv")" = "$cols" ] && [ "$(wc -l < "$tmp/ws.csv")" -eq 3 ] &&
    within "$r1" "$1" 5e-13 && within "$i1" "$2" 1e-12 && [ "$r2" = 0 ] && [ ! -s "$tmp/ws.err" ]
ok $? "--sweep v=4.2923825:4.2923826:2 --linearize: header v,re1,im1,...,re10,im10; re1 = $r1 (+$1 published) then 0: the weave speed between"
# the capsize speed 6.02426201538837: the capsize eigenvalue, real, turns
# positive between the rows
"$tmp/whipple" --linearize --sweep v=6.024262:6.0242621:2 -o "$tmp/cs.csv" 2> /dev/null; st=$?
c1=$(awk -F, 'NR == 2 { print $2 "," $14 }' "$tmp/cs.csv") c2=$(awk -F, 'NR == 3 { print $2 }' "$tmp/cs.csv")
set -- $(awk -v v=6.024262 -v sr=0 -v si=0 -f "$bench")
b1=$1
set -- $(awk -v v=6.0242621 -v sr=0 -v si=0 -f "$bench")
[ $st -eq 0 ] && [ "${c1%,*}" = 0 ] && within "${c1#*,}" "$b1" 5e-14 && within "$c2" "$1" 5e-14 &&
    awk -v a="${c1#*,}" -v b="$c2" 'BEGIN { exit !(a < 0 && b > 0) }'
ok $? "--sweep v=6.024262:6.0242621:2: capsize ${c1#*,} then $c2 (published $b1, $1): the capsize speed between"
# the pendulum at the bottom over l: +-i sqrt(g/l), in sweep order, on
# two threads the same bytes
"$eomc" run "$pend" --linearize --init theta=0 --sweep l=0.5:2:4 -o "$tmp/pl.csv"; st=$?
"$eomc" run "$pend" --linearize --init theta=0 --sweep l=0.5:2:4 --threads 2 -o "$tmp/pl2.csv"
[ $st -eq 0 ] && [ "$(head -1 "$tmp/pl.csv")" = "l,re1,im1,re2,im2" ] && cmp -s "$tmp/pl.csv" "$tmp/pl2.csv" &&
    awk -F, 'NR > 1 { w = sqrt(9.81 / $1); d1 = $3 - w; d2 = $5 + w
        if (d1 < 0) d1 = -d1; if (d2 < 0) d2 = -d2
        if ($2 != 0 || $4 != 0 || d1 > 2e-15 * w || d2 > 2e-15 * w) bad = 1; n++ }
        END { exit bad || n != 4 }' "$tmp/pl.csv"
ok $? "--sweep l=0.5:2:4 --linearize: each row 0 +- i sqrt(g/l) to 2e-15, the same on two threads"
# a linearization that fails leaves its cells empty and says why
"$tmp/whipple" --linearize --sweep v=4:5:2 --init "thetaR'=1" -o "$tmp/bad.csv" 2> "$tmp/bad.err"; st=$?
[ $st -eq 0 ] && [ "$(sed -n 2p "$tmp/bad.csv")" = "4,,,,,,,,,,,,,,,,,,,," ] &&
    grep -q "warning: 2 of 2 runs failed (their cells are empty); the first: v = 4: t = 0: the linearization: the state is off the constraint rear_x" "$tmp/bad.err"
ok $? "a sweep's linearization off the constraints: empty cells, the warning naming rear_x"
"$eomc" run "$pend" --linearize --sweep l=1:2:2 --csv "$tmp/x.csv" > /dev/null 2> "$tmp/err"; st=$?
"$eomc" run "$pend" --equilibrium --sweep l=1:2:2 > /dev/null 2> "$tmp/err2"; st2=$?
[ $st -eq 2 ] && [ $st2 -eq 2 ] && grep -q "does not take --csv" "$tmp/err" && [ ! -e "$tmp/x.csv" ] &&
    grep -q "does not take --equilibrium" "$tmp/err2"
ok $? "a sweep of --linearize with --csv, or of --equilibrium: usage errors (exit $st, $st2)"

# A body hanging from a ball joint (tests/cli/ball_pendulum.yaml: a unit
# quaternion with speeds), linearized in the tangent space: its small
# rotations rx, ry, rz in its own axes and its angular velocity.  At rest
# hanging, the physical pendulum's +-i sqrt(m g l / (I + m l^2)) about
# both horizontal axes and 0 for the spin; the same body on three hinges
# (hinge_pendulum.yaml, no quaternion) the same eigenvalues.
ball="$src/tests/cli/ball_pendulum.yaml" hinge="$src/tests/cli/hinge_pendulum.yaml"
"$eomc" run "$ball" --linearize --csv "$tmp/ball.csv" > "$tmp/ball.out" 2> "$tmp/ball.err"; st=$?
"$eomc" run "$hinge" --linearize --csv "$tmp/hinge.csv" > /dev/null 2>&1; sth=$?
w=$(awk 'BEGIN { printf "%.17g", sqrt(1.5 * 9.81 * 0.8 / (0.02 + 1.5 * 0.64)) }')
eigs() { sed -n 's/^eig,[0-9]*,\(re\|im\),//p' "$1" | paste -d, - -; }
[ $st -eq 0 ] && [ $sth -eq 0 ] && [ ! -s "$tmp/ball.err" ] &&
    grep -qx 'A,rx,wx,1' "$tmp/ball.csv" && grep -qx 'A,wz,rz,0' "$tmp/ball.csv" &&
    [ "$(grep -c '^A,' "$tmp/ball.csv")" -eq 36 ] &&
    eigs "$tmp/ball.csv" | awk -F, -v w="$w" '{ d1 = $2 - w; d2 = $2 + w; d1 = d1 < 0 ? -d1 : d1
        d2 = d2 < 0 ? -d2 : d2; if ($1 != 0) bad = 1
        if (d1 <= 1e-14 * w) p++; else if (d2 <= 1e-14 * w) m++; else if ($2 == 0) z++ }
        END { exit bad || p != 2 || m != 2 || z != 2 }' &&
    eigs "$tmp/hinge.csv" > "$tmp/hinge.eig" && eigs "$tmp/ball.csv" > "$tmp/ball.eig" &&
    awk -F, 'NR == FNR { r[FNR] = $1; i[FNR] = $2; next } { d = $2 - i[FNR]; d = d < 0 ? -d : d
        if ($1 != r[FNR] || d > 1e-14 * 4) bad = 1 } END { exit bad || FNR != 6 }' \
      "$tmp/hinge.eig" "$tmp/ball.eig"
ok $? "a ball joint's pendulum in its tangent space (rx, ry, rz, wx, wy, wz): +-i $w twice and 0 twice, as on three hinges"
# --equilibrium from a tilted start (its quaternion divided by its
# length, with a warning): Newton's steps turn e until the body hangs,
# e1 = e2 = 0 (its axis down) and |e| = 1 as printed; the turn about the
# vertical is free and stays as it was
"$eomc" run "$ball" --equilibrium --init e0=0.9 --init e1=0.3 --init e2=0.2 --init e3=0.1 \
    > "$tmp/beq.out" 2> "$tmp/beq.err"; st=$?
val() { sed -n "s/^  $1 = //p" "$tmp/beq.out"; }
[ $st -eq 0 ] && grep -q 'warning: the unit quaternion' "$tmp/beq.err" &&
    awk -v a="$(val e0)" -v b="$(val e1)" -v c="$(val e2)" -v d="$(val e3)" 'BEGIN {
        n = sqrt(a * a + b * b + c * c + d * d) - 1; n = n < 0 ? -n : n
        b = b < 0 ? -b : b; c = c < 0 ? -c : c
        exit !(n <= 4.5e-16 && b <= 1e-15 && c <= 1e-15 && d > 0.05) }' &&
    grep -q '^stable to first order only' "$tmp/beq.out"
ok $? "--equilibrium of the ball pendulum tilted: hanging, e = ($(val e0), $(val e1), $(val e2), $(val e3))"
# a free body has none: its accelerations do not depend on where it is
"$eomc" run "$src/tests/cli/free_body.yaml" --equilibrium > /dev/null 2> "$tmp/feq.err"; st=$?
[ $st -eq 3 ] && grep -q 'no equilibrium' "$tmp/feq.err"
ok $? "--equilibrium of a free body: exit 3 ($(cut -c1-90 "$tmp/feq.err"))"

tap_end
