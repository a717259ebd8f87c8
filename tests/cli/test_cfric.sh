#!/bin/sh
# Coulomb friction at contacts with a plane (a contact's `friction: mu`)
# against closed forms (TAP):
#  - a box slid along the floor at v0 (cfric_box.yaml: a block that
#    translates, its four lower corners on the floor, each bounded by
#    mu N_i, their rows alike) decelerates at mu g: it stops at
#    v0^2 / (2 mu g) at t = v0 / (mu g) and stays: over the next 10 s it
#    moves by at most 1e-9 of that distance;
#  - on a 20 degree slope with mu = 0.5 (tan 20 deg = 0.364 < mu) it
#    stays (within 1e-9 m over 10 s); with mu = 0.2 it slides with
#    a = g (sin th - mu cos th);
#  - pulled by pull*t at its centre from rest, it is held until pull*t =
#    mu N (N the floor's push at that instant, m g to 1e-10): the four
#    corners let go at once (the holding shared in proportion to the
#    bounds), each listed by --events, and then x = pull (t - t1)^3 / (6 m);
#  - a ball slid at v0 without spin (cfric_ball.yaml) slides until
#    rolling begins at t = 2 v0 / (7 mu g) at 5/7 v0, then rolls with
#    its contact point stuck (x' - r phi' at most 1e-9 v0), its normal
#    force m g to 1e-8;
#  - on a 20 degree slope it rolls at a = 5/7 g sin th where
#    mu >= 2/7 tan th (mu = 0.2), and slides at g (sin th - mu cos th)
#    where not (mu = 0.05);
#  - the ball dropped while sliding rolls at 5/7 v0 through its bounces
#    (m r x' + I phi' conserved: the floor's forces act at the touch
#    point), sticking the moment each later landing touches, the
#    reference flipping as the run does;
#  - with its units of mass, length and time rescaled (1e-9 .. 1e12) the
#    dropped ball flips the same switches at the same times and states,
#    in its units;
#  - --error on the box says the error the closed form says (within 10%,
#    at 1e-6 and 1e-9), the reference sticking where the run does;
#  - the box dropped while pulled, rkf45 with --error: the reference's
#    flips agree with the run's at 1e-5 .. 1e-10 (no warning), the run's
#    flip times converging to a tight run's;
#  - a box that can turn, pulled off its centre (its corners' rows of rank
#    3): held until the largest pull its corners' friction can balance (a
#    linear program, solved by its vertices), where it breaks away;
#  - eomc accuracy on the box dropped while sliding (it bounces, slides and
#    stops) reports each run's true error (against a far tighter run of
#    another method), falling as the tolerance tightens;
#  - --atol 0 at a state whose components are 0 names them as the cause
#    of the steps' collapse (and with --atol above 0 the run goes on);
#  - the box pulled at y0 = 1 turns on two corners whose rows are one at
#    psi = 0: they let go where rounding parts them, and the run warns,
#    naming them and their condition (cot^2 of half the rows' angle);
#  - --error on the turning box at rest ends, and says the error the
#    closed form says;
#  - Taylor's method is refused by name;
#  - a box on a tilted floor (tests/cli/cfric_tilt.yaml), bounced along
#    its normal: the exact motion keeps every corner stuck, and its
#    corners' speeds along the slope start at 0 but for rounding: the run
#    starts them stuck, and no switch flips.
# usage: test_cfric.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
box="$src/tests/cli/cfric_box.yaml"
ball="$src/tests/cli/cfric_ball.yaml"
tight="--rtol 1e-12 --atol 1e-12"
th20=$(awk 'BEGIN { printf "%.17g", 20 * 3.14159265358979323846 / 180 }')

# the box on the floor: the stop, and the 10 s after it
want=$(awk 'BEGIN { g = 9.81; mu = 0.3; v0 = 3
    printf "%.17g %.17g", v0 * v0 / (2 * mu * g), v0 / (mu * g) }')
