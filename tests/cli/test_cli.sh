#!/bin/sh
# The eomc command line, as a user runs it (TAP):
#  - identical bytes for identical input, wherever eomc is run from;
#  - `eomc build` from the build tree and from an installed tree (meson
#    install --destdir) gives a simulator whose --accel is -g/l sin(theta);
#  - `eomc run` builds once into its cache and reuses it;
#  - failures leave no output file behind and exit with status 2.
# usage: test_cli.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
# |got - want| <= 1e-12 max(1, |want|)
near() { awk -v g="$1" -v w="$2" 'BEGIN { d = g - w; if (d < 0) d = -d; s = w < 0 ? -w : w; if (s < 1) s = 1; exit !(g != "" && d <= 1e-12 * s) }'; }
accel_of() { sed -n "s/^$1'' //p"; }

# determinism, and independence from the working directory
"$eomc" compile "$src/specs/pendulum.yaml" -o "$tmp/a.c"
(cd "$src" && "$eomc" compile specs/pendulum.yaml) > "$tmp/b.c"
cmp -s "$tmp/a.c" "$tmp/b.c"; ok $? "compile output is identical bytes from another directory"

# a special file (here a pipe; /dev/null alike) is written in place, not
# replaced by a renamed temporary file
mkfifo "$tmp/pipe"
cat "$tmp/pipe" > "$tmp/piped.c" &
"$eomc" compile "$src/specs/pendulum.yaml" -o "$tmp/pipe"; st=$?
wait
[ $st -eq 0 ] && [ -p "$tmp/pipe" ] && cmp -s "$tmp/piped.c" "$tmp/a.c"
ok $? "compile -o PIPE writes through the pipe and leaves it a pipe"

# build from the build tree
"$eomc" build "$src/specs/pendulum.yaml" -o "$tmp/pend" 2> "$tmp/err"
got=$("$tmp/pend" --accel --init theta=0.5 | accel_of theta)
want=$(awk 'BEGIN { printf "%.17g", -9.81 * sin(0.5) }')
near "$got" "$want"; ok $? "eomc build (build tree): theta'' = $got = -g/l sin(0.5)"

# build from an installed tree
if meson install -C "$build" --no-rebuild --destdir "$tmp/stage" --quiet > "$tmp/install.log" 2>&1; then
  inst=$(find "$tmp/stage" -path '*/bin/eomc' -type f | head -n 1)
  "$inst" build "$src/specs/pendulum.yaml" -o "$tmp/pend2" 2> "$tmp/err2"
  got=$("$tmp/pend2" --accel --init theta=0.5 --set l=2 | accel_of theta)
  want=$(awk 'BEGIN { printf "%.17g", -9.81 / 2 * sin(0.5) }')
  near "$got" "$want"; ok $? "eomc build (installed, staged with DESTDIR): theta'' = $got"
else
  cat "$tmp/install.log"
  ok 1 "meson install --destdir"
fi

# run: built once, then reused from the cache
export EOMC_CACHE_DIR="$tmp/cache"
got=$("$eomc" run "$src/specs/pendulum.yaml" --accel --init theta=0.25 | accel_of theta)
want=$(awk 'BEGIN { printf "%.17g", -9.81 * sin(0.25) }')
near "$got" "$want"; ok $? "eomc run --accel: theta'' = $got"
exe=$(find "$tmp/cache" -type f -name 'sim-*')
before=$(stat -c '%i %Y %s' $exe)
sleep 1
"$eomc" run "$src/specs/pendulum.yaml" --accel > /dev/null
after=$(stat -c '%i %Y %s' $exe)
count=$(find "$tmp/cache" -type f -name 'sim-*' | wc -l)
[ "$before" = "$after" ] && [ "$count" -eq 1 ]; ok $? "a second eomc run of the same spec does not rebuild"
"$eomc" run "$src/specs/pendulum.yaml" --form nielsen --accel > /dev/null
count=$(find "$tmp/cache" -type f -name 'sim-*' | wc -l)
[ "$count" -eq 2 ]; ok $? "another --form is another cache entry"

