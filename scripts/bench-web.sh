#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# WebAssembly against native, in one run: the web integration's benchmark
# page (integrations/web/bench) in headless Chromium, in real time, and the
# same frame through the same C natively (posemorph-web-bench-native), on
# the rigs the build baked. A frame: every character's points from the rig's
# paths, then Crowd.evaluate (every list, attachment and draw step). Prints
# docs/performance.md's table (medians of REPS runs of 100 frames).
#   scripts/bench-web.sh [REPS]
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-7}
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target posemorph-npm-package posemorph-web-bench-native \
  posemorph-test-rigs >/dev/null
build=$PWD/build/release
site=$build/bench-web
rm -rf "$site" && mkdir -p "$site"
echo '{ "name": "posemorph-bench", "private": true, "type": "module" }' > "$site/package.json"
(cd "$site" && npm install --no-audit --no-fund --offline "$build"/integrations/web/posemorph-*.tgz > /dev/null)
cp integrations/web/bench/index.html integrations/web/bench/bench.mjs "$build"/rigs/{pip,pell-face}.compact.pmrig "$site/"
cases="pip.compact.pmrig:1,pip.compact.pmrig:200,pell-face.compact.pmrig:1,pell-face.compact.pmrig:200"

python3 -m http.server 0 --bind 127.0.0.1 --directory "$site" > "$site.server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 50); do grep -q "port" "$site.server.log" && break; sleep 0.1; done
port=$(grep -o 'port [0-9]*' "$site.server.log" | head -1 | cut -d' ' -f2)
# Real time (a virtual time budget would stop the clock).
title=$(python3 scripts/chromium-title.py "http://127.0.0.1:$port/index.html?cases=$cases&frames=100&reps=$reps" \
        done,error 600 "$site/profile" || true)
case "$title" in done*) ;; *) echo "bench-web: the page said '$title'" >&2; exit 1 ;; esac
isa=$("$build/bin/posemorph-bake" info "$site/pip.compact.pmrig" | grep -o "kernel path [a-z0-9-]*" || true)
echo "$(nproc) x $(awk '/MHz/ {printf "%d MHz", $4; exit}' /proc/cpuinfo), $(date -u +%Y-%m-%dT%H:%M:%S+00:00);" \
  "$(chromium --version 2>/dev/null | head -1); medians of $reps runs of 100 frames, microseconds per frame"
echo
echo "| rig | characters | browser (wasm SIMD128) | native (its best path) | wasm / native | native, SSE2 path | wasm / SSE2 |"
echo "|---|---|---|---|---|---|---|"
for c in ${cases//,/ }; do
  rig=${c%%:*} n=${c##*:}
  wasm=$(tr ' ' '\n' <<< "$title" | grep "^$c$" -A1 | tail -1)
  native=$("$build/bin/posemorph-web-bench-native" "$site/$rig" "$n" 100 "$reps")
  sse2=$(POSEMORPH_ISA=sse2 "$build/bin/posemorph-web-bench-native" "$site/$rig" "$n" 100 "$reps")
  awk -v r="${rig%.pmrig}" -v n="$n" -v w="$wasm" -v a="$native" -v s="$sse2" \
    'BEGIN { printf "| %s | %d | %.1f | %.1f | %.2f x | %.1f | %.2f x |\n", r, n, w, a, w / a, s, w / s }'
done
echo
echo "Native: the $isa of this build and CPU; SSE2: POSEMORPH_ISA=sse2."
