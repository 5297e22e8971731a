#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The C# binding's test (ctest: integration.csharp):
#   run.sh BUILD BINDINGS POSITIONS_HASH
# compiles the binding, its test and its example with mcs into
# BUILD/integration-tests/csharp, and runs them under mono against the shared
# library in BINDINGS: each baked sample's character digest must be the
# native runtime's (POSITIONS_HASH RIG --characters K), and a truncated and
# a corrupted rig must be refused with the native loader's message.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=$1 bindings=$2 hash=$3
if ! command -v mcs >/dev/null || ! command -v mono >/dev/null; then
  echo "integration.csharp: skipped: mcs and mono are not installed (scripts/setup.sh installs mono-mcs, mono-runtime)"
  exit 77
fi
work=$build/integration-tests/csharp  # not integrations/csharp: that is the CMake binary folder
mkdir -p "$work"
mcs -unsafe -target:library -out:"$work/Posemorph.dll" "$here/Posemorph.cs"
mcs -r:"$work/Posemorph.dll" -out:"$work/BindingTest.exe" "$here/tests/BindingTest.cs"
mcs -r:"$work/Posemorph.dll" -out:"$work/Example.exe" "$here/example/Example.cs"
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
