#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Writes the layered-file fixtures of tests/data/import/ with third-party
# writers, so that the readers (bake/src/import/) are tested on files real
# tools make, not on files written by the code that reads them:
#   pell/POSE.psd        GIMP 2.10 (script-fu, batch): Pell's four poses, one
#                        file each, its seven parts as layers cropped to what
#                        they draw (so each has an offset), and a hidden layer
#   pell/pell.ora        Krita 5 (command-line export) of a GIMP file whose
#                        four top-level groups are the poses
#   pell/body.ora        the same without the face (Pell with a face's body
#   pell/face.ora        channel), and its face channel: a group per
#                        expression holding the eyes and the mouth
#   features.psd         GIMP: a translucent group of two offset layers, a
#                        hidden layer, a multiply layer, a layer at 25%
#   features.ora         Krita's export of features.psd
# The Pell drawings come from a build (cmake --build build/release rasterises
# assets/pell/*.svg, one PNG per part and pose). Needs gimp, krita and xvfb-run
# (Debian: apt-get install gimp krita xvfb xauth); not run by CI, whose tests
# read the committed files.
#   scripts/make-import-fixtures.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
pell=$build/assets/pell
for tool in gimp-console krita xvfb-run; do
  command -v $tool > /dev/null || { echo "make-import-fixtures: needs $tool (apt-get install gimp krita xvfb xauth)"; exit 1; }
done
[ -f "$pell/rest-body.png" ] || { echo "make-import-fixtures: no $pell/rest-body.png: build first"; exit 1; }
out=tests/data/import
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out/pell"
poses=(rest wave cross lean)
# Top first, as the layers panel lists them: the face over the head over the
# arms and body.
parts=(mouth eye-right eye-left head arm-right arm-left body)

gimp_batch() { gimp-console -i -d -f -b "$1" -b '(gimp-quit 0)' > "$work/gimp.log" 2>&1 || { cat "$work/gimp.log"; exit 1; }; }
krita_export() { xvfb-run -a krita "$1" --export --export-filename "$2" > "$work/krita.log" 2>&1 || { cat "$work/krita.log"; exit 1; }; }

# Script-fu: (bottom img parent) is the position below everything in PARENT
# (0: the image's top level; an explicit position, since -1 would insert
# into the active layer's group); add-layer adds a PNG there as a layer
# named NAME, cropped to what it draws.
add_layer='(define (bottom img parent)
  (if (= parent 0) (car (gimp-image-get-layers img)) (car (gimp-item-get-children parent))))
(define (add-layer img parent file name)
  (let ((layer (car (gimp-file-load-layer RUN-NONINTERACTIVE img file))))
    (gimp-image-insert-layer img layer parent (bottom img parent))
    (gimp-item-set-name layer name)
    (plug-in-autocrop-layer RUN-NONINTERACTIVE img layer)
    layer))'

# One PSD per pose.
for pose in "${poses[@]}"; do
  body='(let* ((img (car (gimp-image-new 256 256 RGB))))'
  for part in "${parts[@]}"; do
    body+=" (add-layer img 0 \"$pell/$pose-$part.png\" \"$part\")"
  done
  # A hidden sketch layer: left out by the import, with a note.
  body+=" (let ((sketch (car (gimp-layer-new img 40 30 RGBA-IMAGE \"sketch\" 100 LAYER-MODE-NORMAL))))
      (gimp-image-insert-layer img sketch 0 0) (gimp-layer-set-offsets sketch 10 12)
      (gimp-context-set-foreground '(200 40 40)) (gimp-drawable-fill sketch FILL-FOREGROUND)
      (gimp-item-set-visible sketch FALSE))"
  body+=" (file-psd-save RUN-NONINTERACTIVE img (car (gimp-image-get-active-layer img)) \"$out/pell/$pose.psd\" \"$pose.psd\" 1 0)"
  body+=' (gimp-image-delete img))'
  gimp_batch "$add_layer $body"
done

