#!/bin/sh
# Contact effects (TAP): shapes that push each other apart where they
# overlap, N = where(d, max(0, k d + c d'), 0), each value against one
# computed here another way:
#  - tests/cli/contact_drop.yaml: a ball dropped from rest at h0 on a
#    plane.  Free fall to touchdown at t0 = sqrt(2 (h0 - r)/g); in
#    contact, the penetration d = x + m g/k with x the damped oscillator
#    x'' + 2 zeta w x' + w^2 x = 0, x(0) = -m g/k, x'(0) = g t0; the push
#    ends where k d + c d' = 0 (found by bisection), the touch where d
#    returns to 0 in free flight (the push's switch, watched only in
#    touch, on again there), and the apex is the ballistic one.  The near
#    switch turns on before touchdown, where the ball's sphere grown by
#    its margin (r/8) meets the floor.  Each error falls
#    as rtol tightens (1e-6, 1e-9, 1e-12).
#  - tests/cli/contact_box.yaml: a box, its centre of mass off-centre,
#    settles on its four lower corners; at rest their forces k d_i, the
#    d_i from the state's position and quaternion, sum to m g (1e-9) and
#    have no moment about the centre.
#  - tests/cli/contact_spheres.yaml: a head-on collision: momentum kept,
#    and the relative speed after is e v, e the law's restitution
#    (reduced mass mu: the damped oscillator's speed where k d + c d' = 0,
#    w_d t1 = pi - atan2(2 zeta sqrt(1 - zeta^2), 1 - 2 zeta^2)).
#  - tests/cli/contact_capsules.yaml: the rod resting across the log
#    (their axes crossed) at z = r1 + r2 - m g/k; the rod past the log's
#    end, its q'' from the gap to the end's sphere; the rod and a ball at
#    states around a slanted capsule (the nearest points inside the axes
#    or at an end), q'' = k d n/m + g against the gap from the segments'
#    nearest points found by cases (the lines' interior solution, each
#    end against the other segment); the lines' nearest point leaving the
#    rod's axis where the lines' parameter, from the event's state, is h2.
#  - tests/cli/contact_parallel.yaml: a rod 1e-9 and 1e-12 rad from
#    parallel to a log it lies on and to a rail it meets side on: q'' from
#    the gap at its lowest end (that end's distance to the other axis), no
#    clamp, interior or end switch flipping while the pair is close but the
#    log's ends' where they are equally far from the rod's; crossed at 90
#    and 30 degrees, q'' from the lines' distance.
#  - tests/cli/contact_probe.yaml and contact_planar.yaml: a capsule's
#    end spheres and an ellipsoid's lowest point on a tilted plane, a
#    planar bar on a line: q'' from the forces at the touching points and
#    their torques (the ellipsoid's point by a search over its surface).
#  - thrown fast (20 m/s) at the floor and at the other ball, where a
#    step may jump from far to deep in one go: the near switch flips
#    first and each touch is where the closed forms put it (the same
#    damped oscillator from the impact speed; for the balls, no gravity).
#  - the lazy code (--branches lazy, the default) and the code that
#    computes every branch (--branches eager) give the very same rows and
#    events on every scene here: the same operations, in their modes.
#  - the scene turns a contact off; a size of parameters --set below 0
#    is refused; the page's floor is the ground's plane.
# usage: test_contact.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
cli="$src/tests/cli"

