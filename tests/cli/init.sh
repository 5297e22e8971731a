#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# posemorph-bake init (ctest cli.init): for every drawn sample (the build's
# rasterised drawings), a description written from the drawings alone bakes
# with default settings (fold-free, compact) and says so; Pell's per-part
# drawings give a layered description whose joints are the hand-written
# ones within 4 px (head, eyes, mouth); SVGs with a layer per part give
# parts; and the refusals:
# each one line naming the file or the option, status 1 or 2, nothing written.
#   init.sh BAKE ASSETS WORK
set -euo pipefail
bake=$1 assets=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
for sample in pip sprout owl bobble sprites/cat sprites/chick sprites/ghost sprites/slime sprites/slime-shadow; do
  name=$(basename "$sample")
  drawings=("$assets/$sample/rest.png")
  for d in "$assets/$sample"/*.png; do [ "$(basename "$d")" = rest.png ] || drawings+=("$d"); done
  said=$("$bake" init "${drawings[@]}" -o "$work/$name.json" 2>&1) || { fail "$name: init: $said"; continue; }
  case "$said" in *"it bakes as written"*) ;; *) fail "$name: init says: $said" ;; esac
  if baked=$("$bake" "$work/$name.json" -o "$work/$name.pmrig" 2>&1); then
    echo "$name: ${#drawings[@]} drawings -> $(grep -o '^baked [^;]*' <<< "$baked" | sed 's/ nnz.*//')"
  else
    fail "$name: the description init wrote does not bake: $(tail -1 <<< "$baked")"
  fi
done
# A layered character: Pell's parts as POSE-PART.png (the build's per-part
# drawings), glued where they are drawn over each other.
pell=()
for pose in rest wave cross lean; do pell+=("$assets/pell/$pose"-*.png); done
said=$("$bake" init "${pell[@]}" -o "$work/pell.json" 2>&1) || fail "pell: init: $said"
case "$said" in *"4 poses"*"of 7 parts"*"it bakes as written"*) echo "pell: $said" | head -1 ;;
  *) fail "pell: init says: $said" ;; esac
if baked=$("$bake" "$work/pell.json" -o "$work/pell.pmrig" 2>&1); then
  echo "pell: $(grep -o '^baked [^;]*' <<< "$baked" | sed 's/ nnz.*//')"
else
  fail "pell: the layered description init wrote does not bake: $(tail -1 <<< "$baked")"
fi
# The joints it found for the head, the eyes and the mouth are within 4 px of
# the ones written by hand in assets/pell/pell.json, in every pose (the
# overlap's centre on the pixel grid against a designer's pivot: 3.04 px at worst
# when this was written).
python3 - "$work/pell.json" "$(dirname "$0")/../../assets/pell/pell.json" <<'PY' || fail "pell: joints"
import json, math, sys
ours = {g["part"]: g for g in json.load(open(sys.argv[1]))["glue"]}
hand = {g["part"]: g for g in json.load(open(sys.argv[2]))["glue"]}
worst = 0
for part in ("head", "eye-left", "eye-right", "mouth"):
    assert ours[part]["to"] == hand[part]["to"], (part, ours[part]["to"], hand[part]["to"])
    for a, b in zip(ours[part]["at"], hand[part]["at"]):
        worst = max(worst, math.dist(a, b))
print(f"pell: the head's, eyes' and mouth's joints within {worst:.2f} px of the hand-written ones")
sys.exit(0 if worst <= 4 else 1)
PY

