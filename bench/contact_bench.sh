#!/bin/sh
# What contact pairs cost a right-hand side, apart and touching, and a
# humanoid standing on its floor beside MuJoCo's mj_forward.
#
# 1. N free capsules (a free joint each: centre and unit quaternion with
# speeds), `contact: all` (N capsule-plane pairs, two contacts each, and
# N (N - 1)/2 capsule-capsule pairs), and N free boxes over the floor (N
# pairs of 8 corners each; the boxes' conaffinity 0: not each other),
# 1 apart along x.  Each model compiled with the contact off (--effects
# gravity), on with every branch computed (--branches eager) and on as
# eomc writes it (lazy), and timed by bench/contact_time.c at two states:
# apart (2 up: every pair far) and touching (each body standing on the
# floor, 1 mm into it; the bodies still far from each other):
#   pairs            the pairs the contact has
#   ops_off, ops_on  operations of the generated mass_bias (--stats)
#   ns_off           ns per right-hand side without the contact
#   eager_apart, eager_touch   every branch computed (what eomc wrote
#                    before lazy blocks), apart and touching
#   ns_apart, ns_touch   lazy, apart and touching
#   ns_sw            ns per call of the switches, apart
#   pair_eager, pair_apart   (ns - ns_off) per pair, apart
# A right-hand side is the model's accel (M, h and their unrolled
# solve; mass_bias where it has none), its modes those of the state.
#
# 2. With MJ_CONTACT (bench/mj_contact.c, where MuJoCo is installed):
# MuJoCo's humanoid (libmujoco-samples' humanoid.xml, or $BENCH_HUMANOID)
# imported, with its floor and a contact effect of the pairs MuJoCo lets
# touch (mj_contact pairs: contype/conaffinity, no welded parent and
# child), standing on the floor (its root lowered until its lowest geom
# is 1 mm in: mj_contact drop), built by eomc build, and timed the same
# way (contact off, eager, lazy), beside mj_forward with contact at the
# same state (limits and friction loss off, as eomc's import; MJCF's
# friction as written, and frictionless).
# usage: contact_bench.sh EOMC SOURCE_ROOT RUNTIME_INCLUDE RUNTIME_LIB [MJ_CONTACT]
# $BENCH_N: the N to run (default "1 2 4 8").
set -eu
eomc=$1 src=$2 inc=$3 lib=$4 mjc=${5:-}
cc=${CC:-cc}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
gsl_libs=$(pkg-config --libs gsl)

# the model: N bodies of SHAPE ("capsule" or "box") 1 apart along x, 2
# up, or (touch) standing on the floor 1 mm into it
gen() {
  n=$1 shape=$2 touch=$3
  z=0
  if [ "$touch" = 1 ]; then # a capsule upright on its end sphere, a box on its face
    z=-1.651
    [ "$shape" = box ] && z=-1.951
  fi
  echo "name: ${shape}s$n"
  echo "parameters: {m: 1.0, g: 9.81, k: 1.0e4, c: 20.0}"
  printf 'coordinates: ['
  for i in $(seq 1 "$n"); do
    printf '%sx%d, y%d, z%d, a%d, b%d, c%d, d%d' "$([ "$i" -gt 1 ] && echo ', ')" \
      "$i" "$i" "$i" "$i" "$i" "$i" "$i"
  done
  echo ']'
  echo 'frames:'
  for i in $(seq 1 "$n"); do
    echo "  f$i: {rotation: {quaternion: [a$i, b$i, c$i, d$i], speeds: [wx$i, wy$i, wz$i]}}"
  done
  echo 'points:'
  for i in $(seq 1 "$n"); do
    echo "  p$i: {at: [x$i + $i, y$i, z$i + 2]}"
  done
  echo 'bodies:'
  for i in $(seq 1 "$n"); do
    if [ "$shape" = capsule ]; then
      s="{type: capsule, size: [0.05, 0.3]}"
    else
      s="{type: box, size: [0.2, 0.1, 0.05], conaffinity: 0}" # (the floor alone)
    fi
    echo "  body$i: {mass: m, frame: f$i, center: p$i, inertia: [0.01, 0.02, 0.03], shapes: [$s]}"
  done
  echo 'ground: [{type: plane, name: floor}]'
  echo 'effects:'
  echo '  gravity: {gravity: [0, 0, -g]}'
  echo '  contact: {contact: all, stiffness: k, damping: c}'
  printf 'initial: {'
  for i in $(seq 1 "$n"); do
    printf '%sa%d: 1, z%d: %s' "$([ "$i" -gt 1 ] && echo ', ')" "$i" "$i" "$z"
  done
  echo '}'
  echo 'scene: {t_end: 1}'
}

# time FILE.c MODEL: contact_time.c's "ns_rhs ns_switches modes_on modes"
time_c() {
  $cc -std=c11 -O1 -I"$inc" -c "$1" -o "$dir/m.o"
  $cc -std=c11 -O1 -I"$inc" -DMODEL="$2" "$src/bench/contact_time.c" "$dir/m.o" "$lib" \
    $gsl_libs -lm -o "$dir/t"
  "$dir/t" 2> /dev/null
}
per_pair() { awk -v a="$1" -v b="$2" -v p="$3" 'BEGIN { printf "%.1f", (b - a) / p }'; }

printf '%8s %3s %5s %7s %7s %7s %11s %11s %8s %8s %7s %10s %10s\n' shape N pairs ops_off ops_on \
  ns_off eager_apart eager_touch ns_apart ns_touch ns_sw pair_eager pair_apart
