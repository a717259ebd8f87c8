#!/bin/sh
# Rewrite generated/NAME.c from specs/NAME.yaml with the given eomc.
# Run through `meson compile -C build regenerate`.  With the Jacobian and
# Taylor's series, which a plain `eomc compile` prints only for a scene
# that needs them: the tests run these models with implicit methods and
# Taylor's method, and linearize them.
set -eu
eomc=$1
shift
root=${MESON_SOURCE_ROOT:-$(cd "$(dirname "$0")/.." && pwd)}
for name in "$@"; do
  "$eomc" compile "$root/specs/$name.yaml" -o "$root/generated/$name.c" --jacobian auto --taylor
  echo "generated/$name.c"
done
