#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Makes every picture under docs/ from the samples, so that a change that
# alters a frame is a run of this script, never a hand copy:
#
#   scripts/docs-figures.sh [OUT-DIR]     # default: docs/
#
# It needs the release build (cmake --preset release; the drawn samples are
# rasterised by it), rsvg-convert, and for the window and example pictures
# xvfb-run with lavapipe (Vulkan on the CPU: the same pixels on any
# machine), Mesa's llvmpipe and Chromium: what scripts/setup.sh installs.
# Each picture is written to OUT-DIR under its docs/ name. At the end the
# script fails, naming them, if a picture under docs/ was not made, or if a
# picture a Markdown file shows is neither made nor present: CI runs it into
# a scratch folder, so a picture without a recipe here fails CI.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs}
build=build/release
bin=$build/bin
drawn=$build/assets
for tool in "$bin/posemorph-bake" "$bin/posemorph-view" "$bin/posemorph-example-sdl2"; do
  [ -x "$tool" ] || { echo "scripts/docs-figures.sh: $tool is missing: build the release preset first" >&2; exit 1; }
done
mkdir -p "$out/examples"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
lavapipe=$(ls /usr/share/vulkan/icd.d/lvp_icd.*.json 2>/dev/null | head -n1 || true)
[ -n "$lavapipe" ] && export VK_ICD_FILENAMES=$lavapipe
made=()
wrote() { made+=("$1"); echo "docs-figures: $out/$1"; }
bake() { "$bin/posemorph-bake" "$@" > /dev/null; }
view() { "$bin/posemorph-view" "$@" > /dev/null; }
window() { xvfb-run -a -s "-screen 0 1400x900x24" "$bin/posemorph-view" "$@" > /dev/null; }

