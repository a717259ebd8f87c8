#!/usr/bin/env bash
# Run the libFuzzer targets for a bounded time each:
#
#     tests/fuzz/run_fuzz.sh SECONDS [spec|expr|pipeline|runtime]...
#
# Builds the targets in build-fuzz (set up with clang and -Dfuzz=true if
# it does not exist), assembles seed corpora in a temporary directory
# (specs/*.yaml, tests/errors/*.yaml, tests/fuzz/regressions/spec and the
# examples of docs/spec.md for the spec targets; the expressions of specs and
# tests/fuzz/regressions/expr for the expression target;
# tests/fuzz/regressions/runtime for the simulator's command line, whose
# messages are not kept: -close_fd_mask=2), runs each target for SECONDS,
# and prints one line per target:
#
#     fuzz_spec: ok, 60 s, 123456 execs, 789 inputs in the corpus
#     fuzz_spec: FAILED (crash-...): see /tmp/eomc-fuzz-XXXX/fuzz_spec.log
#
# Exits non-zero if any target crashed, leaked, hung or ran out of memory;
# then the work directory (logs, the input that failed) is kept.  Set
# FUZZ_WORK=DIR to keep corpora and logs in DIR in any case (a later run
# with the same DIR goes on from its corpora), FUZZ_ARGS to pass more
# options to libFuzzer (e.g. -len_control=0 -seed=1), FUZZ_JOBS=N to run N
# targets at once.
set -uo pipefail
cd "$(dirname "$0")/../.."

secs=${1:?usage: tests/fuzz/run_fuzz.sh SECONDS [spec|expr|pipeline|runtime]...}
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(spec expr pipeline runtime)

if [ ! -d build-fuzz ]; then
  CC=clang meson setup build-fuzz -Dfuzz=true >/dev/null || {
    echo "run_fuzz: cannot set up build-fuzz (clang and libclang-rt needed)"
    exit 2
  }
fi
bins=()
for t in "${targets[@]}"; do bins+=("tests/fuzz/fuzz_$t"); done
ninja -C build-fuzz "${bins[@]}" >/tmp/eomc-fuzz-build.$$.log 2>&1 || {
  cat /tmp/eomc-fuzz-build.$$.log
  rm -f /tmp/eomc-fuzz-build.$$.log
  echo "run_fuzz: build failed"
  exit 2
}
rm -f /tmp/eomc-fuzz-build.$$.log

if [ -n "${FUZZ_WORK:-}" ]; then
  work=$FUZZ_WORK
  keep=1
  mkdir -p "$work"
else
  work=$(mktemp -d /tmp/eomc-fuzz-XXXXXX)
  keep=0
fi

# Seeds.  Spec targets: the shipped specs, the error cases, the regressions,
# and the YAML examples of docs/spec.md.
mkdir -p "$work/seed-spec" "$work/seed-expr" "$work/seed-runtime"
for f in specs/*.yaml tests/errors/*.yaml tests/fuzz/regressions/spec/*; do
  [ -f "$f" ] && cp "$f" "$work/seed-spec/$(echo "$f" | tr / _)"
done
awk -v dir="$work/seed-spec" '/^```yaml/ { n++; f = 1; next } /^```/ { f = 0 }
  f { print > (dir "/docs_spec_md_" n ".yaml") }' docs/spec.md
# Expression target: every value of a spec line that looks like one
# ("key: value" or "- value", comments cut), and the regressions.
n=0
for f in specs/*.yaml tests/errors/*.yaml; do
  [ -f "$f" ] || continue
  sed -n -e 's/#.*//' -e 's/^[^:]*:[[:space:]]*\(.*[^[:space:]]\)[[:space:]]*$/\1/p' \
         -e 's/^[[:space:]]*-[[:space:]]*\([^:]*[^[:space:]:]\)[[:space:]]*$/\1/p' "$f" |
    grep -v '^[{[]' | sort -u
done | while IFS= read -r line; do
  n=$((n + 1))
  printf '%s' "$line" >"$work/seed-expr/spec-$n"
done
for f in tests/fuzz/regressions/expr/*; do
  [ -f "$f" ] && cp "$f" "$work/seed-expr/regression-$(basename "$f")"
done
for f in tests/fuzz/regressions/runtime/*; do
  [ -f "$f" ] && cp "$f" "$work/seed-runtime/$(basename "$f")"
done

# fuzz_one TARGET: run it, and write its line (and, on failure, the
# first line that says why) to $work/result-TARGET
fuzz_one() {
  local t=$1 seeds dict max_len quiet log rc execs size artifact out
  case $t in
  spec | pipeline) seeds=seed-spec dict=spec.dict max_len=65536 quiet= ;;
  expr) seeds=seed-expr dict=expr.dict max_len=16384 quiet= ;;
  runtime) seeds=seed-runtime dict=runtime.dict max_len=4096 quiet=-close_fd_mask=2 ;;
  *) echo "run_fuzz: unknown target '$t' FAILED" > "$work/result-$t"; return ;;
  esac
  mkdir -p "$work/corpus-$t"
  log=$work/fuzz_$t.log
  out=$work/result-$t
  build-fuzz/tests/fuzz/fuzz_"$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
    -max_len=$max_len -dict=tests/fuzz/$dict -print_final_stats=1 $quiet \
    -artifact_prefix="$work/fuzz_$t-" ${FUZZ_ARGS:-} "$work/corpus-$t" "$work/$seeds" >"$log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  size=$(find "$work/corpus-$t" -type f | wc -l)
  if [ "$rc" -eq 0 ]; then
    echo "fuzz_$t: ok, $secs s, ${execs:-?} execs, $size inputs in the corpus" > "$out"
  else
    artifact=$(ls "$work/fuzz_$t-"* 2>/dev/null | head -1)
    echo "fuzz_$t: FAILED (exit $rc${artifact:+, input $artifact}): see $log" > "$out"
    grep -m1 -E '^==[0-9]+==ERROR|SUMMARY|runtime error|internal error|exited' "$log" |
      sed 's/^/  /' >> "$out"
  fi
}

# FUZZ_JOBS targets at a time (default 1): each target is one process,
# so a machine with N cores runs N of them in the time of one
jobs=${FUZZ_JOBS:-1}
running=0
for t in "${targets[@]}"; do
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
wait
failed=0
for t in "${targets[@]}"; do
  cat "$work/result-$t"
  if grep -q FAILED "$work/result-$t"; then
    failed=1
    keep=1
  fi
done
if [ "$keep" -eq 0 ]; then
  rm -rf "$work"
else
  echo "run_fuzz: work directory kept: $work"
fi
exit $failed
