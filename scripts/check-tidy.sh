#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs clang-tidy 14 with .clang-tidy's checks over every source file of the
# runtime, the bake and the viewer that a build compiles (its
# compile_commands.json; default build/release). Any finding fails.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
tidy=$(command -v clang-tidy-14 || command -v clang-tidy || true)
[ -n "$tidy" ] || { echo "check-tidy: clang-tidy not found (scripts/setup.sh installs clang-tidy-14)" >&2; exit 1; }
[ -f "$build/compile_commands.json" ] || { echo "check-tidy: $build/compile_commands.json not found: build first" >&2; exit 1; }
mapfile -t files < <(python3 - "$build/compile_commands.json" <<'PY'
import json, os, subprocess, sys
compiled = {os.path.realpath(e["file"]) for e in json.load(open(sys.argv[1]))}
tracked = subprocess.run(["git", "ls-files", "runtime/src/*.cpp", "bake/*.cpp", "viewer/*.cpp"],
                         capture_output=True, text=True, check=True).stdout.split()
print("\n".join(f for f in tracked if os.path.realpath(f) in compiled))
PY
)
log=$(mktemp)
jobs=$(nproc 2>/dev/null || echo 2)
if ! printf '%s\n' "${files[@]}" | xargs -P "$jobs" -n 4 "$tidy" -p "$build" --quiet >"$log" 2>&1; then
  grep -E "(warning|error):" "$log" >&2 || cat "$log" >&2
  rm -f "$log"
  echo "check-tidy: findings above (.clang-tidy lists the checks)" >&2
  exit 1
fi
rm -f "$log"
echo "check-tidy: ${#files[@]} files pass .clang-tidy's checks"
