#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Stages the npm package (the ES modules, their types, the WebAssembly build,
# README and LICENSE) and packs it: OUT/posemorph-VERSION.tgz, which
# `npm install` accepts. The package's version must be the runtime's.
#   pack.sh WASM_DIR OUT
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
wasm=$1 out=$2
version=$(sed -n 's/.*"version": "\(.*\)".*/\1/p' "$here/package.json")
runtime=$(sed -n 's/^#define PM_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)$/\2/p' \
  "$here/../../runtime/include/posemorph/posemorph.h" | paste -sd.)
if [ "$version" != "$runtime" ]; then
  echo "pack.sh: integrations/web/package.json says version $version, the runtime is $runtime" >&2
  exit 1
fi
rm -rf "$out/package" && mkdir -p "$out/package"
cp "$here/package.json" "$here/posemorph.mjs" "$here/posemorph.d.mts" "$here/pixi.mjs" "$here/pixi.d.mts" \
   "$here/README.md" "$here/../../LICENSE" "$wasm/posemorph_wasm.mjs" "$wasm/posemorph_wasm.wasm" "$out/package/"
rm -f "$out"/posemorph-*.tgz
(cd "$out/package" && npm pack --silent --pack-destination "$out" > /dev/null)
echo "$out/posemorph-$version.tgz"
