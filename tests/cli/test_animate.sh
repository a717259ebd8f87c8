#!/bin/sh
# --animate FILE.html (TAP): a run's page, on the hand-written pendulum
# draw_model (tests/runtime/models.c: a particle, a body drawn as its
# equivalent box, a link, a trace, two outputs) built as rtsim-draw.
# The page: written beside an unchanged CSV, no FILE.tmp left; its JSON
# (the equivalent box's half-sizes from the inertia, a frame per row,
# the outputs); the size budget on a long run; the rows kept by a failed
# run (exit 3); the usage errors before any run (no three.js, nothing to
# draw, --animate with --accel).  `eomc run --animate` on real models:
# specs/double_pendulum.yaml (planar), specs/rolling_disk.yaml with
# lean's axes (3-D; the disk drawn as a disk of radius R),
# specs/precession.yaml (its box, the camera outside it; given by omega:
# alone, the warning that names the unturned body), a 3-D fall
# (tests/cli/animate_fall.yaml: its ground, a camera that follows) and
# tests/cli/animate_shapes.xml (MJCF geoms: a capsule, a box, a sphere;
# skipped if eomc has no MuJoCo).  In headless chromium (skipped without
# it): the page loads with no error and says it is ready; at two times
# each, where the CSV's coordinates put things (the test computes the
# positions from the coordinates and the model's geometry, projects them
# through the page's camera: page_check.py), the screenshot has their
# colours (the page's palette, a geom's rgba): rtsim-draw's bob and rod,
# the double pendulum's two bobs, the rolling disk's centre (default 3-D
# camera), its plane and lean's three axes, the precessing box's
# silhouette, the falling ball, the ground's grid at z = 0, the followed
# ball at the view's centre, and the MJCF's capsule (and its cap), box
# and ball; without WebGL, the page's text says so.
# usage: test_animate.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
sim="$build/tests/runtime/rtsim-draw" osc="$build/tests/runtime/rtsim-osc"
check="python3 $src/tests/cli/page_check.py"
three=${EOMC_THREE_DIR:-/usr/share/javascript/three}
if [ ! -f "$three/three.min.js" ] || [ ! -f "$three/examples/js/controls/OrbitControls.js" ]; then
    echo "1..0 # SKIP three.js is not installed (Debian: libjs-three)"
    exit 0
fi

# the page beside the CSV, which it leaves as it was
"$sim" -o "$tmp/plain.csv"
"$sim" -o "$tmp/p.csv" --animate "$tmp/p.html" 2> "$tmp/err"
ok $? "a run with --animate"
cmp -s "$tmp/plain.csv" "$tmp/p.csv"
ok $? "the CSV is the same with --animate"
[ -s "$tmp/p.html" ] && [ ! -e "$tmp/p.html.tmp" ] && [ ! -s "$tmp/err" ]
ok $? "the page written, no FILE.tmp left, nothing said"
grep -q 'REVISION' "$tmp/p.html" && grep -q 'var OrbitControls = function' "$tmp/p.html" && ! grep -qE '<script[^>]* src=' "$tmp/p.html"
ok $? "three.js inlined: no script loaded from elsewhere"
rows=$(($(wc -l < "$tmp/p.csv") - 1))
set -- $($check frames "$tmp/p.html")
[ "$1" = "$rows" ] && [ "$2" = 2 ]
ok $? "a frame per row, the last at t_end ($1 frames for $rows rows, the last at $2)"
half=$($check json "$tmp/p.html" items.2.solid.half)
[ "$half" = "[0.04, 0.5, 0.02]" ]
ok $? "the rod's equivalent box has its half-sizes, from its mass and inertia ($half)"
[ "$($check json "$tmp/p.html" outputs)" = '["x_bob", "y_bob"]' ] &&
[ "$($check json "$tmp/p.html" planar)" = true ] &&
[ "$($check json "$tmp/p.html" camera.up)" = '[0, 1, 0]' ]
ok $? "the outputs named; planar: the camera's up is y"

