#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bake's progress line (ctest cli.progress_line): on a terminal (a pty
# from script(1)) a bake over a second redraws its stage in place and erases
# the line before its report; piped, with TERM=dumb or with --quiet it draws
# nothing (--quiet also drops the report, not the result).
#   progress_line.sh BAKE RIG.json WORK
set -euo pipefail
bake=$1 rig=$2 work=$3
rm -rf "$work" && mkdir -p "$work/tty" "$work/pipe"
if ! command -v script > /dev/null; then echo "cli.progress_line: skipped: script(1) is not installed"; exit 77; fi
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
cr=$'\r' erase=$'\r\033[K'

# On a terminal: stages drawn, then erased, then the report.
# (Each rig in a folder of its own under one name: its atlas's pages are named after it.)
script -qec "TERM=xterm '$bake' '$rig' -o '$work/tty/rig.pmrig'" /dev/null > "$work/tty.out"
stages=$(grep -ao "posemorph-bake: [a-z' -]* \.\.\. [0-9.]* s" "$work/tty.out" | sed 's/^posemorph-bake: //; s/ \.\.\. .*//' | sort -u | paste -sd, -)
echo "on a terminal: stages shown: $stages"
# Which stages last long enough to be drawn depends on the machine: one at least.
[ -n "$stages" ] || fail "no stage on the progress line"
grep -aqF "${erase}baked " "$work/tty.out" || fail "the progress line is not erased before the report"
[ -s "$work/tty/rig.pmrig" ] || fail "no rig written on a terminal"

# Piped: the same bake, no carriage return anywhere.
"$bake" "$rig" -o "$work/pipe/rig.pmrig" > "$work/pipe.out" 2>&1
if grep -aq "$cr" "$work/pipe.out"; then fail "a progress line on a pipe"; else echo "piped: no progress line"; fi
grep -aq "^baked " "$work/pipe.out" || fail "no report when piped"
cmp -s "$work/tty/rig.pmrig" "$work/pipe/rig.pmrig" || fail "the rig differs with the progress line on"
cmp -s "$work/tty/rig.page0.png" "$work/pipe/rig.page0.png" || fail "the atlas page differs with the progress line on"

# TERM=dumb and --quiet on a terminal: nothing drawn; --quiet also drops the report.
script -qec "TERM=dumb '$bake' '$rig' -o '$work/dumb.pmrig'" /dev/null > "$work/dumb.out"
if grep -aq "posemorph-bake: .* s" "$work/dumb.out"; then fail "a progress line with TERM=dumb"; else echo "TERM=dumb: no progress line"; fi
script -qec "TERM=xterm '$bake' '$rig' -o '$work/quiet.pmrig' --quiet" /dev/null > "$work/quiet.out"
if grep -aq "posemorph-bake: .* s\|^baked" "$work/quiet.out"; then fail "--quiet printed: $(head -c 200 "$work/quiet.out")"
else echo "--quiet: nothing printed"; fi
[ -s "$work/quiet.pmrig" ] || fail "no rig written with --quiet"
[ "$failures" -eq 0 ] && echo "progress line: ok" || exit 1