# Pip: its drawings side by side, each labelled with its file.
mkdir -p "$work/drawings"
cp assets/pip/*.svg "$work/drawings/"
{
  echo '<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" width="1000" height="236">'
  echo '<rect width="1000" height="236" fill="#f6f6f6"/>'
  x=0
  for pose in rest stretch squash wave lean; do
    echo "<image x=\"$((x + 10))\" y=\"0\" width=\"180\" height=\"180\" xlink:href=\"$pose.svg\"/>"
    echo "<text x=\"$((x + 100))\" y=\"222\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"16\" fill=\"#333\" text-anchor=\"middle\">$pose.svg</text>"
    x=$((x + 200))
  done
  echo '</svg>'
} > "$work/drawings/pip-drawings.svg"
rsvg-convert "$work/drawings/pip-drawings.svg" -o "$out/pip-drawings.png" && wrote pip-drawings.png

# Pip baked as the quick start bakes it, and its contact sheets.
bake "$drawn/pip/pip.json" -o "$work/pip.pmrig"
bake sheet "$work/pip.pmrig" -o "$work/pip-sheet.svg"
rsvg-convert "$work/pip-sheet.svg" -o "$out/pip-sheet.png" && wrote pip-sheet.png
bake sheet "$work/pip.pmrig" --textured --columns 5 --rows 3 -o "$out/pip-sheet-textured.png" && wrote pip-sheet-textured.png

# The interiors: hello at t = 0.3 baked from the outlines only, with the
# drawings' alignment, and with the eye features as well (pip.json itself).
mkdir -p "$work/pip-plain"
cp "$drawn"/pip/*.png "$work/pip-plain/"
python3 - "$drawn/pip/pip.json" "$work/pip-plain/pip.json" <<'EOF'
import json, sys
rig = json.load(open(sys.argv[1]))
for pose in rig['poses']:
    pose.pop('features', None)
json.dump(rig, open(sys.argv[2], 'w'), indent=1)
EOF
bake "$work/pip-plain/pip.json" --no-align -o "$work/pip-plain/outline-only.pmrig"
bake "$work/pip-plain/pip.json" -o "$work/pip-plain/aligned.pmrig"
hello=(--headless --size 320x320 --path hello --time 0.3)
view "$work/pip-plain/outline-only.pmrig" "${hello[@]}" -o "$out/pip-hello-outline-only.png" && wrote pip-hello-outline-only.png
view "$work/pip-plain/aligned.pmrig" "${hello[@]}" -o "$out/pip-hello-aligned.png" && wrote pip-hello-aligned.png
view "$work/pip.pmrig" --images "$drawn/pip" "${hello[@]}" -o "$out/pip-hello-default.png" && wrote pip-hello-default.png

# Crowds.
view "$work/pip.pmrig" --images "$drawn/pip" --headless --size 960x320 --path hello --crowd 40 --seed 4 \
  -o "$out/crowd.png" && wrote crowd.png

# Pell, the layered sample, and Pell with a face channel.
bake "$drawn/pell/pell.json" -o "$work/pell.pmrig"
view "$work/pell.pmrig" --images "$drawn/pell" --headless --bases --size 1024x256 -o "$out/pell.png" && wrote pell.png
bake sheet "$work/pell.pmrig" --textured --columns 5 --rows 3 -o "$out/pell-sheet-textured.png" && wrote pell-sheet-textured.png
bake "$drawn/pell/pell-face.json" -o "$work/pell-face.pmrig"
bake sheet "$work/pell-face.pmrig" --textured --columns 5 --rows 3 -o "$out/pell-face-sheet-body.png" \
  && wrote pell-face-sheet-body.png
bake sheet "$work/pell-face.pmrig" --textured --channel face --columns 5 --rows 3 -o "$out/pell-face-sheet-face.png" \
  && wrote pell-face-sheet-face.png
view "$work/pell-face.pmrig" --images "$drawn/pell" --headless --size 1280x720 --crowd 12 --path greet \
  --channel face=chatter -o "$out/pell-face-crowd.png" && wrote pell-face-crowd.png

# The gingerbread figure's contact sheet (poses made by dragging handles).
bake assets/gingerbread/gingerbread.json -o "$work/gingerbread.pmrig"
bake sheet "$work/gingerbread.pmrig" -o "$work/gingerbread-sheet.svg"
rsvg-convert "$work/gingerbread-sheet.svg" -o "$out/gingerbread-sheet.png" && wrote gingerbread-sheet.png

# Pell with a face driven by its state machine (posemorph-view --inputs):
# six frames of one input timeline, each labelled with its time and the
# states the viewer's log says each layer is in then.
timeline="0.4:wave;1:talking;3:!talking;3.2:ghost;4.6:!ghost;4.6:vanish"
mkdir -p "$work/states"
"$bin/posemorph-view" "$work/pell-face.pmrig" --images "$drawn/pell" --headless --size 280x300 --inputs "$timeline" \
  --fps 10 --frames 56 -o "$work/states/f.png" > "$work/states/log.txt"
python3 - "$work/states" "$timeline" > "$work/states/strip.svg" <<'EOF'
import re, sys
folder, timeline = sys.argv[1], sys.argv[2]
changes = []  # (time, layer, state), from the log's lines "T s  LAYER: FROM -> TO"
for line in open(folder + "/log.txt"):
    m = re.match(r"\s*([0-9.]+) s  (\w+): .* -> (\S+)$", line)
    if m:
        changes.append((float(m.group(1)), m.group(2), m.group(3)))
frames = [0, 9, 16, 31, 40, 52]
w, h = 280, 300
print(f'<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" '
      f'width="{w * len(frames)}" height="{h + 78}">')
print(f'<rect width="{w * len(frames)}" height="{h + 78}" fill="#f6f6f6"/>')
for i, f in enumerate(frames):
    t = f / 10
    state = {}
    for time, layer, to in changes:
        if time <= t + 1e-9:
            state[layer] = to
    x = i * w
    print(f'<image x="{x}" y="0" width="{w}" height="{h}" xlink:href="f-{f:03d}.png"/>')
    label = " \u00b7 ".join(state[k] for k in ("body", "face") if k in state)
    for row, text in enumerate([f"{t:.1f} s", label]):
        print(f'<text x="{x + w / 2}" y="{h + 22 + 22 * row}" font-family="DejaVu Sans, sans-serif" font-size="16" '
              f'fill="#333" text-anchor="middle">{text}</text>')
print(f'<text x="8" y="{h + 72}" font-family="DejaVu Sans Mono, monospace" font-size="12" fill="#777">'
      f'posemorph-view pell-face.pmrig --inputs "{timeline}"</text>')
print("</svg>")
EOF
rsvg-convert "$work/states/strip.svg" -o "$out/pell-face-states.png" && wrote pell-face-states.png

# The window under Xvfb: the smoke test's own screenshot (it drags the pad,
# records a gesture and, on a copy of Pip's description, edits a pose).
mkdir -p "$work/pip-authoring"
cp "$drawn"/pip/* "$work/pip-authoring/"
window "$work/pip.pmrig" --images "$drawn/pip" --size 1280x780 --frames 30 --description "$work/pip-authoring/pip.json" \
  --smoke-test "$out/viewer.png" && wrote viewer.png
window "$work/pell.pmrig" --images "$drawn/pell" --size 1300x920 --joints --frames 20 \
  --smoke-test "$out/pell-window.png" && wrote pell-window.png
window "$work/pell-face.pmrig" --images "$drawn/pell" --size 1300x920 --joints --channel face=chatter --frames 20 \
  --smoke-test "$out/pell-face-window.png" && wrote pell-face-window.png
# The state machine's panel: each layer's state, the inputs, the log (--inputs on the window's clock).
window "$work/pell-face.pmrig" --images "$drawn/pell" --size 1300x920 --inputs "0.2:wave;0.3:talking" --frames 40 \
  --smoke-test "$out/pell-face-machine-window.png" && wrote pell-face-machine-window.png

# The examples and the LÖVE and web integrations: the pictures their tests
# took after comparing them with posemorph-view's frames
# (examples/CMakeLists.txt, integrations/*/tests/run.sh). Shots newer than
# every program that made them come from this build's test run (CI's release
# step has just run the five tests) and are taken as they are; otherwise the
# five run again here.
shots=("$build/example-shots/sdl2-opengl/sdl2.png" "$build/example-shots/sdl2-opengl/crowd.png"
       "$build/example-shots/web/web.png" "$build/example-shots/love/love-crowd.png"
       "$build/example-shots/web-pixi/web-crowd.png" "$build/example-shots/csharp/csharp-crowd.png")