# ---- the ball's drop
want=$(python3 - <<'EOF'
import math
m, r, g, k, c, h0 = 1.0, 0.1, 9.81, 1.0e4, 10.0, 0.5
t0 = math.sqrt(2 * (h0 - r) / g); v0 = g * t0
w = math.sqrt(k / m); z = c / (2 * m * w); wd = w * math.sqrt(1 - z * z)
A = -m * g / k; B = (v0 + z * w * A) / wd
def x(t): return math.exp(-z * w * t) * (A * math.cos(wd * t) + B * math.sin(wd * t))
def xd(t):
    return math.exp(-z * w * t) * ((-z * w * A + wd * B) * math.cos(wd * t)
                                   - (z * w * B + wd * A) * math.sin(wd * t))
def push(t): return k * (x(t) - A) + c * xd(t)
lo, step = 0.0, 1e-5 # the first sign change, then bisection
while push(lo + step) > 0: lo += step
hi = lo + step
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if push(mid) > 0: lo = mid
    else: hi = mid
t1 = 0.5 * (lo + hi)
d1, d1d = x(t1) - A, xd(t1)
s = (-d1d - math.sqrt(d1d * d1d - 2 * g * d1)) / g # d = 0 again, in free flight
tnear = math.sqrt(2 * (h0 - 1.125 * r) / g)
print("%.17g %.17g %.17g %.17g %.17g %.17g" % (t0 + t1 + s, t0, t0 + t1, t0 + t1 + s, r - d1 + d1d * d1d / (2 * g), tnear))
EOF
)
set -- $want - - - - - -
# (ton: the push on again, at the lift-off)
ton=$1 t0=$2 tpush=$3 ttouch=$4 apex=$5 tnear=$6
errs=""
for tol in 1e-6 1e-9 1e-12; do
  "$eomc" run "$cli/contact_drop.yaml" --rtol $tol --atol $tol --events "$tmp/ev$tol.csv" > /dev/null
  st=$?
  [ $st -eq 0 ] && [ "$(cut -d, -f2 "$tmp/ev$tol.csv" | tr '\n' ' ')" = "event ground_contact.ball.floor.near ground_contact.ball.floor.touch ground_contact.ball.floor.push ground_contact.ball.floor.touch ground_contact.ball.floor.push ground_contact.ball.floor.near apex " ]
  ok $? "rtol $tol: the switches ground_contact.ball.floor.touch and .push flip twice each (the push back on with the lift-off), between the near switch's flips, then the apex"
  errs="$errs $(awk -F, -v ton=$ton -v t0=$t0 -v tp=$tpush -v tt=$ttouch -v apex=$apex -v tn=$tnear '
      function a(x) { return x < 0 ? -x : x }
      NR == 2 { e[6] = a($1 - tn) }
      NR == 3 { e[2] = a($1 - t0) } NR == 4 { e[3] = a($1 - tp) } NR == 5 { e[4] = a($1 - tt) }
      NR == 6 { e[1] = a($1 - ton) } NR == 8 { e[5] = a($3 - apex) }
      END { printf "%.2g,%.2g,%.2g,%.2g,%.2g,%.2g", e[1], e[2], e[3], e[4], e[5], e[6] }' "$tmp/ev$tol.csv")"
done
set -- $errs - - -
# each error at 1e-12 within 1e-13 s (1e-12 m for the apex), and none
# larger than at the looser tolerance
echo "$1 $2 $3" | awk '{ n1 = split($1, a, ","); split($2, b, ","); split($3, c, ",")
    for (i = 1; i <= n1; i++) if (c[i] > b[i] * 1.01 + 1e-15 || b[i] > a[i] * 1.01 + 1e-15) exit 1
    for (i = 1; i <= 4; i++) if (c[i] > 1e-13) exit 1
    exit !(c[5] <= 1e-12 && c[6] <= 1e-13 && a[3] > 10 * c[3] && a[5] > 10 * c[5]) }'
ok $? "drop: near $tnear, touchdown $t0, push off $tpush (the contact's end), lift-off $ttouch, apex $apex; errors at rtol 1e-6 / 1e-9 / 1e-12: $1 / $2 / $3"

