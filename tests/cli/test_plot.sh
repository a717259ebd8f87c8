#!/bin/sh
# A run's --plot FILE (TAP): gnuplot draws the coordinates against time,
# the conserved quantity's drift on a second panel when the model has
# one, and each of the scene's outputs on a panel of its own (more than
# six: grouped by magnitude); .svg and .png; the CSV of the run unchanged
# by it; and the usage errors (another extension, no gnuplot, --plot with
# --linearize).
# usage: test_plot.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
pend="$src/specs/pendulum.yaml" cp="$src/specs/cartesian_pendulum.yaml"
if ! command -v gnuplot > /dev/null; then
    echo "1..0 # SKIP gnuplot is not installed"
    exit 0
fi

"$eomc" run "$pend" --t-end 2 --plot "$tmp/p.svg" -o "$tmp/p.csv"; st=$?
"$eomc" run "$pend" --t-end 2 -o "$tmp/q.csv"
[ $st -eq 0 ] && grep -q '<svg' "$tmp/p.svg" && grep -q '>theta<' "$tmp/p.svg" &&
    grep -q 'E - E(t0): drift' "$tmp/p.svg" && cmp -s "$tmp/p.csv" "$tmp/q.csv"
ok $? "pendulum: an SVG with theta and E's drift; the CSV the same as without --plot"
# the panels' y labels, top to bottom: the rotated texts of the SVG
ylabels() { sed -n '/rotate(270)/{n;s/.*<text>\(.*\)<\/text>.*/\1/p}' "$1" | tr '\n' '|'; }
"$eomc" run "$cp" --scene tension --t-end 2 --plot "$tmp/c.svg" > /dev/null
[ "$(ylabels "$tmp/c.svg")" = "coordinates|E - E(t0): drift|tension|theta|ay|" ]
ok $? "each of a scene's outputs on a panel of its own: $(ylabels "$tmp/c.svg")"
# seven outputs, more than six panels' worth: those within a factor of 10
# share one (th and 2 th; 100 th and 150 th), the others stand alone
cat > "$tmp/many.yaml" <<'YAML'
name: many
parameters: {m: 1, l: 1, g: 9.81}
coordinates: [th]
particles:
  bob: {mass: m, position: [l*sin(th), -l*cos(th)]}
effects:
  gravity: {gravity: [0, -g]}
initial: {th: 0.5}
scene:
  t_end: 1
  outputs: {a: 1e6*th, b: th, c: 100*th, d: 2*th, e: 1e4*th, f: 150*th, h: 1e8*th}
YAML
"$eomc" run "$tmp/many.yaml" --plot "$tmp/many.svg" > /dev/null; st=$?
[ $st -eq 0 ] && [ "$(ylabels "$tmp/many.svg")" = "coordinates|E - E(t0): drift|outputs|outputs|e|a|h|" ] &&
  [ "$(grep -c '<title>[a-h]</title>' "$tmp/many.svg")" -eq 7 ]
ok $? "seven outputs: grouped by magnitude, $(ylabels "$tmp/many.svg")"
"$eomc" run "$pend" --t-end 1 --plot "$tmp/p.png" > /dev/null
head -c 8 "$tmp/p.png" | od -An -c | grep -q 'P   N   G'
ok $? ".png: a PNG file"

"$eomc" run "$pend" --plot "$tmp/p.pdf" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "neither .svg nor .png" "$tmp/err"
ok $? "--plot FILE.pdf: exit $st"
exe=$(find "$tmp/cache" -type f -name 'sim-pendulum*' | head -1)
PATH=/nonexistent "$exe" --plot "$tmp/x.svg" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'gnuplot is not installed' "$tmp/err" && [ ! -e "$tmp/x.svg" ]
ok $? "no gnuplot: exit $st before anything runs, no file"
"$eomc" run "$pend" --linearize --plot "$tmp/y.svg" > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ]
ok $? "--plot with --linearize: exit $st"

tap_end
