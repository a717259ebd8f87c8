# Sourced by the cli scripts: a scratch directory $tmp, removed at exit,
# and TAP: ok STATUS TEXT for each check, tap_end last (the plan, and the
# script's status).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0 failed=0
ok() { n=$((n + 1)); if [ "$1" -eq 0 ]; then echo "ok $n - $2"; else echo "not ok $n - $2"; failed=$((failed + 1)); fi; }
# |got - want| <= tol, and got not empty
within() { awk -v g="$1" -v w="$2" -v tol="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= tol) }'; }
tap_end() { echo "1..$n"; [ $failed -eq 0 ]; }
# init SPEC: --init for every coordinate and rate of SPEC, each its own
# value (the state the articulated-body scripts compare forms at)
init() {
  k=0
  for c in $(sed -n 's/^coordinates: \[\(.*\)\]/\1/p' "$1" | tr -d ','); do
    k=$((k + 1))
    printf ' --init %s=0.%d --init %s'"'"'=-0.%d' "$c" $((k % 7 + 1)) "$c" $((k % 5 + 2))
  done
}
