#!/bin/sh
# Taylor's method (--method taylor) on shipped specs, against values got
# without it (TAP):
#  - the pendulum released from rest (specs/swing.yaml, scene quarter)
#    stops at the bottom after a quarter period, K(sin(theta0/2)) /
#    sqrt(g/l) computed here by the arithmetic-geometric mean;
#  - the bouncing ball's impacts at t1 = sqrt(2h/g) and then every
#    2 v1 e^k / g;
#  - the Kepler orbit of e = 0.6 over 100 periods: its energy
#    v^2/2 - mu/r, computed here from the rows, stays within 1e-13 of its
#    start (rk8pd at 1e-14, 5e-12 on the 2-core build machine);
#  - chain5 from q1 = 1: the report's error_max against the reference in
#    extended precision (GBS, long double), order_mean from the tolerance,
#    no side step;
#  - an event that grazes (tests/sim/specs/graze.yaml: x = cos t, the
#    event x = 0.999): the crossings 0.089 apart around each maximum both
#    fall in one step, where g has one sign at its ends; the step ends
#    between the roots of g's series, and all 7 crossings up to t = 20
#    come out at their closed forms 2 pi k -+ acos(0.999);
#  - the Cartesian pendulum (a holonomic constraint, by multipliers and,
#    built with --eliminate, by elimination) released from rest at 1 rad:
#    at the quarter period above, x = 0, y = -l and x' = -sqrt(2 g l (1 -
#    cos 1)), energy's closed form;
#  - the same from a state off the rod with Baumgarte's rates 5, 5: the
#    residual g = x^2 + y^2 - l^2 obeys g'' + 10 g' + 25 g = 0, so from
#    rest g(t) = g0 (1 + 5 t) e^(-5t);
#  - constraints nonlinear in q'': cubic.yaml's particle falls with the
#    constant x'' that is the root of x'' + (x''^3 + x'' + g)(3 x''^2 + 1)
#    = 0 (bisection here), and cubic_spring.yaml's motion at t = 2 is
#    rk8pd's (Newton's method at every stage) at rtol 1e-14;
#  - the reference by Taylor's method in extended precision
#    (--reference-method taylor) against the reference by extrapolation,
#    two ways that share nothing but the model's functions: on seven
#    specs (chain5 from q1 = 1, Kepler, Arenstorf's orbit, the double
#    pendulum, the Cartesian pendulum, precession's second-order
#    constraint, the car axis) their rows differ by no more than the sum
#    of the errors each claims;
#  - the Pleiades and the outer solar system (specs/), against their
#    states at the end computed outside eomc with mpmath to 25 digits
#    (tests/sim/nbody_reference.py, *_reference.csv): the error --error
#    reports (against eomc's extended-precision reference) is the true
#    error to within what that reference claims, for taylor and rk8pd;
#  - refusals, each naming its cause: a model without series (before
#    its C is compiled: no cc runs), fixed steps, a reference by Taylor's
#    method of a constraint nonlinear in q''.
# usage: test_taylor.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
tight="--method taylor --rtol 1e-15 --atol 1e-15"

# a relative difference of $1 from $2 within $3
near() { awk -v g="$1" -v w="$2" -v tol="$3" 'BEGIN { d = g - w; if (d < 0) d = -d
    exit !(g != "" && d <= tol * (w < 0 ? -w : w)) }'; }

# the quarter period at theta0 = 1 (the scene's), l = 1, g = 9.81
"$eomc" run "$src/specs/swing.yaml" --scene quarter $tight -o "$tmp/q.csv" 2> "$tmp/q.err"
st=$?
got=$(tail -1 "$tmp/q.csv" | cut -d, -f1)
want=$(awk 'BEGIN { a = 1; b = cos(0.5)
    for (i = 0; i < 40; i++) { m = (a + b) / 2; b = sqrt(a * b); a = m }
    printf "%.17g", 3.14159265358979323846 / (2 * a) / sqrt(9.81) }')
[ $st = 0 ] && near "$got" "$want" 1e-15
ok $? "swing, scene quarter: the stop at t = $got, the closed form's $want (to 1e-15)"