d=${want% *} ts=${want#* }
t_end=$(awk -v t="$ts" 'BEGIN { printf "%.17g", t + 10 }')
fine=0 got=
for m in rk8pd rkf45; do
  "$eomc" run "$box" --method $m $tight --t-end "$t_end" --events "$tmp/ev.csv" \
    > "$tmp/rows.csv" 2> "$tmp/err" || continue
  stop=$(awk -F, '$2 == "floor.block.floor.v1.x.stick" { print $1 "," $3 }' "$tmp/ev.csv")
  last=$(tail -1 "$tmp/rows.csv" | cut -d, -f2)
  within "${stop#*,}" "$d" 1e-11 && within "${stop%,*}" "$ts" 1e-11 &&
    within "$last" "${stop#*,}" "$(awk -v d="$d" 'BEGIN { print 1e-9 * d }')" &&
    fine=$((fine + 1)) got="$got $m: $stop, then $last;"
done
[ $fine -eq 2 ]
ok $? "a box slid along the floor stops at v0^2/(2 mu g) = $d at t = v0/(mu g) = $ts, and stays 10 s ($got)"

# the slope: held at mu = 0.5, sliding at mu = 0.2
"$eomc" run "$box" --set th=$th20 --set mu=0.5 --set v0=0 --t-end 10 $tight \
  --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 1 ] &&
  awk -F, 'NR > 1 { if ($2 < 0) $2 = -$2; if ($2 > 1e-9) bad = 1 } END { exit bad || NR < 2 }' \
    "$tmp/rows.csv"
ok $? "a box released at rest on a 20 degree slope with mu = 0.5 stays put: x = $(tail -1 "$tmp/rows.csv" | cut -d, -f2) at t = 10"
want=$(awk 'BEGIN { g = 9.81; th = 20 * 3.14159265358979323846 / 180; a = g * (sin(th) - 0.2 * cos(th))
    printf "%.17g", -a * 50 }')
"$eomc" run "$box" --set th=$th20 --set mu=0.2 --set v0=0 --t-end 10 $tight \
  > "$tmp/rows.csv"; st=$?
got=$(tail -1 "$tmp/rows.csv" | cut -d, -f2)
[ $st -eq 0 ] && awk -v g="$got" -v w="$want" 'BEGIN { e = (g - w) / w; if (e < 0) e = -e; exit !(e <= 1e-12) }'
ok $? "with mu = 0.2 it slides down: x(10) = -a 10^2/2 = $want, a = g (sin th - mu cos th) ($got)"

# the tilted floor: speeds along the slope 0 but for rounding at the start
# are at rest (stick.h's sign), so the corners start stuck, and stay: no
# flip, and the centre moves along the normal n = (sin th, 0, cos th)
# alone (its distance along the slope, x cos th - z sin th, as it started).
# Read a speed of 1e-20's sign instead, the run flipped all eight at
# t = 1.5e-20.
"$eomc" run "$src/tests/cli/cfric_tilt.yaml" $tight --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
along=$(awk -F, -v th="$th20" 'NR == 2 { s0 = $2 * cos(th) - $4 * sin(th) }
    NR > 1 { e = $2 * cos(th) - $4 * sin(th) - s0; if (e < 0) e = -e; if (e > most) most = e }
    END { printf "%.3g", most }' "$tmp/rows.csv")
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 1 ] && [ "$(wc -l < "$tmp/rows.csv")" -eq 12 ] &&
  awk -v e="$along" 'BEGIN { exit !(e <= 1e-15) }'
ok $? "a box on a slope bounced along its normal starts stuck and stays: no flip ($(($(wc -l < "$tmp/ev.csv") - 1)) events), its centre moved along the slope by $along (h = 0.05)"

# the pull: held until pull t = mu N, the four corners letting go at once
"$eomc" run "$box" --set pull=3 --set v0=0 --t-end 3 $tight --events "$tmp/ev.csv" \
  > "$tmp/rows.csv"; st=$?
go=$(awk -F, '$2 ~ /\.x\.stick$/ { print $1 "," $5 "," $8; exit }' "$tmp/ev.csv")
t1=${go%%,*}
held=$(awk -F, -v t="$t1" '$1 == t && $2 ~ /\.x\.stick$/' "$tmp/ev.csv" | wc -l)
want=$(echo "$go" | awk -F, '{ k = 1e5; c = 200; h = 0.05; N = 4 * (k * (h - $2) - c * $3)
    printf "%.17g %.17g", 0.3 * N / 3, N / (2 * 9.81) - 1 }')
