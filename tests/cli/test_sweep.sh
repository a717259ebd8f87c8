#!/bin/sh
# Parameter sweeps (TAP): --sweep grids and --sweep-file rows, the
# summary's header and order, each row equal to the same run made alone
# with --set, a failing run among good ones (its error as status, the
# others go on), and the same bytes whatever the threads and, when mpicc
# is there, the MPI ranks.
# usage: test_sweep.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
pend="$src/specs/pendulum.yaml"
"$eomc" build "$pend" -o "$tmp/pend" 2> /dev/null

"$tmp/pend" --sweep g=5:15:3 --sweep l=0.5:1:2 --t-end 1 -o "$tmp/grid.csv"; st=$?
head -1 "$tmp/grid.csv" | grep -qx "g,l,status,t,theta,theta'" &&
    [ "$(cut -d, -f1,2 "$tmp/grid.csv" | tail -n +2 | tr '\n' ' ')" = "5,0.5 5,1 10,0.5 10,1 15,0.5 15,1 " ]
ok $? "the header g,l,status,t,theta,theta', and the grid in order, the last sweep fastest"
"$tmp/pend" --set g=10 --set l=0.5 --t-end 1 | tail -1 > "$tmp/alone.csv"
want=$(cut -d, -f1-3 "$tmp/alone.csv")
got=$(sed -n 4p "$tmp/grid.csv" | cut -d, -f4-6)
[ $st -eq 0 ] && [ "$got" = "$want" ]
ok $? "the row g = 10, l = 0.5 is the run made alone with --set: $got"

printf 'm,l\n1,1\n-1,1\n2,0.5\n' > "$tmp/sets.csv"
"$tmp/pend" --sweep-file "$tmp/sets.csv" --t-end 1 -o "$tmp/file.csv"; st=$?
sed -n 3p "$tmp/file.csv" | grep -q '^-1,1,"particle .bob.: a mass cannot be negative' &&
    [ "$(sed -n 2p "$tmp/file.csv" | cut -d, -f3)" = ok ] &&
    [ "$(sed -n 4p "$tmp/file.csv" | cut -d, -f3)" = ok ] && [ $st -eq 0 ]
ok $? "--sweep-file: the failing run (m = -1) has its error as status, the others run"
# l = 0 makes M = m l^2 = 0: exactly the two runs with it fail, and the
# sweep says so on stderr, naming the first
"$tmp/pend" --sweep l=-1:1:3 --sweep g=1:2:2 --t-end 1 -o "$tmp/fail.csv" 2> "$tmp/fail.err"; st=$?
[ $st -eq 0 ] && [ "$(cut -d, -f3 "$tmp/fail.csv" | grep -c '^ok$')" -eq 4 ] &&
  grep -qx "pend: warning: 2 of 6 runs failed (each row's status says why); the first: l = 0, g = 1: t = 0: mass matrix is singular or not positive definite (pivot 1, coordinate theta); state: theta = 1, theta' = 0" "$tmp/fail.err"
ok $? "failed runs: one warning counting them (2 of 6, l = 0) and naming the first"

"$tmp/pend" --sweep g=1:20:40 --t-end 2 -o "$tmp/serial.csv" 2> "$tmp/serial.err"
"$tmp/pend" --sweep g=1:20:40 --t-end 2 --threads 2 -o "$tmp/threads.csv"
"$tmp/pend" --sweep g=1:20:40 --t-end 2 --threads 7 -o "$tmp/threads7.csv"
cmp -s "$tmp/serial.csv" "$tmp/threads.csv" && cmp -s "$tmp/serial.csv" "$tmp/threads7.csv" &&
  [ -e "$tmp/serial.err" ] && [ ! -s "$tmp/serial.err" ]
ok $? "--threads 2 and 7: the same bytes as serial (40 runs); no run failed, nothing said"

if [ -z "${EOMC_TEST_NO_MPI:-}" ] && command -v mpicc > /dev/null && command -v mpirun > /dev/null; then
    "$eomc" build "$pend" --mpi -o "$tmp/pend_mpi" 2> "$tmp/mpi.err"; st=$?
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    for k in 2 3; do
        mpirun --oversubscribe -n $k "$tmp/pend_mpi" --sweep g=1:20:40 --t-end 2 \
            -o "$tmp/mpi$k.csv" > /dev/null 2>&1
    done
    [ $st -eq 0 ] && cmp -s "$tmp/serial.csv" "$tmp/mpi2.csv" &&
        cmp -s "$tmp/serial.csv" "$tmp/mpi3.csv"
    ok $? "eomc build --mpi; mpirun -n 2 and -n 3: the same bytes as serial"
else
    echo "ok $((n + 1)) # SKIP no MPI here (not installed, or a sanitizer build)"
    n=$((n + 1))