# an effect the scene leaves out generates no code: falling_particle with
# only gravity never reads the push force f, and y'' = -g whatever f is
"$eomc" compile "$src/specs/falling_particle.yaml" --effects gravity -o "$tmp/grav.c"
"$eomc" compile "$src/specs/falling_particle.yaml" -o "$tmp/both.c"
! grep -q 'p_f =\|= p\[2\]' "$tmp/grav.c" && grep -q 'p_f = p\[2\]' "$tmp/both.c"
ok $? "--effects gravity: no code reads the push force f (the full scene does)"
got=$("$eomc" run "$src/specs/falling_particle.yaml" --effects gravity --accel --set f=100 --set g=3.5 | accel_of y)
near "$got" -3.5; ok $? "--effects gravity: y'' = -g = $got with f = 100 set"
got=$("$eomc" run "$src/specs/falling_particle.yaml" --effects push --accel --set f=3 --set m=2 | accel_of y)
near "$got" 1.5; ok $? "--effects push: y'' = f/m = $got, no gravity"

# --explain: the classification of each constraint, and no C on stdout
ex() { "$eomc" compile "$src/specs/$1.yaml" --explain 2>&1; }
ex appell | grep -q "cone *first-order, nonlinear in q'.*determines z"
ok $? "--explain: Appell's cone is first order, nonlinear in q', determines z"
ex precession | grep -q "precession *second-order, affine in q''"
ok $? "--explain: the precession constraint is second order, affine in q''"
ex cartesian_pendulum | grep -q "rod *holonomic.*B = dg/dq"
ok $? "--explain: the rod is holonomic"
printf 'coordinates: [x, y]\nparticles: {b: {mass: 1, position: [x, y]}}\nconstraints: {roll: {expr: "x'"'"' - 2*y'"'"'", dependent: x}}\n' > "$tmp/lin.yaml"
"$eomc" compile "$tmp/lin.yaml" --explain --form maggi > "$tmp/lin.txt" 2>&1
grep -q "roll *first-order, linear in q'.*determines x (named in the spec)" "$tmp/lin.txt" &&
  grep -q "by elimination" "$tmp/lin.txt" && ! grep -q "#include" "$tmp/lin.txt"
ok $? "--explain: a linear first-order constraint, its named dependent, elimination, no C"

# drift control and assembly on the Cartesian pendulum (l = 1, theta0 = 1)
"$eomc" build "$src/specs/cartesian_pendulum.yaml" --jacobian auto -o "$tmp/cp" 2> /dev/null
"$tmp/cp" --init x=1.2 --assemble --accel > "$tmp/asm.out" 2> "$tmp/asm.err"
got=$(sed -n 's/^  x 1.2 -> \([^ ]*\) .*/\1/p' "$tmp/asm.err")
want=$(awk 'BEGIN { y = -cos(1); printf "%.17g", 1.2 / sqrt(1.44 + y * y) }')
near "$got" "$want"; ok $? "--assemble moves x = 1.2 to x / |(x, y)| = $got and says so"
# --hold keeps what it names: x = 0.6 held, y alone meets x^2 + y^2 = 1 (on its branch)
"$tmp/cp" --init x=0.6 --init "x'=0.3" --assemble --hold "x,x'" --accel > /dev/null 2> "$tmp/hold.err"
goty=$(sed -n 's/^  y [^ ]* -> \([^ ]*\) .*/\1/p' "$tmp/hold.err")
gotv=$(sed -n "s/^  y' [^ ]* -> \\([^ ]*\\) .*/\\1/p" "$tmp/hold.err")
! grep -q "^  x" "$tmp/hold.err" && near "$goty" -0.8 &&
  near "$gotv" "$(awk 'BEGIN { printf "%.17g", -0.6 * 0.3 / -0.8 }')"
