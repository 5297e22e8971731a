#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# posemorph-bake import and init on layered files (ctest cli.import), with
# the fixtures GIMP and Krita wrote (tests/data/import/, made by
# scripts/make-import-fixtures.sh from the build's Pell drawings):
#  - Pell as four PSDs (GIMP, a layer per part) and as one OpenRaster file
#    (Krita, a group per pose) imports to drawings from which Pell's own
#    description bakes the very rig the build's drawings give: the same
#    bytes, so the same meshes (tolerance 0);
#  - init on the OpenRaster file writes a description that bakes as written,
#    and init --channels on Pell's body and face files one with two channels
#    whose face joints are the hand-written ones within 4 px;
#  - each refusal is one line naming the file, status 1 or 2, nothing written.
#   import.sh BAKE ASSETS SOURCE WORK
set -euo pipefail
bake=$1 assets=$2 source=$3 work=$4
data=$source/tests/data/import
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The reference: Pell baked from the build's drawings, in the same layout.
mkdir -p "$work/reference"
cp "$assets"/pell/{rest,wave,cross,lean}-*.png "$source/assets/pell/pell.json" "$work/reference/"
"$bake" "$work/reference/pell.json" -o "$work/reference/pell.pmrig" --quiet

for kind in psd ora; do
  if [ $kind = psd ]; then files=("$data"/pell/{rest,wave,cross,lean}.psd); else files=("$data/pell/pell.ora"); fi
  said=$("$bake" import "${files[@]}" -o "$work/$kind" 2>&1) || { fail "$kind: import: $said"; continue; }
  case "$said" in *"wrote 28 drawings of 256 x 256 pixels"*"4 poses of 7 parts"*) ;; *) fail "$kind: import says: $said" ;; esac
  if [ $kind = psd ]; then
    # GIMP's hidden sketch layer in each pose: left out, with a note.
    [ "$(grep -c "layer 'sketch' is hidden: not imported" <<< "$said")" = 4 ] || fail "psd: hidden layers not noted: $said"
  fi
  cp "$source/assets/pell/pell.json" "$work/$kind/"
  "$bake" "$work/$kind/pell.json" -o "$work/$kind/pell.pmrig" --quiet || { fail "$kind: the imported Pell does not bake"; continue; }
  if cmp -s "$work/reference/pell.pmrig" "$work/$kind/pell.pmrig"; then
    echo "$kind: ${#files[@]} file(s) -> 28 drawings -> the same rig as the build's drawings ($(stat -c %s "$work/$kind/pell.pmrig") bytes, identical)"
  else
    fail "$kind: the rig baked from the imported drawings differs from the one baked from the build's"
  fi
done

# init on the OpenRaster file: drawings beside the description, which bakes.
mkdir -p "$work/init"
said=$("$bake" init "$data/pell/pell.ora" -o "$work/init/pell.json" 2>&1) || fail "init: $said"
case "$said" in *"imported 28 drawings from 1 layered file"*"4 poses"*"of 7 parts"*"it bakes as written"*) echo "init: $(head -1 <<< "$said")" ;;
  *) fail "init says: $said" ;; esac
[ -f "$work/init/wave-arm-left.png" ] || fail "init: no wave-arm-left.png beside the description"
# (init's own trial bake, in memory, is what "bakes as written" says.)

# init --channels: Pell with a face from two Krita files, body.ora (a group
# per pose) and face.ora (a group per expression): it bakes as written, and
# the face's joints on the head are the hand-written ones (pell-face.json)
# within 4 px.
mkdir -p "$work/channels"
said=$("$bake" init --channels "$data/pell/body.ora" "$data/pell/face.ora" -o "$work/channels/pell-face.json" 2>&1) ||
  fail "init --channels: $said"
case "$said" in *"2 channels (body: 4 poses of 4 parts, face: 4 poses of 3 parts"*"it bakes as written"*)
  echo "init --channels: $(head -1 <<< "$said")" ;;
  *) fail "init --channels says: $said" ;; esac
worst=$(python3 - "$work/channels/pell-face.json" "$source/assets/pell/pell-face.json" <<'PY'
import json, math, sys
made = {g["part"]: g for g in json.load(open(sys.argv[1]))["glue"]}
hand = {g["part"]: g for g in json.load(open(sys.argv[2]))["glue"]}
worst = 0
for part in ("eye-left", "eye-right", "mouth"):
    assert made[part]["to"] == "head" == hand[part]["to"], part
    worst = max(worst, max(math.dist(a, b) for a, b in zip(made[part]["at"], hand[part]["at"])))
print(f"{worst:.2f}")
PY
) || fail "init --channels: the face's glue is not on the head"
python3 -c "import sys; sys.exit(0 if float('$worst') <= 4 else 1)" || fail "init --channels: a face joint is $worst px from the hand-written one"
echo "init --channels: the face's joints within $worst px of pell-face.json's"
python3 -c "import json, sys; d = json.load(open(sys.argv[1])); sys.exit(0 if [c['name'] for c in d['channels']] == ['body', 'face'] and sum(p.get('channel') == 'face' for p in d['parts']) == 3 else 1)" "$work/channels/pell-face.json" ||
  fail "init --channels: the description has not channels body and face, the face's 3 parts on face"

