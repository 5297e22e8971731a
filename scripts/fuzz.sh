#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The libFuzzer harnesses (tests/fuzz/): builds them (the fuzz preset: Clang,
# AddressSanitizer + UBSan) and runs each for SECONDS (default 60), as many at
# once as there are cores. Any finding fails: a crash, a sanitizer report, an
# input taking more than 10 s, more than 2 GB of memory.
#
#   scripts/fuzz.sh [SECONDS] [HARNESS ...]   harnesses: rig_load description svg_outline png_outline
#                                             layered_image
#
# Each starts from its committed seeds (tests/fuzz/corpus/NAME, read only) and
# the inputs earlier runs found (build/fuzz/corpus/NAME, grows from run to
# run); findings are written to build/fuzz/findings/NAME/, logs to
# build/fuzz/NAME.log. Reproduce one: build/fuzz/bin/posemorph-fuzz-NAME FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
[ $# -gt 0 ] && shift
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(rig_load description svg_outline png_outline layered_image)
jobs=$(nproc)

cmake --preset fuzz -DPOSEMORPH_WERROR=ON >/dev/null
cmake --build --preset fuzz -j"$jobs" --target "${harnesses[@]/#/posemorph-fuzz-}"

max_len() { case $1 in rig_load) echo 65536 ;; *) echo 16384 ;; esac; }
run() {
  local h=$1 work=build/fuzz/corpus/$1 findings=build/fuzz/findings/$1
  mkdir -p "$work" "$findings"
  local dict=()
  [ -f tests/fuzz/$h.dict ] && dict=(-dict=tests/fuzz/$h.dict)
  build/fuzz/bin/posemorph-fuzz-$h "$work" tests/fuzz/corpus/$h "${dict[@]}" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len="$(max_len "$h")" -artifact_prefix="$findings/" -print_final_stats=1 \
    >build/fuzz/$h.log 2>&1
}

declare -A pid
for h in "${harnesses[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run "$h" &
  pid[$h]=$!
done
failed=0
for h in "${harnesses[@]}"; do
  status=0
  wait "${pid[$h]}" || status=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' build/fuzz/$h.log | grep -o '[0-9]*$' || echo "?")
  corpus=$(ls build/fuzz/corpus/$h | wc -l)
  if [ "$status" -eq 0 ]; then
    echo "fuzz $h: ${seconds} s, $runs executions, no finding ($corpus inputs found so far in build/fuzz/corpus/$h)"
  else
    echo "fuzz $h: FINDING (exit status $status) after $runs executions; build/fuzz/$h.log ends:"
    tail -40 build/fuzz/$h.log
    ls build/fuzz/findings/$h
    failed=1
  fi
done
exit $failed
