#!/bin/sh
# examples/ built as another project would build them (TAP): eomc and its
# runtime installed with `meson install --destdir`, then the meson
# example (find_program('eomc'), a custom_target, dependency('eomcrt'))
# and the Makefile example (pkg-config) built against that install; each
# program's q'' at theta = 0.5 against -g/l sin(0.5), and the half period
# against the closed form 2 K(sin(1/2)) / sqrt(g/l) to the 1e-4 output
# interval it is read at.  The installed library exports only the eomc_
# API (tests/runtime/test_symbols.sh checks the built one).
# usage: test_examples.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
. "$src/tests/cli/tap.sh"

if ! meson install -C "$build" --no-rebuild --destdir "$tmp/stage" --quiet > "$tmp/install.log" 2>&1; then
    cat "$tmp/install.log"
    echo "not ok 1 - meson install --destdir"
    echo "1..1"
    exit 1
fi
bin=$(dirname "$(find "$tmp/stage" -path '*/bin/eomc' -type f | head -n 1)")
pc=$(dirname "$(find "$tmp/stage" -name eomcrt.pc | head -n 1)")
export PATH="$bin:$PATH" PKG_CONFIG_PATH="$pc" PKG_CONFIG_SYSROOT_DIR="$tmp/stage"
accel=$(awk 'BEGIN { printf "%.17g", -9.81 * sin(0.5) }')
half=$(awk 'BEGIN { k = sin(0.5); a = 1; b = sqrt(1 - k * k)
    for (i = 0; i < 40; i++) { m = (a + b) / 2; b = sqrt(a * b); a = m }
    printf "%.17g", 2 * 3.14159265358979323846 / (2 * a) / sqrt(9.81) }')
check() { # OUTPUT NAME
    got=$(sed -n "s/^theta'' //p" "$1") per=$(sed -n 's/^half_period //p' "$1")
    within "$got" "$accel" 1e-12 && within "$per" "$half" 1e-4
    ok $? "$2: theta'' = $got, half period $per (closed form $half)"
}

lib=$(find "$tmp/stage" -name libeomcrt.a | head -n 1)
others=$(nm -g --defined-only "$lib" | awk 'NF == 3 && $3 !~ /^eomc_/ { print $3 }' | tr '\n' ' ')
[ -n "$lib" ] && nm -g --defined-only "$lib" | grep -q ' T eomc_main$' && [ -z "$others" ]
ok $? "the installed libeomcrt.a exports only eomc_ symbols${others:+, not: $others}"

cp -r "$src/examples/meson" "$tmp/meson"
if meson setup "$tmp/meson-build" "$tmp/meson" > "$tmp/meson.log" 2>&1 &&
    meson compile -C "$tmp/meson-build" >> "$tmp/meson.log" 2>&1; then
    "$tmp/meson-build/swing_period" > "$tmp/meson.out"
    check "$tmp/meson.out" "examples/meson (find_program('eomc'), dependency('eomcrt'))"
else
    tail -20 "$tmp/meson.log"
    ok 1 "examples/meson builds"
fi

cp -r "$src/examples/make" "$tmp/make"
if make -C "$tmp/make" > "$tmp/make.log" 2>&1; then
    "$tmp/make/swing_period" > "$tmp/make.out"
    check "$tmp/make.out" "examples/make (pkg-config)"
else
    tail -20 "$tmp/make.log"
    ok 1 "examples/make builds"
fi

# examples/python: the package as installed (no PYTHONPATH into the
# source tree; the installed eomc on the PATH builds the spec), its sweep's
# period at theta0 = 1 against the closed form 4 K(sin(1/2)) / sqrt(g/l)
# computed here (the sweep's t is the stop event's, located to the bit)
py=${EOMC_PYTHON:-python3}
site=$(dirname "$(find "$tmp/stage" -path '*/eomc/__init__.py' | head -n 1)")
if ! "$py" -c 'import numpy' 2> /dev/null; then
    echo "ok - examples/python # SKIP no python3 with numpy (python3-numpy)"
elif [ -z "$site" ] || [ "$site" = . ]; then
    echo "not ok - examples/python: meson install put no eomc package in the stage"
else
    # the example finds its spec at ../../specs/swing.yaml, as in the repository
    mkdir -p "$tmp/specs" "$tmp/py/examples" && cp "$src/specs/swing.yaml" "$tmp/specs/" &&
        cp "$src/examples/python/pendulum_period.py" "$tmp/py/examples/"
    (cd "$tmp" && EOMC_CACHE_DIR="$tmp/pycache" PYTHONPATH="$(dirname "$site")" \
        "$py" "$tmp/py/examples/pendulum_period.py") > "$tmp/py.out" 2>&1
    st=$?
    got=$(awk '$1 == "1.0000" { print $2 }' "$tmp/py.out")
    full=$(awk 'BEGIN { k = sin(0.5); a = 1; b = sqrt(1 - k * k)
        for (i = 0; i < 40; i++) { m = (a + b) / 2; b = sqrt(a * b); a = m }
        printf "%.17g", 4 * 3.14159265358979323846 / (2 * a) / sqrt(9.81) }')
    [ $st = 0 ] && within "$got" "$full" 1e-12
    ok $? "examples/python with the installed package: period $got at theta0 = 1 (closed form $full)"
fi

tap_end
