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
#    the output file), run from this directory; cli_import_*.args import a
#    model file of this directory through MuJoCo's loader (their goldens
#    quote MuJoCo 2.2.2's messages, Debian's), and are skipped where eomc
#    was built without MuJoCo.
# Where each error must point is written in the case itself, by hand, as a
# comment `# expect: LINE:COL ...` (one place per error, in order; in the
# .gen script for a generated spec; none in a .args file means no error
# names a place), and the golden's places must be those: so that a golden
# refreshed from eomc's own output cannot bless a wrong location.
# usage: run_errors.sh EOMC SOURCE_DIR SCRATCH_DIR
# UPDATE=1 rewrites each NAME.err from what eomc prints (then read the diff).
set -u
eomc=$1 src=$2 scratch=$3
case $eomc in /*) ;; *) eomc="$PWD/$eomc" ;; esac
case $src in /*) ;; *) src="$PWD/$src" ;; esac
case $scratch in /*) ;; *) scratch="$PWD/$scratch" ;; esac
rm -rf "$scratch"
mkdir -p "$scratch/gen" || exit 1
out="$scratch/out.c"
n=0 failed=0

# places CASE_FILE NAME: the places the case expects, and those its golden
# names (in whichever file: a spec, or an imported model), each as one line
expected() { sed -n 's/^# expect: *//p' "$1" | tr -s ' \n' '  ' | sed 's/ $//'; }
golden() {
  sed -n "s/^[^ ]*:\([0-9]*:[0-9]*\): error:.*/\1/p" "$src/$1.err" | tr '\n' ' ' |
    sed 's/ $//'
}
mujoco=1
"$eomc" import "$scratch/none.xml" 2>&1 | grep -q "built without MuJoCo" && mujoco=0

# check NAME DIR CASE_FILE ARG...: run eomc ARG... in DIR and judge it
check() {
  name=$1 dir=$2 case_file=$3
  shift 3
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
  if [ -z "$why" ] && [ "$(expected "$case_file")" != "$(golden "$name")" ]; then
    why="$name.err names $(golden "$name" | sed 's/^$/no place/'), the case expects $(expected "$case_file" | sed 's/^$/no place/')"
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
  check "$name" "$src" "$f" compile "$name.yaml" -o "$out"
done

for f in "$src"/*.gen; do
  name=${f##*/}
  name=${name%.gen}
  sh "$f" > "$scratch/gen/$name.yaml"
  check "$name" "$scratch/gen" "$f" compile "$name.yaml" -o "$out"
done

for f in "$src"/cli_*.args; do
  name=${f##*/}
  name=${name%.args}
  case $name in cli_import_*) if [ $mujoco = 0 ]; then
    n=$((n + 1)) && echo "ok $n - $name # SKIP eomc was built without MuJoCo" && continue
  fi ;; esac
  set -f # the words of the file, unglobbed
  set --
  for a in $(grep -v '^#' "$f"); do
    [ "$a" = OUT ] && a=$out
    set -- "$@" "$a"
  done
  set +f
  check "$name" "$src" "$f" "$@"
done

echo "1..$n"
[ $failed -eq 0 ]
