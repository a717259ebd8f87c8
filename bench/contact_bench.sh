#!/bin/sh
# What contact pairs cost a right-hand side when none touches: N free
# capsules (a free joint each: centre and unit quaternion with speeds)
# high over a floor plane, `contact: all` (N capsule-plane pairs, two
# contacts each, and N (N - 1)/2 capsule-capsule pairs); and N free boxes
# over the floor (N pairs of 8 corners each; the boxes' conaffinity 0:
# not each other).  Each model compiled with
# the contact on and off (--effects gravity), and timed:
#   pairs       the pairs the contact has
#   ops_off, ops_on   operations of the generated mass_bias (--stats)
#   ns_off, ns_on     ns per call of the model's accel (M, h and their
#               unrolled solve: a right-hand side's generated part; mass_bias
#               where it has none), the modes all 0 (apart); the best of 9
#               runs of enough calls for 50 ms
#   ns_pair     (ns_on - ns_off) / pairs
# usage: contact_bench.sh EOMC SOURCE_ROOT RUNTIME_INCLUDE RUNTIME_LIB
# $BENCH_N: the N to run (default "1 2 4 8").
set -eu
eomc=$1 src=$2 inc=$3 lib=$4
cc=${CC:-cc}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
gsl_libs=$(pkg-config --libs gsl)

# the model: N bodies of SHAPE ("capsule" or "box") 1 apart along x, 2 up
gen() {
  n=$1 shape=$2
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
    printf '%sa%d: 1' "$([ "$i" -gt 1 ] && echo ', ')" "$i"
  done
  echo '}'
  echo 'scene: {t_end: 1}'
}

cat > "$dir/time.c" <<'EOF'
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "eomc.h"
extern const eomc_model MODEL;
static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}
int main(void) {
    const eomc_model *m = &MODEL;
    eomc_sim *s = eomc_sim_alloc(m);
    int n = m->nq, nv = eomc_nv(m);
    double *q = calloc(n, sizeof *q), *v = calloc(nv, sizeof *v);
    double *M = calloc((size_t)nv * nv, sizeof *M), *h = calloc(nv, sizeof *h);
    double *u = calloc(m->nu + m->nmode + 1, sizeof *u), sum = 0; /* the modes 0: apart */
    double *a = calloc(nv, sizeof *a);
    eomc_sim_initial(s, q, v);
    for (int j = 0; j < nv; j++)
        v[j] = 0.1 * (j % 3);
    const double *p = eomc_sim_params(s);
    long calls = 1;
    double t0, t1, best = 1e30;
    do {
        calls *= 4;
        t0 = now();
        for (long k = 0; k < calls; k++) {
            q[0] = 1e-9 * (double)k; /* defeat hoisting */
            if (m->accel)
                m->accel(0, q, v, p, u, a, NULL);
            else
                m->mass_bias(0, q, v, p, u, M, a);
            sum += a[nv - 1];
        }
        t1 = now();
    } while (t1 - t0 < 0.05);
    for (int r = 0; r < 9; r++) {
        t0 = now();
        for (long k = 0; k < calls; k++) {
            q[0] = 1e-9 * (double)k;
            if (m->accel)
                m->accel(0, q, v, p, u, a, NULL);
            else
                m->mass_bias(0, q, v, p, u, M, a);
            sum += a[nv - 1];
        }
        t1 = now();
        if (t1 - t0 < best)
            best = t1 - t0;
    }
    printf("%.1f\n", best / (double)calls * 1e9);
    fprintf(stderr, "(checksum %g)\n", sum);
    eomc_sim_free(s);
    return 0;
}
EOF

printf '%8s %3s %6s %8s %8s %8s %8s %8s\n' shape N pairs ops_off ops_on ns_off ns_on ns_pair
for shape in capsule box; do
  for n in ${BENCH_N:-1 2 4 8}; do
    gen "$n" "$shape" > "$dir/m.yaml"
    for on in off on; do
      effects=gravity
      [ $on = on ] && effects=gravity,contact
      "$eomc" compile "$dir/m.yaml" --effects $effects -o "$dir/m_$on.c" --stats 2> "$dir/st_$on"
      $cc -std=c11 -O1 -I"$inc" -c "$dir/m_$on.c" -o "$dir/m_$on.o"
      $cc -std=c11 -O1 -I"$inc" -DMODEL="${shape}s${n}_model" "$dir/time.c" "$dir/m_$on.o" \
        "$lib" $gsl_libs -lm -o "$dir/t_$on"
    done
    pairs=$n
    [ $shape = capsule ] && pairs=$((n + n * (n - 1) / 2))
    ops_off=$(awk '$1 == "mass_bias" { print $6 }' "$dir/st_off")
    ops_on=$(awk '$1 == "mass_bias" { print $6 }' "$dir/st_on")
    ns_off=$("$dir/t_off" 2>/dev/null) ns_on=$("$dir/t_on" 2>/dev/null)
    printf '%8s %3d %6d %8d %8d %8s %8s %8s\n' $shape "$n" $pairs "$ops_off" "$ops_on" "$ns_off" \
      "$ns_on" "$(awk -v a="$ns_off" -v b="$ns_on" -v p=$pairs 'BEGIN { printf "%.1f", (b - a) / p }')"
  done
done
