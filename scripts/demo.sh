#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build, bake the bundled
# snake and write a contact sheet of its poses across pose space.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" >/dev/null
mkdir -p out
bin=build/release/bin
$bin/posemorph-bake assets/snake/snake.json -o out/snake.pmrig
$bin/posemorph-bake info out/snake.pmrig
$bin/posemorph-bake sheet out/snake.pmrig -o out/snake-sheet.svg
$bin/posemorph-bake eval out/snake.pmrig --path slither --frames 16 -o out/snake-slither.svg
# A rig whose poses are made by dragging handles on one drawn mesh.
$bin/posemorph-bake assets/gingerbread/gingerbread.json -o out/gingerbread.pmrig
$bin/posemorph-bake sheet out/gingerbread.pmrig -o out/gingerbread-sheet.svg
if command -v rsvg-convert >/dev/null; then
  for sheet in snake-sheet gingerbread-sheet; do
    rsvg-convert out/$sheet.svg -o out/$sheet.png
    echo "wrote out/$sheet.png"
  done
fi
