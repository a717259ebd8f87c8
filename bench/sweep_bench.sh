#!/bin/sh
# A sweep of 1000 runs of chain5 (g from 9 to 10.5, its scene: 10 s each, rk8pd at
# the scene's 1e-10): serial, on 2 threads, and on 2 MPI ranks (when
# mpicc is installed), wall-clock seconds and the speed-ups of one run
# of this script; and the check that the three summaries are the same
# bytes.
# usage: sweep_bench.sh EOMC SOURCE_ROOT
set -eu
eomc=$1 src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
now() { date +%s.%N; }
"$eomc" build "$src/specs/chain5.yaml" -o "$dir/chain5" 2> /dev/null
args="--sweep g=9:10.5:1000"
t0=$(now); "$dir/chain5" $args -o "$dir/serial.csv"; t1=$(now)
"$dir/chain5" $args --threads 2 -o "$dir/threads.csv"; t2=$(now)
serial=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
threads=$(awk -v a="$t1" -v b="$t2" 'BEGIN { printf "%.3f", b - a }')
printf '%-12s %8s %8s\n' how seconds speedup
printf '%-12s %8s %8s\n' serial "$serial" 1.00
printf '%-12s %8s %8s\n' threads:2 "$threads" "$(awk -v a="$serial" -v b="$threads" 'BEGIN { printf "%.2f", a / b }')"
fail=0
cmp -s "$dir/serial.csv" "$dir/threads.csv" || { echo "FAIL: threads' summary differs"; fail=1; }
if command -v mpicc > /dev/null && command -v mpirun > /dev/null; then
  "$eomc" build "$src/specs/chain5.yaml" --mpi -o "$dir/chain5_mpi" 2> /dev/null
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  t3=$(now); mpirun --oversubscribe -n 2 "$dir/chain5_mpi" $args -o "$dir/mpi.csv" > /dev/null 2>&1; t4=$(now)
  mpi=$(awk -v a="$t3" -v b="$t4" 'BEGIN { printf "%.3f", b - a }')
  printf '%-12s %8s %8s\n' mpi:2 "$mpi" "$(awk -v a="$serial" -v b="$mpi" 'BEGIN { printf "%.2f", a / b }')"
  cmp -s "$dir/serial.csv" "$dir/mpi.csv" || { echo "FAIL: MPI's summary differs"; fail=1; }
else
  echo "mpi:2        (mpicc not installed)"
fi
exit $fail
