#!/bin/sh
# usage: listed.sh SPECS_DIR NAME...: fails, naming it, when a spec in
# SPECS_DIR is not among the NAMEs (the lists in generated/meson.build).
dir=$1
shift
missing=0
for f in "$dir"/*.yaml; do
  name=$(basename "$f" .yaml)
  found=0
  for n in "$@"; do [ "$n" = "$name" ] && found=1; done
  if [ $found -eq 0 ]; then
    echo "specs/$name.yaml is in neither shipped_specs nor constrained_specs (generated/meson.build)"
    missing=1
  fi
done
exit $missing