got=$(tail -1 "$tmp/rows.csv" | cut -d, -f2,5)
close=$(awk 'BEGIN { ts = 0.3 * 2 * 9.81 / 3; printf "%.17g,%.17g", 3 * (3 - ts)^3 / 12, 3 * (3 - ts)^2 / 4 }')
[ $st -eq 0 ] && within "$t1" "${want% *}" 1e-14 && within "${want#* }" 0 1e-10 &&
  awk -v g="$got" -v w="$close" 'BEGIN { split(g, x, ","); split(w, y, ",")
      for (i = 1; i <= 2; i++) { e = (x[i] - y[i]) / y[i]; if (e < 0) e = -e; if (e > 1e-9) exit 1 } }' &&
  [ "$(awk -F, '$1 > 0 && $2 ~ /\.x\.stick$/' "$tmp/ev.csv" | awk -F, '{ print $1 }' | sort -u | wc -l)" -eq 1 ] &&
  [ "$held" -eq 4 ]
ok $? "a box pulled by pull t from rest is held until pull t = mu N, t = $t1 (mu N / pull = ${want% *}, N / m g - 1 = ${want#* }), its four lower corners letting go at once, each listed ($held flips at that instant), then x(3), x'(3) = $close ($got)"

# the ball: sliding, then rolling.  It rests at depth m g / k, its
# contact point rho = r - m g / k below its centre, where friction mu m g
# slows it (x'' = -mu g) and spins it (phi'' = rho mu m g / I) until x' =
# rho phi': from t = v0 / (mu g (1 + m rho^2 / I)) (2 v0 / (7 mu g) were
# rho r), on at x' = v0 - mu g t
want=$(awk 'BEGIN { m = 1.5; g = 9.81; k = 1e5; r = 0.1; v0 = 2; mu = 0.2; rho = r - m * g / k
    t = v0 / (mu * g * (1 + 2.5 * (rho / r) ^ 2)); printf "%.17g %.17g", t, v0 - mu * g * t }')
"$eomc" run "$ball" $tight --events "$tmp/ev.csv" > "$tmp/rows.csv"; st=$?
roll=$(awk -F, '$2 == "floor.ball.floor.x.stick" { print $1 "," $6 }' "$tmp/ev.csv")
nmg=$(awk -F, 'NR > 1 { e = $12 / (1.5 * 9.81) - 1; if (e < 0) e = -e; if (e > w) w = e } END { printf "%.2g", w }' "$tmp/rows.csv")
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/ev.csv")" -eq 3 ] &&
  within "${roll%,*}" "${want% *}" 1e-12 && within "${roll#*,}" "${want#* }" 1e-12 &&
  awk -F, -v t="${roll%,*}" 'NR > 1 && $1 > t { s = $11; if (s < 0) s = -s; if (s > 1e-9 * 2) bad = 1 }
      END { exit bad }' "$tmp/rows.csv" &&
  awk -v e="$nmg" 'BEGIN { exit !(e <= 1e-8) }'
ok $? "a ball slid at v0 rolls from t = v0/(mu g (1 + m rho^2/I)) = ${want% *} at v0 - mu g t = ${want#* } ($roll), its contact point stuck after (|x' - z phi'| <= 1e-9 v0), its normal force m g to $nmg"

# the ball on a 20 degree slope: rolling at mu = 0.2, sliding at mu = 0.05
fine=0 got=
for mu in 0.2 0.05; do
  want=$(awk -v mu=$mu 'BEGIN { g = 9.81; th = 20 * 3.14159265358979323846 / 180
      rho = 0.1 - 1.5 * g * cos(th) / 1e5; s = 1 + 0.4 * (0.1 / rho) ^ 2
      a = mu >= sin(th) / cos(th) * (s - 1) / s ? g * sin(th) / s : g * (sin(th) - mu * cos(th))
      printf "%.17g", a * 2 }')
  "$eomc" run "$ball" --set th=$th20 --set mu=$mu --set v0=0 --t-end 2 $tight \
    > "$tmp/rows.csv" || continue
  x=$(tail -1 "$tmp/rows.csv" | cut -d, -f2)
  awk -v g="$x" -v w="$want" 'BEGIN { e = (g - w) / w; if (e < 0) e = -e; exit !(e <= 1e-12) }' &&
    fine=$((fine + 1)) got="$got mu = $mu: x(2) = $x, 2 a = $want;"
done
[ $fine -eq 2 ]
ok $? "a ball on a 20 degree slope rolls at g sin th / s, s = 1 + I / (m rho^2) (5/7 g sin th were rho r), where mu >= (1 - 1/s) tan th, slides at g (sin th - mu cos th) where not ($got)"

