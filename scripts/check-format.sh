#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Checks every tracked C and C++ file against .clang-format (clang-format 14,
# Debian 12's): prints the files that differ and exits 1. --fix rewrites them.
set -euo pipefail
cd "$(dirname "$0")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
[ -n "$format" ] || { echo "check-format: clang-format not found (scripts/setup.sh installs clang-format-14)" >&2; exit 1; }
mapfile -t files < <(git ls-files '*.c' '*.cpp' '*.h')
if [ "${1:-}" = "--fix" ]; then
  "$format" -i "${files[@]}"
  exit 0
fi
if ! report=$("$format" --dry-run -Werror "${files[@]}" 2>&1); then
  bad=$(grep -oE '^[^:]+:[0-9]+:[0-9]+: error' <<<"$report" | cut -d: -f1 | sort -u)
  echo "check-format: $(wc -l <<<"$bad") files differ from .clang-format (scripts/check-format.sh --fix rewrites them):" >&2
  sed 's/^/  /' <<<"$bad" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files follow .clang-format"