# the budget: 200 001 rows thinned to at most 20 000 frames and 4 MiB
"$sim" -o /dev/null --dt 1e-5 --animate "$tmp/long.html"
set -- $($check frames "$tmp/long.html")
[ "$1" -le 20000 ] && [ "$1" -ge 10000 ] && [ "$2" = 2 ] && [ "$3" -le 4194304 ]
ok $? "200001 rows thinned to the budget ($1 frames, the last at t = $2, $3 bytes)"

# a failed run's page has the rows its CSV kept
"$sim" -o "$tmp/f.csv" --max-steps 10 --animate "$tmp/f.html" 2> "$tmp/err"
st=$? rows=$(($(wc -l < "$tmp/f.csv") - 1))
set -- $($check frames "$tmp/f.html")
[ $st = 3 ] && [ "$1" = "$rows" ] && [ "$rows" -gt 0 ]
ok $? "a run that fails (exit $st) writes the rows kept ($1 frames, $rows rows)"

# usage errors, before the run: no page, no CSV
EOMC_THREE_DIR="$tmp/none" "$sim" -o "$tmp/u.csv" --animate "$tmp/u.html" 2> "$tmp/err"
st=$?
[ $st = 2 ] && grep -q 'libjs-three' "$tmp/err" && [ ! -e "$tmp/u.html" ] && [ ! -e "$tmp/u.csv" ]
ok $? "no three.js: exit 2 naming libjs-three, before the run ($(head -1 "$tmp/err"))"
"$osc" --animate "$tmp/u.html" > /dev/null 2> "$tmp/err"
st=$?
[ $st = 2 ] && grep -q 'this model has nothing to draw (no bodies or particles)' "$tmp/err" &&
    [ ! -e "$tmp/u.html" ]
ok $? "a model with nothing to draw: exit 2 ($(head -1 "$tmp/err"))"
"$sim" --accel --animate "$tmp/u.html" > /dev/null 2> "$tmp/err"
[ $? = 2 ] && grep -q 'does not take --accel' "$tmp/err"
ok $? "--animate with --accel: exit 2"
"$sim" --help | grep -q -- '--animate FILE.html'
ok $? "--help lists --animate"

# eomc run writes the pages of real specs: the double pendulum (planar:
# its two bobs, rods from the origin, bob2 traced), the rolling disk (3-D:
# its body as the equivalent box; here with `view: {frames: [lean]}`), and
# an imported MJCF's geoms (tests/cli/animate_shapes.xml: a capsule, a box
# and a sphere on two hinges)
"$eomc" run "$src/specs/double_pendulum.yaml" --t-end 4 -o "$tmp/dp.csv" \
    --animate "$tmp/dp.html" 2> "$tmp/err"
st=$?
[ $st = 0 ] && [ -s "$tmp/dp.html" ] && [ ! -s "$tmp/err" ] &&
[ "$($check json "$tmp/dp.html" items.1.name)" = '"bob2"' ] &&
[ "$($check json "$tmp/dp.html" links)" = '[[2, 0], [0, 1]]' ] &&
[ "$($check json "$tmp/dp.html" traces)" = '[1]' ] &&
[ "$($check json "$tmp/dp.html" planar)" = true ]
ok $? "eomc run specs/double_pendulum.yaml --animate: a planar page, its view's links and trace (exit $st)"
sed 's/^scene: {t_end: 10,/scene: {view: {frames: [lean]}, t_end: 10,/' \
    "$src/specs/rolling_disk.yaml" > "$tmp/rolling_disk.yaml"
