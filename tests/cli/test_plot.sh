#!/bin/sh
# A run's --plot FILE (TAP): gnuplot draws the coordinates against time,
# the conserved quantity's drift on a second panel when the model has
# one, and each of the scene's outputs on a panel of its own (more than
# six: grouped by magnitude); .svg and .png; the CSV of the run unchanged
# by it; and the usage errors (another extension, no gnuplot, --plot with
# --linearize).  What an SVG shows is read back from it and checked
# against the run's CSV: each curve (theta, E - E(t0), an output) has one
# vertex per row, at pixels that are one increasing affine map of t and
# one decreasing affine map of the column's values, and the labels of its
# panel's y ticks sit where that map puts their values (to gnuplot's
# 0.01 px rounding).
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

# svg_curve FILE TITLE: the curve titled TITLE as "P,x,y" lines, each
# panel's frame "F,left,top,right,bottom", each y tick with a numeric label
# "T,y,value".  Read element by element: gnuplot writes a curve as a path
# after its title (the key's sample, then the data), a frame as a closed
# path of 5 points, a y tick as marks on both sides and then its label.
svg_curve() {
    awk -v want="$2" -v OFS=, '
BEGIN { RS = "<" }
function points(d,    n, i, tok, xy) {
    gsub(/[MLZ]/, " & ", d)
    n = split(d, tok, /[ \t\n]+/)
    np = ns = 0
    for (i = 1; i <= n; i++) {
        if (tok[i] == "M")
            start[++ns] = np + 1
        else if (tok[i] ~ /,/) {
            split(tok[i], xy, ",")
            px[++np] = xy[1]; py[np] = xy[2]
        }
    }
    start[ns + 1] = np + 1
}
/^title>/ { grab = substr($0, 7) == want; next }
/^path / {
    tick = ""
    if (!match($0, /d=\047[^\047]*\047/))
        next
    points(substr($0, RSTART + 3, RLENGTH - 4))
    if (grab) { # the longest run: the data
        best = 1
        for (s = 2; s <= ns; s++)
            if (start[s + 1] - start[s] > start[best + 1] - start[best])
                best = s
        for (i = start[best]; i < start[best + 1]; i++)
            print "P", px[i], py[i]
        grab = 0
    } else if (np == 5 && $0 ~ /Z/)
        print "F", px[1], py[1] < py[2] ? py[1] : py[2], px[3], py[1] < py[2] ? py[2] : py[1]
    else if (np == 4 && ns == 2 && py[1] == py[2] && py[2] == py[3] && py[3] == py[4])
        tick = py[1]
    next
}
/^text>/ { label = "" }
/^(text|tspan)[ >]/ { v = $0; sub(/^[^>]*>/, "", v); label = label v }
/^\/text>/ {
    gsub(/[ \t\n]/, "", label)
    if (label ~ /^-?[0-9.]+x10-?[0-9]+$/) { # 6x10^{-12}
        split(label, me, "x10")
        label = me[1] * 10 ^ me[2]
    }
    if (tick != "" && label ~ /^-?[0-9.]+([eE][-+]?[0-9]+)?$/)
        print "T", tick, label
    tick = ""
}' "$1"
}

# drawn SVG TITLE CSV COLUMN [shift]: whether the curve TITLE of SVG draws
# COLUMN of CSV against t (less its first value with shift), as the header
# says; prints what it found.
drawn() {
    svg_curve "$1" "$2" > "$tmp/curve"
    awk -F, -v name="$4" -v shift="${5:-}" '
FNR == NR {
    if ($1 == "P") { n++; x[n] = $2; y[n] = $3 }
    else if ($1 == "F") { nf++; fl[nf] = $2; ft[nf] = $3; fr[nf] = $4; fb[nf] = $5 }
    else if ($1 == "T") { nt++; ty[nt] = $2; tv[nt] = $3 }
    next
}
FNR == 1 { for (i = 1; i <= NF; i++) if ($i == name) col = i; next }
{ m++; t[m] = $1; v[m] = $col }
function abs(a) { return a < 0 ? -a : a }
END {
    if (!col || n != m || m < 2) {
        printf "%d points for %d rows of %s", n, m, name
        exit 1
    }
    v0 = v[1]
    imin = imax = 1
    for (k = 1; k <= m; k++) {
        if (shift)
            v[k] -= v0
        if (v[k] < v[imin]) imin = k
        if (v[k] > v[imax]) imax = k
    }
    a = (x[n] - x[1]) / (t[m] - t[1]); b = x[1] - a * t[1]
    c = (y[imax] - y[imin]) / (v[imax] - v[imin]); d = y[imin] - c * v[imin]
    for (k = 1; k <= m; k++) {
        if (abs(a * t[k] + b - x[k]) > ex) ex = abs(a * t[k] + b - x[k])
        if (abs(c * v[k] + d - y[k]) > ey) ey = abs(c * v[k] + d - y[k])
    }
    for (f = 1; f <= nf; f++) # the frame of the curve panel
        if (fl[f] <= x[1] && x[1] <= fr[f] && ft[f] <= y[1] && y[1] <= fb[f])
            break
    for (k = 1; k <= nt; k++)
        if (f <= nf && ft[f] - 0.01 <= ty[k] && ty[k] <= fb[f] + 0.01) {
            used++
            if (abs(c * tv[k] + d - ty[k]) > et) et = abs(c * tv[k] + d - ty[k])
        }
    printf "%d points; %s in [%.6g, %.6g]; off the maps by %.3f px (t), %.3f px (%s), %d y ticks by %.3f px",
        n, name, v[imin], v[imax], ex, ey, name, used, et
    exit !(a > 0 && c < 0 && ex <= 0.02 && ey <= 0.02 && used >= 2 && et <= 0.02)
}' "$tmp/curve" "$3"
}

"$eomc" run "$pend" --t-end 2 --plot "$tmp/p.svg" -o "$tmp/p.csv"; st=$?
"$eomc" run "$pend" --t-end 2 -o "$tmp/q.csv"
[ $st -eq 0 ] && grep -q '<svg' "$tmp/p.svg" && cmp -s "$tmp/p.csv" "$tmp/q.csv"
ok $? "pendulum: an SVG; the CSV the same as without --plot"
got=$(drawn "$tmp/p.svg" theta "$tmp/p.csv" theta)
ok $? "pendulum: theta drawn against t: $got"
got=$(drawn "$tmp/p.svg" "E - E(t0): drift" "$tmp/p.csv" E shift)
ok $? "pendulum: E's drift drawn against t: $got"
"$eomc" run "$cp" --scene tension --t-end 2 --plot "$tmp/c.svg" -o "$tmp/c.csv"
got=$(drawn "$tmp/c.svg" tension "$tmp/c.csv" tension)
ok $? "cartesian_pendulum: its output tension drawn against t: $got"
# the panels' y labels, top to bottom: the rotated texts of the SVG
ylabels() { sed -n '/rotate(270)/{n;s/.*<text>\(.*\)<\/text>.*/\1/p}' "$1" | tr '\n' '|'; }
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
