// SPDX-License-Identifier: MIT
// The wasm_simd path; its compiler flags are set in runtime/CMakeLists.txt.
// SIMD128 holds 2 doubles, but a vector here is 4 (the compiler splits each
// operation into two v128 ones): two independent chains per operation keep
// the engine's pipelines busier, 5-15% less time per crowd in Chromium
// (integrations/web/bench, 200 Pips or Pells) than 2 lanes. Lanes never mix,
// so the bits are those of every other path.
#define POSEMORPH_KERNEL_WIDTH 4
#define POSEMORPH_KERNEL_NAMESPACE wasm_simd
#define POSEMORPH_KERNEL_ISA kWasmSimd
#include "frame_kernels.h"