"$eomc" run "$tmp/rolling_disk.yaml" --t-end 4 -o "$tmp/rd.csv" --animate "$tmp/rd.html" 2> "$tmp/err"
st=$?
[ $st = 0 ] && [ ! -s "$tmp/err" ] && grep -q 'frames: \[lean\]' "$tmp/rolling_disk.yaml" &&
[ "$($check json "$tmp/rd.html" planar)" = false ] &&
[ "$($check json "$tmp/rd.html" camera.up)" = '[0, 0, 1]' ] &&
[ "$($check json "$tmp/rd.html" axes)" = 1 ] &&
[ "$($check json "$tmp/rd.html" items.1.kind)" = '"frame"' ]
ok $? "eomc run rolling_disk --animate: a 3-D page (z up), lean's axes (exit $st)"
# its disk (moments m R^2/4, m R^2/4, m R^2/2) drawn as the uniform
# cylinder of them: radius R = 0.5 (I_axis = m r^2 / 2), thin (2 % of it)
solid=$($check json "$tmp/rd.html" items.0.solid.type)/$($check json "$tmp/rd.html" items.0.solid.half)
[ "$solid" = '"cylinder"/[0.5, 0.5, 0.01]' ]
ok $? "the rolling disk is drawn as a disk of radius R: $solid"
sed 's/^scene: {t_end: 10,/scene: {view: {frames: true}, t_end: 10,/' \
    "$src/specs/rolling_disk.yaml" > "$tmp/rolling_all.yaml"
"$eomc" run "$tmp/rolling_all.yaml" --t-end 0.1 -o /dev/null --animate "$tmp/ra.html" 2> "$tmp/err"
st=$?
nframes=$(awk '/^frames:/ { f = 1; next } /^[a-z]/ { f = 0 } f && /^  [a-z_]+:/' \
    "$src/specs/rolling_disk.yaml" | wc -l)
drawn=$($check json "$tmp/ra.html" items |
    python3 -c 'import json, sys; print(sum(i["kind"] == "frame" for i in json.load(sys.stdin)))')
[ $st = 0 ] && [ "$($check json "$tmp/ra.html" axes)" = 2 ] && [ "$drawn" = "$nframes" ] &&
    [ "$nframes" -ge 2 ]
ok $? "view: {frames: true}: every frame of the spec drawn ($nframes), and the bodies' own axes (axes 2)"
# the shipped precession spec: its body turned by z-x-z Euler angles, drawn
# as the uniform box of its mass 1 and moments A, B, C = 1, 1.5, 2
# (half-sizes a_i^2 = 3 (I_j + I_k - I_i) / 2), the camera outside it
"$eomc" run "$src/specs/precession.yaml" --t-end 3 -o "$tmp/pr.csv" --animate "$tmp/pr.html" \
    2> "$tmp/err"
st=$?
half=$($check json "$tmp/pr.html" items.0.solid.half)
reach=$($check json "$tmp/pr.html" items.0.reach)
set -- $($check json "$tmp/pr.html" camera.position | tr -d '[],')
cam=$(awk -v x="$1" -v y="$2" -v z="$3" 'BEGIN { print sqrt(x * x + y * y + z * z) }')
[ $st = 0 ] && [ ! -s "$tmp/err" ] && [ "$half" = "[1.93649, 1.5, 0.866025]" ] &&
    within "$reach" 2.598076 1e-5 && awk -v c="$cam" -v r="$reach" 'BEGIN { exit !(c > r) }'
ok $? "specs/precession.yaml --animate: its box $half, the camera $cam from its centre, outside its reach $reach (exit $st)"
# the same body given by its angular velocity alone: drawn unturned, and
# the page's writer says so, naming it
sed 's/^    rotation: {zxz: \[psi, theta, phi\]}.*/    omega: [p, q, r]/' "$src/specs/precession.yaml" \
    > "$tmp/prec_omega.yaml"
"$eomc" run "$tmp/prec_omega.yaml" --t-end 1 -o /dev/null --animate "$tmp/po.html" 2> "$tmp/err"
st=$?
grep -q '^    omega: \[p, q, r\]' "$tmp/prec_omega.yaml" && [ $st = 0 ] &&
    grep -q "warning: body 'body' is drawn unturned" "$tmp/err" &&
    [ "$($check json "$tmp/po.html" items.0.unturned)" = true ]
