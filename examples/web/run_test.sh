#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The web example in headless Chromium (SwiftShader WebGL2), served from
# 127.0.0.1: the page's vertex positions equal the native runtime's bit for
# bit, its frame matches posemorph-view's (plain and tinted) drawn from the
# rig's atlas page, and from the drawings for a rig baked without one, load
# errors show in the page, and the runtime's time per frame in the browser
# is reported.
# Usage: run_test.sh WASM-DIR RIG IMAGES VIEW COMPARE HASH WORK SHOTS BAKE
#   RIG: a rig with an atlas (its pages beside it); IMAGES: its drawings and
#   description, baked again here without an atlas.
set -euo pipefail
wasm=$1 rig=$2 images=$3 view=$4 compare=$5 hash=$6 work=$7 shots=$8 bake=$9
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work/site/resized" "$shots"
"$bake" "$images/$(basename "$rig" .pmrig).json" --no-atlas --quiet -o "$work/flat.pmrig"
pages=("${rig%.pmrig}".page*.png)
[ -f "${pages[0]}" ] || { echo "FAIL: $rig has no atlas page beside it"; exit 1; }
for d in "$work/site" "$work/site/resized"; do
  cp "$here/index.html" "$here/main.js" "$here/posemorph.js" "$wasm/posemorph_wasm.js" "$wasm/posemorph_wasm.wasm" \
     "$rig" "${pages[@]}" "$work/flat.pmrig" "$images"/*.png "$d/"
done
# 960x320: neither the size the drawings were baked from nor the page's.
cp "$here/../../docs/crowd.png" "$work/site/resized/rest.png"
cp "$here/../../docs/crowd.png" "$work/site/resized/$(basename "${pages[0]}")"
head -c 1000 "$rig" > "$work/site/bad.pmrig"                    # truncated

python3 -m http.server 0 --bind 127.0.0.1 --directory "$work/site" > "$work/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 50); do grep -q "port" "$work/server.log" && break; sleep 0.1; done
port=$(grep -o 'port [0-9]*' "$work/server.log" | head -1 | cut -d' ' -f2)
site="http://127.0.0.1:$port"
chrome=(chromium --headless=new --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --hide-scrollbars)
page() { timeout 60 "${chrome[@]}" --virtual-time-budget=30000 --dump-dom "$site/$1" 2>/dev/null | grep -o '<pre id="result">[^<]*' | cut -d'>' -f2; }

# 1. The same vertices as the native runtime, bit for bit.
got=$(page "index.html?at=0.5,0.5&size=256")
echo "page: $got"
want=$("$hash" "$rig" 0.5 0.5)
case "$got" in *"$want"*) echo "native: $want (equal)";; *) echo "FAIL: the page's positions differ from the native $want"; exit 1;; esac

# 2. The frame: a screenshot, against posemorph-view at the same point.
timeout 60 "${chrome[@]}" --virtual-time-budget=30000 --window-size=256,256 --screenshot="$work/web.png" \
  "$site/index.html?at=0.5,0.5&size=256" 2>/dev/null
"$view" "$rig" --images "$images" --headless --at 0.5,0.5 --size 256x256 -o "$work/view.png" > /dev/null
echo -n "web page against posemorph-view at (0.5, 0.5): "
"$compare" "$work/web.png" "$work/view.png" 0.01
cp "$work/web.png" "$shots/web.png"
# Tinted and half transparent: the page applies the draw list's colour as the viewer does.
timeout 60 "${chrome[@]}" --virtual-time-budget=30000 --window-size=256,256 --screenshot="$work/web-tint.png" \
  "$site/index.html?at=0.5,0.5&size=256&tint=1,0.5,0.25,0.6" 2>/dev/null
"$view" "$rig" --images "$images" --headless --at 0.5,0.5 --size 256x256 --tint 1,0.5,0.25,0.6 \
  -o "$work/view-tint.png" > /dev/null
echo -n "web page against posemorph-view, tinted 1,0.5,0.25 at opacity 0.6: "
"$compare" "$work/web-tint.png" "$work/view-tint.png" 0.01
if "$compare" "$work/web-tint.png" "$work/web.png" 0.01 > /dev/null; then echo "FAIL: the tint changed nothing"; exit 1; fi
# A rig without an atlas: the page draws each pose's drawing, the same frame.
timeout 60 "${chrome[@]}" --virtual-time-budget=30000 --window-size=256,256 --screenshot="$work/web-flat.png" \
  "$site/index.html?rig=flat.pmrig&at=0.5,0.5&size=256" 2>/dev/null
"$view" "$work/flat.pmrig" --images "$images" --headless --at 0.5,0.5 --size 256x256 -o "$work/view-flat.png" > /dev/null
echo -n "web page from the drawings (a rig without an atlas) against posemorph-view: "
"$compare" "$work/web-flat.png" "$work/view-flat.png" 0.01
echo -n "web page from the atlas page against from the drawings: "
"$compare" "$work/web.png" "$work/web-flat.png" 0.01

# 3. Load errors show in the page.
expect() {
  local text; text=$(page "$1")
  case "$text" in *"$2"*) echo "page $1: $text";; *) echo "FAIL: page $1 says '$text', expected '$2'"; exit 1;; esac
}
expect "index.html?rig=missing.pmrig" "error: missing.pmrig: HTTP 404"
expect "index.html?rig=bad.pmrig" "error: bad.pmrig: "
page_name=$(basename "${pages[0]}")
expect "resized/index.html?at=0,0" "error: $page_name: the atlas page is 960x320, the rig's pages are"
expect "resized/index.html?rig=flat.pmrig&at=0,0" \
  "error: rest.png: the drawing is 960x320, the rig was baked from 256x256"

# 4. Real time (virtual time stops the clock): the page's title, read over the debugging port.
title=$(python3 "$here/../../scripts/chromium-title.py" "$site/index.html?at=0.5,0.5&size=256" ready,error 60 \
        "$work/profile" || true)
echo "timed in real time: $title"
case "$title" in *"us per frame"*) ;; *) echo "FAIL: no timing from the page"; exit 1;; esac