# the bouncing ball: h = 1, g = 9.81, e = 0.5 (the spec's)
"$eomc" run "$src/specs/bouncing_ball.yaml" $tight --events "$tmp/ev.csv" -o /dev/null \
    2> "$tmp/bb.err"
st=$?
impacts=$(awk -F, 'NR > 1 { printf "%s ", $1 }' "$tmp/ev.csv")
set -- $impacts
nimp=$#
bad=$(awk -v list="$impacts" 'BEGIN { g = 9.81; h = 1; e = 0.5; n = split(list, t, " ")
    t1 = sqrt(2 * h / g); v = g * t1; w = t1; bad = 0
    for (k = 1; k <= n; k++) { d = t[k] - w; if (d < 0) d = -d
        if (d > 1e-15 * w) bad++
        v *= e; w += 2 * v / g }
    print bad }')
[ $st = 0 ] && [ "$nimp" = 3 ] && [ "$bad" = 0 ]
ok $? "bouncing ball: $nimp impacts ($impacts) at the closed form's times to 1e-15 ($bad off)"

# Kepler, e = 0.6, 100 periods of 2 pi
"$eomc" run "$src/specs/kepler.yaml" --set e=0.6 $tight --t-end 628.3185307179587 \
    --dt 6.283185307179586 -o "$tmp/k.csv" 2> "$tmp/k.err"
st=$?
drift=$(awk -F, 'NR > 1 { e = ($4 * $4 + $5 * $5) / 2 - 1 / sqrt($2 * $2 + $3 * $3)
    if (NR == 2) e0 = e; d = (e - e0) / e0; if (d < 0) d = -d; if (d > m) m = d }
    END { printf "%.3g", m }' "$tmp/k.csv")
[ $st = 0 ] && [ "$(wc -l < "$tmp/k.csv")" = 102 ] && awk -v d="$drift" 'BEGIN { exit !(d < 1e-13) }'
ok $? "Kepler, e = 0.6, 100 periods: the energy within $drift of its start (< 1e-13)"

# chain5 against the extended-precision reference.  At 1e-13 the error is
# rounding's, amplified by the chain's motion, not the truncation's: the
# last bits of the step sizes draw it anew (2026-12-01, the steps' roots
# by pow: 2.6e-13, 1.2e-13, 4.4e-13 at 1e-12, 1e-13, 1e-14; by exp and
# log: 1.5e-13, 3.3e-13, 1.5e-13; docs/accuracy.md), so the bound is the
# draws' largest, 5e-13, five times the tolerance
"$eomc" accuracy "$src/specs/chain5.yaml" --init q1=1.0 --methods taylor --tolerances 1e-8,1e-13 \
    --csv "$tmp/c5.csv" > "$tmp/c5.txt" 2> "$tmp/c5.err"
st=$?
set -- $(awk -F, 'NR > 1 { printf "%s %s %s ", $10, $13, $6 }' "$tmp/c5.csv")
[ $st = 0 ] && awk -v e8="$1" -v e13="$4" 'BEGIN { exit !(e8 < 1e-7 && e13 < 5e-13) }' &&
    [ "$2" = 11 ] && [ "$5" = 16 ] && [ "$3" = 0 ] && [ "$6" = 0 ]
ok $? "chain5, q1 = 1: error_max $1 at 1e-8 (order $2), $4 at 1e-13 (order $5), against the reference; rejected steps $3, $6"

# the grazing event's 7 crossings, acos(0.999) then 2 pi k -+ acos(0.999)
"$eomc" run "$src/tests/sim/specs/graze.yaml" $tight --events "$tmp/gr.csv" -o /dev/null \
    2> "$tmp/gr.err"
st=$?
set -- $(awk -F, '$2 == "top" { n++; a = atan2(sqrt(1 - 0.999^2), 0.999); k = int(n / 2)
    want = 2 * 3.14159265358979323846 * k + (n % 2 ? a : -a)
    d = $1 - want; d = d < 0 ? -d : d; if (d > m) m = d } END { printf "%d %.2g", n, m }' \
    "$tmp/gr.csv")