makers=("$bin/posemorph-view" "$bin/posemorph-example-sdl2" "$build/examples/web-wasm/posemorph_wasm.wasm"
        "$build/rigs/pip.pmrig" "$build/rigs/pell-face.compact.pmrig" "$build/bindings/libposemorph.so"
        integrations/love/posemorph.lua integrations/love/example/main.lua
        "$build/integrations/web/wasm/posemorph_wasm.wasm" integrations/web/pixi.mjs integrations/web/example/main.mjs
        integrations/csharp/Posemorph.cs integrations/csharp/example/Example.cs integrations/csharp/example/Picture.cs)
fresh=1
for shot in "${shots[@]}"; do
  [ -f "$shot" ] || { fresh=0; break; }
  for maker in "${makers[@]}"; do
    [ -f "$maker" ] && [ "$shot" -nt "$maker" ] || { fresh=0; break 2; }
  done
done
if [ "$fresh" = 1 ]; then
  echo "docs-figures: the example shots in $build/example-shots are newer than their programs: taken as they are"
else
  ctest --test-dir "$build" -R '^(example\.(sdl2_opengl|web)|integration\.(love|web|csharp))$' --output-on-failure \
    > "$work/examples.log" ||
    { cat "$work/examples.log" >&2; exit 1; }
fi
cp "$build/example-shots/sdl2-opengl/sdl2.png" "$out/examples/sdl2-opengl.png" && wrote examples/sdl2-opengl.png
cp "$build/example-shots/sdl2-opengl/crowd.png" "$out/examples/sdl2-opengl-crowd.png" && wrote examples/sdl2-opengl-crowd.png
cp "$build/example-shots/web/web.png" "$out/examples/web.png" && wrote examples/web.png
cp "$build/example-shots/love/love-crowd.png" "$out/examples/love-crowd.png" && wrote examples/love-crowd.png
cp "$build/example-shots/csharp/csharp-crowd.png" "$out/examples/csharp-crowd.png" && wrote examples/csharp-crowd.png
if [ -f "$build/example-shots/web-pixi/web-crowd.png" ]; then
  cp "$build/example-shots/web-pixi/web-crowd.png" "$out/examples/web-crowd.png" && wrote examples/web-crowd.png
else  # integration.web skips, with its reason, where the npm registry cannot be reached
  made+=(examples/web-crowd.png)
  echo "docs-figures: examples/web-crowd.png not made: integration.web did not run (see its output)" >&2
fi

# Every picture under docs/ has a recipe above, and every picture a Markdown
# file shows exists.
missing=()
while IFS= read -r png; do
  name=${png#docs/}
  [[ " ${made[*]} " == *" $name "* ]] || missing+=("$png (no recipe in scripts/docs-figures.sh)")
done < <(git ls-files 'docs/*.png')
while IFS= read -r shown; do
  missing+=("$shown (shown, not there)")
done < <(python3 -c '
import os, re, subprocess
for md in subprocess.run(["git", "ls-files", "*.md"], capture_output=True, text=True, check=True).stdout.split():
    for ref in re.findall(r"(?:\]\(|src=\")([^)\"\s]+\.png)", open(md, encoding="utf-8").read()):
        path = os.path.normpath(os.path.join(os.path.dirname(md), ref))
        if "://" not in ref and not ref.startswith("out/") and not os.path.isfile(path):
            print(path + " in " + md)
')
if [ ${#missing[@]} -gt 0 ]; then
  printf 'scripts/docs-figures.sh: %s\n' "${missing[@]}" >&2
  exit 1
fi
echo "docs-figures: ${#made[@]} pictures in $out"
