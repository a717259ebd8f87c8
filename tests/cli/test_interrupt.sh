#!/bin/sh
# An interrupted run leaves a CSV of whole rows (TAP): SIGINT and SIGTERM
# finish the row being written, say `interrupted at t = ...` and exit 130
# and 143; SIGKILL, which nothing can catch, still leaves only whole rows,
# because rows are written in blocks of whole rows, one write each, but
# for a last line without its newline (Linux lets a fatal signal end a
# write of several pages between two: docs/cli.md).  Every row of the file
# (every complete line, after SIGKILL) is checked to have every column.
# usage: test_interrupt.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
"$eomc" build "$src/specs/chain5.yaml" -o "$tmp/chain5" 2> /dev/null
whole() { # FILE: every line has the header's number of fields, and there are rows
    awk -F, 'NR == 1 { n = NF } NF != n || $NF == "" { bad = 1 } END { exit !(NR > 10 && !bad) }' "$1"
}
# FILE's complete lines (each ending in a newline) into FILE.lines
complete() {
    if [ -n "$(tail -c 1 "$1")" ]; then sed '$d' "$1"; else cat "$1"; fi > "$1.lines"
}
# FILE PID: wait until FILE holds the header and 10 rows (written in
# blocks, so this is the first block or more), for at most 2 minutes
# however slow the machine, or until PID has ended.
rows_written() {
    i=0
    while [ $i -lt 1200 ] && kill -0 "$2" 2> /dev/null; do
        [ -f "$1" ] && [ "$(wc -l < "$1")" -gt 10 ] && return 0
        sleep 0.1
        i=$((i + 1))
    done
    return 1
}
for sig in INT TERM KILL; do
    "$tmp/chain5" --t-end 1e6 --dt 1e-3 -o "$tmp/$sig.csv" 2> "$tmp/$sig.err" &
    pid=$!
    rows_written "$tmp/$sig.csv" $pid || echo "# no rows after 2 minutes"
    kill -$sig $pid
    wait $pid
    st=$?
    case $sig in
        INT) want=130 ;;
        TERM) want=143 ;;
        KILL) want=137 ;;
    esac
    rows=$(($(wc -l < "$tmp/$sig.csv") - 1))
    if [ $sig = KILL ]; then
        complete "$tmp/$sig.csv"
        rows=$(($(wc -l < "$tmp/$sig.csv.lines") - 1))
        [ $st -eq $want ] && whole "$tmp/$sig.csv.lines"
    else
        [ $st -eq $want ] && whole "$tmp/$sig.csv" &&
            grep -q "interrupted at t = .* (SIG$sig): the $rows rows up to then are written" "$tmp/$sig.err"
    fi
    ok $? "SIG$sig: exit $st, $rows whole rows"
done
# --animate: an interrupted run's page has the rows its CSV has, the last
# at the CSV's last time (to the page's 6 digits; the page is written after
# the signal, from the rows the CSV got); skipped without three.js
three=${EOMC_THREE_DIR:-/usr/share/javascript/three}
if [ -f "$three/three.min.js" ] && [ -f "$three/examples/js/controls/OrbitControls.js" ]; then
    "$tmp/chain5" --t-end 1e6 --dt 0.01 -o "$tmp/anim.csv" --animate "$tmp/anim.html" \
        2> "$tmp/anim.err" &
    pid=$!
    rows_written "$tmp/anim.csv" $pid || echo "# no rows after 2 minutes"
    kill -INT $pid
    wait $pid
    st=$?
    rows=$(($(wc -l < "$tmp/anim.csv") - 1))
    last=$(tail -1 "$tmp/anim.csv" | cut -d, -f1)
    set -- $(python3 "$src/tests/cli/page_check.py" frames "$tmp/anim.html")
    [ $st -eq 130 ] && whole "$tmp/anim.csv" && [ "${1:-}" = "$rows" ] &&
        awk -v a="${2:-x}" -v b="$last" 'BEGIN { d = a - b; if (d < 0) d = -d
            exit !(a != "x" && d <= 1e-6 * (b < 0 ? -b : b)) }' &&
        [ ! -e "$tmp/anim.html.tmp" ]
    ok $? "SIGINT with --animate: exit $st, the page has the CSV's $rows rows (${1:-no} frames, the last at t = ${2:-?}, the CSV's $last)"
else
    echo "ok - SIGINT with --animate # SKIP three.js is not installed (libjs-three)"
fi
tap_end
