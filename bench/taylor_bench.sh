#!/bin/sh
# Taylor's method beside rk8pd, measured in the same run (issue 26's
# targets; `meson test -C build --benchmark taylor`):
#  - chain5 from q1 = 1 (t = 0 to 10, 1001 rows): the report's error_max
#    against the extended-precision reference and CPU time of each method
#    over tolerances 1e-8 .. 1e-16, and for each error level the cheapest
#    run of each that reaches it;
#  - Kepler, e = 0.6: the energy's largest relative change over 100,
#    1 000 and 10 000 periods (rows once a period, computed here from
#    them), taylor at 1e-15 and at 1e-18 (its truncation below rounding)
#    and rk8pd at 1e-14 (its tightest that does not grind), with CPU
#    time, and each one's growth from 100 to 10 000 periods against
#    sqrt(100) = 10;
#  - the reference by extrapolation and by Taylor's method in long double
#    (--reference-method taylor) on chain5, the Cartesian pendulum and the
#    car axis: the error each claims and its CPU time;
#  - the checks after the steps, their share of a run (below).
# Prints the figures; the targets are the issue's, and the lines say which
# are met.  usage: taylor_bench.sh EOMC SOURCE_ROOT
set -eu
eomc=$1 src=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
export EOMC_CACHE_DIR="$dir/cache"

echo "chain5, q1 = 1: error_max against the reference and CPU seconds"
"$eomc" accuracy "$src/specs/chain5.yaml" --init q1=1.0 --methods taylor,rk8pd \
    --tolerances 1e-8,1e-10,1e-12,1e-13,1e-14,1e-15,1e-16 --csv "$dir/c5.csv" > "$dir/c5.txt"
awk -F, 'NR > 1 { printf "  %-7s rtol %-6s error_max %-9.3g cpu %.3g ms%s\n", $1, $2, $10, $4 * 1e3,
    $13 != "" ? sprintf(", order %s", $13) : "" }' "$dir/c5.csv"
scale=$(sed -n 's/.*digits of the largest entry, \([0-9.e+-]*\)).*/\1/p' "$dir/c5.txt")
for level in 1e-12 1e-13 "$(awk -v s="$scale" 'BEGIN { printf "%.3g", 1e-15 * s }')"; do
    awk -F, -v lev="$level" 'NR > 1 && $10 != "" && $10 <= lev {
        if (!($1 in best) || $4 < best[$1]) best[$1] = $4 }
        END { t = ("taylor" in best) ? sprintf("%.3g ms", best["taylor"] * 1e3) : "not reached"
              r = ("rk8pd" in best) ? sprintf("%.3g ms", best["rk8pd"] * 1e3) : "not reached"
              printf "  error_max <= %s: taylor %s, rk8pd %s\n", lev, t, r }' "$dir/c5.csv"
done
rkbest=$(awk -F, 'NR > 1 && $1 == "rk8pd" && $10 != "" { if (min == "" || $10 < min) { min = $10; t = $4 } }
    END { print min, t }' "$dir/c5.csv")
set -- $rkbest
awk -F, -v e="$1" -v t="$2" 'NR > 1 && $1 == "taylor" && $10 != "" && $10 <= 1e-13 {
    if (c == "" || $4 < c) c = $4 }
    END {
        if (c == "") verdict = "missed (not reached)"
        else if (c <= t / 4) verdict = sprintf("met (%.3g ms)", c * 1e3)
        else verdict = sprintf("missed (%.3g ms, %.1f times the quarter)", c * 1e3, c / (t / 4))
        printf "  target: error_max <= 1e-13 in at most a quarter of the time rk8pd takes to its best (%.3g in %.3g ms): %s\n", e, t * 1e3, verdict
    }' "$dir/c5.csv"

echo "Kepler, e = 0.6: the energy's largest relative change, rows once a period"
period=6.283185307179586
for n in 100 1000 10000; do
    t_end=$(awk -v n="$n" -v p="$period" 'BEGIN { printf "%.17g", n * p }')
    for m in "taylor 1e-15" "taylor 1e-18" "rk8pd 1e-14"; do
        set -- $m
        "$eomc" run "$src/specs/kepler.yaml" --set e=0.6 --method "$1" --rtol "$2" --atol "$2" \
            --t-end "$t_end" --dt "$period" --stats -o "$dir/k.csv" 2> "$dir/k.err"
        cpu=$(sed -n 's/^cpu_seconds //p' "$dir/k.err")
        steps=$(sed -n 's/^steps //p' "$dir/k.err")
        awk -F, -v n="$n" -v m="$1" -v tol="$2" -v cpu="$cpu" -v steps="$steps" 'NR > 1 {
            e = ($4 * $4 + $5 * $5) / 2 - 1 / sqrt($2 * $2 + $3 * $3)
            if (NR == 2) e0 = e; d = (e - e0) / e0; if (d < 0) d = -d; if (d > mx) mx = d }
            END { printf "  %5d periods: %-6s at %s: %.3g (%d steps, %.3g s)\n", n, m, tol, mx,
                  steps, cpu; printf "%s %s %d %.17g\n", m, tol, n, mx >> growth }' \
            growth="$dir/growth" "$dir/k.csv"
    done
