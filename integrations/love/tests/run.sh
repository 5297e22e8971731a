#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The LÖVE integration's test (ctest: integration.love), under Xvfb (Mesa's llvmpipe):
#   run.sh BUILD BINDINGS POSITIONS_HASH VIEW COMPARE SHOTS
# - each baked sample's character digest from LuaJIT's FFI equals the native
#   runtime's (POSITIONS_HASH RIG --characters K), bit for bit;
# - the example's frame of Pip and of Pell with a face equals posemorph-view's
#   at the same pose-space point within the examples' tolerance (at most 1% of
#   the pixels more than 3 of 255 apart: the two rasterisers' edges);
# - a crowd of 200 Pells with faces walks for 60 frames from one texture,
#   the atlas the bake wrote beside the rig (its screenshot is kept in SHOTS
#   for the README);
# - a truncated and a corrupted rig are refused with the native loader's message.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$1 bindings=$2 hash=$3 view=$4 compare=$5 shots=$6
if ! command -v love >/dev/null || ! command -v Xvfb >/dev/null; then
  echo "integration.love: skipped: love (LÖVE 11) or Xvfb is not installed (scripts/setup.sh installs them)"
  exit 77
fi
work=$build/integration-tests/love  # not integrations/love: that is the CMake binary folder
rm -rf "$work" && mkdir -p "$work" "$shots"
export POSEMORPH_LIBRARY=$bindings/libposemorph.so
# One X server for every run of the example, started and stopped here: an
# Xvfb that xvfb-run left running once held the test's output open, and
# ctest waited on it until the timeout (the test itself had ended).
display=99
while [ -e "/tmp/.X$display-lock" ] || [ -e "/tmp/.X11-unix/X$display" ]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1024x768x24 -nolisten tcp > /dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2> /dev/null || true; wait "$xvfb" 2> /dev/null || true' EXIT
for _ in $(seq 100); do [ -e "/tmp/.X11-unix/X$display" ] && break; sleep 0.1; done
[ -e "/tmp/.X11-unix/X$display" ] || { echo "integration.love: Xvfb :$display did not start"; exit 1; }
export DISPLAY=":$display"
game() {  # the example on that server, without the audio device's complaints
  love "$here/example" "$@" 2> >(grep -v "ALSA\|AL lib\|Could not open device" >&2)
}
failures=0
for rig in pip.compact pip pell-face.compact pell-face sprout.compact arm.compact; do
  native=$("$hash" "$build/rigs/$rig.pmrig" --characters 9)
  lua=$(game "$build/rigs/$rig.pmrig" --digest 9 | tail -1)
  if [ "$lua" = "$native" ]; then
    echo "love: $rig: $lua (the native runtime's)"
  else
    echo "love: $rig: LuaJIT $lua, native $native"
    failures=$((failures + 1))
  fi
done
for case in "pip|pip|0.5,0.5" "pell-face.compact|pell|0.3,0.2"; do
  IFS='|' read -r rig images at <<< "$case"
  game "$build/rigs/$rig.pmrig" --images "$build/assets/$images" --at "$at" --size 256x256 --frames 3 \
    --screenshot "$work/$rig-love.png"
  "$view" "$build/rigs/$rig.pmrig" --images "$build/assets/$images" --headless --at "$at" --size 256x256 \
    -o "$work/$rig-view.png" > /dev/null
  if result=$("$compare" "$work/$rig-love.png" "$work/$rig-view.png" 0.01); then
    echo "love: $rig at ($at) against posemorph-view: $result"
  else
    echo "love: $rig at ($at) differs from posemorph-view: $result"
    failures=$((failures + 1))
  fi
done
out=$(game "$build/rigs/pell-face.compact.pmrig" --images "$build/assets/pell" --crowd 200 --size 800x600 --frames 60 \
  --screenshot "$work/crowd.png")
echo "love: $out"
case "$out" in *"60 frames of 200 character(s), 1 texture(s)"*) cp "$work/crowd.png" "$shots/love-crowd.png" ;;
  *) failures=$((failures + 1)) ;; esac
python3 "$here/../hostile_rigs.py" "$build/rigs/pell-face.compact.pmrig" "$work"
for bad in truncated corrupt; do
  native=$("$hash" "$work/$bad.pmrig" 0 0 2>&1 >/dev/null || true)
  status=0
  lua=$(game "$work/$bad.pmrig" --load-only | tail -1) || status=$?
  if [ "$status" -ne 0 ] && [ "$lua" = "$native" ]; then
    echo "love: refused $bad.pmrig: $lua"
  else
    echo "love: $bad.pmrig: status $status, \"$lua\", expected the native \"$native\""
    failures=$((failures + 1))
  fi
done
[ "$failures" -eq 0 ] && echo "love: ok" || { echo "love: $failures failures"; exit 1; }
