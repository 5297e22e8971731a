#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Uses posemorph the ways a game would, after a native release build (it
# installs that build and reads the rigs it baked):
#   1. cmake --install, then a separate CMake project with find_package
#   2. a C99 program built with plain pkg-config --libs against the same install
#   3. a project that add_subdirectory()s the source tree with Eigen out of
#      reach (-DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON) and no build type, and
#      one that fetches the last commit with FetchContent
#   4. BUILD_SHARED_LIBS=ON: the runtime tests against the shared library,
#      its SONAME, what it exports, and the C and C++ consumers linked to it
# Each consumer evaluates the same frame of the snake; all must print the
# same hash. Prints the installed files and the library sizes.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
rig=$root/build/release/rigs/snake.pmrig
[ -f "$rig" ] || { echo "consumer-test: no $rig: build the release preset first" >&2; exit 1; }
work=$root/build/consumers
rm -rf "$work"
mkdir -p "$work"
jobs=$(nproc)
quiet() { "$@" >"$work/last.log" 2>&1 || { cat "$work/last.log"; exit 1; }; }
expect=""
check_frame() {  # check_frame NAME PROGRAM: run it on the snake, compare the hash
  local out
  out=$("$2" "$rig")
  echo "  $1: $out"
  local hash=${out##* }
  [ -z "$expect" ] && expect=$hash
  [ "$hash" = "$expect" ] || { echo "consumer-test: $1 computed frame $hash, expected $expect" >&2; exit 1; }
}

echo "== install (static runtime, bake, tools)"
quiet cmake --install build/release --prefix "$work/prefix"
(cd "$work/prefix" && find . -type f | sort | sed 's/^\./  /')

echo "== find_package consumer"
quiet cmake -S tests/consumers/find-package -B "$work/find-package" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release
quiet cmake --build "$work/find-package" -j"$jobs"
check_frame find_package "$work/find-package/frame"

echo "== C99 with plain pkg-config --libs (the static library names the C++ runtime in Libs)"
export PKG_CONFIG_PATH=$work/prefix/lib/pkgconfig
cc -std=c99 -Wall -Wextra -pedantic -Werror $(pkg-config --cflags posemorph-runtime) tests/consumers/c/frame.c \
  -o "$work/c-frame" $(pkg-config --libs posemorph-runtime)
check_frame "C99 (pkg-config)" "$work/c-frame"

echo "== add_subdirectory, Eigen disabled, no build type"
quiet cmake -S tests/consumers/subdirectory -B "$work/subdirectory" -DPOSEMORPH_SOURCE_DIR="$root" \
  -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON -DCMAKE_DISABLE_FIND_PACKAGE_doctest=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON
grep -q "the runtime is compiled with -O2 anyway" "$work/last.log" || { echo "consumer-test: no -O2 note without a build type" >&2; exit 1; }
quiet cmake --build "$work/subdirectory" -j"$jobs"
targets=$(cmake --build "$work/subdirectory" --target help | grep -c "posemorph" || true)
echo "  posemorph targets in the consumer's build: $targets (the runtime, nothing else)"
[ -f "$work/subdirectory/posemorph/runtime/libposemorph.a" ] || { echo "consumer-test: no runtime library built" >&2; exit 1; }
if find "$work/subdirectory" -name 'libposemorph_bake*' | grep -q .; then echo "consumer-test: the bake was built" >&2; exit 1; fi
check_frame add_subdirectory "$work/subdirectory/frame"

echo "== FetchContent from this repository's last commit"
quiet cmake -S tests/consumers/fetchcontent -B "$work/fetchcontent" -DPOSEMORPH_GIT="$root" \
  -DPOSEMORPH_GIT_TAG="$(git rev-parse HEAD)" -DCMAKE_BUILD_TYPE=Release -DCMAKE_DISABLE_FIND_PACKAGE_Eigen3=ON
quiet cmake --build "$work/fetchcontent" -j"$jobs"
check_frame FetchContent "$work/fetchcontent/frame"

echo "== shared library"
quiet cmake -S . -B "$work/shared" -DBUILD_SHARED_LIBS=ON -DPOSEMORPH_RUNTIME_ONLY=ON -DPOSEMORPH_BUILD_TESTS=ON \
  -DPOSEMORPH_INSTALL=ON -DCMAKE_BUILD_TYPE=Release -DPOSEMORPH_TEST_RIG_FOLDER="$root/build/release/rigs"
quiet cmake --build "$work/shared" -j"$jobs"
ctest --test-dir "$work/shared" --output-on-failure | grep "tests passed" | sed "s/^/  shared runtime tests: /"
quiet cmake --install "$work/shared" --prefix "$work/shared-prefix"
so=$(readlink -f "$work/shared-prefix/lib/libposemorph.so")
soname=$(readelf -d "$so" | sed -n 's/.*SONAME.*\[\(.*\)\]/\1/p')
[ "$soname" = libposemorph.so.0.5 ] || { echo "consumer-test: SONAME is '$soname'" >&2; exit 1; }
exported=$(nm -D --defined-only "$so" | awk '$2 ~ /[TW]/' | wc -l)
internal=$(nm -D --defined-only -C "$so" | grep -c "posemorph::detail" || true)
echo "  $so: SONAME $soname, $exported functions exported, $internal of them internal (detail)"
[ "$internal" -eq 0 ] || { echo "consumer-test: internal symbols exported" >&2; exit 1; }
quiet cmake -S tests/consumers/find-package -B "$work/find-package-shared" -DCMAKE_PREFIX_PATH="$work/shared-prefix" -DCMAKE_BUILD_TYPE=Release
quiet cmake --build "$work/find-package-shared" -j"$jobs"
check_frame "find_package (shared)" "$work/find-package-shared/frame"
PKG_CONFIG_PATH=$work/shared-prefix/lib/pkgconfig
cc -std=c99 -Wall -Wextra -pedantic -Werror $(PKG_CONFIG_PATH=$PKG_CONFIG_PATH pkg-config --cflags posemorph-runtime) \
  tests/consumers/c/frame.c -o "$work/c-frame-shared" $(PKG_CONFIG_PATH=$PKG_CONFIG_PATH pkg-config --libs posemorph-runtime) \
  -Wl,-rpath,"$work/shared-prefix/lib"
check_frame "C99 (shared)" "$work/c-frame-shared"

echo "== library sizes (bytes)"
strip_size() { cp "$1" "$work/stripped" && strip --strip-unneeded "$work/stripped" && stat -c %s "$work/stripped"; }
echo "  static libposemorph.a: $(stat -c %s "$work/prefix/lib/libposemorph.a"), stripped $(strip_size "$work/prefix/lib/libposemorph.a")"
echo "  shared $(basename "$so"): $(stat -c %s "$so"), stripped $(strip_size "$so")"
echo "consumer-test: every consumer computed frame $expect"
