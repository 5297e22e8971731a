// SPDX-License-Identifier: MIT
#include "ldlt_solve.h"

#include "kernels/kernel_table.h"
#include "rig_internals.h"

namespace posemorph::detail {

// Through the rig's kernel path, so that it measures what a frame runs.
void SolvePinned(const Rig& rig, const double* b, double* scratch, double* x) {
  RigInternals::Kernels(rig)->solve(RigInternals::Solve(rig), b, scratch, x);
}

}  // namespace posemorph::detail