# the ball dropped from z = 0.3 while sliding at v0 without spin.  Its
# contact point is on the floor, z below the centre, so as the ball sinks
# and rises the stuck point's speed x' - z phi' asks for a force of its
# own: each landing slides, sticks, and lets go before the ball leaves
# the floor (m r x' + I phi' is no longer conserved through a bounce, as
# it was with the point r below the centre).  What holds exactly: the
# point's speed is 0 (from the state: |x' - z phi'| <= 1e-9 v0) at every
# stick flip, on and off; the ball ends on the floor (its bounces and then
# its sway in the floor's spring, damped at c / 2m = 33/s, die out by t =
# 1.9) at its resting depth r - m g / k, rolling (x' = z phi', constant)
# under N = m g; and
# the reference solution, in extended precision, flips as the run does
# (no warning from --error).
"$eomc" run "$ball" --init z=0.3 --t-end 2 --dt 0.01 $tight --events "$tmp/ev.csv" \
  > "$tmp/rows.csv" 2> /dev/null; st=$?
first=$(awk -F, '$2 == "floor.ball.floor.x.stick" { print $1; exit }' "$tmp/ev.csv")
lands=$(awk -F, '$2 == "floor.ball.floor.touch"' "$tmp/ev.csv" | wc -l)
last=$(tail -1 "$tmp/ev.csv" | cut -d, -f1)
worst=$(awk -F, '$2 == "floor.ball.floor.x.stick" { s = $6 - $4 * $8; s = s < 0 ? -s : s
    if (s > w) w = s; n++ } END { printf "%.2g %d", w / 2, n }' "$tmp/ev.csv")
rest=$(awk -F, 'NR > 1 && $1 >= 1.9 { s = $5 - $3 * $7; s = s < 0 ? -s : s
    z = ($3 - (0.1 - 1.5 * 9.81 / 1e5)) / 0.1; z = z < 0 ? -z : z; n = $12 / (1.5 * 9.81) - 1
    n = n < 0 ? -n : n; if (!rows++) v = $5; d = ($5 - v) / v; d = d < 0 ? -d : d
    if (s > ws) ws = s; if (z > wz) wz = z; if (n > wn) wn = n; if (d > wd) wd = d }
    END { printf "%.2g %.2g %.2g %.2g %d", ws / 2, wz, wn, wd, rows }' "$tmp/rows.csv")
"$eomc" run "$ball" --init z=0.3 --t-end 2 --rtol 1e-10 --atol 1e-10 --error > /dev/null \
  2> "$tmp/err"; st2=$?
[ $st -eq 0 ] && [ $st2 -eq 0 ] && [ "$lands" -ge 6 ] && [ -n "$first" ] &&
  awk -v w="$worst" -v r="$rest" 'BEGIN { split(w, x, " "); split(r, y, " ")
      exit !(x[1] <= 1e-9 && x[2] >= 2 * 6 && y[1] <= 1e-9 && y[2] <= 1e-9 && y[3] <= 1e-8 &&
             y[4] <= 1e-12 && y[5] >= 10) }' &&
  ! grep -q warning "$tmp/err"
ok $? "a ball dropped while sliding at v0 bounces ($lands touches), its point stuck from t = $first with speed 0 at each stick flip (|x' - z phi'|/v0, flips: $worst), and ends rolling on the floor (last flip at t = $last; over t >= 1.9: |x' - z phi'|/v0, depth, N/(m g) - 1, x' change, rows: $rest); the reference flipping as the run does$(grep -m1 warning "$tmp/err")"

