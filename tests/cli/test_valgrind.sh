#!/bin/sh
# Memory: eomc frees what it allocates (its arena, the DAG, libyaml's
# document) on success and on every error path.  valgrind --leak-check=full
# on `eomc compile` of every shipped spec and of a few bad ones (TAP): no
# leak of any kind and no invalid access, and the exit status eomc means.
# usage: test_valgrind.sh VALGRIND EOMC SOURCE_ROOT
set -u
valgrind=$1 eomc=$2 src=$3
. "$src/tests/cli/tap.sh"

# check WANT_STATUS FILE [ARGS]: valgrind's own errors exit 99
check() {
  want=$1 file=$2
  shift 2
  "$valgrind" -q --leak-check=full --show-leak-kinds=all --errors-for-leak-kinds=all \
    --error-exitcode=99 "$eomc" compile "$file" -o "$tmp/out.c" "$@" > /dev/null 2> "$tmp/vg.err"
  st=$?
  [ $st -eq "$want" ] || { sed 's/^/# /' "$tmp/vg.err" | head -n 40; return 1; }
}

for spec in "$src"/specs/*.yaml; do
  name=$(basename "$spec" .yaml)
  check 0 "$spec"; ok $? "compile $name: no leak, no invalid access"
done
check 0 "$src/specs/appell.yaml" --form gibbs-appell --eliminate
ok $? "compile appell --form gibbs-appell --eliminate: no leak"
printf 'name: x\ncoordinates: [q]\nparticles: {p: {mass: 1, position: [q, zz]}}\n' > "$tmp/bad1.yaml"
check 2 "$tmp/bad1.yaml"; ok $? "an unknown name (exit 2): no leak"
printf 'name: x\ncoordinates: [q\n' > "$tmp/bad2.yaml"
check 2 "$tmp/bad2.yaml"; ok $? "invalid YAML (exit 2): no leak"
printf 'name: x\ncoordinates: [q]\nkinetic: q'"'"'^2/2\nconstraints:\n  c: q + (1 +\n' > "$tmp/bad3.yaml"
check 2 "$tmp/bad3.yaml"; ok $? "an expression syntax error in a constraint (exit 2): no leak"

tap_end
