#!/bin/sh
# Every relative link of the README and docs/ resolves inside the
# repository (TAP, one check per file): each `](PATH)` or
# `](PATH#ANCHOR)` outside fenced code names a file or directory that
# exists, relative to the page that links it, and each `#ANCHOR` (also a
# page's own, `](#ANCHOR)`) is a heading of the page it points to, made
# into an anchor as GitHub does: lower case, spaces to `-`, everything but
# letters, digits, `-` and `_` dropped, `-1`, `-2` after repeats.  Links
# with a scheme (https:, mailto:) are not followed.
# usage: test_links.sh SOURCE_ROOT
set -u
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0 failed=0

# links FILE: one line per link, its target (PATH, PATH#ANCHOR or #ANCHOR)
links() {
  awk '/^[ \t]*```/ { fence = !fence; next }
       fence { next }
       { gsub(/`[^`]*`/, "``")       # code spans hold no links
         s = $0
         while ((i = index(s, "](")) > 0) {
           s = substr(s, i + 2); j = index(s, ")")
           if (j == 0) break
           t = substr(s, 1, j - 1); sub(/[ \t].*/, "", t)   # drop a "title"
           if (t != "") print t
           s = substr(s, j + 1) } }' "$1"
}
# anchors FILE: the anchor of each of its headings
anchors() {
  LC_ALL=C awk '/^[ \t]*```/ { fence = !fence; next }
       fence || !/^#+ / { next }
       { h = $0; sub(/^#+ +/, "", h); h = tolower(h); gsub(/ /, "-", h)
         gsub(/[^a-z0-9_-]/, "", h)
         a = (h in seen) ? h "-" seen[h] : h; seen[h]++; print a }' "$1"
}

for page in "$src/README.md" "$src"/docs/*.md; do
  name=${page#"$src/"}
  dir=$(dirname "$page")
  : > "$tmp/bad"
  links "$page" > "$tmp/links"
  while IFS= read -r t; do
    case $t in
      *:*) continue ;;                       # https:, mailto:, ...
    esac
    path=${t%%#*} anchor=
    case $t in *'#'*) anchor=${t#*#} ;; esac
    if [ -z "$path" ]; then
      target=$page
    else
      target=$dir/$path
    fi
    if [ ! -e "$target" ]; then
      echo "# $name: $t: no such file ($path)" >> "$tmp/bad"
      continue
    fi
    # the target must lie inside the repository
    real=$(cd "$(dirname "$target")" && pwd -P)
    case $real/ in
      "$(cd "$src" && pwd -P)"/*) ;;
      *) echo "# $name: $t: outside the repository" >> "$tmp/bad"; continue ;;
    esac
    if [ -n "$anchor" ]; then
      case $target in
        *.md)
          if ! anchors "$target" | grep -qxF -- "$anchor"; then
            echo "# $name: $t: no heading makes the anchor #$anchor" >> "$tmp/bad"
          fi ;;
      esac
    fi
  done < "$tmp/links"
  count=$(wc -l < "$tmp/links")
  n=$((n + 1))
  if [ -s "$tmp/bad" ]; then
    cat "$tmp/bad"
    echo "not ok $n - $name: every link resolves ($count links)"
    failed=$((failed + 1))
  else
    echo "ok $n - $name: every link resolves ($count links)"
  fi
done
echo "1..$n"
[ $failed -eq 0 ]