# units: the dropped ball with its units of mass, length and time
# rescaled (m M, r L, g L/T^2, k M/T^2, c M/T, v0 L/T, z L, times T) at
# rtol 1e-10 and atol 0 (no unit): the same flips in the same order, and
# their times and states, in the units, the same to 1e-10 of their scale
# (the steps may differ by rounding, so the rows by what the tolerance
# allows)
units() { awk -v M=$1 -v L=$2 -v T=$3 'BEGIN { printf "--set m=%.17g --set r=%.17g --set g=%.17g --set k=%.17g --set c=%.17g --set v0=%.17g --init z=%.17g --t-end %.17g --dt %.17g", 1.5 * M, 0.1 * L, 9.81 * L / (T * T), 1e5 * M / (T * T), 100 * M / T, 2 * L / T, 0.3 * L, T, 0.25 * T }'; }
fine=0 got=
for u in "1 1 1" "1e6 1e-3 1e3" "1e-9 1e5 1e-4" "1e12 1e6 1e-6"; do
  set -- $u
  "$eomc" run "$ball" $(units $1 $2 $3) --rtol 1e-10 --atol 0 --events "$tmp/ev.csv" \
    > /dev/null 2>&1 || continue
  awk -F, -v L=$2 -v T=$3 'NR > 1 { printf "%s %.17g", $2, $1 / T
      split(L " " L " 1 " L / T " " L / T " " 1 / T, unit, " ")
      for (i = 3; i <= 8; i++) printf " %.17g", $i / unit[i - 2]; print "" }' "$tmp/ev.csv" \
    > "$tmp/units_$1.txt"
  [ "$1" = 1 ] && { fine=$((fine + 1)); continue; }
  du=$(paste -d' ' "$tmp/units_1.txt" "$tmp/units_$1.txt" | awk '{ if ($1 != $9) bad = 1
        for (i = 2; i <= 8; i++) { d = $i - $(i + 8); d = d < 0 ? -d : d; s = $i < 0 ? -$i : $i
          s = s > 1 ? s : 1; if (d / s > m) m = d / s } }
      END { if (bad || NR == 0) print "differ"; else printf "%.2g", m }')
  [ "$(wc -l < "$tmp/units_1.txt")" -eq "$(wc -l < "$tmp/units_$1.txt")" ] &&
    awk -v d="$du" 'BEGIN { exit !(d != "differ" && d <= 1e-10) }' && fine=$((fine + 1))
  got="$got M, L, T = $1, $2, $3: $du;"
done
[ $fine -eq 4 ] && [ "$(wc -l < "$tmp/units_1.txt")" -ge 20 ]
ok $? "units rescaled: the dropped ball's $(wc -l < "$tmp/units_1.txt") flips the same, at the same times and states in its units ($got)"

# --error against the closed form: the box at rest at the end, every
# entry of its state known (x = d, z at its resting depth, speeds 0)
fine=0 got=
for e in 6 9; do
  "$eomc" run "$box" --method rkf45 --rtol 1e-$e --atol 1e-$e --error --stats \
    > "$tmp/run.csv" 2> "$tmp/err" || continue
  true=$(tail -1 "$tmp/run.csv" | awk -F, -v d="$d" '{ zr = 0.05 - 2 * 9.81 / 4e5
      e[1] = $2 - d; e[2] = $3; e[3] = $4 - zr; e[4] = $5; e[5] = $6; e[6] = $7
      for (i = 1; i <= 6; i++) { a = e[i] < 0 ? -e[i] : e[i]; if (a > w) w = a }; printf "%.3g", w }')
  said=$(awk '$1 == "error_end" { printf "%.3g", $2 }' "$tmp/err")
  ! grep -q warning "$tmp/err" && awk -v t="$true" -v s="$said" 'BEGIN { exit !(s >= 0.9 * t && s <= 1.1 * t) }' &&
    fine=$((fine + 1)) got="$got 1e-$e: $said against $true;"
done
[ $fine -eq 2 ]
ok $? "--error on the box says the error the closed form says ($got)"

# the box dropped onto the floor while pulled: its corners, landing at
# x' > 0, stick at t = 0.17015 (x.slip). rkf45's flip there differs from
# a tight run's (rk8pd, 1e-13) by 1.3e-6 at 1e-5 down to 3.8e-11 at 1e-10:
# as much as the run's error at the flip explains, which --error measures
# there (the run's state against the reference's, carried along the
# reference's rate to the run's time) and no longer takes from the rows
# before it alone (t = 0: no error yet), where it warned that the flips
# parted at 1e-7, 1e-9 and 1e-10. Checked: no warning at 1e-5 .. 1e-10,
# and the flip's times converge to the tight run's (10^4 closer at 1e-10
# than at 1e-5)
drop="--init z=0.1 --set pull=2 --set v0=0 --t-end 3"
# shellcheck disable=SC2086 # $drop is a list of options
"$eomc" run "$box" --method rk8pd --rtol 1e-13 --atol 1e-13 $drop --events "$tmp/tight.csv" \
  -o /dev/null 2> "$tmp/err"; st=$?
