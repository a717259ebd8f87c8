#!/bin/sh
# What `eomc run`'s cache is keyed by (TAP): the spec's text, $CC, and the
# content of eomc and of the runtime it links (the library and the headers
# the generated code includes), never their modification times.  A copy
# of the runtime (EOMC_RUNTIME_LIB, EOMC_RUNTIME_INCLUDE) and of eomc are
# changed in turn; each case says whether the simulator was built again
# (a new entry in $EOMC_CACHE_DIR) and checks what it computes.
# usage: test_cache.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
export EOMC_CACHE_DIR="$tmp/cache"
mkdir -p "$tmp/rt" "$tmp/inc" "$tmp/bin"
cp "$build/runtime/libeomcrt.a" "$tmp/rt/"
cp "$src/runtime/include/eomc.h" "$src/runtime/include/eomc_model.h" "$src/runtime/include/eomc_main.h" \
  "$src/runtime/include/eomc_mpi.h" "$src/runtime/include/eomc_taylor.h" "$tmp/inc/"
export EOMC_RUNTIME_LIB="$tmp/rt/libeomcrt.a" EOMC_RUNTIME_INCLUDE="$tmp/inc"
lib=$EOMC_RUNTIME_LIB
cp "$src/specs/pendulum.yaml" "$tmp/p.yaml"

entries() { find "$tmp/cache" -type f -name 'sim-*' 2> /dev/null | wc -l; }
# run EOMC: theta'' at theta = 0.5 in got, and in built whether the run
# added an entry to the cache (1) or not (0)
run() {
    before=$(entries)
    got=$("$1" run "$tmp/p.yaml" --accel --init theta=0.5 | sed -n "s/^theta'' //p")
    built=$(($(entries) - before))
}
# g sin(0.5) for g = $1, to 1e-12
is_accel() { awk -v g="$got" -v w="$1" 'BEGIN { w = -w * sin(0.5); d = g - w; if (d < 0) d = -d
    exit !(g != "" && d <= 1e-12 * (w < 0 ? -w : w)) }'; }

run "$eomc"
[ "$built" -eq 1 ] && is_accel 9.81
ok $? "first run: built, theta'' = $got = -9.81 sin(0.5)"
run "$eomc"
[ "$built" -eq 0 ] && is_accel 9.81
ok $? "the same run again: not rebuilt"

sed 's/g: 9.81/g: 3.5/' "$src/specs/pendulum.yaml" > "$tmp/p.yaml"
run "$eomc"
[ "$built" -eq 1 ] && is_accel 3.5
ok $? "the spec edited (g = 3.5): rebuilt, theta'' = $got"

touch -d '2001-02-03 04:05:06' "$lib" "$tmp/inc/"*.h
run "$eomc"
[ "$built" -eq 0 ] && is_accel 3.5
ok $? "the runtime's files touched (new times, the same bytes): not rebuilt"

# the runtime rebuilt to other bytes of the same size, at the same time: a
# digit of the archive's first member header (its date field, which the
# linker ignores) changed, and the time set back
c=$(dd if="$lib" bs=1 skip=24 count=1 2> /dev/null)
[ "$c" = 1 ] && d=2 || d=1
printf '%s' "$d" | dd of="$lib" bs=1 seek=24 count=1 conv=notrunc 2> /dev/null
touch -d '2001-02-03 04:05:06' "$lib"
size=$(wc -c < "$lib")
run "$eomc"
[ "$built" -eq 1 ] && is_accel 3.5 && [ "$size" -eq "$(wc -c < "$build/runtime/libeomcrt.a")" ]
ok $? "the library's bytes changed, its size and time kept: rebuilt"

printf '/* a changed header */\n' >> "$tmp/inc/eomc_model.h"
touch -d '2001-02-03 04:05:06' "$tmp/inc/eomc_model.h"
run "$eomc"
[ "$built" -eq 1 ] && is_accel 3.5
ok $? "eomc_model.h changed, its time kept: rebuilt"