[ $st = 0 ] && [ "$1" = 7 ] && awk -v d="$2" 'BEGIN { exit !(d <= 2e-14) }'
ok $? "graze: $1 crossings of x = 0.999 (want 7), at the closed form's times within $2 (<= 2e-14)"

# the Cartesian pendulum at the quarter period (the swing's above: l = 1,
# g = 9.81, theta0 = 1), by multipliers and by elimination
cp="$src/specs/cartesian_pendulum.yaml"
"$eomc" build "$cp" --eliminate --taylor -o "$tmp/cpel" 2> "$tmp/cpel.err"
for how in multipliers elimination; do
  if [ $how = multipliers ]; then
    "$eomc" run "$cp" $tight --t-end "$want" -o "$tmp/cp.csv" 2> "$tmp/cp.err"
  else
    "$tmp/cpel" $tight --t-end "$want" -o "$tmp/cp.csv" 2> "$tmp/cp.err"
  fi
  st=$?
  got=$(tail -1 "$tmp/cp.csv" | awk -F, '{ w = -sqrt(2 * 9.81 * (1 - cos(1)))
      d = ($4 - w) / w; printf "%.2g %.2g %.2g", $2, $3 + 1, d < 0 ? -d : d }')
  [ $st = 0 ] && [ ! -s "$tmp/cp.err" ] && echo "$got" | awk '{ for (i = 1; i <= 3; i++)
      if (($i < 0 ? -$i : $i) > 1e-15) exit 1 }'
  ok $? "cartesian_pendulum by $how: at the quarter period x, y + l and x' off by $got (<= 1e-15)"
done

# Baumgarte's stabilization from x = 0.7, y = -cos 1 (g0 = 0.49 + cos^2 1 - 1)
"$eomc" run "$cp" $tight --baumgarte 5,5 --init x=0.7 --t-end 0.5 -o "$tmp/b.csv" 2> /dev/null
st=$?
rel=$(tail -1 "$tmp/b.csv" | awk -F, '{ g = $2 * $2 + $3 * $3 - 1; g0 = 0.49 + cos(1)^2 - 1
    w = g0 * (1 + 5 * $1) * exp(-5 * $1); d = (g - w) / w; printf "%.2g", d < 0 ? -d : d }')
[ $st = 0 ] && awk -v r="$rel" 'BEGIN { exit !(r != "" && r <= 1e-13) }'
ok $? "cartesian_pendulum, Baumgarte 5, 5 from off the rod: g(0.5) within $rel of g0 (1 + 5t) e^(-5t) (<= 1e-13)"

# a constraint nonlinear in q'': from rest at 0, x = x'' t^2 / 2 and
# y = (x''^3 + x'') t^2 / 2 at t = 10 (m = 1.5, g = 9.81)
"$eomc" run "$src/tests/sim/specs/cubic.yaml" $tight -o "$tmp/cu.csv" 2> "$tmp/cu.err"
st=$?
rel=$(tail -1 "$tmp/cu.csv" | awk -F, '{ lo = -10; hi = 10; g = 9.81
    for (i = 0; i < 200; i++) { a = (lo + hi) / 2; r = a + (a^3 + a + g) * (3 * a^2 + 1)
        if (r > 0) hi = a; else lo = a }
    x = a * $1^2 / 2; y = (a^3 + a) * $1^2 / 2; d = ($2 - x) / x; e = ($3 - y) / y
    d = d < 0 ? -d : d; e = e < 0 ? -e : e; printf "%.2g", (d > e ? d : e) }')
[ $st = 0 ] && awk -v r="$rel" 'BEGIN { exit !(r != "" && r <= 1e-15) }'
ok $? "cubic (nonlinear in q''): x and y at t = 10 within $rel of the closed form (<= 1e-15)"
# its reference by extrapolation, whose Newton's method starts from rest
# (its steps grow before they shrink): every row within the error it
# claims, itself within 1e-15 of the largest entry (483)
"$eomc" accuracy "$src/tests/sim/specs/cubic.yaml" --methods rk8pd --tolerances 1e-8 \
    --reference-out "$tmp/curef.csv" > "$tmp/curef.txt" 2> /dev/null
