#!/bin/sh
# How eomc build compiles a large model (TAP), on a 10-body tree of 3-axis
# joints (specs/gen_tree.sh 10: 30 coordinates, whose articulated-body
# solve is cut into parts):
#  - `eomc compile` writes one file that is one translation unit, or three
#    with -DEOMC_UNIT=1, 2 and 3 (some parts marked for the second, the
#    tables and the model's struct in the third); a small model's file
#    (specs/chain5.yaml) has units 1 and 3 only;
#  - the three units compiled apart and linked give the same q'' as the
#    file compiled whole, to the bit, and both are newton-euler's (its
#    residual and M, factored: another derivation and another solve) to
#    1e-11 of the largest |q''| (as in test_articulated.sh: forming M
#    costs digits at this state, 1.9e-12 here, 3.2e-12 between
#    newton-euler's and lagrange's);
#  - built without --extended, the simulator runs but refuses --error with
#    exit 2, no output, and the rebuild to do; with --extended, and from
#    `eomc run ... --error` (which asks for the twin itself), its error
#    line is printed; a small model gets its twin unasked;
#  - --extended belongs to eomc build: eomc compile refuses it (exit 2);
#  - each unit compiles in the directory of its C, by names relative to it,
#    so that two builds of one model in two temporary directories give $CC
#    the same command line (recorded by a wrapper), and ccache, where it is
#    installed, serves the second from its cache;
#  - the units compile for this CPU (-march=native -ffp-contract=off, on
#    x86-64 and arm64), or for any of its kind with --portable and with
#    --mpi (recorded by the wrapper); both builds of gen_tree 10 give the
#    same q'' and the same run to t = 1, to the bit: no contraction into
#    fused multiply-adds, which would round otherwise.
# usage: test_build.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
cc=${CC:-cc}
inc="$src/runtime/include"
lib="$build/runtime/libeomcrt.a"

sh "$src/specs/gen_tree.sh" 10 > "$tmp/tree10.yaml"
"$eomc" compile "$tmp/tree10.yaml" -o "$tmp/tree10.c"
n2=$(grep -c '^/\* [a-z_]*: part [0-9]* of [0-9]*, in the second unit \*/$' "$tmp/tree10.c")
grep -q '^#if !defined(EOMC_UNIT) || EOMC_UNIT == 1$' "$tmp/tree10.c" &&
    grep -q '^#if !defined(EOMC_UNIT) || EOMC_UNIT == 2$' "$tmp/tree10.c" && [ "$n2" -ge 3 ]
ok $? "gen_tree 10: three units, $n2 parts in the second"
"$eomc" compile "$src/specs/chain5.yaml" -o "$tmp/chain5.c" &&
  grep -q '^#if !defined(EOMC_UNIT) || EOMC_UNIT == 3$' "$tmp/chain5.c" &&
  ! grep -q 'EOMC_UNIT == 2' "$tmp/chain5.c" && ! grep -q 'second unit' "$tmp/chain5.c"
ok $? "chain5: units 1 and 3, no part for a second"

# the units apart, and the file whole (as a user compiles it)
flags="-std=c11 -O1 -DEOMC_MAIN -pthread -I$inc"
gsl=$(pkg-config --libs gsl)
# shellcheck disable=SC2086 # $flags and $gsl are lists of options
$cc $flags -DEOMC_UNIT=1 -c "$tmp/tree10.c" -o "$tmp/u1.o" &&
    $cc $flags -DEOMC_UNIT=2 -c "$tmp/tree10.c" -o "$tmp/u2.o" &&
    $cc $flags -DEOMC_UNIT=3 -c "$tmp/tree10.c" -o "$tmp/u3.o" &&
    $cc "$tmp/u1.o" "$tmp/u2.o" "$tmp/u3.o" "$lib" $gsl -lm -pthread -o "$tmp/two" &&
    $cc $flags -c "$tmp/tree10.c" -o "$tmp/one.o" &&
    $cc "$tmp/one.o" "$lib" $gsl -lm -pthread -o "$tmp/one"
ok $? "the three units compile apart and link; the file compiles whole"
init=$(init "$tmp/tree10.yaml")
# shellcheck disable=SC2086 # $init is a list of options
"$tmp/two" $init --accel > "$tmp/two.acc" && "$tmp/one" $init --accel > "$tmp/one.acc" &&
    "$eomc" run "$tmp/tree10.yaml" --form newton-euler $init --accel > "$tmp/ne.acc"
st=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/two.acc")" -eq 30 ] && cmp -s "$tmp/two.acc" "$tmp/one.acc"
ok $? "q'' of the three units equals the whole file's, to the bit"
d=$(accel_diff "$tmp/ne.acc" "$tmp/two.acc" 30)
within "$d" 0 1e-11
ok $? "q'' of the three units equals newton-euler's to $d (<= 1e-11)"

# the extended-precision twin
"$eomc" build "$tmp/tree10.yaml" -o "$tmp/plain"
"$tmp/plain" --accel > /dev/null
ok $? "built without --extended: it runs"
"$tmp/plain" --error --t-end 0.01 > "$tmp/out" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && [ ! -s "$tmp/out" ] &&
    grep -q 'without its extended-precision functions' "$tmp/err" &&
    grep -q 'rebuild with `eomc build tree10.yaml --extended`' "$tmp/err"
ok $? "built without --extended, --error: exit $st, no output, the rebuild said"
"$eomc" build "$tmp/tree10.yaml" -o "$tmp/twin" --extended &&
    "$tmp/twin" --error --t-end 0.01 -o /dev/null 2> "$tmp/err1" &&
    grep -q 'error against the reference solution' "$tmp/err1"
