#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# posemorph-view built with -DPOSEMORPH_VIEWER_EDIT=OFF, after a native
# release build (it reads the rigs that build baked): the viewer then needs
# the runtime, Vulkan, GLFW and Dear ImGui alone. Checks that no viewer
# source is compiled with Eigen, nlohmann-json or tinyxml2, that the link
# names no bake library, that the binary loads no libtinyxml2, and that its
# headless frame of Pip is the release viewer's, byte for byte. It is built
# with Clang (-Werror): the one Clang build of the viewer's sources in CI
# (the sanitized debug preset leaves the viewer out), and the frame from
# Clang's runtime is GCC's.
set -euo pipefail
cd "$(dirname "$0")/.."
rig=build/release/rigs/pip.pmrig
view=build/release/bin/posemorph-view
for f in "$rig" "$view"; do
  [ -e "$f" ] || { echo "viewer-without-bake: no $f: build the release preset first" >&2; exit 1; }
done
work=build/viewer-without-bake
fail() { echo "viewer-without-bake: $*" >&2; exit 1; }
cmake -S . -B "$work" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DPOSEMORPH_VIEWER_EDIT=OFF -DPOSEMORPH_WERROR=ON \
  -DPOSEMORPH_BUILD_TESTS=OFF -DPOSEMORPH_BUILD_BENCH=OFF -DPOSEMORPH_BUILD_EXAMPLES=OFF >"$work.log" 2>&1 ||
  { cat "$work.log"; fail "configure failed"; }
cmake --build "$work" --target posemorph-view -j"$(nproc)" >"$work.log" 2>&1 || { cat "$work.log"; fail "build failed"; }
python3 - "$work/compile_commands.json" <<'PY' || fail "a viewer source is compiled with the bake's dependencies"
import json, sys
bad = [e["file"] for e in json.load(open(sys.argv[1]))
       if "/viewer/" in e["file"] and any(d in e["command"].lower() for d in ("eigen", "nlohmann", "tinyxml"))]
for f in bad:
    print("  compiled with Eigen, nlohmann-json or tinyxml2:", f)
sys.exit(1 if bad else 0)
PY
link=$(cat "$work/viewer/CMakeFiles/posemorph-view.dir/link.txt")
case "$link" in *posemorph_bake*|*tinyxml*) fail "the link names the bake: $link" ;; esac
if ldd "$work/bin/posemorph-view" | grep -q tinyxml2; then fail "posemorph-view loads libtinyxml2"; fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$work/bin/posemorph-view" "$rig" --headless --size 160x160 --at 0.4,0.3 -o "$out/off.png" >/dev/null
"$view" "$rig" --headless --size 160x160 --at 0.4,0.3 -o "$out/on.png" >/dev/null
cmp -s "$out/off.png" "$out/on.png" || fail "its frame differs from the release viewer's"
status=0
"$work/bin/posemorph-view" "$rig" --description x.json >/dev/null 2>"$out/err" || status=$?
[ "$status" -eq 2 ] && grep -q "POSEMORPH_VIEWER_EDIT=ON" "$out/err" || fail "--description was not refused with status 2"
echo "viewer-without-bake: posemorph-view without edit mode links $(ldd "$work/bin/posemorph-view" | wc -l) shared libraries, no bake; its frame is the release viewer's"
