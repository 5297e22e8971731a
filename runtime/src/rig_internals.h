// SPDX-License-Identifier: MIT
// What the jobs and kernels read of a Rig besides its public accessors: the
// layouts built at load for them (the solve's, the SIMD blend blocks) and
// the kernel path chosen at load. Internal to the runtime (and its tests).
#pragma once
#include "posemorph/rig.h"

namespace posemorph::detail {

struct RigInternals {
  static const SolveLayout& Solve(const Rig& rig) { return rig.solve_; }
  static Span<const double> BlendBlocks(const Rig& rig) { return rig.blend_blocks_; }
  static const KernelTable* Kernels(const Rig& rig) { return rig.kernels_; }
};

}  // namespace posemorph::detail
