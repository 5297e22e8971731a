#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# docs/bake.md's table of compact rigs, generated from this build's test rigs
# (build/<preset>/rigs: NAME.pmrig exact, NAME.compact.pmrig compact), their
# drawings, what the bake measured (QINF) and load times measured now by
# `posemorph-bake info`. Usage: scripts/compact-table.sh [build folder]
set -euo pipefail
build=${1:-build/release}
bake=$build/bin/posemorph-bake
field() { sed -n "$1" | head -1; }
echo "| sample | exact bytes | compact bytes | ratio | drawings (PNG bytes) | max vertex error (measured by the bake) | load exact | load compact | gzip -9 / zstd -19 of compact |"
echo "|---|---|---|---|---|---|---|---|---|"
for name in pip sprout snake gingerbread worm-line; do
  exact=$build/rigs/$name.pmrig compact=$build/rigs/$name.compact.pmrig
  eb=$(stat -c %s "$exact") cb=$(stat -c %s "$compact")
  drawings="-"
  if ls "$build"/assets/$name/*.png >/dev/null 2>&1; then drawings=$(cat "$build"/assets/$name/*.png | wc -c); fi
  err=$("$bake" info "$compact" | field 's/.*measured max \([0-9.e-]*\) px.*/\1/p')
  le=$("$bake" info "$exact" | field 's/.*load \([0-9.]*\) us.*/\1/p')
  lc=$("$bake" info "$compact" | field 's/.*load \([0-9.]*\) us.*/\1/p')
  gz=$(gzip -9 -c "$compact" | wc -c) zs=$(zstd -19 -q -c "$compact" | wc -c)
  printf "| %s | %d | %d | %.1fx | %s | %.4f px | %s us | %s us | %d / %d |\n" "$name" "$eb" "$cb" "$(echo "$eb / $cb" | bc -l)" "$drawings" "$err" "$le" "$lc" "$gz" "$zs"
done