fine=0 got= first= last=
for e in 5 7 9 10; do
  # shellcheck disable=SC2086
  "$eomc" run "$box" --method rkf45 --rtol 1e-$e --atol 1e-$e $drop --error \
    --events "$tmp/ev.csv" -o /dev/null 2> "$tmp/err$e" || continue
  d=$(awk -F, 'NR == FNR { if ($2 ~ /v1\.x\.slip$/ && $1 > 0.15 && w == "") w = $1; next }
      $2 ~ /v1\.x\.slip$/ && $1 > 0.15 && g == "" { g = $1 }
      END { d = g - w; if (g == "" || w == "") print "none"; else printf "%.3g", d < 0 ? -d : d }' \
      "$tmp/tight.csv" "$tmp/ev.csv")
  [ -n "$first" ] || first=$d
  last=$d
  ! grep -q warning "$tmp/err$e" && [ "$d" != none ] && fine=$((fine + 1))
  got="$got 1e-$e: $d;"
done
[ $st -eq 0 ] && [ $fine -eq 4 ] &&
  awk -v a="$first" -v b="$last" 'BEGIN { exit !(a > 0 && b <= 1e-4 * a) }'
ok $? "the box dropped while pulled: rkf45's flips agree with the reference's, no warning, the x.slip flip apart from a tight run's by$got ($(grep -h warning "$tmp"/err5 "$tmp"/err7 "$tmp"/err9 "$tmp"/err10 | head -1 | cut -c1-200))"

# eomc accuracy on the box dropped while sliding (z = 0.1, x' = 3: it lands,
# bounces on its compliant floor, slides, stops): each run's error_max is
# its true largest error over the rows, within 10%, the truth taken from
# a run of another method far tighter (rk8pd at 1e-13), and the errors
# fall at least 100-fold from 1e-6 to 1e-9, for rkf45 and rk8pd
"$eomc" accuracy "$box" --methods rkf45,rk8pd --tolerances 1e-6,1e-9 --init z=0.1 \
  --csv "$tmp/acc.csv" > /dev/null 2> "$tmp/err"; st=$?
"$eomc" run "$box" --method rk8pd --rtol 1e-13 --atol 1e-13 --init z=0.1 -o "$tmp/truth.csv" \
  2> /dev/null
fine=0 got=
for meth in rkf45 rk8pd; do
  for e in 6 9; do
    "$eomc" run "$box" --method $meth --rtol 1e-$e --atol 1e-$e --init z=0.1 \
      -o "$tmp/r.csv" 2> /dev/null
    true=$(paste -d, "$tmp/r.csv" "$tmp/truth.csv" | awk -F, 'NR > 1 { n = NF / 2
        for (i = 2; i <= n; i++) { d = $i - $(i + n); if (d < 0) d = -d; if (d > m) m = d } }
        END { printf "%.4g", m }')
    said=$(awk -F, -v m=$meth -v tol=1e-0$e '$1 == m && $2 == tol { printf "%.4g", $10 }' \
      "$tmp/acc.csv")
    eval "true_${meth}_$e=$true"
    awk -v t="$true" -v s="$said" 'BEGIN { exit !(t > 0 && s / t < 1.1 && t / s < 1.1) }' &&
      fine=$((fine + 1))
    got="$got $meth 1e-$e: $said (true $true);"
  done
done
[ $st -eq 0 ] && [ $fine -eq 4 ] &&
  awk -v a="$true_rkf45_6" -v b="$true_rkf45_9" -v c="$true_rk8pd_6" -v d="$true_rk8pd_9" \
    'BEGIN { exit !(b <= a / 100 && d <= c / 100) }'
ok $? "eomc accuracy on the box dropped while sliding: error_max as the truth says ($got)$(why $st "$tmp/err")"

# the box that can turn (cfric_yaw.yaml), pulled by pull*t off its centre
# at (0, y0): its eight items' rows have rank 3, so the holding is not
# unique. It holds while some sharing keeps every corner's force within
# its bound, and breaks away where none does: at the largest pull the
# corners' friction can balance, a linear program solved here by its
# vertices (awk below), 0.3 * 2 * 9.81 * 0.3 / (y0 + 0.1) for y0 >= 0.2.
# Least-norm shares (the proportional sharing of rows alike) put one
# corner at its bound first, at t = 3.27 for y0 = 0.4, where the run
# stopped (exit 3: the corner let go, held still by the others' rows).
yaw="$src/tests/cli/cfric_yaw.yaml"
cat > "$tmp/lp.awk" <<'LP'
# The largest pull P that the four corners' friction can hold (each force
# component within [-B, B], B = mu m g / 4), a linear program solved by its
# vertices: the three equilibrium equations (sum fx = P, sum fy = 0, the
# moment about the vertical through the centre, sum (x fy - y fx) = y0 P)
# with six of the eight components at +-B, for the other two and P
# (Cramer's rule); the largest P whose two free components are in bounds.
BEGIN {
  B = mu * m * g / 4
  cx[1] = a; cy[1] = b; cx[2] = -a; cy[2] = b; cx[3] = -a; cy[3] = -b; cx[4] = a; cy[4] = -b
  for (i = 1; i <= 4; i++) {          # columns: fx_i, fy_i, then P
    A[1, i] = 1; A[2, i] = 0; A[3, i] = -cy[i]
    A[1, 4 + i] = 0; A[2, 4 + i] = 1; A[3, 4 + i] = cx[i]
  }
  A[1, 9] = -1; A[2, 9] = 0; A[3, 9] = -y0
  best = -1
  for (p = 1; p <= 8; p++) for (q = p + 1; q <= 8; q++) for (s = 0; s < 64; s++) {
    for (r = 1; r <= 3; r++) rhs[r] = 0
    k = 0
    for (i = 1; i <= 8; i++) {
      if (i == p || i == q) continue
      sg = int(s / 2 ^ k) % 2 ? -B : B; k++
      for (r = 1; r <= 3; r++) rhs[r] -= A[r, i] * sg
    }
    for (r = 1; r <= 3; r++) { M[r, 1] = A[r, p]; M[r, 2] = A[r, q]; M[r, 3] = A[r, 9] }
    det = det3(M)
    if (det * det < 1e-24) continue
    for (c = 1; c <= 3; c++) {
      for (r = 1; r <= 3; r++) for (cc = 1; cc <= 3; cc++) N[r, cc] = cc == c ? rhs[r] : M[r, cc]
      x[c] = det3(N) / det
    }
    if (x[1] * x[1] <= B * B * (1 + 1e-12) && x[2] * x[2] <= B * B * (1 + 1e-12) && x[3] > best)
      best = x[3]
  }
  printf "%.17g\n", best
}
function det3(T) {
  return T[1,1] * (T[2,2] * T[3,3] - T[2,3] * T[3,2]) - T[1,2] * (T[2,1] * T[3,3] - T[2,3] * T[3,1]) \
         + T[1,3] * (T[2,1] * T[3,2] - T[2,2] * T[3,1])
}
LP
fine=0 got=
for y0 in 0.4 1.0; do
  want=$(awk -v m=2 -v g=9.81 -v mu=0.3 -v a=0.2 -v b=0.1 -v y0=$y0 -f "$tmp/lp.awk")
  "$eomc" run "$yaw" --set y0=$y0 --rtol 1e-10 --atol 1e-12 --events "$tmp/yev.csv" \
    -o /dev/null 2> "$tmp/err"; st=$?
  first=$(awk -F, 'NR == 2 { print $1; exit }' "$tmp/yev.csv")
  [ $st -eq 0 ] && awk -v t="$first" -v w="$want" 'BEGIN { d = t - w; if (d < 0) d = -d
      exit !(t != "" && d <= 1e-9 * w) }' && fine=$((fine + 1))
  got="$got y0 = $y0: at t = $first, the program's $want (exit $st);"
