#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quick start, command 2: install what is missing, then build and run every
# test: the full suite with GCC (release), then the runtime suite with Clang
# -O3 (clang-runtime: the same bits from the other compiler), each run again
# on every other kernel path this CPU runs (POSEMORPH_ISA = the fastest by
# default, then avx2, sse2, scalar); the bake and every test built with
# Clang under AddressSanitizer + UBSan (debug: the viewer left out), the
# runtime's threads under ThreadSanitizer (tsan), the libFuzzer harnesses
# for 40 s each (scripts/fuzz.sh; POSEMORPH_FUZZ_SECONDS changes it),
# the hostile-input corpus (a ctest test, tests/hostile/), the ways a game
# consumes the library (install + find_package, pkg-config from C,
# add_subdirectory without the bake's dependencies, a shared library:
# scripts/consumer-test.sh), posemorph-view without edit mode, which must
# link no bake, built with Clang (scripts/viewer-without-bake.sh), every picture of docs/
# made again by its recipe (scripts/docs-figures.sh, into a scratch
# folder), and the runtime's own tests built for aarch64 (qemu), Windows (wine) and
# WebAssembly (node): scripts/cross-test.sh.
# First the guard rails: the layout (scripts/check-format.sh), warnings as
# errors in every build, and clang-tidy (scripts/check-tidy.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc)
# Each step's banner says when it began (seconds since the start): where CI's time goes.
say() { echo "== [${SECONDS}s] $*"; }
scripts/check-format.sh  # the layout (.clang-format)
python3 scripts/docs-tables.py --check examples  # the documents' tables that depend only on the sources

# The x86-64 paths to force besides the default one. A path the CPU lacks
# would fail every load with a clear error; it is left out here instead.
forced=()
if [ "$(uname -m)" = x86_64 ]; then
  forced=(avx2 sse2 scalar)
  grep -qw avx2 /proc/cpuinfo || forced=(sse2 scalar)
fi

build() {
  say "$1: build"
  cmake --preset "$1" -DPOSEMORPH_WERROR=ON >/dev/null  # warnings fail CI
  cmake --build --preset "$1" -j"$jobs"
}

# Clang builds the bake and every test once, in the sanitized debug preset
# below, and the viewer in scripts/viewer-without-bake.sh; here it builds
# the runtime alone, optimised, whose
# bits must be GCC's (the frame hashes), reading the rigs release baked.
for preset in release clang-runtime; do
  build "$preset"
  if [ "$preset" = release ]; then
    say "clang-tidy (.clang-tidy) on the runtime, the bake and the viewer"
    scripts/check-tidy.sh build/release
  fi
  say "$preset: every test it built, default path"
  ctest --preset "$preset" -j"$jobs"
  for isa in "${forced[@]}"; do
    say "$preset: the runtime suite, POSEMORPH_ISA=$isa"
    # The kernel path changes only the runtime's per-frame arithmetic, and the
    # runtime suite checks on each path that its bits are the committed ones
    # (tests/goldens/frame-hashes.txt: single, batched and threaded frames of
    # every sample) and that every job keeps its contract; every other test's
    # frames are those bits, so it runs once per compiler.
    POSEMORPH_ISA=$isa ctest --preset "$preset" -j"$jobs" -L runtime
  done
done
say "pictures: scripts/docs-figures.sh into a scratch folder (every docs/ picture has a recipe)"
figures=$(mktemp -d)
scripts/docs-figures.sh "$figures" > /dev/null
rm -rf "$figures"
say "consumers (scripts/consumer-test.sh)"
scripts/consumer-test.sh
say "the viewer without edit mode links no bake (scripts/viewer-without-bake.sh)"
scripts/viewer-without-bake.sh
# Under AddressSanitizer the debug preset leaves out seven tests that
# re-measure figures of the drawn characters (CMakePresets.json: the
# ghosting figures, the permutation roundoff, the samples' mapping quality,
# the thin-plate weights, Pip's eye centres): the release run checks those
# figures, and the sanitized run still bakes, maps, aligns and measures
# through the other tests (about 80 s of the debug step).
for preset in tsan debug; do
  build "$preset"
  say "$preset: tests"
  ctest --preset "$preset" -j"$jobs"
done
say "fuzz: each libFuzzer harness for ${POSEMORPH_FUZZ_SECONDS:-40} s"
scripts/fuzz.sh "${POSEMORPH_FUZZ_SECONDS:-40}"
say "cross builds (scripts/cross-test.sh)"
scripts/cross-test.sh
say "done"
