#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/runtime.md's table of examples: lines of code per example (not blank, not
# only a comment) and, of those, lines of posemorph glue (lines that name a
# posemorph function, type or field: pm_*, posemorph::, the draw-list and
# rig accessors), then the same for each integration (integrations/: the
# binding or renderer, and its example; comments in C#, Lua, C++ and JavaScript alike).
set -euo pipefail
cd "$(dirname "$0")/.."
glue='pm_|posemorph|DrawList|Transform2D|CharacterBuffers|BlendedDrawing|LoadRig|SamplePath|PathView|PoseSpaceGrid|Quantize|PackPoint|DequantizePoint|drawLists|loadRig|\brig[.>]|\.drawings|\.positions|\.indices|\.transform|drawing_count|job\.'
count() { grep -hvE '^\s*(//|/\*|\*|#|<!--|--|$)' "$@" | wc -l; }
glue_count() { grep -hvE '^\s*(//|/\*|\*|#|<!--|--|$)' "$@" | grep -cE "$glue"; }
echo "| example | files | lines of code | of which posemorph glue |"
echo "|---|---|---|---|"
for e in c avatar-udp sdl2-opengl web; do
  case $e in
    c) files=(examples/c/play_path.c) ;;
    avatar-udp) files=(examples/avatar-udp/sender.cpp examples/avatar-udp/receiver.cpp examples/avatar-udp/wire.h) ;;
    sdl2-opengl) files=(examples/sdl2-opengl/main.cpp) ;;
    web) files=(examples/web/main.js examples/web/posemorph.js examples/web/bindings.c examples/web/index.html) ;;
  esac
  echo "| \`examples/$e\` | $(printf '%s ' "${files[@]##*/}")| $(count "${files[@]}") | $(glue_count "${files[@]}") |"
done
for i in opengl csharp love web; do
  case $i in
    opengl) files=(integrations/opengl/posemorph_gl.h integrations/opengl/posemorph_gl.cpp) ;;
    csharp) files=(integrations/csharp/Posemorph.cs integrations/csharp/example/Example.cs
            integrations/csharp/example/Picture.cs) ;;
    love) files=(integrations/love/posemorph.lua integrations/love/example/main.lua) ;;
    web) files=(integrations/web/src/posemorph_web.c integrations/web/posemorph.mjs integrations/web/pixi.mjs
               integrations/web/example/main.mjs) ;;
  esac
  echo "| \`integrations/$i\` | $(printf '%s ' "${files[@]#integrations/$i/}")| $(count "${files[@]}") | $(glue_count "${files[@]}") |"
done
