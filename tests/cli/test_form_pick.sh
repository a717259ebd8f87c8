#!/bin/sh
# The default form is the cheapest that applies (TAP): for every spec of
# specs/ and two generated trees (specs/gen_tree.sh 4 and 10: 12 and 30
# coordinates), each form is compiled with --stats, and what a right-hand
# side costs is read from the emitted functions' operation counts: the
# accel function where there is one and no constraint, else mass_bias
# plus the runtime's dense factorization: LDL^T of M, 5 (n^3/3 + 2 n^2),
# or with nc constraints LU of the KKT matrix, 5 (N^3/3 + 2 N^2), N = n +
# nc (eom.h's EOM_DENSE_WEIGHT).  A constrained tree solved by unit loads
# (minv in the C): accel, nc passes of minv, and 5 (nc^2 n + nc^3/3 +
# 2 nc n) for B M^-1 B^T, its factorization and q'' = a - Y lambda.
# The default's cost is the least of them, --explain and the banner say
# it was picked, and --form still forces another.  On tree 20 (60
# coordinates), where only the recursive forms are candidates, the
# articulated-body solve is picked over Newton-Euler's M and dense solve.
# usage: test_form_pick.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"

sh "$src/specs/gen_tree.sh" 4 > "$tmp/tree4.yaml"
sh "$src/specs/gen_tree.sh" 10 > "$tmp/tree10.yaml"
# cost SPEC [FORM]: the right-hand side's operations, or nothing if the form does not apply
cost() {
  "$eomc" compile "$1" ${2:+--form "$2"} --stats -o "$tmp/c.c" 2> "$tmp/stats" || return 0
  n=$(sed -n 's/^static const char \*const q_names\[\([0-9]*\)\].*/\1/p' "$tmp/c.c")
  nc=$(sed -n 's/^static const char \*const c_names\[\([0-9]*\)\].*/\1/p' "$tmp/c.c")
  awk -v n="$n" -v nc="${nc:-0}" '$1 == "accel" { a = $6 } $1 == "mass_bias" { m = $6 }
       $1 == "minv" { y = $6 }
       END { N = n + nc
             if (nc == 0 && a > 0) print a
             else if (y > 0) print a + nc * y + 5 * (nc * nc * n + int(nc * nc * nc / 3) + 2 * nc * n)
             else if (nc > 0) print m + 5 * (int(N * N * N / 3) + 2 * N * N)
             else print m + 5 * (int(n * n * n / 3) + 2 * n * n) }' "$tmp/stats"
}
for spec in "$src"/specs/*.yaml "$tmp/tree4.yaml" "$tmp/tree10.yaml"; do
  name=$(basename "$spec" .yaml)
  picked=$("$eomc" compile "$spec" --explain -o /dev/null | sed -n 's/^form \([a-z-]*\):.*/\1/p')
  def=$(cost "$spec")
  least=$def worst=
  for f in lagrange nielsen tzenoff gibbs-appell newton-euler articulated-body; do
    c=$(cost "$spec" "$f")
    [ -n "$c" ] || continue
    [ "$c" -lt "$least" ] && least=$c worst="$worst $f:$c"
  done
  [ -n "$def" ] && [ "$def" -le "$least" ] && [ -z "$worst" ]
  ok $? "$name: the default ($picked) costs $def operations per right-hand side, no form less$worst"
done

sh "$src/specs/gen_tree.sh" 20 > "$tmp/tree20.yaml"
"$eomc" compile "$tmp/tree20.yaml" --explain -o /dev/null > "$tmp/explain20"
ab=$(sed -n 's/^  the cheapest that applies: \([0-9]*\) operations.*/\1/p' "$tmp/explain20")
# newton-euler priced from the tree's pattern: its dense factorization alone
ne=$(sed -n 's/.*(newton-euler more than \([0-9]*\), its dense factorization alone)$/\1/p' \
  "$tmp/explain20")
grep -q '^form articulated-body:' "$tmp/explain20" && [ -n "$ab" ] && [ "$ne" = 396000 ] &&
  [ "$ab" -lt "$ne" ]
ok $? "tree20: articulated-body ($ab operations), cheaper than newton-euler's dense solve alone ($ne = 5 (60^3/3 + 2 60^2))"

"$eomc" compile "$src/specs/chain5.yaml" -o "$tmp/chain5.c" &&
  grep -q '^ \* The form is the cheapest that applies: [0-9]* operations per right-hand' "$tmp/chain5.c" &&
  "$eomc" compile "$src/specs/chain5.yaml" --explain -o /dev/null |
    grep -q '^  the cheapest that applies: [0-9]* operations per right-hand side (lagrange [0-9]*, '
ok $? "the banner and --explain say the form was picked, and what the others cost"
"$eomc" compile "$src/specs/chain5.yaml" --form tzenoff -o "$tmp/tz.c" &&
  grep -q '^ \* form:    tzenoff' "$tmp/tz.c" && ! grep -q 'The form is the cheapest' "$tmp/tz.c"
ok $? "--form tzenoff still forces Tzenoff's form"
tap_end