done
[ $fine -eq 2 ]
ok $? "the box pulled off its centre holds until no sharing of its corners' forces can, then breaks away:$got$(why $st "$tmp/err")"

# pulled at y0 = 1, the box breaks away turning about its corners on the
# edge y = -b, v1 and v2, which stay stuck: their rows along x, (1, 0,
# -(x_i sin psi + y_i cos psi)) over (x, y, psi), are one row at psi = 0
# and part as the box turns (by 2 a sin psi). Held both, their forces grow
# as the condition of their system: they let go where its rank first
# counts them apart, where rounding says, and the run warns of it. The
# condition it names is cot^2(th/2), th the angle between the two rows in
# the metric M^-1 (M = diag(m, m, m, I), I = m (a^2 + b^2) / 3) at the
# psi of that let-go (--events).
"$eomc" run "$yaw" --set y0=1 --rtol 1e-10 --atol 1e-12 --t-end 2 --events "$tmp/yev.csv" \
  -o /dev/null 2> "$tmp/err"; st=$?
psi=$(awk -F, '$2 ~ /^floor\.block\.floor\.v[12]\.x\.stick$/ { print $6; exit }' "$tmp/yev.csv")
want=$(awk -v p="$psi" 'BEGIN { m = 2; a = 0.2; b = 0.1; I = m * (a * a + b * b) / 3
    s = sin(p); c = cos(p); b1 = -(a * s - b * c) / sqrt(I); b2 = -(-a * s - b * c) / sqrt(I)
    d = b1 - b2; if (d < 0) d = -d
    th = atan2(d / sqrt(m), 1 / m + b1 * b2); printf "%.6g", 1 / (sin(th / 2) / cos(th / 2))^2 }')
