#!/bin/sh
# --animate FILE.html (TAP): a run's page, on the hand-written pendulum
# draw_model (tests/runtime/models.c: a particle, a body drawn as its
# equivalent box, a link, a trace, two outputs) built as rtsim-draw.
# The page: written beside an unchanged CSV, no FILE.tmp left; its JSON
# (the equivalent box's half-sizes from the inertia, a frame per row,
# the outputs); the size budget on a long run; the rows kept by a failed
# run (exit 3); the usage errors before any run (no three.js, nothing to
# draw, --animate with --accel); `eomc run` passing it through.  In
# headless chromium (skipped without it): the page loads with no error
# and says it is ready, and at t = 0.5 and 1.5 the bob (a particle) and
# the rod's centre (a body) are at the pixels where the CSV's values put
# them through the page's camera (page_check.py projects them; the
# colours are the page's palette).
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
half=$($check json "$tmp/p.html" items.2.box.half)
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

# eomc run passes it to the simulator: a page, or (until the compiler
# fills the drawing members) the usage error
"$eomc" run "$src/specs/pendulum.yaml" --t-end 0.1 -o /dev/null --animate "$tmp/e.html" 2> "$tmp/err"
st=$?
{ [ $st = 0 ] && [ -s "$tmp/e.html" ]; } || { [ $st = 2 ] && grep -q 'nothing to draw' "$tmp/err"; }
ok $? "eomc run --animate reaches the simulator (exit $st)"

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
tap_end