ok $? "a body given by omega: alone: its page is written with a warning naming it ($(head -1 "$tmp/err"))"
# shapes of parameters follow --set: the sleigh's blade is b behind its
# centre of mass (specs/chaplygin_sleigh.yaml); with b < 0 no size is
# positive: a warning, and the sleigh drawn as its solid instead
sleigh() { # sleigh B: the blade's position on the page with b = B
    "$eomc" run "$src/specs/chaplygin_sleigh.yaml" --t-end 0.1 --set b=$1 -o /dev/null \
        --animate "$tmp/cs.html" 2> "$tmp/err$1"
    $check json "$tmp/cs.html" shapes.1.pos 2> /dev/null
}
blade05=$(sleigh 0.5) blade1=$(sleigh 1)
sleigh -1 > /dev/null
[ "$blade05" = "[-0.5, 0, 0.015]" ] && [ "$blade1" = "[-1, 0, 0.03]" ] && [ ! -s "$tmp/err1" ] &&
    grep -q "warning: a shape of 'sleigh' has size \[-0.9, -0.3, -0.02\]" "$tmp/err-1" &&
    [ "$($check json "$tmp/cs.html" shapes)" = "[]" ] &&
    [ "$($check json "$tmp/cs.html" items.0.solid.type)" = '"cylinder"' ]
ok $? "the sleigh's blade follows --set b: at $blade05 for b = 0.5, at $blade1 for b = 1; b = -1: $(head -c 70 "$tmp/err-1")..."
# a 3-D fall (tests/cli/animate_fall.yaml, 5 m in 0.9 s): the ground is the
# model's, z = 0; the followed scene's camera follows the ball
for sc in fixed followed; do
    "$eomc" run "$src/tests/cli/animate_fall.yaml" --scene $sc -o "$tmp/fall_$sc.csv" \
        --animate "$tmp/fall_$sc.html" 2> "$tmp/err" || echo "# $sc: $(cat "$tmp/err")"
done
[ "$($check json "$tmp/fall_fixed.html" floor)" = 0 ] &&
    [ "$($check json "$tmp/fall_fixed.html" follow)" = -1 ] &&
    [ "$($check json "$tmp/fall_followed.html" follow)" = 0 ]
ok $? "a 3-D fall's page: the ground at z = 0; view: {follow: ball} follows item 0"

mjcf=0
"$eomc" import "$src/tests/cli/animate_shapes.xml" > /dev/null 2> "$tmp/err"
st=$?
if [ $st = 0 ] || ! grep -q 'libmujoco-dev' "$tmp/err"; then
    mjcf=1
    "$eomc" run "$src/tests/cli/animate_shapes.xml" --t-end 2 -o "$tmp/mj.csv" \
        --animate "$tmp/mj.html" 2> "$tmp/err"
    st=$?
    [ $st = 0 ] && [ ! -s "$tmp/err" ] &&
    [ "$($check json "$tmp/mj.html" shapes.0.type)/$($check json "$tmp/mj.html" shapes.1.type)/$($check json "$tmp/mj.html" shapes.2.type)" = 2/0/1 ]
    ok $? "eomc run MODEL.xml --animate: the geoms as shapes, a capsule, a box, a sphere (exit $st)"
else
    echo "ok $((n + 1)) # SKIP eomc import needs MuJoCo: $(head -1 "$tmp/err")"
    n=$((n + 1))
fi

# the page in a real browser
chromium=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$chromium" ]; then
    echo "ok $((n + 1)) # SKIP chromium is not installed"
    n=$((n + 1))
    tap_end
    exit $?
