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
if command -v rsvg-convert >/dev/null; then
  rsvg-convert out/snake-sheet.svg -o out/snake-sheet.png
  echo "wrote out/snake-sheet.png"
fi