st=$?
claim=$(sed -n 's/.*its error is at most \([0-9.e+-]*\).*/\1/p' "$tmp/curef.txt")
# the closed form in 40 digits (Python's decimal; in double, y's a^3 alone
# is off by 1e-13 at t = 10), at the rows' own times and values: the
# doubles the CSV's shortest digits stand for (float), not those digits
# (8.63 is 7.8e-16 off the double 8.63 names, which y' = -84 makes 7e-14)
worst=$(python3 - "$tmp/curef.csv" <<'PY'
import sys
from decimal import Decimal as D, getcontext
getcontext().prec = 40
g = D(9.81)  # the double the model holds, exactly
lo, hi = D(-10), D(10)
for _ in range(160):  # bisection on a + (a^3 + a + g)(3a^2 + 1), increasing
    a = (lo + hi) / 2
    if a + (a**3 + a + g) * (3 * a**2 + 1) > 0:
        hi = a
    else:
        lo = a
b = a**3 + a
w = D(0)
rows = open(sys.argv[1]).read().split()[1:]
for line in rows:
    t, x, y, vx, vy = (D(float(v)) for v in line.split(",")[:5])
    w = max(w, abs(x - a * t * t / 2), abs(y - b * t * t / 2), abs(vx - a * t), abs(vy - b * t))
print("%.3g" % w)
PY
)
[ $st = 0 ] && awk -v w="$worst" -v c="$claim" 'BEGIN { exit !(c != "" && w != "" && w <= c && c <= 1e-15 * 483) }'
ok $? "cubic: the reference by extrapolation, from rest, on the closed form to $worst over the rows, within the $claim it claims (<= 1e-15 of 483)"
cs="$src/tests/sim/specs/cubic_spring.yaml"
"$eomc" run "$cs" --method rk8pd --rtol 1e-14 --atol 0 -o "$tmp/cs8.csv" 2> /dev/null &&
    "$eomc" run "$cs" --method taylor --rtol 1e-14 --atol 0 -o "$tmp/cst.csv" 2> /dev/null
st=$?
diff=$(paste -d, "$tmp/cs8.csv" "$tmp/cst.csv" | awk -F, 'NR > 1 { for (i = 2; i <= 5; i++) {
    d = $i - $(i + 10); d = d < 0 ? -d : d; if (d > m) m = d } } END { printf "%.2g", m }')
[ $st = 0 ] && [ "$(wc -l < "$tmp/cst.csv")" = 202 ] &&
    awk -v d="$diff" 'BEGIN { exit !(d != "" && d <= 1e-12) }'
ok $? "cubic_spring (nonlinear in q''): taylor's rows within $diff of rk8pd's, both at 1e-14 (<= 1e-12)"

# the two references, each with the error it claims (the report's "its
# error is at most E"), over the coordinates and velocities (the columns
# named q and q' in the CSV)
for spec in "specs/chain5.yaml --init q1=1.0" specs/kepler.yaml specs/arenstorf.yaml \
            specs/double_pendulum.yaml specs/cartesian_pendulum.yaml specs/precession.yaml \
            tests/hard/specs/car_axis.yaml; do
  set -- $spec
  file=$1 name=$(basename "$1" .yaml)
  shift
  why=
  for how in extrapolation taylor; do
    "$eomc" accuracy "$src/$file" "$@" --methods rk8pd --tolerances 1e-6 --reference-method $how \
        --reference-out "$tmp/ref_$how.csv" > "$tmp/ref_$how.txt" 2> "$tmp/ref_$how.err" ||
      why="$why; $how failed: $(tail -2 "$tmp/ref_$how.err" | tr '\n' ' ' | cut -c1-300)"
  done
  ea=$(sed -n 's/.*its error is at most \([0-9.e+-]*\).*/\1/p' "$tmp/ref_extrapolation.txt")
  eb=$(sed -n 's/.*its error is at most \([0-9.e+-]*\).*/\1/p' "$tmp/ref_taylor.txt")
  d=$(paste -d, "$tmp/ref_extrapolation.csv" "$tmp/ref_taylor.csv" | awk -F, 'NR == 1 {
      h = NF / 2; for (i = 2; i <= h; i++) if ($i ~ /\047$/) n++; next }
      { for (i = 2; i <= 1 + 2 * n; i++) { x = $i - $(i + h); x = x < 0 ? -x : x; if (x > m) m = x } }
      END { if (n == 0) print "none"; else printf "%.3g", m }')
  grep -q "by Taylor's method\|reference: Taylor's method" "$tmp/ref_taylor.txt" &&
      awk -v d="$d" -v a="$ea" -v b="$eb" 'BEGIN { exit !(d != "none" && a != "" && b != "" && d <= a + b) }'
  ok $? "$name: the references by extrapolation and by Taylor's method differ by $d, within the errors they claim ($ea + $eb)$why"