fi
W=800 H=600
browse() { # browse URL ARGS...: headless chromium, software WebGL
    url=$1
    shift
    "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
        --disable-background-networking --disable-component-update --disable-sync \
        --enable-unsafe-swiftshader --user-data-dir="$(mktemp -d "$tmp/profile.XXXXXX")" \
        --window-size=$W,$H --virtual-time-budget=5000 "$@" "$url" 2> /dev/null
}
browse "file://$tmp/p.html#t=0.5" --dump-dom > "$tmp/dom"
grep -q '<title>eomc ready</title>' "$tmp/dom" && grep -q '<pre id="errors"[^>]*></pre>' "$tmp/dom"
ok $? "the page loads in chromium, says it is ready, and has no error"
for t in 0.5 1.5; do
    browse "file://$tmp/p.html#t=$t" --screenshot="$tmp/shot$t.png" > /dev/null
    set -- $($check pixel "$tmp/p.html" "$tmp/shot$t.png" "$tmp/p.csv" $t x_bob y_bob 1 $W $H)
    echo "# t = $t: the bob projects to ($1, $2), its colour's centroid ($3, $4): $5 px, $6 px"
    within "$5" 0 3 && [ "$6" -ge 20 ]
    ok $? "t = $t: the bob is where the CSV puts it ($5 px off)"
    set -- $($check pixel "$tmp/p.html" "$tmp/shot$t.png" "$tmp/p.csv" $t \
        '0.5*sin(theta)' '-0.5*cos(theta)' 2 $W $H)
    echo "# t = $t: the rod's centre projects to ($1, $2), its colour's centroid ($3, $4): $5 px, $6 px"
    within "$5" 0 3 && [ "$6" -ge 100 ]
    ok $? "t = $t: the rod's centre is where the CSV puts it ($5 px off)"
done

# at() T EXPECT X Y Z COLOUR WHAT [R]: in the screenshot $shot of page
# $page at t = T, the point (X, Y, Z) (expressions of $csv's columns at
# T) projected through the page's camera by page_check.py: EXPECT centre,
# the centroid of COLOUR's pixels within R px (20) is within 3 px of it
# (with 20 pixels or more); EXPECT box, within 6 px (a box's visible
# faces are not symmetric about its centre), and the pixel at it is
# COLOUR's; EXPECT on, the pixel at it is COLOUR's; EXPECT off, it is not
at() {
    t=$1 expect=$2 what=$7
    set -- $($check at "$page" "$shot" "$csv" "$1" "$3" "$4" "$5" "$6" $W $H ${8:-20})
    echo "# t = $t: $what projects to ($1, $2), its colour's centroid ($3, $4): $5 px, $6 px, hit $7"
    case $expect in
    centre) within "$5" 0 3 && [ "$6" -ge 20 ] ;;
    box) within "$5" 0 6 && [ "$7" = 1 ] ;;
    on) [ "$7" = 1 ] ;;
    off) [ "$7" = 0 ] ;;
    esac
    case $expect in
    on) verdict="is drawn in its colour" ;;
    off) verdict="is not drawn in its colour" ;;
    *) verdict="is where the CSV puts it" ;;
    esac
    ok $? "t = $t: $what $verdict ($expect: $5 px, hit $7)"
}

# the double pendulum: th1 and th2 from the downward vertical, rods of
# length 1 (the spec's l1, l2); bob1 the palette's colour 0, bob2 its 1
page=$tmp/dp.html csv=$tmp/dp.csv
for t in 1.5 3; do
    shot=$tmp/dp$t.png
    browse "file://$page#t=$t" --screenshot="$shot" > /dev/null
    at $t centre 'sin(th1)' '-cos(th1)' 0 0 "the double pendulum's bob1"
    at $t centre 'sin(th1) + sin(th2)' '-cos(th1) - cos(th2)' 0 1 "the double pendulum's bob2"
done

