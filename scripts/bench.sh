#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the benchmark suite and prints medians and ratios. All benchmarks run
# in one process with their repetitions randomly interleaved, so ratios hold
# on a noisy machine even when absolute times drift.
# Usage: scripts/bench.sh [REPETITIONS]   (default 7; needs python3 for the table)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" >/dev/null
out=build/release/bench.json
build/release/bin/posemorph-bench --benchmark_repetitions="${1:-7}" --benchmark_enable_random_interleaving=true \
  --benchmark_report_aggregates_only=true --benchmark_min_time=0.2 \
  --benchmark_out="$out" --benchmark_out_format=json >/dev/null
python3 scripts/bench_table.py "$out"