for shape in capsule box; do
  for n in ${BENCH_N:-1 2 4 8}; do
    for touch in 0 1; do
      gen "$n" "$shape" $touch > "$dir/m$touch.yaml"
    done
    name="${shape}s${n}_model"
    "$eomc" compile "$dir/m0.yaml" --effects gravity -o "$dir/off.c" --stats 2> "$dir/st_off"
    "$eomc" compile "$dir/m0.yaml" --branches eager -o "$dir/eager.c"
    "$eomc" compile "$dir/m1.yaml" --branches eager -o "$dir/eager1.c"
    "$eomc" compile "$dir/m0.yaml" -o "$dir/apart.c" --stats 2> "$dir/st_on"
    "$eomc" compile "$dir/m1.yaml" -o "$dir/touch.c"
    set -- $(time_c "$dir/off.c" "$name") ; off=$1
    set -- $(time_c "$dir/eager.c" "$name") ; eager=$1
    set -- $(time_c "$dir/eager1.c" "$name") ; eager1=$1
    set -- $(time_c "$dir/apart.c" "$name") ; apart=$1 sw=$2
    set -- $(time_c "$dir/touch.c" "$name") ; touch=$1
    pairs=$n
    [ $shape = capsule ] && pairs=$((n + n * (n - 1) / 2))
    ops_off=$(awk '$1 == "mass_bias" { print $6 }' "$dir/st_off")
    ops_on=$(awk '$1 == "mass_bias" { print $6 }' "$dir/st_on")
    printf '%8s %3d %5d %7d %7d %7s %11s %11s %8s %8s %7s %10s %10s\n' $shape "$n" $pairs \
      "$ops_off" "$ops_on" "$off" "$eager" "$eager1" "$apart" "$touch" "$sw" \
      "$(per_pair "$off" "$eager" $pairs)" "$(per_pair "$off" "$apart" $pairs)"
  done
done

# ---- the humanoid standing on its floor, beside mj_forward
model=${BENCH_HUMANOID:-/usr/share/mujoco/model/humanoid/humanoid.xml}
if [ -z "$mjc" ] || [ ! -e "$model" ]; then
  echo "humanoid: skipped (needs MuJoCo, libmujoco-dev, and $model)"
  exit 0
fi
"$eomc" import "$model" -o "$dir/h.yaml" 2> /dev/null
dz=$("$mjc" "$model" drop)
pairs=$("$mjc" "$model" pairs | awk '{ printf "%s[%s, %s]", (NR > 1 ? ", " : ""), $1, $2 }')
npairs=$("$mjc" "$model" pairs | wc -l)
# its floor, the contact effect, the root lowered (a spring and damper
# stiff enough to stand on: the timing does not depend on their values)
python3 - "$dir/h.yaml" "$dz" "$pairs" <<'PY'
import re, sys
path, dz, pairs = sys.argv[1], float(sys.argv[2]), sys.argv[3]
s = open(path).read()
s = s.replace("\neffects:\n", "\nground: [{type: plane, name: floor}]\neffects:\n"
              "  contact: {contact: [%s], stiffness: 1.0e5, damping: 1.0e3}\n" % pairs, 1)
m = re.search(r"\n  root_z: ([-0-9.e]+)\n", s)
s = s.replace(m.group(0), "\n  root_z: %.17g\n" % (float(m.group(1)) - dz))
open(path, "w").write(s)
PY
effects=$(sed -n '/^effects:/,/^[a-z]/p' "$dir/h.yaml" | sed -n 's/^  \([a-z_0-9]*\):.*/\1/p' |
  grep -v '^contact$' | paste -sd, -)
# build: eomc build's objects (its cache's), timed by contact_time.c
build_time() {
  rm -rf "$dir/cache"
  EOMC_CACHE_DIR="$dir/cache" "$eomc" build "$dir/h.yaml" "$@" -o "$dir/hsim" 2> /dev/null
  objs=
  for o in "$dir/cache"/objects/*.o; do
    nm --defined-only "$o" | grep -q ' T main$' || objs="$objs $o"
  done
  # shellcheck disable=SC2086 # lists
  $cc -std=c11 -O1 -I"$inc" -DMODEL=Humanoid_model "$src/bench/contact_time.c" $objs "$lib" \
    $gsl_libs -lm -o "$dir/ht"
  "$dir/ht" 2> /dev/null
}
set -- $(build_time --effects "$effects"); h_off=$1
set -- $(build_time --branches eager); h_eager=$1
set -- $(build_time); h_lazy=$1 h_sw=$2 h_near=$5
set -- $("$mjc" "$model" time "$dz"); mj=$1 ncon=$2
set -- $("$mjc" "$model" time "$dz" frictionless); mj_nf=$1
echo
# body pairs (MuJoCo's), of which near at the state (eomc's shape pairs
# are more: a foot has two capsules), ns per right-hand side: off, every
# branch, lazy; ns per switches call; mj_forward with and without
# friction, its contacts; mj_forward / eomc's lazy right-hand side
printf '%-10s %6s %5s %8s %8s %8s %8s %10s %10s %7s %7s\n' model pairs near ns_off ns_eager \
  ns_lazy ns_sw mj_ns mj_ns_nofr mj_ncon ratio
printf '%-10s %6s %5s %8s %8s %8s %8s %10s %10s %7s %7s\n' humanoid "$npairs" "$h_near" "$h_off" \
  "$h_eager" "$h_lazy" "$h_sw" "$mj" "$mj_nf" "$ncon" \
  "$(awk -v a="$mj" -v b="$h_lazy" 'BEGIN { printf "%.2f", a / b }')"