# the rolling disk, through the default 3-D camera: its centre is R = 0.5
# above the contact (x, y, 0) along lean's y, lean = Rz(psi) Rx(theta);
# the equivalent solid of a thin disk (a disk of radius R) is the
# palette's colour 0.  The disk's plane: points 0.3 from the centre
# along lean's x and y are on it, 0.6 along lean's z are off it (t = 2.5,
# where it faces the camera).  lean's axes at the world's origin (three.js's
# AxesHelper, 0.15 extents long: x red, y green, z blue): along each, the
# pixels of its colour, and none along -z
page=$tmp/rd.html csv=$tmp/rd.csv
cx='x - 0.5*sin(psi)*cos(theta)' cy='y + 0.5*cos(psi)*cos(theta)' cz='0.5*sin(theta)'
lx='cos(psi)' ly='sin(psi)' lz=0
yx='-sin(psi)*cos(theta)' yy='cos(psi)*cos(theta)' yz='sin(theta)'
zx='sin(psi)*sin(theta)' zy='-cos(psi)*sin(theta)' zz='cos(theta)'
axis=$(awk -v e="$($check json "$page" extent)" 'BEGIN { print 0.15 * e }')
for t in 1 2.5; do
    shot=$tmp/rd$t.png
    browse "file://$page#t=$t" --screenshot="$shot" > /dev/null
    at $t centre "$cx" "$cy" "$cz" 0 "the rolling disk's centre"
    for a in "x $lx $ly $lz #ff0000" "y $yx $yy $yz #00ff00" "z $zx $zy $zz #0000ff" \
        "-z -($zx) -($zy) -($zz) #0000ff"; do
        set -- $a
        set -- "$1" $($check line "$page" "$shot" "$csv" $t 0 0 0 \
            "$axis*($2)" "$axis*($3)" "$axis*($4)" "$5" $W $H)
        echo "# t = $t: lean's $1 axis: $3 of $2 pixels along it of its colour"
        case $1 in
        -z) [ "$2" -ge 20 ] && [ "$3" = 0 ]
            ok $? "t = $t: nothing blue along lean's -z ($3 of $2 pixels)" ;;
        *) [ "$2" -ge 20 ] && [ "$3" -ge $(($2 * 9 / 10)) ]
            ok $? "t = $t: lean's $1 axis is drawn where the CSV turns it ($3 of $2 pixels)" ;;
        esac
    done
done
t=2.5
for s in 1 -1; do
    at $t on "$cx + $s*0.3*$lx" "$cy + $s*0.3*$ly" "$cz" 0 "a point 0.3*$s along lean's x from the disk's centre" 3
    at $t on "$cx + $s*0.3*$yx" "$cy + $s*0.3*$yy" "$cz + $s*0.3*$yz" 0 "a point 0.3*$s along lean's y from the disk's centre" 3
    at $t off "$cx + $s*0.6*$zx" "$cy + $s*0.6*$zy" "$cz + $s*0.6*$zz" 0 "a point 0.6*$s along lean's z from the disk's centre" 3
done

# precession at t = 2: the box's silhouette, the hull of its 8 corners
# turned by Rz(psi) Rx(theta) Rz(phi) of the CSV's angles and projected,
# is the body's colour (the palette's 0) inside it and not around it
page=$tmp/pr.html shot=$tmp/pr2.png
browse "file://$page#t=2" --screenshot="$shot" > /dev/null
set -- $($check box "$page" "$shot" "$tmp/pr.csv" 2 0 0 0 zxz:psi:theta:phi \
    1.936492 1.5 0.866025 0 $W $H)
echo "# t = 2: the box's silhouette: $2 of $1 pixels inside it, $4 of $3 around it are its colour"
[ "${1:-0}" -ge 10000 ] && [ "$2" -ge $(($1 * 95 / 100)) ] && [ "$3" -ge 10000 ] &&
    [ "$4" -le $(($3 / 100)) ]
ok $? "t = 2: the precessing body is drawn turned as the CSV's Euler angles turn it ($2 of $1 in, $4 of $3 out)"