# One file whose top-level groups are the poses: GIMP writes it as PSD,
# Krita turns that into OpenRaster.
body='(let* ((img (car (gimp-image-new 256 256 RGB))))'
for pose in "${poses[@]}"; do
  body+=" (let ((group (car (gimp-layer-group-new img))))
      (gimp-image-insert-layer img group 0 (bottom img 0))
      (gimp-item-set-name group \"$pose\")"
  for part in "${parts[@]}"; do body+=" (add-layer img group \"$pell/$pose-$part.png\" \"$part\")"; done
  body+=")"
done
body+=" (file-psd-save RUN-NONINTERACTIVE img (car (gimp-image-get-active-layer img)) \"$work/pell-poses.psd\" \"pell-poses.psd\" 1 0)"
body+=' (gimp-image-delete img))'
gimp_batch "$add_layer $body"
krita_export "$work/pell-poses.psd" "$out/pell/pell.ora"
# Pell with a face as two channels (init --channels): body.ora, the four
# poses without the face, and face.ora, a group per expression holding the
# eyes and the mouth.
body='(let* ((img (car (gimp-image-new 256 256 RGB))))'
for pose in "${poses[@]}"; do
  body+=" (let ((group (car (gimp-layer-group-new img))))
      (gimp-image-insert-layer img group 0 (bottom img 0))
      (gimp-item-set-name group \"$pose\")"
  for part in head arm-right arm-left body; do body+=" (add-layer img group \"$pell/$pose-$part.png\" \"$part\")"; done
  body+=")"
done
body+=" (file-psd-save RUN-NONINTERACTIVE img (car (gimp-image-get-active-layer img)) \"$work/body.psd\" \"body.psd\" 1 0)"
body+=' (gimp-image-delete img))'
gimp_batch "$add_layer $body"
krita_export "$work/body.psd" "$out/pell/body.ora"
body='(let* ((img (car (gimp-image-new 256 256 RGB))))'
for face in calm joy surprise sleepy; do
  body+=" (let ((group (car (gimp-layer-group-new img))))
      (gimp-image-insert-layer img group 0 (bottom img 0))
      (gimp-item-set-name group \"$face\")"
  for part in mouth eye-right eye-left; do body+=" (add-layer img group \"$pell/face-$face-$part.png\" \"$part\")"; done
  body+=")"
done
body+=" (file-psd-save RUN-NONINTERACTIVE img (car (gimp-image-get-active-layer img)) \"$work/face.psd\" \"face.psd\" 1 0)"
body+=' (gimp-image-delete img))'
gimp_batch "$add_layer $body"
krita_export "$work/face.psd" "$out/pell/face.ora"

# features: a 64 x 48 canvas, top first:
#   half    layer at opacity 25%, white 8 x 8 at (50, 30)
#   mul     layer in multiply mode, green 6 x 6 at (2, 40)
#   hidden  hidden layer, black 64 x 48 at (0, 0)
#   g       group at opacity 50% holding
#     a       red 20 x 10 at (5, 6)
#     b       blue 10 x 20 at (15, 2)  (below a: a covers it where they overlap)
#   base    grey (128) 4 x 4 at (-2, -2), partly off the canvas
solid='(define (solid img parent name w h x y rgb mode opacity)
  (let ((layer (car (gimp-layer-new img w h RGBA-IMAGE name opacity mode))))
    (gimp-image-insert-layer img layer parent (bottom img parent))
    (gimp-layer-set-offsets layer x y)
    (gimp-context-set-foreground rgb) (gimp-drawable-fill layer FILL-FOREGROUND)
    layer))'
gimp_batch "$add_layer $solid"' (let* ((img (car (gimp-image-new 64 48 RGB))))
  (solid img 0 "half" 8 8 50 30 (quote (255 255 255)) LAYER-MODE-NORMAL 25)
  (solid img 0 "mul" 6 6 2 40 (quote (0 255 0)) LAYER-MODE-MULTIPLY 100)
  (gimp-item-set-visible (solid img 0 "hidden" 64 48 0 0 (quote (0 0 0)) LAYER-MODE-NORMAL 100) FALSE)
  (let ((g (car (gimp-layer-group-new img))))
    (gimp-image-insert-layer img g 0 (bottom img 0))
    (gimp-item-set-name g "g") (gimp-layer-set-opacity g 50)
    (solid img g "a" 20 10 5 6 (quote (255 0 0)) LAYER-MODE-NORMAL 100)
    (solid img g "b" 10 20 15 2 (quote (0 0 255)) LAYER-MODE-NORMAL 100))
  (solid img 0 "base" 4 4 -2 -2 (quote (128 128 128)) LAYER-MODE-NORMAL 100)
  (file-psd-save RUN-NONINTERACTIVE img (car (gimp-image-get-active-layer img)) "'"$out/features.psd"'" "features.psd" 1 0)
  (gimp-image-delete img))'
krita_export "$out/features.psd" "$work/features.ora"
cp "$work/features.ora" "$out/features.ora"
echo "make-import-fixtures: wrote $(cd "$out" && find . -name '*.psd' -o -name '*.ora' | sort | tr '\n' ' ')"
ls -l "$out" "$out/pell"
