#!/bin/sh
# The symbols libeomcrt exports (TAP): only its eomc_ API, so that a user's
# program cannot clash with its internals (test_namespace.c links one that
# defines them).
#  - every global symbol the library defines starts with eomc_;
#  - it defines every eomc_ symbol the objects before localization define
#    (the same objects: nothing of the API was hidden by mistake);
#  - the generated models call nothing of the runtime but its eomc_ API:
#    each undefined symbol of theirs that the runtime's objects define is
#    eomc_ (the shipped simulators link the localized library, so one that
#    did not would not link at all; this names it).
# usage: test_symbols.sh NM LIBRARY INTERNAL_LIBRARY MODEL_LIBRARY...
set -u
nm=$1 lib=$2 internal=$3
shift 3
. "$(dirname "$0")/../cli/tap.sh"

# The global symbols lib defines that a C program could name too (not,
# under -fsanitize=address, its __odr_asan.NAME indicators).
defined() {
    "$nm" -g --defined-only "$1" | awk 'NF == 3 && $3 ~ /^[A-Za-z_][A-Za-z0-9_]*$/ { print $3 }' |
        sort -u
}

defined "$lib" > "$tmp/exported"
others=$(grep -v '^eomc_' "$tmp/exported" | tr '\n' ' ')
count=$(wc -l < "$tmp/exported")
[ "$count" -gt 0 ] && [ -z "$others" ]
ok $? "$count global symbols in $(basename "$lib"), none without the eomc_ prefix${others:+: $others}"

defined "$internal" > "$tmp/all"
grep '^eomc_' "$tmp/all" > "$tmp/api"
missing=$(comm -23 "$tmp/api" "$tmp/exported" | tr '\n' ' ')
[ -s "$tmp/api" ] && [ -z "$missing" ]
ok $? "every eomc_ symbol of the objects is exported ($(wc -l < "$tmp/api") of them)${missing:+, not: $missing}"

for m in "$@"; do
    "$nm" -u "$m" | awk '{ print $NF }' | sort -u > "$tmp/undefined"
    bad=$(comm -12 "$tmp/undefined" "$tmp/all" | grep -v '^eomc_' | tr '\n' ' ')
    calls=$(comm -12 "$tmp/undefined" "$tmp/all" | tr "\n" " " | sed "s/ $//")
    [ -z "$bad" ]
    ok $? "$(basename "$m") calls the runtime's ${calls:-nothing}${bad:+ (not the API: $bad)}"
done
tap_end