# the fall at t = 0.9 (z = 5 - 9.81 0.9^2 / 2 = 1.03): the ball where the
# CSV puts it; the grid's line y = 0 lies in the ground z = 0 (pale grey
# pixels along its projection, x from -2 to 2, but where the ball hides
# it), few along the same line at the lowest point of the motion, where
# the grid used to be.  (Along x: from this camera the line x = 0 at that
# height projects close to the grid's line x = -1 at z = 0.)
page=$tmp/fall_fixed.html csv=$tmp/fall_fixed.csv shot=$tmp/fall.png
browse "file://$page#t=0.9" --screenshot="$shot" > /dev/null
at 0.9 centre 0 0 z 0 "the falling ball"
low=$(tail -1 "$csv" | cut -d, -f2)
for z in 0 "$low"; do
    set -- $z $($check line "$page" "$shot" "$csv" 0.9 -2 0 "$z" 2 0 "$z" grid $W $H)
    echo "# the line y = 0 at z = $1: $3 of $2 pixels along it are the grid's"
    if [ "$1" = 0 ]; then
        [ "$2" -ge 100 ] && [ "$3" -ge $(($2 * 3 / 4)) ]
        ok $? "the ground's grid lies in z = 0 ($3 of $2 pixels along y = 0)"
    else
        [ "$2" -ge 100 ] && [ "$3" -le $(($2 / 5)) ]
        ok $? "no grid at the motion's lowest point z = $1 ($3 of $2 pixels)"
    fi
done
# followed: the camera moves with the ball, which stays at the view's centre
shot=$tmp/fall_followed.png
browse "file://$tmp/fall_followed.html#t=0.9" --screenshot="$shot" > /dev/null
set -- $($check near "$tmp/fall_followed.html" "$shot" $((W / 2)) $((H / 2)) 0 60)
echo "# followed, t = 0.9: the ball's colour centred at ($1, $2), $3 px off the view's centre, $4 px"
within "$3" 0 3 && [ "$4" -ge 200 ]
ok $? "view: {follow: ball}: at t = 0.9 the ball is at the view's centre ($3 px off, $4 px)"

# without WebGL the page says so in its own text
browse "file://$tmp/p.html" --disable-webgl --dump-dom > "$tmp/dom"
grep -q '<title>eomc: no WebGL</title>' "$tmp/dom" &&
    grep -q "<div id=\"nowebgl\"[^>]*>This page draws the motion of 'drawn' with WebGL" "$tmp/dom" &&
    grep -q 'enable-unsafe-swiftshader' "$tmp/dom"
ok $? "without WebGL (--disable-webgl) the page's text says it needs WebGL: $(sed -n 's/.*<div id="nowebgl"[^>]*>\([^<]*\)<.*/\1/p' "$tmp/dom" | cut -c1-80)..."

# the MJCF's geoms in their rgba: hinge1 turns the arm about y at
# (0, 0, 1), R_y(q)(x, 0, z) = (x cos q + z sin q, 0, z cos q - x sin q);
# the capsule from the pivot to 0.6 along the arm (radius 0.05), a point
# 0.045 behind the pivot on its axis is on its cap; the box at 0.6; the
# ball 0.4 below the tip in the tip's axes, turned by hinge1 + hinge2
if [ $mjcf = 1 ]; then
    page=$tmp/mj.html csv=$tmp/mj.csv
    for t in 0.5 1; do
        shot=$tmp/mj$t.png
        browse "file://$page#t=$t" --screenshot="$shot" > /dev/null
        at $t centre '0.3*cos(hinge1)' 0 '1 - 0.3*sin(hinge1)' '#e61a1a' "the capsule's centre"
        at $t on '-0.045*cos(hinge1)' 0 '1 + 0.045*sin(hinge1)' '#e61a1a' "the capsule's cap at the pivot"
        at $t box '0.6*cos(hinge1)' 0 '1 - 0.6*sin(hinge1)' '#1ab31a' "the box's centre"
        at $t centre '0.6*cos(hinge1) - 0.4*sin(hinge1 + hinge2)' 0 \
            '1 - 0.6*sin(hinge1) - 0.4*cos(hinge1 + hinge2)' '#1a33e6' "the ball's centre"
    done
fi
tap_end