got=$(sed -n 's/.*warning: t = [0-9.]*: the stuck friction rows (floor.block.floor.v1.x, floor.block.floor.v2.x) at a let-go is ill-conditioned (condition \([0-9.e+]*\) at worst.*/\1/p' "$tmp/err")
[ $st -eq 0 ] && [ -n "$psi" ] && [ -n "$got" ] &&
  awk -v g="$got" -v w="$want" 'BEGIN { e = g / w - 1; if (e < 0) e = -e; exit !(e <= 0.03) }'
ok $? "the box pulled at y0 = 1: its corners v1 and v2 let go where rounding parts their rows, and the run warns: condition $got, cot^2(th/2) = $want at psi = $psi$(why $st "$tmp/err")"

# --error on the turning box left at rest (no pull): the exact motion is
# rest (x, y, psi and every speed 0, z at its resting depth); its
# velocities are rounding alone (its depth, in doubles, bounces by 1e-19
# m/s), and the reference once judged them against their own size: its
# steps fell to 1e-12 s and it never ended. It ends, and says the error
# the closed form says (1e-14).
"$eomc" run "$yaw" --set pull=0 --t-end 1 --rtol 1e-9 --atol 1e-12 --error --stats \
  > "$tmp/run.csv" 2> "$tmp/err"; st=$?
true=$(tail -1 "$tmp/run.csv" | awk -F, '{ zr = 0.05 - 2 * 9.81 / 4e5
    e[1] = $2; e[2] = $3; e[3] = $4 - zr; e[4] = $5; e[5] = $6; e[6] = $7; e[7] = $8; e[8] = $9
    for (i = 1; i <= 8; i++) { a = e[i] < 0 ? -e[i] : e[i]; if (a > w) w = a }; printf "%.3g", w }')
said=$(awk '$1 == "error_end" { printf "%.3g", $2 }' "$tmp/err")
[ $st -eq 0 ] && [ -n "$said" ] && ! grep -q warning "$tmp/err" &&
  awk -v t="$true" -v s="$said" 'BEGIN { exit !(t <= 1e-12 && s >= 0.9 * t && s <= 1.1 * t) }'
ok $? "--error on the turning box at rest ends and says the error the closed form says: $said against $true$(why $st "$tmp/err")"

# --atol 0 where the box at rest has coordinates and speeds exactly 0: no
# step can meet rtol times 0, so the steps collapse at t = 0 (exit 3);
# the message names the cause and the components, and with --atol 1e-12
# the same run goes through (exit 0)
"$eomc" run "$box" --rtol 1e-9 --atol 0 --set pull=2 --set v0=0 --t-end 3 -o /dev/null \
  2> "$tmp/err"; st=$?
"$eomc" run "$box" --rtol 1e-9 --atol 1e-12 --set pull=2 --set v0=0 --t-end 3 -o /dev/null \
  2> "$tmp/err2"; st2=$?
[ $st -eq 3 ] && [ $st2 -eq 0 ] &&
  grep -q "likely cause: --atol 0 asks each component for rtol of its own size, and x, y, x', y' and 1 more are 0 there" "$tmp/err"
ok $? "--atol 0 at a state with zeros: exit $st, the zeros named as the cause ($(head -c 260 "$tmp/err")), exit $st2 with --atol 1e-12$(why $st2 "$tmp/err2")"

"$eomc" run "$ball" --method taylor > /dev/null 2> "$tmp/err"; st=$?
[ $st -ne 0 ] && grep -q "dry friction" "$tmp/err"
ok $? "Taylor's method is refused by name (exit $st: $(head -c 160 "$tmp/err"))"

tap_end
