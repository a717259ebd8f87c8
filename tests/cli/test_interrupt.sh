#!/bin/sh
# An interrupted run leaves a CSV of whole rows (TAP): SIGINT and SIGTERM
# finish the row being written, say `interrupted at t = ...` and exit 130
# and 143; SIGKILL, which nothing can catch, still leaves only whole rows,
# because rows are written in blocks of whole rows, one write each.  Every
# row of the file is checked to have every column.
# usage: test_interrupt.sh EOMC SOURCE_ROOT BUILD_ROOT
set -u
eomc=$1 src=$2 build=$3
case $eomc in /*) ;; *) eomc="$build/$eomc" ;; esac
. "$src/tests/cli/tap.sh"
"$eomc" build "$src/specs/chain5.yaml" -o "$tmp/chain5" 2> /dev/null
whole() { # FILE: every line has the header's number of fields, and there are rows
    awk -F, 'NR == 1 { n = NF } NF != n || $NF == "" { bad = 1 } END { exit !(NR > 10 && !bad) }' "$1"
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
        [ $st -eq $want ] && whole "$tmp/$sig.csv"
    else
        [ $st -eq $want ] && whole "$tmp/$sig.csv" &&
            grep -q "interrupted at t = .* (SIG$sig): the $rows rows up to then are written" "$tmp/$sig.err"
    fi
    ok $? "SIG$sig: exit $st, $rows whole rows"
done
tap_end
