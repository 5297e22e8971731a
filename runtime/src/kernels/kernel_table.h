// SPDX-License-Identifier: MIT
// The per-frame kernels of one instruction set, reached through a table
// chosen once when a rig loads (no ifunc, no target_clones: each path is its
// own translation unit built with its own flags; see runtime/CMakeLists.txt).
#pragma once
#include <cstddef>

#include "posemorph/isa.h"

namespace posemorph {
class Rig;
}  // namespace posemorph

namespace posemorph::detail {

struct SolveLayout;

// Characters evaluated together by a batch group, on any path: the workspace
// of MorphBatchJob is sized for this many lanes.
constexpr int kMaxLanes = 8;

struct KernelTable {
  Isa isa;
  int lanes;  // characters per batch group: doubles per vector on this path
  // One character (MorphJob, rigid): w, ws: N weights; work: 4V doubles;
  // x: 2V positions.
  void (*rigid)(const Rig& rig, const double* w, const double* ws, double* work, double* x);
  // `lanes` characters: W, WS: N x lanes weights (pose-major); x: 2V x lanes
  // positions out; y: 2(V-1) x lanes scratch. x and y aligned to 64 bytes.
  void (*group)(const Rig& rig, const double* W, const double* WS, double* x, double* y);
  // K x = b for the free unknowns, both coordinates interleaved (2n doubles);
  // scratch 2n doubles; b and x may be the same array.
  void (*solve)(const SolveLayout& factor, const double* b, double* scratch, double* x);
};

// The table of a path compiled into this build, or null.
const KernelTable* CompiledKernels(Isa isa);

// One declaration per path; each is defined only where it is compiled.
namespace scalar {
extern const KernelTable kKernels;
}
namespace sse2 {
extern const KernelTable kKernels;
}
namespace avx2 {
extern const KernelTable kKernels;
}
namespace avx512 {
extern const KernelTable kKernels;
}
namespace neon {
extern const KernelTable kKernels;
}
namespace wasm_simd {
extern const KernelTable kKernels;
}

}  // namespace posemorph::detail