ok $? "eomc build --extended: --error measures the run"
"$eomc" run "$tmp/tree10.yaml" --error --t-end 0.01 -o /dev/null 2> "$tmp/err2" &&
    grep -q 'error against the reference solution' "$tmp/err2"
ok $? "eomc run --error: built with its twin, unasked"
"$eomc" build "$src/specs/chain5.yaml" -o "$tmp/chain5" &&
    "$tmp/chain5" --error --t-end 0.1 -o /dev/null 2> "$tmp/err3" && grep -q 'error against the reference solution' "$tmp/err3"
ok $? "a small model: its twin built unasked"
"$eomc" compile "$tmp/tree10.yaml" -o "$tmp/x.c" --extended 2> "$tmp/err4"; st=$?
[ $st -eq 2 ] && [ ! -e "$tmp/x.c" ] && grep -q -- '--extended belongs to `eomc build`' "$tmp/err4"
ok $? "eomc compile --extended: exit $st, belongs to eomc build"

# the same command line for the same C, from one build to the next
cat > "$tmp/rec.sh" <<EOF
#!/bin/sh
case " \$* " in *" -c "*) echo "\$(pwd | sed 's|/eomc-[^/]*\$|/eomc-X|') \$*" >> "$tmp/cc.log" ;; esac
exec $cc "\$@"
EOF
for k in 1 2; do
  EOMC_CACHE_DIR="$tmp/cache-rec$k" CC="sh $tmp/rec.sh" "$eomc" build "$src/specs/pendulum.yaml" \
    -o "$tmp/rec$k" || echo "build $k failed" >> "$tmp/cc.log"
done
# (units 1 and 3, the twin's and the main's: five compiles a build, at
# once, in any order)
[ "$(wc -l < "$tmp/cc.log")" -eq 10 ] && ! grep -q ' /tmp/eomc-' "$tmp/cc.log" &&
  [ "$(sed -n 1,5p "$tmp/cc.log" | sort)" = "$(sed -n 6,10p "$tmp/cc.log" | sort)" ] &&
  grep -q '^/tmp/eomc-X .* -DEOMC_UNIT=1 -c model.c -o model.o$' "$tmp/cc.log"
ok $? "two builds of one model: the same compile commands, in the C's directory, by relative names"
if command -v ccache > /dev/null; then
  for k in 1 2; do
    CCACHE_DIR="$tmp/ccache" EOMC_CACHE_DIR="$tmp/cache-cc$k" CC="ccache ${cc#ccache }" \
      "$eomc" build "$src/specs/pendulum.yaml" -o "$tmp/cc$k" || echo failed
  done
  hits=$(CCACHE_DIR="$tmp/ccache" ccache -s | sed -n 's/^ *Hits: *\([0-9]*\) .*/\1/p')
  [ "$hits" = 5 ] && cmp -s "$tmp/cc1" "$tmp/cc2"
  ok $? "ccache: the second build's five compiles served from the cache ($hits hits), the same simulator"
else
  n=$((n + 1))
  echo "ok $n # SKIP ccache not installed"
fi

# for this CPU or any: the flags, and the same numbers to the bit
case $(uname -m) in x86_64 | aarch64) native=1 ;; *) native=0 ;; esac
rm -f "$tmp/cc.log"
EOMC_CACHE_DIR="$tmp/cache-n" CC="sh $tmp/rec.sh" "$eomc" build "$tmp/tree10.yaml" -o "$tmp/nat" &&
  mv "$tmp/cc.log" "$tmp/nat.log" &&
  EOMC_CACHE_DIR="$tmp/cache-n" CC="sh $tmp/rec.sh" "$eomc" build "$tmp/tree10.yaml" --portable \
    -o "$tmp/port" && mv "$tmp/cc.log" "$tmp/port.log"
st=$?
EOMC_CACHE_DIR="$tmp/cache-n" EOMC_MPICC="sh $tmp/rec.sh" "$eomc" build "$tmp/tree10.yaml" --mpi \
  -o "$tmp/mpi" > /dev/null 2>&1 # (it needs mpi.h: only its commands count)
nn=$(grep -c ' -march=native -ffp-contract=off ' "$tmp/nat.log")
np=$(cat "$tmp/port.log" "$tmp/cc.log" | grep -c -- '-march=native\|-ffp-contract')
[ $st -eq 0 ] && [ "$np" -eq 0 ] && [ "$(grep -c ' -c ' "$tmp/cc.log")" -ge 1 ] &&
  { [ "$native" -eq 0 ] || [ "$nn" -eq "$(wc -l < "$tmp/nat.log")" ]; }
ok $? "for this CPU: -march=native -ffp-contract=off on each unit ($nn); --portable and --mpi without"
# shellcheck disable=SC2086 # $init is a list of options
"$tmp/nat" $init --accel > "$tmp/nat.acc" && "$tmp/port" $init --accel > "$tmp/port.acc" &&
  "$tmp/nat" $init --t-end 1 -o "$tmp/nat.csv" && "$tmp/port" $init --t-end 1 -o "$tmp/port.csv"
st=$?
[ $st -eq 0 ] && cmp -s "$tmp/nat.acc" "$tmp/port.acc" && cmp -s "$tmp/nat.csv" "$tmp/port.csv" &&
  [ "$(wc -l < "$tmp/nat.csv")" -gt 10 ]
ok $? "for this CPU and for any: the same q'' and the same run to t = 1, to the bit"

tap_end