done
awk '{ key = $1 " at " $2; if ($3 == 100) a[key] = $4; if ($3 == 10000) b[key] = $4 }
    END { for (k in a) printf "  growth from 100 to 10 000 periods, %s: %.3g (sqrt of time: 10)\n",
          k, b[k] / a[k] }' "$dir/growth" | sort

echo "The reference two ways: the error each claims and its CPU seconds"
for spec in "specs/chain5.yaml --init q1=1.0" specs/cartesian_pendulum.yaml \
            tests/hard/specs/car_axis.yaml; do
    set -- $spec
    file=$1
    shift
    for how in extrapolation taylor; do
        "$eomc" accuracy "$src/$file" "$@" --methods rk8pd --tolerances 1e-8 \
            --reference-method $how > "$dir/ref.txt" 2> /dev/null
        sed -n 's/.*its error is at most \([0-9.e+-]*\).*computed in \([0-9.e+-]*\) s.*/\1 \2/p' \
            "$dir/ref.txt" | awk -v f="$(basename "$file" .yaml)" -v h="$how" \
            '{ printf "  %-20s %-13s claims %s in %s s\n", f, h, $1, $2 }'
    done
done

# The checks after the steps (the condition estimates, the conserved
# quantity's budget): their share of a run, --stats' monitor_seconds over
# cpu_seconds (the two clocks differ: on a busy machine the share reads
# high).  The issue's target: each under 5 % of a run's instructions
# (docs/numerics.md has them measured by callgrind, one by one).
echo "The checks after the steps: chain5 from q1 = 1 over 100 s at 1e-10, their share of the run"
for m in rk2 rkf45 rk8pd msadams taylor; do
    "$eomc" run "$src/specs/chain5.yaml" --init q1=1.0 --method $m --rtol 1e-10 --atol 1e-10 \
        --t-end 100 --dt 10 --stats -o /dev/null 2> "$dir/m.err"
    awk -v m=$m '/^cpu_seconds / { c = $2 } /^monitor_seconds / { s = $2 }
        END { printf "  %-8s %.3g of %.3g s, %.1f %%\n", m, s, c, 100 * s / c }' "$dir/m.err"
done

# Issue 46: the Pleiades (t = 0 to 3) and the outer solar system (200 000
# days), each against its reference at the end computed with mpmath
# outside eomc (tests/sim/*_reference.csv).  The error of a run is the
# largest difference at the end relative to the largest entry of the
# same kind (positions, velocities); each method's CPU is its least over
# 5 runs, taylor and rk8pd in turns, with two rows (the integration, not
# the CSV).  At equal error: taylor at a tolerance against rk8pd's
# cheapest run that is at least as accurate.  Instructions a step by
# callgrind where valgrind is installed (Kepler too, 100 periods).
echo "N-body problems against their mpmath references (least CPU of 5 runs, in turns)"
nbody_error() { # run.csv reference.csv: the error at the end
    awk -F, 'FNR == 1 && $0 !~ /^#/ && $1 == "t" { next } /^#/ || /^t,/ { next }
        FILENAME == ARGV[1] { last_run = $0; next } { last_ref = $0 }
        END { split(last_run, a, ","); n = split(last_ref, b, ","); h = (n - 1) / 2
              for (i = 2; i <= n; i++) { k = (i - 2 < h) ? 0 : 1; d = a[i] - b[i]
                  if (d < 0) d = -d; s = b[i] < 0 ? -b[i] : b[i]
                  if (d > err[k]) err[k] = d; if (s > big[k]) big[k] = s }
              e = err[0] / big[0]; if (err[1] / big[1] > e) e = err[1] / big[1]; printf "%.3g", e }' \
        "$1" "$2"
}
for spec in pleiades outer_solar_system; do
    ref="$src/tests/sim/${spec}_reference.csv"
    t_end=$(awk -F, '!/^#/ && !/^t,/ { t = $1 } END { print t }' "$ref")
    start=$(date +%s.%N)
    "$eomc" build "$src/specs/$spec.yaml" -o "$dir/$spec" 2> /dev/null
    end=$(date +%s.%N)
    awk -v s="$start" -v e="$end" -v n="$spec" \
        'BEGIN { printf "  %s: built in %.2f s%s\n", n, e - s, n == "pleiades" ? " (target <= 3 s)" : "" }'
    : > "$dir/$spec.runs"
    for tol in 1e-10 1e-12 1e-13 1e-14 1e-15; do
        for m in taylor rk8pd; do
            "$dir/$spec" --method $m --rtol $tol --atol $tol --t-end "$t_end" --dt "$t_end" \
                --stats -o "$dir/n.csv" 2> "$dir/n.err"
            err=$(nbody_error "$dir/n.csv" "$ref")
            steps=$(sed -n 's/^steps //p' "$dir/n.err")
            best=""
            for r in 1 2 3 4 5; do
                "$dir/$spec" --method $m --rtol $tol --atol $tol --t-end "$t_end" --dt "$t_end" \
                    --stats -o /dev/null 2> "$dir/n.err"
                c=$(sed -n 's/^cpu_seconds //p' "$dir/n.err")
                best=$(awk -v a="$best" -v b="$c" 'BEGIN { print (a == "" || b < a) ? b : a }')
            done
            echo "$m $tol $err $best $steps" >> "$dir/$spec.runs"
            printf '  %-18s %-6s rtol %-6s error %-9s cpu %.3g ms, %s steps\n' "$spec" $m $tol \
                "$err" "$(awk -v c="$best" 'BEGIN { print c * 1e3 }')" "$steps"
        done
    done
    for level in 1e-12 1e-15; do
        [ $spec = outer_solar_system ] && [ $level = 1e-15 ] && continue
        target=$([ $spec = pleiades ] && echo 0.8 || echo 0.35)
        awk -v lev=$level -v tgt=$target -v n=$spec '
            $1 == "taylor" && $2 == lev { te = $3; tc = $4 }
            $1 == "rk8pd" { e[NR] = $3; c[NR] = $4 }
            END { for (i in e) if (e[i] <= te && (rc == "" || c[i] < rc)) rc = c[i]
                  if (rc == "") { printf "  %s, taylor at %s (error %s): no rk8pd run as accurate\n", n, lev, te; exit }
                  r = tc / rc
                  printf "  %s, taylor at %s (error %s) against rk8pd at least as accurate: %.3g of its time%s\n",
                      n, lev, te, r, lev == "1e-12" ? sprintf(" (target <= %s: %s)", tgt, r <= tgt ? "met" : "missed") : "" }' \
            "$dir/$spec.runs"
    done
