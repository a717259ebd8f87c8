#!/bin/sh
# usage: reproducible.sh EOMC SOURCE_ROOT BUILD_ROOT CC_ID
#
# The C that eomc writes must not depend on the C compiler that built eomc.
# Builds a second eomc from the same sources with the other compiler (clang
# when CC_ID, this build's, is gcc, and gcc otherwise) at -O0, compiles
# every spec of the tree (specs/, tests/*/specs, examples/) under each of
# its scenes, each form, Jacobian mode, --eliminate, --stats and --explain
# with both, and compares the C, stdout, stderr and exit status: one TAP
# line per spec.  Skipped without the other compiler.
set -u
eomc=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") src=$2 build=$3 id=$4
case $id in
gcc) other=clang ;;
*) other=gcc ;;
esac
if ! command -v "$other" >/dev/null 2>&1; then
  echo "1..0 # SKIP $other not found"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/a" "$tmp/b"
ln -s "$eomc" "$tmp/a/eomc"
# the flags compiler/meson.build gives the compiler (c_std, project
# arguments, -ffp-contract=off), nothing else
if ! "$other" -std=c11 -O0 -D_POSIX_C_SOURCE=200809L -ffp-contract=off \
    -I"$build/compiler" -I"$src/compiler" -I"$src" $(pkg-config --cflags yaml-0.1) \
    "$src"/compiler/*/*.c "$src/runtime/base/numfmt.c" \
    -o "$tmp/b/eomc" $(pkg-config --libs yaml-0.1) -lm -pthread 2>"$tmp/cc.log"; then
  echo "1..1"
  echo "not ok 1 - $other cannot build eomc"
  sed 's/^/# /' "$tmp/cc.log"
  exit 0
fi

cd "$src" || exit 1
specs=$(ls specs/*.yaml tests/*/specs/*.yaml examples/*/*.yaml)
echo "1..$(echo "$specs" | wc -l)"
i=0
for spec in $specs; do
  i=$((i + 1))
  scenes=$("$eomc" compile "$spec" --scene '?' -o /dev/null 2>&1 | sed -n 's/.* are //p' | tr -d ,)
  n=0 bad=
  for scene in "" $scenes; do
    for how in "" "--form lagrange" "--form maggi" "--form nielsen" "--form tzenoff" \
        "--form gibbs-appell" "--form newton-euler" "--jacobian unrolled" "--jacobian seeded" \
        "--jacobian none" "--eliminate" "--stats" "--explain"; do
      for d in a b; do
        rm -f "$tmp/$d/out.c"
        (cd "$tmp/$d" && ./eomc compile "$src/$spec" ${scene:+--scene "$scene"} $how -o out.c \
          >stdout 2>stderr; echo $? >status)
      done
      n=$((n + 1))
      for f in out.c stdout stderr status; do
        # (no out.c from either is the same; from one only, not)
        if [ -e "$tmp/a/$f" ] || [ -e "$tmp/b/$f" ] && ! cmp -s "$tmp/a/$f" "$tmp/b/$f"; then
          bad=$(echo ${scene:+--scene $scene} $how)
          bad="${bad:-no options}: $f"
          diff "$tmp/a/$f" "$tmp/b/$f" 2>&1 | head -6 | sed 's/^/# /' >"$tmp/diff"
          break 3
        fi
      done
    done
  done
  if [ -z "$bad" ]; then
    echo "ok $i - $spec: $n compilations the same with $other's eomc"
  else
    echo "not ok $i - $spec: $bad differs with $other's eomc"
    cat "$tmp/diff"
  fi
done
