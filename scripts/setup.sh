#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian 12 packages posemorph needs. Idempotent: packages that
# are already installed are skipped, and apt is not touched when none is missing.
set -euo pipefail

packages=(
  cmake g++ make            # build
  libeigen3-dev             # bake: sparse Cholesky (LDL^T), AMD ordering, KKT solve
  nlohmann-json3-dev        # bake: rig description (JSON) reader
  doctest-dev               # tests
  libbenchmark-dev          # bench: the benchmark suite
  libsuitesparse-dev        # bench: CHOLMOD, the solver the runtime is measured against
  libpng-dev                # bake: reading drawings (PNG alpha)
  libtinyxml2-dev           # bake: reading SVG outlines (XML), OpenRaster's stack.xml
  libzip-dev                # bake: reading OpenRaster drawings (a zip of PNG layers)
  librsvg2-bin              # build: drawn samples SVG -> PNG; demo: contact sheets (rsvg-convert)
  libvulkan-dev             # viewer: Vulkan headers and loader
  glslang-tools             # viewer: GLSL -> SPIR-V at build time (glslangValidator)
  mesa-vulkan-drivers       # viewer: lavapipe, Vulkan on the CPU
  vulkan-validationlayers   # viewer tests: the Khronos validation layer
  libglfw3-dev              # viewer: the window
  libglm-dev                # viewer: the structs shared with the shaders, the camera (GLM)
  libsdl2-dev libgl1-mesa-dri   # examples/sdl2-opengl: SDL2, and Mesa's OpenGL (llvmpipe) under Xvfb
  chromium python3          # examples/web: headless Chromium (WebGL2 on SwiftShader), a static server on 127.0.0.1
  libxrandr2 libxcursor1 libxinerama1 libxi6   # viewer: X11 libraries GLFW loads at run time
  libimgui-dev              # viewer: the panel (Dear ImGui with its GLFW and Vulkan backends)
  pkg-config                # viewer build: finds Dear ImGui (imgui.pc)
  xvfb xauth                # viewer tests: a display for the window smoke test (xvfb-run needs xauth)
  clang libclang-rt-14-dev  # tests: the Clang build, and ThreadSanitizer's runtime
  clang-format-14 clang-tidy-14   # CI: the layout check (.clang-format) and the static checks (.clang-tidy)
  g++-aarch64-linux-gnu qemu-user   # tests: the runtime for aarch64, run under qemu
  g++-mingw-w64-x86-64 wine64       # tests: the runtime for Windows, run under wine
  emscripten node-acorn nodejs      # tests: the runtime for WebAssembly, run under node (emcc needs acorn)
  mono-mcs mono-runtime             # integrations/csharp: the C# binding, compiled with mcs, run with mono
  love                              # integrations/love: LÖVE 11 (LuaJIT), the FFI module and its example game
)
# integrations/web packs an npm package and its test installs it: npm comes
# with some builds of nodejs (NodeSource's), else from Debian's npm package.
command -v npm > /dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
