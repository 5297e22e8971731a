#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The kernel paths against each other on this CPU: every path this build and
# CPU run, forced in turn, in one process with repetitions interleaved (the
# docs/runtime.md's "Kernel paths" table). Usage: scripts/bench-paths.sh [REPETITIONS]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target posemorph-bench >/dev/null
out=build/release/bench-paths.json
build/release/bin/posemorph-bench --benchmark_filter='BM_Path' --benchmark_repetitions="${1:-5}" \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
  --benchmark_out="$out" --benchmark_out_format=json >/dev/null
python3 scripts/bench_table.py "$out" --paths-only
