#!/bin/sh
# Taylor's method on models with speeds of their own (a unit quaternion
# whose speeds are its body's angular velocity, q' = W(q) v), against
# values got without it (TAP):
#  - the symmetric top free of torques (tests/sim/specs/free_top.yaml):
#    every row, quaternion and angular velocity, on the closed form
#    (computed here in Python from the spec's numbers), each quaternion of
#    length 1;
#  - --error on it: the error_max it reports is the rows' true error
#    against the closed form, at 1e-6, 1e-8 and 1e-10; the rows, read off
#    the steps' series, renormalized as the steps' ends are (|e|
#    within 4 units of rounding of 1, state.c);
#  - the asymmetric heavy top whose tip three constraints hold
#    (tests/sim/specs/heavy_top.yaml): taylor's rows within 1e-12 of
#    rk8pd's at 1e-15; its reference by Taylor's method in extended
#    precision against the reference by extrapolation, within the errors
#    both claim;
#  - an MJCF's free body (tests/import/models/robots/freebody.xml,
#    imported through MuJoCo's loader; skipped without libmujoco-dev), spun
#    and thrown, by `--method taylor` with no --form: eomc picks a form
#    that has series (the cheapest, the articulated-body form, computes M by
#    columns), and taylor's rows at 1e-14 are within 1e-12 of rk8pd's in
#    the articulated-body form; at 1e-15, where the truncation is below
#    rounding, its energy stays within 1e-14 of its start (45 units of
#    rounding; at 1e-14 the truncation's own drift is about the
#    tolerance, 9e-15 to 1.2e-14 as the sums' order draws rounding).
# usage: test_taylor_speeds.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"

# the largest difference over the columns 2 .. $3 of two CSVs of the same
# rows, or "none" (no rows)
state_diff() { paste -d, "$1" "$2" | awk -F, -v last="$3" 'NR == 1 { h = NF / 2; next }
    { n++; for (i = 2; i <= last; i++) { d = $i - $(i + h); d = d < 0 ? -d : d; if (d > m) m = d } }
    END { if (n == 0) print "none"; else printf "%.3g", m }'; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && a != "none" && a + 0 <= b + 0) }'; }

# free_top's closed form: with A = B, w's cross component turns about the
# axis at Omega = (C - A)/A wz, and e(t) = p(t) (x) e(0) (x) qz(-Omega t),
# p(t) the turn by |L|/A t about L = R(e(0)) I w(0), fixed in space.
# Prints the largest difference of the rows' e and w from it, and of |e|
# from 1.
cat > "$tmp/closed.py" <<'PY'
import math, sys
A, C = 0.3, 0.5
e0 = (0.9, 0.3, 0.1, 0.3)
wx, wy, wz = 0.7, 0.2, 3.0
def qmul(a, b):
    return (a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0])
def turn(e, v):  # e (x) (0, v) (x) e*
    return qmul(qmul(e, (0.0,) + tuple(v)), (e[0], -e[1], -e[2], -e[3]))[1:]
om = (C - A) / A * wz
Lb = (A * wx, A * wy, C * wz)
L = math.sqrt(sum(x * x for x in Lb))
n = [x / L for x in turn(e0, Lb)]
rate = L / A
worst = unit = 0.0
for line in open(sys.argv[1]).read().split()[1:]:
    r = [float(x) for x in line.split(",")]
    t = r[0]
    p = (math.cos(rate * t / 2),) + tuple(x * math.sin(rate * t / 2) for x in n)
    e = qmul(qmul(p, e0), (math.cos(om * t / 2), 0.0, 0.0, -math.sin(om * t / 2)))
    w = (wx * math.cos(om * t) - wy * math.sin(om * t),
         wx * math.sin(om * t) + wy * math.cos(om * t), wz)
    worst = max([worst] + [abs(a - b) for a, b in zip(r[1:8], list(e) + list(w))])
    unit = max(unit, abs(math.sqrt(sum(x * x for x in r[1:5])) - 1))
print("%.17g %.3g" % (worst, unit))
PY

top="$src/tests/sim/specs/free_top.yaml"
"$eomc" run "$top" --method taylor --rtol 1e-15 --atol 1e-15 -o "$tmp/ft.csv" 2> "$tmp/ft.err"
st=$?
set -- $(python3 "$tmp/closed.py" "$tmp/ft.csv" 2> /dev/null) "" ""
# 20 s of w ~ 3, |L|/A ~ 5: the closed form's own rounding is some 1e-15
[ $st = 0 ] && [ "$(wc -l < "$tmp/ft.csv")" = 82 ] && [ ! -s "$tmp/ft.err" ] && le "$1" 2e-14 &&
    le "$2" 4.5e-16
ok $? "free_top by Taylor at 1e-15: every row within $(printf %.3g "$1") of the closed form (<= 2e-14), |e| within $2 of 1"

