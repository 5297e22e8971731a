#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# posemorph-bake import on a sprite sheet (ctest cli.import_sheet): the
# build's ghost drawings (4 poses) laid out in a sheet of 3 x 2 cells, the
# last two empty, as a game keeps its frames:
#  - --frames 3x2 writes the 4 frames, each the very pixels of its drawing
#    (compared byte for byte, decoded), names them in the sheet's order and
#    notes the 2 empty cells; --cell WxH writes the same files;
#  - init on the frames writes a description that bakes as written;
#  - each refusal is one line naming the file or the option, status 1 or 2,
#    and nothing is written.
#   import_sheet.sh BAKE ASSETS SOURCE WORK
set -euo pipefail
bake=$1 assets=$2 source=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
ghost=$assets/sprites/ghost
png() { PYTHONPATH="$source/scripts" python3 -c "import game_art_compose as g, sys; $1" "${@:2}"; }

# The sheet: rest, wave, lean, stretch in the first row and a half.
png '
w, h, _ = g.read_png(sys.argv[1])
cells = [g.read_png(p)[2] for p in sys.argv[1:5]]
sheet = bytearray(3 * w * 2 * h * 4)
for k, c in enumerate(cells):
    x0, y0 = (k % 3) * w, (k // 3) * h
    for y in range(h):
        sheet[((y0 + y) * 3 * w + x0) * 4:((y0 + y) * 3 * w + x0 + w) * 4] = c[y * w * 4:(y + 1) * w * 4]
g.write_png(sys.argv[5], 3 * w, 2 * h, sheet)
print(w, h)' "$ghost"/{rest,wave,lean,stretch}.png "$work/ghost sheet.png" > "$work/size"
read -r w h < "$work/size"

said=$("$bake" import "$work/ghost sheet.png" --frames 3x2 -o "$work/frames" 2>&1) || fail "import --frames: $said"
case "$said" in *"wrote 4 frames of $w x $h pixels to $work/frames: ghost_sheet_0.png .. ghost_sheet_3.png"*) ;;
  *) fail "import --frames says: $said" ;; esac
[ "$(grep -c "is empty (no pixel above zero alpha): no frame made of it" <<< "$said")" = 2 ] ||
  fail "the empty cells are not noted: $said"
grep -q "cell (column 1, row 1) at ($w, $h) is empty" <<< "$said" || fail "the empty cell's place: $said"
k=0
for pose in rest wave lean stretch; do
  png 'assert g.read_png(sys.argv[1]) == g.read_png(sys.argv[2]), sys.argv[2]' \
    "$ghost/$pose.png" "$work/frames/ghost_sheet_$k.png" || fail "frame $k is not the $pose drawing's pixels"
  k=$((k + 1))
done
said=$("$bake" import "$work/ghost sheet.png" --cell "${w}x${h}" --name ghost -o "$work/cells" 2>&1) || fail "import --cell: $said"
for k in 0 1 2 3; do
  cmp -s "$work/frames/ghost_sheet_$k.png" "$work/cells/ghost_$k.png" || fail "--cell: frame $k differs from --frames'"
done
echo "import: a 3 x 2 sheet -> 4 frames of $w x $h, the drawings' own pixels; 2 empty cells noted"

# init on the frames: a description that bakes.
said=$("$bake" init "$work"/frames/ghost_sheet_{0,1,2,3}.png -o "$work/frames/ghost.json" 2>&1) || fail "init: $said"
case "$said" in *"it bakes as written"*) echo "init on the frames: $(head -1 <<< "$said")" ;; *) fail "init says: $said" ;; esac

# Refusals: one line, status 1 (the input) or 2 (the command line), nothing written.
refuse() {
  local status=$1 expect=$2
  shift 2
  local out rc=0
  out=$("$bake" import "$@" -o "$work/refused" 2>&1) || rc=$?
  [ "$rc" = "$status" ] || fail "import $*: status $rc, not $status: $out"
  [ "$(wc -l <<< "$out")" = 1 ] || fail "import $*: not one line: $out"
  case "$out" in *"$expect"*) ;; *) fail "import $*: says '$out', not '$expect'" ;; esac
  [ ! -e "$work/refused" ] || fail "import $*: wrote $work/refused"
}
refuse 1 "ghost sheet.png: a sheet of $((3 * w)) x $((2 * h)) pixels does not divide into 5 x 2 cells" \
  "$work/ghost sheet.png" --frames 5x2
refuse 1 "does not divide into cells of 100 x $h pixels" "$work/ghost sheet.png" --cell "100x$h"
refuse 2 "a sprite sheet is cut by --frames COLUMNSxROWS or --cell WIDTHxHEIGHT" "$work/ghost sheet.png"
refuse 2 "--frames takes AxB, two whole numbers in 1..16384 (3by2)" "$work/ghost sheet.png" --frames 3by2
refuse 2 "--frames and --cell cut a sheet two ways" "$work/ghost sheet.png" --frames 3x2 --cell "${w}x${h}"
png 'g.write_png(sys.argv[1], 4, 2, bytes(32))' "$work/empty.png"
refuse 1 "empty.png: every cell of the sheet is empty" "$work/empty.png" --frames 2x1
printf 'not a png' > "$work/text.png"
refuse 1 "text.png: cannot read PNG" "$work/text.png" --frames 1x1

[ "$failures" = 0 ] || { echo "$failures failure(s)"; exit 1; }
echo "import_sheet: every check passed"