ok $? "--assemble --hold x,x': x and x' stay, y = -0.8 = $goty, y' = -x x'/y = $gotv"
# the rolling disk started with x' = 0: projected freely, the spin changes too
# (6 -> 2); holding the angles' rates, only x' moves, to -R phi' cos(psi) = -3
"$eomc" build "$src/specs/rolling_disk.yaml" -o "$tmp/rd" 2> /dev/null
"$tmp/rd" --init "x'=0" --assemble --t-end 0.01 -o /dev/null 2> "$tmp/free.err"
grep -q "^  phi' 6 -> " "$tmp/free.err"
ok $? "rolling disk, --assemble without --hold: the spin rate moves ($(grep "phi'" "$tmp/free.err"))"
"$tmp/rd" --init "x'=0" --assemble --hold "phi',psi',theta'" --t-end 0.01 -o /dev/null \
  2> "$tmp/held.err"
gotx=$(sed -n "s/^  x' 0 -> \\([^ ]*\\) .*/\\1/p" "$tmp/held.err")
[ "$(grep -c '^  ' "$tmp/held.err")" -eq 1 ] && near "$gotx" -3
ok $? "rolling disk, --hold phi',psi',theta': only x' moves, to $gotx = -R phi' cos(psi)"
# A heavy symmetric top on frames (z-x-z turns, its centre a point on the
# body's axis, inertia [A, A, C] about the centre): steady precession at
# theta = 0.5 needs A' W^2 cos(theta) - C w3 W + m g l = 0, A' = A + m l^2
# about the pivot, w3 = phi' + W cos(theta); with the slow root W it stays
# at theta = 0.5, and with W computed from A alone (the classic slip)
# theta'' = (A' W^2 s c - C w3 W s + m g l s) / A' there.
cat > "$tmp/top.yaml" <<'YAML'
name: top
parameters: {m: 1.0, l: 0.2, g: 9.81, A: 0.05, C: 0.02}
coordinates: [psi, theta, phi]
frames:
  body_axes: {rotation: [{z: psi}, {x: theta}, {z: phi}]}
points:
  centre: {frame: body_axes, at: [0, 0, l]}
bodies:
  top: {mass: m, frame: body_axes, center: centre, inertia: [A, A, C]}
effects:
  gravity: {gravity: [0, 0, -g]}