cp "$eomc" "$tmp/bin/eomc"
touch -d '2001-02-03 04:05:06' "$tmp/bin/eomc"
run "$tmp/bin/eomc"
[ "$built" -eq 0 ] && is_accel 3.5
ok $? "a copy of eomc (the same bytes, another file and time): not rebuilt"
printf '\0' >> "$tmp/bin/eomc"
run "$tmp/bin/eomc"
[ "$built" -eq 1 ] && is_accel 3.5
ok $? "eomc's bytes changed: rebuilt"

# another $CC: the one the tests run with and a harmless definition
cc_run() {
    before=$(entries)
    got=$(CC="${CC:-cc} -DEOMC_CACHE_TEST" "$eomc" run "$tmp/p.yaml" --accel --init theta=0.5 |
          sed -n "s/^theta'' //p")
    built=$(($(entries) - before))
}
cc_run
[ "$built" -eq 1 ] && is_accel 3.5
ok $? "another \$CC: rebuilt"
cc_run
[ "$built" -eq 0 ] && is_accel 3.5
ok $? "that \$CC again: not rebuilt"

# eomc build --cache: the same cache, a library kept beside the simulators
# (--shared: the model under fixed names and the whole runtime API, no main)
unset EOMC_RUNTIME_LIB EOMC_RUNTIME_INCLUDE
libs() { find "$tmp/cache" -type f -name 'lib*.so' 2> /dev/null | wc -l; }
before=$(libs)
path=$("$eomc" build "$tmp/p.yaml" --shared --cache)
[ $? = 0 ] && [ "$(libs)" -eq $((before + 1)) ] && [ -f "$path" ] &&
    case $path in "$tmp/cache/"*/libp.so) true ;; *) false ;; esac
ok $? "build --shared --cache: built into the cache, its path printed ($path)"
stamp=$(stat -c %Y.%i "$path")
again=$("$eomc" build "$tmp/p.yaml" --shared --cache)
[ "$again" = "$path" ] && [ "$(stat -c %Y.%i "$path")" = "$stamp" ] && [ "$(libs)" -eq $((before + 1)) ]
ok $? "the same build again: the same path, nothing built"
other=$("$eomc" build "$tmp/p.yaml" --shared --cache --fix g=9.81)
[ -f "$other" ] && [ "$other" != "$path" ]
ok $? "other options (--fix): another entry"
syms=$(nm -D --defined-only "$path" | awk '{ print $3 }')
for s in eomc_shared_model eomc_shared_model_ext eomc_main_mem eomc_sim_accel eomc_model_count; do
    echo "$syms" | grep -qx "$s" || echo "missing $s"
done > "$tmp/missing"
[ ! -s "$tmp/missing" ] && ! echo "$syms" | grep -qx main &&
    ! echo "$syms" | grep -v '^eomc_' | grep -v '^pendulum_model' | grep -v '^_' | grep -q .
ok $? "the library exports the model by fixed names and eomc.h's API (and, under a sanitizer, its _ names), and no main ($(tr '\n' ' ' < "$tmp/missing"))"
sim=$("$eomc" build "$tmp/p.yaml" --cache)
[ -x "$sim" ] && [ "$("$sim" --accel --init theta=0.5 | sed -n "s/^theta'' //p")" = "$got" ]
ok $? "build --cache without --shared: a simulator in the cache, which runs"
"$eomc" build "$tmp/p.yaml" --shared --mpi 2> "$tmp/err"
[ $? = 2 ] && grep -q -- '--shared and --mpi cannot go together' "$tmp/err"
ok $? "--shared with --mpi: exit 2 ($(head -1 "$tmp/err"))"
"$eomc" build "$tmp/p.yaml" --cache -o "$tmp/x" 2> "$tmp/err"
[ $? = 2 ] && grep -q -- '--cache and -o cannot go together' "$tmp/err" && [ ! -e "$tmp/x" ]
ok $? "--cache with -o: exit 2"
(cd "$tmp" && "$eomc" build p.yaml --shared) && [ -f "$tmp/libp.so" ]
ok $? "build --shared names its library libSPEC.so by default"

tap_end
