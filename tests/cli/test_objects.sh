#!/bin/sh
# A model's C is compiled once (TAP): eomc build keeps each translation
# unit's object in the object cache ($EOMC_CACHE_DIR/objects) under its
# content, so that the commands that need the same C link the same
# objects.  A wrapper $CC records every compile (a unit: -DEOMC_UNIT=1,
# -DEOMC_UNIT=2, 3 and 4, the twin's same units of model_ext.c, the main
# main.c).  On a
# 10-body tree (specs/gen_tree.sh 10: three units, a fourth with E's
# Jacobian and the series):
#  - eomc run compiles the three units and the main; eomc run --error then
#    compiles the twin's units alone (the main is the same), eomc build of the same
#    C nothing, and every one of them gives the same q'' to the bit, within
#    1e-11 of newton-euler's (another derivation and another solve);
#  - a library (--shared), whose C adds E's Jacobian and Taylor's series to
#    the simulator's (enough of them for a unit 4), compiles its units 3 and
#    4 and the main's unit for a library alone: the model's functions are
#    not compiled a second time, nor the twin's with --extended (its units
#    3 and 4 alone, after eomc run --error built the others); a second
#    library of the same C compiles nothing; the library's q'' (through
#    Python's package) is the simulator's to the bit;
#  - what makes that so: for every spec of specs/ and every model of
#    tests/import/models (robots included), units 1 and 2 of `eomc compile`'s
#    C are the same bytes with E's Jacobian (auto, seeded, unrolled) and the
#    series as without them;
#  - a small model (specs/pendulum.yaml, whose twin is built unasked): its
#    library compiles unit 3, the main and the twin's unit 3 (which holds the series
#    in extended precision), not unit 1;
#  - another C (a --fix), another $CC, or a changed runtime header is
#    compiled again; a cache that cannot be written is compiled without,
#    as before.
# usage: test_objects.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
cc=${CC:-cc}
cat > "$tmp/rec.sh" <<EOF
#!/bin/sh
case " \$* " in *" -c "*) echo "\$*" >> "$tmp/cc.log" ;; esac
exec $cc "\$@"
EOF
export CC="sh $tmp/rec.sh"
# compiles CMD...: run eomc CMD..., its output in $tmp/out; the units it
# compiled, in $units ("u1 u2 u3 u4 x1 x2 x3 x4 main" in that order: uK the
# model's unit K, xK the twin's, model_ext.c's)
compiles() {
  : > "$tmp/cc.log"
  "$eomc" "$@" > "$tmp/out" 2> "$tmp/err"
  st=$?
  units=$(awk '{ k = 0; for (i = 1; i <= NF; i++) if ($i ~ /^-DEOMC_UNIT=/) k = substr($i, 13) + 0 }
               / model\.c / { n["u" (k ? k : "whole")]++ } / model_ext\.c / { n["x" (k ? k : "whole")]++ }
               / main\.c / { n["main"]++ }
               END { split("u1 u2 u3 u4 uwhole x1 x2 x3 x4 xwhole main", order, " ")
                     for (j = 1; j <= 11; j++) for (c = 0; c < n[order[j]]; c++) s = s " " order[j]
                     print substr(s, 2) }' "$tmp/cc.log")
  return $st
}

sh "$src/specs/gen_tree.sh" 10 > "$tmp/tree10.yaml"
init=$(init "$tmp/tree10.yaml")
# shellcheck disable=SC2086 # $init is a list of options
compiles run "$tmp/tree10.yaml" $init --accel && cp "$tmp/out" "$tmp/run.acc"
[ $? -eq 0 ] && [ "$units" = "u1 u2 u3 main" ] && [ "$(wc -l < "$tmp/run.acc")" -eq 30 ]
ok $? "eomc run: the three units and the main compiled ($units)"
compiles run "$tmp/tree10.yaml" --error --t-end 0.01 -o /dev/null
[ $? -eq 0 ] && [ "$units" = "x1 x2 x3" ] && grep -q 'error against the reference solution' "$tmp/err"
ok $? "eomc run --error then: the twin's units compiled alone ($units)"
# shellcheck disable=SC2086
compiles build "$tmp/tree10.yaml" -o "$tmp/sim" && "$tmp/sim" $init --accel > "$tmp/sim.acc"
[ $? -eq 0 ] && [ -z "$units" ] && cmp -s "$tmp/run.acc" "$tmp/sim.acc"
ok $? "eomc build of the same C: nothing compiled (${units:-none}), the same q'' to the bit"
# shellcheck disable=SC2086
"$eomc" run "$tmp/tree10.yaml" --form newton-euler $init --accel > "$tmp/ne.acc"
d=$(accel_diff "$tmp/ne.acc" "$tmp/sim.acc" 30)
within "$d" 0 1e-11
ok $? "its q'' is newton-euler's to $d (<= 1e-11)"

compiles build "$tmp/tree10.yaml" --shared -o "$tmp/a.so"
[ $? -eq 0 ] && [ "$units" = "u3 u4 main" ] && grep -q -- '-DEOMC_SHARED' "$tmp/cc.log" &&
  nm -D --defined-only "$tmp/a.so" | grep -q ' eomc_shared_model$'
ok $? "a library after the simulator: its units 3 and 4 and the main's for a library alone ($units)"
compiles build "$tmp/tree10.yaml" --shared --cache
[ $? -eq 0 ] && [ -z "$units" ] && [ -f "$(cat "$tmp/out")" ] && cmp -s "$tmp/a.so" "$(cat "$tmp/out")"
ok $? "a second library of the same C: nothing compiled (${units:-none}), the same library"
compiles build "$tmp/tree10.yaml" --shared --extended -o "$tmp/b.so"
[ $? -eq 0 ] && [ "$units" = "x3 x4" ] && nm -D --defined-only "$tmp/b.so" | grep -q ' eomc_shared_model$'
ok $? "a library with its twin after those: the twin's units 3 and 4 alone (${units:-none})"
# (Debian's python3, where numpy is: not a virtual environment's first in PATH)
py=python3 && [ -x /usr/bin/python3 ] && py=/usr/bin/python3
if nm -D "$tmp/a.so" | grep -q ' U __[a-z]*san_'; then
  n=$((n + 1))
  echo "ok $n # SKIP a sanitizer's library: the interpreter cannot load it"
elif "$py" -c 'import numpy' 2> /dev/null; then
  "$eomc" run "$tmp/tree10.yaml" --accel | awk '{ print $2 }' > "$tmp/sim0.acc"
  PYTHONPATH="$src" "$py" -c '
import sys, eomc
m = eomc.load(sys.argv[1])
q, v = m.initial()
print("\n".join(repr(float(x)) for x in m.accel(q, v)))' "$tmp/a.so" > "$tmp/lib0.acc"
  [ "$(wc -l < "$tmp/lib0.acc")" -eq 30 ] &&
    paste "$tmp/sim0.acc" "$tmp/lib0.acc" | awk '$1 != $2 { bad++ } END { exit bad > 0 }'
  ok $? "the library's q'' (Python's accel) is the simulator's, to the bit"
else
  n=$((n + 1))
  echo "ok $n # SKIP numpy not installed"
fi
# unit U's section of C file F
section() {
  awk -v u="$1" '$0 == "#if !defined(EOMC_UNIT) || EOMC_UNIT == " u { on = 1 } on { print }
                 $0 == "#endif /* EOMC_UNIT " u " */" { on = 0 }' "$2"
}
nm=0 bad=""
for f in "$src"/specs/*.yaml "$src"/tests/import/models/*.xml "$src"/tests/import/models/*.urdf \
         "$src"/tests/import/models/robots/*.xml; do
  "$eomc" compile "$f" -o "$tmp/sim.c" 2> /dev/null || { bad="$bad $f"; continue; }
  for opts in "--jacobian auto --taylor" "--jacobian seeded" "--jacobian unrolled"; do
    # shellcheck disable=SC2086 # $opts is a list of options
    "$eomc" compile "$f" $opts -o "$tmp/lib.c" 2> /dev/null || continue # (too large unrolled)
    for u in 1 2; do
      section $u "$tmp/sim.c" > "$tmp/s$u" && section $u "$tmp/lib.c" > "$tmp/l$u"
      cmp -s "$tmp/s$u" "$tmp/l$u" || bad="$bad ${f##*/}($opts: unit $u)"
    done
  done
  [ -s "$tmp/s1" ] || bad="$bad ${f##*/}(no unit 1)"
  nm=$((nm + 1))
