// SPDX-License-Identifier: MIT
// Solving the pinned cotangent system with the baked factor.
#pragma once
#include "posemorph/rig.h"

namespace posemorph::detail {

// Solves K x = b (the rig's factor, on the rig's kernel path) for both coordinates at once. b and x hold the n free
// unknowns interleaved (x0, y0, x1, y1, ...); scratch holds 2n doubles.
// b and x may be the same array; scratch must differ from both.
void SolvePinned(const Rig& rig, const double* b, double* scratch, double* x);

}  // namespace posemorph::detail