initial: {theta: 0.5, phi': 60}
scene: {t_end: 2, rtol: 1e-12, atol: 1e-12}
YAML
slow() { awk -v A="$1" 'BEGIN { C = 0.02; c = cos(0.5); a = (A - C) * c; b = -0.02 * 60
    k = 9.81 * 0.2; printf "%.17g", (-b - sqrt(b * b - 4 * a * k)) / (2 * a) }'; }
W=$(slow 0.09) W0=$(slow 0.05)
"$eomc" build "$tmp/top.yaml" -o "$tmp/top" 2> /dev/null
"$tmp/top" --init "psi'=$W" > "$tmp/top.csv"; st=$?
dev=$(awk -F, -v W="$W" 'NR > 1 { d = $3 - 0.5; if (d < 0) d = -d; if (d > m) m = d
    e = $5 - W; if (e < 0) e = -e; if (e > m) m = e } END { printf "%.2g", m }' "$tmp/top.csv")
got=$("$tmp/top" --init "psi'=$W0" --accel | sed -n "s/^theta'' //p")
want=$(awk -v W="$W0" 'BEGIN { s = sin(0.5); c = cos(0.5); w3 = 60 + W * c
    printf "%.17g", (0.09 * W * W * s * c - 0.02 * w3 * W * s + 9.81 * 0.2 * s) / 0.09 }')
[ $st -eq 0 ] && awk -v d="$dev" 'BEGIN { exit !(d <= 1e-10) }' && near "$got" "$want"
ok $? "a heavy top on frames: steady precession at W = $W holds theta and psi' to $dev; with A alone theta'' = $got"
usage_err() { "$@" > /dev/null 2> "$tmp/u.err"; [ $? -eq 2 ]; }
usage_err "$tmp/rd" --hold "x'" -o /dev/null && grep -q "^rd: --hold belongs to --assemble" "$tmp/u.err"
ok $? "--hold without --assemble: exit 2, saying it belongs to --assemble"
usage_err "$tmp/rd" --assemble --hold "xx'" -o /dev/null &&
  grep -q "^rd: --hold: 'xx'' is not a coordinate or velocity (did you mean 'x''?)" "$tmp/u.err"
ok $? "--hold with an unknown name: exit 2, the nearest name"
"$tmp/rd" --init "x'=0" --assemble --hold "x',y'" -o /dev/null 2> "$tmp/over.err"; st=$?
[ $st -eq 3 ] && grep -q "moving only the velocities not held" "$tmp/over.err"
ok $? "--hold leaving a constraint no freedom: exit 3, saying what was held"
"$tmp/cp" --method rkf45 --rtol 1e-6 --atol 1e-6 --t-end 50 --stabilize project --stats \
  -o "$tmp/cp.csv" 2> "$tmp/proj.err"
res=$(sed -n 's/^max_residual //p' "$tmp/proj.err")
awk -v r="$res" 'BEGIN { exit !(r != "" && r < 1e-12) }'
ok $? "--stabilize project --stats: max_residual $res < 1e-12 over 50 s at rtol 1e-6"
"$tmp/cp" --init x=1.2 --t-end 0.1 -o /dev/null 2> "$tmp/warn.err"; st=$?
[ $st -eq 0 ] && grep -q "warning: the initial state is off the constraint rod (positions: its residual is" "$tmp/warn.err"
ok $? "an initial state off the constraints: a warning naming the constraint, suggesting --assemble"
"$tmp/cp" --t-end 0.1 -o /dev/null 2> "$tmp/nowarn.err"
[ ! -s "$tmp/nowarn.err" ]; ok $? "a consistent initial state: no warning"
"$tmp/cp" --set l=1e6 --t-end 0.1 -o /dev/null 2> "$tmp/nowarn6.err"
[ ! -s "$tmp/nowarn6.err" ]; ok $? "a consistent initial state with l = 1e6: no warning (the test is relative)"
# x' = 0.05, y' = 0 at theta0 = 1: a radial velocity of 0.05 sin(1), the
# share sin(1) = 0.84 of the velocity
"$tmp/cp" --init "x'=0.05" --t-end 0.1 -o /dev/null 2> "$tmp/warnv.err"; st=$?
[ $st -eq 0 ] && grep -q "warning: the initial state is off the constraint rod (velocities: its residual is 0.84 of" "$tmp/warnv.err"
ok $? "initial velocities off the constraints: a warning at velocity level, the share along the rod"
# upright, x' = 1: x = sin(pi) = 1.2e-16 is the only term of g' = 2 (x x' + y y'),
# which is rounding against the speed
"$tmp/cp" --set theta0=3.141592653589793 --init "x'=1" --t-end 0.1 -o /dev/null 2> "$tmp/top.err"; st=$?
[ $st -eq 0 ] && [ ! -s "$tmp/top.err" ]
ok $? "a consistent start where each term of g' is rounding (upright): no warning"
# an ill-conditioned mass matrix: warned once, naming t and the coordinates
"$eomc" build "$src/specs/double_pendulum.yaml" --jacobian auto -o "$tmp/dp" 2> /dev/null
"$tmp/dp" --set m1=1e-9 --method bsimp --rtol 1e-10 --atol 1e-10 --stats -o /dev/null \
  2> "$tmp/ill.err"; st=$?
[ $st -eq 0 ] && [ "$(grep -c warning "$tmp/ill.err")" -eq 1 ] &&
  grep -q "warning: t = 0.41[0-9]*: the mass matrix (coordinates th1, th2) is ill-conditioned" "$tmp/ill.err" &&
  awk '/^max_condition / { c = $2 } END { exit !(c >= 1e9 && c < 1e10) }' "$tmp/ill.err"
ok $? "m1/m2 = 1e-9: one warning naming t and th1, th2; --stats prints max_condition"
"$tmp/dp" --stats -o /dev/null 2> "$tmp/well.err"
! grep -q warning "$tmp/well.err" &&
  awk '/^max_condition / { c = $2 } END { exit !(c > 0 && c < 1000) }' "$tmp/well.err"
ok $? "the default double pendulum: no warning, a small max_condition"
# physical data from --set: exit 2 naming what and the parameters, no output
rm -f "$tmp/neg.csv"
usage_err "$tmp/cp" --set m=-1 -o "$tmp/neg.csv" &&
  grep -q "^cp: --set: particle 'bob': a mass cannot be negative (m = -1)$" "$tmp/u.err" &&
  [ ! -e "$tmp/neg.csv" ]
ok $? "--set m=-1: exit 2 naming the particle's mass and m, no output file"
"$eomc" build "$src/specs/precession.yaml" -o "$tmp/prec" 2> /dev/null
usage_err "$tmp/prec" --set C=5 --accel &&
  grep -q "body 'body': no distribution of mass has this inertia .* (A = 1, B = 1.5, C = 5)" "$tmp/u.err"
ok $? "--set C=5 (A + B < C): exit 2 naming the body and A, B, C with their values"
usage_err "$tmp/prec" --set A=-1 &&
  grep -q "body 'body': its inertia must be positive definite .* (A = -1)" "$tmp/u.err"
ok $? "--set A=-1: exit 2, the inertia is not positive definite"
# a turn's axis of parameters: --set making it zero leaves no direction
cat > "$tmp/axis.yaml" <<'YAML'
name: axis
parameters: {a: 1.0, g: 9.81}
coordinates: [q]
frames:
  arm: {rotation: [{axis: [a, 0, 0], angle: q}]}
points:
  tip: {frame: arm, at: [0, 1, 0]}
particles:
  bob: {mass: 1, position: tip}
effects:
  gravity: {gravity: [0, 0, -g]}
initial: {q: 0.3}
scene: {t_end: 1}
YAML
"$eomc" build "$tmp/axis.yaml" -o "$tmp/axis" 2> /dev/null
usage_err "$tmp/axis" --set a=0 -o "$tmp/axis0.csv" &&
  grep -q "^axis: --set: frame 'arm': an axis cannot be zero (a = 0)$" "$tmp/u.err" &&
  [ ! -e "$tmp/axis0.csv" ]
ok $? "--set a=0 zeroing a turn's axis: exit 2 naming the frame and a, no output file"
# a massless bob (allowed: forces may act on a point) leaves M singular:
# the run stops at t = 0, where the equations cannot be solved, before any row
"$tmp/axis" --set a=-2 -o /dev/null; sta=$?
cat > "$tmp/massless.yaml" <<'YAML'
name: massless
parameters: {m: 1.0, g: 9.81}
coordinates: [q]
particles:
  bob: {mass: m, position: [cos(q), sin(q)]}
effects:
  gravity: {gravity: [0, -g]}
initial: {q: 0.3}
scene: {t_end: 1}
YAML
"$eomc" build "$tmp/massless.yaml" -o "$tmp/massless" 2> /dev/null
"$tmp/massless" --set m=0 -o "$tmp/m0.csv" 2> "$tmp/m0.err"; st=$?
[ $sta -eq 0 ] && [ $st -eq 3 ] && [ "$(wc -l < "$tmp/m0.csv")" -eq 1 ] &&
  grep -q "error: t = 0: mass matrix is singular or not positive definite (pivot 1, coordinate q)" "$tmp/m0.err" &&
  grep -q "no row was computed: $tmp/m0.csv holds the header alone" "$tmp/m0.err" &&
  ! grep -q "rows computed" "$tmp/m0.err"
ok $? "a massless bob: exit 3 at t = 0 naming M and q, before any row: says the header alone is kept"
usage_err "$tmp/cp" --stabilize projct && grep -q "did you mean 'project'" "$tmp/u.err"
ok $? "--stabilize with a typo: usage error suggesting project"
usage_err "$tmp/cp" --baumgarte 1 && grep -q "ALPHA,BETA" "$tmp/u.err"
ok $? "--baumgarte 1: usage error asking for ALPHA,BETA"
usage_err "$tmp/cp" --stabilize project --baumgarte 1,2 &&
  grep -q "^cp: --baumgarte gives the rates of --stabilize baumgarte, not of --stabilize project" "$tmp/u.err"
ok $? "--baumgarte with --stabilize project: usage error, the rates belong to baumgarte"
# --baumgarte A,B sets the rates: from a start off the circle (g = x^2 +
# y^2 - l^2 = 0.06, g' = 0) the residual column res[rod] follows the
# closed-form solution of g'' + 2A g' + B^2 g = 0, under-, over- and
# critically damped (the default rates 10,10 would give another curve).
for rates in 1,2 3,2 2,2; do
  "$tmp/cp" --baumgarte $rates --init x=0.9 --init y=-0.5 --t-end 3 --dt 0.25 \
    --rtol 1e-12 --atol 1e-12 -o "$tmp/bg.csv" 2> /dev/null; st=$?
  got=$(awk -F, -v rates=$rates '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == "res[rod]") c = i; next }
    NR == 2 { g0 = $c; split(rates, r, ","); a = r[1]; b = r[2] }
    { t = $1
      if (b > a) { w = sqrt(b * b - a * a); want = g0 * exp(-a * t) * (cos(w * t) + a / w * sin(w * t)) }
      else if (a > b) { s = sqrt(a * a - b * b); r1 = -a + s; r2 = -a - s
                        want = g0 * (r2 * exp(r1 * t) - r1 * exp(r2 * t)) / (r2 - r1) }
      else want = g0 * (1 + a * t) * exp(-a * t)
      d = ($c - want) / g0; if (d < 0) d = -d; if (d > e) e = d; n++ }
    END { printf "%d rows, g(0) = %s, largest |g - closed form| %.2g of g(0)", n, g0, e
          exit !(c && n == 13 && g0 > 0.05 && e <= 1e-9) }' "$tmp/bg.csv")
  [ $st -eq 0 ]
  ok $? "--baumgarte $rates: res[rod] = g(t) of g'' + 2A g' + B^2 g = 0: $got"
done
usage_err "$tmp/pend" --stabilize project && grep -q "no holonomic or first-order" "$tmp/u.err"
ok $? "--stabilize on a model without constraints: usage error"
usage_err "$tmp/cp" --method msbdf --stabilize project -o "$tmp/ms.csv" &&
  grep -q "with --stabilize project use a one-step method (rk2, rk4" "$tmp/u.err" &&
  [ ! -s "$tmp/ms.csv" ]
ok $? "--method msbdf --stabilize project: usage error naming the one-step methods"

# failures: exit status 2, no output left
printf 'coordinates: [x]\nparticles: {p: {mass: 1, position: [x, y]}}\n' > "$tmp/bad.yaml"
"$eomc" compile "$tmp/bad.yaml" -o "$tmp/bad.c" 2> "$tmp/bad.err"; st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/bad.c" ] && ! ls "$tmp"/bad.c.tmp* > /dev/null 2>&1
ok $? "a bad spec exits 2 and leaves no .c (status $st)"
grep -q "bad.yaml:2:" "$tmp/bad.err"; ok $? "the error names file:line"
"$eomc" build "$tmp/bad.yaml" -o "$tmp/badexe" 2> /dev/null; st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/badexe" ]; ok $? "eomc build of a bad spec exits 2, no executable"
"$eomc" compile "$src/specs/pendulum.yaml" --form nope > /dev/null 2> "$tmp/form.err"; st=$?
[ $st -eq 2 ] && grep -q "lagrange" "$tmp/form.err"; ok $? "an unknown form is a usage error listing the forms"
"$eomc" compile "$src/specs/gear_link.yaml" --form gibbs-appell -o "$tmp/ga.c" 2> "$tmp/ga.err"; st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/ga.c" ] && grep -q "explicit kinetic-energy terms" "$tmp/ga.err"
ok $? "gibbs-appell on a spec with explicit kinetic terms: refused (no S), exit 2"
"$eomc" frobnicate 2> /dev/null; ok $(($? != 2)) "an unknown command exits 2"

# what a user reads (issue 21): usage errors under `eomc run` name the
# command typed, not the cached binary; a built simulator names itself
"$eomc" run "$src/specs/pendulum.yaml" --dt -1 > /dev/null 2> "$tmp/see.err"; st=$?
"$eomc" run "$src/specs/pendulum.yaml" --help > "$tmp/help.out"
"$tmp/pend" --dt -1 2> "$tmp/see2.err"
[ $st -eq 2 ] && grep -qx "(see eomc run $src/specs/pendulum.yaml --help)" "$tmp/see.err" &&
  grep -q "^usage: eomc run $src/specs/pendulum.yaml \[OPTION\]" "$tmp/help.out" &&
  grep -qx "(see pend --help)" "$tmp/see2.err"
ok $? "eomc run's usage errors say 'see eomc run SPEC --help'; a built simulator's its own name"
# a zero is printed 0, never -0: Kepler's y = 0 makes y'' = -GM y / r^3 = -0
"$eomc" run "$src/specs/kepler.yaml" --accel > "$tmp/kepler.acc"
"$eomc" run "$src/specs/appell.yaml" --t-end 0.05 > "$tmp/appell.csv"
grep -qx "y'' 0" "$tmp/kepler.acc" && ! grep -q -- "-0$" "$tmp/kepler.acc" &&
  [ "$(wc -l < "$tmp/appell.csv")" -gt 5 ] && ! grep -q -- '\(^\|,\)-0\(,\|$\)' "$tmp/appell.csv"
ok $? "--accel and the CSV print 0 for a negative zero (kepler y'', appell's rows)"
# counts agree with their nouns
"$eomc" compile "$src/specs/pendulum.yaml" --explain > "$tmp/explain.out"
"$eomc" compile "$src/specs/gear_link.yaml" --explain > "$tmp/explain2.out"
"$tmp/pend" --method rk4 --fixed-step 0.1 --t-end 0.1 --dt 0.1 --summary > /dev/null 2> "$tmp/sum.err"
grep -q "3 parameters, 0 inputs, 1 particle, 0 bodies$" "$tmp/explain.out" &&
  grep -q "1 input, 0 particles, 0 bodies$" "$tmp/explain2.out" &&
  tr '\n' ' ' < "$tmp/sum.err" | grep -q "1 step (0 rejected), 5 right-hand sides and 0 Jacobians"
ok $? "plurals: 1 particle, 1 input, 1 step (--explain, --summary)"

# "-o -" is stdout (for the CSV and the C; test_import.sh: a spec), and names
# no file; a simulator cannot be written there
(cd "$tmp" && "$eomc" run "$src/specs/pendulum.yaml" --t-end 0.05 -o - > dash.csv &&
  "$eomc" run "$src/specs/pendulum.yaml" --t-end 0.05 > plain.csv &&
  "$eomc" compile "$src/specs/pendulum.yaml" -o - > dash.c)
[ -s "$tmp/dash.csv" ] && cmp -s "$tmp/dash.csv" "$tmp/plain.csv" && cmp -s "$tmp/dash.c" "$tmp/a.c" &&
  [ ! -e "$tmp/-" ]
ok $? "-o - writes the CSV and the C to stdout, the same bytes as without -o, and no file '-'"
(cd "$tmp" && "$eomc" build "$src/specs/pendulum.yaml" -o - > /dev/null 2> dash.err); st=$?
[ $st -eq 2 ] && grep -q "cannot be written to stdout" "$tmp/dash.err" && [ ! -e "$tmp/-" ]
ok $? "build -o -: exit 2, an executable cannot be written to stdout"

tap_end
