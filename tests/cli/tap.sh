# Sourced by the cli scripts: a scratch directory $tmp, removed at exit,
# and TAP: ok STATUS TEXT for each check, tap_end last (the plan, and the
# script's status).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0 failed=0
# (the text on one line: a message quoting a command's output, an
# error's caret under its line, would leave lines TAP does not know)
ok() {
  n=$((n + 1))
  set -- "$1" "$(printf '%s' "$2" | tr '\n' ' ')"
  if [ "$1" -eq 0 ]; then echo "ok $n - $2"; else echo "not ok $n - $2"; failed=$((failed + 1)); fi
}
# |got - want| <= tol, and got not empty
within() { awk -v g="$1" -v w="$2" -v tol="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= tol) }'; }
tap_end() { echo "1..$n"; [ $failed -eq 0 ]; }
# stat_of NAME FILE: the value of --stats' line NAME in FILE
stat_of() { sed -n "s/^$1 //p" "$2"; }
# why ST FILE: for a check's message, what a command that exited ST said
# on its standard error (FILE) where ST is not 0: so that a failure in CI,
# whose log keeps the message alone, says its cause
why() { [ "$1" -eq 0 ] || printf '; exit %s: %s' "$1" "$(tail -2 "$2" 2> /dev/null | tr '\n' ' ' | cut -c1-300)"; }
# init SPEC: --init for every coordinate and rate of SPEC, each its own
# value (the state the articulated-body scripts compare forms at)
init() {
  k=0
  for c in $(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$1" | tr -d ','); do
    k=$((k + 1))
    printf ' --init %s=0.%d --init %s'"'"'=-0.%d' "$c" $((k % 7 + 1)) "$c" $((k % 5 + 2))
  done
}
# accel_diff REF GOT WANT [SCALE]: the largest difference of two `NAME
# VALUE` listings (--accel's) over REF's largest |value|, GOT's NAME first
# multiplied by its factor in SCALE ("x'' 1e4 lambda[roll_x] 1e-2");
# nan unless both list the same number of lines, at least WANT
accel_diff() {
  awk -v want="$3" -v scale="${4:-}" '
       BEGIN { ns = split(scale, s, " "); for (i = 1; i < ns; i += 2) f[s[i]] = s[i + 1] }
       NR == FNR { w[$1] = $2; nw++; next }
       { x = ($1 in f) ? $2 * f[$1] : $2; d = x - w[$1]; if (d < 0) d = -d; if (d > dm) dm = d;
         a = w[$1] < 0 ? -w[$1] : w[$1]; if (a > am) am = a; n++ }
       END { if (n < want || n != nw || am == 0) print "nan"; else printf "%.3g\n", dm / am }' "$1" "$2"
}
# row_diff REF GOT [WANT]: the last rows of two runs (one CSV line each),
# entry by entry after t, over REF's largest |entry|; nan unless they have
# the same number of columns, at least WANT
row_diff() {
  awk -F, -v want="${3:-0}" 'NR == FNR { n = split($0, w, ","); next }
           { m = split($0, g, ","); for (i = 2; i <= m; i++) { d = g[i] - w[i]; if (d < 0) d = -d;
             if (d > dm) dm = d; a = w[i] < 0 ? -w[i] : w[i]; if (a > am) am = a } }
           END { if (m != n || m < want || am == 0) print "nan"; else printf "%.3g\n", dm / am }' \
    "$1" "$2"
}
