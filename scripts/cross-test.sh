#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the runtime and its own tests (tests/runtime/) for the other targets
# and runs them, against the rigs and frame hashes of the native release
# build (run scripts/test.sh, or build the release preset, first):
#   aarch64 Linux  g++-aarch64-linux-gnu, run under qemu-aarch64
#   Windows x64    mingw-w64 (POSIX threads), run under wine64
#   WebAssembly    Emscripten with SIMD128, run under node
# Usage: scripts/cross-test.sh [aarch64|windows|wasm ...]   (default: all three)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
rigs=$root/build/release/rigs
[ -f "$rigs/snake.pmrig" ] || { echo "cross-test: no $rigs/snake.pmrig: build the release preset first" >&2; exit 1; }
jobs=$(nproc)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(aarch64 windows wasm)

common=(-DPOSEMORPH_RUNTIME_ONLY=ON -DCMAKE_BUILD_TYPE=Release -DPOSEMORPH_TEST_RIG_FOLDER="$rigs" -DPOSEMORPH_WERROR=ON)
for target in "${targets[@]}"; do
  echo "== $target"
  dir=build/cross-$target
  case $target in
    aarch64)
      cmake -S . -B "$dir" --toolchain cmake/toolchains/aarch64-linux-gnu.cmake "${common[@]}" >/dev/null
      ;;
    windows)
      # wine keeps its prefix in the build folder, so a fresh machine needs nothing in $HOME.
      export WINEPREFIX=$root/$dir/wineprefix WINEDEBUG=-all
      cmake -S . -B "$dir" --toolchain cmake/toolchains/x86_64-w64-mingw32.cmake "${common[@]}" >/dev/null
      ;;
    wasm)
      # Debian's Emscripten needs acorn from Debian's node modules, and Node 20's
      # global fetch breaks its loader (../shared notes, docs/runtime.md "Targets").
      export NODE_PATH=/usr/share/nodejs
      emcmake cmake -S . -B "$dir" "${common[@]}" \
        "-DCMAKE_CROSSCOMPILING_EMULATOR=$(command -v node);--no-experimental-fetch" >/dev/null
      ;;
    *) echo "cross-test: unknown target $target (aarch64, windows, wasm)" >&2; exit 2 ;;
  esac
  cmake --build "$dir" -j"$jobs" -- --no-print-directory >/dev/null
  ctest --test-dir "$dir" --output-on-failure
done