# A layered character drawn as one SVG per pose, a top-level layer per part
# (Inkscape layers, a hidden one that is no part; a viewBox not at 0, 0 and
# smaller than 256, so init fills the layers at 256/150 pixels per unit):
# parts from the layers' names, each joint inside both parts in the
# drawing's own coordinates; a set of layers that differs is refused.
python3 - "$work" <<'PY'
import math, sys
for i, angle in enumerate((-100, -40, 20)):
    t = math.radians(angle)
    at = lambda x, y: (85 + math.cos(t) * x - math.sin(t) * y, 75 + math.sin(t) * x + math.cos(t) * y)
    arm = " L ".join("%.4f %.4f" % at(x, y) for x, y in ((-8, -8), (60, -8), (60, 8), (-8, 8)))
    open(f"{sys.argv[1]}/svg{i}.svg", "w").write(
        '<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        'viewBox="20 10 150 150">\n'
        '<g inkscape:groupmode="layer" inkscape:label="paper" id="layer1" style="display:none">'
        '<path d="M 20 10 H 170 V 160 H 20 Z"/></g>\n'
        '<g inkscape:groupmode="layer" inkscape:label="body" id="layer2">'
        '<polygon points="40,60 100,60 100,140 40,140"/></g>\n'
        f'<g inkscape:groupmode="layer" inkscape:label="arm" id="layer3"><path d="M {arm} Z"/></g>\n</svg>\n')
PY
said=$("$bake" init "$work"/svg{0,1,2}.svg -o "$work/svg.json" 2>&1) || fail "svg layers: init: $said"
case "$said" in *"3 poses"*"of 2 parts (each SVG's top-level layers"*"it bakes as written"*) echo "svg layers: $said" | head -1 ;;
  *) fail "svg layers: init says: $said" ;; esac
python3 - "$work/svg.json" <<'PY' || fail "svg layers: parts or joints"
import json, math, sys
d = json.load(open(sys.argv[1]))
assert [p["name"] for p in d["parts"]] == ["body", "arm"], [p["name"] for p in d["parts"]]
assert [p["drawing"] for p in d["parts"][1]["poses"]] == ["svg0.svg", "svg1.svg", "svg2.svg"]
(glue,) = d["glue"]
for (x, y), angle in zip(glue["at"], (-100, -40, 20)):
    t = math.radians(angle)  # the joint in the arm's own frame, and in the body
    u, v = math.cos(t) * (x - 85) + math.sin(t) * (y - 75), -math.sin(t) * (x - 85) + math.cos(t) * (y - 75)
    assert 40 < x < 100 and 60 < y < 140 and -8 < u < 60 and -8 < v < 8, (x, y, u, v)
print("svg layers: body and arm, joints", glue["at"], "inside both")
PY
sed 's/inkscape:label="arm"/inkscape:label="wing"/' "$work/svg2.svg" > "$work/svg3.svg"

# The layout: the first pose at the centre, the others clockwise from the top.
grep -q '"name": "rest", "point": \[0, 0\]' "$work/pip.json" || fail "pip: rest is not at the centre"
grep -q '"point": \[0, 1\]' "$work/pip.json" && grep -q '"point": \[-1, 0\]' "$work/pip.json" ||
  fail "pip: the other poses are not up, right, down, left"

refused() {  # expected status, expected text, arguments...
  local status=$1 text=$2 got rc=0
  shift 2
  got=$("$bake" init "$@" 2>&1) || rc=$?
  if [ "$rc" = "$status" ] && [[ "$got" == *"$text"* ]]; then echo "refused ($rc): $got"
  else fail "init $*: status $rc, '$got' (expected $status, '$text')"; fi
}
p=$assets/pip
refused 2 "init needs -o RIG.json" "$p/rest.png" "$p/wave.png"
refused 2 "init needs two drawings or more" "$p/rest.png" -o "$work/one.json"
refused 2 "-o must name a .json file" "$p/rest.png" "$p/wave.png" -o "$work/out.txt"
refused 1 "$work/missing.png: cannot read the drawing" "$p/rest.png" "$work/missing.png" -o "$work/missing.json"
refused 2 "init takes layered files (.ora, .psd) or flat drawings (PNG, SVG), not both" "$p/rest.png" \
  "$work/pose.ora" -o "$work/ora.json"
refused 1 "$work/pip.json: exists; init does not overwrite" "$p/rest.png" "$p/wave.png" -o "$work/pip.json"
refused 1 "$work/svg3.svg: its layers ('body', 'wing') are not $work/svg0.svg's ('body', 'arm')" \
  "$work/svg0.svg" "$work/svg3.svg" -o "$work/layers.json"
for f in one missing ora layers; do [ ! -e "$work/$f.json" ] || fail "$f.json was written"; done
[ "$failures" -eq 0 ] && echo "init: ok" || exit 1