done

# refusals
"$eomc" run "$src/tests/sim/specs/cubic.yaml" --error --reference-method taylor -o "$tmp/r.csv" \
    2> "$tmp/r.err"
st=$?
[ $st = 2 ] && grep -q "reference-method taylor: a constraint of cubic is nonlinear in q''" \
    "$tmp/r.err" && [ ! -s "$tmp/r.csv" ]
ok $? "a reference by Taylor's method of a constraint nonlinear in q'': exit 2, naming why"
"$eomc" run "$src/specs/rolling_disk.yaml" --form articulated-body --method taylor -o "$tmp/r.csv" \
    2> "$tmp/r.err"
st=$?
[ $st = 2 ] && grep -q "has no Taylor series: its form computes the mass matrix by columns" \
    "$tmp/r.err" && [ ! -s "$tmp/r.csv" ]
ok $? "a form without the expressions of M: exit 2, naming why ($(head -1 "$tmp/r.err"))"
# without --form a run by Taylor's method takes the cheapest form with series:
# the disk's rows are rk8pd's (in the cheapest form of all) to 1e-10
"$eomc" run "$src/specs/rolling_disk.yaml" --method taylor --t-end 1 --dt 0.5 --rtol 1e-13 \
    --atol 1e-13 -o "$tmp/dt.csv" 2> "$tmp/dt.err" &&
  "$eomc" run "$src/specs/rolling_disk.yaml" --method rk8pd --t-end 1 --dt 0.5 --rtol 1e-13 \
    --atol 1e-13 -o "$tmp/d8.csv" 2> /dev/null
st=$?
d=$(paste -d, "$tmp/dt.csv" "$tmp/d8.csv" | awk -F, 'NR > 1 { h = NF / 2
    for (i = 2; i <= h; i++) { x = $i - $(i + h); x = x < 0 ? -x : x; if (x > m) m = x } }
    END { print (NR > 1 ? m + 0 : "none") }')
[ $st = 0 ] && [ ! -s "$tmp/dt.err" ] && awk -v d="$d" 'BEGIN { exit !(d == d + 0 && d < 1e-10) }'
ok $? "--method taylor without --form: a form with series taken, the disk's rows rk8pd's to $d"
# ... refused before anything is built: no C compiler run (a CC that
# records its calls; a cache of its own, where no build of it can be),
# the simulator's message; as is a reference by Taylor's method that the
# run would compute; --accel takes no step of it, so it runs
printf '#!/bin/sh\necho "$*" >> "%s/cc.calls"\nexec %s "$@"\n' "$tmp" "${CC:-cc}" > "$tmp/cc"
chmod +x "$tmp/cc"
: > "$tmp/cc.calls"
for how in "--method taylor" "--method=rk4 --method taylor" "--error --reference-method taylor"; do
  # shellcheck disable=SC2086 # $how is a list of options
  CC="$tmp/cc" EOMC_CACHE_DIR="$tmp/cache_cc" "$eomc" run "$src/specs/rolling_disk.yaml" \
    --form articulated-body $how \
    -o "$tmp/r.csv" 2> "$tmp/r.err"
  st=$?
  opt=$(echo "$how" | sed 's/.* \(--[a-z-]*method taylor\)$/\1/')
  [ $st = 2 ] && [ ! -s "$tmp/cc.calls" ] && [ ! -s "$tmp/r.csv" ] &&
    grep -q "^rolling_disk: $opt: rolling_disk has no Taylor series: its form computes the mass matrix by columns" "$tmp/r.err" &&
    grep -q "^(see eomc run .*rolling_disk.yaml --help)$" "$tmp/r.err"
  ok $? "$how, a model without series: refused before it is built, no cc run ($(wc -l < "$tmp/cc.calls") calls; $(head -1 "$tmp/r.err"))"
