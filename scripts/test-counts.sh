#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/testing.md's table of test builds, with each build's test count as ctest
# lists it (`ctest -N`) in build/<preset>. Usage: scripts/test-counts.sh
# (after scripts/test.sh, or after configuring and building the presets).
set -euo pipefail
cd "$(dirname "$0")/.."
count() {
  local dir=build/$1
  shift
  [ -f "$dir/CTestTestfile.cmake" ] || { echo "scripts/test-counts.sh: $dir is not built" >&2; exit 1; }
  ctest --test-dir "$dir" -N "$@" | sed -n 's/^Total Tests: //p'
}
release=$(count release) isa=$(count release -L runtime) clang=$(count clang-runtime)
integration=$(count release -L integration)
tsan=$(count tsan)
# The debug preset's filter (CMakePresets.json) leaves seven tests out: count as it runs.
debug=$(ctest --preset debug -N | sed -n 's/^Total Tests: //p')
echo "| build | preset | tests | what |"
echo "|---|---|---|---|"
echo "| GCC 12, -O3 | \`release\` | $release | every test (examples included); then the runtime suite again with \`POSEMORPH_ISA=avx2\`, \`sse2\` and \`scalar\` ($isa each: the kernel path changes only the runtime's frame arithmetic, and the suite checks its bits on each path against the committed frame hashes; the default run takes AVX-512 where the CPU has it) |"
echo "| Clang 14, -O3 | \`clang-runtime\` | $clang | the runtime suite, built alone and reading the rigs release baked, on the same four paths: the same bits from the other compiler (the frame hashes). The \`clang\` preset builds everything with Clang for local use; CI builds the bake and every test with Clang once, in \`debug\`, and the viewer in \`scripts/viewer-without-bake.sh\` |"
echo "| GCC 12, -O3, label \`integration\` | \`release\` | $integration of the $release | the engine integrations (integrations/): the C# binding under mono, the LÖVE module under Xvfb, the OpenGL renderer through the SDL2 example, the npm package in headless Chromium (installed with pixi.js and TypeScript from the registry, its types checked with tsc); frames bit for bit with the native runtime (the character digest), pictures against posemorph-view's, hostile rigs refused with the loader's own messages |"
echo "| Clang, ThreadSanitizer | \`tsan\` | $tsan | the runtime suite (threads splitting a crowd, batch = single) |"
echo "| Clang 14, AddressSanitizer + UBSan, -O1 | \`debug\` | $debug | the runtime, the bake, the tools and every test built with Clang (warnings as errors), the viewer left out (\`POSEMORPH_BUILD_VIEWER=OFF\`: the Vulkan loader and driver are not built with the sanitisers, so its tests run in release only); every test but allocation counting (the sanitiser owns malloc), the hostile-input corpus (its 1 GiB address-space limit leaves no room for the shadow memory) and seven that re-measure figures release checks: the three ghosting figures, the permutation roundoff, the drawn samples' mapping quality, the weights against a thin-plate spline and Pip's eye centres (the code they run is run under the sanitisers by the other tests); the test rigs are copied from release's build (\`POSEMORPH_TEST_RIGS_FROM\`), not baked again under the sanitisers |"
echo "| Clang, libFuzzer + ASan + UBSan | \`fuzz\` (\`scripts/fuzz.sh\`) | 5 harnesses | 40 s each: rig loader and frames, rig description, SVG outlines, PNG tracer, layered files (PSD, OpenRaster) (\"Hostile input and fuzzing\" below) |"
echo "| aarch64 (g++-aarch64-linux-gnu) under qemu-aarch64 | \`scripts/cross-test.sh\` | runtime suite | NEON and scalar paths |"
echo "| Windows x64 (mingw-w64) under wine64 | \`scripts/cross-test.sh\` | runtime suite | every x86-64 path the CPU runs |"
echo "| WebAssembly (Emscripten 3.1.6) under node | \`scripts/cross-test.sh\` | runtime suite | SIMD128 and scalar paths |"
echo "| consumers | \`scripts/consumer-test.sh\` | 6 programs | install + find_package, C99 + pkg-config, add_subdirectory without Eigen, FetchContent, shared library (its runtime suite, SONAME, exports) with both consumers: all compute the same frame |"
echo "| viewer without edit mode | \`scripts/viewer-without-bake.sh\` | 1 program | \`-DPOSEMORPH_VIEWER_EDIT=OFF\`, built with Clang (warnings as errors): no viewer source compiled with Eigen, nlohmann-json or tinyxml2, no bake in its link, its headless frame byte-identical to the release viewer's |"
echo "| pictures | \`scripts/docs-figures.sh\` | $(git ls-files 'docs/*.png' | wc -l) pictures | every picture under docs/ made again from the samples into a scratch folder; fails on a picture without a recipe or one a document shows that is not there |"