fi

"$tmp/pend" --sweep theta0=0:1:2 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "'theta0' is not a parameter" "$tmp/err"
ok $? "a name that is not a parameter: exit $st"
"$eomc" build "$src/specs/swing.yaml" -o "$tmp/swing" 2> /dev/null
"$tmp/swing" --sweep A=0:1:2 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "fixed in scene 'free'" "$tmp/err"
ok $? "a fixed parameter cannot be swept: exit $st, naming the scene"
printf 'm,l\n1,x\n' > "$tmp/bad.csv"
"$tmp/pend" --sweep-file "$tmp/bad.csv" -o "$tmp/none.csv" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "bad.csv:2:3: expected 2 finite numbers" "$tmp/err" && [ ! -e "$tmp/none.csv" ]
ok $? "a bad value in --sweep-file: FILE:LINE:COLUMN, exit $st, no summary file"
"$tmp/pend" --sweep g=1:2:0 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ]
ok $? "COUNT 0: exit $st"
# (fuzz_runtime's finds: a header with an empty name read as having fewer
# columns, and with none freed the values twice after 64 rows; a bad COUNT
# overflowed the count of runs)
{ echo 'g,'; seq 70; } > "$tmp/noname.csv"
"$tmp/pend" --sweep-file "$tmp/noname.csv" -o "$tmp/none.csv" 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "noname.csv:1:3: an empty name: the header names the parameter of every column" "$tmp/err" &&
  [ ! -e "$tmp/none.csv" ]
ok $? "an empty name in --sweep-file's header: FILE:LINE:COLUMN, exit $st, no summary file"
"$tmp/pend" --sweep g=1:2:3 --sweep l=1:2:8888888888888888882:8 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "l=1:2:8888888888888888882:8: expected START:STOP:COUNT" "$tmp/err"
ok $? "a COUNT that is not one: exit $st, naming it"
"$tmp/pend" --threads 2 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'runs the runs of a sweep' "$tmp/err"
ok $? "--threads without a sweep: exit $st"

# --assemble applies to each run of a sweep, as to a single run: the
# Cartesian pendulum started off its rod (x = 1.2) is put on it, and
# without stabilization stays on it, so at the end x^2 + y^2 = l^2 for
# every l (it was ignored: the runs drifted from 1.2^2 + y^2)
"$eomc" run "$src/specs/cartesian_pendulum.yaml" --init x=0.6 --assemble --hold x \
    --sweep l=1:2:3 --t-end 0.5 -o "$tmp/asm.csv" 2> /dev/null; st=$?
[ $st -eq 0 ] && [ "$(wc -l < "$tmp/asm.csv")" -eq 4 ] &&
    awk -F, 'NR > 1 { d = $4 * $4 + $5 * $5 - $1 * $1; if (d < 0) d = -d
        if ($2 != "ok" || d > 1e-8 * $1 * $1) bad = 1 } END { exit bad }' "$tmp/asm.csv"
ok $? "--assemble --hold x in a sweep: each run starts on its rod (x^2 + y^2 = l^2 at the end, l = 1, 1.5, 2)"

# --batch: a Taylor sweep's runs four at a time, one series for the four
# lanes (eomc_model.h's taylor_run4), each lane with its own steps and
# events.  The rows are the single runs' to the bit, and the motion's own
# values: Kepler's orbit back at periapsis after three periods, x = a (1 -
# e), y = 0; the ball's height at 1.2 s from its bounces in closed form.
kep="$src/specs/kepler.yaml"
"$eomc" build "$kep" --taylor -o "$tmp/kep" 2> /dev/null
kt="--method taylor --rtol 1e-15 --atol 1e-15"
"$tmp/kep" $kt --sweep e=0.1:0.7:13 --batch 1 -o "$tmp/kb1.csv"; st1=$?
"$tmp/kep" $kt --sweep e=0.1:0.7:13 -o "$tmp/kb4.csv"; st4=$?
"$tmp/kep" $kt --sweep e=0.1:0.7:13 --batch 4 --threads 2 -o "$tmp/kb4t.csv"
"$tmp/kep" $kt --set e=0.35 | tail -1 > "$tmp/kalone.csv"
[ $st1 -eq 0 ] && [ $st4 -eq 0 ] && cmp -s "$tmp/kb1.csv" "$tmp/kb4.csv" &&
    cmp -s "$tmp/kb1.csv" "$tmp/kb4t.csv" &&
    [ "$(sed -n 7p "$tmp/kb4.csv" | cut -d, -f3-7)" = "$(cut -d, -f1-5 "$tmp/kalone.csv")" ]