done
CC="$tmp/cc" EOMC_CACHE_DIR="$tmp/cache_cc" "$eomc" run "$src/specs/rolling_disk.yaml" \
  --form articulated-body --method taylor --accel > "$tmp/r.out" 2> "$tmp/r.err"
[ $? = 0 ] && [ -s "$tmp/cc.calls" ] && grep -q "^theta'' " "$tmp/r.out"
ok $? "--method taylor --accel, the same model: built and run (it takes no step)"
# eomc build of a scene whose method is taylor, on a model without series:
# built (its simulator runs with another --method), with a warning naming why
sed 's/method: rk8pd/method: taylor/' "$src/specs/rolling_disk.yaml" > "$tmp/disk_taylor.yaml"
"$eomc" build "$tmp/disk_taylor.yaml" --form articulated-body -o "$tmp/disk_taylor" 2> "$tmp/b.err"
st=$?
[ $st = 0 ] && grep -q "warning: the scene's method is taylor, but rolling_disk has no Taylor series (its form computes the mass matrix by columns" "$tmp/b.err" &&
  "$tmp/disk_taylor" --method rk8pd --t-end 0.1 > /dev/null
ok $? "eomc build, a scene's method taylor without series: built, warned ($(head -1 "$tmp/b.err"))"
"$eomc" run "$src/specs/pendulum.yaml" --method taylor --fixed-step 0.01 > /dev/null 2> "$tmp/f.err"
[ $? = 2 ] && grep -q "taylor chooses its own steps" "$tmp/f.err"
ok $? "--fixed-step with taylor: exit 2"
"$eomc" run "$src/specs/pendulum.yaml" --method taylor --rtol 0 --atol 1e-9 > /dev/null \
    2> "$tmp/z.err"
[ $? = 2 ] && grep -q "rtol must be positive" "$tmp/z.err"
ok $? "--rtol 0 with taylor: exit 2"

# the N-body problems: --error's error against the mpmath reference's
nbody_true() { # run.csv reference.csv: the largest |x - x_ref| at the end
    awk -F, '/^#/ || /^t,/ { next } FILENAME == ARGV[1] { run = $0; next } { ref = $0 }
        END { split(run, a, ","); n = split(ref, b, ",") # (T, V, E follow in the run)
              for (i = 2; i <= n; i++) { d = a[i] - b[i]; d = d < 0 ? -d : d; if (d > m) m = d }
              printf "%.17g", m }' "$1" "$2"
}
for spec in pleiades outer_solar_system; do
    ref="$src/tests/sim/${spec}_reference.csv"
    t_end=$(awk -F, '!/^#/ && !/^t,/ { t = $1 } END { print t }' "$ref")
    for run in "taylor 1e-13" "rk8pd 1e-10"; do
        set -- $run
        "$eomc" run "$src/specs/$spec.yaml" --method $1 --rtol $2 --atol $2 --t-end "$t_end" \
            --dt "$t_end" --error --stats -o "$tmp/nb.csv" 2> "$tmp/nb.err"
        st=$?
        true_err=$(nbody_true "$tmp/nb.csv" "$ref")
        emax=$(stat_of error_max "$tmp/nb.err") refe=$(stat_of reference_error "$tmp/nb.err")
        # the two agree to the reference's claim (the mpmath one's 25
        # digits are exact here) and the rows' rounding, 2 ulps of 50
        [ $st = 0 ] && [ -n "$refe" ] && awk -v a="$emax" -v b="$true_err" -v r="$refe" 'BEGIN {
            d = a - b; d = d < 0 ? -d : d; exit !(a > 0 && b > 0 && d <= r + 2.2e-14) }'
        ok $? "$spec, $1 at $2 to t = $t_end: --error's error_max $(printf %.6g "$emax"), the mpmath reference's true error $(printf %.6g "$true_err") (eomc's reference within $(printf %.2g "$refe"))"
    done
done

tap_end
