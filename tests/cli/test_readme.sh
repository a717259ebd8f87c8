#!/bin/sh
# The README's two commands, as far as they can be run here (not apt-get):
# the test command's set-up of build/ must take in what was installed since
# the directory was first set up.  The run command sets build/ up with only
# what running needs, so a test command that kept that set-up would skip the
# suites of the packages it has just installed (python, import, page).  Its
# set-up part (after the install, up to " && meson test")
# runs here twice on a scratch project whose meson.build looks for a file:
# absent the first time, present the second, and the build must see it.
# Also: the README prints no count of build steps, which drifts with every
# file added (what it says of the build is its time).
# usage: test_readme.sh SOURCE_ROOT
set -u
src=$1
. "$(dirname "$0")/tap.sh"

test_cmd=$(awk '/^```sh/{f=1; next} /^```/{if (f) exit} f' "$src/README.md" | sed -n 2p)
setup=${test_cmd#*apt-get install -y *&& }   # after the install
setup=${setup%% && meson test*}
ok $(case $setup in *"meson setup"*) echo 0 ;; *) echo 1 ;; esac) "the test command sets build/ up before meson test: '$setup'"

mkdir -p "$tmp/p"
cat >"$tmp/p/meson.build" <<'MESON'
project('readme_setup', 'c')
message('installed: @0@'.format(import('fs').exists('installed') ? 'yes' : 'no'))
MESON
state() { grep -ho 'installed: [a-z]*' "$tmp/p/build/meson-logs/meson-log.txt" | tail -1; }
(cd "$tmp/p" && eval "$setup") >"$tmp/first.log" 2>&1
ok $([ "$(state)" = "installed: no" ]; echo $?) "first set-up: $(state)"
touch "$tmp/p/installed"
(cd "$tmp/p" && eval "$setup") >"$tmp/second.log" 2>&1
ok $([ "$(state)" = "installed: yes" ]; echo $?) \
  "a second set-up of the same build/ sees what was installed since: $(state)"

ok $(! grep -nE '[0-9]+ build steps' "$src/README.md" >&2; echo $?) \
  "README.md prints no count of build steps"
tap_end
