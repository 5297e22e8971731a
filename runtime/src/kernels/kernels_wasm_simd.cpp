// SPDX-License-Identifier: MIT
// The wasm_simd path (2 doubles per vector); its compiler flags are set in runtime/CMakeLists.txt.
#define POSEMORPH_KERNEL_WIDTH 2
#define POSEMORPH_KERNEL_NAMESPACE wasm_simd
#define POSEMORPH_KERNEL_ISA kWasmSimd
#include "frame_kernels.h"
