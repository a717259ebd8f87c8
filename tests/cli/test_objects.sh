#!/bin/sh
# A model's C is compiled once (TAP): eomc build keeps each translation
# unit's object in the object cache ($EOMC_CACHE_DIR/objects) under its
# content, so that the commands that need the same C link the same
# objects.  A wrapper $CC records every compile (a unit: -DEOMC_UNIT=1,
# -DEOMC_UNIT=2, the twin model_ext.c, the main main.c).  On a 10-body tree
# (specs/gen_tree.sh 10: two units):
#  - eomc run compiles the two units and the main; eomc run --error then
#    compiles the twin alone (the main is the same), eomc build of the same C nothing, and every
#    one of them gives the same q'' to the bit, within 1e-11 of
#    newton-euler's (another derivation and another solve);
#  - a library (--shared) compiles each unit once, with the main's unit
#    for a library; a second library of the same C compiles nothing;
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
# compiled, in $units ("u1 u2 twin main", in that order)
compiles() {
  : > "$tmp/cc.log"
  "$eomc" "$@" > "$tmp/out" 2> "$tmp/err"
  st=$?
  units=$(awk '/-DEOMC_UNIT=1 / { u1++ } /-DEOMC_UNIT=2 / { u2++ } / model_ext\.c / { t++ }
               / main\.c / { m++ } / model\.c / && !/-DEOMC_UNIT/ { w++ }
               END { s = ""; for (k = 0; k < u1; k++) s = s " u1"; for (k = 0; k < u2; k++) s = s " u2"
                     for (k = 0; k < w; k++) s = s " whole"; for (k = 0; k < t; k++) s = s " twin"
                     for (k = 0; k < m; k++) s = s " main"; print substr(s, 2) }' "$tmp/cc.log")
  return $st
}

sh "$src/specs/gen_tree.sh" 10 > "$tmp/tree10.yaml"
init=$(init "$tmp/tree10.yaml")
# shellcheck disable=SC2086 # $init is a list of options
compiles run "$tmp/tree10.yaml" $init --accel && cp "$tmp/out" "$tmp/run.acc"
[ $? -eq 0 ] && [ "$units" = "u1 u2 main" ] && [ "$(wc -l < "$tmp/run.acc")" -eq 30 ]
ok $? "eomc run: the two units and the main compiled ($units)"
compiles run "$tmp/tree10.yaml" --error --t-end 0.01 -o /dev/null
[ $? -eq 0 ] && [ "$units" = "twin" ] && grep -q 'error against the reference solution' "$tmp/err"
ok $? "eomc run --error then: the twin compiled alone ($units)"
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
[ $? -eq 0 ] && [ "$units" = "u1 u2 main" ] && grep -q -- '-DEOMC_SHARED' "$tmp/cc.log" &&
  nm -D --defined-only "$tmp/a.so" | grep -q ' eomc_shared_model$'
ok $? "a library: each unit compiled once ($units), the main's unit for a library"
compiles build "$tmp/tree10.yaml" --shared --cache
[ $? -eq 0 ] && [ -z "$units" ] && [ -f "$(cat "$tmp/out")" ] && cmp -s "$tmp/a.so" "$(cat "$tmp/out")"
ok $? "a second library of the same C: nothing compiled (${units:-none}), the same library"

# shellcheck disable=SC2086
compiles run "$tmp/tree10.yaml" --fix g=3 $init --accel
[ $? -eq 0 ] && [ "$units" = "u1 u2" ] && ! cmp -s "$tmp/out" "$tmp/run.acc"
ok $? "another C (--fix g=3): its units compiled ($units; the main is the model's), another q''"
: > "$tmp/cc.log"
CC="sh $tmp/rec.sh -DEOMC_OTHER_CC" "$eomc" build "$tmp/tree10.yaml" -o "$tmp/sim2" &&
  [ "$(grep -c -- '-DEOMC_UNIT=' "$tmp/cc.log")" -eq 2 ]
ok $? "another \$CC: compiled"
mkdir "$tmp/inc"
cp "$src/runtime/include/"*.h "$tmp/inc/"
printf '/* a changed header */\n' >> "$tmp/inc/eomc_tree.h"
EOMC_RUNTIME_INCLUDE="$tmp/inc" compiles build "$tmp/tree10.yaml" -o "$tmp/sim3"
[ $? -eq 0 ] && [ "$units" = "u1 u2 main" ]
ok $? "a runtime header changed (one the model may include): compiled ($units)"
: > "$tmp/file"
EOMC_CACHE_DIR="$tmp/file" compiles build "$tmp/tree10.yaml" -o "$tmp/sim4" &&
  "$tmp/sim4" $init --accel > "$tmp/sim4.acc" && cmp -s "$tmp/run.acc" "$tmp/sim4.acc" &&
  [ "$units" = "u1 u2 main" ] && [ ! -e "$tmp/sim4.tmp"* ] && [ -z "$(ls "$tmp" | grep '\.o$')" ]
ok $? "no cache to write to (\$EOMC_CACHE_DIR a file): built all the same, the same q''"

tap_end
