#!/usr/bin/env bash
# Quick start, command 2: install what is missing, then build and run every
# test twice: optimised (release) and under AddressSanitizer + UBSan (debug).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs=$(nproc)
for preset in release debug; do
  echo "== $preset"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j"$jobs"
  ctest --preset "$preset" -j"$jobs"
done