for tol in 1e-6 1e-8 1e-10; do
  "$eomc" run "$top" --method taylor --rtol $tol --atol $tol --error --stats -o "$tmp/fe.csv" \
      2> "$tmp/fe.err"
  st=$?
  set -- $(python3 "$tmp/closed.py" "$tmp/fe.csv" 2> /dev/null) "" ""
  true_err=$1 unit=$2
  emax=$(stat_of error_max "$tmp/fe.err") refe=$(stat_of reference_error "$tmp/fe.err")
  # the two agree to the reference's error and the closed form's rounding
  [ $st = 0 ] && [ -n "$refe" ] && awk -v a="$emax" -v b="$true_err" -v r="$refe" 'BEGIN {
      d = a - b; d = d < 0 ? -d : d; exit !(a > 0 && b > 0 && d <= r + 2e-14) }' &&
      le "$unit" 1e-15
  ok $? "free_top, taylor at $tol, --error: error_max $(printf %.4g "$emax"), the closed form's true error $(printf %.4g "$true_err") (reference within $(printf %.2g "$refe")); the rows' |e| within $unit of 1"
done

# the heavy top: against rk8pd, and the two references
heavy="$src/tests/sim/specs/heavy_top.yaml"
"$eomc" run "$heavy" --method taylor --rtol 1e-14 --atol 1e-14 -o "$tmp/ht.csv" 2> "$tmp/ht.err" &&
    "$eomc" run "$heavy" --method rk8pd --rtol 1e-15 --atol 1e-15 -o "$tmp/h8.csv" 2> /dev/null
st=$?
d=$(state_diff "$tmp/ht.csv" "$tmp/h8.csv" 14)
[ $st = 0 ] && [ ! -s "$tmp/ht.err" ] && [ "$(wc -l < "$tmp/ht.csv")" = 12 ] && le "$d" 1e-12
ok $? "heavy_top (constrained, in gravity) by Taylor at 1e-14: the state within $d of rk8pd's at 1e-15 (<= 1e-12)"
for how in extrapolation taylor; do
  "$eomc" run "$heavy" --method taylor --rtol 1e-10 --atol 1e-10 --error --stats \
      --reference-method $how --reference-out "$tmp/ref_$how.csv" -o /dev/null \
      2> "$tmp/ref_$how.err" || echo "# $how: exit $?"
done
ea=$(stat_of reference_error "$tmp/ref_extrapolation.err")
eb=$(stat_of reference_error "$tmp/ref_taylor.err")
d=$(state_diff "$tmp/ref_extrapolation.csv" "$tmp/ref_taylor.csv" 14)
[ -n "$ea" ] && [ -n "$eb" ] && le "$d" "$(awk -v a="$ea" -v b="$eb" 'BEGIN { print a + b }')"
ok $? "heavy_top: the references by extrapolation and by Taylor's method differ by $d, within the errors they claim ($ea + $eb)"

# an MJCF's free body, spun and thrown
fb="$src/tests/import/models/robots/freebody.xml"
init="--init root_wx=2 --init root_wy=-1 --init root_wz=5 --init root_x'=0.3 --t-end 2 --dt 0.1"
# shellcheck disable=SC2086 # $init is a list of options
"$eomc" run "$fb" --method taylor --rtol 1e-14 --atol 1e-14 $init \
    -o "$tmp/fbt.csv" 2> "$tmp/fbt.err"
st=$?
if [ $st != 0 ] && grep -q 'libmujoco-dev' "$tmp/fbt.err"; then
  echo "ok $((n + 1)) # SKIP eomc import needs MuJoCo: $(head -1 "$tmp/fbt.err")"
  n=$((n + 1))
else
  # shellcheck disable=SC2086
  "$eomc" run "$fb" --method rk8pd --rtol 1e-15 --atol 1e-15 $init -o "$tmp/fb8.csv" 2> /dev/null
  d=$(state_diff "$tmp/fbt.csv" "$tmp/fb8.csv" 14)
  # shellcheck disable=SC2086
  "$eomc" run "$fb" --method taylor --rtol 1e-15 --atol 1e-15 $init -o "$tmp/fbt15.csv" \
      2> /dev/null
  drift=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "E") c = i; next }
      NR == 2 { e0 = $c } { d = ($c - e0) / e0; d = d < 0 ? -d : d; if (d > m) m = d }
      END { printf "%.3g", m }' "$tmp/fbt15.csv")
  [ $st = 0 ] && [ "$(wc -l < "$tmp/fbt.csv")" = 22 ] && le "$d" 1e-12 && le "$drift" 1e-14
  ok $? "freebody.xml by Taylor at 1e-14 (a form with series picked): within $d of rk8pd's at 1e-15 in the articulated-body form (<= 1e-12); at 1e-15 E within $drift of its start (<= 1e-14)"
fi

tap_end