ok $? "--batch 4 (13 runs: idle lanes; and on 2 threads): the bytes of --batch 1, row e = 0.35 the run alone"
awk -F, 'NR > 1 { dx = $4 - (1 - $1); if (dx < 0) dx = -dx; y = $5 < 0 ? -$5 : $5
    if ($2 != "ok" || dx > 1e-12 || y > 1e-12) bad = 1 } END { exit bad || NR != 14 }' "$tmp/kb4.csv"
ok $? "--batch 4: every orbit back at periapsis, x = 1 - e and y = 0 to 1e-12"
"$tmp/kep" $kt --sweep e=0.5:1:3 --batch 1 -o "$tmp/kf1.csv" 2> /dev/null
"$tmp/kep" $kt --sweep e=0.5:1:3 --batch 4 -o "$tmp/kf4.csv" 2> "$tmp/kf4.err"; st=$?
[ $st -eq 0 ] && cmp -s "$tmp/kf1.csv" "$tmp/kf4.csv" && [ "$(grep -c ',ok,' "$tmp/kf4.csv")" -eq 2 ] &&
    grep -q 'warning: 1 of 3 runs failed' "$tmp/kf4.err"
ok $? "--batch 4 with a failing run (e = 1): its error as status, the others' bytes as --batch 1"
ball="$src/specs/bouncing_ball.yaml"
"$eomc" build "$ball" --scene bounce --taylor -o "$tmp/ball" 2> /dev/null
"$tmp/ball" --method taylor --sweep e=0.5:0.8:4 --batch 1 -o "$tmp/bb1.csv"
"$tmp/ball" --method taylor --sweep e=0.5:0.8:4 --batch 4 -o "$tmp/bb4.csv"; st=$?
# the height at T = 1.2: the bounce before it at t_k, leaving at v_k upwards
awk -F, 'NR > 1 { g = 9.81; T = 1.2; t = sqrt(2 / g); v = g * t * $1
        while (t + 2 * v / g <= T) { t += 2 * v / g; v *= $1 }
        y = v * (T - t) - g * (T - t) ^ 2 / 2; d = $4 - y; if (d < 0) d = -d
        if ($2 != "ok" || d > 1e-9) bad = 1 } END { exit bad || NR != 5 }' "$tmp/bb4.csv" &&
    [ $st -eq 0 ] && cmp -s "$tmp/bb1.csv" "$tmp/bb4.csv"
ok $? "--batch 4 with events in each lane (a ball bouncing, e = 0.5 .. 0.8): the bounces' closed form to 1e-9, the bytes of --batch 1"
# a switched expression in every lane (max(0, -k y - c y'), its modes
# each lane's): without damping the mass leaves the floor spring after
# half its period, pi / 10, at v0, so y(1) = v0 (1 - pi / 10)
"$eomc" build "$src/tests/cli/spring_floor.yaml" --taylor -o "$tmp/floor" 2> /dev/null
ft="--method taylor --rtol 1e-13 --atol 1e-13 --sweep v0=0.5:2:7 --sweep c=0:4:3"
"$tmp/floor" $ft --batch 1 -o "$tmp/fb1.csv"
"$tmp/floor" $ft --batch 4 -o "$tmp/fb4.csv"; st=$?
[ $st -eq 0 ] && cmp -s "$tmp/fb1.csv" "$tmp/fb4.csv" &&
    awk -F, 'NR > 1 && $2 == 0 { k++; y = $1 * (1 - 3.14159265358979324 / 10); d = $5 - y
        e = $6 - $1; if (d < 0) d = -d; if (e < 0) e = -e
        if ($3 != "ok" || d > 1e-12 || e > 1e-12) bad = 1 } END { exit bad || k != 7 }' "$tmp/fb4.csv"
ok $? "--batch 4 with switches in each lane (a one-sided floor spring, 21 runs): undamped, y(1) = v0 (1 - pi/10) and y' = v0 to 1e-12; the bytes of --batch 1"
"$tmp/kep" --sweep e=0.1:0.7:3 --batch 3 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "batch: '3' is not 1 or 4" "$tmp/err"
ok $? "--batch 3: exit $st (1 or 4, a vector's lanes)"
"$tmp/kep" --method rk8pd --sweep e=0.1:0.7:3 --batch 4 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q "by Taylor's method alone (--method taylor), not by rk8pd" "$tmp/err"
ok $? "--batch 4 with rk8pd: exit $st, naming the method"
"$tmp/kep" $kt --batch 4 > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'batch runs the runs of a sweep' "$tmp/err"
ok $? "--batch without a sweep: exit $st"
"$eomc" run "$src/specs/cartesian_pendulum.yaml" --method taylor --sweep l=1:2:2 --batch 4 \
    > /dev/null 2> "$tmp/err"; st=$?
[ $st -eq 2 ] && grep -q 'has no series for 4 runs at once' "$tmp/err"
ok $? "--batch 4 for a model with constraints: exit $st, saying why"

tap_end