done
[ -z "$bad" ] && [ "$nm" -ge 30 ]
ok $? "units 1 and 2 of $nm models' C: the same bytes with E's Jacobian and the series as without${bad:+ (not:$bad)}"
compiles build "$src/specs/pendulum.yaml" -o "$tmp/pend" &&
  [ "$units" = "u1 u3 x1 x3 main" ] &&
  compiles build "$src/specs/pendulum.yaml" --shared -o "$tmp/pend.so" &&
  [ "$units" = "u3 x3 main" ]
ok $? "a small model with its twin: the simulator's units 1 and 3, the twin's and the main; its library's unit 3, the twin's and the main (${units:-none})"

# shellcheck disable=SC2086
compiles run "$tmp/tree10.yaml" --fix g=3 $init --accel
[ $? -eq 0 ] && [ "$units" = "u1 u2 u3" ] && ! cmp -s "$tmp/out" "$tmp/run.acc"
ok $? "another C (--fix g=3): its units compiled ($units; the main is the model's), another q''"
: > "$tmp/cc.log"
CC="sh $tmp/rec.sh -DEOMC_OTHER_CC" "$eomc" build "$tmp/tree10.yaml" -o "$tmp/sim2" &&
  [ "$(grep -c -- '-DEOMC_UNIT=' "$tmp/cc.log")" -eq 3 ]
ok $? "another \$CC: compiled"
mkdir "$tmp/inc"
cp "$src/runtime/include/"*.h "$tmp/inc/"
printf '/* a changed header */\n' >> "$tmp/inc/eomc_tree.h"
EOMC_RUNTIME_INCLUDE="$tmp/inc" compiles build "$tmp/tree10.yaml" -o "$tmp/sim3"
[ $? -eq 0 ] && [ "$units" = "u1 u2 u3 main" ]
ok $? "a runtime header changed (one the model may include): compiled ($units)"
: > "$tmp/file"
EOMC_CACHE_DIR="$tmp/file" compiles build "$tmp/tree10.yaml" -o "$tmp/sim4" &&
  "$tmp/sim4" $init --accel > "$tmp/sim4.acc" && cmp -s "$tmp/run.acc" "$tmp/sim4.acc" &&
  [ "$units" = "u1 u2 u3 main" ] && [ ! -e "$tmp/sim4.tmp"* ] && [ -z "$(ls "$tmp" | grep '\.o$')" ]
ok $? "no cache to write to (\$EOMC_CACHE_DIR a file): built all the same, the same q''"

tap_end
