#!/bin/sh
# The bad-input corpus (TAP, one test per case).  Each case must make eomc
# exit with status 2 within 10 s, print nothing on stdout, leave no output
# file (nor a temporary OUT.tmp*), and print exactly the golden NAME.err on
# stderr:
#  - NAME.yaml: `eomc compile NAME.yaml -o OUT`, run from this directory so
#    that messages name the file as NAME.yaml;
#  - NAME.gen: a script printing a spec too big to commit; it is written to
#    SCRATCH/gen/NAME.yaml and compiled from there in the same way;
#  - cli_NAME.args: the arguments of an eomc command line (OUT stands for
#    the output file), run from this directory.
# usage: run_errors.sh EOMC SOURCE_DIR SCRATCH_DIR
# UPDATE=1 rewrites each NAME.err from what eomc prints (then read the diff:
# every message must name the right line and column).
set -u
eomc=$1 src=$2 scratch=$3
case $eomc in /*) ;; *) eomc="$PWD/$eomc" ;; esac
case $src in /*) ;; *) src="$PWD/$src" ;; esac
case $scratch in /*) ;; *) scratch="$PWD/$scratch" ;; esac
rm -rf "$scratch"
mkdir -p "$scratch/gen" || exit 1
out="$scratch/out.c"
n=0 failed=0

# check NAME DIR ARG...: run eomc ARG... in DIR and judge it
check() {
  name=$1 dir=$2
  shift 2
  rm -f "$out" "$out".*
  (cd "$dir" && exec timeout 10 "$eomc" "$@") > "$scratch/stdout" 2> "$scratch/$name.err"
  st=$?
  why=
  if [ $st -eq 124 ]; then
    why="timed out (10 s)"
  elif [ $st -ne 2 ]; then
    why="exit status $st, not 2"
  elif [ -s "$scratch/stdout" ]; then
    why="wrote to stdout"
  elif ls "$out" "$out".* > /dev/null 2>&1; then
    why="left an output file behind"
  fi
  if [ -z "$why" ] && [ "${UPDATE:-}" = 1 ]; then
    cp "$scratch/$name.err" "$src/$name.err"
  fi
  if [ -z "$why" ] && ! cmp -s "$src/$name.err" "$scratch/$name.err"; then
    why="stderr differs from $name.err"
    diff -u "$src/$name.err" "$scratch/$name.err" 2>&1 | sed 's/^/# /'
  fi
  n=$((n + 1))
  if [ -z "$why" ]; then
    echo "ok $n - $name"
  else
    echo "not ok $n - $name: $why"
    sed 's/^/# /' "$scratch/$name.err" | head -n 20
    failed=$((failed + 1))
  fi
}

for f in "$src"/*.yaml; do
  name=${f##*/}
  name=${name%.yaml}
  check "$name" "$src" compile "$name.yaml" -o "$out"
done

for f in "$src"/*.gen; do
  name=${f##*/}
  name=${name%.gen}
  sh "$f" > "$scratch/gen/$name.yaml"
  check "$name" "$scratch/gen" compile "$name.yaml" -o "$out"
done

for f in "$src"/cli_*.args; do
  name=${f##*/}
  name=${name%.args}
  set -f # the words of the file, unglobbed
  set --
  for a in $(cat "$f"); do
    [ "$a" = OUT ] && a=$out
    set -- "$@" "$a"
  done
  set +f
  check "$name" "$src" "$@"
done

echo "1..$n"
[ $failed -eq 0 ]
