#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Animator's update beside the frame it feeds (bench/animator_bench.cpp):
# per character, the update with and without behaviours and crossfades, and
# the update's share of update + frame measured in the same iterations
# (docs/animation.md's "Cost" table; medians of the repetitions, on this
# machine). Usage: scripts/bench-animator.sh [REPETITIONS]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target posemorph-bench >/dev/null
out=build/release/bench-animator.json
build/release/bin/posemorph-bench --benchmark_filter='BM_Animat' --benchmark_repetitions="${1:-5}" \
  --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true \
  --benchmark_out="$out" --benchmark_out_format=json >/dev/null
python3 - "$out" <<'PY'
import json, sys
runs = {b["run_name"]: b for b in json.load(open(sys.argv[1]))["benchmarks"] if b.get("aggregate_name") == "median"}
def update(count, full):
    b = runs[f"BM_AnimatorUpdate/{count}/{full}"]
    return b["cpu_time"] / count  # microseconds per character (the benchmark's unit)
print("| characters | update alone, us per character (paths only) | update, us per character (spring, breath, blink, look-at, crossfades) | in update + frame: update | frame | update's share |")
print("|---|---|---|---|---|---|")
for count in (1, 1000):
    b = runs[f"BM_AnimatedCrowd/{count}"]
    print(f"| {count} | {update(count, 0):.2f} | {update(count, 1):.2f} | {b['update_us_per_character']:.2f} us "
          f"| {b['frame_us_per_character']:.2f} us | {100 * b['update_share']:.1f} % |")
PY