# Refusals: one line, the status, nothing written.
refuse() {  # refuse STATUS EXPECTED-TEXT CHECK-ABSENT ARGS...
  local status=$1 text=$2 absent=$3 said rc=0
  shift 3
  said=$("$bake" "$@" 2>&1) || rc=$?
  [ "$rc" = "$status" ] || fail "posemorph-bake $*: status $rc, expected $status: $said"
  [ "$(wc -l <<< "$said")" = 1 ] || fail "posemorph-bake $*: more than one line: $said"
  case "$said" in *"$text"*) ;; *) fail "posemorph-bake $*: says '$said', expected '$text'" ;; esac
  [ -z "$absent" ] || [ ! -e "$absent" ] || fail "posemorph-bake $*: wrote $absent"
}
# The same description naming the Krita file's layers directly
# ("pell.ora#rest/body"): the same meshes (eval's frame), the same atlas page
# (its pixels come from the layers), no PNG written.
mkdir -p "$work/refs"
cp "$data/pell/pell.ora" "$work/refs/"
python3 - "$source/assets/pell/pell.json" "$work/refs/pell.json" <<'PY'
import json, re, sys
d = json.load(open(sys.argv[1]))
for part in d["parts"]:
    for pose in part["poses"]:
        m = re.fullmatch(r"(rest|wave|cross|lean)-(.+)\.png", pose["drawing"])
        pose["drawing"] = "pell.ora#%s/%s" % (m.group(1), m.group(2))
json.dump(d, open(sys.argv[2], "w"))
PY
if "$bake" "$work/refs/pell.json" -o "$work/refs/pell.pmrig" --quiet; then
  "$bake" eval "$work/reference/pell.pmrig" --at 0.3,0.2 -o "$work/reference/frame.json" > /dev/null
  "$bake" eval "$work/refs/pell.pmrig" --at 0.3,0.2 -o "$work/refs/frame.json" > /dev/null
  cmp -s "$work/reference/frame.json" "$work/refs/frame.json" || fail "layer references: the frame differs from the PNGs'"
  cmp -s "$work/reference/pell.page0.png" "$work/refs/pell.page0.png" || fail "layer references: the atlas page differs"
  [ -z "$(find "$work/refs" -name '*-*.png')" ] || fail "layer references: PNG drawings were written"
  echo "layer references: pell.ora#POSE/PART -> the same frame and atlas page as the imported PNGs"
else
  fail "the description naming pell.ora's layers does not bake"
fi
sed 's|pell.ora#rest/arm-left|pell.ora#rest/elbow|' "$work/refs/pell.json" > "$work/refs/elbow.json"
refuse 1 "no layer or group 'elbow' in 'rest' (it holds" "$work/refs/elbow.pmrig" \
  "$work/refs/elbow.json" -o "$work/refs/elbow.pmrig"
refuse 1 "cannot be baked with \"atlas\": false or --no-atlas" "$work/refs/flat.pmrig" \
  "$work/refs/pell.json" --no-atlas -o "$work/refs/flat.pmrig"

mkdir -p "$work/again"
cp "$work/init/rest-head.png" "$work/again/rest-body.png"  # another drawing where one would be written
refuse 1 "$work/again/rest-body.png: exists, and the drawing of $data/pell/pell.ora: group 'rest': layer 'body' would replace it (--force does)" \
  "$work/again/pell.json" init "$data/pell/pell.ora" -o "$work/again/pell.json"
[ ! -e "$work/again/rest-mouth.png" ] || fail "init wrote drawings before refusing"
head -c 3000 "$data/features.psd" > "$work/cut.psd"
refuse 1 "$work/cut.psd: damaged or truncated: " "$work/cut" import "$work/cut.psd" -o "$work/cut"
refuse 1 "$data/features.psd: a canvas of 64 x 48, but $data/pell/rest.psd's is 256 x 256" "$work/mixed" \
  import "$data/pell/rest.psd" "$data/features.psd" -o "$work/mixed"
refuse 1 "$assets/pell/rest-body.png: not a layered file import reads (.ora or .psd); a sprite sheet (.png) is imported alone" \
  "$work/png" import "$data/pell/rest.psd" "$assets/pell/rest-body.png" -o "$work/png"
refuse 2 "init takes layered files (.ora, .psd) or flat drawings (PNG, SVG), not both" "$work/both.json" \
  init "$data/pell/pell.ora" "$assets/pell/rest-body.png" -o "$work/both.json"
refuse 2 "--flatten is for layered files (.ora, .psd)" "$work/flat.json" \
  init "$assets/pell/rest-body.png" "$assets/pell/wave-body.png" --flatten -o "$work/flat.json"
refuse 1 "$data/pell/rest.psd: gives one pose: init needs two poses or more" "$work/one.json" \
  init "$data/pell/rest.psd" -o "$work/one.json"
[ ! -e "$work/rest-body.png" ] || fail "init wrote drawings of a single pose before refusing"
refuse 1 "$data/pell/face.ora: part 'mouth' is also a part of $data/pell/pell.ora" "$work/both-mouths.json" \
  init --channels "$data/pell/pell.ora" "$data/pell/face.ora" -o "$work/both-mouths.json"
refuse 2 "--channels takes 2 to 8 layered files" "$work/one-channel.json" \
  init --channels "$data/pell/pell.ora" -o "$work/one-channel.json"

[ "$failures" = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "import: PSD (GIMP) and OpenRaster (Krita) Pell bake to the build's rig, init and init --channels bake, 9 refusals"
