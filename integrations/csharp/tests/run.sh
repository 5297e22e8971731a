#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The C# binding's test (ctest: integration.csharp):
#   run.sh BUILD BINDINGS POSITIONS_HASH [VIEW COMPARE SHOTS]
# compiles the binding, its test and its example with mcs into
# BUILD/integration-tests/csharp, and runs them under mono against the shared
# library in BINDINGS: each baked sample's character digest must be the
# native runtime's (POSITIONS_HASH RIG --characters K), and a truncated and
# a corrupted rig must be refused with the native loader's message. With
# VIEW: the example's software-rendered frames of Pip and Pell with a face
# against posemorph-view's (at most 1% of pixels off by more than 3/255),
# and its crowd of 200 written to SHOTS/csharp-crowd.png.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$1 bindings=$2 hash=$3 view=${4:-} compare=${5:-} shots=${6:-}
if ! command -v mcs >/dev/null || ! command -v mono >/dev/null; then
  echo "integration.csharp: skipped: mcs and mono are not installed (scripts/setup.sh installs mono-mcs, mono-runtime)"
  exit 77
fi
work=$build/integration-tests/csharp  # not integrations/csharp: that is the CMake binary folder
mkdir -p "$work"
mcs -unsafe -target:library -out:"$work/Posemorph.dll" "$here/Posemorph.cs"
mcs -r:"$work/Posemorph.dll" -out:"$work/BindingTest.exe" "$here/tests/BindingTest.cs"
mcs -r:"$work/Posemorph.dll" -out:"$work/Example.exe" "$here/example/Example.cs" "$here/example/Picture.cs"
args=()
for rig in pip.compact pip pell-face.compact pell-face sprout.compact snake.compact arm.compact; do
  line=$("$hash" "$build/rigs/$rig.pmrig" --characters 9)
  args+=("$build/rigs/$rig.pmrig=$line")
done
# Hostile bytes: the first 1,000 bytes of a rig, and a rig with one byte changed.
python3 "$here/../hostile_rigs.py" "$build/rigs/pell-face.compact.pmrig" "$work"
for bad in truncated corrupt; do
  message=$("$hash" "$work/$bad.pmrig" 0 0 2>&1 >/dev/null || true)
  args+=(--refuse "$work/$bad.pmrig" "$message")
done
export LD_LIBRARY_PATH=$bindings${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
mono "$work/BindingTest.exe" "${args[@]}"
mono "$work/Example.exe" "$build/rigs/pell-face.compact.pmrig" 200 > "$work/example.txt"
tail -3 "$work/example.txt"
grep -q "200 characters, 4 lists each, 1400 draw calls a frame (7 per character), 1 texture(s) (an atlas)" \
  "$work/example.txt" || { echo "csharp: the example's crowd: $(head -1 "$work/example.txt")"; exit 1; }
if [ -n "$view" ]; then
  for case in "pip|pip|0.5,0.5" "pell-face.compact|pell|0.3,0.2"; do
    IFS='|' read -r rig images at <<< "$case"
    mono "$work/Example.exe" "$build/rigs/$rig.pmrig" --picture "$work/$rig-csharp.png" --at "$at" --size 256x256
    "$view" "$build/rigs/$rig.pmrig" --images "$build/assets/$images" --headless --at "$at" --size 256x256 \
      -o "$work/$rig-view.png" > /dev/null
    echo -n "csharp: $rig at ($at) against posemorph-view: "
    "$compare" "$work/$rig-csharp.png" "$work/$rig-view.png" 0.01
  done
  mono "$work/Example.exe" "$build/rigs/pell-face.compact.pmrig" --picture "$work/crowd.png" --crowd 200 --size 800x600
  mkdir -p "$shots" && cp "$work/crowd.png" "$shots/csharp-crowd.png"
  # A page that is no PNG, and one of another size: one line naming the page, status 1.
  mkdir -p "$work/bad"
  cp "$build/rigs/pip.pmrig" "$work/bad/"
  for page in "not a png|not a PNG" "$work/crowd.png|the page is 800x600, the rig says 512x512"; do
    IFS='|' read -r bytes expected <<< "$page"
    if [ -f "$bytes" ]; then cp "$bytes" "$work/bad/pip.page0.png"; else printf '%s' "$bytes" > "$work/bad/pip.page0.png"; fi
    status=0
    said=$(mono "$work/Example.exe" "$work/bad/pip.pmrig" --picture "$work/bad/out.png" --at 0,0 2>&1) || status=$?
    if [ "$status" = 1 ] && [ "$said" = "Example: $work/bad/pip.page0.png: $expected" ] && [ ! -e "$work/bad/out.png" ]; then
      echo "csharp: refused: $said"
    else
      echo "csharp: a bad page gave status $status, '$said' (expected 'Example: $work/bad/pip.page0.png: $expected')"
      exit 1
    fi
  done
fi