done
# A sweep's runs four at a time (--batch 4, one series for four lanes)
# against one at a time (--batch 1), in the same process kind: 1000
# Kepler orbits, e = 0.1 .. 0.7, 100 periods each, one row at the end;
# CPU of the whole sweep (children's user + system), least of 3 rounds
# in turns.  The rows are the same bytes (tests/cli/test_sweep.sh).
echo "A sweep: 1000 Kepler runs (e = 0.1 .. 0.7, 100 periods), taylor at 1e-15"
"$eomc" build "$src/specs/kepler.yaml" --taylor -o "$dir/kep" 2> /dev/null
cpu_of() { # the command's CPU seconds
    python3 -c 'import resource, subprocess, sys
subprocess.run(sys.argv[1:], check=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(r.ru_utime + r.ru_stime)' "$@"
}
for round in 1 2 3; do
    for b in 1 4; do
        c=$(cpu_of "$dir/kep" --method taylor --rtol 1e-15 --atol 1e-15 --sweep e=0.1:0.7:1000 \
            --t-end 628.3185307179586 --dt 628.3185307179586 --batch $b -o "$dir/sweep$b.csv")
        echo "$b $c" >> "$dir/sweep.cpu"
    done
done
cmp -s "$dir/sweep1.csv" "$dir/sweep4.csv" || echo "  (the rows differ: a defect)"
awk '{ if (!($1 in m) || $2 < m[$1]) m[$1] = $2 }
    END { r = m[4] / m[1]
          printf "  --batch 1: %.3g ms a run; --batch 4: %.3g ms a run: %.3g of it (target <= 0.4: %s)\n",
              m[1], m[4], r, r <= 0.4 ? "met" : "missed" }' "$dir/sweep.cpu"

if command -v valgrind > /dev/null 2>&1; then
    ipstep() { # what steps: instructions a step, all in (two rows)
        valgrind --tool=callgrind --callgrind-out-file="$dir/cg.out" "$@" --stats -o /dev/null \
            2> "$dir/cg.err" > /dev/null
        awk '/^steps / { s = $2 } /refs:/ { gsub(",", "", $NF); i = $NF } END { printf "%.0f", i / s }' \
            "$dir/cg.err"
    }
    "$eomc" build "$src/specs/kepler.yaml" --taylor -o "$dir/kepler" 2> /dev/null
    period=6.283185307179586
    # the issue's target is at order 15, rtol 1e-12 (the order rule's);
    # the bench's Kepler runs above are at 1e-15, order 19
    for m in "1e-12 15 (target <= 4000)" "1e-15 19"; do
        set -- $m
        tol=$1 order=$2
        shift 2
        k=$(ipstep "$dir/kepler" --set e=0.6 --method taylor --rtol $tol --atol $tol \
            --t-end 628.3185307179586 --dt 628.3185307179586)
        echo "  instructions a step (callgrind, all in): Kepler at $tol (order $order) $k $*"
    done
    k=$(ipstep "$dir/pleiades" --method taylor --rtol 1e-12 --atol 1e-12 --t-end 3 --dt 3)
    echo "  instructions a step (callgrind, all in): the Pleiades at 1e-12 (order 15) $k (target <= 50000)"
else
    echo "  (no valgrind: instructions a step not counted)"
fi
