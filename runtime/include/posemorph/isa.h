// SPDX-License-Identifier: MIT
// The code paths the per-frame kernels are compiled for. Every path performs
// the same IEEE operations in the same order (no FMA contraction, no
// fast-math), so every path gives the same bits; they differ only in speed.
#pragma once
#include "posemorph/export.h"

namespace posemorph {

enum class Isa : int {
  kAuto = 0,      // the fastest path this CPU runs (or POSEMORPH_ISA, if set)
  kScalar = 1,    // portable C++: one double at a time (any compiler, any CPU)
  kSse2 = 2,      // x86-64 baseline: 2 lanes
  kAvx2 = 3,      // x86-64 with AVX2: 4 lanes
  kAvx512 = 4,    // x86-64 with AVX-512F: 8 lanes
  kNeon = 5,      // aarch64 Advanced SIMD: 2 lanes
  kWasmSimd = 6,  // WebAssembly SIMD128: 2 lanes
};

// "auto", "scalar", "sse2", "avx2", "avx512", "neon", "wasm-simd".
PM_API const char* IsaName(Isa isa);
// The path named `name` (as IsaName writes it); false for an unknown name.
PM_API bool ParseIsa(const char* name, Isa* out);
// True when this build contains the path and this CPU can run it.
PM_API bool IsaAvailable(Isa isa);
// The path kAuto resolves to, ignoring POSEMORPH_ISA.
PM_API Isa BestIsa();

}  // namespace posemorph
