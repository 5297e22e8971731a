#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start, command 1: install what is missing, build, bake the drawn
# character Pip from its five drawings (N-way mapping: outlines, matching,
# simplification, compatible triangulation) and write a contact sheet of its
# poses across pose space; then Pell, the layered sample (seven parts glued
# in one solve, drawn in order); then the other samples.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" >/dev/null
mkdir -p out
bin=build/release/bin
drawn=build/release/assets   # the SVG drawings of assets/pip, pell and sprout, rasterised by the build
$bin/posemorph-bake $drawn/pip/pip.json -o out/pip.pmrig
$bin/posemorph-bake info out/pip.pmrig
$bin/posemorph-bake sheet out/pip.pmrig -o out/pip-sheet.svg
$bin/posemorph-bake sheet out/pip.pmrig --textured --columns 5 --rows 3 -o out/pip-sheet-textured.png
$bin/posemorph-bake eval out/pip.pmrig --path hello --frames 16 -o out/pip-hello.svg
# Pell: one SVG per pose, each part a layer; the sheet draws the parts back to front.
$bin/posemorph-bake $drawn/pell/pell.json -o out/pell.pmrig
$bin/posemorph-bake sheet out/pell.pmrig --textured --columns 5 --rows 3 -o out/pell-sheet-textured.png
# Pell with two control channels: "body" drives the body, arms and head, "face" the eyes and the mouth.
$bin/posemorph-bake $drawn/pell/pell-face.json -o out/pell-face.pmrig
$bin/posemorph-bake sheet out/pell-face.pmrig --textured --columns 5 --rows 3 -o out/pell-face-sheet-body.png
$bin/posemorph-bake sheet out/pell-face.pmrig --textured --channel face --columns 5 --rows 3 -o out/pell-face-sheet-face.png
$bin/posemorph-bake $drawn/sprout/sprout.json -o out/sprout.pmrig
$bin/posemorph-bake sheet out/sprout.pmrig -o out/sprout-sheet.svg
# Procedural samples: a snake given as meshes, and a figure whose poses are made by dragging handles.
$bin/posemorph-bake assets/snake/snake.json -o out/snake.pmrig
$bin/posemorph-bake sheet out/snake.pmrig -o out/snake-sheet.svg
$bin/posemorph-bake eval out/snake.pmrig --path slither --frames 16 -o out/snake-slither.svg
$bin/posemorph-bake assets/gingerbread/gingerbread.json -o out/gingerbread.pmrig
$bin/posemorph-bake sheet out/gingerbread.pmrig -o out/gingerbread-sheet.svg
if command -v rsvg-convert >/dev/null; then
  for sheet in pip-sheet sprout-sheet snake-sheet gingerbread-sheet; do
    rsvg-convert out/$sheet.svg -o out/$sheet.png
    echo "wrote out/$sheet.png"
  done
fi
# The viewer: a window when there is a display, otherwise frames rendered headless.
view=$bin/posemorph-view
if [ ! -x $view ]; then
  echo "posemorph-view was not built (see the cmake warnings); skipping the viewer"
elif [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  echo "opening the viewer on out/pip.pmrig, then on out/pell.pmrig, then on out/pell-face.pmrig, twice (close each window to go on)"
  $view out/pip.pmrig --description $drawn/pip/pip.json
  $view out/pell.pmrig
  $view out/pell-face.pmrig --channel face=chatter
  echo "and on out/pell-face.pmrig driven by its state machine (the panel's inputs and log)"
  $view out/pell-face.pmrig --inputs "0.4:wave;1:talking;3:!talking"
else
  mkdir -p out/frames
  $view out/pip.pmrig --headless --size 480x480 --path hello --frames 24 -o out/frames/pip-hello.png
  $view out/pip.pmrig --headless --size 1280x720 --path hello --crowd 100 -o out/frames/pip-crowd.png
  $view out/pip.pmrig --headless --size 960x480 --at 1.4,0.4 --compare -o out/frames/pip-rigid-vs-linear.png
  $view out/pell.pmrig --headless --size 480x480 --path greet --frames 24 -o out/frames/pell-greet.png
  $view out/pell.pmrig --headless --size 1024x256 --bases -o out/frames/pell-bases.png
  $view out/pell-face.pmrig --headless --size 1280x720 --crowd 12 --path greet --channel face=chatter --frames 24 \
    -o out/frames/pell-face-crowd.png
  $view out/sprout.pmrig --headless --size 480x480 --path breeze --frames 24 -o out/frames/sprout-breeze.png
  # Pell with a face driven by its state machine: its log of states and events, 60 frames at 10 per second.
  $view out/pell-face.pmrig --headless --size 480x480 --fps 10 --frames 60 -o out/frames/pell-face-states.png \
    --inputs "0.4:wave;1:talking;3:!talking;3.2:ghost;4.6:!ghost;4.6:vanish"
fi