# ---- the box at rest: the corners' forces from the state
"$eomc" run "$cli/contact_box.yaml" > "$tmp/box.csv" 2> "$tmp/box.err"; st=$?
res=$(tail -1 "$tmp/box.csv" | python3 -c '
import math, sys
row = [float(v) for v in sys.stdin.read().split(",")]
x, y, z, e0, e1, e2, e3 = row[1:8]
w, ex, ey, ez = e0, e1, e2, e3
R = [[1 - 2 * (ey * ey + ez * ez), 2 * (ex * ey - w * ez), 2 * (ex * ez + w * ey)],
     [2 * (ex * ey + w * ez), 1 - 2 * (ex * ex + ez * ez), 2 * (ey * ez - w * ex)],
     [2 * (ex * ez - w * ey), 2 * (ey * ez + w * ex), 1 - 2 * (ex * ex + ey * ey)]]
a, b, h, k, m, g, floor = 0.2, 0.1, 0.05, 1000.0, 1.0, 9.81, -0.25
pos = [0.06, -0.03, 0.01]
F, Mx, My, n = 0.0, 0.0, 0.0, 0
for sx in (-1, 1):
    for sy in (-1, 1):
        for sz in (-1, 1):
            l = [pos[0] + sx * a, pos[1] + sy * b, pos[2] + sz * h]
            arm = [sum(R[i][j] * l[j] for j in range(3)) for i in range(3)]
            d = floor - (z + arm[2])
            if d > 0:
                n += 1; F += k * d; Mx += arm[1] * k * d; My -= arm[0] * k * d
print("%d %.3g %.3g" % (n, abs(F / (m * g) - 1), max(abs(Mx), abs(My)) / (m * g * a)))')
set -- $res - - -
[ $st -eq 0 ] && [ ! -s "$tmp/box.err" ] && [ "$1" = 4 ] && awk -v f=$2 -v mo=$3 'BEGIN { exit !(f <= 1e-9 && mo <= 1e-9) }'
ok $? "box at rest on $1 corners: sum k d_i = m g to $2, their moment about the centre $3 of m g a"
# at rest the switch functions' rates are rounding, which must not send
# each of the 16 switches on a dozen side steps per step in search of two
# crossings (436 046 right-hand sides for 479 steps before the search
# looked at how far from 0 the cubic through g and its rates turns)
"$eomc" run "$cli/contact_box.yaml" --stats > /dev/null 2> "$tmp/boxs.err"
steps=$(sed -n 's/^steps //p' "$tmp/boxs.err") evals=$(sed -n 's/^rhs_evals //p' "$tmp/boxs.err")
[ -n "$steps" ] && [ "$evals" -le $((40 * steps)) ]
ok $? "box at rest: $evals right-hand sides for $steps steps (at most 40 a step)"

# ---- two balls head-on
"$eomc" run "$cli/contact_spheres.yaml" > "$tmp/sph.csv"; st=$?
want=$(awk 'BEGIN { m1 = 1; m2 = 3; k = 1e4; c = 20; v = 2; mu = m1 * m2 / (m1 + m2)
    w = sqrt(k / mu); z = c / (2 * mu * w); wd = w * sqrt(1 - z * z); s = sqrt(1 - z * z)
    t1 = (3.14159265358979323846 - atan2(2 * z * s, 1 - 2 * z * z)) / wd
    e = exp(-z * w * t1) * (-z * w * sin(wd * t1) / wd + cos(wd * t1)); e = -e
    printf "%.17g %.17g %.17g", e, (m1 * v - m2 * e * v) / (m1 + m2), m1 * (1 + e) * v / (m1 + m2) }')
set -- $want - - -
last=$(tail -1 "$tmp/sph.csv")
v1=$(echo "$last" | cut -d, -f4) v2=$(echo "$last" | cut -d, -f5)
p=$(awk -v a=$v1 -v b=$v2 'BEGIN { printf "%.17g", a + 3 * b }')
[ $st -eq 0 ] && within "$p" 2 1e-13 && within "$v1" "$2" 1e-11 && within "$v2" "$3" 1e-11
ok $? "spheres: momentum kept ($p for 2), restitution e = $1: speeds after $v1, $v2 (closed form $2, $3)"

# ---- thrown fast: a step may jump from far to deep, the near switch
# flips first and the touch is where the closed forms put it
want=$(python3 - <<'EOF'
import math
m, r, g, k, c, h0, V = 1.0, 0.1, 9.81, 1.0e4, 10.0, 0.5, 20.0
t0 = (-V + math.sqrt(V * V + 2 * g * (h0 - r))) / g; v0 = V + g * t0
w = math.sqrt(k / m); z = c / (2 * m * w); wd = w * math.sqrt(1 - z * z)
A = -m * g / k; B = (v0 + z * w * A) / wd
def x(t): return math.exp(-z * w * t) * (A * math.cos(wd * t) + B * math.sin(wd * t))
def xd(t):
    return math.exp(-z * w * t) * ((-z * w * A + wd * B) * math.cos(wd * t)
                                   - (z * w * B + wd * A) * math.sin(wd * t))
def push(t): return k * (x(t) - A) + c * xd(t)
lo, step = 0.0, 1e-5
while push(lo + step) > 0: lo += step
hi = lo + step
for _ in range(200):
    mid = 0.5 * (lo + hi)
    if push(mid) > 0: lo = mid
    else: hi = mid
t1 = 0.5 * (lo + hi)
d1, d1d = x(t1) - A, xd(t1)
s = (-d1d - math.sqrt(d1d * d1d - 2 * g * d1)) / g
tnear = (-V + math.sqrt(V * V + 2 * g * (h0 - 1.125 * r))) / g
print("%.17g %.17g %.17g %.17g %.17g" % (tnear, t0, t0 + t1, t0 + t1 + s, t0 + t1 + s))
EOF
)
"$eomc" run "$cli/contact_drop.yaml" --init "z'=-20" --rtol 1e-12 --atol 1e-12 \
  --events "$tmp/fast.csv" > /dev/null; st=$?
err=$(echo "$want" | awk -F, 'NR == FNR { split($0, w, " "); next }
    FNR > 1 && FNR <= 6 { e = $1 - w[FNR - 1]; if (e < 0) e = -e; if (e > m) m = e }
    END { printf "%.2g", m }' - "$tmp/fast.csv")
# (the push's switch is watched only in touch: on at the start, off at
# the push's end, on again with the lift-off, at the same instant)
[ $st -eq 0 ] && [ "$(cut -d, -f2 "$tmp/fast.csv" | tr '\n' ' ')" = "event ground_contact.ball.floor.near ground_contact.ball.floor.touch ground_contact.ball.floor.push ground_contact.ball.floor.touch ground_contact.ball.floor.push ground_contact.ball.floor.near " ] &&
  awk -v e=$err 'BEGIN { exit !(e <= 1e-13) }'
ok $? "the ball thrown at the floor at 20 m/s: near, touchdown, push off, lift-off (the push on again) at the closed forms' times (largest error $err s; $want)"
want=$(awk 'BEGIN { m1 = 1; m2 = 3; k = 1e4; c = 20; v = 20; mu = m1 * m2 / (m1 + m2)
    w = sqrt(k / mu); z = c / (2 * mu * w); wd = w * sqrt(1 - z * z); s = sqrt(1 - z * z)
    t1 = (3.14159265358979323846 - atan2(2 * z * s, 1 - 2 * z * z)) / wd
    d1 = v / wd * exp(-z * w * t1) * sin(wd * t1)
    d1d = v * exp(-z * w * t1) * (cos(wd * t1) - z / s * sin(wd * t1))
    t0 = 0.2 / v; tnear = (0.2 - 0.125 * 0.3) / v
    printf "%.17g %.17g %.17g %.17g %.17g", tnear, t0, t0 + t1, t0 + t1 - d1 / d1d, t0 + t1 - d1 / d1d }')
"$eomc" run "$cli/contact_spheres.yaml" --set v=20 --events "$tmp/sfast.csv" > /dev/null; st=$?
err=$(echo "$want" | awk -F, 'NR == FNR { split($0, w, " "); next }
    FNR > 1 && FNR <= 6 { e = $1 - w[FNR - 1]; if (e < 0) e = -e; if (e > m) m = e }
    END { printf "%.2g", m }' - "$tmp/sfast.csv")
[ $st -eq 0 ] && [ "$(cut -d, -f2 "$tmp/sfast.csv" | tr '\n' ' ')" = "event bump.one.two.near bump.one.two.touch bump.one.two.push bump.one.two.touch bump.one.two.push bump.one.two.near " ] &&
  awk -v e=$err 'BEGIN { exit !(e <= 1e-13) }'
ok $? "the balls at 20 m/s: near, touch, push off, touch off (the push on again) at the closed forms' times (largest error $err s; $want)"

# ---- lazy and eager code: the very same rows and events
same=0 scenes=0
for spec in contact_drop contact_box contact_spheres contact_capsules contact_parallel contact_planar contact_probe; do
  for b in lazy eager; do
    "$eomc" run "$cli/$spec.yaml" --branches $b --events "$tmp/$b.ev" > "$tmp/$b.rows" 2> /dev/null
  done
  scenes=$((scenes + 1))
  [ -s "$tmp/lazy.rows" ] && cmp -s "$tmp/lazy.rows" "$tmp/eager.rows" &&
    cmp -s "$tmp/lazy.ev" "$tmp/eager.ev" && same=$((same + 1))
done
[ $same -eq $scenes ]
ok $? "--branches lazy and eager: the same rows and events, bit for bit, on $same of $scenes scenes"

# ---- capsules
"$eomc" run "$cli/contact_capsules.yaml" > "$tmp/cap.csv"; st=$?
zr=$(tail -1 "$tmp/cap.csv" | cut -d, -f4)
[ $st -eq 0 ] && within "$zr" 0.08019 1e-9
ok $? "a capsule at rest across another, crossed: z = r1 + r2 - m g/k = 0.08019 ($zr)"

# past the log's end (x = h1 + 0.03): the gap to its end's sphere, d =
# r1 + r2 - sqrt(0.03^2 + z^2), pushing along (0.03, 0, z)
"$eomc" run "$cli/contact_capsules.yaml" --accel --init x=0.53 --init z=0.05 > "$tmp/end.txt"
want=$(awk 'BEGIN { L = sqrt(0.03^2 + 0.05^2); N = 1000 * (0.09 - L)
    printf "x%s %.17g\nz%s %.17g\n", "'"''"'", N * 0.03 / L, "'"''"'", N * 0.05 / L - 9.81 }')
echo "$want" > "$tmp/end.want"
d=$(grep -E "^[xz]''" "$tmp/end.txt" | accel_diff "$tmp/end.want" /dev/stdin 2)
awk -v d=$d 'BEGIN { exit !(d <= 1e-13) }'
ok $? "past the log's end: q'' from the gap to its end's sphere (relative difference $d)"

# around the slanted capsule: each state's q'' against the segments'
# nearest points by cases
cat > "$tmp/seg.py" <<'EOF'
import math, sys
def quat_z(q):
    n = math.sqrt(sum(v * v for v in q)); w, x, y, z = [v / n for v in q]
    return [2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def add(a, b): return [a[i] + b[i] for i in range(3)]
def mul(s, a): return [s * v for v in a]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def on_segment(o, u, h, p):
    return add(o, mul(max(-h, min(h, dot(u, sub(p, o)))), u))
def nearest(oa, ua, ha, ob, ub, hb):
    cands = []
    r = sub(oa, ob); b = dot(ua, ub); c = dot(ua, r); f = dot(ub, r); den = 1 - b * b
    if den > 0:
        s = (b * f - c) / den; t = b * s + f
        if abs(s) <= ha and abs(t) <= hb:
            cands.append((add(oa, mul(s, ua)), add(ob, mul(t, ub))))
    for e in (-ha, ha):
        pa = add(oa, mul(e, ua)); cands.append((pa, on_segment(ob, ub, hb, pa)))
    for e in (-hb, hb):
        pb = add(ob, mul(e, ub)); cands.append((on_segment(oa, ua, ha, pb), pb))
    return min(cands, key=lambda p: dot(sub(p[1], p[0]), sub(p[1], p[0])))
k, m, g = 1000.0, 1.0, 9.81
o, u = [0.0, 3.0, 0.0], quat_z([0.8, 0.2, 0.3, 0.4])
x, y, z, bx, by, bz = [float(v) for v in sys.argv[1:7]]
pa, pb = nearest(o, u, 0.5, [x, y, z], [0.0, 1.0, 0.0], 0.3)
ball = on_segment(o, u, 0.5, [bx, by, bz])
out = []
for (p, q, r) in ((pa, pb, 0.09), (ball, [bx, by, bz], 0.12)):
    dv = sub(q, p); L = math.sqrt(dot(dv, dv)); N = k * max(0.0, r - L)
    out += [N * dv[0] / L / m, N * dv[1] / L / m, N * dv[2] / L / m - g]
for name, v in zip(("x", "y", "z", "bx", "by", "bz"), out):
    print("%s'' %.17g" % (name, v))
EOF
worst=0
# (the rod's nearest points: both inside the axes, at the rod's end, at
# the slant's, at both; the ball's: inside, at the slant's end; each gap
# 0.006 to 0.035)
for state in "0.23 2.94 0.32 0.06 2.99 0.2" "-0.33 2.67 -0.27 -0.41 3.11 -0.3" \
             "0.4 3.19 0.38 0.06 2.99 0.2" "0.37 2.59 0.38 -0.41 3.11 -0.3"; do
  set -- $state
  python3 "$tmp/seg.py" $state > "$tmp/seg.want"
  "$eomc" run "$cli/contact_capsules.yaml" --effects gravity,slant --accel --init x=$1 \
    --init y=$2 --init z=$3 --init bx=$4 --init by=$5 --init bz=$6 > "$tmp/seg.got"
  d=$(accel_diff "$tmp/seg.want" "$tmp/seg.got" 6)
  worst=$(awk -v a=$worst -v b=$d 'BEGIN { print (b == "nan" || b > a) ? b : a }')
done
awk -v d=$worst 'BEGIN { exit !(d <= 1e-12) }'
ok $? "capsule-capsule and sphere-capsule around a slanted capsule, 4 states: q'' from the nearest points by cases (largest relative difference $worst)"

# where each state's nearest points are: the two capsules' switches flip
# where the nearest point reaches an end
"$eomc" run "$cli/contact_capsules.yaml" --effects gravity,slant --init x=0.2 --init y=3.25 \
  --init z=0.3 --init "y'=-2" --t-end 0.4 --events "$tmp/slev.csv" > /dev/null; st=$?
# (the lines' nearest point of the rod's axis leaves it, .a.in, where
# the lines' s0, computed here from the event's state, is at the end)
s0=$(awk -F, '$2 == "slant.rod.slant.a.in" { print $3, $4, $5; exit }' "$tmp/slev.csv" |
  python3 -c '
import math, sys
exec(open(sys.argv[1]).read().split("k, m, g")[0])
x, y, z = [float(v) for v in sys.stdin.read().split()]
o, u = [0.0, 3.0, 0.0], quat_z([0.8, 0.2, 0.3, 0.4])
r = sub([x, y, z], o); b = u[1]; c = r[1]; f = dot(u, r)
print("%.17g" % abs((b * f - c) / (1 - b * b)))' "$tmp/seg.py")
[ $st -eq 0 ] && within "$s0" 0.3 1e-9
ok $? "a rod sliding along the slanted capsule: the lines' nearest point leaves the rod at its end, slant.rod.slant.a.in where |s0| = h2 = 0.3 ($s0)"

# ---- nearly parallel capsules (tests/cli/contact_parallel.yaml), tilted
# by 1e-9 and 1e-12 rad: the gap least at an end, conditioned whatever
# the angle (the lines' nearest points, x/den with den ~ angle^2, are
# rounding there), and crossing ones, whose gap is the lines' distance
cat > "$tmp/par.py" <<'EOF'
import math, re, sys
def qmul(a, b):
    w1, x1, y1, z1 = a; w2, x2, y2, z2 = b
    return (w1*w2 - x1*x2 - y1*y2 - z1*z2, w1*x2 + x1*w2 + y1*z2 - z1*y2,
            w1*y2 - x1*z2 + y1*w2 + z1*x2, w1*z2 + x1*y2 - y1*x2 + z1*w2)
def about(axis, a):
    q = [math.cos(a / 2), 0.0, 0.0, 0.0]; q[axis] = math.sin(a / 2); return q
def fmt(q): return "[%s]" % ", ".join("%.17g" % v for v in q)
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def cross(a, b): return [a[1]*b[2] - a[2]*b[1], a[2]*b[0] - a[0]*b[2], a[0]*b[1] - a[1]*b[0]]
k, m, g, r1, r2, h2 = 1000.0, 1.0, 9.81, 0.05, 0.04, 0.3
what, th = sys.argv[1], float(sys.argv[2])
if what == "spec":   # the spec turned by th: the rod about y, the rail about z
    lines = open(sys.argv[3]).read().split("\n")
    for i, l in enumerate(lines):
        if "# tilt" in l:
            q = qmul(about(3, th), about(2, math.pi / 2)) if "rail" in lines[i + 1] \
                else about(2, math.pi / 2 + th)
            lines[i + 1] = re.sub(r"quat: \[[^]]*\]", "quat: " + fmt(q), lines[i + 1])
    print("\n".join(lines)); sys.exit()
x, y, z = [float(v) for v in sys.argv[3:6]]
end2 = [x + h2 * math.cos(th), y, z - h2 * math.sin(th)]   # the rod's end at +x
if what in ("stack", "side"):   # that end's distance to the log's or rail's axis
    o, u = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]) if what == "stack" else \
           ([0.0, -0.2, 0.0], [math.cos(th), math.sin(th), 0.0])
    rel = sub(end2, o); foot = dot(rel, u); dv = [rel[i] - foot * u[i] for i in range(3)]
else:   # crossed: the lines' distance along n = ua x ub
    a = math.radians(float(what[5:]))
    n = cross([math.cos(th), 0.0, -math.sin(th)], [math.cos(a), math.sin(a), 0.0])
    s = dot([x, y, z], n) / dot(n, n); dv = [s * v for v in n]
L = math.sqrt(dot(dv, dv)); N = k * (r1 + r2 - L)
G = -g if what != "side" else 0.0
for name, v in zip(("x", "y", "z"), (N * dv[0] / L / m, N * dv[1] / L / m, N * dv[2] / L / m + G)):
    print("%s'' %.17g" % (name, v))
EOF
par_worst=0 par_flips= par_why=
for tilt in 1e-9 1e-12; do
  python3 "$tmp/par.py" spec $tilt "$cli/contact_parallel.yaml" > "$tmp/par.yaml"
  # q'' where the rod lies on the log (its end at +x the nearest), beside
  # the rail, and across 'cross' and 'cross30', at rest (no damping), against the closed forms
  for c in "stack gravity,stack 0.05 0.01 0.084" "side side 0.05 -0.118 0" \
           "cross90 gravity,cross 0.05 0.02 0.084" "cross30 gravity,cross30 0.05 0.02 0.084"; do
    set -- $c
    python3 "$tmp/par.py" $1 $tilt $3 $4 $5 > "$tmp/par.want"
    "$eomc" run "$tmp/par.yaml" --effects $2 --accel --init x=$3 --init y=$4 --init z=$5 --init "x'=0" \
      > "$tmp/par.got" 2> "$tmp/said" || par_why="$par_why$(why $? "$tmp/said")"
    d=$(accel_diff "$tmp/par.want" "$tmp/par.got" 3)
    par_worst=$(awk -v a=$par_worst -v b=$d 'BEGIN { print (b == "nan" || b > a) ? b : a }')
  done
  # the rod dropped on the log sliding along it at 0.2 m/s, and thrown at
  # the rail side on: while the pair is close, its touch and push flip and
  # no clamp, no interior nor end switch, but the log's ends' .b.end
  # where they are equally far from the rod's ends (e1 = e2, computed here
  # from the event's state: x = -1.5 z tilt, near 0)
  "$eomc" run "$tmp/par.yaml" --events "$tmp/par1.ev" > /dev/null; s1=$?
  "$eomc" run "$tmp/par.yaml" --effects side --init y=-0.05 --init z=0 --init "y'=-0.5" \
    --events "$tmp/par2.ev" > /dev/null; s2=$?
  f=$(awk -F, -v th=$tilt 'FNR == 1 { on = 0 }
      $2 ~ /\.close$/ { on = !on; tc = $1; next }
      $2 == "stack.pill.log.b.end" { c = 0.3 * cos(th); s = 0.3 * sin(th)
        e1 = ($3 - c + 0.5)^2 + ($5 + s)^2; e2 = (0.5 - $3 - c)^2 + ($5 - s)^2
        if ((e1 - e2)^2 <= (1e-12 * e1)^2) { ends++; next } }
      on && $1 != tc && $2 !~ /\.(touch|push)$/ { n++ }
      END { print n + 0 (ends == 1 ? "" : " (.b.end " ends + 0 ")") }' "$tmp/par1.ev" "$tmp/par2.ev")
  [ $s1 -eq 0 ] && [ $s2 -eq 0 ] && grep -q ',side\.pill\.rail\.touch,' "$tmp/par2.ev" ||
    f="$f (exit $s1 $s2)"
  par_flips="$par_flips $tilt: $f"
done
awk -v d=$par_worst 'BEGIN { exit !(d <= 1e-12) }'
ok $? "capsules 1e-9 and 1e-12 rad from parallel, resting and side on: q'' from the gap at the rod's end (its distance to the other axis); crossed at 90 and 30 degrees: from the lines' distance (largest relative difference $par_worst)$par_why"
[ "$par_flips" = " 1e-9: 0 1e-12: 0" ]
ok $? "nearly parallel capsules, the rod sliding on the log and thrown at the rail: no clamp, interior or end switch flips while close, the log's ends' .b.end once, where they are equally far from the rod's ends (flips:$par_flips)"

# ---- a capsule's end spheres and an ellipsoid on a tilted plane, and a
# planar bar on a line: q'' from the forces at the points that touch and
# their torques, the ellipsoid's lowest point found by a search over its
# surface (not the closed form)
cat > "$tmp/probe.py" <<'EOF'
import math, sys
def quat(q):
    n = math.sqrt(sum(v * v for v in q)); w, x, y, z = [v / n for v in q]
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
def mv(R, v): return [sum(R[i][j] * v[j] for j in range(3)) for i in range(3)]
def add(a, b): return [a[i] + b[i] for i in range(3)]
def sub(a, b): return [a[i] - b[i] for i in range(3)]
def mul(s, a): return [s * v for v in a]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def golden(f, lo, hi):
    g = (math.sqrt(5) - 1) / 2
    for _ in range(90):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(a) < f(b): hi = b
        else: lo = a
    return (lo + hi) / 2
k, m = 1000.0, 2.0
p0, n = [0.1, 0.2, 0.3], mv(quat([0.95, 0.2, -0.1, 0.05]), [0, 0, 1])
out = []
# the pill: its end spheres (radius 0.05, at +-0.2 along its axis)
c = [0.1, 0.2, 0.25]; o = add(c, [0.01, 0.02, 0.03]); u = mv(quat([0.9, 0.1, 0.3, 0.2]), [0, 0, 1])
F, T = [0, 0, 0], [0, 0, 0]
for e in (-0.2, 0.2):
    end = add(o, mul(e, u)); d = 0.05 - dot(n, sub(end, p0))
    if d > 0:
        f = mul(k * d, n); F = add(F, f); T = add(T, cross(sub(sub(end, mul(0.05, n)), c), f))
I = [0.1, 0.2, 0.3]
out += [F[i] / m for i in range(3)] + [T[i] / I[i] for i in range(3)]
# the egg: its surface o + A diag(a) s, |s| = 1, lowest along n by a search on the angles
c = [0.3, 0.1, 0.2]; o = add(c, [-0.02, 0.01, 0.0]); A = quat([0.8, 0.3, -0.2, 0.1]); a = [0.1, 0.2, 0.3]
def point(th, ph):
    s = [math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)]
    return add(o, mv(A, [a[i] * s[i] for i in range(3)]))
best = min(((dot(n, point(th, ph)), th, ph) for th in [i * math.pi / 60 for i in range(1, 60)]
            for ph in [j * math.pi / 60 for j in range(120)]))
th, ph = best[1], best[2]
for _ in range(40): # coordinate descent about the best sample
    th = golden(lambda t: dot(n, point(t, ph)), th - 0.1, th + 0.1)
    ph = golden(lambda f: dot(n, point(th, f)), ph - 0.1, ph + 0.1)
p = point(th, ph); d = -dot(n, sub(p, p0)); f = mul(k * d, n)
T = cross(sub(p, c), f); I = [0.3, 0.2, 0.25]
out += [f[i] / m for i in range(3)] + [T[i] / I[i] for i in range(3)]
for name, v in zip(("x''", "y''", "z''", "pwx'", "pwy'", "pwz'", "ex''", "ey''", "ez''", "ewx'", "ewy'", "ewz'"), out):
    print(name, "%.17g" % v)
EOF
python3 "$tmp/probe.py" > "$tmp/probe.want"
"$eomc" run "$cli/contact_probe.yaml" --accel --init x=0.1 --init y=0.2 --init z=0.25 --init ex=0.3 \
  --init ey=0.1 --init ez=0.2 > "$tmp/probe.got"; st=$?
d=$(accel_diff "$tmp/probe.want" "$tmp/probe.got" 12)
# (the search finds the lowest point to about 1e-8: a minimum's position
# is good to the square root of its value's rounding)
[ $st -eq 0 ] && awk -v d=$d 'BEGIN { exit !(d <= 1e-7) }'
ok $? "a capsule's end spheres and an ellipsoid's lowest point on a tilted plane: forces and torques (relative difference $d)"
awk 'BEGIN { k = 1000; c = 5; m = 2; I = 0.05; y = 0.02; th = 0.1; yd = -0.1; thd = 0.2
    for (e = -1; e <= 1; e += 2) { d = 0.05 - (y + e * 0.3 * sin(th)); dd = -(yd + e * 0.3 * cos(th) * thd)
        N = k * d + c * dd; F += N; T += e * 0.3 * cos(th) * N }
    q = sprintf("%c%c", 39, 39)
    printf "x%s 0\ny%s %.17g\nth%s %.17g\n", q, q, F / m, q, T / I }' > "$tmp/bar.want"
"$eomc" run "$cli/contact_planar.yaml" --accel --init y=0.02 --init th=0.1 --init "y'=-0.1" \
  --init "th'=0.2" > "$tmp/bar.got"; st=$?
d=$(accel_diff "$tmp/bar.want" "$tmp/bar.got" 3)
[ $st -eq 0 ] && awk -v d=$d 'BEGIN { exit !(d <= 1e-13) }'
ok $? "a planar bar on a line, both ends pushing with damping: y'' and th'' (relative difference $d)"

# ---- a box landing flat, tilted by 1e-19 rad: its four lower corners
# touch within a rounding of extended precision of each other (the
# reference's settled bracket), as a humanoid's two feet do.  Each
# touch turns on once (4 flips), in the run and in the reference,
# which must not read a corner flipped a rounding short of 0 as a second
# flip (it stopped, "chatters", before)
ok=0
for tilt in 3e-20 1e-19; do
  "$eomc" run "$cli/contact_box.yaml" --init e0=1 --init e1=$tilt --init e2=0 --t-end 2 \
    --error --stats -o /dev/null 2> "$tmp/flat$tilt" &&
    grep -q "^reference_switches 4$" "$tmp/flat$tilt" && grep -q "^switches 4$" "$tmp/flat$tilt" &&
    ! grep -q "warning\|error:" "$tmp/flat$tilt" || ok=1
done
[ $ok -eq 0 ]
ok $? "a box landing flat (tilt 3e-20, 1e-19 rad): 4 flips in the run and in its reference, no warning ($(grep error: "$tmp/flat1e-19" | head -c 160))"

# ---- the effect off: no switches, the ball falls through
"$eomc" run "$cli/contact_drop.yaml" --effects gravity --events "$tmp/off.csv" > "$tmp/off.rows"; st=$?
zend=$(tail -1 "$tmp/off.rows" | cut -d, -f2)
[ $st -eq 0 ] && within "$zend" "$(awk 'BEGIN { printf "%.17g", 0.5 - 9.81 * 0.36 / 2 }')" 1e-12 &&
  ! grep -q ground_contact "$tmp/off.csv"
ok $? "with the contact off, no switch: the ball falls through the floor (z = $zend)"

# a size of parameters is checked with the run's values too
"$eomc" run "$cli/contact_drop.yaml" --set r=-0.1 > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "shape 'ball': its size must be positive" "$tmp/err"
ok $? "--set r=-0.1: exit 2, the shape's size must be positive ($(head -1 "$tmp/err"))"
"$eomc" run "$cli/contact_drop.yaml" --set k=-1 > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] && grep -q "stiffness cannot be negative" "$tmp/err"
ok $? "--set k=-1: exit 2, the stiffness cannot be negative"

# ---- the page: the ground's plane is the floor
three=${EOMC_THREE_DIR:-/usr/share/javascript/three}
if [ -f "$three/three.min.js" ] && [ -f "$three/examples/js/controls/OrbitControls.js" ]; then
  "$eomc" run "$cli/contact_box.yaml" --t-end 1 --animate "$tmp/box.html" > /dev/null; st=$?
  fl=$(python3 "$cli/page_check.py" json "$tmp/box.html" floor)
  ns=$(python3 "$cli/page_check.py" json "$tmp/box.html" shapes | python3 -c 'import json, sys; print(len(json.load(sys.stdin)))')
  [ $st -eq 0 ] && [ "$fl" = -0.25 ] && [ "$ns" = 1 ]
  ok $? "the page's floor is the ground plane's height ($fl), the plane no shape of its own ($ns shape)"
else
  echo "ok $((n + 1)) # SKIP three.js is not installed (Debian: libjs-three)"; n=$((n + 1))
fi
tap_end
